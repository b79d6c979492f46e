//! Proven depth bounds of pieces in f64: the cheap tests of Newell's sort and the occlusion
//! cells compare depths through them, never through an unbounded f64 value.
//!
//! Invariant: every bound returned contains the exact depth (grid z, larger is farther) of every
//! point it speaks for. Each is the support plane's depth `z = -(a·x + b·y + d) / c` at a few
//! points in f64, widened by its error bound ([`plane_depth`]), and clamped to the polygon's
//! exact corner range (the piece lies in its polygon).

use crate::exact::polygon::Piece;
use crate::exact::{i128_to_f64, i256_to_f64};
use crate::project::ScreenScene;

/// The support plane's depth at a point known within `e` of (x, y) in each coordinate:
/// (depth, error bound).
///
/// Bound: with the plane's coefficients rounded once each, `|z - ẑ| <= ((|a|+|b|)·e +
/// 4·U·(|a·x| + |b·y| + |d|)) / c + 2·U·|ẑ|` to first order; the code doubles each rounding term
/// and widens by 1 % for the rest.
fn plane_depth(p: &Piece, [x, y, e]: [f64; 3]) -> (f64, f64) {
    const U: f64 = f64::EPSILON / 2.0;
    let s = &p.support;
    let (a, b, c, d) = (
        i128_to_f64(s.a),
        i128_to_f64(s.b),
        i128_to_f64(s.c),
        i256_to_f64(s.d),
    );
    let (ax, by) = (a * x, b * y);
    let z = -(ax + by + d) / c;
    let err = ((a.abs() + b.abs()) * e + 8.0 * U * (ax.abs() + by.abs() + d.abs())) / c
        + 4.0 * U * z.abs();
    (z, err * 1.01)
}

/// The exact range of the piece's polygon's corner depths (grid depths are below 2^54: exact
/// in f64).
fn corner_range(screen: &ScreenScene, p: &Piece) -> [f64; 2] {
    let corners = screen.corners(&screen.polys[p.poly as usize]);
    let lo = corners.iter().map(|c| c.z).min().unwrap_or(0);
    let hi = corners.iter().map(|c| c.z).max().unwrap_or(0);
    [lo as f64, hi as f64]
}

/// The depth range [near, far] that certainly contains the piece: each vertex's depth with its
/// bound (the vertex's own error included), within the polygon's corner range.
pub fn range(screen: &ScreenScene, p: &Piece) -> [f64; 2] {
    let [lo, hi] = corner_range(screen, p);
    let (mut near, mut far) = (f64::MAX, f64::MIN);
    for &point in &p.points {
        if !point[2].is_finite() {
            return [lo, hi];
        }
        let (z, err) = plane_depth(p, point);
        near = near.min(z - err);
        far = far.max(z + err);
    }
    [near.max(lo), far.min(hi)]
}

/// An upper bound of the piece's depth within the rectangle `rect` (x0, y0, x1, y1, exact
/// integers in f64): the plane's largest value over the rectangle shared by `rect` and the
/// piece's bounds `b` widened to integers (a linear function: at a corner, exact there), never
/// beyond the polygon's farthest corner.
pub fn farthest_within(screen: &ScreenScene, p: &Piece, rect: [f64; 4], b: [f64; 4]) -> f64 {
    let (x0, y0, x1, y1) = (
        rect[0].max(b[0].floor()),
        rect[1].max(b[1].floor()),
        rect[2].min(b[2].ceil()),
        rect[3].min(b[3].ceil()),
    );
    let far = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
        .into_iter()
        .map(|(x, y)| {
            let (z, err) = plane_depth(p, [x, y, 0.0]);
            z + err
        })
        .fold(f64::MIN, f64::max);
    far.min(corner_range(screen, p)[1])
}
