//! Scenes generated in code: boxes, spheres and polygons each in a mesh of their own, random
//! triangle soups, and random faces built to hit the hard cases of a pixel-exact renderer. A
//! seed always makes the same scene.

use super::camera::{LATTICE_H, LATTICE_W, lattice_point};
use super::rng::Rng;
use glam::{DMat4, DVec3};
use sightline::scene::{Material, Scene, SceneBuilder, primitives};

/// Adds an axis-aligned box (outward, closed) in a mesh of its own.
pub fn add_box(b: &mut SceneBuilder, lo: DVec3, hi: DVec3, name: &str) {
    b.begin_mesh(name);
    let m = b.default_material();
    let at = DMat4::from_translation((lo + hi) * 0.5);
    primitives::add_box(b, &at, hi - lo, m);
}

/// Adds a polygon in a mesh of its own called `name` (open: never back-face culled under
/// `CullMode::Auto`).
pub fn add_named_polygon(b: &mut SceneBuilder, name: &str, pts: &[DVec3]) {
    b.begin_mesh(name);
    let m = b.default_material();
    let v: Vec<u32> = pts.iter().map(|&p| b.add_vertex(p)).collect();
    b.add_face(&v, m);
}

/// Adds a polygon in a mesh of its own (open: never culled).
pub fn add_polygon(b: &mut SceneBuilder, pts: &[DVec3]) {
    add_named_polygon(b, "poly", pts);
}

/// Adds a triangle in a mesh of its own (open: never culled).
pub fn add_triangle(b: &mut SceneBuilder, p: [DVec3; 3]) {
    add_named_polygon(b, "tri", &p);
}

/// Adds a closed UV sphere of `seg` x `rings` in a mesh of its own.
pub fn add_sphere(b: &mut SceneBuilder, c: DVec3, r: f64, seg: usize, rings: usize) {
    b.begin_mesh("sphere");
    let m = b.default_material();
    primitives::add_sphere(b, &DMat4::from_translation(c), r, seg, rings, m);
}

/// Two interpenetrating boxes and a sphere of `seg` x `rings` passing through both: closed
/// meshes, interpenetration, and silhouettes at every angle.
pub fn boxes_and_sphere(seg: usize, rings: usize) -> Scene {
    let mut b = SceneBuilder::new("boxes");
    add_box(
        &mut b,
        DVec3::new(-1.0, -1.0, -1.0),
        DVec3::new(0.3, 0.5, 0.2),
        "a",
    );
    add_box(
        &mut b,
        DVec3::new(0.1, -0.4, -0.3),
        DVec3::new(1.2, 0.9, 0.9),
        "b",
    );
    add_sphere(&mut b, DVec3::new(-0.2, 0.6, 0.6), 0.55, seg, rings);
    b.finish().unwrap()
}

/// `n` random triangles in [-1,1]^3 (overlapping and interpenetrating), each its own mesh.
pub fn random_triangles(n: usize, seed: u64) -> Scene {
    let mut rng = Rng(seed);
    let mut b = SceneBuilder::new("random");
    for _ in 0..n {
        let c = rng.vec3(-1.0, 1.0);
        let p = [
            c + rng.vec3(-0.6, 0.6),
            c + rng.vec3(-0.6, 0.6),
            c + rng.vec3(-0.6, 0.6),
        ];
        add_triangle(&mut b, p);
    }
    b.finish().unwrap()
}

/// `n` faces (or so), mostly triangles, made to hit a pixel-exact renderer's hard cases, each in
/// a mesh of its own (open: never culled) with a material of its own:
/// - corners from a small shared pool, half of them on pixel centres of
///   [`super::camera::lattice_camera`] at one of three depths (edges and corners exactly through
///   samples);
/// - quads split in two (a shared edge), triangles sharing an edge with an earlier one;
/// - exact duplicates of earlier triangles, some reversed (coplanar overlap: exact depth ties
///   under any camera), and triangles at one constant depth (coplanar under view-aligned
///   cameras);
/// - non-convex stars at one constant depth, some self-intersecting (the even-odd fill rule);
/// - everything else interpenetrating at random.
///
/// With `translucent`, materials get transparencies among 0, 0.25, 0.5, 0.75 and 1; colours are
/// emissive multiples of 1/4 (diffuse 0), so shading leaves them exact.
pub fn tricky_faces(seed: u64, n: usize, translucent: bool) -> Scene {
    let mut rng = Rng(seed);
    let mut b = SceneBuilder::new("tricky");
    let levels = [-0.5, 0.0, 0.5];
    let pool_size = 6 + rng.below(10) as usize;
    let mut pool: Vec<u32> = Vec::new();
    for k in 0..pool_size {
        let p = if k % 2 == 0 {
            lattice_point(
                rng.below(LATTICE_W as u64 + 1) as i64,
                rng.below(LATTICE_H as u64 + 1) as i64,
                levels[rng.below(3) as usize],
            )
        } else {
            DVec3::new(
                rng.range(-1.8, 1.8),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            )
        };
        pool.push(b.add_vertex(p));
    }
    let mut tris: Vec<Vec<u32>> = Vec::new();
    let pick = |rng: &mut Rng| pool[rng.below(pool.len() as u64) as usize];
    while tris.len() < n {
        let kind = rng.below(12);
        match kind {
            0..=3 => tris.push(vec![pick(&mut rng), pick(&mut rng), pick(&mut rng)]),
            4 | 5 => {
                let (a, bb, c, d) = (
                    pick(&mut rng),
                    pick(&mut rng),
                    pick(&mut rng),
                    pick(&mut rng),
                );
                tris.push(vec![a, bb, c]);
                tris.push(vec![a, c, d]);
            }
            6 if !tris.is_empty() => {
                let mut t = tris[rng.below(tris.len() as u64) as usize].clone();
                if rng.below(2) == 0 {
                    t.rotate_left(1);
                } else {
                    t.reverse();
                }
                tris.push(t);
            }
            7 if !tris.is_empty() => {
                let t = &tris[rng.below(tris.len() as u64) as usize];
                let e = rng.below(t.len() as u64) as usize;
                let shared = vec![t[(e + 1) % t.len()], t[e], pick(&mut rng)];
                tris.push(shared);
            }
            8 | 9 => {
                // A star: corners alternately far from and near its centre (non-convex); taken
                // two steps at a time around an odd count, it crosses itself (a pentagram).
                let z = levels[rng.below(3) as usize];
                let (cx, cy) = (rng.range(-1.5, 1.5), rng.range(-0.8, 0.8));
                let points = 5 + 2 * rng.below(3) as usize;
                let (r_out, r_in) = (rng.range(0.3, 1.0), rng.range(0.05, 0.3));
                let ring: Vec<u32> = (0..points)
                    .map(|k| {
                        let a = std::f64::consts::TAU * k as f64 / points as f64;
                        let r = if kind == 8 && k % 2 == 1 { r_in } else { r_out };
                        b.add_vertex(DVec3::new(cx + r * a.cos(), cy + r * a.sin(), z))
                    })
                    .collect();
                let order: Vec<u32> = if kind == 8 {
                    ring
                } else {
                    (0..points).map(|k| ring[(2 * k) % points]).collect()
                };
                tris.push(order);
            }
            _ => {
                let z = levels[rng.below(3) as usize];
                let mut v = vec![0u32; 3];
                for c in &mut v {
                    *c = b.add_vertex(lattice_point(
                        rng.below(LATTICE_W as u64 + 1) as i64,
                        rng.below(LATTICE_H as u64 + 1) as i64,
                        z,
                    ));
                }
                tris.push(v);
            }
        }
    }
    let quarter = |rng: &mut Rng| rng.below(5) as f64 / 4.0;
    for (k, t) in tris.iter().enumerate() {
        let transparency = if translucent { quarter(&mut rng) } else { 0.0 };
        let m = b.add_material(Material {
            name: format!("m{k}"),
            diffuse: [0.0; 3],
            emissive: [quarter(&mut rng), quarter(&mut rng), quarter(&mut rng)],
            transparency,
            two_sided: false,
        });
        b.begin_mesh(format!("t{k}"));
        b.add_face(t, m);
    }
    b.finish().unwrap_or_else(|| {
        // Every triangle degenerate (rare with small pools): one plain triangle instead.
        let mut b = SceneBuilder::new("tricky");
        let m = b.default_material();
        let v: Vec<u32> = [
            lattice_point(3, 3, 0.0),
            lattice_point(40, 5, 0.0),
            lattice_point(9, 30, 0.0),
        ]
        .iter()
        .map(|&p| b.add_vertex(p))
        .collect();
        b.add_face(&v, m);
        b.finish().unwrap()
    })
}
