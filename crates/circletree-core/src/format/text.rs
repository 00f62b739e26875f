//! The text form of a `circletree` value. It carries every stored field, so that
//! `value::text::circletree` has exactly the bytes of `value`:
//!
//! ```text
//! SRID=32760;CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=10;max_error=10;
//!   vertices=2029;wkb_bytes=32513;repaired=3;bbox=(1722871 5472139.5,1733310 5480262);
//!   POLYGON((1728112.5 5475313 -40.5,1728120 5475290 0,...)))
//! ```
//! (one line in practice). Coordinates and radii are exact decimals that must lie on the grid;
//! `dp_tolerance=NULL` when no Douglas-Peucker circles were added; an empty value reads
//! `POLYGON EMPTY` and has no `bbox`. Keywords are case-insensitive and blanks are allowed
//! between tokens.

use crate::error::{Error, Result};
use crate::format::decimal::Decimal;
use crate::format::{Circle, CircleTree, Params, VERSIONS};
use crate::geom::Kind;
use std::fmt::Write;

fn coord(out: &mut String, grid: Decimal, q: i64) {
    match grid.times(q) {
        Some(d) => {
            let _ = write!(out, "{d}");
        }
        // Unreachable for validated values (|q| <= 2^52 and the grid mantissa is small), kept total.
        None => {
            let _ = write!(out, "{}", q as f64 * grid.to_f64());
        }
    }
}

/// Print a value.
pub fn to_text(ct: &CircleTree) -> String {
    let mut s = String::with_capacity(96 + 24 * ct.ncircles());
    let p = &ct.params;
    let dp = p.dp_tolerance.map_or("NULL".to_string(), |d| d.to_string());
    let _ = write!(
        s,
        "SRID={};CIRCLETREE({}grid={};min_radius={};overlap={};dp_tolerance={};max_error={};vertices={};wkb_bytes={};repaired={};",
        ct.srid,
        if ct.version == 1 { String::new() } else { format!("version={};", ct.version) },
        ct.grid,
        p.min_radius, p.overlap, dp, p.max_error, ct.vertices, ct.wkb_bytes, ct.repaired
    );
    if let Some(b) = ct.bbox {
        s.push_str("bbox=(");
        coord(&mut s, ct.grid, b[0]);
        s.push(' ');
        coord(&mut s, ct.grid, b[1]);
        s.push(',');
        coord(&mut s, ct.grid, b[2]);
        s.push(' ');
        coord(&mut s, ct.grid, b[3]);
        s.push_str(");");
    }
    s.push_str(ct.kind.name());
    if ct.parts.is_empty() {
        s.push_str(" EMPTY)");
        return s;
    }
    let multi = ct.kind == Kind::MultiPolygon;
    if multi {
        s.push('(');
    }
    for (pi, part) in ct.parts.iter().enumerate() {
        if pi > 0 {
            s.push(',');
        }
        s.push('(');
        for (ri, ring) in part.iter().enumerate() {
            if ri > 0 {
                s.push(',');
            }
            s.push('(');
            for (ci, c) in ring.iter().enumerate() {
                if ci > 0 {
                    s.push(',');
                }
                coord(&mut s, ct.grid, c.x);
                s.push(' ');
                coord(&mut s, ct.grid, c.y);
                s.push(' ');
                coord(&mut s, ct.grid, c.r);
            }
            s.push(')');
        }
        s.push(')');
    }
    if multi {
        s.push(')');
    }
    s.push(')');
    s
}

struct Parser<'a> {
    s: &'a str,
    pos: usize,
}

impl<'a> Parser<'a> {
    fn err<T>(&self, expected: impl Into<String>) -> Result<T> {
        Err(Error::Syntax {
            expected: expected.into(),
            position: self.s[..self.pos].chars().count() + 1,
        })
    }
    fn skip_ws(&mut self) {
        while let Some(c) = self.s[self.pos..].chars().next() {
            if c.is_whitespace() {
                self.pos += c.len_utf8();
            } else {
                break;
            }
        }
    }
    fn eat(&mut self, tok: &str) -> bool {
        self.skip_ws();
        let rest = &self.s[self.pos..];
        if rest.len() >= tok.len()
            && rest.is_char_boundary(tok.len())
            && rest[..tok.len()].eq_ignore_ascii_case(tok)
        {
            self.pos += tok.len();
            true
        } else {
            false
        }
    }
    fn expect_token(&mut self, tok: &str) -> Result<()> {
        if self.eat(tok) {
            Ok(())
        } else {
            self.err(format!("'{tok}'"))
        }
    }
    fn word(&mut self) -> &'a str {
        self.skip_ws();
        let start = self.pos;
        let rest = &self.s[start..];
        let len = rest
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == '-' || c == '+'))
            .unwrap_or(rest.len());
        self.pos += len;
        &self.s[start..start + len]
    }
    fn decimal(&mut self, what: &str) -> Result<Decimal> {
        let save = self.pos;
        let w = self.word();
        match Decimal::parse(w) {
            Some(d) => Ok(d),
            None => {
                self.pos = save;
                self.skip_ws();
                self.err(format!("a number for {what}"))
            }
        }
    }
    fn uint(&mut self, what: &str) -> Result<u64> {
        let save = self.pos;
        let w = self.word();
        match w.parse::<u64>() {
            Ok(v) => Ok(v),
            Err(_) => {
                self.pos = save;
                self.skip_ws();
                self.err(format!("a non-negative integer for {what}"))
            }
        }
    }
    fn on_grid(&mut self, grid: Decimal, what: &str) -> Result<i64> {
        self.skip_ws();
        let save = self.pos;
        let d = self.decimal(what)?;
        match grid.divide_exact(d) {
            Some(q) => Ok(q),
            None => {
                self.pos = save;
                self.err(format!("{what} on the grid (a multiple of {grid})"))
            }
        }
    }
    fn param(&mut self, name: &str) -> Result<Decimal> {
        self.expect_token(name)?;
        self.expect_token("=")?;
        let d = self.decimal(name)?;
        self.expect_token(";")?;
        Ok(d)
    }
    fn count(&mut self, name: &str) -> Result<u64> {
        self.expect_token(name)?;
        self.expect_token("=")?;
        let v = self.uint(name)?;
        self.expect_token(";")?;
        Ok(v)
    }
    fn list<T>(&mut self, mut item: impl FnMut(&mut Self) -> Result<T>) -> Result<Vec<T>> {
        self.expect_token("(")?;
        let mut v = vec![item(self)?];
        while self.eat(",") {
            v.push(item(self)?);
        }
        self.expect_token(")")?;
        Ok(v)
    }
}

/// Parse the text form. Errors name what was expected and the character position.
pub fn from_text(s: &str) -> Result<CircleTree> {
    let mut p = Parser { s, pos: 0 };
    let mut srid = 0i32;
    if p.eat("SRID") {
        p.expect_token("=")?;
        p.skip_ws();
        let save = p.pos;
        let w = p.word();
        srid = match w.parse::<i32>() {
            Ok(v) => v,
            Err(_) => {
                p.pos = save;
                return p.err("an integer SRID");
            }
        };
        p.expect_token(";")?;
    }
    p.expect_token("CIRCLETREE")?;
    p.expect_token("(")?;
    // Absent in the text of version-1 values (release 0.1.0 printed none).
    let version = if p.eat("version") {
        p.expect_token("=")?;
        let save = p.pos;
        let v = p.uint("version")?;
        match u8::try_from(v)
            .ok()
            .filter(|v| VERSIONS.contains(v) && *v != 1)
        {
            Some(v) => {
                p.expect_token(";")?;
                v
            }
            None => {
                p.pos = save;
                return p.err("format version 2 (version 1 values print no version)");
            }
        }
    } else {
        1
    };
    let grid = p.param("grid")?;
    if grid.mantissa <= 0 {
        p.pos = s[..p.pos].rfind('=').map_or(p.pos, |i| i + 1);
        return p.err("a positive grid");
    }
    let min_radius = p.param("min_radius")?;
    let overlap = p.param("overlap")?;
    p.expect_token("dp_tolerance")?;
    p.expect_token("=")?;
    let dp_tolerance = if p.eat("NULL") {
        None
    } else {
        Some(p.decimal("dp_tolerance")?)
    };
    p.expect_token(";")?;
    let max_error = p.param("max_error")?;
    let vertices = p.count("vertices")?;
    let wkb_bytes = p.count("wkb_bytes")?;
    let repaired = p.count("repaired")?;
    let mut bbox = None;
    if p.eat("bbox") {
        p.expect_token("=")?;
        p.expect_token("(")?;
        let x0 = p.on_grid(grid, "bbox xmin")?;
        let y0 = p.on_grid(grid, "bbox ymin")?;
        p.expect_token(",")?;
        let x1 = p.on_grid(grid, "bbox xmax")?;
        let y1 = p.on_grid(grid, "bbox ymax")?;
        p.expect_token(")")?;
        p.expect_token(";")?;
        bbox = Some([x0, y0, x1, y1]);
    }
    let kind = if p.eat("MULTIPOLYGON") {
        Kind::MultiPolygon
    } else if p.eat("POLYGON") {
        Kind::Polygon
    } else {
        return p.err("POLYGON or MULTIPOLYGON");
    };
    let circle = |p: &mut Parser| -> Result<Circle> {
        let x = p.on_grid(grid, "a circle's x")?;
        let y = p.on_grid(grid, "a circle's y")?;
        let r = p.on_grid(grid, "a circle's radius")?;
        Ok(Circle { x, y, r })
    };
    let ring = |p: &mut Parser| p.list(circle);
    let polygon = |p: &mut Parser| p.list(ring);
    let parts = if p.eat("EMPTY") {
        vec![]
    } else if kind == Kind::MultiPolygon {
        p.list(polygon)?
    } else {
        vec![polygon(&mut p)?]
    };
    p.expect_token(")")?;
    p.skip_ws();
    if p.pos != s.len() {
        return p.err("the end of the value");
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
        parts,
    };
    // A well-formed text can still describe an impossible value (a ring of two points, ...).
    ct.validate().map_err(|e| match e {
        Error::Corrupt(m) => Error::Syntax {
            expected: format!("a valid value ({m})"),
            position: s.chars().count(),
        },
        other => other,
    })?;
    Ok(ct)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLE: &str = "SRID=32760;CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON((5 5 5)))";

    #[test]
    fn round_trip() {
        let ct = from_text(SAMPLE).unwrap();
        assert_eq!(
            ct.parts[0][0][0],
            Circle {
                x: 10,
                y: 10,
                r: 10
            }
        );
        assert_eq!(to_text(&ct), SAMPLE);
        let multi = "SRID=0;CIRCLETREE(grid=0.01;min_radius=1;overlap=0;dp_tolerance=2.5;max_error=2.5;vertices=12;wkb_bytes=200;repaired=1;bbox=(-1.5 0,3 4.25);MULTIPOLYGON(((0 0 0,3 0 0,3 4.25 -0.5)),((-1.5 1 0,-1 1 0,-1 2 1.25),(1 1 0,1.5 1 0,1 1.5 0))))";
        let m = from_text(multi).unwrap();
        assert_eq!(to_text(&m), multi);
        assert_eq!(CircleTree::from_bytes(&m.to_bytes()).unwrap(), m);
        let empty = "SRID=4326;CIRCLETREE(grid=1;min_radius=1;overlap=0.4;dp_tolerance=NULL;max_error=1;vertices=0;wkb_bytes=9;repaired=0;POLYGON EMPTY)";
        assert_eq!(to_text(&from_text(empty).unwrap()), empty);
    }

    #[test]
    fn errors_name_expectation_and_position() {
        let e = from_text("CIRCLETREE(grid=x;").unwrap_err();
        assert_eq!(
            e,
            Error::Syntax {
                expected: "a number for grid".into(),
                position: 17
            }
        );
        let off_grid = SAMPLE.replace("(5 5 5)", "(5.25 5 5)");
        assert!(
            matches!(from_text(&off_grid), Err(Error::Syntax { expected, .. }) if expected.contains("multiple of 0.5"))
        );
        assert!(matches!(
            from_text("POINT(1 2)"),
            Err(Error::Syntax { position: 1, .. })
        ));
        let trailing = format!("{SAMPLE} x");
        assert!(
            matches!(from_text(&trailing), Err(Error::Syntax { expected, .. }) if expected == "the end of the value")
        );
        let two_points = SAMPLE.replace("(5 5 5)", "(5 5 0,6 6 0)");
        assert!(
            matches!(from_text(&two_points), Err(Error::Syntax { expected, .. }) if expected.contains("too few"))
        );
    }
}
