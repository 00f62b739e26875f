//! What the encoders check of a rebuilt value, and how the metrics measure it: OGC validity of
//! the stroked rings ([`validity`]) and of the true arcs ([`arcs`]), the input's touch points, the
//! only points where rebuilt rings may meet ([`touch`]), the quick proof that an input is valid
//! ([`proof`]), and the distances and areas between a value and its original ([`metrics`]).

pub(crate) mod arcs;
pub(crate) mod metrics;
pub(crate) mod proof;
pub(crate) mod touch;
pub(crate) mod validity;

pub use metrics::{measure_tolerance, shape_hausdorff, value_hausdorff, value_sliver};
pub use proof::proves_valid;
pub use validity::{problems, RingRef};
