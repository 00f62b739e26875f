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
use spade::handles::{FixedFaceHandle, FixedVertexHandle};
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
    // Inserted one by one, in rounds of a biased randomized insertion order: each vertex draws a
    // level from a hash of its index (level k with odds 2^-(k+1)), the rounds go from the highest
    // level down, and each round in ring order, every vertex walked to from the one inserted
    // before it. Random rounds keep the expected work O(n log n) whatever the ring (in plain ring
    // order a convex arc costs O(n^2): 20 s for an ellipse of 100,000 vertices; strided rounds
    // were as bad on a star), and ring order within a round keeps each walk short. A ring's
    // points all lie far from their mean, the centre spade's bulk load sweeps from, and its hull
    // work made that twice as slow as this (a million vertices: 0.63 s against 1.35 s, the same
    // triangles).
    let mut order: Vec<(u8, u32)> = (0..n).map(|i| (insertion_level(i), i as u32)).collect();
    order.sort_unstable_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut cdt = ConstrainedDelaunayTriangulation::<V>::with_capacity(n, 3 * n, 2 * n);
    let mut handles = vec![FixedVertexHandle::from_index(0); n];
    let mut last = None;
    for (k, &(_, i)) in order.iter().enumerate() {
        if k % 4096 == 0 {
            interrupt();
        }
        let v = verts[i as usize];
        let inserted = match last {
            Some(h) => cdt.insert_with_hint(v, h),
            None => cdt.insert(v),
        };
        let Ok(h) = inserted else {
            return vec![];
        };
        handles[i as usize] = h;
        last = Some(h);
    }
    // a repeated point (the triangulation keeps one)
    if cdt.num_vertices() != n {
        return vec![];
    }
    for i in 0..n {
        if i % 4096 == 0 {
            interrupt();
        }
        // none when it would cross an edge already constrained: the ring crosses itself
        if cdt
            .try_add_constraint(handles[i], handles[(i + 1) % n])
            .is_empty()
        {
            return vec![];
        }
    }
    interrupt();
    // The faces' sides and their circumcircles need nothing of each other: on a large ring they
    // are found side by side.
    let (side, circles) = crate::parallel::join(
        n as u64 >= crate::parallel::MIN_VERTICES,
        interrupt,
        |_| sides(&cdt, n),
        |i| circumcircles(&cdt, i),
    );
    // The faces with a side, in order of their vertices: by the lowest (a counting sort, placed
    // straight from the faces), then the other two.
    let mut start = vec![0usize; n + 1];
    for &(f, _, _, verts) in &circles {
        if side[f].is_some() {
            start[verts[0] + 1] += 1;
        }
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let unset = Candidate {
        c: [0.0; 2],
        r: 0.0,
        verts: [0; 3],
    };
    let mut out = vec![unset; start[n]];
    let mut next = start.clone();
    for (f, c, r, verts) in circles {
        if let Some(inside) = side[f] {
            out[next[verts[0]]] = Candidate {
                c: [c[0] + o[0], c[1] + o[1]],
                r: if inside { r } else { -r },
                verts,
            };
            next[verts[0]] += 1;
        }
    }
    for v in 0..n {
        out[start[v]..start[v + 1]].sort_unstable_by_key(|c| c.verts);
    }
    out
}

/// Each inner face's side of the ring (`Some(true)`: the polygon's, left of the ring), by face
/// index: a face with a ring edge knows it from the edge's direction, the others inherit it by
/// flood fill across unconstrained edges.
fn sides(cdt: &ConstrainedDelaunayTriangulation<V>, n: usize) -> Vec<Option<bool>> {
    let mut side: Vec<Option<bool>> = vec![None; cdt.all_faces().len()];
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
    side
}

/// Each inner face's circumcircle, where it has one: face index, centre (local coordinates),
/// radius and vertices from the lowest.
#[allow(clippy::type_complexity)]
fn circumcircles(
    cdt: &ConstrainedDelaunayTriangulation<V>,
    interrupt: &mut dyn FnMut(),
) -> Vec<(usize, Pt, f64, [usize; 3])> {
    let mut out = Vec::with_capacity(cdt.num_inner_faces());
    for (k, face) in cdt.inner_faces().enumerate() {
        if k % 4096 == 0 {
            interrupt();
        }
        let (c, r2) = face.circumcircle();
        if !(r2.is_finite() && c.x.is_finite() && c.y.is_finite()) || r2 <= 0.0 {
            continue;
        }
        let vs = face.vertices();
        out.push((
            face.fix().index(),
            [c.x, c.y],
            r2.sqrt(),
            first_lowest([vs[0].data().i, vs[1].data().i, vs[2].data().i]),
        ));
    }
    out
}

/// The round vertex `i` is inserted in (see [`candidates`]): the trailing zeros of a hash of
/// `i`, at most 24.
fn insertion_level(i: usize) -> u8 {
    // splitmix64's finalizer
    let mut z = (i as u64).wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    z.trailing_zeros().min(24) as u8
}

/// A triangle's vertices (counter-clockwise) from the lowest index on, so that a triangle is
/// written one way whatever the triangulation's own numbering.
fn first_lowest(v: [usize; 3]) -> [usize; 3] {
    if v[0] < v[1] && v[0] < v[2] {
        v
    } else if v[1] < v[2] {
        [v[1], v[2], v[0]]
    } else {
        [v[2], v[0], v[1]]
    }
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

    /// The triangles of the bulk-loaded constrained triangulation, each from its lowest vertex.
    fn bulk_triangles(ring: &[Pt]) -> Vec<[usize; 3]> {
        let verts: Vec<V> = ring
            .iter()
            .enumerate()
            .map(|(i, p)| V {
                p: Point2::new(p[0] - ring[0][0], p[1] - ring[0][1]),
                i,
            })
            .collect();
        let n = ring.len();
        let edges: Vec<[usize; 2]> = (0..n).map(|i| [i, (i + 1) % n]).collect();
        let cdt = ConstrainedDelaunayTriangulation::<V>::bulk_load_cdt(verts, edges).unwrap();
        let mut t: Vec<[usize; 3]> = cdt
            .inner_faces()
            .map(|f| {
                let v = f.vertices();
                first_lowest([v[0].data().i, v[1].data().i, v[2].data().i])
            })
            .collect();
        t.sort_unstable();
        t
    }

    #[test]
    fn the_same_triangles_as_spades_bulk_load_in_a_fixed_order() {
        let tau = std::f64::consts::TAU;
        let n = 3000;
        let mut uniform = crate::test_uniform(7);
        let mut noise = || uniform() - 0.5;
        let at = |i: usize| i as f64 / n as f64 * tau;
        // an ellipse and a parabola arc (convex: quadratic in plain ring order), a star of
        // spikes (quadratic in strided rounds), a wavy coastline, all in UTM-sized coordinates
        // and a little noise (four points on one circle have two triangulations)
        let shapes: Vec<Vec<Pt>> = vec![
            (0..n)
                .map(|i| {
                    let r = 1.0 + 1e-4 * noise();
                    [5e5 + 1e5 * r * at(i).cos(), 6e6 + 3e4 * r * at(i).sin()]
                })
                .collect(),
            (0..n)
                .map(|i| {
                    let x = 1.0 - 2.0 * i as f64 / (n - 1) as f64 + 1e-5 * noise();
                    [5e5 + 1e4 * x, 6e6 + 1e4 * x * x]
                })
                .chain([[5e5, 6e6 + 2e4]])
                .collect(),
            (0..n)
                .map(|i| {
                    let r = if i % 2 == 0 { 1e5 } else { 5e4 } + noise();
                    [5e5 + r * at(i).cos(), 6e6 + r * at(i).sin()]
                })
                .collect(),
            (0..n)
                .map(|i| {
                    let r =
                        1e5 + 3e3 * (17.0 * at(i)).sin() + 40.0 * (131.0 * at(i)).sin() + noise();
                    [5e5 + r * at(i).cos(), 6e6 + r * at(i).sin()]
                })
                .collect(),
        ];
        for (k, ring) in shapes.iter().enumerate() {
            let c = candidates(ring, &mut || {});
            let ours: Vec<[usize; 3]> = c.iter().map(|c| c.verts).collect();
            // listed in order of their vertices, each triangle once
            assert!(ours.windows(2).all(|w| w[0] < w[1]), "shape {k}");
            assert_eq!(ours, bulk_triangles(ring), "shape {k}");
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
