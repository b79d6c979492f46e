//! Scenes generated in code, and a brute-force visibility reference, shared by the tests.
#![allow(dead_code)]

use glam::{DMat4, DVec3};
use sightline::camera::{Camera, Projection};
use sightline::scene::{Scene, SceneBuilder, primitives};

/// A tiny deterministic RNG (splitmix64).
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e3779b97f4a7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
        z ^ (z >> 31)
    }
    /// Uniform in 0..n.
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn vec3(&mut self, lo: f64, hi: f64) -> DVec3 {
        DVec3::new(self.range(lo, hi), self.range(lo, hi), self.range(lo, hi))
    }
}

/// Adds an axis-aligned box (outward, closed) in a mesh of its own.
pub fn add_box(b: &mut SceneBuilder, lo: DVec3, hi: DVec3, name: &str) {
    b.begin_mesh(name);
    let m = b.default_material();
    let at = DMat4::from_translation((lo + hi) * 0.5);
    primitives::add_box(b, &at, hi - lo, m);
}

/// Adds a triangle in a mesh of its own (open: never culled).
pub fn add_triangle(b: &mut SceneBuilder, p: [DVec3; 3]) {
    b.begin_mesh("tri");
    let m = b.default_material();
    let v: Vec<u32> = p.iter().map(|&q| b.add_vertex(q)).collect();
    b.add_face(&v, m);
}

/// Adds a closed UV sphere of `seg` x `rings` in a mesh of its own.
pub fn add_sphere(b: &mut SceneBuilder, c: DVec3, r: f64, seg: usize, rings: usize) {
    b.begin_mesh("sphere");
    let m = b.default_material();
    primitives::add_sphere(b, &DMat4::from_translation(c), r, seg, rings, m);
}

/// `n` random triangles in [-1,1]^3 (overlapping and interpenetrating), each its own mesh.
pub fn random_triangles(n: usize, seed: u64) -> Scene {
    let mut rng = Rng(seed);
    let mut b = SceneBuilder::new("random");
    for _ in 0..n {
        let c = rng.vec3(-1.0, 1.0);
        let p = [
            c + rng.vec3(-0.6, 0.6),
            c + rng.vec3(-0.6, 0.6),
            c + rng.vec3(-0.6, 0.6),
        ];
        add_triangle(&mut b, p);
    }
    b.finish().unwrap()
}

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

/// A 48x40 camera looking at the origin from `eye`, orthographic (view height 3, near plane
/// behind the eye) or perspective with the given vertical field of view and near plane; far 12.
/// `None` when the eye is too close to the origin or the camera is invalid.
pub fn random_camera(eye: [f64; 3], ortho: bool, fov: f64, near: f64) -> Option<Camera> {
    let eye = DVec3::from_array(eye);
    if eye.length() <= 0.3 {
        return None;
    }
    let cam = Camera {
        eye,
        target: DVec3::ZERO,
        up: if eye.cross(DVec3::Y).length() > 1e-3 {
            DVec3::Y
        } else {
            DVec3::X
        },
        projection: if ortho {
            Projection::Orthographic { height: 3.0 }
        } else {
            Projection::Perspective { fovy_deg: fov }
        },
        near: if ortho { -6.0 } else { near },
        far: 12.0,
        width: 48,
        height: 40,
    };
    cam.validate().is_ok().then_some(cam)
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
