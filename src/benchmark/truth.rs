//! The per-pixel truth: each pixel's area split among the faces visible in it, and a method's
//! error against it. See the module docs of [`crate::benchmark`] for the error bound.

use crate::project::ScreenScene;
use crate::visibility::{CoverageMap, Strategy};

/// The exact visible set of `screen` (every face opaque) as pixel rings, one per visible piece,
/// each with its input face id: the truth the errors are measured against.
pub fn truth_rings(screen: &ScreenScene) -> Vec<(u32, Vec<[f64; 2]>)> {
    let visible = CoverageMap.visible_set(screen, &|_| false, None);
    visible
        .pixel_rings(screen)
        .into_iter()
        .map(|(poly, ring)| (screen.polys[poly as usize].id, ring))
        .collect()
}

/// Calls `visit(pixel, face, area)` for every pixel (row-major index, row 0 at the top) of a
/// `width x height` image that the convex polygon `ring` (pixel coordinates, y down, either
/// orientation) covers with positive computed area, `area` in pixels (at most about 1). Only the
/// pixels of the ring's bounding box inside the image are visited, in row-major order.
pub fn for_each_pixel_area(
    ring: &[[f64; 2]],
    face: u32,
    width: u32,
    height: u32,
    visit: &mut impl FnMut(usize, u32, f64),
) {
    if ring.len() < 3 || ring.iter().flatten().any(|c| !c.is_finite()) {
        return;
    }
    let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, f64::MIN, f64::MIN);
    for &[x, y] in ring {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let (w, h) = (width as f64, height as f64);
    if x1 <= 0.0 || y1 <= 0.0 || x0 >= w || y0 >= h {
        return;
    }
    // Pixel (i, j) is [i, i+1] x [j, j+1]; the bounds are clamped to the image.
    let (c0, c1) = (x0.max(0.0).floor() as u32, x1.min(w).ceil() as u32);
    let (r0, r1) = (y0.max(0.0).floor() as u32, y1.min(h).ceil() as u32);
    let mut strip = Vec::with_capacity(ring.len() + 2);
    let mut scratch = Vec::with_capacity(ring.len() + 4);
    let mut cell = Vec::with_capacity(ring.len() + 4);
    for j in r0..r1 {
        // The ring cut to the row's strip, then each pixel's square cut from the strip.
        clip(ring, Axis::Y, j as f64, true, &mut scratch);
        clip(&scratch, Axis::Y, (j + 1) as f64, false, &mut strip);
        if strip.len() < 3 {
            continue;
        }
        for i in c0..c1 {
            clip(&strip, Axis::X, i as f64, true, &mut scratch);
            clip(&scratch, Axis::X, (i + 1) as f64, false, &mut cell);
            let a = area_local(&cell, i as f64, j as f64);
            if a > 0.0 {
                visit(j as usize * width as usize + i as usize, face, a);
            }
        }
    }
}

#[derive(Clone, Copy)]
enum Axis {
    X,
    Y,
}

/// Sutherland–Hodgman against one axis-aligned half-plane: `coord >= at` when `keep_above`,
/// else `coord <= at`. A crossing takes `at` exactly on the clipped axis.
fn clip(poly: &[[f64; 2]], axis: Axis, at: f64, keep_above: bool, out: &mut Vec<[f64; 2]>) {
    out.clear();
    let n = poly.len();
    if n == 0 {
        return;
    }
    let (a, b) = match axis {
        Axis::X => (0, 1),
        Axis::Y => (1, 0),
    };
    let inside = |p: &[f64; 2]| if keep_above { p[a] >= at } else { p[a] <= at };
    for k in 0..n {
        let (p, q) = (poly[k], poly[(k + 1) % n]);
        let (pin, qin) = (inside(&p), inside(&q));
        if pin {
            out.push(p);
        }
        if pin != qin {
            let t = (at - p[a]) / (q[a] - p[a]);
            let mut x = [0.0; 2];
            x[a] = at;
            x[b] = p[b] + (q[b] - p[b]) * t;
            out.push(x);
        }
    }
}

/// |shoelace area| of `poly` after moving the origin to the pixel corner (i, j): the
/// differences are exact (Sterbenz) for points within the pixel.
fn area_local(poly: &[[f64; 2]], i: f64, j: f64) -> f64 {
    let n = poly.len();
    if n < 3 {
        return 0.0;
    }
    let mut s = 0.0;
    for k in 0..n {
        let (p, q) = (poly[k], poly[(k + 1) % n]);
        s += (p[0] - i) * (q[1] - j) - (q[0] - i) * (p[1] - j);
    }
    (0.5 * s).abs()
}

/// A method's error against the truth `rings` (face id, pixel ring) of a `width x height`
/// image: the mean over pixels of 1 − the area fraction of the face the method shows at the
/// pixel centre (`ids`, row-major; `None`: background, whose area is what no ring covers).
///
/// Computed in one pass over the rings without storing per-pixel areas:
/// `Σ_p (1 − a(p, ids[p])) = N − Σ_{(p,f,a): ids[p] = f} a − #None + Σ_{(p,f,a): ids[p] = None} a`.
/// The rings must be disjoint (a visible set's pieces are).
pub fn error_of(
    rings: &[(u32, Vec<[f64; 2]>)],
    width: u32,
    height: u32,
    ids: &[Option<u32>],
) -> f64 {
    let n = width as usize * height as usize;
    if n == 0 || ids.len() != n {
        return f64::NAN;
    }
    // Areas of the answered face, and areas covered where the method answered background.
    let (mut hit, mut covered_in_none) = (0.0f64, 0.0f64);
    for (face, ring) in rings {
        let (mut h, mut c) = (0.0, 0.0);
        for_each_pixel_area(ring, *face, width, height, &mut |p, f, a| match ids[p] {
            Some(g) if g == f => h += a,
            None => c += a,
            _ => {}
        });
        hit += h;
        covered_in_none += c;
    }
    let none = ids.iter().filter(|i| i.is_none()).count() as f64;
    let right = hit + none - covered_in_none;
    ((n as f64 - right) / n as f64).clamp(0.0, 1.0)
}

/// The area covered by `rings` in each pixel (row-major): for tests and checks (one f64 per
/// pixel).
pub fn covered_areas(rings: &[(u32, Vec<[f64; 2]>)], width: u32, height: u32) -> Vec<f64> {
    let mut out = vec![0.0; width as usize * height as usize];
    for (face, ring) in rings {
        for_each_pixel_area(ring, *face, width, height, &mut |p, _, a| out[p] += a);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<[f64; 2]> {
        vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
    }

    #[test]
    fn a_pixel_half_covered_is_half_wrong_when_answered_background_or_the_face() {
        // One pixel, its left half covered by face 7 (the centre lies on the edge).
        let rings = vec![(7, rect(0.0, 0.0, 0.5, 1.0))];
        assert_eq!(error_of(&rings, 1, 1, &[None]), 0.5);
        assert_eq!(error_of(&rings, 1, 1, &[Some(7)]), 0.5);
        assert_eq!(error_of(&rings, 1, 1, &[Some(3)]), 1.0);
        // A quarter: background is 3/4 right.
        let rings = vec![(7, rect(0.0, 0.0, 0.5, 0.5))];
        assert_eq!(error_of(&rings, 1, 1, &[None]), 0.25);
        assert_eq!(error_of(&rings, 1, 1, &[Some(7)]), 0.75);
    }

    #[test]
    fn a_thin_sliver_missing_every_centre_is_an_area_error() {
        // 4x4 pixels: face 1 covers all but a sliver along x in [2.6, 2.7], face 2 covers the
        // sliver; no pixel centre (x = k + 0.5) lies in it, so every point-sampling method
        // shows face 1 everywhere, which is right at every centre yet wrong by the sliver.
        let (w, h) = (4u32, 4u32);
        let rings = vec![
            (1, rect(0.0, 0.0, 2.6, 4.0)),
            (2, rect(2.6, 0.0, 2.7, 4.0)),
            (1, rect(2.7, 0.0, 4.0, 4.0)),
        ];
        let ids = vec![Some(1); 16];
        let e = error_of(&rings, w, h, &ids);
        // Sliver area 0.4 of 16 pixels.
        assert!((e - 0.4 / 16.0).abs() < 1e-12, "{e}");
        assert!(e > 0.0);
        // Every pixel is covered once.
        for a in covered_areas(&rings, w, h) {
            assert!((a - 1.0).abs() < 1e-12, "{a}");
        }
    }

    #[test]
    fn areas_sum_to_one_per_pixel_within_the_bound() {
        // A fan of triangles about an off-grid point tiling [−3.3, 19.7] x [−2.1, 17.9] over a
        // 16x16 image: every pixel is covered exactly once.
        let c = [7.123456789, 8.987654321];
        let box_ = [[-3.3, -2.1], [19.7, -2.1], [19.7, 17.9], [-3.3, 17.9]];
        let mut pts = Vec::new();
        for k in 0..4 {
            let (p, q) = (box_[k], box_[(k + 1) % 4]);
            for s in 0..7 {
                let t = s as f64 / 7.0;
                pts.push([p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t]);
            }
        }
        let rings: Vec<(u32, Vec<[f64; 2]>)> = (0..pts.len())
            .map(|k| (k as u32, vec![c, pts[k], pts[(k + 1) % pts.len()]]))
            .collect();
        let areas = covered_areas(&rings, 16, 16);
        // The bound of the module docs for 28 pieces of at most 7 vertices, coordinates below
        // 20 px: far below 1e-12.
        let worst = areas.iter().map(|a| (a - 1.0).abs()).fold(0.0, f64::max);
        assert!(worst < 1e-12, "{worst}");
        // The method showing the centre's face is right except where a pixel is shared.
        let ids = vec![None; 256];
        assert!((error_of(&rings, 16, 16, &ids) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn bad_rings_and_outside_rings_add_nothing() {
        let rings = vec![
            (1, vec![[f64::NAN, 0.0], [1.0, 0.0], [1.0, 1.0]]),
            (2, rect(5.0, 5.0, 6.0, 6.0)),
            (3, vec![[0.0, 0.0], [1.0, 1.0]]),
        ];
        assert_eq!(covered_areas(&rings, 2, 2), vec![0.0; 4]);
        assert_eq!(error_of(&rings, 2, 2, &[None; 4]), 0.0);
        assert!(error_of(&rings, 2, 2, &[None; 3]).is_nan());
    }
}
