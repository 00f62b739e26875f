//! Rebuild a ring from its ordered circles (paper section 3.5): a tangent between each pair of
//! consecutive circles (and from the last to the first), joined at each circle by its arc or, where
//! the two tangents cross, by their intersection.
//!
//! A circle `(c, ρ)` has the boundary on its right when `ρ > 0` (the circle lies inside the polygon,
//! the ring turns counter-clockwise around it), on its left when `ρ < 0`, and passes through `c`
//! when `ρ = 0`. With unit left normal `n` of a directed line, a circle touches the line on the
//! correct side exactly when `n·(c − p) = ρ` for the line's points `p`. For circles A and B this
//! gives one equation for all four internal/external cases of the paper:
//! `n·(c_B − c_A) = ρ_B − ρ_A`, so with `u` the unit vector from A to B, `v` its left normal,
//! `a = (ρ_B − ρ_A)/|c_B − c_A|`: `n = a·u + √(1−a²)·v`, and the tangent points are `c − ρ·n`.
//! When `|a| > 1` (one circle inside the other) no tangent exists; `a` is clamped, the result is
//! still a closed ring, and the encoder's check rejects it. Decoding never fails.
//!
//! At a circle the incoming tangent arrives at `p_in` and the outgoing one leaves at `p_out`.
//! Walking the circle in its own direction from `p_in` to `p_out` sweeps `θ`. When `|θ| ≤ 3π/2`
//! the join is that arc; otherwise the boundary turns the other way by less than a right angle
//! and the join is the intersection of the two tangent lines (a corner).
//!
//! Cost: O(m) for m circles, plus the stroked points.

use crate::geom::Pt;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// A piece of a rebuilt ring.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Seg {
    /// A straight segment.
    Line(Pt, Pt),
    /// A circular arc: centre, radius (> 0), start angle, signed sweep (> 0 counter-clockwise).
    Arc {
        /// Centre.
        c: Pt,
        /// Radius.
        r: f64,
        /// Start angle, radians.
        a0: f64,
        /// Signed sweep, radians.
        sweep: f64,
        /// Exact start point (where the incoming tangent ends).
        from: Pt,
        /// Exact end point (where the outgoing tangent starts).
        to: Pt,
    },
}

impl Seg {
    /// Start point.
    pub fn start(&self) -> Pt {
        match *self {
            Seg::Line(a, _) => a,
            Seg::Arc { from, .. } => from,
        }
    }
    /// End point.
    pub fn end(&self) -> Pt {
        match *self {
            Seg::Line(_, b) => b,
            Seg::Arc { to, .. } => to,
        }
    }
    /// Point at the middle of an arc (the middle point of a CIRCULARSTRING).
    pub fn mid(&self) -> Pt {
        match *self {
            Seg::Line(a, b) => [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0],
            Seg::Arc {
                c, r, a0, sweep, ..
            } => {
                let t = a0 + sweep / 2.0;
                [c[0] + r * t.cos(), c[1] + r * t.sin()]
            }
        }
    }
}

/// Most segments one arc is stroked into.
pub const MAX_ARC_SEGMENTS: usize = 4096;

/// One span: the join at a circle (its arc or a short line to a corner, when there is one), then
/// the tangent to the next circle. At most two pieces, held inline (a ring of a million spans
/// makes no allocation per span).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span {
    segs: [Seg; 2],
    len: u8,
}

impl Default for Span {
    /// A point: a place to be written over.
    fn default() -> Span {
        Span::one(Seg::Line([0.0; 2], [0.0; 2]))
    }
}

impl Span {
    fn one(tangent: Seg) -> Span {
        Span {
            segs: [tangent, tangent],
            len: 1,
        }
    }

    fn two(join: Seg, tangent: Seg) -> Span {
        Span {
            segs: [join, tangent],
            len: 2,
        }
    }
}

impl std::ops::Deref for Span {
    type Target = [Seg];
    fn deref(&self) -> &[Seg] {
        &self.segs[..self.len as usize]
    }
}

impl<'a> IntoIterator for &'a Span {
    type Item = &'a Seg;
    type IntoIter = std::slice::Iter<'a, Seg>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

impl IntoIterator for Span {
    type Item = Seg;
    type IntoIter = std::iter::Take<std::array::IntoIter<Seg, 2>>;
    fn into_iter(self) -> Self::IntoIter {
        self.segs.into_iter().take(self.len as usize)
    }
}

/// A rebuilt ring, as spans: span `i` is the join at circle `i` then the tangent to circle `i+1`.
pub type Spans = Vec<Span>;

/// Tangent from circle A to circle B: start point on A, end point on B, unit direction.
pub fn tangent(ca: Pt, ra: f64, cb: Pt, rb: f64) -> (Pt, Pt, Pt) {
    let d = [cb[0] - ca[0], cb[1] - ca[1]];
    let l = d[0].hypot(d[1]);
    let (u, a) = if l > 0.0 {
        ([d[0] / l, d[1] / l], ((rb - ra) / l).clamp(-1.0, 1.0))
    } else {
        ([1.0, 0.0], (rb - ra).signum())
    };
    let b = (1.0 - a * a).max(0.0).sqrt();
    let v = [-u[1], u[0]];
    let n = [a * u[0] + b * v[0], a * u[1] + b * v[1]];
    let dir = [b * u[0] - a * v[0], b * u[1] - a * v[1]];
    let s = [ca[0] - ra * n[0], ca[1] - ra * n[1]];
    let e = [cb[0] - rb * n[0], cb[1] - rb * n[1]];
    (s, e, dir)
}

fn line_intersection(p: Pt, d: Pt, q: Pt, e: Pt) -> Option<Pt> {
    let den = d[0] * e[1] - d[1] * e[0];
    if den.abs() < 1e-12 {
        return None;
    }
    let t = ((q[0] - p[0]) * e[1] - (q[1] - p[1]) * e[0]) / den;
    Some([p[0] + t * d[0], p[1] + t * d[1]])
}

/// Rebuild one ring from circles `(x, y, ρ)` in boundary order.
pub fn ring_spans(circles: &[[f64; 3]]) -> Spans {
    let mut spans = Vec::with_capacity(circles.len());
    for_each_span(circles, |span| spans.push(span));
    spans
}

/// The tangent from circle `i` to the next (see [`tangent`]).
fn ring_tangent(circles: &[[f64; 3]], i: usize) -> (Pt, Pt, Pt) {
    let a = circles[i];
    let b = circles[(i + 1) % circles.len()];
    if a[2] == 0.0 && b[2] == 0.0 {
        // From point to point: the tangent is the segment between them (what `tangent`
        // gives, to the bit). Its direction is read only at a circle with a radius, never
        // at these two ends.
        ([a[0], a[1]], [b[0], b[1]], [f64::NAN; 2])
    } else {
        tangent([a[0], a[1]], a[2], [b[0], b[1]], b[2])
    }
}

/// The join at circle `i` between the tangent coming in (`prev`) and the one going out
/// (`next`): where the incoming tangent ends, where the outgoing one starts, and the arc
/// between them (none at a point, or where the tangents meet at a corner instead).
fn ring_join(circle: [f64; 3], prev: (Pt, Pt, Pt), next: (Pt, Pt, Pt)) -> (Pt, Pt, Option<Seg>) {
    let (_, e_prev, d_prev) = prev;
    let (s_next, _, d_next) = next;
    let [x, y, r] = circle;
    if r == 0.0 {
        return (e_prev, s_next, None);
    }
    let c = [x, y];
    let ang_in = (e_prev[1] - y).atan2(e_prev[0] - x);
    let ang_out = (s_next[1] - y).atan2(s_next[0] - x);
    let mut theta = (ang_out - ang_in).rem_euclid(TAU);
    if r < 0.0 {
        theta = -((ang_in - ang_out).rem_euclid(TAU));
    }
    if theta.abs() <= PI + FRAC_PI_2 {
        let arc = (theta != 0.0).then_some(Seg::Arc {
            c,
            r: r.abs(),
            a0: ang_in,
            sweep: theta,
            from: e_prev,
            to: s_next,
        });
        (e_prev, s_next, arc)
    } else if let Some(xp) = line_intersection(e_prev, d_prev, s_next, d_next) {
        (xp, xp, None)
    } else {
        (e_prev, s_next, None)
    }
}

/// [`ring_spans`] one span at a time, in order, with nothing held for the whole ring: span `i`
/// needs only the joins at circles `i` and `i + 1`, so each tangent and each join is computed
/// as it is reached (the decoder strokes straight from here; `ring_spans` collects).
pub fn for_each_span(circles: &[[f64; 3]], mut f: impl FnMut(Span)) {
    let m = circles.len();
    if m == 0 {
        return;
    }
    if m == 1 {
        let [x, y, r] = circles[0];
        if r == 0.0 {
            f(Span::one(Seg::Line([x, y], [x, y])));
            return;
        }
        let p = [x + r.abs(), y];
        f(Span::one(Seg::Arc {
            c: [x, y],
            r: r.abs(),
            a0: 0.0,
            sweep: TAU * r.signum(),
            from: p,
            to: p,
        }));
        return;
    }
    for_each_span_in(circles, 0..m, f);
}

/// [`for_each_span`] for spans `range` alone (of a ring of two circles or more): the same spans,
/// so that parts of a long ring can be rebuilt apart.
pub fn for_each_span_in(
    circles: &[[f64; 3]],
    range: std::ops::Range<usize>,
    mut f: impl FnMut(Span),
) {
    let m = circles.len();
    if range.is_empty() {
        return;
    }
    let at = |i: usize| if i == m { 0 } else { i };
    let before = if range.start == 0 {
        m - 1
    } else {
        range.start - 1
    };
    let mut tan = ring_tangent(circles, range.start);
    let mut join = ring_join(circles[range.start], ring_tangent(circles, before), tan);
    for i in range {
        let next_tan = ring_tangent(circles, at(i + 1));
        let next_join = ring_join(circles[at(i + 1)], tan, next_tan);
        let (p_in, p_out, arc) = join;
        let tangent = Seg::Line(p_out, next_join.0);
        f(if let Some(a) = arc {
            Span::two(a, tangent)
        } else if p_in != p_out {
            Span::two(Seg::Line(p_in, p_out), tangent)
        } else {
            Span::one(tangent)
        });
        (tan, join) = (next_tan, next_join);
    }
}

/// Number of chords for an arc so that no chord is farther than `tol` from the arc.
pub fn arc_segments(r: f64, sweep: f64, tol: f64) -> usize {
    let quarter = (sweep.abs() / FRAC_PI_2).ceil().max(1.0);
    let k = if tol > 0.0 && r > tol {
        let step = 2.0 * (1.0 - tol / r).acos();
        (sweep.abs() / step).ceil()
    } else {
        1.0
    };
    (k.max(quarter) as usize).clamp(1, MAX_ARC_SEGMENTS)
}

/// Stroke spans into ring points (open ring), recording for each point its span when asked.
pub fn stroke_spans(
    spans: &Spans,
    tol: f64,
    pts: &mut Vec<Pt>,
    mut span_of: Option<&mut Vec<u32>>,
) {
    for (i, span) in spans.iter().enumerate() {
        let start = pts.len();
        stroke_span(span, tol, pts);
        if let Some(ids) = span_of.as_deref_mut() {
            ids.resize(ids.len() + pts.len() - start, i as u32);
        }
    }
}

/// Stroke one span: each segment's start, and an arc's chords.
pub fn stroke_span(span: &Span, tol: f64, pts: &mut Vec<Pt>) {
    for seg in span {
        match *seg {
            Seg::Line(a, _) => pts.push(a),
            Seg::Arc {
                c,
                r,
                a0,
                sweep,
                from,
                ..
            } => {
                let k = arc_segments(r, sweep, tol);
                pts.push(from);
                for j in 1..k {
                    let t = a0 + sweep * (j as f64) / (k as f64);
                    pts.push([c[0] + r * t.cos(), c[1] + r * t.sin()]);
                }
            }
        }
    }
}

/// Stroke one ring: open ring points with consecutive repeats removed.
pub fn stroke_ring(circles: &[[f64; 3]], tol: f64) -> Vec<Pt> {
    if circles.iter().all(|c| c[2] == 0.0) {
        return point_ring(circles.iter().map(|c| [c[0], c[1]]));
    }
    let mut pts = Vec::with_capacity(circles.len());
    for_each_span(circles, |span| stroke_span(&span, tol, &mut pts));
    open_ring(pts)
}

/// The ring of zero-radius circles at `points`, as [`stroke_ring`] gives it: between two points
/// the tangent is the segment joining them and no join adds a point, so the ring is the points
/// themselves (consecutive repeats removed). No span is built: `ct_encode_within`'s values are
/// all points, and this is most of their decode.
pub fn point_ring(points: impl ExactSizeIterator<Item = Pt>) -> Vec<Pt> {
    let mut pts = Vec::with_capacity(points.len());
    pts.extend(points);
    open_ring(pts)
}

/// Stroked points as an open ring: consecutive repeats removed, and the closing repeats of the
/// first point.
fn open_ring(mut pts: Vec<Pt>) -> Vec<Pt> {
    pts.dedup();
    while pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    pts
}

/// The ring as WKT `COMPOUNDCURVE(...)` with true arcs.
pub fn ring_wkt(circles: &[[f64; 3]], out: &mut String) {
    use std::fmt::Write;
    let segs: Vec<Seg> = ring_spans(circles).into_iter().flatten().collect();
    let pt = |out: &mut String, p: Pt| {
        let _ = write!(out, "{} {}", p[0], p[1]);
    };
    out.push_str("COMPOUNDCURVE(");
    let mut first = true;
    let mut line: Vec<Pt> = Vec::new();
    let flush = |out: &mut String, line: &mut Vec<Pt>, first: &mut bool| {
        if line.len() >= 2 {
            if !*first {
                out.push(',');
            }
            out.push('(');
            for (k, p) in line.iter().enumerate() {
                if k > 0 {
                    out.push(',');
                }
                pt(out, *p);
            }
            out.push(')');
            *first = false;
        }
        line.clear();
    };
    for seg in &segs {
        match *seg {
            Seg::Line(a, b) => {
                if a == b {
                    continue;
                }
                if line.is_empty() {
                    line.push(a);
                }
                line.push(b);
            }
            Seg::Arc { .. } => {
                let end = line.last().copied();
                flush(out, &mut line, &mut first);
                if !first {
                    out.push(',');
                }
                first = false;
                out.push_str("CIRCULARSTRING(");
                pt(out, end.unwrap_or(seg.start()));
                out.push(',');
                if seg_is_full(seg) {
                    if let Seg::Arc { c, r, a0, .. } = *seg {
                        // the point opposite the start
                        pt(
                            out,
                            [c[0] + r * (a0 + PI).cos(), c[1] + r * (a0 + PI).sin()],
                        );
                    }
                } else {
                    pt(out, seg.mid());
                }
                out.push(',');
                pt(out, seg.end());
                out.push(')');
                line.push(seg.end());
            }
        }
    }
    // Close on the first point exactly.
    if let Some(first_pt) = segs
        .iter()
        .find(|s| !matches!(s, Seg::Line(a, b) if a == b))
        .map(|s| s.start())
    {
        let n = line.len();
        if n >= 2 {
            line[n - 1] = first_pt;
        }
    }
    flush(out, &mut line, &mut first);
    out.push(')');
}

fn seg_is_full(seg: &Seg) -> bool {
    matches!(*seg, Seg::Arc { sweep, .. } if sweep.abs() >= TAU - 1e-12)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Pt, b: Pt) -> bool {
        (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9
    }

    #[test]
    fn four_tangent_cases() {
        // internal/internal: below both, going +x
        let (s, e, d) = tangent([0.0, 0.0], 1.0, [4.0, 0.0], 1.0);
        assert!(close(s, [0.0, -1.0]) && close(e, [4.0, -1.0]) && close(d, [1.0, 0.0]));
        // external/external: above both
        let (s, e, _) = tangent([0.0, 0.0], -1.0, [4.0, 0.0], -1.0);
        assert!(close(s, [0.0, 1.0]) && close(e, [4.0, 1.0]));
        // internal/external: crosses between them
        let (s, e, d) = tangent([0.0, 0.0], 1.0, [4.0, 0.0], -1.0);
        assert!(close(s, [0.5, -(0.75f64).sqrt()]) && close(e, [3.5, (0.75f64).sqrt()]));
        assert!((d[0] * (e[1] - s[1]) - d[1] * (e[0] - s[0])).abs() < 1e-9);
        // external/internal, and zero radius is a point
        let (s, e, _) = tangent([0.0, 0.0], -1.0, [4.0, 0.0], 1.0);
        assert!(close(s, [0.5, (0.75f64).sqrt()]) && close(e, [3.5, -(0.75f64).sqrt()]));
        let (s, e, _) = tangent([0.0, 0.0], 0.0, [4.0, 0.0], 0.0);
        assert!(close(s, [0.0, 0.0]) && close(e, [4.0, 0.0]));
    }

    #[test]
    fn square_of_points_is_the_square() {
        let pts = stroke_ring(
            &[
                [0.0, 0.0, 0.0],
                [10.0, 0.0, 0.0],
                [10.0, 10.0, 0.0],
                [0.0, 10.0, 0.0],
            ],
            0.1,
        );
        assert_eq!(
            pts,
            vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]
        );
    }

    #[test]
    fn a_ring_of_points_is_what_its_spans_stroke_to_the_bit() {
        // repeats (consecutive, and of the first point at the end), a lone point, a pair, and
        // coordinates that are not exact in binary
        let rings: Vec<Vec<[f64; 3]>> = vec![
            vec![[0.1, 0.2, 0.0]],
            vec![[0.1, 0.2, 0.0], [0.3, -0.7, 0.0]],
            vec![
                [0.1, 0.2, 0.0],
                [0.1, 0.2, 0.0],
                [1e6 + 0.3, -0.7, -0.0],
                [5.5, 3.3, 0.0],
                [5.5, 3.3, 0.0],
                [0.1, 0.2, 0.0],
                [0.1, 0.2, 0.0],
            ],
            (0..1000)
                .map(|i| {
                    let t = i as f64 * 0.0063;
                    [
                        (t.cos() * 1234.567 * 10.0).round() / 10.0,
                        (t.sin() * 765.4321 * 10.0).round() / 10.0,
                        0.0,
                    ]
                })
                .collect(),
        ];
        for ring in rings {
            let mut spans_pts = Vec::new();
            stroke_spans(&ring_spans(&ring), 0.01, &mut spans_pts, None);
            let want = open_ring(spans_pts);
            let got = stroke_ring(&ring, 0.01);
            assert_eq!(
                got.iter().map(|p| p.map(f64::to_bits)).collect::<Vec<_>>(),
                want.iter().map(|p| p.map(f64::to_bits)).collect::<Vec<_>>()
            );
            assert!(!got.is_empty());
        }
    }

    #[test]
    fn one_circle_is_a_disc_and_stadium_has_two_arcs() {
        let pts = stroke_ring(&[[0.0, 0.0, 5.0]], 0.01);
        assert_eq!(pts.len(), 50);
        assert!(pts.iter().all(|p| (p[0].hypot(p[1]) - 5.0).abs() < 1e-9));
        let area = crate::geom::signed_area(&pts);
        assert!((area - 25.0 * PI).abs() < 0.5, "{area}");
        // Two internal circles: a stadium, area = pi r^2 + 2r * d
        let st = stroke_ring(&[[0.0, 0.0, 1.0], [10.0, 0.0, 1.0]], 1e-4);
        let a = crate::geom::signed_area(&st);
        assert!((a - (PI + 20.0)).abs() < 1e-3, "{a}");
    }

    #[test]
    fn concave_corner_uses_tangent_intersection() {
        // An L-shaped bay: points and one internal circle whose tangents cross -> corner, not a loop.
        let c = [
            [0.0, 0.0, 0.0],
            [20.0, 0.0, 0.0],
            [20.0, 20.0, 0.0],
            [10.0, 10.0, 2.0],
            [0.0, 20.0, 0.0],
        ];
        let spans = ring_spans(&c);
        assert!(spans[3].iter().all(|s| matches!(s, Seg::Line(..))));
        let pts = stroke_ring(&c, 0.01);
        assert!(crate::geom::signed_area(&pts) > 0.0);
    }

    #[test]
    fn curved_wkt_for_a_disc() {
        let mut s = String::new();
        ring_wkt(&[[0.0, 0.0, 5.0]], &mut s);
        assert!(
            s.starts_with("COMPOUNDCURVE(CIRCULARSTRING(5 0,-5 0.0") && s.ends_with(",5 0))"),
            "{s}"
        );
    }
}
