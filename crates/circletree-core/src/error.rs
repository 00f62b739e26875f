//! Every error the core can report. The pgrx glue maps each variant to a SQLSTATE
//! (see `src/error.rs` in the extension) and adds a hint; nothing here panics.

use thiserror::Error;

/// A number as an error message shows it: plainly, or in exponent form when it is very large or
/// very small (`1e-300`, not three hundred zeros).
pub fn number(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && a.is_finite() && !(1e-6..1e16).contains(&a) {
        format!("{v:e}")
    } else {
        v.to_string()
    }
}

/// Errors of the circletree core.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Error {
    /// A parameter is outside its valid range (SQLSTATE 22023).
    #[error("invalid value for {name}: {value}; {name} must be {range}")]
    InvalidParameter {
        /// The parameter's SQL name.
        name: &'static str,
        /// The value received, as text.
        value: String,
        /// The valid range, in words.
        range: String,
    },
    /// The geometry is of a type circletree does not encode (SQLSTATE 22023).
    #[error("circletree encodes Polygon and MultiPolygon geometries, not {0}")]
    UnsupportedGeometry(String),
    /// A coordinate is NaN or infinite (SQLSTATE 22023).
    #[error("the geometry has a non-finite coordinate ({0})")]
    NonFinite(String),
    /// The input polygon is not valid (SQLSTATE 22023).
    #[error("the input polygon is not valid: {0}")]
    InvalidPolygon(String),
    /// The input WKB could not be read (SQLSTATE 22023).
    #[error("could not read the input geometry: {0}")]
    BadWkb(String),
    /// Stored or received circletree bytes are corrupt (SQLSTATE 22P03).
    #[error("corrupt circletree value: {0}")]
    Corrupt(String),
    /// The text form could not be parsed (SQLSTATE 22P02).
    #[error(
        "invalid input syntax for type circletree: expected {expected} at character {position}"
    )]
    Syntax {
        /// What the parser expected.
        expected: String,
        /// 1-based character position in the input.
        position: usize,
    },
    /// The result would exceed what PostgreSQL can hold in one value (SQLSTATE 54000).
    #[error("{0}")]
    TooLarge(String),
    /// Two rings come closer to each other than the finest grid coordinates of this magnitude
    /// allow can hold apart (SQLSTATE 22023).
    #[error(
        "could not encode the polygon: its rings come within {clearance} of each other (its minimum clearance), and coordinates as large as {magnitude} allow no grid finer than {finest}, which cannot hold rings so close apart"
    )]
    BeyondPrecision {
        /// The input's minimum clearance.
        clearance: String,
        /// Its largest absolute coordinate.
        magnitude: String,
        /// The finest grid they allow.
        finest: String,
    },
    /// The encoder could not produce a valid reconstruction within the error bound (SQLSTATE 22023).
    #[error("could not encode the polygon within max_error {0}")]
    Unencodable(String),
}

/// Result with the core's error.
pub type Result<T> = std::result::Result<T, Error>;

#[cfg(test)]
mod tests {
    #[test]
    fn numbers_stay_short() {
        assert_eq!(super::number(1e-300), "1e-300");
        assert_eq!(super::number(-1e300), "-1e300");
        assert_eq!(super::number(0.4), "0.4");
        assert_eq!(super::number(f64::NAN), "NaN");
        assert_eq!(super::number(-1.0), "-1");
    }
}
