//! PostGIS's own geometry bytes (`GSERIALIZED`, versions 1 and 2, as `geometry` datums hold them,
//! after the varlena header), read in place for what the predicates need: the SRID, the type, a
//! point's coordinates and the box, and on request the lines or polygons themselves
//! ([`read_linework`]). Anything this reader does not know is `None`, and the caller asks PostGIS
//! instead.
//!
//! The layout (PostGIS's `gserialized.txt`), after the varlena header: the SRID in 3 bytes (21
//! bits, signed); a flags byte (Z 0x01, M 0x02, box 0x04, geodetic 0x08; in version 2, bit 0x40
//! set, 0x10 says 8 bytes of extended flags follow); the box as floats (min and max of each
//! dimension, 6 floats when geodetic) when flagged; then the geometry, native byte order: a
//! `u32` type and a `u32` count, a polygon's ring counts padded to 8 bytes, the doubles.

use super::Pt;

/// What the reader found.
#[derive(Clone, Debug, PartialEq)]
pub struct Serialized {
    /// The SRID (0: unknown).
    pub srid: i32,
    /// PostGIS's type number (1 Point, 3 Polygon, 6 MultiPolygon, ...).
    pub kind: u32,
    /// Whether it has no coordinate.
    pub empty: bool,
    /// The point's x and y when it is a Point.
    pub point: Option<[f64; 2]>,
    /// The box `[xmin, ymin, xmax, ymax]`: the stored float box when there is one (rounded
    /// outwards by PostGIS), else the coordinates' own; `None` when empty. [`float_box`] of it
    /// is what PostGIS's `&&` compares.
    pub bbox: Option<[f64; 4]>,
    /// Geodetic (a geography).
    pub geodetic: bool,
}

/// A (multi)linestring's lines or a (multi)polygon's polygons (each its shell, then its holes),
/// x and y only, rings closed as stored.
#[derive(Clone, Debug, PartialEq)]
pub enum Linework {
    /// LineString or MultiLineString.
    Lines(Vec<Vec<Pt>>),
    /// Polygon or MultiPolygon.
    Polygons(Vec<Vec<Vec<Pt>>>),
}

const POINT: u32 = 1;

/// A box rounded outwards to floats, as PostGIS's `&&` sees every box (its `BOX2DF`: the
/// largest float not above each minimum, the smallest not below each maximum).
pub fn float_box(b: [f64; 4]) -> [f64; 4] {
    let down = |d: f64| {
        let f = d as f32;
        f64::from(if f64::from(f) > d { f.next_down() } else { f })
    };
    let up = |d: f64| {
        let f = d as f32;
        f64::from(if f64::from(f) < d { f.next_up() } else { f })
    };
    [down(b[0]), down(b[1]), up(b[2]), up(b[3])]
}

/// Read a geometry datum's bytes (after its varlena header); `None` when they are not a geometry this reader knows.
pub fn read(bytes: &[u8]) -> Option<Serialized> {
    read_as(bytes, false).map(|(s, _)| s)
}

/// As [`read`], with the lines or polygons when the geometry is a (multi)linestring or a
/// (multi)polygon (`None` for any other type).
pub fn read_linework(bytes: &[u8]) -> Option<(Serialized, Option<Linework>)> {
    read_as(bytes, true)
}

fn read_as(bytes: &[u8], collect: bool) -> Option<(Serialized, Option<Linework>)> {
    let head = bytes.get(..4)?;
    let raw = (i32::from(head[0]) << 16) | (i32::from(head[1]) << 8) | i32::from(head[2]);
    let srid = (raw << 11) >> 11;
    let flags = head[3];
    let v2 = flags & 0x40 != 0;
    let (z, m, has_box, geodetic) = (
        flags & 1 != 0,
        flags & 2 != 0,
        flags & 4 != 0,
        flags & 8 != 0,
    );
    let dims = 2 + usize::from(z) + usize::from(m);
    let mut at = 4;
    if v2 && flags & 0x10 != 0 {
        at += 8;
    }
    let mut bbox = None;
    if has_box {
        let nf = if geodetic { 6 } else { 2 * dims };
        let f = |i: usize| -> Option<f64> {
            let b = bytes.get(at + 4 * i..at + 4 * i + 4)?;
            Some(f64::from(f32::from_ne_bytes(b.try_into().ok()?)))
        };
        if !geodetic {
            bbox = Some([f(0)?, f(2)?, f(1)?, f(3)?]);
        }
        at += 4 * nf;
    }
    let mut r = Reader {
        bytes,
        at,
        dims,
        bbox: [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        n: 0,
        collect,
        lines: Vec::new(),
        polygons: Vec::new(),
    };
    let kind = r.u32()?;
    let mut point = None;
    if kind == POINT {
        let n = r.u32()?;
        if n == 1 {
            let p = [r.f64_at(r.at)?, r.f64_at(r.at + 8)?];
            point = Some(p);
        }
        r.at -= 8;
    } else {
        r.at -= 4;
    }
    r.geometry(0)?;
    let empty = r.n == 0;
    let coords_box = (!empty).then_some(r.bbox);
    let linework = match kind {
        2 | 5 if collect => Some(Linework::Lines(r.lines)),
        3 | 6 if collect => Some(Linework::Polygons(r.polygons)),
        _ => None,
    };
    let s = Serialized {
        srid,
        kind,
        empty,
        point,
        bbox: if empty { None } else { bbox.or(coords_box) },
        geodetic,
    };
    Some((s, linework))
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
    dims: usize,
    bbox: [f64; 4],
    n: usize,
    collect: bool,
    lines: Vec<Vec<Pt>>,
    polygons: Vec<Vec<Vec<Pt>>>,
}

impl Reader<'_> {
    fn u32(&mut self) -> Option<u32> {
        let b = self.bytes.get(self.at..self.at + 4)?;
        self.at += 4;
        Some(u32::from_ne_bytes(b.try_into().ok()?))
    }

    fn f64_at(&self, at: usize) -> Option<f64> {
        let b = self.bytes.get(at..at + 8)?;
        Some(f64::from_ne_bytes(b.try_into().ok()?))
    }

    fn points(&mut self, n: u32) -> Option<Vec<Pt>> {
        let mut out = Vec::new();
        if self.collect {
            // the count is the datum's: bounded by its length before anything is reserved
            let bytes = (n as usize).checked_mul(8 * self.dims)?;
            self.bytes.get(self.at..self.at.checked_add(bytes)?)?;
            out.reserve_exact(n as usize);
        }
        for _ in 0..n {
            let (x, y) = (self.f64_at(self.at)?, self.f64_at(self.at + 8)?);
            if self.collect {
                out.push([x, y]);
            }
            self.bbox = [
                self.bbox[0].min(x),
                self.bbox[1].min(y),
                self.bbox[2].max(x),
                self.bbox[3].max(y),
            ];
            self.at += 8 * self.dims;
            self.n += 1;
        }
        Some(out)
    }

    fn geometry(&mut self, depth: usize) -> Option<()> {
        if depth > 32 {
            return None;
        }
        let kind = self.u32()?;
        let count = self.u32()?;
        match kind {
            2 => {
                let line = self.points(count)?;
                if self.collect {
                    self.lines.push(line);
                }
                Some(())
            }
            1 | 8 | 14 => self.points(count).map(drop),
            3 => {
                let counts: Vec<u32> = (0..count).map(|_| self.u32()).collect::<Option<_>>()?;
                if count % 2 == 1 {
                    self.at += 4;
                }
                let rings: Vec<Vec<Pt>> = counts
                    .into_iter()
                    .map(|n| self.points(n))
                    .collect::<Option<_>>()?;
                if self.collect {
                    self.polygons.push(rings);
                }
                Some(())
            }
            4..=7 | 9..=13 | 15 => (0..count).try_for_each(|_| self.geometry(depth + 1)),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn datum(srid: i32, flags: u8, body: &[u8]) -> Vec<u8> {
        let s = (srid as u32) & 0x1F_FFFF;
        let mut v = vec![(s >> 16) as u8, (s >> 8) as u8, s as u8, flags];
        v.extend_from_slice(body);
        v
    }

    fn words(w: &[u32], d: &[f64]) -> Vec<u8> {
        let mut v: Vec<u8> = w.iter().flat_map(|x| x.to_ne_bytes()).collect();
        v.extend(d.iter().flat_map(|x| x.to_ne_bytes()));
        v
    }

    #[test]
    fn points_polygons_and_the_srid() {
        let p = read(&datum(3857, 0x40, &words(&[1, 1], &[1.5, -2.0]))).unwrap();
        assert_eq!(
            (p.srid, p.kind, p.point, p.empty),
            (3857, 1, Some([1.5, -2.0]), false)
        );
        assert_eq!(p.bbox, Some([1.5, -2.0, 1.5, -2.0]));
        let e = read(&datum(0, 0x40, &words(&[1, 0], &[]))).unwrap();
        assert!(e.empty && e.point.is_none() && e.bbox.is_none());
        let neg = read(&datum(-5, 0x40, &words(&[1, 1], &[0.0, 0.0]))).unwrap();
        assert_eq!(neg.srid, -5);
        // a version-1 3-D point: the third double is skipped
        let z = read(&datum(4326, 0x01, &words(&[1, 1], &[3.0, 4.0, 5.0]))).unwrap();
        assert_eq!(z.point, Some([3.0, 4.0]));
        // a polygon with a stored box (floats: xmin xmax ymin ymax) and one ring (padded)
        let mut body: Vec<u8> = [0.0f32, 2.0, -1.0, 1.0]
            .iter()
            .flat_map(|f| f.to_ne_bytes())
            .collect();
        body.extend(words(
            &[3, 1, 4, 0],
            &[0.0, -1.0, 2.0, 0.0, 0.0, 1.0, 0.0, -1.0],
        ));
        let poly = read(&datum(32760, 0x44, &body)).unwrap();
        assert_eq!(
            (poly.kind, poly.point, poly.bbox),
            (3, None, Some([0.0, -1.0, 2.0, 1.0]))
        );
        // a collection of two points, no box: the coordinates' own
        let mut body = words(&[4, 2, 1, 1], &[5.0, 6.0]);
        body.extend(words(&[1, 1], &[-5.0, 7.0]));
        let mp = read(&datum(0, 0x40, &body)).unwrap();
        assert_eq!((mp.point, mp.bbox), (None, Some([-5.0, 6.0, 5.0, 7.0])));
        assert!(read(&datum(0, 0x40, &words(&[99, 0], &[]))).is_none());
        assert!(read(&datum(0, 0x40, &words(&[3, 5], &[]))).is_none());
    }

    #[test]
    fn lines_and_polygons_are_read_on_request() {
        // a 3-D linestring: z is dropped
        let l = datum(0, 0x41, &words(&[2, 2], &[0.0, 1.0, 9.0, 2.0, 3.0, 9.0]));
        let (s, lw) = read_linework(&l).unwrap();
        assert_eq!(s.kind, 2);
        assert_eq!(
            lw,
            Some(Linework::Lines(vec![vec![[0.0, 1.0], [2.0, 3.0]]]))
        );
        // a multipolygon of one polygon with two rings
        let mut body = words(&[6, 1, 3, 2, 4, 4], &[]);
        body.extend(words(&[], &[0.0, 0.0, 4.0, 0.0, 0.0, 4.0, 0.0, 0.0]));
        body.extend(words(&[], &[1.0, 1.0, 2.0, 1.0, 1.0, 2.0, 1.0, 1.0]));
        let (_, lw) = read_linework(&datum(0, 0x40, &body)).unwrap();
        let Some(Linework::Polygons(p)) = lw else {
            panic!("{lw:?}")
        };
        assert_eq!((p.len(), p[0].len(), p[0][1][1]), (1, 2, [2.0, 1.0]));
        // a point has none; a count larger than the bytes is refused
        let (_, none) = read_linework(&datum(0, 0x40, &words(&[1, 1], &[1.0, 2.0]))).unwrap();
        assert_eq!(none, None);
        assert!(read_linework(&datum(0, 0x40, &words(&[2, 1 << 30], &[1.0, 2.0]))).is_none());
        // read() alone collects nothing and agrees on the rest
        assert_eq!(read(&l).unwrap(), s);
    }

    #[test]
    fn boxes_round_outwards_to_floats() {
        let b = float_box([500101.001, -0.1, 500101.001, 6000050.0]);
        assert!(b[0] < 500101.001 && b[2] > 500101.001);
        assert_eq!((b[0], b[2]), (500101.0, 500101.03125)); // floats 1/32 apart there
        assert!(b[1] < -0.1 && b[1] as f32 as f64 == b[1]);
        assert_eq!(b[3], 6000050.0); // a float already
        assert!(float_box([f64::NAN; 4])[0].is_nan());
    }
}
