//! The paper's encoder steps (Moore 2002, sections 3.1-3.5): candidate circles at the Voronoi
//! vertices of the boundary points ([`medial`]), filtered and mapped to runs of edges
//! ([`filter`]), and Douglas-Peucker points ([`douglas_peucker`]) where no circle covers the
//! boundary. `ct_encode` starts from them; the closed loop ([`super::repair`]) then makes the
//! result valid and bounded.

pub mod douglas_peucker;
pub mod filter;
pub mod medial;

use super::Options;
use crate::geom::Pt;
use filter::Mapped;

/// The paper's circles of one ring (sections 3.1-3.3), and its Douglas-Peucker points when
/// `opts.dp_tolerance` asks for them (3.5). `max_error / 2` is how far a circle may stray from the
/// edges it stands for.
pub(crate) fn circles(
    ring: &[Pt],
    opts: &Options,
    max_error: f64,
    interrupt: &mut dyn FnMut(),
) -> (Vec<Mapped>, Option<Vec<usize>>) {
    let n = ring.len();
    // Douglas-Peucker's points need nothing of the circles: on a large ring they are found
    // beside the triangulation (its insertion runs on one thread; `select` uses two).
    let (cands, dp_points) = crate::parallel::join(
        n as u64 >= crate::parallel::MIN_VERTICES,
        interrupt,
        |i| medial::candidate_lists(ring, i),
        |_| opts.dp_tolerance.map(|dp| douglas_peucker::keep(ring, dp)),
    );
    let [first, second] = &cands;
    let runs = filter::map_runs_of(
        ring,
        [first, second],
        opts.min_radius,
        max_error / 2.0,
        interrupt,
    );
    drop(cands);
    interrupt();
    (filter::select(n, runs, opts.overlap, interrupt), dp_points)
}

/// The Douglas-Peucker points no kept circle covers: a vertex on a kept run (its ends included,
/// since a point on a circle has a degenerate tangent to it) is left to the circle.
pub(crate) fn uncovered(n: usize, kept: &[Mapped], dp_points: Vec<usize>) -> Vec<usize> {
    let mut covered = vec![false; n];
    for m in kept {
        for k in 0..=m.len {
            covered[(m.start + k) % n] = true;
        }
    }
    dp_points.into_iter().filter(|&v| !covered[v]).collect()
}
