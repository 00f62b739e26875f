//! A quick proof that a Polygon or MultiPolygon is valid as PostGIS's `ST_IsValid` (GEOS) defines
//! it, so that the host's slower check can be skipped. It proves only the plainest case and says
//! "not proved" (`false`) for everything else, which the caller then asks the host about:
//!
//! - every ring as it was given (closed, at least four points, no repeated point: see
//!   [`crate::geom::wkb::Input::as_given`]; the caller checks that);
//! - no two segments of any rings share a point, except consecutive segments of one ring at their
//!   common vertex, which do not fold back onto each other: so no ring crosses or touches itself
//!   or another ring, and every ring encloses area;
//! - every hole inside its shell and outside the part's other holes; every part's shell outside
//!   the other parts' shells, or inside one of their holes.
//!
//! With no ring touching another, the interior is connected and that is every rule GEOS checks
//! (`IsValidOp`: coordinates, ring size, self-intersection, ring crossings and touches, holes in
//! shell, nested holes, disconnected interior, nested shells). Non-finite coordinates never get
//! here: [`crate::geom::wkb::read`] refuses them.
//!
//! *Decided beyond doubt*: every predicate is the sign of an orientation determinant computed in
//! floating point and taken only when it exceeds a bound thousands of times the determinant's
//! rounding error ([`side`]); a sign that close to zero makes the proof give up. GEOS's own
//! orientation (`CGAlgorithmsDD`) returns the floating-point sign whenever it clears a filter
//! far tighter than this one, so wherever this proof decides, GEOS decides the same way, and
//! a segment pair whose end points lie strictly on one side of the other's line is exactly the
//! pair GEOS's `LineIntersector` reports as not intersecting.
//!
//! *Fast*: segments are grouped into monotone chains (consecutive segments whose directions
//! all lie in one closed quadrant; within such a chain only neighbours can meet, and they
//! cannot fold back), chains whose boxes meet are paired by [`crate::geom::box_grid`], and two chains'
//! segments are paired by one merge along x (both chains are monotone in x). This is GEOS's own
//! way of finding the pairs (monotone chains), without its noding. A coastline's chains are
//! short (137,000 for the 306,000 vertices of `tests/data`), so the grid's lookups are most of
//! the time: about 28 ms for that set on one thread against `ST_IsValid`'s 75-78 ms.

use crate::geom::box_grid::{Bbox, BoxIndex};
use crate::geom::{Pt, Shape};

/// How far beyond its rounding error a determinant must be to be trusted: the error of the
/// floating-point determinant is below 3.3e-16 of the sum of its two products' magnitudes
/// (Shewchuk's `ccwerrboundA`); this is 3,000 times that.
const CLEAR: f64 = 1e-12;

/// Below this the products may have lost bits to underflow: nothing is decided.
const TINY: f64 = 1e-250;

/// The side of `c` from the line `a→b` when the floating-point determinant decides it beyond
/// doubt: `1` left, `-1` right, `0` collinear or too close to tell.
#[inline]
fn side(a: Pt, b: Pt, c: Pt) -> i8 {
    let l = (b[0] - a[0]) * (c[1] - a[1]);
    let r = (b[1] - a[1]) * (c[0] - a[0]);
    let det = l - r;
    let bound = CLEAR * (l.abs() + r.abs());
    // NaN (products overflowing) decides nothing
    if bound.is_nan() || bound < TINY {
        0
    } else if det > bound {
        1
    } else if det < -bound {
        -1
    } else {
        0
    }
}

/// Are closed segments `a-b` and `c-d` disjoint beyond doubt (both ends of one strictly on one
/// side of the other's line)?
#[inline]
fn apart(a: Pt, b: Pt, c: Pt, d: Pt) -> bool {
    let (s1, s2) = (side(a, b, c), side(a, b, d));
    if s1 != 0 && s1 == s2 {
        return true;
    }
    let (s3, s4) = (side(c, d, a), side(c, d, b));
    s3 != 0 && s3 == s4
}

/// Do consecutive segments `a-b` and `b-c` meet only at `b` (no fold back) beyond doubt?
#[inline]
fn turn_ok(a: Pt, b: Pt, c: Pt) -> bool {
    if side(a, b, c) != 0 {
        return true;
    }
    // (nearly) collinear: fine when going on, not back
    let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - b[0], c[1] - b[1]]);
    let dot = u[0] * v[0] + u[1] * v[1];
    dot > 0.25 * (u[0].abs() + u[1].abs()) * (v[0].abs() + v[1].abs()) && dot.is_finite()
}

/// Consecutive segments of one ring, all with directions in one closed quadrant.
struct Chain {
    ring: u32,
    /// First segment (segment `i` runs from vertex `i` to `i + 1`, wrapping).
    start: u32,
    len: u32,
    /// x decreases along the chain: its segments are visited backwards to go by increasing x.
    back: bool,
}

fn sign(v: f64) -> i8 {
    (v > 0.0) as i8 - (v < 0.0) as i8
}

/// The rings' monotone chains and their boxes; `None` when a ring is too short or repeats a
/// point.
fn chains(rings: &[&[Pt]]) -> Option<(Vec<Chain>, Vec<Bbox>)> {
    let mut chains = Vec::new();
    let mut boxes = Vec::new();
    for (k, r) in rings.iter().enumerate() {
        let n = r.len();
        if n < 3 || n >= u32::MAX as usize {
            return None;
        }
        let mut i = 0;
        while i < n {
            let start = i;
            let (mut cx, mut cy) = (0i8, 0i8);
            while i < n {
                let (a, b) = (r[i], r[if i + 1 == n { 0 } else { i + 1 }]);
                let (sx, sy) = (sign(b[0] - a[0]), sign(b[1] - a[1]));
                if sx == 0 && sy == 0 {
                    return None;
                }
                if (cx != 0 && sx != 0 && sx != cx) || (cy != 0 && sy != 0 && sy != cy) {
                    break;
                }
                if cx == 0 {
                    cx = sx;
                }
                if cy == 0 {
                    cy = sy;
                }
                i += 1;
            }
            // a monotone chain's box is its two ends'
            let (a, b) = (r[start], r[if i == n { 0 } else { i }]);
            boxes.push([
                a[0].min(b[0]),
                a[1].min(b[1]),
                a[0].max(b[0]),
                a[1].max(b[1]),
            ]);
            chains.push(Chain {
                ring: k as u32,
                start: start as u32,
                len: (i - start) as u32,
                back: cx < 0,
            });
        }
    }
    Some((chains, boxes))
}

/// Is every pair of segments of chains `p` and `q` whose boxes meet fine (apart, or neighbours
/// in one ring that turn)? `meet` is where the chains' boxes meet. Both chains are walked by
/// increasing x, `q`'s from the first segment that can reach the current one of `p`.
fn chains_ok(rings: &[&[Pt]], p: &Chain, q: &Chain, meet: &Bbox) -> bool {
    let seg = |c: &Chain, t: u32| -> (usize, Pt, Pt) {
        let r = rings[c.ring as usize];
        let i = (if c.back {
            c.start + c.len - 1 - t
        } else {
            c.start + t
        }) as usize;
        let j = if i + 1 == r.len() { 0 } else { i + 1 };
        (i, r[i], r[j])
    };
    let same = p.ring == q.ring;
    let n = rings[p.ring as usize].len();
    let next = |i: usize| if i + 1 == n { 0 } else { i + 1 };
    let mut lo = 0;
    for t in 0..p.len {
        let (i, a, b) = seg(p, t);
        let (ax0, ax1) = (a[0].min(b[0]), a[0].max(b[0]));
        if ax1 < meet[0] {
            continue;
        }
        if ax0 > meet[2] {
            break;
        }
        let (ay0, ay1) = (a[1].min(b[1]), a[1].max(b[1]));
        while lo < q.len {
            let (_, c, d) = seg(q, lo);
            if c[0].max(d[0]) >= ax0 {
                break;
            }
            lo += 1;
        }
        let mut u = lo;
        while u < q.len {
            let (j, c, d) = seg(q, u);
            if c[0].min(d[0]) > ax1 {
                break;
            }
            u += 1;
            if c[1].max(d[1]) < ay0 || c[1].min(d[1]) > ay1 {
                continue;
            }
            let ok = if same && j == next(i) {
                turn_ok(a, b, d)
            } else if same && i == next(j) {
                turn_ok(c, d, b)
            } else {
                apart(a, b, c, d)
            };
            if !ok {
                return false;
            }
        }
    }
    true
}

/// Every pair of segments whose boxes meet is fine: chains whose boxes meet are paired by a
/// grid, each pair once; on a large input the two halves of the chains side by side.
fn segments_ok(rings: &[&[Pt]], interrupt: &mut dyn FnMut()) -> bool {
    let Some((chains, boxes)) = chains(rings) else {
        return false;
    };
    let index = BoxIndex::new(
        boxes
            .iter()
            .copied()
            .enumerate()
            .map(|(i, b)| (b, i))
            .collect(),
    );
    let check = |from: usize, to: usize, interrupt: &mut dyn FnMut()| {
        for c in from..to {
            if c % 4096 == 0 {
                interrupt();
            }
            let b = &boxes[c];
            let mut ok = true;
            index.for_each_meeting(b, |d| {
                if ok && d > c {
                    let e = &boxes[d];
                    let meet = [
                        b[0].max(e[0]),
                        b[1].max(e[1]),
                        b[2].min(e[2]),
                        b[3].min(e[3]),
                    ];
                    ok = chains_ok(rings, &chains[c], &chains[d], &meet);
                }
            });
            if !ok {
                return false;
            }
        }
        true
    };
    let (n, half) = (chains.len(), chains.len() / 2);
    let vertices: usize = rings.iter().map(|r| r.len()).sum();
    let (a, b) = crate::parallel::join(
        vertices as u64 >= crate::parallel::MIN_VERTICES,
        interrupt,
        |i| check(0, half, i),
        |i| check(half, n, i),
    );
    a && b
}

/// Where points lie against a ring (ray crossing, each crossing decided beyond doubt): `true`
/// inside, or `None` when a point is too close to the ring to tell. The points are taken in
/// one pass over the ring's segments.
fn locate(ring: &[Pt], points: &[Pt]) -> Option<Vec<bool>> {
    if points.len() < 4 {
        return points.iter().map(|&p| locate_one(ring, p)).collect();
    }
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_unstable_by(|&a, &b| points[a][1].total_cmp(&points[b][1]));
    let ys: Vec<f64> = order.iter().map(|&k| points[k][1]).collect();
    let mut inside = vec![false; points.len()];
    let n = ring.len();
    for i in 0..n {
        let (a, b) = (ring[i], ring[if i + 1 == n { 0 } else { i + 1 }]);
        let (lo, hi) = if a[1] < b[1] {
            (a[1], b[1])
        } else {
            (b[1], a[1])
        };
        // the points whose horizontal line the segment crosses: lo <= y < hi
        let first = ys.partition_point(|&y| y < lo);
        for s in first..ys.len() {
            if ys[s] >= hi {
                break;
            }
            let k = order[s];
            match crossing(a, b, points[k]) {
                Some(true) => inside[k] = !inside[k],
                Some(false) => {}
                None => return None,
            }
        }
    }
    Some(inside)
}

/// Does the segment `a-b`, which spans the horizontal line through `p` (one end strictly above
/// it, the other not), cross that line to the right of `p`? `None` when too close to tell.
#[inline]
fn crossing(a: Pt, b: Pt, p: Pt) -> Option<bool> {
    match side(a, b, p) {
        0 => None,
        // p left of an upward segment, or right of a downward one: the segment is to its right
        s => Some((b[1] > a[1]) == (s > 0)),
    }
}

fn locate_one(ring: &[Pt], p: Pt) -> Option<bool> {
    let n = ring.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (ring[i], ring[if i + 1 == n { 0 } else { i + 1 }]);
        if (a[1] > p[1]) != (b[1] > p[1]) && crossing(a, b, p)? {
            inside = !inside;
        }
    }
    Some(inside)
}

fn ring_box(r: &[Pt]) -> Bbox {
    r.iter().fold(
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, p| {
            [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ]
        },
    )
}

/// Every `(ring, point)` query answered, grouped by ring so that each ring is walked once.
fn locate_many(rings: &[&[Pt]], queries: &[(usize, Pt)]) -> Option<Vec<bool>> {
    let mut order: Vec<usize> = (0..queries.len()).collect();
    order.sort_unstable_by_key(|&q| queries[q].0);
    let mut out = vec![false; queries.len()];
    for group in order.chunk_by(|&a, &b| queries[a].0 == queries[b].0) {
        let pts: Vec<Pt> = group.iter().map(|&q| queries[q].1).collect();
        let found = locate(rings[queries[group[0]].0], &pts)?;
        for (&q, f) in group.iter().zip(found) {
            out[q] = f;
        }
    }
    Some(out)
}

/// Is `shape` (open rings, as [`crate::geom::wkb::read`] returns them from an input it read
/// [`as given`](crate::geom::wkb::Input::as_given)) valid beyond doubt? `false` means "not proved",
/// not "invalid". `interrupt` is called now and then.
pub fn proves_valid(shape: &Shape, interrupt: &mut dyn FnMut()) -> bool {
    // every ring, with its part and whether it is a shell
    let mut rings: Vec<&[Pt]> = Vec::new();
    let mut owner: Vec<(usize, bool)> = Vec::new();
    for (part, poly) in shape.parts.iter().enumerate() {
        for (k, r) in poly.iter().enumerate() {
            rings.push(r);
            owner.push((part, k == 0));
        }
    }
    proves_rings(&rings, &owner, interrupt)
}

/// [`proves_valid`] for rings given one by one: `owner[k]` is ring `k`'s part (numbered from
/// 0, each part with exactly one shell) and whether it is that part's shell. The encoder proves
/// its own rebuilt rings with it.
pub fn proves_rings(rings: &[&[Pt]], owner: &[(usize, bool)], interrupt: &mut dyn FnMut()) -> bool {
    let nparts = owner.iter().map(|o| o.0 + 1).max().unwrap_or(0);
    let mut shells = vec![0usize; nparts];
    for &(part, shell) in owner {
        shells[part] += usize::from(shell);
    }
    if rings.is_empty() || rings.len() != owner.len() || shells.iter().any(|&s| s != 1) {
        return false;
    }
    if !segments_ok(rings, interrupt) {
        return false;
    }
    interrupt();
    // No two rings meet. Nesting, each ring represented by its first vertex (on no other ring).
    let ring_boxes: Vec<Bbox> = rings.iter().map(|r| ring_box(r)).collect();
    let rindex = BoxIndex::new(
        ring_boxes
            .iter()
            .copied()
            .enumerate()
            .map(|(i, b)| (b, i))
            .collect(),
    );
    let mut shell_of = vec![0; nparts];
    for (k, &(part, shell)) in owner.iter().enumerate() {
        if shell {
            shell_of[part] = k;
        }
    }
    // (ring, point) queries and what each must answer; a shell inside another part's shell
    // must then be in one of that part's holes
    let mut must: Vec<(usize, Pt, bool)> = Vec::new();
    let mut shell_in_shell: Vec<(usize, usize)> = Vec::new();
    for (k, r) in rings.iter().enumerate() {
        let p = r[0];
        let (part, shell) = owner[k];
        if !shell {
            must.push((shell_of[part], p, true));
        }
        rindex.for_each_meeting(&[p[0], p[1], p[0], p[1]], |g| {
            let (gpart, gshell) = owner[g];
            if g == k {
            } else if !shell && !gshell && gpart == part {
                // holes of one part are not nested
                must.push((g, p, false));
            } else if shell && gshell {
                shell_in_shell.push((k, g));
            }
        });
    }
    let queries: Vec<(usize, Pt)> = must.iter().map(|&(g, p, _)| (g, p)).collect();
    match locate_many(rings, &queries) {
        Some(found) if found.iter().zip(&must).all(|(f, m)| *f == m.2) => {}
        _ => return false,
    }
    interrupt();
    let queries: Vec<(usize, Pt)> = shell_in_shell
        .iter()
        .map(|&(k, g)| (g, rings[k][0]))
        .collect();
    let Some(found) = locate_many(rings, &queries) else {
        return false;
    };
    // the shells inside another part's shell, and the holes of that part whose box holds them
    let mut in_hole: Vec<(usize, Pt)> = Vec::new();
    let mut asked: Vec<usize> = Vec::new();
    for (&(k, g), inside) in shell_in_shell.iter().zip(found) {
        if !inside {
            continue;
        }
        let p = rings[k][0];
        let gpart = owner[g].0;
        let before = in_hole.len();
        rindex.for_each_meeting(&[p[0], p[1], p[0], p[1]], |h| {
            if owner[h] == (gpart, false) {
                in_hole.push((h, p));
            }
        });
        asked.push(in_hole.len() - before);
    }
    let Some(found) = locate_many(rings, &in_hole) else {
        return false;
    };
    // each such shell inside (exactly) one of the holes asked about
    let mut at = 0;
    for count in asked {
        if !found[at..at + count].iter().any(|&f| f) {
            return false;
        }
        at += count;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Kind;

    fn shape(parts: Vec<Vec<Vec<Pt>>>) -> Shape {
        Shape {
            kind: Kind::MultiPolygon,
            parts,
        }
    }

    fn sq(x: f64, y: f64, s: f64) -> Vec<Pt> {
        vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]]
    }

    fn proved(parts: Vec<Vec<Vec<Pt>>>) -> bool {
        proves_valid(&shape(parts), &mut || {})
    }

    #[test]
    fn plain_polygons_are_proved() {
        assert!(proved(vec![vec![sq(0.0, 0.0, 10.0)]]));
        assert!(proved(vec![vec![vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]]]));
        // a hole, two holes side by side, a part in another's hole, two parts apart
        assert!(proved(vec![vec![sq(0.0, 0.0, 10.0), sq(2.0, 2.0, 2.0)]]));
        assert!(proved(vec![vec![
            sq(0.0, 0.0, 10.0),
            sq(2.0, 2.0, 2.0),
            sq(6.0, 6.0, 2.0)
        ]]));
        assert!(proved(vec![
            vec![sq(0.0, 0.0, 10.0), sq(2.0, 2.0, 6.0)],
            vec![sq(3.0, 3.0, 1.0)]
        ]));
        assert!(proved(vec![
            vec![sq(0.0, 0.0, 1.0)],
            vec![sq(5.0, 5.0, 1.0)]
        ]));
        // collinear vertices going on along a side
        assert!(proved(vec![vec![vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [2.0, 2.0],
            [0.0, 2.0]
        ]]]));
    }

    #[test]
    fn invalid_or_touching_rings_are_not_proved() {
        // bow tie; spike (folds back); collinear triangle; too few points
        assert!(!proved(vec![vec![vec![
            [0.0, 0.0],
            [10.0, 10.0],
            [10.0, 0.0],
            [0.0, 10.0]
        ]]]));
        assert!(!proved(vec![vec![vec![
            [0.0, 0.0],
            [10.0, 0.0],
            [20.0, 0.0],
            [5.0, 0.0],
            [5.0, 5.0]
        ]]]));
        assert!(!proved(vec![vec![vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0]
        ]]]));
        assert!(!proved(vec![vec![vec![[0.0, 0.0], [1.0, 0.0]]]]));
        // a ring touching itself at a vertex (a valid "inverted hole" only with ESRI's rules)
        assert!(!proved(vec![vec![vec![
            [0.0, 0.0],
            [10.0, 0.0],
            [5.0, 5.0],
            [7.0, 8.0],
            [3.0, 8.0],
            [5.0, 5.0],
            [0.0, 10.0]
        ]]]));
        // hole outside its shell, holes nested, hole crossing, hole touching the shell
        assert!(!proved(vec![vec![sq(0.0, 0.0, 10.0), sq(20.0, 2.0, 2.0)]]));
        assert!(!proved(vec![vec![
            sq(0.0, 0.0, 10.0),
            sq(2.0, 2.0, 6.0),
            sq(3.0, 3.0, 1.0)
        ]]));
        assert!(!proved(vec![vec![sq(0.0, 0.0, 10.0), sq(8.0, 2.0, 4.0)]]));
        assert!(!proved(vec![vec![sq(0.0, 0.0, 10.0), sq(0.0, 2.0, 2.0)]]));
        // shell in shell, shells overlapping, shells touching at a corner, the same part twice
        assert!(!proved(vec![
            vec![sq(0.0, 0.0, 10.0)],
            vec![sq(2.0, 2.0, 2.0)]
        ]));
        assert!(!proved(vec![
            vec![sq(2.0, 2.0, 2.0)],
            vec![sq(0.0, 0.0, 10.0)]
        ]));
        assert!(!proved(vec![
            vec![sq(0.0, 0.0, 10.0)],
            vec![sq(5.0, 5.0, 10.0)]
        ]));
        assert!(!proved(vec![
            vec![sq(0.0, 0.0, 1.0)],
            vec![sq(1.0, 1.0, 1.0)]
        ]));
        assert!(!proved(vec![
            vec![sq(0.0, 0.0, 1.0)],
            vec![sq(0.0, 0.0, 1.0)]
        ]));
        // a part in another part's hole, but touching the hole
        assert!(!proved(vec![
            vec![sq(0.0, 0.0, 10.0), sq(2.0, 2.0, 6.0)],
            vec![sq(2.0, 3.0, 1.0)]
        ]));
        // nothing
        assert!(!proved(vec![]));
    }

    #[test]
    fn rings_one_by_one_need_one_shell_a_part() {
        let (outer, inner) = (sq(0.0, 0.0, 10.0), sq(2.0, 2.0, 2.0));
        let rings: Vec<&[Pt]> = vec![&outer, &inner];
        assert!(proves_rings(&rings, &[(0, true), (0, false)], &mut || {}));
        // the same rings as two parts' shells: one inside the other's shell, not in a hole
        assert!(!proves_rings(&rings, &[(0, true), (1, true)], &mut || {}));
        // a part with no shell, a part with two, an owner missing
        assert!(!proves_rings(&rings, &[(0, false), (0, false)], &mut || {}));
        assert!(!proves_rings(&rings, &[(0, true), (0, true)], &mut || {}));
        assert!(!proves_rings(&rings, &[(0, true)], &mut || {}));
        assert!(!proves_rings(&[], &[], &mut || {}));
    }

    #[test]
    fn too_close_to_tell_is_not_proved() {
        // a hole's vertex a hair off the shell's side: apart in exact arithmetic, but closer than
        // the rounding this proof trusts
        let shell = vec![[0.0, 0.0], [10.0, 0.0], [3.0, 7.0]];
        let hole = vec![[1.5, 3.5 - 1e-15], [2.0, 1.0], [4.0, 1.0]];
        assert!(!proved(vec![vec![shell.clone(), hole]]));
        // the same a little further in
        let hole = vec![[1.5, 3.4], [2.0, 1.0], [4.0, 1.0]];
        assert!(proved(vec![vec![shell, hole]]));
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(4000))]
        /// Whatever the proof accepts, `geo`'s validation accepts too: random rings on a small
        /// grid (so that vertices, crossings, touches and collinear runs are common), with a
        /// random second ring as a hole or a second part.
        #[test]
        fn what_is_proved_is_valid(
            a in proptest::collection::vec((0i32..8, 0i32..8), 3..9),
            b in proptest::collection::vec((0i32..8, 0i32..8), 3..6),
            as_hole in proptest::bool::ANY,
        ) {
            use geo::Validation;
            let ring = |v: &[(i32, i32)]| -> Vec<Pt> {
                let mut r: Vec<Pt> = v.iter().map(|&(x, y)| [x as f64, y as f64]).collect();
                crate::geom::dedup_ring(&mut r);
                r
            };
            let (ra, rb) = (ring(&a), ring(&b));
            for parts in [
                vec![vec![ra.clone()]],
                if as_hole { vec![vec![ra.clone(), rb.clone()]] } else { vec![vec![ra.clone()], vec![rb.clone()]] },
            ] {
                if parts.iter().flatten().any(|r| r.len() < 3) {
                    continue;
                }
                let sh = shape(parts);
                if proves_valid(&sh, &mut || {}) {
                    let g = crate::geom::wkb::to_geo(&sh.parts);
                    proptest::prop_assert!(g.is_valid(), "proved but invalid: {:?}", sh.parts);
                }
            }
        }
    }
}
