#![allow(unsafe_code)] // fn_extra, raw datums, fmgr calls into PostGIS
//! Predicates and distances on a circletree in place (`ct_intersects`, `ct_contains`,
//! `ct_dwithin`, `ct_distance`, each in both argument orders), with no decode per call: each
//! call site (`fn_extra`) keeps the values it met, rebuilt once with an edge index
//! ([`circletree_core::access::Prepared`]), keyed by their TOAST pointer (so a cached value is not
//! even detoasted) or by their bytes, least recently used out first beyond [`CACHE_BYTES`].
//!
//! A point is answered here, with PostGIS's own arithmetic, and whether a (multi)linestring or a
//! (multi)polygon intersects, with exact predicates as GEOS's; anything else goes to PostGIS's
//! own function on the rebuilt geometry, so the answer is PostGIS's. Mixed SRIDs and a
//! negative distance are refused before either, with PostGIS's message as 22023 and a hint.

use crate::datatype::CircleTree;
use crate::error::OrRaise;
use circletree_core::access::{Location, Prepared};
use circletree_core::geom::gserialized;
use pgrx::datum::Internal;
use pgrx::memcxt::PgMemoryContexts;
use pgrx::pg_sys;
use pgrx::pg_sys::panic::ErrorReport;
use pgrx::prelude::*;
use pgrx::{FromDatum, IntoDatum};
use std::collections::HashMap;
use std::rc::Rc;

/// The most bytes of rebuilt rings and edge indexes one call site keeps.
pub const CACHE_BYTES: usize = 64 << 20;

#[derive(Clone, Copy, PartialEq, Eq)]
enum Op {
    Intersects,
    Contains,
    DWithin,
    Distance,
}

impl Op {
    fn postgis(self) -> (&'static std::ffi::CStr, usize) {
        match self {
            Op::Intersects => (c"st_intersects", 2),
            Op::Contains => (c"st_contains", 2),
            Op::DWithin => (c"st_dwithin", 3),
            Op::Distance => (c"st_distance", 2),
        }
    }
}

struct Entry {
    prep: Rc<Prepared>,
    last: u64,
    size: usize,
}

/// One call site's values and PostGIS's functions (looked up when first needed).
#[derive(Default)]
struct CallSite {
    toasted: HashMap<(u32, u32), Entry>,
    inline: HashMap<Box<[u8]>, Entry>,
    bytes: usize,
    tick: u64,
    postgis: Option<Box<[pg_sys::FmgrInfo; 2]>>,
}

impl CallSite {
    /// The prepared value of a circletree datum.
    ///
    /// # Safety
    /// `d` is a circletree datum, not NULL.
    unsafe fn prepared(&mut self, d: pg_sys::Datum) -> Rc<Prepared> {
        self.tick += 1;
        let tick = self.tick;
        // SAFETY: a varlena datum
        let toast = unsafe { toast_pointer(d) };
        if let Some(k) = toast {
            if let Some(e) = self.toasted.get_mut(&k) {
                e.last = tick;
                return e.prep.clone();
            }
        }
        // SAFETY: a circletree datum is a plain varlena; this detoasts it
        let bytes = unsafe { <&[u8]>::from_polymorphic_datum(d, false, pg_sys::InvalidOid) }
            .unwrap_or_default();
        if toast.is_none() {
            if let Some(e) = self.inline.get_mut(bytes) {
                e.last = tick;
                return e.prep.clone();
            }
        }
        let ct = CircleTree::from_stored(bytes);
        let prep = Rc::new(Prepared::new(&ct.value).or_raise());
        let size = prep.heap_bytes() + if toast.is_none() { bytes.len() } else { 0 };
        if size > CACHE_BYTES {
            return prep;
        }
        while self.bytes + size > CACHE_BYTES {
            self.evict_oldest();
        }
        self.bytes += size;
        let e = Entry {
            prep: prep.clone(),
            last: tick,
            size,
        };
        match toast {
            Some(k) => {
                self.toasted.insert(k, e);
            }
            None => {
                self.inline.insert(bytes.into(), e);
            }
        }
        prep
    }

    fn evict_oldest(&mut self) {
        let t = self
            .toasted
            .iter()
            .min_by_key(|(_, e)| e.last)
            .map(|(k, e)| (*k, e.last));
        let i = self
            .inline
            .iter()
            .min_by_key(|(_, e)| e.last)
            .map(|(k, e)| (k.clone(), e.last));
        let size = match (t, i) {
            (Some((k, a)), Some((_, b))) if a <= b => self.toasted.remove(&k).map(|e| e.size),
            (_, Some((k, _))) => self.inline.remove(&k).map(|e| e.size),
            (Some((k, _)), None) => self.toasted.remove(&k).map(|e| e.size),
            (None, None) => None,
        };
        self.bytes -= size.unwrap_or(self.bytes);
    }
}

/// The TOAST relation and value of an on-disk TOAST pointer (`varatt_external`), else `None`.
///
/// # Safety
/// `d` is a varlena datum.
unsafe fn toast_pointer(d: pg_sys::Datum) -> Option<(u32, u32)> {
    let p = d.cast_mut_ptr::<u8>() as *const u8;
    // SAFETY: a varlena has at least its header byte; an external one its tag and pointer
    unsafe {
        // VARATT_IS_EXTERNAL_ONDISK: a 1-byte header of 0x01 (little endian) and VARTAG_ONDISK
        if *p != 0x01 || u32::from(*p.add(1)) != pg_sys::vartag_external::VARTAG_ONDISK {
            return None;
        }
        let mut ext = [0u8; 16];
        std::ptr::copy_nonoverlapping(p.add(2), ext.as_mut_ptr(), 16);
        let word = |i: usize| u32::from_ne_bytes([ext[i], ext[i + 1], ext[i + 2], ext[i + 3]]);
        Some((word(12), word(8)))
    }
}

/// This call site's cache, made on its first call in the function's memory context.
///
/// # Safety
/// `fcinfo` is the current call's.
unsafe fn call_site<'a>(fcinfo: pg_sys::FunctionCallInfo) -> &'a mut CallSite {
    // SAFETY: PostgreSQL's flinfo for this call; fn_extra is ours
    unsafe {
        let flinfo = (*fcinfo).flinfo;
        if (*flinfo).fn_extra.is_null() {
            let site = PgMemoryContexts::For((*flinfo).fn_mcxt)
                .leak_and_drop_on_delete(CallSite::default());
            (*flinfo).fn_extra = site.cast();
        }
        &mut *((*flinfo).fn_extra as *mut CallSite)
    }
}

/// One predicate call: the circletree argument, the geometry argument, whether the circletree is
/// the first, and the distance.
///
/// # Safety
/// `fcinfo` is the current call's; `ct` and `geom` its (not NULL) arguments of those types.
unsafe fn answer(
    fcinfo: pg_sys::FunctionCallInfo,
    op: Op,
    ct: pg_sys::Datum,
    geom: pg_sys::Datum,
    ct_first: bool,
    d: f64,
) -> Option<pg_sys::Datum> {
    // SAFETY: per this function's contract
    let site = unsafe { call_site(fcinfo) };
    let prep = unsafe { site.prepared(ct) };
    // SAFETY: a geometry datum is a varlena (a point's is small, never toasted out of line)
    let bytes = unsafe { <&[u8]>::from_polymorphic_datum(geom, false, pg_sys::InvalidOid) };
    // lines and polygons are read only where they are answered here
    let (g, linework) = match bytes.and_then(|b| match op {
        Op::Intersects => gserialized::read_linework(b),
        _ => gserialized::read(b).map(|g| (g, None)),
    }) {
        Some((g, lw)) => (Some(g), lw),
        None => (None, None),
    };
    if let Some(g) = &g {
        if g.srid != prep.srid {
            mixed_srids(op, &prep, g);
        }
    }
    if op == Op::DWithin && d < 0.0 {
        ErrorReport::new(
            PgSqlErrorCode::ERRCODE_INVALID_PARAMETER_VALUE,
            "ct_dwithin: the distance cannot be less than zero (as ST_DWithin's tolerance)",
            "circletree",
        )
        .set_hint("Pass a distance of 0 or more, in the units of the SRID.")
        .report(PgLogLevel::ERROR);
    }
    if let Some(g) = g.filter(|g| !g.geodetic) {
        let fast = match (op, g.point) {
            (Op::Distance, _) if g.empty || prep.is_empty() => return None,
            (Op::Intersects, Some(p)) => Some((prep.locate(p) != Location::Outside).into_datum()),
            (Op::Intersects, None) if linework.is_some() => linework
                .as_ref()
                .map(|lw| prep.intersects_linework(lw).into_datum()),
            (Op::Contains, Some(p)) if ct_first => {
                Some((prep.locate(p) == Location::Inside).into_datum())
            }
            (Op::DWithin, Some(p)) => Some(prep.dwithin(p, d).into_datum()),
            (Op::Distance, Some(p)) => prep.distance(p).into_datum().map(Some),
            _ => None,
        };
        if let Some(v) = fast {
            return v;
        }
    }
    // SAFETY: per this function's contract
    Some(unsafe { postgis_answer(site, fcinfo, op, &prep, geom, ct_first, d) })
}

/// PostGIS's message for mixed SRIDs, under the circletree function's name, as 22023 with a hint.
fn mixed_srids(op: Op, prep: &Prepared, g: &gserialized::Serialized) -> ! {
    const NAMES: [&str; 16] = [
        "Unknown",
        "Point",
        "LineString",
        "Polygon",
        "MultiPoint",
        "MultiLineString",
        "MultiPolygon",
        "GeometryCollection",
        "CircularString",
        "CompoundCurve",
        "CurvePolygon",
        "MultiCurve",
        "MultiSurface",
        "PolyhedralSurface",
        "Triangle",
        "Tin",
    ];
    let name = |k: u32| NAMES.get(k as usize).copied().unwrap_or("Unknown");
    let ct = if prep.kind == circletree_core::geom::Kind::Polygon {
        3
    } else {
        6
    };
    let f = match op {
        Op::Intersects => "ct_intersects",
        Op::Contains => "ct_contains",
        Op::DWithin => "ct_dwithin",
        Op::Distance => "ct_distance",
    };
    ErrorReport::new(
        PgSqlErrorCode::ERRCODE_INVALID_PARAMETER_VALUE,
        format!(
            "{f}: Operation on mixed SRID geometries ({}, {}) != ({}, {})",
            name(ct),
            prep.srid,
            name(g.kind),
            g.srid
        ),
        "circletree",
    )
    .set_hint("Bring both to one SRID first, e.g. ST_Transform(geom, ct_srid(ct)).")
    .report(PgLogLevel::ERROR);
    unreachable!("ereport(ERROR) returned") // ok: report(ERROR) never returns (it unwinds to pgrx's guard)
}

/// PostGIS's own function on the rebuilt geometry.
///
/// # Safety
/// As [`answer`].
unsafe fn postgis_answer(
    site: &mut CallSite,
    fcinfo: pg_sys::FunctionCallInfo,
    op: Op,
    prep: &Prepared,
    geom: pg_sys::Datum,
    ct_first: bool,
    d: f64,
) -> pg_sys::Datum {
    // SAFETY: flinfo and its memory context are this call's
    let f = site
        .postgis
        .get_or_insert_with(|| unsafe { lookup(fcinfo, op) });
    let ewkb = prep.ewkb();
    let ewkb = ewkb
        .as_slice()
        .into_datum()
        .unwrap_or(pg_sys::Datum::from(0usize));
    // SAFETY: the functions were looked up with these argument types
    unsafe {
        let decoded = pg_sys::FunctionCall1Coll(&mut f[0], pg_sys::InvalidOid, ewkb);
        let (a, b) = if ct_first {
            (decoded, geom)
        } else {
            (geom, decoded)
        };
        if op == Op::DWithin {
            pg_sys::FunctionCall3Coll(
                &mut f[1],
                pg_sys::InvalidOid,
                a,
                b,
                d.into_datum().unwrap_or(pg_sys::Datum::from(0usize)),
            )
        } else {
            pg_sys::FunctionCall2Coll(&mut f[1], pg_sys::InvalidOid, a, b)
        }
    }
}

/// PostGIS's `ST_GeomFromEWKB(bytea)` and the predicate's own function, from the schema of the
/// geometry type's input function (catalog look-ups only: this may run in a parallel worker).
///
/// # Safety
/// `fcinfo` is the current call's.
unsafe fn lookup(fcinfo: pg_sys::FunctionCallInfo, op: Op) -> Box<[pg_sys::FmgrInfo; 2]> {
    // SAFETY: this call's flinfo
    let (own, mcxt) = unsafe { ((*(*fcinfo).flinfo).fn_oid, (*(*fcinfo).flinfo).fn_mcxt) };
    let geometry = pgrx::pg_catalog::pg_proc::PgProc::new(own)
        .and_then(|p| {
            p.proargtypes()
                .iter()
                .copied()
                .find(|t| *t != pg_sys::FLOAT8OID && *t != CircleTree::type_oid())
        })
        .unwrap_or(pg_sys::InvalidOid);
    let (name, nargs) = op.postgis();
    let args = [geometry, geometry, pg_sys::FLOAT8OID];
    let find = |name: &std::ffi::CStr, args: &[pg_sys::Oid]| {
        crate::postgis::postgis_function(geometry, name, args, false)
    };
    let from_ewkb = find(c"st_geomfromewkb", &[pg_sys::BYTEAOID]);
    let pred = find(name, &args[..nargs]);
    // SAFETY: zeroed FmgrInfo filled by fmgr_info_cxt, in the function's memory context
    unsafe {
        let mut f: Box<[pg_sys::FmgrInfo; 2]> = Box::new(std::mem::zeroed());
        pg_sys::fmgr_info_cxt(from_ewkb, &mut f[0], mcxt);
        pg_sys::fmgr_info_cxt(pred, &mut f[1], mcxt);
        f
    }
}

macro_rules! predicate {
    ($name:ident, $op:expr, ct_first, $ret:ty) => {
        #[pg_extern(sql = false)]
        fn $name(ct: Internal, geom: Internal, fcinfo: pg_sys::FunctionCallInfo) -> Option<$ret> {
            let (ct, geom) = (ct.unwrap()?, geom.unwrap()?); // ok: Internal::unwrap is an Option
                                                             // SAFETY: this call's fcinfo and its arguments
            let d = unsafe { answer(fcinfo, $op, ct, geom, true, 0.0) }?;
            unsafe { <$ret>::from_datum(d, false) }
        }
    };
    ($name:ident, $op:expr, geom_first, $ret:ty) => {
        #[pg_extern(sql = false)]
        fn $name(geom: Internal, ct: Internal, fcinfo: pg_sys::FunctionCallInfo) -> Option<$ret> {
            let (ct, geom) = (ct.unwrap()?, geom.unwrap()?); // ok: Internal::unwrap is an Option
                                                             // SAFETY: this call's fcinfo and its arguments
            let d = unsafe { answer(fcinfo, $op, ct, geom, false, 0.0) }?;
            unsafe { <$ret>::from_datum(d, false) }
        }
    };
}

predicate!(_ct_intersects, Op::Intersects, ct_first, bool);
predicate!(_ct_intersects_g, Op::Intersects, geom_first, bool);
predicate!(_ct_contains, Op::Contains, ct_first, bool);
predicate!(_ct_contains_g, Op::Contains, geom_first, bool);
predicate!(_ct_distance, Op::Distance, ct_first, f64);
predicate!(_ct_distance_g, Op::Distance, geom_first, f64);

/// `ct_dwithin(circletree, geometry, float8)`.
#[pg_extern(sql = false)]
fn _ct_dwithin(
    ct: Internal,
    geom: Internal,
    d: Option<f64>,
    fcinfo: pg_sys::FunctionCallInfo,
) -> Option<bool> {
    let (ct, geom, d) = (ct.unwrap()?, geom.unwrap()?, d?); // ok: Internal::unwrap is an Option
                                                            // SAFETY: this call's fcinfo and its arguments
    let v = unsafe { answer(fcinfo, Op::DWithin, ct, geom, true, d) }?;
    unsafe { bool::from_datum(v, false) }
}

/// `ct_dwithin(geometry, circletree, float8)`.
#[pg_extern(sql = false)]
fn _ct_dwithin_g(
    geom: Internal,
    ct: Internal,
    d: Option<f64>,
    fcinfo: pg_sys::FunctionCallInfo,
) -> Option<bool> {
    let (ct, geom, d) = (ct.unwrap()?, geom.unwrap()?, d?); // ok: Internal::unwrap is an Option
                                                            // SAFETY: this call's fcinfo and its arguments
    let v = unsafe { answer(fcinfo, Op::DWithin, ct, geom, false, d) }?;
    unsafe { bool::from_datum(v, false) }
}
