//! The automatic strategy (`auto`, the default for vector output): the stages an exact visible
//! set can need, each run only where the scene needs it, and `--stats` saying for each what was
//! done or why it was skipped (`stage_*` keys).
//!
//! - **cull**: done during projection for closed meshes with a certain orientation (their back
//!   faces can never show); open meshes keep their back faces.
//! - **order**: only pieces that overlap on screen are compared in depth. The coverage map finds
//!   them through its screen grid and an exact overlap test ([`crate::exact::polygon::separated`]):
//!   a piece that overlaps nothing (all of a convex closed mesh once culled, objects apart on
//!   screen) is placed with no depth comparison.
//! - **split**: a pair is cut where its planes meet only when each reaches in front of the
//!   other's plane where they overlap (interpenetration, cyclic overlap); every other
//!   overlapping pair is only clipped, in its depth order.
//! - **blend**: translucent faces need the exact back-to-front order of their fragments (a BSP of
//!   their pieces, layered over the opaque visible set).
//!
//! So far the choice is within the coverage map (the fastest exact strategy on every scene
//! measured); the scene analysis that would hand parts of a scene to other strategies (a convex
//! mesh's faces tiling its silhouette once, depth-separable groups) is the next step (see
//! PROGRESS.md). Invariant: the visible set is the coverage map's.

use super::coverage_map::coverage_of;
use super::visible_set::{Stats, VisibleSet};
use super::{CoverageMap, Strategy, initial_pieces, translucent_polygons};
use crate::exact::predicates::fallback_count;
use crate::progress::Report;
use crate::project::ScreenScene;

/// The automatic strategy. See the module docs.
#[derive(Clone, Copy, Debug, Default)]
pub struct Auto;

impl Strategy for Auto {
    fn visible_set(
        &self,
        screen: &ScreenScene,
        translucent: &dyn Fn(u32) -> bool,
        report: Option<Report>,
    ) -> VisibleSet {
        let fallbacks = fallback_count();
        let mut stats = Stats::new();
        let mut stage = |k: &str, v: String| {
            stats.insert(format!("stage_{k}"), v.into());
        };
        let ps = &screen.stats;
        stage(
            "cull",
            if ps.culled_meshes > 0 {
                format!(
                    "done in projection: {} of {}",
                    count(ps.backface_culled, "back face", "back faces"),
                    count(ps.culled_meshes, "closed mesh", "closed meshes")
                )
            } else {
                "skipped: no closed mesh of certain orientation (open meshes keep their back faces)"
                    .into()
            },
        );
        if translucent_polygons(screen, translucent) {
            let n = (0..screen.polys.len() as u32)
                .filter(|&k| translucent(k))
                .count();
            stage(
                "blend",
                format!(
                    "done: {} layered back to front",
                    count(n, "translucent polygon", "translucent polygons")
                ),
            );
            stage(
                "order",
                "done: the coverage map of every opaque piece (translucent scene)".into(),
            );
            stage(
                "split",
                "done where needed by the coverage map (translucent scene)".into(),
            );
            let mut v = CoverageMap.visible_set(screen, translucent, report);
            v.stats.append(&mut stats);
            return v;
        }
        stage("blend", "skipped: every face is opaque".into());
        let pieces = initial_pieces(screen);
        let n = pieces.len();
        let coverage = coverage_of(screen, pieces, report);
        let cs = coverage.stats.clone();
        let visible = coverage.into_pieces();
        let mut stage = |k: &str, v: String| {
            stats.insert(format!("stage_{k}"), v.into());
        };
        stage(
            "order",
            if cs.overlap_tests == 0 {
                format!("skipped: none of the {n} pieces meets another on screen")
            } else {
                format!(
                    "done where pieces meet on screen: {} for {}, {} cut back by nearer ones",
                    count(
                        cs.overlap_tests,
                        "exact overlap test",
                        "exact overlap tests"
                    ),
                    count(n, "piece", "pieces"),
                    count(cs.replaced, "visible piece", "visible pieces")
                )
            },
        );
        stage(
            "split",
            if cs.plane_splits == 0 {
                "skipped: no overlapping pair reaches in front of the other's plane where they \
                 overlap (pieces only clipped)"
                    .into()
            } else {
                format!(
                    "done: {} split where their planes meet",
                    count(cs.plane_splits, "overlapping pair", "overlapping pairs")
                )
            },
        );
        for (k, v) in [
            ("pieces", cs.inserted),
            ("overlap_tests", cs.overlap_tests),
            ("replaced", cs.replaced),
            ("plane_splits", cs.plane_splits),
        ] {
            stats.insert(k.into(), v.into());
        }
        VisibleSet::exact(screen, visible, Vec::new(), stats, fallbacks)
    }
}

/// `n` and the noun in its number: "1 piece", "2 pieces".
fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}
