//! From a stored value back to geometry: circles on the grid to coordinates, rings rebuilt with
//! [`crate::decode::reconstruct`], stroked to a chord tolerance (WKB) or kept as true arcs (curved WKT).

pub(crate) mod picture;
pub(crate) mod reconstruct;

pub use picture::to_svg;

use crate::decode::reconstruct::{point_ring, ring_wkt, stroke_ring};
use crate::error::{Error, Result};
use crate::format::grid::Grid;
use crate::format::{Circle, CircleTree};
use crate::geom::{Kind, Polygon, Pt};

/// Grid steps to coordinates: `q × mantissa / 10^k` in one correctly rounded operation.
/// The value's grid ([`Grid::coord`] is the one conversion every reader and writer uses).
pub fn scale(ct: &CircleTree) -> impl Fn(i64) -> f64 {
    let g = Grid::new(ct.grid);
    move |q: i64| g.coord(q)
}

/// A ring's circles as `(x, y, ρ)` coordinates.
pub fn ring_circles(ct: &CircleTree, ring: &[Circle]) -> Vec<[f64; 3]> {
    let f = scale(ct);
    ring.iter().map(|c| [f(c.x), f(c.y), f(c.r)]).collect()
}

/// Below this fraction of a value's largest radius an arc tolerance may need more chords than
/// [`crate::decode::reconstruct::MAX_ARC_SEGMENTS`] on some arc (a full circle stroked at it takes 4,056),
/// so the arcs themselves are measured ([`finest_tolerance`]).
pub const MIN_TOLERANCE_PER_RADIUS: f64 = 3e-7;

/// The finest tolerance at which no arc of the value needs more than `MAX_ARC_SEGMENTS` chords.
pub fn finest_tolerance(ct: &CircleTree) -> f64 {
    let mut worst = 0.0f64;
    for ring in ct.parts.iter().flatten() {
        for seg in crate::decode::reconstruct::ring_spans(&ring_circles(ct, ring))
            .iter()
            .flatten()
        {
            if let crate::decode::reconstruct::Seg::Arc { r, sweep, .. } = *seg {
                let step = sweep.abs() / (crate::decode::reconstruct::MAX_ARC_SEGMENTS - 1) as f64;
                worst = worst.max(r * (1.0 - (step / 2.0).cos()));
            }
        }
    }
    worst
}

/// `x` rounded up to two significant digits (a number a message can show and a user can type).
fn round_up_2(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return 0.0;
    }
    let e = x.log10().floor() as i32 - 1;
    if e < 0 {
        (x * 10f64.powi(-e)).ceil() / 10f64.powi(-e)
    } else {
        (x / 10f64.powi(e)).ceil() * 10f64.powi(e)
    }
}

/// Check an arc tolerance (`None` means the grid step). A tolerance so fine that some arc would
/// need more than `MAX_ARC_SEGMENTS` chords is refused, never silently stroked coarser; by
/// default (`None`) such a value is stroked at the finest tolerance it allows.
pub fn arc_tolerance(ct: &CircleTree, tol: Option<f64>) -> Result<f64> {
    let t = match tol {
        None => ct.grid_f64(),
        Some(t) if t.is_finite() && t > 0.0 => t,
        Some(t) => {
            return Err(Error::InvalidParameter {
                name: "arc_tolerance",
                value: crate::error::number(t),
                range: "a positive, finite length".into(),
            })
        }
    };
    let rmax = ct
        .parts
        .iter()
        .flatten()
        .flatten()
        .map(|c| c.r.unsigned_abs())
        .max()
        .unwrap_or(0) as f64
        * ct.grid_f64();
    if t >= rmax * MIN_TOLERANCE_PER_RADIUS {
        return Ok(t);
    }
    let finest = round_up_2(finest_tolerance(ct));
    match tol {
        _ if t >= finest => Ok(t),
        None => Ok(finest),
        Some(_) => Err(Error::InvalidParameter {
            name: "arc_tolerance",
            value: crate::error::number(t),
            range: format!(
                "at least {} for this value (finer, an arc of one of its circles would need more \
                 than {} chords)",
                crate::error::number(finest),
                crate::decode::reconstruct::MAX_ARC_SEGMENTS
            ),
        }),
    }
}

/// Rebuild every ring, arcs stroked so no chord is farther than `tol` from its arc.
/// Degenerate rings are padded to the 4 points WKB readers demand (they stay invalid).
pub fn polygons(ct: &CircleTree, tol: f64) -> Vec<Polygon> {
    ct.parts
        .iter()
        .map(|part| {
            part.iter()
                .map(|ring| {
                    let mut pts: Vec<Pt> = if ring.iter().all(|c| c.r == 0) {
                        let f = scale(ct);
                        point_ring(ring.iter().map(|c| [f(c.x), f(c.y)]))
                    } else {
                        stroke_ring(&ring_circles(ct, ring), tol)
                    };
                    while !pts.is_empty() && pts.len() < 3 {
                        pts.push(pts[pts.len() - 1]);
                    }
                    pts
                })
                .collect()
        })
        .collect()
}

/// The most points a decode may produce: 16 WKB bytes each, so the result stays below
/// PostgreSQL's 1 GB limit for one value (and is refused before anything that size is built).
pub const MAX_DECODED_POINTS: usize = 60_000_000;

/// The number of points `polygons(ct, tol)` would produce, at most (its rings before repeated
/// points are removed). Cheap when every circle stroked whole would stay under the limit;
/// otherwise the arcs are measured.
pub fn stroked_points(ct: &CircleTree, tol: f64) -> usize {
    let circles = || ct.parts.iter().flatten().flatten();
    let g = ct.grid_f64();
    let whole: usize = circles()
        .map(|c| {
            1 + crate::decode::reconstruct::arc_segments(
                c.r.unsigned_abs() as f64 * g,
                std::f64::consts::TAU,
                tol,
            )
        })
        .fold(0usize, usize::saturating_add);
    if whole <= MAX_DECODED_POINTS {
        return whole;
    }
    let mut n = 0usize;
    for ring in ct.parts.iter().flatten() {
        for seg in crate::decode::reconstruct::ring_spans(&ring_circles(ct, ring))
            .iter()
            .flatten()
        {
            n = n.saturating_add(match *seg {
                crate::decode::reconstruct::Seg::Line(..) => 1,
                crate::decode::reconstruct::Seg::Arc { r, sweep, .. } => {
                    crate::decode::reconstruct::arc_segments(r, sweep, tol)
                }
            });
        }
    }
    n
}

/// Refuse a decode that would produce more than [`MAX_DECODED_POINTS`] points.
pub fn check_size(ct: &CircleTree, tol: f64) -> Result<()> {
    let n = stroked_points(ct, tol);
    if n > MAX_DECODED_POINTS {
        return Err(Error::TooLarge(format!(
            "decoding this value at arc tolerance {} would give {n} points, more than the {} \
             (about 1 GB of geometry) one value can hold",
            crate::error::number(tol),
            MAX_DECODED_POINTS
        )));
    }
    Ok(())
}

/// The rebuilt geometry as ISO WKB.
pub fn to_wkb(ct: &CircleTree, tol: Option<f64>) -> Result<Vec<u8>> {
    rebuilt_ewkb(ct, tol, 0)
}

/// The rebuilt geometry as PostGIS's EWKB: ISO WKB with the value's SRID in it (when not 0), so
/// that one decode gives PostGIS everything (`ST_GeomFromEWKB`).
pub fn to_ewkb(ct: &CircleTree, tol: Option<f64>) -> Result<Vec<u8>> {
    rebuilt_ewkb(ct, tol, ct.srid)
}

fn rebuilt_ewkb(ct: &CircleTree, tol: Option<f64>, srid: i32) -> Result<Vec<u8>> {
    let tol = arc_tolerance(ct, tol)?;
    check_size(ct, tol)?;
    Ok(crate::geom::wkb::write_ewkb(
        ct.kind,
        &polygons(ct, tol),
        srid,
    ))
}

/// The envelope of a stored value as EWKB, from its header alone ([`CircleTree::envelope`]): a
/// Polygon box holding the original and the rebuilt geometry, SRID kept; an empty Polygon for an
/// empty value.
pub fn envelope_ewkb(bytes: &[u8]) -> Result<Vec<u8>> {
    let (srid, bbox) = CircleTree::envelope(bytes)?;
    let ring = bbox.map(|[x0, y0, x1, y1]| vec![vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]]);
    Ok(crate::geom::wkb::write_ewkb(
        Kind::Polygon,
        &ring.into_iter().collect::<Vec<_>>(),
        srid,
    ))
}

/// The rebuilt geometry with true arcs as EWKT, `SRID=n;` first when the SRID is not 0.
pub fn to_curved_ewkt(ct: &CircleTree) -> String {
    let wkt = to_curved_wkt(ct);
    if ct.srid == 0 {
        wkt
    } else {
        format!("SRID={};{wkt}", ct.srid)
    }
}

/// The rebuilt geometry with true arcs: `CURVEPOLYGON` or `MULTISURFACE` WKT.
pub fn to_curved_wkt(ct: &CircleTree) -> String {
    let mut s = String::new();
    let poly = |s: &mut String, part: &Vec<Vec<Circle>>| {
        s.push_str("CURVEPOLYGON(");
        for (i, ring) in part.iter().enumerate() {
            if i > 0 {
                s.push(',');
            }
            ring_wkt(&ring_circles(ct, ring), s);
        }
        s.push(')');
    };
    match ct.kind {
        Kind::Polygon => match ct.parts.first() {
            None => s.push_str("CURVEPOLYGON EMPTY"),
            Some(p) => poly(&mut s, p),
        },
        Kind::MultiPolygon => {
            if ct.parts.is_empty() {
                s.push_str("MULTISURFACE EMPTY");
            } else {
                s.push_str("MULTISURFACE(");
                for (i, p) in ct.parts.iter().enumerate() {
                    if i > 0 {
                        s.push(',');
                    }
                    poly(&mut s, p);
                }
                s.push(')');
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decode::reconstruct::{arc_segments, MAX_ARC_SEGMENTS};

    #[test]
    fn ewkb_carries_the_srid_once() {
        let poly = vec![vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]];
        for (kind, parts, code) in [
            (Kind::MultiPolygon, vec![poly.clone(), poly.clone()], 6u32),
            (Kind::Polygon, vec![poly.clone()], 3),
            (Kind::Polygon, vec![], 3),
        ] {
            let wkb = crate::geom::wkb::write(kind, &parts);
            let e = crate::geom::wkb::write_ewkb(kind, &parts, 32760);
            assert_eq!(e.len(), wkb.len() + 4);
            assert_eq!(&e[1..5], &(code | 0x2000_0000).to_le_bytes());
            assert_eq!(&e[5..9], &32760i32.to_le_bytes());
            // the nested polygons carry no SRID: the rest is the WKB's
            assert_eq!(&e[9..], &wkb[5..]);
            assert_eq!(crate::geom::wkb::write_ewkb(kind, &parts, 0), wkb);
        }
    }

    #[test]
    fn the_finest_tolerance_strokes_every_arc_within_the_cap() {
        for r in [1.0, 37.5, 1e6] {
            let k = arc_segments(r, std::f64::consts::TAU, r * MIN_TOLERANCE_PER_RADIUS);
            assert!(k < MAX_ARC_SEGMENTS, "{k} chords for radius {r}");
        }
        // one circle, its whole boundary one arc of radius 100
        let ct = crate::format::text::from_text(
            "CIRCLETREE(version=2;grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;\
             vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,200 200);POLYGON((100 100 100)))",
        )
        .unwrap();
        let f = finest_tolerance(&ct);
        assert!(f > 2e-5 && f < 3e-5, "{f}");
        let circle = |t: f64| polygons(&ct, t)[0][0].len();
        assert_eq!(arc_tolerance(&ct, Some(3e-5)).unwrap(), 3e-5);
        assert!(circle(3e-5) <= MAX_ARC_SEGMENTS);
        let err = arc_tolerance(&ct, Some(1e-300)).unwrap_err().to_string();
        assert!(
            err.contains("1e-300") && err.contains("at least 0.00003 "),
            "{err}"
        );
        assert!(arc_tolerance(&ct, Some(f64::NAN)).is_err());
        assert_eq!(arc_tolerance(&ct, None).unwrap(), 0.5);
    }

    #[test]
    fn a_decode_beyond_a_value_s_limit_is_refused_before_it_is_built() {
        // 30,000 parts, each one circle of radius 1,000,000: about 2,221 chords each at the grid
        let disc = "(1000000 1000000 1000000)";
        let parts = vec![format!("({disc})"); 30_000].join(",");
        let ct = crate::format::text::from_text(&format!(
            "CIRCLETREE(version=2;grid=1;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;\
             vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,2000000 2000000);MULTIPOLYGON({parts}))"
        ))
        .unwrap();
        let n = stroked_points(&ct, 1.0);
        assert!(n > MAX_DECODED_POINTS && n < 70_000_000, "{n}");
        let err = to_wkb(&ct, None).unwrap_err();
        assert!(matches!(err, Error::TooLarge(_)), "{err}");
        assert!(err.to_string().contains("60000000"), "{err}");
        // coarser, it decodes; the count bounds what is built
        assert!(stroked_points(&ct, 10_000.0) < MAX_DECODED_POINTS);
        let few = crate::format::text::from_text(&format!(
            "CIRCLETREE(version=2;grid=1;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;\
             vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,2000000 2000000);MULTIPOLYGON(({disc})))"
        ))
        .unwrap();
        let built: usize = polygons(&few, 1.0).iter().flatten().map(Vec::len).sum();
        assert!(
            built <= stroked_points(&few, 1.0) && built > 2000,
            "{built}"
        );
    }
}
