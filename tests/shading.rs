//! Shading, perspective-correct interpolation and textures: the worked numbers of seeds 002 and
//! 004, and renders whose pixels are predicted by hand.

mod support;

use glam::DVec3;
use sightline::Scene;
use sightline::camera::{Camera, Projection};
use sightline::paint::lighting::{FILL, KEY, Light, Lighting};
use sightline::paint::{flat_color, to_u8};
use sightline::pipeline::render_zbuffer;
use sightline::project::CullMode;
use sightline::raster::interpolate::{
    hit_face, perspective_correct, perspective_depth, perspective_weights, screen_weights,
};
use sightline::raster::lighting::{Shading, Textures, shade_zbuffer, vertex_normals};
use sightline::raster::texture::{Mipmap, level_of_detail};
use sightline::scene::CameraLights;
use sightline::scene::primitives::sphere_scene;
use support::camera::look_at;
use support::fixtures::{fixture, fixtures_dir};
use support::render::flat_headlight;

fn round3(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

/// Seed 002: the triangle (26.95, 23.52), (32.77, 23.18), (30, 16.65), pixel (28.5, 22.5).
#[test]
fn seed_002_screen_weights_depth_and_corrected_colour() {
    let w = screen_weights([28.5, 22.5], [26.95, 23.52], [32.77, 23.18], [30.0, 16.65]);
    assert_eq!(w.map(round3), [0.668, 0.194, 0.139]);
    let z = [9.5, 10.5, 10.0];
    // The seed goes on with its printed (rounded) weights, which sum to 1.001.
    let printed = [0.668, 0.194, 0.139];
    let depth = perspective_depth(printed, z);
    assert_eq!((depth * 100.0).round() / 100.0, 9.74);
    let rgb = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let c = perspective_correct(printed, z, rgb);
    assert_eq!(c.map(round3), [0.685, 0.180, 0.135]);
    // With the unrounded weights the depth is 9.75 and the colour still rounds to the same three digits;
    // the seed's "these numbers may vary with your implementation".
    assert_eq!((perspective_depth(w, z) * 100.0).round() / 100.0, 9.75);
    assert_eq!(
        perspective_correct(w, z, rgb).map(round3),
        [0.685, 0.180, 0.135]
    );
}

fn persp_camera(eye: DVec3, size: u32) -> Camera {
    look_at(
        eye,
        DVec3::ZERO,
        Projection::Perspective { fovy_deg: 40.0 },
        0.5,
        20.0,
        (size, size),
    )
}

/// The renderer's ray-plane weights are the seed's perspective-corrected screen weights.
#[test]
fn ray_hit_weights_equal_corrected_screen_weights() {
    let cam = persp_camera(DVec3::new(1.0, 2.0, 6.0), 100);
    let tri = [
        DVec3::new(-1.0, -1.0, 0.5),
        DVec3::new(1.5, -0.5, -2.0),
        DVec3::new(0.0, 1.2, 1.0),
    ];
    let vp = cam.view_projection();
    let view = cam.view_matrix();
    let screen = tri.map(|p| {
        let n = vp.project_point3(p);
        [(n.x + 1.0) * 50.0, (1.0 - n.y) * 50.0]
    });
    let depth = tri.map(|p| -view.transform_point3(p).z);
    let (i, j) = (
        ((screen[0][0] + screen[1][0] + screen[2][0]) / 3.0).floor(),
        ((screen[0][1] + screen[1][1] + screen[2][1]) / 3.0).floor(),
    );
    let w = screen_weights([i + 0.5, j + 0.5], screen[0], screen[1], screen[2]);
    let expected = perspective_weights(w, depth);
    let (x, y) = cam.pixel_center_ndc(i as u32, j as u32);
    let (o, d) = cam.ray_through_ndc(x, y);
    let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
    let hit = hit_face(&tri, n, o, d).unwrap();
    for k in 0..3 {
        assert!(
            (hit.weights[k] - expected[k]).abs() < 1e-9,
            "{hit:?} {expected:?}"
        );
    }
    // And they differ from the uncorrected screen weights: the correction matters here.
    assert!((0..3).any(|k| (w[k] - expected[k]).abs() > 1e-3));
}

/// Seed 002, mipmap: chess.png 32x32, pixel (28, 22) at UV (0.264, 0.139), right neighbour
/// (0.414, 0.129), lower neighbour (0.248, -0.010).
#[test]
fn seed_002_level_of_detail() {
    // The seed's rounded derivatives (texels per pixel): L = 4.83, D = 2.27, level 2.
    let (l, d) = level_of_detail(4.8, -0.32, -0.56, -4.8);
    assert_eq!((l * 100.0).round() / 100.0, 4.83);
    assert_eq!((d * 100.0).round() / 100.0, 2.27);
    assert_eq!(d.floor(), 2.0);
    // From the UVs themselves: 32·(0.248 - 0.264) is -0.512 (the seed prints -0.56), so L is
    // the x derivative's 4.81; D still rounds to 2.27 and the level is still 2.
    let mip = Mipmap::new(32, 32, vec![[0.0; 3]; 32 * 32]);
    let d2 = mip.lod(0.414 - 0.264, 0.129 - 0.139, 0.248 - 0.264, -0.010 - 0.139);
    assert_eq!((d2 * 100.0).round() / 100.0, 2.27);
    assert_eq!(d2.floor(), 2.0);
    assert_eq!(mip.levels.len(), 6);
    assert_eq!((mip.levels[2].width, mip.levels[2].height), (8, 8));
}

#[test]
fn trilinear_blends_the_two_levels() {
    // 2x2: black, white / white, black. Level 1 is grey 0.5.
    let b = [0.0; 3];
    let w = [1.0; 3];
    let mip = Mipmap::new(2, 2, vec![b, w, w, b]);
    assert_eq!(mip.levels[1].texels, vec![[0.5; 3]]);
    // Texel (0, 0) (top left, black) has its centre at u = 0.25, v = 0.75.
    assert_eq!(mip.trilinear(0.25, 0.75, 0.0), b);
    assert_eq!(mip.trilinear(0.75, 0.75, -3.0), w);
    let t = mip.trilinear(0.25, 0.75, 0.25);
    assert!((t[0] - 0.125).abs() < 1e-12, "{t:?}");
    assert_eq!(mip.trilinear(0.25, 0.75, 7.0), [0.5; 3]);
}

/// Seed 004: I = Ia·Ka + Il·(Kd·cos θ + Ks·cosⁿ α), lights adding linearly.
#[test]
fn seed_004_lighting_model() {
    let mut lighting = Lighting {
        ambient: 0.1,
        diffuse: 0.6,
        specular: 0.5,
        shininess: 10.0,
        camera_lights: [None, None],
        view: None,
        lights: vec![Light::Directional {
            // cos θ = 0.5 (60° from the normal), travelling towards -x, -z.
            direction: DVec3::new(-(3f64.sqrt()) / 2.0, 0.0, -0.5),
            intensity: [1.0; 3],
        }],
    };
    let n = DVec3::Z;
    let p = DVec3::ZERO;
    // Eye on the mirror direction: cos α = 1.
    let mirror = DVec3::new(-(3f64.sqrt()) / 2.0, 0.0, 0.5) * 4.0;
    let (lit, spec) = lighting.terms(n, p, mirror, true);
    assert!((lit[0] - (0.1 + 0.6 * 0.5)).abs() < 1e-12, "{lit:?}");
    assert!((spec[0] - 0.5).abs() < 1e-12, "{spec:?}");
    // Eye straight above: α = 60°, cos α = 0.5, 0.5^10.
    let (_, spec) = lighting.terms(n, p, DVec3::Z * 3.0, true);
    assert!((spec[0] - 0.5 * 0.5f64.powi(10)).abs() < 1e-12, "{spec:?}");
    // A point light straight above adds Kd·1 and, seen from above, Ks·1.
    lighting.lights.push(Light::Point {
        position: DVec3::Z * 2.0,
        intensity: [0.5, 0.0, 0.0],
    });
    let (lit, spec) = lighting.terms(n, p, DVec3::Z * 3.0, true);
    assert!((lit[0] - (0.1 + 0.3 + 0.5 * 0.6)).abs() < 1e-12);
    assert!((lit[1] - (0.1 + 0.3)).abs() < 1e-12);
    assert!((spec[0] - (0.5 * 0.5f64.powi(10) + 0.5 * 0.5)).abs() < 1e-12);
    // The back of the surface is lit as its front (normal turned to the viewer).
    let (lit_back, _) = lighting.terms(-n, p, DVec3::Z * 3.0, true);
    assert_eq!(lit_back, lit);
    // A light behind the surface adds nothing but ambient.
    let behind = Lighting {
        lights: vec![Light::Directional {
            direction: DVec3::Z,
            intensity: [1.0; 3],
        }],
        ..lighting.clone()
    };
    assert_eq!(behind.terms(n, p, DVec3::Z, true), ([0.1; 3], [0.0; 3]));
}

#[test]
fn vertex_normals_keep_cad_edges_and_smooth_spheres() {
    let cube = fixture("cube_ascii.stl");
    let vn = vertex_normals(&cube);
    for f in &cube.faces {
        let fnorm = cube.face_normal(f).normalize();
        for k in 0..f.len as usize {
            assert!((vn[f.start as usize + k] - fnorm).length() < 1e-12);
        }
    }
    let sphere = sphere_scene(200);
    let vn = vertex_normals(&sphere);
    for f in &sphere.faces {
        for (k, p) in sphere.face_positions(f).enumerate() {
            // A smooth sphere's vertex normal is close to the radius direction.
            assert!(vn[f.start as usize + k].dot(p.normalize()) > 0.99);
        }
    }
}

#[test]
fn flat_through_lighting_is_the_flat_renderer() {
    let scene = fixture("cube.obj");
    let cam = persp_camera(DVec3::new(3.0, 2.5, 4.0), 48);
    let (prep, zb) = render_zbuffer(&scene, &cam, CullMode::Auto, |_| {});
    let img = shade_zbuffer(
        &scene,
        &prep.screen,
        &zb,
        &cam,
        // Flat and matte, as `flat_color` under the scene's (default) lights.
        &Lighting {
            specular: 0.0,
            ..Lighting::of_scene(&scene, &cam)
        },
        Shading::Flat,
        &Textures::load(&scene),
        [0.0; 3],
    );
    let mut covered = 0;
    for (idx, &p) in zb.poly.iter().enumerate() {
        if p == sightline::raster::EMPTY {
            assert_eq!(img[idx], [0.0; 3]);
            continue;
        }
        covered += 1;
        let want = flat_color(&scene, prep.screen.polys[p as usize].face as usize, &cam);
        for k in 0..3 {
            assert!((img[idx][k] - want[k]).abs() < 1e-12);
        }
    }
    assert!(covered > 200);
}

/// On a sphere, Gouraud and Phong are smooth where flat is not, Phong shows a highlight at the
/// mirror point that Gouraud (highlight only at vertices, interpolated) spreads and dims.
#[test]
fn gouraud_and_phong_on_a_sphere() {
    let scene = sphere_scene(800);
    let cam = persp_camera(DVec3::new(0.0, 0.0, 4.0), 64);
    let (prep, zb) = render_zbuffer(&scene, &cam, CullMode::Auto, |_| {});
    let lighting = Lighting::headlight(&cam);
    let matte = Lighting {
        specular: 0.0,
        ..lighting.clone()
    };
    let tex = Textures::default();
    let render = |s| {
        shade_zbuffer(
            &scene,
            &prep.screen,
            &zb,
            &cam,
            &lighting,
            s,
            &tex,
            [0.0; 3],
        )
    };
    let matte_render =
        |s| shade_zbuffer(&scene, &prep.screen, &zb, &cam, &matte, s, &tex, [0.0; 3]);
    // Flat with Ks > 0 adds each face's highlight at its centroid; compare with flat matte.
    let (flat, gouraud, phong) = (
        matte_render(Shading::Flat),
        render(Shading::Gouraud),
        render(Shading::Phong),
    );
    let centre = 32 * 64 + 32;
    // Facing the headlight: lit = 0.2 + 0.8 = 1, base 0.8, highlight Ks = 0.3 → clamped 1.
    assert!(phong[centre][0] > 0.99, "{:?}", phong[centre]);
    assert!(flat[centre][0] < 0.81);
    assert!(gouraud[centre][0] > flat[centre][0]);
    // Smoothness: the largest jump between horizontal neighbours in the middle of the sphere
    // (away from the limb, where even smooth shading falls off steeply).
    let jump = |img: &[[f64; 3]]| {
        let mut m: f64 = 0.0;
        for j in 20..44 {
            for i in 20..43 {
                let (a, b) = (j * 64 + i, j * 64 + i + 1);
                if zb.poly[a] != sightline::raster::EMPTY && zb.poly[b] != sightline::raster::EMPTY
                {
                    m = m.max((img[a][0] - img[b][0]).abs());
                }
            }
        }
        m
    };
    // Without the (sharp, n = 32) highlight, the smooth shadings have no facet steps.
    let (mf, mg, mp) = (
        matte_render(Shading::Flat),
        matte_render(Shading::Gouraud),
        matte_render(Shading::Phong),
    );
    assert!(jump(&mp) < jump(&mf) / 2.0, "{} {}", jump(&mp), jump(&mf));
    assert!(jump(&mg) < jump(&mf) / 2.0, "{} {}", jump(&mg), jump(&mf));
}

/// The 16x16 one-texel checkerboard (white at texel (0, 0), the top left).
fn checker16() -> Vec<[f64; 3]> {
    (0..16 * 16)
        .map(|k| {
            let (x, y) = (k % 16, k / 16);
            if (x + y) % 2 == 0 { [1.0; 3] } else { [0.0; 3] }
        })
        .collect()
}

#[test]
fn checker_fixture_is_the_generated_checkerboard() {
    let path = fixtures_dir().join("checker16.png");
    let want = checker16();
    if std::env::var_os("SIGHTLINE_WRITE_FIXTURES").is_some() {
        let img = image::RgbImage::from_fn(16, 16, |x, y| {
            image::Rgb(want[(y * 16 + x) as usize].map(|c| (c * 255.0) as u8))
        });
        img.save(&path).unwrap();
    }
    let mip = Mipmap::load(&path).unwrap();
    assert_eq!(mip.levels[0].texels, want);
}

/// The textured quad of `fixtures/checker_quad.obj`, flat and matte under the seed's headlight.
fn render_checker(size: u32) -> Vec<[f64; 3]> {
    let scene = fixture("checker_quad.obj");
    assert!(scene.corner_uvs.iter().all(|u| u.is_some()));
    assert_eq!(scene.corner_normals, vec![Some(DVec3::Z); 4]);
    flat_headlight(&scene, size)
}

/// One pixel per texel (L = 1, level 0): every pixel centre is a texel centre, so the image is
/// the checkerboard itself (headlight straight on: ambient + diffuse = 1, Kd = 1).
#[test]
fn textured_quad_at_one_texel_per_pixel_is_the_checkerboard() {
    let img = render_checker(16);
    let want = checker16();
    for (k, (got, want)) in img.iter().zip(&want).enumerate() {
        for c in 0..3 {
            assert!(
                (got[c] - want[c]).abs() < 1e-9,
                "pixel {k}: {got:?} vs {want:?}"
            );
        }
    }
}

/// Two texels per pixel (L = 2, level 1): level 1 of a one-texel checkerboard is uniform grey.
#[test]
fn textured_quad_minified_shows_the_grey_of_level_one() {
    let img = render_checker(8);
    for (k, got) in img.iter().enumerate() {
        for c in got {
            assert!((c - 0.5).abs() < 1e-9, "pixel {k}: {got:?}");
        }
    }
}

/// The flat colours (8-bit) of the cube's faces turned towards +x, +y and +z, in the iso view
/// fitted as the CLI fits it.
fn iso_cube_face_colours(scene: &Scene) -> Vec<[u8; 3]> {
    let spec = sightline::camera::CameraSpec {
        view: Some(sightline::camera::NamedView::Iso),
        ..Default::default()
    };
    let cam = spec.resolve(scene.bounds().unwrap(), None).unwrap();
    [DVec3::X, DVec3::Y, DVec3::Z]
        .iter()
        .map(|axis| {
            let face = (0..scene.faces.len())
                .find(|&f| scene.face_normal(&scene.faces[f]).normalize().dot(*axis) > 0.99)
                .expect("the cube has a face on every side");
            to_u8(flat_color(scene, face, &cam))
        })
        .collect()
}

fn rgb_sum_difference(a: [u8; 3], b: [u8; 3]) -> i32 {
    (0..3).map(|k| (a[k] as i32 - b[k] as i32).abs()).sum()
}

/// Point 12 of issue 8: by default the three faces of the iso cube (one material) get three
/// clearly different shades, brightest on top; the headlight, kept for `--headlight`, lights
/// them alike.
#[test]
fn default_lights_give_the_iso_cube_three_shades() {
    let mut scene = fixture("cube_ascii.stl");
    let [x, y, z] = iso_cube_face_colours(&scene)[..] else {
        unreachable!()
    };
    for (a, b) in [(x, y), (y, z), (z, x)] {
        assert!(rgb_sum_difference(a, b) > 20, "{x:?} {y:?} {z:?}");
    }
    assert!(
        y[0] > z[0] && z[0] > x[0],
        "top, left, right: {y:?} {z:?} {x:?}"
    );
    // Nothing blown out or black: the darkest face keeps ambient + fill.
    assert!(y[0] < 250 && x[0] > 60, "{x:?} {y:?}");
    scene.lights.camera = CameraLights::Headlight;
    let head = iso_cube_face_colours(&scene);
    assert!(head.iter().all(|c| *c == head[0]), "{head:?}");
}

/// The default key and fill lights are fixed to the camera: a face turned towards the key light,
/// as the camera sees it, gets the same light from every camera position.
#[test]
fn camera_lights_follow_the_camera() {
    let scene = Scene::default();
    let dot = (0..3)
        .map(|k| KEY.towards[k] * FILL.towards[k])
        .sum::<f64>();
    let want = 0.2 + 0.8 * (KEY.intensity + FILL.intensity * dot.max(0.0));
    for eye in [
        DVec3::new(0.0, 0.0, 5.0),
        DVec3::new(3.0, 2.5, 4.0),
        DVec3::new(-7.0, -1.0, 0.5),
        DVec3::new(0.1, -6.0, 0.2),
    ] {
        let cam = persp_camera(eye, 32);
        let lighting = Lighting::of_scene(&scene, &cam);
        let forward = cam.forward();
        let right = forward.cross(cam.up).normalize();
        let up = right.cross(forward);
        let [kx, ky, kz] = KEY.towards;
        let n = right * kx + up * ky - forward * kz;
        let (lit, spec) = lighting.terms(n, DVec3::ZERO, eye, false);
        assert!((lit[0] - want).abs() < 1e-12, "{eye}: {lit:?} vs {want}");
        assert_eq!(spec, [0.0; 3]);
    }
}

/// The default lights never saturate a white matte face, whatever its direction: at most what
/// the headlight gives a face seen head-on (Ka + Kd = 1).
#[test]
fn default_lights_do_not_blow_out_a_white_face() {
    let cam = persp_camera(DVec3::new(3.0, 2.5, 4.0), 32);
    let lighting = Lighting::of_scene(&Scene::default(), &cam);
    let n = 20_000;
    let mut most: f64 = 0.0;
    for i in 0..n {
        // Fibonacci sphere: normals spread evenly over every direction.
        let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
        let a = i as f64 * std::f64::consts::PI * (3.0 - 5f64.sqrt());
        let r = (1.0 - z * z).sqrt();
        let normal = DVec3::new(r * a.cos(), r * a.sin(), z);
        most = most.max(lighting.terms(normal, DVec3::ZERO, cam.eye, false).0[0]);
    }
    assert!(most <= 1.0 && most > 0.99, "{most}");
}
