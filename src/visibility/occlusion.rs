//! Occlusion cells: where the polygons facing the eye certainly cover the screen, and how far
//! they lie there at most, so that a piece facing away that lies within such cells, wholly behind
//! them, is proven hidden without being cut by anything (open meshes keep their back faces; most
//! of them lie behind the front of the surface).
//!
//! The cover is the union U of the polygons seen from the front (`ScreenPoly::front`:
//! counter-clockwise on screen, clockwise in meshes wound inwards, as many exporters write
//! spheres); only the others are tried against it. Which polygons cover is a choice of what to
//! try, never a reason to drop anything: a piece is dropped only by the exact test below. U's
//! boundary lies on the cover's contour: the sides that no other cover polygon runs along the
//! other way (two polygons of one orientation running along a side in opposite directions lie on
//! its two sides, so the points inside it are inside U; a boundary point at a corner lies on a
//! side that has U on one side only; cover polygons of both orientations only leave more sides
//! unmatched). The screen box is divided into cells with integer corners:
//! - a cell met by no contour side (by its box, widened) holds no boundary point of U, so its
//!   interior lies wholly inside U or wholly outside; it is inside when its centre, a grid point
//!   inside the cell, lies in a cover piece;
//! - such a cell's `far` bounds the depth of every cover piece meeting it over the cell (its
//!   plane at the corners of the cell's overlap with the piece's bounds: a linear function), so
//!   at every point of the cell the nearest surface is at most `far` away (a cover piece covers
//!   the point, and the nearest surface is no farther than it).
//!
//! A piece facing away whose bounds lie within covered cells and whose proven nearest depth is
//! strictly beyond each of their `far` is hidden everywhere ([`Occlusion::hides`]). Invariant:
//! every decision is exact (integer cells and contour sides, exact point-in-piece signs) or a
//! proven f64 bound ([`depth`]); a piece the test cannot prove hidden goes the usual way.

use super::depth;
use super::live::bounds;
use super::pieces_of;
use super::point_pairs::{point_pairs, side_key};
use super::strips::appended;
use crate::exact::polygon::Piece;
use crate::project::ScreenScene;
use rayon::prelude::*;
use std::cmp::Ordering;

/// Occlusion cells per piece (about): finer cells follow the contour more closely but cost more
/// to fill; one per piece measured best on the bunny and the teapot (0.25 and 4 did worse).
pub(crate) const CELLS_PER_PIECE: f64 = 1.0;

/// The cells' rows are filled in this many bands, on all cores.
const ROW_BANDS: usize = 32;

/// Removes from `pieces` (the pieces of whole polygons) those facing away that the occlusion
/// cells prove hidden; returns how many. What is left has the same visible set.
#[cfg(test)]
pub(crate) fn drop_hidden(screen: &ScreenScene, pieces: &mut Vec<Piece>) -> usize {
    let refs: Vec<&Piece> = pieces.iter().collect();
    let Some(cells) = Occlusion::of(screen, &refs, CELLS_PER_PIECE) else {
        return 0;
    };
    cells.drop_hidden(screen, pieces)
}

/// The first pieces ([`super::initial_pieces`]) of the polygons `polys` (increasing) less those
/// facing away that the occlusion cells prove hidden, and how many were dropped: the same as
/// `initial_pieces` then [`drop_hidden`], but a triangle facing away is tried whole and its
/// piece made only if it may show (most of an open mesh's back faces never become pieces).
pub(crate) fn unhidden_pieces(screen: &ScreenScene, polys: &[u32]) -> (Vec<Piece>, usize) {
    let back_facing = back_facing(screen);
    let tried_whole = |k: u32| back_facing[k as usize] && screen.polys[k as usize].len == 3;
    let (whole, others): (Vec<u32>, Vec<u32>) = polys.iter().partition(|&&k| tried_whole(k));
    let mut made = pieces_of(screen, &others);
    let refs: Vec<&Piece> = made.iter().collect();
    let frame = |k: u32| {
        let c = screen.corners(&screen.polys[k as usize]);
        c.iter()
            .fold([i64::MAX, i64::MAX, i64::MIN, i64::MIN], |f, p| {
                [f[0].min(p.x), f[1].min(p.y), f[2].max(p.x), f[3].max(p.y)]
            })
    };
    let parts =
        (refs.iter().map(|p| (p.poly, p.grid_frame()))).chain(whole.iter().map(|&k| (k, frame(k))));
    let Some(cells) = Occlusion::of_parts(screen, parts, &refs, CELLS_PER_PIECE) else {
        drop(refs);
        return (merged(made, pieces_of(screen, &whole)), 0);
    };
    drop(refs);
    let mut dropped = cells.drop_hidden(screen, &mut made);
    let shown: Vec<u32> = (whole.par_iter().with_min_len(1024))
        .filter(|&&k| !cells.hides_triangle(screen, k))
        .copied()
        .collect();
    dropped += whole.len() - shown.len();
    let unhidden = merged(made, pieces_of(screen, &shown));
    // The cells' and the dropped pieces' room, back before the caller cuts and solves.
    crate::memory::give_back_after(polys.len());
    (unhidden, dropped)
}

/// Two lists of pieces, each in increasing polygon order and no polygon in both, as one in that
/// order (the order the pieces of all polygons together would have).
pub(crate) fn merged(a: Vec<Piece>, b: Vec<Piece>) -> Vec<Piece> {
    merged_by(a, b, |p| p.poly)
}

/// [`merged`] of any lists ordered by `key`, no key in both. The shorter is appended to the
/// longer and the two runs merged in place by the standard library's stable sort (the order
/// of equal keys within a list is kept): only the longer list's elements past the shorter's
/// first key move, once each, within room already in memory; the sort's buffer holds the
/// shorter run. (Popping both into a new list faulted in its pages one by one, then reversed
/// it: on the 1M sphere's 400k pieces a serial 50 ms. Its peak is the same either way.)
fn merged_by<T>(a: Vec<T>, b: Vec<T>, key: impl Fn(&T) -> u32) -> Vec<T> {
    let mut all = appended(a, b);
    all.sort_by_key(key);
    all
}

/// Per polygon of `screen`: is it seen from the back (`ScreenPoly::front`)?
fn back_facing(screen: &ScreenScene) -> Vec<bool> {
    screen.polys.iter().map(|p| !p.front).collect()
}

/// The cells. See the module docs.
pub(crate) struct Occlusion {
    /// The cells.
    grid: CellGrid,
    /// Per cell: the cover's far bound, or infinity where the cell is not known to be covered.
    far: Vec<f64>,
    /// Per polygon: seen from the back? Only those pieces are tried: the cover is made of the
    /// others.
    back_facing: Vec<bool>,
}

impl Occlusion {
    /// The cells of `pieces` (the pieces of whole polygons), about `cells_per_piece` cells to a
    /// piece. `None` when no polygon is seen from the back, or none from the front (nothing to
    /// try the test on, or no cover).
    pub fn of(screen: &ScreenScene, pieces: &[&Piece], cells_per_piece: f64) -> Option<Occlusion> {
        let parts = pieces.iter().map(|p| (p.poly, p.grid_frame()));
        Occlusion::of_parts(screen, parts, pieces, cells_per_piece)
    }

    /// [`Occlusion::of`] for pieces some of which are not made yet: `parts` are every piece's
    /// polygon and grid frame ([`Piece::grid_frame`]), `pieces` those made, which must include
    /// every piece seen from the front (the cover); the others are only tried.
    fn of_parts(
        screen: &ScreenScene,
        parts: impl Iterator<Item = (u32, [i64; 4])>,
        pieces: &[&Piece],
        cells_per_piece: f64,
    ) -> Option<Occlusion> {
        let back_facing = back_facing(screen);
        let ccw = |poly: u32| !back_facing[poly as usize];
        let mut all = [i64::MAX, i64::MAX, i64::MIN, i64::MIN];
        let (mut count, mut fronts, mut backs) = (0usize, false, false);
        for (poly, f) in parts {
            count += 1;
            fronts |= ccw(poly);
            backs |= !ccw(poly);
            all = [
                all[0].min(f[0]),
                all[1].min(f[1]),
                all[2].max(f[2]),
                all[3].max(f[3]),
            ];
        }
        if !(fronts && backs) {
            return None;
        }
        let front: Vec<u32> = {
            let mut v: Vec<u32> = pieces.iter().map(|p| p.poly).filter(|&k| ccw(k)).collect();
            v.sort_unstable();
            v.dedup();
            v
        };
        let grid = CellGrid::over(all, count as f64 * cells_per_piece);
        let mut occlusion = Occlusion {
            grid,
            far: vec![f64::NEG_INFINITY; grid.len()],
            back_facing: Vec::new(),
        };
        // Cells a contour side may meet are not covered (NaN marks them until the end).
        let contour = contour_sides(screen, &front);
        for [u, v] in contour {
            grid.segment_cells(u, v, |cell| occlusion.far[cell] = f64::NAN);
        }
        let fronts: Vec<&Piece> = pieces.iter().copied().filter(|p| ccw(p.poly)).collect();
        let inside = occlusion.fill_far_bounds(screen, &fronts);
        for (far, inside) in occlusion.far.iter_mut().zip(inside) {
            if !inside || far.is_nan() {
                *far = f64::INFINITY;
            }
        }
        occlusion.back_facing = back_facing;
        Some(occlusion)
    }

    /// Fills the far bounds (`self.far`, NaN where a contour side may pass stays NaN) and
    /// returns which cells have their centre inside a front piece: band of cell rows by band on
    /// all cores. A band writes its own rows only, visiting the pieces whose cells reach them
    /// (a piece across bands is visited by each). Each cell's bound is a maximum and its flag
    /// an `or`, so the order of the pieces does not matter.
    fn fill_far_bounds(&mut self, screen: &ScreenScene, fronts: &[&Piece]) -> Vec<bool> {
        let (boxes, cells): (Vec<[f64; 4]>, Vec<[i64; 4]>) = (fronts.par_iter().with_min_len(1024))
            .map(|p| {
                let b = bounds(p);
                (b, self.grid.cells_of(b))
            })
            .unzip();
        let mut inside = vec![false; self.far.len()];
        let CellGrid {
            origin,
            size,
            count,
        } = self.grid;
        let width = count[0];
        let band_rows = (count[1] as usize).div_ceil(ROW_BANDS).max(1);
        let band = band_rows * width as usize;
        let bands = self.far.len().div_ceil(band);
        // The pieces of each band, by a counting sort: band n's are
        // `in_band[starts[n]..starts[n + 1]]`, in piece order.
        let bands_of = |c: &[i64; 4]| {
            let band_of = |j: i64| j.clamp(0, count[1] - 1) as usize / band_rows;
            band_of(c[2])..=band_of(c[3])
        };
        let mut starts = vec![0usize; bands + 1];
        for c in &cells {
            for n in bands_of(c) {
                starts[n + 1] += 1;
            }
        }
        for n in 0..bands {
            starts[n + 1] += starts[n];
        }
        let mut in_band = vec![0u32; starts[bands]];
        let mut next = starts.clone();
        for (k, c) in cells.iter().enumerate() {
            for n in bands_of(c) {
                in_band[next[n]] = k as u32;
                next[n] += 1;
            }
        }
        (self
            .far
            .par_chunks_mut(band)
            .zip(inside.par_chunks_mut(band)))
        .enumerate()
        .for_each(|(n, (far, inside))| {
            let rows = [(n * band_rows) as i64, ((n + 1) * band_rows) as i64 - 1];
            for &k in &in_band[starts[n]..starts[n + 1]] {
                let (p, b, [i0, i1, j0, j1]) =
                    (fronts[k as usize], boxes[k as usize], cells[k as usize]);
                let (j0, j1) = (j0.max(rows[0]), j1.min(rows[1]).min(count[1] - 1));
                if j0 > j1 {
                    continue;
                }
                let depth = depth::Farthest::of(screen, p, b);
                for j in j0..=j1 {
                    for i in i0.max(0)..=i1.min(width - 1) {
                        let cell = ((j - rows[0]) * width + i) as usize;
                        if far[cell].is_nan() {
                            continue;
                        }
                        let rect = [
                            (origin[0] + i * size[0]) as f64,
                            (origin[1] + j * size[1]) as f64,
                            (origin[0] + (i + 1) * size[0]) as f64,
                            (origin[1] + (j + 1) * size[1]) as f64,
                        ];
                        far[cell] = far[cell].max(depth.within(rect));
                        if !inside[cell] {
                            let (x, y) = (
                                origin[0] + i * size[0] + size[0] / 2,
                                origin[1] + j * size[1] + size[1] / 2,
                            );
                            inside[cell] =
                                p.lines().all(|l| l.sign_at_grid(x, y) != Ordering::Less);
                        }
                    }
                }
            }
        });
        inside
    }

    /// Removes from `pieces` those [`Occlusion::hides`]; returns how many.
    fn drop_hidden(&self, screen: &ScreenScene, pieces: &mut Vec<Piece>) -> usize {
        // Each test reads the cells only: on all cores.
        let hidden: Vec<bool> = (pieces.par_iter().with_min_len(1024))
            .map(|p| self.hides(screen, p))
            .collect();
        let dropped = hidden.iter().filter(|&&h| h).count();
        let mut hidden = hidden.into_iter();
        pieces.retain(|_| !hidden.next().expect("one flag per piece"));
        dropped
    }

    /// Is `piece` seen from the back and proven hidden behind the cover? (See the module docs.)
    pub fn hides(&self, screen: &ScreenScene, piece: &Piece) -> bool {
        self.back_facing[piece.poly as usize]
            && self.hides_within(bounds(piece), || depth::range(screen, piece)[0])
    }

    /// [`Occlusion::hides`] for the piece a triangle would make, without making it: its
    /// bounds are its corners' box (widened as [`bounds`] widens), its nearest depth its nearest
    /// corner's (the proven range of a piece whose vertices are grid corners, exactly).
    fn hides_triangle(&self, screen: &ScreenScene, poly: u32) -> bool {
        if !self.back_facing[poly as usize] {
            return false;
        }
        let c = screen.corners(&screen.polys[poly as usize]);
        let b = c
            .iter()
            .fold([f64::MAX, f64::MAX, f64::MIN, f64::MIN], |b, p| {
                let (x, y) = (p.x as f64, p.y as f64);
                [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)]
            });
        let near = c.iter().map(|p| p.z).min().unwrap_or(0) as f64;
        self.hides_within([b[0] - 1.0, b[1] - 1.0, b[2] + 1.0, b[3] + 1.0], || near)
    }

    /// Do covered cells hold the box `b` (grid units), all nearer than `near()`?
    fn hides_within(&self, b: [f64; 4], near: impl FnOnce() -> f64) -> bool {
        let [i0, i1, j0, j1] = self.grid.cells_of(b);
        if i0 < 0 || j0 < 0 || i1 >= self.grid.count[0] || j1 >= self.grid.count[1] {
            return false;
        }
        let mut far = f64::NEG_INFINITY;
        for j in j0..=j1 {
            for i in i0..=i1 {
                far = far.max(self.far[(j * self.grid.count[0] + i) as usize]);
                if far == f64::INFINITY {
                    return false;
                }
            }
        }
        near() > far
    }
}

/// The contour sides of the polygons `front` (increasing): the segments (grid x, y) along which
/// they run one way only. Two polygons of one orientation running along a side in opposite
/// directions lie on its two sides, so the points inside it are inside their union; a side no
/// other polygon runs along the other way may have the union on one side only. A side of no
/// length is none.
///
/// Most sides are matched by their corners' grid points ([`point_pairs`]); only the pairs left
/// running one way are compared by their coordinates (distinct vertices may snap to one point:
/// unwelded seams). That second match sees those pairs only: where a segment has sides matched
/// by their points and others not, those others are contour sides, which only keeps more cells
/// from being covered. (Sorting every side by a hash of its segment and comparing the segments
/// again took 148 ms on the 1M sphere on one core; this takes 13-16 ms.)
fn contour_sides(screen: &ScreenScene, front: &[u32]) -> Vec<[[i64; 2]; 2]> {
    let keys: Vec<u64> = (front.par_iter().with_min_len(1024))
        .flat_map_iter(|&k| {
            let c = screen.corner_indices(&screen.polys[k as usize]);
            (0..c.len())
                .map(move |i| (c[i], c[(i + 1) % c.len()]))
                .filter(|(u, v)| u != v)
                .map(|(u, v)| side_key(u, v))
        })
        .collect();
    let one_way = point_pairs(screen.grid_points.len(), &keys, |up, down| {
        up == 0 || down == 0
    });
    drop(keys);
    // By coordinates from here: (the segment, its ends in increasing order; does the side run
    // that way?).
    let xy = |i: u32| {
        let g = screen.grid_points[i as usize];
        [g.x, g.y]
    };
    let mut unmatched: Vec<([[i64; 2]; 2], bool)> = (one_way.into_iter())
        .map(|pair| {
            let (u, v, up) = (xy(pair.lo), xy(pair.hi), pair.up > 0);
            if u <= v { ([u, v], up) } else { ([v, u], !up) }
        })
        .collect();
    // A segment is a contour side when its sides all run one way (the first and last of its
    // run agree) and it has a length.
    unmatched.par_sort_unstable();
    (unmatched.chunk_by(|a, b| a.0 == b.0))
        .filter(|run| run[0].1 == run[run.len() - 1].1 && run[0].0[0] != run[0].0[1])
        .map(|run| run[0].0)
        .collect()
}

/// Cells with integer corners over a frame of the screen grid, row by row: cell (i, j) is
/// `[origin + (i, j)·size, origin + (i + 1, j + 1)·size]`, at index `j·count[0] + i`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CellGrid {
    pub(crate) origin: [i64; 2],
    /// Cell width and height in grid units (at least 2: a cell's centre is inside it).
    pub(crate) size: [i64; 2],
    /// Cells per row and per column.
    pub(crate) count: [i64; 2],
}

impl CellGrid {
    /// About `cells` cells (at most 2048 a side) over the frame `all` (x0, y0, x1, y1).
    pub(crate) fn over(all: [i64; 4], cells: f64) -> CellGrid {
        let side = cells.sqrt().clamp(1.0, 2048.0) as i64;
        let span = |lo: i64, hi: i64| ((hi - lo).max(1) + side - 1) / side;
        let size = [span(all[0], all[2]).max(2), span(all[1], all[3]).max(2)];
        let count = [
            ((all[2] - all[0]) / size[0] + 1).min(side),
            ((all[3] - all[1]) / size[1] + 1).min(side),
        ];
        CellGrid {
            origin: [all[0], all[1]],
            size,
            count,
        }
    }

    /// How many cells.
    pub(crate) fn len(&self) -> usize {
        (self.count[0] * self.count[1]) as usize
    }

    /// The cells (i0, i1, j0, j1, inclusive, unclamped) whose closed rectangles may meet the
    /// box `b`: widened by a unit to integers that contain it, so the range is a superset.
    pub(crate) fn cells_of(&self, b: [f64; 4]) -> [i64; 4] {
        let (x0, y0) = (b[0].floor() as i64 - 1, b[1].floor() as i64 - 1);
        let (x1, y1) = (b[2].ceil() as i64 + 1, b[3].ceil() as i64 + 1);
        let cell = |v: i64, axis: usize| (v - self.origin[axis]).div_euclid(self.size[axis]);
        [cell(x0, 0), cell(x1, 0), cell(y0, 1), cell(y1, 1)]
    }

    /// Calls `mark` with (the index of) every cell that the segment from `u` to `v` (grid
    /// points) may meet: column by column of cells, the rows between the segment's lowest and
    /// highest y over the column, rounded outwards exactly (integer division) and widened by a
    /// unit, as [`Self::cells_of`] widens boxes. A long slanted side so marks the cells along
    /// it, not its whole box.
    pub(crate) fn segment_cells(&self, u: [i64; 2], v: [i64; 2], mut mark: impl FnMut(usize)) {
        let (u, v) = if u[0] <= v[0] { (u, v) } else { (v, u) };
        let [i0, i1, _, _] = self.cells_of([u[0] as f64, 0.0, v[0] as f64, 0.0]);
        let (dx, dy) = ((v[0] - u[0]) as i128, (v[1] - u[1]) as i128);
        for i in i0.max(0)..=i1.min(self.count[0] - 1) {
            // The segment's x-range within the column (closed), then y at its two ends.
            let cx0 = (self.origin[0] + i * self.size[0]).max(u[0]);
            let cx1 = (self.origin[0] + (i + 1) * self.size[0]).min(v[0]);
            let (ylo, yhi) = if dx == 0 {
                (u[1].min(v[1]), u[1].max(v[1]))
            } else if cx0 > cx1 {
                continue;
            } else {
                // y(x) = u.y + (x - u.x)·dy / dx, exactly bracketed by floor and ceil.
                let at = |x: i64| {
                    let num = (x - u[0]) as i128 * dy;
                    let floor = num.div_euclid(dx);
                    let ceil = floor + (num.rem_euclid(dx) != 0) as i128;
                    (u[1] as i128 + floor, u[1] as i128 + ceil)
                };
                let (a, b) = (at(cx0), at(cx1));
                (a.0.min(b.0) as i64, a.1.max(b.1) as i64)
            };
            let col = [
                (self.origin[0] + i * self.size[0]) as f64,
                ylo as f64,
                (self.origin[0] + i * self.size[0]) as f64,
                yhi as f64,
            ];
            let [_, _, j0, j1] = self.cells_of(col);
            for j in j0.max(0)..=j1.min(self.count[1] - 1) {
                mark((j * self.count[0] + i) as usize);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::GridPoint;
    use crate::visibility::initial_pieces;

    /// A screen scene of triangles given as (x, y, z) corners.
    fn screen_of(tris: &[[[i64; 3]; 3]]) -> ScreenScene {
        crate::visibility::screen_of_polygons(
            (tris.iter()).map(|t| t.iter().map(|&[x, y, z]| GridPoint { x, y, z }).collect()),
        )
    }

    /// An 8 x 8 grid of counter-clockwise squares of side 8 at depth `z`, two triangles each,
    /// less the square at (hole, hole) when given.
    fn front_grid(z: i64, hole: Option<i64>) -> Vec<[[i64; 3]; 3]> {
        let mut tris = Vec::new();
        for j in 0..8 {
            for i in 0..8 {
                if hole == Some(i) && hole == Some(j) {
                    continue;
                }
                let (x, y) = (8 * i, 8 * j);
                tris.push([[x, y, z], [x + 8, y, z], [x + 8, y + 8, z]]);
                tris.push([[x, y, z], [x + 8, y + 8, z], [x, y + 8, z]]);
            }
        }
        tris
    }

    /// Is the last triangle (seen from the back: clockwise) proven hidden?
    fn last_hidden(tris: &[[[i64; 3]; 3]]) -> bool {
        let s = screen_of(tris);
        let pieces = initial_pieces(&s);
        let refs: Vec<&Piece> = pieces.iter().collect();
        let back = back_facing(&s);
        assert!(back[tris.len() - 1] && !back[0]);
        let o = Occlusion::of(&s, &refs, 1.0).expect("front and back");
        o.hides(&s, pieces.last().unwrap())
    }

    /// A small clockwise triangle around (cx, cy) at depth z.
    fn back_triangle(cx: i64, cy: i64, z: i64) -> [[i64; 3]; 3] {
        [
            [cx - 3, cy - 3, z],
            [cx, cy + 3, z + 1],
            [cx + 3, cy - 3, z],
        ]
    }

    /// Two ordered lists with no key in common merged: the order of a forward merge, each
    /// list's equal keys in their order, whichever is longer, with either empty.
    #[test]
    fn merged_lists_keep_the_order_of_a_forward_merge() {
        let forward = |a: &[(u32, char)], b: &[(u32, char)]| {
            let mut all: Vec<(u32, char)> = a.iter().chain(b).copied().collect();
            all.sort_by_key(|x| x.0); // stable: a's before b's among equal keys
            all
        };
        let a = vec![(1, 'p'), (3, 'r'), (3, 'q'), (4, 's'), (9, 't')];
        let b = vec![(0, 'u'), (5, 'w'), (5, 'v'), (8, 'y'), (12, 'x'), (12, 'z')];
        for (x, y) in [
            (a.clone(), b.clone()),
            (b.clone(), a.clone()),
            (a.clone(), Vec::new()),
            (Vec::new(), b.clone()),
            (a[..1].to_vec(), b.clone()),
            (b.clone(), a[3..].to_vec()),
        ] {
            let want = forward(&x, &y);
            assert_eq!(merged_by(x, y, |p| p.0), want);
        }
    }

    #[test]
    fn triangles_tried_whole_are_dropped_exactly_as_their_pieces_would_be() {
        // A sheet with a hole, and behind, in front of and around it back-facing triangles and
        // a back-facing quad (a quad is made into its piece first, a triangle only if shown).
        let mut tris = front_grid(1000, Some(2));
        for (cx, cy, z) in [
            (36, 28, 2000),
            (36, 28, 500),
            (63, 28, 2000),
            (20, 20, 2000),
        ] {
            tris.push(back_triangle(cx, cy, z));
        }
        // Through the sheet: its nearest corner is in front, its farthest behind.
        tris.push([[33, 25, 900], [36, 31, 2000], [39, 25, 900]]);
        let gp = |x, y, z| GridPoint { x, y, z };
        let mut polys: Vec<Vec<GridPoint>> = (tris.iter())
            .map(|t| t.iter().map(|&[x, y, z]| gp(x, y, z)).collect())
            .collect();
        polys.push(vec![
            gp(40, 40, 3000),
            gp(40, 46, 3000),
            gp(46, 46, 3000),
            gp(46, 40, 3000),
        ]);
        let s = crate::visibility::screen_of_polygons(polys);
        let mut want = initial_pieces(&s);
        let dropped = drop_hidden(&s, &mut want);
        assert_eq!(dropped, 2, "the triangle and the quad behind the sheet");
        let all: Vec<u32> = (0..s.polys.len() as u32).collect();
        assert_eq!(unhidden_pieces(&s, &all), (want, dropped));
        // A subset of the polygons: the cells are made of those alone.
        let some: Vec<u32> = all.iter().copied().filter(|k| k % 3 != 1).collect();
        let mut want: Vec<Piece> = initial_pieces(&s)
            .into_iter()
            .filter(|p| some.contains(&p.poly))
            .collect();
        let dropped = drop_hidden(&s, &mut want);
        assert_eq!(unhidden_pieces(&s, &some), (want, dropped));
    }

    #[test]
    fn a_back_face_behind_a_closed_front_sheet_is_proven_hidden() {
        let mut tris = front_grid(1000, None);
        tris.push(back_triangle(36, 28, 2000));
        assert!(last_hidden(&tris));
    }

    #[test]
    fn the_cover_is_what_faces_the_eye_so_meshes_wound_inwards_hide_their_far_side_too() {
        // Clockwise triangles facing the eye (a mesh wound inwards) hide a counter-clockwise
        // one behind them; then the same scene wound outwards hides nothing.
        let flip = |[a, b, c]: [[i64; 3]; 3]| [a, c, b];
        let mut tris: Vec<_> = front_grid(1000, None).into_iter().map(flip).collect();
        tris.push(flip(back_triangle(36, 28, 2000)));
        let mut s = screen_of(&tris);
        for p in s.polys.iter_mut() {
            p.front = !p.front;
        }
        let pieces = initial_pieces(&s);
        let refs: Vec<&Piece> = pieces.iter().collect();
        let o = Occlusion::of(&s, &refs, 1.0).expect("front and back");
        assert!(o.hides(&s, pieces.last().unwrap()));
        let s = screen_of(&tris);
        let o = Occlusion::of(&s, &refs, 1.0).expect("front and back");
        assert!(!o.hides(&s, pieces.last().unwrap()));
    }

    #[test]
    fn a_long_slanted_contour_side_leaves_the_cells_away_from_it_covered() {
        // The grid's lower right half: below the diagonal from (0, 0) to (64, 64), which the
        // diagonal squares' lower triangles make one long slanted contour of eight sides.
        let mut tris: Vec<[[i64; 3]; 3]> = front_grid(1000, None)
            .into_iter()
            .filter(|t| t.iter().all(|&[x, y, _]| x >= y))
            .collect();
        // Its box meets the diagonal's, but not the cells along the diagonal.
        tris.push(back_triangle(44, 16, 2000));
        assert!(last_hidden(&tris));
        // Across the diagonal: not covered.
        let last = tris.len() - 1;
        tris[last] = back_triangle(30, 30, 2000);
        assert!(!last_hidden(&tris));
    }

    #[test]
    fn a_back_face_in_front_of_the_sheet_or_beyond_its_contour_or_behind_a_hole_is_not() {
        // In front of the sheet.
        let mut tris = front_grid(1000, None);
        tris.push(back_triangle(36, 28, 500));
        assert!(!last_hidden(&tris));
        // Through the sheet: its far corner is behind, its near corners in front.
        let mut tris = front_grid(1000, None);
        tris.push([[33, 25, 900], [36, 31, 2000], [39, 25, 900]]);
        assert!(!last_hidden(&tris));
        // Behind, but reaching beyond the sheet's edge.
        let mut tris = front_grid(1000, None);
        tris.push(back_triangle(63, 28, 2000));
        assert!(!last_hidden(&tris));
        // Behind a hole in the sheet (the square at (4, 4) is missing).
        let mut tris = front_grid(1000, Some(4));
        tris.push(back_triangle(36, 36, 2000));
        assert!(!last_hidden(&tris));
        // Behind a sheet whose triangles share no side (each one's sides are all contour).
        let mut tris: Vec<[[i64; 3]; 3]> = front_grid(1000, None)
            .into_iter()
            .map(|t| t.map(|[x, y, z]| [2 * x, 2 * y, z]))
            .collect();
        for t in tris.iter_mut() {
            // Shrink every triangle towards its first corner: gaps everywhere.
            let [a, b, c] = *t;
            let mid = |p: [i64; 3]| [(a[0] + p[0] * 3) / 4, (a[1] + p[1] * 3) / 4, p[2]];
            *t = [a, mid(b), mid(c)];
        }
        tris.push(back_triangle(72, 56, 2000));
        assert!(!last_hidden(&tris));
    }
}
