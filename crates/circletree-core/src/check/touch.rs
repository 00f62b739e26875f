//! Points where two different rings of a valid polygon touch (OGC allows isolated points: parts of
//! a MultiPolygon meeting at a corner, a hole touching its shell). The encoder keeps each such point
//! exactly: it becomes a vertex of every ring through it (inserted into an edge where it lies inside
//! one, which does not change the geometry), and a zero-radius circle of each of those rings, so
//! that every ring rebuilds through the same grid point and none is moved into another.
//!
//! Exact predicates decide "lies on an edge", as GEOS does for `ST_IsValid`. Segments are found
//! with [`crate::geom::box_grid`]: two linear passes to build, a cell or a few per vertex looked up.

use crate::geom::box_grid::BoxIndex;
use crate::geom::{Pt, Shape};
use robust::{orient2d, Coord};
use rustc_hash::FxHashMap;

fn on_segment(a: Pt, b: Pt, p: Pt) -> bool {
    orient2d(
        Coord { x: a[0], y: a[1] },
        Coord { x: b[0], y: b[1] },
        Coord { x: p[0], y: p[1] },
    ) == 0.0
        && p[0] >= a[0].min(b[0])
        && p[0] <= a[0].max(b[0])
        && p[1] >= a[1].min(b[1])
        && p[1] <= a[1].max(b[1])
}

/// Make every touch point a vertex of each ring through it; return, per part and ring, the
/// indices of the vertices that are touch points, and the touch points themselves.
pub fn pin(shape: &mut Shape) -> (Vec<Vec<Vec<usize>>>, Vec<Pt>) {
    let mut pinned: Vec<Vec<Vec<usize>>> = shape
        .parts
        .iter()
        .map(|p| vec![Vec::new(); p.len()])
        .collect();
    let ids: Vec<(usize, usize)> = shape
        .parts
        .iter()
        .enumerate()
        .flat_map(|(pi, p)| (0..p.len()).map(move |ri| (pi, ri)))
        .collect();
    if ids.len() < 2 {
        return (pinned, vec![]);
    }
    // Vertices of one ring lying inside an edge of another: insert them there.
    let mut inserts: FxHashMap<(usize, usize), Vec<Pt>> = FxHashMap::default();
    {
        // a uniform grid of the segments' boxes (an R-tree when they suit no grid): a lookup per
        // vertex, and no recursive sort to build (rstar's bulk load was most of `pin`)
        let mut segs = Vec::new();
        for (k, &(pi, ri)) in ids.iter().enumerate() {
            let r = &shape.parts[pi][ri];
            for i in 0..r.len() {
                let (a, b) = (r[i], r[(i + 1) % r.len()]);
                segs.push((
                    [
                        a[0].min(b[0]),
                        a[1].min(b[1]),
                        a[0].max(b[0]),
                        a[1].max(b[1]),
                    ],
                    (k, i),
                ));
            }
        }
        let index = BoxIndex::new(segs);
        for (k, &(pi, ri)) in ids.iter().enumerate() {
            for &p in &shape.parts[pi][ri] {
                index.for_each_meeting(&[p[0], p[1], p[0], p[1]], |(k2, i)| {
                    if k2 == k {
                        return;
                    }
                    let r = &shape.parts[ids[k2].0][ids[k2].1];
                    let (a, b) = (r[i], r[(i + 1) % r.len()]);
                    if p != a && p != b && on_segment(a, b, p) {
                        inserts.entry((k2, i)).or_default().push(p);
                    }
                });
            }
        }
    }
    if !inserts.is_empty() {
        for (k, &(pi, ri)) in ids.iter().enumerate() {
            let ring = &shape.parts[pi][ri];
            if !(0..ring.len()).any(|i| inserts.contains_key(&(k, i))) {
                continue;
            }
            let mut out = Vec::with_capacity(ring.len() + 4);
            for (i, &a) in ring.iter().enumerate() {
                out.push(a);
                if let Some(extra) = inserts.get_mut(&(k, i)) {
                    let d2 = |p: &Pt| (p[0] - a[0]).powi(2) + (p[1] - a[1]).powi(2);
                    extra.sort_by(|p, q| d2(p).total_cmp(&d2(q)));
                    extra.dedup();
                    out.extend(extra.iter().copied());
                }
            }
            shape.parts[pi][ri] = out;
        }
    }
    // Vertices shared by two or more rings.
    let mut seen: FxHashMap<[u64; 2], usize> = FxHashMap::default();
    let mut shared: FxHashMap<[u64; 2], bool> = FxHashMap::default();
    for (k, &(pi, ri)) in ids.iter().enumerate() {
        for p in &shape.parts[pi][ri] {
            let key = [p[0].to_bits(), p[1].to_bits()];
            match seen.get(&key) {
                Some(&k0) if k0 != k => {
                    shared.insert(key, true);
                }
                Some(_) => {}
                None => {
                    seen.insert(key, k);
                }
            }
        }
    }
    let mut points = Vec::new();
    if shared.is_empty() {
        return (pinned, points);
    }
    for &(pi, ri) in &ids {
        for (v, p) in shape.parts[pi][ri].iter().enumerate() {
            if shared.contains_key(&[p[0].to_bits(), p[1].to_bits()]) {
                pinned[pi][ri].push(v);
                points.push(*p);
            }
        }
    }
    points.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    points.dedup();
    (pinned, points)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Kind;

    #[test]
    fn corner_touch_and_hole_on_an_edge() {
        let mut s = Shape {
            kind: Kind::MultiPolygon,
            parts: vec![
                vec![vec![[0.0, 0.0], [100.0, 0.0], [100.0, 100.0], [0.0, 100.0]]],
                vec![vec![
                    [100.0, 100.0],
                    [200.0, 100.0],
                    [200.0, 200.0],
                    [100.0, 200.0],
                ]],
            ],
        };
        let (pinned, pts) = pin(&mut s);
        assert_eq!(pts, vec![[100.0, 100.0]]);
        assert_eq!(pinned, vec![vec![vec![2]], vec![vec![0]]]);

        let mut h = Shape {
            kind: Kind::Polygon,
            parts: vec![vec![
                vec![[0.0, 0.0], [100.0, 0.0], [100.0, 100.0], [0.0, 100.0]],
                vec![[50.0, 0.0], [60.0, 20.0], [40.0, 20.0]],
            ]],
        };
        let (pinned, pts) = pin(&mut h);
        assert_eq!(pts, vec![[50.0, 0.0]]);
        assert_eq!(h.parts[0][0][1], [50.0, 0.0]);
        assert_eq!(pinned, vec![vec![vec![1], vec![0]]]);
    }
}
