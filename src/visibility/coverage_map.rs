//! The coverage-map strategy (`coverage`): the exact visible set with no tree.
//!
//! Every screen polygon becomes convex pieces; they go, nearest corner first, into the
//! depth-aware coverage map ([`Coverage::insert`]), which splits two overlapping pieces by the
//! line where their planes meet and keeps the nearer side of each. The order only saves work
//! (most pieces then meet only nearer ones); it decides nothing. On interpenetrating soups a
//! BSP cuts each triangle by the plane of every other it straddles (100 random triangles gave
//! 7,100 fragments, 1,000 gave 3.1 million), while the coverage map only makes the splits the
//! visible result has (818 and 7,287 pieces); it is about twice as fast on closed meshes too.
//!
//! Translucent faces are left out of the map and layered over it in the exact back-to-front
//! order of a BSP of their own pieces ([`translucent_layer`]).

use super::bsp::translucent_layer;
use super::clear::clear_pieces;
use super::coverage::{Coverage, CoverageStats, nearest_first};
use super::occlusion::unhidden_pieces;
use super::strips::{Strips, solve_strips_beside};
use super::visible_set::{Stats, VisibleSet};
use super::{Strategy, pieces_of, translucent_polygons};
use crate::exact::polygon::Piece;
use crate::exact::predicates::fallback_count;
use crate::progress::{Report, Ticker};
use crate::project::ScreenScene;

/// The coverage-map strategy. See the module docs.
#[derive(Clone, Copy, Debug, Default)]
pub struct CoverageMap;

impl Strategy for CoverageMap {
    fn visible_set(
        &self,
        screen: &ScreenScene,
        translucent: &dyn Fn(u32) -> bool,
        report: Option<Report>,
    ) -> VisibleSet {
        let fallbacks = fallback_count();
        let mut stats = Stats::new();
        let mut put = |k: &str, v: serde_json::Value| {
            stats.insert(k.to_string(), v);
        };
        let layered = translucent_polygons(screen, translucent);
        put("translucent_painter_order", layered.into());
        let (pieces, layered) = if layered {
            let (see_through, opaque): (Vec<u32>, Vec<u32>) =
                (0..screen.polys.len() as u32).partition(|&k| translucent(k));
            let see_through = pieces_of(screen, &see_through);
            let (visible, cs, strips) = visible_pieces_of(screen, &opaque, report);
            let mut coverage = Coverage::of_visible(screen, visible);
            let (layered, bsp) = translucent_layer(screen, &mut coverage, see_through, report);
            put("pieces", (cs.inserted + bsp.pieces).into());
            put("translucent_parts", layered.len().into());
            put("strips", strips.into());
            bsp.put_tree(&mut stats);
            (coverage.into_pieces(), layered)
        } else {
            let all: Vec<u32> = (0..screen.polys.len() as u32).collect();
            let (visible, cs, strips) = visible_pieces_of(screen, &all, report);
            put("pieces", cs.inserted.into());
            put("replaced", cs.replaced.into());
            put("overlap_tests", cs.overlap_tests.into());
            put("occluded", cs.occluded.into());
            put("clear", cs.clear.into());
            put("covered", cs.covers.hits.into());
            put("strips", strips.into());
            (visible, Vec::new())
        };
        VisibleSet::exact(screen, pieces, layered, stats, fallbacks)
    }
}

/// The exact visible set of every polygon of `screen`, all taken as opaque, with the coverage
/// map's counters.
pub fn visible_set(screen: &ScreenScene) -> (VisibleSet, CoverageStats) {
    visible_set_with_progress(screen, None)
}

/// [`visible_set`], reporting stage "visible set": pieces inserted into the coverage map of
/// all the pieces.
pub fn visible_set_with_progress(
    screen: &ScreenScene,
    report: Option<Report>,
) -> (VisibleSet, CoverageStats) {
    let all: Vec<u32> = (0..screen.polys.len() as u32).collect();
    let (pieces, stats, _) = visible_pieces_of(screen, &all, report);
    (VisibleSet::of_pieces(pieces), stats)
}

/// The visible pieces of the polygons `polys` (increasing) by the coverage map: their pieces
/// less what the occlusion cells prove hidden ([`unhidden_pieces`]: hidden triangles are never
/// made into pieces) and those no other piece overlaps ([`clear_pieces`]: visible whole, never
/// in a map), the rest strip by strip on all cores ([`super::strips`]), with the map's counters
/// summed (the dropped and the clear pieces count as inserted) and the number of strips.
fn visible_pieces_of(
    screen: &ScreenScene,
    polys: &[u32],
    report: Option<Report>,
) -> (Vec<Piece>, CoverageStats, usize) {
    let (pieces, occluded) = unhidden_pieces(screen, polys);
    let clear = clear_pieces(screen, &pieces);
    let (strips, rest, clear) = Strips::cut_all_but(pieces, &clear);
    let clear_count = clear.len();
    let (visible, mut stats) = visible_pieces_of_strips(screen, rest, clear, report);
    stats.dropped_before_insertion(occluded);
    stats.clear_before_insertion(clear_count);
    (visible, stats, strips.count())
}

/// The visible pieces of `strips` (pieces already cut into strips, [`Strips::cut`]) by the
/// coverage map of each strip, on all cores, with the map's counters summed, then with `beside`
/// ([`solve_strips_beside`]).
pub(crate) fn visible_pieces_of_strips(
    screen: &ScreenScene,
    strips: Vec<Vec<Piece>>,
    beside: Vec<Piece>,
    report: Option<Report>,
) -> (Vec<Piece>, CoverageStats) {
    solve_strips_beside(strips, beside, report, |strip, report| {
        let coverage = coverage_of(screen, strip, report);
        let stats = coverage.stats.clone();
        Ok((coverage.into_pieces(), stats))
    })
    .expect("the coverage map never gives up")
}

/// The coverage map of `pieces`, inserted nearest corner first, reporting stage "visible set"
/// (no occlusion cells: the caller's [`unhidden_pieces`] applied them to the whole scene).
pub(crate) fn coverage_of<'a>(
    screen: &'a ScreenScene,
    pieces: Vec<Piece>,
    report: Option<Report>,
) -> Coverage<'a> {
    // The order sorted, not the pieces: a piece is a few hundred bytes inline, and a sort
    // moves each many times. A stable sort of the indices gives the stable sort's order. Each
    // key is computed once, from the piece's own polygon (a strip holds a few of the scene's
    // polygons: a table over all of them, per strip, cost more than the sort).
    let mut order: Vec<u32> = (0..pieces.len() as u32).collect();
    order.sort_by_cached_key(|&i| nearest_first(screen, pieces[i as usize].poly));
    let mut coverage =
        Coverage::with_occlusion(screen, order.iter().map(|&i| &pieces[i as usize]), false);
    let mut ticker = Ticker::new(report, "visible set", pieces.len() as u64);
    let mut pieces: Vec<Option<Piece>> = pieces.into_iter().map(Some).collect();
    for (n, &i) in order.iter().enumerate() {
        coverage.insert(pieces[i as usize].take().expect("each piece once"));
        ticker.tick(n as u64 + 1);
    }
    ticker.finish();
    coverage
}
