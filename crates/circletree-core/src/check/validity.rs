//! Is a set of rings a valid (Multi)Polygon boundary, as OGC defines it? Within a ring, no two
//! segments may cross or touch except consecutive ones at their shared end point, and those may not
//! fold back onto each other (a ring is simple); every ring must enclose area; every hole must lie
//! inside its shell and no part's shell inside another part. Two *different* rings may touch at
//! isolated points, but only at the points the caller allows (the encoder allows exactly the touch
//! points of the input, kept as shared vertices, so the interior stays connected as it was), only
//! vertex to vertex, and without crossing there. Segment pairs are found with a uniform grid
//! ([`crate::geom::box_grid`]; an R-tree when the segments are spread too unevenly for one). [`crate::check::arcs`] checks the true arcs between the stroked points.

use crate::geom::box_grid::{union, Bbox, BoxIndex, EMPTY};
use crate::geom::{signed_area, Pt};
use robust::{orient2d, Coord};

/// Points where two different rings may touch, by the bits of their coordinates.
pub type Touches = rustc_hash::FxHashSet<[u64; 2]>;

/// The key of a point in [`Touches`].
pub fn touch_key(p: Pt) -> [u64; 2] {
    [p[0].to_bits(), p[1].to_bits()]
}

/// A ring to check: its part, its index in the part (0 = shell) and its open points.
pub struct RingRef<'a> {
    /// Part index.
    pub part: usize,
    /// 0 for the shell, then holes.
    pub ring: usize,
    /// Open ring points.
    pub pts: &'a [Pt],
}

fn o(a: Pt, b: Pt, c: Pt) -> f64 {
    orient2d(
        Coord { x: a[0], y: a[1] },
        Coord { x: b[0], y: b[1] },
        Coord { x: c[0], y: c[1] },
    )
}

fn on_seg(a: Pt, b: Pt, p: Pt) -> bool {
    p[0] >= a[0].min(b[0])
        && p[0] <= a[0].max(b[0])
        && p[1] >= a[1].min(b[1])
        && p[1] <= a[1].max(b[1])
}

/// Do closed segments `a-b` and `c-d` share any point?
pub fn segments_touch(a: Pt, b: Pt, c: Pt, d: Pt) -> bool {
    let (d1, d2, d3, d4) = (o(c, d, a), o(c, d, b), o(a, b, c), o(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    (d1 == 0.0 && on_seg(c, d, a))
        || (d2 == 0.0 && on_seg(c, d, b))
        || (d3 == 0.0 && on_seg(a, b, c))
        || (d4 == 0.0 && on_seg(a, b, d))
}

/// Crossing-number point-in-ring test.
pub fn point_in_ring(p: Pt, ring: &[Pt]) -> bool {
    let n = ring.len();
    let mut inside = false;
    let mut j = n.wrapping_sub(1);
    for i in 0..n {
        let (a, b) = (ring[i], ring[j]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0]
        {
            inside = !inside;
        }
        j = i;
    }
    inside
}

/// The grid cells that changed segments touch, so that unchanged segments far from every change
/// skip the tree lookup (a few changes among a million segments is the common case after the
/// first round). Cells are a few times the typical changed segment; only touched cells are stored.
struct NearHot {
    cell: f64,
    marked: rustc_hash::FxHashSet<(i64, i64)>,
}

impl NearHot {
    /// Most cells marked for one envelope; a larger envelope lets everything pass.
    const MAX_CELLS: i64 = 1 << 12;

    fn new(hot: &[(Bbox, (usize, usize))], total: usize) -> Option<Self> {
        if hot.is_empty() || hot.len() * 4 > total {
            return None;
        }
        let mut sizes: Vec<f64> = hot
            .iter()
            .map(|(e, _)| (e[2] - e[0]).max(e[3] - e[1]))
            .collect();
        let mid = sizes.len() / 2;
        let (_, median, _) = sizes.select_nth_unstable_by(mid, f64::total_cmp);
        let cell = 4.0 * *median;
        if !(cell.is_finite() && cell > 0.0) {
            return None;
        }
        let mut grid = NearHot {
            cell,
            marked: rustc_hash::FxHashSet::default(),
        };
        for (e, _) in hot {
            let (x0, y0, x1, y1) = grid.cells(e)?;
            for y in y0..=y1 {
                for x in x0..=x1 {
                    grid.marked.insert((x, y));
                }
            }
        }
        Some(grid)
    }

    /// Cell range of a box; `None` when it is too large to mark.
    fn cells(&self, e: &Bbox) -> Option<(i64, i64, i64, i64)> {
        let f = |v: f64| (v / self.cell).floor() as i64;
        let (x0, y0, x1, y1) = (f(e[0]), f(e[1]), f(e[2]), f(e[3]));
        ((x1 - x0 + 1).saturating_mul(y1 - y0 + 1) <= Self::MAX_CELLS).then_some((x0, y0, x1, y1))
    }
}

trait MayMeet {
    fn may_meet(&self, e: &Bbox) -> bool;
}

impl MayMeet for Option<NearHot> {
    /// Could a segment with this box meet a changed one? (`true` when unsure.)
    fn may_meet(&self, e: &Bbox) -> bool {
        let Some(g) = self else {
            return true;
        };
        let Some((x0, y0, x1, y1)) = g.cells(e) else {
            return true;
        };
        (y0..=y1).any(|y| (x0..=x1).any(|x| g.marked.contains(&(x, y))))
    }
}

/// Segments looked at together first in [`problems_where`]'s later checks.
const NEAR_BLOCK: usize = 32;

/// The box of segment `a-b`.
fn seg_box(a: Pt, b: Pt) -> Bbox {
    [
        a[0].min(b[0]),
        a[1].min(b[1]),
        a[0].max(b[0]),
        a[1].max(b[1]),
    ]
}

/// What one pair of segments shows: a problem, or a touch at an allowed shared vertex (whether
/// the rings cross there is decided from both rings' neighbours).
enum Found {
    Bad,
    Touch((usize, usize, usize, usize)),
}

/// Segment `i` of ring `k` (from `a` to `b`) against segment `j` of ring `k2`, whose boxes meet;
/// `None` when all is well or the pair is another's to report (each pair once when `changed`).
fn pair_problem(
    rings: &[RingRef],
    allowed: &Touches,
    changed: bool,
    (k, i): (usize, usize),
    (a, b): (Pt, Pt),
    (k2, j): (usize, usize),
) -> Option<Found> {
    if changed && (k2, j) <= (k, i) {
        return None;
    }
    let n = rings[k].pts.len();
    let p2 = rings[k2].pts;
    let n2 = p2.len();
    let (c, d) = (p2[j], p2[(j + 1) % n2]);
    let adjacent = k == k2 && (j == (i + 1) % n || i == (j + 1) % n);
    if adjacent {
        // Consecutive segments share one end point; they may not fold back along each other.
        let (shared, x, y) = if j == (i + 1) % n {
            (b, a, d)
        } else {
            (a, b, c)
        };
        if o(x, shared, y) == 0.0 {
            let dot =
                (x[0] - shared[0]) * (y[0] - shared[0]) + (x[1] - shared[1]) * (y[1] - shared[1]);
            if dot > 0.0 {
                return Some(Found::Bad);
            }
        }
        return None;
    }
    if !segments_touch(a, b, c, d) {
        return None;
    }
    if k != k2 {
        // Different rings: a touch at one shared, allowed vertex is fine.
        let shared = [
            (a, i, c, j),
            (a, i, d, (j + 1) % n2),
            (b, (i + 1) % n, c, j),
            (b, (i + 1) % n, d, (j + 1) % n2),
        ]
        .into_iter()
        .find(|(x, _, y, _)| x == y);
        if let Some((p, vi, _, vj)) = shared {
            let (x, y) = (if p == a { b } else { a }, if p == c { d } else { c });
            let overlap = o(p, x, y) == 0.0
                && (x[0] - p[0]) * (y[0] - p[0]) + (x[1] - p[1]) * (y[1] - p[1]) > 0.0;
            if !overlap && allowed.contains(&touch_key(p)) {
                return Some(Found::Touch((k, vi, k2, vj)));
            }
        }
    }
    Some(Found::Bad)
}

/// Problems found: `(ring index in the input slice, segment index)`; `usize::MAX` as the segment
/// means the whole ring (degenerate, or misplaced).
pub fn problems(rings: &[RingRef], interrupt: &mut dyn FnMut()) -> Vec<(usize, usize)> {
    problems_where(rings, None, &Touches::default(), interrupt)
}

/// Is `q` strictly inside the sector swept counter-clockwise around `p` from ray `p→s` to ray
/// `p→e`? (Exact predicates; `None` when `q` lies on either ray, in its direction.)
fn in_sector(p: Pt, s: Pt, e: Pt, q: Pt) -> Option<bool> {
    let same_dir = |r: Pt| {
        o(p, r, q) == 0.0 && (r[0] - p[0]) * (q[0] - p[0]) + (r[1] - p[1]) * (q[1] - p[1]) > 0.0
    };
    if same_dir(s) || same_dir(e) {
        return None;
    }
    let turn = o(p, s, e);
    Some(if turn > 0.0 {
        o(p, s, q) > 0.0 && o(p, q, e) > 0.0
    } else if turn < 0.0 {
        !(o(p, e, q) >= 0.0 && o(p, q, s) >= 0.0)
    } else {
        // s and e opposite (a straight ring): the left half-plane
        o(p, s, q) > 0.0
    })
}

/// Two rings meeting at a shared vertex `p` (ring A through `a_prev, p, a_next`, ring B through
/// `b_prev, p, b_next`): do they only touch there (B's two neighbours on the same side of A)?
pub fn touch_without_crossing(p: Pt, a_prev: Pt, a_next: Pt, b_prev: Pt, b_next: Pt) -> bool {
    match (
        in_sector(p, a_next, a_prev, b_prev),
        in_sector(p, a_next, a_prev, b_next),
    ) {
        (Some(x), Some(y)) => x == y,
        _ => false,
    }
}

/// [`problems`], when only some segments changed since a check that found none: `changed[k][i]`
/// marks segment `i` of ring `k`. Pairs of unchanged segments are not looked at again; whole-ring
/// checks (area, nesting) always run.
pub fn problems_where(
    rings: &[RingRef],
    changed: Option<&[Vec<bool>]>,
    allowed: &Touches,
    interrupt: &mut dyn FnMut(),
) -> Vec<(usize, usize)> {
    let is_changed = |k: usize, i: usize| {
        changed.is_none_or(|c| c.get(k).and_then(|r| r.get(i)) != Some(&false))
    };
    let mut bad = Vec::new();
    // The rings checked, and where each one's segments start in one numbering of them all (the
    // segments are read from the rings where they are looked at: a list of every segment's box,
    // 48 bytes each, was written and read again on every check).
    let mut checked: Vec<(usize, usize)> = Vec::new();
    let mut total = 0;
    for (k, r) in rings.iter().enumerate() {
        let n = r.pts.len();
        if n < 3 || signed_area(r.pts).abs() == 0.0 {
            bad.push((k, usize::MAX));
            continue;
        }
        checked.push((k, total));
        total += n;
    }
    let seg = |k: usize, i: usize| {
        let pts = rings[k].pts;
        (pts[i], pts[(i + 1) % pts.len()])
    };
    interrupt();
    // Every segment is looked up in an index of the changed ones (all of them on a first check):
    // each pair with a changed segment is met once, and a small index is cheap to build.
    let mut hot: Vec<(Bbox, (usize, usize))> = Vec::new();
    for &(k, _) in &checked {
        for i in 0..rings[k].pts.len() {
            if is_changed(k, i) {
                let (a, b) = seg(k, i);
                hot.push((seg_box(a, b), (k, i)));
            }
        }
    }
    let near = NearHot::new(&hot, total);
    // the changed segments, by (ring, segment): a grid, measured several times faster than the
    // R-tree on boundaries, whose segments are short and even (the tree when they are not)
    let index = BoxIndex::new(hot);
    // Each segment's pairs are found independently: on a large input the two halves of the
    // segments run side by side, their findings then taken in order, as one pass would.
    let pairs = |from: usize, to: usize, interrupt: &mut dyn FnMut()| {
        let mut bad = Vec::new();
        let mut touches = Vec::new();
        for &(k, first) in &checked {
            let n = rings[k].pts.len();
            let (lo, hi) = (
                from.clamp(first, first + n) - first,
                to.clamp(first, first + n) - first,
            );
            let (mut block_end, mut skip) = (lo, false);
            for i in lo..hi {
                if (first + i) % 8192 == 0 {
                    interrupt();
                }
                // A block of unchanged segments whose box meets no changed segment's cell is
                // passed over with one look instead of one a segment (the later rounds' case:
                // a few changes among a ring of thousands of segments).
                if i == block_end {
                    block_end = (i + NEAR_BLOCK).min(hi);
                    skip = near.is_some()
                        && (i..block_end).all(|i| !is_changed(k, i))
                        && !near.may_meet(&(i..block_end).fold(EMPTY, |b, i| {
                            let (a, c) = seg(k, i);
                            union(b, seg_box(a, c))
                        }));
                }
                if skip {
                    continue;
                }
                let item_changed = is_changed(k, i);
                let (a, b) = seg(k, i);
                let env = seg_box(a, b);
                if !item_changed && !near.may_meet(&env) {
                    continue;
                }
                index.for_each_meeting(&env, |(k2, j)| {
                    if let Some(found) =
                        pair_problem(rings, allowed, item_changed, (k, i), (a, b), (k2, j))
                    {
                        match found {
                            Found::Bad => {
                                bad.push((k, i));
                                bad.push((k2, j));
                            }
                            Found::Touch(t) => touches.push(t),
                        }
                    }
                });
            }
        }
        (bad, touches)
    };
    let half = total / 2;
    let ((bad_a, touches_a), (bad_b, touches_b)) = crate::parallel::join(
        total as u64 >= crate::parallel::MIN_VERTICES,
        interrupt,
        |i| pairs(0, half, i),
        |i| pairs(half, total, i),
    );
    bad.extend(bad_a);
    bad.extend(bad_b);
    // (ring, vertex, other ring, its vertex) where two rings share an allowed vertex, inserted
    // in the order one pass would (the set's order decides the order of what is reported)
    let mut touches: rustc_hash::FxHashSet<(usize, usize, usize, usize)> = Default::default();
    for t in touches_a.into_iter().chain(touches_b) {
        touches.insert(t);
    }
    for &(k, vi, k2, vj) in &touches {
        let (pa, pb) = (rings[k].pts, rings[k2].pts);
        let (na, nb) = (pa.len(), pb.len());
        if !touch_without_crossing(
            pa[vi],
            pa[(vi + na - 1) % na],
            pa[(vi + 1) % na],
            pb[(vj + nb - 1) % nb],
            pb[(vj + 1) % nb],
        ) {
            bad.extend([
                (k, vi),
                (k, (vi + na - 1) % na),
                (k2, vj),
                (k2, (vj + nb - 1) % nb),
            ]);
        }
    }
    if !bad.is_empty() {
        return bad;
    }
    // A point of each ring that no other ring touches: the middle of its first segment.
    let probe = |r: &RingRef| {
        let (a, b) = (r.pts[0], r.pts[1 % r.pts.len()]);
        [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0]
    };
    // No crossings: check nesting. Holes inside their shell; a part's shell outside the other parts.
    let shell_of = |part: usize| rings.iter().position(|r| r.part == part && r.ring == 0);
    for (k, r) in rings.iter().enumerate() {
        if r.ring > 0 {
            if let Some(s) = shell_of(r.part) {
                if !point_in_ring(probe(r), rings[s].pts) {
                    bad.push((k, usize::MAX));
                }
            }
        }
    }
    let shells: Vec<usize> = (0..rings.len()).filter(|&k| rings[k].ring == 0).collect();
    if shells.len() > 1 {
        let env: Vec<[f64; 4]> = shells
            .iter()
            .map(|&k| {
                let p = rings[k].pts;
                p.iter()
                    .fold([f64::MAX, f64::MAX, f64::MIN, f64::MIN], |b, q| {
                        [
                            b[0].min(q[0]),
                            b[1].min(q[1]),
                            b[2].max(q[0]),
                            b[3].max(q[1]),
                        ]
                    })
            })
            .collect();
        for (x, &kx) in shells.iter().enumerate() {
            let p = probe(&rings[kx]);
            for (y, &ky) in shells.iter().enumerate() {
                let e = env[y];
                if x == y || p[0] < e[0] || p[0] > e[2] || p[1] < e[1] || p[1] > e[3] {
                    continue;
                }
                if point_in_ring(p, rings[ky].pts) {
                    // inside another part's shell: fine only inside one of that part's holes
                    let part = rings[ky].part;
                    let in_hole = rings
                        .iter()
                        .any(|h| h.part == part && h.ring > 0 && point_in_ring(p, h.pts));
                    if !in_hole {
                        bad.push((kx, usize::MAX));
                    }
                }
            }
        }
    }
    bad
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bow_tie_and_spike_are_invalid() {
        let sq = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
        assert!(problems(
            &[RingRef {
                part: 0,
                ring: 0,
                pts: &sq
            }],
            &mut || {}
        )
        .is_empty());
        let bow = [[0.0, 0.0], [10.0, 10.0], [10.0, 0.0], [0.0, 10.0]];
        assert!(!problems(
            &[RingRef {
                part: 0,
                ring: 0,
                pts: &bow
            }],
            &mut || {}
        )
        .is_empty());
        let spike = [[0.0, 0.0], [10.0, 0.0], [20.0, 0.0], [5.0, 0.0], [5.0, 5.0]];
        assert!(!problems(
            &[RingRef {
                part: 0,
                ring: 0,
                pts: &spike
            }],
            &mut || {}
        )
        .is_empty());
    }

    /// With only a few segments changed, a changed one crossing an unchanged one in the middle of
    /// a long unchanged stretch is found (blocks of unchanged segments are passed over only when
    /// nothing changed comes near them), and without the crossing nothing is.
    #[test]
    fn a_change_crossing_an_unchanged_stretch_is_found() {
        // a comb: a long bottom edge of 400 short segments, then up, and back along the top
        let mut ring: Vec<Pt> = (0..=400).map(|i| [i as f64, 0.0]).collect();
        ring.extend([
            [400.0, 50.0],
            [210.0, 50.0],
            [200.5, 20.0],
            [190.0, 50.0],
            [0.0, 50.0],
        ]);
        let n = ring.len();
        let changed_at = |tip: f64| {
            let mut r = ring.clone();
            r[403][1] = tip;
            let mut changed = vec![false; n];
            changed[402] = true;
            changed[403] = true;
            (r, vec![changed])
        };
        for (tip, crosses) in [(20.0, false), (-5.0, true)] {
            let (r, changed) = changed_at(tip);
            let rings = [RingRef {
                part: 0,
                ring: 0,
                pts: &r,
            }];
            let found = problems_where(&rings, Some(&changed), &Touches::default(), &mut || {});
            assert_eq!(!found.is_empty(), crosses, "tip at {tip}: {found:?}");
            if crosses {
                // the bottom segments under the tip, far inside the unchanged stretch
                assert!(
                    found.iter().any(|&(_, i)| (199..=201).contains(&i)),
                    "{found:?}"
                );
            }
        }
    }

    #[test]
    fn holes_and_parts() {
        let sq = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
        let hole = [[2.0, 2.0], [2.0, 4.0], [4.0, 4.0], [4.0, 2.0]];
        let outside = [[20.0, 2.0], [20.0, 4.0], [24.0, 4.0], [24.0, 2.0]];
        let ok = [
            RingRef {
                part: 0,
                ring: 0,
                pts: &sq,
            },
            RingRef {
                part: 0,
                ring: 1,
                pts: &hole,
            },
        ];
        assert!(problems(&ok, &mut || {}).is_empty());
        let bad = [
            RingRef {
                part: 0,
                ring: 0,
                pts: &sq,
            },
            RingRef {
                part: 0,
                ring: 1,
                pts: &outside,
            },
        ];
        assert_eq!(problems(&bad, &mut || {}), vec![(1, usize::MAX)]);
        let nested = [
            RingRef {
                part: 0,
                ring: 0,
                pts: &sq,
            },
            RingRef {
                part: 1,
                ring: 0,
                pts: &hole,
            },
        ];
        assert_eq!(problems(&nested, &mut || {}), vec![(1, usize::MAX)]);
    }
}
