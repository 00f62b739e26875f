//! SQL functions over `circletree`: inspection and decoding. PostGIS-facing wrappers that take
//! or return `geometry` are SQL functions in `lib.rs` over these WKB functions.

use crate::datatype::memory::StoredBytes;
use crate::datatype::CircleTree;
use crate::error::OrRaise;
use circletree_core::decode;
use circletree_core::geom::Kind;
use pgrx::prelude::*;
use serde_json::json;

/// The circles in stored order: part, ring and position (1-based), centre and signed radius.
#[pg_extern(immutable, strict, parallel_safe)]
fn ct_circles(
    ct: CircleTree,
) -> TableIterator<
    'static,
    (
        name!(part, i32),
        name!(ring, i32),
        name!(seq, i32),
        name!(x, f64),
        name!(y, f64),
        name!(r, f64),
    ),
> {
    let f = decode::scale(&ct.value);
    let mut rows = Vec::with_capacity(ct.value.ncircles());
    for (pi, part) in ct.value.parts.iter().enumerate() {
        for (ri, ring) in part.iter().enumerate() {
            for (ci, c) in ring.iter().enumerate() {
                rows.push((
                    pi as i32 + 1,
                    ri as i32 + 1,
                    ci as i32 + 1,
                    f(c.x),
                    f(c.y),
                    f(c.r),
                ));
            }
        }
    }
    TableIterator::new(rows)
}

/// Number of circles in all rings (a repeated circle counts each time it is stored).
#[pg_extern(immutable, strict, parallel_safe)]
fn ct_ncircles(ct: CircleTree) -> i32 {
    ct.value.ncircles() as i32
}

/// The SRID the value was encoded with.
#[pg_extern(immutable, strict, parallel_safe)]
fn ct_srid(ct: StoredBytes) -> i32 {
    circletree_core::format::CircleTree::envelope(ct.0)
        .or_raise()
        .0
}

/// Bytes of the value in memory, varlena header included (as ST_MemSize).
#[pg_extern(immutable, strict, parallel_safe)]
fn ct_memsize(ct: StoredBytes) -> i32 {
    (ct.0.len() + pgrx::pg_sys::VARHDRSZ) as i32
}

/// Everything about a value in one JSON object.
#[pg_extern(immutable, strict, parallel_safe)]
fn ct_summary(ct: CircleTree) -> pgrx::JsonB {
    let v = &ct.value;
    let all = v.parts.iter().flatten().flatten();
    let (mut internal, mut external, mut zero) = (0u64, 0u64, 0u64);
    for c in all {
        match c.r.signum() {
            1 => internal += 1,
            -1 => external += 1,
            _ => zero += 1,
        }
    }
    let bytes = ct.bytes.len() + pgrx::pg_sys::VARHDRSZ;
    let p = &v.params;
    let num = |d: circletree_core::format::Decimal| d.to_f64();
    pgrx::JsonB(json!({
        "format_version": v.version,
        "srid": v.srid,
        "kind": if v.kind == Kind::Polygon { "Polygon" } else { "MultiPolygon" },
        "parts": v.parts.len(),
        "rings": v.parts.iter().map(Vec::len).sum::<usize>(),
        "circles": v.ncircles(),
        "internal": internal,
        "external": external,
        "zero": zero,
        "added_by_repair": v.repaired,
        "grid": num(v.grid),
        "bytes": bytes,
        "original_vertices": v.vertices,
        "original_wkb_bytes": v.wkb_bytes,
        "storage_ratio": if v.wkb_bytes > 0 { bytes as f64 / v.wkb_bytes as f64 } else { f64::NAN },
        "params": {
            "min_radius": num(p.min_radius),
            "overlap": num(p.overlap),
            "dp_tolerance": p.dp_tolerance.map(num),
            "max_error": num(p.max_error),
        },
    }))
}

/// The rebuilt boundary as WKB, arcs stroked to `arc_tolerance` (NULL: the grid step). Kept for
/// 0.3.0's SQL definitions (a database not yet updated calls it); 0.4.0's use `_ct_decode_ewkb`.
#[pg_extern(immutable, parallel_safe)]
fn _ct_decode_wkb(ct: Option<CircleTree>, arc_tolerance: Option<f64>) -> Option<Vec<u8>> {
    let ct = ct?;
    Some(decode::to_wkb(&ct.value, arc_tolerance).or_raise())
}

/// The rebuilt boundary as EWKB (the SRID inside), arcs stroked to `arc_tolerance` (NULL: the
/// grid step): what `ct_decode` hands to `ST_GeomFromEWKB`, one decode per call.
#[pg_extern(immutable, parallel_safe)]
fn _ct_decode_ewkb(ct: Option<CircleTree>, arc_tolerance: Option<f64>) -> Option<Vec<u8>> {
    let ct = ct?;
    Some(decode::to_ewkb(&ct.value, arc_tolerance).or_raise())
}

/// The envelope (a box holding the original and the rebuilt polygon) as EWKB, read from the
/// header alone: the argument is a circletree datum taken as its bytes (a plain varlena, detoasted),
/// so no circle is decoded.
// Declared in sql/postgis_wrappers.sql with a circletree argument (after the type exists).
#[pg_extern(sql = false)]
fn _ct_envelope_ewkb(ct: &[u8]) -> Vec<u8> {
    decode::envelope_ewkb(ct).or_raise()
}

/// The rebuilt boundary with true arcs, as EWKT (the SRID inside).
#[pg_extern(immutable, strict, parallel_safe)]
fn _ct_decode_curved_ewkt(ct: CircleTree) -> String {
    decode::to_curved_ewkt(&ct.value)
}

/// The rebuilt boundary with true arcs, as WKT.
#[pg_extern(immutable, strict, parallel_safe)]
fn _ct_decode_curved_wkt(ct: CircleTree) -> String {
    decode::to_curved_wkt(&ct.value)
}

pub(crate) fn interrupt() {
    pgrx::check_for_interrupts!();
}

/// An encoder's call from SQL: PostGIS's verdict on the input passed in (`invalid_reason` from
/// `ST_IsValidReason` when `ST_IsValid` is false), interrupted as a statement is.
fn call<'a>(
    srid: Option<i32>,
    invalid_reason: Option<&'a str>,
    interrupt: &'a mut dyn FnMut(),
) -> circletree_core::encode::Call<'a> {
    use circletree_core::encode::{Call, Validity};
    Call {
        srid: srid.unwrap_or(0),
        validity: invalid_reason.map_or(Validity::Valid, Validity::Invalid),
        interrupt: Some(interrupt),
    }
}

/// The encoders store 2D boundaries: say so when the input had Z or M values.
pub(crate) fn notice_dropped_zm(report: &circletree_core::encode::Report) {
    if report.dropped_zm {
        pgrx::notice!("circletree: the geometry's Z and M values were dropped; circletree stores 2D boundaries");
    }
}

/// Encode a WKB Polygon/MultiPolygon. `invalid_reason` comes from ST_IsValidReason when
/// ST_IsValid is false. NULL geometry, min_radius or overlap give NULL.
#[allow(clippy::too_many_arguments)]
#[pg_extern(immutable, parallel_safe)]
fn _ct_encode_wkb(
    wkb: Option<&[u8]>,
    srid: Option<i32>,
    invalid_reason: Option<&str>,
    min_radius: Option<f64>,
    overlap: Option<f64>,
    dp_tolerance: Option<f64>,
    max_error: Option<f64>,
) -> Option<CircleTree> {
    let (wkb, min_radius, overlap) = (wkb?, min_radius?, overlap?);
    crate::settings::check_encode_memory(
        wkb,
        crate::settings::ENCODE_BYTES_PER_VERTEX,
        "ct_encode",
    );
    let opts = circletree_core::encode::Options {
        min_radius,
        overlap,
        dp_tolerance,
        max_error,
    };
    let (value, bytes, report) =
        circletree_core::encode::encode(wkb, &opts, call(srid, invalid_reason, &mut interrupt))
            .or_raise()
            .into_parts();
    notice_dropped_zm(&report);
    Some(CircleTree { value, bytes })
}

/// [`_ct_encode_wkb`]'s counterpart for `ct_encode_within`: the fewest bytes within `max_error`.
/// NULL geometry or max_error give NULL.
#[pg_extern(immutable, parallel_safe)]
fn _ct_encode_within_wkb(
    wkb: Option<&[u8]>,
    srid: Option<i32>,
    invalid_reason: Option<&str>,
    max_error: Option<f64>,
) -> Option<CircleTree> {
    let (wkb, max_error) = (wkb?, max_error?);
    crate::settings::check_encode_memory(
        wkb,
        crate::settings::ENCODE_WITHIN_BYTES_PER_VERTEX,
        "ct_encode_within",
    );
    let (value, bytes, report) = circletree_core::encode::encode_within(
        wkb,
        max_error,
        call(srid, invalid_reason, &mut interrupt),
    )
    .or_raise()
    .into_parts();
    notice_dropped_zm(&report);
    Some(CircleTree { value, bytes })
}

/// The metrics stroke a value's arcs to a hundredth of its grid: refuse one whose stroke would
/// exceed the decode limit before it is built.
fn measurable(ct: &CircleTree) {
    decode::check_size(
        &ct.value,
        circletree_core::check::measure_tolerance(&ct.value),
    )
    .or_raise();
}

fn original(wkb: &[u8]) -> Vec<circletree_core::geom::Polygon> {
    circletree_core::geom::wkb::read(wkb).or_raise().shape.parts
}

/// Area of the symmetric difference between the rebuilt value and a geometry (WKB). Release
/// 0.4.0's wrappers call this one; 0.5.0's pass the geometry's validity too.
#[pg_extern(immutable, strict, parallel_safe)]
fn _ct_sliver_error_wkb(ct: CircleTree, wkb: &[u8]) -> f64 {
    measurable(&ct);
    circletree_core::check::value_sliver(&ct.value, &original(wkb))
}

/// [`_ct_sliver_error_wkb`] refusing an invalid original (`invalid_reason` is PostGIS's
/// `ST_IsValidReason` when `ST_IsValid` is false): an area between an invalid polygon and the
/// rebuilt one is not defined (PostGIS's `ST_SymDifference` raises on such input too).
#[pg_extern(immutable, parallel_safe, name = "_ct_sliver_error_wkb")]
fn _ct_sliver_error_checked_wkb(
    ct: Option<CircleTree>,
    wkb: Option<&[u8]>,
    invalid_reason: Option<&str>,
) -> Option<f64> {
    let (ct, wkb) = (ct?, wkb?);
    if let Some(reason) = invalid_reason {
        crate::error::raise(circletree_core::Error::InvalidPolygon(reason.to_string()));
    }
    measurable(&ct);
    Some(circletree_core::check::value_sliver(
        &ct.value,
        &original(wkb),
    ))
}

/// True, or an ERROR when a longitude/latitude SRID (`lonlat`, read from spatial_ref_sys by the
/// SQL wrapper) meets a length of a degree or more: such lengths are metres given by mistake.
#[pg_extern(immutable, parallel_safe)]
fn _ct_check_degrees(
    lonlat: Option<bool>,
    srid: Option<i32>,
    min_radius: Option<f64>,
    dp_tolerance: Option<f64>,
    max_error: Option<f64>,
) -> bool {
    if lonlat == Some(true) {
        circletree_core::encode::check_degrees(
            srid.unwrap_or(0),
            &[
                ("min_radius", min_radius),
                ("dp_tolerance", dp_tolerance),
                ("max_error", max_error),
            ],
        )
        .or_raise();
    }
    true
}

/// Continuous Hausdorff distance between the rebuilt boundary and a geometry's boundary (WKB).
#[pg_extern(immutable, strict, parallel_safe)]
fn _ct_hausdorff_wkb(ct: CircleTree, wkb: &[u8]) -> f64 {
    measurable(&ct);
    circletree_core::check::value_hausdorff(&ct.value, &original(wkb), &mut interrupt)
}

/// Continuous Hausdorff distance between the boundaries of two (Multi)Polygons (WKB).
#[pg_extern(immutable, strict, parallel_safe)]
fn _ct_hausdorff_wkb2(a: &[u8], b: &[u8]) -> f64 {
    circletree_core::check::shape_hausdorff(&original(a), &original(b), &mut interrupt)
}

/// ct_memsize(ct) over the original's WKB bytes, both recorded in the value.
#[pg_extern(immutable, strict, parallel_safe)]
fn ct_storage_ratio(ct: CircleTree) -> Option<f64> {
    let w = ct.value.wkb_bytes;
    (w > 0).then(|| (ct.bytes.len() + pgrx::pg_sys::VARHDRSZ) as f64 / w as f64)
}

/// An SVG picture of the value (and of the original, from its WKB, when given): circles inside and
/// outside, boundary points, the rebuilt polygon, a legend. NULL value gives NULL; NULL width, 800.
#[pg_extern(immutable, parallel_safe)]
fn _ct_svg_wkb(ct: Option<CircleTree>, wkb: Option<&[u8]>, width: Option<i32>) -> Option<String> {
    let ct = ct?;
    let original = wkb.map(original);
    let width = width.unwrap_or(800);
    let width = u32::try_from(width).map_err(|_| circletree_core::Error::InvalidParameter {
        name: "width",
        value: width.to_string(),
        range: "a positive number of pixels".into(),
    });
    let (svg, _) = width
        .and_then(|w| circletree_core::decode::to_svg(&ct.value, original.as_deref(), w))
        .or_raise();
    Some(svg)
}
