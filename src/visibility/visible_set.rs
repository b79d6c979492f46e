//! The product of every object-space strategy: what the camera sees, exactly, before anything is
//! rounded, merged or coloured (that is [`crate::draw`]'s job).
//!
//! Invariants of a [`VisibleSet`] made by an exact strategy ([`crate::methods::Method::exact`]):
//! - [`VisibleSet::pieces`] are convex, have pairwise disjoint interiors, each lies in the
//!   projection of its own screen polygon, and at every point of a piece no opaque polygon is
//!   nearer. Coplanar overlaps go to the larger face id, then the later polygon: the z-buffer's
//!   tie rule, so the result never depends on input order. Their union is everything the
//!   opaque faces show.
//! - [`VisibleSet::layered`] are drawn over the pieces, back to front: the parts of translucent
//!   faces that no opaque face hides, in an exact depth order, so each blends over exactly what
//!   lies behind it.
//!
//! Every strategy, exact or not, keeps `pieces` pairwise disjoint: the drawing stage relies on it
//! (it may reorder their regions). An approximate strategy (the painter) keeps the shape of the
//! result, not its guarantees: its fragments are whole polygons in `layered`, in its own order,
//! possibly overlapping.
//!
//! Where a boundary comes from: every side of a piece is a kernel [`Line`] (never rounded here;
//! vertices are implicit, where two lines cross) with its [`Boundary`]: a side of a screen
//! polygon's outline (`ScreenScene::sides` then tells a face edge, and which, from a clip by the
//! near or far plane), a diagonal of a non-convex face's decomposition (inside the face), the
//! meeting of two polygons' support planes (an intersection line, or where one face passes
//! behind another: the cut is stored as the two polygons, whose planes are the table), or a
//! screen line the BSP chose (no feature of the scene). A boundary names a line, not a segment:
//! pieces inherit the lines of what they were cut by, so a piece side may run past the side it
//! names, and two pieces of one face may abut along an occluder's line. A hidden-line drawing
//! reads the boundaries of the piece sides that separate different faces (or a face from the
//! background). Faces that the loader triangulated (non-planar input polygons) keep their input
//! id: a side between two of them is no edge of the input.
//!
//! [`Boundary`]: crate::exact::polygon::Boundary

use super::coverage::subtract_all;
use super::live::{Live, bounds};
use crate::exact::Samples;
use crate::exact::polygon::Piece;
use crate::exact::predicates::line_side;
use crate::project::ScreenScene;
use std::cmp::Ordering;

/// A strategy's counters (pieces, splits, fallbacks, ...), keys sorted; written into the JSON
/// output as they are, so they hold no timings.
pub type Stats = serde_json::Map<String, serde_json::Value>;

/// Adds counters to a strategy's stats.
pub(crate) fn put_counts<'k>(
    stats: &mut Stats,
    counts: impl IntoIterator<Item = (&'k str, usize)>,
) {
    for (k, v) in counts {
        stats.insert(k.into(), v.into());
    }
}

/// Something drawn over the visible pieces.
#[derive(Clone, Debug, PartialEq)]
pub enum Fragment {
    /// An exact convex part of a translucent face (boxed: a painter's list of polygons stays
    /// small).
    Piece(Box<Piece>),
    /// A whole screen polygon (index into `ScreenScene::polys`): the painter's unit.
    Polygon(u32),
}

impl Fragment {
    /// The screen polygon it belongs to.
    pub fn poly(&self) -> u32 {
        match self {
            Fragment::Piece(p) => p.poly,
            Fragment::Polygon(k) => *k,
        }
    }
}

/// What the camera sees. See the module docs for the invariants.
#[derive(Clone, Debug, Default)]
pub struct VisibleSet {
    /// The visible pieces of the opaque faces: convex, disjoint, exact.
    pub pieces: Vec<Piece>,
    /// Drawn over `pieces`, back to front.
    pub layered: Vec<Fragment>,
    /// The strategy's counters.
    pub stats: Stats,
}

impl VisibleSet {
    /// A visible set of opaque pieces only.
    pub fn of_pieces(pieces: Vec<Piece>) -> Self {
        VisibleSet {
            pieces,
            ..VisibleSet::default()
        }
    }

    /// An exact strategy's result: `pieces` and `layered` with the strategy's own counters
    /// `stats`, plus the ones every exact strategy reports: "polygons", "visible_pieces", "drawn_pieces_per_polygon" (pieces and layered fragments, per polygon)
    /// and "exact_fallbacks" (kernel fallbacks since the count was `fallbacks_before`).
    pub(crate) fn exact(
        screen: &ScreenScene,
        pieces: Vec<Piece>,
        layered: Vec<Fragment>,
        mut stats: Stats,
        fallbacks_before: u64,
    ) -> Self {
        let polygons = screen.polys.len();
        let drawn = (pieces.len() + layered.len()) as f64 / polygons.max(1) as f64;
        let fallbacks = crate::exact::predicates::fallback_count() - fallbacks_before;
        for (k, v) in [
            ("polygons", polygons.into()),
            ("visible_pieces", pieces.len().into()),
            ("drawn_pieces_per_polygon", drawn.into()),
            ("exact_fallbacks", fallbacks.into()),
        ] {
            stats.insert(k.into(), v);
        }
        VisibleSet {
            pieces,
            layered,
            stats,
        }
    }

    /// The face id of the [`Self::pieces`] at every pixel centre (row-major, row 0 at the top),
    /// decided exactly: a sample on a boundary between pieces goes to the earlier piece.
    pub fn face_ids(&self, screen: &ScreenScene) -> Vec<Option<u32>> {
        let (w, h) = (screen.width as i64, screen.height as i64);
        let s = Samples::new(screen.width, screen.height);
        let mut ids: Vec<Option<u32>> = vec![None; (w * h) as usize];
        for piece in &self.pieces {
            let v = piece.vertices_f64();
            let (mut c0, mut c1, mut r0, mut r1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
            for [x, y] in &v {
                c0 = c0.min(s.col_of(*x));
                c1 = c1.max(s.col_of(*x));
                r0 = r0.min(s.row_of(*y));
                r1 = r1.max(s.row_of(*y));
            }
            let i0 = ((c0 - 1.0).floor() as i64).clamp(0, w);
            let i1 = ((c1 + 1.0).ceil() as i64).clamp(0, w);
            let j0 = ((r0 - 1.0).floor() as i64).clamp(0, h);
            let j1 = ((r1 + 1.0).ceil() as i64).clamp(0, h);
            let id = screen.polys[piece.poly as usize].id;
            for j in j0..j1 {
                let row = s.row_line(j);
                for i in i0..i1 {
                    let k = (j * w + i) as usize;
                    if ids[k].is_some() {
                        continue;
                    }
                    let col = s.column_line(i);
                    let inside = piece
                        .lines()
                        .all(|l| line_side([&col, &row], l) != Some(Ordering::Less));
                    if inside {
                        ids[k] = Some(id);
                    }
                }
            }
        }
        ids
    }

    /// The exact symmetric difference of two visible sets of one screen scene: the parts of
    /// each set's pieces that the other set's pieces of the same polygon do not cover, opaque
    /// pieces against opaque pieces and layered exact pieces against layered exact pieces
    /// (their order is not compared). Empty exactly when the two show every polygon in the same
    /// places; each part has positive area. Whole-polygon fragments (the painter's) are not
    /// compared.
    pub fn symmetric_difference(&self, other: &VisibleSet) -> Vec<Piece> {
        let layered = |v: &VisibleSet| -> Vec<Piece> {
            v.layered
                .iter()
                .filter_map(|f| match f {
                    Fragment::Piece(p) => Some((**p).clone()),
                    Fragment::Polygon(_) => None,
                })
                .collect()
        };
        let (la, lb) = (layered(self), layered(other));
        let mut out = uncovered(&self.pieces, &other.pieces);
        out.extend(uncovered(&other.pieces, &self.pieces));
        out.extend(uncovered(&la, &lb));
        out.extend(uncovered(&lb, &la));
        out
    }

    /// The pieces' vertices in pixel coordinates (y down), rounded once: for drawing.
    pub fn pixel_rings(&self, screen: &ScreenScene) -> Vec<(u32, Vec<[f64; 2]>)> {
        let s = Samples::new(screen.width, screen.height);
        self.pieces
            .iter()
            .map(|p| {
                let ring = p
                    .vertices_f64()
                    .into_iter()
                    .map(|[x, y]| [s.col_of(x), s.row_of(y)])
                    .collect();
                (p.poly, ring)
            })
            .collect()
    }
}

/// The parts of `pieces` that no piece of `cover` of the same polygon covers, exactly.
fn uncovered(pieces: &[Piece], cover: &[Piece]) -> Vec<Piece> {
    let boxes: Vec<[f64; 4]> = cover.iter().map(bounds).collect();
    let mut index = Live::over(&boxes, boxes.len());
    for (p, b) in cover.iter().zip(&boxes) {
        index.add(p.clone(), *b);
    }
    let mut out = Vec::new();
    for piece in pieces {
        let near = index.near(&bounds(piece));
        let same_polygon = near
            .iter()
            .map(|&v| index.get(v).expect("never removed"))
            .filter(|c| c.poly == piece.poly);
        out.extend(subtract_all(piece.clone(), same_polygon));
    }
    out
}
