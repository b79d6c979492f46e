//! Where two visible groups meet: the boundary segments that two pieces of different groups
//! share, found exactly. A drawing paints them under its fills ([`crate::output::drawing::Seams`])
//! so that viewers' anti-aliasing does not show the background through the boundary (two
//! abutting edges each cover part of a pixel, and blending them one after the other lets the
//! background through: "conflation").
//!
//! Invariant: every segment returned lies on the common boundary of two pieces whose interiors
//! lie on its two sides, and the union of the segments is the whole boundary that pieces of
//! different groups share (touching at a single point is not sharing). T-junction parts are
//! decided exactly from the pieces' implicit vertices; edges shared whole are paired by their
//! endpoints' exact vertex ids (on the 54-bit grid, two distinct exact points can round to the
//! same f64 pixel, so rounded bits do not name a point).
//! Boundaries against nothing (the silhouette) or between pieces of one group are never returned.

use super::regions::{UnionFind, Vertices, surely_off_line};
use crate::exact::polygon::Piece;
use crate::visibility::grid::for_each_near_edges;
use smallvec::SmallVec;
use std::cmp::Ordering;

/// One shared boundary segment: 32 bytes (a drawing of a million pieces has about as many).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SharedEdge {
    /// The two pieces (indices into the slice given), the first smaller.
    pub pieces: [u32; 2],
    /// The exact endpoints: each a vertex (piece, vertex index) of one of the two pieces.
    pub vertices: [(u32, u32); 2],
    /// The segment runs along line `.1` of piece `.0` (the first piece).
    pub line: (u32, u32),
}

impl SharedEdge {
    fn new(pieces: [usize; 2], vertices: [(usize, usize); 2], line: (usize, usize)) -> Self {
        // Piece and vertex counts fit u32 (as the pieces' vertex ids do).
        let pair = |(a, b): (usize, usize)| (a as u32, b as u32);
        SharedEdge {
            pieces: pieces.map(|a| a as u32),
            vertices: vertices.map(pair),
            line: pair(line),
        }
    }

    /// The endpoints in pixels (y down), rounded once from the exact vertices: the
    /// [`Vertices`] the edges were found with.
    pub fn ends(&self, vertices: &Vertices) -> [[f64; 2]; 2] {
        self.vertices
            .map(|(p, v)| vertices.pixels[p as usize][v as usize])
    }

    /// This edge, number `edge` of its list, as a stroke reads it ([`StrokeSegment`]).
    pub fn segment(&self, edge: usize, vertices: &Vertices) -> StrokeSegment {
        StrokeSegment {
            ids: (self.vertices).map(|(p, v)| vertices.ids[p as usize][v as usize]),
            ends: self.ends(vertices),
            edge: u32::try_from(edge).expect("edges are numbered in 32 bits"),
        }
    }
}

/// A shared edge as [`straight_runs`] reads it: its ends' vertex ids and pixels, read once
/// (in edge order, where they are near each other in memory: read per stroke, each cost two
/// cache misses), and its number in the list of [`SharedEdge`]s for the exact tests where
/// segments meet.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StrokeSegment {
    /// The ends' exact vertex ids ([`Vertices::ids`]).
    pub ids: [u32; 2],
    /// The ends in pixels ([`SharedEdge::ends`]).
    pub ends: [[f64; 2]; 2],
    /// Its [`SharedEdge`]'s index.
    pub edge: u32,
}

/// The boundary segments shared by pieces of different groups (`group(i)` of piece i), in
/// piece order. `pieces` must have pairwise disjoint interiors (a visible set); `vertices` are
/// their [`shared_vertices`]: exact vertex ids, and pixels with the same bits for one exact
/// vertex in every piece.
///
/// Two passes. Whole edges first: an edge of one piece whose ends are, the other way round,
/// the ends of an edge of another is shared whole ([`Vertices::partners`]; this is most of a
/// mesh). Then the edges left, where T-junctions and occlusion boundaries are: an edge of
/// another piece lies on the same line, decided exactly, and the part they share runs between
/// the ends of each that lie in the other piece.
///
/// [`shared_vertices`]: super::regions::shared_vertices
pub fn shared_edges(
    pieces: &[Piece],
    vertices: &Vertices,
    group: impl Fn(usize) -> u32,
) -> Vec<SharedEdge> {
    let (pixels, ids) = (&vertices.pixels, &vertices.ids);
    // Edge k of piece a is edge `ids.first(a) + k` of all.
    let edge = |a: usize, k: usize| ids.first(a) + k;
    // Edge e (of all): shared whole with another piece, the other way round.
    let whole = |e: usize| vertices.partners[e] != Vertices::ALONE;
    let mut out = Vec::new();
    for a in 0..pieces.len() {
        let n = ids[a].len();
        for (k, &b) in vertices.partners_of(a).iter().enumerate() {
            let b = b as usize;
            if b != Vertices::ALONE as usize && a < b && group(a) != group(b) {
                out.push(SharedEdge::new([a, b], [(a, k), (a, (k + 1) % n)], (a, k)));
            }
        }
    }
    // Two collinear segments sharing a part have an end of one on the other: the pairs of
    // pieces where one has a vertex on an edge of the other not shared whole, both ways.
    let open = |a: usize| vertices.partners_of(a).contains(&Vertices::ALONE);
    // (earlier piece, later piece) of every pair, then sorted: pieces in order, partners
    // ascending.
    let mut pairs: Vec<(u32, u32)> = Vec::new();
    let points = |a: usize| &pixels[a];
    for_each_near_edges(
        pieces.len(),
        points,
        open,
        |a, k| !whole(edge(a, k)),
        |a, near| {
            for &b in near {
                let (first, second) = if a < b { (a, b) } else { (b, a) };
                pairs.push((first as u32, second as u32));
            }
        },
    );
    pairs.sort_unstable();
    pairs.dedup();
    for (a, b) in pairs.into_iter().map(|(a, b)| (a as usize, b as usize)) {
        if group(b) == group(a) {
            continue;
        }
        for k in (0..pieces[a].len()).filter(|&k| !whole(edge(a, k))) {
            let (pa, pb) = ((a, &pieces[a]), (b, &pieces[b]));
            if let Some(ends) = shared_part(pa, k, pb, vertices) {
                out.push(SharedEdge::new([a, b], ends, (a, k)));
                // Two disjoint convex pieces share at most one segment.
                break;
            }
        }
    }
    out
}

/// `segments` (of one stroke; [`SharedEdge::segment`]s of `edges`) with the segments that
/// continue each other joined: two segments meeting at an exact vertex, the other end of one
/// exactly on the other's kernel line, are one run, drawn as the union of its segments along
/// the line. Pieces cut a boundary at points of their own (the BSP's screen splits, the
/// coverage map's splits); joined, the segments are the maximal straight runs of the point set
/// the edges cover, whatever the cut. `vertices` are the pieces' [`Vertices`], which the
/// edges were found with.
pub fn straight_runs(
    segments: &[StrokeSegment],
    edges: &[SharedEdge],
    pieces: &[Piece],
    vertices: &Vertices,
) -> Vec<[[f64; 2]; 2]> {
    // Every segment end as (vertex id, segment, end) in one sortable word: by vertex id.
    assert!(
        segments.len() < 1 << 31,
        "a stroke's segments are numbered in 31 bits"
    );
    let mut ends: Vec<u64> = (segments.iter().enumerate())
        .flat_map(|(s, g)| [0, 1].map(|end| u64::from(g.ids[end]) << 32 | (s << 1 | end) as u64))
        .collect();
    ends.sort_unstable();
    let (segment_of, end_of) = (|e: u64| (e as u32 >> 1) as usize, |e: u64| (e & 1) as usize);
    let edge = |s: usize| &edges[segments[s].edge as usize];
    let mut runs = UnionFind::new(segments.len());
    let mut joined = false;
    for meeting in ends.chunk_by(|a, b| a >> 32 == b >> 32) {
        for (i, &e) in meeting.iter().enumerate() {
            if i + 1 == meeting.len() {
                break;
            }
            let (s, at) = (&segments[segment_of(e)], end_of(e));
            // Segment s's line, approximated once for every later segment at this point that
            // the pixels do not already put off it.
            let mut line = None;
            for &f in &meeting[i + 1..] {
                let far = segments[segment_of(f)].ends[1 - end_of(f)];
                if surely_off_line(s.ends[at], s.ends[1 - at], far, vertices.pixel_error) {
                    continue;
                }
                let (line, approx) = *line.get_or_insert_with(|| {
                    let (lp, l) = edge(segment_of(e)).line;
                    let lp = &pieces[lp as usize];
                    (lp.line(l as usize), lp.line_approx(l as usize))
                });
                let (fp, fv) = edge(segment_of(f)).vertices[1 - end_of(f)];
                let (fp, fv) = (fp as usize, fv as usize);
                if pieces[fp].vertex_line_sign_with(fv, line, &approx) == Ordering::Equal {
                    runs.union(segment_of(e), segment_of(f));
                    joined = true;
                }
            }
        }
    }
    drop(ends);
    // Runs by their root, each in segment order. Where no segments joined (most strokes),
    // each is its own root: already in that order.
    let mut order: Vec<u64> = (0..segments.len())
        .map(|s| (runs.find(s) as u64) << 32 | s as u64)
        .collect();
    if joined {
        order.sort_unstable();
    }
    let mut out = Vec::with_capacity(segments.len());
    let mut run: Vec<[[f64; 2]; 2]> = Vec::new();
    for members in order.chunk_by(|a, b| a >> 32 == b >> 32) {
        // A path of segments along one line, or segments overlapping on it (two strategies cut
        // one boundary into different parts): their union, whatever the cut.
        run.clear();
        run.extend(members.iter().map(|&m| segments[m as u32 as usize].ends));
        union_along_line(&mut run, &mut out);
    }
    out
}

/// The union of collinear `segments` (pixels, each end rounded once from an exact vertex) as
/// maximal segments, appended to `out` in order along the line by their coordinate on its
/// longer axis: an output canonicalization of overlapping runs, on the rounded ends (equal
/// bits are one point). `segments` is left reordered.
fn union_along_line(segments: &mut [[[f64; 2]; 2]], out: &mut Vec<[[f64; 2]; 2]>) {
    // The line's direction from its longest segment: a short one may round to a point, or to
    // two points differing in one coordinate only, which says nothing of the line.
    let extent = |s: &[[f64; 2]; 2]| (s[1][0] - s[0][0]).abs().max((s[1][1] - s[0][1]).abs());
    let Some(&[p, q]) = segments
        .iter()
        .max_by(|a, b| extent(a).total_cmp(&extent(b)))
    else {
        return;
    };
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let axis = usize::from(dy.abs() > dx.abs());
    // Ends with the same coordinate on the longer axis are in order along the line by the
    // other coordinate, increasing or decreasing as the line goes.
    let other = if dx * dy < 0.0 { -1.0 } else { 1.0 };
    let key = |v: &[f64; 2]| (v[axis], other * v[1 - axis]);
    let before = |a: &[f64; 2], b: &[f64; 2]| key(a).partial_cmp(&key(b)) == Some(Ordering::Less);
    for s in segments.iter_mut() {
        if before(&s[1], &s[0]) {
            s.swap(0, 1);
        }
    }
    segments.sort_by(|a, b| {
        key(&a[0])
            .partial_cmp(&key(&b[0]))
            .unwrap_or(Ordering::Equal)
    });
    let first = out.len();
    for &s in segments.iter() {
        match out[first..].last_mut() {
            Some(last) if !before(&last[1], &s[0]) => {
                if before(&last[1], &s[1]) {
                    last[1] = s[1];
                }
            }
            _ => out.push(s),
        }
    }
}

/// The segment of positive length that edge k of piece `a` (index `ia`) shares with an edge of
/// piece `b` (index `ib`) not shared whole elsewhere ([`Vertices::partners`]), its ends as
/// (piece index, vertex) of the pieces' vertices. `a` and `b` have disjoint interiors.
fn shared_part(
    (ia, a): (usize, &Piece),
    k: usize,
    (ib, b): (usize, &Piece),
    vertices: &Vertices,
) -> Option<[(usize, usize); 2]> {
    let (na, nb) = (a.len(), b.len());
    let (ids_a, ids_b) = (&vertices.ids[ia], &vertices.ids[ib]);
    let (line, approx) = (a.line(k), a.line_approx(k));
    // An edge j of b on a's line k: both of its ends on that line (a strictly convex piece has
    // at most one edge on a line). A vertex of b at an end of the edge is on it without a test
    // (an exact one: a point on the line never clears the filter).
    let ends_a = [ids_a[k], ids_a[(k + 1) % na]];
    let on: SmallVec<[bool; 8]> = (0..nb)
        .map(|v| {
            ends_a.contains(&ids_b[v])
                || b.vertex_line_sign_with(v, line, &approx) == Ordering::Equal
        })
        .collect();
    let alone = |j: usize| vertices.partners_of(ib)[j] == Vertices::ALONE;
    let j = (0..nb).find(|&j| alone(j) && on[j] && on[(j + 1) % nb])?;
    // The shared part of the two collinear edges runs between the ends of each that lie in the
    // other piece (closed); an end of b that is an end of a (the same exact point: the same
    // id) counts once. A vertex of the other piece lies in it without a test. Edges with both
    // pieces on one side of the line meet at most at a point: no segment.
    let in_closed = |p: &Piece, id: u32, v: usize, q: &Piece, q_ids: &[u32]| {
        q_ids.contains(&id)
            || (q.lines_with_approx())
                .all(|(l, la)| p.vertex_line_sign_with(v, l, &la) != Ordering::Less)
    };
    let from_a: SmallVec<[usize; 2]> = [k, (k + 1) % na]
        .into_iter()
        .filter(|&v| in_closed(a, ids_a[v], v, b, ids_b))
        .collect();
    let from_b = [j, (j + 1) % nb].into_iter().filter(|&w| {
        !from_a.iter().any(|&v| ids_a[v] == ids_b[w]) && in_closed(b, ids_b[w], w, a, ids_a)
    });
    let ends: SmallVec<[(usize, usize); 4]> = from_a
        .iter()
        .map(|&v| (ia, v))
        .chain(from_b.map(|w| (ib, w)))
        .collect();
    // Exactly distinct points on one line, at most two of them: a convex piece's edge holds
    // at most one end of the other's collinear edge strictly inside, and an end of both counts
    // once. Three would mean an end of each edge inside the other, impossible for disjoint
    // pieces on opposite sides of the line.
    match ends[..] {
        [p, q] => Some([p, q]),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`union_along_line`] of `segments` alone.
    fn union_of(segments: impl Iterator<Item = [[f64; 2]; 2]>) -> Vec<[[f64; 2]; 2]> {
        let (mut segments, mut out): (Vec<_>, _) = (segments.collect(), Vec::new());
        union_along_line(&mut segments, &mut out);
        out
    }

    #[test]
    fn overlapping_collinear_seams_are_drawn_as_their_union() {
        let seg = |a: f64, b: f64| [[a, 2.0 * a], [b, 2.0 * b]];
        // The same boundary cut two ways, with a repeated part: one segment.
        let got =
            union_of([seg(0.0, 1.0), seg(3.0, 1.0), seg(1.0, 3.0), seg(2.0, 4.0)].into_iter());
        assert_eq!(got, vec![seg(0.0, 4.0)]);
        // Apart: two segments, in order along the line.
        let got = union_of([seg(5.0, 6.0), seg(0.0, 1.0)].into_iter());
        assert_eq!(got, vec![seg(0.0, 1.0), seg(5.0, 6.0)]);
    }

    /// A seam along which y falls as x grows, continued by a part so short that its rounded ends
    /// differ only in y (two exact vertices an ulp apart): the union reaches the far end,
    /// whichever segment comes first (the BSP and the coverage map cut there differently).
    #[test]
    fn a_seam_continued_by_a_part_shorter_than_its_rounding_reaches_its_end() {
        let end = [2.0, 1.0];
        let beyond = [2.0, f64::from_bits(1.0f64.to_bits() - 1)];
        let long = [[0.0, 2.0], end];
        let tiny = [end, beyond];
        let whole = vec![[[0.0, 2.0], beyond]];
        assert_eq!(union_of([long, tiny].into_iter()), whole);
        assert_eq!(union_of([tiny, long].into_iter()), whole);
        assert_eq!(union_of([[end, [0.0, 2.0]], tiny].into_iter()), whole);
        // Where y grows with x, the part beyond has the larger y.
        let beyond = [2.0, f64::from_bits(1.0f64.to_bits() + 1)];
        let whole = vec![[[0.0, 0.0], beyond]];
        assert_eq!(
            union_of([[[0.0, 0.0], end], [end, beyond]].into_iter()),
            whole
        );
    }
    use crate::draw::regions::shared_vertices;
    use crate::draw::regions::tests::{cut, grid_piece as piece, grid_samples, to_grid};
    use crate::exact::Samples;

    /// The shared segments as (pieces, ends in grid units, ends sorted).
    fn shared(pieces: &[Piece], group: impl Fn(usize) -> u32) -> Vec<([usize; 2], [[f64; 2]; 2])> {
        let vertices = shared_vertices(pieces, &grid_samples());
        let mut out: Vec<_> = shared_edges(pieces, &vertices, group)
            .into_iter()
            .map(|e| {
                let mut ends = e.ends(&vertices).map(to_grid);
                ends.sort_by(|x, y| x.partial_cmp(y).unwrap());
                (e.pieces.map(|a| a as usize), ends)
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

    /// The stroke segments of `pieces` (one colour), grid units, each from its smaller end.
    fn runs(pieces: &[Piece], group: impl Fn(usize) -> u32) -> Vec<[[f64; 2]; 2]> {
        let mut out: Vec<[[f64; 2]; 2]> = pixel_runs(pieces, &grid_samples(), group, true)
            .into_iter()
            .map(|e| {
                let mut e = e.map(to_grid);
                e.sort_by(|x, y| x.partial_cmp(y).unwrap());
                e
            })
            .collect();
        out.sort_by(|x, y| x.partial_cmp(y).unwrap());
        out
    }

    #[test]
    fn a_seam_is_one_segment_however_its_sides_are_cut() {
        let a = || piece(0, &[[0, 0], [4, 0], [4, 4], [0, 4]]);
        let whole = [a(), piece(1, &[[4, 0], [8, 0], [8, 4], [4, 4]])];
        let cut = [
            a(),
            piece(1, &[[4, 0], [8, 0], [8, 1], [4, 1]]),
            piece(1, &[[4, 1], [8, 1], [8, 4], [4, 4]]),
        ];
        let right = vec![[[4.0, 0.0], [4.0, 4.0]]];
        assert_eq!(runs(&whole, |i| (i > 0) as u32), right);
        assert_eq!(runs(&cut, |i| (i > 0) as u32), right);
        // Segments meeting at a corner are two runs.
        let corner = [
            a(),
            piece(1, &[[4, 0], [8, 0], [8, 4], [4, 4]]),
            piece(2, &[[0, 4], [4, 4], [4, 8], [0, 8]]),
        ];
        assert_eq!(
            runs(&corner, |i| (i > 0) as u32),
            vec![[[0.0, 4.0], [4.0, 4.0]], [[4.0, 0.0], [4.0, 4.0]]]
        );
    }

    /// The stroke segments of `pieces` (one colour) in pixels of `samples`, with the pixel
    /// filter ([`surely_off_line`]) or without it (every meeting tested exactly).
    fn pixel_runs(
        pieces: &[Piece],
        samples: &Samples,
        group: impl Fn(usize) -> u32,
        filter: bool,
    ) -> Vec<[[f64; 2]; 2]> {
        let mut vertices = shared_vertices(pieces, samples);
        if !filter {
            vertices.pixel_error = f64::INFINITY;
        }
        let edges = shared_edges(pieces, &vertices, group);
        let segments: Vec<StrokeSegment> = (edges.iter().enumerate())
            .map(|(i, e)| e.segment(i, &vertices))
            .collect();
        straight_runs(&segments, &edges, pieces, &vertices)
    }

    proptest::proptest! {
        /// Two triangles at the screen's scale sharing a slanted edge, cut by lines across it:
        /// the seam is that edge, one segment between its corners, however the cuts' rounded
        /// crossings lie on it (the pixel filter never puts a part of it off its line), as
        /// with every meeting decided exactly.
        #[test]
        fn a_slanted_seam_cut_at_rounded_crossings_is_one_segment(
            c in proptest::array::uniform4(proptest::array::uniform2(-(1i64 << 51)..1 << 51)),
            cuts in proptest::collection::vec(
                proptest::array::uniform2(proptest::array::uniform2(-(1i64 << 51)..1 << 51)),
                1..4,
            ),
        ) {
            let [mut p, mut q, r, s] = c;
            let turn = |a: [i64; 2], b: [i64; 2], c: [i64; 2]| {
                let d = |u: i64, v: i64| i128::from(u) - i128::from(v);
                d(b[0], a[0]) * d(c[1], a[1]) - d(b[1], a[1]) * d(c[0], a[0])
            };
            // r on the left of p -> q, s on its right.
            proptest::prop_assume!(turn(p, q, r).signum() * turn(p, q, s).signum() < 0);
            if turn(p, q, r) < 0 {
                (p, q) = (q, p);
            }
            proptest::prop_assume!(cuts.iter().all(|l| l[0] != l[1]));
            let pieces = cut(vec![piece(0, &[p, q, r]), piece(1, &[q, p, s])], &cuts);
            let samples = Samples::new(1000, 800);
            let pixel = |[x, y]: [i64; 2]| [samples.col_of(x as f64), samples.row_of(y as f64)];
            let got = pixel_runs(&pieces, &samples, |i| pieces[i].poly, true);
            proptest::prop_assert_eq!(got.len(), 1, "{:?}", got);
            let mut ends = got[0];
            ends.sort_by(|a, b| a.partial_cmp(b).unwrap());
            let mut want = [pixel(p), pixel(q)];
            want.sort_by(|a, b| a.partial_cmp(b).unwrap());
            proptest::prop_assert_eq!(ends, want);
            proptest::prop_assert_eq!(&got, &pixel_runs(&pieces, &samples, |i| pieces[i].poly, false));
        }
    }
}
