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
//! Which strategy orders what overlaps: the coverage map, unless the overlapping pieces are a
//! soup of large crossing faces ([`depth_complexity`] above [`SUBDIVIDE_ABOVE_DEPTH`]), where
//! Warnock's subdivision at object precision drops far pieces wholesale behind surrounding
//! ones instead of cutting them by every nearer piece. Not yet: depth-separable groups handed
//! to Newell's sort, per-group choices (see PROGRESS.md). Invariant: the visible set is the
//! coverage map's, so the drawing's bytes are the same whichever strategy ran.

use super::coverage_map::coverage_of;
use super::grid::sweep_overlapping;
use super::tiling::tiles_convex_region_once;
use super::visible_set::{Stats, VisibleSet, put_counts};
use super::warnock_exact;
use super::{CoverageMap, Strategy, initial_pieces, translucent_polygons};
use crate::exact::polygon::Piece;
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
        let ps = &screen.stats;
        stage(
            &mut stats,
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
                &mut stats,
                "blend",
                format!(
                    "done: {} layered back to front",
                    count(n, "translucent polygon", "translucent polygons")
                ),
            );
            stage(
                &mut stats,
                "order",
                "done: the coverage map of every opaque piece (translucent scene)".into(),
            );
            stage(
                &mut stats,
                "split",
                "done where needed by the coverage map (translucent scene)".into(),
            );
            let mut v = CoverageMap.visible_set(screen, translucent, report);
            v.stats.append(&mut stats);
            return v;
        }
        stage(&mut stats, "blend", "skipped: every face is opaque".into());
        let pieces = initial_pieces(screen);
        let whole = whole_meshes(screen);
        let (mut visible, overlapping): (Vec<Piece>, Vec<Piece>) = pieces
            .into_iter()
            .partition(|p| whole.placed[screen.polys[p.poly as usize].mesh as usize]);
        let placed = visible.len();
        let n = overlapping.len();
        let depth = depth_complexity(&overlapping);
        stats.insert("depth_complexity_estimate".into(), depth.into());
        let whole_meshes = whole.placed.iter().filter(|&&w| w).count();
        put_counts(
            &mut stats,
            [
                ("meshes_on_screen", whole.on_screen),
                ("meshes_apart", whole.apart),
                ("meshes_placed_whole", whole_meshes),
                ("pieces_placed_whole", placed),
            ],
        );
        let skipped = match whole_meshes {
            0 => String::new(),
            m => format!(
                "skipped for {} of {} on screen ({}: apart from the others on screen, faces \
                 covering their outline once); ",
                count(m, "mesh", "meshes"),
                whole.on_screen,
                count(placed, "piece placed whole", "pieces placed whole")
            ),
        };
        if n > 0 && depth > SUBDIVIDE_ABOVE_DEPTH {
            // Large faces crossing many others (a soup): the coverage map would cut each far
            // piece by every nearer one before all of it vanished; Warnock's subdivision drops
            // it wherever one surrounding face hides it.
            let (pieces, ws) = warnock_exact::visible_pieces(screen, &overlapping, report);
            visible.extend(pieces);
            stage(
                &mut stats,
                "order",
                format!(
                    "{skipped}done by Warnock's subdivision at object precision for {}: \
                     estimated depth complexity {depth:.1} (their number times the median \
                     screen box, over the box of all) is above {SUBDIVIDE_ABOVE_DEPTH}; {} settled by one \
                     surrounding face in front, {} hidden pieces dropped",
                    count(n, "overlapping piece", "overlapping pieces"),
                    count(ws.settled, "area", "areas"),
                    ws.hidden
                ),
            );
            stage(
                &mut stats,
                "split",
                format!(
                    "done only in {} (clipped exactly, Weiler-Atherton)",
                    count(ws.leaves, "small area", "small areas")
                ),
            );
            put_counts(
                &mut stats,
                [
                    ("areas", ws.areas),
                    ("areas_settled", ws.settled),
                    ("leaves_clipped", ws.leaves),
                ],
            );
            return VisibleSet::exact(screen, visible, Vec::new(), stats, fallbacks);
        }
        let coverage = coverage_of(screen, overlapping, report);
        let cs = coverage.stats.clone();
        visible.extend(coverage.into_pieces());
        stage(
            &mut stats,
            "order",
            if n == 0 {
                format!("{skipped}nothing left to order")
            } else if cs.overlap_tests == 0 {
                format!("{skipped}skipped: none of the other {n} pieces meets another on screen")
            } else {
                format!(
                    "{skipped}done by the coverage map where pieces meet on screen (estimated \
                     depth complexity {depth:.1}): {} for {}, {} cut back by nearer ones",
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
            &mut stats,
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
        put_counts(
            &mut stats,
            [
                ("pieces", cs.inserted),
                ("overlap_tests", cs.overlap_tests),
                ("replaced", cs.replaced),
                ("plane_splits", cs.plane_splits),
            ],
        );
        VisibleSet::exact(screen, visible, Vec::new(), stats, fallbacks)
    }
}

/// Above this estimated depth complexity ([`depth_complexity`]) the overlapping pieces go to
/// Warnock's subdivision at object precision rather than the coverage map. Measured (bench
/// --repeat 3, one run): soups of 100, 300 and 1,000 large triangles (estimates far above 8)
/// took 0.024, 0.12 and 0.57 s there against 0.054, 0.44 and 5.0 s in the map; meshes are 1.6
/// to 6 times faster in the map (samurai_monastery 10.3 s against 16.6 s: its mean-box estimate
/// is 39, from a few huge faces, its median-box estimate small).
pub const SUBDIVIDE_ABOVE_DEPTH: f64 = 8.0;

/// How many pieces lie over a point, estimated from boxes as if every piece had the median
/// piece's box: the piece count times the median box area, over the area of the box of all.
/// Large for a soup of large crossing faces, small for meshes even when a few huge faces
/// (a ground plane, walls) lie under everything, which a mean would count. A choice of method,
/// never a decision about what is visible.
pub fn depth_complexity(pieces: &[Piece]) -> f64 {
    let mut all = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];
    let mut areas: Vec<f64> = pieces
        .iter()
        .map(|p| {
            let b = p.bounds();
            all = [
                all[0].min(b[0]),
                all[1].min(b[1]),
                all[2].max(b[2]),
                all[3].max(b[3]),
            ];
            (b[2] - b[0]).max(0.0) * (b[3] - b[1]).max(0.0)
        })
        .collect();
    let area = (all[2] - all[0]) * (all[3] - all[1]);
    if areas.is_empty() || area <= 0.0 {
        return 0.0;
    }
    let mid = areas.len() / 2;
    let (_, median, _) = areas.select_nth_unstable_by(mid, f64::total_cmp);
    pieces.len() as f64 * *median / area
}

/// Records what a stage did, or why it was skipped (`stage_{name}`; `--stats` prints these as
/// lines, see `render::Computed::detail`).
fn stage(stats: &mut Stats, name: &str, what: String) {
    stats.insert(format!("stage_{name}"), what.into());
}

/// `n` and the noun in its number: "1 piece", "2 pieces".
fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// Which meshes need no ordering at all: see [`whole_meshes`].
struct WholeMeshes {
    /// Per mesh (index into `Scene::meshes`): its pieces are visible whole.
    placed: Vec<bool>,
    /// Meshes with a polygon on screen.
    on_screen: usize,
    /// Of those, the ones whose screen box meets no other's.
    apart: usize,
}

/// The meshes whose pieces are all visible whole: the mesh's screen box (exact, from its grid
/// corners) overlaps no other mesh's, and its polygons cover their outline exactly once
/// ([`tiles_convex_region_once`]: a convex closed mesh once culled, or any mesh seen so that
/// its faces do not overlap). Then no other piece can meet them, nor they each other.
fn whole_meshes(screen: &ScreenScene) -> WholeMeshes {
    let meshes = screen
        .polys
        .iter()
        .map(|p| p.mesh as usize + 1)
        .max()
        .unwrap_or(0);
    let mut boxes = vec![[i64::MAX, i64::MAX, i64::MIN, i64::MIN]; meshes];
    let mut polys_of: Vec<Vec<u32>> = vec![Vec::new(); meshes];
    for (k, p) in screen.polys.iter().enumerate() {
        let b = &mut boxes[p.mesh as usize];
        for c in screen.corners(p) {
            *b = [b[0].min(c.x), b[1].min(c.y), b[2].max(c.x), b[3].max(c.y)];
        }
        polys_of[p.mesh as usize].push(k as u32);
    }
    // A mesh is crowded when its box's interior meets another's.
    let order: Vec<usize> = (0..meshes).filter(|&m| !polys_of[m].is_empty()).collect();
    let on_screen: Vec<[i64; 4]> = order.iter().map(|&m| boxes[m]).collect();
    let mut crowded = vec![false; meshes];
    sweep_overlapping(&on_screen, |a, b| {
        crowded[order[a]] = true;
        crowded[order[b]] = true;
        true
    });
    let placed: Vec<bool> = (0..meshes)
        .map(|m| {
            !polys_of[m].is_empty() && !crowded[m] && tiles_convex_region_once(screen, &polys_of[m])
        })
        .collect();
    WholeMeshes {
        placed,
        on_screen: order.len(),
        apart: order.iter().filter(|&&m| !crowded[m]).count(),
    }
}
