//! Plain polygon geometry: points, open rings, polygons with holes, multipolygons.
//!
//! Rings are stored *open* (no repeated closing point). [`orient`] puts every ring so that the
//! polygon's interior is on its left: shells counter-clockwise, holes clockwise. The encoder relies
//! on that: a circle with positive radius lies on the left of the ring (inside the polygon).

pub(crate) mod box_grid;
pub(crate) mod clearance;
pub mod gserialized;
pub mod wkb;

/// A point `[x, y]`.
pub type Pt = [f64; 2];
/// An open ring: the closing point is implied.
pub type Ring = Vec<Pt>;
/// A polygon: its shell, then its holes.
pub type Polygon = Vec<Ring>;

/// The kind of geometry a value stores.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// One polygon (zero parts when empty).
    Polygon,
    /// Any number of polygons.
    MultiPolygon,
}

impl Kind {
    /// The WKB type code (3 or 6).
    pub fn wkb_code(self) -> u8 {
        match self {
            Kind::Polygon => 3,
            Kind::MultiPolygon => 6,
        }
    }
    /// From the WKB type code.
    pub fn from_wkb_code(code: u8) -> Option<Kind> {
        match code {
            3 => Some(Kind::Polygon),
            6 => Some(Kind::MultiPolygon),
            _ => None,
        }
    }
    /// The WKT keyword.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Polygon => "POLYGON",
            Kind::MultiPolygon => "MULTIPOLYGON",
        }
    }
}

/// A Polygon or MultiPolygon (a Polygon has at most one part).
#[derive(Clone, Debug, PartialEq)]
pub struct Shape {
    /// Polygon or MultiPolygon.
    pub kind: Kind,
    /// The parts; each part is its shell followed by its holes.
    pub parts: Vec<Polygon>,
}

impl Shape {
    /// `ST_NPoints`: vertices with every ring's closing point counted.
    pub fn npoints(&self) -> usize {
        self.rings().map(|r| r.len() + 1).sum()
    }
    /// True when there is no part.
    pub fn is_empty(&self) -> bool {
        self.parts.is_empty()
    }
    /// Every ring of every part.
    pub fn rings(&self) -> impl Iterator<Item = &Ring> {
        self.parts.iter().flat_map(|p| p.iter())
    }
    /// `[xmin, ymin, xmax, ymax]`, or `None` when empty.
    pub fn bbox(&self) -> Option<[f64; 4]> {
        let mut it = self.rings().flat_map(|r| r.iter());
        let first = it.next()?;
        let mut b = [first[0], first[1], first[0], first[1]];
        for p in it {
            b[0] = b[0].min(p[0]);
            b[1] = b[1].min(p[1]);
            b[2] = b[2].max(p[0]);
            b[3] = b[3].max(p[1]);
        }
        Some(b)
    }
    /// Area of the shape (shells minus holes), whatever the ring orientation.
    pub fn area(&self) -> f64 {
        self.parts
            .iter()
            .map(|p| {
                p.iter()
                    .enumerate()
                    .map(|(i, r)| {
                        let a = signed_area(r).abs();
                        if i == 0 {
                            a
                        } else {
                            -a
                        }
                    })
                    .sum::<f64>()
            })
            .sum()
    }
}

/// Twice-free signed area of an open ring (positive when counter-clockwise).
pub fn signed_area(ring: &[Pt]) -> f64 {
    let n = ring.len();
    if n < 3 {
        return 0.0;
    }
    // Shoelace relative to the first point, to keep digits for UTM-sized coordinates.
    let o = ring[0];
    let mut s = 0.0;
    for i in 1..n - 1 {
        let a = [ring[i][0] - o[0], ring[i][1] - o[1]];
        let b = [ring[i + 1][0] - o[0], ring[i + 1][1] - o[1]];
        s += a[0] * b[1] - a[1] * b[0];
    }
    s / 2.0
}

/// Orient every ring so the polygon interior is on its left (shells CCW, holes CW).
pub fn orient(shape: &mut Shape) {
    for part in &mut shape.parts {
        for (i, ring) in part.iter_mut().enumerate() {
            let ccw = signed_area(ring) > 0.0;
            if ccw != (i == 0) {
                ring.reverse();
            }
        }
    }
}

/// Drop consecutive repeated points (and a last point equal to the first).
pub fn dedup_ring(ring: &mut Ring) {
    ring.dedup();
    while ring.len() > 1 && ring.first() == ring.last() {
        ring.pop();
    }
}

/// Euclidean distance.
#[inline]
pub fn dist(a: Pt, b: Pt) -> f64 {
    // Coordinates are far below 1e150: the squares cannot overflow, and `sqrt` is several
    // times faster than `hypot`.
    let (dx, dy) = (a[0] - b[0], a[1] - b[1]);
    (dx * dx + dy * dy).sqrt()
}

/// Distance from `p` to the segment `a`-`b`.
#[inline]
pub fn dist_to_segment(p: Pt, a: Pt, b: Pt) -> f64 {
    dist2_to_segment(p, a, b).sqrt()
}

/// Squared distance from `p` to the segment `a`-`b`.
#[inline]
pub fn dist2_to_segment(p: Pt, a: Pt, b: Pt) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    let t = if len2 == 0.0 {
        0.0
    } else {
        (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
    };
    let (dx, dy) = (p[0] - a[0] - t * d[0], p[1] - a[1] - t * d[1]);
    dx * dx + dy * dy
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_and_area() {
        let mut s = Shape {
            kind: Kind::Polygon,
            parts: vec![vec![
                vec![[0.0, 0.0], [0.0, 10.0], [10.0, 10.0], [10.0, 0.0]],
                vec![[2.0, 2.0], [4.0, 2.0], [4.0, 4.0], [2.0, 4.0]],
            ]],
        };
        assert_eq!(s.area(), 96.0);
        orient(&mut s);
        assert!(signed_area(&s.parts[0][0]) > 0.0);
        assert!(signed_area(&s.parts[0][1]) < 0.0);
        assert_eq!(s.npoints(), 10);
        assert_eq!(s.bbox(), Some([0.0, 0.0, 10.0, 10.0]));
    }

    #[test]
    fn segment_distance() {
        assert_eq!(dist_to_segment([5.0, 3.0], [0.0, 0.0], [10.0, 0.0]), 3.0);
        assert_eq!(dist_to_segment([13.0, 4.0], [0.0, 0.0], [10.0, 0.0]), 5.0);
    }
}
