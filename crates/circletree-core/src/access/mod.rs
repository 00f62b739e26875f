//! Access without a decode per call: a value rebuilt once into [`Prepared`] rings with an edge
//! index ([`strips::Strips`]), then asked where a point lies and how far it is.
//!
//! The answers are PostGIS's on `ct_decode(ct)`: the same rings (the decode at the value's own arc
//! tolerance) and the same floating-point arithmetic as PostGIS's point-in-polygon test (a
//! winding number; a point on a ring is on the boundary) and its point-to-segment distance, so a
//! point exactly on an edge or a vertex gets the answer PostGIS gives. Lines and polygons are
//! met with exact predicates, as GEOS meets them ([`Prepared::intersects_linework`]).

mod intersects;
pub mod strips;

use crate::decode;
use crate::format::CircleTree;
use crate::geom::{Kind, Pt};
use crate::Result;
use strips::Strips;

/// Where a point lies against a (multi)polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// In the interior.
    Inside,
    /// On a ring.
    Boundary,
    /// In the exterior.
    Outside,
}

/// A value's rings as `ct_decode` gives them, each with its edge index.
#[derive(Debug)]
pub struct Prepared {
    /// The SRID the value was encoded with.
    pub srid: i32,
    /// Polygon or MultiPolygon.
    pub kind: Kind,
    /// Every part: its shell, then its holes.
    pub parts: Vec<Vec<Strips>>,
    /// The box of every ring: `[xmin, ymin, xmax, ymax]` (`None` when empty).
    pub bbox: Option<[f64; 4]>,
}

impl Prepared {
    /// Rebuild a value as `ct_decode` does (the same rings, point for point) and index its edges.
    pub fn new(ct: &CircleTree) -> Result<Prepared> {
        let tol = decode::arc_tolerance(ct, None)?;
        decode::check_size(ct, tol)?;
        let parts: Vec<Vec<Strips>> = decode::polygons(ct, tol)
            .into_iter()
            .filter(|p| p.first().is_some_and(|s| !s.is_empty()))
            .map(|p| p.into_iter().map(Strips::new).collect())
            .collect();
        let bbox = parts
            .iter()
            .flat_map(|p| p.first())
            .map(|s| s.bbox)
            .reduce(|a, b| {
                [
                    a[0].min(b[0]),
                    a[1].min(b[1]),
                    a[2].max(b[2]),
                    a[3].max(b[3]),
                ]
            });
        Ok(Prepared {
            srid: ct.srid,
            kind: ct.kind,
            parts,
            bbox,
        })
    }

    /// The rings as `ct_decode`'s EWKB (the same bytes, without stroking the arcs again).
    pub fn ewkb(&self) -> Vec<u8> {
        let parts: Vec<Vec<Vec<Pt>>> = self
            .parts
            .iter()
            .map(|p| {
                p.iter()
                    .map(|r| r.pts[..r.pts.len() - 1].to_vec())
                    .collect()
            })
            .collect();
        crate::geom::wkb::write_ewkb(self.kind, &parts, self.srid)
    }

    /// Whether the value has no polygon.
    pub fn is_empty(&self) -> bool {
        self.parts.is_empty()
    }

    /// Bytes held (for the cache's bound).
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self
                .parts
                .iter()
                .flatten()
                .map(Strips::heap_bytes)
                .sum::<usize>()
    }

    /// Where `p` lies: on any ring is the boundary; inside a part's shell and in none of its holes
    /// is the interior.
    pub fn locate(&self, p: Pt) -> Location {
        if !self.bbox.is_some_and(|b| in_box(&b, p)) {
            return Location::Outside;
        }
        for part in &self.parts {
            match ring_location(&part[0], p) {
                Location::Outside => continue,
                Location::Boundary => return Location::Boundary,
                Location::Inside => {}
            }
            let mut inside = true;
            for hole in &part[1..] {
                match ring_location(hole, p) {
                    Location::Inside => {
                        inside = false;
                        break;
                    }
                    Location::Boundary => return Location::Boundary,
                    Location::Outside => {}
                }
            }
            if inside {
                return Location::Inside;
            }
        }
        Location::Outside
    }

    /// The distance from `p` to the (multi)polygon, as PostGIS's `ST_Distance` computes it: 0 in
    /// the interior or on the boundary; else, per part, the distance to its shell (outside it) or
    /// to the hole the point is in; the least over the parts. `None` when empty.
    pub fn distance(&self, p: Pt) -> Option<f64> {
        self.distance_within(p, f64::INFINITY)
    }

    /// Whether the distance from `p` is at most `d` (`ST_DWithin`; `d` not negative).
    pub fn dwithin(&self, p: Pt, d: f64) -> bool {
        let Some(b) = self.bbox else { return false };
        // Farther than d from the box (with room for rounding): farther from every edge.
        let slack = d
            + (d + b
                .iter()
                .fold(p[0].abs().max(p[1].abs()), |m, v| m.max(v.abs())))
                * 1e-12;
        if p[0] < b[0] - slack || p[0] > b[2] + slack || p[1] < b[1] - slack || p[1] > b[3] + slack
        {
            return false;
        }
        self.distance_within(p, d).is_some_and(|m| m <= d)
    }

    /// The least distance, looking only at edges that could be within `d` of `p` when `d` is
    /// finite (then a result above `d` only means "farther than d").
    fn distance_within(&self, p: Pt, d: f64) -> Option<f64> {
        if self.is_empty() {
            return None;
        }
        if self.locate(p) != Location::Outside {
            return Some(0.0);
        }
        let mut best = f64::INFINITY;
        for part in &self.parts {
            let ring = if ring_location(&part[0], p) == Location::Outside {
                &part[0]
            } else {
                match part[1..]
                    .iter()
                    .find(|h| ring_location(h, p) != Location::Outside)
                {
                    Some(h) => h,
                    None => continue, // inside this part: locate said otherwise (not reached)
                }
            };
            best = best.min(ring_distance(ring, p, d));
            if best <= d && d.is_finite() {
                break;
            }
        }
        Some(best)
    }
}

fn in_box(b: &[f64; 4], p: Pt) -> bool {
    p[0] >= b[0] && p[0] <= b[2] && p[1] >= b[1] && p[1] <= b[3]
}

/// PostGIS's point in ring: a winding number over the edges that span the point's y, a point with
/// an exactly zero side within an edge's box is on the ring (the `determineSide` and
/// `isOnSegment` of liblwgeom's point_in_ring; edges shorter than 1e-12 are skipped).
fn ring_location(ring: &Strips, p: Pt) -> Location {
    if !in_box(&ring.bbox, p) {
        return Location::Outside;
    }
    let mut wn = 0i64;
    for (a, b) in ring.edges_at(p[1]) {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        if dx * dx + dy * dy < 1e-12 * 1e-12 {
            continue;
        }
        let side = dx * (p[1] - a[1]) - (p[0] - a[0]) * dy;
        if side == 0.0
            && p[0] >= a[0].min(b[0])
            && p[0] <= a[0].max(b[0])
            && p[1] >= a[1].min(b[1])
            && p[1] <= a[1].max(b[1])
        {
            return Location::Boundary;
        }
        if a[1] <= p[1] && p[1] < b[1] && side > 0.0 {
            wn += 1;
        } else if b[1] <= p[1] && p[1] < a[1] && side < 0.0 {
            wn -= 1;
        }
    }
    if wn == 0 {
        Location::Outside
    } else {
        Location::Inside
    }
}

/// The least point-to-segment distance over a ring's edges (liblwgeom's `lw_dist2d_pt_seg`: the
/// projection's parameter clamped to the ends, the foot point, then the hypotenuse), looking only
/// at the strips within `d` of the point when `d` is finite.
fn ring_distance(ring: &Strips, p: Pt, d: f64) -> f64 {
    let mut best = f64::INFINITY;
    let mut see = |a: Pt, b: Pt| {
        best = best.min(segment_distance(p, a, b));
    };
    if d.is_finite() {
        let reach = d * (1.0 + 1e-9) + 1e-300;
        for (a, b) in ring.edges_between(p[1] - reach, p[1] + reach) {
            if a[0].min(b[0]) - reach <= p[0] && p[0] <= a[0].max(b[0]) + reach {
                see(a, b);
            }
        }
    } else {
        for (a, b) in ring.all_edges() {
            see(a, b);
        }
    }
    best
}

fn point_distance(p: Pt, q: Pt) -> f64 {
    let (h, v) = (q[0] - p[0], q[1] - p[1]);
    (h * h + v * v).sqrt()
}

fn segment_distance(p: Pt, a: Pt, b: Pt) -> f64 {
    if a == b {
        return point_distance(p, a);
    }
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let r = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy);
    if r < 0.0 {
        return point_distance(p, a);
    }
    if r >= 1.0 {
        return point_distance(p, b);
    }
    if (a[1] - p[1]) * dx == (a[0] - p[0]) * dy {
        return 0.0;
    }
    point_distance(p, [a[0] + r * dx, a[1] + r * dy])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::encode;

    pub(super) fn prepared(wkt: &str, max_error: f64) -> Prepared {
        let g: geo_types::Geometry<f64> = wkt::TryFromWkt::try_from_wkt_str(wkt).unwrap();
        let mut wkb = Vec::new();
        ::wkb::writer::write_geometry(&mut wkb, &g, &Default::default()).unwrap();
        let ct = encode::encode_within(&wkb, max_error, encode::Call::new(0))
            .unwrap()
            .into_parts()
            .0;
        Prepared::new(&ct).unwrap()
    }

    #[test]
    fn a_square_with_a_hole_and_a_second_part() {
        let p = prepared(
            "MULTIPOLYGON(((0 0,10 0,10 10,0 10,0 0),(2 2,2 8,8 8,8 2,2 2)),((20 0,30 0,30 10,20 10,20 0)))",
            0.01,
        );
        // the rebuilt rings (on the value's grid, within 0.01 of the input's)
        let (shell, hole) = (&p.parts[0][0].pts, &p.parts[0][1].pts);
        let mid = |a: Pt, b: Pt| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        use Location::*;
        for (pt, want) in [
            ([1.0, 1.0], Inside),
            ([5.0, 5.0], Outside), // in the hole
            (hole[0], Boundary),
            (mid(hole[0], hole[1]), Boundary),
            (shell[2], Boundary),
            (mid(shell[1], shell[2]), Boundary),
            ([25.0, 5.0], Inside),
            ([15.0, 5.0], Outside),
            ([shell[0][0], 12.0], Outside), // in line with an edge
            ([-1.0, 0.0], Outside),
        ] {
            assert_eq!(p.locate(pt), want, "{pt:?}");
        }
        assert_eq!(p.distance([1.0, 1.0]), Some(0.0));
        let to_hole = p.distance([5.0, 5.0]).unwrap(); // to the hole's ring
        assert!((to_hole - (5.0 - hole[0][0]).min(hole[2][0] - 5.0)).abs() < 1e-12);
        let gap = p.parts[1][0].pts[0][0] - shell[1][0];
        let between = p.distance([shell[1][0] + gap / 2.0, 5.0]).unwrap();
        assert!((between - gap / 2.0).abs() < 1e-12);
        let c = shell[2];
        assert_eq!(p.distance([c[0] + 3.0, c[1] + 4.0]), Some(5.0)); // to the corner
        assert!(p.dwithin([5.0, 5.0], to_hole) && !p.dwithin([5.0, 5.0], to_hole * 0.99));
        assert!(!p.dwithin([1e6, 5.0], 10.0));
    }

    /// A star of `n` points, 1000 and 600 from the origin in turn, encoded within 1.
    pub(super) fn star(n: usize) -> Prepared {
        let ring: Vec<String> = (0..=n)
            .map(|i| {
                let t = (i % n) as f64 / n as f64 * std::f64::consts::TAU;
                let r = if i % 2 == 0 { 1000.0 } else { 600.0 };
                format!("{} {}", r * t.cos(), r * t.sin())
            })
            .collect();
        prepared(&format!("POLYGON(({}))", ring.join(",")), 1.0)
    }

    #[test]
    fn the_edge_index_gives_the_full_scan_s_answers() {
        // A many-sided star: every query compared with a scan of every edge.
        let p = star(400);
        let mut u = crate::test_uniform(3);
        for _ in 0..3000 {
            let q = [2400.0 * u() - 1200.0, 2400.0 * u() - 1200.0];
            let full = p.parts[0][0]
                .all_edges()
                .map(|(a, b)| segment_distance(q, a, b))
                .fold(f64::INFINITY, f64::min);
            let inside = p.locate(q) != Location::Outside;
            let want = if inside { 0.0 } else { full };
            assert_eq!(p.distance(q), Some(want));
            for d in [1.0, 50.0, 300.0] {
                assert_eq!(p.dwithin(q, d), want <= d, "{q:?} {d}");
            }
        }
    }

    #[test]
    fn its_ewkb_is_ct_decode_s() {
        let wkt = "MULTIPOLYGON(((0 0,10 0,10 10,0 10,0 0),(2 2,2 8,8 8,8 2,2 2)),((20 0,30 0,30 10,20 10,20 0)))";
        let g: geo_types::Geometry<f64> = wkt::TryFromWkt::try_from_wkt_str(wkt).unwrap();
        let mut wkb = Vec::new();
        ::wkb::writer::write_geometry(&mut wkb, &g, &Default::default()).unwrap();
        let ct = encode::encode_within(&wkb, 0.5, encode::Call::new(3857))
            .unwrap()
            .into_parts()
            .0;
        let p = Prepared::new(&ct).unwrap();
        assert_eq!(p.ewkb(), decode::to_ewkb(&ct, None).unwrap());
    }

    #[test]
    fn an_empty_value_meets_nothing() {
        let p = prepared("POLYGON EMPTY", 1.0);
        assert!(p.is_empty());
        assert_eq!(p.locate([0.0, 0.0]), Location::Outside);
        assert_eq!(p.distance([0.0, 0.0]), None);
        assert!(!p.dwithin([0.0, 0.0], 1e9));
    }
}
