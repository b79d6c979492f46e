//! The tests' cameras: written once, so that "the front orthographic camera" or "the scene's own
//! view at 96x72" means one thing in every test. Every camera made here is valid (checked).
//!
//! The benchmarks include this file too (`benches/common`).
#![allow(dead_code)]

use glam::DVec3;
use proptest::prelude::*;
use sightline::camera::{Camera, CameraSpec, NamedView, Projection};
use sightline::scene::Scene;

/// A camera at `eye` looking at `target`, up +y, with a `size` (width, height) image.
pub fn look_at(
    eye: DVec3,
    target: DVec3,
    projection: Projection,
    near: f64,
    far: f64,
    size: (u32, u32),
) -> Camera {
    let c = Camera {
        eye,
        target,
        up: DVec3::Y,
        projection,
        near,
        far,
        width: size.0,
        height: size.1,
    };
    c.validate().unwrap();
    c
}

/// Orthographic camera from (0, 0, `distance`) down -z, `height` world units high, near 1, far
/// twice the distance.
pub fn ortho_down_z(distance: f64, height: f64, size: (u32, u32)) -> Camera {
    let eye = DVec3::new(0.0, 0.0, distance);
    let ortho = Projection::Orthographic { height };
    look_at(eye, DVec3::ZERO, ortho, 1.0, 2.0 * distance, size)
}

/// The front orthographic camera: from (0, 0, 5) down -z, `height` world units high, near 1,
/// far 10.
pub fn front_ortho(height: f64, width: u32, h: u32) -> Camera {
    ortho_down_z(5.0, height, (width, h))
}

/// The perspective camera the random triangle soups are seen through: from (0.4, 0.7, 4) at the
/// origin, 50 degrees, near 1, far 8 (the soups fill [-1.6, 1.6]^3).
pub fn soup_camera(size: (u32, u32)) -> Camera {
    let eye = DVec3::new(0.4, 0.7, 4.0);
    let perspective = Projection::Perspective { fovy_deg: 50.0 };
    look_at(eye, DVec3::ZERO, perspective, 1.0, 8.0, size)
}

/// The scene's own view (its viewpoint, or the default one) as the CLI resolves it, at `size`.
pub fn spec_camera(scene: &Scene, size: (u32, u32)) -> Camera {
    CameraSpec {
        size: Some(size),
        ..CameraSpec::default()
    }
    .resolve(scene.bounds().unwrap(), scene.viewpoint.as_ref())
    .unwrap()
}

/// The scene's own view at the CLI's default size.
pub fn scene_camera(scene: &Scene) -> Camera {
    CameraSpec::default()
        .resolve(scene.bounds().unwrap(), scene.viewpoint.as_ref())
        .unwrap()
}

/// A named view as `--view` gives it (the scene's viewpoint ignored), at `size`.
pub fn named_view(scene: &Scene, view: NamedView, size: (u32, u32)) -> Camera {
    CameraSpec {
        view: Some(view),
        size: Some(size),
        ..CameraSpec::default()
    }
    .resolve(scene.bounds().unwrap(), None)
    .unwrap()
}

/// A named view fitted to the scene's bounds with a 40-degree field of view (or orthographic).
pub fn fit(scene: &Scene, view: NamedView, ortho: bool, width: u32, height: u32) -> Camera {
    Camera::fit(view, scene.bounds().unwrap(), ortho, 40.0, width, height)
}

/// Cameras for a scene: its own (or the default) view, and fitted named views, perspective and
/// orthographic.
pub fn cameras(scene: &Scene, w: u32, h: u32) -> Vec<Camera> {
    vec![
        spec_camera(scene, (w, h)),
        fit(scene, NamedView::Iso, false, w, h),
        fit(scene, NamedView::Front, true, w, h),
        Camera::fit(NamedView::Top, scene.bounds().unwrap(), false, 60.0, w, h),
    ]
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

/// Proptest's draw of a [`random_camera`]: the eye in [-4, 4)^3, orthographic or not, a field
/// of view in [20, 100) degrees, the near plane drawn from `near`; `None` where the camera is
/// invalid (the test decides: reject the case, or skip that camera).
pub fn random_cameras(near: impl Strategy<Value = f64>) -> impl Strategy<Value = Option<Camera>> {
    (
        prop::array::uniform3(-4.0f64..4.0),
        any::<bool>(),
        20.0f64..100.0,
        near,
    )
        .prop_map(|(eye, ortho, fov, near)| random_camera(eye, ortho, fov, near))
}

/// Image size of [`lattice_camera`]: powers of two, so pixel centres fall exactly on the grid.
pub const LATTICE_W: u32 = 64;
pub const LATTICE_H: u32 = 32;

/// Orthographic front camera: world x in [-2, 2], y in [-1, 1] fills the 64 x 32 image, and the
/// world point [`lattice_point`]`(i, j, z)` projects exactly onto the centre of pixel (i, j).
pub fn lattice_camera() -> Camera {
    front_ortho(2.0, LATTICE_W, LATTICE_H)
}

/// The world point on the centre of pixel (i, j) of [`lattice_camera`], at depth `z`.
pub fn lattice_point(i: i64, j: i64, z: f64) -> DVec3 {
    DVec3::new(
        ((2 * i + 1) as f64 / LATTICE_W as f64 - 1.0) * 2.0,
        1.0 - (2 * j + 1) as f64 / LATTICE_H as f64,
        z,
    )
}
