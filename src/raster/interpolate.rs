//! Perspective-correct interpolation (seed 002).
//!
//! Invariant: every attribute interpolated across a face (colour, normal, texture coordinate) is
//! an affine function of the *3D point* on the face, never of the screen position. Screen-space
//! barycentric weights are not affine in 3D under perspective; [`perspective_correct`] turns them
//! into 3D weights with the corners' view depths (the seed's `Z = 1 / Σ αᵢ/Zᵢ`,
//! `C = Z · Σ αᵢ Cᵢ/Zᵢ`). The renderer gets the same 3D weights directly, by intersecting the
//! pixel-centre ray with the face's support plane ([`FaceHit`]); the tests check the two agree.

use glam::{DVec2, DVec3};

/// Area of a screen triangle, as the seed computes it: `|x0(y1-y2) + x1(y2-y0) + x2(y0-y1)| / 2`.
pub fn triangle_area(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1])).abs() / 2.0
}

/// Screen-space barycentric weights (α, β, γ) of `p` in triangle `abc`: each corner's weight is
/// the area of the triangle `p` makes with the other two corners over the whole area (seed 002,
/// unsigned areas, so `p` must lie inside).
pub fn screen_weights(p: [f64; 2], a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> [f64; 3] {
    let area = triangle_area(a, b, c);
    [
        triangle_area(p, b, c) / area,
        triangle_area(a, p, c) / area,
        triangle_area(a, b, p) / area,
    ]
}

/// The view depth at the point with screen weights `w`, corners at view depths `z` (positive
/// distances along the view axis): `Z = 1 / Σ wᵢ/zᵢ` (1/z is affine on the screen, z is not).
pub fn perspective_depth(w: [f64; 3], z: [f64; 3]) -> f64 {
    1.0 / (w[0] / z[0] + w[1] / z[1] + w[2] / z[2])
}

/// Screen weights turned into 3D (perspective-correct) weights: `Z · wᵢ/zᵢ`. They sum to 1.
pub fn perspective_weights(w: [f64; 3], z: [f64; 3]) -> [f64; 3] {
    let depth = perspective_depth(w, z);
    [0, 1, 2].map(|k| depth * w[k] / z[k])
}

/// The seed's corrected attribute: `C = Z · Σ wᵢ Cᵢ/zᵢ`.
pub fn perspective_correct<const N: usize>(
    w: [f64; 3],
    z: [f64; 3],
    values: [[f64; N]; 3],
) -> [f64; N] {
    blend(perspective_weights(w, z), values)
}

/// Σ wᵢ vᵢ.
pub fn blend<const N: usize>(w: [f64; 3], v: [[f64; N]; 3]) -> [f64; N] {
    std::array::from_fn(|k| w[0] * v[0][k] + w[1] * v[1][k] + w[2] * v[2][k])
}

/// Where a ray meets a planar face: the 3D point, the fan triangle `(0, k, k+1)` of the face's
/// corners it falls in, and its barycentric weights in that triangle (3D, so perspective-correct).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceHit {
    /// The point hit (world space).
    pub point: DVec3,
    /// Positions within the face's corner list of the triangle's corners.
    pub corners: [usize; 3],
    /// Barycentric weights of those corners at the point, summing to 1.
    pub weights: [f64; 3],
}

/// Intersects the ray `origin + t·dir` with the planar polygon `pts` (normal `n`, any length)
/// and locates the point in the polygon's fan triangulation. A polygon is interpolated
/// piecewise-linearly over its fan from corner 0 (exactly linear for triangles, and for
/// quadrilaterals whose attributes are affine). When the point lies outside every fan triangle
/// (the pixel centre is on the face by the exact coverage test but rounding puts it a hair
/// outside, or the polygon is not convex), the triangle it is least outside of is used, with
/// weights extrapolated. `None` when the ray is parallel to the plane.
pub fn hit_face(pts: &[DVec3], n: DVec3, origin: DVec3, dir: DVec3) -> Option<FaceHit> {
    let denom = n.dot(dir);
    if denom == 0.0 || !denom.is_finite() {
        return None;
    }
    let t = n.dot(pts[0] - origin) / denom;
    let point = origin + dir * t;
    let mut best: Option<FaceHit> = None;
    let mut best_min = f64::NEG_INFINITY;
    for k in 1..pts.len() - 1 {
        let corners = [0, k, k + 1];
        let weights = weights_in(point, [pts[0], pts[k], pts[k + 1]], n);
        let m = weights[0].min(weights[1]).min(weights[2]);
        if m > best_min {
            best_min = m;
            best = Some(FaceHit {
                point,
                corners,
                weights,
            });
        }
        if m >= 0.0 {
            break;
        }
    }
    best
}

/// Barycentric weights of `p` (on the plane) in the 3D triangle `t`, plane normal `n`: signed
/// areas in the coordinate plane where the triangle's projection is largest.
pub fn weights_in(p: DVec3, t: [DVec3; 3], n: DVec3) -> [f64; 3] {
    let a = n.abs();
    let drop = |v: DVec3| {
        if a.x >= a.y && a.x >= a.z {
            DVec2::new(v.y, v.z)
        } else if a.y >= a.z {
            DVec2::new(v.z, v.x)
        } else {
            DVec2::new(v.x, v.y)
        }
    };
    let (p, a, b, c) = (drop(p), drop(t[0]), drop(t[1]), drop(t[2]));
    let area = (b - a).perp_dot(c - a);
    if area == 0.0 {
        return [1.0, 0.0, 0.0];
    }
    let wa = (b - p).perp_dot(c - p) / area;
    let wb = (c - p).perp_dot(a - p) / area;
    [wa, wb, 1.0 - wa - wb]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fan_hit_recovers_the_point() {
        let pts = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 2.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ];
        let h = hit_face(&pts, DVec3::Z, DVec3::new(0.5, 1.5, 5.0), -DVec3::Z).unwrap();
        assert_eq!(h.corners, [0, 2, 3]);
        let back = h.weights[0] * pts[0] + h.weights[1] * pts[2] + h.weights[2] * pts[3];
        assert!((back - DVec3::new(0.5, 1.5, 0.0)).length() < 1e-12);
        assert!(hit_face(&pts, DVec3::Z, DVec3::ZERO, DVec3::X).is_none());
    }
}
