//! A uniform grid of axis-aligned boxes for "which boxes meet this one?" when the boxes are the
//! segments of boundaries: many, short and evenly spread along lines. Built in two linear passes
//! (count, then fill one flat array), no sorting and no tree; a query visits the cells its box
//! covers and reports each stored box that meets it once.
//!
//! Measured against `rstar`'s bulk-loaded R-tree on the rebuilt rings of `tests/data` (the
//! encoder's validity check, every segment looked up among all): the tree's bulk load sorts the
//! boxes recursively and each lookup walks nodes; the grid does neither. Boxes spread unevenly
//! (a few long edges across a large extent) would fill many cells each: [`BoxGrid::new`] then
//! returns `None` and the caller keeps its tree.

use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{RTree, AABB};

/// A box: `[xmin, ymin, xmax, ymax]`.
pub type Bbox = [f64; 4];

/// The box of nothing: [`union`] with it gives the other box.
pub const EMPTY: Bbox = [
    f64::INFINITY,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NEG_INFINITY,
];

/// The smallest box holding both.
pub fn union(a: Bbox, b: Bbox) -> Bbox {
    [
        a[0].min(b[0]),
        a[1].min(b[1]),
        a[2].max(b[2]),
        a[3].max(b[3]),
    ]
}

/// Boxes stored by the cells they cover.
pub struct BoxGrid {
    x0: f64,
    y0: f64,
    cell: f64,
    nx: usize,
    ny: usize,
    /// `start[c]..start[c + 1]`: the entries of cell `c` in `items`.
    start: Vec<u32>,
    items: Vec<u32>,
    boxes: Vec<Bbox>,
}

/// Cells a box may cover on average before the grid is given up (the R-tree is used instead).
const MAX_CELLS_PER_BOX: usize = 6;

impl BoxGrid {
    /// A grid of `boxes`, or `None` when they are too few, not finite, or would cover too many
    /// cells. Cells are about the median box's larger side, but no more than about twice as
    /// many cells as boxes.
    pub fn new(boxes: Vec<Bbox>) -> Option<BoxGrid> {
        let n = boxes.len();
        if n == 0 || n >= u32::MAX as usize / 2 {
            return None;
        }
        let ext = boxes.iter().fold(EMPTY, |e, b| union(e, *b));
        let (w, h) = (ext[2] - ext[0], ext[3] - ext[1]);
        if !(w.is_finite() && h.is_finite()) {
            return None;
        }
        let mut sides: Vec<f64> = boxes
            .iter()
            .map(|b| (b[2] - b[0]).max(b[3] - b[1]))
            .collect();
        let mid = n / 2;
        let median = *sides.select_nth_unstable_by(mid, f64::total_cmp).1;
        let cell = median
            .max((w * h / (2 * n) as f64).sqrt())
            .max(w.max(h) / 4096.0);
        if !(cell.is_finite() && cell > 0.0) {
            return None;
        }
        let nx = ((w / cell).floor() as usize).saturating_add(1);
        let ny = ((h / cell).floor() as usize).saturating_add(1);
        let ncells = nx.checked_mul(ny)?;
        if ncells > 4 * n + 64 {
            return None;
        }
        let mut grid = BoxGrid {
            x0: ext[0],
            y0: ext[1],
            cell,
            nx,
            ny,
            start: vec![0; ncells + 1],
            items: Vec::new(),
            boxes,
        };
        let mut total = 0usize;
        for b in &grid.boxes {
            let (cx0, cy0, cx1, cy1) = grid.range(b);
            total += (cx1 - cx0 + 1) * (cy1 - cy0 + 1);
            if total > MAX_CELLS_PER_BOX * n + 1024 || total > u32::MAX as usize {
                return None;
            }
            for cy in cy0..=cy1 {
                for cx in cx0..=cx1 {
                    grid.start[cy * nx + cx + 1] += 1;
                }
            }
        }
        for c in 0..ncells {
            grid.start[c + 1] += grid.start[c];
        }
        let mut fill = grid.start.clone();
        grid.items = vec![0; total];
        for (i, b) in grid.boxes.iter().enumerate() {
            let (cx0, cy0, cx1, cy1) = grid.range(b);
            for cy in cy0..=cy1 {
                for cx in cx0..=cx1 {
                    let c = cy * nx + cx;
                    grid.items[fill[c] as usize] = i as u32;
                    fill[c] += 1;
                }
            }
        }
        Some(grid)
    }

    // A float-to-unsigned cast truncates toward zero and sends negatives and NaN to 0, so for the
    // cell index it is `floor(v).max(0)` exactly, without `floor` (a libm call on baseline x86-64,
    // 8% of a validity check's time).
    fn col(&self, x: f64) -> usize {
        (((x - self.x0) / self.cell) as usize).min(self.nx - 1)
    }

    fn row(&self, y: f64) -> usize {
        (((y - self.y0) / self.cell) as usize).min(self.ny - 1)
    }

    /// Cells covered by a box, clamped to the grid: `(col0, row0, col1, row1)`.
    fn range(&self, b: &Bbox) -> (usize, usize, usize, usize) {
        (
            self.col(b[0]),
            self.row(b[1]),
            self.col(b[2]),
            self.row(b[3]),
        )
    }

    /// Calls `f(i)` once for every stored box `i` that meets `q` (closed boxes: touching counts).
    pub fn for_each_meeting(&self, q: &Bbox, mut f: impl FnMut(usize)) {
        let (cx0, cy0, cx1, cy1) = self.range(q);
        for cy in cy0..=cy1 {
            for cx in cx0..=cx1 {
                let c = cy * self.nx + cx;
                for &i in &self.items[self.start[c] as usize..self.start[c + 1] as usize] {
                    let b = &self.boxes[i as usize];
                    if b[0] > q[2] || q[0] > b[2] || b[1] > q[3] || q[1] > b[3] {
                        continue;
                    }
                    // Reported only from the cell holding the low corner of the two boxes'
                    // intersection, so a box in several of the visited cells comes once.
                    if self.col(b[0].max(q[0])) == cx && self.row(b[1].max(q[1])) == cy {
                        f(i as usize);
                    }
                }
            }
        }
    }
}

/// Boxes with data, looked up by box: a [`BoxGrid`] when the boxes suit one, else `rstar`'s
/// R-tree. Either reports the same set.
pub enum BoxIndex<T> {
    /// The grid and each box's data.
    Grid(BoxGrid, Vec<T>),
    /// The fallback.
    Tree(RTree<GeomWithData<Rectangle<[f64; 2]>, T>>),
}

impl<T: Copy> BoxIndex<T> {
    /// An index of `items`.
    pub fn new(items: Vec<(Bbox, T)>) -> BoxIndex<T> {
        match BoxGrid::new(items.iter().map(|i| i.0).collect()) {
            Some(grid) => BoxIndex::Grid(grid, items.into_iter().map(|i| i.1).collect()),
            None => BoxIndex::Tree(RTree::bulk_load(
                items
                    .into_iter()
                    .map(|(b, t)| {
                        GeomWithData::new(Rectangle::from_corners([b[0], b[1]], [b[2], b[3]]), t)
                    })
                    .collect(),
            )),
        }
    }

    /// Calls `f` once with the data of every box that meets `q` (closed boxes).
    pub fn for_each_meeting(&self, q: &Bbox, mut f: impl FnMut(T)) {
        match self {
            BoxIndex::Grid(grid, data) => grid.for_each_meeting(q, |i| f(data[i])),
            BoxIndex::Tree(tree) => {
                let env = AABB::from_corners([q[0], q[1]], [q[2], q[3]]);
                for item in tree.locate_in_envelope_intersecting(&env) {
                    f(item.data);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every pair found by the grid is found by brute force and the other way round, once each.
    #[test]
    fn the_grid_finds_what_brute_force_finds() {
        let mut rnd = crate::test_uniform(7);
        // a wavy ring of short segments, plus a few long ones across it
        let mut pts: Vec<[f64; 2]> = (0..2000)
            .map(|i| {
                let t = i as f64 / 2000.0 * std::f64::consts::TAU;
                let r = 1000.0 + 50.0 * (13.0 * t).sin() + 5.0 * rnd();
                [r * t.cos(), r * t.sin()]
            })
            .collect();
        pts.extend([
            [-1100.0, 0.0],
            [1100.0, 30.0],
            [0.0, -1100.0],
            [5.0, 1100.0],
        ]);
        let boxes: Vec<Bbox> = pts
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0], w[1]);
                [
                    a[0].min(b[0]),
                    a[1].min(b[1]),
                    a[0].max(b[0]),
                    a[1].max(b[1]),
                ]
            })
            .collect();
        let grid = BoxGrid::new(boxes.clone()).expect("a grid");
        let meets =
            |a: &Bbox, b: &Bbox| !(b[0] > a[2] || a[0] > b[2] || b[1] > a[3] || a[1] > b[3]);
        let mut pairs = 0;
        for q in boxes
            .iter()
            .chain([[-2000.0, -2000.0, -1500.0, -1500.0], [0.0, 0.0, 0.0, 0.0]].iter())
        {
            let mut got = Vec::new();
            grid.for_each_meeting(q, |i| got.push(i));
            got.sort_unstable();
            let want: Vec<usize> = (0..boxes.len()).filter(|&i| meets(q, &boxes[i])).collect();
            assert_eq!(got, want, "query {q:?}");
            pairs += got.len();
        }
        assert!(
            pairs > 3 * boxes.len(),
            "{pairs} pairs: the test has to meet neighbours"
        );
    }

    /// The tree fallback reports what the grid reports.
    #[test]
    fn both_indexes_agree() {
        let boxes: Vec<(Bbox, usize)> = (0..500)
            .map(|i| {
                let t = i as f64 * 0.05;
                (
                    [
                        t.cos() * 100.0,
                        t.sin() * 100.0,
                        t.cos() * 100.0 + 3.0,
                        t.sin() * 100.0 + 2.0,
                    ],
                    i,
                )
            })
            .collect();
        let grid = BoxIndex::new(boxes.clone());
        assert!(matches!(grid, BoxIndex::Grid(..)));
        let tree = BoxIndex::Tree(RTree::bulk_load(
            boxes
                .iter()
                .map(|&(b, t)| {
                    GeomWithData::new(Rectangle::from_corners([b[0], b[1]], [b[2], b[3]]), t)
                })
                .collect(),
        ));
        for (q, _) in &boxes {
            let (mut a, mut b) = (Vec::new(), Vec::new());
            grid.for_each_meeting(q, |i| a.push(i));
            tree.for_each_meeting(q, |i| b.push(i));
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b);
        }
    }

    #[test]
    fn degenerate_sets_are_refused_or_work() {
        assert!(BoxGrid::new(vec![]).is_none());
        assert!(BoxGrid::new(vec![[0.0, 0.0, f64::INFINITY, 1.0]]).is_none());
        // all boxes at one point: a one-cell grid (or none); never a panic
        if let Some(g) = BoxGrid::new(vec![[1.0, 1.0, 1.0, 1.0]; 3]) {
            let mut n = 0;
            g.for_each_meeting(&[1.0, 1.0, 1.0, 1.0], |_| n += 1);
            assert_eq!(n, 3);
        }
        // a few long diagonals over a large extent with many tiny boxes: too many cells, no grid
        let mut boxes: Vec<Bbox> = (0..1000)
            .map(|i| {
                [
                    10.0 * i as f64,
                    10.0 * i as f64,
                    10.0 * i as f64 + 0.1,
                    10.0 * i as f64 + 0.1,
                ]
            })
            .collect();
        boxes.extend((0..10).map(|i| [0.0, 0.0, 1e4 + i as f64, 1e4]));
        assert!(BoxGrid::new(boxes).is_none());
    }
}
