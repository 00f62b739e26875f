//! Format version 2: the same header as version 1, then one range-coded stream
//! ([`crate::format::coder`]) holding every count and every circle.
//!
//! ```text
//! stream: per part: nrings − 1; per ring: ncircles            (the counts model)
//!         per circle: flag "has a radius"                      (context: the previous circle's)
//!                     dx, dy from the previous circle's centre (models by this and the previous
//!                                                              circle's kind: point or circle)
//!                     r, when it has one                       (the radius model)
//! ```
//! A zero-radius circle (a boundary point) stores no radius: runs of points cost two coded deltas
//! each. The first prediction of each model comes from the header, not from any data set: the
//! deltas from the bounding box and the number of circles, the radii from `min_radius`.

use super::{Circle, Cursor};
use crate::error::{Error, Result};
use crate::format::coder::{class, Bit, IntModel, Meter, Reader, Sink, Writer};

/// Adaptive models of the stream, in their starting state for a value.
pub struct Models {
    counts: IntModel,
    kind: [Bit; 2],
    /// `[this kind][previous kind]`, kind 0 a point, 1 a circle: x then y.
    delta: [[[IntModel; 2]; 2]; 2],
    radius: IntModel,
    prev_circle: bool,
}

impl Models {
    /// Starting models for a value with this bounding box (grid steps), number of circles and
    /// minimum radius (grid steps).
    pub fn new(extent: u64, ncircles: u64, min_radius: u64) -> Models {
        let step = class(extent.saturating_mul(3) / ncircles.max(1));
        let d = IntModel::expecting(step);
        let r = IntModel::expecting(class(min_radius.saturating_mul(2)));
        Models {
            counts: IntModel::expecting(4),
            kind: [Bit::default(); 2],
            delta: [
                [[d.clone(), d.clone()], [d.clone(), d.clone()]],
                [[d.clone(), d.clone()], [d.clone(), d]],
            ],
            radius: r,
            prev_circle: false,
        }
    }

    /// Code one circle after the one at `cur`.
    pub fn put<S: Sink>(&mut self, w: &mut S, c: &Circle, cur: (i64, i64)) {
        let is_circle = c.r != 0;
        let (k, p) = (is_circle as usize, self.prev_circle as usize);
        w.flag(&mut self.kind[p], is_circle);
        if is_circle {
            w.int(&mut self.radius, c.r);
            self.expect_radius(c.r, k, p);
        }
        w.int(&mut self.delta[0][k][p], c.x - cur.0);
        w.int(&mut self.delta[1][k][p], c.y - cur.1);
        self.prev_circle = is_circle;
    }

    /// A circle's centre lies about its radius from the boundary: predict its deltas' class so.
    fn expect_radius(&mut self, r: i64, k: usize, p: usize) {
        let c = class(r.unsigned_abs()).saturating_sub(1);
        self.delta[0][k][p].predict(c);
        self.delta[1][k][p].predict(c);
    }

    /// Bits one circle would cost next (the encoders' cost function; nothing is updated).
    pub fn cost(&self, c: &Circle, cur: (i64, i64)) -> f64 {
        let is_circle = c.r != 0;
        let (k, p) = (is_circle as usize, self.prev_circle as usize);
        let (mut dx, mut dy) = (self.delta[0][k][p].clone(), self.delta[1][k][p].clone());
        if is_circle {
            let cl = class(c.r.unsigned_abs()).saturating_sub(1);
            dx.predict(cl);
            dy.predict(cl);
        }
        self.kind[p].cost(is_circle)
            + dx.cost(c.x - cur.0)
            + dy.cost(c.y - cur.1)
            + if is_circle {
                self.radius.cost(c.r)
            } else {
                0.0
            }
    }

    fn get(&mut self, r: &mut Reader, cur: (i64, i64)) -> Result<Circle> {
        let p = self.prev_circle as usize;
        let is_circle = r.flag(&mut self.kind[p])?;
        let k = is_circle as usize;
        let rad = if is_circle {
            let v = r.int(&mut self.radius)?;
            if v == 0 {
                return Err(Error::Corrupt(
                    "a circle flagged with a radius has none".into(),
                ));
            }
            self.expect_radius(v, k, p);
            v
        } else {
            0
        };
        let dx = r.int(&mut self.delta[0][k][p])?;
        let dy = r.int(&mut self.delta[1][k][p])?;
        self.prev_circle = is_circle;
        let (Some(x), Some(y)) = (cur.0.checked_add(dx), cur.1.checked_add(dy)) else {
            return Err(Error::Corrupt("a circle's coordinates overflow".into()));
        };
        Ok(Circle { x, y, r: rad })
    }
}

/// The coded stream of a value's parts.
pub fn write(parts: &[Vec<Vec<Circle>>], cur: Cursor) -> Vec<u8> {
    let mut w = Writer::default();
    code(parts, cur, &mut w);
    w.finish()
}

/// What [`write`]'s stream would cost, without writing it (bounds on its length:
/// [`Meter::bytes`]).
pub fn meter(parts: &[Vec<Vec<Circle>>], cur: Cursor) -> Meter {
    let mut m = Meter::default();
    code(parts, cur, &mut m);
    m
}

/// Every symbol of a value's parts, in order, into `w`.
fn code<S: Sink>(parts: &[Vec<Vec<Circle>>], cur: Cursor, w: &mut S) {
    let n: usize = parts.iter().flatten().map(Vec::len).sum();
    let mut m = Models::new(cur.extent, n as u64, cur.min_radius);
    for part in parts {
        w.int(&mut m.counts, part.len() as i64 - 1);
    }
    for ring in parts.iter().flatten() {
        w.int(&mut m.counts, ring.len() as i64);
    }
    let mut at = cur.start;
    for c in parts.iter().flatten().flatten() {
        m.put(w, c, at);
        at = (c.x, c.y);
    }
}

/// Where the bits of a stream go, estimated by the models' own costs just before each symbol is
/// coded (the coder's output is within a few bytes of the sum).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Breakdown {
    /// Ring and circle counts.
    pub counts: f64,
    /// The "has a radius" flags.
    pub flags: f64,
    /// Centre deltas of zero-radius circles (boundary points).
    pub point_deltas: f64,
    /// Centre deltas of circles with a radius.
    pub circle_deltas: f64,
    /// Radii.
    pub radii: f64,
}

/// The bits of [`write`]'s stream by kind of symbol (for benchmarks: where the bytes go).
pub fn breakdown(parts: &[Vec<Vec<Circle>>], cur: Cursor) -> Breakdown {
    let n: usize = parts.iter().flatten().map(Vec::len).sum();
    let mut m = Models::new(cur.extent, n as u64, cur.min_radius);
    let mut w = Writer::default();
    let mut b = Breakdown::default();
    let counts = parts
        .iter()
        .map(|p| p.len() as i64 - 1)
        .chain(parts.iter().flatten().map(|r| r.len() as i64));
    for v in counts {
        b.counts += m.counts.cost(v);
        w.int(&mut m.counts, v);
    }
    let mut at = cur.start;
    for c in parts.iter().flatten().flatten() {
        let p = m.prev_circle as usize;
        let flag = m.kind[p].cost(c.r != 0);
        let radius = if c.r != 0 { m.radius.cost(c.r) } else { 0.0 };
        let total = m.cost(c, at);
        b.flags += flag;
        b.radii += radius;
        if c.r != 0 {
            b.circle_deltas += total - flag - radius;
        } else {
            b.point_deltas += total - flag;
        }
        m.put(&mut w, c, at);
        at = (c.x, c.y);
    }
    b
}

/// Circles per byte of stream that a value may claim: far more than any real value reaches (a
/// coded circle takes at least three decisions of at most 4064/4096 each), far fewer than a
/// hostile count could ask for.
const MAX_CIRCLES_PER_BYTE: usize = 512;

/// Read the coded stream of `nparts` parts.
pub fn read(bytes: &[u8], nparts: usize, cur: Cursor) -> Result<Vec<Vec<Vec<Circle>>>> {
    let budget = MAX_CIRCLES_PER_BYTE * (bytes.len() + 8);
    let mut r = Reader::new(bytes)?;
    let mut counts = IntModel::expecting(4);
    let count = |r: &mut Reader, m: &mut IntModel, what: &str, plus: i64| -> Result<usize> {
        let v = r.int(m)?.checked_add(plus).unwrap_or(-1);
        usize::try_from(v)
            .ok()
            .filter(|&n| n <= budget)
            .ok_or_else(|| Error::Corrupt(format!("the value claims {v} {what}")))
    };
    if nparts > budget {
        return Err(Error::Corrupt(format!("the value claims {nparts} parts")));
    }
    // reservations never exceed what a real stream of this length holds (counts are only bounded
    // by the coder's floor, hundreds a byte); vectors grow past that as circles are decoded
    let cap = 8 * bytes.len() + 16;
    let mut nrings = Vec::with_capacity(nparts.min(cap));
    let mut total_rings = 0usize;
    for _ in 0..nparts {
        let n = count(&mut r, &mut counts, "rings", 1)?;
        total_rings += n;
        if total_rings > budget {
            return Err(Error::Corrupt(format!(
                "the value claims {total_rings} rings"
            )));
        }
        nrings.push(n);
    }
    let mut sizes = Vec::with_capacity(total_rings.min(cap));
    let mut total = 0usize;
    for _ in 0..total_rings {
        let n = count(&mut r, &mut counts, "circles", 0)?;
        total += n;
        if total > budget {
            return Err(Error::Corrupt(format!(
                "the value claims {total} circles in {} bytes",
                bytes.len()
            )));
        }
        sizes.push(n);
    }
    let mut m = Models::new(cur.extent, total as u64, cur.min_radius);
    m.counts = counts;
    let mut at = cur.start;
    let mut sizes = sizes.into_iter();
    let mut parts = Vec::with_capacity(nparts.min(cap));
    for nr in nrings {
        let mut rings = Vec::with_capacity(nr.min(cap));
        for _ in 0..nr {
            let n = sizes.next().unwrap_or(0);
            let mut ring = Vec::with_capacity(n.min(cap));
            for _ in 0..n {
                let c = m.get(&mut r, at)?;
                at = (c.x, c.y);
                ring.push(c);
            }
            rings.push(ring);
        }
        parts.push(rings);
    }
    Ok(parts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn breakdown_adds_up_to_the_stream() {
        let ring: Vec<Circle> = (0..400)
            .map(|i| {
                let t = i as f64 / 400.0 * std::f64::consts::TAU;
                let r = if i % 7 == 0 { 30 + (i % 11) } else { 0 };
                Circle {
                    x: (5000.0 + 3000.0 * t.cos() + (i % 5) as f64 * 3.0) as i64,
                    y: (5000.0 + 2000.0 * t.sin()) as i64,
                    r,
                }
            })
            .collect();
        let parts = vec![vec![ring]];
        let cur = Cursor {
            start: (0, 0),
            extent: 20000,
            min_radius: 10,
        };
        let b = breakdown(&parts, cur);
        let bits = b.counts + b.flags + b.point_deltas + b.circle_deltas + b.radii;
        let stream = write(&parts, cur).len() as f64 * 8.0;
        assert!(b.radii > 0.0 && b.circle_deltas > 0.0 && b.point_deltas > b.circle_deltas);
        assert!(
            (bits - stream).abs() < 40.0,
            "{bits} bits estimated, {stream} coded"
        );
    }
}
