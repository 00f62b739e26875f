//! Every user-facing error: the core's error mapped to its SQLSTATE, with a hint.

use circletree_core::Error;
use pgrx::pg_sys::panic::ErrorReport;
use pgrx::prelude::*;

/// SQLSTATE and hint for a core error.
fn classify(e: &Error) -> (PgSqlErrorCode, &'static str) {
    use PgSqlErrorCode::*;
    match e {
        Error::InvalidParameter { .. } => (
            ERRCODE_INVALID_PARAMETER_VALUE,
            "min_radius, dp_tolerance, max_error and arc_tolerance are lengths in the units of the geometry's SRID, like ST_Simplify's tolerance; overlap is a fraction.",
        ),
        Error::UnsupportedGeometry(_) => (
            ERRCODE_INVALID_PARAMETER_VALUE,
            "Pass a Polygon or MultiPolygon: ST_CollectionExtract(geom, 3) takes the polygons out of a collection, ST_CurveToLine strokes curves.",
        ),
        Error::NonFinite(_) => {
            (ERRCODE_INVALID_PARAMETER_VALUE, "Remove NaN or infinite coordinates before encoding.")
        }
        Error::InvalidPolygon(_) => (
            ERRCODE_INVALID_PARAMETER_VALUE,
            "Repair the geometry first with ST_MakeValid(geom); ST_IsValidReason(geom) says what is wrong.",
        ),
        Error::BadWkb(_) => (ERRCODE_INVALID_PARAMETER_VALUE, "The geometry could not be read as WKB."),
        Error::Corrupt(_) => (
            ERRCODE_INVALID_BINARY_REPRESENTATION,
            "The bytes were not written by circletree or were damaged; encode the original geometry again with ct_encode.",
        ),
        Error::Syntax { .. } => (
            ERRCODE_INVALID_TEXT_REPRESENTATION,
            "The text form is SRID=...;CIRCLETREE(grid=...;...;POLYGON((x y r,...))); print any value with ::text to see one, docs/FORMAT.md describes it.",
        ),
        Error::TooLarge(_) => (
            ERRCODE_PROGRAM_LIMIT_EXCEEDED,
            "Decode at a coarser arc tolerance, ct_decode(ct, arc_tolerance), or keep the true arcs with ct_decode_curved(ct).",
        ),
        Error::BeyondPrecision { .. } => (
            ERRCODE_INVALID_PARAMETER_VALUE,
            "Move the rings apart first, e.g. ST_MakeValid(ST_SnapToGrid(geom, g)) with g a few times that finest grid, or translate the geometry nearer the origin (a double holds about 16 significant digits of each coordinate).",
        ),
        Error::Unencodable(_) => (
            ERRCODE_INVALID_PARAMETER_VALUE,
            "Snap the geometry first, e.g. ST_MakeValid(ST_SnapToGrid(geom, g)) with g a few times the grid named; a valid polygon should encode, so please report it with ST_AsEWKT(geom) if it persists.",
        ),
    }
}

/// Raise a core error as a PostgreSQL ERROR. Does not return.
#[track_caller]
pub fn raise(e: Error) -> ! {
    let (code, hint) = classify(&e);
    ErrorReport::new(code, e.to_string(), "circletree")
        .set_hint(hint)
        .report(PgLogLevel::ERROR);
    unreachable!("ereport(ERROR) returned") // ok: report(ERROR) never returns (it unwinds to pgrx's guard)
}

/// Unwrap a core result or raise its error.
pub trait OrRaise<T> {
    /// The value, or an ERROR with SQLSTATE and hint.
    fn or_raise(self) -> T;
}

impl<T> OrRaise<T> for Result<T, Error> {
    #[track_caller]
    fn or_raise(self) -> T {
        match self {
            Ok(v) => v,
            Err(e) => raise(e),
        }
    }
}
