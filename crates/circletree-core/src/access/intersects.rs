//! Whether a prepared value meets lines or polygons, with exact predicates (Shewchuk's
//! `orient2d`), as GEOS decides `ST_Intersects` exactly on the same coordinates.
//!
//! Two closed sets meet if a segment of one touches a segment of the other. If none does, each
//! ring and line of one lies wholly inside or wholly outside the other, so one vertex of each
//! decides: a line or ring of the geometry in the value's interior, or a ring of the value in the
//! polygon's interior.

use super::Prepared;
use crate::check::validity::segments_touch;
use crate::geom::gserialized::Linework;
use crate::geom::Pt;
use robust::{orient2d, Coord};

fn side(a: Pt, b: Pt, p: Pt) -> f64 {
    orient2d(
        Coord { x: a[0], y: a[1] },
        Coord { x: b[0], y: b[1] },
        Coord { x: p[0], y: p[1] },
    )
}

fn boxes_meet(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3]
}

fn segment_box(a: Pt, b: Pt) -> [f64; 4] {
    [
        a[0].min(b[0]),
        a[1].min(b[1]),
        a[0].max(b[0]),
        a[1].max(b[1]),
    ]
}

/// The winding number of a closed ring's edges around `p` (not on the ring), exactly.
fn winding(edges: impl Iterator<Item = (Pt, Pt)>, p: Pt) -> i64 {
    let mut wn = 0;
    for (a, b) in edges {
        if a[1] <= p[1] && p[1] < b[1] && side(a, b, p) > 0.0 {
            wn += 1;
        } else if b[1] <= p[1] && p[1] < a[1] && side(a, b, p) < 0.0 {
            wn -= 1;
        }
    }
    wn
}

impl Prepared {
    /// Whether a segment touches any edge of the value.
    fn touches_segment(&self, c: Pt, d: Pt) -> bool {
        let sb = segment_box(c, d);
        self.parts.iter().flatten().any(|ring| {
            boxes_meet(&ring.bbox, &sb)
                && ring
                    .edges_between(sb[1], sb[3])
                    .any(|(a, b)| boxes_meet(&segment_box(a, b), &sb) && segments_touch(a, b, c, d))
        })
    }

    /// Whether `p`, on no ring of the value, is in its interior (exactly).
    fn holds(&self, p: Pt) -> bool {
        self.parts.iter().any(|part| {
            let inside =
                |r: &super::Strips| super::in_box(&r.bbox, p) && winding(r.edges_at(p[1]), p) != 0;
            inside(&part[0]) && !part[1..].iter().any(inside)
        })
    }

    /// Whether the value and the lines or polygons share a point (`ST_Intersects` on
    /// `ct_decode(ct)`); false when either is empty.
    pub fn intersects_linework(&self, lw: &Linework) -> bool {
        let Some(bbox) = self.bbox else { return false };
        let rings: Vec<&[Pt]> = match lw {
            Linework::Lines(l) => l.iter().map(Vec::as_slice).collect(),
            Linework::Polygons(p) => p.iter().flatten().map(Vec::as_slice).collect(),
        };
        let edges = || {
            rings
                .iter()
                .flat_map(|r| r.windows(2).map(|w| (w[0], w[1])))
                .chain(rings.iter().filter(|r| r.len() == 1).map(|r| (r[0], r[0])))
        };
        for (c, d) in edges() {
            if boxes_meet(&segment_box(c, d), &bbox) && self.touches_segment(c, d) {
                return true;
            }
        }
        // No segment touches: a line or ring of the geometry inside the value's interior ...
        if rings
            .iter()
            .filter_map(|r| r.first())
            .any(|&p| self.holds(p))
        {
            return true;
        }
        // ... or a ring of the value inside the polygons' interior.
        let Linework::Polygons(polys) = lw else {
            return false;
        };
        self.parts.iter().flatten().any(|ring| {
            let p = ring.pts[0];
            polys.iter().any(|poly| {
                let inside = |r: &Vec<Pt>| winding(r.windows(2).map(|w| (w[0], w[1])), p) != 0;
                poly.first().is_some_and(inside) && !poly[1..].iter().any(inside)
            })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{prepared, star};
    use super::super::Location;
    use super::*;

    fn lines(wkt: &[&[Pt]]) -> Linework {
        Linework::Lines(wkt.iter().map(|l| l.to_vec()).collect())
    }

    fn window(x0: f64, y0: f64, x1: f64, y1: f64) -> Linework {
        Linework::Polygons(vec![vec![vec![
            [x0, y0],
            [x1, y0],
            [x1, y1],
            [x0, y1],
            [x0, y0],
        ]]])
    }

    #[test]
    fn windows_and_lines_against_a_square_with_a_hole_and_a_second_part() {
        let p = prepared(
            "MULTIPOLYGON(((0 0,10 0,10 10,0 10,0 0),(2 2,2 8,8 8,8 2,2 2)),((20 0,30 0,30 10,20 10,20 0)))",
            0.01,
        );
        let shell = p.parts[0][0].pts.clone();
        let hole = p.parts[0][1].pts.clone();
        let (hx0, hx1) = (hole[0][0].min(hole[2][0]), hole[0][0].max(hole[2][0]));
        for (lw, want) in [
            (window(1.0, 1.0, 1.5, 1.5), true),             // in the interior
            (window(4.0, 4.0, 6.0, 6.0), false),            // in the hole
            (window(-5.0, -5.0, 40.0, 40.0), true),         // around everything
            (window(12.0, 0.0, 18.0, 10.0), false),         // between the parts
            (window(hx0 + 1.0, 4.0, hx1 + 1.0, 6.0), true), // across the hole's ring
            (window(shell[2][0], shell[2][1], 15.0, 15.0), true), // at a corner
            (window(shell[2][0] + 1e-9, 11.0, 15.0, 15.0), false),
            (lines(&[&[[4.0, 4.0], [6.0, 6.0]]]), false), // in the hole
            (
                lines(&[&[[4.0, 4.0], [6.0, 6.0]], &[[25.0, 5.0], [26.0, 5.0]]]),
                true,
            ),
            (lines(&[&[[15.0, -5.0], [15.0, 15.0]]]), false),
            (lines(&[&[hole[0], [5.0, 5.0]]]), true), // from a vertex into the hole
            (lines(&[&[[-1.0, -1.0], shell[0]]]), true), // to a vertex
            (lines(&[&[[25.0, 5.0]]]), true),         // one point
            (Linework::Lines(vec![]), false),
            (Linework::Polygons(vec![]), false),
        ] {
            assert_eq!(p.intersects_linework(&lw), want, "{lw:?}");
        }
        let empty = prepared("POLYGON EMPTY", 1.0);
        assert!(!empty.intersects_linework(&window(-1e9, -1e9, 1e9, 1e9)));
    }

    #[test]
    fn windows_agree_with_the_points_they_hold() {
        // A star: a window meets it iff one of its points does, sampled finely; windows far from
        // the ring's edges are decided by one vertex, windows on them by a segment.
        let p = star(300);
        let mut u = crate::test_uniform(11);
        for _ in 0..400 {
            let (x, y, w) = (2400.0 * u() - 1200.0, 2400.0 * u() - 1200.0, 60.0 * u());
            let got = p.intersects_linework(&window(x, y, x + w, y + w));
            // the window's boundary and interior sampled on a grid
            let k = 40;
            let any = (0..=k).any(|i| {
                (0..=k).any(|j| {
                    let q = [x + w * i as f64 / k as f64, y + w * j as f64 / k as f64];
                    p.locate(q) != Location::Outside
                })
            });
            if any {
                assert!(got, "window at {x} {y} of {w} holds a point of the star");
            }
            if !got {
                assert!(!p.holds([x, y]));
            }
        }
    }
}
