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
use crate::geometry::{dist, dist2_to_segment, dist_to_segment, Polygon, Pt};
use geo::{Area, BooleanOps};
use rstar::primitives::Line;
use rstar::{PointDistance, RTree};

/// Sliver area: area of the symmetric difference of two polygon sets.
pub fn sliver_area(a: &[Polygon], b: &[Polygon]) -> f64 {
    let (ga, gb) = (crate::wkb::to_geo(a), crate::wkb::to_geo(b));
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
/// searched by brute force), or `floor` if that is larger, to within `eps`.
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
            dist_to_segment(a, c, d).max(dist_to_segment(b, c, d))
        },
        a,
        b,
        floor,
        eps,
    )
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
