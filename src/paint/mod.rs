//! Colour and paint: what every method, object-space or image-space, fills a face with. A leaf
//! of the crate (it depends on the scene and the camera only), so that visibility strategies
//! and renderers colour faces alike without depending on each other.
//!
//! Opacity is the one convention: a [`Paint`] has `opacity` in \[0, 1\] (1 = opaque), the
//! material's `1 - transparency`, computed here once; every method (A-buffer blending, drawing
//! items, SVG `fill-opacity`) reads it and none converts back.
//!
//! Flat fills and id colours. A face's flat colour is the seed 004 model ([`lighting`])
//! at its centroid with its normal turned towards the viewer (open and two-sided surfaces are
//! lit on the side that is seen). With directional lights only and no specular (the default:
//! the camera's key and fill) that is `emissive + diffuse·(Ka + Σ Kd·I·max(N·L, 0))`: coplanar
//! faces get exactly the same colour whatever their size or place.

pub mod lighting;

use crate::camera::Camera;
use crate::project::ScreenScene;
use crate::scene::Scene;
use lighting::Lighting;

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
    Lighting::of_scene(scene, camera).flat_color(scene, &scene.faces[face], camera.eye)
}

/// What a face is filled with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Paint {
    /// Linear RGB in \[0, 1\].
    pub color: [f64; 3],
    /// 1 = opaque, 0 = invisible: the material's `1 - transparency`.
    pub opacity: f64,
}

impl Paint {
    /// An opaque paint hides what is behind it; any other blends over it.
    pub fn is_opaque(&self) -> bool {
        self.opacity >= 1.0
    }
}

/// Each screen polygon's paint: its face's flat colour and its material's opacity, or with
/// `Fill::Id` its id label, opaque (blending labels would show ids that do not exist). The
/// lights are set up once.
pub fn screen_paints(
    scene: &Scene,
    screen: &ScreenScene,
    camera: &Camera,
    fill: Fill,
) -> Vec<Paint> {
    use rayon::prelude::*;
    let lighting = Lighting::of_scene(scene, camera);
    (screen.polys.par_iter())
        .map(|p| paint_with(&lighting, scene, p.face as usize, camera, fill))
        .collect()
}

fn paint_with(
    lighting: &Lighting,
    scene: &Scene,
    face: usize,
    camera: &Camera,
    fill: Fill,
) -> Paint {
    let f = &scene.faces[face];
    match fill {
        Fill::Shade => Paint {
            color: lighting.flat_color(scene, f, camera.eye),
            opacity: scene.materials[f.material as usize].opacity(),
        },
        Fill::Id => Paint {
            color: id_color(f.id).map(|c| c as f64 / 255.0),
            opacity: 1.0,
        },
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
