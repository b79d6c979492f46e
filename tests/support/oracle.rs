//! References to check renderers against, sharing no code with what they check: a brute-force
//! ray cast in world space, the interior pixels where two face-id images must agree, and the
//! seed's transparent scene as the course material gives it.

use glam::DVec3;
use sightline::camera::Camera;
use sightline::scene::Scene;

/// Is `p` inside the planar polygon `poly` (even-odd, projected on its dominant plane)? f64.
fn inside_polygon(poly: &[DVec3], n: DVec3, p: DVec3) -> bool {
    let (i, j) = match n.abs().max_position() {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    };
    let mut inside = false;
    for k in 0..poly.len() {
        let a = poly[k];
        let b = poly[(k + 1) % poly.len()];
        if (a[j] > p[j]) != (b[j] > p[j]) {
            let x = a[i] + (p[j] - a[j]) / (b[j] - a[j]) * (b[i] - a[i]);
            if p[i] < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// Brute force, independent of the projection code: for each pixel centre, cast the world-space
/// ray from the near plane to the far plane and take the nearest face hit (input face id).
pub fn brute_force_ids(scene: &Scene, camera: &Camera) -> Vec<Option<u32>> {
    let inv = camera.view_projection().inverse();
    let faces: Vec<(u32, Vec<DVec3>, DVec3)> = scene
        .faces
        .iter()
        .map(|f| {
            let pts: Vec<DVec3> = scene.face_positions(f).collect();
            (f.id, pts, scene.face_normal(f))
        })
        .collect();
    let mut out = Vec::with_capacity((camera.width * camera.height) as usize);
    for j in 0..camera.height {
        for i in 0..camera.width {
            let (x, y) = camera.pixel_center_ndc(i, j);
            let a = inv.project_point3(DVec3::new(x, y, -1.0));
            let b = inv.project_point3(DVec3::new(x, y, 1.0));
            let d = b - a;
            let mut best: Option<(f64, u32)> = None;
            for (id, pts, n) in &faces {
                let denom = n.dot(d);
                if denom == 0.0 {
                    continue;
                }
                let t = n.dot(pts[0] - a) / denom;
                if !(0.0..=1.0).contains(&t) {
                    continue;
                }
                if best.is_some_and(|(bt, _)| bt <= t) {
                    continue;
                }
                if inside_polygon(pts, *n, a + d * t) {
                    best = Some((t, *id));
                }
            }
            out.push(best.map(|(_, id)| id));
        }
    }
    out
}

/// Pixels whose 3x3 neighbourhood (clipped to the image) holds one value.
pub fn interior_pixels<T: PartialEq>(img: &[T], w: usize, h: usize) -> Vec<usize> {
    let mut out = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let v = &img[j * w + i];
            let mut same = true;
            for dj in -1i64..=1 {
                for di in -1i64..=1 {
                    let (x, y) = (i as i64 + di, j as i64 + dj);
                    if x >= 0 && y >= 0 && (x as usize) < w && (y as usize) < h {
                        same &= img[y as usize * w + x as usize] == *v;
                    }
                }
            }
            if same {
                out.push(j * w + i);
            }
        }
    }
    out
}

/// A mismatch at pixel (x, y): the reference's id, then the checked one.
pub type Mismatch = (usize, usize, Option<u32>, Option<u32>);

/// The interior pixels of `reference` (3x3 neighbourhood of one id) and those among them where
/// `ids` differs.
pub fn interior_mismatches(
    reference: &[Option<u32>],
    ids: &[Option<u32>],
    w: usize,
    h: usize,
) -> (Vec<usize>, Vec<Mismatch>) {
    let interior = interior_pixels(reference, w, h);
    let bad = interior
        .iter()
        .filter(|&&k| ids[k] != reference[k])
        .map(|&k| (k % w, k / w, reference[k], ids[k]))
        .collect();
    (interior, bad)
}

/// Row-major index of the pixel containing the projection of world point `p`.
pub fn pixel_of(camera: &Camera, p: DVec3) -> usize {
    let q = camera.view_projection().project_point3(p);
    let i = ((q.x + 1.0) / 2.0 * camera.width as f64) as usize;
    let j = ((1.0 - q.y) / 2.0 * camera.height as f64) as usize;
    j * camera.width as usize + i
}

/// Checks a picture of the seed's transparent scene (`fixtures/seed_transparent.x3d`, over
/// black, through `camera`): green (0, 0.6, 0) alone, green over blue (0, 0.6, 0.4), blue
/// (0, 0, 1) and black, each where the seed puts it, every pixel exactly one of the four (no
/// anti-aliasing), each on more than 1,000 pixels. Returns the four pixel counts in that order.
pub fn assert_seed_transparent_colours(c: &[[f64; 3]], camera: &Camera) -> [usize; 4] {
    let green = [0.0, 0.6, 0.0];
    let green_over_blue = [0.0, 0.6, 0.4];
    let blue = [0.0, 0.0, 1.0];
    let black = [0.0; 3];
    assert_eq!(c[pixel_of(camera, DVec3::new(-2.0, -1.5, 0.0))], green);
    assert_eq!(
        c[pixel_of(camera, DVec3::new(0.0, -1.5, 0.0))],
        green_over_blue
    );
    assert_eq!(c[pixel_of(camera, DVec3::new(2.0, -1.5, -1.0))], blue);
    assert_eq!(c[0], black);
    let mut counts = [0usize; 4];
    for px in c {
        let k = [green, green_over_blue, blue, black]
            .iter()
            .position(|q| q == px)
            .unwrap_or_else(|| panic!("unexpected colour {px:?}"));
        counts[k] += 1;
    }
    assert!(counts.iter().all(|&n| n > 1000), "{counts:?}");
    counts
}
