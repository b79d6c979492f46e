//! A growing set of convex pieces on a screen grid, any of which may be removed: the working
//! store of the strategies that cut pieces one against another (the coverage map, Newell's
//! overpainting, Weiler–Atherton's lists).
//!
//! Invariant: a piece's index never changes and is never reused; a removed piece leaves its grid
//! cells lazily, on the next query that visits them. Bounds are a filter ([`bounds`]): callers
//! decide exactly what a query returns.

use super::grid::BoxGrid;
use crate::exact::polygon::Piece;

/// Screen bounds (grid units) that certainly contain the piece, widened by a unit so that
/// touching pieces also meet: a filter for candidate pairs, never a decision.
pub(crate) fn bounds(p: &Piece) -> [f64; 4] {
    let b = p.bounds();
    [b[0] - 1.0, b[1] - 1.0, b[2] + 1.0, b[3] + 1.0]
}

/// Do two boxes overlap (open: touching boxes do not)?
pub(crate) fn overlap(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// The store. See the module docs.
pub(crate) struct Live {
    pieces: Vec<Option<Piece>>,
    bounds: Vec<[f64; 4]>,
    grid: BoxGrid,
    /// Per piece, the last query that met it (dedupes across cells).
    seen: Vec<u32>,
    query: u32,
}

impl Live {
    /// An empty store whose grid covers `boxes` (about one cell per box): every piece added
    /// later should lie in their union (pieces outside it still work, in the border cells).
    pub fn over<'b>(boxes: impl IntoIterator<Item = &'b [f64; 4]>, count: usize) -> Live {
        Live {
            pieces: Vec::new(),
            bounds: Vec::new(),
            grid: BoxGrid::over(boxes, count),
            seen: Vec::new(),
            query: 0,
        }
    }

    /// Adds a piece with its bounds; returns its index.
    pub fn add(&mut self, piece: Piece, b: [f64; 4]) -> u32 {
        let index = self.pieces.len() as u32;
        self.grid.insert(index, &b);
        self.pieces.push(Some(piece));
        self.bounds.push(b);
        self.seen.push(0);
        index
    }

    /// The piece at `v`, if not removed.
    pub fn get(&self, v: u32) -> Option<&Piece> {
        self.pieces[v as usize].as_ref()
    }

    /// The bounds of piece `v` (removed or not).
    pub fn bounds_of(&self, v: u32) -> &[f64; 4] {
        &self.bounds[v as usize]
    }

    /// Removes piece `v` and returns it.
    pub fn take(&mut self, v: u32) -> Option<Piece> {
        self.pieces[v as usize].take()
    }

    /// The live pieces whose bounds overlap `b`, ascending.
    pub fn near(&mut self, b: &[f64; 4]) -> Vec<u32> {
        let mut near = Vec::new();
        self.near_into(b, &mut near);
        near
    }

    /// [`Live::near`] into `near` (cleared first): a buffer reused across queries.
    pub fn near_into(&mut self, b: &[f64; 4], near: &mut Vec<u32>) {
        self.query += 1;
        near.clear();
        let (pieces, bounds, seen, query) =
            (&self.pieces, &self.bounds, &mut self.seen, self.query);
        self.grid.visit(
            b,
            |v| pieces[v as usize].is_some(),
            |v| {
                if seen[v as usize] != query && overlap(&bounds[v as usize], b) {
                    seen[v as usize] = query;
                    near.push(v);
                }
            },
        );
        near.sort_unstable();
    }

    /// The live pieces, ascending by index.
    pub fn into_pieces(self) -> Vec<Piece> {
        // Sized first: collecting through `flatten` grows by doubling (up to twice the room).
        let live = self.pieces.iter().filter(|p| p.is_some()).count();
        let mut out = Vec::with_capacity(live);
        out.extend(self.pieces.into_iter().flatten());
        out
    }
}
