//! The grid every stored coordinate lies on, and the one routine that turns grid steps into
//! coordinates. The encoder checks exactly the points the decoder will produce because both call
//! [`Grid::coord`]: `q × mantissa / 10^k` (or `× 10^k`) in one correctly rounded operation, never
//! `q × step` (which differs in the last bit on grids such as 0.1).

use crate::format::decimal::Decimal;

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
        round_i64(v / self.f)
    }

    /// A coordinate moved to the grid, as the decoder will give it back.
    #[inline]
    pub fn snap(&self, v: f64) -> f64 {
        self.coord(self.quantize(v))
    }
}

/// `v.round() as i64` for every `v` (halves away from zero; NaN 0; beyond the range of `i64`
/// its ends), without a call: `round` is a libm call on baseline x86-64, and this is asked
/// millions of times an encode.
#[inline]
pub fn round_i64(v: f64) -> i64 {
    // from 2^52 on every f64 is a whole number already (and NaN and the infinities are cast too)
    if v.is_nan() || v.abs() >= 4_503_599_627_370_496.0 {
        return v as i64;
    }
    // toward zero, then the fraction left (exact below 2^52)
    let t = v as i64;
    let frac = v - t as f64;
    // without branches: which way a fraction goes is a coin toss, and a mispredicted branch
    // costs more than `round`'s call
    t + i64::from(frac >= 0.5) - i64::from(frac <= -0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`round_i64`] is `round` then a cast, on halves, their neighbours, both signs, every
    /// magnitude and the values that are not numbers.
    #[test]
    fn round_i64_is_round_then_cast() {
        let mut vals = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -2.5,
            0.49999999999999994,
            -0.49999999999999994,
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
            4_503_599_627_370_496.0,
            9.3e18,
            -9.3e18,
            1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            f64::MIN_POSITIVE,
        ];
        for k in 0..60 {
            let h = 2f64.powi(k) + 0.5;
            vals.extend([
                h,
                -h,
                h.next_up(),
                h.next_down(),
                -h.next_up(),
                -h.next_down(),
            ]);
        }
        let mut uniform = crate::test_uniform(3);
        for _ in 0..100_000 {
            let v = (uniform() - 0.5) * 10f64.powi((uniform() * 40.0) as i32 - 20);
            vals.push(v);
        }
        for v in vals {
            assert_eq!(round_i64(v), v.round() as i64, "{v:e}");
        }
    }

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
