//! The z-buffer against a brute-force ray cast in world space: the same face id at every interior
//! pixel (3x3 neighbourhood of one id). The brute force shares no code with the projection,
//! clipping, snapping or rasterization it checks.

mod support;

use glam::DVec3;
use sightline::camera::{Camera, NamedView, Projection};
use sightline::pipeline::render_zbuffer;
use sightline::project::CullMode;
use sightline::scene::{Scene, SceneBuilder};
use support::camera::{fit, look_at, random_cameras, soup_camera};
use support::oracle::{brute_force_ids, interior_mismatches};
use support::scenes::{add_box, add_triangle, boxes_and_sphere, random_triangles};

/// The image size of the cameras here.
const SIZE: (u32, u32) = (160, 120);

fn check_against_brute_force(scene: &Scene, camera: &Camera, cull: CullMode) -> (usize, usize) {
    let (prepared, zb) = render_zbuffer(scene, camera, cull, |_| {});
    let ids = zb.face_ids(&prepared.screen);
    let reference = brute_force_ids(scene, camera);
    let (w, h) = (camera.width as usize, camera.height as usize);
    // Interior pixels of the z-buffer image, where the brute force must agree.
    let (interior, mismatches) = interior_mismatches(&ids, &reference, w, h);
    assert!(
        mismatches.is_empty(),
        "{} of {} interior pixels differ from the brute force, first: {:?}",
        mismatches.len(),
        interior.len(),
        &mismatches[..mismatches.len().min(5)]
    );
    let covered = interior.iter().filter(|&&k| ids[k].is_some()).count();
    (interior.len(), covered)
}

#[test]
fn closed_interpenetrating_meshes_in_perspective() {
    let scene = boxes_and_sphere(24, 12);
    let cam = fit(&scene, NamedView::Iso, false, SIZE.0, SIZE.1);
    let (interior, covered) = check_against_brute_force(&scene, &cam, CullMode::Auto);
    assert!(interior > 10_000 && covered > 1_500, "{interior} {covered}");
}

#[test]
fn closed_meshes_in_orthographic_views() {
    let scene = boxes_and_sphere(24, 12);
    for view in [
        NamedView::Front,
        NamedView::Top,
        NamedView::Left,
        NamedView::Iso,
    ] {
        let cam = fit(&scene, view, true, SIZE.0, SIZE.1);
        let (_, covered) = check_against_brute_force(&scene, &cam, CullMode::Auto);
        assert!(covered > 1_500, "{view:?}: {covered}");
    }
}

#[test]
fn random_interpenetrating_triangles() {
    for seed in 1..=4 {
        let scene = random_triangles(60, seed);
        let ortho = look_at(
            DVec3::new(3.0, 1.0, 2.0),
            DVec3::ZERO,
            Projection::Orthographic { height: 3.5 },
            0.5,
            8.0,
            SIZE,
        );
        for cam in [soup_camera(SIZE), ortho] {
            let (_, covered) = check_against_brute_force(&scene, &cam, CullMode::Auto);
            assert!(covered > 1_000, "seed {seed}: {covered}");
        }
    }
}

#[test]
fn faces_crossing_the_near_plane_are_clipped_not_dropped() {
    // A floor running from far in front to behind the camera, a wall the camera stands next to,
    // and a box: the floor and wall cross the near plane.
    let mut b = SceneBuilder::new("near");
    b.begin_mesh("floor");
    let m = b.default_material();
    let f: Vec<u32> = [
        DVec3::new(-6.0, -1.0, -20.0),
        DVec3::new(6.0, -1.0, -20.0),
        DVec3::new(6.0, -1.0, 20.0),
        DVec3::new(-6.0, -1.0, 20.0),
    ]
    .iter()
    .map(|&p| b.add_vertex(p))
    .collect();
    b.add_face(&[f[3], f[2], f[1], f[0]], m);
    add_triangle(
        &mut b,
        [
            DVec3::new(0.6, -1.0, 8.0),
            DVec3::new(0.6, -1.0, -6.0),
            DVec3::new(0.6, 2.0, -2.0),
        ],
    );
    add_box(
        &mut b,
        DVec3::new(-1.5, -1.0, -4.0),
        DVec3::new(-0.2, 0.5, -2.5),
        "box",
    );
    let scene = b.finish().unwrap();
    let cam = look_at(
        DVec3::new(0.0, 0.2, 4.0),
        DVec3::new(0.0, -0.2, 0.0),
        Projection::Perspective { fovy_deg: 70.0 },
        0.3,
        40.0,
        SIZE,
    );
    let (prepared, _) = render_zbuffer(&scene, &cam, CullMode::Auto, |_| {});
    assert!(
        prepared.screen.stats.clipped >= 2,
        "{:?}",
        prepared.screen.stats
    );
    let on_screen: Vec<u32> = prepared.screen.polys.iter().map(|p| p.id).collect();
    assert!(
        on_screen.contains(&0) && on_screen.contains(&1),
        "floor and wall kept"
    );
    let (_, covered) = check_against_brute_force(&scene, &cam, CullMode::Auto);
    assert!(covered > 8_000, "{covered}");
}

#[test]
fn the_camera_inside_a_closed_box_sees_its_inside() {
    // The near plane cuts the box, so its back faces must not be culled.
    let mut b = SceneBuilder::new("room");
    add_box(&mut b, DVec3::splat(-2.0), DVec3::splat(2.0), "room");
    add_box(
        &mut b,
        DVec3::new(-0.5, -0.5, -1.5),
        DVec3::new(0.5, 0.5, -0.8),
        "inner",
    );
    let scene = b.finish().unwrap();
    let cam = look_at(
        DVec3::new(0.2, 0.3, 1.0),
        DVec3::new(0.0, 0.0, -1.0),
        Projection::Perspective { fovy_deg: 90.0 },
        0.05,
        20.0,
        SIZE,
    );
    let (prepared, zb) = render_zbuffer(&scene, &cam, CullMode::Auto, |_| {});
    assert_eq!(prepared.screen.stats.meshes_cut_by_near, 1);
    assert!(
        zb.poly.iter().all(|&p| p != sightline::raster::EMPTY),
        "walls everywhere"
    );
    check_against_brute_force(&scene, &cam, CullMode::Auto);
}

mod random_scenes {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

        /// Random triangle soups under random perspective and orthographic cameras, the eye
        /// sometimes among the triangles (so faces cross the near plane).
        #[test]
        fn zbuffer_matches_brute_force_at_interior_pixels(
            seed in any::<u64>(),
            n in 1usize..25,
            cam in random_cameras(0.05f64..1.0),
        ) {
            let scene = random_triangles(n, seed);
            prop_assume!(cam.is_some());
            let cam = cam.unwrap();
            check_against_brute_force(&scene, &cam, CullMode::Auto);
        }
    }
}
