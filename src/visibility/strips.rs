//! Screen strips: one visible-set problem cut into independent ones, solved on all cores.
//!
//! The screen is cut by vertical grid lines x = c (the cuts, chosen from the pieces alone: never
//! from the number of threads), every piece exactly into its parts between them
//! ([`Piece::split_by_line`], the cut sides marked [`Boundary::ScreenSplit`]), and each strip's
//! pieces go to a strategy on their own, in parallel (rayon).
//!
//! Invariants:
//! - What is visible at a point depends only on the pieces over that point, and every exact
//!   strategy's visible set is defined point by point (the tie rule included), so the union of
//!   the strips' visible sets is the scene's. The strips' results are concatenated in strip
//!   order and their counters summed in strip order: the output is the same whatever the
//!   number of threads, and whichever thread ran which strip.
//! - The cuts add sides between pieces of one face and collinear vertices on their outlines;
//!   the drawing merges pieces into maximal straight runs between true corners, so a drawing
//!   is the same, byte for byte, as the drawing of the same scene solved in one strip.
//! - Exact fallbacks are counted per thread ([`fallback_count`]): each strip's count is added
//!   to the calling thread's, so a strategy's `exact_fallbacks` covers all of its strips.

use super::bsp::screen_line;
use crate::exact::polygon::{Boundary, Piece, Split};
use crate::exact::predicates::{add_fallbacks, fallback_count, reset_fallbacks};
use crate::memory::GiveBackEvery;
use crate::progress::{Report, Ticker};
use rayon::prelude::*;
use std::cell::Cell;
use std::sync::Mutex;

/// About how many pieces make a strip worth its cut: fewer, and the scene is solved whole.
pub const PIECES_PER_STRIP: usize = 4096;
/// At most this many strips: each cut adds the parts of the pieces it crosses.
pub const MOST_STRIPS: usize = 32;

thread_local! {
    /// Set by [`with_strip_size`]; `None`: the default.
    static STRIP_SIZE: Cell<Option<usize>> = const { Cell::new(None) };
}

/// Runs `run` with strips of about `pieces_per_strip` pieces (still at most [`MOST_STRIPS`],
/// however large the pieces) for the strategies it calls on this thread; `usize::MAX` solves
/// every scene whole. For tests and measurements: many strips on a small scene, or none on a
/// large one. The output's drawing does not change; its counters do.
pub fn with_strip_size<T>(pieces_per_strip: usize, run: impl FnOnce() -> T) -> T {
    let before = STRIP_SIZE.with(|s| s.replace(Some(pieces_per_strip.max(1))));
    // Restored even if `run` panics, so a caught panic leaves no setting behind.
    struct Restore(Option<usize>);
    impl Drop for Restore {
        fn drop(&mut self) {
            STRIP_SIZE.with(|s| s.set(self.0));
        }
    }
    let _restore = Restore(before);
    run()
}

/// The cuts of a strip set: increasing grid x, one fewer than the strips.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Strips {
    cuts: Vec<i64>,
}

impl Strips {
    /// The strips for `pieces`: one per [`PIECES_PER_STRIP`] pieces, at most [`MOST_STRIPS`],
    /// and fewer (down to one) while the pieces' bounds would meet more than 1.25 strips on
    /// average; or as [`with_strip_size`] sets.
    pub fn for_pieces(pieces: &[Piece]) -> Strips {
        Strips::for_boxes(boxes_of(pieces))
    }

    /// The strips for the pieces not flagged in `whole` ([`Self::for_pieces`] of them), those
    /// pieces cut into them ([`Self::cut`]), and the flagged ones whole, in the order of
    /// `pieces`: (strips, their pieces, the whole ones). The bounds are found once for both.
    pub(crate) fn cut_all_but(
        pieces: Vec<Piece>,
        whole: &[bool],
    ) -> (Strips, Vec<Vec<Piece>>, Vec<Piece>) {
        let boxes = boxes_of(&pieces);
        let strips = Strips::for_boxes(
            (boxes.iter().zip(whole))
                .filter_map(|(b, &w)| (!w).then_some(*b))
                .collect(),
        );
        let (cut, kept) = strips.cut_with(pieces, whole, &boxes);
        (strips, cut, kept)
    }

    /// [`Self::for_pieces`] of the pieces with the bounds `boxes`.
    fn for_boxes(boxes: Vec<[f64; 4]>) -> Strips {
        if let Some(size) = STRIP_SIZE.with(Cell::get) {
            let count = (boxes.len() / size).clamp(1, MOST_STRIPS);
            return Strips::at_quantiles(&centres_of(&boxes), count);
        }
        let mut count = (boxes.len() / PIECES_PER_STRIP).clamp(1, MOST_STRIPS);
        if count == 1 {
            return Strips::none();
        }
        // Large pieces (a soup of crossing faces) would be cut into many parts, each strip
        // holding most of the scene: halve the strips until the cuts add at most a quarter.
        let centres = centres_of(&boxes);
        loop {
            let strips = Strips::at_quantiles(&centres, count);
            let parts: usize = (boxes.par_iter())
                .map(|b| strips.last(b) - strips.first(b) + 1)
                .sum();
            if 4 * parts <= 5 * boxes.len() || strips.count() == 1 {
                return strips;
            }
            count /= 2;
        }
    }

    /// At most `count` strips holding about as many of `pieces` each: the cuts are quantiles of
    /// the pieces' centres in x (equal quantiles give one cut).
    #[cfg(test)]
    pub fn with_count(pieces: &[Piece], count: usize) -> Strips {
        if count <= 1 || pieces.is_empty() {
            return Strips { cuts: Vec::new() };
        }
        Strips::at_quantiles(&centres_of(&boxes_of(pieces)), count)
    }

    /// [`Strips::with_count`] of pieces whose centres in x are `centres`, sorted.
    fn at_quantiles(centres: &[i64], count: usize) -> Strips {
        if count <= 1 || centres.is_empty() {
            return Strips { cuts: Vec::new() };
        }
        let mut cuts: Vec<i64> = (1..count)
            .map(|k| centres[k * centres.len() / count])
            .collect();
        cuts.dedup();
        Strips { cuts }
    }

    /// One strip: the scene solved whole.
    pub fn none() -> Strips {
        Strips { cuts: Vec::new() }
    }

    /// How many strips.
    pub fn count(&self) -> usize {
        self.cuts.len() + 1
    }

    /// The pieces of each strip, left to right: every piece cut exactly by the cuts it crosses,
    /// its parts in the order of `pieces`.
    pub fn cut(&self, pieces: Vec<Piece>) -> Vec<Vec<Piece>> {
        if self.cuts.is_empty() {
            return vec![pieces];
        }
        let boxes = boxes_of(&pieces);
        self.cut_with(pieces, &vec![false; boxes.len()], &boxes).0
    }

    /// [`Self::cut`] of the pieces not flagged in `whole`, and the flagged ones uncut, in the
    /// order of `pieces` (each piece is moved once either way); `boxes` are the pieces' bounds.
    fn cut_with(
        &self,
        mut pieces: Vec<Piece>,
        whole: &[bool],
        boxes: &[[f64; 4]],
    ) -> (Vec<Vec<Piece>>, Vec<Piece>) {
        let kept = whole.iter().filter(|&&w| w).count();
        if kept == 0 && self.cuts.is_empty() {
            return (vec![pieces], Vec::new());
        }
        // Sized first (an upper bound: each piece in every strip its bounds meet), so that each
        // piece is moved once: pieces are a few hundred bytes each.
        let mut sizes = vec![0usize; self.count()];
        for b in boxes
            .iter()
            .zip(whole)
            .filter(|(_, w)| !**w)
            .map(|(b, _)| b)
        {
            for size in &mut sizes[self.first(b)..=self.last(b)] {
                *size += 1;
            }
        }
        let mut strips: Vec<Vec<Piece>> = sizes.into_iter().map(Vec::with_capacity).collect();
        // A piece goes to each strip its bounds `b` meet, cut exactly at the cuts it crosses.
        let mut route = |piece: Piece, b: &[f64; 4]| {
            let (mut k, last) = (self.first(b), self.last(b));
            let mut rest = piece;
            loop {
                if k == last {
                    strips[k].push(rest);
                    break;
                }
                match rest.split_by_line(&screen_line(0, self.cuts[k]), Boundary::ScreenSplit) {
                    Split::Negative | Split::On => {
                        strips[k].push(rest);
                        break;
                    }
                    Split::Positive => {}
                    Split::Both(left, right) => {
                        strips[k].push(left);
                        rest = right;
                    }
                }
                k += 1;
            }
        };
        if kept == 0 {
            // Last piece first, the list giving back its room as it empties: the list and the
            // strips are never both whole in memory. A piece goes to a strip at most once, so
            // each strip reversed at the end is in the order of `pieces`.
            while let Some(piece) = pop_giving_back(&mut pieces) {
                route(piece, &boxes[pieces.len()]);
            }
            strips.par_iter_mut().for_each(|strip| strip.reverse());
            return (strips, Vec::new());
        }
        // The flagged pieces stay in the list, moved down over the others as those leave for
        // their strips in order: moving the flagged ones too, into a fresh list whose pages
        // fault in, took twice as long (dragon: 209k of 424k flagged). The list keeps its
        // room until the end; no peak is there (the 1M sphere's and dragon's peaks of
        // `render` were the same within 1 %).
        let mut index = 0;
        let unflagged = pieces.extract_if(.., |_| {
            index += 1;
            !whole[index - 1]
        });
        for (piece, k) in unflagged.zip((0..whole.len()).filter(|&k| !whole[k])) {
            route(piece, &boxes[k]);
        }
        pieces.shrink_to_fit();
        (strips, pieces)
    }

    /// The first strip that bounds `b` meet: cuts left of them cannot meet the piece.
    fn first(&self, b: &[f64; 4]) -> usize {
        self.cuts.partition_point(|&c| (c as f64) < b[0])
    }

    /// The last strip that bounds `b` meet: cuts right of them cannot meet the piece.
    fn last(&self, b: &[f64; 4]) -> usize {
        self.cuts.partition_point(|&c| (c as f64) <= b[2])
    }
}

/// The pieces' bounds, on all cores.
fn boxes_of(pieces: &[Piece]) -> Vec<[f64; 4]> {
    (pieces.par_iter().with_min_len(1024))
        .map(Piece::bounds)
        .collect()
}

/// The boxes' centres in x (rounded down to grid units), sorted.
fn centres_of(boxes: &[[f64; 4]]) -> Vec<i64> {
    let mut centres: Vec<i64> = (boxes.iter())
        .map(|b| (0.5 * (b[0] + b[2])).floor() as i64)
        .collect();
    centres.par_sort_unstable();
    centres
}

/// Pops the last element of `list`, handing its room back to the allocator an eighth at a time
/// as it empties: a list of pieces moved out one by one into another is then never whole in
/// both at once (glibc shrinks a large allocation in place and unmaps the pages it drops).
pub(crate) fn pop_giving_back<T>(list: &mut Vec<T>) -> Option<T> {
    let last = list.pop();
    if list.len() < list.capacity() - list.capacity() / 8 {
        list.shrink_to_fit();
    }
    last
}

/// Two lists as one: the shorter appended to the longer (a long list grows in place,
/// its pages remapped, not copied). Deterministic: the same lists give the same order.
pub(crate) fn appended<T>(a: Vec<T>, b: Vec<T>) -> Vec<T> {
    let (mut long, mut short) = if a.len() >= b.len() { (a, b) } else { (b, a) };
    long.append(&mut short);
    long
}

/// Counters of a strategy that add up over strips.
pub(crate) trait Counters: Default + Send {
    /// Adds another strip's counters (a maximum, such as a depth, takes the larger).
    fn add(&mut self, other: &Self);
}

/// What a given-up [`solve_strips`] hands back: each strip's pieces as they were given, `None`
/// for a strip solved before the attempt was given up (its pieces are gone).
pub(crate) type GivenUp = Vec<Option<Vec<Piece>>>;

/// Solves each strip with `solve(pieces, report)` on the rayon pool and returns the visible
/// pieces in strip order with the counters summed. A `solve` may give up, handing back the
/// strip's pieces as it was given them (`Err`); then the whole is given up ([`GivenUp`]), its
/// exact fallbacks not counted (`solve` may stop other strips early, so how far they got
/// depends on timing).
/// Progress: a single strip is solved on this thread with `report` as it is; several report
/// stage "visible set" as pieces of finished strips.
pub(crate) fn solve_strips<C: Counters>(
    strips: Vec<Vec<Piece>>,
    report: Option<Report>,
    solve: impl Fn(Vec<Piece>, Option<Report>) -> Result<(Vec<Piece>, C), Vec<Piece>> + Sync,
) -> Result<(Vec<Piece>, C), GivenUp> {
    solve_strips_beside(strips, Vec::new(), report, solve)
}

/// [`solve_strips`], its visible pieces then [`appended`] with `beside` (pieces settled
/// without the strips), each piece moved once. On giving up, `beside` is dropped.
pub(crate) fn solve_strips_beside<C: Counters>(
    strips: Vec<Vec<Piece>>,
    beside: Vec<Piece>,
    report: Option<Report>,
    solve: impl Fn(Vec<Piece>, Option<Report>) -> Result<(Vec<Piece>, C), Vec<Piece>> + Sync,
) -> Result<(Vec<Piece>, C), GivenUp> {
    if strips.len() == 1 {
        let only = strips.into_iter().next().expect("one strip");
        let before = fallback_count();
        return solve(only, report)
            .map(|(visible, c)| (appended(visible, beside), c))
            .map_err(|given| {
                reset_fallbacks(before);
                vec![Some(given)]
            });
    }
    let total: usize = strips.iter().map(Vec::len).sum();
    let ticker = Mutex::new((Ticker::new(report, "visible set", total as u64), 0u64));
    let own_before = fallback_count();
    // Each strip's input, freed by `solve`, goes to the arena of the thread that cut the
    // strips, out of the solving threads' reach: handed back as strips finish.
    let consumed = GiveBackEvery::default();
    // Per strip: what `solve` returned, and the exact fallbacks it counted.
    type Solved<C> = (Result<(Vec<Piece>, C), Vec<Piece>>, u64);
    let solved: Vec<Solved<C>> = strips
        .into_par_iter()
        .map(|pieces| {
            let n = pieces.len() as u64;
            let before = fallback_count();
            let out = solve(pieces, None);
            let fallbacks = fallback_count() - before;
            consumed.freed(n as usize);
            let mut t = ticker.lock().unwrap_or_else(|e| e.into_inner());
            t.1 += n;
            let done = t.1;
            t.0.tick(done);
            (out, fallbacks)
        })
        .collect();
    // Strips solved on this thread (a pool thread calling) are in both counts. (`solve` starts
    // no rayon work of its own, so a thread running a strip runs nothing else meanwhile.)
    let own = fallback_count() - own_before;
    let (ticker, _) = ticker.into_inner().unwrap_or_else(|e| e.into_inner());
    ticker.finish();
    if solved.iter().any(|s| s.0.is_err()) {
        reset_fallbacks(own_before);
        return Err(solved.into_iter().map(|s| s.0.err()).collect());
    }
    let fallbacks: u64 = solved.iter().map(|s| s.1).sum();
    add_fallbacks(fallbacks.saturating_sub(own));
    // The whole list is made at its size, then filled strip by strip, each strip freed once
    // moved and its room handed back to the system every few strips: the strips' room, left
    // resident in the allocator's arenas, and the whole list were the process's peak on a
    // million triangles (481 -> 682 MB while joining, the visible pieces being 189 MB). As
    // `appended` would order them, the strips' pieces go after `beside` when it is the longer,
    // grown in place (its pages remapped), else into a fresh list with `beside` after them.
    let total: usize = solved
        .iter()
        .filter_map(|s| s.0.as_ref().ok())
        .map(|s| s.0.len())
        .sum();
    let (mut pieces, mut after) = if beside.len() > total {
        let mut pieces = beside;
        pieces.reserve_exact(total);
        (pieces, Vec::new())
    } else {
        (Vec::with_capacity(total + beside.len()), beside)
    };
    let mut counters = C::default();
    let joined = GiveBackEvery::default();
    // Every strip is `Ok` (checked above).
    for (p, c) in solved.into_iter().filter_map(|s| s.0.ok()) {
        let n = p.len();
        pieces.extend(p);
        counters.add(&c);
        joined.freed(n);
    }
    pieces.append(&mut after);
    Ok((pieces, counters))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::GridPoint;
    use crate::visibility::coverage::CoverageStats;
    use crate::visibility::{initial_pieces, screen_of_polygons};
    use std::cmp::Ordering;

    /// Twice the area of a piece, from its f64 vertices (a measure for the test, not a decision).
    fn area2(p: &Piece) -> f64 {
        let v = p.vertices_f64();
        (0..v.len())
            .map(|k| {
                let (a, b) = (v[k], v[(k + 1) % v.len()]);
                a[0] * b[1] - a[1] * b[0]
            })
            .sum()
    }

    /// Triangles scattered over a 1000-unit square, some wide enough to cross several cuts.
    fn triangles() -> Vec<Vec<GridPoint>> {
        let mut seed = 12345u64;
        let mut next = move |m: i64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 33) % m as u64) as i64
        };
        (0..60)
            .map(|k| {
                let (x, y, w) = (next(1000), next(1000), if k % 5 == 0 { 600 } else { 40 });
                let gp = |x, y| GridPoint { x, y, z: k };
                vec![gp(x, y), gp(x + w, y + next(30)), gp(x + next(w), y + 50)]
            })
            .collect()
    }

    /// Exact fallbacks counted in strips reach the caller, except when a strip gave up: how far
    /// the others got then depends on timing, and counting it would make the counts vary.
    #[test]
    fn fallbacks_of_solved_strips_are_counted_and_of_a_given_up_attempt_are_not() {
        let strips = || vec![Vec::new(), Vec::new(), Vec::new()];
        let before = fallback_count();
        let solved = solve_strips(strips(), None, |_, _| {
            add_fallbacks(5);
            Ok((Vec::new(), CoverageStats::default()))
        });
        assert!(solved.is_ok());
        assert_eq!(fallback_count() - before, 15);
        let before = fallback_count();
        let calls = std::sync::atomic::AtomicUsize::new(0);
        let solved = solve_strips(strips(), None, |_, _| {
            add_fallbacks(5);
            let k = calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            match k {
                1 => Err(Vec::new()),
                _ => Ok((Vec::new(), CoverageStats::default())),
            }
        });
        assert!(solved.is_err());
        assert_eq!(fallback_count(), before);
    }

    #[test]
    fn cutting_into_strips_keeps_every_piece_whole_and_each_part_in_its_strip() {
        let screen = screen_of_polygons(triangles());
        let pieces = initial_pieces(&screen);
        let strips = Strips::with_count(&pieces, 6);
        assert_eq!(strips.count(), 6);
        let parts = strips.cut(pieces.clone());
        assert!(parts.iter().map(Vec::len).sum::<usize>() > pieces.len() + 10);
        for (k, strip) in parts.iter().enumerate() {
            assert!(!strip.is_empty(), "strip {k} is empty");
            for part in strip {
                // Exactly between the strip's cuts: no vertex left of its left cut (the line is
                // positive to its right) or right of its right cut.
                for i in 0..part.len() {
                    if k > 0 {
                        let left = screen_line(0, strips.cuts[k - 1]);
                        assert_ne!(part.vertex_line_sign(i, &left), Ordering::Less);
                    }
                    if k < strips.cuts.len() {
                        let right = screen_line(0, strips.cuts[k]);
                        assert_ne!(part.vertex_line_sign(i, &right), Ordering::Greater);
                    }
                }
            }
        }
        // Every piece's area is the sum of its parts' (each face is one piece here).
        for p in &pieces {
            let sum: f64 = parts
                .iter()
                .flatten()
                .filter(|q| q.poly == p.poly)
                .map(area2)
                .sum();
            assert!(
                (sum - area2(p)).abs() <= 1e-9 * area2(p),
                "{sum} vs {}",
                area2(p)
            );
        }
    }

    /// The flagged pieces stay whole and in order, and the others are cut into the same strip
    /// parts, in the same order, as when they are cut alone.
    #[test]
    fn flagged_pieces_stay_whole_in_order_and_the_rest_are_cut_as_alone() {
        let screen = screen_of_polygons(triangles());
        let pieces = initial_pieces(&screen);
        let strips = Strips::with_count(&pieces, 6);
        let boxes = boxes_of(&pieces);
        // Every third piece flagged, the first and the last among them.
        let whole: Vec<bool> = (0..pieces.len())
            .map(|k| k % 3 == 0 || k + 1 == pieces.len())
            .collect();
        let (parts, kept) = strips.cut_with(pieces.clone(), &whole, &boxes);
        let (mut flagged, mut rest) = (Vec::new(), Vec::new());
        for (p, &w) in pieces.iter().zip(&whole) {
            if w { &mut flagged } else { &mut rest }.push(p.clone());
        }
        assert!(flagged.len() > 2 && rest.len() > 2);
        assert_eq!(kept, flagged);
        assert_eq!(parts, strips.cut(rest));
        // None flagged: the same parts as `cut`, nothing kept.
        let none = vec![false; pieces.len()];
        let (parts, kept) = strips.cut_with(pieces.clone(), &none, &boxes);
        assert!(kept.is_empty());
        assert_eq!(parts, strips.cut(pieces));
    }

    #[test]
    fn many_small_pieces_get_strips_and_large_crossing_ones_do_not() {
        let tri = |x: i64, y: i64, w: i64, k: i64| {
            let gp = |x, y| GridPoint { x, y, z: k };
            vec![gp(x, y), gp(x + w, y + 1), gp(x + w / 2, y + w)]
        };
        let n = 2 * PIECES_PER_STRIP as i64 + 100;
        // Small triangles on a 100 x 100 grid of spots: as many strips as pieces call for.
        let small = screen_of_polygons((0..n).map(|k| tri(10 * (k % 97), 10 * (k / 97), 8, k)));
        assert_eq!(Strips::for_pieces(&initial_pieces(&small)).count(), 2);
        // Triangles as wide as the scene (a soup): each would be cut in two, so one strip.
        let wide = screen_of_polygons((0..n).map(|k| tri(k % 50, k / 50, 1000, k)));
        assert_eq!(Strips::for_pieces(&initial_pieces(&wide)).count(), 1);
    }

    #[test]
    fn strips_come_from_the_pieces_and_the_size_setting_only() {
        let screen = screen_of_polygons(triangles());
        let pieces = initial_pieces(&screen);
        assert_eq!(Strips::for_pieces(&pieces).count(), 1);
        let ten = with_strip_size(6, || Strips::for_pieces(&pieces));
        assert_eq!(ten, Strips::with_count(&pieces, 10));
        // The setting is restored afterwards.
        assert_eq!(Strips::for_pieces(&pieces).count(), 1);
        let most = with_strip_size(1, || Strips::for_pieces(&pieces));
        assert_eq!(most.count(), MOST_STRIPS);
    }
}
