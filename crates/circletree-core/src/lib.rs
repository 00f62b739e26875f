//! circletree-core: store polygons as ordered circles `(x, y, ±r)` and rebuild them from tangents
//! and arcs. Pure Rust, no PostgreSQL: the extension's glue only moves bytes and maps errors.
//!
//! One module per step: [`wkb`] (input/output), [`medial`] (Voronoi circles, paper 3.1),
//! [`filter`] (3.3), [`douglas_peucker`] (3.5), [`min_points`] (fewest points within a tolerance), [`reconstruct`] (tangents and arcs, 3.5),
//! [`validity`], [`encode`] (the pipeline and its closed repair loop), [`picture`] (an SVG of a value), [`format`] (the stored
//! bytes), [`text`] (the text form), [`metrics`] (sliver area, Hausdorff).
#![forbid(unsafe_code)]

pub mod arcs;
pub mod box_grid;
pub mod coder;
pub mod decimal;
pub mod decode;
pub mod douglas_peucker;
pub mod encode;
pub mod error;
pub mod filter;
pub mod format;
pub mod geometry;
pub mod grid;
pub mod medial;
pub mod metrics;
pub mod min_points;
pub mod parallel;
pub mod picture;
pub mod proof;
pub mod reconstruct;
pub mod text;
pub mod touch;
pub mod validity;
pub mod wkb;

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

pub use error::{Error, Result};
