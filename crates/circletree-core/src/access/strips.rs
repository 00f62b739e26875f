//! The edge index of one ring: its edges sorted into horizontal strips of equal height, so that a
//! point meets only the edges of its strip (a ray-crossing test) or of the strips within a
//! distance of it. Built once per value and kept by the extension's per-call-site cache.

use crate::geom::Pt;

/// One ring's edges, closed (`pts[0]` repeated last), and the strips they cross.
#[derive(Debug)]
pub struct Strips {
    /// The ring's points, the first repeated at the end.
    pub pts: Vec<Pt>,
    /// The ring's box: `[xmin, ymin, xmax, ymax]`.
    pub bbox: [f64; 4],
    /// Strips per unit of y.
    per_unit: f64,
    /// Edge `i` (from `pts[i]` to `pts[i + 1]`) is listed in every strip its y-range meets:
    /// strip `s` holds `edges[starts[s]..starts[s + 1]]`.
    starts: Vec<u32>,
    edges: Vec<u32>,
}

/// Edges per strip, on average, that the index aims at.
const EDGES_PER_STRIP: usize = 4;

impl Strips {
    /// Index an open ring (its closing edge is added).
    pub fn new(ring: Vec<Pt>) -> Strips {
        let mut pts = ring;
        if let Some(&first) = pts.first() {
            pts.push(first);
        }
        let mut bbox = [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ];
        for p in &pts {
            bbox[0] = bbox[0].min(p[0]);
            bbox[1] = bbox[1].min(p[1]);
            bbox[2] = bbox[2].max(p[0]);
            bbox[3] = bbox[3].max(p[1]);
        }
        let nedges = pts.len().saturating_sub(1);
        let nstrips = (nedges / EDGES_PER_STRIP).clamp(1, 1 << 16);
        let span = bbox[3] - bbox[1];
        let per_unit = if span > 0.0 {
            nstrips as f64 / span
        } else {
            1.0
        };
        let mut s = Strips {
            pts,
            bbox,
            per_unit,
            starts: vec![0; nstrips + 1],
            edges: Vec::new(),
        };
        // Each point's strip once, then a counting sort of the edges: count, prefix sums, fill.
        let at: Vec<u32> = s.pts.iter().map(|p| s.strip(p[1]) as u32).collect();
        let span_of = |i: usize| {
            let (a, b) = (at[i], at[i + 1]);
            (a.min(b) as usize, a.max(b) as usize)
        };
        for i in 0..nedges {
            let (a, b) = span_of(i);
            for k in a..=b {
                s.starts[k + 1] += 1;
            }
        }
        for k in 0..nstrips {
            s.starts[k + 1] += s.starts[k];
        }
        let mut next = s.starts.clone();
        s.edges = vec![0; s.starts[nstrips] as usize];
        for i in 0..nedges {
            let (a, b) = span_of(i);
            for slot in &mut next[a..=b] {
                s.edges[*slot as usize] = i as u32;
                *slot += 1;
            }
        }
        s
    }

    fn nstrips(&self) -> usize {
        self.starts.len() - 1
    }

    /// The strip of a y: monotone in y (one subtraction and one multiplication by a positive
    /// constant, each rounded monotonically), so an edge whose y-range holds y is listed in y's
    /// strip.
    fn strip(&self, y: f64) -> usize {
        let k = (y - self.bbox[1]) * self.per_unit;
        if k.is_nan() || k < 0.0 {
            0
        } else {
            (k as usize).min(self.nstrips() - 1)
        }
    }

    /// The edges whose y-range may meet `[y0, y1]`, each strip's list in turn (an edge crossing
    /// several strips comes once per strip).
    pub fn edges_between(&self, y0: f64, y1: f64) -> impl Iterator<Item = (Pt, Pt)> + '_ {
        let (a, b) = (self.strip(y0), self.strip(y1));
        let e = &self.edges[self.starts[a] as usize..self.starts[b + 1] as usize];
        e.iter()
            .map(|&i| (self.pts[i as usize], self.pts[i as usize + 1]))
    }

    /// The edges whose y-range may hold `y` (one strip's).
    pub fn edges_at(&self, y: f64) -> impl Iterator<Item = (Pt, Pt)> + '_ {
        self.edges_between(y, y)
    }

    /// Every edge once.
    pub fn all_edges(&self) -> impl Iterator<Item = (Pt, Pt)> + '_ {
        self.pts.windows(2).map(|w| (w[0], w[1]))
    }

    /// Bytes held (for the cache's bound).
    pub fn heap_bytes(&self) -> usize {
        self.pts.capacity() * 16 + (self.starts.capacity() + self.edges.capacity()) * 4
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_edge_meeting_a_y_is_in_its_strip() {
        let mut u = crate::test_uniform(7);
        let ring: Vec<Pt> = (0..500)
            .map(|i| {
                let t = i as f64 / 500.0 * std::f64::consts::TAU;
                let r = 100.0 + 30.0 * u();
                [r * t.cos(), r * t.sin()]
            })
            .collect();
        let s = Strips::new(ring);
        assert!(s.nstrips() > 50);
        for _ in 0..2000 {
            let y = -140.0 + 280.0 * u();
            let want: Vec<(Pt, Pt)> = s
                .all_edges()
                .filter(|(a, b)| a[1].min(b[1]) <= y && y <= a[1].max(b[1]))
                .collect();
            let got: Vec<(Pt, Pt)> = s.edges_at(y).collect();
            for e in &want {
                assert!(got.contains(e), "edge {e:?} at y {y} not in its strip");
            }
            assert!(
                got.len() <= want.len() + 60,
                "{} listed for {} meeting",
                got.len(),
                want.len()
            );
        }
        // the ends of every edge, exactly
        for w in s.pts.windows(2) {
            for y in [w[0][1], w[1][1]] {
                assert!(s.edges_at(y).any(|e| e == (w[0], w[1])));
            }
        }
    }
}
