//! Proof that a piece lies wholly under pieces already visible, before any cut: a front-to-back
//! map ([`super::coverage::Coverage::insert_behind`]), the rest of a BSP node's front layer, or
//! a map filled in any order where every piece meeting it lies in front of it
//! ([`super::coverage::Coverage::insert`]) then drops it whole instead of cutting it by each
//! piece in front until nothing is left (most pieces that meet a visible piece are hidden:
//! dragon's 103k of 114k front to back, which took 591k cuts).
//!
//! The visible pieces have disjoint interiors; U is their union. Its boundary lies on their
//! sides, and only on sides that no other visible piece runs along the other way: a side from
//! vertex a to b of one piece and a side from b to a of another have the two pieces on their two
//! sides, so every point strictly between a and b is inside U; around a vertex all of whose
//! sides are matched that way the pieces close a full turn. So a point of U's boundary lies on
//! an unmatched side. If no unmatched side meets the open interior of a convex piece P, P's
//! interior (connected) lies wholly inside U or wholly outside; if some visible piece meets it,
//! inside: P's area is hidden.
//!
//! Invariant: every decision is exact (sides matched by exact vertex equality,
//! [`Piece::same_vertex`]; a side meets P's interior unless a line separates them, by exact
//! signs). Unmatched is the safe answer: a side that other pieces match only in parts (one
//! piece's side against two pieces' sides) counts as unmatched, and the piece is then cut as
//! before.

use super::live::bounds;
use crate::exact::polygon::Piece;
use smallvec::SmallVec;
use std::cmp::Ordering;

/// Whether trying pieces whole ([`covered`]) pays where they come from: always for the first
/// tries, then while at least half of the tries prove a piece covered (a surface in front of
/// others: dragon 88 %, the 1M sphere 99 %), else one candidate in sixteen, so that the rate
/// can recover. Soups of crossing faces are proven covered a third of the time, and the fronts
/// a try needs cost them more than the proofs save. Deterministic: a count of what came before.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CoverTries {
    /// Pieces tried.
    pub tries: usize,
    /// Pieces proven covered.
    pub hits: usize,
    /// Candidates not tried while the tries were not paying.
    pub skips: usize,
}

impl CoverTries {
    /// Should the next candidate be tried?
    pub(crate) fn worth_trying(&mut self) -> bool {
        const FIRST_TRIES: usize = 64;
        if self.tries < FIRST_TRIES || 2 * self.hits >= self.tries {
            return true;
        }
        self.skips += 1;
        self.skips.is_multiple_of(16)
    }

    /// Counts a try and whether it proved the piece covered; returns that.
    pub(crate) fn record(&mut self, hit: bool) -> bool {
        self.tries += 1;
        self.hits += usize::from(hit);
        hit
    }

    /// Adds another's counts.
    pub(crate) fn add(&mut self, o: &CoverTries) {
        self.tries += o.tries;
        self.hits += o.hits;
        self.skips += o.skips;
    }
}

/// One side of a visible piece: side k of `near[piece]`, from vertex k to vertex k + 1, and its
/// ends as grid corners when both are (matched by equal corners; others by exact vertex
/// equality).
struct Side {
    piece: u32,
    k: u32,
    corners: Option<[[i64; 2]; 2]>,
}

/// Does `piece` lie wholly under the union of `near`, given that some piece of `near` meets its
/// interior? `near` (pieces with disjoint interiors) must hold every visible piece whose
/// interior meets `piece`'s: only their sides can meet it, and a side that does has its partner
/// in such a piece too. Exact; `false` when not proven.
pub(crate) fn covered(piece: &Piece, near: &[&Piece]) -> bool {
    // The sides that may meet the piece: the box of their ends (each within its error bound of
    // its f64 point) meets the piece's bounds, widened by a unit (far above the rounding of
    // either box). A side's partner has the same ends, so it is among them too.
    let b = bounds(piece);
    let mut sides: Vec<Side> = Vec::new();
    for (i, v) in near.iter().enumerate() {
        let n = v.len();
        let points: SmallVec<[[f64; 4]; 6]> = (v.points())
            .map(|[x, y, e]| [x - e, y - e, x + e, y + e])
            .collect();
        for k in 0..n {
            let (p, q) = (points[k], points[(k + 1) % n]);
            let reach = [
                p[0].min(q[0]),
                p[1].min(q[1]),
                p[2].max(q[2]),
                p[3].max(q[3]),
            ];
            if reach[0] > b[2] || b[0] > reach[2] || reach[1] > b[3] || b[1] > reach[3] {
                continue;
            }
            let corners = v.corner(k).zip(v.corner((k + 1) % n)).map(|(a, c)| [a, c]);
            sides.push(Side {
                piece: i as u32,
                k: k as u32,
                corners,
            });
        }
    }
    // Sides between grid corners, sorted by their ends: a side's partner runs from its second
    // end to its first.
    let mut by_ends: Vec<[[i64; 2]; 2]> = sides.iter().filter_map(|side| side.corners).collect();
    by_ends.sort_unstable();
    // The other sides by a key of their first end's f64 point, x + K·y: a partner's first end
    // is this side's second end, the same exact point, so its x and y are each within the two
    // points' error bounds of this one's (the key also within its own rounding). Only those
    // are compared exactly. (Not x alone: the ends cut on one vertical screen line share it.)
    const K: f64 = 0.754_877_666_246_692_7;
    let key = |[x, y, _]: [f64; 3]| x + K * y;
    let mut by_key: Vec<(f64, u32)> = (sides.iter().enumerate())
        .filter(|(_, side)| side.corners.is_none())
        .map(|(s, side)| {
            (
                key(near[side.piece as usize].point(side.k as usize)),
                s as u32,
            )
        })
        .collect();
    by_key.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    let (mut most_error, mut most_xy) = (0.0f64, 0.0f64);
    for side in sides.iter().filter(|side| side.corners.is_none()) {
        let [x, y, e] = near[side.piece as usize].point(side.k as usize);
        most_error = most_error.max(e);
        most_xy = most_xy.max(x.abs() + y.abs());
    }
    let has_partner = |side: &Side| -> bool {
        let (v, k) = (near[side.piece as usize], side.k as usize);
        let k1 = (k + 1) % v.len();
        match side.corners {
            Some([a, c]) => by_ends.binary_search(&[c, a]).is_ok(),
            None => {
                let end = v.point(k1);
                let [x, y, e] = end;
                // Far wider than `Piece::same_vertex`'s own reach, 2(e + f) and the rounding
                // of the coordinates, on each of x and y.
                let reach =
                    4.0 * (e + most_error) + 8.0 * (x.abs() + y.abs() + most_xy) * f64::EPSILON;
                let (at, within) = (key(end), 2.0 * reach);
                let from = by_key.partition_point(|c| c.0 < at - within);
                by_key[from..]
                    .iter()
                    .take_while(|c| c.0 <= at + within)
                    .any(|&(_, o)| {
                        let other = &sides[o as usize];
                        let w = near[other.piece as usize];
                        let m = other.k as usize;
                        let [u, t, _] = w.point(m);
                        other.piece != side.piece
                            && (u - x).abs() <= reach
                            && (t - y).abs() <= reach
                            && w.same_vertex(m, v, k1)
                            && v.same_vertex(k, w, (m + 1) % w.len())
                    })
            }
        }
    };
    sides.iter().all(|side| {
        has_partner(side) || !side_meets_interior(near[side.piece as usize], side.k as usize, piece)
    })
}

/// Does side k of `v` (the closed segment from vertex k to vertex k + 1) meet the open interior
/// of the convex piece `p`? Exact: no, when `p` lies on one closed side of the side's line, or
/// both ends lie on the closed outer side of one of `p`'s lines (for two convex sets, one of
/// those lines separates them whenever the segment misses the open interior).
fn side_meets_interior(v: &Piece, k: usize, p: &Piece) -> bool {
    let k1 = (k + 1) % v.len();
    let outside_of = |m: usize| {
        let (l, la) = (p.line(m), p.line_approx(m));
        v.vertex_line_sign_with(k, l, &la) != Ordering::Greater
            && v.vertex_line_sign_with(k1, l, &la) != Ordering::Greater
    };
    if (0..p.len()).any(outside_of) {
        return false;
    }
    let (neg, pos) = p.sides_of_line(v.line(k));
    neg && pos
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::polygon::{Boundary, Split, separated};
    use crate::exact::predicates::Line;
    use crate::exact::{GridPoint, Plane, w256};
    use crate::visibility::coverage::subtract_all;
    use crate::visibility::{initial_pieces, screen_of_polygons};
    use proptest::prelude::*;

    /// The pieces of triangles given by their (x, y) corners (counter-clockwise).
    fn pieces(tris: &[[[i64; 2]; 3]]) -> Vec<Piece> {
        let screen = screen_of_polygons(
            (tris.iter()).map(|t| t.iter().map(|&[x, y]| GridPoint { x, y, z: 0 }).collect()),
        );
        initial_pieces(&screen)
    }

    /// A sheet of n x n squares of side 8 from the origin, two triangles each, split along
    /// the diagonal that `flip(i, j)` chooses, less the squares `hole(i, j)` picks.
    fn sheet(
        n: i64,
        flip: impl Fn(i64, i64) -> bool,
        hole: impl Fn(i64, i64) -> bool,
    ) -> Vec<[[i64; 2]; 3]> {
        let mut tris = Vec::new();
        for j in 0..n {
            for i in (0..n).filter(|&i| !hole(i, j)) {
                let (x, y) = (8 * i, 8 * j);
                let [a, b, c, d] = [[x, y], [x + 8, y], [x + 8, y + 8], [x, y + 8]];
                if flip(i, j) {
                    tris.extend([[a, b, d], [b, c, d]]);
                } else {
                    tris.extend([[a, b, c], [a, c, d]]);
                }
            }
        }
        tris
    }

    /// Every piece cut by the line a·x + b·y + d = 0 where it crosses it (new vertices off the
    /// grid, on both sides of the cut).
    fn cut(pieces: Vec<Piece>, [a, b, d]: [i128; 3]) -> Vec<Piece> {
        let line = Line::vertical(&Plane {
            a,
            b,
            c: 0,
            d: w256(d),
        });
        let mut out = Vec::new();
        for p in pieces {
            match p.split_by_line(&line, Boundary::ScreenSplit) {
                Split::Both(n, q) => out.extend([n, q]),
                _ => out.push(p),
            }
        }
        out
    }

    /// `covered` of `piece` under the pieces of `fronts` that meet it, as the coverage map asks;
    /// `None` when none meets it. Checks that a covered piece has nothing left outside them.
    fn covered_under(piece: &Piece, fronts: &[Piece]) -> Option<bool> {
        let near: Vec<&Piece> = fronts.iter().filter(|f| !separated(piece, f)).collect();
        if near.is_empty() {
            return None;
        }
        let hidden = covered(piece, &near);
        if hidden {
            assert!(
                subtract_all(piece.clone(), near.iter().copied()).is_empty(),
                "a covered piece keeps area"
            );
        }
        Some(hidden)
    }

    fn triangle(t: [[i64; 2]; 3]) -> Piece {
        pieces(&[t]).pop().expect("a triangle")
    }

    #[test]
    fn a_piece_under_a_whole_sheet_is_covered_and_not_over_a_hole_or_the_edge() {
        let inside = triangle([[10, 10], [50, 13], [30, 51]]);
        let whole = pieces(&sheet(8, |i, j| (i + j) % 3 == 0, |_, _| false));
        assert_eq!(covered_under(&inside, &whole), Some(true));
        // One square missing under the piece (and one away from it, which changes nothing).
        let holed = pieces(&sheet(8, |i, j| (i + j) % 3 == 0, |i, j| (i, j) == (3, 3)));
        assert_eq!(covered_under(&inside, &holed), Some(false));
        let away = pieces(&sheet(8, |i, j| (i + j) % 3 == 0, |i, j| (i, j) == (7, 0)));
        assert_eq!(covered_under(&inside, &away), Some(true));
        // Reaching past the sheet's edge, or along it from outside.
        let over_edge = triangle([[40, 10], [70, 13], [50, 30]]);
        assert_eq!(covered_under(&over_edge, &whole), Some(false));
        let along_edge = triangle([[0, 0], [64, 0], [30, 20]]);
        assert_eq!(covered_under(&along_edge, &whole), Some(true));
    }

    #[test]
    fn sides_cut_off_the_grid_match_their_partners_exactly() {
        let inside = triangle([[10, 10], [50, 13], [30, 51]]);
        let whole = pieces(&sheet(8, |i, _| i % 2 == 0, |_, _| false));
        // A slanted line and a vertical one: their crossings with the sheet's sides are off
        // the grid, each made twice (once for each piece on the side).
        let sliced = cut(cut(whole, [3, 7, -161]), [1, 0, -21]);
        assert!(sliced.iter().any(|p| p.grid_corners().is_none()));
        assert_eq!(covered_under(&inside, &sliced), Some(true));
    }

    /// A hole whose sides the piece crosses were all cut off the grid (by the lines x = 28.5 and
    /// y = 28.5): they have no partner, so the hole shows.
    #[test]
    fn a_hole_bounded_by_sides_cut_off_the_grid_is_seen() {
        let holed = pieces(&sheet(8, |_, _| false, |i, j| (i, j) == (3, 3)));
        let sliced = cut(cut(holed, [2, 0, -57]), [0, 2, -57]);
        let piece = triangle([[22, 27], [35, 27], [28, 35]]);
        assert_eq!(covered_under(&piece, &sliced), Some(false));
    }

    /// A side that two pieces match in parts (a T-junction) is taken as unmatched: the piece
    /// across it is not proven covered, though it is (it is then cut as before).
    #[test]
    fn a_side_matched_only_in_parts_counts_as_a_contour() {
        let fronts = pieces(&[
            [[0, 0], [16, 0], [8, 8]],
            [[0, 0], [8, -8], [8, 0]],
            [[8, 0], [8, -8], [16, 0]],
        ]);
        let across = triangle([[6, -1], [10, -1], [8, 2]]);
        assert_eq!(covered_under(&across, &fronts), Some(false));
        assert!(subtract_all(across, fronts.iter()).is_empty());
    }

    /// Filled in any order, the map drops a piece under a sheet inserted before it only when
    /// the sheet lies in front of it: the same piece in front of the sheet stays whole.
    #[test]
    fn a_map_filled_in_any_order_drops_only_what_lies_behind() {
        use crate::visibility::coverage::Coverage;
        let tri = [[10, 10], [50, 13], [30, 51]];
        for (z, hidden) in [(150, true), (50, false)] {
            let mut polys: Vec<Vec<GridPoint>> = (sheet(8, |i, j| (i + j) % 2 == 0, |_, _| false))
                .iter()
                .map(|t| t.iter().map(|&[x, y]| GridPoint { x, y, z: 100 }).collect())
                .collect();
            polys.push(tri.iter().map(|&[x, y]| GridPoint { x, y, z }).collect());
            let screen = screen_of_polygons(polys);
            let pieces = initial_pieces(&screen);
            let mut map = Coverage::new(&screen, &pieces);
            pieces.iter().for_each(|p| map.insert(p.clone()));
            assert_eq!(map.stats.covers.hits, usize::from(hidden), "z = {z}");
            let last = screen.polys.len() as u32 - 1;
            let shown = map.into_pieces().iter().any(|p| p.poly == last);
            assert_eq!(shown, !hidden, "z = {z}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// Covered means hidden: nothing of the piece is outside the pieces that meet it
        /// (checked in `covered_under`), whatever the sheet's holes and cuts; and on a sheet with
        /// no holes, cut or not, a piece inside it is always proven covered.
        #[test]
        fn covered_pieces_are_hidden_and_pieces_inside_a_whole_sheet_are_covered(
            flips in prop::collection::vec(any::<bool>(), 36),
            holes in prop::collection::vec(0usize..36, 0..3),
            corners in prop::array::uniform3((1i64..47, 1i64..47)),
            cuts in prop::collection::vec((-5i128..=5, -5i128..=5, -200i128..=0), 0..3),
        ) {
            let [p, q, r] = corners.map(|(x, y)| [x, y]);
            let turn = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
            prop_assume!(turn != 0);
            let piece = triangle(if turn > 0 { [p, q, r] } else { [p, r, q] });
            let at = |i: i64, j: i64| (6 * j + i) as usize;
            let mut fronts = pieces(&sheet(
                6,
                |i, j| flips[at(i, j)],
                |i, j| holes.contains(&at(i, j)),
            ));
            for &(a, b, d) in &cuts {
                if (a, b) != (0, 0) {
                    fronts = cut(fronts, [a, b, d]);
                }
            }
            let got = covered_under(&piece, &fronts);
            if holes.is_empty() {
                prop_assert_eq!(got, Some(true));
            }
        }
    }
}
