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
    /// integers in f64): the plane's largest value over the rectangle shared by `rect` and the
    /// piece's bounds (a linear function: at a corner, exact there), never beyond the polygon's
    /// farthest corner.
    pub fn within(&self, rect: [f64; 4]) -> f64 {
        let b = self.bounds;
        let (x0, y0, x1, y1) = (
            rect[0].max(b[0]),
            rect[1].max(b[1]),
            rect[2].min(b[2]),
            rect[3].min(b[3]),
        );
        let far = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
            .into_iter()
            .map(|(x, y)| {
                let (z, err) = self.plane.depth([x, y, 0.0]);
                z + err
            })
            .fold(f64::MIN, f64::max);
        far.min(self.hi)
    }
}
