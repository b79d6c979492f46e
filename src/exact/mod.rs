//! The exact screen representation and the predicates the renderers need.
//!
//! # Representation
//!
//! After clipping (in f64 homogeneous coordinates) every polygon is projected to NDC and its
//! corners are rounded once onto a signed integer grid:
//!
//! - `x`, `y`: `round(ndc · 2^52)`. Polygons are clipped to a guard band `|x|, |y| <= 2·w`, so
//!   `|x|, |y| <= 2^53`; the visible view `[-1, 1]` is 2^53 units across. `y` grows upward here,
//!   as in NDC; outputs flip it.
//! - `z`: `round(ndc_z · 2^53)`, `|z| <= 2^53`, smaller is nearer.
//!
//! **Why this grid.** Every grid coordinate is an integer of at most 54 bits, so it is exactly
//! an f64, and f64 filters read the input without rounding it again. The rounding onto the grid
//! is at most 2^-53 NDC in x and y and 2^-54 in z: the size of the projection's own f64
//! rounding (the divide by w rounds to half an ulp of the NDC value, 2^-53 for values in
//! [1, 2) and 2^-54 in [0.5, 1), where perspective depths lie; the matrix product before it
//! rounds by a few ulps of its terms). Every NDC z in [0.5, 1] and every NDC x, y in [1, 2] is
//! on the grid exactly. Surfaces closer in depth than the projection can tell apart are the
//! camera's f64 limit, not the kernel's; everything after this one rounding is exact.
//!
//! A face is its snapped 2D polygon plus one support plane through three of its snapped corners
//! ([`Plane`]): the depth of the face at any (x, y) is the plane's, so a face is exactly planar
//! after snapping even when its corners' snapped z are not coplanar (a quad whose four rounded
//! corners are not coplanar). For triangles the plane passes through all three corners.
//!
//! # Bit budget
//!
//! Coordinates are below 2^53 and their differences below 2^54, so:
//! - a plane normal component is below 2·2^54·2^54 = 2^109 (i128) and its offset below
//!   3·2^109·2^53 < 2^165 (`I256`); an edge line (a vertical plane) has `a`, `b` below 2^54 and
//!   `d` below 2^108;
//! - the predicates on lines and implicit points ([`predicates`]) take determinants of degree up
//!   to 13 in the coordinates, below 2^716: their exact path computes in 768-bit integers;
//! - a pixel-sample coordinate, scaled to an integer by the image side (at most 2^14), is below
//!   2^67 (i128); edge-versus-sample tests are below 2^123 before the last scaling and are done
//!   in `I256`; the depth of a plane at a sample (numerator) is below 2^193 and comparing two
//!   such depths cross-multiplies by the other plane's z-normal: below 2^303, in `I512`.
//!
//! # Filters
//!
//! Hot predicates are evaluated in f64 with an error bound proven in their docs; only when the
//! bound cannot decide do they fall back to the integer computation. Every fallback is counted
//! in [`Fallbacks`] or [`predicates::fallback_count`]. The bounds are relative to the magnitudes
//! of the terms, so they do not depend on the scale of the integers.

pub mod big;
pub mod polygon;
pub mod predicates;

use bnum::cast::As;
pub use bnum::types::I256;
use bnum::types::I512;
use std::cell::Cell;

/// log2 of [`XY_SCALE`].
pub const XY_BITS: u32 = 52;
/// Grid units per NDC unit in x and y.
pub const XY_SCALE: f64 = (1u64 << XY_BITS) as f64;
/// Grid units per NDC unit in z.
pub const Z_SCALE: f64 = (1u64 << 53) as f64;
/// Polygons are clipped to |x|, |y| <= GUARD · w in clip space.
pub const GUARD: f64 = 2.0;
/// Largest |coordinate| on the grid.
pub const GRID_MAX: i64 = 1 << 53;

/// f64 unit roundoff.
pub const U: f64 = f64::EPSILON / 2.0;

/// A snapped corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct GridPoint {
    /// `round(ndc_x · 2^52)`.
    pub x: i64,
    /// `round(ndc_y · 2^52)`, growing upward.
    pub y: i64,
    /// `round(ndc_z · 2^53)`, smaller is nearer.
    pub z: i64,
}

impl GridPoint {
    /// The grid point with these coordinates.
    pub const fn new(x: i64, y: i64, z: i64) -> GridPoint {
        GridPoint { x, y, z }
    }

    /// Snaps an NDC point (already inside the guard band and depth range).
    #[inline]
    pub fn snap(ndc_x: f64, ndc_y: f64, ndc_z: f64) -> GridPoint {
        let c = |v: f64, s: f64| {
            let g = (v * s).round();
            g.clamp(-(GRID_MAX as f64), GRID_MAX as f64) as i64
        };
        GridPoint {
            x: c(ndc_x, XY_SCALE),
            y: c(ndc_y, XY_SCALE),
            z: c(ndc_z, Z_SCALE),
        }
    }
}

/// The sign of the signed area of a grid polygon's (x, y) projection, exactly. `Greater` when the
/// polygon runs counter-clockwise with y up: for a front face (OpenGL's GL_CCW).
///
/// Each term is a cross product of differences from the first corner (below 2^109); the sum
/// is kept in i128 while it fits and finished in 256 bits otherwise. Only its sign is returned:
/// `Greater` for counter-clockwise, `Equal` for no area.
pub fn twice_signed_area(points: &[GridPoint]) -> std::cmp::Ordering {
    let Some(&o) = points.first() else {
        return std::cmp::Ordering::Equal;
    };
    let term = |a: GridPoint, b: GridPoint| {
        let (ax, ay) = ((a.x - o.x) as i128, (a.y - o.y) as i128);
        let (bx, by) = ((b.x - o.x) as i128, (b.y - o.y) as i128);
        ax * by - bx * ay
    };
    let mut s: i128 = 0;
    for (k, w) in points.windows(2).enumerate().skip(1) {
        match s.checked_add(term(w[0], w[1])) {
            Some(v) => s = v,
            None => {
                let mut wide: I256 = s.as_();
                for w in points[k..].windows(2) {
                    wide += term(w[0], w[1]).as_::<I256>();
                }
                return wide.cmp(&w256(0));
            }
        }
    }
    s.cmp(&0)
}

/// A plane `a·x + b·y + c·z + d = 0` of the grid, built from grid points only: a support plane
/// (`c > 0`, through three snapped corners) or an edge plane (`c == 0`, vertical, through two).
/// Normal components are below 2^109 and the offset below 2^165 (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Plane {
    /// Coefficient of x.
    pub a: i128,
    /// Coefficient of y.
    pub b: i128,
    /// Coefficient of z: positive for a support plane, 0 for an edge plane.
    pub c: i128,
    /// The constant term.
    pub d: I256,
}

/// A plane's coefficients, each rounded to the nearest f64 once: for many sign tests against
/// one plane (the conversions from 128 and 256 bits cost more than the test).
#[derive(Clone, Copy, Debug)]
pub struct PlaneApprox([f64; 4]);

impl PlaneApprox {
    /// The rounded coefficients of `plane`.
    #[inline]
    pub fn of(plane: &Plane) -> PlaneApprox {
        PlaneApprox([
            i128_to_f64(plane.a),
            i128_to_f64(plane.b),
            i128_to_f64(plane.c),
            i256_to_f64(plane.d),
        ])
    }

    /// The sign of `plane`'s equation at a grid point, exactly, where `self` is
    /// `PlaneApprox::of(plane)`: in f64 when its error bound decides (each coefficient rounded
    /// once, each product and sum once more: below `6·U` times the sum of the terms'
    /// magnitudes), otherwise in 256-bit integers.
    #[inline]
    pub fn sign_at(&self, plane: &Plane, p: GridPoint) -> std::cmp::Ordering {
        let [a, b, c, d] = self.0;
        let terms = [a * p.x as f64, b * p.y as f64, c * p.z as f64, d];
        let v = terms[0] + terms[1] + terms[2] + terms[3];
        let bound = 6.0 * U * terms.iter().map(|t| t.abs()).sum::<f64>() * 1.01;
        if v > bound {
            std::cmp::Ordering::Greater
        } else if v < -bound {
            std::cmp::Ordering::Less
        } else {
            plane.value_at(p).cmp(&w256(0))
        }
    }
}

/// A two's-complement integer of `N` little-endian bytes (16 to 128, a multiple of 8) rounded to
/// the nearest f64, ties to even: the same value as bnum's `as_::<f64>()`, which the f64 filters
/// rely on (each entry within half an ulp), at a fraction of its cost. The top 128 bits of the
/// magnitude are converted with the rest folded into their lowest bit as a sticky bit; a
/// 128-bit integer has 75 bits below an f64's 53, so the sticky bit decides ties and nothing
/// else, and the result is correctly rounded.
pub fn int_to_f64<const N: usize>(le: [u8; N]) -> f64 {
    const { assert!(N.is_multiple_of(8) && N >= 16 && N <= 128) };
    let limbs = N / 8;
    let mut m = [0u64; 16];
    for (k, limb) in m[..limbs].iter_mut().enumerate() {
        *limb = u64::from_le_bytes(le[8 * k..8 * k + 8].try_into().expect("8 bytes"));
    }
    let negative = le[N - 1] & 0x80 != 0;
    if negative {
        // The magnitude, as an unsigned integer (the most negative value included).
        let mut carry = true;
        for limb in m[..limbs].iter_mut() {
            let (v, c) = (!*limb).overflowing_add(carry as u64);
            *limb = v;
            carry = c;
        }
    }
    let magnitude = match (0..limbs).rev().find(|&k| m[k] != 0) {
        None => 0.0,
        Some(top) if top < 2 => ((m[1] as u128) << 64 | m[0] as u128) as f64,
        Some(top) => {
            let lz = m[top].leading_zeros();
            let high = (m[top] as u128) << 64 | m[top - 1] as u128;
            let next = m[top - 2];
            let mut bits = if lz == 0 {
                high
            } else {
                high << lz | (next >> (64 - lz)) as u128
            };
            let sticky = (next << lz) != 0 || m[..top - 2].iter().any(|&l| l != 0);
            bits |= sticky as u128;
            // bits · 2^(64·(top − 1) − lz), the scale an exact power of two.
            let exponent = 64 * (top as i32 - 1) - lz as i32;
            (bits as f64) * f64::from_bits(((exponent + 1023) as u64) << 52)
        }
    };
    if negative { -magnitude } else { magnitude }
}

/// An i128 rounded to the nearest f64 (ties to even), exactly as `as f64` does, without the
/// generic library routine: the top 64 bits of the magnitude with the rest folded into a
/// sticky bit (11 bits below an f64's last), then one hardware conversion and an exact scale.
#[inline]
pub fn i128_to_f64(v: i128) -> f64 {
    if let Ok(small) = i64::try_from(v) {
        return small as f64;
    }
    let m = v.unsigned_abs();
    let lz = m.leading_zeros(); // below 65: |v| >= 2^63
    let shifted = m << lz;
    let top = (shifted >> 64) as u64 | ((shifted as u64 != 0) as u64);
    let magnitude = (top as f64) * f64::from_bits((64 - lz as u64 + 1023) << 52);
    if v < 0 { -magnitude } else { magnitude }
}

/// [`int_to_f64`] of a 256-bit integer, in two 128-bit halves (the filters convert plane
/// offsets often: this is their hot path).
#[inline]
pub fn i256_to_f64(v: I256) -> f64 {
    let bytes = v.to_le_bytes();
    let lo = u128::from_le_bytes(bytes[..16].try_into().expect("16 bytes"));
    let hi = i128::from_le_bytes(bytes[16..].try_into().expect("16 bytes"));
    if hi == (lo as i128) >> 127 {
        return i128_to_f64(lo as i128);
    }
    let negative = hi < 0;
    let (mhi, mlo) = if negative {
        let mlo = (!lo).wrapping_add(1);
        ((!hi as u128).wrapping_add((mlo == 0) as u128), mlo)
    } else {
        (hi as u128, lo)
    };
    let magnitude = if mhi == 0 {
        mlo as f64
    } else {
        let lz = mhi.leading_zeros();
        let bits = if lz == 0 {
            mhi
        } else {
            mhi << lz | mlo >> (128 - lz)
        };
        // The sticky bit, as in `int_to_f64`; the scale 2^(128 - lz) is exact.
        let bits = bits | ((mlo << lz) != 0) as u128;
        (bits as f64) * f64::from_bits(((128 - lz as u64) + 1023) << 52)
    };
    if negative { -magnitude } else { magnitude }
}

/// An i128 widened to 256 bits.
#[inline]
pub fn w256(v: i128) -> I256 {
    v.as_()
}

impl Plane {
    /// The plane through three points, or `None` when their (x, y) projections are collinear
    /// (the plane would be parallel to the view direction).
    pub fn through(p: GridPoint, q: GridPoint, r: GridPoint) -> Option<Plane> {
        let (ux, uy, uz) = (
            (q.x - p.x) as i128,
            (q.y - p.y) as i128,
            (q.z - p.z) as i128,
        );
        let (vx, vy, vz) = (
            (r.x - p.x) as i128,
            (r.y - p.y) as i128,
            (r.z - p.z) as i128,
        );
        let mut a = uy * vz - uz * vy;
        let mut b = uz * vx - ux * vz;
        let mut c = ux * vy - uy * vx;
        if c == 0 {
            return None;
        }
        if c < 0 {
            (a, b, c) = (-a, -b, -c);
        }
        let d = -(w256(a) * w256(p.x as i128)
            + w256(b) * w256(p.y as i128)
            + w256(c) * w256(p.z as i128));
        Some(Plane { a, b, c, d })
    }

    /// The vertical plane through the (x, y) of `p` and `q`, positive on the left of `p → q`
    /// (inside a counter-clockwise polygon, y up): its value at r is `orient2d(p, q, r)`.
    /// `None` when `p` and `q` have the same (x, y).
    pub fn edge(p: GridPoint, q: GridPoint) -> Option<Plane> {
        // The edge line's coefficients, computed in one place.
        predicates::Line::edge(p, q)?.vertical_plane()
    }

    /// The plane's equation at a grid point, exactly.
    #[inline]
    pub fn value_at(&self, p: GridPoint) -> I256 {
        w256(self.a) * w256(p.x as i128)
            + w256(self.b) * w256(p.y as i128)
            + w256(self.c) * w256(p.z as i128)
            + self.d
    }

    /// The sign of the plane's equation at a grid point, exactly (see [`PlaneApprox::sign_at`]).
    #[inline]
    pub fn sign_at(&self, p: GridPoint) -> std::cmp::Ordering {
        PlaneApprox::of(self).sign_at(self, p)
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
        // Squares of differences below 2^54 stay below 2^109: i128.
        let d2 = |q: &GridPoint| {
            let dx = (q.x - p.x) as i128;
            let dy = (q.y - p.y) as i128;
            dx * dx + dy * dy
        };
        let q = *points.iter().max_by_key(|q| d2(q))?;
        let cross = |r: &GridPoint| {
            ((q.x - p.x) as i128 * (r.y - p.y) as i128 - (q.y - p.y) as i128 * (r.x - p.x) as i128)
                .abs()
        };
        let r = *points.iter().max_by_key(|r| cross(r))?;
        Plane::through(p, q, r)
    }
}

/// The pixel-sample lattice of a `width x height` image on the grid. Sample (i, j) is the centre
/// of pixel column i, row j (row 0 at the top), at grid
/// `x = (2i + 1 - W)·2^52 / W`, `y = (H - 2j - 1)·2^52 / H`.
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

    /// Numerator of sample column i's x (denominator W): below 2^67 for columns within a few
    /// image widths of the view.
    #[inline]
    pub fn x_num(&self, i: i64) -> i128 {
        ((2 * i + 1 - self.width) as i128) << XY_BITS
    }

    /// Numerator of sample row j's y (denominator H).
    #[inline]
    pub fn y_num(&self, j: i64) -> i128 {
        ((self.height - 2 * j - 1) as i128) << XY_BITS
    }

    /// Sample column i as the exact line `W·x - x_num = 0` (for [`predicates::line_side`]).
    pub fn column_line(&self, i: i64) -> predicates::Line {
        predicates::Line::vertical(&Plane {
            a: self.width as i128,
            b: 0,
            c: 0,
            d: w256(-self.x_num(i)),
        })
    }

    /// Sample row j as the exact line `H·y - y_num = 0`.
    pub fn row_line(&self, j: i64) -> predicates::Line {
        predicates::Line::vertical(&Plane {
            a: 0,
            b: self.height as i128,
            c: 0,
            d: w256(-self.y_num(j)),
        })
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
    /// Filter: the crossing's column coordinate is computed in f64 from integer inputs (each
    /// exact or rounded once) with at most 10 roundings on quantities bounded by 2^56 grid
    /// units, so its error is below 10 · U · 2^56 grid units, or 10 · U · 2^56 · W / 2^53 =
    /// 80 · U · W < 1e-10 columns for W <= 2^14. When the crossing is farther than 1e-9 from a
    /// sample column the rounded-up column is right; otherwise the exact computation decides.
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
        let (w, h) = (w256(self.width as i128), w256(self.height as i128));
        let dy = w256((q.y - p.y) as i128);
        let dx = w256((q.x - p.x) as i128);
        let (px, py) = (w256(p.x as i128), w256(p.y as i128));
        // Crossing x = p.x + (ys - p.y)·dx/dy with ys = y_num/H. Scaled by W/2^52 it is N / D
        // (|N| < 2^138, D < 2^121):
        let n = (px * dy * h + (w256(self.y_num(j)) - py * h) * dx) * w;
        let d = (dy * h) << XY_BITS;
        // Sample i is at or right of the crossing iff (2i + 1 - W)·D >= N.
        let t = div_ceil(n, d);
        div_ceil(t + w - w256(1), w256(2)).as_::<i64>()
    }
}

fn div_ceil(n: I256, d: I256) -> I256 {
    debug_assert!(d > w256(0));
    let q = n.div_euclid(d);
    if n.rem_euclid(d) == w256(0) {
        q
    } else {
        q + w256(1)
    }
}

/// Depth of a plane across the sample lattice in f64, with its certified error bound.
///
/// `z(i, j) = zi·i + zj·j + z0` (grid units). Each coefficient comes from the plane's integers
/// (each rounded once to f64) through at most 8 more roundings, each relative to the magnitude
/// of the terms it combines; the evaluation adds 4 more. The terms of `z0` are bounded by
/// `|zi|·W/2 + |zj|·H/2 + 2^53` (the plane passes through a corner with |x|, |y|, |z| <=
/// 2^53), so `|z_f64 - z| <= 14·U·(|zi|·W + |zj|·H + |z0| + 2^54)`; `err` takes 20·U for
/// margin.
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
            i128_to_f64(plane.a),
            i128_to_f64(plane.b),
            i128_to_f64(plane.c),
            i256_to_f64(plane.d),
        );
        // z = -(a·x + b·y + d)/c with x = (2i + 1 - W)·2^52/W, y = (H - 2j - 1)·2^52/H.
        let zi = -a * (2.0 * XY_SCALE) / (w * c);
        let zj = b * (2.0 * XY_SCALE) / (h * c);
        let z0 = -(a * ((1.0 - w) * XY_SCALE / w) + b * ((h - 1.0) * XY_SCALE / h) + d) / c;
        let mag = zi.abs() * w + zj.abs() * h + z0.abs() + 2.0 * GRID_MAX as f64;
        let err = 20.0 * U * mag;
        DepthPlane { zi, zj, z0, err }
    }

    /// The depth at sample (i, j), within `err` of the exact one.
    #[inline]
    pub fn at(&self, i: i64, j: i64) -> f64 {
        self.zi * i as f64 + self.zj * j as f64 + self.z0
    }
}

/// Numerator of a plane's depth at sample (i, j): `z = -N/(c·W·H)` with
/// `N = a·xn·H + b·yn·W + d·W·H` (xn, yn the sample numerators), below 2^193.
fn depth_numerator(pl: &Plane, s: &Samples, i: i64, j: i64) -> I256 {
    let (w, h) = (w256(s.width as i128), w256(s.height as i128));
    w256(pl.a) * w256(s.x_num(i)) * h + w256(pl.b) * w256(s.y_num(j)) * w + pl.d * w * h
}

/// Exact comparison of two planes' depths at sample (i, j): `Less` when `p` is nearer.
pub fn compare_depth_exact(
    p: &Plane,
    q: &Plane,
    s: &Samples,
    i: i64,
    j: i64,
) -> std::cmp::Ordering {
    // z_p < z_q  <=>  -N_p/c_p < -N_q/c_q  <=>  N_q·c_p < N_p·c_q   (c > 0)
    let wide = |v: I256| -> I512 { v.as_() };
    let lhs = wide(depth_numerator(q, s, i, j)) * wide(w256(p.c));
    let rhs = wide(depth_numerator(p, s, i, j)) * wide(w256(q.c));
    lhs.cmp(&rhs)
}

/// Exact depth of a plane at sample (i, j), as NDC z in f64 (rounded, for output only).
pub fn depth_ndc(p: &Plane, s: &Samples, i: i64, j: i64) -> f64 {
    let n = int_to_f64(depth_numerator(p, s, i, j).to_le_bytes());
    let den = i128_to_f64(p.c) * s.width as f64 * s.height as f64;
    -(n / den) / Z_SCALE
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

    /// The fast conversion rounds exactly as bnum does (correctly, ties to even), on values
    /// built to hit every case: ties with and without a sticky bit far below, carries into the
    /// next power of two, each limb count, both signs, the extremes.
    #[test]
    fn int_to_f64_rounds_every_width_exactly_as_bnum() {
        use bnum::types::I512;
        let mut rng = crate::stress::rng::Rng::of(&[0x9e37_79b9_7f4a_7c15]);
        let mut next = move || rng.next_u64();
        let mut values: Vec<I512> = vec![
            I512::MAX,
            I512::MIN,
            w256(0).as_(),
            w256(1).as_(),
            w256(i128::MAX).as_(),
            w256(i128::MIN).as_(),
        ];
        for shift in 0..500u32 {
            let one: I512 = w256(1).as_();
            let p = one << shift;
            // Exactly halfway between two f64s (53 bits then a 1), with and without a
            // sticky bit at the very bottom, and the values around them.
            let tie = p.wrapping_mul(w256((1i128 << 53) + 1).as_::<I512>());
            for v in [p, p - one, p + one, tie, tie + one, tie - one] {
                values.push(v);
                values.push(-v);
            }
        }
        for _ in 0..20_000 {
            let bits = (next() % 511) as u32;
            let mut v: I512 = w256(0).as_();
            for _ in 0..8 {
                v = (v << 64u32) | w256(next() as i128).as_::<I512>();
            }
            values.push(v >> (511 - bits));
        }
        for v in values {
            let want: f64 = v.as_();
            assert_eq!(int_to_f64(v.to_le_bytes()).to_bits(), want.to_bits(), "{v}");
            let narrow: I256 = v.as_();
            if narrow.as_::<I512>() == v {
                assert_eq!(i256_to_f64(narrow).to_bits(), want.to_bits(), "{v}");
            }
            let narrowest: i128 = v.as_();
            if narrowest.as_::<I512>() == v {
                assert_eq!(i128_to_f64(narrowest).to_bits(), want.to_bits(), "{v}");
            }
        }
    }

    /// Slow reference: smallest i whose sample x (rational) is >= the crossing x (rational).
    fn first_column_reference(s: &Samples, p: GridPoint, q: GridPoint, j: i64) -> i64 {
        let (p, q) = if p.y <= q.y { (p, q) } else { (q, p) };
        // crossing x = (p.x·dy·H + (yn - p.y·H)·dx) / (dy·H)
        let big = |v: i128| w256(v);
        let dy = big((q.y - p.y) as i128);
        let h = big(s.height as i128);
        let cn = big(p.x as i128) * dy * h
            + (big(s.y_num(j)) - big(p.y as i128) * h) * big((q.x - p.x) as i128);
        let cd = dy * h;
        (-2 * s.width - 2..3 * s.width + 2)
            .find(|&i| big(s.x_num(i)) * cd >= cn * big(s.width as i128))
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
        let m = GRID_MAX;
        for k in 0..20000 {
            // Half the edges have endpoints on sample columns and rows (exact ties).
            let (p, q) = if k % 2 == 0 {
                let pick = |r: i64| ((((2 * r + 1 - 16) as i128) << XY_BITS) / 16) as i64;
                (
                    GridPoint::new(pick(rnd(8) + 8), rnd(m / 2), 0),
                    GridPoint::new(pick(rnd(8) + 8), rnd(m / 2), 0),
                )
            } else {
                (
                    GridPoint::new(rnd(m), rnd(m), 0),
                    GridPoint::new(rnd(m), rnd(m), 0),
                )
            };
            if p.y == q.y {
                continue;
            }
            let (lo, hi) = (p.y.min(q.y) as i128, p.y.max(q.y) as i128);
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
            (seed % (2 * m as u64 + 1)) as i64 - m
        };
        let m = GRID_MAX;
        for _ in 0..2000 {
            let pts: Vec<GridPoint> = (0..6)
                .map(|_| GridPoint::new(rnd(m), rnd(m), rnd(m)))
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
        let c = |i: i64, j: i64, z: i64| {
            GridPoint::new((s.x_num(i) / 4) as i64, (s.y_num(j) / 4) as i64, z)
        };
        let p = Plane::through(c(0, 0, 100), c(3, 0, -5000), c(0, 3, 777)).unwrap();
        assert!((depth_ndc(&p, &s, 0, 0) * Z_SCALE - 100.0).abs() < 1e-6);
        assert!((depth_ndc(&p, &s, 3, 0) * Z_SCALE + 5000.0).abs() < 1e-6);
        assert!((depth_ndc(&p, &s, 0, 3) * Z_SCALE - 777.0).abs() < 1e-6);
    }
}
