//! Format version 1, frozen: written by release 0.1.0, read by every release after it. After the
//! shared header, per part: varint nrings; per ring: varint ncircles; per circle: zigzag dx,
//! zigzag dy (from the previous circle's centre), zigzag r.

use super::{Circle, Cursor, Reader, Writer};
use crate::error::{Error, Result};

/// The circles of a value, after the header.
pub fn write(w: &mut Writer, parts: &[Vec<Vec<Circle>>], cur: Cursor) {
    let mut cur = cur.start;
    for part in parts {
        w.put(&(part.len() as u64));
        for ring in part {
            w.put(&(ring.len() as u64));
            for c in ring {
                w.put(&(c.x - cur.0));
                w.put(&(c.y - cur.1));
                w.put(&c.r);
                cur = (c.x, c.y);
            }
        }
    }
}

/// Read `nparts` parts; every count is checked against the bytes left first.
pub fn read(r: &mut Reader, nparts: usize, cur: Cursor) -> Result<Vec<Vec<Vec<Circle>>>> {
    let mut cur = cur.start;
    let mut parts = Vec::with_capacity(nparts);
    for _ in 0..nparts {
        let nrings = r.count("rings", 4)?;
        let mut rings = Vec::with_capacity(nrings);
        for _ in 0..nrings {
            let n = r.count("circles", 3)?;
            let mut ring = Vec::with_capacity(n);
            for _ in 0..n {
                let dx: i64 = r.take("a circle")?;
                let dy: i64 = r.take("a circle")?;
                let rad: i64 = r.take("a circle")?;
                let (Some(x), Some(y)) = (cur.0.checked_add(dx), cur.1.checked_add(dy)) else {
                    return Err(Error::Corrupt("a circle's coordinates overflow".into()));
                };
                cur = (x, y);
                ring.push(Circle { x, y, r: rad });
            }
            rings.push(ring);
        }
        parts.push(rings);
    }
    if !r.buf.is_empty() {
        return Err(Error::Corrupt(format!(
            "{} bytes left over after the last circle",
            r.buf.len()
        )));
    }
    Ok(parts)
}
