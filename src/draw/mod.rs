//! The drawing stage: a [`VisibleSet`] becomes a [`Drawing`] (filled regions in pixel
//! coordinates, back to front), the same way whichever strategy computed it.
//!
//! Steps: each exact vertex of the visible pieces is named and rounded to pixels once
//! ([`regions::shared_vertices`], so abutting pieces share their rounded vertices); the pieces
//! of a group (one face, or with [`DrawOptions::merge_surfaces`] one surface of coplanar faces
//! of one paint, [`regions::surfaces`]) are merged into regions with holes ([`mod@regions`]); the
//! layered fragments follow, one item per run of one polygon, so a viewer never blends their
//! common edges twice; with [`DrawOptions::seams`], the boundaries that opaque regions share
//! are collected as strokes under the fills ([`seams`]), clipped to the outline of the opaque
//! regions.
//!
//! Invariant: the output rounding (one f64 rounding per exact vertex, a function of the exact
//! point) is the only approximation between the visible set and the drawing, and the drawing
//! depends only on the visible point set, not on how a strategy cut it into pieces: regions,
//! outline and seam segments are merged exactly into maximal straight runs between true
//! corners, so two strategies with the same visible set draw the same bytes. Items keep the
//! visible set's order (opaque regions, then the layered fragments) and the drawing is in
//! canonical form ([`canonicalize`]): rings start at a defined vertex with a defined
//! orientation, disjoint opaque regions are sorted by face.

pub mod regions;
pub mod seams;

use crate::camera::Camera;
use crate::exact::Samples;
use crate::exact::polygon::Piece;
use crate::output::canonical::canonicalize;
use crate::output::drawing::{DrawItem, Drawing, Rings, SeamStroke, Seams};
use crate::paint::{Fill, Paint, to_u8};
use crate::progress::Report;
use crate::project::ScreenScene;
use crate::scene::Scene;
use crate::visibility::{Fragment, Stats, Strategy, VisibleSet, pixel_ring};
use regions::{Vertices, outline, regions, regions_into, shared_vertices, surfaces};
use rustc_hash::FxHashMap;
use std::cmp::Ordering;

/// How a visible set is drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DrawOptions {
    /// Draw abutting visible regions of coplanar faces with the same colour and material as one
    /// region (listing every face it covers), so that viewers' anti-aliasing shows no cracks
    /// inside a surface (a CAD face triangulated in the file). Off: one region set per face, as
    /// per-face output (JSON) needs.
    pub merge_surfaces: bool,
    /// Also find the boundaries that two opaque regions share ([`Seams`]), painted under the
    /// fills of vector output so that anti-aliasing shows no seams between regions.
    pub seams: bool,
    /// The drawing's background, `None` for transparent.
    pub background: Option<[f64; 3]>,
}

impl DrawOptions {
    /// For pictures (SVG, PNG): surfaces merged, seams filled.
    pub fn picture() -> Self {
        DrawOptions {
            merge_surfaces: true,
            seams: true,
            background: None,
        }
    }

    /// For per-face output (JSON, face ids): one region set per face, no seams.
    pub fn per_face() -> Self {
        DrawOptions::default()
    }

    /// The same, on the background `fill` requires: black under `Fill::Id` (the id contract:
    /// black is no face), `background` otherwise.
    pub fn with_background(self, fill: Fill, background: Option<[f64; 3]>) -> Self {
        DrawOptions {
            background: match fill {
                Fill::Id => Some([0.0; 3]),
                Fill::Shade => background,
            },
            ..self
        }
    }
}

/// A strategy's drawing and its counters.
#[derive(Clone, Debug, PartialEq)]
pub struct Picture {
    /// The drawing.
    pub drawing: Drawing,
    /// The strategy's counters.
    pub stats: Stats,
}

/// The whole object-space path in one call: paints of `fill`, `strategy`'s visible set (the
/// faces whose paint is not opaque layered), its drawing with `options` (and the background
/// `fill` requires, [`DrawOptions::with_background`]). Reports the strategy's stages and
/// "regions".
pub fn picture(
    strategy: &dyn Strategy,
    scene: &Scene,
    screen: &ScreenScene,
    camera: &Camera,
    fill: Fill,
    options: DrawOptions,
    report: Option<Report>,
) -> Picture {
    let paints = crate::paint::screen_paints(scene, screen, camera, fill);
    let visible = strategy.visible_set(screen, &|k| !paints[k as usize].is_opaque(), report);
    let options = options.with_background(fill, options.background);
    Picture {
        drawing: draw(scene, screen, camera, &paints, &visible, options, report),
        stats: visible.stats,
    }
}

/// The drawing of `visible`, a visible set of `screen` (the projection of `scene` by `camera`);
/// `paints[k]` fills `screen.polys[k]` ([`crate::paint::screen_paints`]). Reports stage
/// "regions".
pub fn draw(
    scene: &Scene,
    screen: &ScreenScene,
    camera: &Camera,
    paints: &[Paint],
    visible: &VisibleSet,
    options: DrawOptions,
    report: Option<Report>,
) -> Drawing {
    assert_eq!(paints.len(), screen.polys.len(), "one paint per polygon");
    let opaque = &visible.pieces;
    // The regions of a group are drawn as one item: one face, or (merging) one surface of
    // coplanar faces of one paint. One paint is what the output shows: the 8-bit colour,
    // material and opacity.
    let samples = Samples::new(screen.width, screen.height);
    // The groups, and one rounding per exact vertex (for the regions, the outline and the seams
    // alike): independent, so side by side.
    let (group, vertices): (Vec<u32>, Vertices) = rayon::join(
        || {
            if options.merge_surfaces {
                surfaces(scene, screen, camera.eye, |i| {
                    let p = paints[i];
                    (
                        to_u8(p.color),
                        scene.faces[screen.polys[i].face as usize].material,
                        p.opacity.to_bits(),
                    )
                })
            } else {
                screen.polys.iter().map(|p| p.id).collect()
            }
        },
        || shared_vertices(opaque, &samples),
    );
    let item = |poly: u32, faces: &[u32], rings: Rings| {
        let p = paints[poly as usize];
        DrawItem {
            face: faces[0],
            merged: faces[1..].to_vec(),
            material: scene.faces[screen.polys[poly as usize].face as usize].material,
            rings,
            color: p.color,
            opacity: p.opacity,
        }
    };
    let group_of = |p: &Piece| group[p.poly as usize];
    // The maps that named the vertices are gone; the regions are the drawing's peak.
    crate::memory::give_back_after(opaque.len());
    // The regions, the seam strokes and the outline read the same pieces and vertices, each on
    // its own: on all cores.
    let seams = options.seams && !opaque.is_empty();
    let color = |p: &Piece| paints[p.poly as usize].color;
    let (mut items, (strokes, outline)) = rayon::join(
        || {
            regions_into(opaque, &vertices, screen, group_of, report, |r| {
                item(opaque[r.piece].poly, &r.faces, r.rings)
            })
        },
        || {
            rayon::join(
                || {
                    let strokes = seams.then(|| seam_strokes(opaque, &vertices, &group_of, &color));
                    // The shared edges' room, back while the regions still grow.
                    crate::memory::give_back_after(opaque.len());
                    strokes
                },
                || seams.then(|| outline(opaque, &vertices)),
            )
        },
    );
    // Consecutive exact pieces of one face (a face may be several polygons: `project` splits
    // a face that is not planar on the grid) are one item, their union; a painter's whole
    // polygons are one item each (they may overlap).
    let face_id = |f: &Fragment| screen.polys[f.poly() as usize].id;
    let same_item = |a: &Fragment, b: &Fragment| match (a, b) {
        (Fragment::Piece(_), Fragment::Piece(_)) => face_id(a) == face_id(b),
        _ => a.poly() == b.poly(),
    };
    for run in visible.layered.chunk_by(same_item) {
        let poly = run[0].poly();
        let pieces: Vec<Piece> = run
            .iter()
            .filter_map(|f| match f {
                Fragment::Piece(p) => Some((**p).clone()),
                Fragment::Polygon(_) => None,
            })
            .collect();
        let mut rings: Rings = regions(&pieces, screen, |_| ())
            .into_iter()
            .flat_map(|r| r.rings)
            .collect();
        if run.iter().any(|f| matches!(f, Fragment::Polygon(_))) {
            let p = &screen.polys[poly as usize];
            rings.push(pixel_ring(&samples, &screen.corners(p)));
        }
        items.push(item(poly, &[screen.polys[poly as usize].id], rings));
    }
    let seams = match (strokes, outline) {
        (Some(strokes), Some(outline)) => Seams { strokes, outline },
        _ => Seams::default(),
    };
    // The region items partition the opaque visible pieces; every layered fragment of an exact
    // strategy is translucent. A painter layers opaque polygons that overlap: no promise.
    let opaque_disjoint = visible
        .layered
        .iter()
        .all(|f| !paints[f.poly() as usize].is_opaque());
    let mut drawing = Drawing {
        width: screen.width,
        height: screen.height,
        background: options.background,
        items,
        seams,
        opaque_disjoint,
    };
    canonicalize(&mut drawing);
    drawing
}

/// The boundaries that opaque pieces of different groups share, stroked in the darker of the
/// two colours (8-bit, then exactly), one [`SeamStroke`] per 8-bit colour (in the least exact
/// colour its edges have) in colour order, each segment a maximal straight run of its colour
/// ([`seams::straight_runs`]).
fn seam_strokes(
    pieces: &[Piece],
    vertices: &Vertices,
    group: &dyn Fn(&Piece) -> u32,
    color: &dyn Fn(&Piece) -> [f64; 3],
) -> Vec<SeamStroke> {
    use rayon::prelude::*;
    // Groups per piece first: read per edge, each cost a cache miss into the pieces.
    let piece_group: Vec<u32> = pieces.iter().map(group).collect();
    let shared = seams::shared_edges(pieces, vertices, |i| piece_group[i]);
    drop(piece_group);
    // Colours by their 8-bit value (its sum, then its channels), then exactly: the darker of
    // an edge's two, and the least of a stroke's, whatever the order the pieces come in.
    let exactly = |x: &[f64; 3], y: &[f64; 3]| {
        let mut by_channel = x.iter().zip(y.iter()).map(|(a, b)| a.total_cmp(b));
        by_channel.find(|o| o.is_ne()).unwrap_or(Ordering::Equal)
    };
    let darker = |x: &[f64; 3], y: &[f64; 3]| {
        let key = |c: &[f64; 3]| {
            let u = to_u8(*c);
            (u.iter().map(|&v| v as u32).sum::<u32>(), u)
        };
        key(x).cmp(&key(y)).then_with(|| exactly(x, y))
    };
    // Per edge, the colour it is stroked in. Colours per piece first: read per edge, they
    // cost two cache misses into the pieces each. (Not kept per edge: 24 bytes an edge beside
    // the regions, the drawing's peak.)
    let piece_color: Vec<[f64; 3]> = pieces.iter().map(color).collect();
    let stroked = |e: &seams::SharedEdge| {
        let [ca, cb] = e.pieces.map(|i| piece_color[i as usize]);
        if darker(&cb, &ca).is_lt() { cb } else { ca }
    };
    // Per 8-bit colour: the least exact colour its edges have (faces of one 8-bit colour may
    // differ below it), found as the edges are read in edge order (read again per colour,
    // they cost a cache miss an edge), and its number of edges.
    let mut by_rgb: FxHashMap<u32, ([f64; 3], usize)> = FxHashMap::default();
    let rgb_of: Vec<u32> = (shared.iter())
        .map(|edge| {
            let c = stroked(edge);
            let [r, g, b] = to_u8(c).map(u32::from);
            let rgb = r << 16 | g << 8 | b;
            let (least, count) = by_rgb.entry(rgb).or_insert((c, 0));
            if exactly(&c, least).is_lt() {
                *least = c;
            }
            *count += 1;
            rgb
        })
        .collect();
    let mut colors: Vec<(u32, [f64; 3], usize)> = (by_rgb.into_iter())
        .map(|(rgb, (least, count))| (rgb, least, count))
        .collect();
    colors.sort_unstable_by_key(|&(rgb, ..)| rgb);
    // The edges by colour, each colour's in edge order, read once in edge order
    // ([`seams::StrokeSegment`]) and placed by a counting sort: each stroke's segments are
    // one stretch of memory. Per colour, its stretch and where its next segment goes.
    let mut stretches = Vec::with_capacity(colors.len());
    let mut next: FxHashMap<u32, usize> = FxHashMap::default();
    for &(rgb, _, count) in &colors {
        let start = stretches
            .last()
            .map_or(0, |s: &std::ops::Range<usize>| s.end);
        stretches.push(start..start + count);
        next.insert(rgb, start);
    }
    let mut segments = vec![seams::StrokeSegment::default(); shared.len()];
    for (e, (edge, rgb)) in shared.iter().zip(rgb_of).enumerate() {
        let at = next.get_mut(&rgb).expect("every colour has its stretch");
        segments[*at] = edge.segment(e, vertices);
        *at += 1;
    }
    // Colour by colour on all cores (a mesh shaded flat has hundreds), in colour order.
    (colors.into_par_iter().zip(stretches))
        .map(|((_, color, _), stretch)| SeamStroke {
            color,
            segments: seams::straight_runs(&segments[stretch], &shared, pieces, vertices),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::regions::tests::{grid_piece, grid_samples};
    use super::*;

    /// Three squares in a row, A | B | C, each its own group: A and B of one 8-bit colour a
    /// little apart below it, C lighter. Both seams are stroked in that 8-bit colour, in the
    /// smaller of A's and B's exact colours, whichever order the pieces come in (an edge
    /// between equal 8-bit colours once took its first piece's).
    #[test]
    fn a_seam_stroke_takes_the_least_exact_colour_whatever_the_piece_order() {
        let square =
            |poly: u32, x: i64| grid_piece(poly, &[[x, 0], [x + 4, 0], [x + 4, 4], [x, 4]]);
        let exact = [[0.5, 0.5, 0.5], [0.5 + 1e-6, 0.5, 0.5], [0.9, 0.9, 0.9]];
        assert_eq!(to_u8(exact[0]), to_u8(exact[1]));
        for order in [[0, 1, 2], [2, 1, 0], [1, 0, 2], [1, 2, 0]] {
            let pieces: Vec<Piece> = order.iter().map(|&p| square(p, 4 * p as i64)).collect();
            let vertices = shared_vertices(&pieces, &grid_samples());
            let strokes =
                seam_strokes(&pieces, &vertices, &|p| p.poly, &|p| exact[p.poly as usize]);
            assert_eq!(strokes.len(), 1, "{order:?}");
            assert_eq!(strokes[0].color, exact[0], "{order:?}");
            assert_eq!(strokes[0].segments.len(), 2, "{order:?}");
        }
    }
}
