//! What a plan starts from, per ring: the paper's circles (medial circles filtered and mapped to
//! runs of edges, sections 3.1-3.3) with Douglas-Peucker points where no circle covers the boundary
//! (3.5), or the fewest points within a tolerance alone ([`crate::encode::min_points`]); the input's touch
//! points always. Ordered along the ring by the first vertex each stands for.

use super::paper;
use super::{Options, Report};
use crate::format::grid::Grid;
use crate::geom::Pt;

#[derive(Clone, Copy, Debug)]
pub(super) struct Entry {
    pub(super) c: Pt,
    pub(super) r: f64,
    pub(super) anchor: usize,
    pub(super) repaired: bool,
    /// New, or next to a change, since the last check.
    pub(super) touched: bool,
}

impl Entry {
    /// Vertex `v` of `ring` as a zero-radius circle (`repaired`: added by the closed loop).
    pub(super) fn point(ring: &[Pt], v: usize, repaired: bool) -> Entry {
        Entry {
            c: ring[v],
            r: 0.0,
            anchor: v,
            repaired,
            touched: true,
        }
    }
}

#[allow(clippy::too_many_arguments)]
pub(super) fn initial_entries(
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
    let (kept, dp_points) = if circles {
        paper::circles(ring, opts, max_error, interrupt)
    } else {
        (Vec::new(), None)
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
    entries.extend(pinned.iter().map(|&v| Entry::point(ring, v, false)));
    if !circles {
        // points alone: the fewest within the tolerance, the touch points among them
        if let Some(tol) = opts.dp_tolerance {
            let snap = |p: Pt| [grid.snap(p[0]), grid.snap(p[1])];
            for v in crate::encode::min_points::keep(ring, tol, pinned, &snap, interrupt) {
                if !pinned.contains(&v) {
                    entries.push(Entry::point(ring, v, false));
                    report.dp_points += 1;
                }
            }
        }
    } else if let Some(dp_points) = dp_points {
        for v in paper::uncovered(n, &kept, dp_points) {
            entries.push(Entry::point(ring, v, false));
            report.dp_points += 1;
        }
    }
    if entries.iter().filter(|e| e.r == 0.0).count()
        + 3 * entries.iter().filter(|e| e.r != 0.0).count()
        < 3
    {
        for v in [0, n / 3, 2 * n / 3] {
            entries.push(Entry::point(ring, v, true));
        }
    }
    sort_entries(&mut entries);
    entries
}

pub(super) fn sort_entries(entries: &mut Vec<Entry>) {
    entries.sort_by(|a, b| {
        a.anchor
            .cmp(&b.anchor)
            .then((a.r != 0.0).cmp(&(b.r != 0.0)))
    });
    entries.dedup_by(|b, a| a.anchor == b.anchor && a.r == 0.0 && b.r == 0.0);
}
