//! Measurement only (not a format): how many bytes arcs stored as "end points + signed sagitta"
//! would save over `encode_within`'s points, in version 2's coder.
//!
//! For each ring, on the grid `encode_within` chose and at its tolerance: the fewest points
//! (`min_points::keep`, the baseline), and a cheapest path over the input vertices in bits, whose
//! steps are a straight shortcut (every vertex between within `tol` of the segment between the
//! two stored ends, up to 256 vertices) or an arc between two stored vertices (every vertex between,
//! and every edge's midpoint, within `tol` of the circle through both ends with a sagitta a
//! multiple of `q` grid steps, at most a half circle, up to 96 vertices). Priced at `CT_BP` bits a
//! point (default 9) and 2.5 + 2 x (bit length of the sagitta) an arc. Both chains are then written
//! with version 2's point models; the arc chain adds a flag per point ("an arc to the next",
//! adaptive) and the sagitta (its own adaptive integer model). The repair loop is not run (the
//! encoder's own ranges are what `plain_stream` is next to `stored_within`). `CT_DATA=holdout`,
//! `CT_Q` (the sagitta's step in grid steps, default 1), `CT_NOARC=1` (straight steps only: checks
//! the path search against `min_points`).
#![allow(clippy::needless_range_loop)]
#[path = "../tests/common/mod.rs"]
mod common;
use circletree_core::coder::{class, Bit, IntModel, Sink, Writer};
use circletree_core::encode::encode_within;
use circletree_core::format::v2::Models;
use circletree_core::format::Circle;
use circletree_core::geometry::{dist, dist_to_segment, Pt};
use circletree_core::grid::Grid;

const RUN: usize = 96;

/// Sagitta (in units of `q`) of an arc from `p` to `e` passing within `tol` of every vertex of
/// `mid` (and of the midpoints of the chain's segments), if there is one.
fn fit(p: Pt, e: Pt, chain: &[Pt], tol: f64, q: f64) -> Option<i64> {
    let c = dist(p, e);
    if c < 1e-9 {
        return None;
    }
    let h = c / 2.0;
    let d = [(e[0] - p[0]) / c, (e[1] - p[1]) / c];
    let n = [-d[1], d[0]];
    let m = [(p[0] + e[0]) / 2.0, (p[1] + e[1]) / 2.0];
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    let t2 = tol * 0.9;
    for v in chain {
        let (x, y) = (v[0] - m[0], v[1] - m[1]);
        let a = x * d[0] + y * d[1];
        let b = x * n[0] + y * n[1];
        if a.abs() >= h {
            return None;
        }
        let w = 1.0 - (a / h) * (a / h);
        let sv = if b.abs() < 1e-12 {
            0.0
        } else {
            let u = (a * a + b * b - h * h) / (2.0 * b);
            u + b.signum() * (u * u + h * h).sqrt()
        };
        lo = lo.max(sv - t2 / w);
        hi = hi.min(sv + t2 / w);
        if lo > hi {
            return None;
        }
    }
    let k = ((lo + hi) / 2.0 / q).round() as i64;
    let k = if (k as f64) * q < lo {
        k + 1
    } else if (k as f64) * q > hi {
        k - 1
    } else {
        k
    };
    let s = k as f64 * q;
    if s < lo || s > hi || k == 0 || s.abs() > h {
        return None;
    }
    // exact check: every vertex and segment midpoint within tol of the circle
    let u = (s * s - h * h) / (2.0 * s);
    let ctr = [m[0] + n[0] * u, m[1] + n[1] * u];
    let r = (u * u + h * h).sqrt();
    let mut prev = p;
    for v in chain.iter().chain(std::iter::once(&e)) {
        let mp = [(prev[0] + v[0]) / 2.0, (prev[1] + v[1]) / 2.0];
        if (dist(*v, ctr) - r).abs() > tol || (dist(mp, ctr) - r).abs() > tol {
            return None;
        }
        prev = *v;
    }
    Some(k)
}

fn main() {
    let t: f64 = std::env::args()
        .nth(1)
        .map(|s| s.parse().expect("t"))
        .unwrap_or(10.0);
    let qf: f64 = std::env::var("CT_Q")
        .ok()
        .map(|s| s.parse().expect("q"))
        .unwrap_or(1.0);
    let (mut pts_bytes, mut arc_bytes, mut np, mut na, mut narcs, mut stored) =
        (0usize, 0usize, 0usize, 0usize, 0usize, 0usize);
    for s in common::load(&[]) {
        let Ok((ct, _)) = encode_within(&s.wkb, s.srid, t, None, &mut || {}) else {
            continue;
        };
        stored += ct.to_bytes().len();
        let g = Grid::new(ct.grid);
        let step = g.step_f64();
        let q = step * qf;
        let tol = t - 4e-3 * step;
        let input = circletree_core::wkb::read(&s.wkb).expect("wkb");
        let snap = |p: Pt| [g.snap(p[0]), g.snap(p[1])];
        let ext = ct.bbox.map_or(1, |b| (b[2] - b[0]).max(b[3] - b[1]) as u64);
        let rings: Vec<&Vec<Pt>> = input.shape.rings().collect();
        // points-only and arc chains, as grid integers: (x, y, sagitta of the arc to the next)
        let mut plain: Vec<Vec<(i64, i64)>> = Vec::new();
        let mut arcs: Vec<Vec<(i64, i64, i64)>> = Vec::new();
        for ring in rings {
            let keep = circletree_core::min_points::keep(ring, tol, &[], &snap, &mut || {});
            let n = ring.len();
            let vtx = |i: usize| ring[i % n];
            let bp: f64 = std::env::var("CT_BP")
                .ok()
                .map_or(9.0, |s| s.parse().expect("bp"));
            // best[k]: (cost, from, sagitta) of reaching input vertex k (n = vertex 0 again)
            let mut best = vec![(f64::INFINITY, 0usize, 0i64); n + 1];
            best[0].0 = 0.0;
            for i in 0..n {
                let base = best[i].0;
                if !base.is_finite() {
                    continue;
                }
                let c = base + bp + 0.2;
                if c < best[i + 1].0 {
                    best[i + 1] = (c, i, 0);
                }
                let p = snap(vtx(i));
                // straight shortcuts: the wedge of directions from p passing within tol of
                // every vertex so far (angles relative to the first one)
                let first = vtx(i + 1);
                let th0 = (first[1] - p[1]).atan2(first[0] - p[0]);
                let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
                let mut far = 0.0f64;
                for j in i + 2..=(i + 256).min(n) {
                    let v = vtx(j - 1);
                    let d = dist(p, v);
                    far = far.max(d);
                    if d > tol {
                        let mut th = (v[1] - p[1]).atan2(v[0] - p[0]) - th0;
                        th = (th + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                            - std::f64::consts::PI;
                        let w = (tol / d).asin();
                        lo = lo.max(th - w);
                        hi = hi.min(th + w);
                        if lo > hi {
                            break;
                        }
                    }
                    let e = snap(vtx(j));
                    let de = dist(p, e);
                    let mut th = (e[1] - p[1]).atan2(e[0] - p[0]) - th0;
                    th = (th + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                        - std::f64::consts::PI;
                    if th >= lo && th <= hi && far <= de + tol {
                        // exact check
                        if (i + 1..j).all(|k| dist_to_segment(vtx(k), p, e) <= tol) {
                            let c = base + bp + 0.2;
                            if c < best[j].0 {
                                best[j] = (c, i, 0);
                            }
                        }
                    }
                }
                // arcs
                let mut fails = 0;
                let run = if std::env::var("CT_NOARC").is_ok() {
                    0
                } else {
                    RUN
                };
                for j in i + 2..=(i + run).min(n) {
                    let chain: Vec<Pt> = (i + 1..j).map(vtx).collect();
                    match fit(p, snap(vtx(j)), &chain, tol, q) {
                        Some(k) => {
                            fails = 0;
                            let c = base + bp + 2.5 + 2.0 * class(k.unsigned_abs()) as f64;
                            if c < best[j].0 {
                                best[j] = (c, i, k);
                            }
                        }
                        None => {
                            fails += 1;
                            if fails > 6 {
                                break;
                            }
                        }
                    }
                }
            }
            let mut path = vec![];
            let mut k = n;
            while k > 0 {
                let (_, f, sg) = best[k];
                path.push((f, sg));
                k = f;
            }
            path.reverse();
            let kp: Vec<Pt> = keep.iter().map(|&i| snap(ring[i])).collect();
            let q = |p: Pt| (g.quantize(p[0]), g.quantize(p[1]));
            plain.push(kp.iter().map(|p| q(*p)).collect());
            arcs.push(
                path.iter()
                    .map(|&(f, sg)| {
                        let (x, y) = q(snap(vtx(f)));
                        (x, y, sg)
                    })
                    .collect(),
            );
        }
        let write = |rings: &[Vec<(i64, i64, i64)>], with_flags: bool| -> (usize, usize) {
            let n: usize = rings.iter().map(Vec::len).sum();
            let mut mo = Models::new(ext, n as u64, 1);
            let mut w = Writer::default();
            let mut flag = [Bit::default(); 2];
            let mut sag = IntModel::expecting(2);
            let mut at = (0i64, 0i64);
            let mut prev = 0usize;
            let mut count = 0;
            for r in rings {
                for &(x, y, sg) in r {
                    mo.put(&mut w, &Circle { x, y, r: 0 }, at);
                    at = (x, y);
                    if with_flags {
                        w.flag(&mut flag[prev], sg != 0);
                        prev = (sg != 0) as usize;
                        if sg != 0 {
                            w.int(&mut sag, sg);
                            count += 1;
                        }
                    }
                }
            }
            (w.finish().len(), count)
        };
        let plain3: Vec<Vec<(i64, i64, i64)>> = plain
            .iter()
            .map(|r| r.iter().map(|&(x, y)| (x, y, 0)).collect())
            .collect();
        let (pb, _) = write(&plain3, false);
        let (ab, ac) = write(&arcs, true);
        let (p_n, a_n): (usize, usize) = (
            plain.iter().map(Vec::len).sum(),
            arcs.iter().map(Vec::len).sum(),
        );
        println!(
            "{:28} grid={} pts={p_n:6} arcpts={a_n:6} arcs={ac:5} plain={pb:7} witharcs={ab:7} {:.3}",
            s.name,
            ct.grid,
            ab as f64 / pb as f64
        );
        pts_bytes += pb;
        arc_bytes += ab;
        np += p_n;
        na += a_n;
        narcs += ac;
    }
    println!(
        "TOTAL t={t} stored_within={stored} plain_stream={pts_bytes} arcs_stream={arc_bytes} ratio={:.3} points {np} -> {na} ({narcs} arcs)",
        arc_bytes as f64 / pts_bytes as f64
    );
}
