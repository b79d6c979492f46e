//! Scenes and cameras for the image-space renderer tests (A-buffer, scanline, Warnock): the
//! fixtures, and random triangles built to hit the hard cases of a pixel-exact renderer.
#![allow(dead_code)]

use glam::DVec3;
use sightline::camera::{Camera, CameraSpec, NamedView, Projection};
use sightline::scene::{Material, Scene, SceneBuilder};
use std::path::{Path, PathBuf};
// The test files that use these scenes include `support` too.
use super::support::Rng;

/// Every loadable fixture (`fixtures/`, not `fixtures/bad`), by path, in name order.
pub fn fixture_paths() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures");
    let mut out: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.is_file()
                && matches!(
                    p.extension().and_then(|e| e.to_str()),
                    Some("obj" | "stl" | "ply" | "x3d")
                )
        })
        .collect();
    out.sort();
    assert!(out.len() >= 15, "fixtures missing: {out:?}");
    out
}

/// Cameras for a scene: its own (or the default) view, and fitted named views, perspective and
/// orthographic.
pub fn cameras(scene: &Scene, w: u32, h: u32) -> Vec<Camera> {
    let bounds = scene.bounds().unwrap();
    let own = CameraSpec {
        size: Some((w, h)),
        ..CameraSpec::default()
    }
    .resolve(bounds, scene.viewpoint.as_ref())
    .unwrap();
    vec![
        own,
        Camera::fit(NamedView::Iso, bounds, false, 40.0, w, h),
        Camera::fit(NamedView::Front, bounds, true, 40.0, w, h),
        Camera::fit(NamedView::Top, bounds, false, 60.0, w, h),
    ]
}

/// Image size of [`lattice_camera`]: powers of two, so pixel centres fall exactly on the grid.
pub const LATTICE_W: u32 = 64;
pub const LATTICE_H: u32 = 32;

/// Orthographic front camera: world x in [-2, 2], y in [-1, 1] fills the 64 x 32 image, and the
/// world point [`lattice_point`]`(i, j, z)` projects exactly onto the centre of pixel (i, j).
pub fn lattice_camera() -> Camera {
    Camera {
        eye: DVec3::new(0.0, 0.0, 5.0),
        target: DVec3::ZERO,
        up: DVec3::Y,
        projection: Projection::Orthographic { height: 2.0 },
        near: 1.0,
        far: 10.0,
        width: LATTICE_W,
        height: LATTICE_H,
    }
}

/// The world point on the centre of pixel (i, j) of [`lattice_camera`], at depth `z`.
pub fn lattice_point(i: i64, j: i64, z: f64) -> DVec3 {
    DVec3::new(
        ((2 * i + 1) as f64 / LATTICE_W as f64 - 1.0) * 2.0,
        1.0 - (2 * j + 1) as f64 / LATTICE_H as f64,
        z,
    )
}

/// `n` faces (or so), mostly triangles, made to hit a pixel-exact renderer's hard cases, each in
/// a mesh of its own (open: never culled) with a material of its own:
/// - corners from a small shared pool, half of them on pixel centres of [`lattice_camera`] at
///   one of three depths (edges and corners exactly through samples);
/// - quads split in two (a shared edge), triangles sharing an edge with an earlier one;
/// - exact duplicates of earlier triangles, some reversed (coplanar overlap: exact depth ties
///   under any camera), and triangles at one constant depth (coplanar under view-aligned
///   cameras);
/// - non-convex stars at one constant depth, some self-intersecting (the even-odd fill rule);
/// - everything else interpenetrating at random.
///
/// With `translucent`, materials get transparencies among 0, 0.25, 0.5, 0.75 and 1; colours are
/// emissive multiples of 1/4 (diffuse 0), so shading leaves them exact.
pub fn tricky_faces(seed: u64, n: usize, translucent: bool) -> Scene {
    let mut rng = Rng(seed);
    let mut b = SceneBuilder::new("tricky");
    let levels = [-0.5, 0.0, 0.5];
    let pool_size = 6 + rng.below(10) as usize;
    let mut pool: Vec<u32> = Vec::new();
    for k in 0..pool_size {
        let p = if k % 2 == 0 {
            lattice_point(
                rng.below(LATTICE_W as u64 + 1) as i64,
                rng.below(LATTICE_H as u64 + 1) as i64,
                levels[rng.below(3) as usize],
            )
        } else {
            DVec3::new(
                rng.range(-1.8, 1.8),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            )
        };
        pool.push(b.add_vertex(p));
    }
    let mut tris: Vec<Vec<u32>> = Vec::new();
    let pick = |rng: &mut Rng| pool[rng.below(pool.len() as u64) as usize];
    while tris.len() < n {
        let kind = rng.below(12);
        match kind {
            0..=3 => tris.push(vec![pick(&mut rng), pick(&mut rng), pick(&mut rng)]),
            4 | 5 => {
                let (a, bb, c, d) = (
                    pick(&mut rng),
                    pick(&mut rng),
                    pick(&mut rng),
                    pick(&mut rng),
                );
                tris.push(vec![a, bb, c]);
                tris.push(vec![a, c, d]);
            }
            6 if !tris.is_empty() => {
                let mut t = tris[rng.below(tris.len() as u64) as usize].clone();
                if rng.below(2) == 0 {
                    t.rotate_left(1);
                } else {
                    t.reverse();
                }
                tris.push(t);
            }
            7 if !tris.is_empty() => {
                let t = &tris[rng.below(tris.len() as u64) as usize];
                let e = rng.below(t.len() as u64) as usize;
                let shared = vec![t[(e + 1) % t.len()], t[e], pick(&mut rng)];
                tris.push(shared);
            }
            8 | 9 => {
                // A star: corners alternately far from and near its centre (non-convex); taken
                // two steps at a time around an odd count, it crosses itself (a pentagram).
                let z = levels[rng.below(3) as usize];
                let (cx, cy) = (rng.range(-1.5, 1.5), rng.range(-0.8, 0.8));
                let points = 5 + 2 * rng.below(3) as usize;
                let (r_out, r_in) = (rng.range(0.3, 1.0), rng.range(0.05, 0.3));
                let ring: Vec<u32> = (0..points)
                    .map(|k| {
                        let a = std::f64::consts::TAU * k as f64 / points as f64;
                        let r = if kind == 8 && k % 2 == 1 { r_in } else { r_out };
                        b.add_vertex(DVec3::new(cx + r * a.cos(), cy + r * a.sin(), z))
                    })
                    .collect();
                let order: Vec<u32> = if kind == 8 {
                    ring
                } else {
                    (0..points).map(|k| ring[(2 * k) % points]).collect()
                };
                tris.push(order);
            }
            _ => {
                let z = levels[rng.below(3) as usize];
                let mut v = vec![0u32; 3];
                for c in &mut v {
                    *c = b.add_vertex(lattice_point(
                        rng.below(LATTICE_W as u64 + 1) as i64,
                        rng.below(LATTICE_H as u64 + 1) as i64,
                        z,
                    ));
                }
                tris.push(v);
            }
        }
    }
    let quarter = |rng: &mut Rng| rng.below(5) as f64 / 4.0;
    for (k, t) in tris.iter().enumerate() {
        let transparency = if translucent { quarter(&mut rng) } else { 0.0 };
        let m = b.add_material(Material {
            name: format!("m{k}"),
            diffuse: [0.0; 3],
            emissive: [quarter(&mut rng), quarter(&mut rng), quarter(&mut rng)],
            transparency,
            two_sided: false,
        });
        b.begin_mesh(format!("t{k}"));
        b.add_face(t, m);
    }
    b.finish().unwrap_or_else(|| {
        // Every triangle degenerate (rare with small pools): one plain triangle instead.
        let mut b = SceneBuilder::new("tricky");
        let m = b.default_material();
        let v: Vec<u32> = [
            lattice_point(3, 3, 0.0),
            lattice_point(40, 5, 0.0),
            lattice_point(9, 30, 0.0),
        ]
        .iter()
        .map(|&p| b.add_vertex(p))
        .collect();
        b.add_face(&v, m);
        b.finish().unwrap()
    })
}
