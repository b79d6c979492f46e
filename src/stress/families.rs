//! The stress families: deterministic generators of hard scenes and their cameras.
//!
//! Invariant: [`Family::case`] is a pure function of (family, seed, case index): the same
//! arguments give the same faces, bit for bit, and the same camera. Each case draws its scale
//! parameter log-uniformly from its family's range ([`Family::range`]), so a run of many cases
//! covers every scale of the range; the other choices (counts, directions, projection) are drawn
//! from the same stream. Faces are lists of world points, built into a [`Scene`] by the crate's
//! own [`SceneBuilder`] (which triangulates the polygons its exact test finds non-planar).

use super::rng::Rng;
use crate::camera::{Camera, Projection};
use crate::scene::Scene;
use crate::scene::SceneBuilder;
use glam::{DQuat, DVec3};
use std::f64::consts::{PI, TAU};

/// A family of hard cases (issue 11).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Family {
    /// Two to four large faces crossing at tiny angles.
    Grazing,
    /// Faces stacked a tiny distance apart, slightly turned.
    Stacks,
    /// A small plate just above a big floor, in deep perspective.
    Decals,
    /// A scene and its camera translated far from the origin.
    FarOffsets,
    /// A scene and its camera scaled down.
    Tiny,
    /// Vertices lying on other faces' edges.
    TJunctions,
    /// Long thin triangles crossing each other and a backdrop.
    Needles,
    /// Many triangles through one vertex, nearly coplanar neighbours, a face crossing them.
    Fans,
    /// Faces seen nearly or exactly edge-on.
    EdgeOn,
    /// Faces sharing an edge or a vertex, or with a vertex on another face, not crossing.
    Touching,
    /// Three or more bars overlapping cyclically.
    Cyclic,
}

/// One generated case: a scene (as world polygons) and a camera.
#[derive(Clone, Debug)]
pub struct Case {
    /// What it is, for messages: family, seed, index.
    pub label: String,
    /// Its scale parameter (see [`Family::range`]).
    pub scale: f64,
    /// Its faces: world polygons, counter-clockwise from the front.
    pub faces: Vec<Vec<DVec3>>,
    /// The camera.
    pub camera: Camera,
    /// The seed of its sample points.
    pub stream: u64,
    /// The family, seed and index it was generated from (`None` for a loaded scene).
    pub origin: Option<(Family, u64, u64)>,
}

impl Case {
    /// The scene, built with [`SceneBuilder`] (one mesh, the default material; equal points
    /// share a vertex). `None` when every face is degenerate.
    pub fn scene(&self) -> Option<Scene> {
        let (positions, faces) = self.indexed();
        let mut b = SceneBuilder::new(&self.label);
        let m = b.default_material();
        b.begin_mesh("stress");
        for p in positions {
            b.add_vertex(p);
        }
        for f in &faces {
            b.add_face(f, m);
        }
        b.finish()
    }

    /// The faces over shared vertices: positions, and each face's vertex indices (equal points
    /// share one vertex, so that the same scene written as OBJ and read back is the same).
    pub fn indexed(&self) -> (Vec<DVec3>, Vec<Vec<u32>>) {
        let mut index = std::collections::HashMap::new();
        let mut positions = Vec::new();
        let faces = self
            .faces
            .iter()
            .map(|f| {
                f.iter()
                    .map(|&p| {
                        let key = p.to_array().map(f64::to_bits);
                        *index.entry(key).or_insert_with(|| {
                            positions.push(p);
                            positions.len() as u32 - 1
                        })
                    })
                    .collect()
            })
            .collect();
        (positions, faces)
    }

    /// A case of a loaded scene (every face's corners) seen by `camera`.
    pub fn of_scene(label: &str, scene: &Scene, camera: Camera, stream: u64) -> Case {
        Case {
            label: label.to_string(),
            scale: f64::NAN,
            faces: scene
                .faces
                .iter()
                .map(|f| scene.face_positions(f).collect())
                .collect(),
            camera,
            stream,
            origin: None,
        }
    }
}

impl Family {
    /// Every family, in the order reports list them.
    pub const ALL: [Family; 11] = [
        Family::Grazing,
        Family::Stacks,
        Family::Decals,
        Family::FarOffsets,
        Family::Tiny,
        Family::TJunctions,
        Family::Needles,
        Family::Fans,
        Family::EdgeOn,
        Family::Touching,
        Family::Cyclic,
    ];

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Family::Grazing => "grazing",
            Family::Stacks => "stacks",
            Family::Decals => "decals",
            Family::FarOffsets => "far-offsets",
            Family::Tiny => "tiny",
            Family::TJunctions => "t-junctions",
            Family::Needles => "needles",
            Family::Fans => "fans",
            Family::EdgeOn => "edge-on",
            Family::Touching => "touching",
            Family::Cyclic => "cyclic",
        }
    }

    /// The family called `name`.
    pub fn by_name(name: &str) -> Option<Family> {
        Family::ALL.into_iter().find(|f| f.name() == name)
    }

    /// The range its scale parameter is drawn from (log-uniformly), and what that parameter is.
    pub fn range(self) -> (f64, f64, &'static str) {
        match self {
            Family::Grazing => (1e-12, 1e-3, "crossing angle, rad"),
            Family::Stacks => (1e-12, 1e-5, "gap between faces (faces ~5 across)"),
            Family::Decals => (1e2, 1e6, "far / near"),
            Family::FarOffsets => (1e3, 1e7, "offset of scene and camera"),
            Family::Tiny => (1e-9, 1e-3, "scale of scene and camera"),
            Family::TJunctions => (1e-9, 0.5, "junction's place along the edge"),
            Family::Needles => (1e2, 1e9, "aspect ratio"),
            Family::Fans => (1e-9, 1.0, "apex height over the rim (rim radius 2)"),
            Family::EdgeOn => (1e-12, 1e-2, "tilt from edge-on, rad"),
            Family::Touching => (1e-9, 1.0, "angle between touching faces, rad"),
            Family::Cyclic => (1e-9, 1e-1, "rise of each bar (bars ~2 long)"),
        }
    }

    /// Case `index` of the run seeded `seed`.
    pub fn case(self, seed: u64, index: u64) -> Case {
        let mut rng = Rng::of(&[seed, self as u64, index]);
        let (lo, hi, _) = self.range();
        let scale = rng.log_uniform(lo, hi);
        self.build(rng, scale, seed, index)
    }

    /// Case `index` of the run seeded `seed` with its scale parameter `scale` instead of the one
    /// it draws (everything else as [`Self::case`] draws it): a case at a chosen scale, such as
    /// the ends of the range.
    pub fn case_at(self, seed: u64, index: u64, scale: f64) -> Case {
        let mut rng = Rng::of(&[seed, self as u64, index]);
        rng.next_u64(); // the draw `case` spends on the scale
        self.build(rng, scale, seed, index)
    }

    fn build(self, mut rng: Rng, scale: f64, seed: u64, index: u64) -> Case {
        let rng = &mut rng;
        let (faces, camera) = match self {
            Family::Grazing => grazing(rng, scale),
            Family::Stacks => stacks(rng, scale),
            Family::Decals => decals(rng, scale),
            Family::FarOffsets => far_offset(rng, scale),
            Family::Tiny => tiny(rng, scale),
            Family::TJunctions => t_junctions(rng, scale),
            Family::Needles => needles(rng, scale),
            Family::Fans => fans(rng, scale),
            Family::EdgeOn => edge_on(rng, scale),
            Family::Touching => touching(rng, scale),
            Family::Cyclic => cyclic(rng, scale),
        };
        Case {
            label: format!("{} seed {seed} case {index}", self.name()),
            scale,
            faces,
            camera,
            stream: Rng::of(&[seed, self as u64, index, 1]).next_u64(),
            origin: Some((self, seed, index)),
        }
    }
}

type Faces = Vec<Vec<DVec3>>;

/// Image size of every generated camera.
const SIZE: (u32, u32) = (800, 600);

/// Two unit vectors completing `n` (unit) to an orthonormal basis.
fn basis(n: DVec3) -> (DVec3, DVec3) {
    let u = n.any_orthonormal_vector();
    (u, n.cross(u))
}

/// A unit vector within `max_angle` of `n` (unit), uniformly in angle.
fn near_direction(rng: &mut Rng, n: DVec3, max_angle: f64) -> DVec3 {
    let (u, v) = basis(n);
    let (t, a) = (rng.range(0.0, max_angle), rng.range(0.0, TAU));
    n * t.cos() + (u * a.cos() + v * a.sin()) * t.sin()
}

/// A triangle in the plane through `c` spanned by (u, v): corners at radius `r` from c.
fn disc_triangle(rng: &mut Rng, c: DVec3, u: DVec3, v: DVec3, r: f64) -> Vec<DVec3> {
    let a0 = rng.range(0.0, TAU);
    (0..3)
        .map(|k| {
            let a = a0 + k as f64 * TAU / 3.0;
            c + (u * a.cos() + v * a.sin()) * r
        })
        .collect()
}

/// `p` turned by `angle` about the axis through `c` along `axis` (unit).
fn turn(p: DVec3, c: DVec3, axis: DVec3, angle: f64) -> DVec3 {
    c + DQuat::from_axis_angle(axis, angle) * (p - c)
}

/// A camera at `eye` looking at `target`, perspective (random field of view) or, when
/// `allow_ortho` and one time in four, orthographic showing about `radius` around the target;
/// near and far fitted to the faces.
fn camera(
    rng: &mut Rng,
    eye: DVec3,
    target: DVec3,
    radius: f64,
    allow_ortho: bool,
    faces: &Faces,
) -> Camera {
    let dir = (target - eye).normalize();
    let mut up = rng.unit_vector();
    while up.cross(dir).length() < 0.3 {
        up = rng.unit_vector();
    }
    let projection = if allow_ortho && rng.chance(0.25) {
        Projection::Orthographic {
            height: 2.0 * radius,
        }
    } else {
        Projection::Perspective {
            fovy_deg: rng.range(25.0, 70.0),
        }
    };
    let mut cam = Camera {
        eye,
        target,
        up,
        projection,
        near: 0.1,
        far: 10.0,
        width: SIZE.0,
        height: SIZE.1,
    };
    cam.fit_depth_range(bounds(faces));
    cam
}

fn bounds(faces: &Faces) -> (DVec3, DVec3) {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for p in faces.iter().flatten() {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    (lo, hi)
}

/// A camera looking at the origin from about `distance` along a direction within 60° of `n`.
fn facing(rng: &mut Rng, n: DVec3, distance: f64, faces: &Faces) -> Camera {
    let dir = near_direction(rng, n, PI / 3.0);
    let target = rng.unit_vector() * rng.range(0.0, 0.3);
    camera(rng, dir * distance, target, distance * 0.5, true, faces)
}

/// Two to four large triangles through the origin's neighbourhood, each turned from the first by
/// a multiple of `angle` about an axis in its plane.
fn grazing(rng: &mut Rng, angle: f64) -> (Faces, Camera) {
    let n = rng.unit_vector();
    let faces = grazing_faces(rng, n, angle);
    let cam = facing(rng, n, 4.0, &faces);
    (faces, cam)
}

fn grazing_faces(rng: &mut Rng, n: DVec3, angle: f64) -> Faces {
    let (u, v) = basis(n);
    let count = 2 + rng.below(3);
    (0..count)
        .map(|k| {
            let r = rng.range(2.5, 4.0);
            let tri = disc_triangle(rng, DVec3::ZERO, u, v, r);
            if k == 0 {
                return tri;
            }
            let a = rng.range(0.0, TAU);
            let axis = u * a.cos() + v * a.sin();
            let c = (u * rng.range(-0.5, 0.5)) + (v * rng.range(-0.5, 0.5));
            let by = angle * rng.range(0.5, 3.0) * rng.sign();
            tri.into_iter().map(|p| turn(p, c, axis, by)).collect()
        })
        .collect()
}

/// Three to eight faces `gap` apart along one normal, each turned by up to 20 gaps (radians)
/// about an axis in its plane; half of them quads.
fn stacks(rng: &mut Rng, gap: f64) -> (Faces, Camera) {
    let n = rng.unit_vector();
    let count = 3 + rng.below(6);
    let faces = stack_faces(rng, n, gap, count);
    let cam = facing(rng, n, 5.0, &faces);
    (faces, cam)
}

fn stack_faces(rng: &mut Rng, n: DVec3, gap: f64, count: usize) -> Faces {
    let (u, v) = basis(n);
    (0..count)
        .map(|k| {
            let c = n * (k as f64 * gap * rng.range(0.5, 1.5));
            let face = if rng.chance(0.5) {
                let r = rng.range(2.0, 3.0);
                disc_triangle(rng, c, u, v, r)
            } else {
                let a = rng.range(0.0, PI);
                let (du, dv) = (u * a.cos() + v * a.sin(), v * a.cos() - u * a.sin());
                let (w, h) = (rng.range(1.0, 2.5), rng.range(1.0, 2.5));
                vec![
                    c - du * w - dv * h,
                    c + du * w - dv * h,
                    c + du * w + dv * h,
                    c - du * w + dv * h,
                ]
            };
            let a = rng.range(0.0, TAU);
            let axis = u * a.cos() + v * a.sin();
            let pivot = c + u * rng.range(-1.0, 1.0) + v * rng.range(-1.0, 1.0);
            let by = gap * rng.range(0.0, 20.0) * rng.sign();
            face.into_iter().map(|p| turn(p, pivot, axis, by)).collect()
        })
        .collect()
}

/// A 2 x 2 plate (and up to two smaller ones) a tiny height above a big floor, seen from up to
/// a fifth of the far distance with near 0.01 and far `ratio` times that.
fn decals(rng: &mut Rng, ratio: f64) -> (Faces, Camera) {
    let near = 0.01;
    let far = near * ratio;
    let distance = rng.log_uniform(2.0, (far / 5.0).max(2.0));
    let floor = (distance * 3.0).max(10.0).min(far);
    let mut faces: Faces = vec![vec![
        DVec3::new(-floor, 0.0, -floor),
        DVec3::new(-floor, 0.0, floor),
        DVec3::new(floor, 0.0, floor),
        DVec3::new(floor, 0.0, -floor),
    ]];
    for k in 0..1 + rng.below(3) {
        let size = if k == 0 { 1.0 } else { rng.range(0.1, 0.8) };
        let h = rng.log_uniform(1e-7, 1e-2);
        let c = if k == 0 {
            DVec3::new(0.0, h, 0.0)
        } else {
            DVec3::new(rng.range(-1.5, 1.5), h, rng.range(-1.5, 1.5))
        };
        let a = rng.range(0.0, PI);
        let (du, dv) = (
            DVec3::new(a.cos(), 0.0, a.sin()),
            DVec3::new(-a.sin(), 0.0, a.cos()),
        );
        faces.push(vec![
            c - du * size - dv * size,
            c - du * size + dv * size,
            c + du * size + dv * size,
            c + du * size - dv * size,
        ]);
    }
    let elevation = rng.range(10f64.to_radians(), 80f64.to_radians());
    let azimuth = rng.range(0.0, TAU);
    let dir = DVec3::new(
        elevation.cos() * azimuth.cos(),
        elevation.sin(),
        elevation.cos() * azimuth.sin(),
    );
    let mut cam = camera(rng, dir * distance, DVec3::ZERO, 1.0, false, &faces);
    (cam.near, cam.far) = (near, far);
    if rng.chance(0.5) {
        // Turned as a whole: the plate and the floor are then parallel only to f64 rounding.
        let q = DQuat::from_axis_angle(rng.unit_vector(), rng.range(0.0, PI));
        for p in faces.iter_mut().flatten() {
            *p = q * *p;
        }
        (cam.eye, cam.target, cam.up) = (q * cam.eye, q * cam.target, q * cam.up);
    }
    (faces, cam)
}

/// A scene of everything at unit scale, for translating and scaling: a grazing pair, a short
/// stack and a stray triangle.
fn mixed(rng: &mut Rng) -> (Faces, Camera) {
    let n = rng.unit_vector();
    let angle = rng.log_uniform(1e-8, 1e-2);
    let mut faces = grazing_faces(rng, n, angle);
    faces.truncate(2);
    let m = near_direction(rng, n, 1.0);
    let gap = rng.log_uniform(1e-6, 1e-2);
    faces.extend(stack_faces(rng, m, gap, 3));
    faces.push((0..3).map(|_| rng.unit_vector() * 2.0).collect());
    let cam = facing(rng, n, 5.0, &faces);
    (faces, cam)
}

/// [`mixed`] with the scene and the camera translated by `offset` in a random direction.
fn far_offset(rng: &mut Rng, offset: f64) -> (Faces, Camera) {
    let (mut faces, mut cam) = mixed(rng);
    let t = rng.unit_vector() * offset;
    for p in faces.iter_mut().flatten() {
        *p += t;
    }
    cam.eye += t;
    cam.target += t;
    (faces, cam)
}

/// [`mixed`] with the scene and the camera scaled by `scale`.
fn tiny(rng: &mut Rng, scale: f64) -> (Faces, Camera) {
    let (mut faces, mut cam) = mixed(rng);
    for p in faces.iter_mut().flatten() {
        *p *= scale;
    }
    cam.eye *= scale;
    cam.target *= scale;
    cam.near *= scale;
    cam.far *= scale;
    if let Projection::Orthographic { height } = &mut cam.projection {
        *height *= scale;
    }
    (faces, cam)
}

/// Triangles meeting a big triangle's edge with a vertex on it at `t` (and a second one between
/// that and the far end), folded slightly or not at all, and a triangle crossing behind.
fn t_junctions(rng: &mut Rng, t: f64) -> (Faces, Camera) {
    let n = rng.unit_vector();
    let (u, v) = basis(n);
    let (a, b) = (
        u * -2.0 + v * rng.range(-0.5, 0.5),
        u * 2.0 + v * rng.range(-0.5, 0.5),
    );
    let c = v * 2.5;
    let fold = if rng.chance(0.5) {
        0.0
    } else {
        rng.log_uniform(1e-9, 1e-1) * rng.sign()
    };
    let d = -v * 2.5 + n * fold;
    let m1 = a + (b - a) * t;
    let m2 = m1 + (b - m1) * rng.range(0.2, 0.8);
    let mut faces = vec![
        vec![a, b, c],
        vec![a, d, m1],
        vec![m1, d, m2],
        vec![m2, d, b],
    ];
    let behind = -n * rng.log_uniform(1e-6, 1.0);
    let w = near_direction(rng, v, 0.3);
    faces.push(disc_triangle(rng, behind, u, w, 3.0));
    let cam = facing(rng, n, 5.0, &faces);
    (faces, cam)
}

/// Three to six needles (triangles `aspect` times longer than wide), crossing in depth and
/// piercing a backdrop.
fn needles(rng: &mut Rng, aspect: f64) -> (Faces, Camera) {
    let n = rng.unit_vector();
    let (u, v) = basis(n);
    let mut faces = vec![disc_triangle(rng, DVec3::ZERO, u, v, 3.0)];
    for _ in 0..3 + rng.below(4) {
        let len = rng.range(2.0, 4.0);
        let a = rng.range(0.0, TAU);
        let along = ((u * a.cos() + v * a.sin()) + n * rng.range(-0.5, 0.5)).normalize();
        let start = (u * rng.range(-0.5, 0.5)) + (v * rng.range(-0.5, 0.5)) - along * (len / 2.0);
        let across = along.any_orthonormal_vector();
        let across = DQuat::from_axis_angle(along, rng.range(0.0, TAU)) * across;
        let half = across * (len / aspect / 2.0);
        faces.push(vec![start - half, start + half, start + along * len]);
    }
    let cam = facing(rng, n, 5.0, &faces);
    (faces, cam)
}

/// A fan of 6 to 48 triangles around an apex `height` above its rim (a cone, or a zigzag), and
/// a triangle crossing it near the apex.
fn fans(rng: &mut Rng, height: f64) -> (Faces, Camera) {
    let n = rng.unit_vector();
    let (u, v) = basis(n);
    let count = 6 + rng.below(43);
    let zigzag = rng.chance(0.5);
    let mut angles: Vec<f64> = (0..count).map(|_| rng.range(0.0, TAU)).collect();
    angles.sort_by(f64::total_cmp);
    let rim: Vec<DVec3> = angles
        .iter()
        .enumerate()
        .map(|(k, a)| {
            let lift = if zigzag && k % 2 == 1 { height } else { 0.0 };
            (u * a.cos() + v * a.sin()) * 2.0 + n * (lift - height)
        })
        .collect();
    let mut faces: Faces = (0..count)
        .map(|k| vec![DVec3::ZERO, rim[k], rim[(k + 1) % count]])
        .collect();
    let m = near_direction(rng, n, 1.2);
    let (mu, mv) = basis(m);
    let c = n * rng.range(-0.2, 0.0) * height;
    faces.push(disc_triangle(rng, c, mu, mv, 1.0));
    let cam = facing(rng, n, 5.0, &faces);
    (faces, cam)
}

/// Two to five triangles in planes through the eye (edge-on), each tilted by about `tilt`, with
/// a backdrop behind and a face in front.
fn edge_on(rng: &mut Rng, tilt: f64) -> (Faces, Camera) {
    let dir = rng.unit_vector();
    let distance = 5.0;
    let eye = dir * distance;
    let f = -dir;
    let mut faces: Faces = Vec::new();
    for _ in 0..2 + rng.below(4) {
        let (a, b) = basis(f);
        let s = rng.range(0.0, TAU);
        let side = a * s.cos() + b * s.sin();
        let tri: Vec<DVec3> = (0..3)
            .map(|_| {
                eye + f * rng.range(distance - 2.0, distance + 2.0) + side * rng.range(-1.5, 1.5)
            })
            .collect();
        let c = (tri[0] + tri[1] + tri[2]) / 3.0;
        let by = tilt * rng.range(0.5, 2.0) * rng.sign();
        faces.push(tri.into_iter().map(|p| turn(p, c, side, by)).collect());
    }
    let (a, b) = basis(f);
    faces.push(disc_triangle(rng, f * 1.5, a, b, 3.0));
    faces.push(disc_triangle(rng, -f * 1.0, a, b, 0.8));
    let cam = camera(rng, eye, DVec3::ZERO, 2.5, true, &faces);
    (faces, cam)
}

/// A big triangle in the plane z = 0 (exactly), with a triangle sharing an edge, one sharing a
/// vertex and one with a vertex on its face, each at `angle` from it, none crossing it; seen
/// from above.
fn touching(rng: &mut Rng, angle: f64) -> (Faces, Camera) {
    let z = DVec3::Z;
    let (a, b, c) = (
        DVec3::new(-2.0, -1.5, 0.0),
        DVec3::new(2.0, -1.5, 0.0),
        DVec3::new(0.0, 2.0, 0.0),
    );
    let mut faces = vec![vec![a, b, c]];
    let lift = |d: DVec3, r: f64, over: bool| {
        let s = if over { 1.0 } else { -1.0 };
        d * (angle.cos() * r) + z * (angle.sin() * r) * s
    };
    // Sharing edge b–c: folded back over the face, or going on beyond it.
    let m = (b + c) / 2.0;
    let out = DVec3::new(c.y - b.y, b.x - c.x, 0.0).normalize();
    let over = rng.chance(0.5);
    let dir = if over { -out } else { out };
    faces.push(vec![c, b, m + lift(dir, rng.range(0.5, 2.0), true)]);
    // Sharing vertex a only.
    let d1 = DVec3::new(rng.range(-1.0, 0.0), rng.range(-1.0, 1.0), 0.0).normalize();
    let d2 = DQuat::from_rotation_z(rng.range(0.3, 1.0)) * d1;
    faces.push(vec![a, a + lift(d1, 1.5, true), a + lift(d2, 1.5, true)]);
    // A vertex on the face (exactly: z = 0), rising from it.
    let p = DVec3::new(rng.range(-0.5, 0.5), rng.range(-0.5, 0.5), 0.0);
    let e1 = DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), 0.0).normalize();
    let e2 = DQuat::from_rotation_z(rng.range(0.3, 1.5)) * e1;
    faces.push(vec![p, p + lift(e1, 1.0, true), p + lift(e2, 1.0, true)]);
    let cam = facing(rng, z, 5.0, &faces);
    (faces, cam)
}

/// Three to six bars in a ring, each rising by `rise` from its start to its end, so that each
/// lies over the next at one end and under the one before at the other; seen from above.
fn cyclic(rng: &mut Rng, rise: f64) -> (Faces, Camera) {
    let count = 3 + rng.below(4);
    let r = 1.2;
    let corner = |k: usize| {
        let a = TAU * k as f64 / count as f64;
        DVec3::new(a.cos() * r, a.sin() * r, 0.0)
    };
    let faces: Faces = (0..count)
        .map(|k| {
            let (p, q) = (corner(k), corner(k + 1));
            let e = (q - p).normalize();
            let w = DVec3::new(-e.y, e.x, 0.0) * (0.15 * r);
            let (s, t) = (p - e * (0.35 * r), q + e * (0.35 * r));
            let (s, t) = (s + DVec3::Z * (rise / 2.0), t - DVec3::Z * (rise / 2.0));
            vec![s - w, t - w, t + w, s + w]
        })
        .collect();
    let cam = facing(rng, DVec3::Z, 5.0, &faces);
    (faces, cam)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_case_is_a_function_of_its_seed_and_index() {
        for f in Family::ALL {
            let (a, b, c) = (f.case(7, 3), f.case(7, 3), f.case(7, 4));
            assert_eq!(a.faces, b.faces, "{}", f.name());
            assert_eq!(a.camera, b.camera, "{}", f.name());
            assert_ne!(a.faces, c.faces, "{}", f.name());
            let (lo, hi, _) = f.range();
            assert!(a.scale >= lo && a.scale <= hi, "{}", f.name());
            a.camera.validate().unwrap();
            assert!(a.scene().is_some(), "{}", f.name());
            assert_eq!(Family::by_name(f.name()), Some(f));
            let at = f.case_at(7, 3, a.scale);
            assert_eq!(
                (at.faces, at.camera),
                (a.faces.clone(), a.camera),
                "{}",
                f.name()
            );
        }
    }
}
