//! A picture of a value, as the paper draws its figures 9, 10 and 15: the original boundary (when
//! given), the circles inside (positive radius) and outside (negative), the zero-radius boundary
//! points, and the polygon the decoder rebuilds from them, with a legend. Written with the `svg`
//! crate; y grows upwards as in the data (the drawing is flipped into SVG's downward y).

use crate::decode;
use crate::error::{Error, Result};
use crate::format::CircleTree;
use crate::geom::{Polygon, Pt};
use svg::node::element::path::Data;
use svg::node::element::{Circle, Group, Line, Path, Rectangle, Text};
use svg::Document;

/// Widths `ct_svg` accepts, in pixels.
pub const WIDTHS: (u32, u32) = (16, 8192);

const ORIGINAL: &str = "#9e9e9e";
const INSIDE: &str = "#1f77b4";
const OUTSIDE: &str = "#d62728";
const POINT: &str = "#2ca02c";
const REBUILT: &str = "#000000";

/// What the picture shows, counted (for tests and captions).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    /// Circles with a positive radius.
    pub inside: usize,
    /// Circles with a negative radius.
    pub outside: usize,
    /// Zero-radius circles (boundary points).
    pub points: usize,
    /// Rings of the rebuilt polygon.
    pub rings: usize,
}

/// The SVG document of `ct` (and of `original`, drawn beneath it), `width` pixels wide.
pub fn to_svg(
    ct: &CircleTree,
    original: Option<&[Polygon]>,
    width: u32,
) -> Result<(String, Counts)> {
    if !(WIDTHS.0..=WIDTHS.1).contains(&width) {
        return Err(Error::InvalidParameter {
            name: "width",
            value: width.to_string(),
            range: format!("between {} and {} pixels", WIDTHS.0, WIDTHS.1),
        });
    }
    let tol = decode::arc_tolerance(ct, None)?;
    decode::check_size(ct, tol)?;
    let rebuilt = decode::polygons(ct, tol);
    // the box of everything drawn: circles reach beyond the boundary
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    let mut grow = |x: f64, y: f64, r: f64| {
        b[0] = b[0].min(x - r);
        b[1] = b[1].min(y - r);
        b[2] = b[2].max(x + r);
        b[3] = b[3].max(y + r);
    };
    let circles: Vec<[f64; 3]> = ct
        .parts
        .iter()
        .flatten()
        .flat_map(|ring| decode::ring_circles(ct, ring))
        .collect();
    for c in &circles {
        grow(c[0], c[1], c[2].abs());
    }
    for p in rebuilt
        .iter()
        .chain(original.unwrap_or(&[]))
        .flatten()
        .flatten()
    {
        grow(p[0], p[1], 0.0);
    }
    if !b[0].is_finite() {
        b = [0.0, 0.0, 1.0, 1.0];
    }
    let span = (b[2] - b[0]).max(b[3] - b[1]).max(f64::MIN_POSITIVE);
    let legend_h = 18.0 * 5.0 + 8.0;
    let scale = f64::from(width) / span;
    let height = ((b[3] - b[1]) * scale).ceil() + legend_h;
    // data to pixels, y flipped
    let px = |p: Pt| (((p[0] - b[0]) * scale), legend_h + (b[3] - p[1]) * scale);
    let ring_path = |ring: &[Pt], colour: &str, stroke: f64, dash: Option<&str>| {
        let mut d = Data::new();
        for (k, p) in ring.iter().enumerate() {
            let (x, y) = px(*p);
            d = if k == 0 {
                d.move_to((round(x), round(y)))
            } else {
                d.line_to((round(x), round(y)))
            };
        }
        let mut path = Path::new()
            .set("d", d.close())
            .set("fill", "none")
            .set("stroke", colour)
            .set("stroke-width", stroke);
        if let Some(dash) = dash {
            path = path.set("stroke-dasharray", dash);
        }
        path
    };
    let mut counts = Counts::default();
    let mut doc = Document::new()
        .set("width", width)
        .set("height", height)
        .set("viewBox", (0, 0, width, height))
        .add(
            Rectangle::new()
                .set("width", "100%")
                .set("height", "100%")
                .set("fill", "#ffffff"),
        );
    if let Some(orig) = original {
        let mut g = Group::new().set("id", "original");
        for ring in orig.iter().flatten() {
            g = g.add(ring_path(ring, ORIGINAL, 3.0, None));
        }
        doc = doc.add(g);
    }
    let (mut inside, mut outside, mut points) = (
        Group::new()
            .set("id", "inside")
            .set("fill", "none")
            .set("stroke", INSIDE),
        Group::new()
            .set("id", "outside")
            .set("fill", "none")
            .set("stroke", OUTSIDE),
        Group::new().set("id", "points").set("fill", POINT),
    );
    for c in &circles {
        let (x, y) = px([c[0], c[1]]);
        let r = c[2].abs() * scale;
        let shape = Circle::new().set("cx", round(x)).set("cy", round(y));
        if c[2] > 0.0 {
            counts.inside += 1;
            inside = inside.add(shape.set("r", round(r)).set("stroke-width", 0.6));
        } else if c[2] < 0.0 {
            counts.outside += 1;
            outside = outside.add(shape.set("r", round(r)).set("stroke-width", 0.6));
        } else {
            counts.points += 1;
            points = points.add(shape.set("r", 1.6));
        }
    }
    doc = doc.add(inside).add(outside);
    let mut g = Group::new().set("id", "rebuilt");
    for ring in rebuilt.iter().flatten() {
        counts.rings += 1;
        g = g.add(ring_path(ring, REBUILT, 1.0, None));
    }
    doc = doc.add(g).add(points);
    // legend
    let rows: [(&str, String); 5] = [
        (ORIGINAL, "original boundary".into()),
        (INSIDE, format!("{} circles inside (r > 0)", counts.inside)),
        (
            OUTSIDE,
            format!("{} circles outside (r < 0)", counts.outside),
        ),
        (POINT, format!("{} boundary points (r = 0)", counts.points)),
        (
            REBUILT,
            format!("rebuilt: tangents and arcs, within {}", ct.params.max_error),
        ),
    ];
    let mut legend = Group::new()
        .set("id", "legend")
        .set("font-family", "sans-serif")
        .set("font-size", 12);
    for (k, (colour, label)) in rows.iter().enumerate() {
        if k == 0 && original.is_none() {
            continue;
        }
        let y = 14.0 + 18.0 * k as f64;
        legend = legend
            .add(
                Line::new()
                    .set("x1", 6)
                    .set("y1", y - 4.0)
                    .set("x2", 26)
                    .set("y2", y - 4.0)
                    .set("stroke", *colour)
                    .set("stroke-width", 3),
            )
            .add(
                Text::new(label.clone())
                    .set("x", 32)
                    .set("y", y)
                    .set("fill", "#000000"),
            );
    }
    doc = doc.add(legend);
    Ok((doc.to_string(), counts))
}

fn round(v: f64) -> f64 {
    (v * 100.0).round() / 100.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_every_circle_and_the_legend() {
        let ct = crate::format::text::from_text(
            "CIRCLETREE(version=2;grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;\
             vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,100 100);\
             POLYGON((20 20 10,80 20 0,80 80 -5,20 80 0)))",
        )
        .unwrap();
        let (svg, counts) = to_svg(&ct, None, 400).unwrap();
        assert_eq!(
            counts,
            Counts {
                inside: 1,
                outside: 1,
                points: 2,
                rings: 1
            }
        );
        assert!(svg.starts_with("<svg"));
        assert_eq!(svg.matches("<circle").count(), 4);
        assert!(svg.contains("1 circles inside") && !svg.contains("original boundary"));
        let orig = vec![vec![vec![
            [0.0, 0.0],
            [100.0, 0.0],
            [100.0, 100.0],
            [0.0, 100.0],
        ]]];
        let (svg, _) = to_svg(&ct, Some(&orig), 400).unwrap();
        assert!(svg.contains("original boundary") && svg.contains("id=\"original\""));
        assert!(to_svg(&ct, None, 3).is_err());
    }
}
