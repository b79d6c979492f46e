//! Clear pieces: those that no other piece overlaps on screen, found before any pair of pieces
//! is tested. A clear piece is visible whole and hides nothing, so it skips the strips, the
//! trees and the coverage map; on a surface it is most of the pieces (every piece away from the
//! folds of the surface and from the parts it hides).
//!
//! Every piece is counter-clockwise, so at a point on no side, the number of pieces whose
//! interior holds it (the count) is the winding number of all their sides around it. A side
//! from a to b and one from b to a add nothing to any winding number, so the count is the
//! winding number of the sides along which as many run one way as the other are left out
//! (the contour), and it is constant on any connected region that no contour side meets.
//!
//! The screen is divided into cells with integer corners ([`CellGrid`], about one per piece).
//! A cell that no contour side may meet has one count over its interior, read at one point: its
//! centre, moved off every side by an infinitesimal step (x + ε, y + ε²), so that the point lies
//! strictly inside or outside every piece. A piece whose box lies within such cells all of count
//! 1 is clear: the cells' union is a rectangle no contour side meets, so the count is 1 all over
//! it, and the piece itself covers its own interior; no other piece reaches into it.
//!
//! Invariant: every decision is exact (integer cells, sides matched by equal grid corners,
//! counts from exact signs). A piece not proven clear goes the usual way; so does every piece
//! when one is off the grid.

use super::occlusion::{CELLS_PER_PIECE, CellGrid};
use super::point_pairs::{point_pairs, side_key};
use crate::exact::polygon::{Boundary, Piece};
use crate::project::ScreenScene;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU32, Ordering};

/// A cell that a contour side may meet.
const MARKED: u32 = u32::MAX;

/// Per piece of `pieces` (whole polygons' pieces of `screen`, every vertex a grid corner): is it
/// clear? All `false` when a piece has a vertex off the grid.
pub(crate) fn clear_pieces(screen: &ScreenScene, pieces: &[Piece]) -> Vec<bool> {
    // Nothing is kept per piece but the flag: the pieces are read again where needed (a list
    // of their corners and frames was a fifth of the 1M sphere's peak memory).
    let on_grid = |p: &Piece| (0..p.len()).all(|k| p.corner(k).is_some());
    if pieces.is_empty() || !pieces.par_iter().with_min_len(1024).all(on_grid) {
        return vec![false; pieces.len()];
    }
    let all = (pieces.par_iter().with_min_len(1024))
        .map(Piece::grid_frame)
        .reduce(
            || [i64::MAX, i64::MAX, i64::MIN, i64::MIN],
            |f, b| {
                [
                    f[0].min(b[0]),
                    f[1].min(b[1]),
                    f[2].max(b[2]),
                    f[3].max(b[3]),
                ]
            },
        );
    let grid = CellGrid::over(all, pieces.len() as f64 * CELLS_PER_PIECE);
    let count: Vec<AtomicU32> = (0..grid.len()).map(|_| AtomicU32::new(0)).collect();
    for [u, v] in contour(screen, pieces) {
        grid.segment_cells(u, v, |cell| count[cell].store(MARKED, Ordering::Relaxed));
    }
    let cells_of = |p: &Piece| grid.cells_of(p.grid_frame().map(|v| v as f64));
    // Each unmarked cell's count: the pieces holding its moved centre. Counts only grow, so the
    // order does not matter; a marked cell is never counted.
    (pieces.par_iter().with_min_len(1024)).for_each(|p| {
        let c = p.grid_corners().expect("on the grid");
        let [i0, i1, j0, j1] = cells_of(p);
        for j in j0.max(0)..=j1.min(grid.count[1] - 1) {
            for i in i0.max(0)..=i1.min(grid.count[0] - 1) {
                let cell = (j * grid.count[0] + i) as usize;
                let centre = [
                    grid.origin[0] + i * grid.size[0] + grid.size[0] / 2,
                    grid.origin[1] + j * grid.size[1] + grid.size[1] / 2,
                ];
                if count[cell].load(Ordering::Relaxed) != MARKED && holds_moved(&c, centre) {
                    count[cell].fetch_add(1, Ordering::Relaxed);
                }
            }
        }
    });
    (pieces.par_iter().with_min_len(1024))
        .map(|p| {
            let [i0, i1, j0, j1] = cells_of(p);
            i0 >= 0
                && j0 >= 0
                && i1 < grid.count[0]
                && j1 < grid.count[1]
                && (j0..=j1).all(|j| {
                    (i0..=i1).all(|i| {
                        count[(j * grid.count[0] + i) as usize].load(Ordering::Relaxed) == 1
                    })
                })
        })
        .collect()
}

/// Does the convex counter-clockwise polygon `c` hold the point `p` moved by (ε, ε²) strictly
/// inside? Exact: at a side through `p`, the step's sign decides (its x part, then its y part).
fn holds_moved(c: &[[i64; 2]], p: [i64; 2]) -> bool {
    let mut from = c[c.len() - 1];
    c.iter().all(|&to| {
        let (a, b) = ((to[0] - from[0]) as i128, (to[1] - from[1]) as i128);
        // The side's function at q: a·(q.y − from.y) − b·(q.x − from.x), positive inside (a
        // side of no length bounds nothing).
        let at = a * (p[1] - from[1]) as i128 - b * (p[0] - from[0]) as i128;
        from = to;
        at > 0 || (at == 0 && (-b > 0 || (b == 0 && a >= 0)))
    })
}

/// The contour sides' segments of `pieces` (every vertex on the grid, of polygons of
/// `screen`): the segments along which the sides do not cancel (as many running one way as the
/// other).
///
/// Most sides run along a side of their polygon between two shared corners (a mesh's vertex is
/// one grid point, `ScreenScene::grid_points`, whichever faces name it): those are matched first
/// by the two corners' indices ([`point_pairs`], 8 bytes a side: this contour took 55 ms on
/// dragon on one core with a comparison sort of them, 45 ms so). Sides of one pair of corners
/// that cancel leave; the others, and every side not so keyed, are matched by their ends'
/// coordinates: each sorted as its segment (ends in increasing order) with its direction in the
/// last bit (32 bytes a side), so that the sides of one segment are neighbours and no piece is
/// read again (reading each side's ends back from its piece, in the order of a hash of the
/// segments, was half of this module's time on dragon). Either way a run of sides cancels only
/// as a whole, and a cancelled run adds nothing to any winding number, so what is left decides
/// the same.
fn contour(screen: &ScreenScene, pieces: &[Piece]) -> Vec<[[i64; 2]; 2]> {
    use rayon::iter::Either;
    let xy = |i: u32| {
        let g = screen.grid_points[i as usize];
        [g.x, g.y]
    };
    let side = coordinate_side;
    // Side k of `p` as (lower corner index, upper, runs upwards) packed in a u64, when it runs
    // between the two corners of its polygon's side (a line can run on along collinear sides:
    // then its ends are not those corners).
    let by_corners = |p: &Piece, k: usize| -> Option<u64> {
        let Boundary::Outline { poly, side } = p.boundary(k) else {
            return None;
        };
        let corners = screen.corner_indices(&screen.polys[poly as usize]);
        let (i, j) = (
            corners[side as usize],
            corners[(side as usize + 1) % corners.len()],
        );
        let (a, b) = (p.corner(k)?, p.corner((k + 1) % p.len())?);
        let (from, to) = if (xy(i), xy(j)) == (a, b) {
            (i, j)
        } else if (xy(j), xy(i)) == (a, b) {
            (j, i)
        } else {
            return None;
        };
        (from != to && from.max(to) < 1 << 31).then(|| side_key(from, to))
    };
    let corner = |p: &Piece, k: usize| p.corner(k % p.len()).expect("on the grid");
    let (keyed, mut sides): (Vec<u64>, Vec<[i64; 4]>) = (pieces.par_iter().with_min_len(1024))
        .flat_map_iter(|p| {
            (0..p.len()).map(move |k| match by_corners(p, k) {
                Some(key) => Either::Left(key),
                None => Either::Right(side(corner(p, k), corner(p, k + 1))),
            })
        })
        .partition_map(|e| e);
    let left: Vec<[i64; 4]> =
        (point_pairs(screen.grid_points.len(), &keyed, |up, down| up != down).into_iter())
            .flat_map(|p| {
                let up = std::iter::repeat_n(side(xy(p.lo), xy(p.hi)), p.up as usize);
                up.chain(std::iter::repeat_n(
                    side(xy(p.hi), xy(p.lo)),
                    p.down as usize,
                ))
            })
            .collect();
    drop(keyed);
    sides.extend(left);
    uncancelled(sides)
}

/// The side of a piece from `u` to `v` as [`uncancelled`] sorts it: its segment (ends in
/// increasing order) with its direction in the last bit. Grid coordinates are at most 2^53 in
/// size: doubled and a bit added, they still fit.
fn coordinate_side(u: [i64; 2], v: [i64; 2]) -> [i64; 4] {
    let (lo, hi, up) = if u <= v { (u, v, 1) } else { (v, u, 0) };
    [lo[0], lo[1], hi[0], hi[1] << 1 | up]
}

/// The segments of `sides` ([`coordinate_side`]s) along which they do not cancel.
fn uncancelled(mut sides: Vec<[i64; 4]>) -> Vec<[[i64; 2]; 2]> {
    sides.par_sort_unstable();
    let segment = |s: &[i64; 4]| [[s[0], s[1]], [s[2], s[3] >> 1]];
    (sides.par_chunk_by(|a, b| segment(a) == segment(b)))
        .filter(|run| 2 * run.iter().filter(|s| s[3] & 1 == 1).count() != run.len())
        .map(|run| segment(&run[0]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::GridPoint;
    use crate::exact::polygon::separated;
    use crate::visibility::{initial_pieces, screen_of_polygons};
    use proptest::prelude::*;

    /// The screen of triangles given as (x, y, z) corners, in either winding (each corner its
    /// own grid point), and its pieces.
    fn pieces_of(tris: &[[[i64; 3]; 3]]) -> (ScreenScene, Vec<Piece>) {
        let s = screen_of_polygons(
            (tris.iter()).map(|t| t.iter().map(|&[x, y, z]| GridPoint { x, y, z }).collect()),
        );
        let pieces = initial_pieces(&s);
        (s, pieces)
    }

    /// An n x n sheet of counter-clockwise squares of side `side` at depth `z` from (x0, y0),
    /// two triangles each.
    fn sheet(n: i64, side: i64, [x0, y0]: [i64; 2], z: i64) -> Vec<[[i64; 3]; 3]> {
        let mut tris = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let (x, y) = (x0 + side * i, y0 + side * j);
                tris.push([[x, y, z], [x + side, y, z], [x + side, y + side, z]]);
                tris.push([[x, y, z], [x + side, y + side, z], [x, y + side, z]]);
            }
        }
        tris
    }

    /// Every clear piece overlaps no other piece: the property the module promises.
    fn clear_ones_overlap_nothing(screen: &ScreenScene, pieces: &[Piece]) -> usize {
        let clear = clear_pieces(screen, pieces);
        for (k, p) in pieces.iter().enumerate().filter(|&(k, _)| clear[k]) {
            for (j, q) in pieces.iter().enumerate() {
                assert!(
                    j == k || separated(p, q),
                    "clear piece {k} overlaps piece {j}"
                );
            }
        }
        clear.iter().filter(|&&c| c).count()
    }

    #[test]
    fn the_inside_of_a_sheet_is_clear_and_its_rim_is_not() {
        let (screen, pieces) = pieces_of(&sheet(16, 8, [0, 0], 10));
        let clear = clear_pieces(&screen, &pieces);
        // The outline is contour: the squares along it are near a marked cell.
        let at = |k: usize| {
            let [x, y, _, _] = pieces[k].grid_frame();
            [x / 8, y / 8]
        };
        for (k, &c) in clear.iter().enumerate() {
            let [i, j] = at(k);
            if i == 0 || j == 0 || i == 15 || j == 15 {
                assert!(!c, "rim square ({i}, {j}) is clear");
            }
        }
        let inner = (2..14).flat_map(|j| (2..14).map(move |i| [i, j]));
        for [i, j] in inner {
            let k = (0..pieces.len()).find(|&k| at(k) == [i, j]).unwrap();
            assert!(clear[k], "inner square ({i}, {j}) is not clear");
        }
    }

    /// A large triangle over the middle of a sheet: the sheet's pieces under it are covered
    /// twice, and no cell there is met by a contour side (the triangle is many cells wide), so
    /// only the count keeps them from being clear. Behind or in front, the same.
    #[test]
    fn pieces_under_another_are_not_clear_where_no_contour_passes() {
        for z in [1, 100] {
            let mut tris = sheet(32, 8, [0, 0], 10);
            tris.push([[40, 40, z], [220, 40, z], [130, 220, z]]);
            let (screen, pieces) = pieces_of(&tris);
            let clear = clear_pieces(&screen, &pieces);
            let centre = (0..pieces.len())
                .find(|&k| pieces[k].grid_frame()[..2] == [128, 96])
                .unwrap();
            assert!(
                !clear[centre],
                "a piece under the big triangle is clear (z {z})"
            );
            assert!(
                !clear[pieces.len() - 1],
                "the big triangle is clear (z {z})"
            );
            let far = (0..pieces.len())
                .find(|&k| pieces[k].grid_frame()[..2] == [232, 16])
                .unwrap();
            assert!(
                clear[far],
                "a piece far from the triangle is not clear (z {z})"
            );
            assert!(clear_ones_overlap_nothing(&screen, &pieces) > 500);
        }
    }

    /// A face listed twice: its sides run twice one way and once the other along each shared
    /// segment, so they are contour, and the count there is 2.
    #[test]
    fn a_face_listed_twice_is_not_clear() {
        let mut tris = sheet(16, 8, [0, 0], 10);
        let twin = tris[2 * (8 * 16 + 8)];
        tris.push(twin);
        let (screen, pieces) = pieces_of(&tris);
        let clear = clear_pieces(&screen, &pieces);
        assert!(!clear[2 * (8 * 16 + 8)] && !clear[pieces.len() - 1]);
        clear_ones_overlap_nothing(&screen, &pieces);
    }

    /// A sliver listed twice inside a sheet: each of its sides has a partner running the other
    /// way, but two run along it one way and one the other, so the sides are still contour
    /// (the count steps by one across them). Matching a side by any partner, the sliver, far
    /// smaller than a cell and holding no cell's centre, would look clear.
    #[test]
    fn a_sliver_listed_twice_is_contour_even_where_partners_exist() {
        // A sheet of squares of side 8, the square at (64, 64) four triangles around a point
        // near its right side instead of two: the one on that side is a sliver a unit wide,
        // which holds no cell's centre (cells are 6 units here, centres at 3 + 6i).
        let mut tris: Vec<[[i64; 3]; 3]> = sheet(16, 8, [0, 0], 10)
            .into_iter()
            .filter(|t| t[0][..2] != [64, 64])
            .collect();
        let (a, b, c, d, e) = (
            [64, 64, 10],
            [72, 64, 10],
            [72, 72, 10],
            [64, 72, 10],
            [71, 68, 10],
        );
        tris.extend([[a, b, e], [b, c, e], [c, d, e], [d, a, e]]);
        let sliver = tris.len() - 3;
        tris.push(tris[sliver]);
        let (screen, pieces) = pieces_of(&tris);
        let clear = clear_pieces(&screen, &pieces);
        assert!(
            !clear[sliver] && !clear[pieces.len() - 1],
            "a twin is clear"
        );
        clear_ones_overlap_nothing(&screen, &pieces);
    }

    /// Cell centres on shared sides and corners (a sheet on the cells' own lattice) are moved
    /// off them: the count there is still 1.
    #[test]
    fn centres_on_sides_and_corners_count_once() {
        for side in [2, 4, 6] {
            let (screen, pieces) = pieces_of(&sheet(24, side, [0, 0], 10));
            assert!(
                clear_ones_overlap_nothing(&screen, &pieces) > 0,
                "side {side}"
            );
        }
    }

    /// Meshes through the whole pipeline, their vertices shared grid points (the sides keyed by
    /// corner indices): an open sphere (less the back faces the occlusion cells drop, as the
    /// strategies take it; the rest folds under the front at the silhouette), two
    /// interpenetrating tori, and a sphere wound inwards with unwelded poles, seen from three
    /// sides. The contour is the same as matching every side by its ends.
    #[test]
    fn clear_pieces_of_meshes_overlap_nothing() {
        use crate::camera::{Camera, NamedView};
        use crate::pipeline::prepare;
        use crate::project::CullMode;
        use crate::scene::primitives::{holed_sphere_scene, interpenetrating_tori};
        let mut clear = 0;
        use crate::scene::primitives::exported_sphere_scene;
        let scenes = [
            holed_sphere_scene(48, 24),
            interpenetrating_tori(24, 12),
            exported_sphere_scene(2_000),
        ];
        for scene in scenes {
            for view in [NamedView::Iso, NamedView::Front, NamedView::Top] {
                let camera = Camera::fit(view, scene.bounds().unwrap(), false, 40.0, 256, 256);
                let screen = prepare(&scene, &camera, CullMode::Auto).screen;
                let all: Vec<u32> = (0..screen.polys.len() as u32).collect();
                let pieces = crate::visibility::occlusion::unhidden_pieces(&screen, &all).0;
                clear += clear_ones_overlap_nothing(&screen, &pieces);
                // Keyed by corner indices first, the contour is the one of the ends alone.
                let by_ends = (pieces.iter())
                    .flat_map(|p| {
                        let corner = |k: usize| p.corner(k % p.len()).unwrap();
                        (0..p.len()).map(move |k| coordinate_side(corner(k), corner(k + 1)))
                    })
                    .collect();
                let (mut fast, mut slow) = (contour(&screen, &pieces), uncancelled(by_ends));
                fast.sort_unstable();
                slow.sort_unstable();
                assert_eq!(fast, slow);
            }
        }
        assert!(clear >= 100, "{clear} clear pieces");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Sheets at two depths, offset, and loose triangles of either winding: whatever the
        /// arrangement, a clear piece overlaps no other.
        #[test]
        fn a_clear_piece_overlaps_no_other(
            offset in (0i64..40, 0i64..40),
            side in 3i64..9,
            loose in proptest::collection::vec(
                ((0i64..120, 0i64..120), (0i64..120, 0i64..120), (0i64..120, 0i64..120)),
                0..6,
            ),
        ) {
            let mut tris = sheet(10, side, [0, 0], 10);
            tris.extend(sheet(6, side + 1, [offset.0, offset.1], 20));
            for ((ax, ay), (bx, by), (cx, cy)) in loose {
                let t = [[ax, ay, 5], [bx, by, 6], [cx, cy, 7]];
                let twice_area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
                if twice_area != 0 {
                    tris.push(t);
                }
            }
            let (screen, pieces) = pieces_of(&tris);
            clear_ones_overlap_nothing(&screen, &pieces);
        }
    }
}
