//! Object-space visibility: strategies that compute a [`VisibleSet`] from a projected scene,
//! behind one trait, so the CLI, the tests and the benchmarks run any of them alike and compare
//! the results. What the set looks like on a page is [`crate::draw`]'s job, done once for all.
//!
//! Every exact strategy starts from the convex pieces of the screen polygons
//! ([`initial_pieces`]) and keeps the [`visible_set`] invariants; an approximate one (the
//! [`Painter`]) keeps their shape and is measured against the exact ones.
//!
//! | strategy | name | idea |
//! |---|---|---|
//! | [`Auto`] | `auto` | looks at the scene, then runs only the stages it needs (the coverage map on what overlaps) |
//! | [`CoverageMap`] | `coverage` | pieces into a depth-aware coverage map, overlaps split where their planes meet |
//! | [`BspTree`] | `bsp` | a 3D BSP of the pieces walked front to back into the coverage map |
//! | [`Newell`] | `newell` | Newell's depth sort with cuts, then exact overpainting along its list |
//! | [`WeilerAtherton`] | `weiler-atherton` | the nearest polygon clips the rest into inside and outside lists; inside and behind is hidden, inside and in front recurses |
//! | [`WarnockExact`] | `warnock-exact` | a quadtree of screen areas, each settled where one piece is in front of the rest there, leaves clipped exactly |
//! | [`Painter`] | `painter` | whole faces sorted by farthest depth (approximate) |
//!
//! Adding a strategy: one file implementing [`Strategy`], listed once in the method registry
//! ([`crate::methods`]).

pub mod auto;
pub mod bsp;
pub mod bsp_tree;
pub(crate) mod clear;
pub mod coverage;
pub mod coverage_map;
pub(crate) mod covered;
pub mod depth;
pub(crate) mod grid;
pub(crate) mod live;
pub mod newell;
pub(crate) mod occlusion;
pub mod painter;
pub(crate) mod point_pairs;
pub mod strips;
pub mod tiling;
pub mod visible_set;
pub mod warnock_exact;
pub mod weiler_atherton;

pub use auto::Auto;
pub use bsp_tree::BspTree;
pub use coverage_map::CoverageMap;
pub use newell::Newell;
pub use painter::Painter;
pub use visible_set::{Fragment, Stats, VisibleSet};
pub use warnock_exact::WarnockExact;
pub use weiler_atherton::WeilerAtherton;

use crate::exact::polygon::{
    Boundary, CornerLines, CornerOutline, EdgeLine, Piece, convex_piece_indices, edge_lines,
    push_edge_lines,
};
use crate::exact::{GridPoint, Samples};
use crate::progress::Report;
use crate::project::ScreenScene;
use smallvec::SmallVec;

/// An object-space visibility strategy. Its name and whether it is exact (keeps every
/// [`visible_set`] invariant) are in the method registry ([`crate::methods`]).
pub trait Strategy: Send + Sync {
    /// What the camera sees of `screen`. `translucent(k)`: does `screen.polys[k]` blend over what
    /// lies behind it (then it is layered, not hidden)? `report` gets the progress of the long
    /// stages (see [`crate::progress`]).
    fn visible_set(
        &self,
        screen: &ScreenScene,
        translucent: &dyn Fn(u32) -> bool,
        report: Option<Report>,
    ) -> VisibleSet;
}

/// The visible set of a strategy that resolves opaque pieces only: `resolve` gets the opaque
/// pieces (of one strip when `in_strips`: [`strips`], all cores on a large scene) and returns
/// the visible ones with its counters, which `put` writes once summed; translucent polygons are layered over
/// them as the coverage map layers them (a BSP of their pieces, less what the opaque set hides).
fn opaque_then_layered<C: strips::Counters>(
    screen: &ScreenScene,
    translucent: &dyn Fn(u32) -> bool,
    report: Option<Report>,
    in_strips: bool,
    resolve: impl Fn(Vec<Piece>, Option<Report>) -> (Vec<Piece>, C) + Sync,
    put: impl FnOnce(C, &mut Stats),
) -> VisibleSet {
    let fallbacks = crate::exact::predicates::fallback_count();
    let layered = translucent_polygons(screen, translucent);
    let (see_through, opaque): (Vec<Piece>, Vec<Piece>) = initial_pieces(screen)
        .into_iter()
        .partition(|p| layered && translucent(p.poly));
    let strips = match in_strips {
        true => strips::Strips::for_pieces(&opaque),
        false => strips::Strips::none(),
    };
    let strip_count = strips.count();
    let (visible, counters) = strips::solve_strips(strips.cut(opaque), report, |strip, report| {
        Ok(resolve(strip, report))
    })
    .expect("resolve never gives up");
    let mut stats = Stats::new();
    put(counters, &mut stats);
    stats.insert("strips".into(), strip_count.into());
    stats.insert("translucent_painter_order".into(), layered.into());
    let (pieces, layered) = if layered {
        let mut coverage = coverage::Coverage::of_visible(screen, visible);
        let (parts, bsp) = bsp::translucent_layer(screen, &mut coverage, see_through, report);
        stats.insert("translucent_fragments".into(), bsp.fragments.into());
        (coverage.into_pieces(), parts)
    } else {
        (visible, Vec::new())
    };
    VisibleSet::exact(screen, pieces, layered, stats, fallbacks)
}

/// Is any polygon of `screen` translucent?
fn translucent_polygons(screen: &ScreenScene, translucent: &dyn Fn(u32) -> bool) -> bool {
    (0..screen.polys.len() as u32).any(translucent)
}

/// The convex pieces of every screen polygon, counter-clockwise (y up); non-convex polygons are
/// decomposed exactly. Each line's boundary is the polygon's outline side it runs along, or a
/// diagonal of the decomposition.
pub fn initial_pieces(screen: &ScreenScene) -> Vec<Piece> {
    let all: Vec<u32> = (0..screen.polys.len() as u32).collect();
    pieces_of(screen, &all)
}

/// The convex pieces of the polygons `polys` (increasing; [`initial_pieces`]), in that order.
pub(crate) fn pieces_of(screen: &ScreenScene, polys: &[u32]) -> Vec<Piece> {
    use rayon::prelude::*;
    // Polygon by polygon on all cores. A triangle is one piece, made straight into its place
    // in one list; rayon collects the other polygons' any number of pieces per thread, then
    // copies them into one list: two whole copies at once, which on a million triangles was
    // the visible set's peak (434-492 MB where the pieces and their planes are 230 MB).
    let (triangles, others): (Vec<u32>, Vec<u32>) =
        (polys.iter()).partition(|&&k| screen.polys[k as usize].len == 3);
    let whole: Vec<Piece> = (triangles.par_iter().with_min_len(4096))
        .map(|&k| {
            let mut pieces = pieces_of_polygon(screen, k).into_iter();
            let piece = pieces
                .next()
                .expect("a triangle on screen is one convex piece");
            debug_assert!(pieces.next().is_none());
            piece
        })
        .collect();
    let parts: Vec<Piece> = (others.par_iter().with_min_len(4096))
        .flat_map_iter(|&k| pieces_of_polygon(screen, k))
        .collect();
    occlusion::merged(whole, parts)
}

/// The convex pieces of screen polygon `poly` ([`initial_pieces`]).
fn pieces_of_polygon(screen: &ScreenScene, poly: u32) -> SmallVec<[Piece; 1]> {
    let p = &screen.polys[poly as usize];
    let pts = &screen.corners(p);
    let plane = screen.plane(p);
    let n = pts.len();
    // Back faces seen from behind run clockwise on screen: walk them backwards, the k-th
    // side of the walk running along outline side n - 2 - k (mod n) the other way.
    let reversed = crate::exact::twice_signed_area(pts).is_le();
    let ccw: SmallVec<[GridPoint; 4]> = if reversed {
        pts.iter().rev().copied().collect()
    } else {
        SmallVec::from_slice(pts)
    };
    let outline = |k: usize| Boundary::Outline {
        poly,
        side: if reversed { (2 * n - 2 - k) % n } else { k } as u32,
    };
    let pieces = convex_piece_indices(&ccw);
    if let [whole] = &pieces[..]
        && whole.len() == n
    {
        // Convex (the common case): the polygon itself, every side an outline side.
        return smallvec::smallvec![Piece::from_convex(poly, plane, &ccw, outline)];
    }
    pieces
        .iter()
        .map(|piece| {
            let m = piece.len();
            let corners: Vec<GridPoint> = piece.iter().map(|&v| ccw[v]).collect();
            let side = |k: usize| {
                let (a, b) = (piece[k], piece[(k + 1) % m]);
                if b == (a + 1) % n {
                    outline(a)
                } else {
                    Boundary::Diagonal { poly }
                }
            };
            Piece::from_convex(poly, plane, &corners, side)
        })
        .collect()
}

/// [`separated`](crate::exact::polygon::separated) on a screen: pieces of triangles whose
/// corners are apart ([`ScreenScene::triangle_xy`]) are apart, with no test of their own lines.
/// Pieces cut off the grid (by strips, splits, front pieces) mostly meet their mesh neighbours'
/// pieces that way.
pub(crate) fn separated_on(screen: &ScreenScene, p: &Piece, q: &Piece) -> bool {
    Outline::of(p).separated_from(screen, q)
}

/// What [`separated_on`] reads of one piece, found once for a piece tested against many: its
/// grid corners and their edge lines (an uncut face), and its face's triangle.
pub(crate) struct Outline<'p> {
    piece: &'p Piece,
    corners: Option<CornerOutline>,
    /// Found when first needed.
    triangle: std::cell::OnceCell<Option<CornerOutline>>,
}

impl<'p> Outline<'p> {
    pub(crate) fn of(piece: &'p Piece) -> Self {
        Outline {
            piece,
            corners: piece.grid_corners().map(|c| CornerOutline::of(&c)),
            triangle: std::cell::OnceCell::new(),
        }
    }

    /// [`separated_on`] of the piece and `q`.
    pub(crate) fn separated_from(&self, screen: &ScreenScene, q: &Piece) -> bool {
        let q_corners = q.grid_corners();
        if let Some(own) = &self.corners
            && let Some(c) = &q_corners
        {
            // The piece's own lines first: when one excludes `q`, `q`'s are never made.
            let own = own.view();
            return own.excludes(c) || CornerLines::new(c, &edge_lines(c)).excludes(own.corners());
        }
        let q_corners = q_corners.map(|c| CornerOutline::of(&c));
        self.separated_from_with(screen, q, q_corners.as_ref().map(CornerOutline::view))
    }

    /// [`Self::separated_from`] with `q`'s [`Piece::grid_corners`] and their lines found
    /// already (for pieces tested against many).
    pub(crate) fn separated_from_with(
        &self,
        screen: &ScreenScene,
        q: &Piece,
        q_corners: Option<CornerLines>,
    ) -> bool {
        let own_corners = self.corners.as_ref().map(CornerOutline::view);
        if let Some(a) = own_corners
            && let Some(b) = q_corners
        {
            return a.separated(b);
        }
        // A piece with a vertex off the grid lies within its face's triangle: outlines (the
        // exact corners where known, else the triangle) that lie apart hold pieces apart. Else
        // a line of one with the other wholly on its outer side decides.
        let own = own_corners.or_else(|| {
            (self.triangle)
                .get_or_init(|| {
                    screen
                        .triangle_xy(self.piece.poly)
                        .map(|t| CornerOutline::of(&t))
                })
                .as_ref()
                .map(CornerOutline::view)
        });
        let their_triangle;
        let theirs = match q_corners {
            Some(c) => Some(c),
            None => {
                their_triangle = screen.triangle_xy(q.poly).map(|t| CornerOutline::of(&t));
                their_triangle.as_ref().map(CornerOutline::view)
            }
        };
        own.zip(theirs).is_some_and(|(a, b)| a.separated(b))
            || crate::exact::polygon::separated_by_lines(self.piece, q)
    }
}

/// Convex grid polygons' corners and [`push_edge_lines`] in flat lists, for polygons tested
/// against many ([`CornerLines::separated`]): entry k's corners are
/// `corners[start[k][0]..start[k + 1][0]]`, its lines the same span of `lines` by `start[k][1]`.
#[derive(Debug)]
pub(crate) struct CornerTable {
    corners: Vec<[i64; 2]>,
    lines: Vec<EdgeLine>,
    start: Vec<[u32; 2]>,
}

impl CornerTable {
    pub(crate) fn with_capacity(entries: usize) -> Self {
        let mut start = Vec::with_capacity(entries + 1);
        start.push([0, 0]);
        CornerTable {
            corners: Vec::with_capacity(3 * entries),
            lines: Vec::with_capacity(3 * entries),
            start,
        }
    }

    /// Adds an entry: the convex polygon with these corners (none: an entry with no outline,
    /// which [`Self::get`] gives as none).
    pub(crate) fn push(&mut self, corners: &[[i64; 2]]) {
        self.corners.extend_from_slice(corners);
        push_edge_lines(corners, &mut self.lines);
        let ends = [self.corners.len(), self.lines.len()];
        self.start
            .push(ends.map(|e| u32::try_from(e).expect("below 2^32 corners")));
    }

    /// Entry k's outline, none when it has no corners.
    pub(crate) fn get(&self, k: usize) -> Option<CornerLines<'_>> {
        let ([c0, l0], [c1, l1]) = (self.start[k], self.start[k + 1]);
        let corners = &self.corners[c0 as usize..c1 as usize];
        (!corners.is_empty())
            .then(|| CornerLines::new(corners, &self.lines[l0 as usize..l1 as usize]))
    }
}

/// A grid polygon as a pixel ring (y down, the last point not repeated). Output rounding:
/// `Samples::col_of` and `Samples::row_of` round at most twice (the sum with 1 of a 54-bit
/// grid value over 2^52, and the product by the image side), so each pixel coordinate is within
/// `2·U` of its value relative to the image side: below 4e-12 px at 16384 px. The same grid
/// value always gives the same bits.
pub fn pixel_ring(samples: &Samples, corners: &[GridPoint]) -> Vec<[f64; 2]> {
    corners
        .iter()
        .map(|p| [samples.col_of(p.x as f64), samples.row_of(p.y as f64)])
        .collect()
}

/// `n` squares of side `w` over the same screen square, each tilted so that its nearest corner
/// comes after the previous one's while it lies in front of all of them right of the middle:
/// each Weiler–Atherton clip polygon finds the next one in front of it, one level deeper
/// every time. The first square is nearest left of the middle, the last one right of it.
#[cfg(test)]
pub(crate) fn tilted_squares(n: i64, w: i64) -> impl Iterator<Item = Vec<GridPoint>> {
    (0..n).map(move |k| {
        let (left, right) = (k, 10 * n - k);
        vec![
            GridPoint::new(0, 0, left),
            GridPoint::new(w, 0, right),
            GridPoint::new(w, w, right),
            GridPoint::new(0, w, left),
        ]
    })
}

/// A screen scene (8 x 8 pixels) of the given polygons' grid corners, each its own face, all in
/// mesh 0 (wound outwards: the counter-clockwise ones face the eye): the unit tests' scenes.
#[cfg(test)]
pub(crate) fn screen_of_polygons(polys: impl IntoIterator<Item = Vec<GridPoint>>) -> ScreenScene {
    let mut s = ScreenScene {
        width: 8,
        height: 8,
        ..ScreenScene::default()
    };
    for (k, pts) in polys.into_iter().enumerate() {
        crate::exact::Plane::of_polygon(&pts).expect("a plane");
        let start = s.push_corners(&pts);
        s.polys.push(crate::project::ScreenPoly {
            face: k as u32,
            id: k as u32,
            mesh: 0,
            start,
            len: pts.len() as u32,
            front: crate::exact::twice_signed_area(&pts).is_gt(),
        });
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::{GRID_MAX, XY_SCALE};

    /// A fan of thin triangles around a shared corner, a triangle across it (overlapping some)
    /// and one far off; every piece cut by vertical lines, so no part but the end ones has
    /// only grid corners.
    #[test]
    fn separation_on_a_screen_is_separation_and_settles_cut_pieces_of_triangles_apart() {
        use crate::exact::polygon::{Split, separated, separated_at_corners};
        let gp = |x: i64, y: i64, z: i64| GridPoint { x, y, z };
        let mut polys: Vec<Vec<GridPoint>> = (0..12)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 12.0;
                let b = std::f64::consts::TAU * (k + 1) as f64 / 12.0;
                let rim = |t: f64| gp((9e3 * t.cos()) as i64, (9e3 * t.sin()) as i64, 7);
                vec![gp(0, 0, 5), rim(a), rim(b)]
            })
            .collect();
        polys.push(vec![gp(-7000, -500, 3), gp(7000, -400, 3), gp(0, 900, 3)]);
        polys.push(vec![gp(20000, 0, 2), gp(26000, 0, 2), gp(23000, 5000, 2)]);
        let screen = screen_of_polygons(polys);
        let mut parts = Vec::new();
        for piece in initial_pieces(&screen) {
            let mut rest = piece;
            for x in [-4001, -1003, 997, 3999, 22001] {
                let line = bsp::screen_line(0, x);
                if let Split::Both(left, right) = rest.split_by_line(&line, Boundary::ScreenSplit) {
                    parts.push(left);
                    rest = right;
                }
            }
            parts.push(rest);
        }
        let (mut by_faces, mut overlapping) = (0, 0);
        for (i, p) in parts.iter().enumerate() {
            for q in &parts[i + 1..] {
                let apart = separated(p, q);
                assert_eq!(separated_on(&screen, p, q), apart, "{} {}", p.poly, q.poly);
                overlapping += usize::from(!apart);
                let faces = screen.triangle_xy(p.poly).zip(screen.triangle_xy(q.poly));
                by_faces += usize::from(
                    separated_at_corners(p, q).is_none()
                        && faces
                            .is_some_and(|(a, b)| crate::exact::polygon::corners_separated(&a, &b)),
                );
            }
        }
        assert!(by_faces > 100, "{by_faces} pairs settled by their faces");
        assert!(overlapping > 10, "{overlapping} overlapping pairs");
    }

    #[test]
    fn pixel_ring_is_within_its_bound_at_the_grid_extremes_and_flips_y() {
        let s = Samples::new(16384, 3);
        let gp = |x: i64, y: i64| GridPoint { x, y, z: 0 };
        let g = GRID_MAX;
        let ring = pixel_ring(&s, &[gp(-g, g), gp(g - 1, -g + 1), gp(0, 0)]);
        // col = (x + 2^52)·W / 2^53, row = (2^52 - y)·H / 2^53, correctly rounded from exact
        // integers: the ring is within its stated bound of them.
        let col = |x: i64| ((x as i128 + (1 << 52)) * 16384) as f64 / (1u64 << 53) as f64;
        let row = |y: i64| (((1i128 << 52) - y as i128) * 3) as f64 / (1u64 << 53) as f64;
        let close = |got: [f64; 2], want: [f64; 2]| {
            (got[0] - want[0]).abs() <= 2.0 * f64::EPSILON * 16384.0
                && (got[1] - want[1]).abs() <= 2.0 * f64::EPSILON * 3.0
        };
        assert!(close(ring[0], [col(-g), row(g)]), "{:?}", ring[0]);
        assert!(close(ring[1], [col(g - 1), row(-g + 1)]), "{:?}", ring[1]);
        // The guard band's corner is exact.
        assert_eq!(ring[0], [-8192.0, -1.5]);
        assert_eq!(ring[2], [8192.0, 1.5]);
        // The view's top edge (NDC y = 1) is row 0.
        assert_eq!(s.row_of(XY_SCALE), 0.0);
    }
}
