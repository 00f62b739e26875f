//! The paper's encoder steps (Moore 2002, sections 3.1-3.5): candidate circles at the Voronoi
//! vertices of the boundary points ([`medial`]), filtered and mapped to runs of edges
//! ([`filter`]), and Douglas-Peucker points ([`douglas_peucker`]) where no circle covers the
//! boundary. `ct_encode` starts from them; the closed loop ([`super::repair`]) then makes the
//! result valid and bounded.

pub mod douglas_peucker;
pub mod filter;
pub mod medial;
