//! The minimum clearance of a shape (PostGIS's `ST_MinimumClearance`): the least distance from a
//! vertex to a segment of any ring that does not end at it. Moving every vertex by less than half
//! of it cannot make a valid shape cross itself, so it tells how fine a grid must be to hold the
//! shape with every vertex kept.
//!
//! Distances of exactly zero are left out: in a valid shape they are the points where rings touch,
//! which the encoder keeps as shared vertices on every grid.

use super::box_grid::{Bbox, BoxIndex};
use super::{dist_to_segment, Pt, Shape};

/// The minimum clearance if it is below `radius`; otherwise `radius` or more (the search looks no
/// farther than `radius` from each vertex).
pub(crate) fn below(shape: &Shape, radius: f64) -> f64 {
    let rings: Vec<&[Pt]> = shape.rings().map(|r| r.as_slice()).collect();
    let mut segments: Vec<(Bbox, (u32, u32))> = Vec::new();
    for (ri, ring) in rings.iter().enumerate() {
        let n = ring.len();
        for i in 0..n {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            segments.push((
                [
                    a[0].min(b[0]),
                    a[1].min(b[1]),
                    a[0].max(b[0]),
                    a[1].max(b[1]),
                ],
                (ri as u32, i as u32),
            ));
        }
    }
    if segments.is_empty() {
        return f64::INFINITY;
    }
    let index = BoxIndex::new(segments);
    let mut best = f64::INFINITY;
    for (ri, ring) in rings.iter().enumerate() {
        let n = ring.len();
        for (v, &p) in ring.iter().enumerate() {
            let r = best.min(radius);
            let q = [p[0] - r, p[1] - r, p[0] + r, p[1] + r];
            index.for_each_meeting(&q, |(sr, si)| {
                let (sr, si) = (sr as usize, si as usize);
                // the two segments that end at this vertex
                if sr == ri && (si == v || (si + 1) % n == v) {
                    return;
                }
                let s = rings[sr];
                let d = dist_to_segment(p, s[si], s[(si + 1) % s.len()]);
                if d > 0.0 && d < best {
                    best = d;
                }
            });
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Kind;

    fn shape(parts: Vec<Vec<Vec<Pt>>>) -> Shape {
        Shape {
            kind: Kind::Polygon,
            parts,
        }
    }

    #[test]
    fn a_thin_triangle_and_a_hole_near_its_shell() {
        // POLYGON((0 0, 1000 0, 1000 0.000001, 0 0)): ST_MinimumClearance gives about 1e-6
        let thin = shape(vec![vec![vec![[0.0, 0.0], [1000.0, 0.0], [1000.0, 1e-6]]]]);
        let c = below(&thin, 1.0);
        assert!((c - 1e-6).abs() < 1e-9, "{c}");
        // a hole 0.25 from its shell's edge
        let sq =
            |x0: f64, y0: f64, s: f64| vec![[x0, y0], [x0 + s, y0], [x0 + s, y0 + s], [x0, y0 + s]];
        let holed = shape(vec![vec![sq(0.0, 0.0, 10.0), sq(0.25, 2.0, 3.0)]]);
        assert_eq!(below(&holed, 1.0), 0.25);
        // nothing within the radius: the radius or more
        assert!(below(&holed, 0.1) >= 0.1);
    }

    #[test]
    fn rings_touching_at_a_vertex_are_left_out() {
        // two squares sharing the corner (10 10), otherwise 10 apart
        let a = vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
        let b = vec![[10.0, 10.0], [20.0, 10.0], [20.0, 20.0], [10.0, 20.0]];
        let touching = Shape {
            kind: Kind::MultiPolygon,
            parts: vec![vec![a], vec![b]],
        };
        assert_eq!(below(&touching, 100.0), 10.0);
    }
}
