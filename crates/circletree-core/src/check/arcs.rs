//! Validity of the true arcs. [`crate::check::validity`] checks the rings stroked at the grid step; this
//! module checks what lies between those chords and the arcs they stand for, so that the value is
//! valid however finely it is stroked (`ct_decode(ct, tol)` for any `tol` up to the grid step) and
//! as true arcs (`ct_decode_curved`):
//!
//! - no arc may meet a line or another arc of the rings except where they join (arc-segment and
//!   arc-arc intersection, solved from the circle equations);
//! - no ring may lie inside the sliver between a chord of the grid stroke and its arc.
//!
//! Why that is enough: every finer stroke of an arc lies in the slivers between the coarse chords
//! and the arc. A piece of another ring that reaches into a sliver without crossing its chord
//! (checked on the coarse stroke) or its arc (checked here) lies wholly inside it, and then so does
//! its whole ring (the last test). Ends of pieces closer than `eps` count as meeting, so floating
//! point rounding can only make the check stricter, never let a touch through.

use crate::decode::reconstruct::{arc_segments, Seg, Spans};
use crate::geom::box_grid::{union, Bbox, BoxIndex, EMPTY};
use crate::geom::{dist2_to_segment, Pt};
use std::f64::consts::TAU;

/// A ring's rebuilt pieces: its part, its index in the part, its spans, and whether each span
/// changed since the last check that found nothing (`None`: all did).
pub struct ArcRing<'a> {
    /// The spans ([`crate::decode::reconstruct::ring_spans`]).
    pub spans: &'a Spans,
    /// `dirty[s]`: span `s` may differ from the last check.
    pub dirty: Option<&'a [bool]>,
}

/// A piece's ring and position in it.
type Key = (usize, usize);

/// One piece of a ring, read from its spans where it is looked at (a ring's pieces are only
/// listed by where they are: copies of every piece of a large ring each round were megabytes).
#[derive(Clone, Copy)]
struct Piece<'a> {
    ring: usize,
    span: usize,
    /// Position in the ring's sequence of pieces (degenerate lines dropped).
    pos: usize,
    seg: &'a Seg,
}

fn arc_box(c: Pt, r: f64, a0: f64, sweep: f64, from: Pt, to: Pt) -> [f64; 4] {
    let mut b = [
        from[0].min(to[0]),
        from[1].min(to[1]),
        from[0].max(to[0]),
        from[1].max(to[1]),
    ];
    for (k, p) in [
        [c[0] + r, c[1]],
        [c[0], c[1] + r],
        [c[0] - r, c[1]],
        [c[0], c[1] - r],
    ]
    .into_iter()
    .enumerate()
    {
        if on_arc_angle(k as f64 * TAU / 4.0, a0, sweep, 1e-12) {
            b = [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ];
        }
    }
    b
}

fn piece_box(seg: &Seg, pad: f64) -> Bbox {
    let b = match *seg {
        Seg::Line(..) => rough_box(seg),
        Seg::Arc {
            c,
            r,
            a0,
            sweep,
            from,
            to,
        } => arc_box(c, r, a0, sweep, from, to),
    };
    padded(b, pad)
}

/// `b` grown by `pad` on every side.
fn padded(b: Bbox, pad: f64) -> Bbox {
    [b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad]
}

/// Pieces in a block of [`problems`]' first look.
const BLOCK: usize = 32;

/// A box holding the piece, cheaper than [`piece_box`]: an arc's whole circle (and its ends,
/// which rounding may put a hair outside it).
fn rough_box(seg: &Seg) -> Bbox {
    match *seg {
        Seg::Line(a, b) => [
            a[0].min(b[0]),
            a[1].min(b[1]),
            a[0].max(b[0]),
            a[1].max(b[1]),
        ],
        Seg::Arc { c, r, from, to, .. } => [
            (c[0] - r).min(from[0]).min(to[0]),
            (c[1] - r).min(from[1]).min(to[1]),
            (c[0] + r).max(from[0]).max(to[0]),
            (c[1] + r).max(from[1]).max(to[1]),
        ],
    }
}

/// Is angle `t` on the arc starting at `a0` sweeping `sweep` (signed), to `tol` radians?
fn on_arc_angle(t: f64, a0: f64, sweep: f64, tol: f64) -> bool {
    let rel = if sweep >= 0.0 { t - a0 } else { a0 - t }.rem_euclid(TAU);
    rel <= sweep.abs() + tol || rel >= TAU - tol
}

fn on_arc(p: Pt, c: Pt, r: f64, a0: f64, sweep: f64, eps: f64) -> bool {
    on_arc_angle((p[1] - c[1]).atan2(p[0] - c[0]), a0, sweep, eps / r)
}

/// At most three points, without an allocation (the checks ask for them pair by pair).
#[derive(Default)]
struct Few {
    pts: [Pt; 3],
    n: usize,
}

impl Few {
    fn push(&mut self, p: Pt) {
        self.pts[self.n] = p;
        self.n += 1;
    }

    fn iter(&self) -> std::slice::Iter<'_, Pt> {
        self.pts[..self.n].iter()
    }
}

/// Points where the line `a-b` meets the circle (to `eps`).
fn line_circle(a: Pt, b: Pt, c: Pt, r: f64, eps: f64) -> Few {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    let mut out = Few::default();
    if len2 == 0.0 {
        return out;
    }
    // closest point of the segment to the centre: a touch when it is within eps of the circle
    let t0 = (((c[0] - a[0]) * d[0] + (c[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0);
    let q = [a[0] + t0 * d[0], a[1] + t0 * d[1]];
    let dq = (q[0] - c[0]).hypot(q[1] - c[1]);
    if (dq - r).abs() <= eps {
        out.push(q);
    }
    if dq > r + eps {
        return out;
    }
    // the two crossings of the infinite line, kept when on the segment
    let f = [a[0] - c[0], a[1] - c[1]];
    let bq = 2.0 * (f[0] * d[0] + f[1] * d[1]);
    let cq = f[0] * f[0] + f[1] * f[1] - r * r;
    let disc = (bq * bq - 4.0 * len2 * cq).max(0.0).sqrt();
    let tol_t = eps / len2.sqrt();
    for t in [(-bq - disc) / (2.0 * len2), (-bq + disc) / (2.0 * len2)] {
        if (-tol_t..=1.0 + tol_t).contains(&t) {
            out.push([a[0] + t * d[0], a[1] + t * d[1]]);
        }
    }
    out
}

/// Points where two circles meet (to `eps`); `None` when they are the same circle.
fn circle_circle(c1: Pt, r1: f64, c2: Pt, r2: f64, eps: f64) -> Option<Few> {
    let d = (c2[0] - c1[0]).hypot(c2[1] - c1[1]);
    if d <= eps && (r1 - r2).abs() <= eps {
        return None;
    }
    if d > r1 + r2 + eps || d < (r1 - r2).abs() - eps || d == 0.0 {
        return Some(Few::default());
    }
    let u = [(c2[0] - c1[0]) / d, (c2[1] - c1[1]) / d];
    let a = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
    let h = (r1 * r1 - a * a).max(0.0).sqrt();
    let m = [c1[0] + a * u[0], c1[1] + a * u[1]];
    let mut out = Few::default();
    out.push([m[0] - h * u[1], m[1] + h * u[0]]);
    out.push([m[0] + h * u[1], m[1] - h * u[0]]);
    Some(out)
}

fn near(p: Pt, q: Pt, eps: f64) -> bool {
    let d = [p[0] - q[0], p[1] - q[1]];
    // (a distance is at least either difference: most pairs are decided without `hypot`)
    d[0].abs() <= eps && d[1].abs() <= eps && d[0].hypot(d[1]) <= eps
}

/// Do two pieces meet anywhere but at the joints `joints` (points where they are allowed to meet)?
fn meet(x: &Seg, y: &Seg, joints: &[Pt], eps: f64) -> bool {
    let away = |p: &Pt| joints.iter().all(|j| !near(*p, *j, 16.0 * eps));
    match (*x, *y) {
        (Seg::Line(..), Seg::Line(..)) => false, // the stroke check covers straight pieces
        (
            Seg::Line(a, b),
            Seg::Arc {
                c, r, a0, sweep, ..
            },
        )
        | (
            Seg::Arc {
                c, r, a0, sweep, ..
            },
            Seg::Line(a, b),
        ) => line_circle(a, b, c, r, eps)
            .iter()
            .any(|p| away(p) && on_arc(*p, c, r, a0, sweep, eps)),
        (
            Seg::Arc {
                c: c1,
                r: r1,
                a0: s1,
                sweep: w1,
                from: f1,
                to: t1,
            },
            Seg::Arc {
                c: c2,
                r: r2,
                a0: s2,
                sweep: w2,
                from: f2,
                to: t2,
            },
        ) => match circle_circle(c1, r1, c2, r2, eps) {
            Some(pts) => pts.iter().any(|p| {
                away(p) && on_arc(*p, c1, r1, s1, w1, eps) && on_arc(*p, c2, r2, s2, w2, eps)
            }),
            // the same circle: they meet if an end of one lies on the other, off the joints
            None => {
                [f1, t1]
                    .iter()
                    .any(|p| away(p) && on_arc(*p, c2, r2, s2, w2, -eps))
                    || [f2, t2]
                        .iter()
                        .any(|p| away(p) && on_arc(*p, c1, r1, s1, w1, -eps))
            }
        },
    }
}

/// The arcs' boxes, and the box of them all (most pieces are far from every arc).
struct ArcIndex {
    index: BoxIndex<Key>,
    extent: Bbox,
}

impl ArcIndex {
    /// An index of `arcs` (their boxes padded by `eps`, and keys); `None` when there are none.
    fn new(items: Vec<(Bbox, Key)>) -> Option<ArcIndex> {
        if items.is_empty() {
            return None;
        }
        let extent = items.iter().fold(EMPTY, |e, (b, _)| union(e, *b));
        Some(ArcIndex {
            index: BoxIndex::new(items),
            extent,
        })
    }

    /// Could box `b` meet an arc?
    fn may_meet(&self, b: &Bbox) -> bool {
        let e = &self.extent;
        !(b[0] > e[2] || e[0] > b[2] || b[1] > e[3] || e[1] > b[3])
    }
}

/// Problems: `(ring, span)` for every span whose true arcs meet another piece, or whose slivers
/// hold another ring. `tol` is the stroke tolerance of the checked stroke (the grid step), `eps`
/// the distance under which two pieces count as meeting. `probes[k]` is a point of ring `k`.
pub fn problems(
    rings: &[ArcRing],
    probes: &[Pt],
    tol: f64,
    eps: f64,
    interrupt: &mut dyn FnMut(),
) -> Vec<(usize, usize)> {
    // One pass over every span (a span is 168 bytes: on a large ring each pass is megabytes
    // read, and five passes were most of this check's time after the first round): each ring's
    // pieces as (span, index in the span), each block of pieces' rough box and whether it holds
    // a changed piece, and the arcs with their boxes.
    let mut pieces: Vec<Vec<(u32, u8)>> = Vec::with_capacity(rings.len());
    let mut blocks: Vec<Vec<(Bbox, bool)>> = Vec::with_capacity(rings.len());
    let mut arcs: Vec<(Bbox, Key)> = Vec::new();
    let mut changed_arcs: Vec<(Bbox, Key)> = Vec::new();
    for (k, r) in rings.iter().enumerate() {
        let mut v = Vec::new();
        let mut b = Vec::new();
        let mut block = (EMPTY, false);
        for (s, span) in r.spans.iter().enumerate() {
            let span_dirty = r.dirty.is_none_or(|d| d.get(s).copied().unwrap_or(true));
            for (t, seg) in span.iter().enumerate() {
                // Lines shorter than eps are joints, not pieces: their neighbours meet there.
                if let Seg::Line(a, b) = seg {
                    if near(*a, *b, eps) {
                        continue;
                    }
                }
                let pos = v.len();
                v.push((s as u32, t as u8));
                block = (union(block.0, rough_box(seg)), block.1 || span_dirty);
                if pos % BLOCK == BLOCK - 1 {
                    b.push(std::mem::replace(&mut block, (EMPTY, false)));
                }
                if matches!(seg, Seg::Arc { .. }) {
                    let item = (piece_box(seg, eps), (k, pos));
                    if span_dirty {
                        changed_arcs.push(item);
                    }
                    arcs.push(item);
                }
            }
        }
        if v.len() % BLOCK != 0 {
            b.push(block);
        }
        pieces.push(v);
        blocks.push(b);
    }
    let at = |ring: usize, pos: usize| {
        let (s, t) = pieces[ring][pos];
        Piece {
            ring,
            span: s as usize,
            pos,
            seg: &rings[ring].spans[s as usize][t as usize],
        }
    };
    let dirty = |p: &Piece| {
        rings[p.ring]
            .dirty
            .is_none_or(|d| d.get(p.span).copied().unwrap_or(true))
    };
    let is_arc = |p: &Piece| matches!(p.seg, Seg::Arc { .. });
    // A piece that did not change meets only the arcs that did (none after most rounds).
    let all_changed = changed_arcs.len() == arcs.len();
    // Only pairs with an arc are this check's (two lines are the stroke check's), so the index
    // holds the arcs alone: a value of points and a few circles has few of them, and each line
    // asks a nearly empty grid instead of one of every piece.
    let Some(tree) = ArcIndex::new(arcs) else {
        return vec![];
    };
    interrupt();
    let changed = if all_changed {
        None
    } else {
        ArcIndex::new(changed_arcs)
    };
    // Each pair of pieces meeting, one of them an arc and one of them changed, is tested once,
    // from the changed one (the first of the two when both changed), and the findings are listed
    // in the order of the piece each was tested from.
    // (the key of the piece tested from, then each piece's ring and span)
    let mut found: Vec<(Key, [(usize, usize); 2])> = Vec::new();
    // After a first round few pieces change: the unchanged ones are asked of the changed arcs a
    // block at a time first, and a block whose box (each piece bounded cheaply, an arc by its
    // whole circle) meets none of them is passed over, and so is a block of unchanged pieces
    // then, without reading them.
    let block_may_meet = |k: usize, block: usize| -> bool {
        let Some(c) = &changed else {
            return false;
        };
        let b = padded(blocks[k][block].0, eps);
        let mut any = false;
        if c.may_meet(&b) {
            c.index.for_each_meeting(&b, |_| any = true);
        }
        any
    };
    let mut count = 0usize;
    let all = (0..pieces.len()).flat_map(|k| (0..blocks[k].len()).map(move |block| (k, block)));
    for (k, block) in all {
        if block.is_multiple_of(1024) {
            interrupt();
        }
        let clean_may_meet = all_changed || block_may_meet(k, block);
        if !(clean_may_meet || blocks[k][block].1) {
            continue;
        }
        for pos in block * BLOCK..((block + 1) * BLOCK).min(pieces[k].len()) {
            count += 1;
            if count.is_multiple_of(4096) {
                interrupt();
            }
            let p = at(k, pos);
            let p_dirty = dirty(&p);
            if !(p_dirty || clean_may_meet) {
                continue;
            }
            let index = match (&changed, p_dirty || all_changed) {
                (_, true) => &tree,
                (Some(c), false) => c,
                (None, false) => continue,
            };
            let b = piece_box(p.seg, eps);
            if !index.may_meet(&b) {
                continue;
            }
            let p_arc = is_arc(&p);
            index.index.for_each_meeting(&b, |(k2, pos2)| {
                let q = at(k2, pos2);
                let (pk, qk) = ((p.ring, p.pos), (k2, pos2));
                // two arcs: the pair once, from the first
                if (p_arc && qk <= pk) || !(p_dirty || dirty(&q)) {
                    return;
                }
                let (x, y) = if p_dirty && (!dirty(&q) || pk < qk) {
                    (p, q)
                } else {
                    (q, p)
                };
                let (mut joints, mut nj) = ([[0.0; 2]; 2], 0);
                if x.ring == y.ring {
                    let n = pieces[x.ring].len();
                    if (x.pos + 1) % n == y.pos {
                        joints[nj] = x.seg.end();
                        nj += 1;
                    }
                    if (y.pos + 1) % n == x.pos {
                        joints[nj] = x.seg.start();
                        nj += 1;
                    }
                }
                if meet(x.seg, y.seg, &joints[..nj], eps) {
                    found.push(((x.ring, x.pos), [(x.ring, x.span), (y.ring, y.span)]));
                }
            });
        }
    }
    found.sort_by_key(|f| f.0);
    let mut bad: Vec<(usize, usize)> = found.into_iter().flat_map(|(_, pair)| pair).collect();
    // A ring inside the sliver between an arc of another ring and that arc's chords.
    for (k, probe) in probes.iter().enumerate() {
        let b = [probe[0], probe[1], probe[0], probe[1]];
        tree.index.for_each_meeting(&b, |(k2, pos2)| {
            if k2 == k {
                return;
            }
            let q = at(k2, pos2);
            if let Seg::Arc {
                c, r, a0, sweep, ..
            } = *q.seg
            {
                if in_sliver(*probe, c, r, a0, sweep, tol, eps) {
                    bad.push((k, usize::MAX));
                    bad.push((k2, q.span));
                }
            }
        });
    }
    bad
}

/// Is `p` between the arc and its chords when stroked at `tol` (to `eps`)?
fn in_sliver(p: Pt, c: Pt, r: f64, a0: f64, sweep: f64, tol: f64, eps: f64) -> bool {
    let d = (p[0] - c[0]).hypot(p[1] - c[1]);
    if d > r + eps || !on_arc(p, c, r, a0, sweep, eps) {
        return false;
    }
    let k = arc_segments(r, sweep, tol);
    let at = |j: usize| {
        let t = a0 + sweep * (j as f64) / (k as f64);
        [c[0] + r * t.cos(), c[1] + r * t.sin()]
    };
    // the chord whose angular range holds p: p is in its sliver when farther from the centre
    // than the chord's line
    let rel = if sweep >= 0.0 {
        (p[1] - c[1]).atan2(p[0] - c[0]) - a0
    } else {
        a0 - (p[1] - c[1]).atan2(p[0] - c[0])
    }
    .rem_euclid(TAU);
    let j = ((rel / sweep.abs() * k as f64).floor() as usize).min(k - 1);
    (j.saturating_sub(1)..=(j + 1).min(k - 1)).any(|j| {
        let (a, b) = (at(j), at(j + 1));
        let apothem = dist2_to_segment(c, a, b).sqrt();
        d + eps >= apothem
            && on_arc_angle(
                (p[1] - c[1]).atan2(p[0] - c[0]),
                a0 + sweep * (j as f64) / (k as f64),
                sweep / k as f64,
                eps / r,
            )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decode::reconstruct::ring_spans;

    fn check(rings: &[Vec<[f64; 3]>]) -> Vec<(usize, usize)> {
        let spans: Vec<Spans> = rings.iter().map(|c| ring_spans(c)).collect();
        let refs: Vec<ArcRing> = spans
            .iter()
            .map(|s| ArcRing {
                spans: s,
                dirty: None,
            })
            .collect();
        let probes: Vec<Pt> = spans.iter().map(|s| s[0][0].start()).collect();
        problems(&refs, &probes, 1.0, 1e-9, &mut || {})
    }

    #[test]
    fn a_disc_and_a_point_ring_apart_are_fine() {
        let disc = vec![[0.0, 0.0, 10.0]];
        let tri = vec![[20.0, 0.0, 0.0], [30.0, 0.0, 0.0], [25.0, 5.0, 0.0]];
        assert!(check(&[disc, tri]).is_empty());
    }

    #[test]
    fn a_segment_cutting_an_arc_between_chords_is_caught() {
        // A disc of radius 100 stroked at 1 has chords ~28 long; a triangle whose tip pokes 0.3
        // into the disc between two stroke points meets the arc, not the chords.
        let disc = vec![[0.0, 0.0, 100.0]];
        let tri = vec![[99.7, 0.05, 0.0], [110.0, -5.0, 0.0], [110.0, 5.0, 0.0]];
        assert!(!check(&[disc.clone(), tri]).is_empty());
        let clear = vec![[100.3, 0.05, 0.0], [110.0, -5.0, 0.0], [110.0, 5.0, 0.0]];
        assert!(check(&[disc, clear]).is_empty());
    }

    #[test]
    fn a_ring_inside_a_sliver_is_caught() {
        let disc = vec![[0.0, 0.0, 100.0]];
        // a tiny triangle just inside the arc near angle 0.01 rad, outside every chord
        let p = [100.0 * 0.01f64.cos(), 100.0 * 0.01f64.sin()];
        let tiny = vec![
            [p[0] - 0.01, p[1], 0.0],
            [p[0] - 0.01, p[1] + 0.001, 0.0],
            [p[0] - 0.012, p[1], 0.0],
        ];
        assert!(!check(&[disc, tiny]).is_empty());
    }

    #[test]
    fn two_crossing_circles_are_caught() {
        let a = vec![[0.0, 0.0, 10.0]];
        let b = vec![[15.0, 0.0, 10.0]];
        assert!(!check(&[a, b]).is_empty());
        let far = vec![[25.0, 0.0, 4.0]];
        assert!(check(&[vec![[0.0, 0.0, 10.0]], far]).is_empty());
    }

    #[test]
    fn a_stadium_is_not_in_conflict_with_itself() {
        let st = vec![[0.0, 0.0, 5.0], [30.0, 0.0, 5.0]];
        assert!(check(&[st]).is_empty());
        let bay = vec![
            [0.0, 0.0, 0.0],
            [20.0, 0.0, 0.0],
            [20.0, 20.0, 0.0],
            [10.0, 10.0, 2.0],
            [0.0, 20.0, 0.0],
        ];
        assert!(check(&[bay]).is_empty());
    }
}
