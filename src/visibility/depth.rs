//! Proven depth bounds of pieces in f64: the cheap tests of Newell's sort and the occlusion
//! cells compare depths through them, never through an unbounded f64 value.
//!
//! Invariant: every bound returned contains the exact depth (grid z, larger is farther) of every
//! point it speaks for. Each is the support plane's depth `z = -(a·x + b·y + d) / c` at a few
//! points in f64, widened by its error bound (`PlaneF64::depth`), and clamped to the polygon's
//! exact corner range (the piece lies in its polygon).

use crate::exact::polygon::Piece;
use crate::exact::{i128_to_f64, i256_to_f64};
use crate::project::ScreenScene;

/// A piece's support plane with its coefficients rounded to f64 once each.
#[derive(Clone, Copy)]
struct PlaneF64 {
    a: f64,
    b: f64,
    c: f64,
    d: f64,
}

impl PlaneF64 {
    fn of(p: &Piece) -> PlaneF64 {
        let s = &p.support;
        PlaneF64 {
            a: i128_to_f64(s.a),
            b: i128_to_f64(s.b),
            c: i128_to_f64(s.c),
            d: i256_to_f64(s.d),
        }
    }

    /// The depth at a point known within `e` of (x, y) in each coordinate: (depth, error
    /// bound).
    ///
    /// Bound: with the coefficients rounded once each, `|z - ẑ| <= ((|a|+|b|)·e + 4·U·(|a·x| +
    /// |b·y| + |d|)) / c + 2·U·|ẑ|` to first order; the code doubles each rounding term and
    /// widens by 1 % for the rest.
    fn depth(&self, [x, y, e]: [f64; 3]) -> (f64, f64) {
        const U: f64 = f64::EPSILON / 2.0;
        let PlaneF64 { a, b, c, d } = *self;
        let (ax, by) = (a * x, b * y);
        let z = -(ax + by + d) / c;
        let err = ((a.abs() + b.abs()) * e + 8.0 * U * (ax.abs() + by.abs() + d.abs())) / c
            + 4.0 * U * z.abs();
        (z, err * 1.01)
    }
}

/// The exact range of the piece's polygon's corner depths (grid depths are below 2^54: exact
/// in f64).
fn corner_range(screen: &ScreenScene, p: &Piece) -> [f64; 2] {
    let corners = screen.corners(&screen.polys[p.poly as usize]);
    let lo = corners.iter().map(|c| c.z).min().unwrap_or(0);
    let hi = corners.iter().map(|c| c.z).max().unwrap_or(0);
    [lo as f64, hi as f64]
}

/// Can `p` hide no part of `of`? Proven when `p` is wholly deeper (its proven depth range,
/// [`range`], beyond `of`'s), or wholly in the closed half-space behind `of`'s support plane
/// and not in the plane: along every ray through both, `p`'s point is then at least as deep,
/// and as deep only on a line. Each piece comes with its `range`.
pub(crate) fn cannot_hide(p: (&Piece, [f64; 2]), of: (&Piece, [f64; 2])) -> bool {
    p.1[0] > of.1[1] || p.0.sides_of_plane(&of.0.support) == (false, true)
}

/// The depth range [near, far] that certainly contains the piece: each vertex's depth with its
/// bound (the vertex's own error included), within the polygon's corner range.
pub fn range(screen: &ScreenScene, p: &Piece) -> [f64; 2] {
    let [lo, hi] = corner_range(screen, p);
    let plane = PlaneF64::of(p);
    let (mut near, mut far) = (f64::MAX, f64::MIN);
    for point in p.points() {
        if !point[2].is_finite() {
            return [lo, hi];
        }
        let (z, err) = plane.depth(point);
        near = near.min(z - err);
        far = far.max(z + err);
    }
    [near.max(lo), far.min(hi)]
}

/// What [`Farthest::within`] needs of a piece, read once for the many rectangles it is asked
/// about.
pub struct Farthest {
    plane: PlaneF64,
    /// The polygon's farthest corner.
    hi: f64,
    /// The piece's bounds widened to integers.
    bounds: [f64; 4],
}

impl Farthest {
    /// Of `p`, whose bounds are `b` ([`super::live::bounds`] or any box containing it).
    pub fn of(screen: &ScreenScene, p: &Piece, b: [f64; 4]) -> Farthest {
        Farthest {
            plane: PlaneF64::of(p),
            hi: corner_range(screen, p)[1],
            bounds: [b[0].floor(), b[1].floor(), b[2].ceil(), b[3].ceil()],
        }
    }

    /// An upper bound of the piece's depth within the rectangle `rect` (x0, y0, x1, y1, exact
    /// integers in f64): the plane's value, with its error bound, at the corner of the rectangle
    /// shared by `rect` and the piece's bounds where the plane is deepest, never beyond the
    /// polygon's farthest corner. The depth is linear, `z = -(a·x + b·y + d) / c`: it grows
    /// with x where `a` and `c` have opposite signs, and rounding keeps each coefficient's sign
    /// (and zero), so that corner is found exactly and is the rectangle's deepest point.
    pub fn within(&self, rect: [f64; 4]) -> f64 {
        let b = self.bounds;
        let PlaneF64 { a, b: pb, c, .. } = self.plane;
        let deeper_right = (a < 0.0) == (c > 0.0) && a != 0.0;
        let deeper_down = (pb < 0.0) == (c > 0.0) && pb != 0.0;
        let x = if deeper_right {
            rect[2].min(b[2])
        } else {
            rect[0].max(b[0])
        };
        let y = if deeper_down {
            rect[3].min(b[3])
        } else {
            rect[1].max(b[1])
        };
        let (z, err) = self.plane.depth([x, y, 0.0]);
        (z + err).min(self.hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::{GridPoint, Plane, w256};
    use crate::visibility::{initial_pieces, live::bounds, screen_of_polygons};
    use proptest::prelude::*;

    /// Is the exact depth of `plane` (a support plane: `c > 0`) at (x, y) at most `w`? The
    /// plane's equation grows with z, so it is when the equation at z = w is not negative:
    /// `w = ±m·2^e` multiplied out to integers.
    fn depth_at_most(plane: &Plane, x: i64, y: i64, w: f64) -> bool {
        assert!(plane.c > 0 && w.is_finite());
        let bits = w.to_bits();
        let (exp, frac) = (((bits >> 52) & 0x7ff) as i32, bits & ((1 << 52) - 1));
        let (m, e) = if exp == 0 {
            (frac, -1074)
        } else {
            (frac | 1 << 52, exp - 1075)
        };
        let m = if w < 0.0 { -(m as i128) } else { m as i128 };
        let rest = w256(plane.a) * w256(x as i128) + w256(plane.b) * w256(y as i128) + plane.d;
        let cz = w256(plane.c) * w256(m);
        let value = if e >= 0 {
            rest + (cz << e as u32)
        } else {
            (rest << (-e) as u32) + cz
        };
        value >= w256(0)
    }

    proptest! {
        /// `within` bounds the piece's plane's exact depth at every corner of the rectangle it
        /// is asked about (its part within the piece's bounds) unless it is the polygon's
        /// farthest corner, the deepest corner included: a bound taken at any other corner of
        /// a slanted plane falls short there.
        #[test]
        fn the_farthest_depth_within_a_rectangle_bounds_its_every_corner(
            corners in prop::array::uniform3((-4096i64..4096, -4096i64..4096, 0i64..1 << 30)),
            weights in prop::array::uniform3(1i64..100),
            size in (0i64..64, 0i64..64),
        ) {
            let pts: Vec<GridPoint> =
                corners.iter().map(|&(x, y, z)| GridPoint { x, y, z }).collect();
            prop_assume!(Plane::of_polygon(&pts).is_some());
            let s = screen_of_polygons([pts]);
            let piece = &initial_pieces(&s)[0];
            let b = bounds(piece);
            let far = Farthest::of(&s, piece, b);
            // A small rectangle from a point inside the triangle (mostly within it).
            let total: i64 = weights.iter().sum();
            let at = |f: fn(&(i64, i64, i64)) -> i64| {
                corners.iter().zip(weights).map(|(c, w)| f(c) * w).sum::<i64>() / total
            };
            let (x0, y0) = (at(|c| c.0), at(|c| c.1));
            let (x1, y1) = (x0 + size.0, y0 + size.1);
            let w = far.within([x0 as f64, y0 as f64, x1 as f64, y1 as f64]);
            let [bx0, by0, bx1, by1] = far.bounds.map(|v| v as i64);
            let (cx0, cy0, cx1, cy1) = (x0.max(bx0), y0.max(by0), x1.min(bx1), y1.min(by1));
            prop_assume!(cx0 <= cx1 && cy0 <= cy1);
            // The polygon's farthest corner bounds every point of the piece; below it, the
            // plane itself is bounded over the rectangle.
            let hi = corners.iter().map(|c| c.2).max().unwrap();
            prop_assume!(w < hi as f64);
            for (x, y) in [(cx0, cy0), (cx1, cy0), (cx1, cy1), (cx0, cy1)] {
                prop_assert!(depth_at_most(&piece.support, x, y, w), "({x}, {y}) deeper than {w}");
            }
        }
    }
}
