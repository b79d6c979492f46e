//! Random scenes and cameras for the properties. Everything about a case (the scene, the camera,
//! the cull mode) follows from its `Case { kind, n, seed }`, so a failure's minimal case
//! reproduces it; and over a few hundred cases the generators reach the degenerate cases the
//! properties are meant to meet (checked at the end of this file).
//!
//! Scenes: random triangle soups, closed meshes (rotated boxes, low-resolution spheres,
//! tetrahedra) interpenetrating each other, interpenetrating pairs, coplanar overlapping faces
//! (exact: layers on one plane seen along its normal, duplicated faces), meshes sharing edges and
//! vertices (height fields, fans), fans of thin triangles around a hub with faces through it,
//! T-junctions, non-convex (star) polygons, cyclic bars, and mixtures; seen by random perspective
//! and orthographic cameras, some with the eye among the faces (the near plane cuts them), some
//! looking exactly along -z, and an "exact" orthographic camera under which dyadic world
//! coordinates land on the grid without rounding (exact coplanarity, exact T-junctions).

use crate::oracle::{Poly, orient, screen_polys};
use crate::support::camera::look_at;
use crate::support::rng::Rng;
use crate::support::scenes::add_polygon;
use crate::support::strategy::bsp_walk;
use glam::{DMat4, DQuat, DVec3};
use proptest::prelude::*;
use sightline::camera::{Camera, Projection};
use sightline::exact::polygon::same_plane;
use sightline::exact::predicates::Line;
use sightline::pipeline::prepare;
use sightline::project::{CullMode, ScreenScene};
use sightline::scene::{Scene, SceneBuilder, primitives};
use std::cmp::Ordering;
use std::f64::consts::TAU;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Triangles,
    Closed,
    Pairs,
    Coplanar,
    Shared,
    Slivers,
    TJunctions,
    Bars,
    Mixed,
}

pub const KINDS: [Kind; 9] = [
    Kind::Triangles,
    Kind::Closed,
    Kind::Pairs,
    Kind::Coplanar,
    Kind::Shared,
    Kind::Slivers,
    Kind::TJunctions,
    Kind::Bars,
    Kind::Mixed,
];

/// One random case: everything else (the scene, the camera, the cull mode) follows from the seed.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    pub kind: Kind,
    /// Size knob: how many faces or objects the kind makes (shrinks toward small scenes).
    pub n: usize,
    pub seed: u64,
}

pub fn cases() -> impl Strategy<Value = Case> {
    (0..KINDS.len(), 1usize..=12, any::<u64>()).prop_map(|(k, n, seed)| Case {
        kind: KINDS[k],
        n,
        seed,
    })
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum CamKind {
    /// Orthographic along -z, square image, under which world coordinates that are multiples of
    /// 1/64 in [-2, 2] snap to the grid exactly (x·2^21, y·2^21, -z·2^21).
    Exact,
    /// Perspective or orthographic looking exactly along -z: planes z = const keep one snapped
    /// depth, so faces on them are exactly coplanar.
    AxisZ,
    /// Anywhere, some with the eye among the faces.
    Random,
}

pub struct Gen {
    pub rng: Rng,
    /// Round coordinates to multiples of 1/64 (for the exact camera).
    pub dyadic: bool,
}

impl Gen {
    fn unit(&mut self) -> f64 {
        self.rng.range(0.0, 1.0)
    }

    fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    fn int(&mut self, lo: usize, hi: usize) -> usize {
        lo + (self.rng.next_u64() % (hi - lo + 1) as u64) as usize
    }

    fn q(&self, v: f64) -> f64 {
        if self.dyadic {
            (v * 64.0).round() / 64.0
        } else {
            v
        }
    }

    fn qv(&self, p: DVec3) -> DVec3 {
        DVec3::new(self.q(p.x), self.q(p.y), self.q(p.z))
    }

    /// A quantized random number in [lo, hi).
    fn qr(&mut self, lo: f64, hi: f64) -> f64 {
        let v = self.rng.range(lo, hi);
        self.q(v)
    }

    /// `c` moved by a random offset in [-r, r)^3, quantized.
    fn near(&mut self, c: DVec3, r: f64) -> DVec3 {
        let d = self.rng.vec3(-r, r);
        self.qv(c + d)
    }

    fn point(&mut self, lo: f64, hi: f64) -> DVec3 {
        let p = self.rng.vec3(lo, hi);
        self.qv(p)
    }

    fn direction(&mut self) -> DVec3 {
        loop {
            let v = self.rng.vec3(-1.0, 1.0);
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l;
            }
        }
    }

    fn rotation(&mut self) -> DQuat {
        let axis = self.direction();
        DQuat::from_axis_angle(axis, self.rng.range(0.0, TAU))
    }
}

/// A polygon in a mesh of its own (open: never back-face culled under `CullMode::Auto`).
/// A star-shaped (usually non-convex) ring of 4 to 7 points around the origin of the plane, as
/// (u, v) offsets: simple, since its corners are in angular order.
pub fn star(g: &mut Gen) -> Vec<[f64; 2]> {
    let k = g.int(4, 7);
    let (r_out, r_in) = (g.rng.range(0.4, 0.8), g.rng.range(0.15, 0.4));
    (0..k)
        .map(|i| {
            let t = TAU * (i as f64 + g.rng.range(-0.2, 0.2)) / k as f64;
            let r = if i % 2 == 0 { r_out } else { r_in };
            [g.q(r * t.cos()), g.q(r * t.sin())]
        })
        .collect()
}

fn tri_soup(g: &mut Gen, b: &mut SceneBuilder, n: usize) {
    for _ in 0..n {
        let c = g.point(-1.0, 1.0);
        if g.chance(0.12) {
            // A non-convex planar polygon on a plane x, y or z = const (exactly planar).
            let axis = g.int(0, 2);
            let p: Vec<DVec3> = star(g)
                .into_iter()
                .map(|[u, v]| {
                    let mut q = c.to_array();
                    q[(axis + 1) % 3] += u;
                    q[(axis + 2) % 3] += v;
                    DVec3::from_array(q)
                })
                .collect();
            add_polygon(b, &p);
            continue;
        }
        let p = [g.near(c, 0.6), g.near(c, 0.6), g.near(c, 0.6)];
        add_polygon(b, &p);
    }
}

/// A closed box of `size` at `centre`, turned at random (axis-aligned for the exact camera).
fn add_turned_box(g: &mut Gen, b: &mut SceneBuilder, centre: DVec3, size: DVec3) {
    b.begin_mesh("box");
    let m = b.default_material();
    let rot = if g.dyadic {
        DQuat::IDENTITY
    } else {
        g.rotation()
    };
    let t = DMat4::from_rotation_translation(rot, centre);
    primitives::add_box(b, &t, size, m);
}

/// A closed low-resolution sphere (3 to 7 segments, 2 to 4 rings) at `centre`, turned at random.
fn add_turned_sphere(g: &mut Gen, b: &mut SceneBuilder, centre: DVec3, r: f64) {
    b.begin_mesh("sphere");
    let m = b.default_material();
    let (seg, rings) = (g.int(3, 7), g.int(2, 4));
    let t = DMat4::from_rotation_translation(g.rotation(), centre);
    primitives::add_sphere(b, &t, r, seg, rings, m);
}

fn add_tetra(g: &mut Gen, b: &mut SceneBuilder, centre: DVec3, r: f64) {
    let mut p: Vec<DVec3> = (0..4).map(|_| g.near(centre, r)).collect();
    let vol = (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]);
    if vol.abs() < 1e-3 * r * r * r {
        return;
    }
    if vol > 0.0 {
        // Faces below are outward for a negatively oriented (0, 1, 2, 3).
        p.swap(1, 2);
    }
    b.begin_mesh("tetra");
    let m = b.default_material();
    let v: Vec<u32> = p.iter().map(|&q| b.add_vertex(q)).collect();
    for f in [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]] {
        b.add_face(&f.map(|k| v[k]), m);
    }
}

fn closed_meshes(g: &mut Gen, b: &mut SceneBuilder, n: usize) {
    let mut spheres = 0;
    for _ in 0..1 + n / 3 {
        let c = g.point(-0.7, 0.7);
        match g.int(0, 2) {
            0 => {
                let s = g.point(0.3, 1.2);
                add_turned_box(g, b, c, s);
            }
            1 if spheres == 0 => {
                spheres += 1;
                let r = g.rng.range(0.3, 0.8);
                add_turned_sphere(g, b, c, r);
            }
            _ => {
                let r = g.rng.range(0.3, 0.9);
                add_tetra(g, b, c, r);
            }
        }
    }
}

/// Two things that pass through each other.
fn pair(g: &mut Gen, b: &mut SceneBuilder) {
    let c = g.point(-0.3, 0.3);
    match g.int(0, 3) {
        0 => {
            // Two triangles crossing in an X.
            let (u, v, w) = (g.direction(), g.direction(), g.direction());
            add_polygon(b, &[g.qv(c - u), g.qv(c + u), g.qv(c + v * 0.8)]);
            add_polygon(
                b,
                &[
                    g.qv(c - v * 0.3 - w),
                    g.qv(c + u * 0.2 + w),
                    g.qv(c - w * 0.1),
                ],
            );
        }
        1 => {
            // A box pierced by a triangle.
            let s = g.point(0.5, 1.0);
            add_turned_box(g, b, c, s);
            let d = g.direction();
            add_polygon(
                b,
                &[
                    g.qv(c - d * 1.2),
                    g.near(c + d * 1.2, 0.2),
                    g.point(-1.0, 1.0),
                ],
            );
        }
        2 => {
            // Two overlapping boxes.
            let (s, t) = (g.point(0.4, 1.0), g.point(0.4, 1.0));
            let e = g.point(-0.3, 0.3);
            add_turned_box(g, b, c, s);
            add_turned_box(g, b, c + e, t);
        }
        _ => {
            // Two planar quads crossing at an angle (the builder triangulates one that rounding
            // left non-planar: then two polygons share its id).
            for _ in 0..2 {
                let (u, v) = (g.direction() * 0.8, g.direction() * 0.6);
                add_polygon(
                    b,
                    &[
                        g.qv(c - u - v),
                        g.qv(c + u - v),
                        g.qv(c + u + v),
                        g.qv(c - u + v),
                    ],
                );
            }
        }
    }
}

/// Faces on a few planes z = const (and on one tilted dyadic plane), overlapping, some reversed,
/// some exact duplicates of others (same positions, corners rotated or reversed).
fn coplanar(g: &mut Gen, b: &mut SceneBuilder, n: usize) {
    let layers: Vec<f64> = (0..g.int(1, 3)).map(|_| g.qr(-0.8, 0.8)).collect();
    // A tilted plane z = a·x + b·y + c with dyadic a, b, c: exact under the exact camera.
    let (ta, tb, tc) = (
        g.int(0, 4) as f64 / 8.0 - 0.25,
        g.int(0, 4) as f64 / 8.0 - 0.25,
        g.qr(-0.5, 0.5),
    );
    let mut made: Vec<Vec<DVec3>> = Vec::new();
    for _ in 0..n {
        if !made.is_empty() && g.chance(0.25) {
            // A duplicate, corners rotated and maybe reversed.
            let k = g.int(0, made.len() - 1);
            let mut p = made[k].clone();
            let r = g.int(0, p.len() - 1);
            p.rotate_left(r);
            if g.chance(0.3) {
                p.reverse();
            }
            add_polygon(b, &p);
            continue;
        }
        let tilted = g.chance(0.25);
        let z = layers[g.int(0, layers.len() - 1)];
        let on = |x: f64, y: f64| {
            if tilted {
                DVec3::new(x, y, ta * x + tb * y + tc)
            } else {
                DVec3::new(x, y, z)
            }
        };
        let c = g.point(-0.8, 0.8);
        let shape = g.unit();
        let mut p: Vec<DVec3> = if shape < 0.25 {
            star(g)
                .into_iter()
                .map(|[u, v]| on(c.x + u, c.y + v))
                .collect()
        } else if shape < 0.6 {
            // An axis-aligned rectangle (collinear and overlapping edges between faces),
            // sometimes with an extra corner in the middle of its bottom edge (a straight corner,
            // as meshes fixed for T-junctions have).
            let (hx, hy) = (g.qr(0.1, 0.7), g.qr(0.1, 0.7));
            let mut r = vec![
                on(c.x - hx, c.y - hy),
                on(c.x + hx, c.y - hy),
                on(c.x + hx, c.y + hy),
                on(c.x - hx, c.y + hy),
            ];
            if g.chance(0.15) {
                r.insert(1, on(c.x, c.y - hy));
            }
            r
        } else {
            (0..3)
                .map(|_| {
                    let d = g.point(-0.7, 0.7);
                    on(c.x + d.x, c.y + d.y)
                })
                .collect()
        };
        if g.chance(0.3) {
            p.reverse();
        }
        made.push(p.clone());
        add_polygon(b, &p);
    }
}

/// Thin triangles fanning out of one hub (nearly parallel edges meeting at a shared corner) and
/// faces passing through or near the hub (cut lines nearly parallel to those edges): where f64
/// crossings of lines are at their worst.
fn slivers(g: &mut Gen, b: &mut SceneBuilder, n: usize) {
    let hub = g.point(-0.3, 0.3);
    for _ in 0..g.int(1, 2) {
        b.begin_mesh("sliver fan");
        let m = b.default_material();
        let h = b.add_vertex(hub);
        let k = 2 + n;
        let (base, spread) = (g.rng.range(0.0, TAU), g.rng.range(0.02, 0.6));
        let ring: Vec<u32> = (0..=k)
            .map(|i| {
                let t = base + spread * (i as f64 + g.rng.range(-0.3, 0.3)) / k as f64;
                let r = g.rng.range(0.8, 1.6);
                let z = g.rng.range(-0.6, 0.6);
                let p = g.qv(hub + DVec3::new(r * t.cos(), r * t.sin(), z));
                b.add_vertex(p)
            })
            .collect();
        for i in 0..k {
            b.add_face(&[h, ring[i], ring[i + 1]], m);
        }
    }
    for _ in 0..g.int(1, 3) {
        let through = if g.chance(0.5) {
            hub
        } else {
            g.near(hub, 0.02)
        };
        let (u, v) = (g.direction(), g.direction());
        add_polygon(
            b,
            &[through, g.qv(through + u * 1.5), g.qv(through + v * 1.5)],
        );
    }
}

/// Faces sharing edges and vertices: a height field of triangles, or a fan.
fn shared(g: &mut Gen, b: &mut SceneBuilder, n: usize) {
    b.begin_mesh("shared");
    let m = b.default_material();
    if g.chance(0.5) {
        let k = 1 + n.min(11) / 3; // 1..4 cells a side: 2..32 triangles
        let z: Vec<f64> = (0..(k + 1) * (k + 1)).map(|_| g.qr(-0.5, 0.5)).collect();
        let side = 2.4 / k as f64;
        let mut v = Vec::new();
        for j in 0..=k {
            for i in 0..=k {
                let p = DVec3::new(
                    -1.2 + side * i as f64,
                    -1.2 + side * j as f64,
                    z[j * (k + 1) + i],
                );
                v.push(b.add_vertex(g.qv(p)));
            }
        }
        let at = |i: usize, j: usize| v[j * (k + 1) + i];
        for j in 0..k {
            for i in 0..k {
                let (a, bb, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                if g.chance(0.5) {
                    b.add_face(&[a, bb, c], m);
                    b.add_face(&[a, c, d], m);
                } else {
                    b.add_face(&[a, bb, d], m);
                    b.add_face(&[bb, c, d], m);
                }
            }
        }
    } else {
        let spokes = 3 + n;
        let centre = b.add_vertex(g.point(-0.3, 0.3));
        let full = g.chance(0.6);
        let ring: Vec<u32> = (0..spokes)
            .map(|k| {
                let t = TAU * (k as f64 + g.rng.range(-0.3, 0.3)) / spokes as f64;
                let r = g.rng.range(0.4, 1.4);
                let z = g.rng.range(-0.6, 0.6);
                b.add_vertex(g.qv(DVec3::new(r * t.cos(), r * t.sin(), z)))
            })
            .collect();
        let last = if full { spokes } else { spokes - 1 };
        for k in 0..last {
            b.add_face(&[centre, ring[k], ring[(k + 1) % spokes]], m);
        }
    }
}

/// A big triangle (a, b, c) whose edge ab holds the shared vertex m of two small triangles on the
/// other side: (a, p, m) and (m, p, b).
fn t_junctions(g: &mut Gen, b: &mut SceneBuilder, n: usize) {
    for _ in 0..1 + n / 4 {
        let a = g.point(-1.2, 1.2);
        let bb = g.point(-1.2, 1.2);
        let c = g.point(-1.2, 1.2);
        let t = [0.25, 0.5, 0.75][g.int(0, 2)];
        let m = a + (bb - a) * t; // exact for dyadic a and b
        let side = (bb - a).cross(c - a);
        // p on the other side of ab from c (in the plane's normal sense), roughly.
        let back = g.rng.range(0.3, 0.9);
        let p = g.qv(m - (c - a) * back + side.normalize_or_zero() * 0.1);
        b.begin_mesh("tjunction");
        let mat = b.default_material();
        let [va, vb, vc, vm, vp] = [a, bb, c, m, p].map(|q| b.add_vertex(q));
        b.add_face(&[va, vb, vc], mat);
        b.add_face(&[va, vp, vm], mat);
        b.add_face(&[vm, vp, vb], mat);
    }
}

/// Three bars in cyclic overlap (as `fixtures/cyclic_bars.obj`): bar i runs from corner i (near)
/// to corner i + 1 (far) of a triangle, so no order of whole faces exists.
fn bars(g: &mut Gen, b: &mut SceneBuilder, n: usize) {
    let r = g.rng.range(1.0, 1.6);
    let w = g.rng.range(0.1, 0.35);
    let h = g.rng.range(0.2, 0.7);
    let theta0 = g.rng.range(0.0, TAU);
    let corner = |i: usize| {
        let t = theta0 + TAU * i as f64 / 3.0;
        DVec3::new(r * t.cos(), r * t.sin(), 0.0)
    };
    b.begin_mesh("bars");
    let m = b.default_material();
    for i in 0..3 {
        let (p, q) = (corner(i), corner(i + 1));
        let dir = (q - p).normalize();
        let nrm = DVec3::new(-dir.y, dir.x, 0.0) * w;
        let ext = dir * g.rng.range(0.0, 0.3);
        let (s, e) = (p - ext + DVec3::Z * h, q + ext - DVec3::Z * h);
        let v: Vec<u32> = [s - nrm, e - nrm, e + nrm, s + nrm]
            .iter()
            .map(|&x| b.add_vertex(x))
            .collect();
        b.add_face(&v, m);
    }
    tri_soup(g, b, n / 4);
}

fn generate(g: &mut Gen, b: &mut SceneBuilder, kind: Kind, n: usize) {
    match kind {
        Kind::Triangles => tri_soup(g, b, n + n / 2),
        Kind::Closed => closed_meshes(g, b, n),
        Kind::Pairs => {
            for _ in 0..1 + n / 5 {
                pair(g, b);
            }
        }
        Kind::Coplanar => coplanar(g, b, n + 2),
        Kind::Shared => shared(g, b, n),
        Kind::Slivers => slivers(g, b, n),
        Kind::TJunctions => t_junctions(g, b, n),
        Kind::Bars => bars(g, b, n),
        Kind::Mixed => {
            for _ in 0..g.int(2, 3) {
                let k = KINDS[g.int(0, KINDS.len() - 2)];
                let m = g.int(1, n.div_ceil(2));
                generate(g, b, k, m);
            }
        }
    }
}

/// Orthographic along -z, 40 x 40: world coordinates that are multiples of 1/64 in [-2, 2] snap
/// to the grid exactly (x·2^21, y·2^21, -z·2^21).
pub fn exact_camera() -> Camera {
    let eye = DVec3::new(0.0, 0.0, 4.0);
    let ortho = Projection::Orthographic { height: 4.0 };
    look_at(eye, DVec3::ZERO, ortho, 0.0, 8.0, (40, 40))
}

fn random_camera(g: &mut Gen, along_z: bool) -> Camera {
    let target = g.rng.vec3(-0.3, 0.3);
    let dir = if along_z { DVec3::Z } else { g.direction() };
    let up = if dir.cross(DVec3::Y).length() > 0.1 {
        DVec3::Y
    } else {
        DVec3::X
    };
    let (eye, projection, near) = if g.chance(0.4) {
        let height = g.rng.range(2.0, 5.0);
        // Some near planes cut through the scene.
        let near = if g.chance(0.3) {
            g.rng.range(2.5, 4.5)
        } else {
            -6.0
        };
        (
            target + dir * 4.0,
            Projection::Orthographic { height },
            near,
        )
    } else {
        // Some eyes among the faces.
        let dist = if g.chance(0.3) {
            g.rng.range(0.15, 1.2)
        } else {
            g.rng.range(2.0, 5.0)
        };
        let fovy_deg = g.rng.range(20.0, 100.0);
        let near = g.rng.range(0.02, 0.3).min(dist * 0.5);
        (
            target + dir * dist,
            Projection::Perspective { fovy_deg },
            near,
        )
    };
    Camera {
        eye,
        target,
        up,
        projection,
        near,
        far: 12.0,
        width: 48,
        height: 40,
    }
}

pub struct Setup {
    pub scene: Scene,
    pub camera: Camera,
    pub cull: CullMode,
}

/// The scene, camera and cull mode of a case; deterministic in the case.
pub fn setup(case: &Case) -> Option<Setup> {
    let mut g = Gen {
        rng: Rng(case.seed),
        dyadic: false,
    };
    let u = g.unit();
    let cam = match case.kind {
        Kind::Coplanar if u < 0.6 => CamKind::Exact,
        Kind::Coplanar if u < 0.85 => CamKind::AxisZ,
        Kind::Shared | Kind::TJunctions | Kind::Slivers if u < 0.3 => CamKind::Exact,
        Kind::Triangles | Kind::Closed | Kind::Pairs | Kind::Mixed if u < 0.15 => CamKind::Exact,
        Kind::Bars if u < 0.5 => CamKind::AxisZ,
        _ if u > 0.9 => CamKind::AxisZ,
        _ => CamKind::Random,
    };
    g.dyadic = cam == CamKind::Exact;
    let mut b = SceneBuilder::new("properties");
    generate(&mut g, &mut b, case.kind, case.n);
    let scene = b.finish()?;
    let camera = match cam {
        CamKind::Exact => exact_camera(),
        CamKind::AxisZ => random_camera(&mut g, true),
        CamKind::Random => random_camera(&mut g, false),
    };
    camera.validate().expect("generated cameras are valid");
    let cull = if g.chance(0.2) {
        CullMode::Off
    } else {
        CullMode::Auto
    };
    Some(Setup {
        scene,
        camera,
        cull,
    })
}

/// Does some screen polygon have a corner on the line through its neighbours (a straight
/// corner, as a T-junction vertex is)? The generators must reach these.
fn has_straight_corner(screen: &ScreenScene) -> bool {
    screen.polys.iter().any(|p| {
        let c = screen.corners(p);
        let n = c.len();
        (0..n).any(|k| {
            sightline::exact::predicates::orient2d(c[(k + n - 1) % n], c[k], c[(k + 1) % n])
                == std::cmp::Ordering::Equal
        })
    })
}

// ------------------------------------------------------------------------------------------------
// The generators reach what they are meant to
// ------------------------------------------------------------------------------------------------

/// The exact camera puts dyadic world points on the grid without rounding.
#[test]
fn exact_camera_snaps_dyadic_points_exactly() {
    let mut b = SceneBuilder::new("dyadic");
    let p = [
        DVec3::new(-1.5, -0.75, 0.5),
        DVec3::new(1.25, -1.0 + 1.0 / 64.0, -1.5),
        DVec3::new(3.0 / 64.0, 1.5, 0.25),
    ];
    add_polygon(&mut b, &p);
    let scene = b.finish().unwrap();
    let screen = prepare(&scene, &exact_camera(), CullMode::Auto).screen;
    let grid: Vec<[i64; 3]> = screen.grid_points.iter().map(|c| [c.x, c.y, c.z]).collect();
    let want: Vec<[i64; 3]> = p
        .iter()
        .map(|q| {
            let s = (1u64 << 51) as f64;
            [(q.x * s) as i64, (q.y * s) as i64, (-q.z * s) as i64]
        })
        .collect();
    assert_eq!(grid, want);
}

/// Over a few hundred cases, the generators make what the properties are meant to meet:
/// interpenetration (cut lines in visible pieces), exact coplanar overlaps, exact T-junctions on
/// screen, faces cut by the near plane, back faces kept and culled, non-convex polygons, several
/// polygons with one face id.
#[test]
fn generators_reach_the_degenerate_cases() {
    let mut rng = Rng(0x1234_5678);
    let mut count = std::collections::BTreeMap::<&str, usize>::new();
    let mut add = |k: &'static str, yes: bool| *count.entry(k).or_default() += yes as usize;
    let cases = 400;
    for i in 0..cases {
        let case = Case {
            kind: KINDS[i % KINDS.len()],
            n: 1 + (rng.next_u64() % 12) as usize,
            seed: rng.next_u64(),
        };
        let Some(s) = setup(&case) else { continue };
        let screen = prepare(&s.scene, &s.camera, s.cull).screen;
        let polys = screen_polys(&screen);
        add("cases", true);
        add("straight corners", has_straight_corner(&screen));
        let (visible, _) = bsp_walk(&screen);
        add(
            "cut lines in visible pieces",
            visible
                .pieces
                .iter()
                .any(|p| p.lines().any(|l| matches!(l, Line::Cut(..)))),
        );
        let overlap = |a: &Poly, b: &Poly| {
            let bx = |p: &Poly| {
                let xs = p.pts.iter().map(|q| q[0]);
                let ys = p.pts.iter().map(|q| q[1]);
                [
                    xs.clone().min().unwrap(),
                    ys.clone().min().unwrap(),
                    xs.max().unwrap(),
                    ys.max().unwrap(),
                ]
            };
            let (p, q) = (bx(a), bx(b));
            p[0] < q[2] && q[0] < p[2] && p[1] < q[3] && q[1] < p[3]
        };
        let mut coplanar = false;
        let mut t_junction = false;
        let mut same_id = false;
        for (i, a) in polys.iter().enumerate() {
            for b in &polys[i + 1..] {
                coplanar |= same_plane(&a.plane, &b.plane) && overlap(a, b);
                same_id |= a.id == b.id;
                // A corner of b strictly inside an edge of a.
                let n = a.pts.len();
                t_junction |= (0..n).any(|k| {
                    let (p, q) = (a.pts[k], a.pts[(k + 1) % n]);
                    b.pts.iter().any(|&c| {
                        c != p
                            && c != q
                            && orient(p, q, c) == Ordering::Equal
                            && c[0] >= p[0].min(q[0])
                            && c[0] <= p[0].max(q[0])
                            && c[1] >= p[1].min(q[1])
                            && c[1] <= p[1].max(q[1])
                    })
                });
            }
        }
        add("exact coplanar overlaps", coplanar);
        add("exact T-junctions on screen", t_junction);
        add("several polygons of one face id", same_id);
        add(
            "non-convex polygons",
            polys.iter().any(|p| {
                let n = p.pts.len();
                let turns: Vec<Ordering> = (0..n)
                    .map(|k| orient(p.pts[k], p.pts[(k + 1) % n], p.pts[(k + 2) % n]))
                    .collect();
                turns.contains(&Ordering::Less) && turns.contains(&Ordering::Greater)
            }),
        );
        add("clipped faces", screen.stats.clipped > 0);
        add(
            "meshes cut by the near plane",
            screen.stats.meshes_cut_by_near > 0,
        );
        add("back faces culled", screen.stats.backface_culled > 0);
        add("back faces kept", screen.polys.iter().any(|p| !p.front));
        add("no polygon on screen", polys.is_empty());
    }
    eprintln!("{count:#?}");
    for (k, v) in &count {
        if *k != "no polygon on screen" && *k != "straight corners" {
            assert!(*v >= cases / 50, "only {v} of {cases} cases have {k}");
        }
    }
    assert!(count["no polygon on screen"] < cases / 10);
}
