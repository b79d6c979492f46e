//! Exact plane geometry for the references, independent of the kernel's predicates: points with
//! rational coordinates (homogeneous, big integers), lines and planes with big-integer
//! coefficients, polygons located by the even-odd rule, depth order, and distances.
//!
//! Invariant: every decision here (inside, on an edge, nearer) is the sign of an exact integer.
//! f64 appears in three places only: bounding-box prefilters, whose margins exceed the rounding
//! of the values they compare by many orders of magnitude (they only skip work whose exact
//! answer is certain); filters that decide a sign in f64 only when a bound proves it (below);
//! and the distances returned for the comparison band, each an exact value rounded once.
//!
//! **Filters.** A line or plane is also kept as f64 coefficients scaled so that the largest is 1,
//! each correctly rounded (relative error `u = 2^-53`, or an absolute one below 2^-1074 when it
//! underflows); a point as its correctly rounded coordinates. Evaluating `a·x + b·y + d` from
//! them errs by at most about `6u·(|a·x| + |b·y| + |d|)` (two roundings of each input, one per
//! product, two for the sums, to first order); the filters demand `|value| > 1e-13·(|a·x| +
//! |b·y| + |d|) + 1e-290`, over 400 times that, and otherwise decide in big integers.

use num_bigint::BigInt;
use num_rational::{BigRational, Ratio};
use num_traits::{Signed, ToPrimitive, Zero};
use std::cmp::Ordering;

/// A point (x/w, y/w), w > 0.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Point {
    /// Numerator of x.
    pub x: BigInt,
    /// Numerator of y.
    pub y: BigInt,
    /// The common denominator, positive.
    pub w: BigInt,
}

impl Point {
    /// The point (x, y) of integers.
    pub fn integer(x: BigInt, y: BigInt) -> Point {
        Point {
            x,
            y,
            w: BigInt::from(1),
        }
    }

    /// The point (x, y) of rationals.
    pub fn of(x: &BigRational, y: &BigRational) -> Point {
        let w = lcm(x.denom(), y.denom());
        Point {
            x: x.numer() * (&w / x.denom()),
            y: y.numer() * (&w / y.denom()),
            w,
        }
    }

    /// Its coordinates as rationals.
    pub fn rationals(&self) -> [BigRational; 2] {
        [
            BigRational::new(self.x.clone(), self.w.clone()),
            BigRational::new(self.y.clone(), self.w.clone()),
        ]
    }

    /// Its coordinates, each correctly rounded to f64.
    pub fn to_f64(&self) -> [f64; 2] {
        [ratio_f64(&self.x, &self.w), ratio_f64(&self.y, &self.w)]
    }
}

/// The least common multiple of two positive integers.
fn lcm(a: &BigInt, b: &BigInt) -> BigInt {
    // a/b reduced is (a/g)/(b/g), g = gcd(a, b): lcm = a·(b/g).
    a * Ratio::new(a.clone(), b.clone()).denom()
}

/// A finite f64, exactly.
pub fn rational(v: f64) -> BigRational {
    BigRational::from_float(v).expect("a finite value")
}

/// n / d correctly rounded (d != 0).
pub fn ratio_f64(n: &BigInt, d: &BigInt) -> f64 {
    Ratio::new_raw(n.clone(), d.clone())
        .to_f64()
        .unwrap_or(f64::NAN)
}

/// A line `a·x + b·y + d = 0`.
pub type Line = [BigInt; 3];

/// `a·x + b·y + d·w` at p: its sign is the side of the line p lies on (w > 0).
pub fn line_value(l: &Line, p: &Point) -> BigInt {
    &l[0] * &p.x + &l[1] * &p.y + &l[2] * &p.w
}

/// The side of a line p lies on.
pub fn side(l: &Line, p: &Point) -> Ordering {
    line_value(l, p).sign_cmp()
}

/// The line through p and q, positive on the left of p → q (y up): its value at r is
/// `orient2d(p, q, r)` times a positive factor (the cross product of the homogeneous points).
pub fn line_through(p: &Point, q: &Point) -> Line {
    [
        &p.y * &q.w - &p.w * &q.y,
        &p.w * &q.x - &p.x * &q.w,
        &p.x * &q.y - &p.y * &q.x,
    ]
}

/// The exact distance from p to a line, rounded once (infinite when `a = b = 0`).
pub fn distance_to_line(l: &Line, p: &Point) -> f64 {
    let norm = &l[0] * &l[0] + &l[1] * &l[1];
    if norm.is_zero() {
        return f64::INFINITY;
    }
    let v = line_value(l, p);
    ratio_f64(&(&v * &v), &(norm * &p.w * &p.w)).sqrt()
}

/// The exact distance from p to the segment a–b, rounded once.
pub fn distance_to_segment(p: &Point, a: &Point, b: &Point) -> f64 {
    let [px, py] = p.rationals();
    let [ax, ay] = a.rationals();
    let [bx, by] = b.rationals();
    let (dx, dy) = (&bx - &ax, &by - &ay);
    let (vx, vy) = (&px - &ax, &py - &ay);
    let t = &vx * &dx + &vy * &dy;
    let dd = &dx * &dx + &dy * &dy;
    let squared = if !t.is_positive() || dd.is_zero() {
        &vx * &vx + &vy * &vy
    } else if t >= dd {
        let (ux, uy) = (&px - &bx, &py - &by);
        &ux * &ux + &uy * &uy
    } else {
        let cross = &vx * &dy - &vy * &dx;
        &cross * &cross / dd
    };
    squared.to_f64().unwrap_or(f64::INFINITY).sqrt()
}

/// The sign of a big integer as an ordering against 0.
pub trait SignCmp {
    /// `Less`, `Equal` or `Greater` than 0.
    fn sign_cmp(&self) -> Ordering;
}

impl SignCmp for BigInt {
    fn sign_cmp(&self) -> Ordering {
        self.cmp(&BigInt::zero())
    }
}

/// The filters' relative bound (see the module docs).
const FILTER: f64 = 1e-13;
/// The filters' absolute bound: covers coefficients that underflow.
const TINY: f64 = 1e-290;

/// The coefficients scaled by one positive factor so that the largest is 1, each correctly
/// rounded; `None` when all are 0.
pub fn normalized<const N: usize>(c: &[BigInt; N]) -> Option<[f64; N]> {
    let m = c.iter().map(|v| v.abs()).max()?;
    if m.is_zero() {
        return None;
    }
    Some(std::array::from_fn(|k| ratio_f64(&c[k], &m)))
}

/// The sign of `a·x + b·y + d` (normalized coefficients) at q (a point's correctly rounded
/// coordinates), when the f64 evaluation proves it.
fn filtered_side(l: &[f64; 3], q: [f64; 2]) -> Option<Ordering> {
    let (t0, t1) = (l[0] * q[0], l[1] * q[1]);
    let v = t0 + t1 + l[2];
    let bound = FILTER * (t0.abs() + t1.abs() + l[2].abs()) + TINY;
    if v > bound {
        Some(Ordering::Greater)
    } else if v < -bound {
        Some(Ordering::Less)
    } else {
        None
    }
}

/// The order of two correctly rounded values, when their f64 values prove it.
fn filtered_cmp(a: f64, b: f64) -> Option<Ordering> {
    let m = FILTER * a.abs().max(b.abs()) + TINY;
    if a < b - m {
        Some(Ordering::Less)
    } else if a > b + m {
        Some(Ordering::Greater)
    } else {
        None
    }
}

/// A plane's depth at q in f64 with its error bound, from normalized coefficients (a, b, c, d):
/// `z = -(a·x + b·y + d) / c`; `None` when c is too small for a bound.
fn filtered_depth(pl: &[f64; 4], q: [f64; 2]) -> Option<(f64, f64)> {
    let (t0, t1) = (pl[0] * q[0], pl[1] * q[1]);
    if pl[2] < 1e-200 {
        return None;
    }
    let z = -(t0 + t1 + pl[3]) / pl[2];
    let err = (FILTER * (t0.abs() + t1.abs() + pl[3].abs()) + TINY) / pl[2];
    Some((z, err))
}

/// A plane `a·x + b·y + c·z + d = 0` with `c > 0` (smaller z is nearer).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plane {
    /// a, b, c, d.
    pub coefficients: [BigInt; 4],
}

impl Plane {
    /// A plane from its coefficients (`c > 0`).
    pub fn new(coefficients: [BigInt; 4]) -> Plane {
        debug_assert!(coefficients[2].is_positive());
        Plane { coefficients }
    }

    /// The plane through three points with rational (x, y, z), or `None` when their (x, y) are
    /// collinear (the plane contains the view direction).
    pub fn through(
        p: &[BigRational; 3],
        q: &[BigRational; 3],
        r: &[BigRational; 3],
    ) -> Option<Plane> {
        let u: Vec<BigRational> = (0..3).map(|k| &q[k] - &p[k]).collect();
        let v: Vec<BigRational> = (0..3).map(|k| &r[k] - &p[k]).collect();
        let mut n = [
            &u[1] * &v[2] - &u[2] * &v[1],
            &u[2] * &v[0] - &u[0] * &v[2],
            &u[0] * &v[1] - &u[1] * &v[0],
        ];
        if n[2].is_zero() {
            return None;
        }
        if n[2].is_negative() {
            n = n.map(|c| -c);
        }
        let d = -(&n[0] * &p[0] + &n[1] * &p[1] + &n[2] * &p[2]);
        // Clear the denominators: multiply by their product.
        let all = [&n[0], &n[1], &n[2], &d];
        let scale = all.iter().fold(BigInt::from(1), |s, c| lcm(&s, c.denom()));
        let int = |c: &BigRational| c.numer() * (&scale / c.denom());
        Some(Plane::new([int(&n[0]), int(&n[1]), int(&n[2]), int(&d)]))
    }

    /// `a·x + b·y + d·w` at p: the depth there is `-value / (c·w)`.
    pub fn depth_value(&self, p: &Point) -> BigInt {
        let [a, b, _, d] = &self.coefficients;
        a * &p.x + b * &p.y + d * &p.w
    }

    /// Depth order at p: `Less` when `self` is nearer than `other`.
    pub fn order_at(&self, other: &Plane, p: &Point) -> Ordering {
        // z_s < z_o  <=>  N_s·c_o > N_o·c_s  (c > 0, w > 0).
        let (s, o) = (self.depth_value(p), other.depth_value(p));
        (&o * &self.coefficients[2]).cmp(&(&s * &other.coefficients[2]))
    }

    /// Are the two the same plane (proportional coefficients)?
    pub fn same(&self, other: &Plane) -> bool {
        let (s, o) = (&self.coefficients, &other.coefficients);
        [0, 1, 3].iter().all(|&k| &s[k] * &o[2] == &o[k] * &s[2])
    }

    /// Where the two have equal depth, on screen: `c_o·self - c_s·other` without its z term,
    /// positive where `self` is nearer. Zero coefficients (a = b = 0) when they are parallel.
    pub fn meeting(&self, other: &Plane) -> Line {
        let (s, o) = (&self.coefficients, &other.coefficients);
        let l = |k: usize| &o[2] * &s[k] - &s[2] * &o[k];
        [l(0), l(1), l(3)]
    }

    /// The depth gradient (dz/dx, dz/dy), rounded once each.
    pub fn gradient(&self) -> [f64; 2] {
        let [a, b, c, _] = &self.coefficients;
        [-ratio_f64(a, c), -ratio_f64(b, c)]
    }
}

/// Where a point lies relative to a closed region.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Loc {
    /// In its interior.
    Inside,
    /// On its boundary.
    Boundary,
    /// Outside its closure.
    Outside,
}

/// f64 bounds (x0, y0, x1, y1) of points, widened by `margin`.
pub fn bounds(points: &[Point], margin: f64) -> [f64; 4] {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for p in points {
        let [x, y] = p.to_f64();
        b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
    }
    [b[0] - margin, b[1] - margin, b[2] + margin, b[3] + margin]
}

/// Is the f64 point `q` (each coordinate within `err` of the exact one) inside the bounds `b`
/// widened by `reach`? `false` proves the exact point farther than `reach` outside.
pub fn near_bounds(b: &[f64; 4], q: [f64; 2], err: f64, reach: f64) -> bool {
    let m = err + reach;
    q[0] >= b[0] - m && q[0] <= b[2] + m && q[1] >= b[1] - m && q[1] <= b[3] + m
}

/// A polygon of the reference: exact corners, an exact support plane, and what the tie rule
/// between coplanar polygons needs.
#[derive(Clone, Debug)]
pub struct Polygon {
    /// Index into `Scene::faces`.
    pub face: u32,
    /// The input face id: among coplanar polygons the larger is in front, then the later one.
    pub id: u32,
    /// The corners, in order.
    pub corners: Vec<Point>,
    /// `edges[k]`: the line through corners k and k + 1.
    pub edges: Vec<Line>,
    /// The support plane.
    pub plane: Plane,
    /// The corners in f64, correctly rounded.
    corners_f64: Vec<[f64; 2]>,
    /// The edges' normalized f64 coefficients (the filter).
    edges_f64: Vec<Option<[f64; 3]>>,
    /// The plane's normalized f64 coefficients (the filter).
    plane_f64: Option<[f64; 4]>,
    /// f64 bounds of the corners, widened by the margin.
    pub bounds: [f64; 4],
    /// Bounds the rounding of any coordinate of the scene to f64, and of an f64 distance
    /// between such points, many times over.
    pub margin: f64,
}

impl Polygon {
    /// A polygon from its corners and plane; `margin` bounds the rounding of any coordinate
    /// of the scene to f64 (many times over).
    pub fn new(face: u32, id: u32, corners: Vec<Point>, plane: Plane, margin: f64) -> Polygon {
        let n = corners.len();
        let edges: Vec<Line> = (0..n)
            .map(|k| line_through(&corners[k], &corners[(k + 1) % n]))
            .collect();
        let bounds = bounds(&corners, margin);
        Polygon {
            face,
            id,
            corners_f64: corners.iter().map(Point::to_f64).collect(),
            edges_f64: edges.iter().map(normalized).collect(),
            plane_f64: normalized(&plane.coefficients),
            corners,
            edges,
            plane,
            bounds,
            margin,
        }
    }

    /// Exact point-in-polygon (even-odd, so any simple polygon) of a rational point p; `q` is
    /// p correctly rounded.
    pub fn locate(&self, p: &Point, q: [f64; 2]) -> Loc {
        let n = self.corners.len();
        let mut inside = false;
        // y_a > y_p, exactly.
        let above = |k: usize| {
            let a = &self.corners[k];
            filtered_cmp(self.corners_f64[k][1], q[1])
                .unwrap_or_else(|| (&a.y * &p.w).cmp(&(&p.y * &a.w)))
                == Ordering::Greater
        };
        for k in 0..n {
            let o = self.edges_f64[k]
                .and_then(|l| filtered_side(&l, q))
                .unwrap_or_else(|| side(&self.edges[k], p));
            let (a, b) = (&self.corners[k], &self.corners[(k + 1) % n]);
            if o == Ordering::Equal && within_box(a, b, p) {
                return Loc::Boundary;
            }
            // Half-open rule on y; the crossing is right of p when p is left of the upward edge.
            let (a_above, b_above) = (above(k), above((k + 1) % n));
            if a_above != b_above {
                let upward = b_above;
                if (upward && o == Ordering::Greater) || (!upward && o == Ordering::Less) {
                    inside = !inside;
                }
            }
        }
        if inside { Loc::Inside } else { Loc::Outside }
    }

    /// The depth at q (p correctly rounded) in f64 with a bound on its error, when the filter
    /// can bound it.
    pub fn depth_f64(&self, q: [f64; 2]) -> Option<(f64, f64)> {
        self.plane_f64.and_then(|pl| filtered_depth(&pl, q))
    }

    /// Depth order at p against `other`: `Less` when `self` is nearer (f64 first, exact when
    /// the filter cannot tell).
    pub fn order_at(&self, other: &Polygon, p: &Point, q: [f64; 2]) -> Ordering {
        if let (Some(s), Some(o)) = (self.plane_f64, other.plane_f64)
            && let (Some((zs, es)), Some((zo, eo))) = (filtered_depth(&s, q), filtered_depth(&o, q))
        {
            if zs + es < zo - eo {
                return Ordering::Less;
            }
            if zs - es > zo + eo {
                return Ordering::Greater;
            }
        }
        self.plane.order_at(&other.plane, p)
    }

    /// Is some edge within `reach` of p (exact distance, rounded once)? `q` is p in f64, within
    /// `err` of it. An edge is skipped without exact arithmetic when its f64 distance exceeds
    /// `reach` by more than the margin (which bounds the f64 distance's error many times over).
    pub fn edge_within(&self, p: &Point, q: [f64; 2], err: f64, reach: f64) -> bool {
        if !near_bounds(&self.bounds, q, err, reach) {
            return false;
        }
        let n = self.corners.len();
        (0..n).any(|k| {
            let (a, b) = (&self.corners[k], &self.corners[(k + 1) % n]);
            approx_segment_distance(q, a.to_f64(), b.to_f64()) <= reach + err + self.margin
                && distance_to_segment(p, a, b) <= reach
        })
    }
}

/// The distance from q to the segment a–b in f64.
fn approx_segment_distance(q: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let (vx, vy) = (q[0] - a[0], q[1] - a[1]);
    let dd = dx * dx + dy * dy;
    let t = if dd > 0.0 {
        ((vx * dx + vy * dy) / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (vx - t * dx).hypot(vy - t * dy)
}

/// Is p within the closed box of segment a–b (exact)?
fn within_box(a: &Point, b: &Point, p: &Point) -> bool {
    let le = |u: &BigInt, uw: &BigInt, v: &BigInt, vw: &BigInt| u * vw <= v * uw;
    let between = |ac: &BigInt, bc: &BigInt, pc: &BigInt| {
        let (lo, hi) = if le(ac, &a.w, bc, &b.w) {
            ((ac, &a.w), (bc, &b.w))
        } else {
            ((bc, &b.w), (ac, &a.w))
        };
        le(lo.0, lo.1, pc, &p.w) && le(pc, &p.w, hi.0, hi.1)
    };
    between(&a.x, &b.x, &p.x) && between(&a.y, &b.y, &p.y)
}

/// The nearest of the polygons containing p (closed), by exact depth; among coplanar ones the
/// larger face id, then the later polygon (the kernel's tie rule, as the z-buffer's). Also every
/// polygon containing p. `q`/`err`: p in f64 and its error, for the bounds prefilter.
pub fn nearest(polys: &[Polygon], p: &Point, q: [f64; 2], err: f64) -> (Option<usize>, Vec<usize>) {
    let containing: Vec<usize> = polys
        .iter()
        .enumerate()
        .filter(|(_, g)| near_bounds(&g.bounds, q, err, 0.0) && g.locate(p, q) != Loc::Outside)
        .map(|(k, _)| k)
        .collect();
    let mut best: Option<usize> = None;
    for &k in &containing {
        best = Some(match best {
            None => k,
            Some(b) => {
                let (pb, pk) = (&polys[b], &polys[k]);
                match pk.order_at(pb, p, q) {
                    Ordering::Less => k,
                    Ordering::Greater => b,
                    Ordering::Equal => {
                        if (pk.id, k) > (pb.id, b) {
                            k
                        } else {
                            b
                        }
                    }
                }
            }
        });
    }
    (best, containing)
}

/// Where two lines cross, or `None` when they are parallel.
pub fn crossing(l: &Line, m: &Line) -> Option<Point> {
    let w = &l[0] * &m[1] - &m[0] * &l[1];
    if w.is_zero() {
        return None;
    }
    let x = &l[1] * &m[2] - &m[1] * &l[2];
    let y = &m[0] * &l[2] - &l[0] * &m[2];
    Some(if w.is_negative() {
        Point {
            x: -x,
            y: -y,
            w: -w,
        }
    } else {
        Point { x, y, w }
    })
}

/// A convex region bounded by lines (inside on the positive side of each), as a piece is.
#[derive(Clone, Debug)]
pub struct Convex {
    /// Index of the polygon it belongs to.
    pub poly: usize,
    /// Its lines.
    pub lines: Vec<Line>,
    /// Their normalized f64 coefficients (the filter).
    lines_f64: Vec<Option<[f64; 3]>>,
    /// f64 bounds of its vertices (consecutive lines' crossings), widened by the margin; the
    /// whole plane when two consecutive lines are parallel (a malformed piece is then still
    /// located exactly).
    pub bounds: [f64; 4],
}

impl Convex {
    /// A convex region of polygon `poly`; `margin` as for [`Polygon::new`].
    pub fn new(poly: usize, lines: Vec<Line>, margin: f64) -> Convex {
        let n = lines.len();
        let vertices: Option<Vec<Point>> = (0..n)
            .map(|k| crossing(&lines[(k + n - 1) % n], &lines[k]))
            .collect();
        let bounds = match vertices {
            Some(v) if n >= 3 => bounds(&v, margin),
            _ => [
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::INFINITY,
            ],
        };
        Convex {
            poly,
            lines_f64: lines.iter().map(normalized).collect(),
            lines,
            bounds,
        }
    }

    /// Exact location of p.
    pub fn locate(&self, p: &Point, q: [f64; 2], err: f64) -> Loc {
        if !near_bounds(&self.bounds, q, err, 0.0) {
            return Loc::Outside;
        }
        let mut on = false;
        for (l, f) in self.lines.iter().zip(&self.lines_f64) {
            match f
                .and_then(|f| filtered_side(&f, q))
                .unwrap_or_else(|| side(l, p))
            {
                Ordering::Less => return Loc::Outside,
                Ordering::Equal => on = true,
                Ordering::Greater => {}
            }
        }
        if on { Loc::Boundary } else { Loc::Inside }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pt(x: i64, y: i64, w: i64) -> Point {
        Point {
            x: x.into(),
            y: y.into(),
            w: w.into(),
        }
    }

    fn flat(z: i64) -> Plane {
        // z = const: 0·x + 0·y + 1·z - z0 = 0.
        Plane::new([0.into(), 0.into(), 1.into(), (-z).into()])
    }

    fn square(face: u32, z: i64) -> Polygon {
        let c = vec![pt(0, 0, 1), pt(10, 0, 1), pt(10, 10, 1), pt(0, 10, 1)];
        Polygon::new(face, face, c, flat(z), 1e-6)
    }

    #[test]
    fn locate_is_exact_on_edges_corners_and_a_third_of_a_unit_away() {
        let s = square(0, 0);
        assert_eq!(s.locate(&pt(5, 5, 1), pt(5, 5, 1).to_f64()), Loc::Inside);
        assert_eq!(
            s.locate(&pt(10, 5, 1), pt(10, 5, 1).to_f64()),
            Loc::Boundary
        );
        assert_eq!(s.locate(&pt(0, 0, 1), pt(0, 0, 1).to_f64()), Loc::Boundary);
        assert_eq!(
            s.locate(&pt(29, 29, 3), pt(29, 29, 3).to_f64()),
            Loc::Inside
        );
        assert_eq!(
            s.locate(&pt(31, 29, 3), pt(31, 29, 3).to_f64()),
            Loc::Outside
        );
        assert_eq!(
            s.locate(&pt(-1, 10, 1), pt(-1, 10, 1).to_f64()),
            Loc::Outside
        );
    }

    #[test]
    fn nearest_takes_the_smallest_depth_then_the_larger_id_among_coplanar_polygons() {
        let polys = vec![square(0, 5), square(1, 3), square(2, 3)];
        let p = pt(5, 5, 1);
        assert_eq!(nearest(&polys, &p, [5.0, 5.0], 0.0).0, Some(2));
        assert_eq!(nearest(&polys[..1], &p, [5.0, 5.0], 0.0).0, Some(0));
        assert_eq!(nearest(&polys, &pt(50, 5, 1), [50.0, 5.0], 0.0).0, None);
    }

    #[test]
    fn the_meeting_line_is_where_depths_are_equal_and_positive_where_self_is_nearer() {
        // z = x and z = 10 - x meet at x = 5.
        let p = Plane::new([(-1).into(), 0.into(), 1.into(), 0.into()]);
        let q = Plane::new([1.into(), 0.into(), 1.into(), (-10).into()]);
        let m = p.meeting(&q);
        assert_eq!(side(&m, &pt(5, 7, 1)), Ordering::Equal);
        assert_eq!(side(&m, &pt(2, 0, 1)), Ordering::Greater); // p (z = 2) nearer than q (8)
        assert_eq!(p.order_at(&q, &pt(2, 0, 1)), Ordering::Less);
        assert!((distance_to_line(&m, &pt(8, 0, 1)) - 3.0).abs() < 1e-12);
    }

    #[test]
    fn segment_distance_is_to_the_nearest_end_beyond_the_segment() {
        let (a, b) = (pt(0, 0, 1), pt(4, 0, 1));
        assert_eq!(distance_to_segment(&pt(2, 3, 1), &a, &b), 3.0);
        assert_eq!(distance_to_segment(&pt(7, 4, 1), &a, &b), 5.0);
        assert_eq!(distance_to_segment(&pt(-3, -4, 1), &a, &b), 5.0);
    }
}
