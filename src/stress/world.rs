//! The measured cases of issue 11, checked against a reference in world coordinates.
//!
//! The reference projects every world vertex with the camera's f64 view-projection matrix, its
//! entries taken as exact rationals: exact clip coordinates, clipped exactly by the near and far
//! planes, divided exactly: exact rational NDC with no rounding at all. At a pixel centre it
//! names the face whose exact polygon contains the point and is nearest there (the plane through
//! its exact corners), as [`super::reference`] does on the kernel's grid.
//!
//! The engine may differ from it only within a band that widens as the f64 projection's own
//! rounding divided by the angle between the surfaces (see [`Band`]): that rounding is the one
//! loss the issue accepts on the way in. Invariant of [`measure`]: a sample counts as wrong
//! exactly when the engine's face (decided exactly on its pieces) is not the reference's and the
//! sample lies outside that band.

use super::geometry::{Convex, Loc, Plane, Point, Polygon, nearest, rational};
use super::kernel;
use super::rng::Rng;
use crate::camera::{Camera, Projection};
use crate::scene::Scene;
use crate::scene::SceneBuilder;
use glam::{DMat4, DQuat, DVec3, DVec4};
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

/// One measured case: world triangles and a camera.
#[derive(Clone, Debug)]
pub struct MeasuredCase {
    /// Its name in reports.
    pub name: String,
    /// Its triangles (world).
    pub triangles: Vec<[DVec3; 3]>,
    /// The camera.
    pub camera: Camera,
}

impl MeasuredCase {
    /// The scene, one face per triangle.
    pub fn scene(&self) -> Scene {
        let mut b = SceneBuilder::new(&self.name);
        let m = b.default_material();
        for t in &self.triangles {
            let v = t.map(|p| b.add_vertex(p));
            b.add_face(&v, m);
        }
        b.finish().expect("measured cases have faces")
    }
}

/// Every measured case's camera: 40 degrees vertical field of view, 800 x 600, and the clip
/// range a modelling package uses by default, near 0.01 and far 10000 (the plate case).
fn camera(eye: DVec3, up: DVec3) -> Camera {
    Camera {
        eye,
        target: DVec3::ZERO,
        up,
        projection: Projection::Perspective { fovy_deg: 40.0 },
        near: 0.01,
        far: 10_000.0,
        width: 800,
        height: 600,
    }
}

/// The quad (c ± u ± v) as two triangles, counter-clockwise seen from `u × v`.
fn quad(c: DVec3, u: DVec3, v: DVec3) -> [[DVec3; 3]; 2] {
    let (a, b, d, e) = (c - u - v, c + u - v, c + u + v, c - u + v);
    [[a, b, d], [a, d, e]]
}

/// Two large triangles crossing along the x axis at `angle` rad, seen obliquely from 6 m.
pub fn crossing(angle: f64) -> MeasuredCase {
    let t1 = [
        DVec3::new(-3.0, -2.5, 0.0),
        DVec3::new(3.0, -2.5, 0.0),
        DVec3::new(0.0, 3.5, 0.0),
    ];
    let q = DQuat::from_rotation_x(angle);
    let t2 = [
        DVec3::new(-3.0, 2.5, 0.0),
        DVec3::new(0.0, -3.5, 0.0),
        DVec3::new(3.0, 2.5, 0.0),
    ]
    .map(|p| q * p);
    let camera = camera(DVec3::new(1.0, -4.0, 4.5), DVec3::Z);
    MeasuredCase {
        name: format!("two triangles crossing at {angle:e} rad"),
        triangles: vec![t1, t2],
        camera,
    }
}

/// Forty 2 x 2 quads stacked 1e-7 apart, each turned by about 1e-7 rad about an axis in its
/// plane, seen at 45 degrees from 5 m.
pub fn stack() -> MeasuredCase {
    let mut rng = Rng::of(&[0x57ac]);
    let mut triangles = Vec::new();
    for k in (0..40).rev() {
        let c = DVec3::new(0.0, 0.0, k as f64 * 1e-7);
        let a = rng.range(0.0, std::f64::consts::TAU);
        let q = DQuat::from_axis_angle(
            DVec3::new(a.cos(), a.sin(), 0.0),
            1e-7 * rng.range(0.5, 1.5) * rng.sign(),
        );
        triangles.extend(quad(c, q * DVec3::X, q * DVec3::Y));
    }
    let camera = camera(DVec3::new(0.0, -3.5, 3.5), DVec3::Z);
    MeasuredCase {
        name: "forty quads 1e-7 apart, turned 1e-7 rad".into(),
        triangles,
        camera,
    }
}

/// A 2 x 2 m plate `height` above a 200 x 200 m floor, 60 m from a perspective camera with near
/// 0.01 and far 10000, at 800 x 600.
pub fn plate(height: f64) -> MeasuredCase {
    let mut triangles = quad(DVec3::ZERO, DVec3::X * 100.0, DVec3::NEG_Z * 100.0).to_vec();
    triangles.extend(quad(DVec3::Y * height, DVec3::X, DVec3::NEG_Z));
    let e = 30f64.to_radians();
    let eye = DVec3::new(0.0, e.sin(), e.cos()) * 60.0;
    MeasuredCase {
        name: format!("2 m plate {height:e} m above a 200 m floor at 60 m"),
        triangles,
        camera: camera(eye, DVec3::Y),
    }
}

/// Six 2 x 2 sheets 1e-5 apart, each shifted 0.3 along x from the one below, seen at 45
/// degrees from 5 m.
pub fn sheets() -> MeasuredCase {
    let mut triangles = Vec::new();
    for k in (0..6).rev() {
        let c = DVec3::new(k as f64 * 0.3 - 0.75, 0.0, k as f64 * 1e-5);
        triangles.extend(quad(c, DVec3::X, DVec3::Y));
    }
    // 45 degrees above the sheets, 30 degrees round from their rows: corners at many depths.
    let (e, a) = (45f64.to_radians(), 30f64.to_radians());
    let camera = camera(
        DVec3::new(a.sin() * e.cos(), -a.cos() * e.cos(), e.sin()) * 5.0,
        DVec3::Z,
    );
    MeasuredCase {
        name: "six sheets 1e-5 apart at 45 degrees".into(),
        triangles,
        camera,
    }
}

/// Every measured case of the issue.
pub fn cases() -> Vec<MeasuredCase> {
    vec![
        crossing(1e-6),
        crossing(1e-9),
        stack(),
        plate(1e-4),
        plate(1e-5),
        plate(1e-6),
        sheets(),
    ]
}

/// The band around the world reference's edges and meeting lines, in NDC.
///
/// `rho_xy`, `rho_z` bound the rounding of every projected coordinate: the largest difference,
/// over the case's vertices, between the f64 NDC the kernel starts from (the f64 matrix product
/// and division) and the exact rational NDC, plus 2^-53 (half an ulp of 1: one more rounding of
/// an NDC value, which the issue allows the kernel's grid). A point is in the band when
/// - it lies within `2e-9 + √2·rho_xy` of an edge (1e-9 of the view width, plus how far a
///   corner may move), or
/// - another face G containing it lies behind the nearest face N by no more than the two planes'
///   depth rounding: `z_G - z_N <= 2·rho_z + rho_xy·(|∇z_N|₁ + |∇z_G|₁) + 2e-9·|∇z_N - ∇z_G|`
///   (∇z the NDC depth gradient of each exact plane). Near the line where the two meet this is
///   a distance `2e-9 + (2·rho_z + rho_xy·(|∇z_N|₁ + |∇z_G|₁)) / |∇z_N - ∇z_G|` from it: the
///   rounding divided by the angle between the surfaces (in NDC), as the issue asks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Band {
    /// Bound on the rounding of projected x and y (NDC).
    pub rho_xy: f64,
    /// Bound on the rounding of projected depth (NDC).
    pub rho_z: f64,
}

/// What [`measure`] found.
#[derive(Clone, Debug)]
pub struct Measurement {
    /// The case's name.
    pub name: String,
    /// Pixel centres sampled.
    pub samples: u64,
    /// Samples in the band (not compared).
    pub in_band: u64,
    /// Samples on a piece boundary and inside no piece (no engine answer).
    pub on_piece_boundary: u64,
    /// Samples where the engine's face is not the reference's, outside the band.
    pub wrong: u64,
    /// The band used.
    pub band: Band,
    /// The kernel's own rounding of the same vertices: the largest difference between its grid
    /// coordinates (in NDC) and their exact NDC, (x and y, z). Reported, not used by the band:
    /// on a coarse grid it would widen the band over the very errors measured here.
    pub grid_rounding: [f64; 2],
    /// Kernel fallbacks while projecting and computing the visible set.
    pub fallbacks: u64,
    /// Seconds for the whole measurement.
    pub seconds: f64,
}

impl Measurement {
    /// `wrong / samples`.
    pub fn wrong_fraction(&self) -> f64 {
        self.wrong as f64 / self.samples.max(1) as f64
    }
}

/// A matrix entry or a world coordinate, exactly.
fn exact(v: f64) -> BigRational {
    rational(v)
}

/// Exact clip coordinates of a world point under `m` (entries taken exactly).
fn clip(m: &DMat4, p: DVec3) -> [BigRational; 4] {
    let pe = [
        exact(p.x),
        exact(p.y),
        exact(p.z),
        BigRational::from_integer(1.into()),
    ];
    std::array::from_fn(|row| {
        (0..4).fold(BigRational::zero(), |s, col| {
            s + exact(m.col(col)[row]) * &pe[col]
        })
    })
}

/// Sutherland–Hodgman in exact rationals against `value(p) >= 0`.
fn clip_by(
    poly: Vec<[BigRational; 4]>,
    value: impl Fn(&[BigRational; 4]) -> BigRational,
) -> Vec<[BigRational; 4]> {
    let n = poly.len();
    let mut out = Vec::new();
    for k in 0..n {
        let (a, b) = (&poly[k], &poly[(k + 1) % n]);
        let (da, db) = (value(a), value(b));
        if !da.is_negative() {
            out.push(a.clone());
        }
        if da.is_negative() != db.is_negative() && !(da.is_zero() || db.is_zero()) {
            let t = &da / (&da - &db);
            out.push(std::array::from_fn(|i| &a[i] + &t * (&b[i] - &a[i])));
        }
    }
    out
}

/// The exact NDC polygons of the scene's faces (clipped by near and far), as reference
/// polygons; faces seen edge-on or clipped away are left out.
fn world_polygons(scene: &Scene, camera: &Camera) -> Vec<Polygon> {
    let m = camera.view_projection();
    let mut exact = Vec::new();
    for (k, f) in scene.faces.iter().enumerate() {
        let poly: Vec<[BigRational; 4]> = scene.face_positions(f).map(|p| clip(&m, p)).collect();
        let poly = clip_by(poly, |p| &p[2] + &p[3]);
        let poly = clip_by(poly, |p| &p[3] - &p[2]);
        if poly.len() < 3 {
            continue;
        }
        let ndc: Vec<[BigRational; 3]> = poly
            .iter()
            .map(|p| [&p[0] / &p[3], &p[1] / &p[3], &p[2] / &p[3]])
            .collect();
        let plane = (1..ndc.len() - 1).find_map(|j| Plane::through(&ndc[0], &ndc[j], &ndc[j + 1]));
        let Some(plane) = plane else { continue };
        let corners: Vec<Point> = ndc.iter().map(|p| Point::of(&p[0], &p[1])).collect();
        exact.push((k as u32, f.id, corners, plane));
    }
    // Prefilter margins relative to the largest coordinate (a floor reaching behind the camera
    // projects far outside the view).
    let extent = exact
        .iter()
        .flat_map(|(_, _, c, _)| c.iter().flat_map(|p| p.to_f64()))
        .fold(1.0, |m: f64, v| m.max(v.abs()));
    exact
        .into_iter()
        .map(|(face, id, corners, plane)| Polygon::new(face, id, corners, plane, extent * 1e-12))
        .collect()
}

/// The band of a case: the f64 projection's rounding of its vertices (see [`Band`]), and the
/// kernel's grid rounding of the same vertices.
fn roundings(scene: &Scene, camera: &Camera) -> (Band, [f64; 2]) {
    let m = camera.view_projection();
    let (sxy, sz) = kernel::grid_scale();
    let (mut band, mut grid) = (
        Band {
            rho_xy: 0.0,
            rho_z: 0.0,
        },
        [0.0f64; 2],
    );
    for &p in &scene.positions {
        let c = clip(&m, p);
        if !c[3].is_positive() || (&c[2] + &c[3]).is_negative() || (&c[3] - &c[2]).is_negative() {
            continue;
        }
        let ndc: [BigRational; 3] = std::array::from_fn(|i| &c[i] / &c[3]);
        let diff = |approx: &BigRational, i: usize| {
            (approx - &ndc[i]).abs().to_f64().unwrap_or(f64::INFINITY)
        };
        let f: DVec4 = m * p.extend(1.0);
        let f64_ndc = [f.x / f.w, f.y / f.w, f.z / f.w];
        band.rho_xy = band
            .rho_xy
            .max(diff(&exact(f64_ndc[0]), 0))
            .max(diff(&exact(f64_ndc[1]), 1));
        band.rho_z = band.rho_z.max(diff(&exact(f64_ndc[2]), 2));
        if let Some(g) = kernel::snapped_vertex(camera, p) {
            let on =
                |v: &num_bigint::BigInt, s: f64| BigRational::from_integer(v.clone()) / exact(s);
            grid[0] = grid[0]
                .max(diff(&on(&g[0], sxy), 0))
                .max(diff(&on(&g[1], sxy), 1));
            grid[1] = grid[1].max(diff(&on(&g[2], sz), 2));
        }
    }
    let half_ulp = f64::EPSILON / 2.0;
    band.rho_xy += half_ulp;
    band.rho_z += half_ulp;
    (band, grid)
}

impl Band {
    /// Is the NDC point p (nearest face `n`, faces `containing` it) in the band?
    fn holds(&self, polys: &[Polygon], n: Option<usize>, containing: &[usize], p: &Point) -> bool {
        let q = p.to_f64();
        let edge = 2e-9 + std::f64::consts::SQRT_2 * self.rho_xy;
        if polys.iter().any(|g| g.edge_within(p, q, 1e-12, edge)) {
            return true;
        }
        let Some(n) = n else { return false };
        let pn = &polys[n];
        let gn = pn.plane.gradient();
        containing.iter().any(|&g| {
            let pg = &polys[g];
            if g == n || pn.plane.same(&pg.plane) {
                return false;
            }
            let gg = pg.plane.gradient();
            let l1 = |v: [f64; 2]| v[0].abs() + v[1].abs();
            let apart = (gn[0] - gg[0]).hypot(gn[1] - gg[1]);
            let allowed = 2.0 * self.rho_z + self.rho_xy * (l1(gn) + l1(gg)) + 2e-9 * apart;
            // The f64 depths settle most points; the exact gap (rounded once) the rest.
            if let (Some((zn, en)), Some((zg, eg))) = (pn.depth_f64(q), pg.depth_f64(q)) {
                let (gap, err) = (zg - zn, en + eg);
                if gap - err > allowed * (1.0 + 1e-9) {
                    return false;
                }
                if gap + err < allowed * (1.0 - 1e-9) {
                    return true;
                }
            }
            depth_gap(&pn.plane, &pg.plane, p) <= allowed
        })
    }
}

/// `z_g - z_n` at p, exactly, rounded once: `(N_n·c_g - N_g·c_n) / (c_n·c_g·w)` with
/// `z = -N / (c·w)`.
fn depth_gap(n: &Plane, g: &Plane, p: &Point) -> f64 {
    let (cn, cg) = (&n.coefficients[2], &g.coefficients[2]);
    let num = n.depth_value(p) * cg - g.depth_value(p) * cn;
    super::geometry::ratio_f64(&num, &(cn * cg * &p.w))
}

/// Measures a case: the fraction of `points` pixel centres (all of them when `points` is at
/// least the image's pixel count, else a random subset drawn from `seed`) where the engine's
/// face differs from the world reference's outside the band.
pub fn measure(
    case: &MeasuredCase,
    strategy: &dyn crate::Strategy,
    points: usize,
    seed: u64,
) -> Measurement {
    let start = std::time::Instant::now();
    let scene = case.scene();
    let camera = &case.camera;
    let before = kernel::fallbacks();
    let prepared = crate::pipeline::prepare(&scene, camera, crate::project::CullMode::Auto);
    let visible = strategy.visible_set(&prepared.screen, &|_| false, None);
    let fallbacks = kernel::fallbacks() - before;
    let faces: Vec<u32> = prepared.screen.polys.iter().map(|p| p.face).collect();

    let pieces: Vec<Convex> = kernel::pieces(&visible)
        .into_iter()
        .map(|p| Convex::new(p.poly, p.lines, kernel::grid_scale().0 * 4e-12))
        .collect();
    let polys = world_polygons(&scene, camera);
    let (band, grid_rounding) = roundings(&scene, camera);
    let (w, h) = (camera.width as u64, camera.height as u64);
    let all = points as u64 >= w * h;
    let count = if all { w * h } else { points as u64 };
    let mut rng = Rng::of(&[seed, 0x3ea5]);
    let scale = exact(kernel::grid_scale().0);
    let mut m = Measurement {
        name: case.name.clone(),
        samples: count,
        in_band: 0,
        on_piece_boundary: 0,
        wrong: 0,
        band,
        grid_rounding,
        fallbacks,
        seconds: 0.0,
    };
    for k in 0..count {
        let pixel = if all { k } else { rng.next_u64() % (w * h) };
        let (i, j) = ((pixel % w) as i64, (pixel / w) as i64);
        let x = BigRational::new((2 * i + 1 - w as i64).into(), (w as i64).into());
        let y = BigRational::new((h as i64 - 2 * j - 1).into(), (h as i64).into());
        let p = Point::of(&x, &y);
        let g = Point::of(&(&x * &scale), &(&y * &scale));
        let gq = g.to_f64();
        let (mut inside, mut on) = (None, false);
        for piece in &pieces {
            match piece.locate(&g, gq, gq[0].abs().max(gq[1].abs()) * 1e-12) {
                Loc::Inside => inside = Some(faces[piece.poly]),
                Loc::Boundary => on = true,
                Loc::Outside => {}
            }
        }
        if inside.is_none() && on {
            m.on_piece_boundary += 1;
            continue;
        }
        let (n, containing) = nearest(&polys, &p, p.to_f64(), 1e-12);
        let reference = n.map(|n| polys[n].face);

        if band.holds(&polys, n, &containing, &p) {
            m.in_band += 1;
        } else if inside != reference {
            m.wrong += 1;
        }
    }
    m.seconds = start.elapsed().as_secs_f64();
    m
}
