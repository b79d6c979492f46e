//! A uniform grid over screen boxes (x0, y0, x1, y1): each box is listed in every cell it
//! covers, so the boxes near a box are found in time proportional to how many there are. Boxes
//! are a filter here, never a decision: callers test what the grid returns exactly.

/// The box of no point: joined with a box, that box.
pub(crate) const NO_BOX: [f64; 4] = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];

/// The smallest box holding boxes `a` and `b`.
pub(crate) fn joined(a: [f64; 4], b: &[f64; 4]) -> [f64; 4] {
    [
        a[0].min(b[0]),
        a[1].min(b[1]),
        a[2].max(b[2]),
        a[3].max(b[3]),
    ]
}

/// The grid. Entries are `u32` indices into the caller's own list of boxes.
pub(crate) struct BoxGrid {
    origin: [f64; 2],
    cell: [f64; 2],
    /// Columns and rows.
    cols: usize,
    rows: usize,
    buckets: Vec<Vec<u32>>,
}

/// The most cells a grid has (the buckets' own room is 24 bytes a cell).
const MOST_CELLS: usize = 512 * 512;

impl BoxGrid {
    /// An empty grid of about `count` cells over the union of `boxes` (at most [`MOST_CELLS`],
    /// each at least one grid unit wide), as near square as the union allows: a box then lies in
    /// about as many columns as rows. Square counts of columns and rows made a screen strip's
    /// cells 32 times taller than wide (the strip is), so that each piece was listed in a row of
    /// a dozen cells and every query visited them.
    pub fn over<'b>(boxes: impl IntoIterator<Item = &'b [f64; 4]>, count: usize) -> BoxGrid {
        let mut all = boxes.into_iter().fold(NO_BOX, joined);
        if all[0] > all[2] {
            all = [0.0, 0.0, 1.0, 1.0];
        }
        let (width, height) = ((all[2] - all[0]).max(1.0), (all[3] - all[1]).max(1.0));
        let cells = count.clamp(1, MOST_CELLS) as f64;
        // Square cells of side s: (width / s) · (height / s) = cells.
        let side = (width * height / cells).sqrt();
        let cols = ((width / side).round() as usize).clamp(1, MOST_CELLS);
        let rows = ((cells / cols as f64).round() as usize).clamp(1, MOST_CELLS / cols);
        BoxGrid {
            origin: [all[0], all[1]],
            cell: [
                (width / cols as f64).max(1.0),
                (height / rows as f64).max(1.0),
            ],
            cols,
            rows,
            buckets: vec![Vec::new(); cols * rows],
        }
    }

    /// The cells (column range, row range) a box covers, clamped to the grid.
    fn range(&self, b: &[f64; 4]) -> (usize, usize, usize, usize) {
        let c =
            |v: f64, o: f64, s: f64, n: usize| (((v - o) / s).floor().max(0.0) as usize).min(n - 1);
        (
            c(b[0], self.origin[0], self.cell[0], self.cols),
            c(b[2], self.origin[0], self.cell[0], self.cols),
            c(b[1], self.origin[1], self.cell[1], self.rows),
            c(b[3], self.origin[1], self.cell[1], self.rows),
        )
    }

    /// A grid over `boxes` with every box listed as its index.
    pub fn holding(boxes: &[[f64; 4]]) -> BoxGrid {
        let mut grid = BoxGrid::over(boxes, boxes.len());
        for (i, b) in boxes.iter().enumerate() {
            grid.insert(i as u32, b);
        }
        grid
    }

    /// The entries listed in the cells that `b` covers, each once, ascending, into `near`
    /// (cleared first).
    pub fn entries_near(&self, b: &[f64; 4], near: &mut Vec<u32>) {
        near.clear();
        self.visit_all(b, |i| near.push(i));
        near.sort_unstable();
        near.dedup();
    }

    /// Lists entry `index` in every cell its box `b` covers.
    pub fn insert(&mut self, index: u32, b: &[f64; 4]) {
        let (i0, i1, j0, j1) = self.range(b);
        for j in j0..=j1 {
            for i in i0..=i1 {
                self.buckets[j * self.cols + i].push(index);
            }
        }
    }

    /// Calls `f` with every entry listed in a cell that `b` covers (an entry may come more than
    /// once).
    pub fn visit_all(&self, b: &[f64; 4], mut f: impl FnMut(u32)) {
        let (i0, i1, j0, j1) = self.range(b);
        let rows = &self.buckets[j0 * self.cols..(j1 + 1) * self.cols];
        for row in rows.chunks_exact(self.cols) {
            row[i0..=i1].iter().flatten().for_each(|&v| f(v));
        }
    }

    /// How many cells box `b` covers.
    pub fn cells_of(&self, b: &[f64; 4]) -> usize {
        let (i0, i1, j0, j1) = self.range(b);
        (i1 - i0 + 1) * (j1 - j0 + 1)
    }

    /// Calls `f(entry, step)` with every entry listed in a cell within `margin` of the segment
    /// `p`–`q` (an entry may come more than once), and the box of the step it was found for:
    /// the segment is walked in steps about a cell long, each step's box widened by `margin`.
    /// The steps' boxes cover every point within `margin` of the segment less the steps' own
    /// rounding (a few ulps of the coordinates): consecutive steps share their computed ends.
    /// A cell is found from a point by the same monotone arithmetic as from a box.
    pub fn visit_segment(
        &self,
        p: [f64; 2],
        q: [f64; 2],
        margin: f64,
        mut f: impl FnMut(u32, &[f64; 4]),
    ) {
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        // A step per cell crossed, along the longer axis: at most as many as columns and rows.
        let steps = ((dx.abs() / self.cell[0])
            .max(dy.abs() / self.cell[1])
            .ceil() as usize)
            .clamp(1, self.cols + self.rows + 1);
        let mut from = p;
        for s in 1..=steps {
            let to = if s == steps {
                q
            } else {
                let t = s as f64 / steps as f64;
                [p[0] + t * dx, p[1] + t * dy]
            };
            let b = [
                from[0].min(to[0]) - margin,
                from[1].min(to[1]) - margin,
                from[0].max(to[0]) + margin,
                from[1].max(to[1]) + margin,
            ];
            self.visit_all(&b, |e| f(e, &b));
            from = to;
        }
    }

    /// Calls `f` with every entry listed in a cell that `b` covers (an entry may come more than
    /// once), first dropping from those cells the entries `keep` rejects.
    pub fn visit(&mut self, b: &[f64; 4], keep: impl Fn(u32) -> bool, mut f: impl FnMut(u32)) {
        let (i0, i1, j0, j1) = self.range(b);
        for j in j0..=j1 {
            for i in i0..=i1 {
                let bucket = &mut self.buckets[j * self.cols + i];
                bucket.retain(|&v| keep(v));
                bucket.iter().for_each(|&v| f(v));
            }
        }
    }
}

/// Calls `pair(a, b)` for pairs of integer boxes (x0, y0, x1, y1) whose interiors overlap, found
/// by a sweep over the left edges, until it returns `false`. Exact: grid integers.
pub(crate) fn sweep_overlapping(boxes: &[[i64; 4]], mut pair: impl FnMut(usize, usize) -> bool) {
    let mut order: Vec<usize> = (0..boxes.len()).collect();
    order.sort_by_key(|&i| (boxes[i][0], i));
    let mut active: Vec<usize> = Vec::new();
    for &i in &order {
        let b = boxes[i];
        active.retain(|&a| boxes[a][2] > b[0]);
        for &a in &active {
            if boxes[a][1] < b[3] && b[1] < boxes[a][3] && !pair(a, i) {
                return;
            }
        }
        active.push(i);
    }
}

/// How far, relative to `1 +` the largest coordinate, [`for_each_near_edges`] looks beyond an
/// edge: far above the errors it must cover. Vertices are exact points correctly rounded to
/// f64 and mapped to pixels (a few ulps, 2^-51 relative at most), and the walk's points along
/// an edge err by a few ulps of the largest coordinate; 2^-30 is a million times more.
pub(crate) const EDGE_MARGIN: f64 = 1.0 / (1u64 << 30) as f64;

/// For every item `a` that `wanted(a)` selects, in order, calls `f(a, near)` with the other
/// selected items one of whose points may lie on an edge of `a` that `open_edge(a, k)`
/// selects (edge k runs from point k to point k + 1 of `points(a)`, cyclically), ascending: a
/// filter (the caller decides exactly), complete for points on those closed segments (within
/// [`EDGE_MARGIN`] of them).
///
/// The points of the selected items are listed in a grid of cells. An item whose points lie
/// within a few cells looks in the cells of its box; a larger one walks the cells along each
/// of its open edges: a long thin piece (a sliver) meets the few cells its edges cross, not
/// every cell of its box.
pub(crate) fn for_each_near_edges<'p>(
    count: usize,
    points: impl Fn(usize) -> &'p [[f64; 2]],
    wanted: impl Fn(usize) -> bool,
    open_edge: impl Fn(usize, usize) -> bool,
    mut f: impl FnMut(usize, &[usize]),
) {
    let chosen: Vec<usize> = (0..count).filter(|&a| wanted(a)).collect();
    let boxes: Vec<[f64; 4]> = chosen.iter().map(|&a| box_of(points(a))).collect();
    // About one cell per item, as for boxes; an entry is a point, by its place in `at`.
    let mut grid = BoxGrid::over(&boxes, chosen.len());
    let mut at: Vec<([f64; 2], u32)> = Vec::new();
    let mut largest = 0.0f64;
    for (c, &a) in chosen.iter().enumerate() {
        for p in points(a) {
            grid.insert(at.len() as u32, &[p[0], p[1], p[0], p[1]]);
            at.push((*p, c as u32));
            largest = largest.max(p[0].abs()).max(p[1].abs());
        }
    }
    let margin = EDGE_MARGIN * (1.0 + largest);
    let widen = |b: &[f64; 4]| [b[0] - margin, b[1] - margin, b[2] + margin, b[3] + margin];
    // The last item whose neighbours listed each item (each listed once).
    let mut seen = vec![usize::MAX; chosen.len()];
    let mut near = Vec::new();
    for (c, &a) in chosen.iter().enumerate() {
        near.clear();
        // The owner of entry `e` if its point lies in box `b`.
        let mut list = |e: u32, b: &[f64; 4]| {
            let (p, d) = at[e as usize];
            let d = d as usize;
            if d != c
                && seen[d] != c
                && b[0] <= p[0]
                && p[0] <= b[2]
                && b[1] <= p[1]
                && p[1] <= b[3]
            {
                seen[d] = c;
                near.push(chosen[d]);
            }
        };
        let (ps, b) = (points(a), widen(&boxes[c]));
        if grid.cells_of(&b) <= SMALL_BOX_CELLS {
            grid.visit_all(&b, |e| list(e, &b));
        } else {
            for k in (0..ps.len()).filter(|&k| open_edge(a, k)) {
                grid.visit_segment(ps[k], ps[(k + 1) % ps.len()], margin, &mut list);
            }
        }
        near.sort_unstable();
        f(a, &near);
    }
}

/// Up to this many cells, an item's box is searched whole rather than along its edges (the
/// edges of a small item cross most of its cells anyway).
const SMALL_BOX_CELLS: usize = 4;

/// The box of `points` (x0, y0, x1, y1): [min x, min y, max x, max y].
pub(crate) fn box_of(points: &[[f64; 2]]) -> [f64; 4] {
    points.iter().fold(
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, p| {
            [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ]
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A tall narrow union (a screen strip) gets tall narrow columns of square cells: a small
    /// box lies in a couple of cells, not in a row of many thin ones.
    #[test]
    fn cells_are_square_whatever_the_unions_shape() {
        for (width, height) in [(100.0, 3200.0), (3200.0, 100.0), (640.0, 640.0)] {
            let boxes: Vec<[f64; 4]> = (0..1024)
                .map(|k| {
                    let (x, y) = (
                        (k % 32) as f64 * width / 32.0,
                        (k / 32) as f64 * height / 32.0,
                    );
                    [x, y, x + 1.0, y + 1.0]
                })
                .chain([[0.0, 0.0, width, height]])
                .collect();
            let grid = BoxGrid::over(&boxes, boxes.len());
            let (cell_w, cell_h) = (grid.cell[0], grid.cell[1]);
            assert!(
                cell_w <= 1.5 * cell_h && cell_h <= 1.5 * cell_w,
                "{width} x {height}: cells {cell_w} x {cell_h}"
            );
            assert!((900..=1200).contains(&(grid.cols * grid.rows)));
            // A box the size of a cell lies in at most four.
            let side = cell_w.max(cell_h);
            assert!(grid.cells_of(&[side * 0.5, side * 0.5, side * 1.5, side * 1.5]) <= 4);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// Every item with a point on an edge of another (computed along it in f64, so within a
        /// few ulps) is near that one, however long and thin the edge and however fine the
        /// grid; items whose points are all far from it are not.
        #[test]
        fn points_on_an_edge_are_near_it(
            ends in prop::collection::vec((-1e4f64..1e4, -1e4f64..1e4), 2..40),
            on in prop::collection::vec((0usize..40, 0.0f64..=1.0), 1..60),
        ) {
            // Item 0: a polygon through the ends (its edges long and thin); items 1..: a point
            // on one of its edges each, or far off the whole drawing.
            let polygon: Vec<[f64; 2]> = ends.iter().map(|&(x, y)| [x, y]).collect();
            let n = polygon.len();
            let mut items = vec![polygon.clone()];
            let mut expected: Vec<Vec<usize>> = vec![Vec::new(); n];
            for (j, &(k, t)) in on.iter().enumerate() {
                let k = k % n;
                let (p, q) = (polygon[k], polygon[(k + 1) % n]);
                if j % 5 == 4 {
                    items.push(vec![[3e4 + j as f64, 3e4]]);
                } else {
                    items.push(vec![[p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]]);
                    expected[k].push(items.len() - 1);
                }
            }
            let mut met: Vec<(usize, Vec<usize>)> = Vec::new();
            let points = |a: usize| items[a].as_slice();
            for_each_near_edges(items.len(), points, |_| true, |a, _| a == 0, |a, near| {
                met.push((a, near.to_vec()));
            });
            // Item 0 meets every point on its edges.
            prop_assert_eq!(&met[0].0, &0);
            for e in expected.iter().flatten() {
                prop_assert!(met[0].1.contains(e), "item {} missed", e);
            }
            for &d in &met[0].1 {
                prop_assert!(items[d][0][0] < 2e4, "a far item {} is near", d);
            }
            prop_assert_eq!(met.len(), items.len());
        }
    }
}
