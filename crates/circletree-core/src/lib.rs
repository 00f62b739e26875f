//! circletree-core: polygons stored as ordered circles `(x, y, ±r)` and rebuilt from tangents and
//! arcs (the circle tree of Moore 2002), made valid and bounded by a closed loop. Pure Rust, no
//! PostgreSQL: the extension's glue only moves bytes and maps errors.
//!
//! The folders follow the design:
//! - [`geom`]: points, rings and polygons, WKB in and out;
//! - [`encode`]: the two encoders, [`encode::encode`] (the paper's circles, `encode/paper/`) and
//!   [`encode::encode_within`] (the fewest points within a bound), and the closed repair loop both
//!   pass through;
//! - [`check`]: validity of the rebuilt rings and arcs, the quick proof of an input's validity,
//!   and the metrics (sliver area, continuous Hausdorff distance);
//! - [`format`]: the stored bytes (`docs/FORMAT.md`): the grid, decimals, the range coder, format
//!   versions 1 and 2, and the text form;
//! - [`decode`]: from a stored value back to geometry (tangents and arcs), and its picture;
//! - [`access`]: a value rebuilt once, with an edge index, to answer where a point lies and how
//!   far it is (the SQL predicates), and PostGIS's own geometry bytes read in place.
#![forbid(unsafe_code)]

pub mod access;
pub mod check;
pub mod decode;
pub mod encode;
mod error;
pub mod format;
pub mod geom;
mod parallel;

pub use error::{Error, Result};
pub use parallel::set_threads;

/// Not a stable API: the steps the benches of this repository time one by one, and the pieces its
/// measurement examples price designs with (`examples/tokens.rs`, `examples/levels.rs`).
#[doc(hidden)]
pub mod internals {
    pub use crate::encode::min_points::keep as min_points;
    pub use crate::encode::paper::{douglas_peucker, filter, medial};
    pub use crate::format::coder::{class, Bit, IntModel, Meter, Sink};
}

/// Tests' reproducible numbers in `[0, 1)` from a seed (Knuth's MMIX linear congruential
/// generator, its top 53 bits).
#[cfg(test)]
pub(crate) fn test_uniform(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}
