//! Where two visible groups meet: the boundary segments that two pieces of different groups
//! share, found exactly. A drawing paints them under its fills ([`crate::output::drawing::Seam`])
//! so that viewers' anti-aliasing does not show the background through the boundary (two
//! abutting edges each cover part of a pixel, and blending them one after the other lets the
//! background through: "conflation").
//!
//! Invariant: every segment returned lies on the common boundary of two pieces whose interiors
//! lie on its two sides, and the union of the segments is the whole boundary that pieces of
//! different groups share (touching at a single point is not sharing). Both are decided exactly
//! from the pieces' implicit vertices; only the endpoints written out are rounded (to pixels).
//! Boundaries against nothing (the silhouette) or between pieces of one group are never returned.

use super::coverage::bounds;
use super::grid::for_each_near;
use crate::exact::Samples;
use crate::exact::polygon::Piece;
use std::cmp::Ordering;

/// One shared boundary segment.
#[derive(Clone, Debug, PartialEq)]
pub struct SharedEdge {
    /// The two pieces (indices into the slice given), the first smaller.
    pub pieces: [usize; 2],
    /// Endpoints in pixels (y down), rounded once from the exact vertices.
    pub ends: [[f64; 2]; 2],
}

/// The boundary segments shared by pieces of different groups (`group(i)` of piece i), in
/// piece order. `pieces` must have pairwise disjoint interiors (a visible set).
pub fn shared_edges(
    pieces: &[Piece],
    group: impl Fn(usize) -> u32,
    samples: &Samples,
) -> Vec<SharedEdge> {
    let px = |[x, y]: [f64; 2]| [samples.col_of(x), samples.row_of(y)];
    let boxes: Vec<[f64; 4]> = pieces.iter().map(bounds).collect();
    let mut out = Vec::new();
    for_each_near(&boxes, |a, near| {
        for &b in near.iter().filter(|&&b| b > a && group(b) != group(a)) {
            if let Some(ends) = common_segment(&pieces[a], &pieces[b]) {
                out.push(SharedEdge {
                    pieces: [a, b],
                    ends: ends.map(px),
                });
            }
        }
    });
    out
}

/// The segment two convex pieces with disjoint interiors share, in f64 grid coordinates, if
/// they share one of positive length. Two disjoint convex polygons share at most one segment,
/// lying on an edge line of each.
fn common_segment(a: &Piece, b: &Piece) -> Option<[[f64; 2]; 2]> {
    let (na, nb) = (a.len(), b.len());
    for k in 0..na {
        let (line, approx) = (&a.lines[k], &a.line_approx[k]);
        // An edge j of b on a's line k: both of its ends on that line.
        let on: Vec<bool> = (0..nb)
            .map(|v| b.vertex_line_sign_with(v, line, approx) == Ordering::Equal)
            .collect();
        let Some(j) = (0..nb).find(|&j| on[j] && on[(j + 1) % nb]) else {
            continue;
        };
        // The shared part of the two collinear edges runs between the ends of each that lie
        // in the other piece (closed).
        let in_closed = |p: &Piece, v: usize, q: &Piece| {
            (q.lines.iter().zip(&q.line_approx))
                .all(|(l, la)| p.vertex_line_sign_with(v, l, la) != Ordering::Less)
        };
        let mut ends: Vec<[f64; 2]> = Vec::with_capacity(4);
        for v in [k, (k + 1) % na] {
            if in_closed(a, v, b) {
                ends.push(a.vertex_f64(v));
            }
        }
        for v in [j, (j + 1) % nb] {
            if in_closed(b, v, a) {
                ends.push(b.vertex_f64(v));
            }
        }
        // The two ends farthest apart (an end found from both pieces appears twice).
        let mut best: Option<([[f64; 2]; 2], f64)> = None;
        for (i, p) in ends.iter().enumerate() {
            for q in &ends[i + 1..] {
                let d = (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
                if d > best.map_or(0.0, |(_, bd)| bd) {
                    best = Some(([*p, *q], d));
                }
            }
        }
        // Collinear edges of pieces on the same side of the line meet at most at a point:
        // then another pair of edges may still be shared.
        if let Some((e, _)) = best {
            return Some(e);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::{GridPoint, Plane};

    fn piece(poly: u32, corners: &[[i32; 2]]) -> Piece {
        let gp: Vec<GridPoint> = corners
            .iter()
            .map(|&[x, y]| GridPoint { x, y, z: 0 })
            .collect();
        let support = Plane {
            a: 0,
            b: 0,
            c: 1,
            d: 0,
        };
        Piece::from_convex(poly, support, &gp)
    }

    #[test]
    fn abutting_squares_share_their_common_edge_and_a_t_junction_part() {
        // a: [0,4]x[0,4]; b: [4,8]x[0,4] shares the whole edge x = 4; c: [4,8]x[4,6] touches a
        // only at the corner (4,4); d: [-4,0]x[2,6] shares x = 0 for y in [2,4] (a T-junction).
        let pieces = [
            piece(0, &[[0, 0], [4, 0], [4, 4], [0, 4]]),
            piece(1, &[[4, 0], [8, 0], [8, 4], [4, 4]]),
            piece(2, &[[4, 4], [8, 4], [8, 6], [4, 6]]),
            piece(3, &[[-4, 2], [0, 2], [0, 6], [-4, 6]]),
        ];
        let seg = |a: &Piece, b: &Piece| {
            common_segment(a, b).map(|[p, q]| {
                let mut e = [p, q];
                e.sort_by(|x, y| x.partial_cmp(y).unwrap());
                e
            })
        };
        assert_eq!(seg(&pieces[0], &pieces[1]), Some([[4.0, 0.0], [4.0, 4.0]]));
        assert_eq!(
            seg(&pieces[0], &pieces[2]),
            None,
            "a corner is not a segment"
        );
        assert_eq!(seg(&pieces[0], &pieces[3]), Some([[0.0, 2.0], [0.0, 4.0]]));
        assert_eq!(seg(&pieces[1], &pieces[2]), Some([[4.0, 4.0], [8.0, 4.0]]));
        assert_eq!(seg(&pieces[1], &pieces[3]), None, "apart");
    }

    #[test]
    fn one_group_has_no_seams_and_the_silhouette_is_never_a_seam() {
        let pieces = [
            piece(0, &[[0, 0], [4, 0], [4, 4], [0, 4]]),
            piece(1, &[[4, 0], [8, 0], [8, 4], [4, 4]]),
        ];
        let s = Samples::new(16, 16);
        assert!(shared_edges(&pieces, |_| 7, &s).is_empty());
        let e = shared_edges(&pieces, |i| i as u32, &s);
        assert_eq!(e.len(), 1);
        assert_eq!(e[0].pieces, [0, 1]);
        let x = s.col_of(4.0);
        let mut ys = [e[0].ends[0][1], e[0].ends[1][1]];
        ys.sort_by(f64::total_cmp);
        assert_eq!(e[0].ends.map(|p| p[0]), [x, x]);
        assert_eq!(ys, [s.row_of(4.0), s.row_of(0.0)]);
    }
}
