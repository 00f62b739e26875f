#![allow(unsafe_code)] // GiST's and the planner's C interfaces
//! The native index: a GiST operator class on circletree keyed by the header's box (PostgreSQL's
//! own `box`, so the built-in box support functions union, split and compare the keys), the `&&`
//! operators between circletree and geometry, and the planner support that turns
//! `ct_intersects`, `ct_contains` and `ct_dwithin` into an index condition with no `&&` written.
//!
//! A circletree's box is its envelope (`ct_envelope`: the original's box widened by max_error,
//! which holds the rebuilt polygon), a geometry's its stored box or its coordinates', each rounded
//! outwards to floats as PostGIS's own `&&` rounds them, so `ct && g` is `ct_envelope(ct) && g`.
//! An empty value's key is NaN: the index hands it to the operator, which says it meets nothing.

use crate::datatype::CircleTree;
use crate::error::OrRaise;
use circletree_core::format::CircleTree as Value;
use circletree_core::geom::gserialized;
use pgrx::datum::Internal;
use pgrx::pg_sys;
use pgrx::prelude::*;
use pgrx::{FromDatum, PgList};
use std::ffi::CStr;

/// `[xmin, ymin, xmax, ymax]`.
type Bbox = [f64; 4];

/// The envelope of a circletree datum, from its header.
///
/// # Safety
/// `d` is a circletree datum, not NULL.
unsafe fn ct_box(d: pg_sys::Datum) -> Option<Bbox> {
    // SAFETY: a plain varlena; detoasted
    let bytes = unsafe { <&[u8]>::from_polymorphic_datum(d, false, pg_sys::InvalidOid) }
        .unwrap_or_default();
    Value::envelope(bytes)
        .or_raise()
        .1
        .map(gserialized::float_box)
}

/// The box `&&` takes of a geometry datum (`None`: empty).
///
/// # Safety
/// `d` is a geometry datum, not NULL.
unsafe fn geom_box(d: pg_sys::Datum) -> Option<Bbox> {
    // SAFETY: a geometry datum is a varlena
    let bytes = unsafe { <&[u8]>::from_polymorphic_datum(d, false, pg_sys::InvalidOid) }
        .unwrap_or_default();
    match gserialized::read(bytes) {
        Some(g) => g.bbox.map(gserialized::float_box),
        None => pgrx::error!("circletree: the geometry's bytes could not be read"),
    }
}

fn overlaps(a: &Bbox, b: &Bbox) -> bool {
    a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3]
}

fn both(a: Option<Bbox>, b: Option<Bbox>) -> bool {
    matches!((a, b), (Some(a), Some(b)) if overlaps(&a, &b))
}

/// `circletree && geometry`: their boxes meet.
#[pg_extern(sql = false)]
fn _ct_overlaps(ct: Internal, geom: Internal) -> Option<bool> {
    let (ct, geom) = (ct.unwrap()?, geom.unwrap()?); // ok: Internal::unwrap is an Option
                                                     // SAFETY: the SQL declaration's types
    Some(unsafe { both(ct_box(ct), geom_box(geom)) })
}

/// `geometry && circletree`.
#[pg_extern(sql = false)]
fn _ct_overlaps_g(geom: Internal, ct: Internal) -> Option<bool> {
    let (ct, geom) = (ct.unwrap()?, geom.unwrap()?); // ok: Internal::unwrap is an Option
                                                     // SAFETY: the SQL declaration's types
    Some(unsafe { both(ct_box(ct), geom_box(geom)) })
}

/// `circletree && circletree`.
#[pg_extern(sql = false)]
fn _ct_overlaps_ct(a: Internal, b: Internal) -> Option<bool> {
    let (a, b) = (a.unwrap()?, b.unwrap()?); // ok: Internal::unwrap is an Option
                                             // SAFETY: the SQL declaration's types
    Some(unsafe { both(ct_box(a), ct_box(b)) })
}

/// GiST `compress`: a leaf's circletree becomes its envelope as a `box` (NaN when empty).
#[pg_extern(sql = false)]
fn _ct_gist_compress(entry: Internal) -> Internal {
    let Some(d) = entry.unwrap() else {
        return Internal::from(None);
    }; // ok: Internal::unwrap is an Option
    let e = d.cast_mut_ptr::<pg_sys::GISTENTRY>();
    // SAFETY: GiST passes a GISTENTRY; a leaf's key is the indexed circletree datum
    unsafe {
        if !(*e).leafkey {
            return Internal::from(Some(d));
        }
        let b = ct_box((*e).key).unwrap_or([f64::NAN; 4]);
        let key = pg_sys::palloc(std::mem::size_of::<pg_sys::BOX>()).cast::<pg_sys::BOX>();
        *key = pg_sys::BOX {
            high: pg_sys::Point { x: b[2], y: b[3] },
            low: pg_sys::Point { x: b[0], y: b[1] },
        };
        let out =
            pg_sys::palloc(std::mem::size_of::<pg_sys::GISTENTRY>()).cast::<pg_sys::GISTENTRY>();
        *out = pg_sys::GISTENTRY {
            key: pg_sys::Datum::from(key),
            rel: (*e).rel,
            page: (*e).page,
            offset: (*e).offset,
            leafkey: false,
        };
        Internal::from(Some(pg_sys::Datum::from(out)))
    }
}

/// GiST `consistent` for `&&` (strategy 3) with a geometry or a circletree query: the key's box
/// meets the query's. Exact (no recheck): the operator compares the same boxes.
#[pg_extern(sql = false)]
fn _ct_gist_consistent(
    entry: Internal,
    query: Internal,
    strategy: i16,
    subtype: pg_sys::Oid,
    recheck: Internal,
    fcinfo: pg_sys::FunctionCallInfo,
) -> bool {
    let (Some(e), Some(q)) = (entry.unwrap(), query.unwrap()) else {
        return false;
    }; // ok: Internal::unwrap is an Option
    if strategy != 3 {
        pgrx::error!("circletree: GiST strategy {strategy} is not one of circletree's (3, &&)");
    }
    // SAFETY: GiST passes a GISTENTRY whose key is a box, the query of the operator's right type
    // and a bool to set
    unsafe {
        let k = &*(*e.cast_mut_ptr::<pg_sys::GISTENTRY>())
            .key
            .cast_mut_ptr::<pg_sys::BOX>();
        let key = [k.low.x, k.low.y, k.high.x, k.high.y];
        // An empty value's key (NaN), or an inner key over one, may hold anything: on a leaf the
        // operator itself decides (recheck), which never holds for an empty value.
        let unknown = key.iter().any(|v| v.is_nan());
        if let Some(r) = recheck.unwrap() {
            // ok: Internal::unwrap is an Option, no panic
            *r.cast_mut_ptr::<bool>() = unknown;
        }
        let q = if subtype == circletree_oid(fcinfo) {
            ct_box(q)
        } else {
            geom_box(q)
        };
        let Some(q) = q else { return false };
        unknown || overlaps(&key, &q)
    }
}

/// circletree's type OID, kept in the support function's `fn_extra` (the index's relcache entry
/// holds it, and goes with the extension): looking it up by name parses a type name.
///
/// # Safety
/// `fcinfo` is the current call's.
unsafe fn circletree_oid(fcinfo: pg_sys::FunctionCallInfo) -> pg_sys::Oid {
    // SAFETY: this call's flinfo; fn_extra is ours, allocated in its memory context
    unsafe {
        let flinfo = (*fcinfo).flinfo;
        if (*flinfo).fn_extra.is_null() {
            let slot =
                pg_sys::MemoryContextAlloc((*flinfo).fn_mcxt, std::mem::size_of::<pg_sys::Oid>())
                    .cast::<pg_sys::Oid>();
            *slot = CircleTree::type_oid();
            (*flinfo).fn_extra = slot.cast();
        }
        *((*flinfo).fn_extra as *const pg_sys::Oid)
    }
}

/// Planner support of `ct_intersects`, `ct_contains` and `ct_dwithin` (either argument order):
/// with a circletree GiST index on the circletree argument, the index condition
/// `ct && other` (`ct && ST_Expand(other, distance)` for `ct_dwithin`), lossy.
#[pg_extern(sql = false)]
fn _ct_support(req: Internal) -> Internal {
    // "No answer" is a NULL pointer, not an SQL NULL.
    let none = Internal::from(Some(pg_sys::Datum::from(0usize)));
    let Some(r) = req.unwrap() else { return none }; // ok: Internal::unwrap is an Option
                                                     // SAFETY: the planner passes a Node; a SupportRequestIndexCondition when its tag says so
    unsafe {
        let node = r.cast_mut_ptr::<pg_sys::Node>();
        if (*node).type_ != pg_sys::NodeTag::T_SupportRequestIndexCondition {
            return none;
        }
        let req = node.cast::<pg_sys::SupportRequestIndexCondition>();
        let f = (*req).node;
        if (*f).type_ != pg_sys::NodeTag::T_FuncExpr || (*req).indexarg > 1 {
            return none;
        }
        let name = CStr::from_ptr(pg_sys::get_func_name((*req).funcid))
            .to_string_lossy()
            .into_owned();
        let args = PgList::<pg_sys::Node>::from_pg((*f.cast::<pg_sys::FuncExpr>()).args);
        let i = (*req).indexarg as usize;
        let (Some(indexed), Some(other)) = (args.get_ptr(i), args.get_ptr(1 - i)) else {
            return none;
        };
        let ct_type = CircleTree::type_oid();
        if pg_sys::exprType(indexed) != ct_type {
            return none;
        }
        let other_type = pg_sys::exprType(other);
        let op = pg_sys::get_opfamily_member((*req).opfamily, ct_type, other_type, 3);
        if op == pg_sys::InvalidOid
            || !pg_sys::is_pseudo_constant_for_index((*req).root, other, (*req).index)
        {
            return none;
        }
        let right: *mut pg_sys::Node = match name.as_str() {
            "ct_intersects" | "ct_contains" => other,
            "ct_dwithin" => {
                let Some(d) = args.get_ptr(2) else {
                    return none;
                };
                if !pg_sys::is_pseudo_constant_for_index((*req).root, d, (*req).index) {
                    return none;
                }
                let Some(expand) = st_expand(other_type) else {
                    return none;
                };
                let mut fargs = PgList::<pg_sys::Node>::new();
                fargs.push(other);
                fargs.push(d);
                pg_sys::makeFuncExpr(
                    expand,
                    other_type,
                    fargs.into_pg(),
                    pg_sys::InvalidOid,
                    pg_sys::InvalidOid,
                    pg_sys::CoercionForm::COERCE_EXPLICIT_CALL,
                )
                .cast()
            }
            _ => return none,
        };
        let clause = pg_sys::make_opclause(
            op,
            pg_sys::BOOLOID,
            false,
            indexed.cast(),
            right.cast(),
            pg_sys::InvalidOid,
            pg_sys::InvalidOid,
        );
        (*req).lossy = true;
        let mut out = PgList::<pg_sys::Expr>::new();
        out.push(clause);
        Internal::from(Some(pg_sys::Datum::from(out.into_pg())))
    }
}

/// PostGIS's `ST_Expand(geometry, float8)`.
fn st_expand(geometry: pg_sys::Oid) -> Option<pg_sys::Oid> {
    let f = crate::postgis::postgis_function(
        geometry,
        c"st_expand",
        &[geometry, pg_sys::FLOAT8OID],
        true,
    );
    (f != pg_sys::InvalidOid).then_some(f)
}
