//! Exact predicates on planes and lines of the screen grid, with split points kept implicit.
//!
//! Geometry is in grid space (see the parent module): a face lies in its support [`Plane`]; an
//! edge is a vertical plane, i.e. a [`Line`] on screen. A point that splitting creates is never
//! rounded: it is named by the planes that meet there ([`meet_side`], [`depth_order_at`]) or by
//! two lines ([`line_side`]), and every decision about it is the sign of a small determinant of
//! the defining coefficients.
//!
//! A [`Line`] is an input edge (a vertical plane through two grid points, coefficients below
//! 2^55 and 2^108, kept as its two ends), another vertical plane (screen and sample lines,
//! within the same bounds) or the screen projection of the meeting of two input planes,
//! `c_Q·P - c_P·Q` (a support plane's normal is below 2^109 and its offset below 2^165, so the
//! cut's coefficients are below 2^219 and 2^275). The largest determinant any predicate here
//! takes is of degree 13 in the grid coordinates:
//! - the side of a line at the crossing of two cuts, `det3` of three cut rows: at most 6 terms
//!   of 2^219 · 2^219 · 2^275, below 2^716;
//! - the depth order of two support planes at the crossing of two cuts, `det4(S, m0, m1, T)`:
//!   at most 24 terms, each a product of one entry per row in distinct columns, the largest
//!   2^165 · 2^219 · 2^219 · 2^109 (or 2^109 · 2^219 · 2^275 · 2^109), below 2^717;
//! - the meeting point of three support planes against a fourth, `det4` of plane rows, below
//!   2^500.
//!
//! so the exact path computes in integers of at most 768 bits: fixed width, no growth however
//! often a polygon is split, because every line and plane is built from input planes only. The
//! predicates' fallbacks use [`super::big::Big`], whose products cost the limbs their operands
//! have; [`Line::exact`] gives the coefficients as [`Wide`] for callers that divide.
//!
//! **Filter.** Every predicate first evaluates its determinant in f64. Each entry is carried with
//! a magnitude `M >= |entry|` and an error below `5·U·M`: an input coefficient is rounded once
//! to f64 (the grid's integers exceed 2^53), and a cut's entry `c_Q·p - c_P·q` takes two
//! rounded inputs per product, the product's rounding and the subtraction's. A Laplace expansion
//! of an n x n determinant multiplies n entries and sums its terms; with entry error `e·U·M` its
//! error is below `(2e + 1)·U·perm(M)` for n = 2, `(3e + 5)·U·perm(M)` for n = 3 and
//! `(4e + 9)·U·perm(M) = 29·U·perm(M)` for n = 4 and e = 5, where `perm(M)` is the permanent of
//! the magnitudes (to first order in U; the margin below covers the higher-order terms). When
//! `|det| > 32·U·perm(M)`, the f64 sign is the exact sign; otherwise the 768-bit computation
//! decides. Each fallback is counted ([`fallback_count`]).

use super::big::Big;
use super::{GridPoint, Plane, U, i128_to_f64, i256_to_f64, w256};
use bnum::cast::As;
use bnum::types::I512;
use std::cell::Cell;
use std::cmp::Ordering;
use std::sync::Arc;

/// The exact path's integers: 768 bits, enough for every determinant here (module docs).
pub type Wide = bnum::Int<96>;

thread_local! {
    static FALLBACKS: Cell<u64> = const { Cell::new(0) };
}

/// How many predicate evaluations on this thread the f64 filter could not decide.
pub fn fallback_count() -> u64 {
    FALLBACKS.with(|c| c.get())
}

/// Adds `n` to this thread's count: fallbacks counted on other threads for work done on its
/// behalf ([`crate::visibility::strips`]).
pub(crate) fn add_fallbacks(n: u64) {
    FALLBACKS.with(|c| c.set(c.get() + n));
}

/// Sets this thread's count back to `n`, an earlier [`fallback_count`]: work thrown away whose
/// extent depended on other threads' timing, so that the counts stay deterministic.
pub(crate) fn reset_fallbacks(n: u64) {
    FALLBACKS.with(|c| c.set(n));
}

fn count_fallback() {
    FALLBACKS.with(|c| c.set(c.get() + 1));
}

/// A line on screen: a vertical plane `a·x + b·y + d = 0` of the grid. Its positive side is its
/// left (counter-clockwise interior, y up) for edges made by [`Line::edge`].
///
/// A line is 40 bytes: every piece holds one per vertex, so its size is the pieces' size. An
/// edge keeps its two grid ends (32 bytes) instead of the 80-byte [`Plane`] of its
/// coefficients, which are recomputed from them exactly in i128 (as [`Plane::edge`] computes
/// them) whenever they are needed; a cut holds its two planes by shared pointer: they are
/// support planes of polygons, held once by the pieces of each polygon (`Piece::support`) and by
/// every line cut from them.
///
/// Lines are equal when their coefficients are (`PartialEq`, `Hash`): an edge and a vertical
/// line with the same coefficients are the same line, as two edges whose ends differ but give
/// the same coefficients are; a cut equals only a cut of the same two planes.
#[derive(Clone, Debug)]
pub enum Line {
    /// An edge of a face: the vertical plane through the grid points `p → q` (x, y), whose
    /// coefficients are [`Plane::edge`]`(p, q)`'s. The ends differ.
    Edge([[i64; 2]; 2]),
    /// Any other vertical plane (`c == 0`): a screen line, a sample row or column.
    Vertical(Vertical),
    /// The projection of the meeting line of two non-parallel input planes `P`, `Q`:
    /// `c_Q·P - c_P·Q`, which has no z term.
    Cut(Arc<Plane>, Arc<Plane>),
}

/// The coefficients of a vertical plane `a·x + b·y + d = 0` with `|a|, |b| < 2^63` and
/// `|d| < 2^127`, in 32 bytes aligned to 8 (an i128 field would make [`Line`] 48 bytes): every
/// vertical line the crate makes fits (edges have `|a|, |b| <= 2^54`, `|d| < 2^108`; sample
/// lines `a <= 2^16`, `|d| < 2^70`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Vertical {
    a: i64,
    b: i64,
    d: [u64; 2],
}

impl Vertical {
    /// Packs (a, b, d); the caller has checked the bounds.
    fn new(a: i64, b: i64, d: i128) -> Vertical {
        Vertical {
            a,
            b,
            d: [d as u64, (d >> 64) as u64],
        }
    }

    /// The coefficients (a, b, d).
    #[inline]
    pub fn coefficients(&self) -> [i128; 3] {
        let d = ((self.d[1] as i128) << 64) | self.d[0] as i128;
        [self.a as i128, self.b as i128, d]
    }
}

impl Line {
    /// The cut of two planes given by value (`Line::Cut` of new shared planes).
    pub fn cut(p: Plane, q: Plane) -> Line {
        Line::Cut(Arc::new(p), Arc::new(q))
    }

    /// The edge through grid points `p → q` (their x and y): `Plane::edge(p, q)` as a line.
    /// `None` when they have the same x and y.
    pub fn edge(p: GridPoint, q: GridPoint) -> Option<Line> {
        (p.x != q.x || p.y != q.y).then_some(Line::Edge([[p.x, p.y], [q.x, q.y]]))
    }

    /// The vertical plane `p` (`c == 0`) as a line. Panics when its coefficients do not fit
    /// [`Vertical`] (no line the crate makes comes near).
    pub fn vertical(p: &Plane) -> Line {
        assert_eq!(p.c, 0, "a screen line is a vertical plane");
        // Strictly below 2^63 and 2^127 in magnitude, so that the negated line fits too.
        let fits = |v: i128| {
            assert!(
                v.unsigned_abs() < 1 << 63,
                "vertical line coefficient below 2^63"
            );
            v as i64
        };
        let d: i128 = p.d.as_();
        assert!(
            w256(d) == p.d && d != i128::MIN,
            "vertical line offset below 2^127"
        );
        Line::Vertical(Vertical::new(fits(p.a), fits(p.b), d))
    }

    /// The coefficients (a, b, d) of an edge or vertical line, exactly; `None` for a cut.
    #[inline]
    pub fn vertical_coefficients(&self) -> Option<[i128; 3]> {
        match self {
            Line::Edge(e) => Some(edge_coefficients(e)),
            Line::Vertical(v) => Some(v.coefficients()),
            Line::Cut(..) => None,
        }
    }

    /// An edge or vertical line as its plane (`c == 0`); `None` for a cut.
    pub fn vertical_plane(&self) -> Option<Plane> {
        let [a, b, d] = self.vertical_coefficients()?;
        Some(Plane {
            a,
            b,
            c: 0,
            d: w256(d),
        })
    }

    /// The line with its sides swapped (exactly the negated coefficients: an edge runs the
    /// other way, `Plane::edge(q, p)` being `-Plane::edge(p, q)` for a line through both).
    pub fn negated(&self) -> Line {
        match self {
            Line::Edge([p, q]) => Line::Edge([*q, *p]),
            Line::Vertical(v) => {
                // |a|, |b| < 2^63 and |d| < 2^127 (checked when made): the negations fit.
                let [a, b, d] = v.coefficients();
                Line::Vertical(Vertical::new(-a as i64, -b as i64, -d))
            }
            Line::Cut(p, q) => Line::Cut(q.clone(), p.clone()),
        }
    }
}

impl Line {
    /// Is `self` the line `l` or `l` with its sides swapped (`== l || == l.negated()`, without
    /// building the negation)?
    pub fn is_same_or_opposite(&self, l: &Line) -> bool {
        match (self, l) {
            (Line::Cut(p, q), Line::Cut(r, s)) => (p == r && q == s) || (p == s && q == r),
            (Line::Cut(..), _) | (_, Line::Cut(..)) => false,
            (Line::Edge([p, q]), Line::Edge([r, s])) if (p, q) == (r, s) || (p, q) == (s, r) => {
                true
            }
            _ => {
                let (own, [a, b, d]) = (
                    self.vertical_coefficients(),
                    l.vertical_coefficients().expect("a vertical line"),
                );
                own == Some([a, b, d]) || own == Some([-a, -b, -d])
            }
        }
    }
}

/// [`Plane::edge`]'s coefficients for the ends `p → q`: `a = p.y - q.y`, `b = q.x - p.x`,
/// `d = -(a·p.x + b·p.y)`; grid coordinates are below 2^53, so `|a|, |b| <= 2^54` and the
/// offset is below 2^108: i128 holds them exactly.
#[inline]
fn edge_coefficients([p, q]: &[[i64; 2]; 2]) -> [i128; 3] {
    let a = (p[1] - q[1]) as i128;
    let b = (q[0] - p[0]) as i128;
    [a, b, -(a * p[0] as i128 + b * p[1] as i128)]
}

impl PartialEq for Line {
    fn eq(&self, other: &Line) -> bool {
        match (self, other) {
            (Line::Cut(p, q), Line::Cut(r, s)) => p == r && q == s,
            (Line::Cut(..), _) | (_, Line::Cut(..)) => false,
            (Line::Edge(e), Line::Edge(f)) if e == f => true,
            _ => self.vertical_coefficients() == other.vertical_coefficients(),
        }
    }
}

impl Eq for Line {}

impl std::hash::Hash for Line {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        match self {
            Line::Cut(p, q) => (1u8, p, q).hash(h),
            _ => (0u8, self.vertical_coefficients()).hash(h),
        }
    }
}

/// A line's coefficients in f64 with their error bounds, for testing many points against it:
/// `|A - a| <= ea`, `|B - b| <= eb`, `|D - d| <= ed` for the exact coefficients (A, B, D).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineApprox {
    a: f64,
    b: f64,
    d: f64,
    ea: f64,
    eb: f64,
    ed: f64,
}

impl LineApprox {
    /// The sign of the line at a point known to within `e` in x and y (`|X - x|, |Y - y| <= e`),
    /// when the f64 evaluation proves it; never `Equal`.
    ///
    /// `V - (a·x + b·y + d) = (A·X - a·x) + (B·Y - b·y) + (D - d)`, and
    /// `|A·X - a·x| <= ea·(|x| + e) + |a|·e`; evaluating `a·x + b·y + d` in f64 errs by at most
    /// `3·U·(|a·x| + |b·y| + |d|)` (to first order; the bound is widened by 1% for the rest and
    /// for its own rounding). The point's coordinates are grid values below 2^56, so `x` and
    /// `y` themselves are exact or carried in `e`.
    #[inline]
    pub fn sign_at(&self, [x, y, e]: [f64; 3]) -> Option<Ordering> {
        let (ax, by) = (self.a * x, self.b * y);
        let v = ax + by + self.d;
        let bound = self.ea * (x.abs() + e)
            + self.eb * (y.abs() + e)
            + (self.a.abs() + self.b.abs()) * e
            + self.ed
            + 3.0 * U * (ax.abs() + by.abs() + self.d.abs());
        let bound = bound * 1.01;
        if v > bound {
            Some(Ordering::Greater)
        } else if v < -bound {
            Some(Ordering::Less)
        } else {
            None
        }
    }
}

/// One coefficient, three ways: f64 value, f64 magnitude bound, and exact.
#[derive(Clone, Copy)]
struct Entry {
    value: f64,
    magnitude: f64,
}

impl Line {
    /// f64 coefficients (a, b, d) with their magnitude bounds.
    fn filtered(&self) -> [Entry; 3] {
        match self {
            Line::Edge(_) | Line::Vertical(_) => {
                // The same f64s as from the plane's I256 offset: `i256_to_f64` converts an
                // offset that fits i128 with `i128_to_f64`.
                let [a, b, d] = self.vertical_coefficients().expect("a vertical line");
                [
                    entry(i128_to_f64(a)),
                    entry(i128_to_f64(b)),
                    entry(i128_to_f64(d)),
                ]
            }
            Line::Cut(p, q) => {
                let (pc, qc) = (i128_to_f64(p.c), i128_to_f64(q.c));
                let combine = |pv: f64, qv: f64| Entry {
                    value: qc * pv - pc * qv,
                    magnitude: (qc * pv).abs() + (pc * qv).abs(),
                };
                [
                    combine(i128_to_f64(p.a), i128_to_f64(q.a)),
                    combine(i128_to_f64(p.b), i128_to_f64(q.b)),
                    combine(i256_to_f64(p.d), i256_to_f64(q.d)),
                ]
            }
        }
    }

    /// The f64 coefficients with error bounds (each below `5·U·M`, see the module docs).
    pub fn approx(&self) -> LineApprox {
        if let Line::Edge([p, q]) = self {
            // The hot case (pieces no longer cache their lines' approximations): the same
            // values as below, without the i128 detour for a and b, which fit i64.
            let (a, b) = (p[1] - q[1], q[0] - p[0]);
            let d = -(a as i128 * p[0] as i128 + b as i128 * p[1] as i128);
            let (a, b, d) = (a as f64, b as f64, i128_to_f64(d));
            return LineApprox {
                a,
                b,
                d,
                ea: ENTRY_ERROR * a.abs(),
                eb: ENTRY_ERROR * b.abs(),
                ed: ENTRY_ERROR * d.abs(),
            };
        }
        self.approx_filtered()
    }

    /// [`Self::approx`] through [`Self::filtered`], for every kind of line.
    fn approx_filtered(&self) -> LineApprox {
        let [a, b, d] = self.filtered();
        let e = |c: Entry| ENTRY_ERROR * c.magnitude;
        LineApprox {
            a: a.value,
            b: b.value,
            d: d.value,
            ea: e(a),
            eb: e(b),
            ed: e(d),
        }
    }

    /// The sign of the line at grid point (x, y), exactly: the f64 filter first, then exact
    /// integers (i128 for an edge line; 512 bits for a cut, whose value reaches 2^274). Exact
    /// evaluations here are not counted as fallbacks: they settle the exact zeros at shared grid
    /// corners, which are common and expected.
    pub fn sign_at_grid(&self, x: i64, y: i64) -> Ordering {
        match self {
            Line::Edge([p, q]) => {
                // `a·(x - p.x) + b·(y - p.y)`, the edge's value at (x, y) (its offset is
                // `-(a·p.x + b·p.y)`): differences below 2^54, products below 2^108, i128.
                let (a, b) = ((p[1] - q[1]) as i128, (q[0] - p[0]) as i128);
                (a * (x as i128 - p[0] as i128) + b * (y as i128 - p[1] as i128)).cmp(&0)
            }
            Line::Vertical(v) => {
                // Coefficients below 2^63 (in practice 2^16 here) at |x|, |y| <= 2^53: i128.
                let [a, b, d] = v.coefficients();
                (a * x as i128 + b * y as i128 + d).cmp(&0)
            }
            Line::Cut(..) => match self.approx().sign_at([x as f64, y as f64, 0.0]) {
                Some(s) => s,
                None => self.sign_at_grid_exact(x, y),
            },
        }
    }

    /// [`Self::sign_at_grid`] without the filter: for callers whose own filter failed.
    pub fn sign_at_grid_exact(&self, x: i64, y: i64) -> Ordering {
        match self {
            Line::Edge(..) | Line::Vertical(..) => self.sign_at_grid(x, y),
            Line::Cut(p, q) => {
                let (x, y) = (w256(x as i128), w256(y as i128));
                let at = |pl: &Plane| -> I512 { (w256(pl.a) * x + w256(pl.b) * y + pl.d).as_() };
                let w = |v: i128| -> I512 { v.as_() };
                (w(q.c) * at(p) - w(p.c) * at(q)).cmp(&w(0))
            }
        }
    }

    /// Exact coefficients (a, b, d), in the fixed width of callers that divide or compare
    /// ratios ([`Self::exact_big`]'s values).
    pub fn exact(&self) -> [Wide; 3] {
        self.exact_big().map(Big::to_bnum::<96>)
    }

    /// Exact coefficients (a, b, d) as [`Big`]s, the fallbacks' integers: products cost the
    /// limbs the coefficients have (an edge's two, a cut's four or five), not the full width.
    fn exact_big(&self) -> [Big; 3] {
        match self {
            Line::Edge(_) | Line::Vertical(_) => self
                .vertical_coefficients()
                .expect("a vertical line")
                .map(Big::from_i128),
            Line::Cut(p, q) => {
                let (pc, qc) = (Big::from_i128(p.c), Big::from_i128(q.c));
                let of = |pv: i128, qv: i128| qc * Big::from_i128(pv) - pc * Big::from_i128(qv);
                [
                    of(p.a, q.a),
                    of(p.b, q.b),
                    qc * Big::from_i256(p.d) - pc * Big::from_i256(q.d),
                ]
            }
        }
    }

    /// The line as a plane row (a, b, 0, d) for 4x4 determinants.
    fn filtered_row(&self) -> [Entry; 4] {
        let [a, b, d] = self.filtered();
        [a, b, entry(0.0), d]
    }

    fn exact_row(&self) -> [Big; 4] {
        let [a, b, d] = self.exact_big();
        [a, b, Big::ZERO, d]
    }
}

fn entry(v: f64) -> Entry {
    Entry {
        value: v,
        magnitude: v.abs(),
    }
}

fn plane_filtered(p: &Plane) -> [Entry; 4] {
    [
        entry(i128_to_f64(p.a)),
        entry(i128_to_f64(p.b)),
        entry(i128_to_f64(p.c)),
        entry(i256_to_f64(p.d)),
    ]
}

fn plane_exact(p: &Plane) -> [Big; 4] {
    [
        Big::from_i128(p.a),
        Big::from_i128(p.b),
        Big::from_i128(p.c),
        Big::from_i256(p.d),
    ]
}

/// Laplace expansion of a 3x3 determinant in f64, with the permanent of the magnitudes.
fn det3_f64(m: [[Entry; 3]; 3]) -> (f64, f64) {
    let minor = |r1: [Entry; 3], r2: [Entry; 3], i: usize, j: usize| {
        (
            r1[i].value * r2[j].value - r1[j].value * r2[i].value,
            r1[i].magnitude * r2[j].magnitude + r1[j].magnitude * r2[i].magnitude,
        )
    };
    let (m12, p12) = minor(m[1], m[2], 1, 2);
    let (m02, p02) = minor(m[1], m[2], 0, 2);
    let (m01, p01) = minor(m[1], m[2], 0, 1);
    let det = m[0][0].value * m12 - m[0][1].value * m02 + m[0][2].value * m01;
    let perm = m[0][0].magnitude * p12 + m[0][1].magnitude * p02 + m[0][2].magnitude * p01;
    (det, perm)
}

fn det3_exact(m: [[Big; 3]; 3]) -> Big {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

fn drop_col<T: Copy>(row: [T; 4], col: usize) -> [T; 3] {
    let mut out = [row[0]; 3];
    let mut k = 0;
    for (c, v) in row.into_iter().enumerate() {
        if c != col {
            out[k] = v;
            k += 1;
        }
    }
    out
}

/// 4x4 determinant in f64 by expansion along the first row, with the permanent of magnitudes.
fn det4_f64(m: [[Entry; 4]; 4]) -> (f64, f64) {
    let mut det = 0.0;
    let mut perm = 0.0;
    for col in 0..4 {
        let sub = [
            drop_col(m[1], col),
            drop_col(m[2], col),
            drop_col(m[3], col),
        ];
        let (d, p) = det3_f64(sub);
        let sign = if col % 2 == 0 { 1.0 } else { -1.0 };
        det += sign * m[0][col].value * d;
        perm += m[0][col].magnitude * p;
    }
    (det, perm)
}

fn det4_exact(m: [[Big; 4]; 4]) -> Big {
    let mut det = Big::ZERO;
    for col in 0..4 {
        if m[0][col].signum() == Ordering::Equal {
            continue;
        }
        let sub = [
            drop_col(m[1], col),
            drop_col(m[2], col),
            drop_col(m[3], col),
        ];
        let d = m[0][col] * det3_exact(sub);
        det = if col % 2 == 0 { det + d } else { det - d };
    }
    det
}

/// Error bound of an f64 entry, relative to its magnitude (see the module docs).
const ENTRY_ERROR: f64 = 5.0 * U;

/// Error bound factor of the filter (see the module docs).
const FILTER: f64 = 32.0 * U;

/// The sign of a filtered determinant, or `None` when the filter cannot decide.
fn filtered_sign(det: f64, perm: f64) -> Option<Ordering> {
    if det > FILTER * perm {
        Some(Ordering::Greater)
    } else if det < -FILTER * perm {
        Some(Ordering::Less)
    } else {
        None
    }
}

/// Which side of `q` the point where `p0`, `p1`, `p2` meet lies on: `Greater` where `q`'s
/// equation is positive. `None` when the three planes do not meet in one point.
pub fn meet_side(p: [&Plane; 3], q: &Plane) -> Option<Ordering> {
    let rows = [
        plane_filtered(p[0]),
        plane_filtered(p[1]),
        plane_filtered(p[2]),
    ];
    let normals = rows.map(|r| [r[0], r[1], r[2]]);
    let exact_rows = || [plane_exact(p[0]), plane_exact(p[1]), plane_exact(p[2])];
    // With D the normals' determinant, Cramer's rule gives q at the point as det4(p0,p1,p2,q)/D.
    let d_sign = match filtered_sign_of(det3_f64(normals)) {
        Some(s) => s,
        None => {
            let e = exact_rows();
            det3_exact(e.map(|r| [r[0], r[1], r[2]])).signum()
        }
    };
    if d_sign == Ordering::Equal {
        return None;
    }
    let m = [rows[0], rows[1], rows[2], plane_filtered(q)];
    let det_sign = match filtered_sign_of(det4_f64(m)) {
        Some(s) => s,
        None => {
            let e = exact_rows();
            det4_exact([e[0], e[1], e[2], plane_exact(q)]).signum()
        }
    };
    Some(combine_signs(det_sign, d_sign))
}

fn filtered_sign_of((det, perm): (f64, f64)) -> Option<Ordering> {
    let s = filtered_sign(det, perm);
    if s.is_none() {
        count_fallback();
    }
    s
}

fn combine_signs(a: Ordering, b: Ordering) -> Ordering {
    match (a, b) {
        (Ordering::Equal, _) | (_, Ordering::Equal) => Ordering::Equal,
        (x, y) if x == y => Ordering::Greater,
        _ => Ordering::Less,
    }
}

/// Which side of line `l` the screen point where `m0` and `m1` cross lies on (`Greater`: where
/// `l`'s equation is positive). `None` when `m0` and `m1` are parallel.
pub fn line_side(m: [&Line; 2], l: &Line) -> Option<Ordering> {
    if let Some(s) = line_side_filtered(m, l) {
        return Some(s);
    }
    count_fallback();
    // Crossing point (x, y) of a0 x + b0 y + d0 = 0 and a1 x + b1 y + d1 = 0:
    // l at it = det3(m0, m1, l) / D with D = a0 b1 - a1 b0.
    let e = [m[0].exact_big(), m[1].exact_big(), l.exact_big()];
    let d_sign = (e[0][0] * e[1][1] - e[1][0] * e[0][1]).signum();
    if d_sign == Ordering::Equal {
        return None;
    }
    Some(combine_signs(det3_exact(e).signum(), d_sign))
}

/// [`line_side`] by the f64 filter alone (both determinants): `None` where it cannot decide
/// (not counted as a fallback: the caller may have other ways). Never `Equal`. [`line_side`]
/// is this, then the exact computation.
pub fn line_side_filtered(m: [&Line; 2], l: &Line) -> Option<Ordering> {
    let f = [m[0].filtered(), m[1].filtered(), l.filtered()];
    let (a0, b0, a1, b1) = (f[0][0], f[0][1], f[1][0], f[1][1]);
    let d = a0.value * b1.value - a1.value * b0.value;
    let d_perm = a0.magnitude * b1.magnitude + a1.magnitude * b0.magnitude;
    let d_sign = filtered_sign(d, d_perm)?;
    let (det, perm) = det3_f64(f);
    Some(combine_signs(filtered_sign(det, perm)?, d_sign))
}

/// [`depth_order_at`] by the f64 filter alone, as [`line_side_filtered`].
pub fn depth_order_filtered(m: [&Line; 2], s: &Plane, t: &Plane) -> Option<Ordering> {
    let rows = [plane_filtered(s), m[0].filtered_row(), m[1].filtered_row()];
    let (d, d_perm) = det3_f64(rows.map(|r| [r[0], r[1], r[2]]));
    let d_sign = filtered_sign(d, d_perm)?;
    let (det, perm) = det4_f64([rows[0], rows[1], rows[2], plane_filtered(t)]);
    Some(combine_signs(filtered_sign(det, perm)?, d_sign))
}

/// At the screen point where lines `m0` and `m1` cross, is the support plane `s` nearer than `t`
/// (`Less`), at the same depth (`Equal`) or farther (`Greater`)? Both planes must have `c > 0`
/// (support planes). `None` when the lines are parallel.
pub fn depth_order_at(m: [&Line; 2], s: &Plane, t: &Plane) -> Option<Ordering> {
    debug_assert!(s.c > 0 && t.c > 0);
    if let Some(order) = depth_order_filtered(m, s, t) {
        return Some(order);
    }
    count_fallback();
    // The 3D point on s above the crossing: s ∩ m0 ∩ m1. It is nearer than t's point (smaller
    // z) exactly when it lies on t's negative side, since t's equation grows with z (c > 0):
    // the order is the sign of t there, det4(s, m0, m1, t)/D by Cramer's rule.
    let e = [plane_exact(s), m[0].exact_row(), m[1].exact_row()];
    let d_sign = det3_exact(e.map(|r| [r[0], r[1], r[2]])).signum();
    if d_sign == Ordering::Equal {
        return None;
    }
    let det = det4_exact([e[0], e[1], e[2], plane_exact(t)]);
    Some(combine_signs(det.signum(), d_sign))
}

/// Where two lines cross, in f64 grid coordinates, rounded: for output and bounds, never for a
/// decision. The same lines in either order, or with their sides swapped, give the same bits.
pub fn crossing_f64(l: &Line, m: &Line) -> [f64; 2] {
    let (den, nx, ny) = crossing_terms(l.filtered(), m.filtered());
    let (x, y) = (nx / den, ny / den);
    if x.is_finite() && y.is_finite() {
        return [x, y];
    }
    // Nearly parallel lines whose f64 denominator cancelled to 0: the crossing from exact
    // integers, correctly rounded. Lines that are exactly parallel have no crossing: NaN, never
    // used.
    crossing_rounded(l, m).unwrap_or([f64::NAN; 2])
}

/// Where two lines cross, each coordinate correctly rounded; `None` for parallel lines.
pub fn crossing_rounded(l: &Line, m: &Line) -> Option<[f64; 2]> {
    // Two edges or vertical lines: a, b below 2^63 (i64), d below 2^127, so Cramer's numerators
    // stay below 2^191, the denominator below 2^128, and the numerator ratio_f64 shifts to 55
    // bits above the denominator below 2^184: 256 bits do, a third of the general width (most
    // vertices of a visible set are edges crossing edges).
    if let (Some(p), Some(q)) = (l.vertical_coefficients(), m.vertical_coefficients()) {
        return cramer_rounded(p.map(w256), q.map(w256));
    }
    crossing_rounded_wide(l, m)
}

/// [`crossing_rounded`] in the general width: Cramer's products in [`Big`]s (the limbs the
/// coefficients have), the two divisions in 768 bits.
fn crossing_rounded_wide(l: &Line, m: &Line) -> Option<[f64; 2]> {
    let ([a0, b0, d0], [a1, b1, d1]) = (l.exact_big(), m.exact_big());
    let den = a0 * b1 - a1 * b0;
    let wide = |v: Big| v.to_bnum::<96>();
    (den.signum() != Ordering::Equal).then(|| {
        let den = wide(den);
        [
            ratio_f64(wide(b0 * d1 - b1 * d0), den),
            ratio_f64(wide(a1 * d0 - a0 * d1), den),
        ]
    })
}

/// Cramer's rule for two lines' exact (a, b, d) in `N` bytes, each coordinate correctly rounded
/// ([`ratio_f64`]); `None` for parallel lines.
fn cramer_rounded<const N: usize>(
    [a0, b0, d0]: [bnum::Int<N>; 3],
    [a1, b1, d1]: [bnum::Int<N>; 3],
) -> Option<[f64; 2]> {
    let den = a0 * b1 - a1 * b0;
    (!den.is_zero()).then(|| {
        [
            ratio_f64(b0 * d1 - b1 * d0, den),
            ratio_f64(a1 * d0 - a0 * d1, den),
        ]
    })
}

/// `n / d` correctly rounded to f64 (to nearest, ties to even); `d != 0`, and the quotient of
/// crossing coordinates (far inside f64's normal range), with room in `N` bytes for the larger
/// of n and d shifted left by 56 bits.
fn ratio_f64<const N: usize>(n: bnum::Int<N>, d: bnum::Int<N>) -> f64 {
    if n.is_zero() {
        return 0.0;
    }
    let negative = n.is_negative() != d.is_negative();
    let (n, d): (bnum::Uint<N>, bnum::Uint<N>) = (n.unsigned_abs(), d.unsigned_abs());
    // Scale so that q = floor(n·2^s / d) has 55 or 56 bits: 53 kept, then a rounding bit and
    // more, and the remainder says whether anything lies below them.
    let s = 55 + d.bit_width() as i32 - n.bit_width() as i32;
    let (num, den) = if s >= 0 {
        (n << s as u32, d)
    } else {
        (n, d << (-s) as u32)
    };
    let (q, r) = (num / den, num % den);
    let extra = q.bit_width() - 53;
    let kept: u64 = (q >> extra).as_();
    // The bits dropped (two or three, so the low word holds them) and half of their unit.
    let dropped = q.as_::<u64>() & ((1 << extra) - 1);
    let half = 1 << (extra - 1);
    let up = dropped > half || (dropped == half && (!r.is_zero() || kept & 1 == 1));
    // At most 2^53: exact. The power of two is exact too.
    let m = (kept + up as u64) as f64;
    let exponent = extra as i32 - s;
    let v = m * f64::from_bits(((exponent + 1023) as u64) << 52);
    if negative { -v } else { v }
}

/// Cramer's rule for a0·x + b0·y + d0 = 0, a1·x + b1·y + d1 = 0: (denominator, x and y
/// numerators).
fn crossing_terms([a0, b0, d0]: [Entry; 3], [a1, b1, d1]: [Entry; 3]) -> (f64, f64, f64) {
    (
        a0.value * b1.value - a1.value * b0.value,
        b0.value * d1.value - b1.value * d0.value,
        a1.value * d0.value - a0.value * d1.value,
    )
}

/// Where two lines cross, in f64, with a bound on the error of each coordinate; `None` when the
/// lines are too close to parallel for the bound to hold (the caller must then fall back on
/// something exact, such as the bounds of the face).
///
/// Each coefficient carries an error below `5·U·M` (see the module docs); the numerators
/// `b0·d1 - b1·d0`, `a1·d0 - a0·d1` and the denominator `a0·b1 - a1·b0` then err by at most
/// `13·U` times the sum of their products' magnitudes, and the quotient by
/// `(e_num + |q|·e_den) / (|den| - e_den)` plus one rounding. The bound below doubles that.
pub fn crossing_with_error(l: &Line, m: &Line) -> Option<([f64; 2], f64)> {
    let ([a0, b0, d0], [a1, b1, d1]) = (l.filtered(), m.filtered());
    let (den, nx, ny) = crossing_terms([a0, b0, d0], [a1, b1, d1]);
    let e_den = 13.0 * U * (a0.magnitude * b1.magnitude + a1.magnitude * b0.magnitude);
    if !den.is_finite() || den.abs() <= 2.0 * e_den || e_den.is_nan() {
        return None;
    }
    let e_nx = 13.0 * U * (b0.magnitude * d1.magnitude + b1.magnitude * d0.magnitude);
    let e_ny = 13.0 * U * (a1.magnitude * d0.magnitude + a0.magnitude * d1.magnitude);
    let (x, y) = (nx / den, ny / den);
    let err = |q: f64, e_num: f64| (e_num + q.abs() * e_den) / (den.abs() - e_den) + U * q.abs();
    let e = 2.0 * err(x, e_nx).max(err(y, e_ny));
    (x.is_finite() && y.is_finite() && e.is_finite()).then_some(([x, y], e))
}

/// The sign of `a_m·b_l - b_m·a_l` for lines `l`, `m`: how `m` runs along `l` (`Greater` when
/// `m`'s value grows in `l`'s direction `(b_l, -a_l)`, `Equal` when they are parallel). Exact,
/// through the f64 filter.
pub fn heading(l: &Line, m: &Line) -> Ordering {
    let ([a0, b0, _], [a1, b1, _]) = (l.filtered(), m.filtered());
    let det = a1.value * b0.value - b1.value * a0.value;
    let perm = a1.magnitude * b0.magnitude + b1.magnitude * a0.magnitude;
    if let Some(s) = filtered_sign(det, perm) {
        return s;
    }
    count_fallback();
    let ([a0, b0, _], [a1, b1, _]) = (l.exact_big(), m.exact_big());
    (a1 * b0 - b1 * a0).signum()
}

/// Exact orientation of three grid points' (x, y): `Greater` for counter-clockwise (y up).
pub fn orient2d(p: GridPoint, q: GridPoint, r: GridPoint) -> Ordering {
    cross_xy([p.x, p.y], [q.x, q.y], [r.x, r.y]).cmp(&0)
}

/// Twice the signed area of the triangle of three grid (x, y) points, exact: positive for
/// counter-clockwise (y up). Differences below 2^54, products below 2^108: i128.
pub fn cross_xy(o: [i64; 2], a: [i64; 2], b: [i64; 2]) -> i128 {
    (a[0] - o[0]) as i128 * (b[1] - o[1]) as i128 - (a[1] - o[1]) as i128 * (b[0] - o[0]) as i128
}

/// How two closed screen segments `p0p1` and `q0q1` (grid points, x and y) meet.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Crossing {
    /// No common point.
    Disjoint,
    /// They cross at one point interior to both.
    Proper,
    /// They share a point that is an endpoint of one of them, or overlap collinearly.
    Touch,
}

/// Exact classification of two segments on screen.
pub fn segments_cross(p0: GridPoint, p1: GridPoint, q0: GridPoint, q1: GridPoint) -> Crossing {
    let d1 = orient2d(q0, q1, p0);
    let d2 = orient2d(q0, q1, p1);
    let d3 = orient2d(p0, p1, q0);
    let d4 = orient2d(p0, p1, q1);
    use Ordering::*;
    if d1 != Equal && d2 != Equal && d1 != d2 && d3 != Equal && d4 != Equal && d3 != d4 {
        return Crossing::Proper;
    }
    let on = |a: GridPoint, b: GridPoint, c: GridPoint| {
        c.x.min(a.x.max(b.x)) == c.x
            && c.x >= a.x.min(b.x)
            && c.y <= a.y.max(b.y)
            && c.y >= a.y.min(b.y)
    };
    if (d1 == Equal && on(q0, q1, p0))
        || (d2 == Equal && on(q0, q1, p1))
        || (d3 == Equal && on(p0, p1, q0))
        || (d4 == Equal && on(p0, p1, q1))
    {
        return Crossing::Touch;
    }
    Crossing::Disjoint
}

#[cfg(test)]
mod tests {
    use super::*;
    use bnum::types::I256;

    /// A small deterministic generator (xorshift64) for the tests' random values.
    fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        }
    }

    /// Random grid coordinates within the grid's extremes, `scale` bits shorter (0: out to
    /// `GRID_MAX`), either sign.
    fn grid_coordinates(seed: u64) -> impl FnMut(u32) -> i64 {
        let mut next = xorshift(seed);
        let max = super::super::GRID_MAX;
        move |scale: u32| {
            let v = (next() >> (11 + scale)) as i64 % (max + 1);
            if next() & 1 == 0 { v } else { -v }
        }
    }

    /// An edge's f64 coefficients and bounds from the i64 fast path are the general path's,
    /// bit for bit, out to the grid's extremes (where a and b reach 2^54 and round).
    #[test]
    fn an_edges_approximation_is_the_general_one() {
        let max = super::super::GRID_MAX;
        let mut coordinate = grid_coordinates(5);
        let mut edges = vec![
            Line::edge(GridPoint::new(-max, -max, 0), GridPoint::new(max, max, 0)),
            Line::edge(
                GridPoint::new(max, -max, 0),
                GridPoint::new(-max, max - 1, 0),
            ),
        ];
        for case in 0..20_000 {
            let scale = (case % 4) * 12;
            let mut point = || GridPoint::new(coordinate(scale), coordinate(scale), 0);
            edges.push(Line::edge(point(), point()));
        }
        for l in edges.into_iter().flatten() {
            assert_eq!(l.approx(), l.approx_filtered(), "{l:?}");
        }
    }

    /// Edges (and vertical lines) cross in 256 bits exactly as in the general width, out to the
    /// grid's extremes.
    #[test]
    fn edges_cross_in_256_bits_as_in_the_general_width() {
        let mut coordinate = grid_coordinates(11);
        let mut crossed = 0;
        for case in 0..20_000 {
            let scale = (case % 4) * 12;
            let mut point = || GridPoint::new(coordinate(scale), coordinate(scale), 0);
            let (Some(l), Some(m)) = (Line::edge(point(), point()), Line::edge(point(), point()))
            else {
                continue;
            };
            let fast = crossing_rounded(&l, &m);
            assert_eq!(fast, crossing_rounded_wide(&l, &m), "{l:?} {m:?}");
            crossed += fast.is_some() as usize;
        }
        assert!(crossed > 19_000, "{crossed}");
        // Vertical lines at their extremes: a, b just below 2^63, d just below 2^127.
        let big = |a: i128, b: i128, d: i128| {
            Line::vertical(&Plane {
                a,
                b,
                c: 0,
                d: w256(d),
            })
        };
        let (a, d) = ((1i128 << 63) - 1, i128::MAX);
        let lines = [
            big(a, -a + 1, d),
            big(-a, a - 7, -d),
            big(a - 3, a, d - 5),
            big(1, 0, -(1 << 52)),
            big(0, 1, 1 << 52),
        ];
        for l in &lines {
            for m in &lines {
                assert_eq!(crossing_rounded(l, m), crossing_rounded_wide(l, m));
            }
        }
    }

    /// The fallbacks' coefficients ([`Line::exact_big`]) are those computed in 768 bits
    /// throughout, for cuts of planes out to the bit budget's extremes (normals below 2^109, offsets below 2^165) and
    /// for edges at the grid's; cuts cross where 768-bit integers say.
    #[test]
    fn fallback_coefficients_are_the_exact_ones() {
        // A value of at most `bits` bits, either sign.
        fn signed(next: &mut impl FnMut() -> u64, bits: u32) -> i128 {
            let v = (((next() as u128) << 64 | next() as u128) >> (128 - bits)) as i128;
            if next() & 1 == 0 { v } else { -v }
        }
        let mut next = xorshift(5);
        let (mut previous, mut crossed) = (None::<Line>, 0);
        for case in 0..5_000 {
            // Every fifth case at the largest magnitudes, the others at random sizes.
            let mut plane = || {
                let mut bits = |top: u32| {
                    if case % 5 == 0 {
                        top
                    } else {
                        1 + (next() % top as u64) as u32
                    }
                };
                let (ba, bb, bc, bd) = (bits(109), bits(109), bits(109), bits(37));
                let d_high: I256 = signed(&mut next, bd).as_();
                let d_low: I256 = signed(&mut next, 127).abs().as_();
                Plane {
                    a: signed(&mut next, ba),
                    b: signed(&mut next, bb),
                    c: signed(&mut next, bc).abs().max(1),
                    d: (d_high << 128u32) + d_low,
                }
            };
            let (p, q) = (plane(), plane());
            // The cut's coefficients c_Q·P - c_P·Q, computed here in 768 bits throughout.
            let w = |v: i128| -> Wide { v.as_() };
            let w256 = |v: I256| -> Wide { v.as_() };
            let in_768_bits = [
                w(q.c) * w(p.a) - w(p.c) * w(q.a),
                w(q.c) * w(p.b) - w(p.c) * w(q.b),
                w(q.c) * w256(p.d) - w(p.c) * w256(q.d),
            ];
            let l = Line::cut(p, q);
            assert_eq!(l.exact_big().map(Big::to_bnum::<96>), in_768_bits, "{l:?}");
            // Crossings of cuts from their products in limbs, as in 768 bits throughout.
            if let Some(m) = &previous {
                let in_768_bits = cramer_rounded(l.exact(), m.exact());
                assert_eq!(crossing_rounded_wide(&l, m), in_768_bits, "{l:?} {m:?}");
                crossed += in_768_bits.is_some() as usize;
            }
            previous = Some(l);
        }
        assert!(crossed > 4_900, "{crossed}");
        let max = super::super::GRID_MAX;
        let corner = GridPoint::new(max, -max, 0);
        let far = GridPoint::new(-max, max - 1, 0);
        let l = Line::edge(corner, far).expect("an edge");
        let edge = Plane::edge(corner, far).expect("an edge");
        let in_768_bits: [Wide; 3] = [edge.a.as_(), edge.b.as_(), edge.d.as_()];
        assert_eq!(l.exact_big().map(Big::to_bnum::<96>), in_768_bits);
    }

    #[test]
    fn ratios_are_correctly_rounded() {
        let big = |v: i128| -> Wide { v.as_() };
        // Below 2^53 both are exact in f64, and IEEE division rounds correctly.
        let mut next = xorshift(7);
        for _ in 0..10_000 {
            let n = (next() >> 11) as i128 - (1 << 52);
            let d = ((next() >> 11) as i128 | 1) * if next() & 1 == 0 { 1 } else { -1 };
            assert_eq!(ratio_f64(big(n), big(d)), n as f64 / d as f64, "{n} / {d}");
            // Scaling both by a power of two changes nothing.
            let shift = (next() % 300) as u32;
            assert_eq!(
                ratio_f64(big(n) << shift, big(d) << shift),
                n as f64 / d as f64
            );
        }
        // Ties go to even: 2^53 + 1 lies halfway between 2^53 and 2^53 + 2.
        let t = 1i128 << 53;
        assert_eq!(ratio_f64(big(t + 1), big(1)), t as f64);
        assert_eq!(ratio_f64(big(t + 3), big(1)), (t + 4) as f64);
        // Just above the tie rounds up, just below rounds down.
        assert_eq!(ratio_f64(big(2 * t + 3), big(2)), (t + 2) as f64);
        assert_eq!(ratio_f64(big(2 * t + 1), big(2)), t as f64);
        assert_eq!(ratio_f64(big(0), big(-5)), 0.0);
    }
}
