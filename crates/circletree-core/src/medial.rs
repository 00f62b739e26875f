//! Candidate circles from the medial axis (paper section 3.1): the circumcircles of the triangles
//! of a constrained Delaunay triangulation of one ring (spade), i.e. the Voronoi vertices of the
//! ring's points. A triangle on the polygon's side of the ring gives a positive radius (internal
//! circle), one on the other side a negative radius (external circle, section 3.4).
//!
//! The ring's edges are the constraints, so every triangle lies wholly on one side: a triangle with
//! a ring edge knows its side from the edge's direction, the others inherit it by flood fill across
//! unconstrained edges. Coordinates are moved to a local origin first (circumcentres of UTM-sized
//! coordinates lose digits). Cost: O(n log n).

use crate::geometry::Pt;
use spade::handles::FixedFaceHandle;
use spade::{ConstrainedDelaunayTriangulation, HasPosition, Point2, Triangulation};

/// A candidate circle: centre, signed radius, and the ring vertices it passes through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    /// Centre.
    pub c: Pt,
    /// Signed radius: `> 0` on the polygon's side of the ring, `< 0` on the other.
    pub r: f64,
    /// Indices of the three ring vertices on the circle.
    pub verts: [usize; 3],
}

#[derive(Clone, Copy, Debug)]
struct V {
    p: Point2<f64>,
    i: usize,
}

impl HasPosition for V {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.p
    }
}

/// Candidate circles of one ring (open, oriented with the polygon on its left).
/// Returns an empty list when the ring crosses itself (the triangulation reports a conflict).
pub fn candidates(ring: &[Pt], interrupt: &mut dyn FnMut()) -> Vec<Candidate> {
    let n = ring.len();
    if n < 3 {
        return vec![];
    }
    let o = ring[0];
    let verts: Vec<V> = ring
        .iter()
        .enumerate()
        .map(|(i, p)| V {
            p: Point2::new(p[0] - o[0], p[1] - o[1]),
            i,
        })
        .collect();
    let edges: Vec<[usize; 2]> = (0..n).map(|i| [i, (i + 1) % n]).collect();
    let mut conflict = false;
    let Ok(cdt) =
        ConstrainedDelaunayTriangulation::<V>::try_bulk_load_cdt(verts, edges, |_| conflict = true)
    else {
        return vec![];
    };
    if conflict || cdt.num_vertices() != n {
        return vec![];
    }
    interrupt();
    // side[f]: Some(true) = polygon side (left of the ring)
    let nf = cdt.all_faces().len();
    let mut side: Vec<Option<bool>> = vec![None; nf];
    let mut queue: Vec<FixedFaceHandle<spade::handles::InnerTag>> = Vec::new();
    for face in cdt.inner_faces() {
        for e in face.adjacent_edges() {
            if e.is_constraint_edge() {
                let (a, b) = (e.from().data().i, e.to().data().i);
                // Faces lie to the left of their own (counter-clockwise) edges.
                side[face.fix().index()] = Some(b == (a + 1) % n);
                queue.push(face.fix());
                break;
            }
        }
    }
    while let Some(f) = queue.pop() {
        let face = cdt.face(f);
        let s = side[f.index()];
        for e in face.adjacent_edges() {
            if e.is_constraint_edge() {
                continue;
            }
            if let Some(other) = e.rev().face().as_inner() {
                let k = other.fix().index();
                if side[k].is_none() {
                    side[k] = s;
                    queue.push(other.fix());
                }
            }
        }
    }
    let mut out = Vec::with_capacity(cdt.num_inner_faces());
    for (k, face) in cdt.inner_faces().enumerate() {
        if k % 4096 == 0 {
            interrupt();
        }
        let Some(inside) = side[face.fix().index()] else {
            continue;
        };
        let (c, r2) = face.circumcircle();
        if !(r2.is_finite() && c.x.is_finite() && c.y.is_finite()) || r2 <= 0.0 {
            continue;
        }
        let r = r2.sqrt();
        let vs = face.vertices();
        out.push(Candidate {
            c: [c.x + o[0], c.y + o[1]],
            r: if inside { r } else { -r },
            verts: [vs[0].data().i, vs[1].data().i, vs[2].data().i],
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_gives_one_internal_circle_per_triangle() {
        let sq = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
        let c = candidates(&sq, &mut || {});
        assert_eq!(c.len(), 2);
        for k in c {
            assert!((k.r - 50f64.sqrt()).abs() < 1e-9);
            assert!((k.c[0] - 5.0).abs() < 1e-9 && (k.c[1] - 5.0).abs() < 1e-9);
        }
    }

    #[test]
    fn bay_gives_external_circles() {
        // A "U": the notch between x=4 and x=6 is outside the polygon.
        let u = [
            [0.0, 0.0],
            [10.0, 0.0],
            [10.0, 10.0],
            [6.0, 10.0],
            [6.0, 2.0],
            [4.0, 2.0],
            [4.0, 10.0],
            [0.0, 10.0],
        ];
        let c = candidates(&u, &mut || {});
        assert!(c.iter().any(|k| k.r < 0.0), "{c:?}");
        assert!(c.iter().any(|k| k.r > 0.0));
        // every external circle's centre lies in the notch's column
        for k in c.iter().filter(|k| k.r < 0.0) {
            assert!(k.c[0] > 3.9 && k.c[0] < 6.1, "{k:?}");
        }
    }
}
