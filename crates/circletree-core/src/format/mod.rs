//! The stored bytes of a `circletree` value. `docs/FORMAT.md` describes them byte by byte. Every
//! version shares the header; the circles follow in the version's own form: [`v1`] (zigzag
//! varints, frozen) or [`v2`] (range-coded, written by this release).
//!
//! ```text
//! u8  version (1 or 2)       u8  kind (3 Polygon, 6 MultiPolygon)
//! varint srid (zigzag)       decimal grid            (decimal = zigzag varint mantissa, i8 exponent)
//! decimal min_radius         decimal overlap         option<decimal> dp_tolerance   decimal max_error
//! varint vertices            varint wkb_bytes        varint repaired
//! varint nparts              [if nparts > 0: zigzag xmin, zigzag ymin, varint width, varint height]
//! v1: per part: varint nrings; per ring: varint ncircles; per circle: zigzag dx, zigzag dy, zigzag r
//! v2: one range-coded stream of the same counts and circles (points without a radius)
//! ```
//! Coordinates are integers on the grid. `dx, dy` are deltas from the previous circle's centre,
//! running through every ring of every part, starting at `(xmin, ymin)`.
//!
//! Decoding trusts no count: a count is checked against the bytes that remain before anything is
//! allocated for it, every sum is checked for overflow, and every field is range-checked.

use crate::error::{Error, Result};
use crate::geom::Kind;
use serde::de::DeserializeOwned;
use serde::Serialize;

pub(crate) mod coder;
pub(crate) mod decimal;
pub(crate) mod grid;
pub(crate) mod text;
pub(crate) mod v1;
pub(crate) mod v2;

pub use decimal::Decimal;
pub use text::{from_text, to_text};

/// The version byte written by this release.
pub const FORMAT_VERSION: u8 = 2;
/// Every version this release reads.
pub const VERSIONS: [u8; 2] = [1, 2];

/// Where the circles of a value start, and what the header tells about their scale.
#[derive(Clone, Copy, Debug)]
pub struct Cursor {
    /// The first circle's deltas are from here (the bounding box's lower corner).
    pub start: (i64, i64),
    /// Width plus height of the bounding box, grid steps.
    pub extent: u64,
    /// `min_radius` in grid steps.
    pub min_radius: u64,
}
/// Largest absolute coordinate or radius, in grid steps (keeps `q × grid` exact in f64).
pub const MAX_STEPS: i64 = 1 << 52;

/// A circle on the grid: centre `(x, y)` and signed radius `r` (`> 0` inside, `< 0` outside,
/// `0` a boundary point), all in grid steps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Circle {
    /// Centre x, grid steps.
    pub x: i64,
    /// Centre y, grid steps.
    pub y: i64,
    /// Signed radius, grid steps.
    pub r: i64,
}

/// The parameters the value was encoded with, as the user gave them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Params {
    /// Minimum circle radius.
    pub min_radius: Decimal,
    /// Allowed overlap between circles, 0..1.
    pub overlap: Decimal,
    /// Douglas-Peucker tolerance, if zero-radius DP circles were added.
    pub dp_tolerance: Option<Decimal>,
    /// The Hausdorff bound the encoder enforced.
    pub max_error: Decimal,
}

/// A decoded `circletree` value.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CircleTree {
    /// The format version the value was read as, and is written as.
    pub version: u8,
    /// Spatial reference id (0 = unknown).
    pub srid: i32,
    /// Polygon or MultiPolygon.
    pub kind: Kind,
    /// Coordinate units per grid step.
    pub grid: Decimal,
    /// Encoding parameters.
    pub params: Params,
    /// `ST_NPoints` of the original geometry.
    pub vertices: u64,
    /// WKB bytes of the original geometry.
    pub wkb_bytes: u64,
    /// Zero-radius circles added by the encoder's repair loop (beyond the paper's method).
    pub repaired: u64,
    /// Bounding box of the original, grid steps: `[xmin, ymin, xmax, ymax]`; `None` when empty.
    pub bbox: Option<[i64; 4]>,
    /// Parts, each a list of rings (shell first), each a list of circles in boundary order.
    pub parts: Vec<Vec<Vec<Circle>>>,
}

impl CircleTree {
    /// Number of circles in all rings.
    pub fn ncircles(&self) -> usize {
        self.parts.iter().flatten().map(Vec::len).sum()
    }

    /// Grid step as a float.
    pub fn grid_f64(&self) -> f64 {
        self.grid.to_f64()
    }

    /// Check every invariant a stored value must satisfy.
    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(Error::Corrupt(m));
        self.validate_header()?;
        if self.kind == Kind::Polygon && self.parts.len() > 1 {
            return bad(format!("a Polygon with {} parts", self.parts.len()));
        }
        match (self.parts.is_empty(), self.bbox) {
            (true, Some(_)) => return bad("an empty value with a bounding box".into()),
            (false, None) => return bad("a bounding box is missing".into()),
            _ => {}
        }
        for (pi, part) in self.parts.iter().enumerate() {
            if part.is_empty() {
                return bad(format!("part {} has no ring", pi + 1));
            }
            for (ri, ring) in part.iter().enumerate() {
                let zero = ring.iter().filter(|c| c.r == 0).count();
                if ring.is_empty() || (zero == ring.len() && ring.len() < 3) {
                    return bad(format!(
                        "ring {} of part {} has {} circles, too few for a ring",
                        ri + 1,
                        pi + 1,
                        ring.len()
                    ));
                }
                if ring.iter().any(|c| {
                    [c.x, c.y, c.r]
                        .iter()
                        .any(|v| v.unsigned_abs() > MAX_STEPS as u64)
                }) {
                    return bad(format!(
                        "a circle of ring {} of part {} is out of range",
                        ri + 1,
                        pi + 1
                    ));
                }
            }
        }
        if self.repaired > self.ncircles() as u64 {
            return bad(format!(
                "{} repaired circles of {}",
                self.repaired,
                self.ncircles()
            ));
        }
        Ok(())
    }

    /// The invariants of the header alone: grid, parameters and bounding box in range.
    fn validate_header(&self) -> Result<()> {
        let bad = |m: String| Err(Error::Corrupt(m));
        if self.grid.mantissa <= 0 || !(-12..=12).contains(&self.grid.exp) {
            return bad(format!(
                "grid {} is not a positive step between 1e-12 and 1e12",
                self.grid
            ));
        }
        let p = &self.params;
        if p.min_radius.mantissa <= 0 {
            return bad(format!("min_radius {} is not positive", p.min_radius));
        }
        let ov = p.overlap.to_f64();
        if !(0.0..=1.0).contains(&ov) {
            return bad(format!("overlap {} is outside [0, 1]", p.overlap));
        }
        if p.dp_tolerance.is_some_and(|d| d.mantissa <= 0) {
            return bad("dp_tolerance is not positive".into());
        }
        if p.max_error.mantissa <= 0 {
            return bad(format!("max_error {} is not positive", p.max_error));
        }
        if let Some(b) = self.bbox {
            if b[0] > b[2] || b[1] > b[3] {
                return bad("the bounding box is inverted".into());
            }
            if b.iter().any(|v| v.unsigned_abs() > MAX_STEPS as u64) {
                return bad("the bounding box is out of range".into());
            }
        }
        Ok(())
    }

    /// The stored bytes.
    ///
    /// ```
    /// use circletree_core::format::*;
    /// use circletree_core::format::Decimal;
    /// use circletree_core::geom::Kind;
    /// let d = |s| Decimal::parse(s).unwrap();
    /// let ct = CircleTree { version: FORMAT_VERSION, srid: 32760, kind: Kind::Polygon, grid: d("0.5"),
    ///   params: Params { min_radius: d("5"), overlap: d("0.4"), dp_tolerance: None, max_error: d("5") },
    ///   vertices: 5, wkb_bytes: 93, repaired: 0, bbox: Some([0, 0, 20, 20]),
    ///   parts: vec![vec![vec![Circle { x: 10, y: 10, r: 10 }]]] };
    /// let bytes = ct.to_bytes();
    /// assert_eq!(CircleTree::from_bytes(&bytes).unwrap(), ct);
    /// ```
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut w = self.header(32 + 4 * self.ncircles());
        let cur = self.cursor();
        if self.version == 1 {
            v1::write(&mut w, &self.parts, cur);
        } else {
            w.0.extend(v2::write(&self.parts, cur));
        }
        w.0
    }

    /// Bounds on `to_bytes().len()`, without coding the circles (the header is written: it is a
    /// few dozen bytes). Exact for format version 1; for version 2 within a few bytes plus a
    /// few in ten thousand of the stream ([`crate::format::coder::Meter::bytes`]).
    pub fn size_bounds(&self) -> (usize, usize) {
        if self.version == 1 {
            let n = self.to_bytes().len();
            return (n, n);
        }
        let header = self.header(64).0.len();
        let (lo, hi) = v2::meter(&self.parts, self.cursor()).bytes();
        (header + lo, header + hi)
    }

    /// The header: everything before the circles.
    fn header(&self, capacity: usize) -> Writer {
        let mut w = Writer(Vec::with_capacity(capacity));
        w.0.push(self.version);
        w.0.push(self.kind.wkb_code());
        w.put(&self.srid);
        for d in [self.grid, self.params.min_radius, self.params.overlap] {
            w.decimal(d);
        }
        w.put(&self.params.dp_tolerance.map(|d| (d.mantissa, d.exp)));
        w.decimal(self.params.max_error);
        w.put(&self.vertices);
        w.put(&self.wkb_bytes);
        w.put(&self.repaired);
        w.put(&(self.parts.len() as u64));
        if let Some(b) = self.bbox {
            w.put(&b[0]);
            w.put(&b[1]);
            w.put(&((b[2] - b[0]) as u64));
            w.put(&((b[3] - b[1]) as u64));
        }
        w
    }

    /// Where this value's bytes go: the header (everything before the circles) and, for format
    /// version 2, the coded stream by kind of symbol (`None` for version 1).
    pub fn breakdown(&self) -> (usize, Option<v2::Breakdown>) {
        let total = self.to_bytes().len();
        if self.version == 1 {
            let mut w = Writer(Vec::new());
            v1::write(&mut w, &self.parts, self.cursor());
            return (total - w.0.len(), None);
        }
        let stream = v2::write(&self.parts, self.cursor()).len();
        (
            total - stream,
            Some(v2::breakdown(&self.parts, self.cursor())),
        )
    }

    /// Where the circles start and the scales the header implies.
    fn cursor(&self) -> Cursor {
        let (start, extent) = match self.bbox {
            Some(b) => (
                (b[0], b[1]),
                (b[2].saturating_sub(b[0]) as u64).saturating_add(b[3].saturating_sub(b[1]) as u64),
            ),
            None => ((0, 0), 0),
        };
        let ratio = self.params.min_radius.to_f64() / self.grid.to_f64();
        let min_radius = if ratio.is_finite() && ratio > 0.0 {
            ratio.min(1e18) as u64
        } else {
            0
        };
        Cursor {
            start,
            extent,
            min_radius,
        }
    }

    /// Decode and validate bytes from outside (binary COPY, a bytea cast, a fuzzer): everything
    /// [`CircleTree::from_stored_bytes`] checks, and that a version-2 stream is exactly what its
    /// value encodes to (nothing appended or altered that the coder would not notice).
    pub fn from_bytes(bytes: &[u8]) -> Result<CircleTree> {
        Self::read(bytes, true)
    }

    /// Decode and validate bytes this extension stored. Never panics, never trusts a count;
    /// skips only the re-encoding of [`CircleTree::from_bytes`] (values written by `to_bytes`
    /// are canonical by construction).
    pub fn from_stored_bytes(bytes: &[u8]) -> Result<CircleTree> {
        Self::read(bytes, false)
    }

    /// The header alone (everything before the circles): the value with no parts, and the number
    /// of parts its circles hold.
    fn read_header<'a>(r: &mut Reader<'a>) -> Result<(CircleTree, usize)> {
        let version = r.byte("the format version")?;
        if !VERSIONS.contains(&version) {
            return Err(Error::Corrupt(format!(
                "format version {version} is not known to this release (it reads versions 1 and 2)"
            )));
        }
        let code = r.byte("the geometry kind")?;
        let kind = Kind::from_wkb_code(code)
            .ok_or_else(|| Error::Corrupt(format!("geometry kind {code} is neither 3 nor 6")))?;
        let srid: i32 = r.take("the SRID")?;
        let grid = r.decimal("the grid")?;
        let min_radius = r.decimal("min_radius")?;
        let overlap = r.decimal("overlap")?;
        let dp: Option<(i64, i8)> = r.take("dp_tolerance")?;
        let dp_tolerance = match dp {
            Some((m, e)) => Some(
                Decimal::new(m, e as i32).ok_or_else(|| Error::Corrupt("dp_tolerance".into()))?,
            ),
            None => None,
        };
        let max_error = r.decimal("max_error")?;
        let vertices: u64 = r.take("the vertex count")?;
        let wkb_bytes: u64 = r.take("the WKB size")?;
        let repaired: u64 = r.take("the repaired count")?;
        // Version 1 spends at least 5 bytes a part (two counts and a circle); version 2's coded
        // stream can hold a part in well under a byte, and its reader bounds the count itself
        // (`v2::read`: at most `MAX_CIRCLES_PER_BYTE` a byte). Releases up to 0.5.0 applied
        // version 1's bound to both and so refused their own version-2 values of many small, alike
        // parts: those values read now.
        let nparts = if version == 1 {
            r.count("parts", 5)?
        } else {
            let n: u64 = r.take("the part count")?;
            usize::try_from(n).map_err(|_| Error::Corrupt(format!("the value claims {n} parts")))?
        };
        let mut bbox = None;
        if nparts > 0 {
            let xmin: i64 = r.take("the bounding box")?;
            let ymin: i64 = r.take("the bounding box")?;
            let w: u64 = r.take("the bounding box")?;
            let h: u64 = r.take("the bounding box")?;
            let add = |a: i64, b: u64| i64::try_from(b).ok().and_then(|b| a.checked_add(b));
            let (Some(xmax), Some(ymax)) = (add(xmin, w), add(ymin, h)) else {
                return Err(Error::Corrupt("the bounding box overflows".into()));
            };
            bbox = Some([xmin, ymin, xmax, ymax]);
        }
        let ct = CircleTree {
            version,
            srid,
            kind,
            grid,
            params: Params {
                min_radius,
                overlap,
                dp_tolerance,
                max_error,
            },
            vertices,
            wkb_bytes,
            repaired,
            bbox,
            parts: vec![],
        };
        Ok((ct, nparts))
    }

    /// A box holding both the original polygon and everything [`crate::decode`] rebuilds from
    /// these bytes, read from the header alone (no circle is decoded): the stored bounding box of
    /// the original, widened by the value's `max_error` (the rebuilt boundary lies within it of
    /// the original's). `None` for an empty value.
    pub fn envelope(bytes: &[u8]) -> Result<(i32, Option<[f64; 4]>)> {
        let mut r = Reader { buf: bytes };
        let (ct, _) = Self::read_header(&mut r)?;
        ct.validate_header()?;
        let g = crate::format::grid::Grid::new(ct.grid);
        let m = ct.params.max_error.to_f64();
        Ok((
            ct.srid,
            ct.bbox.map(|b| {
                [
                    g.coord(b[0]) - m,
                    g.coord(b[1]) - m,
                    g.coord(b[2]) + m,
                    g.coord(b[3]) + m,
                ]
            }),
        ))
    }

    fn read(bytes: &[u8], canonical: bool) -> Result<CircleTree> {
        let mut r = Reader { buf: bytes };
        let (mut ct, nparts) = Self::read_header(&mut r)?;
        let version = ct.version;
        let cur = ct.cursor();
        ct.parts = if version == 1 {
            v1::read(&mut r, nparts, cur)?
        } else {
            v2::read(r.buf, nparts, cur)?
        };
        ct.validate()?;
        // One value, one byte string (`=` compares bytes): bytes that are not exactly what this
        // value encodes to are refused, whatever the version: an overlong varint in a header or
        // in version 1's circles, a version-2 stream extended, truncated past its zeros or altered.
        if canonical && ct.to_bytes() != bytes {
            return Err(Error::Corrupt(
                "the value is not in its canonical form (bytes changed or appended)".into(),
            ));
        }
        Ok(ct)
    }
}
/// Plain header fields (postcard varints).
pub struct Writer(Vec<u8>);

impl Writer {
    fn put<T: Serialize + ?Sized>(&mut self, v: &T) {
        // postcard into a Vec only fails on unsupported serde types, which we never pass.
        if let Ok(b) = postcard::to_extend(v, std::mem::take(&mut self.0)) {
            self.0 = b;
        }
    }
    fn decimal(&mut self, d: Decimal) {
        self.put(&(d.mantissa, d.exp));
    }
}

/// Reads header fields.
pub struct Reader<'a> {
    buf: &'a [u8],
}

impl<'a> Reader<'a> {
    fn byte(&mut self, what: &str) -> Result<u8> {
        let (&b, rest) = self
            .buf
            .split_first()
            .ok_or_else(|| Error::Corrupt(format!("the value ends before {what}")))?;
        self.buf = rest;
        Ok(b)
    }
    fn take<T: DeserializeOwned>(&mut self, what: &str) -> Result<T> {
        let (v, rest) = postcard::take_from_bytes::<T>(self.buf)
            .map_err(|e| Error::Corrupt(format!("cannot read {what}: {e}")))?;
        self.buf = rest;
        Ok(v)
    }
    fn decimal(&mut self, what: &str) -> Result<Decimal> {
        let (m, e): (i64, i8) = self.take(what)?;
        Decimal::new(m, e as i32).ok_or_else(|| Error::Corrupt(format!("{what} is out of range")))
    }
    /// A count of items each needing at least `min_bytes`; refused when the bytes left cannot hold them.
    fn count(&mut self, what: &str, min_bytes: usize) -> Result<usize> {
        let n: u64 = self.take(what)?;
        let room = (self.buf.len() / min_bytes) as u64;
        if n > room {
            return Err(Error::Corrupt(format!(
                "the value claims {n} {what} but only {} bytes remain",
                self.buf.len()
            )));
        }
        Ok(n as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn sample_v(version: u8) -> CircleTree {
        let d = |s| Decimal::parse(s).unwrap();
        CircleTree {
            version,
            srid: 32760,
            kind: Kind::MultiPolygon,
            grid: d("0.5"),
            params: Params {
                min_radius: d("5"),
                overlap: d("0.4"),
                dp_tolerance: Some(d("10")),
                max_error: d("10"),
            },
            vertices: 2029,
            wkb_bytes: 32513,
            repaired: 1,
            bbox: Some([1_000_000, 12_000_000, 1_000_400, 12_000_300]),
            parts: vec![
                vec![vec![
                    Circle {
                        x: 1_000_100,
                        y: 12_000_100,
                        r: 40,
                    },
                    Circle {
                        x: 1_000_200,
                        y: 12_000_050,
                        r: 0,
                    },
                    Circle {
                        x: 1_000_300,
                        y: 12_000_200,
                        r: -30,
                    },
                ]],
                vec![vec![Circle {
                    x: 1_000_390,
                    y: 12_000_290,
                    r: 10,
                }]],
            ],
        }
    }

    /// Found by the decode fuzz target: an integer coded as going up from a predicted class of
    /// 64 (which no writer makes) overflowed the reader's arithmetic (a panic in debug builds).
    /// Now an error.
    #[test]
    fn a_class_going_up_from_the_top_is_an_error() {
        let bytes: &[u8] = &[
            2, 3, 240, 255, 3, 70, 0, 50, 0, 0, 0, 1, 236, 38, 254, 50, 0, 237, 15, 221, 253, 1, 0,
            1, 132, 143, 1, 196, 138, 19, 254, 255, 255, 255, 255, 255, 255, 255, 44, 75, 58, 13,
            71, 52, 121, 198, 230, 162, 241, 37, 65, 36, 148, 214, 2, 151, 226, 179, 30, 182, 172,
            205, 142, 125, 117, 230, 8, 12, 93, 129, 161, 246, 229, 41, 71, 239, 5, 216, 55, 108,
            57, 33, 176, 69, 74, 215, 10, 104, 68, 159, 115, 194, 121, 224, 200, 146, 113, 6, 18,
            219, 1, 0, 208, 1, 0, 0, 0, 0, 0, 0, 0, 0, 158, 1, 5, 35, 16, 31, 0, 69, 20, 41, 49,
            21, 37, 61, 22, 47, 41, 19, 0, 85, 2, 27, 25, 6, 0, 143, 1, 61, 138, 1, 35, 31, 13, 0,
            193, 1, 184, 166, 117, 239, 130, 158, 228, 158, 140,
        ];
        assert!(CircleTree::from_bytes(bytes).is_err());
    }

    #[test]
    fn round_trip_and_size() {
        for v in VERSIONS {
            let ct = sample_v(v);
            let b = ct.to_bytes();
            assert_eq!(b[0], v);
            assert_eq!(CircleTree::from_bytes(&b).unwrap(), ct);
            // header: 2 + srid 3 + grid 2 + min_radius 2 + overlap 2 + dp 3 + max_error 2 + 2 + 3 + 1
            //   + nparts 1 + bbox 3 + 4 + 2 + 2 = 34; circles: deltas of a few bytes each
            assert!(b.len() < 60, "{} bytes", b.len());
        }
    }

    #[test]
    fn many_small_alike_parts_read_back() {
        // Version 2 codes a part in well under the 5 bytes version 1 needs: 20,000 alike squares
        // (what ct_encode_within writes for a grid of parcels) must read back from their bytes.
        let mut ct = sample_v(2);
        ct.parts = (0..20_000i64)
            .map(|i| {
                let (x, y) = (1_000_000 + (i % 200) * 2, 12_000_000 + (i / 200) * 2);
                vec![vec![
                    Circle { x, y, r: 0 },
                    Circle { x: x + 1, y, r: 0 },
                    Circle {
                        x: x + 1,
                        y: y + 1,
                        r: 0,
                    },
                ]]
            })
            .collect();
        let b = ct.to_bytes();
        assert!(b.len() < 5 * 20_000, "{} bytes", b.len());
        assert_eq!(CircleTree::from_bytes(&b).unwrap(), ct);
        assert_eq!(CircleTree::from_stored_bytes(&b).unwrap(), ct);
        assert!(CircleTree::envelope(&b).is_ok());
        // version 1 still bounds its count by the bytes left
        ct.version = 1;
        let mut b1 = ct.to_bytes();
        assert_eq!(CircleTree::from_bytes(&b1).unwrap(), ct);
        b1.truncate(60);
        assert!(CircleTree::from_bytes(&b1).is_err());
    }

    #[test]
    fn rejects_lies_and_leftovers() {
        let ct = sample_v(1);
        let mut b = ct.to_bytes();
        b.push(0);
        assert!(
            matches!(CircleTree::from_bytes(&b), Err(Error::Corrupt(m)) if m.contains("left over"))
        );
        let mut b = sample_v(2).to_bytes();
        b.push(7);
        assert!(
            matches!(CircleTree::from_bytes(&b), Err(Error::Corrupt(m)) if m.contains("canonical"))
        );
        let mut v = ct.to_bytes();
        v[0] = 3;
        assert!(
            matches!(CircleTree::from_bytes(&v), Err(Error::Corrupt(m)) if m.contains("version 3"))
        );
        assert!(matches!(
            CircleTree::from_bytes(&[]),
            Err(Error::Corrupt(_))
        ));
    }

    #[test]
    fn overlong_varints_are_refused_from_outside() {
        // found by the `decode` fuzz target: a varint with a redundant continuation byte reads
        // as the same number, so two byte strings held one value and `=` (bytes) told them apart
        for v in VERSIONS {
            let ct = sample_v(v);
            let b = ct.to_bytes();
            assert_eq!(&b[2..5], &[0xf0, 0xff, 0x03], "SRID 32760, zigzag");
            let mut long = b[..2].to_vec();
            long.extend([0xf0, 0xff, 0x83, 0x00]);
            long.extend(&b[5..]);
            assert_eq!(CircleTree::from_stored_bytes(&long).unwrap(), ct);
            assert!(matches!(CircleTree::from_bytes(&long),
                Err(Error::Corrupt(m)) if m.contains("canonical")));
        }
    }

    #[test]
    fn the_most_negative_coordinate_is_out_of_range() {
        // found by the `decode` fuzz target: `i64::MIN.abs()` overflows (a panic in debug builds,
        // and in release it stays negative, so the range check let the circle through)
        let mut ct = sample_v(1);
        ct.bbox = Some([i64::MIN, 0, 0, 10]);
        assert!(ct.validate().is_err());
        let mut ct = sample_v(1);
        ct.parts[0][0][1].x = i64::MIN;
        assert!(matches!(ct.validate(), Err(Error::Corrupt(m)) if m.contains("out of range")));
    }

    #[test]
    fn envelope_from_the_header_alone() {
        for v in VERSIONS {
            let ct = sample_v(v);
            let mut b = ct.to_bytes();
            let (srid, bbox) = CircleTree::envelope(&b).unwrap();
            assert_eq!(srid, 32760);
            // grid 0.5, max_error 10: the stored box widened by 10
            assert_eq!(bbox, Some([499_990.0, 5_999_990.0, 500_210.0, 6_000_160.0]));
            // the circles are not read: a value cut after its header still has its envelope
            b.truncate(b.len() - 3);
            assert!(CircleTree::from_bytes(&b).is_err());
            assert_eq!(CircleTree::envelope(&b).unwrap().1, bbox);
        }
        assert!(CircleTree::envelope(&[2, 3]).is_err());
    }

    #[test]
    fn huge_count_does_not_allocate() {
        // A polygon claiming 2^32 circles in its one ring.
        let d = |s| Decimal::parse(s).unwrap();
        let mut w = Writer(vec![1, 3]);
        w.put(&0i32);
        for x in [d("1"), d("5"), d("0.4")] {
            w.decimal(x);
        }
        w.put(&None::<(i64, i8)>);
        w.decimal(d("5"));
        for _ in 0..3 {
            w.put(&0u64);
        }
        w.put(&1u64);
        for _ in 0..4 {
            w.put(&0u64);
        }
        w.put(&1u64);
        w.put(&(1u64 << 32));
        let err = CircleTree::from_bytes(&w.0).unwrap_err();
        assert!(matches!(err, Error::Corrupt(m) if m.contains("claims 4294967296 circles")));
    }

    proptest! {
        #[test]
        fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..200)) {
            let _ = CircleTree::from_bytes(&bytes);
        }

        #[test]
        fn mutated_values_never_panic(pos in 0usize..60, val in any::<u8>(), version in 1u8..=2) {
            let mut b = sample_v(version).to_bytes();
            let i = pos % b.len();
            b[i] = val;
            if let Ok(ct) = CircleTree::from_bytes(&b) {
                prop_assert_eq!(CircleTree::from_bytes(&ct.to_bytes()).unwrap(), ct);
            }
        }
    }
}
