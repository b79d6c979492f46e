//! Seed 002's worked z-buffer example: two triangles seen from (0, 0, 8), red at z = 0 translated
//! +1, blue at z = -1 translated -1. With near 5 and far 10 the seed gives normalized depths 0.75
//! (16-bit 49151) for red and 0.8889 (58253) for blue; with near 0.01 and far 1000, 65454 and
//! 65463. Red is in front where they overlap.

mod support;

use glam::DVec3;
use sightline::camera::{Camera, CameraSpec};
use sightline::output::png::depth_to_u16;
use sightline::pipeline::render_zbuffer;
use sightline::project::CullMode;
use sightline::scene::Scene;
use std::collections::BTreeMap;
use support::fixtures::fixture;
use support::oracle::pixel_of;

fn seed_scene() -> Scene {
    fixture("seed_two_triangles.x3d")
}

fn seed_camera(scene: &Scene, near: f64, far: f64) -> Camera {
    let spec = CameraSpec {
        near: Some(near),
        far: Some(far),
        size: Some((120, 100)),
        ..CameraSpec::default()
    };
    spec.resolve(scene.bounds().unwrap(), scene.viewpoint.as_ref())
        .unwrap()
}

/// Pixel count per (face id or u32::MAX for background, 16-bit depth).
type DepthHistogram = BTreeMap<(u32, u16), usize>;

/// The depth histogram, the 16-bit depths and the face ids of a z-buffer render.
fn depths_by_face(scene: &Scene, camera: &Camera) -> (DepthHistogram, Vec<u16>, Vec<Option<u32>>) {
    let (prepared, zb) = render_zbuffer(scene, camera, CullMode::Auto, |_| {});
    let depth: Vec<u16> = zb
        .normalized_depth(&prepared.screen)
        .iter()
        .map(|&d| depth_to_u16(d))
        .collect();
    let ids = zb.face_ids(&prepared.screen);
    let mut hist = BTreeMap::new();
    for (id, d) in ids.iter().zip(&depth) {
        *hist.entry((id.unwrap_or(u32::MAX), *d)).or_insert(0) += 1;
    }
    (hist, depth, ids)
}

#[test]
fn seed_scene_loads_with_the_viewpoint() {
    let scene = seed_scene();
    assert_eq!(scene.faces.len(), 2);
    let vp = scene.viewpoint.expect("the seed has a Viewpoint");
    assert_eq!(vp.position, DVec3::new(0.0, 0.0, 8.0));
    let red = &scene.materials[scene.faces[0].material as usize];
    assert_eq!(red.emissive, [1.0, 0.0, 0.0]);
}

#[test]
fn near_5_far_10_gives_49151_and_58253() {
    let scene = seed_scene();
    let cam = seed_camera(&scene, 5.0, 10.0);
    let (hist, depth, ids) = depths_by_face(&scene, &cam);
    // Exactly three depth values: red, blue and the background.
    let values: std::collections::BTreeSet<u16> = hist.keys().map(|k| k.1).collect();
    assert_eq!(
        values.into_iter().collect::<Vec<_>>(),
        vec![49151, 58253, 65535]
    );
    assert!(hist.contains_key(&(0, 49151)) && hist.contains_key(&(1, 58253)));
    assert!(!hist.contains_key(&(0, 58253)) && !hist.contains_key(&(1, 49151)));
    // Where they overlap (world (0, -1) is inside both), red is in front.
    let k = pixel_of(&cam, DVec3::new(0.0, -1.0, 0.0));
    assert_eq!(ids[k], Some(0));
    assert_eq!(depth[k], 49151);
    // Blue alone to the left.
    let k = pixel_of(&cam, DVec3::new(-2.2, -1.5, -1.0));
    assert_eq!((ids[k], depth[k]), (Some(1), 58253));
}

#[test]
fn near_001_far_1000_gives_65454_and_65463() {
    let scene = seed_scene();
    let cam = seed_camera(&scene, 0.01, 1000.0);
    let (hist, _, _) = depths_by_face(&scene, &cam);
    let values: Vec<(u32, u16)> = hist.keys().copied().collect();
    assert_eq!(values, vec![(0, 65454), (1, 65463), (u32::MAX, 65535)]);
}
