//! The encoder: the paper's method (sections 3.1-3.5) followed by a closed loop that the paper
//! did not have.
//!
//! Per ring: candidate circles ([`crate::encode::paper::medial`]), filtered and mapped to runs of edges
//! ([`crate::encode::paper::filter`]), Douglas-Peucker points as zero-radius circles where no circle covers the
//! boundary ([`crate::encode::paper::douglas_peucker`]), everything ordered along the ring by the first vertex it
//! stands for. Then, for the whole geometry at once:
//!
//! 1. quantize the circles to the grid and rebuild every ring exactly as `ct_decode` will
//!    ([`crate::decode::reconstruct`], arcs stroked to the grid step);
//! 2. measure the continuous Hausdorff distance between each rebuilt ring and its original, both
//!    ways, with R-trees and a Lipschitz bound on each segment (no sampling gaps), against
//!    `max_error − grid` (so the true arcs are within `max_error` too);
//! 3. check validity as OGC defines it ([`crate::check::validity`] on the stroke, [`crate::check::arcs`] on the
//!    true arcs, so that every finer stroke and the curved form are valid too); rings may touch
//!    only at the input's own touch points ([`crate::check::touch`]), which every ring through them keeps
//!    as a zero-radius circle;
//! 4. where a span between two consecutive circles fails, add an original vertex inside it as a
//!    zero-radius circle (counted as *repaired*); a span with no vertex left loses its circle.
//!
//! The loop ends because each round adds a vertex or removes a circle; its end point, every vertex
//! kept, is the quantized original. If even that fails (rings closer to each other than the grid
//! can hold), the grid is refined: tenfold at first ([`TENFOLD`] times), then at once to half the
//! input's minimum clearance ([`crate::geom::clearance`]) when that is what is close, as far as the
//! coordinates allow ([`finest_grid`]). The result is valid and within `max_error`; a shape that
//! even the finest grid cannot hold is refused with its clearance, its magnitude and that grid
//! ([`Error::BeyondPrecision`]).
//!
//! Parameters are checked by one rule before any work ([`LENGTHS`], [`check_magnitude`]), so
//! every value returned reads back.
//!
//! The work is split by job: [`initial`] (what a plan starts from: the paper's circles and
//! Douglas-Peucker points, or the fewest points alone) and [`repair`] (the closed loop every
//! encoder's result must pass: quantize, rebuild, measure, check validity, repair); this module
//! holds the parameters, the plans and the grid refinement around them.

mod host_check;
mod initial;
pub(crate) mod min_points;
mod nudge;
pub(crate) mod paper;
mod repair;

use crate::check::touch;
use crate::check::validity::{touch_key, Touches};
use crate::error::{Error, Result};
use crate::format::decimal::Decimal;
use crate::format::grid::Grid;
use crate::format::{Circle, CircleTree, Params, MAX_STEPS};
use crate::geom::{clearance, orient, Pt, Shape};
use crate::parallel;
pub use host_check::HostCheck;
use host_check::{beside, Verdict};
use repair::{initial_rings, unchecked_parts, verify_and_repair, Context, Outcome, RingState};
use std::sync::atomic::Ordering;

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

/// Every length parameter (`min_radius`, `dp_tolerance`, `max_error`) is finite and within this
/// range, in the units of the geometry's SRID: the grid, about half of `max_error` and refined as
/// far as a polygon needs, must stay within the format's steps of 1e-12 ..= 9e12.
pub const LENGTHS: (f64, f64) = (1e-11, 1e13);

/// The one rule for a length parameter ([`LENGTHS`]).
fn length(name: &'static str, v: f64) -> Result<f64> {
    if v.is_finite() && (LENGTHS.0..=LENGTHS.1).contains(&v) {
        Ok(v)
    } else {
        Err(length_error(name, v))
    }
}

fn length_error(name: &'static str, v: f64) -> Error {
    Error::InvalidParameter {
        name,
        value: crate::error::number(v),
        range: format!(
            "a length between {:e} and {:e}, in the units of the geometry's SRID",
            LENGTHS.0, LENGTHS.1
        ),
    }
}

/// A checked parameter as the value stores it.
fn decimal(name: &'static str, v: f64) -> Result<Decimal> {
    Decimal::from_f64(v).ok_or_else(|| length_error(name, v))
}

impl Options {
    /// Check the ranges; returns `max_error` resolved.
    pub fn check(&self) -> Result<f64> {
        length("min_radius", self.min_radius)?;
        // a fraction: 0, or as fine as a length may be
        if !(self.overlap == 0.0 || (LENGTHS.0..=1.0).contains(&self.overlap)) {
            return Err(Error::InvalidParameter {
                name: "overlap",
                value: crate::error::number(self.overlap),
                range: format!("0, or a fraction between {:e} and 1", LENGTHS.0),
            });
        }
        if let Some(d) = self.dp_tolerance {
            length("dp_tolerance", d)?;
        }
        match self.max_error {
            Some(m) => length("max_error", m),
            // both checked: their larger is within the range too
            None => Ok(self.min_radius.max(self.dp_tolerance.unwrap_or(0.0))),
        }
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

/// What is known of the input's validity when an encoder is called. An invalid input is refused
/// with the host's reason ([`Error::InvalidPolygon`]); the encoders do not judge it themselves.
pub enum Validity<'a> {
    /// The caller vouches that the input is valid (it checked, or the data is known to be).
    Valid,
    /// The caller found it invalid: the reason the error carries (PostGIS's `ST_IsValidReason`).
    Invalid(&'a str),
    /// Asked of the host while the encoder runs ([`HostCheck`]).
    Host(HostCheck<'a>),
}

/// One call of an encoder: the input's SRID, what is known of its validity, and the host's
/// interrupt check (called often; it may unwind to cancel the call).
pub struct Call<'a> {
    /// The SRID the value records.
    pub srid: i32,
    /// What is known of the input's validity.
    pub validity: Validity<'a>,
    /// The host's interrupt check; `None`: never interrupted.
    pub interrupt: Option<&'a mut dyn FnMut()>,
}

impl<'a> Call<'a> {
    /// A call on an input known to be valid, never interrupted.
    pub fn new(srid: i32) -> Self {
        Call {
            srid,
            validity: Validity::Valid,
            interrupt: None,
        }
    }

    /// The same call with this validity.
    pub fn validity(self, validity: Validity<'a>) -> Self {
        Call { validity, ..self }
    }

    /// The same call with this interrupt check.
    pub fn interrupt(self, interrupt: &'a mut dyn FnMut()) -> Self {
        Call {
            interrupt: Some(interrupt),
            ..self
        }
    }
}

/// What an encoder returns: the value, what it did, and the stored bytes when it wrote them
/// already (`encode_within` writes them to rank its plans).
#[derive(Clone, Debug)]
pub struct Encoded {
    /// The value.
    pub value: CircleTree,
    /// What the encoder did.
    pub report: Report,
    bytes: Option<Vec<u8>>,
}

impl Encoded {
    /// The value, its stored bytes (`value.to_bytes()`, not written twice) and the report.
    pub fn into_parts(self) -> (CircleTree, Vec<u8>, Report) {
        let bytes = self.bytes.unwrap_or_else(|| self.value.to_bytes());
        (self.value, bytes, self.report)
    }
}

/// Runs `f` with the call's validity as the encoder takes it: a host check runs beside it.
fn with_call<T: Send>(
    wkb: &[u8],
    call: Call<'_>,
    f: impl FnOnce(Verdict<'_>, Option<crate::geom::wkb::Input>, &mut dyn FnMut()) -> Result<T> + Send,
) -> Result<T> {
    let mut never = || {};
    let interrupt: &mut dyn FnMut() = match call.interrupt {
        Some(i) => i,
        None => &mut never,
    };
    match call.validity {
        Validity::Valid => f(Verdict::Known(None), None, interrupt),
        Validity::Invalid(reason) => f(Verdict::Known(Some(reason)), None, interrupt),
        Validity::Host(check) => beside(wkb, check, interrupt, f),
    }
}

/// The paper's circles (Moore 2002, sections 3.1-3.5) of a WKB Polygon or MultiPolygon, through
/// the closed loop: valid, and within `max_error` (continuous Hausdorff) of the input.
pub fn encode(wkb: &[u8], opts: &Options, call: Call<'_>) -> Result<Encoded> {
    let srid = call.srid;
    with_call(wkb, call, |verdict, read, i| {
        encode_verdict(wkb, srid, opts, verdict, read, i)
    })
    .map(|(value, report)| Encoded {
        value,
        report,
        bytes: None,
    })
}

/// `read`: the input, when the caller has read it already.
fn encode_verdict(
    wkb: &[u8],
    srid: i32,
    opts: &Options,
    verdict: Verdict<'_>,
    read: Option<crate::geom::wkb::Input>,
    interrupt: &mut dyn FnMut(),
) -> Result<(CircleTree, Report)> {
    let max_error = opts.check()?;
    let prep = prepare(wkb, verdict, read)?;
    let plan = Plan {
        opts: *opts,
        circles: true,
        grid: first_grid(&prep, max_error, 2.0)?,
    };
    run(&prep, srid, &plan, max_error, None, interrupt)
}

/// The fewest bytes within `max_error`: several plans go through the same closed loop as
/// [`encode`] (so each result is valid and within the bound), and the smallest value is kept. A
/// plan is priced before its loop runs, and a plan whose price is not below the best result so far
/// is not run (the same bytes as running all of them).
///
/// Every plan keeps points only: the fewest vertices whose stored (rounded) shortcuts stay within
/// max_error of the ring ([`min_points`]), on grids of [`WITHIN_GRIDS`] times max_error.
/// Where vertices are far apart (GSHHG's ~180 m) almost every one is kept and the coarsest grid
/// wins; where they are dense (LINZ at 100 m) a finer grid skips more. The paper's circles are not
/// tried (`docs/decisions/points-over-circles.md`).
pub fn encode_within(wkb: &[u8], max_error: f64, call: Call<'_>) -> Result<Encoded> {
    let srid = call.srid;
    with_call(wkb, call, |verdict, read, i| {
        within_verdict(wkb, srid, max_error, verdict, read, i)
    })
    .map(|(value, bytes, report)| Encoded {
        value,
        report,
        bytes: Some(bytes),
    })
}

fn within_verdict(
    wkb: &[u8],
    srid: i32,
    max_error: f64,
    verdict: Verdict<'_>,
    read: Option<crate::geom::wkb::Input>,
    interrupt: &mut dyn FnMut(),
) -> Result<(CircleTree, Vec<u8>, Report)> {
    length("max_error", max_error)?;
    let checked = Options {
        min_radius: max_error,
        overlap: 0.0,
        dp_tolerance: None,
        max_error: Some(max_error),
    };
    let max_error = checked.check()?;
    let prep = prepare(wkb, verdict, read)?;
    // the same parameter ranges as `encode` at this bound (its grid must hold the coordinates)
    first_grid(&prep, max_error, 2.0)?;
    // Every plan's start is priced on its grid, and the closed loop runs on the cheapest first.
    // Repair only adds points and refining a grid only lengthens coordinates, so a start's price
    // is (all but always) a floor of its result: the next plan is run only while its price is
    // below the best result so far (a plan whose grid had to be refined usually is).
    let mut specs = Vec::new();
    let mut first_error = None;
    for fraction in WITHIN_GRIDS {
        // every plan's grid holds the coordinates: it is at least 0.45 max_error, and
        // `check_magnitude` (in `first_grid` above) asked for 2^-47 of them
        let grid = match grid_near(max_error * fraction)
            .ok_or_else(|| length_error("max_error", max_error))
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
        specs.push(Plan {
            opts: Options {
                dp_tolerance: Some(tol),
                ..checked
            },
            circles: false,
            grid,
        });
    }
    // The plans are priced independently. On a large input the first plan (the coarsest grid,
    // which most often wins) is priced and its loop run here while a second thread prices the
    // others; the choice below is then made as if one thing were done after the other, so the
    // value is the same (a run the order would not have needed is dropped).
    let worth_it =
        prep.vertices >= PLANS_APART_VERTICES && specs.len() > 1 && parallel::threads() > 1;
    // The first plan, which most often wins, is priced by writing it (its bytes are then the
    // result's when its start needs no repair); the others by bounds on their size, written only
    // where the bounds leave the choice open.
    let price = |plan: &Plan, exact: bool, interrupt: &mut dyn FnMut()| {
        let (result, plan) = (
            unchecked(&prep, srid, plan, max_error, exact, interrupt),
            *plan,
        );
        (
            result.map(|(priced, start)| (priced, Start::Rings(start))),
            plan,
        )
    };
    let (first, rest) = specs.split_at(specs.len().min(1));
    let (mut priced, rest) = parallel::join(
        worth_it,
        interrupt,
        |i| {
            first
                .iter()
                .map(|p| match price(p, true, i) {
                    (Ok((priced, Start::Rings(start))), plan) if worth_it => {
                        let ran = run(&prep, srid, &plan, max_error, Some(start), i);
                        (Ok((priced, Start::Ran(ran))), plan)
                    }
                    other => other,
                })
                .collect::<Vec<_>>()
        },
        |i| rest.iter().map(|p| price(p, false, i)).collect::<Vec<_>>(),
    );
    priced.extend(rest);
    let mut plans = Vec::new();
    for (result, plan) in priced {
        match result {
            Ok((priced, start)) => plans.push((priced, plan, start)),
            Err(e) => {
                first_error.get_or_insert(e);
            }
        }
    }
    // The order of the exact sizes: where two plans' bounds overlap, both are written.
    for i in 0..plans.len() {
        for j in i + 1..plans.len() {
            let ((a0, a1), (b0, b1)) = (plans[i].0 .1.range(), plans[j].0 .1.range());
            if a0 <= b1 && b0 <= a1 {
                for k in [i, j] {
                    let (ct, price) = &mut plans[k].0;
                    price.make_exact(ct);
                }
            }
        }
    }
    plans.sort_by_key(|p| p.0 .1.range().0);
    let mut best: Option<(CircleTree, Vec<u8>, Report)> = None;
    for ((priced, mut price), plan, start) in plans {
        if let Some(b) = &best {
            let (lo, hi) = price.range();
            if b.1.len() <= lo {
                break;
            }
            if b.1.len() <= hi && b.1.len() <= price.make_exact(&priced) {
                break;
            }
        }
        let ran = match start {
            Start::Ran(ran) => ran,
            Start::Rings(start) => run(&prep, srid, &plan, max_error, Some(start), interrupt),
        };
        match ran {
            Ok((ct, report)) => {
                // most starts need no repair: the result is then the value already written
                let bytes = match price {
                    Price::Exact(bytes) if ct == priced => bytes,
                    _ => ct.to_bytes(),
                };
                if best.as_ref().is_none_or(|b| bytes.len() < b.1.len()) {
                    best = Some((ct, bytes, report));
                }
            }
            Err(e) => {
                first_error.get_or_insert(e);
            }
        }
    }
    match (best, first_error) {
        (Some((ct, bytes, report)), _) => Ok((ct, bytes, report)),
        (None, Some(e)) => Err(e),
        (None, None) => Err(length_error("max_error", max_error)),
    }
}

/// Inputs of at least this many vertices have their plans priced on two threads. Lower than
/// [`parallel::MIN_VERTICES`]: pricing a plan is a millisecond at this size against tens of
/// microseconds to start a thread, so from this size up a second thread pays for itself (below
/// it, the public set's `ct_encode_within(geom, 10)` gains nothing more).
const PLANS_APART_VERTICES: u64 = 1_000;

/// What a plan's start would store: its bytes, or bounds on their number
/// ([`CircleTree::size_bounds`]).
enum Price {
    Exact(Vec<u8>),
    Bounds(usize, usize),
}

impl Price {
    /// The least and the most bytes.
    fn range(&self) -> (usize, usize) {
        match self {
            Price::Exact(b) => (b.len(), b.len()),
            Price::Bounds(lo, hi) => (*lo, *hi),
        }
    }

    /// Write `ct` if only its bounds were known; its exact size.
    fn make_exact(&mut self, ct: &CircleTree) -> usize {
        if let Price::Bounds(..) = self {
            *self = Price::Exact(ct.to_bytes());
        }
        self.range().0
    }
}

/// A priced plan's start: its rings before the loop, or the loop's outcome when already run.
enum Start {
    Rings((Vec<RingState>, Report)),
    Ran(Result<(CircleTree, Report)>),
}

/// Grids `encode_within` tries, as fractions of max_error. 1.4 is about the coarsest allowed
/// (rounding moves a point by up to 0.71 of a step, and the ring must stay within max_error of the
/// stored points); finer grids leave room to skip more vertices where the rounding would otherwise
/// use the bound. Measured on the corpus (bytes summed; 1.4 alone / these three / adding 1 and 0.4):
/// 10 m 341,205 / 339,824 / 339,625; 25 m 235,173 / 234,417 / 234,293; 100 m 92,465 / 70,944 / 73,362.
const WITHIN_GRIDS: [f64; 3] = [1.4, 0.8, 0.5];

/// Refuse lengths of a degree or more on a longitude/latitude SRID: no one means an error of 111 km,
/// so they are metres given by mistake (`ct_encode(geom, 5, 0.4, 10)` on EPSG:4326 would otherwise
/// keep four points of a whole island). Smaller lengths are taken as degrees, as PostGIS does.
pub fn check_degrees(srid: i32, lengths: &[(&'static str, Option<f64>)]) -> Result<()> {
    for &(name, v) in lengths {
        if let Some(v) = v.filter(|v| v.abs() >= 1.0) {
            return Err(Error::InvalidParameter {
                name,
                value: crate::error::number(v),
                range: format!(
                    "less than 1 on SRID {srid}, whose units are degrees of longitude and latitude; \
                     for metres, encode the geography: ct_encode(geom::geography, ...) works in the \
                     UTM zone's metres (ct_utm_srid)"
                ),
            });
        }
    }
    Ok(())
}

/// The largest grid of two significant digits not above `x` (`None` outside the format's range).
fn grid_near(x: f64) -> Option<Decimal> {
    if !(x.is_finite() && x > 0.0) {
        return None;
    }
    let k = x.log10().floor() as i32 - 1;
    let m = (x / 10f64.powi(k)).floor() as i64;
    Decimal::new(m.clamp(10, 99), k).filter(|g| Grid::storable(*g))
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
    /// Rings nearly touching made to touch on the finest grid ([`nudge`]): the encoder's last try.
    nudged: bool,
}

fn prepare(
    wkb: &[u8],
    verdict: Verdict<'_>,
    read: Option<crate::geom::wkb::Input>,
) -> Result<Prepared> {
    let input = match read {
        Some(input) => input,
        None => crate::geom::wkb::read(wkb)?,
    };
    match verdict {
        Verdict::Known(Some(reason)) => return Err(Error::InvalidPolygon(reason.to_string())),
        Verdict::Known(None) => {}
        Verdict::Pending(read) => read.store(true, Ordering::Release),
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
        nudged: false,
    })
}

/// Coordinates must stay within 2^50 grid steps (the format's range, with room for circles).
const STEP_LIMIT: f64 = MAX_STEPS as f64 / 4.0;

/// The least `max_error` for coordinates as large as `magnitude`: 2^-47 of it (about 7.1e-15 of
/// it, a few units in the last place of a double), so that the coarsest grid of every plan holds
/// the coordinates in [`STEP_LIMIT`] steps.
pub fn least_max_error(magnitude: f64) -> f64 {
    magnitude * STEP_LIMIT.recip() * 8.0
}

/// The second rule for `max_error`, beside [`LENGTHS`]: at least [`least_max_error`] of the
/// input's largest absolute coordinate.
fn check_magnitude(prep: &Prepared, max_error: f64) -> Result<()> {
    let least = least_max_error(prep.magnitude);
    if max_error < least {
        return Err(Error::InvalidParameter {
            name: "max_error",
            value: crate::error::number(max_error),
            range: format!(
                "at least {} for coordinates as large as {} (2^-47 of them: a double holds about 16 significant digits)",
                crate::error::number(least),
                crate::error::number(prep.magnitude)
            ),
        });
    }
    Ok(())
}

/// The finest grid a value of coordinates as large as `magnitude` may have: the finest 1, 2 or
/// 5 × 10^k that holds them in [`STEP_LIMIT`] steps, and no finer than the format's 1e-12
/// (`None` for coordinates [`check_magnitude`] refuses).
pub fn finest_grid(magnitude: f64) -> Option<Decimal> {
    let least = (magnitude / STEP_LIMIT).max(10f64.powi(crate::format::grid::MIN_EXP as i32));
    let k = least.log10().floor() as i32;
    [k, k + 1]
        .into_iter()
        .flat_map(|e| [1i64, 2, 5].map(|m| Decimal::new(m, e)))
        .flatten()
        .find(|d| d.to_f64() >= least && Grid::storable(*d))
}

/// The grid a plan starts on: the coarsest "nice" step not above `max_error / fraction`.
fn first_grid(prep: &Prepared, max_error: f64, fraction: f64) -> Result<Decimal> {
    check_magnitude(prep, max_error)?;
    nice_grid(max_error / fraction)
        .filter(|g| Grid::storable(*g))
        .ok_or_else(|| length_error("max_error", max_error))
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

/// The parameters a plan stores.
fn params(opts: &Options, max_error: f64) -> Result<Params> {
    Ok(Params {
        min_radius: decimal("min_radius", opts.min_radius)?,
        overlap: decimal("overlap", opts.overlap)?,
        dp_tolerance: opts
            .dp_tolerance
            .map(|d| decimal("dp_tolerance", d))
            .transpose()?,
        max_error: decimal("max_error", max_error)?,
    })
}

/// The input's touch points on the grid: the only points where two rebuilt rings may meet.
fn allowed_touches(prep: &Prepared, g: Grid) -> Touches {
    prep.touches
        .iter()
        .map(|p| touch_key([g.snap(p[0]), g.snap(p[1])]))
        .collect()
}

/// A value of `parts` on `grid`, with the input's header fields.
fn tree(
    prep: &Prepared,
    srid: i32,
    grid: Decimal,
    params: Params,
    parts: Vec<Vec<Vec<Circle>>>,
    repaired: usize,
) -> CircleTree {
    let g = Grid::new(grid).step_f64();
    CircleTree {
        version: crate::format::FORMAT_VERSION,
        srid,
        kind: prep.shape.kind,
        grid,
        params,
        vertices: prep.vertices,
        wkb_bytes: prep.wkb_bytes,
        repaired: repaired as u64,
        bbox: prep.bbox.map(|b| {
            [
                (b[0] / g).floor() as i64,
                (b[1] / g).floor() as i64,
                (b[2] / g).ceil() as i64,
                (b[3] / g).ceil() as i64,
            ]
        }),
        parts,
    }
}

/// A plan's starting rings on its first grid, and the value they would make if nothing needed
/// repair with its price (the repair loop adds a point or two in a thousand, so this ranks plans
/// as their results rank, for a fraction of the work): its bytes when `exact`, else bounds.
#[allow(clippy::type_complexity)]
fn unchecked(
    prep: &Prepared,
    srid: i32,
    plan: &Plan,
    max_error: f64,
    exact: bool,
    interrupt: &mut dyn FnMut(),
) -> Result<((CircleTree, Price), (Vec<RingState>, Report))> {
    let g = Grid::new(plan.grid);
    let allowed = Touches::default();
    let ctx = Context {
        shape: &prep.shape,
        pinned: &prep.pinned,
        allowed: &allowed,
        circles: plan.circles,
    };
    let mut report = Report::default();
    let rings = initial_rings(&ctx, &plan.opts, max_error, g, interrupt, &mut report);
    let parts = unchecked_parts(&rings, prep.shape.parts.len(), g);
    let ct = tree(
        prep,
        srid,
        plan.grid,
        params(&plan.opts, max_error)?,
        parts,
        0,
    );
    let price = if exact {
        Price::Exact(ct.to_bytes())
    } else {
        let (lo, hi) = ct.size_bounds();
        Price::Bounds(lo, hi)
    };
    Ok(((ct, price), (rings, report)))
}

/// Run the closed loop for one plan, refining the grid when even every vertex is not enough.
/// `first`: the plan's starting rings on its first grid, when already built ([`unchecked`]).
fn run(
    prep: &Prepared,
    srid: i32,
    plan: &Plan,
    max_error: f64,
    mut first: Option<(Vec<RingState>, Report)>,
    interrupt: &mut dyn FnMut(),
) -> Result<(CircleTree, Report)> {
    let mut opts = plan.opts;
    let mut circles = plan.circles;
    let shape = &prep.shape;
    let mut report = Report {
        dropped_zm: prep.dropped_zm,
        ..Report::default()
    };
    let params = params(&opts, max_error)?;
    let mut grid = plan.grid;
    let finest = finest_grid(prep.magnitude).ok_or_else(|| length_error("max_error", max_error))?;
    // the input's minimum clearance, once a grid has proved too coarse (see below)
    let mut clearance: Option<f64> = None;
    let mut refinements = 0;
    loop {
        let g = Grid::new(grid);
        let allowed = allowed_touches(prep, g);
        let ctx = Context {
            shape,
            pinned: &prep.pinned,
            allowed: &allowed,
            circles,
        };
        // the plan's starting rings are those of its first grid only
        let rings = match first.take() {
            Some((rings, start)) => {
                report.filtered_circles = start.filtered_circles;
                report.dp_points = start.dp_points;
                rings
            }
            _ => initial_rings(&ctx, &opts, max_error, g, interrupt, &mut report),
        };
        match verify_and_repair(&ctx, rings, max_error, g, interrupt, &mut report)? {
            Outcome::Done(rings, repaired) => {
                let mut parts: Vec<Vec<Vec<Circle>>> = vec![Vec::new(); shape.parts.len()];
                for r in rings {
                    parts[r.part].push(r.circles);
                }
                let ct = tree(prep, srid, grid, params, parts, repaired);
                // Whatever is returned must read back: the format's own checks, before storing.
                ct.validate()
                    .map_err(|e| Error::Unencodable(format!("{max_error}: {e}")))?;
                return Ok((ct, report));
            }
            Outcome::FinerGrid(at) => {
                // Even every vertex kept, the rings touch or cross on this grid. Moving each
                // vertex by less than half the minimum clearance cannot make them cross, so a
                // grid of half of it holds them. The first [`TENFOLD`] refinements are tenfold
                // (rings a little closer than the grid most often need no more); after that the
                // grid goes at once to half the clearance when that is what is close (looked for
                // within a few steps of the grid that failed first), else tenfold again.
                let c =
                    *clearance.get_or_insert_with(|| clearance::below(shape, 4.0 * g.step_f64()));
                if grid.to_f64() <= finest.to_f64() {
                    let refused = refusal(prep, max_error, c, finest, at);
                    return match refused {
                        Error::BeyondPrecision { .. } if !prep.nudged => {
                            nudged(prep, srid, opts, circles, finest, max_error, interrupt)
                                .map(|(mut ct, r)| {
                                    ct.params = params;
                                    (ct, r)
                                })
                                .ok_or(refused)
                        }
                        _ => Err(refused),
                    };
                }
                let tenth = Decimal::new(grid.mantissa, grid.exp as i32 - 1);
                let by_clearance =
                    nice_grid(c / 2.0).filter(|_| refinements >= TENFOLD && c < 4.0 * g.step_f64());
                let next = [tenth, by_clearance]
                    .into_iter()
                    .flatten()
                    .min_by(|a, b| a.to_f64().total_cmp(&b.to_f64()));
                refinements += 1;
                grid = next
                    .filter(|n| n.to_f64() > finest.to_f64())
                    .unwrap_or(finest);
                // On a grid far finer than the bound, arcs stroked to the grid step take many
                // thousands of chords each: the paper's circles give way to the fewest points
                // within the bound, as `encode_within` keeps (the value stays valid and within
                // max_error; its stored parameters are the caller's).
                if circles && grid.to_f64() < max_error * POINTS_BELOW {
                    circles = false;
                    opts.dp_tolerance = Some(max_error - 4e-3 * grid.to_f64());
                }
            }
        }
    }
}

/// The input with its rings that come within two grid steps of each other pushed apart, encoded on
/// the finest grid within `max_error` less the distance the nudge moved it ([`nudge`]); `None`
/// when the pushes do not settle or the encoding fails (the caller then refuses).
#[allow(clippy::too_many_arguments)]
fn nudged_as(
    prep: &Prepared,
    srid: i32,
    opts: Options,
    circles: bool,
    finest: Decimal,
    max_error: f64,
    scaled: bool,
    interrupt: &mut dyn FnMut(),
) -> Option<(CircleTree, Report)> {
    let (shape, pinned, touches) =
        nudge::apart(&prep.shape, &prep.touches, Grid::new(finest), scaled)?;
    // an upper bound of the distance moved: the measure is within eps of it
    let extent = prep.magnitude;
    let moved = crate::check::metrics::shape_hausdorff(&prep.shape.parts, &shape.parts, interrupt)
        + (extent * 1e-9).max(1e-12);
    let inner = max_error - moved;
    if inner < max_error / 2.0 {
        return None;
    }
    let near = Prepared {
        shape,
        pinned,
        touches,
        nudged: true,
        ..*prep
    };
    let mut opts = opts;
    if !circles {
        opts.dp_tolerance = Some(inner - 4e-3 * finest.to_f64());
    }
    let plan = Plan {
        opts,
        circles,
        grid: finest,
    };
    run(&near, srid, &plan, inner, None, interrupt).ok()
}

/// [`nudged_as`] with rings too small for the grid scaled up, else made thin triangles.
fn nudged(
    prep: &Prepared,
    srid: i32,
    opts: Options,
    circles: bool,
    finest: Decimal,
    max_error: f64,
    interrupt: &mut dyn FnMut(),
) -> Option<(CircleTree, Report)> {
    [true, false].into_iter().find_map(|scaled| {
        nudged_as(
            prep, srid, opts, circles, finest, max_error, scaled, interrupt,
        )
    })
}

/// A grid finer than this fraction of max_error holds points only (see [`run`]).
const POINTS_BELOW: f64 = 1e-7;

/// Refinements that are tenfold whatever the clearance. Islands much smaller than max_error
/// (Scilly's rocks at 50 km) need a grid far finer than max_error/2, yet most often coarser than
/// half their clearance: a refinement costs the bytes of the finer coordinates, and a polygon that
/// needs none never pays for it.
const TENFOLD: usize = 6;

/// Why a shape cannot be encoded on the finest grid its coordinates allow.
fn refusal(
    prep: &Prepared,
    max_error: f64,
    clearance: f64,
    finest: Decimal,
    at: Option<Pt>,
) -> Error {
    if clearance < 2.0 * finest.to_f64() {
        return Error::BeyondPrecision {
            clearance: crate::error::number(clearance),
            magnitude: crate::error::number(prep.magnitude),
            finest: finest.to_string(),
        };
    }
    let at = at.map_or(String::new(), |p| format!(" near ({} {})", p[0], p[1]));
    Error::Unencodable(format!(
        "{max_error}: even keeping every vertex, the rebuilt rings touch or cross{at} on a grid of {finest}, the finest coordinates as large as {} allow",
        crate::error::number(prep.magnitude)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degrees_are_checked() {
        assert!(
            check_degrees(4326, &[("min_radius", Some(0.001)), ("dp_tolerance", None)]).is_ok()
        );
        let e = check_degrees(
            4326,
            &[("min_radius", Some(0.5)), ("max_error", Some(10.0))],
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("max_error: 10;") && e.contains("SRID 4326"),
            "{e}"
        );
    }
    use crate::geom::Kind;

    fn wkb_of(parts: Vec<Vec<Vec<Pt>>>) -> Vec<u8> {
        crate::geom::wkb::write(Kind::Polygon, &parts)
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
        let ct = encode(&wkb_of(sq), &opts(5.0, Some(1.0)), Call::new(0))
            .unwrap()
            .value;
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
        let ct = encode(
            &wkb_of(vec![vec![disc]]),
            &opts(5.0, None),
            Call::new(32760),
        )
        .unwrap()
        .value;
        let ring = &ct.parts[0][0];
        assert!(ring.len() <= 2, "{ring:?}");
        assert!(ring.iter().all(|c| c.r > 0));
    }

    #[test]
    fn bad_parameters_name_themselves() {
        let sq = wkb_of(vec![vec![vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]]]);
        let e = encode(&sq, &opts(0.0, None), Call::new(0)).unwrap_err();
        assert!(matches!(
            e,
            Error::InvalidParameter {
                name: "min_radius",
                ..
            }
        ));
        let e = encode(
            &sq,
            &Options {
                overlap: 1.5,
                ..opts(1.0, None)
            },
            Call::new(0),
        )
        .unwrap_err();
        assert!(matches!(
            e,
            Error::InvalidParameter {
                name: "overlap",
                ..
            }
        ));
        let e = encode(&sq, &opts(1.0, Some(-1.0)), Call::new(0)).unwrap_err();
        assert!(matches!(
            e,
            Error::InvalidParameter {
                name: "dp_tolerance",
                ..
            }
        ));
    }
    /// Both encoders, with every bound given.
    fn both(wkb: &[u8], bounds: &[f64]) -> Vec<Result<CircleTree>> {
        bounds
            .iter()
            .flat_map(|&t| {
                let o = Options {
                    max_error: Some(t),
                    ..opts(t, Some(t))
                };
                [
                    encode(wkb, &o, Call::new(0)).map(|e| e.value),
                    encode_within(wkb, t, Call::new(0)).map(|e| e.value),
                ]
            })
            .collect()
    }

    #[test]
    fn rings_closer_than_a_double_holds_are_nudged_apart_within_the_bound() {
        // two squares near x = 1e6, 5e-10 apart (four units in the last place there): the finest
        // grid at that magnitude is 1e-9, so their facing corners are pushed a few steps apart
        let sq = |x0: f64| {
            vec![vec![
                [x0, 0.0],
                [x0 + 10.0, 0.0],
                [x0 + 10.0, 10.0],
                [x0, 10.0],
            ]]
        };
        let a = 1e6;
        let parts = [sq(a), sq(a + 10.0 + 5e-10)];
        let wkb = crate::geom::wkb::write(Kind::MultiPolygon, &parts);
        for (e, t) in both(&wkb, &[1.0, 0.01])
            .into_iter()
            .zip([1.0, 1.0, 0.01, 0.01])
        {
            let ct = e.unwrap();
            assert_eq!(ct.grid.to_string(), "0.000000001");
            let h = crate::check::metrics::value_hausdorff(&ct, &parts, &mut || {});
            assert!(h <= t, "{h} > {t}");
        }
    }

    #[test]
    fn the_finest_grid_follows_the_magnitude() {
        assert_eq!(finest_grid(1.0).unwrap().to_string(), "0.000000000001");
        assert_eq!(finest_grid(1e6).unwrap().to_string(), "0.000000001");
        // 2^-50 of 5e6 is 4.4e-9
        assert_eq!(finest_grid(5e6).unwrap().to_string(), "0.000000005");
        assert!(finest_grid(1e30).is_none());
        assert_eq!(least_max_error(2f64.powi(47)), 1.0);
    }
}
