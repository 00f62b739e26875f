//! PostGIS's validity of an encoder's input, asked by the encoder itself (release 0.6.0 on) so
//! that it can run beside the encoder (`circletree_core::encode::HostCheck`): the SQL wrappers
//! pass the geometry and PostGIS's `ST_IsValid` and `ST_IsValidReason` as `regprocedure`s
//! resolved, schema-qualified, when the wrapper's query is planned.
//!
//! The functions are called on the backend's thread only (the core calls `HostCheck` there), and
//! only after checking what they are: one argument of the type of the geometry received, the
//! expected result type, not a set, and executable by the current user. So a direct call of the
//! C function with other `regprocedure`s can run nothing the caller could not run in SQL on the
//! same geometry, and no function ever receives a datum of a type it does not take.

#![allow(unsafe_code)] // calls into PostGIS by OID, and the call's own fcinfo

use crate::datatype::CircleTree;
use crate::error::OrRaise;
use crate::settings::{ENCODE_BYTES_PER_VERTEX, ENCODE_WITHIN_BYTES_PER_VERTEX};
use circletree_core::encode::{Call, HostCheck, Validity as Verdict};
use pgrx::datum::Internal;
use pgrx::pg_catalog::pg_proc::{PgProc, ProKind};
use pgrx::pg_sys;
use pgrx::pg_sys::panic::ErrorReport;
use pgrx::prelude::*;
use pgrx::FromDatum;

/// Release 0.6.0's `ct_encode`: `_ct_encode_wkb` given the geometry itself and PostGIS's
/// `ST_IsValid` and `ST_IsValidReason`, which it calls while the encoder runs (on a large input
/// the encoder works on a second thread meanwhile). NULL geometry, min_radius or overlap give
/// NULL.
// Declared in sql/postgis_wrappers.sql (its first argument is PostGIS's geometry).
#[allow(clippy::too_many_arguments)]
#[pg_extern(sql = false)]
fn _ct_encode_geom(
    geom: Internal,
    wkb: Option<&[u8]>,
    srid: Option<i32>,
    is_valid: Option<pg_sys::Oid>,
    reason: Option<pg_sys::Oid>,
    min_radius: Option<f64>,
    overlap: Option<f64>,
    dp_tolerance: Option<f64>,
    max_error: Option<f64>,
    fcinfo: pg_sys::FunctionCallInfo,
) -> Option<CircleTree> {
    let (geom, wkb, min_radius, overlap) = (geom.unwrap()?, wkb?, min_radius?, overlap?); // ok: Internal::unwrap is an Option
    let (is_valid, reason) = (is_valid?, reason?);
    // SAFETY: this call's fcinfo, and its first argument (not NULL)
    let validity = unsafe {
        Validity::for_encoder(
            fcinfo,
            geom,
            wkb,
            (is_valid, reason),
            ENCODE_BYTES_PER_VERTEX,
            "ct_encode",
        )
    };
    let opts = circletree_core::encode::Options {
        min_radius,
        overlap,
        dp_tolerance,
        max_error,
    };
    let mut interrupt = crate::functions::interrupt;
    let (value, bytes, report) =
        circletree_core::encode::encode(wkb, &opts, validity.call(srid, &mut interrupt))
            .or_raise()
            .into_parts();
    crate::functions::notice_dropped_zm(&report);
    Some(CircleTree { value, bytes })
}

/// Release 0.6.0's `ct_encode_within`: `_ct_encode_within_wkb` with PostGIS's validity asked
/// while the encoder runs, as [`_ct_encode_geom`]. NULL geometry or max_error give NULL.
// Declared in sql/postgis_wrappers.sql (its first argument is PostGIS's geometry).
#[pg_extern(sql = false)]
fn _ct_encode_within_geom(
    geom: Internal,
    wkb: Option<&[u8]>,
    srid: Option<i32>,
    is_valid: Option<pg_sys::Oid>,
    reason: Option<pg_sys::Oid>,
    max_error: Option<f64>,
    fcinfo: pg_sys::FunctionCallInfo,
) -> Option<CircleTree> {
    let (geom, wkb, max_error) = (geom.unwrap()?, wkb?, max_error?); // ok: Internal::unwrap is an Option
    let (is_valid, reason) = (is_valid?, reason?);
    // SAFETY: this call's fcinfo, and its first argument (not NULL)
    let validity = unsafe {
        Validity::for_encoder(
            fcinfo,
            geom,
            wkb,
            (is_valid, reason),
            ENCODE_WITHIN_BYTES_PER_VERTEX,
            "ct_encode_within",
        )
    };
    let mut interrupt = crate::functions::interrupt;
    let (value, bytes, report) =
        circletree_core::encode::encode_within(wkb, max_error, validity.call(srid, &mut interrupt))
            .or_raise()
            .into_parts();
    crate::functions::notice_dropped_zm(&report);
    Some(CircleTree { value, bytes })
}

/// PostGIS's check of one input, ready to be called.
struct Validity {
    geom: pg_sys::Datum,
    is_valid: pg_sys::Oid,
    reason: pg_sys::Oid,
    /// Whether the WKB is a (Multi)Polygon: other types are refused by the encoder by their type,
    /// unchecked (as `_ct_invalid_reason` does).
    polygonal: bool,
}

impl Validity {
    /// What both encoders check before they start: the memory the input would need
    /// (`circletree.max_encode_memory`, at `bytes_per_vertex`), then the two functions against
    /// the type of this call's first argument (the geometry).
    ///
    /// # Safety
    /// `fcinfo` is the current call's, and `geom` its first argument, not NULL.
    unsafe fn for_encoder(
        fcinfo: pg_sys::FunctionCallInfo,
        geom: pg_sys::Datum,
        wkb: &[u8],
        (is_valid, reason): (pg_sys::Oid, pg_sys::Oid),
        bytes_per_vertex: f64,
        function: &str,
    ) -> Self {
        crate::settings::check_encode_memory(wkb, bytes_per_vertex, function);
        // SAFETY: the caller passes this call's fcinfo, whose flinfo PostgreSQL set up
        let own = unsafe { (*(*fcinfo).flinfo).fn_oid };
        let geometry = PgProc::new(own)
            .and_then(|p| p.proargtypes().first().copied())
            .unwrap_or(pg_sys::InvalidOid);
        check_function(is_valid, geometry, pg_sys::BOOLOID, "is_valid");
        check_function(reason, geometry, pg_sys::TEXTOID, "reason");
        Validity {
            geom,
            is_valid,
            reason,
            polygonal: circletree_core::geom::wkb::is_polygonal(wkb),
        }
    }

    /// An encoder's call with this check asked beside it.
    fn call<'a>(&'a self, srid: Option<i32>, interrupt: &'a mut dyn FnMut()) -> Call<'a> {
        Call {
            srid: srid.unwrap_or(0),
            validity: Verdict::Host(HostCheck {
                is_valid: Box::new(|| self.is_valid()),
                reason: Box::new(|| self.reason()),
            }),
            interrupt: Some(interrupt),
        }
    }

    /// PostGIS's `ST_IsValid` (true for other types than (Multi)Polygon, which are not asked).
    fn is_valid(&self) -> bool {
        if !self.polygonal {
            return true;
        }
        let d = call(self.is_valid, self.geom);
        // SAFETY: a bool datum (OidFunctionCall1Coll raises an ERROR on a NULL result)
        unsafe { bool::from_datum(d, false) }.unwrap_or(false)
    }

    /// PostGIS's `ST_IsValidReason`.
    fn reason(&self) -> String {
        let d = call(self.reason, self.geom);
        // SAFETY: a text datum, not NULL
        unsafe { String::from_datum(d, false) }.unwrap_or_default()
    }
}

/// Call a checked function of the geometry. A cancel (or statement_timeout) that reaches GEOS
/// makes PostGIS raise its own ERROR ("GEOS isvalid() threw an error!", SQLSTATE XX000), the
/// cancel still pending: it is raised instead, as PostgreSQL would have (57014).
fn call(f: pg_sys::Oid, geom: pg_sys::Datum) -> pg_sys::Datum {
    PgTryBuilder::new(|| {
        // SAFETY: `f` was checked to take the geometry's type (`check_function`); a PostgreSQL
        // ERROR inside becomes a Rust panic at pgrx's guarded boundary
        unsafe { pg_sys::OidFunctionCall1Coll(f, pg_sys::InvalidOid, geom) }
    })
    .catch_others(|e| {
        pgrx::check_for_interrupts!();
        e.rethrow()
    })
    .execute()
}

/// Refuse a function that is not one of `arg` returning `returns`, or that the user may not run.
fn check_function(f: pg_sys::Oid, arg: pg_sys::Oid, returns: pg_sys::Oid, name: &str) {
    let fits = PgProc::new(f).is_some_and(|p| {
        matches!(p.prokind(), ProKind::Function)
            && !p.proretset()
            && p.prorettype() == returns
            && p.proargtypes() == [arg]
            && arg != pg_sys::InvalidOid
    });
    if !fits {
        ErrorReport::new(
            PgSqlErrorCode::ERRCODE_INVALID_PARAMETER_VALUE,
            format!("circletree: {name} must be a function of one geometry returning {}", if returns == pg_sys::BOOLOID { "boolean" } else { "text" }),
            "circletree",
        )
        .set_hint("Call ct_encode or ct_encode_within: they pass PostGIS's ST_IsValid and ST_IsValidReason.")
        .report(PgLogLevel::ERROR);
    }
    // SAFETY: plain catalog calls; aclcheck_error raises the standard permission ERROR
    unsafe {
        let ok = pg_sys::pg_proc_aclcheck(f, pg_sys::GetUserId(), pg_sys::ACL_EXECUTE as _);
        if ok != pg_sys::AclResult::ACLCHECK_OK {
            pg_sys::aclcheck_error(
                ok,
                pg_sys::ObjectType::OBJECT_FUNCTION,
                pg_sys::get_func_name(f),
            );
        }
    }
}

/// A function of PostGIS's by name and argument types, looked up in the schema of the geometry
/// type's input function (catalog look-ups only, so also in a parallel worker or the planner).
/// `InvalidOid` when missing and `missing_ok`, else the usual ERROR.
pub(crate) fn postgis_function(
    geometry: pg_sys::Oid,
    name: &std::ffi::CStr,
    args: &[pg_sys::Oid],
    missing_ok: bool,
) -> pg_sys::Oid {
    // SAFETY: catalog calls on a type OID; the name list is built in the current memory context
    unsafe {
        let (mut input, mut ioparam) = (pg_sys::InvalidOid, pg_sys::InvalidOid);
        pg_sys::getTypeInputInfo(geometry, &mut input, &mut ioparam);
        let nsp = pg_sys::get_namespace_name(pg_sys::get_func_namespace(input));
        if nsp.is_null() {
            return pg_sys::InvalidOid;
        }
        let mut qualified = pgrx::PgList::<pg_sys::Node>::new();
        qualified.push(pg_sys::makeString(nsp).cast());
        qualified.push(pg_sys::makeString(pg_sys::pstrdup(name.as_ptr())).cast());
        pg_sys::LookupFuncName(
            qualified.into_pg(),
            args.len() as i32,
            args.as_ptr(),
            missing_ok,
        )
    }
}
