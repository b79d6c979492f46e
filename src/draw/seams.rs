//! Where two visible groups meet: the boundary segments that two pieces of different groups
//! share, found exactly. A drawing paints them under its fills ([`crate::output::drawing::Seams`])
//! so that viewers' anti-aliasing does not show the background through the boundary (two
//! abutting edges each cover part of a pixel, and blending them one after the other lets the
//! background through: "conflation").
//!
//! Invariant: every segment returned lies on the common boundary of two pieces whose interiors
//! lie on its two sides, and the union of the segments is the whole boundary that pieces of
//! different groups share (touching at a single point is not sharing). Both are decided exactly
//! from the pieces' implicit vertices; only the endpoints written out are rounded (to pixels).
//! Boundaries against nothing (the silhouette) or between pieces of one group are never returned.

use crate::exact::polygon::Piece;
use crate::visibility::coverage::bounds;
use crate::visibility::grid::for_each_near;
use std::cmp::Ordering;
use std::collections::HashMap;

/// One shared boundary segment.
#[derive(Clone, Debug, PartialEq)]
pub struct SharedEdge {
    /// The two pieces (indices into the slice given), the first smaller.
    pub pieces: [usize; 2],
    /// Endpoints in pixels (y down), rounded once from the exact vertices.
    pub ends: [[f64; 2]; 2],
}

/// The boundary segments shared by pieces of different groups (`group(i)` of piece i), in
/// piece order. `pieces` must have pairwise disjoint interiors (a visible set); `vertices` are
/// their [`shared_vertices`]' pixels, so that one exact vertex has the same bits in every piece.
///
/// Two passes. Whole edges first: an edge of one piece whose ends are, the other way round,
/// the ends of an edge of another is shared whole (the same exact vertices have the same
/// rounding, so a hash of the rounded ends finds them; this is most of a mesh). Then the edges
/// left, where T-junctions and occlusion boundaries are: an edge of another piece lies on the
/// same line, decided exactly, and the part they share runs between the ends of each that lie
/// in the other piece.
///
/// [`shared_vertices`]: super::regions::shared_vertices
pub fn shared_edges(
    pieces: &[Piece],
    vertices: &[Vec<[f64; 2]>],
    group: impl Fn(usize) -> u32,
) -> Vec<SharedEdge> {
    let bits = |p: [f64; 2], q: [f64; 2]| {
        [
            p[0].to_bits(),
            p[1].to_bits(),
            q[0].to_bits(),
            q[1].to_bits(),
        ]
    };
    let ends = |a: usize, k: usize| {
        let v = &vertices[a];
        (v[k], v[(k + 1) % v.len()])
    };
    let mut edges: HashMap<[u64; 4], (usize, usize)> =
        HashMap::with_capacity(vertices.iter().map(Vec::len).sum());
    for (a, v) in vertices.iter().enumerate() {
        for k in 0..v.len() {
            let (p, q) = ends(a, k);
            edges.insert(bits(p, q), (a, k));
        }
    }
    // Per piece and edge: shared whole with another piece.
    let mut whole: Vec<Vec<bool>> = vertices.iter().map(|v| vec![false; v.len()]).collect();
    let mut out = Vec::new();
    for a in 0..pieces.len() {
        for k in 0..vertices[a].len() {
            let (p, q) = ends(a, k);
            if let Some(&(b, j)) = edges.get(&bits(q, p)) {
                whole[a][k] = true;
                whole[b][j] = true;
                if a < b && group(a) != group(b) {
                    out.push(SharedEdge {
                        pieces: [a, b],
                        ends: [p, q],
                    });
                }
            }
        }
    }
    let open = |a: usize| whole[a].iter().any(|w| !w);
    let boxes: Vec<[f64; 4]> = pieces.iter().map(bounds).collect();
    for_each_near(&boxes, open, |a, near| {
        for &b in near
            .iter()
            .filter(|&&b| b > a && group(b) != group(a) && open(b))
        {
            for k in (0..pieces[a].len()).filter(|&k| !whole[a][k]) {
                let (pa, pb) = (
                    (&pieces[a], &vertices[a][..]),
                    (&pieces[b], &vertices[b][..]),
                );
                if let Some(ends) = shared_part(pa, k, pb, &whole[b]) {
                    out.push(SharedEdge {
                        pieces: [a, b],
                        ends,
                    });
                    // Two disjoint convex pieces share at most one segment.
                    break;
                }
            }
        }
    });
    out
}

/// The segment of positive length that edge k of piece `a` shares with an edge of piece `b`
/// not shared whole elsewhere (`b_whole`), with the ends taken from the pieces' vertices in
/// pixels (`va`, `vb`). `a` and `b` have disjoint interiors.
fn shared_part(
    (a, va): (&Piece, &[[f64; 2]]),
    k: usize,
    (b, vb): (&Piece, &[[f64; 2]]),
    b_whole: &[bool],
) -> Option<[[f64; 2]; 2]> {
    let (na, nb) = (a.len(), b.len());
    let (line, approx) = (&a.lines[k], &a.line_approx[k]);
    // An edge j of b on a's line k: both of its ends on that line (a strictly convex piece has
    // at most one edge on a line).
    let on: Vec<bool> = (0..nb)
        .map(|v| b.vertex_line_sign_with(v, line, approx) == Ordering::Equal)
        .collect();
    let j = (0..nb).find(|&j| !b_whole[j] && on[j] && on[(j + 1) % nb])?;
    // The shared part of the two collinear edges runs between the ends of each that lie in the
    // other piece (closed); an end of b that is an end of a (decided exactly) counts once.
    // Edges with both pieces on one side of the line meet at most at a point: no segment.
    let in_closed = |p: &Piece, v: usize, q: &Piece| {
        (q.lines.iter().zip(&q.line_approx))
            .all(|(l, la)| p.vertex_line_sign_with(v, l, la) != Ordering::Less)
    };
    let from_a: Vec<usize> = [k, (k + 1) % na]
        .into_iter()
        .filter(|&v| in_closed(a, v, b))
        .collect();
    let from_b = [j, (j + 1) % nb]
        .into_iter()
        .filter(|&w| in_closed(b, w, a) && !from_a.iter().any(|&v| a.same_vertex(v, b, w)));
    let ends: Vec<[f64; 2]> = from_a
        .iter()
        .map(|&v| va[v])
        .chain(from_b.map(|w| vb[w]))
        .collect();
    // Exactly distinct points on one line: the farthest two (in f64, which only picks among
    // them) bound the shared part.
    let mut best: Option<([[f64; 2]; 2], f64)> = None;
    for (i, p) in ends.iter().enumerate() {
        for q in &ends[i + 1..] {
            let d = (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
            if best.is_none_or(|(_, bd)| d > bd) {
                best = Some(([*p, *q], d));
            }
        }
    }
    best.map(|(e, _)| e)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::regions::shared_vertices;
    use crate::draw::regions::tests::{grid_piece as piece, grid_samples, to_grid};

    /// The shared segments as (pieces, ends in grid units, ends sorted).
    fn shared(pieces: &[Piece], group: impl Fn(usize) -> u32) -> Vec<([usize; 2], [[f64; 2]; 2])> {
        let vertices = shared_vertices(pieces, &grid_samples()).pixels;
        let mut out: Vec<_> = shared_edges(pieces, &vertices, group)
            .into_iter()
            .map(|e| {
                let mut ends = e.ends.map(to_grid);
                ends.sort_by(|x, y| x.partial_cmp(y).unwrap());
                (e.pieces, ends)
            })
            .collect();
        out.sort_by(|x, y| x.partial_cmp(y).unwrap());
        out
    }

    #[test]
    fn abutting_pieces_share_whole_edges_t_junction_parts_and_never_a_corner() {
        // a: [0,4]x[0,4]; b: [4,8]x[0,4] shares the whole edge x = 4 (its bottom edge lies on
        // a's bottom line too, on the same side: not shared); c: [4,8]x[4,6] touches a only at
        // the corner (4,4) and shares y = 4 with b whole; d: [-4,0]x[2,6] shares x = 0 for y in
        // [2,4] with a (a T-junction, found exactly).
        let pieces = [
            piece(0, &[[0, 0], [4, 0], [4, 4], [0, 4]]),
            piece(1, &[[4, 0], [8, 0], [8, 4], [4, 4]]),
            piece(2, &[[4, 4], [8, 4], [8, 6], [4, 6]]),
            piece(3, &[[-4, 2], [0, 2], [0, 6], [-4, 6]]),
        ];
        assert_eq!(
            shared(&pieces, |i| i as u32),
            vec![
                ([0, 1], [[4.0, 0.0], [4.0, 4.0]]),
                ([0, 3], [[0.0, 2.0], [0.0, 4.0]]),
                ([1, 2], [[4.0, 4.0], [8.0, 4.0]]),
            ]
        );
    }

    #[test]
    fn one_group_has_no_seams_and_the_silhouette_is_never_a_seam() {
        let pieces = [
            piece(0, &[[0, 0], [4, 0], [4, 4], [0, 4]]),
            piece(1, &[[4, 0], [8, 0], [8, 4], [4, 4]]),
        ];
        assert!(shared(&pieces, |_| 7).is_empty());
        assert_eq!(
            shared(&pieces, |i| i as u32),
            vec![([0, 1], [[4.0, 0.0], [4.0, 4.0]])]
        );
    }

    #[test]
    fn a_partly_shared_edge_beside_a_collinear_edge_on_the_same_side_is_found() {
        // b's bottom edge lies on a's bottom line (same side, touching at (4,0)) before the
        // edge they share: the search goes on past it. b is shorter than a's right edge.
        let pieces = [
            piece(0, &[[0, 0], [4, 0], [4, 4], [0, 4]]),
            piece(1, &[[4, 0], [8, 0], [8, 2], [4, 2]]),
        ];
        assert_eq!(
            shared(&pieces, |i| i as u32),
            vec![([0, 1], [[4.0, 0.0], [4.0, 2.0]])]
        );
    }
}
