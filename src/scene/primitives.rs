//! Generated geometry: the X3D primitives (Box, Sphere, Cone, Cylinder), a torus, and the meshes
//! benchmarks and tests are built from.
//!
//! Guarantees:
//! - every mesh is built in the X3D local frame (centred on the origin, y up; a Cone's apex and a
//!   Cylinder's top at `+height/2`);
//! - every face is counter-clockwise seen from outside, and a mesh with all its parts (a Box, a
//!   Sphere, a torus, a Cone with side and bottom, a Cylinder with side, top and bottom) is closed
//!   and consistently oriented: every edge, by vertex index, is used by exactly two faces in
//!   opposite directions, so its signed volume is positive;
//! - a transform with a negative determinant (a mirror) has every face's winding reversed, so
//!   faces stay counter-clockwise seen from outside after the transform;
//! - nothing is added to the builder when the transform would make a vertex non-finite (the
//!   `add_*` functions then record a warning instead).
//!
//! The surface is kept as quads where it has quads (sphere and torus bands, cylinder side, box
//! sides) and as one polygon per cap. Quads that are not exactly planar once rounded to f64
//! (sphere and torus bands, or anything after a rotation) are split into triangles by
//! [`SceneBuilder::add_face`], keeping one face id per quad.
//!
//! Default resolution ([`DEFAULT_SEGMENTS`] around, [`DEFAULT_RINGS`] from pole to pole) is what
//! the X3D loader uses: a default Sphere has 512 faces (960 triangles) and is within 1.3% of the
//! analytic volume.

use super::{Material, Scene, SceneBuilder};
use glam::{DMat4, DVec3};
use std::f64::consts::TAU;

/// Segments around the y axis of a Sphere, Cone or Cylinder.
pub const DEFAULT_SEGMENTS: usize = 32;
/// Rings (latitude bands) of a Sphere, pole to pole.
pub const DEFAULT_RINGS: usize = 16;

/// Which parts of a Cone or Cylinder to build (X3D `side`, `top`, `bottom`; a Cone has no top).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parts {
    /// The curved side.
    pub side: bool,
    /// The top cap.
    pub top: bool,
    /// The bottom cap.
    pub bottom: bool,
}

impl Parts {
    /// Every part: the closed solid.
    pub const ALL: Parts = Parts {
        side: true,
        top: true,
        bottom: true,
    };
}

/// A polygon mesh in local coordinates, faces counter-clockwise seen from outside.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tessellation {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Vertex indices of all faces, face after face.
    pub corners: Vec<u32>,
    /// End of each face in `corners` (the face starts where the previous one ended).
    pub face_ends: Vec<u32>,
}

/// A transform made some vertex of a generated mesh non-finite.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NonFinite;

impl Tessellation {
    fn vertex(&mut self, p: DVec3) -> u32 {
        self.positions.push(p);
        (self.positions.len() - 1) as u32
    }

    fn face(&mut self, corners: &[u32]) {
        self.corners.extend_from_slice(corners);
        self.face_ends.push(self.corners.len() as u32);
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_ends.len()
    }

    /// The faces, as slices of vertex indices.
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> {
        let mut start = 0usize;
        self.face_ends.iter().map(move |&end| {
            let f = &self.corners[start..end as usize];
            start = end as usize;
            f
        })
    }

    /// Adds the mesh, transformed, to the builder's current mesh. When the transform makes a
    /// vertex non-finite nothing is added. A mirroring transform (negative determinant) reverses
    /// every face so that faces stay counter-clockwise seen from outside.
    pub fn emit(
        &self,
        b: &mut SceneBuilder,
        transform: &DMat4,
        material: u32,
    ) -> Result<(), NonFinite> {
        let world: Vec<DVec3> = self
            .positions
            .iter()
            .map(|&p| transform.transform_point3(p))
            .collect();
        if !world.iter().all(|p| p.is_finite()) {
            return Err(NonFinite);
        }
        let base = b.vertex_count() as u32;
        for p in world {
            b.add_vertex(p);
        }
        let flip = transform.determinant() < 0.0;
        let mut face = Vec::new();
        for f in self.faces() {
            face.clear();
            face.extend(f.iter().map(|&v| v + base));
            if flip {
                face.reverse();
            }
            b.add_face(&face, material);
        }
        Ok(())
    }
}

/// An axis-aligned box centred on the origin: 8 vertices, 6 quads.
pub fn box_mesh(size: DVec3) -> Tessellation {
    let h = size.abs() / 2.0;
    let mut t = Tessellation::default();
    // Vertex k has x = +h.x when bit 0 is set, y when bit 1 is, z when bit 2 is.
    for k in 0..8u32 {
        let s = |bit: u32| if k & bit != 0 { 1.0 } else { -1.0 };
        t.vertex(DVec3::new(s(1) * h.x, s(2) * h.y, s(4) * h.z));
    }
    for f in [
        [5, 1, 3, 7], // +x
        [0, 4, 6, 2], // -x
        [2, 6, 7, 3], // +y
        [0, 1, 5, 4], // -y
        [4, 5, 7, 6], // +z
        [0, 2, 3, 1], // -z
    ] {
        t.face(&f);
    }
    t
}

/// The sine and cosine of `n/d` of a turn, exactly symmetric: the angle is reduced to the first
/// eighth of a turn by exact integer reflections (`a -> 1 - a`, `1/2 - a`, `1/4 - a`) before
/// one `sin_cos`, so points mirrored across an axis or a diagonal of the circle are mirrored
/// exactly, and quarter turns are exactly 0 and ±1. An exact engine then sees a symmetric
/// primitive's symmetric parts coincide exactly (as a cube's faces do).
pub fn turn_sin_cos(n: usize, d: usize) -> (f64, f64) {
    let full = 8 * d;
    let m = (8 * n) % full;
    let (m, sin_sign) = if m > full / 2 {
        (full - m, -1.0)
    } else {
        (m, 1.0)
    };
    let (m, cos_sign) = if m > full / 4 {
        (full / 2 - m, -1.0)
    } else {
        (m, 1.0)
    };
    let (m, swap) = if m > full / 8 {
        (full / 4 - m, true)
    } else {
        (m, false)
    };
    let (s, c) = if m == 0 {
        (0.0, 1.0)
    } else if m == full / 8 {
        (
            std::f64::consts::FRAC_1_SQRT_2,
            std::f64::consts::FRAC_1_SQRT_2,
        )
    } else {
        (TAU * m as f64 / full as f64).sin_cos()
    };
    let (s, c) = if swap { (c, s) } else { (s, c) };
    // No negative zeros: a mirrored zero is the same coordinate.
    let signed = |v: f64, sign: f64| if v == 0.0 { 0.0 } else { sign * v };
    (signed(s, sin_sign), signed(c, cos_sign))
}

/// A quarter turn about the x axis (y to z), exactly: `DMat4::from_rotation_x(PI / 2)` has
/// cos(PI / 2) = 6e-17 where this has 0.
pub fn quarter_turn_x() -> DMat4 {
    DMat4::from_cols(
        glam::DVec4::new(1.0, 0.0, 0.0, 0.0),
        glam::DVec4::new(0.0, 0.0, 1.0, 0.0),
        glam::DVec4::new(0.0, -1.0, 0.0, 0.0),
        glam::DVec4::new(0.0, 0.0, 0.0, 1.0),
    )
}

/// The ring point at angle index `j` of `segments`: angle 0 on +x, increasing towards -z, so
/// that increasing `j` runs left to right seen from outside (y up).
fn ring_point(radius: f64, y: f64, j: usize, segments: usize) -> DVec3 {
    let (s, c) = turn_sin_cos(j, segments);
    DVec3::new(radius * c, y, -radius * s)
}

/// A UV sphere: `segments` (at least 3) around the y axis, `rings` (at least 2) bands from pole
/// to pole; triangles at the poles, quads between.
pub fn sphere_mesh(radius: f64, segments: usize, rings: usize) -> Tessellation {
    let (r, s, n) = (radius.abs(), segments.max(3), rings.max(2));
    let mut t = Tessellation::default();
    let north = t.vertex(DVec3::new(0.0, r, 0.0));
    // Ring i (1..n) starts at vertex 1 + (i - 1) * s.
    for i in 1..n {
        let (sp, cp) = turn_sin_cos(i, 2 * n);
        for j in 0..s {
            t.vertex(ring_point(r * sp, r * cp, j, s));
        }
    }
    let south = t.vertex(DVec3::new(0.0, -r, 0.0));
    let v = |i: usize, j: usize| (1 + (i - 1) * s + j % s) as u32;
    for j in 0..s {
        t.face(&[v(1, j), v(1, j + 1), north]);
    }
    for i in 1..n - 1 {
        for j in 0..s {
            // Ring i is above ring i + 1: bottom-left, bottom-right, top-right, top-left.
            t.face(&[v(i + 1, j), v(i + 1, j + 1), v(i, j + 1), v(i, j)]);
        }
    }
    for j in 0..s {
        t.face(&[south, v(n - 1, j + 1), v(n - 1, j)]);
    }
    t
}

/// A cone along y: apex at `+height/2`, base disc of `bottom_radius` at `-height/2`; side
/// triangles and one base polygon of `segments` (at least 3) corners. A Cone has no top: only
/// `parts.side` and `parts.bottom` are looked at.
pub fn cone_mesh(bottom_radius: f64, height: f64, segments: usize, parts: Parts) -> Tessellation {
    let (r, h, s) = (bottom_radius.abs(), height.abs(), segments.max(3));
    let mut t = Tessellation::default();
    for j in 0..s {
        t.vertex(ring_point(r, -h / 2.0, j, s));
    }
    if parts.side {
        let apex = t.vertex(DVec3::new(0.0, h / 2.0, 0.0));
        for j in 0..s {
            t.face(&[j as u32, ((j + 1) % s) as u32, apex]);
        }
    }
    if parts.bottom {
        let base: Vec<u32> = (0..s as u32).rev().collect();
        t.face(&base);
    }
    t
}

/// A cylinder along y from `-height/2` to `+height/2`: side quads and one polygon per cap, with
/// `segments` (at least 3) around.
pub fn cylinder_mesh(radius: f64, height: f64, segments: usize, parts: Parts) -> Tessellation {
    let (r, h, s) = (radius.abs(), height.abs(), segments.max(3));
    let mut t = Tessellation::default();
    // Bottom ring is vertices 0..s, top ring s..2s.
    for y in [-h / 2.0, h / 2.0] {
        for j in 0..s {
            t.vertex(ring_point(r, y, j, s));
        }
    }
    let bottom = |j: usize| (j % s) as u32;
    let top = |j: usize| (s + j % s) as u32;
    if parts.side {
        for j in 0..s {
            t.face(&[bottom(j), bottom(j + 1), top(j + 1), top(j)]);
        }
    }
    if parts.top {
        let cap: Vec<u32> = (0..s).map(top).collect();
        t.face(&cap);
    }
    if parts.bottom {
        let cap: Vec<u32> = (0..s).rev().map(bottom).collect();
        t.face(&cap);
    }
    t
}

/// A torus around the y axis: tube centre circle of radius `major` in the xz plane, tube radius
/// `minor`; `segments` (at least 3) around y, `sides` (at least 3) around the tube; all quads.
pub fn torus_mesh(major: f64, minor: f64, segments: usize, sides: usize) -> Tessellation {
    let (big, small) = (major.abs(), minor.abs());
    let (s, k) = (segments.max(3), sides.max(3));
    let mut t = Tessellation::default();
    for j in 0..s {
        let (st, ct) = turn_sin_cos(j, s);
        for i in 0..k {
            let (sp, cp) = turn_sin_cos(i, k);
            let rho = big + small * cp;
            t.vertex(DVec3::new(rho * ct, small * sp, -rho * st));
        }
    }
    let v = |j: usize, i: usize| ((j % s) * k + i % k) as u32;
    for j in 0..s {
        for i in 0..k {
            // j runs left to right seen from outside, i upwards on the outer equator.
            t.face(&[v(j, i), v(j + 1, i), v(j + 1, i + 1), v(j, i + 1)]);
        }
    }
    t
}

fn add(b: &mut SceneBuilder, t: Tessellation, transform: &DMat4, material: u32, what: &str) {
    if t.emit(b, transform, material).is_err() {
        b.warn(format!(
            "{what}: the transform makes a vertex non-finite; nothing added"
        ));
    }
}

/// Adds a box of the given size (centred on the transform's origin) to the current mesh.
pub fn add_box(b: &mut SceneBuilder, transform: &DMat4, size: DVec3, material: u32) {
    add(b, box_mesh(size), transform, material, "box");
}

/// Adds a UV sphere to the current mesh; see [`sphere_mesh`].
pub fn add_sphere(
    b: &mut SceneBuilder,
    transform: &DMat4,
    radius: f64,
    segments: usize,
    rings: usize,
    material: u32,
) {
    add(
        b,
        sphere_mesh(radius, segments, rings),
        transform,
        material,
        "sphere",
    );
}

/// Adds a cone to the current mesh; see [`cone_mesh`].
pub fn add_cone(
    b: &mut SceneBuilder,
    transform: &DMat4,
    bottom_radius: f64,
    height: f64,
    segments: usize,
    parts: Parts,
    material: u32,
) {
    let t = cone_mesh(bottom_radius, height, segments, parts);
    add(b, t, transform, material, "cone");
}

/// Adds a cylinder to the current mesh; see [`cylinder_mesh`].
pub fn add_cylinder(
    b: &mut SceneBuilder,
    transform: &DMat4,
    radius: f64,
    height: f64,
    segments: usize,
    parts: Parts,
    material: u32,
) {
    let t = cylinder_mesh(radius, height, segments, parts);
    add(b, t, transform, material, "cylinder");
}

/// Adds a closed, outward-facing torus to the current mesh; see [`torus_mesh`].
pub fn torus(
    b: &mut SceneBuilder,
    transform: &DMat4,
    major: f64,
    minor: f64,
    segments: usize,
    sides: usize,
    material: u32,
) {
    let t = torus_mesh(major, minor, segments, sides);
    add(b, t, transform, material, "torus");
}

/// Segments and rings of the UV sphere [`sphere_scene`] builds for about `triangles` triangles:
/// a sphere of `s` segments and `n` rings has exactly `2·s·(n-1)` triangles; segments are kept
/// near twice the rings so the quads are close to square at the equator.
pub fn sphere_scene_resolution(triangles: usize) -> (usize, usize) {
    let t = triangles.max(1) as f64;
    // 2·s·(n-1) with s = 2n gives 4n(n-1) ≈ t.
    let n = ((0.5 + (0.25 + t / 4.0).sqrt()).round() as usize).max(2);
    let s = ((t / (2.0 * (n - 1) as f64)).round() as usize).max(3);
    (s, n)
}

/// A closed UV sphere of unit radius at the origin made of about `triangles` triangles (exactly
/// `2·s·(n-1)` for the resolution [`sphere_scene_resolution`] picks; the scene's face count
/// tells). Every face is a triangle: the band quads are split in two. One mesh, default material.
pub fn sphere_scene(triangles: usize) -> Scene {
    uv_sphere_triangles(&format!("sphere_scene({triangles})"), triangles, true)
}

/// The sphere of [`sphere_scene`] as many tools export it, and as the benchmark scenes of
/// `../shared/compare/scenes.py` write it: without the triangle fans at the poles (so open) and
/// wound inwards (inside out). An open mesh of a single orientation seen from the inside: its
/// back faces cannot be culled, and the near half is clockwise on screen.
pub fn exported_sphere_scene(triangles: usize) -> Scene {
    uv_sphere_triangles(
        &format!("exported_sphere_scene({triangles})"),
        triangles,
        false,
    )
}

/// The triangles of the UV sphere of about `triangles` triangles: closed and wound outwards, or
/// without the pole fans and wound inwards.
fn uv_sphere_triangles(name: &str, triangles: usize, closed_outwards: bool) -> Scene {
    let (s, n) = sphere_scene_resolution(triangles);
    let t = sphere_mesh(1.0, s, n);
    let mut b = SceneBuilder::new(name);
    b.begin_mesh("sphere");
    let m = b.default_material();
    for p in &t.positions {
        b.add_vertex(*p);
    }
    let mut add = |[a, b_, c]: [u32; 3]| {
        let f = if closed_outwards {
            [a, b_, c]
        } else {
            [a, c, b_]
        };
        b.add_face(&f, m);
    };
    for f in t.faces() {
        if f.len() == 4 {
            add([f[0], f[1], f[2]]);
            add([f[0], f[2], f[3]]);
        } else if closed_outwards {
            add([f[0], f[1], f[2]]);
        }
    }
    b.finish().unwrap_or_default()
}

/// A UV sphere of unit radius (`segments` x `rings`) with every fourth face left out: an open
/// mesh full of holes, so its back faces are kept (no closed mesh to cull) and are seen through
/// the holes. One mesh, default material; quads stay quads.
pub fn holed_sphere_scene(segments: usize, rings: usize) -> Scene {
    let t = sphere_mesh(1.0, segments, rings);
    let mut b = SceneBuilder::new(&format!("holed_sphere_scene({segments}, {rings})"));
    b.begin_mesh("holed sphere");
    let m = b.default_material();
    for p in &t.positions {
        b.add_vertex(*p);
    }
    for (k, f) in t.faces().enumerate() {
        if k % 4 != 1 {
            b.add_face(f, m);
        }
    }
    b.finish().unwrap_or_default()
}

/// SplitMix64: a tiny deterministic generator, enough for benchmark geometry and test data;
/// the number is the seed.
pub(crate) struct SplitMix64(pub(crate) u64);

impl SplitMix64 {
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1), 53 bits.
    pub(crate) fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// Two closed tori linked like chain links (each passes through the other's hole), each a mesh
/// of its own: `segments` around the ring, `sides` around the tube. Their surfaces do not touch,
/// but no plane separates them: a visibility method must split to order them.
pub fn interlocked_tori(segments: usize, sides: usize) -> Scene {
    let mut b = SceneBuilder::new("interlocked_tori");
    let m = b.default_material();
    b.begin_mesh("torus a");
    torus(&mut b, &DMat4::IDENTITY, 1.0, 0.3, segments, sides, m);
    b.begin_mesh("torus b");
    let t = DMat4::from_translation(DVec3::new(1.0, 0.0, 0.0))
        * DMat4::from_rotation_x(std::f64::consts::FRAC_PI_2);
    torus(&mut b, &t, 1.0, 0.3, segments, sides, m);
    b.finish().expect("two tori have faces")
}

/// Two closed tori whose surfaces cut through each other: the second is the first turned a
/// quarter about the x axis and shifted by half a tube radius, so every ring crosses the other
/// tube. Each a mesh of its own; the visible set must follow the curves where they meet.
pub fn interpenetrating_tori(segments: usize, sides: usize) -> Scene {
    let mut b = SceneBuilder::new("interpenetrating_tori");
    let m = b.default_material();
    b.begin_mesh("torus a");
    torus(&mut b, &DMat4::IDENTITY, 1.0, 0.3, segments, sides, m);
    b.begin_mesh("torus b");
    let t = DMat4::from_translation(DVec3::new(0.15, 0.0, 0.0))
        * DMat4::from_rotation_x(std::f64::consts::FRAC_PI_2);
    torus(&mut b, &t, 1.0, 0.3, segments, sides, m);
    b.finish().expect("two tori have faces")
}

/// `count` independent triangles whose corners are uniform in the unit cube [0,1)³, from a
/// deterministic generator seeded by `seed`. One mesh with a two-sided material (a soup has no
/// inside, so no face is back-face culled). Degenerate triangles (vanishingly rare) are dropped
/// by the builder, so the face count can be below `count`; `count == 0` gives an empty scene.
pub fn random_triangle_soup(count: usize, seed: u64) -> Scene {
    let name = format!("random_triangle_soup({count}, {seed})");
    let mut rng = SplitMix64(seed);
    let mut b = SceneBuilder::new(&name);
    b.begin_mesh("soup");
    let m = b.add_material(Material {
        name: "soup".into(),
        two_sided: true,
        ..Material::default()
    });
    for _ in 0..count {
        let mut tri = [0u32; 3];
        for v in &mut tri {
            let p = DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64());
            *v = b.add_vertex(p);
        }
        b.add_face(&tri, m);
    }
    b.finish().unwrap_or_else(|| Scene {
        source: name,
        ..Scene::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn turns_are_exactly_symmetric_and_quarter_turns_exact() {
        for d in [3, 4, 7, 8, 12, 14, 40, 41] {
            for n in 0..d {
                let (s, c) = turn_sin_cos(n, d);
                let (ms, mc) = turn_sin_cos(d - n, d);
                assert_eq!((s, c), (-ms + 0.0, mc), "{n}/{d} mirrored");
                let want = (std::f64::consts::TAU * n as f64 / d as f64).sin_cos();
                assert!((s - want.0).abs() < 2e-15 && (c - want.1).abs() < 2e-15);
                if 2 * n <= d {
                    // Across the y axis: the half turn minus the angle.
                    if d % 2 == 0 {
                        assert_eq!(turn_sin_cos(d / 2 - n, d), (s, -c + 0.0));
                    }
                }
            }
            if d % 4 == 0 {
                assert_eq!(turn_sin_cos(d / 4, d), (1.0, 0.0));
                assert_eq!(turn_sin_cos(d / 2, d), (0.0, -1.0));
            }
        }
        let p = quarter_turn_x().transform_point3(DVec3::new(1.0, 2.0, 3.0));
        assert_eq!(p, DVec3::new(1.0, -3.0, 2.0));
        let r = DMat4::from_rotation_x(std::f64::consts::FRAC_PI_2)
            .transform_point3(DVec3::new(1.0, 2.0, 3.0));
        assert!((r - p).length() < 1e-15);
    }

    /// Signed volume and "every directed edge once, its reverse once".
    fn check_closed(t: &Tessellation) -> f64 {
        use std::collections::HashMap;
        let mut edges: HashMap<(u32, u32), usize> = HashMap::new();
        let mut vol = 0.0;
        for f in t.faces() {
            for k in 0..f.len() {
                *edges.entry((f[k], f[(k + 1) % f.len()])).or_default() += 1;
            }
            let p0 = t.positions[f[0] as usize];
            for k in 1..f.len() - 1 {
                let (p1, p2) = (t.positions[f[k] as usize], t.positions[f[k + 1] as usize]);
                vol += p0.dot(p1.cross(p2)) / 6.0;
            }
        }
        for (&(a, b), &n) in &edges {
            assert_eq!(n, 1, "edge {a}->{b} used {n} times");
            assert_eq!(edges.get(&(b, a)), Some(&1), "edge {a}->{b} has no twin");
        }
        vol
    }

    #[test]
    fn meshes_are_closed_and_outward() {
        assert!((check_closed(&box_mesh(DVec3::new(1.0, 2.0, 3.0))) - 6.0).abs() < 1e-12);
        let v = check_closed(&sphere_mesh(1.0, DEFAULT_SEGMENTS, DEFAULT_RINGS));
        assert!((v / (4.0 / 3.0 * PI) - 1.0).abs() < 0.02, "{v}");
        let v = check_closed(&cone_mesh(1.0, 2.0, 64, Parts::ALL));
        assert!((v / (PI * 2.0 / 3.0) - 1.0).abs() < 0.01, "{v}");
        let v = check_closed(&cylinder_mesh(1.0, 2.0, 64, Parts::ALL));
        assert!((v / (PI * 2.0) - 1.0).abs() < 0.01, "{v}");
        let v = check_closed(&torus_mesh(2.0, 0.5, 64, 32));
        assert!((v / (2.0 * PI * PI * 2.0 * 0.25) - 1.0).abs() < 0.01, "{v}");
    }

    #[test]
    fn resolution_is_close_to_requested() {
        for t in [1, 10, 100, 960, 1000, 10_000, 123_456, 1_000_000] {
            let (s, n) = sphere_scene_resolution(t);
            let got = 2 * s * (n - 1);
            if t >= 100 {
                assert!((got as f64 / t as f64 - 1.0).abs() < 0.05, "{t}: {got}");
            }
        }
    }

    #[test]
    fn soup_is_deterministic() {
        let a = random_triangle_soup(100, 7);
        let b = random_triangle_soup(100, 7);
        assert_eq!(a.positions, b.positions);
        assert_eq!(a.faces.len(), 100);
        assert!(random_triangle_soup(0, 1).faces.is_empty());
    }
}
