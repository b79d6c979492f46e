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

use super::covered::{CoverTries, covered};
use super::depth::{self, cannot_hide};
pub(crate) use super::live::bounds;
use super::live::{Live, overlap};
use super::occlusion::{CELLS_PER_PIECE, Occlusion};
use super::strips::Counters;
use super::{Outline, separated_on};
use crate::exact::polygon::{Piece, Split, separated};
use crate::project::ScreenScene;
use std::cmp::Reverse;

/// The order of coplanar pieces, front first: larger face id, then later polygon.
pub(crate) fn tie_key(screen: &ScreenScene, p: &Piece) -> (Reverse<u32>, Reverse<u32>) {
    polygon_tie_key(screen, p.poly)
}

/// [`tie_key`] of polygon `poly`'s pieces.
fn polygon_tie_key(screen: &ScreenScene, poly: u32) -> (Reverse<u32>, Reverse<u32>) {
    (Reverse(screen.polys[poly as usize].id), Reverse(poly))
}

/// The order of polygons nearest first: nearest corner first, then the z-buffer's tie rule
/// (front first, as [`tie_key`]). The coverage map inserts pieces in this order, Weiler and
/// Atherton take clip polygons in it, and Warnock's subdivision tries surrounding pieces in it.
pub(crate) fn nearest_first(screen: &ScreenScene, poly: u32) -> impl Ord {
    let p = &screen.polys[poly as usize];
    let nearest = screen.corners(p).iter().map(|c| c.z).min().unwrap_or(0);
    (nearest, polygon_tie_key(screen, poly))
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
    /// Overlapping pairs split where their planes meet (each reaches in front of the other's
    /// plane there): the splits interpenetration and cyclic overlap need.
    pub plane_splits: usize,
    /// Pieces proven hidden by the occlusion cells before any cut.
    pub occluded: usize,
    /// Pieces no other piece overlaps, visible whole without entering a map
    /// (`visibility::clear`).
    pub clear: usize,
    /// Pieces tried whole against the visible pieces in front of them, before any cut, and
    /// those proven hidden so ([`covered`]).
    pub covers: CoverTries,
}

impl CoverageStats {
    /// Counts `n` pieces that the occlusion cells dropped before the map: inserted and occluded,
    /// as the map counts the pieces its own cells drop.
    pub(crate) fn dropped_before_insertion(&mut self, n: usize) {
        self.inserted += n;
        self.occluded += n;
    }

    /// Counts `n` clear pieces ([`super::clear`]) kept out of the map: inserted and clear.
    pub(crate) fn clear_before_insertion(&mut self, n: usize) {
        self.inserted += n;
        self.clear += n;
    }
}

impl Counters for CoverageStats {
    fn add(&mut self, o: &Self) {
        self.inserted += o.inserted;
        self.replaced += o.replaced;
        self.overlap_tests += o.overlap_tests;
        self.plane_splits += o.plane_splits;
        self.occluded += o.occluded;
        self.clear += o.clear;
        self.covers.add(&o.covers);
    }
}

/// The exact visible set under construction. See the module docs.
pub struct Coverage<'a> {
    screen: &'a ScreenScene,
    /// Every piece ever made visible; removed once replaced.
    visible: Live,
    /// Where the pieces facing the eye cover the screen, for the cheap proof that a piece facing
    /// away is hidden; only when there are both.
    occlusion: Option<Occlusion>,
    /// Counters so far.
    pub stats: CoverageStats,
}

impl<'a> Coverage<'a> {
    /// An empty map for `pieces`: the pieces of whole polygons that will all be inserted, in
    /// some order and possibly cut further (their bounds size the grid; the polygons seen from
    /// the front make the occlusion cells, which may prove a piece hidden before the pieces
    /// that hide it are in).
    pub fn new<'p>(screen: &'a ScreenScene, pieces: impl IntoIterator<Item = &'p Piece>) -> Self {
        Coverage::with_occlusion(screen, pieces, true)
    }

    /// [`Coverage::new`], with occlusion cells only when `occlusion` (not worth making again
    /// for pieces that [`super::occlusion::drop_hidden`] has already been through).
    pub(crate) fn with_occlusion<'p>(
        screen: &'a ScreenScene,
        pieces: impl IntoIterator<Item = &'p Piece>,
        occlusion: bool,
    ) -> Self {
        let pieces: Vec<&Piece> = pieces.into_iter().collect();
        let boxes: Vec<[f64; 4]> = pieces.iter().map(|p| bounds(p)).collect();
        Coverage {
            screen,
            visible: Live::over(&boxes, boxes.len()),
            occlusion: occlusion
                .then(|| Occlusion::of(screen, &pieces, CELLS_PER_PIECE))
                .flatten(),
            stats: CoverageStats::default(),
        }
    }

    /// The map of pieces already pairwise disjoint and in front of whatever will be layered
    /// over them (another exact strategy's visible set), as they are.
    pub fn of_visible(screen: &'a ScreenScene, pieces: Vec<Piece>) -> Self {
        // Not whole polygons: no cover can be read from their outlines.
        let mut map = Coverage::with_occlusion(screen, &pieces, false);
        for p in pieces {
            let b = bounds(&p);
            map.visible.add(p, b);
        }
        map
    }

    /// The live visible pieces, in the order they became visible.
    pub fn into_pieces(self) -> Vec<Piece> {
        self.visible.into_pieces()
    }

    /// Inserts a piece that nothing already inserted lies behind where they overlap.
    pub fn insert_behind(&mut self, piece: Piece) {
        self.stats.inserted += 1;
        if self.occluded(&piece) {
            return;
        }
        for part in self.clipped_by_near(piece, true, |_, part, front, out| {
            subtract_overlapping(part, front, out)
        }) {
            let b = bounds(&part);
            self.visible.add(part, b);
        }
    }

    /// Inserts pieces with pairwise disjoint interiors, none of which lies behind an already
    /// inserted piece where they overlap, as [`Coverage::insert_behind`] one by one would (the
    /// same visible pieces, in the same order): none clips another, so each is clipped only
    /// by the pieces in before them, and none is a candidate for the others.
    pub fn insert_disjoint(&mut self, pieces: Vec<Piece>) {
        let mut visible = Vec::new();
        for piece in pieces {
            self.stats.inserted += 1;
            if self.occluded(&piece) {
                continue;
            }
            visible.extend(self.clipped_by_near(piece, true, |_, part, front, out| {
                subtract_overlapping(part, front, out)
            }));
        }
        for part in visible {
            let b = bounds(&part);
            self.visible.add(part, b);
        }
    }

    /// Pushes the parts of `piece` that no live piece hides (nearer, or coplanar and first by
    /// the tie rule), leaving the map as it is: a translucent fragment over an opaque visible
    /// set.
    pub fn unhidden_parts(&mut self, piece: Piece, out: &mut Vec<Piece>) {
        out.extend(
            self.clipped_by_near(piece, false, |screen, part, front, out| {
                let (nearer, farther) = split_by_depth(screen, part, front);
                out.extend(nearer);
                if let Some(farther) = farther {
                    subtract(farther, front, out);
                }
            }),
        );
    }

    /// What is left of `piece` after `clip(screen, part, front, kept)` has kept, of each part
    /// so far that meets one live piece whose bounds meet it ([`separated`] said no), what
    /// that live piece leaves; the live pieces in turn, in index order. Parts apart from a
    /// live piece stay as they are, in place: most near pieces only touch, and moving every
    /// part through each of them was a tenth of the 1M sphere's time. The map is not changed.
    ///
    /// `in_front`: the live pieces lie in front of `piece` wherever they overlap it, so that it
    /// keeps nothing where they cover it. Then a piece that meets some may first be tried whole
    /// against them ([`covered`], while it pays: [`CoverTries`]): most such pieces
    /// in a surface's shadow are hidden, and are dropped uncut.
    fn clipped_by_near(
        &mut self,
        piece: Piece,
        in_front: bool,
        clip: impl Fn(&ScreenScene, Piece, &Piece, &mut Vec<Piece>),
    ) -> Vec<Piece> {
        let mut near = self.visible.near(&bounds(&piece));
        // Tried whole, the pieces that meet it are found first (a part lies in the piece, so no
        // other meets a part), and the first of them is known to meet it.
        let try_whole = in_front && !near.is_empty() && self.stats.covers.worth_trying();
        if try_whole {
            near = self.meeting(&piece, &near);
            if near.is_empty() {
                return vec![piece];
            }
            let fronts = self.live_pieces(&near);
            if self.stats.covers.record(covered(&piece, &fronts)) {
                return Vec::new();
            }
        }
        let mut parts = vec![piece];
        let mut next = Vec::new();
        for (k, &v) in near.iter().enumerate() {
            let front = self.visible.get(v).expect("live");
            let known = try_whole && k == 0;
            let meets = |part: &Piece| known || !separated_on(self.screen, part, front);
            if !known {
                self.stats.overlap_tests += parts.len();
            }
            let Some(first) = parts.iter().position(meets) else {
                continue;
            };
            next.reserve(parts.len());
            for (i, part) in parts.drain(..).enumerate() {
                if i == first || (i > first && meets(&part)) {
                    clip(self.screen, part, front, &mut next);
                } else {
                    next.push(part);
                }
            }
            std::mem::swap(&mut parts, &mut next);
            if parts.is_empty() {
                break;
            }
        }
        parts
    }

    /// Is `piece` proven hidden before any cut ([`Occlusion`])? Counts what it hides.
    fn occluded(&mut self, piece: &Piece) -> bool {
        let hidden = (self.occlusion.as_ref()).is_some_and(|o| o.hides(self.screen, piece));
        self.stats.occluded += hidden as usize;
        hidden
    }

    /// Inserts a piece in any order: see the module docs.
    pub fn insert(&mut self, piece: Piece) {
        self.stats.inserted += 1;
        if self.occluded(&piece) {
            return;
        }
        let b = bounds(&piece);
        let mut queue = self.visible.near(&b);
        if !queue.is_empty() && self.stats.covers.worth_trying() {
            // The near pieces apart from the piece are apart from every part of it: only those
            // that meet it stay in the queue.
            let meeting = self.meeting(&piece, &queue);
            if self.under_all(&piece, &meeting) {
                return;
            }
            queue = meeting;
        }
        // Each part with its bounds, computed once: they cost crossings.
        let mut parts = vec![(piece, b)];
        let mut resolved = Vec::new();
        let mut done = Vec::new();
        let mut next_in_queue = 0;
        while next_in_queue < queue.len() {
            let v = queue[next_in_queue];
            next_in_queue += 1;
            let Some(front) = self.visible.get(v) else {
                continue;
            };
            let vb = *self.visible.bounds_of(v);
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
                if separated_on(self.screen, &parts[i].0, front) {
                    i += 1;
                    continue;
                }
                let (part, _) = parts.swap_remove(i);
                let front_keeps = resolve(
                    self.screen,
                    part,
                    front,
                    &mut resolved,
                    &mut self.stats.plane_splits,
                );
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
                self.visible.take(v);
                self.stats.replaced += 1;
                for p in front_keeps {
                    let b = bounds(&p);
                    queue.push(self.visible.add(p, b));
                }
            }
            if parts.is_empty() {
                return;
            }
        }
        for (part, b) in parts {
            self.visible.add(part, b);
        }
    }

    /// The live pieces of `near` whose interiors meet `piece`'s, in order.
    fn meeting(&mut self, piece: &Piece, near: &[u32]) -> Vec<u32> {
        let (screen, live) = (self.screen, &self.visible);
        let outline = Outline::of(piece);
        self.stats.overlap_tests += near.len();
        (near.iter().copied())
            .filter(|&v| !outline.separated_from(screen, live.get(v).expect("live")))
            .collect()
    }

    /// The live pieces `at` those indices.
    fn live_pieces(&self, at: &[u32]) -> Vec<&Piece> {
        at.iter()
            .map(|&v| self.visible.get(v).expect("live"))
            .collect()
    }

    /// Is `piece` proven hidden whole, before any cut, by the live pieces `meeting` it (all
    /// of them)? When each lies in front of it there (it can hide no part of them:
    /// [`cannot_hide`]) and it lies within their union ([`covered`]). Inserted in any order,
    /// most pieces that meet visible ones still come after what hides them (the coverage
    /// strategy inserts the nearest first). Counted in [`CoverTries`].
    fn under_all(&mut self, piece: &Piece, meeting: &[u32]) -> bool {
        if meeting.is_empty() {
            return false;
        }
        let screen = self.screen;
        let fronts = self.live_pieces(meeting);
        let depth = depth::range(screen, piece);
        let behind_all = (fronts.iter())
            .all(|front| cannot_hide((piece, depth), (front, depth::range(screen, front))));
        self.stats
            .covers
            .record(behind_all && covered(piece, &fronts))
    }
}

/// Resolves an overlapping pair (interiors meeting: [`separated`] said no): pushes what `part`
/// keeps to `kept` and returns what the visible piece `front` keeps, or `None` when it keeps
/// everything. Counts plane splits.
fn resolve(
    screen: &ScreenScene,
    part: Piece,
    front: &Piece,
    kept: &mut Vec<Piece>,
    plane_splits: &mut usize,
) -> Option<Vec<Piece>> {
    // The viewer is on the negative side of every support plane: the negative side of
    // `front`'s plane is nearer than `front`.
    match part.split_by_plane(&front.support, front.poly) {
        Split::Positive => {
            subtract_overlapping(part, front, kept);
            None
        }
        Split::Negative => {
            let mut front_keeps = Vec::new();
            subtract_overlapping(front.clone(), &part, &mut front_keeps);
            kept.push(part);
            Some(front_keeps)
        }
        Split::On => {
            if tie_key(screen, &part) < tie_key(screen, front) {
                let mut front_keeps = Vec::new();
                subtract_overlapping(front.clone(), &part, &mut front_keeps);
                kept.push(part);
                Some(front_keeps)
            } else {
                subtract_overlapping(part, front, kept);
                None
            }
        }
        Split::Both(part_nearer, part_farther) => {
            *plane_splits += 1;
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

/// `piece` split by `front`'s support plane: (the part in front of it, the part behind it),
/// either possibly absent. The viewer is on the negative side of every support plane; a piece in
/// `front`'s plane is in front when it wins the tie rule ([`tie_key`]).
pub(crate) fn split_by_depth(
    screen: &ScreenScene,
    piece: Piece,
    front: &Piece,
) -> (Option<Piece>, Option<Piece>) {
    match piece.split_by_plane(&front.support, front.poly) {
        Split::Negative => (Some(piece), None),
        Split::Positive => (None, Some(piece)),
        Split::On if tie_key(screen, &piece) < tie_key(screen, front) => (Some(piece), None),
        Split::On => (None, Some(piece)),
        Split::Both(nearer, farther) => (Some(nearer), Some(farther)),
    }
}

/// The parts of `piece` outside every one of `covers` (convex pieces), exactly.
pub(crate) fn subtract_all<'c>(
    piece: Piece,
    covers: impl IntoIterator<Item = &'c Piece>,
) -> Vec<Piece> {
    let mut parts = vec![piece];
    for c in covers {
        let mut next = Vec::with_capacity(parts.len());
        for p in parts {
            subtract(p, c, &mut next);
        }
        parts = next;
        if parts.is_empty() {
            break;
        }
    }
    parts
}

/// Pushes the parts of `piece` outside the convex `front` (exactly; touching is outside).
pub(crate) fn subtract(piece: Piece, front: &Piece, out: &mut Vec<Piece>) {
    clip(piece, front, out);
}

/// Clips `piece` by the convex `front`, exactly: pushes the parts outside `front` to `outside`
/// (convex, disjoint; touching is outside) and returns the part inside it, if it has area. The
/// inside part's lines along `front`'s sides keep `front`'s boundaries.
pub(crate) fn clip(piece: Piece, front: &Piece, outside: &mut Vec<Piece>) -> Option<Piece> {
    if separated(&piece, front) {
        outside.push(piece);
        return None;
    }
    clip_overlapping(piece, front, outside)
}

/// [`subtract`] of a piece whose interior is known to meet `front`'s ([`separated`] said no):
/// the same parts, without the test again.
pub(crate) fn subtract_overlapping(piece: Piece, front: &Piece, out: &mut Vec<Piece>) {
    clip_overlapping(piece, front, out);
}

/// [`clip`] of a piece whose interior is known to meet `front`'s ([`separated`] said no): the
/// same parts, without the test again. (A piece that does not meet `front` must go through
/// [`clip`]: `front`'s lines would cut it for nothing where only its own sides separate them.)
pub(crate) fn clip_overlapping(
    piece: Piece,
    front: &Piece,
    outside: &mut Vec<Piece>,
) -> Option<Piece> {
    debug_assert!(
        !separated(&piece, front),
        "clip_overlapping of pieces apart"
    );
    let mut inside = piece;
    for ((line, approx), origin) in front.lines_with_approx().zip(front.boundaries()) {
        match inside.split_by_line_with(line, &approx, origin) {
            // Entirely outside this line of `front`: nothing of it is inside.
            Split::Negative => {
                outside.push(inside);
                return None;
            }
            Split::Positive => {}
            Split::Both(out, rest) => {
                outside.push(out);
                inside = rest;
            }
            // No area: nothing to keep.
            Split::On => return None,
        }
    }
    // What is left is inside every line of `front`.
    Some(inside)
}
