//! The last resort for rings that come closer than the finest grid their coordinates allow
//! (within a unit or so in the last place of a double): the input on that grid, with every vertex
//! that comes within [`REACH`] grid steps of an edge it does not end pushed away from it, to the
//! side of the edge it lies on in the input.
//!
//! Two segments that do not meet are nearest at an end point of one of them, so once no vertex is
//! within [`REACH`] of an edge it does not end, no two segments touch or cross: the rings keep the
//! input's topology, touching only where the input's touch (the input's touch points are shared
//! vertices by then, [`crate::check::touch::pin`], and stay shared). The encoder then holds the
//! nudged shape as it holds any input, within `max_error` less the Hausdorff distance from the
//! input to it, which it measures; its closed loop checks the result as always.

use crate::check::touch;
use crate::format::grid::Grid;
use crate::geom::box_grid::{Bbox, BoxIndex};
use crate::geom::{dist, signed_area, Polygon, Pt, Shape};
use robust::{orient2d, Coord};

/// How near, in grid steps, a vertex may come to an edge it does not end.
const REACH: f64 = 2.0;

/// Rounds of pushing before giving up (a push rarely brings a vertex near another edge).
const ROUNDS: usize = 16;

/// A shape with its touch points: per part and ring the indices of the vertices that are touch
/// points, and the points.
pub(super) type Pinned = (Shape, Vec<Vec<Vec<usize>>>, Vec<Pt>);

/// The shape nudged onto `grid`, with its touch points (`touch::pin`'s), or `None` when the pushes
/// do not settle. A ring the grid leaves with under three points is `scaled` up ([`widen`]), or
/// else made a thin triangle ([`widen_flat`]): each holds some shapes the other does not.
pub(super) fn apart(shape: &Shape, touches: &[Pt], grid: Grid, scaled: bool) -> Option<Pinned> {
    let step = grid.step_f64();
    let snap = |p: Pt| [grid.snap(p[0]), grid.snap(p[1])];
    // per ring: the input's vertices and where they are now, consecutive repeats on the grid
    // dropped (with their input vertex), rings left with fewer than three points widened to a few
    // grid steps (a ring left without area otherwise is opened by the pushes). `touches` are the
    // input's touch points, sorted as `touch::pin` gives them.
    let mut rings: Vec<(usize, Vec<Pt>, Vec<Pt>)> = Vec::new();
    let mut shells = vec![false; shape.parts.len()];
    for (pi, part) in shape.parts.iter().enumerate() {
        for (ri, ring) in part.iter().enumerate() {
            let (mut was, mut now) = placed(ring.iter().copied(), snap);
            if now.len() < 3 {
                // about a point it shares with another ring, so that they still share it
                let anchor = ring
                    .iter()
                    .position(|p| touches.binary_search_by(|t| cmp(t, p)).is_ok())
                    .unwrap_or(0);
                (was, now) = if scaled {
                    widen(ring, anchor, ri == 0, step, &snap)?
                } else {
                    widen_flat(&was, &now, ri == 0, step, &snap)
                };
            }
            shells[pi] |= ri == 0;
            if shells[pi] {
                rings.push((pi, was, now));
            }
        }
    }
    let reach = REACH * step;
    let mut settled = false;
    for _ in 0..ROUNDS {
        let pushes = near_pairs(&rings, reach);
        if pushes.is_empty() {
            settled = true;
            break;
        }
        for (k, v, k2, i) in pushes {
            let n2 = rings[k2].1.len();
            let (a0, b0) = (rings[k2].1[i], rings[k2].1[(i + 1) % n2]);
            let (a, b) = (rings[k2].2[i], rings[k2].2[(i + 1) % n2]);
            let (p0, p) = (rings[k].1[v], rings[k].2[v]);
            rings[k].2[v] = push(p0, a0, b0, p, a, b, reach + step, &snap);
        }
    }
    if !settled {
        return None;
    }
    let mut parts: Vec<Polygon> = vec![Vec::new(); shape.parts.len()];
    for (pi, _, now) in rings {
        parts[pi].push(now);
    }
    parts.retain(|p| !p.is_empty());
    let mut near = Shape {
        kind: shape.kind,
        parts,
    };
    if near.is_empty() {
        return None;
    }
    let (pinned, touches) = touch::pin(&mut near);
    Some((near, pinned, touches))
}

/// A ring that the grid leaves with fewer than three points (a ring a few units in the last place
/// across), scaled up about its anchor until it spans a few grid steps with its orientation kept:
/// the input's vertices and their places.
fn widen(
    ring: &[Pt],
    anchor: usize,
    shell: bool,
    step: f64,
    snap: &impl Fn(Pt) -> Pt,
) -> Option<(Vec<Pt>, Vec<Pt>)> {
    let o = ring[anchor];
    let at = snap(o);
    let r = ring.iter().fold(0.0f64, |m, &p| m.max(dist(p, o)));
    if r == 0.0 {
        return None;
    }
    for spans in [4.0, 8.0, 16.0, 32.0] {
        let k = spans * step / r;
        let (was, now) = placed(
            ring[anchor..].iter().chain(&ring[..anchor]).copied(),
            |p: Pt| snap([at[0] + (p[0] - o[0]) * k, at[1] + (p[1] - o[1]) * k]),
        );
        let area = signed_area(&now);
        if now.len() >= 3 && area != 0.0 && (area > 0.0) == shell {
            return Some((was, now));
        }
    }
    None
}

/// A ring that the grid leaves with one or two points: those and one a grid step beside their
/// middle, on the interior's side (left of a shell, which runs counter-clockwise; right of a hole).
fn widen_flat(
    was: &[Pt],
    now: &[Pt],
    shell: bool,
    step: f64,
    snap: &impl Fn(Pt) -> Pt,
) -> (Vec<Pt>, Vec<Pt>) {
    let a = 0;
    let b = (0..now.len())
        .max_by(|&i, &j| dist(now[a], now[i]).total_cmp(&dist(now[a], now[j])))
        .unwrap_or(0);
    let (pa, pb) = (now[a], now[b]);
    let len = dist(pa, pb);
    let turn = if shell { 1.0 } else { -1.0 };
    let (u, m) = if len == 0.0 {
        ([0.0, turn], [pa[0] + step, pa[1]])
    } else {
        (
            [-(pb[1] - pa[1]) / len * turn, (pb[0] - pa[0]) / len * turn],
            [(pa[0] + pb[0]) / 2.0, (pa[1] + pb[1]) / 2.0],
        )
    };
    let pb = if len == 0.0 { snap(m) } else { pb };
    let wb = if len == 0.0 { pb } else { was[b] };
    let mut c = snap([m[0] + u[0] * step, m[1] + u[1] * step]);
    let mut k = 2.0;
    while side(pa, pb, c) == 0.0 && k < 8.0 {
        c = snap([m[0] + u[0] * step * k, m[1] + u[1] * step * k]);
        k *= 2.0;
    }
    // the three counter-clockwise for a shell, clockwise for a hole
    let ring = if (side(pa, pb, c) > 0.0) == shell {
        vec![pa, pb, c]
    } else {
        vec![pa, c, pb]
    };
    let w = ring
        .iter()
        .map(|&p| {
            if p == pa {
                was[a]
            } else if p == pb {
                wb
            } else {
                c
            }
        })
        .collect();
    (w, ring)
}

/// A ring's points and where `place` puts them, consecutive repeats of a place (and the closing
/// ones) dropped with their point.
fn placed(ring: impl Iterator<Item = Pt>, place: impl Fn(Pt) -> Pt) -> (Vec<Pt>, Vec<Pt>) {
    let (mut was, mut now): (Vec<Pt>, Vec<Pt>) = (Vec::new(), Vec::new());
    for p in ring {
        let q = place(p);
        if now.last() != Some(&q) {
            was.push(p);
            now.push(q);
        }
    }
    while now.len() > 1 && now.first() == now.last() {
        now.pop();
        was.pop();
    }
    (was, now)
}

fn cmp(a: &Pt, b: &Pt) -> std::cmp::Ordering {
    a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1]))
}

fn side(a: Pt, b: Pt, p: Pt) -> f64 {
    orient2d(
        Coord { x: a[0], y: a[1] },
        Coord { x: b[0], y: b[1] },
        Coord { x: p[0], y: p[1] },
    )
}

/// `p` moved from the edge `a-b` to at least `away`, on the side where the input had it (`p0`
/// against `a0-b0`), then to the grid.
#[allow(clippy::too_many_arguments)]
fn push(p0: Pt, a0: Pt, b0: Pt, p: Pt, a: Pt, b: Pt, away: f64, snap: &impl Fn(Pt) -> Pt) -> Pt {
    let (d, len) = ([b[0] - a[0], b[1] - a[1]], dist(a, b));
    let t = if len == 0.0 {
        0.0
    } else {
        ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / (len * len)
    };
    let s = side(a0, b0, p0);
    // beside the edge: along its normal, to the input's side; beyond an end: away from that end,
    // in the input's direction from it
    let dir = if (0.0..=1.0).contains(&t) && s != 0.0 && len > 0.0 {
        [-d[1] / len * s.signum(), d[0] / len * s.signum()]
    } else {
        let e0 = if t < 0.5 { a0 } else { b0 };
        let e = if t < 0.5 { a } else { b };
        let from = [p0[0] - e0[0], p0[1] - e0[1]];
        let l = (from[0] * from[0] + from[1] * from[1]).sqrt();
        if l == 0.0 {
            return p;
        }
        let u = [from[0] / l, from[1] / l];
        let now = (p[0] - e[0]) * u[0] + (p[1] - e[1]) * u[1];
        let by = away - now;
        return snap([p[0] + u[0] * by, p[1] + u[1] * by]);
    };
    let now = (p[0] - a[0]) * dir[0] + (p[1] - a[1]) * dir[1];
    let by = away - now;
    snap([p[0] + dir[0] * by, p[1] + dir[1] * by])
}

/// `(ring, vertex, ring, edge)`: a vertex within `reach` of an edge it does not end, as the input
/// has them (a vertex the input has on an edge's end point, or on the edge, is a touch kept).
fn near_pairs(
    rings: &[(usize, Vec<Pt>, Vec<Pt>)],
    reach: f64,
) -> Vec<(usize, usize, usize, usize)> {
    let mut segs: Vec<(Bbox, (usize, usize))> = Vec::new();
    for (k, (_, _, r)) in rings.iter().enumerate() {
        for i in 0..r.len() {
            let (a, b) = (r[i], r[(i + 1) % r.len()]);
            segs.push((
                [
                    a[0].min(b[0]) - reach,
                    a[1].min(b[1]) - reach,
                    a[0].max(b[0]) + reach,
                    a[1].max(b[1]) + reach,
                ],
                (k, i),
            ));
        }
    }
    let index = BoxIndex::new(segs);
    let mut out = Vec::new();
    for (k, (_, was, now)) in rings.iter().enumerate() {
        for (v, &p) in now.iter().enumerate() {
            let p0 = was[v];
            let mut nearest: Option<(f64, usize, usize)> = None;
            index.for_each_meeting(&[p[0], p[1], p[0], p[1]], |(k2, i)| {
                let n2 = rings[k2].1.len();
                let j = (i + 1) % n2;
                if k2 == k && (i == v || j == v) {
                    return;
                }
                let (a0, b0) = (rings[k2].1[i], rings[k2].1[j]);
                if p0 == a0 || p0 == b0 || on_segment(a0, b0, p0) {
                    return;
                }
                let d = crate::geom::dist_to_segment(p, rings[k2].2[i], rings[k2].2[j]);
                if d < reach && nearest.is_none_or(|(e, _, _)| d < e) {
                    nearest = Some((d, k2, i));
                }
            });
            if let Some((_, k2, i)) = nearest {
                out.push((k, v, k2, i));
            }
        }
    }
    out
}

fn on_segment(a: Pt, b: Pt, p: Pt) -> bool {
    side(a, b, p) == 0.0
        && p[0] >= a[0].min(b[0])
        && p[0] <= a[0].max(b[0])
        && p[1] >= a[1].min(b[1])
        && p[1] <= a[1].max(b[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::validity::{problems_where, touch_key, RingRef, Touches};
    use crate::format::decimal::Decimal;
    use crate::geom::{orient, Kind};

    fn grid() -> Grid {
        Grid::new(Decimal::new(1, -3).unwrap())
    }

    fn apart_and_valid(parts: Vec<Polygon>, kind: Kind) -> (Shape, Vec<Pt>) {
        let mut shape = Shape { kind, parts };
        orient(&mut shape);
        let (_, touches) = touch::pin(&mut shape);
        let (near, _, touches) = apart(&shape, &touches, grid(), true).expect("settled");
        let rings: Vec<RingRef> = near
            .parts
            .iter()
            .enumerate()
            .flat_map(|(part, p)| {
                p.iter()
                    .enumerate()
                    .map(move |(ring, r)| RingRef { part, ring, pts: r })
            })
            .collect();
        let allowed: Touches = touches.iter().map(|&p| touch_key(p)).collect();
        assert!(
            problems_where(&rings, None, &allowed, &mut || {}).is_empty(),
            "{near:?}"
        );
        (near, touches)
    }

    #[test]
    fn parts_a_unit_in_the_last_place_apart_stay_apart() {
        // two squares whose corners are 1e-15 apart: on a grid of 0.001 they would share it
        let a = vec![vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]];
        let b = vec![vec![
            [1.0 + 1e-15, 1.0],
            [2.0, 1.0],
            [2.0, 2.0],
            [1.0 + 1e-15, 2.0],
        ]];
        let (near, touches) = apart_and_valid(vec![a, b], Kind::MultiPolygon);
        assert!(touches.is_empty());
        assert!(dist(near.parts[0][0][2], near.parts[1][0][0]) >= 0.002);
    }

    #[test]
    fn a_hole_nearly_on_its_shell_is_pushed_inside() {
        let shell = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]];
        let hole = vec![[1.0, 1e-12], [2.0, 1.0], [3.0, 1.0]];
        let (near, touches) = apart_and_valid(vec![vec![shell, hole]], Kind::Polygon);
        assert!(touches.is_empty());
        assert!(near.parts[0][1].iter().all(|p| p[1] >= 0.002));
    }

    #[test]
    fn a_hole_a_unit_in_the_last_place_across_is_scaled_up_at_its_touch() {
        // a hole at a corner of its shell, a few units in the last place across
        let shell = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]];
        let hole = vec![
            [4.0, 4.0],
            [4.0 - 2e-15, 4.0 - 1e-15],
            [4.0 - 1e-15, 4.0 - 2e-15],
        ];
        let (near, touches) = apart_and_valid(vec![vec![shell, hole]], Kind::Polygon);
        assert_eq!(touches, vec![[4.0, 4.0]]);
        assert!(near.parts[0][1].len() == 3);
    }

    #[test]
    fn a_sliver_thinner_than_the_grid_is_opened() {
        // a ring 1e-15 wide: on the grid it would fold onto itself
        let sliver = vec![[0.0, 0.0], [0.5, 1e-15], [1.0, 0.0], [0.5, -1e-15]];
        let (near, _) = apart_and_valid(vec![vec![sliver]], Kind::Polygon);
        assert_eq!(near.parts[0][0].len(), 4);
    }

    #[test]
    fn the_input_s_touch_points_stay_shared() {
        // two squares sharing a corner exactly, a third a unit in the last place from the second
        let a = vec![vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]];
        let b = vec![vec![[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]]];
        let c = vec![vec![[2.0 + 1e-15, 1.5], [3.0, 1.0], [3.0, 2.0]]];
        let (_, touches) = apart_and_valid(vec![a, b, c], Kind::MultiPolygon);
        assert_eq!(touches, vec![[1.0, 1.0]]);
    }
}
