//! The shaded image of a z-buffer: the lighting model of seed 004 ([`crate::paint::lighting`])
//! across each face.
//!
//! Shading (the same pixel always gets the same colour whatever the order faces are drawn in):
//! - **Flat**: the model at the face's centroid with the face normal: one colour per face (times
//!   the texture); ambient + diffuse only (the seed's "tonalização constante") unless Ks > 0,
//!   then the centroid's highlight too (SVG fills use the same, [`Lighting::flat_color`]). With
//!   the scene's lights and Ks = 0 it equals [`crate::paint::flat_color`].
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
pub use crate::paint::lighting::Lighting;
use crate::paint::lighting::combine;
use crate::project::ScreenScene;
use crate::scene::Scene;
use glam::{DMat4, DVec3};
use std::collections::HashMap;

/// Faces meeting at a position are smoothed together when their normals differ by at most this.
pub const CREASE_DEGREES: f64 = 60.0;

/// How light is interpolated across a face.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Shading {
    /// One colour per face: the model at its centroid.
    #[default]
    Flat,
    /// The model at the corners, interpolated.
    Gouraud,
    /// The normals interpolated, the model at every pixel.
    Phong,
}

impl Shading {
    /// The name the command line gives it (`--shading NAME`).
    pub fn name(self) -> &'static str {
        match self {
            Shading::Flat => "flat",
            Shading::Gouraud => "gouraud",
            Shading::Phong => "phong",
        }
    }
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
