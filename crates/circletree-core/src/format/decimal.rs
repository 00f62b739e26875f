//! Exact decimal numbers `mantissa × 10^exp`, used for the grid and the encoding parameters so
//! that they are stored in 2-4 bytes and print and parse back exactly.

use std::fmt;

/// `mantissa × 10^exp`, normalized: the mantissa has no trailing zero (zero is `0e0`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Decimal {
    /// Signed digits.
    pub mantissa: i64,
    /// Power of ten.
    pub exp: i8,
}

impl Decimal {
    /// Build and normalize; `None` when the exponent leaves `i8`.
    pub fn new(mut mantissa: i64, exp: i32) -> Option<Decimal> {
        let mut exp = exp;
        if mantissa == 0 {
            return Some(Decimal {
                mantissa: 0,
                exp: 0,
            });
        }
        while mantissa % 10 == 0 {
            mantissa /= 10;
            exp += 1;
        }
        Some(Decimal {
            mantissa,
            exp: i8::try_from(exp).ok()?,
        })
    }

    /// The shortest decimal that reads back as `v` (Rust's float formatting is shortest-round-trip).
    ///
    /// ```
    /// use circletree_core::format::Decimal;
    /// assert_eq!(Decimal::from_f64(0.4).unwrap(), Decimal { mantissa: 4, exp: -1 });
    /// assert_eq!(Decimal::from_f64(0.4).unwrap().to_f64(), 0.4);
    /// ```
    pub fn from_f64(v: f64) -> Option<Decimal> {
        if !v.is_finite() {
            return None;
        }
        Decimal::parse(&format!("{v:e}"))
    }

    /// The nearest `f64`.
    pub fn to_f64(self) -> f64 {
        // Clinger's fast path: a mantissa and a power of ten both exact in f64, one correctly
        // rounded operation, so the nearest f64 (what parsing gives); else parse the digits.
        const POW10: [f64; 23] = [
            1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
            1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
        ];
        let e = usize::from(self.exp.unsigned_abs());
        if self.mantissa.unsigned_abs() < 1 << 53 && e < POW10.len() {
            let m = self.mantissa as f64;
            return if self.exp < 0 {
                m / POW10[e]
            } else {
                m * POW10[e]
            };
        }
        format!("{}e{}", self.mantissa, self.exp)
            .parse()
            .unwrap_or(f64::NAN)
    }

    /// Parse `-12.5`, `3`, `1e-7`, `2.50E+3`. `None` on anything else or on overflow.
    pub fn parse(s: &str) -> Option<Decimal> {
        let (num, exp) = match s.find(['e', 'E']) {
            Some(i) => (&s[..i], s[i + 1..].parse::<i32>().ok()?),
            None => (s, 0),
        };
        let (neg, digits) = match num.strip_prefix('-') {
            Some(rest) => (true, rest),
            None => (false, num.strip_prefix('+').unwrap_or(num)),
        };
        let (int, frac) = match digits.find('.') {
            Some(i) => (&digits[..i], &digits[i + 1..]),
            None => (digits, ""),
        };
        if int.is_empty() && frac.is_empty() {
            return None;
        }
        if !int.bytes().chain(frac.bytes()).all(|b| b.is_ascii_digit()) {
            return None;
        }
        let all = format!("{int}{frac}");
        // trailing zeros go to the exponent, so that a mantissa of many zeros fits i64: the text
        // form prints 51e20 as 5100000000000000000000, and that must read back
        let trimmed = all.trim_start_matches('0');
        let digits = trimmed.trim_end_matches('0');
        let zeros = i32::try_from(trimmed.len() - digits.len()).ok()?;
        let mut m: i64 = if digits.is_empty() {
            0
        } else {
            digits.parse().ok()?
        };
        if neg {
            m = -m;
        }
        let frac_len = i32::try_from(frac.len()).ok()?;
        Decimal::new(m, exp.checked_sub(frac_len)?.checked_add(zeros)?)
    }

    /// Exact `value / self` when that is an integer (`self` must be positive).
    pub fn divide_exact(self, value: Decimal) -> Option<i64> {
        let (vm, ve) = (value.mantissa as i128, value.exp as i32);
        let (gm, ge) = (self.mantissa as i128, self.exp as i32);
        if gm <= 0 {
            return None;
        }
        let num = if ve >= ge {
            vm.checked_mul(10i128.checked_pow(u32::try_from(ve - ge).ok()?)?)?
        } else {
            let p = 10i128.checked_pow(u32::try_from(ge - ve).ok()?)?;
            if vm % p != 0 {
                return None;
            }
            vm / p
        };
        if num % gm != 0 {
            return None;
        }
        i64::try_from(num / gm).ok()
    }

    /// `q × self` as an exact decimal.
    pub fn times(self, q: i64) -> Option<Decimal> {
        Decimal::new(self.mantissa.checked_mul(q)?, self.exp as i32)
    }
}

impl fmt::Display for Decimal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let neg = self.mantissa < 0;
        let digits = self.mantissa.unsigned_abs().to_string();
        let sign = if neg { "-" } else { "" };
        let e = self.exp as i32;
        if e >= 0 {
            if e > 20 {
                return write!(f, "{sign}{digits}e{e}");
            }
            write!(f, "{sign}{digits}{}", "0".repeat(e as usize))
        } else {
            let shift = (-e) as usize;
            if shift > 24 {
                return write!(f, "{sign}{digits}e{e}");
            }
            if digits.len() > shift {
                let (a, b) = digits.split_at(digits.len() - shift);
                write!(f, "{sign}{a}.{b}")
            } else {
                write!(f, "{sign}0.{}{digits}", "0".repeat(shift - digits.len()))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn many_trailing_zeros_read_back() {
        // found by the text fuzz target: max_error=51e+020 printed as 22 digits that did not parse
        let d = Decimal::parse("51e+020").unwrap();
        assert_eq!(
            d,
            Decimal {
                mantissa: 51,
                exp: 20
            }
        );
        assert_eq!(Decimal::parse(&d.to_string()), Some(d));
        assert_eq!(Decimal::parse("5100000000000000000000.000"), Some(d));
        assert_eq!(Decimal::parse("-0.000"), Decimal::new(0, 0));
    }

    #[test]
    fn prints_and_parses() {
        for (s, m, e) in [
            ("0.4", 4, -1),
            ("5", 5, 0),
            ("250", 25, 1),
            ("-0.005", -5, -3),
            ("0", 0, 0),
        ] {
            let d = Decimal::parse(s).unwrap();
            assert_eq!((d.mantissa, d.exp), (m, e as i8), "{s}");
            assert_eq!(d.to_string(), s);
        }
        assert_eq!(Decimal::parse("1e-7").unwrap().to_string(), "0.0000001");
        assert!(Decimal::parse("1.2.3").is_none());
        assert!(Decimal::parse("").is_none());
        assert!(Decimal::parse("abc").is_none());
    }

    #[test]
    fn exact_division() {
        let grid = Decimal::parse("0.5").unwrap();
        assert_eq!(
            grid.divide_exact(Decimal::parse("751223.5").unwrap()),
            Some(1502447)
        );
        assert_eq!(
            grid.divide_exact(Decimal::parse("751223.25").unwrap()),
            None
        );
        assert_eq!(grid.times(1502447).unwrap().to_string(), "751223.5");
    }

    proptest! {
        #[test]
        fn f64_round_trip(v in -1e12f64..1e12) {
            let d = Decimal::from_f64(v).unwrap();
            prop_assert_eq!(d.to_f64(), v);
            prop_assert_eq!(Decimal::parse(&d.to_string()), Some(d));
        }
    }

    #[test]
    fn the_fast_path_reads_as_parsing_does() {
        let mut u = crate::test_uniform(5);
        for _ in 0..20000 {
            let m = ((u() - 0.5) * 2f64.powi(54)) as i64 >> (u() * 50.0) as u32;
            let exp = (u() * 60.0) as i32 - 30;
            let Some(d) = Decimal::new(m, exp) else {
                continue;
            };
            let parsed: f64 = format!("{}e{}", d.mantissa, d.exp).parse().unwrap();
            assert_eq!(d.to_f64().to_bits(), parsed.to_bits(), "{d:?}");
        }
    }
}
