//! Watkins' scanline algorithm (seeds 001 and 004), exact.
//!
//! The classic structures, one row of samples at a time from the top:
//! - **Edge table**: every edge that covers some sample row, bucketed by the first row it covers
//!   (its "ymin" in scan order), with the last row it covers.
//! - **Active edge table**: the edges covering the current row, sorted by the column where they
//!   cross it, advanced incrementally from row to row (edge coherence).
//! - **Polygon table**: per polygon its support plane (the depth order of [`sample`]), its in/out
//!   flag, and the list of polygons whose flag is "in" (the active polygon table).
//! - **Spans**: walking the active edges left to right toggles in/out flags; between two
//!   consecutive crossing columns the set of "in" polygons is constant. A span with no polygon is
//!   background, with one it is that polygon's, with several the nearest one at the span's first
//!   sample is checked against all others at its last sample: if it wins at both ends it wins all
//!   along (span coherence: depth is linear along a row, see [`sample`]); if not, two polygons
//!   interpenetrate inside the span and it is bisected until each piece is coherent or one sample.
//!
//! **Invariant**: every pixel shows exactly the polygon the z-buffer shows there. Coverage is never
//! decided by a rounded x: each active edge carries, besides its f64 column estimate advanced by
//! 1/m per row, the exact integer residue `E = (2·col + 1 - W)·D - N` of the z-buffer's crossing
//! test ("sample `col` is at or right of the crossing" is `E >= 0`, see
//! [`Samples::first_column_at_or_right`]), advanced by exact integer steps; the estimate proposes
//! a column and the residue accepts it (`0 <= E < 2D`) or corrects it one column at a time
//! (counted in [`ScanlineStats::x_corrections`]). So the crossing columns, hence the in/out flags
//! at every sample, are the z-buffer's; shared edges go to the same side by the same fill rule;
//! and depth decisions are [`DepthOrder`]'s exact ones.

use super::EMPTY;
use super::sample::{self, DepthOrder};
use crate::exact::{Fallbacks, GridPoint, I256, Samples, XY_BITS, w256};
use crate::project::ScreenScene;

/// The result: per pixel the index of the visible [`ScreenPoly`](crate::project::ScreenPoly)
/// (or [`EMPTY`]), as [`ZBuffer::poly`](super::ZBuffer).
#[derive(Clone, Debug)]
pub struct Scanline {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Row-major, row 0 at the top: index into `ScreenScene::polys`, or [`EMPTY`].
    pub poly: Vec<u32>,
    /// Counters of the run.
    pub stats: ScanlineStats,
}

/// Work counters.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ScanlineStats {
    /// Edges entered in the edge table (covering at least one row of the image).
    pub edges: u64,
    /// Rows with at least one active edge.
    pub rows: u64,
    /// Largest number of edges active on one row.
    pub max_active_edges: u64,
    /// Spans (inside the image) with at least one active polygon.
    pub spans: u64,
    /// Spans with exactly one active polygon: filled with no depth computation.
    pub single_spans: u64,
    /// Spans (or pieces of spans) with several polygons filled after one decision at each end.
    pub coherent_spans: u64,
    /// Bisections of spans inside which the front polygon changes (interpenetration).
    pub span_splits: u64,
    /// Samples decided alone with several polygons active: one-sample spans, or the end of a
    /// bisection.
    pub pixel_decisions: u64,
    /// Edge-rows whose incremental f64 column was corrected by the exact residue.
    pub x_corrections: u64,
    /// First-row crossings the f64 filter could not decide (exact computation).
    pub column_fallbacks: u64,
    /// Depth comparisons the f64 filter could not decide.
    pub depth_fallbacks: u64,
    /// Exact depth ties resolved by the id rule.
    pub depth_ties: u64,
}

impl Scanline {
    /// The input face id at every pixel (`None` for background).
    pub fn face_ids(&self, screen: &ScreenScene) -> Vec<Option<u32>> {
        sample::face_ids(&self.poly, screen)
    }
}

/// An edge of the edge table: corner `k` to corner `k + 1` of polygon `poly`, covering rows
/// `first..=last` (clipped to the image).
#[derive(Clone, Copy, Debug)]
struct EdgeEntry {
    poly: u32,
    k: u32,
    last: u32,
}

/// An edge of the active edge table, on the current row.
#[derive(Clone, Copy, Debug)]
struct ActiveEdge {
    poly: u32,
    last: i64,
    /// Exact: the first column whose sample is at or right of the crossing with the current row.
    col: i64,
    /// `(2·col + 1 - W)·D - N(row)`; `col` is right exactly when `0 <= e < two_d`. D is below
    /// 2^121 and N below 2^138 (see [`Samples::first_column_exact`]): 256-bit integers.
    e: I256,
    two_d: I256,
    /// Change of `e` from one row to the next at a fixed `col`.
    e_step: I256,
    /// f64 estimate of the crossing's column coordinate minus 0.5 (`col == ceil(t)` unless the
    /// crossing is within rounding of a sample), and its change per row (1/m in columns).
    t: f64,
    dt: f64,
    /// The edge with its lower end first (`p.y < q.y`), to recompute `t` after a correction.
    p: GridPoint,
    q: GridPoint,
}

/// Rows `[first, last]` (unclipped, possibly empty) whose sample y lies in `[lo, hi)`, exactly.
fn rows_in(s: &Samples, lo: i64, hi: i64) -> (i64, i64) {
    // y_num(j) = k·2^52 with k = H - 1 - 2j, and y_j = y_num / H.
    // y_j < hi  <=>  k·2^52 < hi·H  <=>  k <= ceil(hi·H / 2^52) - 1.
    let unit = 1i128 << XY_BITS;
    let ceil_div = |v: i128| (v.div_euclid(unit) + (v.rem_euclid(unit) != 0) as i128) as i64;
    let kmax = ceil_div(hi as i128 * s.height as i128) - 1;
    // y_j >= lo  <=>  k·2^52 >= lo·H  <=>  k >= ceil(lo·H / 2^52).
    let kmin = ceil_div(lo as i128 * s.height as i128);
    // 2j >= H - 1 - kmax and 2j <= H - 1 - kmin.
    let first =
        (s.height - 1 - kmax).div_euclid(2) + ((s.height - 1 - kmax).rem_euclid(2) != 0) as i64;
    let last = (s.height - 1 - kmin).div_euclid(2);
    (first, last)
}

impl ActiveEdge {
    /// The edge `a → b` of polygon `poly` entering the active table on row `j`.
    fn enter(
        s: &Samples,
        poly: u32,
        a: GridPoint,
        b: GridPoint,
        last: i64,
        j: i64,
        fb: &Fallbacks,
    ) -> ActiveEdge {
        let (p, q) = if a.y <= b.y { (a, b) } else { (b, a) };
        let (w, h) = (w256(s.width as i128), w256(s.height as i128));
        let dy = w256((q.y - p.y) as i128);
        let dx = w256((q.x - p.x) as i128);
        // The z-buffer's crossing test (Samples::first_column_exact): sample i is at or right of
        // the crossing iff (2i + 1 - W)·D >= N(j), with
        let d = (dy * h) << XY_BITS;
        let n = (w256(p.x as i128) * dy * h + (w256(s.y_num(j)) - w256(p.y as i128) * h) * dx) * w;
        // and y_num(j + 1) = y_num(j) - 2^53, so N(j + 1) = N(j) - 2^53·dx·W.
        let col = s.first_column_at_or_right(p, q, j, fb);
        let two_d = d + d;
        let e = w256(2 * col as i128 + 1) * d - w * d - n;
        debug_assert!(w256(0) <= e && e < two_d, "crossing residue out of range");
        ActiveEdge {
            poly,
            last,
            col,
            e,
            two_d,
            e_step: (dx * w) << (XY_BITS + 1),
            t: estimate(s, p, q, j),
            // One row down, y drops 2^53/H grid units: x moves -(dx/dy)·2^53/H grid units, which
            // is -(dx/dy)·W/H columns.
            dt: -((q.x - p.x) as f64 / (q.y - p.y) as f64) * (s.width as f64 / s.height as f64),
            p,
            q,
        }
    }

    /// Moves the edge to the next row: the f64 estimate proposes a column, the exact residue
    /// accepts or corrects it. Returns whether it had to correct.
    #[inline]
    fn advance(&mut self, s: &Samples, next_row: i64) -> bool {
        self.t += self.dt;
        let cand = self.t.ceil() as i64;
        self.e += self.e_step + self.two_d * w256((cand - self.col) as i128);
        self.col = cand;
        let zero = w256(0);
        if zero <= self.e && self.e < self.two_d {
            return false;
        }
        while self.e < zero {
            self.col += 1;
            self.e += self.two_d;
        }
        while self.e >= self.two_d {
            self.col -= 1;
            self.e -= self.two_d;
        }
        // Re-anchor the estimate so that rounding drift does not pile up.
        self.t = estimate(s, self.p, self.q, next_row);
        true
    }
}

/// The f64 column coordinate (minus 0.5) where edge `p → q` (`p.y < q.y`) crosses row `j`: the
/// formula of the z-buffer's filter.
fn estimate(s: &Samples, p: GridPoint, q: GridPoint, j: i64) -> f64 {
    let ys = s.y(j);
    let xc = p.x as f64 + (ys - p.y as f64) * (q.x - p.x) as f64 / (q.y - p.y) as f64;
    s.col_of(xc) - 0.5
}

/// Renders `screen` scanline by scanline.
pub fn render(screen: &ScreenScene) -> Scanline {
    let (w, h) = (screen.width as usize, screen.height as usize);
    let order = DepthOrder::new(screen);
    let s = order.samples;
    let fb = Fallbacks::default();
    let mut stats = ScanlineStats::default();
    let mut out = vec![EMPTY; w * h];

    // Edge table: a counting sort of the edges by first row.
    let mut firsts: Vec<(u32, EdgeEntry)> = Vec::new();
    for (pi, poly) in screen.polys.iter().enumerate() {
        let pts = screen.corners(poly);
        for k in 0..pts.len() {
            let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
            if a.y == b.y {
                continue; // covers no row: lo <= y < hi is empty
            }
            let (first, last) = rows_in(&s, a.y.min(b.y), a.y.max(b.y));
            let (first, last) = (first.max(0), last.min(h as i64 - 1));
            if first > last {
                continue;
            }
            firsts.push((
                first as u32,
                EdgeEntry {
                    poly: pi as u32,
                    k: k as u32,
                    last: last as u32,
                },
            ));
        }
    }
    stats.edges = firsts.len() as u64;
    let mut bucket_start = vec![0usize; h + 1];
    for &(f, _) in &firsts {
        bucket_start[f as usize + 1] += 1;
    }
    for j in 0..h {
        bucket_start[j + 1] += bucket_start[j];
    }
    let mut table = vec![
        EdgeEntry {
            poly: 0,
            k: 0,
            last: 0
        };
        firsts.len()
    ];
    {
        let mut fill = bucket_start.clone();
        for &(f, e) in &firsts {
            table[fill[f as usize]] = e;
            fill[f as usize] += 1;
        }
    }
    drop(firsts);

    // Polygon table: in/out flags as a slot in the active polygon list (NONE when out).
    const NONE: u32 = u32::MAX;
    let mut slot = vec![NONE; screen.polys.len()];
    let mut active_polys: Vec<u32> = Vec::new();
    // Sorted by column at the top of every row.
    let mut aet: Vec<ActiveEdge> = Vec::new();
    let mut incoming: Vec<ActiveEdge> = Vec::new();
    let mut merged: Vec<ActiveEdge> = Vec::new();

    for j in 0..h as i64 {
        // New edges are sorted among themselves and merged in: inserting them one by one into a
        // long active table would move it for each.
        incoming.clear();
        for e in &table[bucket_start[j as usize]..bucket_start[j as usize + 1]] {
            let pts = screen.corners(&screen.polys[e.poly as usize]);
            let (a, b) = (pts[e.k as usize], pts[(e.k as usize + 1) % pts.len()]);
            incoming.push(ActiveEdge::enter(&s, e.poly, a, b, e.last as i64, j, &fb));
        }
        if !incoming.is_empty() {
            incoming.sort_unstable_by_key(|e| e.col);
            merged.clear();
            let (mut x, mut y) = (0, 0);
            while x < aet.len() && y < incoming.len() {
                if aet[x].col <= incoming[y].col {
                    merged.push(aet[x]);
                    x += 1;
                } else {
                    merged.push(incoming[y]);
                    y += 1;
                }
            }
            merged.extend_from_slice(&aet[x..]);
            merged.extend_from_slice(&incoming[y..]);
            std::mem::swap(&mut aet, &mut merged);
        }
        if aet.is_empty() {
            continue;
        }
        stats.rows += 1;
        stats.max_active_edges = stats.max_active_edges.max(aet.len() as u64);

        let row = &mut out[j as usize * w..(j as usize + 1) * w];
        let mut k = 0;
        while k < aet.len() {
            // Toggle every polygon with an edge crossing at this column.
            let c = aet[k].col;
            while k < aet.len() && aet[k].col == c {
                let p = aet[k].poly;
                if slot[p as usize] == NONE {
                    slot[p as usize] = active_polys.len() as u32;
                    active_polys.push(p);
                } else {
                    let at = slot[p as usize] as usize;
                    active_polys.swap_remove(at);
                    if at < active_polys.len() {
                        slot[active_polys[at] as usize] = at as u32;
                    }
                    slot[p as usize] = NONE;
                }
                k += 1;
            }
            if active_polys.is_empty() {
                continue;
            }
            // The span up to the next crossing (every polygon's edges cross before it ends).
            let next = if k < aet.len() { aet[k].col } else { w as i64 };
            let (a, b) = (c.max(0), next.min(w as i64));
            if a >= b {
                continue;
            }
            stats.spans += 1;
            if active_polys.len() == 1 {
                stats.single_spans += 1;
                row[a as usize..b as usize].fill(active_polys[0]);
            } else {
                let first = order.nearest(active_polys.iter().copied(), a, j);
                resolve_span(&order, &active_polys, row, a, b, j, first, &mut stats);
            }
        }
        debug_assert!(active_polys.is_empty(), "odd crossing count on row {j}");

        // Edges ending here leave; the others move to the next row, where they are re-sorted by
        // insertion: from one row to the next the order barely changes (edge coherence), each
        // swap is two edges crossing between the rows.
        aet.retain(|e| e.last > j);
        for e in &mut aet {
            stats.x_corrections += e.advance(&s, j + 1) as u64;
        }
        for k in 1..aet.len() {
            let mut m = k;
            while m > 0 && aet[m - 1].col > aet[m].col {
                aet.swap(m - 1, m);
                m -= 1;
            }
        }
    }
    stats.column_fallbacks = fb.column.get();
    stats.depth_fallbacks = order.fallbacks.get();
    stats.depth_ties = order.ties.get();
    Scanline {
        width: screen.width,
        height: screen.height,
        poly: out,
        stats,
    }
}

/// Fills samples `[a, b)` of row `j` (several active polygons), knowing `first` is the nearest at
/// sample `a`: if it also beats every other active polygon at `b - 1` it is the nearest all along
/// (linearity); otherwise the span is bisected.
#[allow(clippy::too_many_arguments)]
fn resolve_span(
    order: &DepthOrder,
    active: &[u32],
    row: &mut [u32],
    a: i64,
    b: i64,
    j: i64,
    first: u32,
    stats: &mut ScanlineStats,
) {
    if b - a == 1 {
        stats.pixel_decisions += 1;
        row[a as usize] = first;
        return;
    }
    let zf = order.depth(first, b - 1, j);
    let coherent = active
        .iter()
        .all(|&o| o == first || order.wins(first, zf, o, order.depth(o, b - 1, j), b - 1, j));
    if coherent {
        stats.coherent_spans += 1;
        row[a as usize..b as usize].fill(first);
        return;
    }
    stats.span_splits += 1;
    let m = a + (b - a) / 2;
    resolve_span(order, active, row, a, m, j, first, stats);
    let second = order.nearest(active.iter().copied(), m, j);
    resolve_span(order, active, row, m, b, j, second, stats);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_in_matches_the_row_test_of_the_zbuffer() {
        for (w, h) in [(16, 12), (7, 5), (3, 96), (100, 33)] {
            let s = Samples::new(w, h);
            // Bounds on and around sample rows, and arbitrary ones.
            let mut ys: Vec<i64> = (0..h as i64)
                .flat_map(|j| {
                    let y = (s.y_num(j) / h as i128) as i64;
                    [y - 1, y, y + 1]
                })
                .collect();
            ys.extend([-(1 << 53), -(1 << 52), -1, 0, 1, 12345, 1 << 52, 1 << 53]);
            for &lo in &ys {
                for &hi in &ys {
                    if lo >= hi {
                        continue;
                    }
                    let (first, last) = rows_in(&s, lo, hi);
                    let p = GridPoint { x: 0, y: lo, z: 0 };
                    let q = GridPoint { x: 5, y: hi, z: 0 };
                    for j in -3..h as i64 + 3 {
                        assert_eq!(
                            sample::edge_covers_row(&s, p, q, j),
                            first <= j && j <= last,
                            "[{lo}, {hi}) row {j} of {h}: rows_in gives {first}..={last}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn the_incremental_crossing_is_the_exact_one_on_every_row() {
        let s = Samples::new(37, 29);
        let fb = Fallbacks::default();
        let mut seed = 7u64;
        let mut rnd = |m: i64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed % (2 * m as u64 + 1)) as i64 - m
        };
        let mut corrections = 0;
        for k in 0..3000 {
            // Every third edge runs between sample points: crossings land exactly on samples.
            let (a, b) = if k % 3 == 0 {
                let cx = |i: i64| (s.x_num(i) / 37) as i64;
                let cy = |j: i64| (s.y_num(j) / 29) as i64;
                (
                    GridPoint {
                        x: cx(rnd(20) + 18),
                        y: cy(rnd(14) + 14),
                        z: 0,
                    },
                    GridPoint {
                        x: cx(rnd(20) + 18),
                        y: cy(rnd(14) + 14),
                        z: 0,
                    },
                )
            } else {
                let m = 1 << 53;
                (
                    GridPoint {
                        x: rnd(m),
                        y: rnd(m),
                        z: 0,
                    },
                    GridPoint {
                        x: rnd(m),
                        y: rnd(m),
                        z: 0,
                    },
                )
            };
            if a.y == b.y {
                continue;
            }
            let (first, last) = rows_in(&s, a.y.min(b.y), a.y.max(b.y));
            let (first, last) = (first.max(0), last.min(28));
            if first > last {
                continue;
            }
            let mut e = ActiveEdge::enter(&s, 0, a, b, last, first, &fb);
            for j in first..=last {
                let (p, q) = if a.y <= b.y { (a, b) } else { (b, a) };
                assert_eq!(
                    e.col,
                    s.first_column_exact(p, q, j),
                    "edge {a:?} {b:?} row {j}"
                );
                if j < last {
                    corrections += e.advance(&s, j + 1) as u64;
                }
            }
        }
        // Edges through sample points make some estimates land on the wrong side.
        assert!(corrections > 0, "the exact correction was never exercised");
    }
}
