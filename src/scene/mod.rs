//! The scene model: meshes of planar polygonal faces, their materials and their provenance.
//!
//! Invariants every `Scene` keeps (the loaders build scenes only through [`SceneBuilder`]):
//! - every face is planar, exactly, in the f64 input coordinates (a non-planar input polygon is
//!   triangulated and each piece keeps the polygon's id);
//! - every face has at least three corners and is not degenerate (its corners are not all
//!   collinear); degenerate input faces are dropped and counted in [`LoadStats`];
//! - a face's id is its index in input order across the whole scene, so ids of dropped faces leave
//!   gaps and the pieces of a triangulated polygon share one id;
//! - every coordinate is finite.

pub mod analysis;
mod builder;
mod input;
pub mod load;
mod mtl;
mod obj;
mod ply;
pub mod primitives;
mod stl;
mod text;
mod x3d;

pub use builder::{CornerAttrs, FaceOutcome, SceneBuilder};
pub use load::{Format, load, load_bytes, load_with_progress};

use glam::DVec3;
use std::ops::Range;
use std::path::PathBuf;

/// Index of an input face, in input order across the whole scene.
pub type FaceId = u32;

/// Surface appearance of a face.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Its name in the file (OBJ `usemtl`), for messages.
    pub name: String,
    /// Lit color (linear RGB in \[0,1\]), scaled by ambient + Lambert terms when shading.
    pub diffuse: [f64; 3],
    /// Unlit color added to the lit one (X3D emissiveColor, OBJ Ke).
    pub emissive: [f64; 3],
    /// 0 = opaque, 1 = invisible.
    pub transparency: f64,
    /// Seen from both sides: never back-face culled.
    pub two_sided: bool,
}

impl Material {
    /// `1 - transparency`, clamped to \[0, 1\]: the one opacity every method blends with
    /// (below 1 the material blends over what lies behind it).
    pub fn opacity(&self) -> f64 {
        1.0 - self.transparency.clamp(0.0, 1.0)
    }
}

impl Default for Material {
    fn default() -> Self {
        Material {
            name: "default".into(),
            diffuse: [0.8, 0.8, 0.8],
            emissive: [0.0; 3],
            transparency: 0.0,
            two_sided: false,
        }
    }
}

/// One planar polygon of the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Face {
    /// Provenance: index of the input face this polygon came from.
    pub id: FaceId,
    /// Index into [`Scene::meshes`].
    pub mesh: u32,
    /// Index into [`Scene::materials`].
    pub material: u32,
    /// Range into [`Scene::corners`].
    pub start: u32,
    /// Number of corners (at least 3).
    pub len: u32,
}

/// A named group of faces loaded together (an OBJ object, an X3D Shape, a whole STL or PLY file).
/// Closedness and orientation are decided per mesh.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Mesh {
    /// Its name for messages and `sightline info`: the OBJ object's, or one made from the file
    /// name or the node.
    pub name: String,
    /// Range into [`Scene::faces`].
    pub faces: Range<usize>,
}

/// A camera stored in the input file (X3D Viewpoint).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viewpoint {
    /// Where the eye is (world space).
    pub position: DVec3,
    /// Rotation of the default view (looking down -z, y up), as a unit axis and an angle in radians.
    pub orientation_axis: DVec3,
    /// The angle of that rotation, radians.
    pub orientation_angle: f64,
    /// X3D fieldOfView: the smaller of the horizontal and vertical angles, radians.
    pub field_of_view: f64,
}

/// What loading noticed but did not refuse.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LoadStats {
    /// Input faces dropped because all their corners were collinear or they had fewer than three
    /// distinct corners.
    pub degenerate_dropped: usize,
    /// Input polygons that were not exactly planar and were triangulated.
    pub nonplanar_triangulated: usize,
    /// What the loader skipped or did not understand, one message each (most name the file and
    /// line).
    pub warnings: Vec<String>,
}

/// A loaded scene. See the module docs for the invariants.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// Name of the source, for messages.
    pub source: String,
    /// Vertex positions (world space), shared by the faces.
    pub positions: Vec<DVec3>,
    /// The planar faces (see the module docs for the invariants).
    pub faces: Vec<Face>,
    /// Vertex indices of all faces, face after face; counter-clockwise seen from the front.
    pub corners: Vec<u32>,
    /// The meshes, each a range of `faces`.
    pub meshes: Vec<Mesh>,
    /// The materials faces refer to by index.
    pub materials: Vec<Material>,
    /// The file's own camera (X3D Viewpoint), if any.
    pub viewpoint: Option<Viewpoint>,
    /// Number of input faces: ids are in `0..input_faces`.
    pub input_faces: u32,
    /// What loading dropped, triangulated or warned about.
    pub stats: LoadStats,
    /// Normals the file gives per face corner (OBJ `vn`, X3D `Normal`), parallel to `corners`;
    /// empty when the file gives none at all, `None` at the corners of faces that have none.
    /// Not normalized. See `raster::lighting::vertex_normals` for what is used instead.
    pub corner_normals: Vec<Option<DVec3>>,
    /// Texture coordinates per face corner (OBJ `vt`, X3D `TextureCoordinate`), parallel to
    /// `corners`; empty when the file gives none, `None` at corners of faces without them.
    pub corner_uvs: Vec<Option<[f64; 2]>>,
    /// Texture image of each material (OBJ `map_Kd`, X3D `ImageTexture`), indexed like
    /// `materials`; a material past its end has none. Paths are resolved against the file's
    /// directory; the image is read only when rendering.
    pub material_textures: Vec<Option<PathBuf>>,
    /// The lights the scene is seen under (`--light`, `--specular`): every shaded method uses
    /// them (see `paint::lighting::Lighting::of_scene`).
    pub lights: SceneLights,
    /// The background colour the file asks for (linear RGB in \[0,1\]): X3D's Background (black by
    /// default); `None` for formats that have no such notion.
    pub background: Option<[f64; 3]>,
}

/// A light source of intensity `intensity` (RGB).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// At infinity; `direction` is where its light travels (need not be unit).
    Directional {
        /// Where the light travels.
        direction: DVec3,
        /// RGB intensity.
        intensity: [f64; 3],
    },
    /// At a point, no attenuation (seed 004's simple model).
    Point {
        /// Where the light is (world space).
        position: DVec3,
        /// RGB intensity.
        intensity: [f64; 3],
    },
}

/// The lights that move with the camera (defined in its frame, so every view is lit alike).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CameraLights {
    /// A key light from above and to the left of the view and a weak fill from the right
    /// (`paint::lighting::KEY` and `FILL`): faces of different directions get different shades,
    /// as in a CAD viewer's or matplotlib's default (`LightSource(azdeg=315, altdeg=45)`).
    #[default]
    KeyFill,
    /// One white light along the view direction (seed 004's and X3D's headlight): every face
    /// seen head-on is equally bright, whatever its direction.
    Headlight,
    /// None: only [`SceneLights::lights`] and the ambient term.
    None,
}

/// How a scene is lit: the seed 004 model's lights and its specular term.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneLights {
    /// The lights attached to the camera.
    pub camera: CameraLights,
    /// Lights fixed in the world, besides the camera's.
    pub lights: Vec<Light>,
    /// Phong specular coefficient Ks (0: none, the default for flat fills).
    pub specular: f64,
    /// Phong exponent n.
    pub shininess: f64,
}

/// The Phong exponent n when none is given.
pub const DEFAULT_SHININESS: f64 = 32.0;

impl Default for SceneLights {
    fn default() -> Self {
        SceneLights {
            camera: CameraLights::KeyFill,
            lights: Vec::new(),
            specular: 0.0,
            shininess: DEFAULT_SHININESS,
        }
    }
}

impl SceneLights {
    /// Checks what a user can get wrong (the messages name the command line's flags): Ks and n
    /// finite and not negative, and every directional light with a direction.
    pub fn check(&self) -> Result<(), crate::Error> {
        let bad = |m: String| Err(crate::Error::Options(m));
        for (flag, v) in [
            ("--specular", self.specular),
            ("--shininess", self.shininess),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(format!("{flag} must be a finite number >= 0, not {v}"));
            }
        }
        let no_direction = |l: &Light| matches!(l, Light::Directional { direction, .. } if *direction == DVec3::ZERO);
        if self.lights.iter().any(no_direction) {
            return bad("--light 0,0,0 has no direction".into());
        }
        Ok(())
    }
}

impl Light {
    /// A white directional light shining from `from` towards the scene (the command line's
    /// `--light X,Y,Z`).
    pub fn white_from(from: DVec3) -> Light {
        Light::Directional {
            direction: -from,
            intensity: [1.0; 3],
        }
    }
}

impl Scene {
    /// The vertex indices of a face.
    #[inline]
    pub fn face_corners(&self, face: &Face) -> &[u32] {
        &self.corners[face.start as usize..(face.start + face.len) as usize]
    }

    /// Iterator over a face's corner positions.
    pub fn face_positions<'a>(&'a self, face: &'a Face) -> impl Iterator<Item = DVec3> + 'a {
        self.face_corners(face)
            .iter()
            .map(move |&v| self.positions[v as usize])
    }

    /// Axis-aligned bounds of the vertices used by faces, or `None` for a scene with no face.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        if self.faces.is_empty() {
            return None;
        }
        let mut used = vec![false; self.positions.len()];
        for &c in &self.corners {
            used[c as usize] = true;
        }
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for (p, _) in self.positions.iter().zip(&used).filter(|(_, u)| **u) {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        Some((lo, hi))
    }

    /// The file's normals at a face's corners, if it gave one at every corner.
    pub fn face_corner_normals(&self, face: &Face) -> Option<Vec<DVec3>> {
        let r = face.start as usize..(face.start + face.len) as usize;
        self.corner_normals.get(r)?.iter().copied().collect()
    }

    /// The texture coordinates at a face's corners, if it has them at every corner.
    pub fn face_corner_uvs(&self, face: &Face) -> Option<Vec<[f64; 2]>> {
        let r = face.start as usize..(face.start + face.len) as usize;
        self.corner_uvs.get(r)?.iter().copied().collect()
    }

    /// The texture image path of a material, if it has one.
    pub fn texture_of(&self, material: u32) -> Option<&std::path::Path> {
        self.material_textures.get(material as usize)?.as_deref()
    }

    /// Newell normal of a face (not normalized; its length is twice the area).
    pub fn face_normal(&self, face: &Face) -> DVec3 {
        newell_normal(self.face_positions(face))
    }
}

/// Newell's normal of a polygon: exact direction for a planar polygon up to rounding, length
/// twice the area.
pub fn newell_normal(points: impl Iterator<Item = DVec3>) -> DVec3 {
    let mut n = DVec3::ZERO;
    let mut it = points.peekable();
    let first = match it.peek() {
        Some(p) => *p,
        None => return n,
    };
    // Centre on the first point to lose less precision far from the origin.
    let pts: Vec<DVec3> = it.map(|p| p - first).collect();
    for i in 0..pts.len() {
        let a = pts[i];
        let b = pts[(i + 1) % pts.len()];
        n.x += (a.y - b.y) * (a.z + b.z);
        n.y += (a.z - b.z) * (a.x + b.x);
        n.z += (a.x - b.x) * (a.y + b.y);
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lights_check_refuses_negative_terms_and_lights_without_direction() {
        let check = |l: SceneLights| l.check().err().map(|e| e.to_string());
        assert_eq!(check(SceneLights::default()), None);
        let lit = SceneLights {
            lights: vec![Light::white_from(DVec3::new(1.0, 2.0, 3.0))],
            specular: 0.5,
            ..SceneLights::default()
        };
        assert_eq!(check(lit), None);
        let dull = SceneLights {
            specular: -1.0,
            ..SceneLights::default()
        };
        assert_eq!(
            check(dull).as_deref(),
            Some("--specular must be a finite number >= 0, not -1")
        );
        let blurred = SceneLights {
            shininess: f64::NAN,
            ..SceneLights::default()
        };
        assert_eq!(
            check(blurred).as_deref(),
            Some("--shininess must be a finite number >= 0, not NaN")
        );
        let nowhere = SceneLights {
            lights: vec![Light::white_from(DVec3::ZERO)],
            ..SceneLights::default()
        };
        assert_eq!(
            check(nowhere).as_deref(),
            Some("--light 0,0,0 has no direction")
        );
    }

    /// `--light X,Y,Z` names where the light comes from: it travels the other way.
    #[test]
    fn a_white_light_from_a_direction_travels_towards_the_scene() {
        assert_eq!(
            Light::white_from(DVec3::new(1.0, 0.0, 0.0)),
            Light::Directional {
                direction: DVec3::new(-1.0, 0.0, 0.0),
                intensity: [1.0; 3],
            }
        );
    }
}
