//! Candidate circles from the medial axis (paper section 3.1): the circumcircles of the triangles
//! of a constrained Delaunay triangulation of one ring (spade), i.e. the Voronoi vertices of the
//! ring's points. A triangle on the polygon's side of the ring gives a positive radius (internal
//! circle), one on the other side a negative radius (external circle, section 3.4).
//!
//! The ring's edges are edges of the triangulation (those Delaunay's lacks are added as
//! constraints), so every triangle lies wholly on one side: a triangle with a ring edge knows its
//! side from the edge's direction, the others take it from their neighbours across the other
//! edges. Coordinates are moved to a local origin first (circumcentres of UTM-sized coordinates
//! lose digits). Cost: O(n log n).

use crate::geom::Pt;
use spade::handles::FixedVertexHandle;
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
    let [mut first, second] = candidate_lists(ring, interrupt);
    first.extend(second);
    first
}

/// [`candidates`] as two lists, one after the other: on a large ring each thread's, as it made
/// them (putting them together was a copy of some 60 MB into fresh pages at a million vertices,
/// 31 ms on one thread, for nothing: [`crate::encode::paper::filter::map_runs`] reads both where they are).
pub fn candidate_lists(ring: &[Pt], interrupt: &mut dyn FnMut()) -> [Vec<Candidate>; 2] {
    let n = ring.len();
    if n < 3 {
        return [vec![], vec![]];
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
    let order = insertion_order(n);
    let mut cdt = Ring::with_capacity(n, 3 * n, 2 * n);
    let mut handles = vec![FixedVertexHandle::from_index(0); n];
    let mut last = None;
    for (k, &i) in order.iter().enumerate() {
        if k % 4096 == 0 {
            interrupt();
        }
        let v = verts[i as usize];
        let inserted = match last {
            Some(h) => cdt.insert_with_hint(v, h),
            None => cdt.insert(v),
        };
        let Ok(h) = inserted else {
            return [vec![], vec![]];
        };
        handles[i as usize] = h;
        last = Some(h);
    }
    // a repeated point (the triangulation keeps one)
    if cdt.num_vertices() != n {
        return [vec![], vec![]];
    }
    // Nearly every edge of a ring is an edge of its Delaunay triangulation already; only the
    // others are added as constraints (spade's `try_add_constraint` walks the line and allocates
    // even for an edge that exists: 5% of the encoder). The triangulation is the same: an edge
    // added as a constraint is found by flips of the edges crossing it alone. The faces on either
    // side of each ring edge take their side from it as it is found (`seed_sides`).
    let mut missing = Vec::new();
    let mut side = seed_sides(&cdt, &handles, &mut missing, interrupt);
    if !missing.is_empty() {
        for (k, &i) in missing.iter().enumerate() {
            if k % 4096 == 0 {
                interrupt();
            }
            // none when it would cross an edge already constrained: the ring crosses itself
            if cdt
                .try_add_constraint(handles[i], handles[(i + 1) % n])
                .is_empty()
            {
                return [vec![], vec![]];
            }
        }
        // An added edge that crossed a ring edge (no constraint itself: the ring crosses
        // itself) flipped it away; one that passed through a vertex was split there (the ring
        // touches itself): either way a ring edge is then no edge of the triangulation.
        missing.clear();
        side = seed_sides(&cdt, &handles, &mut missing, interrupt);
        if !missing.is_empty() {
            return [vec![], vec![]];
        }
    }
    interrupt();
    // The other faces' sides and the circumcircles need nothing of each other: on a large ring
    // they are found side by side, the thread that fills the sides taking fewer vertices
    // (filling is about a third of the circumcircles' cost). Each face is visited from its
    // lowest vertex, so the candidates come in the order of their vertices as they are found
    // (sorting them afterwards, by scattering, was a copy of a hundred megabytes a million
    // vertices and half as long as finding them).
    let split = n * 3 / 8;
    let large = n as u64 >= crate::parallel::MIN_VERTICES;
    let (mut first, mut second) = crate::parallel::join(
        large,
        interrupt,
        |i| {
            fill_sides(&cdt, &mut side);
            circles_from(&cdt, &handles, o, 0..split, 2 * split + 64, i)
        },
        |i| circles_from(&cdt, &handles, o, split..n, 2 * (n - split) + 64, i),
    );
    // each list's sides, side by side
    let side = &side;
    crate::parallel::join(
        large,
        interrupt,
        |_| take_sides(&mut first, side),
        |_| take_sides(&mut second, side),
    );
    [first.0, second.0]
}

/// Each circle's side from its face's (none for a face no ring edge reaches: the circle is
/// dropped).
fn take_sides((out, faces): &mut (Vec<Candidate>, Vec<u32>), side: &[u8]) {
    let mut unset = false;
    for (cand, &f) in out.iter_mut().zip(faces.iter()) {
        match side[f as usize] {
            INSIDE => {}
            OUTSIDE => cand.r = -cand.r,
            _ => unset = true,
        }
    }
    if unset {
        let mut k = 0;
        out.retain(|_| {
            k += 1;
            side[faces[k - 1] as usize] != UNSET
        });
    }
}

/// The circumcircles (centre, moved back from the local origin `o`; radius; vertices from the
/// lowest) of the inner faces whose lowest vertex is one of the ring vertices `vertices`, in the
/// order of their vertices, with their face indices; `capacity`: about how many there will be.
fn circles_from(
    cdt: &Ring,
    handles: &[FixedVertexHandle],
    o: Pt,
    vertices: std::ops::Range<usize>,
    capacity: usize,
    interrupt: &mut dyn FnMut(),
) -> (Vec<Candidate>, Vec<u32>) {
    let mut out = Vec::with_capacity(capacity);
    let mut faces = Vec::with_capacity(capacity);
    let mut here: Vec<(Candidate, u32)> = Vec::new();
    for v in vertices.clone() {
        if (v - vertices.start).is_multiple_of(4096) {
            interrupt();
        }
        here.clear();
        for e in cdt.vertex(handles[v]).out_edges() {
            let Some(face) = e.face().as_inner() else {
                continue;
            };
            // the face's other two vertices, seen from `v`
            if e.to().data().i < v || e.next().to().data().i < v {
                continue;
            }
            // the vertices read once, in the face's own order (the circle's bits depend on it)
            let vs = face.vertices().map(|v| *v.data());
            let (c, r2) = circumcircle(vs.map(|v| v.p));
            if !(r2.is_finite() && c[0].is_finite() && c[1].is_finite()) || r2 <= 0.0 {
                continue;
            }
            let cand = Candidate {
                c: [c[0] + o[0], c[1] + o[1]],
                r: r2.sqrt(),
                verts: first_lowest(vs.map(|v| v.i)),
            };
            here.push((cand, face.fix().index() as u32));
        }
        here.sort_unstable_by_key(|h| h.0.verts);
        for &(cand, f) in &here {
            out.push(cand);
            faces.push(f);
        }
    }
    (out, faces)
}

/// A triangulation of one ring: its constraints are the ring edges Delaunay's lacked.
type Ring = ConstrainedDelaunayTriangulation<V>;

/// A face's side of the ring, by face index: not known (yet), the polygon's (left of the ring),
/// the other.
const UNSET: u8 = 0;
const INSIDE: u8 = 1;
const OUTSIDE: u8 = 2;

/// The sides of the faces on either side of each ring edge, by face index (a face lies to the
/// left of its own counter-clockwise edges, the polygon left of the ring); the ring edges the
/// triangulation lacks are listed in `missing`. On a large ring the edges are looked up in two
/// halves side by side (each a cache miss or two: 43 ms on one thread at a million vertices),
/// then the sides are written in the ring's order, as one pass would.
fn seed_sides(
    cdt: &Ring,
    handles: &[FixedVertexHandle],
    missing: &mut Vec<usize>,
    interrupt: &mut dyn FnMut(),
) -> Vec<u8> {
    let n = handles.len();
    // each ring edge's faces, left then right ([`NO_FACE`]: the outer face; [`NO_EDGE`]: no such
    // edge)
    let faces = |from: usize, to: usize| -> Vec<[u32; 2]> {
        (from..to)
            .map(|i| {
                let next = handles[if i + 1 == n { 0 } else { i + 1 }];
                match cdt.get_edge_from_neighbors(handles[i], next) {
                    Some(e) => [e.face(), e.rev().face()]
                        .map(|f| f.as_inner().map_or(NO_FACE, |f| f.fix().index() as u32)),
                    None => [NO_EDGE; 2],
                }
            })
            .collect()
    };
    let half = n / 2;
    let (first, second) = crate::parallel::join(
        n as u64 >= crate::parallel::MIN_VERTICES,
        interrupt,
        |_| faces(0, half),
        |_| faces(half, n),
    );
    let mut side = vec![UNSET; cdt.all_faces().len()];
    for (i, &[left, right]) in first.iter().chain(&second).enumerate() {
        if left == NO_EDGE {
            missing.push(i);
            continue;
        }
        if left != NO_FACE {
            side[left as usize] = INSIDE;
        }
        if right != NO_FACE {
            side[right as usize] = OUTSIDE;
        }
    }
    side
}

/// [`seed_sides`]: the outer face, which has no side.
const NO_FACE: u32 = u32::MAX;
/// [`seed_sides`]: a ring edge the triangulation lacks.
const NO_EDGE: u32 = u32::MAX - 1;

/// The sides of the inner faces without a ring edge: each group of such faces joined by edges
/// (none of them the ring's) takes the side of a face with a ring edge next to it; a face no such
/// face reaches stays unset. The groups are joined (union-find) in one pass over the edges in the
/// order they are stored: a walk from face to face was cache misses, 10% of the candidates.
fn fill_sides(cdt: &Ring, side: &mut [u8]) {
    let mut parent: Vec<u32> = (0..side.len() as u32).collect();
    fn root(parent: &mut [u32], mut f: u32) -> u32 {
        while parent[f as usize] != f {
            let up = parent[parent[f as usize] as usize];
            parent[f as usize] = up;
            f = up;
        }
        f
    }
    for e in cdt.undirected_edges() {
        let e = e.as_directed();
        let (Some(f), Some(g)) = (e.face().as_inner(), e.rev().face().as_inner()) else {
            continue;
        };
        let (f, g) = (f.fix().index(), g.fix().index());
        if side[f] != UNSET && side[g] != UNSET {
            continue;
        }
        // A root's side is its group's, once the group meets a face that has one.
        let (rf, rg) = (root(&mut parent, f as u32), root(&mut parent, g as u32));
        if rf != rg {
            parent[rg as usize] = rf;
            if side[rf as usize] == UNSET {
                side[rf as usize] = side[rg as usize];
            }
        }
    }
    for f in 0..side.len() {
        if side[f] == UNSET {
            side[f] = side[root(&mut parent, f as u32) as usize];
        }
    }
}

/// The circumcircle's centre and squared radius of a triangle: spade's own formula
/// (`FaceHandle::circumcircle`), the same operations in the same order, so the same bits.
fn circumcircle(p: [Point2<f64>; 3]) -> (Pt, f64) {
    let (bx, by) = (p[1].x - p[0].x, p[1].y - p[0].y);
    let (cx, cy) = (p[2].x - p[0].x, p[2].y - p[0].y);
    let d = 2.0 * (bx * cy - cx * by);
    let len_b = bx * bx + by * by;
    let len_c = cx * cx + cy * cy;
    let d_inv = 1.0 / d;
    let x = (len_b * cy - len_c * by) * d_inv;
    let y = (-len_b * cx + len_c * bx) * d_inv;
    ([x + p[0].x, y + p[0].y], x * x + y * y)
}

/// The round vertex `i` is inserted in (see [`candidates`]): the trailing zeros of a hash of
/// `i`, at most 24.
/// The ring's vertices in the order they are inserted: by [`insertion_level`], highest first,
/// each level's in ring order (a counting sort: a few levels, so two passes instead of sorting a
/// million pairs).
fn insertion_order(n: usize) -> Vec<u32> {
    let levels: Vec<u8> = (0..n).map(insertion_level).collect();
    // where each level's vertices start, the highest level first
    let mut start = [0usize; MAX_LEVEL as usize + 2];
    for &l in &levels {
        start[(MAX_LEVEL - l) as usize + 1] += 1;
    }
    for k in 1..start.len() {
        start[k] += start[k - 1];
    }
    let mut order = vec![0u32; n];
    for (i, &l) in levels.iter().enumerate() {
        let at = &mut start[(MAX_LEVEL - l) as usize];
        order[*at] = i as u32;
        *at += 1;
    }
    order
}

/// The highest [`insertion_level`].
const MAX_LEVEL: u8 = 24;

fn insertion_level(i: usize) -> u8 {
    // splitmix64's finalizer
    let mut z = (i as u64).wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    z.trailing_zeros().min(u32::from(MAX_LEVEL)) as u8
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

    /// The counting sort puts the vertices in the order of sorting them by level, highest
    /// first, then by index: on rings small and large enough to hold many levels (it fails
    /// when the levels go lowest first or a level's vertices leave ring order).
    #[test]
    fn insertion_order_is_by_level_then_ring_order() {
        for n in [0, 1, 2, 3, 17, 1000, 70_000] {
            let mut sorted: Vec<(u8, u32)> =
                (0..n).map(|i| (insertion_level(i), i as u32)).collect();
            sorted.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
            let sorted: Vec<u32> = sorted.into_iter().map(|x| x.1).collect();
            assert_eq!(insertion_order(n), sorted, "n = {n}");
        }
        // the levels this checks are many, not one
        let top = (0..70_000).map(insertion_level).max().unwrap();
        assert!(top >= 10, "{top}");
    }

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

    /// Whether `p` lies inside `ring` (crossing number).
    fn inside(ring: &[Pt], p: Pt) -> bool {
        let mut odd = false;
        for i in 0..ring.len() {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            if (a[1] > p[1]) != (b[1] > p[1])
                && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
            {
                odd = !odd;
            }
        }
        odd
    }

    #[test]
    fn ring_edges_delaunay_lacks_are_added_and_every_side_is_right() {
        // A comb of teeth 1 m apart, long and short in turn: a long tooth's sides pass 1 m from
        // the short teeth's tips on either side, which lie in every circle through a side's
        // ends, so the sides are no Delaunay edges and must be added as constraints. Enough
        // teeth for a large ring's paths (two threads, the ring edges looked up in halves).
        let teeth = 2600;
        let mut ring: Vec<Pt> = vec![[0.0, -10.0], [teeth as f64, -10.0]];
        for k in (0..=teeth).rev() {
            ring.push([k as f64, if k % 2 == 0 { 100.0 } else { 50.0 }]);
            if k > 0 {
                ring.push([k as f64 - 0.5, 0.0]);
            }
        }
        let verts: Vec<Point2<f64>> = ring.iter().map(|p| Point2::new(p[0], p[1])).collect();
        let dt = spade::DelaunayTriangulation::<Point2<f64>>::bulk_load_stable(verts).unwrap();
        let lacking = (0..ring.len())
            .filter(|&i| {
                let h = |i: usize| FixedVertexHandle::from_index(i % ring.len());
                dt.get_edge_from_neighbors(h(i), h(i + 1)).is_none()
            })
            .count();
        assert!(lacking >= 2, "{lacking}");
        assert!(ring.len() as u64 >= crate::parallel::MIN_VERTICES);
        let c = candidates(&ring, &mut || {});
        let ours: Vec<[usize; 3]> = c.iter().map(|c| c.verts).collect();
        assert_eq!(ours, bulk_triangles(&ring));
        for k in &c {
            let [a, b, d] = k.verts.map(|v| ring[v]);
            let mid = [(a[0] + b[0] + d[0]) / 3.0, (a[1] + b[1] + d[1]) / 3.0];
            assert_eq!(k.r > 0.0, inside(&ring, mid), "{k:?}");
        }
        // and on the wavy coastline, whose triangles have no ring edge in long stretches
        let n = 6000;
        let at = |i: usize| i as f64 / n as f64 * std::f64::consts::TAU;
        let wavy: Vec<Pt> = (0..n)
            .map(|i| {
                let r = 1e4 + 3e3 * (7.0 * at(i)).sin() + 40.0 * (131.0 * at(i)).sin();
                [r * at(i).cos(), r * at(i).sin()]
            })
            .collect();
        let c = candidates(&wavy, &mut || {});
        assert_eq!(c.len(), bulk_triangles(&wavy).len());
        for k in &c {
            let [a, b, d] = k.verts.map(|v| wavy[v]);
            let mid = [(a[0] + b[0] + d[0]) / 3.0, (a[1] + b[1] + d[1]) / 3.0];
            assert_eq!(k.r > 0.0, inside(&wavy, mid), "{k:?}");
        }
    }

    #[test]
    fn a_ring_crossing_or_touching_itself_has_no_candidates() {
        // a bow tie: its two diagonals cross (Delaunay has one of them)
        let bow = [[0.0, 0.0], [10.0, 10.0], [10.0, 0.0], [0.0, 10.0]];
        assert!(candidates(&bow, &mut || {}).is_empty());
        // a long edge under a saw crossing it
        let mut saw: Vec<Pt> = vec![[0.0, 0.0], [100.0, 0.0]];
        for k in 0..10 {
            let x = 100.0 - 10.0 * k as f64;
            saw.push([x, 10.0]);
            saw.push([x - 5.0, if k == 4 { -1.0 } else { 1.0 }]);
        }
        saw.push([0.0, 10.0]);
        assert!(candidates(&saw, &mut || {}).is_empty());
        // a vertex on the middle of another edge
        let touch = [
            [0.0, 0.0],
            [10.0, 0.0],
            [10.0, 10.0],
            [5.0, 0.0],
            [0.0, 10.0],
        ];
        assert!(candidates(&touch, &mut || {}).is_empty());
    }
}
