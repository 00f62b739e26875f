//! The closed loop every encoder's result must pass (the paper had none): quantize the circles to
//! the grid and rebuild every ring as `ct_decode` will, measure the continuous Hausdorff distance
//! span by span, check OGC validity on the stroke and on the true arcs, and where a span fails add
//! an original vertex inside it as a zero-radius circle, until nothing fails or nothing is left to
//! add (then the caller refines the grid).

use super::initial::{initial_entries, Entry};
use super::{Options, Report};
use crate::check::arcs;
use crate::check::metrics::{segment_max, Capsules};
use crate::check::validity::{point_in_ring, problems_where, RingRef, Touches};
use crate::decode::reconstruct::{
    for_each_span, for_each_span_in, stroke_span, stroke_spans, Span,
};
use crate::error::Result;
use crate::format::grid::Grid;
use crate::format::Circle;
use crate::geom::{dist2_to_segment, signed_area, Pt, Shape};
use crate::parallel;
use rstar::primitives::Line;
use rstar::RTree;
use std::sync::atomic::{AtomicUsize, Ordering};

pub(super) struct RingState {
    pts: Vec<Pt>,
    pub(super) part: usize,
    index: usize,
    entries: Vec<Entry>,
    pub(super) circles: Vec<Circle>,
    recon: Vec<Pt>,
    span_of: Vec<u32>,
    /// `starts[s]..starts[s + 1]`: the segments of `recon` that span `s` starts.
    starts: Vec<usize>,
    /// The rebuilt pieces (true arcs), for [`arcs::problems`]; none when no ring of the value
    /// has a circle with a radius (every piece is then a segment of `recon`).
    spans: crate::decode::reconstruct::Spans,
    /// Spans whose stroke may differ from the last check.
    dirty: Vec<bool>,
    /// The stroke of a long ring's second half while it is rebuilt on a thread of its own.
    recon_b: Vec<Pt>,
    span_of_b: Vec<u32>,
}

/// Spans within this many of a touched circle are checked again. A span depends on the circles
/// from one before it to two after it (the corner case reads the tangent after next), and the
/// Hausdorff window reaches [`WINDOW`] spans further either way.
const DIRTY_REACH: usize = WINDOW + 2;

/// A span is measured against the spans this many before and after it, too. Two, not one: circles
/// whose vertices round to the same grid point leave a span with no stroke of its own, and its
/// neighbour's stroke then reaches across it.
const WINDOW: usize = 2;

/// Above this many target segments a window is searched through an R-tree, not by brute force.
const BRUTE_FORCE_LIMIT: usize = 96;

impl RingState {
    fn m(&self) -> usize {
        self.entries.len()
    }

    /// Spans whose original edges and strokes a span is measured against: itself and [`WINDOW`]
    /// neighbours either side (every span when there are no more). Measuring against a subset can
    /// only overestimate the distance, so a span that passes is within the bound globally too.
    fn window(&self, s: usize) -> impl Iterator<Item = usize> {
        let m = self.m();
        let (first, count) = self.window_range(s);
        (0..count).map(move |d| (first + d) % m)
    }

    /// Original vertex indices whose edge (to the next vertex) span `s` stands for.
    fn orig_edges(&self, s: usize) -> std::ops::Range<usize> {
        let (n, m) = (self.pts.len(), self.m());
        if m == 1 {
            return 0..n;
        }
        let a = self.entries[s].anchor;
        let b = if s + 1 < m {
            self.entries[s + 1].anchor
        } else {
            self.entries[0].anchor + n
        };
        a..b
    }

    fn orig_seg(&self, v: usize) -> (Pt, Pt) {
        let n = self.pts.len();
        (self.pts[v % n], self.pts[(v + 1) % n])
    }

    fn recon_seg(&self, i: usize) -> (Pt, Pt) {
        let n = self.recon.len();
        (self.recon[i], self.recon[(i + 1) % n])
    }

    /// The first span of span `s`'s window and how many spans it has (consecutive, wrapping).
    fn window_range(&self, s: usize) -> (usize, usize) {
        let m = self.m();
        if m <= 2 * WINDOW + 1 {
            (0, m)
        } else {
            ((s + m - WINDOW) % m, 2 * WINDOW + 1)
        }
    }

    /// The original edges of span `s`'s window, into `out`: consecutive spans stand for
    /// consecutive edges, so the window's are one run of the ring from its first span's anchor.
    fn window_orig(&self, s: usize, out: &mut Vec<(Pt, Pt)>) {
        out.clear();
        let (first, count) = self.window_range(s);
        if self.m() == 1 {
            out.extend(self.orig_edges(0).map(|v| self.orig_seg(v)));
            return;
        }
        let edges: usize = (first..first + count)
            .map(|t| self.orig_edges(t % self.m()).len())
            .sum();
        push_run(&self.pts, self.entries[first].anchor, edges, out);
    }

    /// The stroke of span `s`'s window, into `out`: one run of the stroke from where its first
    /// span starts (span 0 starts at the stroke's first point).
    fn window_recon(&self, s: usize, out: &mut Vec<(Pt, Pt)>) {
        out.clear();
        let (first, count) = self.window_range(s);
        let m = self.m();
        let segments: usize = (first..first + count)
            .map(|t| {
                let t = t % m;
                self.starts[t + 1] - self.starts[t]
            })
            .sum();
        push_run(&self.recon, self.starts[first], segments, out);
    }

    /// Are span `s` and every span of its window straight (between two zero-radius circles)?
    fn straight_window(&self, s: usize) -> bool {
        let m = self.m();
        m > 1
            && self
                .window(s)
                .all(|t| self.entries[t].r == 0.0 && self.entries[(t + 1) % m].r == 0.0)
    }

    /// Is span `s` the original edge between two kept vertices (nothing left to refine)?
    fn exact(&self, s: usize) -> bool {
        let m = self.m();
        self.entries[s].r == 0.0
            && self.entries[(s + 1) % m].r == 0.0
            && self.orig_edges(s).len() <= 1
    }

    /// The span to refine when `p` lies on the wrong side of this ring's rebuild (inside it and
    /// outside the original, or the other way round): the one, not yet exact, whose stroke is
    /// nearest to `p`. `None` when rebuild and original agree about `p`, or nothing is left.
    fn wrong_side(&self, p: Pt) -> Option<usize> {
        if self.recon.len() < 3 || point_in_ring(p, &self.recon) == point_in_ring(p, &self.pts) {
            return None;
        }
        (0..self.recon.len())
            .filter_map(|i| {
                let s = self.span_of[i] as usize;
                let (a, b) = self.recon_seg(i);
                (!self.exact(s)).then(|| (dist2_to_segment(p, a, b), s))
            })
            .min_by(|x, y| x.0.total_cmp(&y.0))
            .map(|(_, s)| s)
    }

    /// A sufficient test for a straight span (both circles zero-radius, one stroked segment
    /// `A-B`) against that segment and its own original chain alone, with no search: the chain's
    /// vertices `v_a ..= v_b` within `target` of `A-B` put the whole chain there (distance to a
    /// segment is convex along each edge); and with `|v_a − A|` and `|v_b − B|` within `target`
    /// and the chain running from `v_a` to `v_b` forward along `A-B`, every point of `A-B` is
    /// within `target` of the chain (between the projections of `v_a` and `v_b` the chain passes
    /// over each point at no more than its largest distance from the line, and beyond them the
    /// nearer end is within its distance to `A` or `B`). Measuring against a subset can only
    /// overestimate, so a pass here is a pass of the window test; `false` means "not proved
    /// here", and the window test decides.
    fn straight_span_fits(&self, s: usize, target: f64) -> bool {
        let (n, m) = (self.pts.len(), self.m());
        if m < 2
            || self.entries[s].r != 0.0
            || self.entries[(s + 1) % m].r != 0.0
            || self.starts[s + 1] != self.starts[s] + 1
        {
            return false;
        }
        let (a, b) = self.recon_seg(self.starts[s]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let edges = self.orig_edges(s);
        let (first, last) = (self.pts[edges.start % n], self.pts[edges.end % n]);
        let t2 = target * target;
        let along = |p: Pt| (p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1];
        if len2 == 0.0 || dist2(first, a) > t2 || dist2(last, b) > t2 || along(first) > along(last)
        {
            return false;
        }
        (edges.start..=edges.end).all(|v| dist2_to_segment(self.pts[v % n], a, b) <= t2)
    }

    /// Does every point of span `s`, and of the original edges it stands for, lie within
    /// `target` of the other boundary (measured on the windows)?
    fn span_fits(&self, s: usize, target: f64, eps: f64, scratch: &mut Scratch) -> bool {
        if self.straight_span_fits(s, target) {
            return true;
        }
        self.window_recon(s, &mut scratch.segs);
        let own_orig = self.orig_edges(s).map(|v| self.orig_seg(v));
        if !all_within(&scratch.segs, own_orig, target, eps, &mut scratch.caps) {
            return false;
        }
        self.window_orig(s, &mut scratch.segs);
        let own_recon = (self.starts[s]..self.starts[s + 1]).map(|i| self.recon_seg(i));
        all_within(&scratch.segs, own_recon, target, eps, &mut scratch.caps)
    }
}

/// What [`RingState::span_fits`] measures with, kept from span to span (an allocation or two
/// for each of a million spans was a third of the distance checks).
#[derive(Default)]
struct Scratch {
    segs: Vec<(Pt, Pt)>,
    caps: Capsules,
}

/// The `count` segments of the closed ring `pts` from vertex `from` on (wrapping), into `out`.
fn push_run(pts: &[Pt], from: usize, count: usize, out: &mut Vec<(Pt, Pt)>) {
    let n = pts.len();
    if count == 0 {
        return;
    }
    // (`from` is the ring's length where the spans before the wrap have no segment)
    let mut v = if from >= n { 0 } else { from };
    out.reserve(count);
    for _ in 0..count {
        let w = if v + 1 >= n { 0 } else { v + 1 };
        out.push((pts[v], pts[w]));
        v = w;
    }
}

/// Squared distance between two points.
fn dist2(p: Pt, q: Pt) -> f64 {
    (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)
}

/// Is every segment of `from` within `target` (to `eps`) of the segments `to`?
fn all_within(
    to: &[(Pt, Pt)],
    mut from: impl Iterator<Item = (Pt, Pt)>,
    target: f64,
    eps: f64,
    caps: &mut Capsules,
) -> bool {
    if to.len() <= BRUTE_FORCE_LIMIT {
        caps.refill(to, target + eps);
        from.all(|(a, b)| caps.covers(a, b))
    } else {
        let tree: RTree<Line<[f64; 2]>> =
            RTree::bulk_load(to.iter().map(|&(c, d)| Line::new(c, d)).collect());
        from.all(|(a, b)| segment_max(&tree, a, b, target, eps) <= target + eps)
    }
}

/// Spans to check again: those within [`DIRTY_REACH`] of a touched circle.
fn dirty_spans(entries: &[Entry]) -> Vec<bool> {
    let m = entries.len();
    let mut dirty = vec![false; m];
    if m <= 2 * DIRTY_REACH + 1 {
        if entries.iter().any(|e| e.touched) {
            dirty.fill(true);
        }
        return dirty;
    }
    for (i, e) in entries.iter().enumerate() {
        if e.touched {
            for d in 0..=2 * DIRTY_REACH {
                dirty[(i + m + d - DIRTY_REACH) % m] = true;
            }
        }
    }
    dirty
}

/// A ring's spans and their stroke with repeated points dropped, as the decoder does, from its
/// circles `fc` in their own coordinates. A long ring is rebuilt in two halves side
/// by side (spans depend on their circles alone, so the same spans; repeats are dropped in each
/// half and where they meet, so the same stroke).
fn rebuild(st: &mut RingState, fc: &[[f64; 3]], tol: f64, interrupt: &mut dyn FnMut()) {
    let m = fc.len();
    if m < 2 {
        // one circle: a whole circle, no tangent
        st.spans.clear();
        for_each_span(fc, |s| st.spans.push(s));
        stroke_dedup(&st.spans, tol, &mut st.recon, &mut st.span_of);
        return;
    }
    let half = m / 2;
    st.spans.resize(m, Span::default());
    let (first, second) = st.spans.split_at_mut(half);
    let (pts, ids) = (&mut st.recon, &mut st.span_of);
    let (pts_b, ids_b) = (&mut st.recon_b, &mut st.span_of_b);
    parallel::join(
        m as u64 >= REBUILD_APART,
        interrupt,
        |_| rebuild_part(fc, 0, first, tol, pts, ids),
        |_| rebuild_part(fc, half, second, tol, pts_b, ids_b),
    );
    // the second half's first point repeating the first half's last
    let skip = usize::from(!pts.is_empty() && pts_b.first() == pts.last());
    pts.extend_from_slice(&pts_b[skip..]);
    ids.extend_from_slice(&ids_b[skip..]);
    while pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
        ids.pop();
    }
}

/// Spans `from..from + out.len()` of the ring of circles `fc` into `out`, stroked into `pts`
/// with their span numbers in `ids`, consecutive repeats dropped.
fn rebuild_part(
    fc: &[[f64; 3]],
    from: usize,
    out: &mut [Span],
    tol: f64,
    pts: &mut Vec<Pt>,
    ids: &mut Vec<u32>,
) {
    let mut k = 0;
    for_each_span_in(fc, from..from + out.len(), |s| {
        out[k] = s;
        k += 1;
    });
    pts.clear();
    ids.clear();
    for (k, span) in out.iter().enumerate() {
        let start = pts.len();
        stroke_span(span, tol, pts);
        ids.resize(ids.len() + pts.len() - start, (from + k) as u32);
    }
    dedup_runs(pts, ids);
}

/// A ring is rebuilt in two halves side by side from this many circles.
const REBUILD_APART: u64 = 20_000;

/// Stroke spans and drop repeated points, as the decoder does, keeping each point's span: into
/// `pts` and `ids`, whose allocations are reused (a round rebuilds every changed ring, and a
/// fresh vector of a large ring is page faults).
fn stroke_dedup(
    spans: &crate::decode::reconstruct::Spans,
    tol: f64,
    pts: &mut Vec<Pt>,
    ids: &mut Vec<u32>,
) {
    pts.clear();
    ids.clear();
    stroke_spans(spans, tol, pts, Some(ids));
    dedup(pts, ids);
}

/// A ring of points stroked: between two zero-radius circles the rebuild is the segment joining
/// their centres, so the stroke is the centres, span `i` starting at centre `i` (what
/// [`stroke_dedup`] makes of their spans, without building them).
fn points_dedup(circles: &[[f64; 3]], pts: &mut Vec<Pt>, ids: &mut Vec<u32>) {
    pts.clear();
    ids.clear();
    pts.extend(circles.iter().map(|c| [c[0], c[1]]));
    ids.extend(0..circles.len() as u32);
    dedup(pts, ids);
}

/// Drop consecutive repeated points (and the closing repeats of the first), with their spans.
fn dedup(pts: &mut Vec<Pt>, ids: &mut Vec<u32>) {
    dedup_runs(pts, ids);
    while pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
        ids.pop();
    }
}

/// Consecutive repeated points dropped (each point's span with it).
fn dedup_runs(pts: &mut Vec<Pt>, ids: &mut Vec<u32>) {
    let mut kept = 0;
    for i in 0..pts.len() {
        if kept == 0 || pts[kept - 1] != pts[i] {
            pts[kept] = pts[i];
            ids[kept] = ids[i];
            kept += 1;
        }
    }
    pts.truncate(kept);
    ids.truncate(kept);
}

pub(super) enum Outcome {
    Done(Vec<RingState>, usize),
    /// Nothing left to repair; a point near the problem.
    FinerGrid(Option<Pt>),
}

/// What every round of the loop reads.
pub(super) struct Context<'a> {
    pub(super) shape: &'a Shape,
    /// Per part and ring: vertices where another ring touches (kept as zero-radius circles).
    pub(super) pinned: &'a [Vec<Vec<usize>>],
    /// Those touch points on the grid: the only points where two rebuilt rings may meet.
    pub(super) allowed: &'a Touches,
    /// Start from the paper's circles (else from Douglas-Peucker points alone).
    pub(super) circles: bool,
}

/// Every ring as its plan starts it on one grid, before any check.
pub(super) fn initial_rings(
    ctx: &Context,
    opts: &Options,
    max_error: f64,
    grid: Grid,
    interrupt: &mut dyn FnMut(),
    report: &mut Report,
) -> Vec<RingState> {
    let shape = ctx.shape;
    let all: Vec<(usize, usize, &Vec<Pt>)> = shape
        .parts
        .iter()
        .enumerate()
        .flat_map(|(pi, part)| {
            part.iter()
                .enumerate()
                .map(move |(ri, ring)| (pi, ri, ring))
        })
        .collect();
    // Rings start independently: on a large input with several rings, the rings up to half the
    // vertices here and the rest on a second thread (the same rings, in the same order).
    let total: usize = all.iter().map(|r| r.2.len()).sum();
    let mut seen = 0;
    let split = all
        .iter()
        .position(|r| {
            seen += r.2.len();
            2 * seen >= total
        })
        .map_or(all.len(), |i| i + 1);
    let (here, there) = all.split_at(split);
    let start = |rings: &[(usize, usize, &Vec<Pt>)], interrupt: &mut dyn FnMut()| {
        let mut report = Report::default();
        let states: Vec<RingState> = rings
            .iter()
            .map(|&(pi, ri, ring)| {
                let entries = initial_entries(
                    ring,
                    &ctx.pinned[pi][ri],
                    ctx.circles,
                    grid,
                    opts,
                    max_error,
                    interrupt,
                    &mut report,
                );
                RingState {
                    pts: ring.clone(),
                    part: pi,
                    index: ri,
                    entries,
                    circles: vec![],
                    recon: vec![],
                    span_of: vec![],
                    recon_b: vec![],
                    span_of_b: vec![],
                    starts: vec![],
                    spans: vec![],
                    dirty: vec![],
                }
            })
            .collect();
        (states, report)
    };
    let ((mut rings, a), (rest, b)) = parallel::join(
        total as u64 >= crate::parallel::MIN_VERTICES && !there.is_empty(),
        interrupt,
        |i| start(here, i),
        |i| start(there, i),
    );
    rings.extend(rest);
    report.filtered_circles = a.filtered_circles + b.filtered_circles;
    report.dp_points = a.dp_points + b.dp_points;
    rings
}

/// The circles of each ring as stored on `grid` (each part's rings in order), before any check:
/// what a plan would cost if nothing needed repair.
pub(super) fn unchecked_parts(
    rings: &[RingState],
    nparts: usize,
    grid: Grid,
) -> Vec<Vec<Vec<Circle>>> {
    let mut parts: Vec<Vec<Vec<Circle>>> = vec![Vec::new(); nparts];
    for st in rings {
        parts[st.part].push(quantized(&st.entries, grid));
    }
    parts
}

fn quantized(entries: &[Entry], grid: Grid) -> Vec<Circle> {
    entries
        .iter()
        .map(|e| Circle {
            x: grid.quantize(e.c[0]),
            y: grid.quantize(e.c[1]),
            r: grid.quantize(e.r),
        })
        .collect()
}

/// Repair `rings` (as [`initial_rings`] gave them on `grid`) until nothing fails.
pub(super) fn verify_and_repair(
    ctx: &Context,
    mut rings: Vec<RingState>,
    max_error: f64,
    grid: Grid,
    interrupt: &mut dyn FnMut(),
    report: &mut Report,
) -> Result<Outcome> {
    let g = grid.step_f64();
    let target = max_error - g;
    let unq = |k: i64| grid.coord(k);
    let mut round = 0;
    loop {
        round += 1;
        report.rounds = round;
        interrupt();
        // Repair never gives a circle a radius, so once none has one, none will.
        let arcs = rings.iter().any(|st| st.entries.iter().any(|e| e.r != 0.0));
        for st in rings.iter_mut() {
            st.dirty = dirty_spans(&st.entries);
            if !st.dirty.iter().any(|&d| d) {
                continue;
            }
            for e in &mut st.entries {
                e.touched = false;
            }
            st.circles = quantized(&st.entries, grid);
            let fc: Vec<[f64; 3]> = st
                .circles
                .iter()
                .map(|c| [unq(c.x), unq(c.y), unq(c.r)])
                .collect();
            if arcs {
                rebuild(st, &fc, g, interrupt);
            } else {
                st.spans = Vec::new();
                points_dedup(&fc, &mut st.recon, &mut st.span_of);
            }
            // `span_of` ascends: where each span's segments start, in one pass
            let mut at = 0;
            st.starts = (0..=st.m())
                .map(|s| {
                    while at < st.span_of.len() && (st.span_of[at] as usize) < s {
                        at += 1;
                    }
                    at
                })
                .collect();
        }
        interrupt();
        // The distance checks and the validity checks read the same rebuilt rings and nothing
        // else: on a large input they run side by side.
        let segments: usize = rings.iter().map(|r| r.recon.len()).sum();
        let rings_ref = &rings;
        // Three checks on two threads: the true arcs' validity on one, the stroke's on the
        // other, and the distances shared between them, a chunk of spans at a time, by whichever
        // is free (each span is measured alone; each ring's failing spans are sorted below).
        let chunks = distance_chunks(rings_ref);
        let next = AtomicUsize::new(0);
        let measure = |i: &mut dyn FnMut()| {
            distance_failures(ctx, rings_ref, &chunks, &next, max_error, g, target, i)
        };
        let ((arc_found, far_a), ((mut problems, mut problem_at), far_b)) = parallel::join(
            segments as u64 >= crate::parallel::MIN_VERTICES,
            interrupt,
            |i| {
                let found = arc_failures(rings_ref, g, i);
                (found, measure(i))
            },
            |i| {
                let found = stroke_failures(ctx, rings_ref, i);
                (found, measure(i))
            },
        );
        let (more, arc_at) = arc_found;
        problems.extend(more);
        problem_at = problem_at.or(arc_at);
        let mut failing: Vec<Vec<usize>> = vec![Vec::new(); rings.len()];
        for (k, s) in far_a.into_iter().chain(far_b).chain(problems) {
            failing[k].push(s);
        }
        if failing.iter().all(Vec::is_empty) {
            let repaired = rings
                .iter()
                .flat_map(|r| r.entries.iter())
                .filter(|e| e.repaired)
                .count();
            return Ok(Outcome::Done(rings, repaired));
        }
        let hurry = round > 24;
        let mut progress = false;
        for (k, mut spans) in failing.into_iter().enumerate() {
            if spans.is_empty() {
                continue;
            }
            spans.sort_unstable();
            spans.dedup();
            let st = &mut rings[k];
            if repair(st, &spans, target, hurry, interrupt) {
                progress = true;
            }
        }
        if !progress {
            // Every failing span is already an original edge between two kept vertices.
            return Ok(Outcome::FinerGrid(problem_at));
        }
    }
}

/// The distance checks' work: (ring, spans) to measure, a ring's spans cut in chunks of
/// [`DISTANCE_CHUNK`] (rings with no dirty span left out).
fn distance_chunks(rings: &[RingState]) -> Vec<(usize, std::ops::Range<usize>)> {
    let mut chunks = Vec::new();
    for (k, st) in rings.iter().enumerate() {
        if !st.dirty.iter().any(|&d| d) {
            continue;
        }
        let m = st.m();
        chunks.extend(
            (0..m)
                .step_by(DISTANCE_CHUNK)
                .map(|s| (k, s..(s + DISTANCE_CHUNK).min(m))),
        );
    }
    chunks
}

/// Spans a thread measures at a time.
const DISTANCE_CHUNK: usize = 1024;

/// Spans (ring, span) whose Hausdorff distance, both ways, is not proved within the bound: of
/// the `chunks` this thread takes (the next one not taken, by `next`, until none is left).
#[allow(clippy::too_many_arguments)]
fn distance_failures(
    ctx: &Context,
    rings: &[RingState],
    chunks: &[(usize, std::ops::Range<usize>)],
    next: &AtomicUsize,
    max_error: f64,
    g: f64,
    target: f64,
    interrupt: &mut dyn FnMut(),
) -> Vec<(usize, usize)> {
    let mut failing = Vec::new();
    // Hausdorff, both ways, span by span. Where the window holds only straight spans, the
    // stroke is the geometry itself and the whole bound is available (arcs keep a grid step of
    // it for the decoder's stroke).
    let eps = g * 1e-3;
    let mut scratch = Scratch::default();
    let straight_target = max_error - 3.0 * eps;
    while let Some((k, spans)) = chunks.get(next.fetch_add(1, Ordering::Relaxed)) {
        interrupt();
        let st = &rings[*k];
        for s in spans.clone() {
            let t = if !ctx.circles && st.straight_window(s) {
                straight_target
            } else {
                target
            };
            if st.dirty[s] && !st.span_fits(s, t, eps, &mut scratch) {
                failing.push((*k, s));
            }
        }
    }
    failing
}

/// Spans (ring, span) that make the stroked rebuild invalid (`usize::MAX` spans are spread to
/// the whole ring), and a point near the first problem.
fn stroke_failures(
    ctx: &Context,
    rings: &[RingState],
    interrupt: &mut dyn FnMut(),
) -> (Vec<(usize, usize)>, Option<Pt>) {
    let mut failing: Vec<(usize, usize)> = Vec::new();
    let mut problem_at: Option<Pt> = None;
    {
        let refs: Vec<RingRef> = rings
            .iter()
            .map(|r| RingRef {
                part: r.part,
                ring: r.index,
                pts: &r.recon,
            })
            .collect();
        let changed: Vec<Vec<bool>> = rings
            .iter()
            .map(|r| {
                r.span_of
                    .iter()
                    .map(|&s| r.dirty.get(s as usize).copied().unwrap_or(true))
                    .collect()
            })
            .collect();
        // Where every segment is new (a first round), a proof that the rebuild is valid
        // without a touch anywhere ([`crate::check::proof`]) is several times quicker than looking for
        // problems, and when it holds there are none to find (it is stricter in every respect:
        // no two rings touch at all, and every side is decided beyond doubt).
        let proved = changed.iter().all(|c| c.iter().all(|&x| x))
            && refs.iter().all(|r| signed_area(r.pts) != 0.0)
            && crate::check::proof::proves_rings(
                &refs.iter().map(|r| r.pts).collect::<Vec<_>>(),
                &refs
                    .iter()
                    .map(|r| (r.part, r.ring == 0))
                    .collect::<Vec<_>>(),
                interrupt,
            );
        let found = if proved {
            Vec::new()
        } else {
            problems_where(&refs, Some(&changed), ctx.allowed, interrupt)
        };
        let mut misplaced = Vec::new();
        for (k, seg) in found {
            if seg == usize::MAX {
                failing.extend((0..rings[k].entries.len()).map(|s| (k, s)));
                problem_at = problem_at.or(rings[k].recon.first().copied());
                misplaced.push(k);
            } else if let Some(&s) = rings[k].span_of.get(seg) {
                failing.push((k, s as usize));
                problem_at = problem_at.or(rings[k].recon.get(seg).copied());
            }
        }
        // A ring on the wrong side of another (a hole outside its shell, an island inside a
        // neighbour) may be right where it is: the neighbour's rebuild can be what is wrong,
        // even when this ring already keeps every vertex. Every ring whose rebuild and
        // original disagree about the misplaced ring's probe is refined next to it too.
        for k in misplaced {
            let r = &rings[k].recon;
            if r.len() < 2 {
                continue;
            }
            let p = [(r[0][0] + r[1][0]) / 2.0, (r[0][1] + r[1][1]) / 2.0];
            for (h, other) in rings.iter().enumerate() {
                if h != k {
                    if let Some(s) = other.wrong_side(p) {
                        failing.push((h, s));
                    }
                }
            }
        }
    }
    (failing, problem_at)
}

/// Spans (ring, span) whose true arcs meet another piece or hold another ring in a sliver
/// (`usize::MAX` spans are spread to the whole ring), and a point near the first.
fn arc_failures(
    rings: &[RingState],
    g: f64,
    interrupt: &mut dyn FnMut(),
) -> (Vec<(usize, usize)>, Option<Pt>) {
    let refs: Vec<arcs::ArcRing> = rings
        .iter()
        .map(|r| arcs::ArcRing {
            spans: &r.spans,
            dirty: Some(&r.dirty),
        })
        .collect();
    let probes: Vec<Pt> = rings
        .iter()
        .map(|r| r.recon.first().copied().unwrap_or([0.0, 0.0]))
        .collect();
    let mut failing: Vec<(usize, usize)> = Vec::new();
    let mut problem_at: Option<Pt> = None;
    for (k, s) in arcs::problems(&refs, &probes, g, g * 1e-6, interrupt) {
        if s == usize::MAX {
            failing.extend((0..rings[k].entries.len()).map(|s| (k, s)));
        } else {
            failing.push((k, s));
        }
        problem_at = problem_at.or(rings[k].recon.first().copied());
    }
    (failing, problem_at)
}

/// Repair failing spans of one ring. `false` when no span had anything left to add or remove.
fn repair(
    st: &mut RingState,
    spans: &[usize],
    target: f64,
    hurry: bool,
    interrupt: &mut dyn FnMut(),
) -> bool {
    let m = st.entries.len();
    // What each failing span asks for reads the ring alone: on many spans, the two halves of
    // the list are looked at side by side (the first round at a million vertices: 48,000
    // spans, 30 ms), and their points are added in the order of the spans as before.
    let half = spans.len() / 2;
    let view = &*st;
    let ((mut add, mut drop), (add_b, drop_b)) = parallel::join(
        spans.len() >= REPAIR_APART,
        interrupt,
        |_| asked(view, &spans[..half], target, hurry),
        |_| asked(view, &spans[half..], target, hurry),
    );
    add.extend(add_b);
    drop.extend(drop_b);
    let mut remove = vec![false; m];
    for i in drop {
        remove[i] = true;
    }
    // Failing spans are checked again next round even where nothing could be done (then the
    // round makes no progress and the grid is refined); neighbours of a removed circle change.
    for &i in spans {
        if i < m {
            st.entries[i].touched = true;
            st.entries[(i + 1) % m].touched = true;
        }
    }
    for (i, _) in remove.iter().enumerate().filter(|(_, &r)| r) {
        st.entries[(i + m - 1) % m].touched = true;
        st.entries[(i + 1) % m].touched = true;
    }
    let removed = remove.iter().filter(|&&r| r).count();
    // The kept entries are in order already: the new ones are sorted and merged in, after any
    // kept entry of the same key (what sorting them all, stably, gave).
    let kept = st
        .entries
        .iter()
        .zip(&remove)
        .filter(|(_, &r)| !r)
        .map(|(e, _)| *e);
    st.entries = merge_entries(kept, add, m - removed);
    // (an added point where one is already is dropped: no change)
    removed > 0 || st.entries.len() != m
}

/// Failing spans at least this many are looked at on two threads.
const REPAIR_APART: usize = 1024;

/// What the failing spans `spans` of a ring ask for: the points to add (in the order of the
/// spans) and the circles to remove.
fn asked(st: &RingState, spans: &[usize], target: f64, hurry: bool) -> (Vec<Entry>, Vec<usize>) {
    let n = st.pts.len();
    let m = st.entries.len();
    let mut add: Vec<Entry> = Vec::new();
    let mut remove: Vec<usize> = Vec::new();
    let point = |v: usize| Entry::point(&st.pts, v, true);
    let mut recon = Vec::new();
    for &i in spans {
        if i >= m {
            continue;
        }
        let a = st.entries[i].anchor;
        let b = if i + 1 < m {
            st.entries[i + 1].anchor
        } else {
            st.entries[0].anchor + n
        };
        let interior = (a + 1..b).map(|v| v % n);
        if interior.len() == 0 {
            let j = (i + 1) % m;
            if st.entries[i].r != 0.0 {
                remove.push(i);
                add.push(point(a));
            } else if st.entries[j].r != 0.0 {
                remove.push(j);
                add.push(point(st.entries[j].anchor));
            } else if m < n && a == b % n && m == 1 {
                add.extend([point((a + n / 3) % n), point((a + 2 * n / 3) % n)]);
            }
            continue;
        }
        if hurry {
            add.extend(interior.map(point));
            for j in [i, (i + 1) % m] {
                if st.entries[j].r != 0.0 {
                    remove.push(j);
                    add.push(point(st.entries[j].anchor));
                }
            }
            continue;
        }
        // the interior vertex farthest from the stroke, if it is far; else the middle one
        st.window_recon(i, &mut recon);
        let far = |v: usize| {
            recon
                .iter()
                .map(|&(c, d)| dist2_to_segment(st.pts[v], c, d))
                .fold(f64::INFINITY, f64::min)
        };
        let best = interior
            .clone()
            .map(|v| (far(v), v))
            .max_by(|x, y| x.0.total_cmp(&y.0));
        let v = match best {
            Some((d2, v)) if d2 > (target * 0.5).powi(2) => v,
            _ => interior.clone().nth(interior.len() / 2).unwrap_or(a),
        };
        add.push(point(v));
    }
    (add, remove)
}

/// The entries `kept` (`capacity` of them, in the order of
/// [`sort_entries`](super::initial::sort_entries)) with `add` merged in, as it would order them
/// all (a stable sort: at equal keys the kept ones first, then the added in their order),
/// repeated points dropped.
fn merge_entries(
    kept: impl Iterator<Item = Entry>,
    mut add: Vec<Entry>,
    capacity: usize,
) -> Vec<Entry> {
    let key = |e: &Entry| (e.anchor, e.r != 0.0);
    add.sort_by_key(key);
    let mut out: Vec<Entry> = Vec::with_capacity(capacity + add.len());
    let mut added = add.into_iter().peekable();
    for e in kept {
        while let Some(x) = added.next_if(|x| key(x) < key(&e)) {
            out.push(x);
        }
        out.push(e);
    }
    out.extend(added);
    out.dedup_by(|b, a| a.anchor == b.anchor && a.r == 0.0 && b.r == 0.0);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Merging added entries into the kept ones gives what sorting them all gave: on keys
    /// that repeat (circles and points at one vertex, a point added where one is) and added
    /// entries in no order.
    #[test]
    fn merged_entries_are_the_sorted_entries() {
        let mut uniform = crate::test_uniform(11);
        let entry = |anchor: usize, r: f64, tag: f64| Entry {
            c: [tag, 0.0],
            r,
            anchor,
            repaired: false,
            touched: false,
        };
        for round in 0..200 {
            let mut pick = |k: usize| (uniform() * k as f64) as usize;
            let mut kept: Vec<Entry> = (0..pick(40))
                .map(|t| entry(pick(30), [0.0, 0.0, 1.5][pick(3)], t as f64))
                .collect();
            super::super::initial::sort_entries(&mut kept);
            let add: Vec<Entry> = (0..pick(12))
                .map(|t| entry(pick(30), [0.0, 2.5][pick(2)], 100.0 + t as f64))
                .collect();
            let mut want = kept.clone();
            want.extend(add.iter().copied());
            super::super::initial::sort_entries(&mut want);
            let got = merge_entries(kept.iter().copied(), add, kept.len());
            let tags = |v: &[Entry]| {
                v.iter()
                    .map(|e| (e.anchor, e.r, e.c[0]))
                    .collect::<Vec<_>>()
            };
            assert_eq!(tags(&got), tags(&want), "round {round}");
        }
    }

    #[test]
    fn a_ring_rebuilt_in_halves_is_the_ring_rebuilt_whole() {
        // circles and points, with repeated points where the halves meet (spans 3 and 4 stroke
        // the same point) and where the ring closes (the last circle is the first)
        let mut fc: Vec<[f64; 3]> = vec![
            [0.0, 0.0, 0.0],
            [10.0, 0.0, 2.0],
            [20.0, 0.0, 0.0],
            [25.0, 5.0, 0.0],
            [25.0, 5.0, 0.0],
            [20.0, 10.0, -1.5],
            [10.0, 12.0, 0.0],
            [0.0, 0.0, 0.0],
        ];
        for m in [2, 3, 8, 9] {
            if m == 9 {
                fc.insert(2, [15.0, -3.0, 1.0]);
            }
            let fc = &fc[..m];
            let mut whole = Vec::new();
            for_each_span(fc, |s| whole.push(s));
            let (mut pts, mut ids) = (Vec::new(), Vec::new());
            stroke_dedup(&whole, 0.1, &mut pts, &mut ids);
            let mut st = RingState {
                pts: vec![],
                part: 0,
                index: 0,
                entries: vec![],
                circles: vec![],
                recon: vec![[1.0, 1.0]],
                span_of: vec![7],
                starts: vec![],
                spans: vec![Span::default(); 11],
                dirty: vec![],
                recon_b: vec![],
                span_of_b: vec![],
            };
            rebuild(&mut st, fc, 0.1, &mut || {});
            assert_eq!(st.spans, whole, "{m}");
            assert_eq!((&st.recon, &st.span_of), (&pts, &ids), "{m}");
        }
    }
}
