//! The lighting model of seed 004 and the shaded image of a z-buffer.
//!
//! `I = emissive + base · (Ia·Ka + Σⱼ Iⱼ·Kd·max(N·Lⱼ, 0)) + Σⱼ Iⱼ·Ks·max(R·S, 0)ⁿ`, per RGB channel,
//! clamped to [0, 1] once at the end; `base` is the material's diffuse colour times the texture
//! colour when the face has one. N is turned to face the viewer first (open and two-sided
//! surfaces are lit on the side that is seen, as [`super::shade`] does), R is L mirrored about N,
//! S points to the eye. Lights add linearly (seed 004).
//!
//! The lights ([`Lighting::of_scene`]): the camera's (by default a key light from above left
//! and a weak fill from the right, [`KEY`] and [`FILL`], given in the camera's frame so that
//! every view shows the form; or the seed's headlight; or none, see [`CameraLights`]), then the
//! scene's lights fixed in the world.
//!
//! Shading (the same pixel always gets the same colour whatever the order faces are drawn in):
//! - **Flat**: the model at the face's centroid with the face normal: one colour per face (times
//!   the texture); ambient + diffuse only (the seed's "tonalização constante") unless Ks > 0,
//!   then the centroid's highlight too (SVG fills use the same, [`Lighting::flat_color`]). With
//!   the scene's lights and Ks = 0 it equals [`super::shade::flat_color`].
//! - **Gouraud**: ambient + diffuse + specular evaluated at the corners with the vertex normals,
//!   then the light terms interpolated perspective-correctly to the pixel.
//! - **Phong**: the vertex normals interpolated (perspective-correctly) and renormalized, the
//!   model evaluated at the pixel's 3D point.
//!
//! Vertex normals ([`vertex_normals`]): the file's normal at a corner when it gives one; otherwise
//! the area-weighted mean of the normals of the faces of the same mesh that share the corner's
//! position and bend from this face by at most [`CREASE_DEGREES`]. So a tessellated sphere is
//! smooth, while a CAD-like box (90° edges) stays flat, with no smoothing flags needed.

use super::EMPTY;
use super::interpolate::{FaceHit, blend, hit_face, weights_in};
use super::texture::Mipmap;
use super::zbuffer::ZBuffer;
use crate::camera::Camera;
use crate::project::ScreenScene;
use crate::scene::Scene;
use glam::{DMat4, DVec3};
use std::collections::HashMap;

/// Faces meeting at a position are smoothed together when their normals differ by at most this.
pub const CREASE_DEGREES: f64 = 60.0;

pub use crate::scene::{CameraLights, Light};

/// A light attached to the camera: the direction towards it in the camera's frame (right, up,
/// towards the viewer; unit length) and its white intensity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraLight {
    pub towards: [f64; 3],
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
            ambient: super::shade::AMBIENT,
            diffuse: super::shade::DIFFUSE,
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
            ambient: super::shade::AMBIENT,
            diffuse: super::shade::DIFFUSE,
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
    fn flat_terms(
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

fn combine(base: [f64; 3], emissive: [f64; 3], lit: [f64; 3], spec: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|k| (emissive[k] + base[k] * lit[k] + spec[k]).clamp(0.0, 1.0))
}

/// How light is interpolated across a face.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Shading {
    #[default]
    Flat,
    Gouraud,
    Phong,
}

/// Unit vertex normal at every entry of `scene.corners` (see the module docs for the rule).
pub fn vertex_normals(scene: &Scene) -> Vec<DVec3> {
    let unit: Vec<DVec3> = scene
        .faces
        .iter()
        .map(|f| scene.face_normal(f).normalize_or_zero())
        .collect();
    // (mesh, position bits) -> faces with a corner there.
    let mut at: HashMap<(u32, [u64; 3]), Vec<u32>> = HashMap::new();
    let key = |mesh: u32, v: u32| {
        (
            mesh,
            scene.positions[v as usize].to_array().map(f64::to_bits),
        )
    };
    for (fi, f) in scene.faces.iter().enumerate() {
        for &v in scene.face_corners(f) {
            let list = at.entry(key(f.mesh, v)).or_default();
            if list.last() != Some(&(fi as u32)) {
                list.push(fi as u32);
            }
        }
    }
    let cos_crease = CREASE_DEGREES.to_radians().cos();
    let mut out = Vec::with_capacity(scene.corners.len());
    for (fi, f) in scene.faces.iter().enumerate() {
        for (k, &v) in scene.face_corners(f).iter().enumerate() {
            let given = scene
                .corner_normals
                .get(f.start as usize + k)
                .copied()
                .flatten()
                .map(DVec3::normalize_or_zero)
                .filter(|n| *n != DVec3::ZERO);
            let n = given.unwrap_or_else(|| {
                let mut sum = DVec3::ZERO;
                for &g in &at[&key(f.mesh, v)] {
                    // Newell normals are twice the area long: the sum is area-weighted. Faces
                    // wound the other way (soups) count with their normal flipped.
                    let d = unit[g as usize].dot(unit[fi]);
                    if d.abs() >= cos_crease {
                        sum += scene.face_normal(&scene.faces[g as usize]) * d.signum();
                    }
                }
                let s = sum.normalize_or_zero();
                if s == DVec3::ZERO { unit[fi] } else { s }
            });
            out.push(n);
        }
    }
    out
}

/// The textures of a scene's materials, read once.
#[derive(Clone, Debug, Default)]
pub struct Textures {
    /// Indexed like `scene.materials`.
    pub by_material: Vec<Option<Mipmap>>,
    /// Textures that could not be read (the face is drawn untextured).
    pub warnings: Vec<String>,
}

impl Textures {
    /// Reads every material's texture; a missing or unreadable image is a warning.
    pub fn load(scene: &Scene) -> Textures {
        let mut t = Textures::default();
        for m in 0..scene.materials.len() {
            let mip = scene
                .texture_of(m as u32)
                .and_then(|p| match Mipmap::load(p) {
                    Ok(mip) => Some(mip),
                    Err(e) => {
                        t.warnings.push(e);
                        None
                    }
                });
            t.by_material.push(mip);
        }
        t
    }
}

/// The world-space ray through pixel (i, j) (any real i, j: the centre is at i + 0.5).
struct Rays {
    inv: DMat4,
    w: f64,
    h: f64,
}

impl Rays {
    fn new(camera: &Camera) -> Rays {
        Rays {
            inv: camera.view_projection().inverse(),
            w: camera.width as f64,
            h: camera.height as f64,
        }
    }

    fn through(&self, i: f64, j: f64) -> (DVec3, DVec3) {
        let x = 2.0 * (i + 0.5) / self.w - 1.0;
        let y = 1.0 - 2.0 * (j + 0.5) / self.h;
        let a = self.inv.project_point3(DVec3::new(x, y, -1.0));
        let b = self.inv.project_point3(DVec3::new(x, y, 1.0));
        (a, b - a)
    }
}

/// The shaded image of a z-buffer (linear RGB in [0, 1], row-major, row 0 at the top): at every
/// pixel the winning polygon's input face is hit by the ray through the pixel centre, and the
/// colour follows `shading` (see the module docs), textured where the face's material has a
/// texture and the face has texture coordinates (level of detail from the (u, v) of the rays
/// through the next pixel right and the next pixel down, on the same face plane).
#[allow(clippy::too_many_arguments)]
pub fn shade_zbuffer(
    scene: &Scene,
    screen: &ScreenScene,
    zb: &ZBuffer,
    camera: &Camera,
    lighting: &Lighting,
    shading: Shading,
    textures: &Textures,
    background: [f64; 3],
) -> Vec<[f64; 3]> {
    shade_polys(
        scene, screen, &zb.poly, zb.width, camera, lighting, shading, textures, background,
    )
}

/// [`shade_zbuffer`] for any per-pixel polygon index (row-major, `width` wide, [`EMPTY`] for
/// background): the scanline's and Warnock's results shade the same way.
#[allow(clippy::too_many_arguments)]
pub fn shade_polys(
    scene: &Scene,
    screen: &ScreenScene,
    poly: &[u32],
    width: u32,
    camera: &Camera,
    lighting: &Lighting,
    shading: Shading,
    textures: &Textures,
    background: [f64; 3],
) -> Vec<[f64; 3]> {
    let normals = match shading {
        Shading::Flat => Vec::new(),
        _ => vertex_normals(scene),
    };
    let rays = Rays::new(camera);
    let eye = camera.eye;
    // Per face, computed on first use: flat light terms.
    let mut flat: HashMap<u32, ([f64; 3], [f64; 3])> = HashMap::new();
    let w = width as usize;
    let mut pts: Vec<DVec3> = Vec::new();
    poly.iter()
        .enumerate()
        .map(|(idx, &p)| {
            if p == EMPTY {
                return background;
            }
            let fi = screen.polys[p as usize].face;
            let f = &scene.faces[fi as usize];
            let m = &scene.materials[f.material as usize];
            pts.clear();
            pts.extend(scene.face_positions(f));
            let n = scene.face_normal(f);
            let (i, j) = ((idx % w) as f64, (idx / w) as f64);
            let (o, d) = rays.through(i, j);
            let Some(hit) = hit_face(&pts, n, o, d) else {
                // Seen edge-on: no interior point to shade; the flat colour is the honest one.
                let (lit, spec) = *flat
                    .entry(fi)
                    .or_insert_with(|| lighting.flat_terms(pts.iter().copied(), n, eye));
                return combine(m.diffuse, m.emissive, lit, spec);
            };
            let base = textured_base(scene, f, m.diffuse, textures, &pts, n, &hit, &rays, i, j);
            let (lit, spec) = match shading {
                Shading::Flat => *flat
                    .entry(fi)
                    .or_insert_with(|| lighting.flat_terms(pts.iter().copied(), n, eye)),
                Shading::Gouraud => {
                    let c = hit.corners;
                    let t = c.map(|k| {
                        let (l, s) =
                            lighting.terms_on(normals[f.start as usize + k], n, pts[k], eye, true);
                        (l, s)
                    });
                    (
                        blend(hit.weights, [t[0].0, t[1].0, t[2].0]),
                        blend(hit.weights, [t[0].1, t[1].1, t[2].1]),
                    )
                }
                Shading::Phong => {
                    let c = hit
                        .corners
                        .map(|k| normals[f.start as usize + k].to_array());
                    let nn = DVec3::from_array(blend(hit.weights, c));
                    lighting.terms_on(nn, n, hit.point, eye, true)
                }
            };
            combine(base, m.emissive, lit, spec)
        })
        .collect()
}

/// The material's diffuse colour times the texture at the hit, if there is one.
#[allow(clippy::too_many_arguments)]
fn textured_base(
    scene: &Scene,
    f: &crate::scene::Face,
    diffuse: [f64; 3],
    textures: &Textures,
    pts: &[DVec3],
    n: DVec3,
    hit: &FaceHit,
    rays: &Rays,
    i: f64,
    j: f64,
) -> [f64; 3] {
    let Some(Some(mip)) = textures.by_material.get(f.material as usize) else {
        return diffuse;
    };
    let Some(uvs) = scene.face_corner_uvs(f) else {
        return diffuse;
    };
    let tri = hit.corners.map(|k| pts[k]);
    let tuv = hit.corners.map(|k| uvs[k]);
    let uv_at = |hw: [f64; 3]| blend(hw, tuv);
    let uv = uv_at(hit.weights);
    // Neighbour rays on the same plane and fan triangle: the weights extrapolate linearly.
    let uv_next = |di: f64, dj: f64| {
        let (o, d) = rays.through(i + di, j + dj);
        let denom = n.dot(d);
        let t = n.dot(pts[0] - o) / denom;
        uv_at(weights_in(o + d * t, tri, n))
    };
    let (ux, uy) = (uv_next(1.0, 0.0), uv_next(0.0, 1.0));
    let lod = mip.lod(ux[0] - uv[0], ux[1] - uv[1], uy[0] - uv[0], uy[1] - uv[1]);
    let t = mip.trilinear(uv[0], uv[1], lod);
    std::array::from_fn(|k| diffuse[k] * t[k])
}
