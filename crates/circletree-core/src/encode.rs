//! The encoder: the paper's method (sections 3.1-3.5) followed by a closed loop that the paper
//! did not have.
//!
//! Per ring: candidate circles ([`crate::medial`]), filtered and mapped to runs of edges
//! ([`crate::filter`]), Douglas-Peucker points as zero-radius circles where no circle covers the
//! boundary ([`crate::douglas_peucker`]), everything ordered along the ring by the first vertex it
//! stands for. Then, for the whole geometry at once:
//!
//! 1. quantize the circles to the grid and rebuild every ring exactly as `ct_decode` will
//!    ([`crate::reconstruct`], arcs stroked to the grid step);
//! 2. measure the continuous Hausdorff distance between each rebuilt ring and its original, both
//!    ways, with R-trees and a Lipschitz bound on each segment (no sampling gaps), against
//!    `max_error − grid` (so the true arcs are within `max_error` too);
//! 3. check validity as OGC defines it ([`crate::validity`] on the stroke, [`crate::arcs`] on the
//!    true arcs, so that every finer stroke and the curved form are valid too); rings may touch
//!    only at the input's own touch points ([`crate::touch`]), which every ring through them keeps
//!    as a zero-radius circle;
//! 4. where a span between two consecutive circles fails, add an original vertex inside it as a
//!    zero-radius circle (counted as *repaired*); a span with no vertex left loses its circle.
//!
//! The loop ends because each round adds a vertex or removes a circle; its end point, every vertex
//! kept, is the quantized original. If even that fails (two rings closer than the grid step), the
//! grid is refined tenfold, up to [`REFINEMENTS`] times (parts smaller than the grid need it). The result is valid and within `max_error`.
//!
//! Parameters the stored format cannot hold are refused before any work (a grid outside
//! 1e-12 ..= 9e12, coordinates beyond 2^50 grid steps), so every value returned reads back.

use crate::decimal::Decimal;
use crate::error::{Error, Result};
use crate::format::{Circle, CircleTree, Params, MAX_STEPS};
use crate::geometry::{dist2_to_segment, orient, Pt, Shape};
use crate::grid::Grid;
use crate::metrics::{segment_max, segment_max_in};
use crate::reconstruct::{ring_spans, stroke_spans};
use crate::validity::{point_in_ring, problems_where, touch_key, RingRef, Touches};
use crate::{arcs, douglas_peucker, filter, medial, touch};
use rstar::primitives::Line;
use rstar::RTree;

/// Encoding parameters, in the units of the geometry's SRID.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Smallest circle radius kept.
    pub min_radius: f64,
    /// Overlap allowed between two circles of the same side, 0..1.
    pub overlap: f64,
    /// Douglas-Peucker tolerance for zero-radius circles; `None`: none.
    pub dp_tolerance: Option<f64>,
    /// Hausdorff bound; `None`: `max(min_radius, dp_tolerance)`.
    pub max_error: Option<f64>,
}

/// What the encoder did, beyond the value itself.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Report {
    /// Z or M values were dropped.
    pub dropped_zm: bool,
    /// Circles kept by the paper's filter, before Douglas-Peucker and repair.
    pub filtered_circles: usize,
    /// Zero-radius circles from Douglas-Peucker.
    pub dp_points: usize,
    /// Rounds of the repair loop.
    pub rounds: usize,
}

/// Smallest and largest length parameter (the stored decimals hold any length in this range).
const LENGTH_RANGE: (f64, f64) = (1e-100, 1e100);
/// Smallest and largest `max_error`: its grid (about half of it, refined up to a hundredfold more
/// when rings are very close) must stay within the format's 1e-12 ..= 9e12.
pub const MAX_ERROR_RANGE: (f64, f64) = (1e-9, 1e13);

fn positive(name: &'static str, v: f64) -> Result<f64> {
    if v.is_finite() && v >= LENGTH_RANGE.0 && v <= LENGTH_RANGE.1 {
        Ok(v)
    } else {
        Err(Error::InvalidParameter {
            name,
            value: v.to_string(),
            range: "a positive, finite length between 1e-100 and 1e100".into(),
        })
    }
}

fn decimal(name: &'static str, v: f64) -> Result<Decimal> {
    Decimal::from_f64(v).ok_or(Error::InvalidParameter {
        name,
        value: v.to_string(),
        range: "a positive, finite length between 1e-100 and 1e100".into(),
    })
}

impl Options {
    /// Check the ranges; returns `max_error` resolved.
    pub fn check(&self) -> Result<f64> {
        positive("min_radius", self.min_radius)?;
        if !(self.overlap.is_finite() && (0.0..=1.0).contains(&self.overlap)) {
            return Err(Error::InvalidParameter {
                name: "overlap",
                value: self.overlap.to_string(),
                range: "between 0 and 1".into(),
            });
        }
        if let Some(d) = self.dp_tolerance {
            positive("dp_tolerance", d)?;
        }
        let m = match self.max_error {
            Some(m) => positive("max_error", m)?,
            None => self.min_radius.max(self.dp_tolerance.unwrap_or(0.0)),
        };
        if !(MAX_ERROR_RANGE.0..=MAX_ERROR_RANGE.1).contains(&m) {
            return Err(Error::InvalidParameter {
                name: "max_error",
                value: m.to_string(),
                range: format!(
                    "between {:e} and {:e} (when NULL it is greatest(min_radius, dp_tolerance))",
                    MAX_ERROR_RANGE.0, MAX_ERROR_RANGE.1
                ),
            });
        }
        Ok(m)
    }
}

/// The largest of 1, 2, 5 × 10^k not above `limit`.
pub fn nice_grid(limit: f64) -> Option<Decimal> {
    let k = limit.log10().floor() as i32;
    for m in [5i64, 2, 1] {
        let d = Decimal::new(m, k)?;
        if d.to_f64() <= limit {
            return Some(d);
        }
    }
    Decimal::new(5, k - 1)
}

#[derive(Clone, Copy, Debug)]
struct Entry {
    c: Pt,
    r: f64,
    anchor: usize,
    repaired: bool,
    /// New, or next to a change, since the last check.
    touched: bool,
}

struct RingState {
    pts: Vec<Pt>,
    part: usize,
    index: usize,
    entries: Vec<Entry>,
    circles: Vec<Circle>,
    recon: Vec<Pt>,
    span_of: Vec<u32>,
    /// `starts[s]..starts[s + 1]`: the segments of `recon` that span `s` starts.
    starts: Vec<usize>,
    /// The rebuilt pieces (true arcs), for [`arcs::problems`].
    spans: crate::reconstruct::Spans,
    /// Spans whose stroke may differ from the last check.
    dirty: Vec<bool>,
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
    fn window(&self, s: usize) -> Vec<usize> {
        let m = self.m();
        if m <= 2 * WINDOW + 1 {
            (0..m).collect()
        } else {
            (0..=2 * WINDOW).map(|d| (s + m + d - WINDOW) % m).collect()
        }
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

    fn window_orig(&self, s: usize) -> Vec<(Pt, Pt)> {
        self.window(s)
            .into_iter()
            .flat_map(|t| self.orig_edges(t))
            .map(|v| self.orig_seg(v))
            .collect()
    }

    fn window_recon(&self, s: usize) -> Vec<(Pt, Pt)> {
        self.window(s)
            .into_iter()
            .flat_map(|t| self.starts[t]..self.starts[t + 1])
            .map(|i| self.recon_seg(i))
            .collect()
    }

    /// Are span `s` and every span of its window straight (between two zero-radius circles)?
    fn straight_window(&self, s: usize) -> bool {
        let m = self.m();
        m > 1
            && self
                .window(s)
                .into_iter()
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

    /// Does every point of span `s`, and of the original edges it stands for, lie within
    /// `target` of the other boundary (measured on the windows)?
    fn span_fits(&self, s: usize, target: f64, eps: f64) -> bool {
        let recon = self.window_recon(s);
        let own_orig = self.orig_edges(s).map(|v| self.orig_seg(v));
        if !all_within(&recon, own_orig, target, eps) {
            return false;
        }
        let orig = self.window_orig(s);
        let own_recon = (self.starts[s]..self.starts[s + 1]).map(|i| self.recon_seg(i));
        all_within(&orig, own_recon, target, eps)
    }
}

/// Is every segment of `from` within `target` (to `eps`) of the segments `to`?
fn all_within(
    to: &[(Pt, Pt)],
    mut from: impl Iterator<Item = (Pt, Pt)>,
    target: f64,
    eps: f64,
) -> bool {
    if to.len() <= BRUTE_FORCE_LIMIT {
        from.all(|(a, b)| segment_max_in(to, a, b, target, eps) <= target + eps)
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

/// Stroke spans and drop repeated points, as the decoder does, keeping each point's span.
fn stroke_dedup(spans: &crate::reconstruct::Spans, tol: f64) -> (Vec<Pt>, Vec<u32>) {
    let (mut pts, mut ids) = (Vec::new(), Vec::new());
    stroke_spans(spans, tol, &mut pts, &mut ids);
    let mut rp: Vec<Pt> = Vec::with_capacity(pts.len());
    let mut ri: Vec<u32> = Vec::with_capacity(pts.len());
    for (p, id) in pts.into_iter().zip(ids) {
        if rp.last() != Some(&p) {
            rp.push(p);
            ri.push(id);
        }
    }
    while rp.len() > 1 && rp.first() == rp.last() {
        rp.pop();
        ri.pop();
    }
    (rp, ri)
}

enum Outcome {
    Done(Vec<RingState>, usize),
    /// Nothing left to repair; a point near the problem.
    FinerGrid(Option<Pt>),
}

/// Encode WKB (Polygon or MultiPolygon) into a circletree value.
pub fn encode(
    wkb: &[u8],
    srid: i32,
    opts: &Options,
    interrupt: &mut dyn FnMut(),
) -> Result<(CircleTree, Report)> {
    encode_checked(wkb, srid, opts, None, interrupt)
}

/// [`encode`], told by the caller (PostGIS's `ST_IsValidReason`) when the input is not valid.
pub fn encode_checked(
    wkb: &[u8],
    srid: i32,
    opts: &Options,
    invalid_reason: Option<&str>,
    interrupt: &mut dyn FnMut(),
) -> Result<(CircleTree, Report)> {
    let max_error = opts.check()?;
    let prep = prepare(wkb, invalid_reason)?;
    let plan = Plan {
        opts: *opts,
        circles: true,
        grid: first_grid(&prep, max_error, 2.0)?,
    };
    run(&prep, srid, &plan, max_error, interrupt)
}

/// The fewest bytes within `max_error`: several plans go through the same closed loop as
/// [`encode`] (so each result is valid and within the bound), and the smallest value is kept.
///
/// Every plan keeps points only: the fewest vertices whose stored (rounded) shortcuts stay within
/// max_error of the ring ([`crate::min_points`]), on grids of [`WITHIN_GRIDS`] times max_error.
/// Where vertices are far apart (GSHHG's ~180 m) almost every one is kept and the coarsest grid
/// wins; where they are dense (LINZ at 100 m) a finer grid skips more. The paper's circles, stored
/// by their centres, never won a polygon of the corpus at the same bound (measured as a fourth
/// plan: 48 bytes of 264,331 at 25 m, before the rounding was measured), so they are not tried.
pub fn encode_within(
    wkb: &[u8],
    srid: i32,
    max_error: f64,
    invalid_reason: Option<&str>,
    interrupt: &mut dyn FnMut(),
) -> Result<(CircleTree, Report)> {
    positive("max_error", max_error)?;
    if !(MAX_ERROR_RANGE.0..=MAX_ERROR_RANGE.1).contains(&max_error) {
        return Err(range_error(max_error));
    }
    let checked = Options {
        min_radius: max_error,
        overlap: 0.0,
        dp_tolerance: None,
        max_error: Some(max_error),
    };
    let max_error = checked.check()?;
    let prep = prepare(wkb, invalid_reason)?;
    // the same parameter ranges as `encode` at this bound (its grid must hold the coordinates)
    first_grid(&prep, max_error, 2.0)?;
    let mut best: Option<(usize, CircleTree, Report)> = None;
    let mut first_error = None;
    for fraction in WITHIN_GRIDS {
        // a plan whose grid cannot hold the coordinates is skipped (a coarser one may)
        let grid = match grid_near(max_error * fraction)
            .ok_or_else(|| range_error(max_error))
            .and_then(|g| check_steps(&prep, max_error, g).map(|()| g))
        {
            Ok(g) => g,
            Err(e) => {
                first_error.get_or_insert(e);
                continue;
            }
        };
        // the rounding is measured by `min_points` (each shortcut from its stored ends), so the
        // tolerance is the bound, less the loop's own measuring margin
        let tol = max_error - 4e-3 * grid.to_f64();
        let plan = Plan {
            opts: Options {
                dp_tolerance: Some(tol),
                ..checked
            },
            circles: false,
            grid,
        };
        match run(&prep, srid, &plan, max_error, interrupt) {
            Ok((ct, report)) => {
                let n = ct.to_bytes().len();
                if best.as_ref().is_none_or(|b| n < b.0) {
                    best = Some((n, ct, report));
                }
            }
            Err(e) => {
                first_error.get_or_insert(e);
            }
        }
    }
    match (best, first_error) {
        (Some((_, ct, report)), _) => Ok((ct, report)),
        (None, Some(e)) => Err(e),
        (None, None) => Err(range_error(max_error)),
    }
}

/// Grids `encode_within` tries, as fractions of max_error. 1.4 is about the coarsest allowed
/// (rounding moves a point by up to 0.71 of a step, and the ring must stay within max_error of the
/// stored points); finer grids leave room to skip more vertices where the rounding would otherwise
/// use the bound. Measured on the corpus (bytes summed; 1.4 alone / these three / adding 1 and 0.4):
/// 10 m 341,205 / 339,824 / 339,625; 25 m 235,173 / 234,417 / 234,293; 100 m 92,465 / 70,944 / 73,362.
const WITHIN_GRIDS: [f64; 3] = [1.4, 0.8, 0.5];

/// The largest grid of two significant digits not above `x` (`None` outside the format's range).
fn grid_near(x: f64) -> Option<Decimal> {
    if !(x.is_finite() && x > 0.0) {
        return None;
    }
    let k = x.log10().floor() as i32 - 1;
    let m = (x / 10f64.powi(k)).floor() as i64;
    Decimal::new(m.clamp(10, 99), k).filter(|g| Grid::storable(*g))
}

fn range_error(max_error: f64) -> Error {
    Error::InvalidParameter {
        name: "max_error",
        value: max_error.to_string(),
        range: format!(
            "between {:e} and {:e}",
            MAX_ERROR_RANGE.0, MAX_ERROR_RANGE.1
        ),
    }
}

/// The input, read once for any number of plans.
struct Prepared {
    shape: Shape,
    vertices: u64,
    wkb_bytes: u64,
    pinned: Vec<Vec<Vec<usize>>>,
    touches: Vec<Pt>,
    bbox: Option<[f64; 4]>,
    magnitude: f64,
    dropped_zm: bool,
}

fn prepare(wkb: &[u8], invalid_reason: Option<&str>) -> Result<Prepared> {
    let input = crate::wkb::read(wkb)?;
    if let Some(reason) = invalid_reason {
        return Err(Error::InvalidPolygon(reason.to_string()));
    }
    let mut shape = input.shape;
    orient(&mut shape);
    let vertices = shape.npoints() as u64;
    let (pinned, touches) = touch::pin(&mut shape);
    let bbox = shape.bbox();
    let magnitude = bbox.map_or(0.0, |b| b.iter().fold(0.0f64, |m, v| m.max(v.abs())));
    Ok(Prepared {
        shape,
        vertices,
        wkb_bytes: wkb.len() as u64,
        pinned,
        touches,
        bbox,
        magnitude,
        dropped_zm: input.dropped_zm,
    })
}

/// Coordinates must stay within 2^50 grid steps (the format's range, with room for circles).
const STEP_LIMIT: f64 = MAX_STEPS as f64 / 4.0;

/// The grid a plan starts on: the coarsest "nice" step not above `max_error / fraction`.
fn first_grid(prep: &Prepared, max_error: f64, fraction: f64) -> Result<Decimal> {
    let grid = nice_grid(max_error / fraction)
        .filter(|g| Grid::storable(*g))
        .ok_or_else(|| range_error(max_error))?;
    check_steps(prep, max_error, grid)?;
    Ok(grid)
}

/// The input's coordinates must fit in [`STEP_LIMIT`] steps of `grid`.
fn check_steps(prep: &Prepared, max_error: f64, grid: Decimal) -> Result<()> {
    let magnitude = prep.magnitude;
    if magnitude / grid.to_f64() > STEP_LIMIT {
        return Err(Error::InvalidParameter {
            name: "max_error",
            value: max_error.to_string(),
            range: format!(
                "at least {:e} for coordinates as large as {magnitude:e} (the grid, about half of max_error, must hold them in 2^50 steps)",
                magnitude / STEP_LIMIT * 10.0
            ),
        });
    }
    Ok(())
}

/// What one run of the closed loop starts from.
#[derive(Clone, Copy, Debug)]
struct Plan {
    /// Stored as the value's parameters; `min_radius` and `overlap` only matter with `circles`.
    opts: Options,
    /// The paper's circles (section 3) and Douglas-Peucker points, or the points alone.
    circles: bool,
    /// The first grid (the coarsest the budget allows: 0.2.0 measured about max_error/2 best for
    /// the paper's circles; the closed loop keeps the result within max_error whatever the grid).
    grid: Decimal,
}

/// Run the closed loop for one plan, refining the grid when even every vertex is not enough.
fn run(
    prep: &Prepared,
    srid: i32,
    plan: &Plan,
    max_error: f64,
    interrupt: &mut dyn FnMut(),
) -> Result<(CircleTree, Report)> {
    let opts = &plan.opts;
    let shape = &prep.shape;
    let mut report = Report {
        dropped_zm: prep.dropped_zm,
        ..Report::default()
    };
    let params = Params {
        min_radius: decimal("min_radius", opts.min_radius)?,
        overlap: decimal("overlap", opts.overlap)?,
        dp_tolerance: opts
            .dp_tolerance
            .map(|d| decimal("dp_tolerance", d))
            .transpose()?,
        max_error: decimal("max_error", max_error)?,
    };
    let mut grid = plan.grid;
    let mut last_problem: Option<Pt> = None;
    for attempt in 0..=REFINEMENTS {
        let g = Grid::new(grid);
        let allowed: Touches = prep
            .touches
            .iter()
            .map(|p| touch_key([g.snap(p[0]), g.snap(p[1])]))
            .collect();
        let ctx = Context {
            shape,
            pinned: &prep.pinned,
            allowed: &allowed,
            circles: plan.circles,
        };
        match encode_with_grid(&ctx, opts, max_error, g, interrupt, &mut report)? {
            Outcome::Done(rings, repaired) => {
                let mut parts: Vec<Vec<Vec<Circle>>> = vec![Vec::new(); shape.parts.len()];
                for r in rings {
                    parts[r.part].push(r.circles);
                }
                let ct = CircleTree {
                    version: crate::format::FORMAT_VERSION,
                    srid,
                    kind: shape.kind,
                    grid,
                    params,
                    vertices: prep.vertices,
                    wkb_bytes: prep.wkb_bytes,
                    repaired: repaired as u64,
                    bbox: prep.bbox.map(|b| {
                        [
                            (b[0] / g.step_f64()).floor() as i64,
                            (b[1] / g.step_f64()).floor() as i64,
                            (b[2] / g.step_f64()).ceil() as i64,
                            (b[3] / g.step_f64()).ceil() as i64,
                        ]
                    }),
                    parts,
                };
                // Whatever is returned must read back: the format's own checks, before storing.
                ct.validate()
                    .map_err(|e| Error::Unencodable(format!("{max_error}: {e}")))?;
                return Ok((ct, report));
            }
            Outcome::FinerGrid(at) => {
                last_problem = at;
                let finer = Decimal::new(grid.mantissa, grid.exp as i32 - 1)
                    .filter(|g| Grid::storable(*g) && prep.magnitude / g.to_f64() <= STEP_LIMIT);
                match finer {
                    Some(f) if attempt < REFINEMENTS => grid = f,
                    _ => break,
                }
            }
        }
    }
    let at = last_problem.map_or(String::new(), |p| format!(" near ({} {})", p[0], p[1]));
    Err(Error::Unencodable(format!(
        "{max_error}: even keeping every vertex, the rebuilt rings touch or cross{at} on a grid of {grid} (parts or holes closer to each other than the grid step, or touching at a point that is not a vertex of either)"
    )))
}

/// How many times the grid may be refined tenfold. Islands much smaller than max_error (Scilly's
/// rocks at 50 km) need a grid far finer than max_error/2; a refinement only costs the bytes of the
/// finer coordinates, and a polygon that needs none never pays for it.
const REFINEMENTS: usize = 6;

/// What every round of the loop reads.
struct Context<'a> {
    shape: &'a Shape,
    /// Per part and ring: vertices where another ring touches (kept as zero-radius circles).
    pinned: &'a [Vec<Vec<usize>>],
    /// Those touch points on the grid: the only points where two rebuilt rings may meet.
    allowed: &'a Touches,
    /// Start from the paper's circles (else from Douglas-Peucker points alone).
    circles: bool,
}

#[allow(clippy::too_many_arguments)]
fn initial_entries(
    ring: &[Pt],
    pinned: &[usize],
    circles: bool,
    grid: Grid,
    opts: &Options,
    max_error: f64,
    interrupt: &mut dyn FnMut(),
    report: &mut Report,
) -> Vec<Entry> {
    let n = ring.len();
    let kept = if circles {
        let cands = medial::candidates(ring, interrupt);
        let runs = filter::map_runs(ring, &cands, opts.min_radius, max_error / 2.0);
        interrupt();
        filter::select(n, runs, opts.overlap)
    } else {
        Vec::new()
    };
    report.filtered_circles += kept.len();
    let mut entries: Vec<Entry> = kept
        .iter()
        .map(|m| Entry {
            c: m.c,
            r: m.r,
            anchor: m.start,
            repaired: false,
            touched: true,
        })
        .collect();
    entries.extend(pinned.iter().map(|&v| Entry {
        c: ring[v],
        r: 0.0,
        anchor: v,
        repaired: false,
        touched: true,
    }));
    if !circles {
        // points alone: the fewest within the tolerance, the touch points among them
        if let Some(tol) = opts.dp_tolerance {
            let snap = |p: Pt| [grid.snap(p[0]), grid.snap(p[1])];
            for v in crate::min_points::keep(ring, tol, pinned, &snap) {
                if !pinned.contains(&v) {
                    entries.push(Entry {
                        c: ring[v],
                        r: 0.0,
                        anchor: v,
                        repaired: false,
                        touched: true,
                    });
                    report.dp_points += 1;
                }
            }
        }
    } else if let Some(dp) = opts.dp_tolerance {
        // covered[v]: vertex v lies on a kept run (its ends included: a point on a circle has a
        // degenerate tangent to it)
        let mut covered = vec![false; n];
        for m in &kept {
            for k in 0..=m.len {
                covered[(m.start + k) % n] = true;
            }
        }
        for v in douglas_peucker::keep(ring, dp) {
            if !covered[v] {
                entries.push(Entry {
                    c: ring[v],
                    r: 0.0,
                    anchor: v,
                    repaired: false,
                    touched: true,
                });
                report.dp_points += 1;
            }
        }
    }
    if entries.iter().filter(|e| e.r == 0.0).count()
        + 3 * entries.iter().filter(|e| e.r != 0.0).count()
        < 3
    {
        for v in [0, n / 3, 2 * n / 3] {
            entries.push(Entry {
                c: ring[v],
                r: 0.0,
                anchor: v,
                repaired: true,
                touched: true,
            });
        }
    }
    sort_entries(&mut entries);
    entries
}

fn sort_entries(entries: &mut Vec<Entry>) {
    entries.sort_by(|a, b| {
        a.anchor
            .cmp(&b.anchor)
            .then((a.r != 0.0).cmp(&(b.r != 0.0)))
    });
    entries.dedup_by(|b, a| a.anchor == b.anchor && a.r == 0.0 && b.r == 0.0);
}

fn encode_with_grid(
    ctx: &Context,
    opts: &Options,
    max_error: f64,
    grid: Grid,
    interrupt: &mut dyn FnMut(),
    report: &mut Report,
) -> Result<Outcome> {
    let shape = ctx.shape;
    let g = grid.step_f64();
    let target = max_error - g;
    let mut rings: Vec<RingState> = Vec::new();
    report.filtered_circles = 0;
    report.dp_points = 0;
    for (pi, part) in shape.parts.iter().enumerate() {
        for (ri, ring) in part.iter().enumerate() {
            let pinned = &ctx.pinned[pi][ri];
            let entries = initial_entries(
                ring,
                pinned,
                ctx.circles,
                grid,
                opts,
                max_error,
                interrupt,
                report,
            );
            rings.push(RingState {
                pts: ring.clone(),
                part: pi,
                index: ri,
                entries,
                circles: vec![],
                recon: vec![],
                span_of: vec![],
                starts: vec![],
                spans: vec![],
                dirty: vec![],
            });
        }
    }
    let q = |v: f64| grid.quantize(v);
    let unq = |k: i64| grid.coord(k);
    let mut round = 0;
    loop {
        round += 1;
        report.rounds = round;
        interrupt();
        let mut failing: Vec<Vec<usize>> = vec![Vec::new(); rings.len()];
        for (k, st) in rings.iter_mut().enumerate() {
            st.dirty = dirty_spans(&st.entries);
            if !st.dirty.iter().any(|&d| d) {
                continue;
            }
            for e in &mut st.entries {
                e.touched = false;
            }
            st.circles = st
                .entries
                .iter()
                .map(|e| Circle {
                    x: q(e.c[0]),
                    y: q(e.c[1]),
                    r: q(e.r),
                })
                .collect();
            let fc: Vec<[f64; 3]> = st
                .circles
                .iter()
                .map(|c| [unq(c.x), unq(c.y), unq(c.r)])
                .collect();
            st.spans = ring_spans(&fc);
            (st.recon, st.span_of) = stroke_dedup(&st.spans, g);
            st.starts = (0..=st.m())
                .map(|s| st.span_of.partition_point(|&x| (x as usize) < s))
                .collect();
            // Hausdorff, both ways, span by span. Where the window holds only straight spans,
            // the stroke is the geometry itself and the whole bound is available (arcs keep a
            // grid step of it for the decoder's stroke).
            let eps = g * 1e-3;
            let straight_target = max_error - 3.0 * eps;
            for s in 0..st.m() {
                let t = if !ctx.circles && st.straight_window(s) {
                    straight_target
                } else {
                    target
                };
                if st.dirty[s] && !st.span_fits(s, t, eps) {
                    failing[k].push(s);
                }
            }
        }
        interrupt();
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
            let mut misplaced = Vec::new();
            for (k, seg) in problems_where(&refs, Some(&changed), ctx.allowed, interrupt) {
                if seg == usize::MAX {
                    failing[k].extend(0..rings[k].entries.len());
                    problem_at = problem_at.or(rings[k].recon.first().copied());
                    misplaced.push(k);
                } else if let Some(&s) = rings[k].span_of.get(seg) {
                    failing[k].push(s as usize);
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
                            failing[h].push(s);
                        }
                    }
                }
            }
        }
        {
            // The true arcs between the stroked points.
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
            for (k, s) in arcs::problems(&refs, &probes, g, g * 1e-6, interrupt) {
                if s == usize::MAX {
                    failing[k].extend(0..rings[k].entries.len());
                } else {
                    failing[k].push(s);
                }
                problem_at = problem_at.or(rings[k].recon.first().copied());
            }
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
            if repair(st, &spans, target, hurry) {
                progress = true;
            }
        }
        if !progress {
            // Every failing span is already an original edge between two kept vertices.
            return Ok(Outcome::FinerGrid(problem_at));
        }
    }
}

/// Repair failing spans of one ring. `false` when no span had anything left to add or remove.
fn repair(st: &mut RingState, spans: &[usize], target: f64, hurry: bool) -> bool {
    let n = st.pts.len();
    let m = st.entries.len();
    let mut remove = vec![false; m];
    let mut add: Vec<Entry> = Vec::new();
    let point = |v: usize| Entry {
        c: st.pts[v],
        r: 0.0,
        anchor: v,
        repaired: true,
        touched: true,
    };
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
        let interior: Vec<usize> = (a + 1..b).map(|v| v % n).collect();
        if interior.is_empty() {
            let j = (i + 1) % m;
            if st.entries[i].r != 0.0 {
                remove[i] = true;
                add.push(point(a));
            } else if st.entries[j].r != 0.0 {
                remove[j] = true;
                add.push(point(st.entries[j].anchor));
            } else if m < n && a == b % n && m == 1 {
                add.extend([point((a + n / 3) % n), point((a + 2 * n / 3) % n)]);
            }
            continue;
        }
        if hurry {
            add.extend(interior.iter().map(|&v| point(v)));
            for j in [i, (i + 1) % m] {
                if st.entries[j].r != 0.0 {
                    remove[j] = true;
                    add.push(point(st.entries[j].anchor));
                }
            }
            continue;
        }
        // the interior vertex farthest from the stroke, if it is far; else the middle one
        let recon = st.window_recon(i);
        let far = |v: usize| {
            recon
                .iter()
                .map(|&(c, d)| dist2_to_segment(st.pts[v], c, d))
                .fold(f64::INFINITY, f64::min)
        };
        let best = interior
            .iter()
            .map(|&v| (far(v), v))
            .max_by(|x, y| x.0.total_cmp(&y.0));
        let v = match best {
            Some((d2, v)) if d2 > (target * 0.5).powi(2) => v,
            _ => interior[interior.len() / 2],
        };
        add.push(point(v));
    }
    // Failing spans are checked again next round even where nothing could be done (then the
    // round makes no progress and the grid is refined); neighbours of a removed circle change.
    for &i in spans {
        if i < m {
            st.entries[i].touched = true;
            st.entries[(i + 1) % m].touched = true;
        }
    }
    let removed_at: Vec<usize> = (0..m).filter(|&i| remove[i]).collect();
    for i in removed_at {
        st.entries[(i + m - 1) % m].touched = true;
        st.entries[(i + 1) % m].touched = true;
    }
    let before = st.entries.len();
    let removed = remove.iter().filter(|&&r| r).count();
    let mut next: Vec<Entry> = st
        .entries
        .iter()
        .zip(&remove)
        .filter(|(_, &r)| !r)
        .map(|(e, _)| *e)
        .collect();
    next.extend(add);
    sort_entries(&mut next);
    let changed = removed > 0 || next.len() != before;
    st.entries = next;
    changed
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Kind;

    fn wkb_of(parts: Vec<Vec<Vec<Pt>>>) -> Vec<u8> {
        crate::wkb::write(Kind::Polygon, &parts)
    }

    fn opts(min_radius: f64, dp: Option<f64>) -> Options {
        Options {
            min_radius,
            overlap: 0.4,
            dp_tolerance: dp,
            max_error: None,
        }
    }

    #[test]
    fn grid_is_a_nice_tenth() {
        assert_eq!(nice_grid(1.0).unwrap().to_string(), "1");
        assert_eq!(nice_grid(0.5).unwrap().to_string(), "0.5");
        assert_eq!(nice_grid(2.5).unwrap().to_string(), "2");
        assert_eq!(nice_grid(0.99).unwrap().to_string(), "0.5");
    }

    #[test]
    fn square_is_four_points() {
        let sq = vec![vec![vec![
            [0.0, 0.0],
            [100.0, 0.0],
            [100.0, 100.0],
            [0.0, 100.0],
        ]]];
        let (ct, _) = encode(&wkb_of(sq), 0, &opts(5.0, Some(1.0)), &mut || {}).unwrap();
        let ring = &ct.parts[0][0];
        assert_eq!(ring.len(), 4, "{ring:?}");
        assert!(ring.iter().all(|c| c.r == 0));
    }

    #[test]
    fn buffered_disc_is_one_circle() {
        // ST_Buffer(point, 100, 8): 32 vertices
        let disc: Vec<Pt> = (0..32)
            .map(|i| {
                let t = i as f64 / 32.0 * std::f64::consts::TAU;
                [500000.0 + 100.0 * t.cos(), 6000000.0 + 100.0 * t.sin()]
            })
            .collect();
        let (ct, _) = encode(
            &wkb_of(vec![vec![disc]]),
            32760,
            &opts(5.0, None),
            &mut || {},
        )
        .unwrap();
        let ring = &ct.parts[0][0];
        assert!(ring.len() <= 2, "{ring:?}");
        assert!(ring.iter().all(|c| c.r > 0));
    }

    #[test]
    fn bad_parameters_name_themselves() {
        let sq = wkb_of(vec![vec![vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]]]);
        let e = encode(&sq, 0, &opts(0.0, None), &mut || {}).unwrap_err();
        assert!(matches!(
            e,
            Error::InvalidParameter {
                name: "min_radius",
                ..
            }
        ));
        let e = encode(
            &sq,
            0,
            &Options {
                overlap: 1.5,
                ..opts(1.0, None)
            },
            &mut || {},
        )
        .unwrap_err();
        assert!(matches!(
            e,
            Error::InvalidParameter {
                name: "overlap",
                ..
            }
        ));
        let e = encode(&sq, 0, &opts(1.0, Some(-1.0)), &mut || {}).unwrap_err();
        assert!(matches!(
            e,
            Error::InvalidParameter {
                name: "dp_tolerance",
                ..
            }
        ));
    }
}
