//! The coverage map: the exact visible set, built one convex piece at a time.
//!
//! Invariant: the map's live pieces have pairwise disjoint interiors, each lies in the projection
//! of its own face, and at every point of a live piece no piece inserted so far is nearer (ties
//! between coplanar pieces go to the larger face id, then the later polygon, as in the z-buffer).
//! Once every piece of a scene is in, the live pieces are the scene's visible set.
//!
//! Two ways in:
//! - [`Coverage::insert_behind`], for a piece that nothing already inserted lies behind (the
//!   order a BSP walk gives): the piece is cut by the lines of the visible pieces it overlaps and
//!   only the part outside all of them stays. Visible pieces never change.
//! - [`Coverage::insert`], in any order: where the new piece overlaps a visible piece, both are
//!   split by the line where their planes meet (exactly, [`Piece::split_by_plane`]) and each
//!   keeps the side where it is nearer. A visible piece that loses area is replaced by what it
//!   keeps. The work follows what is visible, not how tangled the scene is: a soup of large
//!   interpenetrating triangles costs the splits its visible arrangement needs, where a BSP
//!   would cut every triangle by the planes of all the others it straddles.
//!
//! Pieces are bucketed on a uniform screen grid so that a new piece meets only the visible
//! pieces whose bounds overlap its own; the bounds are a filter, every decision is exact.

use super::grid::BoxGrid;
use crate::exact::polygon::{Piece, Split, separated};
use crate::project::ScreenScene;
use std::cmp::Reverse;

/// Screen bounds (grid units) that certainly contain the piece, widened by a unit so that
/// touching pieces also meet: a filter for candidate pairs, never a decision.
pub(crate) fn bounds(p: &Piece) -> [f64; 4] {
    let b = p.bounds();
    [b[0] - 1.0, b[1] - 1.0, b[2] + 1.0, b[3] + 1.0]
}

fn overlap(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// The order of coplanar pieces, front first: larger face id, then later polygon.
pub(crate) fn tie_key(screen: &ScreenScene, p: &Piece) -> (Reverse<u32>, Reverse<u32>) {
    (Reverse(screen.polys[p.poly as usize].id), Reverse(p.poly))
}

/// Counters of one coverage pass.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CoverageStats {
    /// Pieces handed in.
    pub inserted: usize,
    /// Visible pieces that lost area to a later, nearer piece and were replaced.
    pub replaced: usize,
    /// Exact overlap tests (after the bounds filter).
    pub overlap_tests: usize,
}

/// The exact visible set under construction. See the module docs.
pub struct Coverage<'a> {
    screen: &'a ScreenScene,
    /// Every piece ever made visible; `None` once replaced.
    visible: Vec<Option<Piece>>,
    bounds: Vec<[f64; 4]>,
    grid: BoxGrid,
    /// Per visible piece, the last query that met it (dedupes across buckets).
    seen: Vec<u32>,
    query: u32,
    /// Counters so far.
    pub stats: CoverageStats,
}

impl<'a> Coverage<'a> {
    /// An empty map sized for `pieces` (only their bounds and number are read).
    pub fn new<'p>(screen: &'a ScreenScene, pieces: impl IntoIterator<Item = &'p Piece>) -> Self {
        let boxes: Vec<[f64; 4]> = pieces.into_iter().map(bounds).collect();
        Coverage {
            screen,
            visible: Vec::new(),
            bounds: Vec::new(),
            grid: BoxGrid::over(&boxes, boxes.len()),
            seen: Vec::new(),
            query: 0,
            stats: CoverageStats::default(),
        }
    }

    /// The live visible pieces, in the order they became visible.
    pub fn into_pieces(self) -> Vec<Piece> {
        self.visible.into_iter().flatten().collect()
    }

    /// The live visible pieces whose bounds overlap `b`, in index order.
    fn near(&mut self, b: &[f64; 4]) -> Vec<u32> {
        self.query += 1;
        let mut near: Vec<u32> = Vec::new();
        let (visible, bounds, seen, query) =
            (&self.visible, &self.bounds, &mut self.seen, self.query);
        // Replaced pieces leave their cells lazily, here.
        self.grid.visit(
            b,
            |v| visible[v as usize].is_some(),
            |v| {
                if seen[v as usize] != query && overlap(&bounds[v as usize], b) {
                    seen[v as usize] = query;
                    near.push(v);
                }
            },
        );
        near.sort_unstable();
        near
    }

    fn add(&mut self, piece: Piece, pb: [f64; 4]) -> u32 {
        let index = self.visible.len() as u32;
        self.grid.insert(index, &pb);
        self.visible.push(Some(piece));
        self.bounds.push(pb);
        self.seen.push(0);
        index
    }

    /// Inserts a piece that nothing already inserted lies behind where they overlap.
    pub fn insert_behind(&mut self, piece: Piece) {
        self.stats.inserted += 1;
        for part in self.clipped_by_near(piece, |_, part, front, out| subtract(part, front, out)) {
            let b = bounds(&part);
            self.add(part, b);
        }
    }

    /// Pushes the parts of `piece` that no live piece hides (nearer, or coplanar and first by
    /// the tie rule), leaving the map as it is: a translucent fragment over an opaque visible
    /// set.
    pub fn unhidden_parts(&mut self, piece: Piece, out: &mut Vec<Piece>) {
        out.extend(self.clipped_by_near(piece, |screen, part, front, out| {
            if separated(&part, front) {
                out.push(part);
                return;
            }
            // The viewer is on the negative side of `front`'s support plane.
            match part.split_by_plane(&front.support, front.poly) {
                Split::Negative => out.push(part),
                Split::Positive => subtract(part, front, out),
                Split::On if tie_key(screen, &part) < tie_key(screen, front) => out.push(part),
                Split::On => subtract(part, front, out),
                Split::Both(nearer, farther) => {
                    out.push(nearer);
                    subtract(farther, front, out);
                }
            }
        }));
    }

    /// What is left of `piece` after `clip(screen, part, front, kept)` has kept, of each part
    /// so far, what one live piece whose bounds meet it leaves; the live pieces in turn, in
    /// index order. The map is not changed.
    fn clipped_by_near(
        &mut self,
        piece: Piece,
        clip: impl Fn(&ScreenScene, Piece, &Piece, &mut Vec<Piece>),
    ) -> Vec<Piece> {
        let near = self.near(&bounds(&piece));
        let mut parts = vec![piece];
        for v in near {
            let front = self.visible[v as usize].as_ref().expect("live");
            let mut next = Vec::with_capacity(parts.len());
            for part in parts {
                self.stats.overlap_tests += 1;
                clip(self.screen, part, front, &mut next);
            }
            parts = next;
            if parts.is_empty() {
                break;
            }
        }
        parts
    }

    /// Inserts a piece in any order: see the module docs.
    pub fn insert(&mut self, piece: Piece) {
        self.stats.inserted += 1;
        let b = bounds(&piece);
        let mut queue = self.near(&b);
        // Each part with its bounds, computed once: they cost crossings.
        let mut parts = vec![(piece, b)];
        let mut resolved = Vec::new();
        let mut done = Vec::new();
        let mut next_in_queue = 0;
        while next_in_queue < queue.len() {
            let v = queue[next_in_queue] as usize;
            next_in_queue += 1;
            let Some(front) = self.visible[v].as_ref() else {
                continue;
            };
            let vb = self.bounds[v];
            let mut replacement: Option<Vec<Piece>> = None;
            // Parts that `front` leaves alone stay in place; resolved ones wait in `done`, since
            // they are settled against `front`.
            let mut i = 0;
            while i < parts.len() {
                if !overlap(&parts[i].1, &vb) {
                    i += 1;
                    continue;
                }
                self.stats.overlap_tests += 1;
                if separated(&parts[i].0, front) {
                    i += 1;
                    continue;
                }
                let (part, _) = parts.swap_remove(i);
                let front_keeps = self.resolve(part, front, &mut resolved);
                done.extend(resolved.drain(..).map(|p| {
                    let b = bounds(&p);
                    (p, b)
                }));
                if front_keeps.is_some() {
                    // The visible piece changed: the parts not yet compared meet what it
                    // keeps through the queue.
                    replacement = front_keeps;
                    break;
                }
            }
            parts.append(&mut done);
            if let Some(front_keeps) = replacement {
                self.visible[v] = None;
                self.stats.replaced += 1;
                for p in front_keeps {
                    let b = bounds(&p);
                    queue.push(self.add(p, b));
                }
            }
            if parts.is_empty() {
                return;
            }
        }
        for (part, b) in parts {
            self.add(part, b);
        }
    }

    /// Resolves an overlapping pair: pushes what `part` keeps to `kept` and returns what the
    /// visible piece `front` keeps, or `None` when it keeps everything.
    fn resolve(&self, part: Piece, front: &Piece, kept: &mut Vec<Piece>) -> Option<Vec<Piece>> {
        // The viewer is on the negative side of every support plane: the negative side of
        // `front`'s plane is nearer than `front`.
        match part.split_by_plane(&front.support, front.poly) {
            Split::Positive => {
                subtract(part, front, kept);
                None
            }
            Split::Negative => {
                let mut front_keeps = Vec::new();
                subtract(front.clone(), &part, &mut front_keeps);
                kept.push(part);
                Some(front_keeps)
            }
            Split::On => {
                if tie_key(self.screen, &part) < tie_key(self.screen, front) {
                    let mut front_keeps = Vec::new();
                    subtract(front.clone(), &part, &mut front_keeps);
                    kept.push(part);
                    Some(front_keeps)
                } else {
                    subtract(part, front, kept);
                    None
                }
            }
            Split::Both(part_nearer, part_farther) => {
                // Where the part is nearer, `front` is farther, and the other way round: the
                // two splits are by the same screen line, the projection of the planes' meet.
                let mut front_keeps = Vec::new();
                let front_nearer = match front.split_by_plane(&part.support, part.poly) {
                    Split::Negative | Split::On => {
                        // `front` is nearer wherever it is, so the part's nearer side misses it.
                        subtract(part_farther, front, kept);
                        kept.push(part_nearer);
                        return None;
                    }
                    Split::Positive => None,
                    Split::Both(nearer, farther) => {
                        subtract(farther, &part_nearer, &mut front_keeps);
                        Some(nearer)
                    }
                };
                match front_nearer {
                    None => {
                        // `front` is farther wherever it is: it loses what the part covers.
                        subtract(front.clone(), &part_nearer, &mut front_keeps);
                        kept.push(part_nearer);
                        kept.push(part_farther);
                    }
                    Some(nearer) => {
                        subtract(part_farther, &nearer, kept);
                        kept.push(part_nearer);
                        front_keeps.push(nearer);
                    }
                }
                Some(front_keeps)
            }
        }
    }
}

/// Pushes the parts of `piece` outside the convex `front` (exactly; touching is outside).
pub(crate) fn subtract(piece: Piece, front: &Piece, out: &mut Vec<Piece>) {
    if separated(&piece, front) {
        out.push(piece);
        return;
    }
    let mut inside = piece;
    let lines = front.lines.iter().zip(&front.line_approx);
    for ((line, approx), origin) in lines.zip(&front.boundaries) {
        match inside.split_by_line_with(line, approx, *origin) {
            // Entirely outside this line of `front`: nothing of it is hidden.
            Split::Negative => {
                out.push(inside);
                return;
            }
            Split::Positive => {}
            Split::Both(outside, rest) => {
                out.push(outside);
                inside = rest;
            }
            // No area: nothing to keep.
            Split::On => return,
        }
    }
    // What is left is inside every line of `front`: hidden.
}
