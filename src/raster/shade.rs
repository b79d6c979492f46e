//! Flat shading with a headlight (seed 004): `I = emissive + diffuse·(ka + kd·|N·L|)`, with L the
//! direction the camera looks from (a directional light over the viewer's shoulder), so coplanar
//! faces get exactly the same shade whatever their size or place. The absolute value lights faces
//! seen from behind (open or two-sided surfaces) as their front would be.

use crate::camera::Camera;
use crate::scene::Scene;

/// Ambient coefficient.
pub const AMBIENT: f64 = 0.2;
/// Diffuse (Lambert) coefficient of the headlight.
pub const DIFFUSE: f64 = 0.8;

/// Flat colour (linear RGB, clamped to [0,1]) of `scene.faces[face]` seen by `camera`, under
/// the scene's lights: with the default (the headlight alone, no specular) the formula above;
/// otherwise the full model of [`super::lighting`] at the face's centroid.
pub fn flat_color(scene: &Scene, face: usize, camera: &Camera) -> [f64; 3] {
    let f = &scene.faces[face];
    if scene.lights != crate::scene::SceneLights::default() {
        return super::lighting::Lighting::of_scene(scene, camera).flat_color(scene, f, camera.eye);
    }
    let m = &scene.materials[f.material as usize];
    let n = scene.face_normal(f).normalize_or_zero();
    let light = AMBIENT + DIFFUSE * n.dot(-camera.forward()).abs();
    std::array::from_fn(|k| (m.emissive[k] + m.diffuse[k] * light).clamp(0.0, 1.0))
}

/// The `--fill id` colour of a face id: id + 1 as 24-bit RGB, so black is the background.
pub fn id_color(id: u32) -> [u8; 3] {
    let v = id.wrapping_add(1);
    [(v >> 16) as u8, (v >> 8) as u8, v as u8]
}

/// Inverse of [`id_color`]: `None` for the background.
pub fn id_from_color(c: [u8; 3]) -> Option<u32> {
    let v = (c[0] as u32) << 16 | (c[1] as u32) << 8 | c[2] as u32;
    v.checked_sub(1)
}

/// Linear [0,1] to 8-bit, rounded.
pub fn to_u8(c: [f64; 3]) -> [u8; 3] {
    c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
}
