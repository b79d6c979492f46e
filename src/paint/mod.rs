//! Colour and paint: what every method, object-space or image-space, fills a face with. A leaf
//! of the crate (it depends on the scene and the camera only), so that visibility strategies
//! and renderers colour faces alike without depending on each other.
//!
//! Flat fills and id colours. A face's flat colour is the seed 004 model ([`lighting`])
//! at its centroid with its normal turned towards the viewer (open and two-sided surfaces are
//! lit on the side that is seen). With directional lights only and no specular (the default:
//! the camera's key and fill) that is `emissive + diffuse·(Ka + Σ Kd·I·max(N·L, 0))`: coplanar
//! faces get exactly the same colour whatever their size or place.

pub mod lighting;

use crate::camera::Camera;
use crate::scene::Scene;

/// How pixels are coloured.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Fill {
    /// Flat shading under the scene's lights (by default the camera's key and fill lights).
    #[default]
    Shade,
    /// Face id + 1 as 24-bit RGB on black: the contract used to compare methods.
    Id,
}

/// Ambient coefficient.
pub const AMBIENT: f64 = 0.2;
/// Diffuse (Lambert) coefficient Kd of every light.
pub const DIFFUSE: f64 = 0.8;

/// Flat colour (linear RGB, clamped to \[0,1\]) of `scene.faces[face]` seen by `camera`, under
/// the scene's lights: the lighting model at the face's centroid ([`Lighting::flat_color`]),
/// the one model every method fills faces with.
///
/// [`Lighting::flat_color`]: lighting::Lighting::flat_color
pub fn flat_color(scene: &Scene, face: usize, camera: &Camera) -> [f64; 3] {
    lighting::Lighting::of_scene(scene, camera).flat_color(scene, &scene.faces[face], camera.eye)
}

/// The colour and the transparency (in [0, 1]) every method gives `scene.faces[face]`: its flat
/// colour and its material's transparency, or with `Fill::Id` its id label, opaque (blending
/// labels would show ids that do not exist).
pub fn face_paint(scene: &Scene, face: usize, camera: &Camera, fill: Fill) -> ([f64; 3], f64) {
    match fill {
        Fill::Shade => {
            let m = &scene.materials[scene.faces[face].material as usize];
            (
                flat_color(scene, face, camera),
                m.transparency.clamp(0.0, 1.0),
            )
        }
        Fill::Id => (
            id_color(scene.faces[face].id).map(|c| c as f64 / 255.0),
            0.0,
        ),
    }
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

/// Linear \[0,1\] to 8-bit, rounded.
pub fn to_u8(c: [f64; 3]) -> [u8; 3] {
    c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
}
