//! The BSP strategy (`bsp`): the exact visible set through a 3D BSP tree of every opaque piece
//! ([`Bsp`]), walked front to back into the coverage map, each piece minus the visible pieces in
//! front of it ([`Bsp::coverage`]). Slower than the coverage map on interpenetrating soups (the
//! tree cuts each face by the plane of every other it straddles), and independent of it: the
//! tests hold the two to the same result. Translucent faces are layered as the coverage map
//! layers them ([`translucent_layer`]).

use super::bsp::{Bsp, translucent_layer};
use super::visible_set::{Stats, VisibleSet};
use super::{Strategy, initial_pieces, translucent_polygons};
use crate::exact::polygon::Piece;
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
        let (see_through, opaque): (Vec<Piece>, Vec<Piece>) = initial_pieces(screen)
            .into_iter()
            .partition(|p| layered && translucent(p.poly));
        let bsp = Bsp::build_from(screen, opaque, report);
        let mut coverage = bsp.coverage(screen);
        let (layered, translucent_bsp) = if layered {
            let (parts, st) = translucent_layer(screen, &mut coverage, see_through, report);
            (parts, Some(st))
        } else {
            (Vec::new(), None)
        };
        let mut stats = Stats::new();
        let mut put = |k: &str, v: serde_json::Value| {
            stats.insert(k.to_string(), v);
        };
        let st = &bsp.stats;
        put(
            "translucent_painter_order",
            translucent_bsp.is_some().into(),
        );
        put("pieces", st.pieces.into());
        put("fragments", st.fragments.into());
        put("bsp_nodes", st.nodes.into());
        put("bsp_depth", st.depth.into());
        if let Some(t) = translucent_bsp {
            put("translucent_pieces", t.pieces.into());
            put("translucent_fragments", t.fragments.into());
            put("translucent_parts", layered.len().into());
        }
        VisibleSet::exact(screen, coverage.into_pieces(), layered, stats, fallbacks)
    }
}
