//! The automatic strategy (`auto`, the default for vector output): the stages an exact visible
//! set can need, each run only where the scene needs it, and `--stats` saying for each what was
//! done or why it was skipped (`stage_*` keys).
//!
//! - **cull**: done during projection for closed meshes with a certain orientation (their back
//!   faces can never show); open meshes keep their back faces.
//! - **order**: only pieces that overlap on screen are compared in depth. The coverage map finds
//!   them through its screen grid and an exact overlap test ([`crate::exact::polygon::separated`]):
//!   a piece that overlaps nothing (all of a convex closed mesh once culled, objects apart on
//!   screen) is placed with no depth comparison. Most such pieces are found before any pair is
//!   compared (`visibility::clear`: the `clear` count) and never reach an orderer.
//! - **split**: a pair is cut where its planes meet only when each reaches in front of the
//!   other's plane where they overlap (interpenetration, cyclic overlap); every other
//!   overlapping pair is only clipped, in its depth order.
//! - **blend**: translucent faces need the exact back-to-front order of their fragments (a BSP of
//!   their pieces, layered over the opaque visible set).
//!
//! Which strategy orders what overlaps ([`Crowding::choose`], from cheap f64 measures of the
//! pieces' screen boxes, never a decision about what is visible): Warnock's subdivision at
//! object precision for a soup of large crossing faces (it drops far pieces wholesale behind
//! surrounding ones instead of cutting them by every nearer piece); Weiler–Atherton clipping
//! where large pieces lie over many small ones (CAD housings over hidden parts: each clip
//! polygon drops everything behind it at once), given up for the coverage map when its
//! recursion runs deep; a BSP tree per strip ([`Bsp`]) where the pieces are slivers, or of like
//! size with none seen from the back (culled closed meshes); the coverage map for the rest
//! (open scans, seen from both sides). Not yet: depth-separable groups handed to Newell's sort, per-group
//! choices (see PROGRESS.md). The `chosen` statistic names what ran. Invariant: the visible set
//! is the coverage map's whatever ran (every exact strategy's is), so the drawing's bytes are
//! the same.

use super::bsp::Bsp;
use super::clear::clear_pieces;
use super::coverage_map::visible_pieces_of_strips;
use super::grid::{NO_BOX, joined, sweep_overlapping};
use super::occlusion::unhidden_pieces;
use super::strips::{Strips, appended, solve_strips};
use super::tiling::{tiles_convex_region_once, twice_hull_area, twice_ring_area};
use super::visible_set::{Stats, VisibleSet, put_counts};
use super::warnock_exact;
use super::weiler_atherton::{self, ClipBudget};
use super::{CoverageMap, Strategy, pieces_of, translucent_polygons};
use crate::exact::polygon::Piece;
use crate::exact::predicates::fallback_count;
use crate::progress::Report;
use crate::project::ScreenScene;
use std::sync::atomic::{AtomicBool, Ordering as AtomicOrdering};

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
            stats.insert("chosen".into(), "coverage".into());
            v.stats.append(&mut stats);
            return v;
        }
        stage(&mut stats, "blend", "skipped: every face is opaque".into());
        let whole = whole_meshes(screen);
        let (placed_polys, other_polys): (Vec<u32>, Vec<u32>) = (0..screen.polys.len() as u32)
            .partition(|&k| whole.placed[screen.polys[k as usize].mesh as usize]);
        let visible = pieces_of(screen, &placed_polys);
        let placed = visible.len();
        // Pieces facing away that the surface facing the eye proves hidden need no orderer (and
        // hidden triangles never become pieces).
        let (mut overlapping, occluded) = unhidden_pieces(screen, &other_polys);
        if occluded > 0 {
            let hidden = format!(
                "{} proven hidden behind the surface facing the eye before any cut (occlusion \
                 cells)",
                count(occluded, "piece facing away", "pieces facing away")
            );
            let culled = match ps.culled_meshes {
                0 => format!("done: {hidden}; no closed mesh of certain orientation to cull"),
                _ => format!(
                    "{}; {hidden}",
                    stats["stage_cull"].as_str().unwrap_or_default()
                ),
            };
            stage(&mut stats, "cull", culled);
        }
        // What no other piece overlaps is visible whole: no orderer needs it.
        let clear = {
            let flags = clear_pieces(screen, &overlapping);
            let mut k = 0;
            let clear: Vec<Piece> = (overlapping.extract_if(.., |_| {
                k += 1;
                flags[k - 1]
            }))
            .collect();
            // The room the clear pieces left, back (a large list shrinks in place).
            overlapping.shrink_to_fit();
            clear
        };
        let n = overlapping.len();
        let crowding = Crowding::of(screen, &overlapping);
        crowding.put(&mut stats);
        let whole_meshes = whole.placed.iter().filter(|&&w| w).count();
        put_counts(
            &mut stats,
            [
                ("meshes_on_screen", whole.on_screen),
                ("meshes_apart", whole.apart),
                ("meshes_placed_whole", whole_meshes),
                ("pieces_placed_whole", placed),
                ("occluded", occluded),
                ("clear", clear.len()),
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
        let (orderer, why) = crowding.choose();
        let mut chosen = match n {
            0 => "nothing to order",
            _ => orderer.name(),
        }
        .to_string();
        // Each orderer writes its stage lines and counters; clipping may give up for the map,
        // handing it the pieces already cut into strips.
        let mut given_up = String::new();
        let mut cut = None;
        let ordered = match orderer {
            _ if n == 0 => None,
            Orderer::Warnock => Some(by_subdivision(
                screen,
                std::mem::take(&mut overlapping),
                report,
                &mut stats,
                &skipped,
                &why,
            )),
            Orderer::WeilerAtherton => {
                let pieces = std::mem::take(&mut overlapping);
                let again = || unhidden_pieces(screen, &other_polys).0;
                match by_clipping(screen, pieces, again, report, &mut stats, &skipped, &why) {
                    Ok(visible) => Some(visible),
                    Err(strips) => {
                        given_up = format!(
                            "Weiler-Atherton clipping ({why}) given up (deeper than {} levels \
                             of recursion, or more than {} pieces handed down per clip \
                             polygon); ",
                            CLIP_BUDGET.deepest, CLIP_BUDGET.recursed_per_clip_polygon
                        );
                        chosen = "coverage after weiler-atherton".into();
                        cut = Some((n, strips));
                        None
                    }
                }
            }
            Orderer::Bsp => Some(by_bsp(
                screen,
                std::mem::take(&mut overlapping),
                report,
                &mut stats,
                &skipped,
                &why,
            )),
            Orderer::CoverageMap => None,
        };
        let pieces = match ordered {
            Some(pieces) => pieces,
            None => {
                let why = match orderer {
                    Orderer::CoverageMap => format!(" ({why})"),
                    _ => String::new(),
                };
                let told = format!("{skipped}{given_up}");
                let strips = cut.unwrap_or_else(|| {
                    let pieces = std::mem::take(&mut overlapping);
                    (n, Strips::for_pieces(&pieces).cut(pieces))
                });
                by_map(screen, strips, report, &mut stats, &told, &why)
            }
        };
        // Each shorter list is appended to the longer, not the ordered pieces copied after the
        // placed ones (a copy of a few hundred bytes a piece into fresh memory, page faults
        // included, cost igea 15 % of its time).
        let visible = appended(appended(visible, clear), pieces);
        stats.insert("chosen".into(), chosen.into());
        VisibleSet::exact(screen, visible, Vec::new(), stats, fallbacks)
    }
}

/// Orders `pieces` by a BSP tree per strip ([`Bsp`]), as the `bsp` strategy does.
fn by_bsp(
    screen: &ScreenScene,
    pieces: Vec<Piece>,
    report: Option<Report>,
    stats: &mut Stats,
    skipped: &str,
    why: &str,
) -> Vec<Piece> {
    let n = pieces.len();
    let strips = Strips::for_pieces(&pieces);
    let strip_count = strips.count();
    let (visible, bs) = solve_strips(strips.cut(pieces), report, |strip, report| {
        Ok(Bsp::visible_pieces_of(screen, strip, report))
    })
    .expect("the BSP never gives up");
    stage(
        stats,
        "order",
        format!(
            "{skipped}done by a BSP tree per strip for {} ({why}): {} between pieces that \
             meet on screen, {} under a front layer dropped whole",
            count(n, "overlapping piece", "overlapping pieces"),
            count(bs.pair_tests, "exact pair test", "exact pair tests"),
            count(bs.covered, "piece", "pieces")
        ),
    );
    stage(
        stats,
        "split",
        match bs.fragments.saturating_sub(bs.pieces) {
            0 => "skipped: no splitting plane cuts a piece".into(),
            cuts => format!(
                "done: {} by splitting planes ({} deep at most)",
                count(cuts, "piece cut", "pieces cut"),
                count(bs.depth, "level", "levels")
            ),
        },
    );
    bs.put_tree(stats);
    put_counts(stats, [("covered", bs.covered), ("strips", strip_count)]);
    visible
}

/// Orders `pieces` by Warnock's subdivision at object precision: large faces crossing many
/// others (a soup), where the coverage map would cut each far piece by every nearer one before
/// all of it vanished, and the subdivision drops it wherever one surrounding face hides it.
fn by_subdivision(
    screen: &ScreenScene,
    pieces: Vec<Piece>,
    report: Option<Report>,
    stats: &mut Stats,
    skipped: &str,
    why: &str,
) -> Vec<Piece> {
    let n = pieces.len();
    // Whole, not in strips (see `WarnockExact`).
    let (visible, ws) = warnock_exact::visible_pieces(screen, &pieces, report);
    stage(
        stats,
        "order",
        format!(
            "{skipped}done by Warnock's subdivision at object precision for {} ({why}): \
             {} settled by one surrounding face in front, {} hidden pieces dropped",
            count(n, "overlapping piece", "overlapping pieces"),
            count(ws.settled, "area", "areas"),
            ws.hidden
        ),
    );
    stage(
        stats,
        "split",
        format!(
            "done only in {} (clipped exactly, Weiler-Atherton)",
            count(ws.leaves, "small area", "small areas")
        ),
    );
    put_counts(
        stats,
        [
            ("areas", ws.areas),
            ("areas_settled", ws.settled),
            ("leaves_clipped", ws.leaves),
            ("strips", 1),
        ],
    );
    visible
}

/// Orders `pieces` by Weiler–Atherton clipping, or gives up past [`CLIP_BUDGET`] and returns
/// the same pieces cut into the same strips for the map (nothing written to `stats` then):
/// each strip as it was given, or, where a strip was solved before another gave up, all of
/// them from `again` (which makes `pieces` again, the same list) cut again.
fn by_clipping(
    screen: &ScreenScene,
    pieces: Vec<Piece>,
    again: impl FnOnce() -> Vec<Piece>,
    report: Option<Report>,
    stats: &mut Stats,
    skipped: &str,
    why: &str,
) -> Result<Vec<Piece>, Vec<Vec<Piece>>> {
    let n = pieces.len();
    let strips = Strips::for_pieces(&pieces);
    let strip_count = strips.count();
    // One strip giving up gives up the whole: the others stop at their next clip polygon, and
    // those not started yet are handed back as they are. Clipping consumes its pieces, so a
    // strip keeps a copy while it runs (a strip of a few thousand pieces, one per thread: the
    // whole list copied would add its size to the peak of every scene where clipping finishes,
    // xarm6_link2 117 -> 134 MB, diff_ring_gear 243 -> 266 MB). Without them, samurai_monastery
    // made its pieces and strips again after giving up: 0.13 s of its 3 s.
    let stop = AtomicBool::new(false);
    let solved = solve_strips(strips.cut(pieces), report, |strip, report| {
        if stop.load(AtomicOrdering::Relaxed) {
            return Err(strip);
        }
        let given = strip.clone();
        weiler_atherton::visible_pieces_within_or_stopped(screen, strip, report, CLIP_BUDGET, &stop)
            .ok_or(given)
    });
    let (visible, ws) = match solved {
        Ok(solved) => solved,
        Err(given) => {
            return Err(match given.into_iter().collect::<Option<Vec<_>>>() {
                Some(strips) => strips,
                // A strip finished before another gave up: its pieces are gone. Every strip
                // is made again (not only the finished ones: which strips finished depends on
                // timing, and the map must get the same pieces whatever it was).
                None => strips.cut(again()),
            });
        }
    };
    stage(
        stats,
        "order",
        format!(
            "{skipped}done by Weiler-Atherton clipping for {} ({why}): {} clipped {} pieces, \
             {} hidden parts dropped",
            count(n, "overlapping piece", "overlapping pieces"),
            count(ws.clip_polygons, "clip polygon", "clip polygons"),
            ws.clipped,
            ws.hidden
        ),
    );
    stage(
        stats,
        "split",
        if ws.recursions == 0 {
            "skipped: no clipped part reaches in front of its clip polygon".into()
        } else {
            format!(
                "done: {} where a part reaches in front of its clip polygon (cut by its plane, \
                 {} deep at most)",
                count(ws.recursions, "recursion", "recursions"),
                count(ws.deepest, "level", "levels")
            )
        },
    );
    put_counts(
        stats,
        [
            ("clip_polygons", ws.clip_polygons),
            ("clipped", ws.clipped),
            ("hidden_parts", ws.hidden),
            ("recursions", ws.recursions),
            ("recursed_pieces", ws.recursed),
            ("strips", strip_count),
        ],
    );
    Ok(visible)
}

/// Orders the `n` pieces cut into `strips` in the coverage map, strip by strip. `told`: what
/// the order line starts with (meshes placed whole, a given-up attempt); `why`: the reason when
/// the map was the choice.
fn by_map(
    screen: &ScreenScene,
    (n, strips): (usize, Vec<Vec<Piece>>),
    report: Option<Report>,
    stats: &mut Stats,
    told: &str,
    why: &str,
) -> Vec<Piece> {
    let strip_count = strips.len();
    // The pieces the occlusion cells prove hidden are gone already (`unhidden_pieces`).
    let (visible, cs) = visible_pieces_of_strips(screen, strips, Vec::new(), report);
    stage(
        stats,
        "order",
        if n == 0 {
            format!("{told}nothing left to order")
        } else if cs.overlap_tests == 0 {
            format!("{told}skipped: none of the other {n} pieces meets another on screen")
        } else {
            format!(
                "{told}done by the coverage map where pieces meet on screen{why}: {} for {}, {} \
                 cut back by nearer ones",
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
        stats,
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
        stats,
        [
            ("pieces", cs.inserted),
            ("overlap_tests", cs.overlap_tests),
            ("replaced", cs.replaced),
            ("plane_splits", cs.plane_splits),
            ("covered", cs.covers.hits),
            ("strips", strip_count),
        ],
    );
    visible
}

/// What orders the pieces that are not placed whole.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Orderer {
    /// The coverage map ([`CoverageMap`]): front to back, each piece cut back by the nearer
    /// pieces it meets.
    CoverageMap,
    /// Weiler–Atherton clipping ([`weiler_atherton`]): each clip polygon drops everything
    /// behind it inside its region at once.
    WeilerAtherton,
    /// Warnock's subdivision at object precision ([`warnock_exact`]).
    Warnock,
    /// A BSP tree per strip ([`Bsp`]): front layers found by exact separation tests, what lies
    /// under them dropped whole, the rest cut by the pieces' planes.
    Bsp,
}

impl Orderer {
    /// The registry name of the strategy.
    pub fn name(self) -> &'static str {
        match self {
            Orderer::CoverageMap => "coverage",
            Orderer::WeilerAtherton => "weiler-atherton",
            Orderer::Warnock => "warnock-exact",
            Orderer::Bsp => "bsp",
        }
    }
}

/// Above this estimated depth complexity ([`Crowding::depth_median`]), a soup (at least
/// [`SOUP_BACK_SHARE`] of its pieces seen from the back) goes to Warnock's subdivision.
/// Measured (bench --repeat 3, one run): soups of 100, 300 and 1,000 large triangles (estimates
/// far above 8) took 0.024, 0.12 and 0.57 s there against 0.054, 0.44 and 5.0 s in the map.
pub const SUBDIVIDE_ABOVE_DEPTH: f64 = 8.0;

/// The share of pieces seen from the back from which the pieces are a soup (or open surfaces
/// seen from both sides), not culled closed meshes: these keep about half their faces back
/// facing, culled ones none. Closed meshes with crowded boxes (gears: 9 to 11 estimated)
/// were 5 to 13 times slower in Warnock's subdivision than clipped.
pub const SOUP_BACK_SHARE: f64 = 0.25;

/// Weiler–Atherton clipping is chosen when large pieces lie over many small ones: the mean
/// box depth ([`Crowding::depth_mean`]) at least this, and at least [`SKEW`] times the median
/// one. CAD assemblies (housings over hidden parts: counter 0.37x the map's time,
/// featuretype 0.48x, idler_riser 0.40x, plate_holes 0.42x, xarm6_link2 0.60x, one run of
/// `examples`-style timing over `../shared/meshes` at 256 px) are so; scans of one surface
/// (bunny 1.44x, buddha 1.30x, fertility 1.45x, horse 1.27x) are not.
pub const CLIP_ABOVE_MEAN_DEPTH: f64 = 2.5;

/// See [`CLIP_ABOVE_MEAN_DEPTH`].
pub const SKEW: f64 = 1.5;

/// A BSP tree per strip orders slivers: the median piece's box at least this many times its
/// area (2 for a right triangle on the axes, about 3 for a mesh of well shaped triangles; gear
/// teeth 10 to 13; the 1M sphere file's poles 29). A sliver's box meets many others' on screen,
/// which the map tests one by one (clipping was 0.76x the map's time on diff_pinion); the
/// tree's layers settle most such pairs by their shared corners, once. Whole `render` against
/// clipping (session 35, 7 interleaved runs, medians): the 1M sphere 1.42 -> 1.22 s,
/// diff_pinion 0.23 -> 0.24 s (peak 57 -> 18 MB); same bytes.
pub const SLIVER_BOX_RATIO: f64 = 8.0;

// Pieces of like size go to the BSP tree too when none is seen from the back (culled closed
// meshes; `Crowding::back_share` zero), else to the coverage map: the tree was the faster of
// the two on every culled closed mesh of ../shared/meshes and the map on the open scans (whole
// `render`, session 35, 7 interleaved runs, medians, map -> tree: dragon 1.42 -> 1.38 s, igea
// 0.37 -> 0.34, counter 0.25 -> 0.22, armadillo 0.20 -> 0.19, nefertiti 0.17 -> 0.16, horse
// 0.15 -> 0.15; open, tree against map: buddha 0.59 / 0.55, dragon_res2 0.84 / 0.76, bunny 0.19
// / 0.18).

/// Weiler–Atherton clipping is given up (for the coverage map) when its recursion goes deeper:
/// large faces whose nearest corner is near but whose body lies behind others keep finding
/// nearer polygons inside them (samurai_monastery: 1,045 levels, 5x the map's time; given up
/// at 96 levels after 0.5 s, at 192 after 0.9 s, at 384 after 7.1 s, of the map's 11 s). The
/// CAD meshes where clipping pays recurse up to 145 levels (octagonal_pocket; xarm6_link2 38,
/// ur5e_upperarm 62, gears 10).
pub const DEEPEST_CLIP_RECURSION: usize = 160;

/// Weiler–Atherton clipping is also given up when its recursions hand down more pieces per clip
/// polygon than this (counted once they outnumber the pieces given), the earlier sign of the
/// same thing: samurai_monastery's strips pass 40 after 0.15 to 0.3 s and 160 levels after
/// 0.45 to 0.6 s (74 to 105 per clip polygon then); the most seen where clipping pays is 24
/// (a strip of ur5e_upperarm; octagonal_pocket 12.6, xarm6_link2 6.9; 256 px views, strips of
/// two threads).
pub const RECURSED_PER_CLIP_POLYGON: usize = 40;

/// [`DEEPEST_CLIP_RECURSION`] and [`RECURSED_PER_CLIP_POLYGON`].
pub const CLIP_BUDGET: ClipBudget = ClipBudget {
    deepest: DEEPEST_CLIP_RECURSION,
    recursed_per_clip_polygon: RECURSED_PER_CLIP_POLYGON,
};

/// The medians of [`Crowding`] are taken over an even sample of at most this many pieces.
pub const MEDIAN_SAMPLE: usize = 4096;

/// Cheap measures of how the pieces to order lie on screen, from f64 boxes and areas: they
/// choose a strategy, never decide what is visible.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Crowding {
    /// The number of pieces.
    pub pieces: usize,
    /// How many pieces lie over a point, estimated as if every piece had the median piece's
    /// box: the count times the median box area, over the area of the box of all. Large for a
    /// soup of large crossing faces, small for meshes even when a few huge faces (a ground,
    /// walls) lie under everything.
    pub depth_median: f64,
    /// The same with the mean box: the sum of the box areas over the area of the box of all.
    /// Far above [`Self::depth_median`] when a few large pieces lie over many small ones.
    pub depth_mean: f64,
    /// The share of pieces seen from their back.
    pub back_share: f64,
    /// The median over pieces of box area over piece area (slivers: large).
    pub sliver: f64,
}

impl Crowding {
    /// The measures of `pieces`.
    pub fn of(screen: &ScreenScene, pieces: &[Piece]) -> Crowding {
        let n = pieces.len();
        // The medians from an even sample of at most MEDIAN_SAMPLE pieces (a choice of method
        // needs no more), the box of all, the mean and the back share from every piece.
        let stride = n.div_ceil(MEDIAN_SAMPLE).max(1);
        let mut all = NO_BOX;
        let mut box_sum = 0.0;
        let mut boxes = Vec::with_capacity(n.min(MEDIAN_SAMPLE));
        let mut ratios = Vec::with_capacity(n.min(MEDIAN_SAMPLE));
        let mut back = 0usize;
        for (k, p) in pieces.iter().enumerate() {
            let b = p.bounds();
            all = joined(all, &b);
            let box_area = (b[2] - b[0]).max(0.0) * (b[3] - b[1]).max(0.0);
            box_sum += box_area;
            back += !screen.polys[p.poly as usize].front as usize;
            if k % stride != 0 {
                continue;
            }
            // The cached f64 vertices (no allocation).
            let n = p.len();
            let twice: f64 = (0..n)
                .map(|k| {
                    let (a, c) = (p.point(k), p.point((k + 1) % n));
                    a[0] * c[1] - c[0] * a[1]
                })
                .sum();
            let area = 0.5 * twice.abs();
            boxes.push(box_area);
            ratios.push(if area > 0.0 {
                box_area / area
            } else {
                f64::MAX
            });
        }
        let area = (all[2] - all[0]) * (all[3] - all[1]);
        if n == 0 || area <= 0.0 {
            return Crowding {
                pieces: n,
                ..Crowding::default()
            };
        }
        let median = |v: &mut Vec<f64>| {
            let mid = v.len() / 2;
            *v.select_nth_unstable_by(mid, f64::total_cmp).1
        };
        Crowding {
            pieces: n,
            depth_median: n as f64 * median(&mut boxes) / area,
            depth_mean: box_sum / area,
            back_share: back as f64 / n as f64,
            sliver: median(&mut ratios),
        }
    }

    /// The strategy for these pieces, and why (see the constants).
    pub fn choose(&self) -> (Orderer, String) {
        let Crowding {
            depth_median: med,
            depth_mean: mean,
            back_share: back,
            sliver,
            ..
        } = *self;
        if med > SUBDIVIDE_ABOVE_DEPTH && back >= SOUP_BACK_SHARE {
            (
                Orderer::Warnock,
                format!(
                    "a soup: estimated depth complexity {med:.1} above {SUBDIVIDE_ABOVE_DEPTH}, \
                     {:.0} % seen from the back",
                    100.0 * back
                ),
            )
        } else if mean >= CLIP_ABOVE_MEAN_DEPTH && mean >= SKEW * med {
            (
                Orderer::WeilerAtherton,
                format!(
                    "large pieces over many small ones: mean box depth {mean:.1}, median box \
                     depth {med:.1}"
                ),
            )
        } else if sliver >= SLIVER_BOX_RATIO {
            (
                Orderer::Bsp,
                format!("slivers: the median piece's box is {sliver:.1} times its area"),
            )
        } else if back == 0.0 {
            (
                Orderer::Bsp,
                format!(
                    "pieces of like size, none seen from the back: mean box depth {mean:.1}, \
                     median box depth {med:.1}"
                ),
            )
        } else {
            (
                Orderer::CoverageMap,
                format!("pieces of like size: mean box depth {mean:.1}, median box depth {med:.1}"),
            )
        }
    }

    /// Records the measures in `stats`.
    fn put(&self, stats: &mut Stats) {
        for (k, v) in [
            ("depth_complexity_estimate", self.depth_median),
            ("mean_box_depth", self.depth_mean),
            ("back_share", self.back_share),
            ("sliver_box_ratio", self.sliver),
        ] {
            stats.insert(k.into(), v.into());
        }
    }
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

/// Eight directions in counterclockwise order (y up or down alike: the order only has to go
/// once around).
const DIRECTIONS: [[i64; 2]; 8] = [
    [1, 0],
    [1, 1],
    [0, 1],
    [-1, 1],
    [-1, 0],
    [-1, -1],
    [0, -1],
    [1, -1],
];

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
    // Twice the polygons' projected areas, summed per mesh, and the corners farthest in eight
    // directions: exact on the grid.
    let mut twice_areas = vec![0i128; meshes];
    let mut extremes = vec![[None::<(i128, [i64; 2])>; 8]; meshes];
    for (k, p) in screen.polys.iter().enumerate() {
        let m = p.mesh as usize;
        let b = &mut boxes[m];
        let corners = screen.corners(p);
        let mut twice = 0i128;
        for (i, c) in corners.iter().enumerate() {
            *b = [b[0].min(c.x), b[1].min(c.y), b[2].max(c.x), b[3].max(c.y)];
            let d = &corners[(i + 1) % corners.len()];
            twice += c.x as i128 * d.y as i128 - d.x as i128 * c.y as i128;
            for (e, [u, v]) in extremes[m].iter_mut().zip(DIRECTIONS) {
                let reach = u as i128 * c.x as i128 + v as i128 * c.y as i128;
                if e.is_none_or(|(r, _)| reach > r) {
                    *e = Some((reach, [c.x, c.y]));
                }
            }
        }
        twice_areas[m] += twice.abs();
        polys_of[m].push(k as u32);
    }
    // Faces covering a convex outline once add up to its area, which is at most its box's and
    // at least that of the polygon of its corners farthest in eight directions (inscribed in
    // the outline, they being on it in turn): an exact test that spares the tiling check on
    // most meshes that fail it.
    let may_tile = |m: usize| {
        let b = boxes[m];
        let box_area = (b[2] - b[0]) as i128 * (b[3] - b[1]) as i128;
        let ring: Vec<[i64; 2]> = extremes[m].iter().flatten().map(|&(_, q)| q).collect();
        let inscribed = twice_ring_area(&ring).abs();
        // Then (exact, and cheaper than matching every edge) the area of the corners' convex
        // hull, which the outline would be.
        (inscribed..=2 * box_area).contains(&twice_areas[m])
            && twice_hull_area(screen, &polys_of[m]) == twice_areas[m]
    };
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
            !polys_of[m].is_empty()
                && !crowded[m]
                && may_tile(m)
                && tiles_convex_region_once(screen, &polys_of[m])
        })
        .collect();
    WholeMeshes {
        placed,
        on_screen: order.len(),
        apart: order.iter().filter(|&&m| !crowded[m]).count(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn crowding(depth_median: f64, depth_mean: f64, back_share: f64, sliver: f64) -> Crowding {
        Crowding {
            pieces: 1000,
            depth_median,
            depth_mean,
            back_share,
            sliver,
        }
    }

    #[test]
    fn each_orderer_is_chosen_for_its_kind_of_scene() {
        let chose = |c: Crowding| c.choose().0;
        // A soup: crowded boxes, half seen from the back.
        assert_eq!(chose(crowding(90.0, 100.0, 0.5, 3.0)), Orderer::Warnock);
        // Culled gears: as crowded, nothing seen from the back, slivers: a tree, not subdivided.
        assert_eq!(chose(crowding(11.2, 13.5, 0.0, 13.4)), Orderer::Bsp);
        // An open sphere's poles seen edge-on: slivers, many seen from the back.
        assert_eq!(chose(crowding(0.35, 0.38, 0.42, 28.9)), Orderer::Bsp);
        // A housing over small parts (counter).
        assert_eq!(
            chose(crowding(0.05, 3.4, 0.0, 3.3)),
            Orderer::WeilerAtherton
        );
        // An open scan seen from both sides (bunny), and a soup too sparse to subdivide.
        assert_eq!(chose(crowding(3.0, 3.1, 0.3, 2.5)), Orderer::CoverageMap);
        assert_eq!(chose(crowding(2.0, 2.2, 0.5, 3.0)), Orderer::CoverageMap);
        // A culled closed mesh (dragon): nothing seen from the back.
        assert_eq!(chose(crowding(1.2, 1.3, 0.0, 2.6)), Orderer::Bsp);
        // The thresholds themselves.
        assert_eq!(chose(crowding(1.0, 2.4, 0.1, 2.5)), Orderer::CoverageMap);
        assert_eq!(chose(crowding(1.0, 2.5, 0.1, 2.5)), Orderer::WeilerAtherton);
        assert_eq!(chose(crowding(2.0, 2.9, 0.1, 2.5)), Orderer::CoverageMap);
        assert_eq!(chose(crowding(2.0, 2.5, 0.1, 8.0)), Orderer::Bsp);
        assert_eq!(chose(crowding(2.0, 2.5, 0.1, 7.9)), Orderer::CoverageMap);
    }

    /// Large squares over many small triangles: clipping is chosen and given up (tilted squares,
    /// [`tilted_squares`]: more levels than [`DEEPEST_CLIP_RECURSION`], each handing all the
    /// rest down). `left` more small triangles left of the squares (a strip of their own, solved
    /// by clipping before the others give up).
    fn squares_over_triangles(left: i64) -> ScreenScene {
        squares_over_triangles_mirrored(left, false)
    }

    /// [`squares_over_triangles`], mirrored (x to -x) when `mirrored`.
    fn squares_over_triangles_mirrored(left: i64, mirrored: bool) -> ScreenScene {
        use crate::exact::GridPoint;
        use crate::visibility::{screen_of_polygons, tilted_squares};
        let planks = DEEPEST_CLIP_RECURSION as i64 + 20;
        const W: i64 = 1 << 30;
        let squares = tilted_squares(planks, W);
        let z = 100 * planks;
        let triangle = move |x: i64| {
            vec![
                GridPoint::new(x, 0, z),
                GridPoint::new(x + 1000, 0, z),
                GridPoint::new(x, 1000, z),
            ]
        };
        // Small triangles far behind the squares, in a row along the bottom.
        let small = (0..1000).map(move |k| triangle(k * (W / 1000)));
        let apart = (1..=left).map(move |k| triangle(-k * (W / 1000)));
        let mirror = move |mut p: Vec<GridPoint>| {
            if mirrored {
                // Counter-clockwise still.
                p.iter_mut().for_each(|q| q.x = -q.x);
                p.reverse();
            }
            p
        };
        screen_of_polygons(squares.chain(small).chain(apart).map(mirror))
    }

    /// Clipping given up: the map finishes the job, and the visible set is the map's.
    #[test]
    fn clipping_given_up_hands_every_piece_to_the_map() {
        let screen = squares_over_triangles(0);
        let auto = Auto.visible_set(&screen, &|_| false, None);
        assert_eq!(auto.stats["chosen"], "coverage after weiler-atherton");
        let map = CoverageMap.visible_set(&screen, &|_| false, None);
        assert!(auto.symmetric_difference(&map).is_empty());
        // What shows: the first square left of the middle, the last one right of it.
        let mut shown: Vec<u32> = auto.pieces.iter().map(|p| p.poly).collect();
        shown.sort_unstable();
        shown.dedup();
        let planks = DEEPEST_CLIP_RECURSION as u32 + 20;
        assert_eq!(shown, [0, planks - 1]);
    }

    /// After giving up, the map gets the very pieces in the very strips it would have got as
    /// the choice, however far the strips got: handed back as they were given (one strip; or
    /// strips not started, or copies of those that ran), or all made again when one was solved
    /// before another gave up (the strip of triangles left of the squares, first on one
    /// thread). So its counters are the map's own, on any number of threads.
    #[test]
    fn clipping_given_up_hands_the_map_the_pieces_it_would_have_chosen() {
        use crate::visibility::strips::with_strip_size;
        let counters = [
            "pieces",
            "overlap_tests",
            "replaced",
            "strips",
            "visible_pieces",
        ];
        for (left, mirrored, size) in [(0, false, usize::MAX), (300, false, 150), (0, true, 150)] {
            let screen = squares_over_triangles_mirrored(left, mirrored);
            for threads in [1, 2] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .expect("a pool");
                let (auto, map) = pool.install(|| {
                    with_strip_size(size, || {
                        let auto = Auto.visible_set(&screen, &|_| false, None);
                        (auto, CoverageMap.visible_set(&screen, &|_| false, None))
                    })
                });
                assert_eq!(auto.stats["chosen"], "coverage after weiler-atherton");
                for k in counters {
                    assert_eq!(
                        auto.stats[k], map.stats[k],
                        "{k}: {left} left, {threads} threads"
                    );
                }
                assert_eq!(auto.pieces, map.pieces);
            }
        }
    }

    #[test]
    fn no_pieces_measure_zero() {
        let screen = ScreenScene::default();
        assert_eq!(Crowding::of(&screen, &[]), Crowding::default());
    }
}
