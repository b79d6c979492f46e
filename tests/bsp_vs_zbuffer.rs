//! The BSP visible set against the z-buffer: the same face id at every interior pixel.

mod support;

use glam::DVec3;
use sightline::camera::{Camera, CameraSpec, NamedView, Projection};
use sightline::pipeline::render_zbuffer;
use sightline::project::CullMode;
use sightline::scene::{Scene, SceneBuilder};
use sightline::visibility::bsp::{Bsp, visible_set};
use support::camera::random_camera;
use support::oracle::interior_mismatches;
use support::scenes::{add_box, add_sphere, random_triangles};

/// Interior mismatches between the exact ids and the z-buffer's, for both exact paths (the
/// coverage map `--method bsp` draws, and the BSP walk). Returns the interior pixel count and
/// the visible pieces of the coverage map.
fn mismatches(scene: &Scene, camera: &Camera) -> (usize, usize) {
    let (prepared, zb) = render_zbuffer(scene, camera, CullMode::Auto, |_| {});
    let z_ids = zb.face_ids(&prepared.screen);
    let (w, h) = (camera.width as usize, camera.height as usize);
    let (visible, stats) = visible_set(&prepared.screen);
    let mut bsp = Bsp::build(&prepared.screen);
    let walked = bsp.visible_set(&prepared.screen);
    let mut interior_count = 0;
    for (path, set) in [("coverage map", &visible), ("BSP walk", &walked)] {
        let ids = set.face_ids(&prepared.screen);
        let (interior, bad) = interior_mismatches(&z_ids, &ids, w, h);
        assert!(
            bad.is_empty(),
            "{path}: {} interior mismatches, first {:?}; stats {stats:?} {:?}",
            bad.len(),
            &bad[..bad.len().min(5)],
            bsp.stats
        );
        interior_count = interior.len();
    }
    (interior_count, visible.pieces.len())
}

#[test]
fn closed_meshes_and_interpenetration() {
    let mut b = SceneBuilder::new("boxes");
    add_box(
        &mut b,
        DVec3::new(-1.0, -1.0, -1.0),
        DVec3::new(0.3, 0.5, 0.2),
        "a",
    );
    add_box(
        &mut b,
        DVec3::new(0.1, -0.4, -0.3),
        DVec3::new(1.2, 0.9, 0.9),
        "b",
    );
    add_sphere(&mut b, DVec3::new(-0.2, 0.6, 0.6), 0.55, 16, 8);
    let scene = b.finish().unwrap();
    for (view, ortho) in [
        (NamedView::Iso, false),
        (NamedView::Front, true),
        (NamedView::Top, false),
    ] {
        let cam = Camera::fit(view, scene.bounds().unwrap(), ortho, 40.0, 120, 90);
        mismatches(&scene, &cam);
    }
}

#[test]
fn random_triangle_soups() {
    for seed in 1..=6 {
        let scene = random_triangles(40, seed);
        let cam = Camera {
            eye: DVec3::new(0.4, 0.7, 4.0),
            target: DVec3::ZERO,
            up: DVec3::Y,
            projection: Projection::Perspective { fovy_deg: 50.0 },
            near: 1.0,
            far: 8.0,
            width: 100,
            height: 80,
        };
        mismatches(&scene, &cam);
    }
}

#[test]
fn fixtures() {
    for f in [
        "fixtures/seed_two_triangles.x3d",
        "fixtures/primitives.x3d",
        "fixtures/indexed.x3d",
        "fixtures/cube.obj",
        "fixtures/two_objects.obj",
    ] {
        let scene = sightline::load(std::path::Path::new(f), None).unwrap();
        let cam = CameraSpec {
            size: Some((96, 72)),
            ..CameraSpec::default()
        }
        .resolve(scene.bounds().unwrap(), scene.viewpoint.as_ref())
        .unwrap();
        mismatches(&scene, &cam);
    }
}

mod random_scenes {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

        /// Random soups (interpenetrating, cyclic overlaps) under random cameras, some with the
        /// eye among the triangles.
        #[test]
        fn bsp_matches_zbuffer_at_interior_pixels(
            seed in any::<u64>(),
            n in 1usize..20,
            eye in prop::array::uniform3(-4.0f64..4.0),
            ortho in any::<bool>(),
            fov in 20.0f64..100.0,
        ) {
            let scene = random_triangles(n, seed);
            let cam = random_camera(eye, ortho, fov, 0.2);
            prop_assume!(cam.is_some());
            let cam = cam.unwrap();
            mismatches(&scene, &cam);
        }
    }
}

/// Regions per face id in the BSP's drawing.
fn regions_per_face(file: &str, view: NamedView) -> std::collections::BTreeMap<u32, usize> {
    use sightline::visibility::{BspMethod, VisibilityMethod};
    let scene = sightline::load(std::path::Path::new(file), None).unwrap();
    let cam = Camera::fit(view, scene.bounds().unwrap(), false, 40.0, 200, 200);
    let prepared = sightline::pipeline::prepare(&scene, &cam, CullMode::Auto);
    let result = BspMethod::default().run(
        &scene,
        &prepared.screen,
        &cam,
        sightline::pipeline::Fill::Shade,
    );
    let mut count = std::collections::BTreeMap::new();
    for item in &result.drawing.items {
        *count.entry(item.face).or_insert(0) += 1;
    }
    count
}

#[test]
fn a_face_visible_region_is_not_needlessly_cut() {
    // Each bar is hidden across its width by the bar lying over its far end, which leaves two
    // visible regions: the body and the tip beyond the crossing bar.
    let bars = regions_per_face("fixtures/cyclic_bars.obj", NamedView::Front);
    assert_eq!(
        bars.values().copied().collect::<Vec<_>>(),
        vec![2, 2, 2],
        "{bars:?}"
    );
    // A cube seen from a corner: three whole faces, one region each.
    let cube = regions_per_face("fixtures/cube.obj", NamedView::Iso);
    assert_eq!(
        cube.values().copied().collect::<Vec<_>>(),
        vec![1, 1, 1],
        "{cube:?}"
    );
}
