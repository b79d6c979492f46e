//! Weiler and Atherton's hidden-surface algorithm (`weiler-atherton`): the nearest polygon clips
//! all the others into what lies inside it and what lies outside; what is inside and behind it
//! is hidden, what is inside and in front of it is resolved recursively; then the outside goes
//! on the same way.
//!
//! Following the course notes (section 5.2) and Weiler and Atherton (1977):
//! 1. The polygons are taken in order of their nearest corner (ties: the z-buffer's, front
//!    first). The next one, C, is the clip polygon: its whole remaining region, which after
//!    earlier clips is in general non-convex and has holes.
//! 2. Every other piece is clipped exactly against C: the parts inside C's region (the inside
//!    list) and outside it (which stay in the list). An inside part wholly behind C's plane is
//!    hidden and dropped; one that reaches in front of it is cut by C's plane and its nearer part
//!    kept.
//! 3. When nothing inside is in front of C, C's region is visible. Otherwise C and the parts in
//!    front of it are resolved by the same procedure, with the nearest offending polygon as the
//!    first clip polygon (Weiler and Atherton's recursive subdivision). There C is hidden
//!    wherever the offender covers it (the offender lies wholly in front of C's plane), so a
//!    recursion never again holds the polygon whose clip began it once its offender is done:
//!    every second level has fewer polygons, and cyclic overlaps end.
//!
//! Regions are held as disjoint convex pieces of the exact kernel (a non-convex region with holes
//! is a set of them); clipping is exact line by line ([`clip`]), with no f64 vertex anywhere.
//! Invariant: the pieces written out are disjoint, each is in its own polygon, and at every point
//! of one no polygon is nearer. Translucent faces are layered over the result as the coverage map
//! layers them ([`super::bsp::translucent_layer`]).

use super::coverage::{clip_overlapping, nearest_first, split_by_depth};
use super::live::{Live, bounds};
use super::strips::Counters;
use super::visible_set::{VisibleSet, put_counts};
use super::{Strategy, opaque_then_layered, separated_on};
use crate::exact::polygon::Piece;
use crate::progress::{Report, Ticker};
use crate::project::ScreenScene;
use std::sync::atomic::{AtomicBool, Ordering as AtomicOrdering};

/// Weiler–Atherton. See the module docs.
#[derive(Clone, Copy, Debug, Default)]
pub struct WeilerAtherton;

/// Counters of one run.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct WeilerAthertonStats {
    /// Clip polygons taken (at every level).
    pub clip_polygons: usize,
    /// Pieces clipped against a clip polygon's piece (after the exact overlap test).
    pub clipped: usize,
    /// Inside parts dropped as hidden behind the clip polygon.
    pub hidden: usize,
    /// Recursive subdivisions (something inside was in front of the clip polygon).
    pub recursions: usize,
    /// The deepest level of recursion.
    pub deepest: usize,
    /// Pieces handed to recursions (each level's pieces, counted at every level).
    pub recursed: usize,
}

impl Counters for WeilerAthertonStats {
    fn add(&mut self, o: &Self) {
        self.clip_polygons += o.clip_polygons;
        self.clipped += o.clipped;
        self.hidden += o.hidden;
        self.recursions += o.recursions;
        self.deepest = self.deepest.max(o.deepest);
        self.recursed += o.recursed;
    }
}

impl Strategy for WeilerAtherton {
    fn visible_set(
        &self,
        screen: &ScreenScene,
        translucent: &dyn Fn(u32) -> bool,
        report: Option<Report>,
    ) -> VisibleSet {
        opaque_then_layered(
            screen,
            translucent,
            report,
            true,
            |opaque, report| visible_pieces(screen, opaque, report),
            |st, stats| {
                put_counts(
                    stats,
                    [
                        ("clip_polygons", st.clip_polygons),
                        ("clipped", st.clipped),
                        ("hidden_parts", st.hidden),
                        ("recursions", st.recursions),
                        ("deepest_recursion", st.deepest),
                        ("recursed_pieces", st.recursed),
                    ],
                );
            },
        )
    }
}

/// The visible parts of opaque `pieces`: see the module docs. `report` gets stage "visible set"
/// (clip polygons done at the top level).
pub fn visible_pieces(
    screen: &ScreenScene,
    pieces: Vec<Piece>,
    report: Option<Report>,
) -> (Vec<Piece>, WeilerAthertonStats) {
    visible_pieces_within(screen, pieces, report, ClipBudget::UNLIMITED).expect("no limit")
}

/// How much work clipping may do before it is given up (for the coverage map, by `auto`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ClipBudget {
    /// The deepest level of recursion allowed.
    pub deepest: usize,
    /// Pieces handed to recursions per clip polygon allowed, counted once they outnumber the
    /// pieces given: recursions re-clip each clip polygon's inside list, and large faces whose
    /// nearest corner is near but whose body lies behind others keep handing most of the
    /// list down.
    pub recursed_per_clip_polygon: usize,
}

impl ClipBudget {
    /// No limit: clipping always finishes.
    pub const UNLIMITED: ClipBudget = ClipBudget {
        deepest: usize::MAX,
        recursed_per_clip_polygon: usize::MAX,
    };

    /// True when the work so far, on `given` pieces, is over the budget.
    fn spent(&self, st: &WeilerAthertonStats, given: usize) -> bool {
        st.recursed > given
            && st.recursed
                > self
                    .recursed_per_clip_polygon
                    .saturating_mul(st.clip_polygons)
    }
}

/// [`visible_pieces`], given up (`None`) as soon as the work exceeds `budget`: the sign of clip
/// polygons that keep finding nearer polygons inside them, where the subdivision costs far
/// more than the coverage map. `auto` falls back on the map then.
pub fn visible_pieces_within(
    screen: &ScreenScene,
    pieces: Vec<Piece>,
    report: Option<Report>,
    budget: ClipBudget,
) -> Option<(Vec<Piece>, WeilerAthertonStats)> {
    let limit = Limit { budget, stop: None };
    within_limit(screen, pieces, report, &limit)
}

/// [`visible_pieces_within`] for one strip of a scene: also given up as soon as `stop` is set,
/// and sets it when it gives up itself (the other strips' work would be thrown away).
pub(crate) fn visible_pieces_within_or_stopped(
    screen: &ScreenScene,
    pieces: Vec<Piece>,
    report: Option<Report>,
    budget: ClipBudget,
    stop: &AtomicBool,
) -> Option<(Vec<Piece>, WeilerAthertonStats)> {
    let limit = Limit {
        budget,
        stop: Some(stop),
    };
    let solved = within_limit(screen, pieces, report, &limit);
    if solved.is_none() {
        stop.store(true, AtomicOrdering::Relaxed);
    }
    solved
}

/// When clipping gives up: past its budget, or once `stop` is set.
struct Limit<'a> {
    budget: ClipBudget,
    stop: Option<&'a AtomicBool>,
}

impl Limit<'_> {
    /// True at `level` of the subdivision of `given` pieces after the work counted in `st`.
    fn reached(&self, level: usize, st: &WeilerAthertonStats, given: usize) -> bool {
        level > self.budget.deepest
            || self.budget.spent(st, given)
            || self.stop.is_some_and(|s| s.load(AtomicOrdering::Relaxed))
    }
}

fn within_limit(
    screen: &ScreenScene,
    pieces: Vec<Piece>,
    report: Option<Report>,
    limit: &Limit,
) -> Option<(Vec<Piece>, WeilerAthertonStats)> {
    let mut st = WeilerAthertonStats::default();
    let mut out = Vec::new();
    let mut ticker = Ticker::new(report, "visible set", screen.polys.len() as u64);
    let finished = resolve(screen, pieces, &mut out, &mut st, limit, &mut |done| {
        ticker.tick(done)
    });
    ticker.finish();
    finished.then_some((out, st))
}

/// The end of a chain of pieces.
const NONE: u32 = u32::MAX;

/// The pieces of each clip polygon (by rank), in the order they were added: one chain per rank
/// through the pieces' indices in the [`Live`] list (indices are dense and never reused).
struct Chains {
    head: Vec<u32>,
    tail: Vec<u32>,
    /// Per piece index: the next piece of its rank.
    next: Vec<u32>,
    /// Per piece index: its rank.
    rank: Vec<u32>,
}

impl Chains {
    fn new(ranks: usize, pieces: usize) -> Chains {
        Chains {
            head: vec![NONE; ranks],
            tail: vec![NONE; ranks],
            next: Vec::with_capacity(pieces),
            rank: Vec::with_capacity(pieces),
        }
    }

    /// Appends piece `v`, the next index of the list, to rank `r`'s chain.
    fn push(&mut self, r: u32, v: u32) {
        debug_assert_eq!(v as usize, self.next.len(), "indices are dense");
        self.next.push(NONE);
        self.rank.push(r);
        match self.tail[r as usize] {
            NONE => self.head[r as usize] = v,
            t => self.next[t as usize] = v,
        }
        self.tail[r as usize] = v;
    }

    /// Rank `r`'s pieces in order, leaving its chain empty.
    fn drain(&mut self, r: u32) -> impl Iterator<Item = u32> + '_ {
        let mut v = std::mem::replace(&mut self.head[r as usize], NONE);
        self.tail[r as usize] = NONE;
        std::iter::from_fn(move || {
            (v != NONE).then(|| {
                let here = v;
                v = self.next[here as usize];
                here
            })
        })
    }
}

/// One level of the subdivision: its pieces in a [`Live`] list, chained by clip polygon rank,
/// and the next rank to take.
struct Level {
    list: Live,
    chains: Chains,
    next: u32,
}

impl Level {
    /// The level resolving `pieces`, taking `first`'s polygon as the first clip polygon when
    /// given, then the others in [`nearest_first`].
    fn new(screen: &ScreenScene, pieces: Vec<Piece>, first: Option<u32>) -> Level {
        // Ranks by `first`, then `nearest_first`. Each rank's live pieces form a chain through
        // `next` from `head[rank]`, so the region of a clip polygon is found without a map of
        // polygons (outside parts join their piece's chain).
        let mut order: Vec<(u32, usize)> = pieces.iter().map(|p| p.poly).zip(0..).collect();
        order.sort_by_cached_key(|&(k, i)| (Some(k) != first, nearest_first(screen, k), i));
        let mut rank_of_piece = vec![0u32; pieces.len()];
        let mut ranks = 0u32;
        for (n, &(poly, i)) in order.iter().enumerate() {
            if n > 0 && order[n - 1].0 != poly {
                ranks += 1;
            }
            rank_of_piece[i] = ranks;
        }
        let ranks = if pieces.is_empty() { 0 } else { ranks + 1 };
        let boxes: Vec<[f64; 4]> = pieces.iter().map(bounds).collect();
        let mut list = Live::over(&boxes, boxes.len());
        let mut chains = Chains::new(ranks as usize, pieces.len());
        for ((p, b), r) in pieces.into_iter().zip(boxes).zip(rank_of_piece) {
            chains.push(r, list.add(p, b));
        }
        Level {
            list,
            chains,
            next: 0,
        }
    }
}

/// Writes the visible parts of `pieces` to `out`. `done(k)`: k clip polygons of the top level
/// are done. False, with `out` incomplete, when `limit` is reached (checked at every clip
/// polygon). The recursion of Weiler and Atherton is a stack of [`Level`]s on the heap, not on
/// the call stack: it runs a thousand levels deep on some scenes (samurai_monastery), on
/// worker threads with small stacks.
fn resolve(
    screen: &ScreenScene,
    pieces: Vec<Piece>,
    out: &mut Vec<Piece>,
    st: &mut WeilerAthertonStats,
    limit: &Limit,
    done: &mut dyn FnMut(u64),
) -> bool {
    let given = pieces.len();
    // A strip another one stopped makes nothing (ordering the list is not free).
    if limit.reached(0, st, given) {
        return false;
    }
    let mut levels = vec![Level::new(screen, pieces, None)];
    let mut near = Vec::new();
    let mut outside = Vec::new();
    while let Some(level) = levels.len().checked_sub(1) {
        if limit.reached(level, st, given) {
            return false;
        }
        st.deepest = st.deepest.max(level);
        let Level { list, chains, next } = &mut levels[level];
        if *next as usize == chains.head.len() {
            levels.pop();
            continue;
        }
        let c = *next;
        *next += 1;
        if level == 0 {
            done(c as u64);
        }
        let region: Vec<Piece> = chains.drain(c).filter_map(|v| list.take(v)).collect();
        if region.is_empty() {
            continue;
        }
        st.clip_polygons += 1;
        // The inside list, less what is hidden: parts in front of the clip polygon.
        let mut in_front: Vec<Piece> = Vec::new();
        for c_piece in &region {
            list.near_into(&bounds(c_piece), &mut near);
            for &v in &near {
                if separated_on(screen, list.get(v).expect("near is live"), c_piece) {
                    continue;
                }
                let p = list.take(v).expect("live");
                st.clipped += 1;
                let r = chains.rank[v as usize];
                debug_assert!(r > c, "a clip polygon's own pieces were taken");
                let inside = clip_overlapping(p, c_piece, &mut outside);
                for o in outside.drain(..) {
                    let b = bounds(&o);
                    chains.push(r, list.add(o, b));
                }
                let Some(q) = inside else { continue };
                let (nearer, farther) = split_by_depth(screen, q, c_piece);
                st.hidden += farther.is_some() as usize;
                in_front.extend(nearer);
            }
        }
        if in_front.is_empty() {
            out.extend(region);
            continue;
        }
        st.recursions += 1;
        let offender = in_front
            .iter()
            .map(|p| p.poly)
            .min_by_key(|&k| nearest_first(screen, k))
            .expect("not empty");
        let mut inside = region;
        inside.extend(in_front);
        st.recursed += inside.len();
        levels.push(Level::new(screen, inside, Some(offender)));
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::GridPoint;
    use crate::visibility::{initial_pieces, screen_of_polygons, tilted_squares};

    /// Two triangles passing through each other: one level of recursion.
    fn crossing_triangles() -> ScreenScene {
        screen_of_polygons([
            vec![
                GridPoint::new(0, 0, 10),
                GridPoint::new(100, 0, 10),
                GridPoint::new(0, 100, 10),
            ],
            vec![
                GridPoint::new(0, 0, 0),
                GridPoint::new(100, 0, 20),
                GridPoint::new(0, 100, 0),
            ],
        ])
    }

    /// A budget of `deepest` levels and no other limit.
    fn levels(deepest: usize) -> ClipBudget {
        ClipBudget {
            deepest,
            ..ClipBudget::UNLIMITED
        }
    }

    /// Tilted squares ([`tilted_squares`]): one level deeper at every clip polygon. Run on a
    /// thread with a 256 KiB stack, the depth of the subdivision must not become the depth of
    /// the call stack: the recursive version needed ~3 KiB a level (samurai_monastery, ~700
    /// levels, overflowed a worker thread's 2 MiB), so 200 levels would need ~600 KiB.
    #[test]
    fn a_subdivision_hundreds_of_levels_deep_runs_on_a_small_stack() {
        const N: i64 = 200;
        const W: i64 = 1 << 20;
        let planks = screen_of_polygons(tilted_squares(N, W));
        let solved = std::thread::Builder::new()
            .stack_size(256 << 10)
            .spawn(move || {
                let pieces = initial_pieces(&planks);
                visible_pieces(&planks, pieces, None)
            })
            .expect("a thread")
            .join()
            .expect("no stack overflow");
        let (visible, st) = solved;
        assert!(st.deepest >= N as usize - 2, "{} levels deep", st.deepest);
        // The first plank is nearest left of the middle, the last one right of it.
        let mut shown: Vec<u32> = visible.iter().map(|p| p.poly).collect();
        shown.sort_unstable();
        shown.dedup();
        assert_eq!(shown, [0, N as u32 - 1]);
    }

    /// Clipping gives up when recursions re-handle more pieces per clip polygon than its
    /// budget allows, but only once they have handed down more pieces than it was given: a
    /// single recursion (two faces passing through each other) is never over budget.
    #[test]
    fn clipping_gives_up_when_recursions_rehandle_too_many_pieces_per_clip_polygon() {
        let rehandling = |n| ClipBudget {
            recursed_per_clip_polygon: n,
            ..ClipBudget::UNLIMITED
        };
        // Tilted squares: each level hands all but one plank down again.
        let planks = screen_of_polygons(tilted_squares(40, 1 << 20));
        let pieces = initial_pieces(&planks);
        let (_, st) = visible_pieces(&planks, pieces.clone(), None);
        let per_clip = st.recursed / st.clip_polygons;
        assert!(st.recursed > pieces.len() && per_clip >= 4, "{st:?}");
        assert!(visible_pieces_within(&planks, pieces.clone(), None, rehandling(2)).is_none());
        let solved = visible_pieces_within(&planks, pieces, None, rehandling(st.recursed));
        assert_eq!(solved.map(|s| s.1), Some(st));
        // Two faces passing through each other: both handed down once, no more than given.
        let crossing = crossing_triangles();
        let pieces = initial_pieces(&crossing);
        let (_, st) = visible_pieces_within(&crossing, pieces.clone(), None, rehandling(0))
            .expect("within budget");
        assert_eq!((st.recursions, st.recursed), (1, pieces.len()));
    }

    /// A strip of a scene stops as soon as another strip gave up (its work would be thrown
    /// away), and one that gives up tells the others.
    #[test]
    fn a_strip_stops_once_another_gave_up_and_tells_the_others_when_it_gives_up() {
        let crossing = crossing_triangles();
        let pieces = initial_pieces(&crossing);
        let stop = AtomicBool::new(false);
        let solved =
            visible_pieces_within_or_stopped(&crossing, pieces.clone(), None, levels(1), &stop);
        assert!(solved.is_some() && !stop.load(AtomicOrdering::Relaxed));
        let stopped = AtomicBool::new(true);
        let solved =
            visible_pieces_within_or_stopped(&crossing, pieces.clone(), None, levels(1), &stopped);
        assert!(solved.is_none(), "another strip gave up");
        let solved = visible_pieces_within_or_stopped(&crossing, pieces, None, levels(0), &stop);
        assert!(
            solved.is_none() && stop.load(AtomicOrdering::Relaxed),
            "gave up and told"
        );
    }
}
