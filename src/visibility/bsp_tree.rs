//! The BSP strategy (`bsp`): the exact visible set through a 3D BSP tree of every opaque piece
//! ([`Bsp`]), walked front to back into the coverage map, each piece minus the visible pieces in
//! front of it ([`Bsp::coverage`]). Slower than the coverage map on interpenetrating soups (the
//! tree cuts each face by the plane of every other it straddles), and independent of it: the
//! tests hold the two to the same result. Pieces facing away that the occlusion cells prove
//! hidden are dropped before the tree is built, and those no other piece overlaps
//! (`visibility::clear`) are visible whole without one; large scenes are solved strip by strip on
//! all cores ([`super::strips`]), a tree per strip. Translucent faces are layered as the
//! coverage map layers them ([`translucent_layer`]).

use super::bsp::{Bsp, translucent_layer};
use super::clear::clear_pieces;
use super::coverage::Coverage;
use super::occlusion::unhidden_pieces;
use super::strips::{Strips, solve_strips_beside};
use super::visible_set::{Stats, VisibleSet};
use super::{Strategy, pieces_of, translucent_polygons};
use crate::exact::predicates::fallback_count;
use crate::progress::Report;
use crate::project::ScreenScene;

/// The BSP strategy. See the module docs.
#[derive(Clone, Copy, Debug, Default)]
pub struct BspTree;

impl Strategy for BspTree {
    fn visible_set(
        &self,
        screen: &ScreenScene,
        translucent: &dyn Fn(u32) -> bool,
        report: Option<Report>,
    ) -> VisibleSet {
        let fallbacks = fallback_count();
        let layered = translucent_polygons(screen, translucent);
        let (see_through, opaque): (Vec<u32>, Vec<u32>) =
            (0..screen.polys.len() as u32).partition(|&k| layered && translucent(k));
        let see_through = pieces_of(screen, &see_through);
        // What the surface facing the eye proves hidden is never cut by the tree.
        let (opaque, occluded) = unhidden_pieces(screen, &opaque);
        // What nothing overlaps is visible whole: only the rest goes into the trees.
        let clear = clear_pieces(screen, &opaque);
        let (strips, rest, clear) = Strips::cut_all_but(opaque, &clear);
        let strip_count = strips.count();
        let clear_count = clear.len();
        let (visible, st) = solve_strips_beside(rest, clear, report, |strip, report| {
            Ok(Bsp::visible_pieces_of(screen, strip, report))
        })
        .expect("the BSP never gives up");
        let (visible, layered, translucent_bsp) = if layered {
            let mut coverage = Coverage::of_visible(screen, visible);
            let (parts, st) = translucent_layer(screen, &mut coverage, see_through, report);
            (coverage.into_pieces(), parts, Some(st))
        } else {
            (visible, Vec::new(), None)
        };
        let mut stats = Stats::new();
        let mut put = |k: &str, v: serde_json::Value| {
            stats.insert(k.to_string(), v);
        };
        put("occluded", occluded.into());
        put("clear", clear_count.into());
        put("covered", st.covered.into());
        put("strips", strip_count.into());
        put(
            "translucent_painter_order",
            translucent_bsp.is_some().into(),
        );
        // Every opaque piece, as the coverage map counts: the occluded and the clear ones never
        // reach a tree.
        put("pieces", (st.pieces + occluded + clear_count).into());
        if let Some(t) = translucent_bsp {
            put("translucent_pieces", t.pieces.into());
            put("translucent_fragments", t.fragments.into());
            put("translucent_parts", layered.len().into());
        }
        st.put_tree(&mut stats);
        VisibleSet::exact(screen, visible, layered, stats, fallbacks)
    }
}
