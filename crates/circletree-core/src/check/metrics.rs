//! How wrong is a value? Sliver area (paper section 5: the area of the symmetric difference, by
//! `geo`'s boolean operations) and the continuous Hausdorff distance between the boundaries.
//!
//! The Hausdorff distance is computed on whole segments, not sampled vertices: for a segment
//! `a-b`, every point `x` has `d(x) ≤ (d(a) + d(b) + |ab|) / 2` (distance is 1-Lipschitz), so a
//! branch-and-bound over segments, with nearest-segment queries in an R-tree, finds the maximum to
//! within `eps`. Arcs are stroked to a tolerance far below the grid first; what that stroking can
//! hide is bounded by the stroke tolerance, which is reported with the result.
//! PostGIS's `ST_HausdorffDistance` is discrete (vertices only) and can only be lower.

use crate::format::CircleTree;
use crate::geom::{dist, dist2_to_segment, Polygon, Pt};
use geo::{Area, BooleanOps};
use rstar::primitives::Line;
use rstar::{PointDistance, RTree};

/// Sliver area: area of the symmetric difference of two polygon sets.
pub fn sliver_area(a: &[Polygon], b: &[Polygon]) -> f64 {
    let (ga, gb) = (crate::geom::wkb::to_geo(a), crate::geom::wkb::to_geo(b));
    ga.xor(&gb).unsigned_area()
}

fn segments(rings: &[&[Pt]]) -> Vec<Line<[f64; 2]>> {
    rings
        .iter()
        .flat_map(|r| {
            let n = r.len();
            (0..n).map(move |i| Line::new(r[i], r[(i + 1) % n]))
        })
        .collect()
}

/// The largest distance from a point of segment `a-b` to the objects of `tree`, or `floor` if
/// that is larger, to within `eps`. See [`segment_max_by`].
pub fn segment_max<T>(tree: &RTree<T>, a: Pt, b: Pt, floor: f64, eps: f64) -> f64
where
    T: PointDistance + rstar::RTreeObject<Envelope = rstar::AABB<[f64; 2]>>,
{
    segment_max_by(
        |p| {
            tree.nearest_neighbor(&p)
                .map(|s| (s.distance_2(&p).sqrt(), s))
        },
        |s, a, b| s.distance_2(&a).max(s.distance_2(&b)).sqrt(),
        a,
        b,
        floor,
        eps,
    )
}

/// The largest distance from a point of segment `a-b` to the segments of `to` (a short list,
/// searched by brute force), or `floor` if that is larger, to within `eps` (the tests' reference).
#[cfg(test)]
pub fn segment_max_in(to: &[(Pt, Pt)], a: Pt, b: Pt, floor: f64, eps: f64) -> f64 {
    segment_max_by(
        |p| {
            to.iter()
                .map(|&(c, d)| dist2_to_segment(p, c, d))
                .enumerate()
                .min_by(|x, y| x.1.total_cmp(&y.1))
                .map(|(i, d2)| (d2.sqrt(), i))
        },
        |&i, a, b| {
            let (c, d) = to[i];
            crate::geom::dist_to_segment(a, c, d).max(crate::geom::dist_to_segment(b, c, d))
        },
        a,
        b,
        floor,
        eps,
    )
}

/// Segments prepared for [`Capsules::covers`]: each with its unit direction and length, and the
/// box of the points within `r` of it.
#[derive(Default)]
pub struct Capsules {
    segs: Vec<CapSeg>,
    r: f64,
    cover: Vec<(f64, f64)>,
    /// The segment whose capsule alone held the last segment asked about, wholly: asked first
    /// (consecutive questions are usually about neighbours).
    hint: usize,
}

struct CapSeg {
    c: Pt,
    e: Pt,
    u: Pt,
    len: f64,
    bbox: [f64; 4],
}

impl Capsules {
    /// The capsules of radius `r` around the segments `to`.
    #[cfg(test)]
    pub fn new(to: &[(Pt, Pt)], r: f64) -> Capsules {
        let mut caps = Capsules::default();
        caps.refill(to, r);
        caps
    }

    /// Make these the capsules of radius `r` around `to`, reusing what is allocated.
    pub fn refill(&mut self, to: &[(Pt, Pt)], r: f64) {
        self.segs.clear();
        self.segs.extend(to.iter().map(|&(c, e)| {
            let v = [e[0] - c[0], e[1] - c[1]];
            let len = (v[0] * v[0] + v[1] * v[1]).sqrt();
            let u = if len > 0.0 {
                [v[0] / len, v[1] / len]
            } else {
                [0.0, 0.0]
            };
            CapSeg {
                c,
                e,
                u,
                len,
                bbox: [
                    c[0].min(e[0]) - r,
                    c[1].min(e[1]) - r,
                    c[0].max(e[0]) + r,
                    c[1].max(e[1]) + r,
                ],
            }
        }));
        self.r = r;
        self.cover.clear();
        self.hint = 0;
    }

    /// Is every point of segment `a-b` within `r` of the segments? Exact up to rounding, with no
    /// search: the points within `r` of one segment (its capsule) form a convex set, so they meet
    /// `a-b` in one interval of its parameter, and `a-b` lies within `r` of the segments exactly
    /// when those intervals cover `[0, 1]`. O(k log k) for k segments, where [`segment_max_in`]'s
    /// bisection asks a nearest-segment query of all k at every midpoint it visits.
    pub fn covers(&mut self, a: Pt, b: Pt) -> bool {
        let d = [b[0] - a[0], b[1] - a[1]];
        let dd = d[0] * d[0] + d[1] * d[1];
        let (r, r2) = (self.r, self.r * self.r);
        if dd == 0.0 {
            return self
                .segs
                .iter()
                .any(|s| dist2_to_segment(a, s.c, s.e) <= r2);
        }
        let bb = [
            a[0].min(b[0]),
            a[1].min(b[1]),
            a[0].max(b[0]),
            a[1].max(b[1]),
        ];
        let meets = |s: &CapSeg| {
            !(s.bbox[0] > bb[2] || s.bbox[2] < bb[0] || s.bbox[1] > bb[3] || s.bbox[3] < bb[1])
        };
        // One capsule holding all of `a-b` is an interval [0, 1], which the sweep below always
        // accepts whatever the others: the same answer without the sweep.
        if let Some(s) = self.segs.get(self.hint) {
            if meets(s) && s.interval(a, d, dd, r, r2) == Some((0.0, 1.0)) {
                return true;
            }
        }
        self.cover.clear();
        for (i, s) in self.segs.iter().enumerate() {
            if !meets(s) {
                continue;
            }
            if let Some(iv) = s.interval(a, d, dd, r, r2) {
                if iv == (0.0, 1.0) {
                    self.hint = i;
                    return true;
                }
                self.cover.push(iv);
            }
        }
        self.cover.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
        let mut reach = 0.0;
        for &(lo, hi) in self.cover.iter() {
            if lo > reach {
                return false;
            }
            if hi > reach {
                reach = hi;
                if reach >= 1.0 {
                    return true;
                }
            }
        }
        false
    }
}

impl CapSeg {
    /// The interval of `t` for which `a + t·d` (`dd = |d|²`) lies within `r` of the segment,
    /// clipped to `[0, 1]`, if not empty: the union of the parameters inside the discs at its
    /// ends and inside the rectangle between them, one interval since the capsule is convex.
    fn interval(&self, a: Pt, d: Pt, dd: f64, r: f64, r2: f64) -> Option<(f64, f64)> {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut disc = |p: Pt| {
            let w = [a[0] - p[0], a[1] - p[1]];
            let half_b = w[0] * d[0] + w[1] * d[1];
            let disc = half_b * half_b - dd * (w[0] * w[0] + w[1] * w[1] - r2);
            if disc >= 0.0 {
                let s = disc.sqrt();
                lo = lo.min((-half_b - s) / dd);
                hi = hi.max((-half_b + s) / dd);
            }
        };
        disc(self.c);
        disc(self.e);
        if self.len > 0.0 {
            let (u, w) = (self.u, [a[0] - self.c[0], a[1] - self.c[1]]);
            // along the segment: 0 <= w·u + t d·u <= len; across it: |w×u + t d×u| <= r
            let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
            let mut clip = |alpha: f64, beta: f64, min: f64, max: f64| {
                if beta == 0.0 {
                    if alpha < min || alpha > max {
                        t0 = f64::INFINITY;
                    }
                } else {
                    let (x, y) = ((min - alpha) / beta, (max - alpha) / beta);
                    let (x, y) = if beta > 0.0 { (x, y) } else { (y, x) };
                    t0 = t0.max(x);
                    t1 = t1.min(y);
                }
            };
            clip(
                w[0] * u[0] + w[1] * u[1],
                d[0] * u[0] + d[1] * u[1],
                0.0,
                self.len,
            );
            clip(w[0] * u[1] - w[1] * u[0], d[0] * u[1] - d[1] * u[0], -r, r);
            if t0 <= t1 {
                lo = lo.min(t0);
                hi = hi.max(t1);
            }
        }
        let (lo, hi) = (lo.max(0.0), hi.min(1.0));
        (lo <= hi).then_some((lo, hi))
    }
}

/// Branch and bound for the largest distance along segment `a-b`. `nearest(p)` gives the distance
/// from `p` to the target set and the object that realises it; `far(o, a, b)` the larger distance
/// from `a` or `b` to that one object. Two bounds prune the search: distance is 1-Lipschitz
/// (`d(x) ≤ (d(a) + d(b) + |ab|) / 2`), and the distance to one fixed object is convex along the
/// segment (`d(x) ≤ max(d(a, s), d(b, s))` for the object `s` nearest the midpoint), which is
/// tight where the segment runs parallel to the boundary it is measured against.
/// An empty target set gives infinity.
pub fn segment_max_by<O>(
    nearest: impl Fn(Pt) -> Option<(f64, O)>,
    far: impl Fn(&O, Pt, Pt) -> f64,
    a: Pt,
    b: Pt,
    floor: f64,
    eps: f64,
) -> f64 {
    let d = |p: Pt| nearest(p).map_or(f64::INFINITY, |(d, _)| d);
    let (da, db) = (d(a), d(b));
    let mut best = floor.max(da).max(db);
    let mut stack = vec![(a, b, da, db, 0u32)];
    while let Some((a, b, da, db, depth)) = stack.pop() {
        let len = dist(a, b);
        if (da + db + len) / 2.0 <= best + eps || depth > 48 {
            continue;
        }
        let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        let Some((dm, s)) = nearest(m) else {
            return f64::INFINITY;
        };
        best = best.max(dm);
        if far(&s, a, b) <= best + eps {
            continue;
        }
        stack.push((a, m, da, dm, depth + 1));
        stack.push((m, b, dm, db, depth + 1));
    }
    best
}

/// Largest distance from any point of the `from` rings to the `to` rings, within `eps`.
pub fn directed_hausdorff(
    from: &[&[Pt]],
    to: &[&[Pt]],
    eps: f64,
    interrupt: &mut dyn FnMut(),
) -> f64 {
    let tree = RTree::bulk_load(segments(to));
    if tree.size() == 0 {
        return if from.iter().all(|r| r.is_empty()) {
            0.0
        } else {
            f64::INFINITY
        };
    }
    let mut best = 0.0f64;
    let mut count = 0usize;
    for r in from {
        let n = r.len();
        for i in 0..n {
            count += 1;
            if count.is_multiple_of(4096) {
                interrupt();
            }
            best = segment_max(&tree, r[i], r[(i + 1) % n], best, eps);
        }
    }
    best
}

/// Hausdorff distance between two sets of rings (both directions).
pub fn hausdorff(a: &[&[Pt]], b: &[&[Pt]], eps: f64, interrupt: &mut dyn FnMut()) -> f64 {
    directed_hausdorff(a, b, eps, interrupt).max(directed_hausdorff(b, a, eps, interrupt))
}

/// Hausdorff distance between the boundaries of two polygon sets (straight segments only), to
/// within a billionth of their extent.
pub fn shape_hausdorff(a: &[Polygon], b: &[Polygon], interrupt: &mut dyn FnMut()) -> f64 {
    let ra: Vec<&[Pt]> = a.iter().flatten().map(|r| r.as_slice()).collect();
    let rb: Vec<&[Pt]> = b.iter().flatten().map(|r| r.as_slice()).collect();
    let extent = ra
        .iter()
        .chain(&rb)
        .flat_map(|r| r.iter())
        .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    hausdorff(&ra, &rb, (extent * 1e-9).max(1e-12), interrupt)
}

/// The tolerance arcs are stroked to when a value is measured: a hundredth of the grid step.
pub fn measure_tolerance(ct: &CircleTree) -> f64 {
    ct.grid_f64() / 100.0
}

/// Hausdorff distance between a value's boundary (arcs stroked to [`measure_tolerance`]) and
/// the original polygons' boundary.
pub fn value_hausdorff(ct: &CircleTree, original: &[Polygon], interrupt: &mut dyn FnMut()) -> f64 {
    let tol = measure_tolerance(ct);
    let rebuilt = crate::decode::polygons(ct, tol);
    let ra: Vec<&[Pt]> = rebuilt.iter().flatten().map(|r| r.as_slice()).collect();
    let rb: Vec<&[Pt]> = original.iter().flatten().map(|r| r.as_slice()).collect();
    hausdorff(&ra, &rb, tol, interrupt)
}

/// Sliver area between a value (arcs stroked to [`measure_tolerance`]) and the original.
pub fn value_sliver(ct: &CircleTree, original: &[Polygon]) -> f64 {
    sliver_area(
        &crate::decode::polygons(ct, measure_tolerance(ct)),
        original,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hausdorff_finds_the_middle_of_a_segment() {
        // Square vs the same square with one edge pushed out by 2 in its middle (a tent).
        let a: Vec<Pt> = vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
        let b: Vec<Pt> = vec![
            [0.0, 0.0],
            [5.0, -2.0],
            [10.0, 0.0],
            [10.0, 10.0],
            [0.0, 10.0],
        ];
        let h = hausdorff(&[&a], &[&b], 1e-9, &mut || {});
        assert!((h - 2.0).abs() < 1e-6, "{h}");
        // The middle of the top edge, not a vertex, is the farthest point: 5/sqrt(26) from c.
        let c: Vec<Pt> = vec![
            [0.0, 0.0],
            [10.0, 0.0],
            [10.0, 10.0],
            [5.0, 9.0],
            [0.0, 10.0],
        ];
        let h2 = directed_hausdorff(&[&a], &[&c], 1e-9, &mut || {});
        assert!((h2 - 5.0 / 26f64.sqrt()).abs() < 1e-6, "{h2}");
    }

    #[test]
    fn capsules_cover_a_segment_inside_and_not_one_that_leaves() {
        // an L-shaped chain; a segment along its corner and one cutting it
        let to = [([0.0, 0.0], [10.0, 0.0]), ([10.0, 0.0], [10.0, 10.0])];
        let mut caps = Capsules::new(&to, 1.0);
        assert!(caps.covers([1.0, 0.5], [9.5, 0.5]));
        assert!(caps.covers([9.5, 1.0], [9.5, 9.0]));
        assert!(caps.covers([9.2, 0.2], [9.2, 0.2]));
        // its middle, (6, 4), is 4 from both legs
        assert!(!caps.covers([2.0, 0.0], [10.0, 8.0]));
        // beyond the chain's end
        assert!(!caps.covers([5.0, 0.0], [12.0, 0.0]));
        assert!(caps.covers([5.0, 0.0], [10.9, 0.0]));
    }

    proptest::proptest! {
        #[test]
        fn capsules_agree_with_the_bisection(
            pts in proptest::collection::vec((-20.0f64..20.0, -20.0f64..20.0), 2..8),
            ends in ((0usize..8, 0.0f64..1.0), (0usize..8, 0.0f64..1.0)),
            off in ((-1.0f64..1.0, -1.0f64..1.0), (-1.0f64..1.0, -1.0f64..1.0)),
            r in 0.5f64..15.0,
        ) {
            let to: Vec<(Pt, Pt)> = pts
                .windows(2)
                .map(|w| ([w[0].0, w[0].1], [w[1].0, w[1].1]))
                .collect();
            // the segment's ends near points of the chain, so that both answers occur
            let near = |(i, t): (usize, f64), (dx, dy): (f64, f64)| {
                let (c, e) = to[i % to.len()];
                [
                    c[0] + t * (e[0] - c[0]) + dx * r,
                    c[1] + t * (e[1] - c[1]) + dy * r,
                ]
            };
            let (a, b) = (near(ends.0, off.0), near(ends.1, off.1));
            let max = segment_max_in(&to, a, b, 0.0, 1e-9);
            let covered = Capsules::new(&to, r).covers(a, b);
            if (max - r).abs() > 1e-6 {
                proptest::prop_assert_eq!(covered, max <= r, "max {} r {}", max, r);
            }
        }
    }

    #[test]
    fn sliver_of_shifted_square() {
        let a = vec![vec![vec![
            [0.0, 0.0],
            [10.0, 0.0],
            [10.0, 10.0],
            [0.0, 10.0],
        ]]];
        let b = vec![vec![vec![
            [1.0, 0.0],
            [11.0, 0.0],
            [11.0, 10.0],
            [1.0, 10.0],
        ]]];
        assert!((sliver_area(&a, &b) - 20.0).abs() < 1e-9);
    }
}
