//! Filtering the candidate circles (paper section 3.3), in the paper's order:
//!
//! 1. drop circles with `|r| < min_radius`;
//! 2. map to each circle the runs of consecutive ring edges tangential to it within the threshold
//!    (both end points and the middle of each edge within `tol` of the circle, the ring turning
//!    around the centre in the circle's direction), after the paper's averaging step (the radius
//!    becomes the mean distance of the run's vertices); drop runs of fewer than two edges;
//! 3. order the runs by length, longer first (then smaller radius first, which keeps detail);
//! 4. keep a run when it covers at least two edges no kept run covers yet and its circle neither
//!    overlaps a kept circle of the same side beyond `overlap` (penetration depth over the smaller
//!    diameter), nor contains or is contained in one, nor overlaps any circle of the other side
//!    (internal and external circles must stay apart for their tangent to exist). A circle whose
//!    boundary runs come back later in the ring is kept once per run (paper figure 6).
//!
//! Internal circles touching no boundary cannot survive step 2. Cost: O(c·k + c log c) for c
//! candidates and runs of k edges, with a hashed grid of the kept circles.

use crate::encode::paper::medial::Candidate;
use crate::format::grid::round_i64;
use crate::geom::{dist, Pt};
use std::hash::BuildHasher;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A kept circle and the run of ring edges it stands for: edges `start .. start + len` (modulo n).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mapped {
    /// Centre.
    pub c: Pt,
    /// Signed radius.
    pub r: f64,
    /// First vertex of the run.
    pub start: usize,
    /// Number of edges in the run.
    pub len: usize,
}

/// What the walks from one seed around one centre have measured: each edge's cross and dot
/// products seen from the centre and, once asked, the distances of its far end (walking away
/// from the seed) and of its middle from the centre. The walk with the averaged radius reads them
/// again instead of measuring them again (the same numbers, so the same run), and so does the
/// average.
#[derive(Default)]
struct Walked {
    c: Pt,
    seed: usize,
    seed_dist: f64,
    /// Edge `seed + k` to `seed + k + 1`, its far end `seed + k + 1`.
    fwd: Vec<Measured>,
    /// Edge `seed - 1 - j` to `seed - j`, its far end `seed - 1 - j`.
    back: Vec<Measured>,
}

/// One edge seen from a centre; a distance not measured yet is NaN.
#[derive(Clone, Copy)]
struct Measured {
    cross: f64,
    dot: f64,
    end: f64,
    mid: f64,
}

impl Walked {
    fn start(&mut self, ring: &[Pt], c: Pt, seed: usize) {
        self.c = c;
        self.seed = seed;
        self.seed_dist = dist(ring[seed], c);
        self.fwd.clear();
        self.back.clear();
    }

    /// Does edge `k` of the walk (forward or backward from the seed) hug the circle of radius
    /// `r` turning `sign`'s way: does it turn that way around the centre, and are its far end and its
    /// middle within `tol` of the circle? Its cross and dot products, when it does.
    // Inlined into the walks: it is called once an edge a walk, and as a call it would need a frame
    // of its own each time.
    #[inline(always)]
    fn hugs(
        &mut self,
        ring: &[Pt],
        forward: bool,
        k: usize,
        (r, sign, tol): (f64, f64, f64),
    ) -> Option<(f64, f64)> {
        let n = ring.len();
        let (seed, c) = (self.seed, self.c);
        // the edge's ends (`k < n`, so one subtraction wraps each)
        let wrap = |x: usize| if x >= n { x - n } else { x };
        let i = wrap(if forward { seed + k } else { seed + n - 1 - k });
        let (a, b) = (ring[i], ring[wrap(i + 1)]);
        let list = if forward {
            &mut self.fwd
        } else {
            &mut self.back
        };
        // (a walk asks its edges in order, so an edge not measured yet is the next one)
        if list.len() <= k {
            debug_assert_eq!(list.len(), k);
            let (cross, dot) = cross_dot(a, b, c);
            list.push(Measured {
                cross,
                dot,
                end: f64::NAN,
                mid: f64::NAN,
            });
        }
        let m = &mut list[k];
        let on = |d: f64| (d - r).abs() <= tol;
        let turns = m.cross * sign > 0.0;
        if !turns {
            return None;
        }
        if m.end.is_nan() {
            m.end = dist(if forward { b } else { a }, c);
        }
        if !on(m.end) {
            return None;
        }
        if m.mid.is_nan() {
            m.mid = dist([(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0], c);
        }
        on(m.mid).then_some((m.cross, m.dot))
    }

    /// The distance from the centre of the vertex `o` after the seed (before it, negative), on
    /// a run walked already.
    fn vertex(&self, o: isize) -> f64 {
        match o {
            0 => self.seed_dist,
            o if o > 0 => self.fwd[o as usize - 1].end,
            o => self.back[(-o) as usize - 1].end,
        }
    }

    /// The exact turn of the first `fwd` edges forward from the seed, then `back` edges backward,
    /// in the walk's order (all walked already).
    fn exact(&self, fwd: usize, back: usize) -> f64 {
        let mut a = 0.0;
        for m in &self.fwd[..fwd] {
            a += sweep(m.cross, m.dot);
        }
        for m in &self.back[..back] {
            a += sweep(m.cross, m.dot);
        }
        a
    }
}

/// The run of edges around the seed of `w` that hug the circle of radius `rho` about its centre
/// within `tol`: its first vertex, its length and how many of its edges are before the seed.
fn run_at(ring: &[Pt], w: &mut Walked, rho: f64, tol: f64) -> (usize, usize, usize) {
    let n = ring.len();
    let circle = (rho.abs(), rho.signum(), tol);
    // (an edge's other end is the run's last vertex, already tested: the seed, before the walk)
    if (w.seed_dist - rho.abs()).abs() > tol {
        return (w.seed, 0, 0);
    }
    let mut turn = Turn::default();
    let mut len = 0;
    while len < n {
        let Some(m) = w.hugs(ring, true, len, circle) else {
            break;
        };
        if turn.reaches_limit(m, || w.exact(len + 1, 0)) {
            break;
        }
        len += 1;
    }
    let fwd = len;
    while len < n {
        let Some(m) = w.hugs(ring, false, len - fwd, circle) else {
            break;
        };
        if turn.reaches_limit(m, || w.exact(fwd, len - fwd + 1)) {
            break;
        }
        len += 1;
    }
    let back = len - fwd;
    ((w.seed + n - back % n) % n, len, back)
}

/// A run stops before it turns this far around its centre (1.9 half-turns).
const TURN_LIMIT: f64 = std::f64::consts::PI * 1.9;

/// How far a run has turned around its centre. The turn is a sum of `atan2`s (the costliest step
/// of the walk), so it is summed only once a cheap upper bound of it could reach the limit; then
/// from the run's first edge in the walk's order, so that it is the same sum to the bit.
#[derive(Default)]
struct Turn {
    bound: f64,
    exact: Option<f64>,
}

impl Turn {
    /// Walk an edge (its cross and dot products seen from the centre): has the run now turned
    /// [`TURN_LIMIT`]? `so_far` gives the exact turn of every edge walked, this one included, in
    /// the walk's order.
    fn reaches_limit(&mut self, (cross, dot): (f64, f64), so_far: impl FnOnce() -> f64) -> bool {
        let turned = match self.exact.as_mut() {
            Some(t) => {
                *t += sweep(cross, dot);
                *t
            }
            None => {
                self.bound += sweep_bound(cross, dot);
                if self.bound < TURN_LIMIT {
                    return false;
                }
                *self.exact.insert(so_far())
            }
        };
        turned >= TURN_LIMIT
    }
}

/// The cross and dot products of `a` and `b` seen from `c`.
fn cross_dot(a: Pt, b: Pt, c: Pt) -> (f64, f64) {
    let (ua, ub) = ([a[0] - c[0], a[1] - c[1]], [b[0] - c[0], b[1] - c[1]]);
    (ua[0] * ub[1] - ua[1] * ub[0], ua[0] * ub[0] + ua[1] * ub[1])
}

/// An upper bound of [`sweep`] without `atan2`: the angle's tangent (a turn below a right
/// angle), else a half turn; widened far beyond the rounding of either, summed over a whole ring.
fn sweep_bound(cross: f64, dot: f64) -> f64 {
    if dot > 0.0 {
        cross.abs() / dot * (1.0 + 1e-6)
    } else {
        std::f64::consts::PI
    }
}

/// The angle an edge turns around a centre, from their cross and dot products seen from it.
fn sweep(cross: f64, dot: f64) -> f64 {
    cross.atan2(dot).abs()
}

/// The candidates (two lists, one after the other) at least `min_radius` in radius, the first of
/// each cell of `cell` in centre and radius, in their order.
fn distinct<'a>(
    lists: [&'a [Candidate]; 2],
    min_radius: f64,
    cell: f64,
    interrupt: &mut dyn FnMut(),
) -> Vec<&'a Candidate> {
    let total = lists[0].len() + lists[1].len();
    let cand_at = |i: usize| in_two(lists[0], lists[1], i);
    let all = || lists[0].iter().chain(lists[1]);
    let key = |cand: &Candidate| {
        (
            round_i64(cand.c[0] / cell),
            round_i64(cand.c[1] / cell),
            round_i64(cand.r / cell),
        )
    };
    // Fx's hash mixed once more (splitmix64's finalizer), so that its middle bits (which list)
    // are as even as its low ones (the table's)
    let hash = |cand: &Candidate| {
        let mut z = rustc_hash::FxBuildHasher.hash_one(key(cand));
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    };
    // One table of every candidate is larger than the caches on a large ring (a miss for each
    // candidate): the candidates are spread over lists by their hash first, each list with a
    // table of its own that fits. A cell's candidates share a hash, so they meet in one list, in
    // order. On a large ring either half of the candidates is hashed and spread on a thread of
    // its own (each candidate read and hashed once), then either half of the lists is looked
    // through on a thread of its own, the first half's part of a list before the second's.
    let spreads = (total / DISTINCT_LIST).next_power_of_two().min(64);
    // (hash, index): a list is read in order, and a candidate itself only where two hashes are
    // equal (on a large ring, a list's candidates are pages apart)
    let spread = |from: usize, to: usize| -> Vec<Vec<(u64, usize)>> {
        let mut spread: Vec<Vec<(u64, usize)>> = vec![Vec::new(); spreads];
        for (i, cand) in all().enumerate().take(to).skip(from) {
            if cand.r.abs() < min_radius {
                continue;
            }
            let h = hash(cand);
            spread[(h >> 40) as usize % spreads].push((h, i));
        }
        spread
    };
    let large = total as u64 >= crate::parallel::MIN_VERTICES;
    let half = if large { total / 2 } else { total };
    let (first, second) = crate::parallel::join(
        large,
        interrupt,
        |_| spread(0, half),
        |_| spread(half, total),
    );
    let firsts = |which: std::ops::Range<usize>| -> Vec<usize> {
        let mut out = Vec::new();
        let mut table: hashbrown::HashTable<usize> = hashbrown::HashTable::new();
        for l in which {
            let (a, b) = (&first[l], &second[l]);
            let at = |p: usize| *in_two(a, b, p);
            table.clear();
            table.reserve(a.len() + b.len(), |&p| at(p).0);
            for (p, &(h, i)) in a.iter().chain(b).enumerate() {
                let same = |&q: &usize| at(q).0 == h && key(cand_at(at(q).1)) == key(cand_at(i));
                if let hashbrown::hash_table::Entry::Vacant(v) = table.entry(h, same, |&q| at(q).0)
                {
                    v.insert(p);
                    out.push(i);
                }
            }
        }
        out
    };
    let (mut firsts, rest) = crate::parallel::join(
        large,
        interrupt,
        |_| firsts(0..spreads / 2),
        |_| firsts(spreads / 2..spreads),
    );
    firsts.extend(rest);
    let mut keep = vec![false; total];
    for i in firsts {
        keep[i] = true;
    }
    all()
        .zip(keep)
        .filter_map(|(c, k)| k.then_some(c))
        .collect()
}

/// About this many candidates to a list in [`distinct`].
const DISTINCT_LIST: usize = 1 << 15;

/// Steps 1-2: runs of at least two edges for each candidate, radius averaged over its run.
pub fn map_runs(
    ring: &[Pt],
    cands: &[Candidate],
    min_radius: f64,
    tol: f64,
    interrupt: &mut dyn FnMut(),
) -> Runs {
    map_runs_of(ring, [cands, &[]], min_radius, tol, interrupt)
}

/// [`map_runs`] of the candidates of two lists, one after the other (as
/// [`crate::encode::paper::medial::candidate_lists`] gives them).
pub fn map_runs_of(
    ring: &[Pt],
    lists: [&[Candidate]; 2],
    min_radius: f64,
    tol: f64,
    interrupt: &mut dyn FnMut(),
) -> Runs {
    let n = ring.len();
    // Nearly identical circles (cocircular vertices give many) would map the same long runs again
    // and again: keep one per cell of a quarter of the tolerance in centre and radius.
    let cell = (tol / 4.0).max(f64::MIN_POSITIVE);
    let cands = distinct(lists, min_radius, cell, interrupt);
    // Where the vertices of a finely stroked arc are all on one circle, their circumcentres scatter
    // by more than that cell (a circumcircle of three close points is ill-conditioned) and each maps
    // a run of most of the ring: quadratic (hours for ST_Buffer(point, 1e6, 250000) at a tolerance
    // of a millimetre). So the edges walked are counted, and past a budget far above what real
    // boundaries need (at most 146 edges per vertex on both data sets, from 1 m to 500 m; 70 on the
    // synthetic million-vertex coastline), a seed that lies on a run of at least LONG_RUN edges
    // already mapped to a circle of the same side is not walked again.
    let budget = WORK_PER_VERTEX.saturating_mul(n).saturating_add(WORK_FLOOR);
    // On a large ring the candidates' two halves are mapped side by side, the work of both
    // counted together: while it stays within the budget no seed is skipped, as in one pass, so
    // the runs are the same; past it both halves stop and the one pass below decides.
    if n as u64 >= crate::parallel::MIN_VERTICES && crate::parallel::threads() > 1 {
        let shared = AtomicUsize::new(0);
        let (first, second) = cands.split_at(cands.len() / 2);
        let (a, b) = crate::parallel::join(
            true,
            interrupt,
            |i| {
                map_list(
                    ring,
                    first,
                    min_radius,
                    tol,
                    Budget::Shared(&shared, budget),
                    i,
                )
            },
            |i| {
                map_list(
                    ring,
                    second,
                    min_radius,
                    tol,
                    Budget::Shared(&shared, budget),
                    i,
                )
            },
        );
        if let (Some(a), Some(b)) = (a, b) {
            return Runs([a, b]);
        }
    }
    let all = map_list(
        ring,
        &cands,
        min_radius,
        tol,
        Budget::Skip(budget),
        interrupt,
    )
    .unwrap_or_default();
    Runs([all, Vec::new()])
}

/// The runs [`map_runs`] found: one list, then another (a large ring's candidates are mapped in
/// two halves; put together, a hundred megabytes at a million vertices, they were copied for
/// nothing: [`select`] reads them where they are).
#[derive(Clone, Debug, Default)]
pub struct Runs([Vec<Mapped>; 2]);

impl Runs {
    /// Every run, the first list's then the second's.
    pub fn iter(&self) -> impl Iterator<Item = &Mapped> {
        self.0[0].iter().chain(&self.0[1])
    }

    pub fn len(&self) -> usize {
        self.0[0].len() + self.0[1].len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Run `i` of [`Runs::iter`]'s order.
    fn get(&self, i: usize) -> &Mapped {
        in_two(&self.0[0], &self.0[1], i)
    }
}

/// Item `i` of `a` then `b`, read as one list (the lists two threads made, where they are).
fn in_two<'a, T>(a: &'a [T], b: &'a [T], i: usize) -> &'a T {
    match i.checked_sub(a.len()) {
        None => &a[i],
        Some(j) => &b[j],
    }
}

/// How [`map_list`] spends its budget of edges walked.
#[derive(Clone, Copy)]
enum Budget<'a> {
    /// Past the budget, skip seeds lying on a long run of the same side (one pass).
    Skip(usize),
    /// The work of every pass is summed here; past the budget, give up (`None`).
    Shared(&'a AtomicUsize, usize),
}

fn map_list(
    ring: &[Pt],
    cands: &[&Candidate],
    min_radius: f64,
    tol: f64,
    budget: Budget,
    interrupt: &mut dyn FnMut(),
) -> Option<Vec<Mapped>> {
    let n = ring.len();
    let mut out: Vec<Mapped> = Vec::new();
    // long_owner[v] is the last run of at least LONG_RUN edges through vertex v.
    let mut long_owner: Vec<u32> = Vec::new();
    let mut work = 0usize;
    let mut total = 0usize;
    let mut walked = Walked::default();
    for cand in cands {
        // runs already mapped from this candidate's other vertices (three at most)
        let mut seen = [(0usize, 0usize); 3];
        let mut nseen = 0;
        for &seed in &cand.verts {
            if work >= INTERRUPT_WORK {
                interrupt();
                total += work;
                if let Budget::Shared(sum, limit) = budget {
                    if sum.fetch_add(work, Ordering::Relaxed) + work > limit {
                        return None;
                    }
                }
                work = 0;
            }
            if seen[..nseen].iter().any(|&(s, l)| (seed + n - s) % n <= l) {
                continue;
            }
            if let Budget::Skip(limit) = budget {
                if total + work > limit {
                    if let Some(o) = long_owner.get(seed).and_then(|&o| out.get(o as usize)) {
                        if o.r.signum() == cand.r.signum() {
                            continue;
                        }
                    }
                }
            }
            walked.start(ring, cand.c, seed);
            let (s0, l0, back0) = run_at(ring, &mut walked, cand.r, tol);
            work += l0 + 1;
            if l0 < 2 {
                continue;
            }
            // The paper's averaging: fit the radius to the run, then map again with it.
            let mean = (0..=l0)
                .map(|k| walked.vertex(k as isize - back0 as isize))
                .sum::<f64>()
                / (l0 + 1) as f64;
            let rho = mean * cand.r.signum();
            let (s, l, _) = run_at(ring, &mut walked, rho, tol);
            work += 2 * l0 + l;
            let (s, l, rho) = if l >= l0 {
                (s, l, rho)
            } else {
                (s0, l0, cand.r)
            };
            if rho.abs() < min_radius || l < 2 {
                continue;
            }
            seen[nseen] = (s, l);
            nseen += 1;
            if l >= LONG_RUN {
                if let Budget::Skip(_) = budget {
                    if long_owner.is_empty() {
                        long_owner = vec![u32::MAX; n];
                    }
                    let id = u32::try_from(out.len()).unwrap_or(u32::MAX);
                    for k in 0..=l {
                        long_owner[(s + k) % n] = id;
                    }
                }
                work += l;
            }
            out.push(Mapped {
                c: cand.c,
                r: rho,
                start: s,
                len: l,
            });
        }
    }
    if let Budget::Shared(sum, limit) = budget {
        if sum.fetch_add(work, Ordering::Relaxed) + work > limit {
            return None;
        }
    }
    Some(out)
}

/// Runs at least this long mark their vertices (see [`map_runs`]).
const LONG_RUN: usize = 64;
/// The budget of edges walked before a seed on a long run is skipped: this many per vertex...
const WORK_PER_VERTEX: usize = 256;
/// ... and this many more (small rings never reach it).
const WORK_FLOOR: usize = 1 << 22;
/// Edges walked between two calls of the interrupt callback.
const INTERRUPT_WORK: usize = 1 << 18;

/// Steps 3-4: choose the runs that cover the ring, longest first, within the overlap allowance.
pub fn select(n: usize, runs: Runs, overlap: f64, interrupt: &mut dyn FnMut()) -> Vec<Mapped> {
    // Longest first, then smallest radius, then in their order: sorted as one packed integer a
    // run (the same order as a stable sort of the runs by length and radius, and several times
    // quicker than moving the runs themselves; `|r|`'s bits order as it does).
    // On a large ring either half of the runs is sorted and put in order on a thread of its own
    // (the putting in order is random reads, a quarter of `select` at a million vertices), and
    // the loop below takes the two halves' runs in turn by their keys: one order, as one sort.
    let (first, second) = match u32::try_from(runs.len()) {
        Ok(_) => {
            let key = |i: usize, m: &Mapped| {
                let len = u32::try_from(m.len).unwrap_or(u32::MAX);
                (u128::from(!len) << 96) | (u128::from(m.r.abs().to_bits()) << 32) | i as u128
            };
            let sorted = |from: usize, to: usize| {
                let mut keys: Vec<u128> = (from..to).map(|i| key(i, runs.get(i))).collect();
                keys.sort_unstable();
                let ordered: Vec<Mapped> = keys
                    .iter()
                    .map(|&k| *runs.get((k as u32) as usize))
                    .collect();
                (keys, ordered)
            };
            let half = runs.len() / 2;
            crate::parallel::join(
                runs.len() as u64 >= crate::parallel::MIN_VERTICES,
                &mut || {},
                |_| sorted(0, half),
                |_| sorted(half, runs.len()),
            )
        }
        Err(_) => {
            let mut runs: Vec<Mapped> = runs.iter().copied().collect();
            runs.sort_by(|a, b| b.len.cmp(&a.len).then(a.r.abs().total_cmp(&b.r.abs())));
            ((Vec::new(), runs), (Vec::new(), Vec::new()))
        }
    };
    let mut ordered = Merged {
        a: (&first.0, &first.1),
        b: (&second.0, &second.1),
        at: (0, 0),
    };
    // owner[e]: the kept run covering edge e (NONE: none yet)
    const NONE: u32 = u32::MAX;
    let mut owner = vec![NONE; n];
    // covered: the edges with an owner, one bit each (a run's new edges are counted here, a
    // 64th of `owner`'s size, which stays in the cache where `owner` does not)
    let mut covered = Bits::new(n);
    let mut kept: Vec<Mapped> = Vec::new();
    // kept circles by their bounding boxes: two circles can only meet where their boxes do
    let mut grid = KeptGrid::new(&first.1);
    // The runs come in no order along the ring, so each one's first edges are a cache miss
    // (a third of this loop at a million vertices): they are read [`AHEAD`] runs early, and
    // are in the cache when their run's turn comes (a read, not used, is all it takes).
    let mut ahead: std::collections::VecDeque<Mapped> = ordered.by_ref().take(AHEAD).collect();
    let mut early = 0u32;
    let mut k = 0usize;
    while let Some(m) = ahead.pop_front() {
        if let Some(next) = ordered.next() {
            early ^= owner[next.start] ^ covered.words[next.start / 64] as u32;
            ahead.push_back(next);
        }
        // (a million-vertex ring has some 2.6 million runs: a quarter of a second here)
        if k.is_multiple_of(4096) {
            interrupt();
        }
        k += 1;
        let new = m.len - covered.count(m.start, m.len);
        if new < 2 {
            continue;
        }
        let r = m.r.abs();
        let clashes = |o: &Mapped| {
            if o.c == m.c && o.r == m.r {
                return false; // the same circle, another run of it
            }
            let ro = o.r.abs();
            let d = dist(o.c, m.c);
            let depth = r + ro - d;
            if depth <= 0.0 {
                return false;
            }
            if o.r.signum() != m.r.signum() || d + r.min(ro) <= r.max(ro) {
                return true;
            }
            depth / (2.0 * r.min(ro)) > overlap
        };
        // Does the kept circle of any of `count` edges from edge `first` on clash? (the edges
        // in order, wrapping, without a division for each)
        let owners_clash = |first: usize, count: usize| {
            let mut last = NONE;
            // (a loop over two slices: a chained, taken iterator was a call an edge)
            let to = (first + count).min(n);
            for &o in owner[first..to]
                .iter()
                .chain(&owner[..count - (to - first)])
            {
                if o == NONE || o == last {
                    continue;
                }
                last = o;
                if clashes(&kept[o as usize]) {
                    return true;
                }
            }
            false
        };
        // The kept circles of the edges this run shares or touches clash most often, then those
        // of the edges up to a run's length (at least [`NEARBY`]) either side: asked first,
        // they spare most look-ups in the grid (a clash with any kept circle is a clash,
        // whichever is found; at a million vertices 0.79 and 0.21 million of the 1.1 million
        // runs with new edges, leaving the grid 0.12 million).
        let wide = m.len.max(NEARBY);
        if owners_clash((m.start + n - 1) % n, (m.len + 2).min(n))
            || if m.len + 2 * wide >= n {
                owners_clash(0, n)
            } else {
                // the edges beyond those asked, up to `wide` either side
                owners_clash((m.start + n - wide) % n, wide - 1)
                    || owners_clash((m.start + m.len + 1) % n, wide - 1)
            }
        {
            continue;
        }
        let bbox = [m.c[0] - r, m.c[1] - r, m.c[0] + r, m.c[1] + r];
        if grid.any_meeting(&bbox, |o| clashes(&kept[o])) {
            continue;
        }
        let id = u32::try_from(kept.len()).unwrap_or(NONE - 1);
        let wrapped = (m.start + m.len).saturating_sub(n);
        owner[m.start..m.start + m.len - wrapped].fill(id);
        owner[..wrapped].fill(id);
        covered.set(m.start, m.len);
        grid.insert(kept.len(), bbox);
        kept.push(m);
    }
    std::hint::black_box(early);
    kept
}

/// [`select`] asks the kept circles of this many edges either side of a run (at least) before
/// its grid.
const NEARBY: usize = 16;
/// [`select`] reads a run's first edges this many runs before its turn.
const AHEAD: usize = 16;

/// One bit per edge of a ring: is it covered by a kept run?
struct Bits {
    words: Vec<u64>,
    n: usize,
}

impl Bits {
    fn new(n: usize) -> Bits {
        Bits {
            words: vec![0; n.div_ceil(64)],
            n,
        }
    }

    /// Set bits `from..to` (not wrapping, `from <= to <= n`).
    fn set_range(&mut self, from: usize, to: usize) {
        for i in from..to {
            self.words[i / 64] |= 1 << (i % 64);
        }
    }

    /// Bits set among `from..to` (not wrapping).
    fn count_range(&self, from: usize, to: usize) -> usize {
        if from >= to {
            return 0;
        }
        let (fw, tw) = (from / 64, (to - 1) / 64);
        let lo = u64::MAX << (from % 64);
        let hi = u64::MAX >> (63 - (to - 1) % 64);
        if fw == tw {
            return (self.words[fw] & lo & hi).count_ones() as usize;
        }
        let mut c = (self.words[fw] & lo).count_ones() + (self.words[tw] & hi).count_ones();
        for w in &self.words[fw + 1..tw] {
            c += w.count_ones();
        }
        c as usize
    }

    /// Set the `len` bits from `start` on, wrapping (`len <= n`).
    fn set(&mut self, start: usize, len: usize) {
        let end = start + len;
        if end <= self.n {
            self.set_range(start, end);
        } else {
            self.set_range(start, self.n);
            self.set_range(0, end - self.n);
        }
    }

    /// Bits set among the `len` from `start` on, wrapping (`len <= n`).
    fn count(&self, start: usize, len: usize) -> usize {
        let end = start + len;
        if end <= self.n {
            self.count_range(start, end)
        } else {
            self.count_range(start, self.n) + self.count_range(0, end - self.n)
        }
    }
}

/// The runs of two lists each in the order of its keys, taken in turn in the order of all keys
/// (a list without keys is taken first, as it is: [`select`]'s one sorted list of runs).
struct Merged<'a> {
    a: (&'a [u128], &'a [Mapped]),
    b: (&'a [u128], &'a [Mapped]),
    at: (usize, usize),
}

impl Iterator for Merged<'_> {
    type Item = Mapped;

    fn next(&mut self) -> Option<Mapped> {
        let (i, j) = self.at;
        let from_a = match (self.a.1.get(i), self.b.1.get(j)) {
            (None, None) => return None,
            (Some(_), None) => true,
            (None, Some(_)) => false,
            (Some(_), Some(_)) => self
                .a
                .0
                .get(i)
                .zip(self.b.0.get(j))
                .is_none_or(|(x, y)| x < y),
        };
        if from_a {
            self.at.0 += 1;
            Some(self.a.1[i])
        } else {
            self.at.1 += 1;
            Some(self.b.1[j])
        }
    }
}

/// The kept circles of [`select`] by their boxes, for "does any kept circle whose box meets this
/// box clash?": a grid of square cells (about twice a typical diameter), only the cells holding a
/// box stored (hashed), each a list
/// of the circles whose boxes cover it. An R*-tree took two thirds of `select`'s loop at a million
/// vertices (320,000 look-ups and 100,000 inserts, each a walk down the tree); here a look-up is a
/// few hashed cells. Which index answers does not change the answer: every circle whose box meets
/// the box asked about is tested, in any order, some more than once.
struct KeptGrid {
    /// Cells per unit of length.
    per: f64,
    /// A cell's first entry in `links`.
    heads: rustc_hash::FxHashMap<u64, u32>,
    /// (circle, next entry of the same cell or `u32::MAX`).
    links: Vec<(u32, u32)>,
    /// Every circle's box, by circle.
    boxes: Vec<[f64; 4]>,
    /// Circles covering too many cells to be entered in each: tested on every look-up.
    big: Vec<usize>,
}

/// Most cells a circle is entered in (larger ones go to [`KeptGrid::big`]).
const MOST_CELLS: i64 = 1024;

impl KeptGrid {
    /// A grid whose cells are about four times the typical radius of `runs` (sampled).
    fn new(runs: &[Mapped]) -> KeptGrid {
        let step = (runs.len() / 4096).max(1);
        let mut radii: Vec<f64> = runs.iter().step_by(step).map(|m| m.r.abs()).collect();
        let cell = if radii.is_empty() {
            1.0
        } else {
            let mid = radii.len() / 2;
            4.0 * *radii.select_nth_unstable_by(mid, f64::total_cmp).1
        };
        KeptGrid {
            per: if cell.is_finite() && cell > 0.0 {
                1.0 / cell
            } else {
                1.0
            },
            heads: Default::default(),
            links: Vec::new(),
            boxes: Vec::new(),
            big: Vec::new(),
        }
    }

    /// The cell of a coordinate: monotone (a cast truncates toward zero and saturates), which
    /// is all a grid needs for a box to be found in every cell it covers.
    fn cell(&self, v: f64) -> i64 {
        ((v * self.per) as i64).clamp(i64::from(i32::MIN), i64::from(i32::MAX))
    }

    fn cells(&self, b: &[f64; 4]) -> (i64, i64, i64, i64) {
        (
            self.cell(b[0]),
            self.cell(b[1]),
            self.cell(b[2]),
            self.cell(b[3]),
        )
    }

    fn key(x: i64, y: i64) -> u64 {
        ((x as u32 as u64) << 32) | (y as u32 as u64)
    }

    fn insert(&mut self, id: usize, b: [f64; 4]) {
        debug_assert_eq!(id, self.boxes.len());
        self.boxes.push(b);
        let (x0, y0, x1, y1) = self.cells(&b);
        if (x1 - x0 + 1).saturating_mul(y1 - y0 + 1) > MOST_CELLS {
            self.big.push(id);
            return;
        }
        for x in x0..=x1 {
            for y in y0..=y1 {
                let head = self.heads.entry(Self::key(x, y)).or_insert(u32::MAX);
                self.links.push((id as u32, *head));
                *head = (self.links.len() - 1) as u32;
            }
        }
    }

    /// Does `test` hold for any stored circle whose box meets `q` (closed boxes)?
    fn any_meeting(&self, q: &[f64; 4], mut test: impl FnMut(usize) -> bool) -> bool {
        let meets = |b: &[f64; 4]| b[0] <= q[2] && b[2] >= q[0] && b[1] <= q[3] && b[3] >= q[1];
        let mut check = |id: usize| meets(&self.boxes[id]) && test(id);
        if self.big.iter().any(|&id| check(id)) {
            return true;
        }
        let (x0, y0, x1, y1) = self.cells(q);
        if (x1 - x0 + 1).saturating_mul(y1 - y0 + 1) > self.heads.len() as i64 {
            // a box over more cells than hold anything: every circle is asked once
            return (0..self.boxes.len()).any(check);
        }
        for x in x0..=x1 {
            for y in y0..=y1 {
                let mut at = self
                    .heads
                    .get(&Self::key(x, y))
                    .copied()
                    .unwrap_or(u32::MAX);
                while at != u32::MAX {
                    let (id, next) = self.links[at as usize];
                    if check(id as usize) {
                        return true;
                    }
                    at = next;
                }
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::encode::paper::medial::candidates;
    use proptest::prelude::*;

    /// [`Merged`] takes two key-sorted lists in the order one sort of both gives.
    #[test]
    fn runs_in_two_lists_are_selected_as_one() {
        let ring = buffer_disc(1.0e4, 3000);
        let mut wavy = ring.clone();
        for (i, p) in wavy.iter_mut().enumerate() {
            let f = 1.0 + 0.05 * (i as f64 * 0.05).sin();
            *p = [p[0] * f, p[1] * f];
        }
        let c = candidates(&wavy, &mut || {});
        let all: Vec<Mapped> = map_runs(&wavy, &c, 5.0, 1.0, &mut || {})
            .iter()
            .copied()
            .collect();
        assert!(all.len() > 100, "{}", all.len());
        let one = select(wavy.len(), Runs([all.clone(), Vec::new()]), 0.4, &mut || {});
        for cut in [1, all.len() / 3, all.len() - 1] {
            let two = Runs([all[..cut].to_vec(), all[cut..].to_vec()]);
            assert_eq!(two.iter().copied().collect::<Vec<_>>(), all);
            assert_eq!(select(wavy.len(), two, 0.4, &mut || {}), one, "{cut}");
        }
    }

    #[test]
    fn select_can_be_cancelled_as_it_goes() {
        // a wavy ring of 48,000 vertices: tens of thousands of runs, asked every 4,096
        let mut ring = buffer_disc(1.0e4, 12_000);
        for (i, p) in ring.iter_mut().enumerate() {
            let f = 1.0 + 0.05 * (i as f64 * 0.05).sin();
            *p = [p[0] * f, p[1] * f];
        }
        let c = candidates(&ring, &mut || {});
        let runs = map_runs(&ring, &c, 5.0, 1.0, &mut || {});
        let (len, mut asked) = (runs.len(), 0);
        select(ring.len(), runs, 0.4, &mut || asked += 1);
        assert!(
            len >= 3 * 4096 && asked >= len / 4096,
            "{asked} for {len} runs"
        );
    }

    #[test]
    fn merged_halves_are_one_order() {
        let mut next = crate::test_uniform(5);
        let run = |start: usize| Mapped {
            c: [0.0, 0.0],
            r: 1.0,
            start,
            len: 2,
        };
        let mut keys: Vec<u128> = (0..1000u128)
            .map(|i| ((next() * 50.0) as u128) << 32 | i)
            .collect();
        let (mut a, mut b) = (keys[..400].to_vec(), keys[400..].to_vec());
        a.sort_unstable();
        b.sort_unstable();
        keys.sort_unstable();
        let runs_of = |k: &[u128]| {
            k.iter()
                .map(|&k| run(k as u32 as usize))
                .collect::<Vec<_>>()
        };
        let (ra, rb) = (runs_of(&a), runs_of(&b));
        let merged: Vec<usize> = Merged {
            a: (&a, &ra),
            b: (&b, &rb),
            at: (0, 0),
        }
        .map(|m| m.start)
        .collect();
        let want: Vec<usize> = keys.iter().map(|&k| k as u32 as usize).collect();
        assert_eq!(merged, want);
        // one list without keys: itself
        let all = runs_of(&keys);
        let alone: Vec<usize> = Merged {
            a: (&[], &all),
            b: (&[], &[]),
            at: (0, 0),
        }
        .map(|m| m.start)
        .collect();
        assert_eq!(alone, want);
    }

    /// [`KeptGrid`] finds what testing every stored box finds: circles from metres to far larger
    /// than the cells (entered as big ones), asked about with boxes as small as a point and as
    /// large as everything, with a test that holds for some circles only.
    #[test]
    fn kept_grid_finds_what_every_box_finds() {
        let mut next = crate::test_uniform(11);
        let runs: Vec<Mapped> = (0..2000)
            .map(|i| Mapped {
                c: [next() * 50_000.0 - 25_000.0, next() * 50_000.0 + 1e6],
                r: (next() * 40.0 + 1.0) * if i % 97 == 0 { 500.0 } else { 1.0 },
                start: i,
                len: 2,
            })
            .collect();
        let mut grid = KeptGrid::new(&runs);
        let boxes: Vec<[f64; 4]> = runs
            .iter()
            .map(|m| [m.c[0] - m.r, m.c[1] - m.r, m.c[0] + m.r, m.c[1] + m.r])
            .collect();
        for (id, b) in boxes.iter().enumerate().take(1500) {
            grid.insert(id, *b);
        }
        assert!(
            !grid.big.is_empty(),
            "some circles must be too large for the cells"
        );
        let meets = |b: &[f64; 4], q: &[f64; 4]| {
            b[0] <= q[2] && b[2] >= q[0] && b[1] <= q[3] && b[3] >= q[1]
        };
        let (mut yes, mut no) = (0, 0);
        for (k, m) in runs.iter().enumerate() {
            let r = if k % 50 == 0 {
                1e7
            } else {
                m.r * (k % 3) as f64
            };
            let q = [m.c[0] - r, m.c[1] - r, m.c[0] + r, m.c[1] + r];
            // a test that holds for a third of the circles (of the small ones, every other time)
            let test =
                |id: usize| id % 3 == k % 3 && (k.is_multiple_of(2) || !id.is_multiple_of(97));
            let want = (0..1500).any(|id| meets(&boxes[id], &q) && test(id));
            assert_eq!(grid.any_meeting(&q, test), want, "query {k}");
            if want {
                yes += 1;
            } else {
                no += 1;
            }
        }
        assert!(
            yes > 100 && no > 100,
            "{yes} found, {no} not: both must be tested"
        );
    }

    /// [`Bits`] counts what a list of booleans counts, for runs that start and end anywhere in
    /// a word, span several words and wrap, on rings of lengths around word sizes.
    #[test]
    fn bits_count_what_a_list_of_flags_counts() {
        let mut seed = 7u64;
        let mut next = |m: usize| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) as usize % m
        };
        for n in [1, 2, 63, 64, 65, 127, 128, 129, 300] {
            let mut bits = Bits::new(n);
            let mut flags = vec![false; n];
            for _ in 0..200 {
                let (start, len) = (next(n), next(n + 1));
                if next(3) == 0 {
                    bits.set(start, len);
                    for k in 0..len {
                        flags[(start + k) % n] = true;
                    }
                }
                let want = (0..len).filter(|k| flags[(start + k) % n]).count();
                assert_eq!(
                    bits.count(start, len),
                    want,
                    "n {n} start {start} len {len}"
                );
            }
        }
    }

    /// [`distinct`] keeps the first candidate of each cell, in order, the same as one plain set
    /// would: here on enough candidates to be spread over many lists and two threads, most of
    /// them sharing a cell with others far before or after them in the list.
    #[test]
    fn distinct_keeps_the_first_of_each_cell_in_order() {
        let mut next = crate::test_uniform(7);
        let cands: Vec<Candidate> = (0..300_000)
            .map(|i| Candidate {
                c: [next() * 300.0 - 150.0, next() * 300.0 - 150.0],
                r: (next() * 40.0 - 20.0).round() * if i % 7 == 0 { 0.01 } else { 1.0 },
                verts: [i, i + 1, i + 2],
            })
            .collect();
        let (min_radius, cell) = (0.5, 2.5);
        let mut seen = std::collections::HashSet::new();
        let expected: Vec<[usize; 3]> = cands
            .iter()
            .filter(|c| {
                c.r.abs() >= min_radius
                    && seen.insert((
                        (c.c[0] / cell).round() as i64,
                        (c.c[1] / cell).round() as i64,
                        (c.r / cell).round() as i64,
                    ))
            })
            .map(|c| c.verts)
            .collect();
        assert!(
            expected.len() > 10_000 && expected.len() < 200_000,
            "{}",
            expected.len()
        );
        // one list, or the same cut in two anywhere (as the candidates come from two threads)
        for cut in [300_000, 0, 1, 123_457, 299_999] {
            let (a, b) = cands.split_at(cut);
            let got: Vec<[usize; 3]> = distinct([a, b], min_radius, cell, &mut || {})
                .iter()
                .map(|c| c.verts)
                .collect();
            assert_eq!(got, expected, "cut at {cut}");
        }
    }

    proptest! {
        /// The walk sums exact turns only once the bound could reach the limit: the bound must
        /// never be below the turn, whatever the edge (short or long, near or far, UTM-sized).
        #[test]
        fn the_turn_bound_is_never_below_the_turn(
            c in (-1e7f64..1e7, -1e7f64..1e7),
            a in (-1e4f64..1e4, -1e4f64..1e4),
            b in (-1e4f64..1e4, -1e4f64..1e4),
            scale in prop::sample::select(vec![1e-6, 1e-3, 1.0, 1e3]),
        ) {
            let c = [c.0, c.1];
            let a = [c[0] + a.0 * scale, c[1] + a.1 * scale];
            let b = [c[0] + b.0 * scale, c[1] + b.1 * scale];
            let (cross, dot) = cross_dot(a, b, c);
            prop_assert!(sweep_bound(cross, dot) >= sweep(cross, dot));
        }
    }

    fn buffer_disc(r: f64, segs_per_quarter: usize) -> Vec<Pt> {
        let n = 4 * segs_per_quarter;
        (0..n)
            .map(|i| {
                let t = i as f64 / n as f64 * std::f64::consts::TAU;
                [1000.0 + r * t.cos(), 2000.0 + r * t.sin()]
            })
            .collect()
    }

    #[test]
    fn disc_maps_to_few_circles() {
        let ring = buffer_disc(100.0, 8);
        let c = candidates(&ring, &mut || {});
        let runs = map_runs(&ring, &c, 5.0, 1.0, &mut || {});
        let kept = select(ring.len(), runs, 0.4, &mut || {});
        assert!(!kept.is_empty() && kept.len() <= 2, "{kept:?}");
        assert!(kept
            .iter()
            .all(|m| (m.r - 100.0).abs() < 1.0 && dist(m.c, [1000.0, 2000.0]) < 1.0));
    }

    #[test]
    fn halves_mapped_apart_are_the_one_pass_within_the_budget() {
        // a wavy ring: many candidates of both sides, runs of all lengths
        let ring: Vec<Pt> = (0..6000)
            .map(|i| {
                let t = i as f64 / 6000.0 * std::f64::consts::TAU;
                let r = 10_000.0 + 300.0 * (17.0 * t).sin() + 40.0 * (131.0 * t).sin();
                [r * t.cos(), r * t.sin()]
            })
            .collect();
        let c = candidates(&ring, &mut || {});
        let cands: Vec<&Candidate> = c.iter().collect();
        let one = map_list(
            &ring,
            &cands,
            5.0,
            1.0,
            Budget::Skip(usize::MAX),
            &mut || {},
        )
        .unwrap_or_default();
        assert!(one.len() > 100, "{}", one.len());
        let (a, b) = cands.split_at(cands.len() / 3);
        let sum = AtomicUsize::new(0);
        let mut both = map_list(
            &ring,
            a,
            5.0,
            1.0,
            Budget::Shared(&sum, usize::MAX),
            &mut || {},
        )
        .unwrap_or_default();
        both.extend(
            map_list(
                &ring,
                b,
                5.0,
                1.0,
                Budget::Shared(&sum, usize::MAX),
                &mut || {},
            )
            .unwrap_or_default(),
        );
        let key = |m: &Mapped| {
            (
                m.c[0].to_bits(),
                m.c[1].to_bits(),
                m.r.to_bits(),
                m.start,
                m.len,
            )
        };
        assert_eq!(
            one.iter().map(key).collect::<Vec<_>>(),
            both.iter().map(key).collect::<Vec<_>>()
        );
        // past the budget a half gives up, and map_runs falls back to the one pass
        let small = AtomicUsize::new(0);
        assert!(map_list(
            &ring,
            &cands,
            5.0,
            1.0,
            Budget::Shared(&small, 10),
            &mut || {}
        )
        .is_none());
    }

    #[test]
    fn a_finely_stroked_disc_maps_its_circle_once_not_once_per_vertex() {
        // ST_Buffer(point, 1e5, 25000): 100,000 vertices all on one circle. Their circumcentres
        // scatter by more than the dedup cell, and each candidate's run is most of the ring: every
        // vertex walking the whole ring again was quadratic (hours at a million vertices, and not
        // cancellable), and the edges it maps are what `select` walks again.
        let ring = buffer_disc(1.0e5, 25_000);
        let c = candidates(&ring, &mut || {});
        let mut calls = 0;
        let runs = map_runs(&ring, &c, 0.001, 0.0005, &mut || calls += 1);
        // edges mapped in all: about 55 per vertex (it was 14,646 runs, 4,400 per vertex)
        let mapped: usize = runs.iter().map(|m| m.len).sum();
        assert!(
            mapped < 256 * ring.len(),
            "{} runs, {mapped} edges",
            runs.len()
        );
        assert!(runs.iter().any(|m| m.len > ring.len() / 2));
        let kept = select(ring.len(), runs, 0.4, &mut || {});
        assert!(kept.iter().all(|m| (m.r - 1.0e5).abs() < 0.01), "{kept:?}");
        assert!(calls >= 1);
    }

    #[test]
    fn min_radius_drops_everything_small() {
        let ring = buffer_disc(10.0, 8);
        let c = candidates(&ring, &mut || {});
        assert!(map_runs(&ring, &c, 11.0, 1.0, &mut || {}).is_empty());
    }
}
