//! The grid every stored coordinate lies on, and the one routine that turns grid steps into
//! coordinates. The encoder checks exactly the points the decoder will produce because both call
//! [`Grid::coord`]: `q × mantissa / 10^k` (or `× 10^k`) in one correctly rounded operation, never
//! `q × step` (which differs in the last bit on grids such as 0.1).

use crate::decimal::Decimal;

/// Smallest and largest grid exponent a stored value may have (`step` in 1e-12 ..= 9e12).
pub const MIN_EXP: i8 = -12;
/// See [`MIN_EXP`].
pub const MAX_EXP: i8 = 12;

/// A grid step, `mantissa × 10^exp`, ready to convert grid steps to coordinates and back.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    step: Decimal,
    m: f64,
    p: f64,
    divide: bool,
    f: f64,
}

impl Grid {
    /// The grid of `step` (positive; stored values keep the exponent within [`MIN_EXP`, `MAX_EXP`]).
    pub fn new(step: Decimal) -> Grid {
        let e = step.exp as i32;
        Grid {
            step,
            m: step.mantissa as f64,
            p: 10f64.powi(e.abs()),
            divide: e < 0,
            f: step.to_f64(),
        }
    }

    /// Can a stored value have this step?
    pub fn storable(step: Decimal) -> bool {
        step.mantissa > 0 && (MIN_EXP..=MAX_EXP).contains(&step.exp)
    }

    /// The step as an exact decimal.
    pub fn step(&self) -> Decimal {
        self.step
    }

    /// The step as the nearest `f64`.
    pub fn step_f64(&self) -> f64 {
        self.f
    }

    /// Grid steps to a coordinate: what `ct_decode` produces.
    #[inline]
    pub fn coord(&self, q: i64) -> f64 {
        let v = q as f64 * self.m;
        if self.divide {
            v / self.p
        } else {
            v * self.p
        }
    }

    /// The nearest grid step of a coordinate.
    #[inline]
    pub fn quantize(&self, v: f64) -> i64 {
        (v / self.f).round() as i64
    }

    /// A coordinate moved to the grid, as the decoder will give it back.
    #[inline]
    pub fn snap(&self, v: f64) -> f64 {
        self.coord(self.quantize(v))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coord_is_the_decimal_not_the_float_product() {
        let g = Grid::new(Decimal::parse("0.1").unwrap());
        // 3 × 0.1 is 0.30000000000000004 in f64; the decimal 0.3 is what users get.
        assert_eq!(g.coord(3), 0.3);
        assert_ne!(3.0 * g.step_f64(), 0.3);
        assert_eq!(g.quantize(0.30000000000000004), 3);
        let big = Grid::new(Decimal::parse("5e3").unwrap());
        assert_eq!(big.coord(-7), -35000.0);
        assert!(Grid::storable(Decimal::parse("1e-12").unwrap()));
        assert!(!Grid::storable(Decimal::parse("1e-13").unwrap()));
    }
}
