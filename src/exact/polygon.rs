//! Convex pieces of faces with implicit vertices, and their exact splitting.
//!
//! A [`Piece`] lies in a support plane and is bounded, counter-clockwise on screen (y up), by a
//! cycle of [`Line`]s whose positive sides are the inside. Vertex k is where lines `k-1` and `k`
//! cross, lifted onto the support plane: it is never computed, only classified. Splitting adds one
//! line, built from input planes (`Line::Cut` of the support plane and the splitter, or the
//! splitting line itself), so precision never grows however often a piece is split.
//!
//! Invariants of every piece made here: at least three lines, strictly convex, positive area.
//! Splitting only ever reads the signs of the vertices, so a part exists only when some vertex is
//! strictly on its side, and then it has positive area.
//!
//! Non-convex faces are cut into convex pieces first ([`convex_pieces`]): every later operation
//! (BSP splitting, coverage) then needs only the convex split.
//!
//! Every line of a piece carries its [`Boundary`]: where it comes from in the scene (a side of
//! the face's outline, a diagonal of its convex decomposition, the meeting of two faces' planes,
//! a screen line the BSP chose). The splits set the new line's boundary from what they split by,
//! so provenance survives every operation exactly, as the lines do.

use super::predicates::{
    Line, LineApprox, crossing_f64, crossing_rounded, crossing_with_error, depth_order_at,
    depth_order_filtered, line_side, line_side_filtered, meet_side,
};
use super::{GridPoint, Plane};
use smallvec::SmallVec;
use std::cmp::Ordering;
use std::sync::Arc;

/// Where a line of a piece comes from. Polygons are indices into `ScreenScene::polys`.
///
/// A boundary names the line a side of a piece lies on, not the extent of that side: a piece
/// cut by an occluder (the coverage map subtracts convex pieces line by line) inherits the
/// occluder's lines, boundaries included, and its side along such a line may reach past the
/// occluder's own side, between two visible parts of the same face. Whether a piece side is a
/// contour of the picture is a question of what lies on its two sides, for the consumer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Boundary {
    /// Along the outline of polygon `poly`, starting with its side `side` (from corner `side`
    /// to the next, in the order of `ScreenScene::corners`; `ScreenScene::sides` tells a face
    /// edge from a clip). Where the polygon has straight corners (T-junction vertices), the line
    /// runs on along the following collinear sides.
    Outline {
        /// The polygon.
        poly: u32,
        /// The side: from corner `side` to corner `side + 1` (mod the corner count).
        side: u32,
    },
    /// A diagonal of the convex decomposition of polygon `poly`: inside the face, not an edge.
    Diagonal {
        /// The polygon decomposed.
        poly: u32,
    },
    /// The projection of the line where the support planes of polygons `a` and `b` meet: an
    /// intersection of two faces, or where one passes behind the other. `a` is the polygon
    /// whose piece was split, `b` the one whose plane split it; a piece may inherit the cut
    /// from an occluder, so neither need be the piece's own polygon.
    Cut {
        /// The polygon whose piece was split.
        a: u32,
        /// The polygon whose plane split it.
        b: u32,
    },
    /// A vertical screen line that a BSP split by to balance its tree: no feature of the scene.
    ScreenSplit,
}

/// A convex piece of a face. See the module docs. Pieces are made only here (`from_convex` and
/// the splits), which keep each vertex's line, its cached f64 point and line coefficients and its
/// grid facts together in one [`Vertex`] record; the records are private (read through
/// [`Piece::line`], [`Piece::corner`] and the like) so that nothing else can make them disagree.
///
/// Layout: up to three vertices live inline, so making, splitting and dropping a triangle
/// allocates nothing (one allocation-free record, where seven parallel `Vec`s made seven); a
/// piece of more vertices keeps them in one heap array. 240 bytes (72 a vertex). Room for four
/// inline (312 bytes) left a slot unused in most pieces of most scenes, triangles (92 % of the
/// 1M sphere's visible pieces, 91 % of dragon's): with three, that sphere's `--method bsp`
/// peaks at 385-394 MB instead of 402-411 and runs no slower (bunny, counter, xarm6_link2,
/// dragon, soups, interleaved), though a triangle split in two now makes a quad on the heap.
/// It kept its polygon's grid frame too (376 bytes then), which only tightened
/// [`Piece::bounds`] by at most a vertex's error bound; without it the 1M sphere's `--method
/// bsp` peaked at 527-531 MB instead of 576-577, for 0.1-0.2 % more exact fallbacks in the BSP
/// (boxes looser by that bound).
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// Index of the screen polygon (face) it belongs to.
    pub poly: u32,
    /// The support plane of that polygon: every point of the piece lies in it. Shared by the
    /// polygon's pieces and the cut lines made from it.
    pub support: Arc<Plane>,
    /// Vertex k and the line leaving it, counter-clockwise: vertex k is where lines k-1 and k
    /// cross.
    vertices: SmallVec<[Vertex; 3]>,
}

/// Vertex k of a piece and its line k (from vertex k to vertex k + 1), with what the exact
/// tests cache about the vertex: 72 bytes (80 with a 12-byte [`Boundary`] and an f64 error
/// bound: the 1M sphere's `--method bsp` peaked 12 MB higher). The line's f64 coefficients are
/// not cached ([`Line::approx`] computes them when a test needs them): a 48-byte cache per vertex made
/// every piece 568 bytes instead of 376, and pieces are moved by value at every split. Without
/// it, `render bunny` (one thread) runs 2 % more instructions, no more time (medians of
/// interleaved runs), and the 1M sphere's `--method bsp` peaks at 0.83-0.86 GB instead of
/// 0.94-1.02 GB.
#[derive(Clone, Debug, PartialEq)]
struct Vertex {
    /// Line k: the boundary line from this vertex to the next; the piece is on its positive side.
    line: Line,
    /// The vertex in f64 grid coordinates (x, y), with a proven error bound `error` (e): the
    /// exact vertex is within e of (x, y) in each coordinate (e = 0 at grid corners, at most
    /// [`Piece::POINT_ERROR_MAX`] elsewhere; see [`point_of`]). Computed once when the vertex is
    /// made: sign tests against many lines then cost a dot product each
    /// ([`LineApprox::sign_at`]). Read as (x, y, e) by [`Vertex::point`].
    xy: [f64; 2],
    /// The bound e of `xy`, rounded up to an f32 (so still a bound; 0 stays 0).
    error: f32,
    /// Where line k comes from.
    boundary: PackedBoundary,
    /// Is the vertex a grid point (an input corner, or two face edges crossing exactly at a
    /// mesh vertex)? Exact fast paths use its grid coordinates. They are `xy`,
    /// which hold them exactly (grid coordinates are integers of at most 2^53, every one an
    /// f64), with e = 0: a flag instead of an `Option<[i64; 2]>` keeps the record at 72 bytes
    /// instead of 96.
    is_corner: bool,
    /// Does line k run along an edge of the face's own outline (a [`Line::Edge`] whose both ends
    /// lie on the support plane, the side of the piece within them)? Then a sign that agrees at
    /// both ends holds all along the piece's side: see [`Piece::segment`]. A line that is an
    /// edge of some other face (a split by an occluder's side) is no such segment: the piece's
    /// side along it may reach past its ends.
    on_face_edge: bool,
}

impl Vertex {
    /// The vertex at `point` on `line`, which comes from `boundary`.
    fn new(line: Line, point: VertexPoint, boundary: Boundary, on_face_edge: bool) -> Vertex {
        let mut v = Vertex {
            line,
            xy: [0.0; 2],
            error: 0.0,
            boundary: PackedBoundary::from(boundary),
            is_corner: false,
            on_face_edge,
        };
        v.set_point(point);
        v
    }

    /// The vertex as (x, y, e): see [`Vertex::xy`].
    #[inline]
    fn point(&self) -> [f64; 3] {
        [self.xy[0], self.xy[1], self.error as f64]
    }

    /// Moves the vertex to `point`.
    fn set_point(&mut self, (is_corner, [x, y, e]): VertexPoint) {
        debug_assert!(e >= 0.0 && e.is_finite());
        let rounded = e as f32;
        self.error = if (rounded as f64) < e {
            rounded.next_up()
        } else {
            rounded
        };
        self.xy = [x, y];
        self.is_corner = is_corner;
    }

    #[inline]
    fn corner(&self) -> Option<[i64; 2]> {
        self.is_corner
            .then(|| [self.xy[0] as i64, self.xy[1] as i64])
    }
}

/// A [`Boundary`] in 8 bytes (the enum takes 12): the variant in the top two bits of the first
/// word, beside a polygon index (below 2^30: a screen of that many polygons would need hundreds
/// of gigabytes), the second word the other field.
#[derive(Clone, Copy, PartialEq, Eq)]
struct PackedBoundary([u32; 2]);

impl PackedBoundary {
    const SHIFT: u32 = 30;
    const INDEX: u32 = (1 << Self::SHIFT) - 1;

    /// The boundary packed.
    #[inline]
    fn unpack(self) -> Boundary {
        let [first, second] = self.0;
        let index = first & Self::INDEX;
        match first >> Self::SHIFT {
            0 => Boundary::Outline {
                poly: index,
                side: second,
            },
            1 => Boundary::Diagonal { poly: index },
            2 => Boundary::Cut {
                a: index,
                b: second,
            },
            _ => Boundary::ScreenSplit,
        }
    }
}

impl From<Boundary> for PackedBoundary {
    fn from(b: Boundary) -> Self {
        let with = |variant: u32, index: u32, second: u32| {
            assert!(index <= Self::INDEX, "polygon index {index} below 2^30");
            PackedBoundary([variant << Self::SHIFT | index, second])
        };
        match b {
            Boundary::Outline { poly, side } => with(0, poly, side),
            Boundary::Diagonal { poly } => with(1, poly, 0),
            Boundary::Cut { a, b } => with(2, a, b),
            Boundary::ScreenSplit => with(3, 0, 0),
        }
    }
}

impl std::fmt::Debug for PackedBoundary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.unpack().fmt(f)
    }
}

/// A vertex's point as [`Vertex`] keeps it: whether it is a grid point, and its f64 point with
/// its error bound ([`grid_point`] for a grid point).
type VertexPoint = (bool, [f64; 3]);

/// Grid point (x, y) as a vertex's f64 point: exact (|x|, |y| <= `GRID_MAX` = 2^53), error 0.
fn grid_point([x, y]: [i64; 2]) -> VertexPoint {
    debug_assert!(x.abs() <= super::GRID_MAX && y.abs() <= super::GRID_MAX);
    (true, [x as f64, y as f64, 0.0])
}

/// The signs of a piece's vertices against a plane or line (on the stack up to eight).
type Signs = SmallVec<[Ordering; 8]>;

/// Where a piece lies relative to a plane or a line.
#[derive(Clone, Debug, PartialEq)]
#[allow(clippy::large_enum_variant)] // returned once per split and taken apart at once
pub enum Split {
    /// Entirely on the negative side (touching allowed).
    Negative,
    /// Entirely on the positive side (touching allowed).
    Positive,
    /// On both sides: the negative part and the positive part.
    Both(Piece, Piece),
    /// Every vertex on the plane (only possible for a plane: the piece lies in it).
    On,
}

impl Piece {
    /// The largest error bound of the f64 point a piece keeps for each vertex: a crossing whose
    /// f64 solution would err more is computed exactly and rounded once (an ulp, at most 2 on
    /// the grid). Only two parallel lines would have none: never adjacent lines of a piece.
    pub const POINT_ERROR_MAX: f64 = REFINE_POINT_ABOVE;

    /// The piece of a convex grid polygon (counter-clockwise, y up) in `support`; `side(k)` is
    /// where its side from corner k to corner k + 1 comes from. Straight corners (a corner on the
    /// line through its neighbours, as T-junction vertices are) are dropped: two adjacent lines
    /// of a piece must cross. The merged line keeps the boundary of its first side.
    pub fn from_convex(
        poly: u32,
        support: Plane,
        corners: &[GridPoint],
        side: impl Fn(usize) -> Boundary,
    ) -> Piece {
        use super::predicates::orient2d;
        let m = corners.len();
        // A dropped corner joins the side before it to the side after: the line keeps the
        // boundary of the side that starts at the kept corner before it.
        let mut kept = Vec::with_capacity(m);
        let mut boundaries = Vec::with_capacity(m);
        for k in 0..m {
            if orient2d(corners[(k + m - 1) % m], corners[k], corners[(k + 1) % m])
                != Ordering::Equal
            {
                kept.push(corners[k]);
                boundaries.push(side(k));
            }
        }
        let corners = &kept[..];
        let n = corners.len();
        // Vertex k is corner k; line k runs along the face's side from corner k to k + 1.
        let vertices = (0..n)
            .map(|k| {
                let (c, next) = (corners[k], corners[(k + 1) % n]);
                let line = Line::edge(c, next).expect("consecutive corners differ");
                Vertex::new(line, grid_point([c.x, c.y]), boundaries[k], true)
            })
            .collect();
        Piece {
            poly,
            support: Arc::new(support),
            vertices,
        }
    }

    /// The number of lines (and of vertices).
    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    /// True for no lines (never the case for a piece made here).
    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty()
    }

    /// Line k, from vertex k to vertex k + 1; the piece is on its positive side.
    #[inline]
    pub fn line(&self, k: usize) -> &Line {
        &self.vertices[k].line
    }

    /// The boundary lines, counter-clockwise: vertex k is where lines k-1 and k cross.
    pub fn lines(&self) -> impl ExactSizeIterator<Item = &Line> + Clone {
        self.vertices.iter().map(|v| &v.line)
    }

    /// Where line k comes from.
    #[inline]
    pub fn boundary(&self, k: usize) -> Boundary {
        self.vertices[k].boundary.unpack()
    }

    /// Where each line comes from, in the order of [`Self::lines`].
    pub fn boundaries(&self) -> impl ExactSizeIterator<Item = Boundary> + Clone {
        self.vertices.iter().map(|v| v.boundary.unpack())
    }

    /// The grid (x, y) of vertex k when it is a grid point (an input corner, or two face edges
    /// crossing exactly at a mesh vertex): exact fast paths use it.
    #[inline]
    pub fn corner(&self, k: usize) -> Option<[i64; 2]> {
        self.vertices[k].corner()
    }

    /// Every vertex as a grid point ([`Self::corner`]), `None` when one is not
    /// ([`separated_at_corners`]).
    pub fn grid_corners(&self) -> Option<SmallVec<[[i64; 2]; 6]>> {
        (0..self.len()).map(|k| self.corner(k)).collect()
    }

    /// For line k, the grid (x, y) of the face edge it runs along, when it is one (both ends lie
    /// on the support plane, the piece's side between them): a sign that agrees at both ends
    /// holds all along it.
    #[inline]
    pub fn segment(&self, k: usize) -> Option<[[i64; 2]; 2]> {
        match &self.vertices[k] {
            Vertex {
                on_face_edge: true,
                line: Line::Edge(ends),
                ..
            } => Some(*ends),
            _ => None,
        }
    }

    /// Vertex k in f64 with its proven error bound (x, y, e): see [`Vertex::point`].
    #[inline]
    pub(crate) fn point(&self, k: usize) -> [f64; 3] {
        self.vertices[k].point()
    }

    /// The points of [`Self::point`], in order.
    pub(crate) fn points(&self) -> impl ExactSizeIterator<Item = [f64; 3]> + Clone {
        self.vertices.iter().map(Vertex::point)
    }

    /// `line(k).approx()`.
    #[inline]
    pub(crate) fn line_approx(&self, k: usize) -> LineApprox {
        self.vertices[k].line.approx()
    }

    /// Each line with its f64 coefficients.
    pub(crate) fn lines_with_approx(&self) -> impl ExactSizeIterator<Item = (&Line, LineApprox)> {
        self.vertices.iter().map(|v| (&v.line, v.line.approx()))
    }

    /// `Cut(q, support)`: on the support plane, the sign of `q` (divided by `c_S > 0`).
    fn cut_by(&self, q: &Arc<Plane>) -> Line {
        Line::Cut(q.clone(), self.support.clone())
    }

    /// The two lines through vertex k.
    fn vertex_lines(&self, k: usize) -> [&Line; 2] {
        let n = self.len();
        [self.line((k + n - 1) % n), self.line(k)]
    }

    /// Is the point of the support plane above vertex k on plane `q`, by construction: `q` is
    /// the support plane, or one of the vertex's lines is the cut of the support plane by `q`.
    fn lifted_vertex_on(&self, k: usize, q: &Plane) -> bool {
        *q == *self.support
            || self.vertex_lines(k).iter().any(|own| match own {
                Line::Cut(x, y) => {
                    (**x == *self.support && **y == *q) || (**x == *q && **y == *self.support)
                }
                Line::Edge(_) | Line::Vertical(_) => false,
            })
    }

    /// The three planes whose meeting point projects to vertex k, when both its lines are cuts
    /// sharing a plane: `Cut(X, Y)` and `Cut(X, Z)` (in any order) cross above X ∩ Y ∩ Z.
    fn vertex_meet(&self, k: usize) -> Option<[Plane; 3]> {
        let [Line::Cut(a0, a1), Line::Cut(b0, b1)] = self.vertex_lines(k) else {
            return None;
        };
        let (x, y, z) = if a0 == b0 || a0 == b1 {
            (a0, a1, if a0 == b0 { b1 } else { b0 })
        } else if a1 == b0 || a1 == b1 {
            (a1, a0, if a1 == b0 { b1 } else { b0 })
        } else {
            return None;
        };
        (y != z).then_some([**x, **y, **z])
    }

    /// The sign of plane `q` at vertex k (lifted onto the support plane). `q.c > 0`.
    pub fn vertex_plane_sign(&self, k: usize, q: &Arc<Plane>) -> Ordering {
        self.vertex_plane_sign_with(k, q, &self.cut_by(q).approx())
    }

    /// [`Self::vertex_plane_sign`] given `Cut(q, support)`'s f64 coefficients: on the support
    /// plane, q has the sign of that screen line (`c_S·q - c_q·S`, divided by `c_S > 0`).
    fn vertex_plane_sign_with(&self, k: usize, q: &Arc<Plane>, qa: &LineApprox) -> Ordering {
        // Most signs are far from zero: the cached point settles them in one dot product (at a
        // grid corner exactly, its error bound being 0).
        if let Some(s) = qa.sign_at(self.point(k)) {
            return s;
        }
        if let Some([x, y]) = self.corner(k) {
            return self.cut_by(q).sign_at_grid_exact(x, y);
        }
        if let Some(s) = depth_order_filtered(self.vertex_lines(k), &self.support, q) {
            return s;
        }
        // Splits by one plane meet exactly on it, and a vertex above the meeting point of the
        // support plane and q with a third plane is on q: no arithmetic needed.
        if self.lifted_vertex_on(k, q)
            || self
                .vertex_meet(k)
                .is_some_and(|m| m.contains(&self.support) && m.contains(q))
        {
            return Ordering::Equal;
        }
        // On a face edge whose two ends have the same sign, every point has it: this settles
        // the exact zeros of shared edges without any determinant.
        let n = self.len();
        for seg in [self.segment((k + n - 1) % n), self.segment(k)]
            .into_iter()
            .flatten()
        {
            let [[px, py], [rx, ry]] = seg;
            let on_s = self.cut_by(q);
            let a = on_s.sign_at_grid(px, py);
            if a == on_s.sign_at_grid(rx, ry) {
                return a;
            }
        }
        depth_order_at(self.vertex_lines(k), &self.support, q)
            .expect("adjacent lines of a convex piece cross")
    }

    /// The sign of line `l` at vertex k.
    pub fn vertex_line_sign(&self, k: usize, l: &Line) -> Ordering {
        self.vertex_line_sign_with(k, l, &l.approx())
    }

    /// [`Self::vertex_line_sign`] with `l`'s f64 coefficients computed once by the caller.
    pub fn vertex_line_sign_with(&self, k: usize, l: &Line, la: &LineApprox) -> Ordering {
        // The cached point and its error bound: one dot product settles most signs (at a grid
        // corner exactly).
        if let Some(sign) = la.sign_at(self.point(k)) {
            return sign;
        }
        if let Some([x, y]) = self.corner(k) {
            return l.sign_at_grid_exact(x, y);
        }
        // A vertex lies on the lines that define it: no arithmetic needed.
        let [a, b] = self.vertex_lines(k);
        if a.is_same_or_opposite(l) || b.is_same_or_opposite(l) {
            return Ordering::Equal;
        }
        // The determinant's filter, tighter than the point's where the crossing is
        // ill-conditioned.
        if let Some(sign) = line_side_filtered([a, b], l) {
            return sign;
        }
        // A cut line c_Q·P - c_P·Q has no z term: its sign at the vertex is its sign at any 3D
        // point above it. At a point on Q it is the sign of P there (c_Q > 0), on P the opposite
        // sign of Q, on both zero. Two such points are known by construction: the vertex lifted
        // onto the support plane, and the meeting point of three planes when both lines of the
        // vertex are cuts sharing a plane. These settle the exact zeros of concurrent cuts (three
        // faces cut pairwise meet in one point) with a plane test or none.
        if let Line::Cut(p0, p1) = l
            && p0.c > 0
            && p1.c > 0
        {
            match (self.lifted_vertex_on(k, p0), self.lifted_vertex_on(k, p1)) {
                (true, true) => return Ordering::Equal,
                (false, true) => return self.vertex_plane_sign(k, p0),
                (true, false) => return self.vertex_plane_sign(k, p1).reverse(),
                (false, false) => {}
            }
            if let Some(m) = self.vertex_meet(k) {
                let side = |q: &Plane| {
                    meet_side([&m[0], &m[1], &m[2]], q).expect("crossing cuts meet in a point")
                };
                match (m.contains(p0), m.contains(p1)) {
                    (true, true) => return Ordering::Equal,
                    (false, true) => return side(p0),
                    (true, false) => return side(p1).reverse(),
                    (false, false) => {}
                }
            }
        }
        // On a face edge whose two ends have the same sign, every point has it.
        let n = self.len();
        for [[x0, y0], [x1, y1]] in [self.segment((k + n - 1) % n), self.segment(k)]
            .into_iter()
            .flatten()
        {
            let s0 = l.sign_at_grid(x0, y0);
            if s0 == l.sign_at_grid(x1, y1) {
                return s0;
            }
        }
        line_side(self.vertex_lines(k), l).expect("adjacent lines of a convex piece cross")
    }

    /// Which sides of `q` (`q.c > 0`) the piece reaches, without building parts: (some vertex
    /// strictly negative, some strictly positive). Stops as soon as both are seen.
    pub fn sides_of_plane(&self, q: &Arc<Plane>) -> (bool, bool) {
        if same_plane(&self.support, q) {
            return (false, false);
        }
        let qa = self.cut_by(q).approx();
        self.sides(|k| self.vertex_plane_sign_with(k, q, &qa))
    }

    /// As [`Self::sides_of_plane`], for a screen line.
    pub fn sides_of_line(&self, l: &Line) -> (bool, bool) {
        self.sides_of_line_with(l, &l.approx())
    }

    /// [`Self::sides_of_line`] with `l.approx()` given (computed once by a caller testing many
    /// pieces).
    pub fn sides_of_line_with(&self, l: &Line, la: &LineApprox) -> (bool, bool) {
        self.sides(|k| self.vertex_line_sign_with(k, l, la))
    }

    fn sides(&self, sign: impl Fn(usize) -> Ordering) -> (bool, bool) {
        let (mut neg, mut pos) = (false, false);
        for k in 0..self.len() {
            match sign(k) {
                Ordering::Less => neg = true,
                Ordering::Greater => pos = true,
                Ordering::Equal => {}
            }
            if neg && pos {
                break;
            }
        }
        (neg, pos)
    }

    /// Splits by a support plane `q` (`q.c > 0`), the plane of polygon `by`. The negative part is
    /// the one nearer the viewer; the new line's boundary is `Cut { a: self.poly, b: by }`.
    pub fn split_by_plane(&self, q: &Arc<Plane>, by: u32) -> Split {
        if same_plane(&self.support, q) {
            return Split::On;
        }
        let qa = self.cut_by(q).approx();
        let signs: Signs = (0..self.len())
            .map(|k| self.vertex_plane_sign_with(k, q, &qa))
            .collect();
        // On the support plane, Cut(S, Q) = c_Q·S - c_S·Q has the sign of -Q: positive on the
        // negative part's inside.
        self.split_with(
            &signs,
            Line::Cut(self.support.clone(), q.clone()),
            self.cut_by(q),
            Boundary::Cut {
                a: self.poly,
                b: by,
            },
        )
    }

    /// Splits by a screen line whose boundary is `origin`: the negative part is where `l` is
    /// negative.
    pub fn split_by_line(&self, l: &Line, origin: Boundary) -> Split {
        self.split_by_line_with(l, &l.approx(), origin)
    }

    /// [`Self::split_by_line`] with `l.approx()` given (computed once by a caller testing many
    /// pieces).
    pub fn split_by_line_with(&self, l: &Line, la: &LineApprox, origin: Boundary) -> Split {
        let signs: Signs = (0..self.len())
            .map(|k| self.vertex_line_sign_with(k, l, la))
            .collect();
        self.split_with(&signs, l.negated(), l.clone(), origin)
    }

    /// Splits given the vertex signs; `neg_line` bounds the negative part (positive inside it),
    /// `pos_line` the positive part; both come from `origin`.
    fn split_with(
        &self,
        signs: &[Ordering],
        neg_line: Line,
        pos_line: Line,
        origin: Boundary,
    ) -> Split {
        let has_neg = signs.contains(&Ordering::Less);
        let has_pos = signs.contains(&Ordering::Greater);
        match (has_neg, has_pos) {
            (false, false) => return Split::On,
            (true, false) => return Split::Negative,
            (false, true) => return Split::Positive,
            (true, true) => {}
        }
        Split::Both(
            self.part(signs, Ordering::Less, neg_line, origin),
            self.part(signs, Ordering::Greater, pos_line, origin),
        )
    }

    /// The part on side `side`: the edges with some point strictly on that side, in order, closed
    /// by `closing`. Edge k runs from vertex k to vertex k+1 along line k.
    fn part(&self, signs: &[Ordering], side: Ordering, closing: Line, origin: Boundary) -> Piece {
        let n = self.len();
        // The boundary of the part enters `side` along the edge that runs from a vertex not on
        // `side` to one on it (unique: the piece is convex and straddles), follows the edges
        // from vertices on `side`, and leaves along the first edge that ends off it.
        let start = (0..n)
            .find(|&k| signs[k] != side && signs[(k + 1) % n] == side)
            .expect("a straddling convex piece enters each side once");
        // An end vertex of the run is not on `side`: it is an old vertex when it lies on the cut,
        // a new (implicit) one otherwise.
        // A new vertex where two face edges cross may be a grid point (a mesh vertex): marking
        // it keeps the exact zeros of edges concurrent there out of the determinants.
        let end_vertex = |v: usize, kept: usize| -> VertexPoint {
            if signs[v] == Ordering::Equal {
                return (self.vertices[v].is_corner, self.point(v));
            }
            let point = point_of(&closing, self.line(kept));
            match grid_crossing(&closing, self.line(kept), point) {
                Some(c) => grid_point(c),
                None => (false, point),
            }
        };
        // The kept lines run from `start` to `last_kept`, then the closing line.
        let mut last_kept = start;
        while signs[(last_kept + 1) % n] == side {
            last_kept = (last_kept + 1) % n;
        }
        let last = (last_kept + 1) % n;
        // Vertex 0 joins the closing line and the first kept edge; vertex i joins kept edges
        // i-1 and i; the last joins the last kept edge and the closing line.
        let first = end_vertex(start, start);
        let (last_is_corner, last_point) = end_vertex(last, last_kept);
        let mut vertices = SmallVec::with_capacity((last_kept + n - start) % n + 2);
        let mut k = start;
        loop {
            let mut v = self.vertices[k].clone();
            if k == start {
                v.set_point(first);
            }
            vertices.push(v);
            if k == last_kept {
                break;
            }
            k = (k + 1) % n;
        }
        vertices.push(Vertex::new(
            closing,
            (last_is_corner, last_point),
            origin,
            false,
        ));
        Piece {
            poly: self.poly,
            support: self.support.clone(),
            vertices,
        }
    }

    /// Bounds (x0, y0, x1, y1) in grid units that certainly contain the piece: its f64 vertices
    /// widened by their proven error (exact at grid corners). A filter for spatial indexing: it
    /// may be loose, never too tight. Every vertex has a bound (at most
    /// [`Piece::POINT_ERROR_MAX`]); were one unbounded, so would the box be.
    pub fn bounds(&self) -> [f64; 4] {
        let mut b = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];
        for [x, y, e] in self.points() {
            if !e.is_finite() {
                return [f64::MIN, f64::MIN, f64::MAX, f64::MAX];
            }
            b = [
                b[0].min(x - e),
                b[1].min(y - e),
                b[2].max(x + e),
                b[3].max(y + e),
            ];
        }
        b
    }

    /// Grid bounds (x0, y0, x1, y1) that contain the piece: exact where every vertex is a grid
    /// corner (a piece of a polygon as made, before any cut), else [`Piece::bounds`] rounded
    /// outwards.
    pub fn grid_frame(&self) -> [i64; 4] {
        let mut f = [i64::MAX, i64::MAX, i64::MIN, i64::MIN];
        for k in 0..self.len() {
            let Some([x, y]) = self.corner(k) else {
                let b = self.bounds();
                // Saturating casts: an unbounded box is the whole grid.
                return [
                    b[0].floor() as i64,
                    b[1].floor() as i64,
                    b[2].ceil() as i64,
                    b[3].ceil() as i64,
                ];
            };
            f = [f[0].min(x), f[1].min(y), f[2].max(x), f[3].max(y)];
        }
        f
    }

    /// Is vertex k the same point as `other`'s vertex v? Exact: the cached points settle most
    /// pairs that are apart, then the point must lie on both lines of vertex k.
    pub fn same_vertex(&self, k: usize, other: &Piece, v: usize) -> bool {
        let ([x, y, e], [u, w, f]) = (self.point(k), other.point(v));
        // Each exact coordinate is within e (f) of its f64 one; the slack covers the rounding
        // of the differences. Infinite bounds never reject.
        let apart =
            |a: f64, b: f64| (a - b).abs() > 2.0 * (e + f) + (a.abs() + b.abs()) * f64::EPSILON;
        if apart(x, u) || apart(y, w) {
            return false;
        }
        self.vertex_lines(k)
            .iter()
            .all(|l| other.vertex_line_sign(v, l) == Ordering::Equal)
    }

    /// Vertex k in f64 grid coordinates (rounded: for output and bounds, never decisions).
    pub fn vertex_f64(&self, k: usize) -> [f64; 2] {
        let [x, y, _] = self.point(k);
        [x, y]
    }

    /// The vertices in f64 grid coordinates (rounded once each: for output only).
    pub fn vertices_f64(&self) -> Vec<[f64; 2]> {
        (0..self.len()).map(|k| self.vertex_f64(k)).collect()
    }
}

/// Where two lines cross with its error bound, as [`Piece::point`] holds it: `crossing_f64`'s
/// point and bound when the bound is at most [`REFINE_POINT_ABOVE`], else the correctly rounded
/// crossing within an ulp (the same bits whatever the order of the lines, either way).
fn point_of(l: &Line, m: &Line) -> [f64; 3] {
    match crossing_with_error(l, m) {
        Some(([x, y], e)) if e <= REFINE_POINT_ABOVE => [x, y, e],
        _ => match crossing_rounded(l, m) {
            Some([x, y]) => [x, y, ulp(x).max(ulp(y))],
            None => {
                let [x, y] = crossing_f64(l, m);
                [x, y, f64::INFINITY]
            }
        },
    }
}

/// A vertex whose f64 crossing errs by more than this many grid units (lines crossing at a
/// small angle) is computed exactly and rounded once instead: a loose bound would send every
/// later test of the vertex near any line to the exact path. samurai_monastery's pieces had
/// vertices with bounds up to 5e16 units (a tenth of the screen), each tested exactly against
/// every edge near it when the regions were merged. Well-conditioned crossings err by a few
/// units (f64's precision at the grid's 2^52 scale).
const REFINE_POINT_ABOVE: f64 = 65536.0;

/// The distance from `v` (finite) to the next f64 away from zero: a correctly rounded value is
/// within half of it.
fn ulp(v: f64) -> f64 {
    let a = v.abs();
    f64::from_bits(a.to_bits() + 1) - a
}

/// Where two face-edge lines cross, when that is a grid point, given the crossing in f64 with
/// its error bound ([`point_of`]). The rounded f64 point is tried first with exact i128 signs
/// (a crossing at a shared mesh vertex lands there); when the bound is below one half no other
/// grid point is possible. Otherwise Cramer's rule decides in 256-bit integers, without a
/// division: see [`exact_quotient`].
fn grid_crossing(l: &Line, m: &Line, [x, y, e]: [f64; 3]) -> Option<[i64; 2]> {
    let (Some(p), Some(q)) = (l.vertical_coefficients(), m.vertical_coefficients()) else {
        return None;
    };
    let on_both = |x: i64, y: i64| {
        l.sign_at_grid(x, y) == Ordering::Equal && m.sign_at_grid(x, y) == Ordering::Equal
    };
    let limit = super::GRID_MAX as f64;
    let (rx, ry) = (x.round(), y.round());
    if !(rx.abs() <= limit && ry.abs() <= limit) {
        return exact_grid_crossing(p, q).filter(|&[x, y]| on_both(x, y));
    }
    let (gx, gy) = (rx as i64, ry as i64);
    if on_both(gx, gy) {
        return Some([gx, gy]);
    }
    if e < 0.5 {
        return None;
    }
    // The crossing is (gx + dx, gy + dy) with `a·dx + b·dy = -v` for each line, v its exact
    // value at (gx, gy) (i128: below 2^110). Solved in f64 with a generous bound (conversions,
    // products, sum and division each within U, taken 8 times): when no integer lies within
    // the bound of dx or dy the crossing is no grid point; when the bound is below one half
    // only the rounded offsets can be one, checked exactly.
    let value = |[a, b, d]: [i128; 3]| a * gx as i128 + b * gy as i128 + d;
    let (v1, v2) = (value(p), value(q));
    let ([pa, pb, _], [qa, qb, _]) = (p, q);
    let den = super::i128_to_f64(pa * qb - qa * pb);
    if den == 0.0 {
        return None;
    }
    let solve = |n1: f64, n2: f64| {
        let terms = (-super::i128_to_f64(v1) * n2, super::i128_to_f64(v2) * n1);
        let d = (terms.0 + terms.1) / den;
        let bound = 8.0 * super::U * ((terms.0.abs() + terms.1.abs()) / den.abs() + d.abs());
        (d, bound)
    };
    let (dx, ex) = solve(super::i128_to_f64(pb), super::i128_to_f64(qb));
    let (dy, ey) = solve(-super::i128_to_f64(pa), -super::i128_to_f64(qa));
    if (dx - dx.round()).abs() > ex || (dy - dy.round()).abs() > ey {
        return None;
    }
    if ex < 0.5 && ey < 0.5 {
        let (cx, cy) = (gx + dx.round() as i64, gy + dy.round() as i64);
        return (cx.abs() <= super::GRID_MAX && cy.abs() <= super::GRID_MAX && on_both(cx, cy))
            .then_some([cx, cy]);
    }
    exact_grid_crossing(p, q).filter(|&[x, y]| on_both(x, y))
}

/// Where two vertical lines (coefficients (a, b, d)) cross when that is a grid point, by
/// Cramer's rule in 256-bit integers, without a division: see [`exact_quotient`].
fn exact_grid_crossing([pa, pb, pd]: [i128; 3], [qa, qb, qd]: [i128; 3]) -> Option<[i64; 2]> {
    use bnum::cast::As;
    use bnum::types::I256;
    // Edge coefficients: a, b below 2^55, d below 2^108.
    let w = |v: i128| -> I256 { v.as_() };
    let den = w(pa * qb - qa * pb);
    if den == w(0) {
        return None;
    }
    let nx = w(pb) * w(qd) - w(qb) * w(pd);
    let ny = w(qa) * w(pd) - w(pa) * w(qd);
    Some([exact_quotient(nx, den)?, exact_quotient(ny, den)?])
}

/// `n / den` when it is an integer within the grid, exactly. The quotient X is estimated in f64
/// (two correctly rounded conversions and a division: relative error below 3·U, so within 3
/// units for |X| <= 2^53), the remainder `r = n - den·q` of the rounded estimate q taken
/// exactly in 256 bits, and `r / den = X - q`, at most 3.5, estimated the same way (now within
/// 2^-50) and checked: two multiplications instead of a 256-bit division. Nothing is returned
/// that is not exact; every integer X within the grid is found.
fn exact_quotient(n: bnum::types::I256, den: bnum::types::I256) -> Option<i64> {
    use bnum::cast::As;
    use bnum::types::I256;
    let limit = 2.0 * super::GRID_MAX as f64;
    let approx = |n: I256| super::i256_to_f64(n) / super::i256_to_f64(den);
    let q = approx(n).round();
    if q.is_nan() || q.abs() > limit {
        return None;
    }
    let q = q as i64;
    let r = n - den * q.as_::<I256>();
    if r == 0i64.as_::<I256>() {
        return (q.abs() <= super::GRID_MAX).then_some(q);
    }
    // X = q + r / den; when X is an integer within the grid, |r / den| <= 3.5 and its estimate
    // rounds to it (a larger k means X is outside the grid or q was far off).
    let k = approx(r).round();
    if k.is_nan() || k.abs() > 64.0 {
        return None;
    }
    let k = k as i64;
    (r == den * k.as_::<I256>())
        .then(|| q + k)
        .filter(|v| v.abs() <= super::GRID_MAX)
}

/// Do two convex pieces have disjoint interiors? Exact: some edge line of one has the other
/// entirely on its outer side (touching allowed); for convex polygons such a line exists
/// whenever they do not overlap.
pub fn separated(p: &Piece, q: &Piece) -> bool {
    separated_at_corners(p, q).unwrap_or_else(|| separated_by_lines(p, q))
}

/// [`separated`] by the pieces' lines, whatever their vertices.
pub fn separated_by_lines(p: &Piece, q: &Piece) -> bool {
    let outside = |a: &Piece, b: &Piece| {
        a.lines_with_approx()
            .any(|(l, la)| !b.sides_of_line_with(l, &la).1)
    };
    outside(q, p) || outside(p, q)
}

/// [`separated`] for two pieces whose vertices are all grid corners (uncut faces, the common
/// case), in i128 on the corners themselves with no line's coefficients: `None` when a vertex
/// of either is not a corner. `separated` tries it first.
pub fn separated_at_corners(p: &Piece, q: &Piece) -> Option<bool> {
    Some(corners_separated(&p.grid_corners()?, &q.grid_corners()?))
}

/// [`separated_at_corners`] on the pieces' [`Piece::grid_corners`] (for a caller testing each
/// piece against many: [`CornerLines`] keeps the edge lines too).
pub fn corners_separated(pc: &[[i64; 2]], qc: &[[i64; 2]]) -> bool {
    // `p`'s lines are made only when `q`'s leave it undecided.
    CornerLines::new(qc, &edge_lines(qc)).excludes(pc)
        || CornerLines::new(pc, &edge_lines(pc)).excludes(qc)
}

/// The line through an edge of a convex grid polygon as `a·x + b·y + c`: positive strictly
/// inside the polygon, zero on the line. Exact in i128: for corners within the grid
/// (|x|, |y| <= 2^53), |a| and |b| are at most 2^54 and |c| at most 2^108, so a value at a grid
/// point is below 2^110. It is the edge's `cross_xy` turned by the polygon's orientation, with
/// the products that do not depend on the point made once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeLine {
    a: i64,
    b: i64,
    c: i128,
}

impl EdgeLine {
    /// The line's value at `v`.
    #[inline]
    pub fn at(&self, v: [i64; 2]) -> i128 {
        self.a as i128 * v[0] as i128 + self.b as i128 * v[1] as i128 + self.c
    }
}

/// Adds to `out` the edge lines of the convex polygon with these corners (either turn), one per
/// edge in order; none when the corners lie on one line (such a polygon has no inside).
pub fn push_edge_lines(corners: &[[i64; 2]], out: &mut impl Extend<EdgeLine>) {
    use super::predicates::cross_xy;
    let turn = (1..corners.len().saturating_sub(1))
        .map(|i| cross_xy(corners[0], corners[i], corners[i + 1]).signum())
        .find(|&t| t != 0)
        .unwrap_or(0) as i64;
    if turn == 0 {
        return;
    }
    let mut c = corners[corners.len() - 1];
    out.extend(corners.iter().map(|&d| {
        let (dx, dy) = ((d[0] - c[0]) * turn, (d[1] - c[1]) * turn);
        // cross_xy(c, d, v) · turn = dx·(vy - cy) - dy·(vx - cx).
        let line = EdgeLine {
            a: -dy,
            b: dx,
            c: dy as i128 * c[0] as i128 - dx as i128 * c[1] as i128,
        };
        c = d;
        line
    }));
}

/// [`push_edge_lines`] of one polygon, for a test or a few.
pub fn edge_lines(corners: &[[i64; 2]]) -> SmallVec<[EdgeLine; 6]> {
    let mut lines = SmallVec::new();
    push_edge_lines(corners, &mut lines);
    lines
}

/// A convex grid polygon's corners with its [`push_edge_lines`], owned: see [`CornerLines`].
#[derive(Clone, Debug)]
pub struct CornerOutline {
    corners: SmallVec<[[i64; 2]; 6]>,
    lines: SmallVec<[EdgeLine; 6]>,
}

impl CornerOutline {
    /// The convex polygon with these corners (either turn).
    pub fn of(corners: &[[i64; 2]]) -> Self {
        CornerOutline {
            corners: SmallVec::from_slice(corners),
            lines: edge_lines(corners),
        }
    }

    /// Borrowed, to test against others.
    pub fn view(&self) -> CornerLines<'_> {
        CornerLines::new(&self.corners, &self.lines)
    }
}

/// A convex grid polygon's corners with its [`push_edge_lines`], borrowed: the lines are found
/// once for a polygon tested against many.
#[derive(Clone, Copy, Debug)]
pub struct CornerLines<'a> {
    corners: &'a [[i64; 2]],
    lines: &'a [EdgeLine],
}

impl<'a> CornerLines<'a> {
    /// `lines` must be [`push_edge_lines`] of `corners`.
    pub fn new(corners: &'a [[i64; 2]], lines: &'a [EdgeLine]) -> Self {
        debug_assert!(lines.is_empty() || lines.len() == corners.len());
        CornerLines { corners, lines }
    }

    /// The polygon's corners.
    pub fn corners(self) -> &'a [[i64; 2]] {
        self.corners
    }

    /// Do the two polygons have disjoint interiors? Exact: an edge line of one has every corner
    /// of the other on its closed outer side (touching allowed).
    #[inline]
    pub fn separated(self, other: CornerLines) -> bool {
        other.excludes(self.corners) || self.excludes(other.corners)
    }

    /// Has one of the polygon's edge lines all of `corners` on its closed outer side? (Then a
    /// convex polygon with those corners has no interior point in common with this one.)
    #[inline]
    pub fn excludes(self, corners: &[[i64; 2]]) -> bool {
        // A line stops at the first corner strictly inside it: testing every corner without a
        // branch was slower (the 1M sphere's bsp stage by 11-13 %, one thread).
        (self.lines.iter()).any(|l| corners.iter().all(|&v| l.at(v) <= 0))
    }
}

/// Are two support planes (c > 0) the same plane? Exact: their coefficients are proportional
/// with a positive factor. The f64 cross products settle almost every pair that differs; the
/// rest is compared in 512-bit integers (offsets below 2^165 times normals below 2^109).
pub fn same_plane(s: &Plane, q: &Plane) -> bool {
    use bnum::cast::As;
    use bnum::types::I512;
    if s == q {
        return true;
    }
    // Each product of two rounded coefficients errs by at most 3·U of its magnitude; a
    // difference larger than that sum (doubled) is not zero.
    let (sc, qc) = (super::i128_to_f64(s.c), super::i128_to_f64(q.c));
    let differs = |sv: f64, qv: f64| {
        let (l, r) = (sv * qc, qv * sc);
        (l - r).abs() > 8.0 * super::U * (l.abs() + r.abs())
    };
    if differs(super::i128_to_f64(s.a), super::i128_to_f64(q.a))
        || differs(super::i128_to_f64(s.b), super::i128_to_f64(q.b))
        || differs(super::i256_to_f64(s.d), super::i256_to_f64(q.d))
    {
        return false;
    }
    let w = |v: i128| -> I512 { v.as_() };
    let wd = |v: bnum::types::I256| -> I512 { v.as_() };
    let (sc, qc) = (w(s.c), w(q.c));
    w(s.a) * qc == w(q.a) * sc && w(s.b) * qc == w(q.b) * sc && wd(s.d) * qc == wd(q.d) * sc
}

/// Cuts a simple grid polygon (counter-clockwise, y up, no repeated consecutive points) into
/// convex polygons, exactly: ear clipping with exact orientation tests, then merging triangles
/// back across diagonals while the union stays convex (Hertel–Mehlhorn). A convex polygon comes
/// back whole.
pub fn convex_pieces(points: &[GridPoint]) -> Vec<Vec<GridPoint>> {
    convex_piece_indices(points)
        .into_iter()
        .map(|p| p.into_iter().map(|v| points[v]).collect())
        .collect()
}

/// [`convex_pieces`] as indices into `points`: a side from index i to (i + 1) mod n is a side of
/// the polygon, any other a diagonal.
pub fn convex_piece_indices(points: &[GridPoint]) -> Vec<Vec<usize>> {
    use super::predicates::orient2d;
    let n = points.len();
    let convex = |ring: &[GridPoint]| {
        let m = ring.len();
        (0..m).all(|k| orient2d(ring[k], ring[(k + 1) % m], ring[(k + 2) % m]) != Ordering::Less)
    };
    if convex(points) {
        return vec![(0..n).collect()];
    }
    let triangles = ear_triangles(points);
    // Hertel–Mehlhorn: greedily merge pieces that share an edge while the result stays convex.
    let mut pieces: Vec<Vec<usize>> = triangles.into_iter().map(|t| t.to_vec()).collect();
    let mut merged = true;
    while merged {
        merged = false;
        'outer: for i in 0..pieces.len() {
            for j in i + 1..pieces.len() {
                if let Some(u) = merge_along_shared_edge(&pieces[i], &pieces[j]) {
                    let ring: Vec<GridPoint> = u.iter().map(|&v| points[v]).collect();
                    if convex(&ring) && straight_only_along_the_outline(&u, &ring, n) {
                        pieces[i] = u;
                        pieces.swap_remove(j);
                        merged = true;
                        break 'outer;
                    }
                }
            }
        }
    }
    pieces
}

/// Triangles of a simple grid polygon (counter-clockwise, y up), as index triples in the
/// polygon's orientation: ear clipping with exact orientation tests. Corners on the line
/// through their neighbours (straight corners) are never ear tips, so no triangle has zero
/// area; a self-touching polygon ends in a fan of what is left (its triangles may then overlap,
/// never crash).
pub fn ear_triangles(points: &[GridPoint]) -> Vec<[usize; 3]> {
    use super::predicates::orient2d;
    let n = points.len();
    // Ear clipping on indices.
    let mut idx: Vec<usize> = (0..n).collect();
    let mut triangles: Vec<[usize; 3]> = Vec::new();
    let mut guard = 0;
    while idx.len() > 3 && guard < n * n {
        guard += 1;
        let m = idx.len();
        let mut clipped = false;
        for k in 0..m {
            let (a, b, c) = (idx[(k + m - 1) % m], idx[k], idx[(k + 1) % m]);
            if orient2d(points[a], points[b], points[c]) != Ordering::Greater {
                continue;
            }
            let inside = idx.iter().any(|&j| {
                j != a
                    && j != b
                    && j != c
                    && orient2d(points[a], points[b], points[j]) != Ordering::Less
                    && orient2d(points[b], points[c], points[j]) != Ordering::Less
                    && orient2d(points[c], points[a], points[j]) != Ordering::Less
            });
            if inside {
                continue;
            }
            triangles.push([a, b, c]);
            idx.remove(k);
            clipped = true;
            break;
        }
        if !clipped {
            // Not a simple polygon (self-touching): drop collinear spikes by taking a fan of the
            // rest; pieces of a malformed input polygon may then overlap, never crash.
            break;
        }
    }
    if idx.len() >= 3 {
        for k in 1..idx.len() - 1 {
            if orient2d(points[idx[0]], points[idx[k]], points[idx[k + 1]]) == Ordering::Greater {
                triangles.push([idx[0], idx[k], idx[k + 1]]);
            }
        }
    }
    triangles
}

/// Does the piece `u` (indices into a polygon of `n` corners, at `ring`) have a straight corner
/// only where two sides of the polygon's outline run on? A piece drops its straight corners, and
/// its line then takes the boundary of the side before: a diagonal running on from an outline
/// side (or the other way) would be mislabelled, so such merges are not made.
fn straight_only_along_the_outline(u: &[usize], ring: &[GridPoint], n: usize) -> bool {
    use super::predicates::orient2d;
    let m = u.len();
    let outline = |a: usize, b: usize| b == (a + 1) % n;
    (0..m).all(|k| {
        let (a, b, c) = ((k + m - 1) % m, k, (k + 1) % m);
        orient2d(ring[a], ring[b], ring[c]) != Ordering::Equal
            || (outline(u[a], u[b]) && outline(u[b], u[c]))
    })
}

/// The union ring of two index rings sharing exactly one edge (a→b in one, b→a in the other).
fn merge_along_shared_edge(p: &[usize], q: &[usize]) -> Option<Vec<usize>> {
    let (np, nq) = (p.len(), q.len());
    for i in 0..np {
        let (a, b) = (p[i], p[(i + 1) % np]);
        for j in 0..nq {
            if q[j] == b && q[(j + 1) % nq] == a {
                // p: ..., a, b, ...  and q: ..., b, a, ...: walk p from b to a, then q's rest.
                let mut ring = Vec::with_capacity(np + nq - 2);
                for k in 0..np {
                    ring.push(p[(i + 1 + k) % np]);
                }
                // ring ends with a; continue along q after a up to before b.
                for k in 2..nq {
                    ring.push(q[(j + k) % nq]);
                }
                return Some(ring);
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The division-free quotient agrees with 256-bit division: integers anywhere in the grid
    /// (its ends included) are found, non-integers and quotients off the grid are refused.
    #[test]
    fn exact_quotient_agrees_with_division() {
        use bnum::cast::As;
        use bnum::types::I256;
        let mut rng = crate::stress::rng::Rng::of(&[0x2545_f491_4f6c_dd1d]);
        let mut next = move || rng.next_u64();
        let g = crate::exact::GRID_MAX;
        for case in 0..30_000 {
            let den_bits = 1 + next() % 110;
            let den: I256 =
                ((next() as i128) << 64 | next() as i128).as_::<I256>() >> (128 - den_bits as u32);
            if den == 0i64.as_::<I256>() {
                continue;
            }
            let x: i64 = match case % 4 {
                0 => g - (next() % 4) as i64,
                1 => -g + (next() % 4) as i64,
                _ => (next() as i64) >> (next() % 64),
            };
            let off = [0i64, 0, 1, -1, 7][case % 5];
            let n = den * x.as_::<I256>() + off.as_::<I256>();
            let want = (n % den == 0i64.as_::<I256>())
                .then(|| n / den)
                .filter(|q| q.abs() <= g.as_::<I256>())
                .map(|q| q.as_::<i64>());
            assert_eq!(exact_quotient(n, den), want, "n {n} den {den}");
        }
    }

    /// Separation by each edge's `cross_xy` times the polygon's turn, as it was computed before
    /// [`EdgeLine`]: the reference the lines must agree with.
    fn separated_by_crosses(pc: &[[i64; 2]], qc: &[[i64; 2]]) -> bool {
        use super::super::predicates::cross_xy;
        fn outside(a: &[[i64; 2]], b: &[[i64; 2]]) -> bool {
            let turn = (1..a.len() - 1)
                .map(|i| cross_xy(a[0], a[i], a[i + 1]).signum())
                .find(|&t| t != 0)
                .unwrap_or(0);
            turn != 0
                && (0..a.len()).any(|k| {
                    let (c, d) = (a[(k + a.len() - 1) % a.len()], a[k]);
                    b.iter().all(|&v| cross_xy(c, d, v) * turn <= 0)
                })
        }
        outside(qc, pc) || outside(pc, qc)
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(3000))]

        /// The edge lines decide separation as the crosses do: triangles on a coarse lattice
        /// (so corners are shared, collinear and repeated often) scaled to the grid's ends,
        /// where the lines' products are largest, in either turn.
        #[test]
        fn edge_lines_separate_as_the_crosses_do(
            p in proptest::collection::vec((-4i64..=4, -4i64..=4), 3),
            q in proptest::collection::vec((-4i64..=4, -4i64..=4), 3),
            shift in (-4i64..=4, -4i64..=4),
            scale_bits in 0u32..=50,
        ) {
            let g = |(x, y): (i64, i64)| [x << scale_bits, y << scale_bits];
            let pc: Vec<[i64; 2]> = p.into_iter().map(g).collect();
            // Shifted by whole lattice steps, the second triangle stays within the grid.
            let q_shift =
                |(x, y): (i64, i64)| ((x + shift.0).clamp(-8, 8), (y + shift.1).clamp(-8, 8));
            let qc: Vec<[i64; 2]> = q.into_iter().map(q_shift).map(g).collect();
            assert!(pc.iter().chain(&qc).flatten().all(|v| v.abs() <= crate::exact::GRID_MAX));
            let want = separated_by_crosses(&pc, &qc);
            proptest::prop_assert_eq!(corners_separated(&pc, &qc), want);
            proptest::prop_assert_eq!(corners_separated(&qc, &pc), want);
        }
    }

    fn area(v: &[[f64; 2]]) -> f64 {
        let n = v.len();
        (0..n)
            .map(|k| v[k][0] * v[(k + 1) % n][1] - v[(k + 1) % n][0] * v[k][1])
            .sum::<f64>()
            / 2.0
    }

    /// Exact validity: every vertex is inside or on every line of the piece.
    fn assert_valid(p: &Piece) {
        assert!(p.len() >= 3);
        for k in 0..p.len() {
            for l in p.lines() {
                assert_ne!(p.vertex_line_sign(k, l), Ordering::Less, "{p:?}");
            }
        }
        assert!(area(&p.vertices_f64()) > 0.0);
    }

    fn square() -> Piece {
        let c = [
            GridPoint::new(0, 0, 0),
            GridPoint::new(100, 0, 0),
            GridPoint::new(100, 100, 0),
            GridPoint::new(0, 100, 0),
        ];
        let support = Plane::through(c[0], c[1], c[2]).unwrap();
        Piece::from_convex(0, support, &c, |side| Boundary::Outline {
            poly: 0,
            side: side as u32,
        })
    }

    #[test]
    fn split_square_by_line_through_the_middle() {
        let sq = square();
        let l = Line::edge(GridPoint::new(50, -10, 0), GridPoint::new(50, 200, 0)).unwrap();
        let Split::Both(neg, pos) = sq.split_by_line(&l, Boundary::ScreenSplit) else {
            panic!()
        };
        assert_valid(&neg);
        assert_valid(&pos);
        // Positive side of an edge p→q is its left: x < 50.
        let (an, ap) = (area(&neg.vertices_f64()), area(&pos.vertices_f64()));
        assert_eq!((an, ap), (5000.0, 5000.0));
        assert!(pos.vertices_f64().iter().all(|v| v[0] <= 50.0));
    }

    #[test]
    fn split_through_vertices_keeps_them_exact() {
        let sq = square();
        let l = Line::edge(GridPoint::new(0, 0, 0), GridPoint::new(100, 100, 0)).unwrap();
        let Split::Both(neg, pos) = sq.split_by_line(&l, Boundary::ScreenSplit) else {
            panic!()
        };
        assert_eq!((neg.len(), pos.len()), (3, 3));
        // The diagonal's ends are the square's corners, kept as grid points.
        assert!((0..neg.len()).all(|k| neg.corner(k).is_some()));
        assert!((0..pos.len()).all(|k| pos.corner(k).is_some()));
        // A line touching at a corner only does not split.
        // Its left (positive) side is x + y > 200: the square is on the negative side.
        let t = Line::edge(GridPoint::new(100, 100, 0), GridPoint::new(200, 0, 0)).unwrap();
        assert_eq!(sq.split_by_line(&t, Boundary::ScreenSplit), Split::Negative);
    }

    #[test]
    fn split_by_a_plane_keeps_the_nearer_part_negative() {
        // The square at z = 0 (tilted support through the corners), cut by the plane z = x - 50:
        // for x < 50 the square is above that plane (farther), for x > 50 below it (nearer).
        let sq = square();
        let q = Arc::new(
            Plane::through(
                GridPoint::new(50, 0, 0),
                GridPoint::new(50, 100, 0),
                GridPoint::new(0, 0, -50),
            )
            .unwrap(),
        );
        assert!(q.c > 0);
        let Split::Both(near, far) = sq.split_by_plane(&q, 7) else {
            panic!()
        };
        assert_valid(&near);
        assert_valid(&far);
        assert!(
            near.vertices_f64().iter().all(|v| v[0] >= 50.0),
            "{:?}",
            near.vertices_f64()
        );
        assert!(far.vertices_f64().iter().all(|v| v[0] <= 50.0));
        assert_eq!(sq.split_by_plane(&sq.support, 0), Split::On);
    }

    /// Each part keeps the boundaries of the sides it keeps, in order, and closes with the
    /// splitter's: a cut by polygon 7's plane, then a screen split.
    #[test]
    fn splits_keep_each_line_with_its_boundary() {
        let sq = square();
        let q = Arc::new(
            Plane::through(
                GridPoint::new(50, 0, 0),
                GridPoint::new(50, 100, 0),
                GridPoint::new(0, 0, -50),
            )
            .unwrap(),
        );
        let Split::Both(near, far) = sq.split_by_plane(&q, 7) else {
            panic!()
        };
        let cut = Boundary::Cut { a: 0, b: 7 };
        let side = |side| Boundary::Outline { poly: 0, side };
        // The square's sides run bottom (0), right (1), top (2), left (3); x > 50 is nearer.
        let boundaries = |p: &Piece| p.boundaries().collect::<Vec<_>>();
        assert_eq!(boundaries(&near), vec![side(0), side(1), side(2), cut]);
        assert_eq!(boundaries(&far), vec![side(2), side(3), side(0), cut]);
        let l = Line::edge(GridPoint::new(0, 50, 0), GridPoint::new(200, 50, 0)).unwrap();
        let Split::Both(below, above) = far.split_by_line(&l, Boundary::ScreenSplit) else {
            panic!()
        };
        assert!(boundaries(&below).contains(&Boundary::ScreenSplit));
        assert!(boundaries(&above).contains(&Boundary::ScreenSplit));
        assert!(boundaries(&below).contains(&cut) && boundaries(&above).contains(&cut));
    }

    #[test]
    fn repeated_random_splits_stay_valid_and_keep_area() {
        let mut seed = 42u64;
        let mut rnd = |m: i64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % (2 * m as u64 + 1)) as i64 - m
        };
        for _ in 0..200 {
            let mut pieces = vec![square()];
            for _ in 0..6 {
                let (a, b) = (
                    GridPoint::new(rnd(150), rnd(150), 0),
                    GridPoint::new(rnd(150), rnd(150), 0),
                );
                let Some(l) = Line::edge(a, b) else { continue };
                let mut next = Vec::new();
                for p in &pieces {
                    match p.split_by_line(&l, Boundary::ScreenSplit) {
                        Split::Both(n, q) => {
                            assert_valid(&n);
                            assert_valid(&q);
                            next.push(n);
                            next.push(q);
                        }
                        _ => next.push(p.clone()),
                    }
                }
                pieces = next;
            }
            let total: f64 = pieces.iter().map(|p| area(&p.vertices_f64())).sum();
            assert!((total - 10000.0).abs() < 1e-6, "{total}");
        }
    }

    /// Every boundary comes back from its 8-byte record as it went in, the largest polygon
    /// index too; one past it is refused, never folded into another boundary.
    #[test]
    fn packed_boundaries_unpack_to_what_was_packed() {
        let top = PackedBoundary::INDEX;
        let all = [
            Boundary::Outline { poly: 0, side: 0 },
            Boundary::Outline {
                poly: top,
                side: u32::MAX,
            },
            Boundary::Diagonal { poly: 7 },
            Boundary::Diagonal { poly: top },
            Boundary::Cut { a: 3, b: 9 },
            Boundary::Cut {
                a: top,
                b: u32::MAX,
            },
            Boundary::ScreenSplit,
        ];
        for b in all {
            assert_eq!(PackedBoundary::from(b).unpack(), b);
        }
        let too_far =
            std::panic::catch_unwind(|| PackedBoundary::from(Boundary::Diagonal { poly: top + 1 }));
        assert!(too_far.is_err());
    }

    /// The layout the module docs promise (64-bit targets): a 40-byte line, a 72-byte vertex
    /// record, three of them inline.
    #[test]
    #[cfg(target_pointer_width = "64")]
    fn layout_sizes() {
        use std::mem::size_of;
        assert_eq!(size_of::<Line>(), 40);
        assert_eq!(size_of::<Vertex>(), 72);
        assert_eq!(size_of::<Piece>(), 240);
        // Splitting a triangle by a line through none of its corners: a triangle, inline, and
        // a quad, on the heap.
        let c = [
            GridPoint::new(0, 0, 0),
            GridPoint::new(100, 0, 0),
            GridPoint::new(0, 100, 0),
        ];
        let tri = Piece::from_convex(0, Plane::through(c[0], c[1], c[2]).unwrap(), &c, |side| {
            Boundary::Outline {
                poly: 0,
                side: side as u32,
            }
        });
        let l = Line::edge(GridPoint::new(50, -10, 0), GridPoint::new(50, 200, 0)).unwrap();
        let Split::Both(neg, pos) = tri.split_by_line(&l, Boundary::ScreenSplit) else {
            panic!()
        };
        assert_eq!((neg.len(), pos.len()), (3, 4));
        assert!(!tri.vertices.spilled() && !neg.vertices.spilled() && pos.vertices.spilled());
        // The corners the split kept are grid points still, the new ones too (x = 50 on the
        // grid), read back exactly from the f64 points.
        let mut quad: Vec<_> = (0..4).map(|k| pos.corner(k)).collect();
        quad.sort();
        let want = [[0, 0], [0, 100], [50, 0], [50, 50]].map(Some);
        assert_eq!(quad, want);
        assert!((0..neg.len()).all(|k| neg.corner(k).is_some()));
    }

    #[test]
    fn convex_pieces_of_an_l_shape() {
        let l = [
            GridPoint::new(0, 0, 0),
            GridPoint::new(20, 0, 0),
            GridPoint::new(20, 10, 0),
            GridPoint::new(10, 10, 0),
            GridPoint::new(10, 20, 0),
            GridPoint::new(0, 20, 0),
        ];
        let pieces = convex_pieces(&l);
        assert_eq!(pieces.len(), 2);
        let total: f64 = pieces
            .iter()
            .map(|p| {
                area(
                    &p.iter()
                        .map(|q| [q.x as f64, q.y as f64])
                        .collect::<Vec<_>>(),
                )
            })
            .sum();
        assert_eq!(total, 300.0);
        let square = [
            GridPoint::new(0, 0, 0),
            GridPoint::new(1, 0, 0),
            GridPoint::new(1, 1, 0),
            GridPoint::new(0, 1, 0),
        ];
        assert_eq!(convex_pieces(&square), vec![square.to_vec()]);
    }
}
