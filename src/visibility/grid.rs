//! A uniform grid over screen boxes (x0, y0, x1, y1): each box is listed in every cell it
//! covers, so the boxes near a box are found in time proportional to how many there are. Boxes
//! are a filter here, never a decision: callers test what the grid returns exactly.

/// The grid. Entries are `u32` indices into the caller's own list of boxes.
pub(crate) struct BoxGrid {
    origin: [f64; 2],
    cell: [f64; 2],
    cells: usize,
    buckets: Vec<Vec<u32>>,
}

impl BoxGrid {
    /// An empty grid of about `count` cells over the union of `boxes` (at most 512 x 512 cells,
    /// at least one grid unit wide).
    pub fn over<'b>(boxes: impl IntoIterator<Item = &'b [f64; 4]>, count: usize) -> BoxGrid {
        let mut all = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];
        for b in boxes {
            all = [
                all[0].min(b[0]),
                all[1].min(b[1]),
                all[2].max(b[2]),
                all[3].max(b[3]),
            ];
        }
        if all[0] > all[2] {
            all = [0.0, 0.0, 1.0, 1.0];
        }
        let cells = ((count as f64).sqrt() as usize).clamp(1, 512);
        BoxGrid {
            origin: [all[0], all[1]],
            cell: [
                ((all[2] - all[0]) / cells as f64).max(1.0),
                ((all[3] - all[1]) / cells as f64).max(1.0),
            ],
            cells,
            buckets: vec![Vec::new(); cells * cells],
        }
    }

    /// The cells (column range, row range) a box covers, clamped to the grid.
    fn range(&self, b: &[f64; 4]) -> (usize, usize, usize, usize) {
        let c =
            |v: f64, o: f64, s: f64| (((v - o) / s).floor().max(0.0) as usize).min(self.cells - 1);
        (
            c(b[0], self.origin[0], self.cell[0]),
            c(b[2], self.origin[0], self.cell[0]),
            c(b[1], self.origin[1], self.cell[1]),
            c(b[3], self.origin[1], self.cell[1]),
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
                self.buckets[j * self.cells + i].push(index);
            }
        }
    }

    /// Calls `f` with every entry listed in a cell that `b` covers (an entry may come more than
    /// once).
    pub fn visit_all(&self, b: &[f64; 4], mut f: impl FnMut(u32)) {
        let (i0, i1, j0, j1) = self.range(b);
        let rows = &self.buckets[j0 * self.cells..(j1 + 1) * self.cells];
        for row in rows.chunks_exact(self.cells) {
            row[i0..=i1].iter().flatten().for_each(|&v| f(v));
        }
    }

    /// Calls `f` with every entry listed in a cell that `b` covers (an entry may come more than
    /// once), first dropping from those cells the entries `keep` rejects.
    pub fn visit(&mut self, b: &[f64; 4], keep: impl Fn(u32) -> bool, mut f: impl FnMut(u32)) {
        let (i0, i1, j0, j1) = self.range(b);
        for j in j0..=j1 {
            for i in i0..=i1 {
                let bucket = &mut self.buckets[j * self.cells + i];
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

/// For every box `a` that `wanted(a)` selects, in order, calls `f(a, near)` with the other
/// selected boxes whose closed extents meet box `a`'s, ascending: the candidate neighbours of
/// `a` (a filter: the caller decides exactly). Only the selected boxes enter the grid (the open
/// pieces of a drawing are a few of its pieces).
pub(crate) fn for_each_near(
    boxes: &[[f64; 4]],
    wanted: impl Fn(usize) -> bool,
    mut f: impl FnMut(usize, &[usize]),
) {
    let chosen: Vec<usize> = (0..boxes.len()).filter(|&a| wanted(a)).collect();
    let chosen_boxes: Vec<[f64; 4]> = chosen.iter().map(|&a| boxes[a]).collect();
    let mut near = NearBoxes::of(&chosen_boxes);
    let mut found = Vec::new();
    for (k, &a) in chosen.iter().enumerate() {
        found.clear();
        found.extend(near.of_box(k).iter().map(|&j| chosen[j]));
        f(a, &found);
    }
}

/// The boxes near each box of a list, asked for one box at a time ([`for_each_near`] asks for
/// all of them in order).
pub(crate) struct NearBoxes<'b> {
    boxes: &'b [[f64; 4]],
    grid: BoxGrid,
    near: Vec<usize>,
    /// The last box whose neighbours listed each box (each listed once).
    seen: Vec<usize>,
}

impl<'b> NearBoxes<'b> {
    /// Over `boxes`.
    pub fn of(boxes: &'b [[f64; 4]]) -> NearBoxes<'b> {
        NearBoxes {
            boxes,
            grid: BoxGrid::holding(boxes),
            near: Vec::new(),
            seen: vec![usize::MAX; boxes.len()],
        }
    }

    /// The other boxes whose closed extents meet box `a`'s, ascending.
    pub fn of_box(&mut self, a: usize) -> &[usize] {
        let (boxes, near, seen) = (self.boxes, &mut self.near, &mut self.seen);
        let ba = &boxes[a];
        near.clear();
        self.grid.visit_all(ba, |b| {
            let b = b as usize;
            let bb = &boxes[b];
            if b != a
                && seen[b] != a
                && ba[0] <= bb[2]
                && bb[0] <= ba[2]
                && ba[1] <= bb[3]
                && bb[1] <= ba[3]
            {
                seen[b] = a;
                near.push(b);
            }
        });
        near.sort_unstable();
        near
    }
}
