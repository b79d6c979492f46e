//! Exact geometry for the properties, independent of the kernel's predicates: big-integer
//! homogeneous points and line coefficients, exact pieces (well formed or an error saying how
//! not), exact point location in polygons and pieces, the separating-axis test, and the exact
//! area of a union of simple integer polygons. The checks at the end of this file hold the oracle
//! itself against known shapes and an independent clipper.

use crate::generators::{Gen, star};
use crate::support::rng::Rng;
use crate::support::strategy::VisibleSet;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};
use proptest::prelude::*;
use sightline::exact::Plane;
use sightline::exact::polygon::Piece;
use sightline::exact::predicates::Line;
use sightline::project::ScreenScene;
use std::cmp::Ordering;

/// A kernel's 256-bit integer, exactly.
pub fn big256(v: sightline::exact::I256) -> BigInt {
    v.to_string().parse().expect("an integer")
}

pub fn big(v: i128) -> BigInt {
    BigInt::from(v)
}

/// A point (x/w, y/w) with w > 0.
#[derive(Clone, Debug)]
pub struct HPoint {
    pub x: BigInt,
    pub y: BigInt,
    pub w: BigInt,
}

impl HPoint {
    pub fn from_rationals(x: &BigRational, y: &BigRational) -> HPoint {
        HPoint {
            x: x.numer() * y.denom(),
            y: y.numer() * x.denom(),
            w: x.denom() * y.denom(),
        }
    }

    pub fn rationals(&self) -> [BigRational; 2] {
        [
            BigRational::new(self.x.clone(), self.w.clone()),
            BigRational::new(self.y.clone(), self.w.clone()),
        ]
    }

    pub fn f64(&self) -> [f64; 2] {
        let w = self.w.to_f64().unwrap();
        [self.x.to_f64().unwrap() / w, self.y.to_f64().unwrap() / w]
    }
}

/// A line a·x + b·y + d = 0 as exact coefficients.
pub type Coeffs = [BigInt; 3];

fn coeffs(l: &Line) -> Coeffs {
    match l {
        // An edge through (px, py) -> (qx, qy): a = py - qy, b = qx - px, d = -(a·px + b·py).
        Line::Edge([[px, py], [qx, qy]]) => {
            let (a, b) = (
                big(*py as i128) - big(*qy as i128),
                big(*qx as i128) - big(*px as i128),
            );
            let d = -(&a * big(*px as i128) + &b * big(*py as i128));
            [a, b, d]
        }
        Line::Vertical(_) => {
            let p = l.vertical_plane().expect("a vertical line");
            [big(p.a), big(p.b), big256(p.d)]
        }
        Line::Cut(p, q) => {
            let (pc, qc) = (big(p.c), big(q.c));
            [
                &qc * big(p.a) - &pc * big(q.a),
                &qc * big(p.b) - &pc * big(q.b),
                &qc * big256(p.d) - &pc * big256(q.d),
            ]
        }
    }
}

/// Where two lines cross (Cramer), or `None` when they are parallel.
fn crossing(l: &Coeffs, m: &Coeffs) -> Option<HPoint> {
    let w = &l[0] * &m[1] - &m[0] * &l[1];
    if w.is_zero() {
        return None;
    }
    let x = &l[1] * &m[2] - &m[1] * &l[2];
    let y = &m[0] * &l[2] - &l[0] * &m[2];
    Some(if w.is_negative() {
        HPoint {
            x: -x,
            y: -y,
            w: -w,
        }
    } else {
        HPoint { x, y, w }
    })
}

/// The sign of a line's equation at a point.
pub fn side(l: &Coeffs, p: &HPoint) -> Ordering {
    (&l[0] * &p.x + &l[1] * &p.y + &l[2] * &p.w).sign_cmp()
}

trait SignCmp {
    fn sign_cmp(&self) -> Ordering;
}

impl SignCmp for BigInt {
    fn sign_cmp(&self) -> Ordering {
        self.cmp(&BigInt::zero())
    }
}

/// Twice the signed area of a polygon with rational vertices.
pub fn twice_area(v: &[[BigRational; 2]]) -> BigRational {
    let n = v.len();
    let mut s = BigRational::zero();
    for k in 0..n {
        let (p, q) = (&v[k], &v[(k + 1) % n]);
        s += &p[0] * &q[1] - &q[0] * &p[1];
    }
    s
}

/// A visible piece with its exact vertices; built only for well-formed pieces.
pub struct ExactPiece {
    pub poly: usize,
    pub lines: Vec<Coeffs>,
    pub verts: Vec<HPoint>,
    pub rats: Vec<[BigRational; 2]>,
    /// f64 bounds widened by one grid unit: the conversion error is below 2^-24 units, so bounds
    /// that do not overlap prove the pieces apart.
    pub bounds: [f64; 4],
    pub twice_area: BigRational,
}

/// The exact form of a piece, checking that it is well formed: at least three lines, adjacent
/// lines cross, every vertex inside or on every line and strictly inside the lines not through
/// it (strictly convex), positive area, and each recorded input corner is the vertex exactly.
pub fn exact_piece(p: &Piece) -> Result<ExactPiece, String> {
    let n = p.lines().len();
    if n < 3 {
        return Err(format!("{n} lines: {p:?}"));
    }
    let lines: Vec<Coeffs> = p.lines().map(coeffs).collect();
    let mut verts = Vec::with_capacity(n);
    for k in 0..n {
        let v = crossing(&lines[(k + n - 1) % n], &lines[k])
            .ok_or_else(|| format!("lines {} and {k} are parallel: {p:?}", (k + n - 1) % n))?;
        if let Some([x, y]) = p.corner(k)
            && (v.x != big(x as i128) * &v.w || v.y != big(y as i128) * &v.w)
        {
            return Err(format!(
                "vertex {k} is {:?}, not its recorded corner ({x}, {y}): {p:?}",
                v.f64()
            ));
        }
        verts.push(v);
    }
    for (k, v) in verts.iter().enumerate() {
        for (j, l) in lines.iter().enumerate() {
            let s = side(l, v);
            let through = j == k || (j + 1) % n == k;
            if through && s != Ordering::Equal {
                return Err(format!("vertex {k} is not on its line {j}: {p:?}"));
            }
            if !through && s != Ordering::Greater {
                return Err(format!(
                    "vertex {k} {:?} is {s:?} on line {j}: not strictly convex: {p:?}",
                    v.f64()
                ));
            }
        }
    }
    let rats: Vec<[BigRational; 2]> = verts.iter().map(HPoint::rationals).collect();
    let twice_area = twice_area(&rats);
    if !twice_area.is_positive() {
        return Err(format!("area {twice_area} is not positive: {p:?}"));
    }
    let mut bounds = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];
    for v in &verts {
        let [x, y] = v.f64();
        bounds = [
            bounds[0].min(x - 1.0),
            bounds[1].min(y - 1.0),
            bounds[2].max(x + 1.0),
            bounds[3].max(y + 1.0),
        ];
    }
    Ok(ExactPiece {
        poly: p.poly as usize,
        lines,
        verts,
        rats,
        bounds,
        twice_area,
    })
}

pub fn exact_pieces(v: &VisibleSet) -> Vec<ExactPiece> {
    v.pieces
        .iter()
        .enumerate()
        .map(|(i, p)| exact_piece(p).unwrap_or_else(|e| panic!("piece {i} malformed: {e}")))
        .collect()
}

/// A screen polygon as integer (x, y) corners, with what the tie rule needs.
pub struct Poly {
    pub id: u32,
    pub plane: Plane,
    pub pts: Vec<[i64; 2]>,
}

pub fn screen_polys(screen: &ScreenScene) -> Vec<Poly> {
    screen
        .polys
        .iter()
        .map(|p| Poly {
            id: p.id,
            plane: screen.plane(p),
            pts: screen.corners(p).iter().map(|c| [c.x, c.y]).collect(),
        })
        .collect()
}

pub fn orient(a: [i64; 2], b: [i64; 2], c: [i64; 2]) -> Ordering {
    let v = (b[0] - a[0]) as i128 * (c[1] - a[1]) as i128
        - (b[1] - a[1]) as i128 * (c[0] - a[0]) as i128;
    v.cmp(&0)
}

/// Do closed segments ab and cd share a point? (CLRS: a proper crossing, or an endpoint of one
/// on the other.)
fn segments_meet(a: [i64; 2], b: [i64; 2], c: [i64; 2], d: [i64; 2]) -> bool {
    use Ordering::{Equal, Greater, Less};
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    let opposite = |x: Ordering, y: Ordering| matches!((x, y), (Less, Greater) | (Greater, Less));
    if opposite(o1, o2) && opposite(o3, o4) {
        return true;
    }
    let within = |p: [i64; 2], q: [i64; 2], r: [i64; 2]| {
        r[0] >= p[0].min(q[0])
            && r[0] <= p[0].max(q[0])
            && r[1] >= p[1].min(q[1])
            && r[1] <= p[1].max(q[1])
    };
    (o1 == Equal && within(a, b, c))
        || (o2 == Equal && within(a, b, d))
        || (o3 == Equal && within(c, d, a))
        || (o4 == Equal && within(c, d, b))
}

/// Is a polygon simple: non-adjacent edges do not meet, adjacent edges meet only at their shared
/// corner (no spike folding back along itself)?
pub fn is_simple(pts: &[[i64; 2]]) -> bool {
    let n = pts.len();
    if n < 3 {
        return false;
    }
    for i in 0..n {
        // Adjacent edges i-1 and i at corner i: no fold back.
        let (a, s, b) = (pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n]);
        if orient(a, s, b) == Ordering::Equal {
            let dot = (a[0] - s[0]) as i128 * (b[0] - s[0]) as i128
                + (a[1] - s[1]) as i128 * (b[1] - s[1]) as i128;
            if dot > 0 {
                return false;
            }
        }
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue;
            }
            if segments_meet(pts[i], pts[(i + 1) % n], pts[j], pts[(j + 1) % n]) {
                return false;
            }
        }
    }
    true
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Loc {
    Inside,
    Boundary,
    Outside,
}

/// Exact point-in-polygon (even-odd; any simple polygon) for a rational point.
pub fn locate(pts: &[[i64; 2]], p: &HPoint) -> Loc {
    let n = pts.len();
    let mut inside = false;
    for k in 0..n {
        let (a, b) = (pts[k], pts[(k + 1) % n]);
        // orient(a, b, p)·w = (b - a) x (p·w - a·w)
        let px = &p.x - big(a[0] as i128) * &p.w;
        let py = &p.y - big(a[1] as i128) * &p.w;
        let o = (big((b[0] - a[0]) as i128) * &py - big((b[1] - a[1]) as i128) * &px).sign_cmp();
        let ge = |v: i64, c: &BigInt| big(v as i128) * &p.w >= *c;
        let le = |v: i64, c: &BigInt| big(v as i128) * &p.w <= *c;
        if o == Ordering::Equal
            && le(a[0].min(b[0]), &p.x)
            && ge(a[0].max(b[0]), &p.x)
            && le(a[1].min(b[1]), &p.y)
            && ge(a[1].max(b[1]), &p.y)
        {
            return Loc::Boundary;
        }
        // Half-open rule on y; the crossing is right of p when p is left of the upward edge.
        let a_above = !le(a[1], &p.y);
        let b_above = !le(b[1], &p.y);
        if a_above != b_above {
            let right = if b[1] > a[1] {
                o == Ordering::Greater
            } else {
                o == Ordering::Less
            };
            if right {
                inside = !inside;
            }
        }
    }
    if inside { Loc::Inside } else { Loc::Outside }
}

/// Is a point strictly inside (`Inside`), on the boundary of, or outside a convex piece?
pub fn locate_in_piece(p: &ExactPiece, q: &HPoint) -> Loc {
    let mut on = false;
    for l in &p.lines {
        match side(l, q) {
            Ordering::Less => return Loc::Outside,
            Ordering::Equal => on = true,
            Ordering::Greater => {}
        }
    }
    if on { Loc::Boundary } else { Loc::Inside }
}

/// Exact SAT: does an edge line of one piece have the whole other piece on its closed outer side?
pub fn sat_separated(p: &ExactPiece, q: &ExactPiece) -> bool {
    let outside = |a: &ExactPiece, b: &ExactPiece| {
        a.lines
            .iter()
            .any(|l| b.verts.iter().all(|v| side(l, v) != Ordering::Greater))
    };
    outside(p, q) || outside(q, p)
}

/// A rational number n/d with d > 0, in 512-bit integers (crossing abscissas of 54-bit grid
/// points: |n| < 2^166, d < 2^111, so a cross-multiplied comparison stays below 2^278).
#[derive(Clone, Copy, Debug)]
struct Frac {
    pub n: I512,
    pub d: I512,
}

type I512 = bnum::types::I512;

fn w512(v: i128) -> I512 {
    bnum::cast::As::as_(v)
}

fn big512(v: I512) -> BigInt {
    v.to_string().parse().expect("an integer")
}

impl Frac {
    fn cmp(&self, o: &Frac) -> Ordering {
        (self.n * o.d).cmp(&(o.n * self.d))
    }
}

/// Exact area of the union of simple integer polygons by vertical slabs: between consecutive
/// abscissas of corners and of edge crossings the union is a stack of trapezoids, so its area is
/// the slab's width times the covered length on the slab's midline.
pub fn union_area(polys: &[&[[i64; 2]]]) -> BigRational {
    // Edges left to right, with their polygon; vertical edges bound no slab.
    let mut edges: Vec<([i64; 2], [i64; 2], usize)> = Vec::new();
    let mut xs: Vec<Frac> = Vec::new();
    for (i, pts) in polys.iter().enumerate() {
        let n = pts.len();
        for k in 0..n {
            let (a, b) = (pts[k], pts[(k + 1) % n]);
            xs.push(Frac {
                n: w512(a[0] as i128),
                d: w512(1),
            });
            match a[0].cmp(&b[0]) {
                Ordering::Less => edges.push((a, b, i)),
                Ordering::Greater => edges.push((b, a, i)),
                Ordering::Equal => {}
            }
        }
    }
    // Proper crossings: abscissa a.x + t·(b.x - a.x), t = o1 / (o1 - o2).
    for (k, &(a, b, _)) in edges.iter().enumerate() {
        for &(c, d, _) in &edges[k + 1..] {
            if c[0] >= b[0] || a[0] >= d[0] {
                continue;
            }
            let o = |p: [i64; 2], q: [i64; 2], r: [i64; 2]| {
                (q[0] - p[0]) as i128 * (r[1] - p[1]) as i128
                    - (q[1] - p[1]) as i128 * (r[0] - p[0]) as i128
            };
            let (o1, o2) = (o(c, d, a), o(c, d, b));
            let (o3, o4) = (o(a, b, c), o(a, b, d));
            if o1.signum() * o2.signum() < 0 && o3.signum() * o4.signum() < 0 {
                let den = w512(o1) - w512(o2);
                let num = w512(a[0] as i128) * den + w512(o1) * w512((b[0] - a[0]) as i128);
                let (num, den) = if den < w512(0) {
                    (-num, -den)
                } else {
                    (num, den)
                };
                xs.push(Frac { n: num, d: den });
            }
        }
    }
    xs.sort_by(Frac::cmp);
    xs.dedup_by(|a, b| a.cmp(b) == Ordering::Equal);
    let index = |x: i64| {
        xs.binary_search_by(|f| {
            f.cmp(&Frac {
                n: w512(x as i128),
                d: w512(1),
            })
        })
        .expect("every corner abscissa is an event")
    };
    let mut slab_edges: Vec<Vec<usize>> = vec![Vec::new(); xs.len().saturating_sub(1)];
    for (k, e) in edges.iter().enumerate() {
        for s in &mut slab_edges[index(e.0[0])..index(e.1[0])] {
            s.push(k);
        }
    }
    let mut total = BigRational::zero();
    for (s, list) in slab_edges.iter().enumerate() {
        if list.is_empty() {
            continue;
        }
        let (l, r) = (xs[s], xs[s + 1]);
        // Midline x = mn / md.
        let mn = big512(l.n) * big512(r.d) + big512(r.n) * big512(l.d);
        let md = big(2) * big512(l.d) * big512(r.d);
        // Edge e at the midline: y = Y / (dx · md) with dx = b.x - a.x > 0 and
        // Y = a.y·dx·md + (mn - a.x·md)·(b.y - a.y). md is common: compare and sum Y/dx.
        let mut by_poly: Vec<Vec<(BigInt, i64)>> = vec![Vec::new(); polys.len()];
        for &k in list {
            let (a, b, i) = edges[k];
            let dx = b[0] - a[0];
            let y = big(a[1] as i128) * big(dx as i128) * &md
                + (&mn - big(a[0] as i128) * &md) * big((b[1] - a[1]) as i128);
            by_poly[i].push((y, dx));
        }
        let cmp = |p: &(BigInt, i64), q: &(BigInt, i64)| {
            (&p.0 * big(q.1 as i128)).cmp(&(&q.0 * big(p.1 as i128)))
        };
        let mut intervals: Vec<((BigInt, i64), (BigInt, i64))> = Vec::new();
        for mut ys in by_poly {
            assert!(
                ys.len() % 2 == 0,
                "a simple polygon crosses a line an even number of times"
            );
            ys.sort_by(cmp);
            let mut it = ys.into_iter();
            while let (Some(lo), Some(hi)) = (it.next(), it.next()) {
                intervals.push((lo, hi));
            }
        }
        intervals.sort_by(|p, q| cmp(&p.0, &q.0));
        let mut length = BigRational::zero();
        let mut current: Option<((BigInt, i64), (BigInt, i64))> = None;
        let frac = |v: &(BigInt, i64)| BigRational::new(v.0.clone(), big(v.1 as i128));
        for (lo, hi) in intervals {
            match &mut current {
                Some((_, chi)) if cmp(&lo, chi) != Ordering::Greater => {
                    if cmp(&hi, chi) == Ordering::Greater {
                        *chi = hi;
                    }
                }
                _ => {
                    if let Some((clo, chi)) = current.take() {
                        length += frac(&chi) - frac(&clo);
                    }
                    current = Some((lo, hi));
                }
            }
        }
        if let Some((clo, chi)) = current {
            length += frac(&chi) - frac(&clo);
        }
        // width = r - l; the covered length is `length / md`.
        let width = BigRational::new(
            big512(r.n) * big512(l.d) - big512(l.n) * big512(r.d),
            big512(l.d) * big512(r.d),
        );
        total += width * length / BigRational::from_integer(md);
    }
    total
}

/// A random point strictly inside a convex piece: a positive rational combination of its
/// vertices. Small weights land on special points (centroids, midpoints of diagonals).
pub fn interior_point(p: &ExactPiece, rng: &mut Rng) -> HPoint {
    let max = [2u64, 5, 1000, 1 << 30][(rng.next_u64() % 4) as usize];
    let mut sx = BigRational::zero();
    let mut sy = BigRational::zero();
    let mut sw = BigInt::zero();
    for v in &p.rats {
        let w = big((1 + rng.next_u64() % max) as i128);
        sx += &v[0] * &w;
        sy += &v[1] * &w;
        sw += w;
    }
    let sw = BigRational::from_integer(sw);
    HPoint::from_rationals(&(sx / &sw), &(sy / &sw))
}

/// The depth numerator of a support plane at a point: z = -N / (c·w).
pub fn depth_num(pl: &Plane, p: &HPoint) -> BigInt {
    big(pl.a) * &p.x + big(pl.b) * &p.y + big256(pl.d) * &p.w
}

// ------------------------------------------------------------------------------------------------
// The oracle checked
// ------------------------------------------------------------------------------------------------

fn shoelace(pts: &[[i64; 2]]) -> BigRational {
    let n = pts.len();
    let s: i128 = (0..n)
        .map(|k| {
            let (p, q) = (pts[k], pts[(k + 1) % n]);
            p[0] as i128 * q[1] as i128 - q[0] as i128 * p[1] as i128
        })
        .sum();
    BigRational::new(big(s.abs()), big(2))
}

pub fn r(n: i64, d: i64) -> BigRational {
    BigRational::new(big(n as i128), big(d as i128))
}

#[test]
fn union_area_of_known_shapes() {
    let sq = |x: i64, y: i64, s: i64| vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]];
    let a = sq(0, 0, 10);
    // Overlapping squares: 100 + 100 - 25.
    assert_eq!(union_area(&[&a, &sq(5, 5, 10)]), r(175, 1));
    // A duplicate, clockwise: still 100. Sharing an edge: 200. Inside: 100.
    let cw: Vec<[i64; 2]> = a.iter().rev().copied().collect();
    assert_eq!(union_area(&[&a, &cw]), r(100, 1));
    assert_eq!(union_area(&[&a, &sq(10, 0, 10)]), r(200, 1));
    assert_eq!(union_area(&[&a, &sq(2, 2, 3)]), r(100, 1));
    // An L shape (non-convex), and a square over its notch: 300 + 100 - (100 - 25).
    let l = vec![[0, 0], [20, 0], [20, 10], [10, 10], [10, 20], [0, 20]];
    assert_eq!(union_area(&[&l]), r(300, 1));
    assert_eq!(union_area(&[&l, &sq(5, 5, 10)]), r(325, 1));
    // A thin triangle crossing a square: 100 + the parts of the triangle outside it.
    let thin = vec![[-3, 4], [13, 5], [-3, 6]];
    // The triangle is 16 wide and 2 high at x = -3, closing at x = 13: area 16. Inside the
    // square (0 <= x <= 10) it spans widths from 2·13/16 down to 2·3/16.
    let inside = r(10, 1) * (r(26, 16) + r(6, 16)) / r(2, 1);
    assert_eq!(union_area(&[&a, &thin]), r(100, 1) + r(16, 1) - inside);
}

#[test]
fn locate_is_exact_on_boundaries_and_in_notches() {
    let l = vec![[0, 0], [20, 0], [20, 10], [10, 10], [10, 20], [0, 20]];
    let at = |x: i64, y: i64, w: i64| HPoint {
        x: big(x as i128),
        y: big(y as i128),
        w: big(w as i128),
    };
    assert_eq!(locate(&l, &at(5, 5, 1)), Loc::Inside);
    assert_eq!(locate(&l, &at(15, 15, 1)), Loc::Outside);
    assert_eq!(locate(&l, &at(10, 15, 1)), Loc::Boundary);
    assert_eq!(locate(&l, &at(10, 10, 1)), Loc::Boundary);
    assert_eq!(locate(&l, &at(20, 0, 1)), Loc::Boundary);
    // Just inside and just outside the notch corner, a third of a unit away.
    assert_eq!(locate(&l, &at(29, 29, 3)), Loc::Inside);
    assert_eq!(locate(&l, &at(31, 31, 3)), Loc::Outside);
    // On the horizontal line of a vertex, left of it and right of the polygon.
    assert_eq!(locate(&l, &at(25, 10, 1)), Loc::Outside);
    assert_eq!(locate(&l, &at(-1, 10, 1)), Loc::Outside);
    assert_eq!(locate(&l, &at(15, 10, 1)), Loc::Boundary);
}

/// Area of the intersection of two counter-clockwise triangles: Sutherland–Hodgman in rationals.
fn triangle_intersection_area(a: &[[i64; 2]; 3], b: &[[i64; 2]; 3]) -> BigRational {
    let q = |p: [i64; 2]| [r(p[0], 1), r(p[1], 1)];
    let mut ring: Vec<[BigRational; 2]> = b.iter().map(|&p| q(p)).collect();
    for k in 0..3 {
        let (p, e) = (q(a[k]), q(a[(k + 1) % 3]));
        // Left of p→e is inside: f(x) = (e - p) x (x - p) >= 0.
        let f = |x: &[BigRational; 2]| {
            (&e[0] - &p[0]) * (&x[1] - &p[1]) - (&e[1] - &p[1]) * (&x[0] - &p[0])
        };
        let mut out = Vec::new();
        for i in 0..ring.len() {
            let (u, v) = (&ring[i], &ring[(i + 1) % ring.len()]);
            let (fu, fv) = (f(u), f(v));
            if !fu.is_negative() {
                out.push(u.clone());
            }
            if (fu.is_negative() && fv.is_positive()) || (fu.is_positive() && fv.is_negative()) {
                let t = &fu / (&fu - &fv);
                out.push([&u[0] + &t * (&v[0] - &u[0]), &u[1] + &t * (&v[1] - &u[1])]);
            }
        }
        ring = out;
        if ring.is_empty() {
            return BigRational::zero();
        }
    }
    twice_area(&ring) / r(2, 1)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    /// Two random triangles: the slab union is area(a) + area(b) - area(a ∩ b), the intersection
    /// clipped independently (crossings at rational abscissas).
    #[test]
    fn union_area_agrees_with_inclusion_exclusion(
        c in prop::array::uniform6(-1000i64..1000),
        d in prop::array::uniform6(-1000i64..1000),
    ) {
        let tri = |c: [i64; 6]| {
            let t = [[c[0], c[1]], [c[2], c[3]], [c[4], c[5]]];
            match orient(t[0], t[1], t[2]) {
                Ordering::Greater => Some(t),
                Ordering::Less => Some([t[0], t[2], t[1]]),
                Ordering::Equal => None,
            }
        };
        let (Some(a), Some(b)) = (tri(c), tri(d)) else { return Ok(()) };
        let want = shoelace(&a) + shoelace(&b) - triangle_intersection_area(&a, &b);
        prop_assert_eq!(union_area(&[&a, &b]), want);
    }

    /// The slab union agrees with the shoelace formula where the answer is known: one star, a
    /// star and its duplicate, a star and a far copy.
    #[test]
    fn union_area_agrees_with_shoelace(seed in any::<u64>()) {
        let mut g = Gen { rng: Rng(seed), dyadic: false };
        let s: Vec<[i64; 2]> = star(&mut g)
            .into_iter()
            .map(|[u, v]| [(u * 1e6) as i64, (v * 1e6) as i64])
            .collect();
        prop_assume!(is_simple(&s));
        let far: Vec<[i64; 2]> = s.iter().map(|p| [p[0] + 3_000_000, p[1] - 7]).collect();
        let area = shoelace(&s);
        prop_assert_eq!(union_area(&[&s]), area.clone());
        prop_assert_eq!(union_area(&[&s, &s]), area.clone());
        prop_assert_eq!(union_area(&[&s, &far]), area * r(2, 1));
    }
}
