//! The fewest vertices of a ring whose chain stays within a tolerance of it (Imai and Iri's
//! shortcut graph, with Chan and Chin's wedge test for which shortcuts are allowed), searched within
//! a bounded window so the cost stays O(n · window) rather than O(n²) or worse.
//!
//! Douglas-Peucker keeps points where the farthest vertex lies and is not minimal. Here a shortcut
//! from vertex `i` to vertex `j` is allowed when every vertex between them lies within `tol` of the
//! segment between the two, *as stored* (each end snapped to the grid, so the rounding is measured,
//! not budgeted); the fewest shortcuts from one fixed vertex to the next is a shortest path in that
//! graph. The chain then lies within `tol` of the ring and the ring within `max(tol, the largest
//! rounding)` of the chain: the ring runs inside the band around each shortcut from near one end
//! to near the other.

use crate::geom::{dist_to_segment, Pt};

/// Longest shortcut, in vertices, that is looked for.
const WINDOW: usize = 256;

/// Indices of the vertices kept, ascending: every index of `fixed` (vertex 0 when there is none)
/// and between consecutive fixed vertices the fewest that keep every skipped vertex within `tol`
/// of its shortcut. The ring is closed (its last vertex joins its first). `interrupt` is called
/// every [`INTERRUPT_EVERY`] vertices (a cancelled query stops within milliseconds).
pub fn keep(
    ring: &[Pt],
    tol: f64,
    fixed: &[usize],
    snap: &dyn Fn(Pt) -> Pt,
    interrupt: &mut dyn FnMut(),
) -> Vec<usize> {
    let n = ring.len();
    if n <= 3 {
        return (0..n).collect();
    }
    let mut anchors: Vec<usize> = fixed.iter().copied().filter(|&v| v < n).collect();
    if anchors.is_empty() {
        // vertex 0 and the vertex farthest from it, as Douglas-Peucker splits a ring
        let far = (1..n)
            .max_by(|&a, &b| {
                crate::geom::dist(ring[0], ring[a]).total_cmp(&crate::geom::dist(ring[0], ring[b]))
            })
            .unwrap_or(n / 2);
        anchors = vec![0, far];
    }
    anchors.sort_unstable();
    anchors.dedup();
    let mut kept = Vec::new();
    for (k, &a) in anchors.iter().enumerate() {
        let b = anchors.get(k + 1).copied().unwrap_or(anchors[0] + n);
        kept.push(a);
        kept.extend(
            chain(ring, a, b, tol, snap, interrupt)
                .into_iter()
                .map(|v| v % n),
        );
    }
    kept.sort_unstable();
    kept.dedup();
    kept
}

/// The fewest interior vertices of the chain `a..=b` (indices modulo the ring's length) to keep.
/// Vertices between two calls of the interrupt callback.
pub const INTERRUPT_EVERY: usize = 1024;

fn chain(
    ring: &[Pt],
    a: usize,
    b: usize,
    tol: f64,
    snap: &dyn Fn(Pt) -> Pt,
    interrupt: &mut dyn FnMut(),
) -> Vec<usize> {
    let n = ring.len();
    let len = b - a;
    if len <= 1 {
        return Vec::new();
    }
    // the chain's vertices in order (no index wraps around the ring below), and as stored
    let pts: Vec<Pt> = (0..=len).map(|k| ring[(a + k) % n]).collect();
    let stored: Vec<Pt> = pts.iter().map(|&q| snap(q)).collect();
    // hops[k]: fewest shortcuts from 0 to k; from[k]: the vertex before k on that path
    let mut hops = vec![usize::MAX; len + 1];
    let mut from = vec![0usize; len + 1];
    hops[0] = 0;
    for i in 0..len {
        if i % INTERRUPT_EVERY == 0 {
            interrupt();
        }
        if hops[i] == usize::MAX {
            continue;
        }
        let next = hops[i] + 1;
        // i to i + 1 is always allowed
        if next < hops[i + 1] {
            hops[i + 1] = next;
            from[i + 1] = i;
        }
        let mut wedge = Wedge::new(stored[i], tol);
        for j in i + 2..=len.min(i + WINDOW) {
            if !wedge.add(pts[j - 1]) {
                break;
            }
            if next < hops[j] {
                let (allowed, len2) = wedge.allows(stored[j]);
                if allowed && wedge.fits(&pts[i + 1..j], stored[j], len2) {
                    hops[j] = next;
                    from[j] = i;
                }
            }
        }
    }
    let mut path = vec![len];
    let mut k = from[len];
    while k > 0 {
        path.push(k);
        k = from[k];
    }
    path.push(0);
    path.reverse();
    merge_long(&pts, &stored, &path, tol, interrupt)
        .into_iter()
        .map(|k| a + k)
        .collect()
}

/// The window bounds each shortcut, so a long straight run (a densified edge) would keep a vertex
/// every [`WINDOW`] vertices. Where two consecutive shortcuts of the shortest path span more than
/// the window (nowhere else could one of their vertices be dropped: the path is the shortest within
/// it), the shared vertex is dropped while one shortcut from the last vertex kept allows it, its
/// wedge carried on past the window. The interior vertices kept, as offsets into the chain.
fn merge_long(
    pts: &[Pt],
    stored: &[Pt],
    path: &[usize],
    tol: f64,
    interrupt: &mut dyn FnMut(),
) -> Vec<usize> {
    let last = path.len() - 1;
    let mut out = Vec::new();
    let mut cur = 0;
    let mut steps = 0usize;
    while cur < last {
        if cur + 2 > last || path[cur + 2] - path[cur] <= WINDOW {
            cur += 1;
            if cur < last {
                out.push(path[cur]);
            }
            continue;
        }
        let i = path[cur];
        let mut wedge = Wedge::new(stored[i], tol);
        let mut best = cur + 1;
        let mut t = cur + 2;
        for (j, &sj) in stored.iter().enumerate().take(path[last] + 1).skip(i + 2) {
            steps += 1;
            if steps.is_multiple_of(INTERRUPT_EVERY) {
                interrupt();
            }
            if !wedge.add(pts[j - 1]) {
                break;
            }
            if j == path[t] {
                let (allowed, len2) = wedge.allows(sj);
                if allowed && wedge.fits(&pts[i + 1..j], sj, len2) {
                    best = t;
                }
                if t == last {
                    break;
                }
                t += 1;
            }
        }
        cur = best;
        if cur < last {
            out.push(path[cur]);
        }
    }
    out
}

/// Directions from `origin` along which a line passes within `tol` of every vertex added so far:
/// an arc of directions narrower than a half turn, held as its two boundary vectors (`lo` then
/// `hi`, counter-clockwise), so that every test is the sign of a cross product and no angle is
/// computed. Within a half turn, `d` lies in the arc exactly when `lo × d ≥ 0` and `d × hi ≥ 0`.
/// Only signs are tested, so a boundary vector may have any length: a vertex's two boundaries
/// are kept scaled by its distance, which leaves one square root per vertex and no division.
struct Wedge {
    origin: Pt,
    tol: f64,
    /// `tol²`
    tol2: f64,
    /// `(lo, hi)`; `None` until constrained.
    range: Option<(Pt, Pt)>,
    /// Squared distance of the farthest vertex added, from `origin`: when a shortcut is shorter, a
    /// vertex may lie beyond its end, where the line test says nothing, and the vertices are
    /// measured exactly.
    farthest2: f64,
}

fn cross(a: Pt, b: Pt) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Is direction `d` within the arc from `lo` to `hi` (narrower than a half turn)?
fn within(lo: Pt, hi: Pt, d: Pt) -> bool {
    cross(lo, d) >= 0.0 && cross(d, hi) >= 0.0
}

impl Wedge {
    fn new(origin: Pt, tol: f64) -> Wedge {
        Wedge {
            origin,
            tol,
            tol2: tol * tol,
            range: None,
            farthest2: 0.0,
        }
    }

    /// `q` from the origin, and its squared length.
    fn rel(&self, q: Pt) -> (Pt, f64) {
        let d = [q[0] - self.origin[0], q[1] - self.origin[1]];
        (d, d[0] * d[0] + d[1] * d[1])
    }

    /// Narrow the wedge to lines passing within `tol` of `q` (on its side of the origin).
    /// `false` when no direction is left.
    fn add(&mut self, q: Pt) -> bool {
        let (d, r2) = self.rel(q);
        self.farthest2 = self.farthest2.max(r2);
        if r2 <= self.tol2 {
            return true;
        }
        // the arc of directions within asin(tol / r) of d, by its two boundaries: d turned by
        // that angle either way (cosine c = sqrt(r² − tol²) / r, sine s = tol / r), times r
        let c = (r2 - self.tol2).sqrt();
        let s = self.tol;
        let a = [c * d[0] + s * d[1], c * d[1] - s * d[0]];
        let b = [c * d[0] - s * d[1], c * d[1] + s * d[0]];
        match self.range {
            None => {
                self.range = Some((a, b));
                true
            }
            Some((lo, hi)) => {
                // two arcs narrower than a half turn meet in one arc or none: it starts at the
                // later start and ends at the earlier end
                let start = if within(lo, hi, a) {
                    a
                } else if within(a, b, lo) {
                    lo
                } else {
                    return false;
                };
                let end = if within(lo, hi, b) {
                    b
                } else if within(a, b, hi) {
                    hi
                } else {
                    return false;
                };
                if cross(start, end) < 0.0 {
                    return false;
                }
                self.range = Some((start, end));
                true
            }
        }
    }

    /// Does the direction to `q` lie within the wedge? Also its squared distance from the origin.
    fn allows(&self, q: Pt) -> (bool, f64) {
        let (d, r2) = self.rel(q);
        let ok = match self.range {
            None => true,
            Some(_) if r2 == 0.0 => false,
            Some((lo, hi)) => within(lo, hi, d),
        };
        (ok, r2)
    }

    /// Exact check of the shortcut from the origin to `pj` (at squared distance `len2`) over the
    /// vertices `between` its ends, when one may lie beyond its end (else the wedge has already
    /// proved them).
    fn fits(&self, between: &[Pt], pj: Pt, len2: f64) -> bool {
        if self.farthest2 <= len2 {
            return true;
        }
        between
            .iter()
            .all(|&q| dist_to_segment(q, self.origin, pj) <= self.tol)
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn long_rings_call_the_interrupt() {
        let ring: Vec<Pt> = (0..5000)
            .map(|i| {
                let t = i as f64 / 5000.0 * std::f64::consts::TAU;
                [1000.0 * t.cos(), 1000.0 * t.sin()]
            })
            .collect();
        let mut calls = 0;
        keep(&ring, 0.5, &[], &|p| p, &mut || calls += 1);
        assert!(calls >= 5000 / INTERRUPT_EVERY, "{calls} calls");
    }

    use super::*;

    fn within(ring: &[Pt], kept: &[usize], tol: f64) -> bool {
        let n = ring.len();
        kept.iter().enumerate().all(|(k, &a)| {
            let b = kept.get(k + 1).copied().unwrap_or(kept[0] + n);
            (a + 1..b).all(|v| dist_to_segment(ring[v % n], ring[a], ring[b % n]) <= tol)
        })
    }

    #[test]
    fn a_densified_square_keeps_its_corners_not_a_vertex_per_window() {
        // 4 × 25,000 vertices a millimetre apart on straight sides, as densified boundaries are:
        // bounded by the window alone, a vertex was kept every 256 (392 in all)
        let q = 25_000;
        let ring: Vec<Pt> = (0..4 * q)
            .map(|i| {
                let s = (i % q) as f64 * 1e-3;
                let l = q as f64 * 1e-3;
                match i / q {
                    0 => [s, 0.0],
                    1 => [l, s],
                    2 => [l - s, l],
                    _ => [0.0, l - s],
                }
            })
            .collect();
        let mut calls = 0;
        let kept = keep(&ring, 0.01, &[], &|p| p, &mut || calls += 1);
        assert!(kept.len() <= 6, "{kept:?}");
        // each corner kept, or a vertex within the tolerance of it (10 vertices of 1 mm)
        for corner in [0, q, 2 * q, 3 * q] {
            assert!(
                kept.iter().any(|&v| v.abs_diff(corner) <= 10),
                "{corner}: {kept:?}"
            );
        }
        assert!(within(&ring, &kept, 0.01));
        assert!(calls >= 4 * q / INTERRUPT_EVERY, "{calls} calls");
    }

    #[test]
    fn a_square_with_noise_keeps_its_corners() {
        let mut ring = Vec::new();
        for side in 0..4 {
            for k in 0..10 {
                let t = k as f64 * 10.0;
                let wiggle = if k % 2 == 0 { 0.3 } else { -0.3 };
                ring.push(match side {
                    0 => [t, wiggle],
                    1 => [100.0 + wiggle, t],
                    2 => [100.0 - t, 100.0 + wiggle],
                    _ => [wiggle, 100.0 - t],
                });
            }
        }
        // corner to corner the wiggles stay within 0.6 of the chord
        let kept = keep(&ring, 0.7, &[], &|p| p, &mut || {});
        assert_eq!(kept, vec![0, 10, 20, 30]);
        assert!(within(&ring, &kept, 0.7));
        // a fixed vertex is kept
        let kept = keep(&ring, 0.7, &[5], &|p| p, &mut || {});
        assert!(kept.contains(&5) && within(&ring, &kept, 0.7), "{kept:?}");
        // below the wiggle, every vertex
        assert_eq!(keep(&ring, 0.2, &[], &|p| p, &mut || {}).len(), 40);
    }

    #[test]
    fn never_more_than_douglas_peucker_and_always_within() {
        // a rough star: 400 vertices, radius jittered deterministically
        let ring: Vec<Pt> = (0..400)
            .map(|k| {
                let a = k as f64 / 400.0 * std::f64::consts::TAU;
                let r = 1000.0 + 80.0 * ((k * 7919 % 13) as f64 / 13.0) + 200.0 * (5.0 * a).sin();
                [r * a.cos(), r * a.sin()]
            })
            .collect();
        for tol in [1.0, 10.0, 40.0, 150.0] {
            let ours = keep(&ring, tol, &[], &|p| p, &mut || {});
            let dp = crate::encode::paper::douglas_peucker::keep(&ring, tol);
            assert!(within(&ring, &ours, tol), "{tol}");
            assert!(
                ours.len() <= dp.len(),
                "{tol}: {} > {}",
                ours.len(),
                dp.len()
            );
        }
    }
}
