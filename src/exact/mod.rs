//! The exact screen representation and the predicates the renderers need.
//!
//! # Representation
//!
//! After clipping (in f64 homogeneous coordinates) every polygon is projected to NDC and its
//! corners are snapped to a signed integer grid:
//!
//! - `x`, `y`: `round(ndc · 2^22)`. Polygons are clipped to a guard band `|x|, |y| <= 2·w`, so
//!   `|x|, |y| <= 2^23`; the visible view `[-1,1]` is 2^23 = 8.4 million units across, over 500
//!   units per pixel even at the largest image side, 16384. `y` grows upward here, as in NDC;
//!   outputs flip it.
//! - `z`: `round(ndc_z · 2^23)`, `|z| <= 2^23`, smaller is nearer.
//!
//! That is B = 24-bit signed input. **Snapping bound**: each coordinate moves by at most half a
//! unit: 2^-23 in NDC x and y (1/16 of a micro-pixel at 1024 px: far below any plot resolution),
//! and 2^-24 in NDC z. This is the one approximation on the way in; everything after it is exact.
//!
//! A face is its snapped 2D polygon plus one support plane through three of its snapped corners
//! ([`Plane`]): the depth of the face at any (x, y) is the plane's, so a face is exactly planar
//! after snapping even when its corners' snapped z are not coplanar (a quad whose four rounded
//! corners are not coplanar). For triangles the plane passes through all three corners.
//!
//! # Bit budget
//!
//! Coordinate differences are below 2^25 (guard band), so a plane normal component is below
//! 2·2^25·2^25 = 2^51 (i64) and its offset below 3·2^51·2^23 < 2^76 (i128). A pixel-sample
//! coordinate, scaled to an integer by the image side (at most 2^14), is below 2^38.
//! - edge-versus-sample tests are below 2^80: i128;
//! - depth of a plane at a sample (numerator) is below 2^104: i128;
//! - comparing two such depths cross-multiplies by the other plane's z-normal: below 2^156, done in
//!   256-bit integers (`bnum::types::I256`).
//!
//! # Filters
//!
//! Hot predicates are evaluated in f64 with an error bound proven in their docs; only when the
//! bound cannot decide do they fall back to the integer computation. Every fallback is counted
//! in [`Fallbacks`].

pub mod polygon;
pub mod predicates;

use bnum::cast::As;
use bnum::types::I256;
use std::cell::Cell;

/// Grid units per NDC unit in x and y.
pub const XY_SCALE: f64 = 4_194_304.0; // 2^22
/// Grid units per NDC unit in z.
pub const Z_SCALE: f64 = 8_388_608.0; // 2^23
/// Polygons are clipped to |x|, |y| <= GUARD · w in clip space.
pub const GUARD: f64 = 2.0;
/// Largest |coordinate| on the grid.
pub const GRID_MAX: i64 = 1 << 23;

/// f64 unit roundoff.
pub const U: f64 = f64::EPSILON / 2.0;

/// A snapped corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct GridPoint {
    /// `round(ndc_x · 2^22)`.
    pub x: i32,
    /// `round(ndc_y · 2^22)`, growing upward.
    pub y: i32,
    /// `round(ndc_z · 2^23)`, smaller is nearer.
    pub z: i32,
}

impl GridPoint {
    /// Snaps an NDC point (already inside the guard band and depth range).
    #[inline]
    pub fn snap(ndc_x: f64, ndc_y: f64, ndc_z: f64) -> GridPoint {
        let c = |v: f64, s: f64| {
            let g = (v * s).round();
            g.clamp(-(GRID_MAX as f64), GRID_MAX as f64) as i32
        };
        GridPoint {
            x: c(ndc_x, XY_SCALE),
            y: c(ndc_y, XY_SCALE),
            z: c(ndc_z, Z_SCALE),
        }
    }
}

/// Twice the signed area of a grid polygon's (x, y) projection, exactly. Positive when the polygon
/// runs counter-clockwise with y up: for a front face (OpenGL's GL_CCW).
pub fn twice_signed_area(points: &[GridPoint]) -> i128 {
    let n = points.len();
    let mut s: i128 = 0;
    for i in 0..n {
        let a = points[i];
        let b = points[(i + 1) % n];
        s += a.x as i128 * b.y as i128 - b.x as i128 * a.y as i128;
    }
    s
}

/// A plane `a·x + b·y + c·z + d = 0` of the grid, built from grid points only: a support plane
/// (`c > 0`, through three snapped corners) or an edge plane (`c == 0`, vertical, through two).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Plane {
    /// Coefficient of x.
    pub a: i64,
    /// Coefficient of y.
    pub b: i64,
    /// Coefficient of z: positive for a support plane, 0 for an edge plane.
    pub c: i64,
    /// The constant term.
    pub d: i128,
}

impl Plane {
    /// The plane through three points, or `None` when their (x, y) projections are collinear
    /// (the plane would be parallel to the view direction).
    pub fn through(p: GridPoint, q: GridPoint, r: GridPoint) -> Option<Plane> {
        let (ux, uy, uz) = ((q.x - p.x) as i64, (q.y - p.y) as i64, (q.z - p.z) as i64);
        let (vx, vy, vz) = ((r.x - p.x) as i64, (r.y - p.y) as i64, (r.z - p.z) as i64);
        let mut a = uy * vz - uz * vy;
        let mut b = uz * vx - ux * vz;
        let mut c = ux * vy - uy * vx;
        if c == 0 {
            return None;
        }
        if c < 0 {
            (a, b, c) = (-a, -b, -c);
        }
        let d = -(a as i128 * p.x as i128 + b as i128 * p.y as i128 + c as i128 * p.z as i128);
        Some(Plane { a, b, c, d })
    }

    /// The vertical plane through the (x, y) of `p` and `q`, positive on the left of `p → q`
    /// (inside a counter-clockwise polygon, y up): its value at r is `orient2d(p, q, r)`.
    /// `None` when `p` and `q` have the same (x, y).
    pub fn edge(p: GridPoint, q: GridPoint) -> Option<Plane> {
        let a = p.y as i64 - q.y as i64;
        let b = q.x as i64 - p.x as i64;
        if a == 0 && b == 0 {
            return None;
        }
        let d = -(a as i128 * p.x as i128 + b as i128 * p.y as i128);
        Some(Plane { a, b, c: 0, d })
    }

    /// The plane's equation at a grid point, exactly.
    #[inline]
    pub fn value_at(&self, p: GridPoint) -> i128 {
        self.a as i128 * p.x as i128
            + self.b as i128 * p.y as i128
            + self.c as i128 * p.z as i128
            + self.d
    }

    /// The same plane with its sides swapped.
    pub fn negated(&self) -> Plane {
        Plane {
            a: -self.a,
            b: -self.b,
            c: -self.c,
            d: -self.d,
        }
    }

    /// The support plane of a snapped polygon: through its first corner, the corner farthest from
    /// it, and the corner making the largest projected area with those two (so `c` is as large
    /// as the polygon allows). `None` when the polygon's projection has no area.
    pub fn of_polygon(points: &[GridPoint]) -> Option<Plane> {
        if points.len() == 3 {
            return Plane::through(points[0], points[1], points[2]);
        }
        let p = points[0];
        let d2 = |q: &GridPoint| {
            let dx = (q.x - p.x) as i64;
            let dy = (q.y - p.y) as i64;
            dx * dx + dy * dy
        };
        let q = *points.iter().max_by_key(|q| d2(q))?;
        let cross = |r: &GridPoint| {
            ((q.x - p.x) as i64 * (r.y - p.y) as i64 - (q.y - p.y) as i64 * (r.x - p.x) as i64)
                .abs()
        };
        let r = *points.iter().max_by_key(|r| cross(r))?;
        Plane::through(p, q, r)
    }
}

/// The pixel-sample lattice of a `width x height` image on the grid. Sample (i, j) is the centre
/// of pixel column i, row j (row 0 at the top), at grid
/// `x = (2i + 1 - W)·2^22 / W`, `y = (H - 2j - 1)·2^22 / H`.
#[derive(Clone, Copy, Debug)]
pub struct Samples {
    /// Image width W in pixels.
    pub width: i64,
    /// Image height H in pixels.
    pub height: i64,
}

impl Samples {
    /// The samples of a `width x height` image (each side at most
    /// [`MAX_IMAGE_SIDE`](crate::camera::MAX_IMAGE_SIDE)).
    pub fn new(width: u32, height: u32) -> Samples {
        debug_assert!(
            width <= crate::camera::MAX_IMAGE_SIDE && height <= crate::camera::MAX_IMAGE_SIDE
        );
        Samples {
            width: width as i64,
            height: height as i64,
        }
    }

    /// Numerator of sample column i's x (denominator W).
    #[inline]
    pub fn x_num(&self, i: i64) -> i64 {
        (2 * i + 1 - self.width) << 22
    }

    /// Numerator of sample row j's y (denominator H).
    #[inline]
    pub fn y_num(&self, j: i64) -> i64 {
        (self.height - 2 * j - 1) << 22
    }

    /// Sample x in grid units (f64).
    #[inline]
    pub fn x(&self, i: i64) -> f64 {
        self.x_num(i) as f64 / self.width as f64
    }

    /// Sample y in grid units (f64).
    #[inline]
    pub fn y(&self, j: i64) -> f64 {
        self.y_num(j) as f64 / self.height as f64
    }

    /// Continuous column coordinate of grid x: sample i sits at i + 0.5.
    #[inline]
    pub fn col_of(&self, x: f64) -> f64 {
        (x / XY_SCALE + 1.0) * 0.5 * self.width as f64
    }

    /// Continuous row coordinate of grid y: sample j sits at j + 0.5.
    #[inline]
    pub fn row_of(&self, y: f64) -> f64 {
        (1.0 - y / XY_SCALE) * 0.5 * self.height as f64
    }

    /// The first column whose sample lies at or to the right of the point where edge `p→q`
    /// crosses sample row j. The edge must cross the row (`p.y <= y_j < q.y` or the reverse).
    ///
    /// Filter: the crossing's column coordinate is computed in f64 from exact integer inputs with
    /// at most 8 roundings on quantities bounded by 2^26 grid units, so its error is below
    /// 2^-22 · W · 2^-52 · 16 < 1e-9 columns for W <= 2^14. When the crossing is farther than 1e-9
    /// from a sample column the rounded-up column is right; otherwise the exact i128 computation
    /// decides.
    #[inline]
    pub fn first_column_at_or_right(
        &self,
        p: GridPoint,
        q: GridPoint,
        j: i64,
        fallbacks: &Fallbacks,
    ) -> i64 {
        let (p, q) = if p.y <= q.y { (p, q) } else { (q, p) };
        let ys = self.y(j);
        let xc = p.x as f64 + (ys - p.y as f64) * (q.x - p.x) as f64 / (q.y - p.y) as f64;
        let t = self.col_of(xc) - 0.5;
        let cand = t.ceil();
        if cand - t > 1e-9 && t - (cand - 1.0) > 1e-9 {
            return cand as i64;
        }
        fallbacks.column.set(fallbacks.column.get() + 1);
        self.first_column_exact(p, q, j)
    }

    /// Exact version of [`Self::first_column_at_or_right`] (`p.y < q.y`).
    pub fn first_column_exact(&self, p: GridPoint, q: GridPoint, j: i64) -> i64 {
        let (w, h) = (self.width as i128, self.height as i128);
        let dy = (q.y - p.y) as i128;
        let dx = (q.x - p.x) as i128;
        // Crossing x = p.x + (ys - p.y)·dx/dy with ys = y_num/H. Scaled by W/2^22 it is N / D:
        let n = (p.x as i128 * dy * h + (self.y_num(j) as i128 - p.y as i128 * h) * dx) * w;
        let d = (dy * h) << 22;
        // Sample i is at or right of the crossing iff (2i + 1 - W)·D >= N.
        let t = div_ceil(n, d);
        div_ceil(t + w - 1, 2) as i64
    }
}

fn div_ceil(n: i128, d: i128) -> i128 {
    debug_assert!(d > 0);
    let q = n.div_euclid(d);
    if n.rem_euclid(d) == 0 { q } else { q + 1 }
}

/// Depth of a plane across the sample lattice in f64, with its certified error bound.
///
/// `z(i, j) = zi·i + zj·j + z0` (grid units). Each coefficient comes from exact integers through
/// at most 7 roundings, each relative to the magnitude of the terms it combines; the evaluation
/// adds 4 more. The terms of `z0` are bounded by `|zi|·W/2 + |zj|·H/2 + 2^23` (the plane passes
/// through a corner with |x|, |y|, |z| <= 2^23), so
/// `|z_f64 - z| <= 12·U·(|zi|·W + |zj|·H + |z0| + 2^24)`; `err` takes 16·U for margin.
#[derive(Clone, Copy, Debug)]
pub struct DepthPlane {
    /// Depth change per sample column.
    pub zi: f64,
    /// Depth change per sample row.
    pub zj: f64,
    /// Depth at sample (0, 0).
    pub z0: f64,
    /// The bound on the error of [`Self::at`] anywhere in the image.
    pub err: f64,
}

impl DepthPlane {
    /// The depth of `plane` across the samples `s`.
    pub fn new(plane: &Plane, s: &Samples) -> DepthPlane {
        let (w, h) = (s.width as f64, s.height as f64);
        let (a, b, c, d) = (
            plane.a as f64,
            plane.b as f64,
            plane.c as f64,
            plane.d as f64,
        );
        // z = -(a·x + b·y + d)/c with x = (2i + 1 - W)·2^22/W, y = (H - 2j - 1)·2^22/H.
        let zi = -a * (2.0 * XY_SCALE) / (w * c);
        let zj = b * (2.0 * XY_SCALE) / (h * c);
        let z0 = -(a * ((1.0 - w) * XY_SCALE / w) + b * ((h - 1.0) * XY_SCALE / h) + d) / c;
        let mag = zi.abs() * w + zj.abs() * h + z0.abs() + 2.0 * GRID_MAX as f64;
        let err = 16.0 * U * mag;
        DepthPlane { zi, zj, z0, err }
    }

    /// The depth at sample (i, j), within `err` of the exact one.
    #[inline]
    pub fn at(&self, i: i64, j: i64) -> f64 {
        self.zi * i as f64 + self.zj * j as f64 + self.z0
    }
}

/// Exact comparison of two planes' depths at sample (i, j): `Less` when `p` is nearer.
pub fn compare_depth_exact(
    p: &Plane,
    q: &Plane,
    s: &Samples,
    i: i64,
    j: i64,
) -> std::cmp::Ordering {
    // z = -N/(c·W·H) with N = a·xn·H + b·yn·W + d·W·H  (xn, yn the sample numerators).
    let num = |pl: &Plane| -> i128 {
        pl.a as i128 * s.x_num(i) as i128 * s.height as i128
            + pl.b as i128 * s.y_num(j) as i128 * s.width as i128
            + pl.d * s.width as i128 * s.height as i128
    };
    // z_p < z_q  <=>  -N_p/c_p < -N_q/c_q  <=>  N_q·c_p < N_p·c_q   (c > 0)
    let wide = |v: i128| -> I256 { v.as_() };
    let lhs = wide(num(q)) * wide(p.c as i128);
    let rhs = wide(num(p)) * wide(q.c as i128);
    lhs.cmp(&rhs)
}

/// Exact depth of a plane at sample (i, j), as NDC z in f64 (rounded once, for output only).
pub fn depth_ndc(p: &Plane, s: &Samples, i: i64, j: i64) -> f64 {
    let n = p.a as i128 * s.x_num(i) as i128 * s.height as i128
        + p.b as i128 * s.y_num(j) as i128 * s.width as i128
        + p.d * s.width as i128 * s.height as i128;
    let den = p.c as i128 * s.width as i128 * s.height as i128;
    -(n as f64 / den as f64) / Z_SCALE
}

/// Counts of predicate evaluations the f64 filter could not decide.
#[derive(Debug, Default)]
pub struct Fallbacks {
    /// Edge-against-sample tests decided exactly.
    pub column: Cell<u64>,
    /// Depth comparisons decided exactly.
    pub depth: Cell<u64>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gp(x: i32, y: i32, z: i32) -> GridPoint {
        GridPoint { x, y, z }
    }

    /// Slow reference: smallest i whose sample x (rational) is >= the crossing x (rational).
    fn first_column_reference(s: &Samples, p: GridPoint, q: GridPoint, j: i64) -> i64 {
        let (p, q) = if p.y <= q.y { (p, q) } else { (q, p) };
        // crossing x = (p.x·dy·H + (yn - p.y·H)·dx) / (dy·H)
        let dy = (q.y - p.y) as i128;
        let h = s.height as i128;
        let cn =
            p.x as i128 * dy * h + (s.y_num(j) as i128 - p.y as i128 * h) * (q.x - p.x) as i128;
        let cd = dy * h;
        (-2 * s.width - 2..3 * s.width + 2)
            .find(|&i| s.x_num(i) as i128 * cd >= cn * s.width as i128)
            .unwrap()
    }

    #[test]
    fn column_filter_agrees_with_reference_on_lattice_aligned_and_random_edges() {
        let s = Samples::new(16, 12);
        let fb = Fallbacks::default();
        let mut seed = 12345u64;
        let mut rnd = |m: i64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % (2 * m as u64 + 1)) as i64 - m
        };
        for k in 0..20000 {
            // Half the edges have endpoints on sample columns and rows (exact ties).
            let (p, q) = if k % 2 == 0 {
                let pick = |r: i64| ((2 * r + 1 - 16) << 22) / 16;
                (
                    gp(pick(rnd(8) + 8) as i32, rnd(1 << 22) as i32, 0),
                    gp(pick(rnd(8) + 8) as i32, rnd(1 << 22) as i32, 0),
                )
            } else {
                (
                    gp(rnd(1 << 23) as i32, rnd(1 << 23) as i32, 0),
                    gp(rnd(1 << 23) as i32, rnd(1 << 23) as i32, 0),
                )
            };
            if p.y == q.y {
                continue;
            }
            let (lo, hi) = (p.y.min(q.y) as i64, p.y.max(q.y) as i64);
            for j in 0..12 {
                let yn = s.y_num(j);
                // lo <= y_j < hi  <=>  lo·H <= yn < hi·H
                if lo * 12 <= yn && yn < hi * 12 {
                    assert_eq!(
                        s.first_column_at_or_right(p, q, j, &fb),
                        first_column_reference(&s, p, q, j),
                        "edge {p:?} {q:?} row {j}"
                    );
                }
            }
        }
        assert!(
            fb.column.get() > 0,
            "aligned edges should exercise the exact path"
        );
    }

    #[test]
    fn depth_filter_bound_holds_and_exact_compare_is_antisymmetric() {
        let s = Samples::new(64, 48);
        let mut seed = 99u64;
        let mut rnd = |m: i64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) % (2 * m as u64 + 1)) as i64 - m
        };
        let m = 1i64 << 23;
        for _ in 0..2000 {
            let pts: Vec<GridPoint> = (0..6)
                .map(|_| gp(rnd(m) as i32, rnd(m) as i32, rnd(m) as i32))
                .collect();
            let (Some(p), Some(q)) = (
                Plane::through(pts[0], pts[1], pts[2]),
                Plane::through(pts[3], pts[4], pts[5]),
            ) else {
                continue;
            };
            let dp = DepthPlane::new(&p, &s);
            for (i, j) in [(0, 0), (63, 47), (17, 30)] {
                let exact = depth_ndc(&p, &s, i, j) * Z_SCALE;
                assert!((dp.at(i, j) - exact).abs() <= dp.err, "bound violated");
                let a = compare_depth_exact(&p, &q, &s, i, j);
                let b = compare_depth_exact(&q, &p, &s, i, j);
                assert_eq!(a, b.reverse());
                assert_eq!(
                    compare_depth_exact(&p, &p, &s, i, j),
                    std::cmp::Ordering::Equal
                );
            }
        }
    }

    #[test]
    fn plane_depth_at_corners_is_the_corner_depth() {
        let s = Samples::new(4, 4);
        // A triangle whose corners are sample points of pixels (0,0), (3,0), (0,3).
        let c = |i: i64, j: i64, z: i32| gp((s.x_num(i) / 4) as i32, (s.y_num(j) / 4) as i32, z);
        let p = Plane::through(c(0, 0, 100), c(3, 0, -5000), c(0, 3, 777)).unwrap();
        assert!((depth_ndc(&p, &s, 0, 0) * Z_SCALE - 100.0).abs() < 1e-6);
        assert!((depth_ndc(&p, &s, 3, 0) * Z_SCALE + 5000.0).abs() < 1e-6);
        assert!((depth_ndc(&p, &s, 0, 3) * Z_SCALE - 777.0).abs() < 1e-6);
    }
}
