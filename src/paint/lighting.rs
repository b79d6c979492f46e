//! The lighting model of seed 004, shared by every method's colours.
//!
//! `I = emissive + base · (Ia·Ka + Σⱼ Iⱼ·Kd·max(N·Lⱼ, 0)) + Σⱼ Iⱼ·Ks·max(R·S, 0)ⁿ`, per RGB channel,
//! clamped to [0, 1] once at the end; `base` is the material's diffuse colour times the texture
//! colour when the face has one. N is turned to face the viewer first (open and two-sided
//! surfaces are lit on the side that is seen), R is L mirrored about N, S points to the eye.
//! Lights add linearly (seed 004).
//!
//! The lights ([`Lighting::of_scene`]): the camera's (by default a key light from above left
//! and a weak fill from the right, [`KEY`] and [`FILL`], given in the camera's frame so that
//! every view shows the form; or the seed's headlight; or none, see [`CameraLights`]), then the
//! scene's lights fixed in the world. How the model varies across a face (flat, Gouraud, Phong)
//! is the image-space renderers' business (`raster::lighting`); a flat fill is the model at the
//! face's centroid ([`Lighting::flat_color`]).
//!
//! [`CameraLights`]: crate::scene::CameraLights

use crate::camera::Camera;
use crate::scene::Scene;
use glam::DVec3;

pub use crate::scene::{CameraLights, Light};

/// A light attached to the camera: the direction towards it in the camera's frame (right, up,
/// towards the viewer; unit length) and its white intensity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraLight {
    /// Unit direction towards the light: right, up, towards the viewer.
    pub towards: [f64; 3],
    /// White intensity.
    pub intensity: f64,
}

/// The default key light: from above left of the view, at azimuth 320° (40° left of straight
/// up) and 35° above the image plane. Close to matplotlib's `LightSource(azdeg=315,
/// altdeg=45)`, a little lower, so that surfaces facing the viewer are set apart from those
/// turned up (the iso cube's top, left and right faces get three shades, brightest on top).
pub const KEY: CameraLight = CameraLight {
    towards: [-0.5265407845183635, 0.6275068715971329, 0.573576436351046],
    intensity: 0.93,
};

/// The default fill light: weak, from the right and a little below the view (azimuth 99°,
/// altitude 53°), so that faces the key does not reach are still read (with the ambient term)
/// instead of going flat dark.
///
/// With Ka = 0.2 and Kd = 0.8, a face turned to both lights gets at most about 1, what the
/// headlight gives a face seen head-on: a white face does not saturate.
pub const FILL: CameraLight = CameraLight {
    towards: [0.6, -0.1, 0.7937253933193772],
    intensity: 0.3,
};

/// The coefficients and the lights.
#[derive(Clone, Debug, PartialEq)]
pub struct Lighting {
    /// Ia·Ka.
    pub ambient: f64,
    /// Kd.
    pub diffuse: f64,
    /// Ks (white highlights).
    pub specular: f64,
    /// Phong exponent n.
    pub shininess: f64,
    /// The camera's lights in world space (the headlight, or the key and the fill), besides
    /// `lights`: kept apart so the common case needs no allocation.
    pub camera_lights: [Option<Light>; 2],
    /// The lights fixed in the world.
    pub lights: Vec<Light>,
    /// The unit direction towards the viewer when it is the same everywhere (orthographic
    /// cameras); `None`: from each point to the eye (perspective).
    pub view: Option<DVec3>,
}

impl Lighting {
    /// One white directional light along the view direction (the headlight), Ka = 0.2, Kd = 0.8
    /// (the flat renderer's coefficients), Ks = 0.3, n = 32.
    pub fn headlight(camera: &Camera) -> Lighting {
        Lighting {
            ambient: crate::paint::AMBIENT,
            diffuse: crate::paint::DIFFUSE,
            specular: 0.3,
            shininess: 32.0,
            camera_lights: camera_lights(CameraLights::Headlight, camera),
            lights: Vec::new(),
            view: view_of(camera),
        }
    }

    /// The scene's lights (`scene.lights`) as seen by `camera`: the camera's lights, then the
    /// others, Ka and Kd of the flat renderer, the scene's Ks and n.
    pub fn of_scene(scene: &Scene, camera: &Camera) -> Lighting {
        let l = &scene.lights;
        Lighting {
            ambient: crate::paint::AMBIENT,
            diffuse: crate::paint::DIFFUSE,
            specular: l.specular,
            shininess: l.shininess,
            camera_lights: camera_lights(l.camera, camera),
            lights: l.lights.clone(),
            view: view_of(camera),
        }
    }

    /// The flat colour of a face: the model at its centroid with its normal, specular included
    /// when Ks > 0 (seen from the camera's eye).
    pub fn flat_color(&self, scene: &Scene, face: &crate::scene::Face, eye: DVec3) -> [f64; 3] {
        let m = &scene.materials[face.material as usize];
        let (lit, spec) = self.flat_terms(scene.face_positions(face), scene.face_normal(face), eye);
        combine(m.diffuse, m.emissive, lit, spec)
    }

    /// The light terms of flat shading, shared by every flat fill: the model at the centroid of
    /// the face's corners with its normal, the highlight only when Ks > 0.
    pub(crate) fn flat_terms(
        &self,
        corners: impl Iterator<Item = DVec3>,
        normal: DVec3,
        eye: DVec3,
    ) -> ([f64; 3], [f64; 3]) {
        let (sum, k) = corners.fold((DVec3::ZERO, 0usize), |(s, k), p| (s + p, k + 1));
        self.terms(normal, sum / k as f64, eye, self.specular > 0.0)
    }

    /// The light at `point` with normal `normal` seen from `eye`: the factor that multiplies
    /// the base colour (ambient + diffuse) and the specular colour added, per channel. Without
    /// `specular` the second is zero.
    pub fn terms(
        &self,
        normal: DVec3,
        point: DVec3,
        eye: DVec3,
        specular: bool,
    ) -> ([f64; 3], [f64; 3]) {
        self.terms_on(normal, normal, point, eye, specular)
    }

    /// [`Self::terms`] with the side seen decided by the face's geometric normal `face`, not by
    /// the shading normal: an interpolated normal near a silhouette may point slightly away from
    /// the eye, and flipping it there would light the rim as if it faced the light.
    pub fn terms_on(
        &self,
        normal: DVec3,
        face: DVec3,
        point: DVec3,
        eye: DVec3,
        specular: bool,
    ) -> ([f64; 3], [f64; 3]) {
        let s = self
            .view
            .unwrap_or_else(|| (eye - point).normalize_or_zero());
        let mut n = normal.normalize_or_zero();
        if face.dot(s) < 0.0 {
            n = -n;
        }
        let mut lit = [self.ambient; 3];
        let mut spec = [0.0; 3];
        for light in self.camera_lights.iter().flatten().chain(&self.lights) {
            let (l, i) = match *light {
                Light::Directional {
                    direction,
                    intensity,
                } => (-direction.normalize_or_zero(), intensity),
                Light::Point {
                    position,
                    intensity,
                } => ((position - point).normalize_or_zero(), intensity),
            };
            let cos_theta = n.dot(l);
            if cos_theta <= 0.0 {
                continue;
            }
            let r = 2.0 * cos_theta * n - l;
            let cos_alpha = r.dot(s).max(0.0);
            let highlight = if specular {
                self.specular * cos_alpha.powf(self.shininess)
            } else {
                0.0
            };
            for k in 0..3 {
                lit[k] += i[k] * self.diffuse * cos_theta;
                spec[k] += i[k] * highlight;
            }
        }
        (lit, spec)
    }

    /// The full model for a base colour: `emissive + base·lit + spec`, clamped to [0, 1].
    pub fn color(
        &self,
        base: [f64; 3],
        emissive: [f64; 3],
        normal: DVec3,
        point: DVec3,
        eye: DVec3,
        specular: bool,
    ) -> [f64; 3] {
        let (lit, spec) = self.terms(normal, point, eye, specular);
        combine(base, emissive, lit, spec)
    }
}

/// The camera's lights as world-space directional lights.
pub fn camera_lights(which: CameraLights, camera: &Camera) -> [Option<Light>; 2] {
    let white = |direction: DVec3, i: f64| Light::Directional {
        direction,
        intensity: [i; 3],
    };
    let forward = camera.forward();
    match which {
        CameraLights::None => [None, None],
        CameraLights::Headlight => [Some(white(forward, 1.0)), None],
        CameraLights::KeyFill => {
            // The camera's frame: right, up (as seen on the image) and back towards the viewer.
            let right = forward
                .cross(camera.up)
                .try_normalize()
                .unwrap_or_else(|| forward.any_orthonormal_vector());
            let up = right.cross(forward);
            let world = |l: &CameraLight| {
                let [x, y, z] = l.towards;
                // A light travels away from where it is.
                white(-(right * x + up * y - forward * z), l.intensity)
            };
            [Some(world(&KEY)), Some(world(&FILL))]
        }
    }
}

/// The direction towards the viewer when it is the same at every point: orthographic cameras.
fn view_of(camera: &Camera) -> Option<DVec3> {
    match camera.projection {
        crate::camera::Projection::Orthographic { .. } => {
            Some(-camera.forward().normalize_or_zero())
        }
        crate::camera::Projection::Perspective { .. } => None,
    }
}

/// A material's colour under light terms `lit` (ambient + diffuse) and `spec` (highlight), with
/// its emissive colour, clamped once.
pub(crate) fn combine(
    base: [f64; 3],
    emissive: [f64; 3],
    lit: [f64; 3],
    spec: [f64; 3],
) -> [f64; 3] {
    std::array::from_fn(|k| (emissive[k] + base[k] * lit[k] + spec[k]).clamp(0.0, 1.0))
}
