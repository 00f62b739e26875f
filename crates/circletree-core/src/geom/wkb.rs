//! WKB in and out, through the `wkb` crate (georust).
//!
//! Reading accepts ISO WKB and PostGIS EWKB, names any type that is not a Polygon or MultiPolygon,
//! drops Z and M (and says so), rejects non-finite coordinates, and returns open rings with
//! repeated points removed. Writing produces ISO WKB (little endian, 2D).

use crate::error::{Error, Result};
use crate::geom::{dedup_ring, Kind, Polygon, Ring, Shape};
use geo_traits::{
    CoordTrait, GeometryTrait, GeometryType, LineStringTrait, MultiPolygonTrait, PolygonTrait,
};

/// A geometry read from WKB.
#[derive(Debug, Clone, PartialEq)]
pub struct Input {
    /// The polygon(s), rings open and deduplicated.
    pub shape: Shape,
    /// True when the input had Z or M values, which were dropped.
    pub dropped_zm: bool,
    /// True when every ring was read as it was given: closed, at least four points, no point
    /// repeated in a row, no empty ring or part left out (what [`crate::check::proof`] may be asked).
    pub as_given: bool,
}

const TYPE_NAMES: [&str; 18] = [
    "Geometry",
    "Point",
    "LineString",
    "Polygon",
    "MultiPoint",
    "MultiLineString",
    "MultiPolygon",
    "GeometryCollection",
    "CircularString",
    "CompoundCurve",
    "CurvePolygon",
    "MultiCurve",
    "MultiSurface",
    "Curve",
    "Surface",
    "PolyhedralSurface",
    "TIN",
    "Triangle",
];

/// The geometry type code of a WKB header (ISO or EWKB), without dimension flags.
fn header_type(buf: &[u8]) -> Result<(u32, bool)> {
    if buf.len() < 5 {
        return Err(Error::BadWkb(format!(
            "{} bytes is too short for a WKB header",
            buf.len()
        )));
    }
    let raw = [buf[1], buf[2], buf[3], buf[4]];
    let code = match buf[0] {
        0 => u32::from_be_bytes(raw),
        1 => u32::from_le_bytes(raw),
        b => {
            return Err(Error::BadWkb(format!(
                "byte order marker {b} is neither 0 nor 1"
            )))
        }
    };
    let ewkb_zm = code & 0xC000_0000 != 0;
    let iso = code & 0x0FFF_FFFF;
    Ok((iso % 1000, ewkb_zm || iso >= 1000))
}

/// Whether WKB or EWKB is a Polygon or MultiPolygon (with or without Z and M) by its header:
/// what the encoders ask PostGIS's validity of (other types are refused by their type).
pub fn is_polygonal(buf: &[u8]) -> bool {
    matches!(header_type(buf), Ok((3 | 6, _)))
}

/// Read a Polygon or MultiPolygon from WKB or EWKB.
///
/// ```
/// let wkb = [1u8, 3, 0, 0, 0, 1, 0, 0, 0, 4, 0, 0, 0,
///   0,0,0,0,0,0,0,0, 0,0,0,0,0,0,0,0,  0,0,0,0,0,0,240,63, 0,0,0,0,0,0,0,0,
///   0,0,0,0,0,0,0,0, 0,0,0,0,0,0,240,63, 0,0,0,0,0,0,0,0, 0,0,0,0,0,0,0,0];
/// let input = circletree_core::geom::wkb::read(&wkb).unwrap();
/// assert_eq!(input.shape.parts[0][0].len(), 3);
/// ```
pub fn read(buf: &[u8]) -> Result<Input> {
    let (base, has_zm) = header_type(buf)?;
    if base != 3 && base != 6 {
        let name = TYPE_NAMES
            .get(base as usize)
            .copied()
            .unwrap_or("an unknown WKB type");
        return Err(Error::UnsupportedGeometry(name.to_string()));
    }
    let geom = ::wkb::reader::read_wkb(buf).map_err(|e| Error::BadWkb(e.to_string()))?;
    let mut as_given = true;
    let shape = match geom.as_type() {
        GeometryType::Polygon(p) => Shape {
            kind: Kind::Polygon,
            parts: read_polygon(p, &mut as_given)?.into_iter().collect(),
        },
        GeometryType::MultiPolygon(mp) => {
            let mut parts = Vec::with_capacity(mp.num_polygons().min(1 << 16));
            for p in mp.polygons() {
                if let Some(poly) = read_polygon(&p, &mut as_given)? {
                    parts.push(poly);
                }
            }
            Shape {
                kind: Kind::MultiPolygon,
                parts,
            }
        }
        _ => return Err(Error::BadWkb("unexpected geometry type".into())),
    };
    Ok(Input {
        shape,
        dropped_zm: has_zm,
        as_given,
    })
}

fn read_polygon(p: &impl PolygonTrait<T = f64>, as_given: &mut bool) -> Result<Option<Polygon>> {
    let Some(ext) = p.exterior() else {
        *as_given = false;
        return Ok(None);
    };
    let shell = read_ring(&ext, as_given)?;
    if shell.is_empty() {
        return Ok(None);
    }
    let mut poly = vec![shell];
    for hole in p.interiors() {
        let r = read_ring(&hole, as_given)?;
        if !r.is_empty() {
            poly.push(r);
        }
    }
    Ok(Some(poly))
}

fn read_ring(ls: &impl LineStringTrait<T = f64>, as_given: &mut bool) -> Result<Ring> {
    let mut ring: Ring = Vec::with_capacity(ls.num_coords());
    for c in ls.coords() {
        let (x, y) = (c.x(), c.y());
        if !x.is_finite() || !y.is_finite() {
            return Err(Error::NonFinite(format!("{x} {y}")));
        }
        ring.push([x, y]);
    }
    let given = ring.len();
    let closed = given >= 4 && ring.first() == ring.last();
    dedup_ring(&mut ring);
    if !closed || ring.len() + 1 != given {
        *as_given = false;
    }
    Ok(ring)
}

fn to_geo_polygon(poly: &[Ring]) -> geo::Polygon<f64> {
    let ls = |r: &Ring| -> geo::LineString<f64> {
        let mut v: Vec<geo::Coord<f64>> =
            r.iter().map(|p| geo::Coord { x: p[0], y: p[1] }).collect();
        if let Some(&f) = v.first() {
            v.push(f);
        }
        geo::LineString(v)
    };
    let mut it = poly.iter();
    let shell = it.next().map(ls).unwrap_or_else(|| geo::LineString(vec![]));
    geo::Polygon::new(shell, it.map(ls).collect())
}

/// The shape as a `geo` MultiPolygon (rings closed).
pub fn to_geo(parts: &[Polygon]) -> geo::MultiPolygon<f64> {
    geo::MultiPolygon(parts.iter().map(|p| to_geo_polygon(p)).collect())
}

/// Points a ring is written with: closed, unless it is empty.
fn closed_len(r: &Ring) -> usize {
    r.len() + usize::from(!r.is_empty())
}

/// The rings a polygon is written with: none when its shell is empty.
fn poly_rings(p: &Polygon) -> &[Ring] {
    match p.first() {
        Some(shell) if !shell.is_empty() => p,
        _ => &[],
    }
}

/// Write rings as ISO WKB (little endian). Rings are given open and written closed (an empty
/// ring stays empty; a polygon with an empty shell has no rings). Written straight into one
/// buffer of the final size, with no `geo` copy on the way (this is every `ct_decode`'s
/// output); the `wkb` crate's writer is the reference it is tested against.
pub fn write(kind: Kind, parts: &[Polygon]) -> Vec<u8> {
    write_ewkb(kind, parts, 0)
}

/// [`write`] as PostGIS's EWKB with `srid` (when not 0): the outer type word gets the SRID flag
/// and the SRID follows it; nested polygons carry none, as PostGIS writes them.
pub fn write_ewkb(kind: Kind, parts: &[Polygon], srid: i32) -> Vec<u8> {
    const SRID_FLAG: u32 = 0x2000_0000;
    let ring_bytes = |r: &Ring| 4 + 16 * closed_len(r);
    let poly_bytes = |p: &Polygon| 9 + poly_rings(p).iter().map(ring_bytes).sum::<usize>();
    let srid_bytes = if srid == 0 { 0 } else { 4 };
    let size = srid_bytes
        + match kind {
            Kind::Polygon => parts.first().map_or(9, poly_bytes),
            Kind::MultiPolygon => 9 + parts.iter().map(poly_bytes).sum::<usize>(),
        };
    let mut out = Vec::with_capacity(size);
    let head = |out: &mut Vec<u8>, code: u32, n: usize, srid: i32| {
        out.push(1);
        if srid == 0 {
            out.extend_from_slice(&code.to_le_bytes());
        } else {
            out.extend_from_slice(&(code | SRID_FLAG).to_le_bytes());
            out.extend_from_slice(&srid.to_le_bytes());
        }
        out.extend_from_slice(&(n as u32).to_le_bytes());
    };
    let polygon = |out: &mut Vec<u8>, p: &Polygon, srid: i32| {
        let rings = poly_rings(p);
        head(out, 3, rings.len(), srid);
        for r in rings {
            out.extend_from_slice(&(closed_len(r) as u32).to_le_bytes());
            for q in r.iter().chain(r.first()) {
                out.extend_from_slice(&q[0].to_le_bytes());
                out.extend_from_slice(&q[1].to_le_bytes());
            }
        }
    };
    match kind {
        Kind::Polygon => match parts.first() {
            Some(p) => polygon(&mut out, p, srid),
            None => head(&mut out, 3, 0, srid),
        },
        Kind::MultiPolygon => {
            head(&mut out, 6, parts.len(), srid);
            for p in parts {
                polygon(&mut out, p, 0);
            }
        }
    }
    debug_assert_eq!(out.len(), size);
    out
}

/// The `wkb` crate's writer through `geo` types: the reference [`write`] is tested against.
#[cfg(test)]
fn write_by_crate(kind: Kind, parts: &[Polygon]) -> Vec<u8> {
    let mut out = Vec::new();
    let opts = ::wkb::writer::WriteOptions {
        endianness: ::wkb::Endianness::LittleEndian,
    };
    let res = match (kind, parts.first()) {
        (Kind::Polygon, None) => {
            out.extend_from_slice(&[1, 3, 0, 0, 0, 0, 0, 0, 0]);
            Ok(())
        }
        (Kind::Polygon, Some(p)) => {
            ::wkb::writer::write_polygon(&mut out, &to_geo_polygon(p), &opts)
        }
        (Kind::MultiPolygon, _) => {
            ::wkb::writer::write_multi_polygon(&mut out, &to_geo(parts), &opts)
        }
    };
    assert!(res.is_ok());
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_direct_writer_writes_what_the_wkb_crate_writes() {
        let sq = |x: f64, y: f64, s: f64| vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]];
        let cases: Vec<(Kind, Vec<Polygon>)> = vec![
            (Kind::Polygon, vec![]),
            (Kind::MultiPolygon, vec![]),
            (Kind::Polygon, vec![vec![sq(0.0, 0.0, 10.0)]]),
            (
                Kind::Polygon,
                vec![vec![
                    sq(0.0, 0.0, 10.0),
                    sq(2.0, 2.0, 1.5),
                    sq(5.0, 5.0, 1.0),
                ]],
            ),
            (
                Kind::MultiPolygon,
                vec![
                    vec![sq(0.0, 0.0, 1.0)],
                    vec![sq(5.0, -3.25, 1e-9), sq(5.0, -3.25, 1e-10)],
                ],
            ),
            (Kind::Polygon, vec![vec![vec![]]]),
            (
                Kind::Polygon,
                vec![vec![sq(0.0, 0.0, 10.0), vec![], sq(2.0, 2.0, 1.0)]],
            ),
            (
                Kind::MultiPolygon,
                vec![vec![vec![]], vec![sq(1e300, -1e-300, 1.0)]],
            ),
        ];
        for (kind, parts) in cases {
            assert_eq!(
                write(kind, &parts),
                write_by_crate(kind, &parts),
                "{kind:?} {parts:?}"
            );
        }
    }

    #[test]
    fn round_trip_polygon_with_hole() {
        let parts = vec![vec![
            vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]],
            vec![[2.0, 2.0], [2.0, 4.0], [4.0, 4.0], [4.0, 2.0]],
        ]];
        let bytes = write(Kind::Polygon, &parts);
        assert_eq!(bytes.len(), 9 + 2 * (4 + 5 * 16));
        let back = read(&bytes).unwrap();
        assert_eq!(back.shape.parts, parts);
        assert!(!back.dropped_zm);
    }

    #[test]
    fn polygonal_headers() {
        let wkb = |le: bool, code: u32| {
            let mut w = vec![u8::from(le)];
            w.extend(if le {
                code.to_le_bytes()
            } else {
                code.to_be_bytes()
            });
            w
        };
        for code in [
            3,
            6,
            1003,
            2006,
            3003,
            0x2000_0003,
            0x8000_0006,
            0xC000_0003,
        ] {
            assert!(is_polygonal(&wkb(true, code)), "{code:#x}");
            assert!(is_polygonal(&wkb(false, code)), "{code:#x}");
        }
        for code in [1, 2, 4, 5, 7, 1001, 3002, 0x2000_0007, 10, 15, 17] {
            assert!(!is_polygonal(&wkb(true, code)), "{code:#x}");
        }
        assert!(!is_polygonal(&[1, 3, 0]));
        assert!(!is_polygonal(&[2, 3, 0, 0, 0]));
        assert!(!is_polygonal(&[]));
    }

    #[test]
    fn names_unsupported_types() {
        let point = [
            1u8, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
        ];
        assert_eq!(
            read(&point),
            Err(Error::UnsupportedGeometry("Point".into()))
        );
        let curve = [1u8, 10, 0, 0, 0, 0, 0, 0, 0];
        assert_eq!(
            read(&curve),
            Err(Error::UnsupportedGeometry("CurvePolygon".into()))
        );
        assert!(matches!(read(&[1u8, 3]), Err(Error::BadWkb(_))));
    }

    #[test]
    fn empty_round_trips() {
        let e = write(Kind::Polygon, &[]);
        assert!(read(&e).unwrap().shape.is_empty());
        let m = write(Kind::MultiPolygon, &[]);
        let back = read(&m).unwrap();
        assert_eq!(back.shape.kind, Kind::MultiPolygon);
        assert!(back.shape.is_empty());
    }
}
