//! Measures seams in the filled SVG of a scene, as issue 8 defines them, with and without the
//! seam strokes under the fills:
//!
//! - (a) the SVG without background, rasterized by resvg onto transparency with anti-aliasing:
//!   the sum of alpha against the exact visible area of the opaque faces (the per-face drawing,
//!   as the JSON has it);
//! - (b) over white, the share of pixels inside the silhouette (3x3 neighbourhood covered in
//!   the z-buffer) whose colour differs from all nine z-buffer flat colours around it by more
//!   than 24 in R+G+B, and (b') the share farther than 24 from the range of those colours (so
//!   that a blend of two neighbouring faces' colours at a crease is not counted);
//! - the same (b) and (b') for the ideal anti-aliased image, the z-buffer at 4x4 samples per
//!   pixel averaged: (b) counts blends of neighbouring faces' colours at every crease, so even
//!   the ideal image has some;
//! - (a) again with `rsvg-convert` when it is installed (librsvg, another renderer);
//! - the SVG's size.
//!
//! `cargo run --release --example seams -- MESH[:CAM] ... [--size WxH] [--sphere N]`
//! (`MESH:CAM` uses that camera file; without one, the iso view).

#[path = "../tests/support/seam_measure.rs"]
mod seam_measure;

use seam_measure::{alpha_area, over_white, rasterize, rings_area, seam_defects};
use sightline::camera::{CamFile, CameraSpec};
use sightline::draw::{DrawOptions, picture};
use sightline::output::svg::{SvgOptions, write_svg};
use sightline::pipeline::{Fill, colorize_polys, prepare};
use sightline::project::CullMode;
use sightline::raster::{EMPTY, zbuffer};
use sightline::scene::Scene;
use sightline::visibility::CoverageMap;

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut size = None;
    if let Some(i) = args.iter().position(|a| a == "--size") {
        let s = args.remove(i + 1);
        args.remove(i);
        let (w, h) = s.split_once('x').expect("--size WxH");
        size = Some((w.parse().unwrap(), h.parse().unwrap()));
    }
    let mut scenes: Vec<(String, Scene, Option<CamFile>)> = Vec::new();
    let mut k = 0;
    while k < args.len() {
        if args[k] == "--sphere" {
            let n: usize = args[k + 1].parse().expect("--sphere N");
            scenes.push((
                format!("sphere {n}"),
                sightline::scene::primitives::sphere_scene(n),
                None,
            ));
            k += 2;
            continue;
        }
        let (mesh, cam) = match args[k].split_once(':') {
            Some((m, c)) => (m.to_string(), Some(c.to_string())),
            None => (args[k].clone(), None),
        };
        let scene = sightline::scene::load(std::path::Path::new(&mesh), None).expect("loads");
        let cam = cam.map(|c| {
            CamFile::parse(&std::fs::read_to_string(&c).expect("reads"), &c).expect("parses")
        });
        scenes.push((mesh, scene, cam));
        k += 1;
    }
    println!(
        "| scene | exact area px | (a) before | (a) after | (b) before | (b) after | (b) ideal | (b') before | (b') after | (b') ideal | (a) rsvg-convert before / after | SVG bytes before | after |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (name, scene, cam) in scenes {
        let spec = CameraSpec {
            cam_file: cam,
            size,
            ..CameraSpec::default()
        };
        let camera = spec
            .resolve(scene.bounds().expect("faces"), scene.viewpoint.as_ref())
            .expect("camera");
        let (w, h) = (camera.width, camera.height);
        let prepared = prepare(&scene, &camera, CullMode::Auto);
        let screen = &prepared.screen;
        let merged = picture(
            &CoverageMap,
            &scene,
            screen,
            &camera,
            Fill::Shade,
            DrawOptions::picture(),
            None,
        )
        .drawing;
        let per_face = picture(
            &CoverageMap,
            &scene,
            screen,
            &camera,
            Fill::Shade,
            DrawOptions::per_face(),
            None,
        )
        .drawing;
        let exact: f64 = per_face
            .items
            .iter()
            .filter(|i| i.opacity >= 1.0)
            .map(|i| rings_area(&i.rings))
            .sum();
        let zb = zbuffer::render(screen, |_| {});
        let reference = colorize_polys(&scene, screen, &zb.poly, &camera, Fill::Shade, [255; 3]);
        let covered: Vec<bool> = zb.poly.iter().map(|&p| p != EMPTY).collect();
        // The ideal anti-aliased image: the z-buffer at 4x4 samples per pixel, averaged.
        let ideal = {
            let mut big = camera;
            big.width *= 4;
            big.height *= 4;
            let prepared = prepare(&scene, &big, CullMode::Auto);
            let zb = zbuffer::render(&prepared.screen, |_| {});
            let colors = colorize_polys(
                &scene,
                &prepared.screen,
                &zb.poly,
                &big,
                Fill::Shade,
                [255; 3],
            );
            let bw = big.width as usize;
            (0..(w * h) as usize)
                .map(|k| {
                    let (i, j) = (k % w as usize, k / w as usize);
                    let mut sum = [0u32; 3];
                    for y in 4 * j..4 * j + 4 {
                        for x in 4 * i..4 * i + 4 {
                            for c in 0..3 {
                                sum[c] += colors[y * bw + x][c] as u32;
                            }
                        }
                    }
                    sum.map(|v| ((v + 8) / 16) as u8)
                })
                .collect::<Vec<[u8; 3]>>()
        };
        let ideal_defects = seam_defects(&ideal, &reference, &covered, w as usize, h as usize);
        let mut before = merged.clone();
        before.seams = Default::default();
        let mut row = Vec::new();
        let mut sizes = Vec::new();
        let mut alphas = Vec::new();
        let mut rsvg = Vec::new();
        let mut defects = Vec::new();
        for d in [&before, &merged] {
            let mut d = d.clone();
            d.background = None;
            let svg = write_svg(&d, &SvgOptions::default());
            alphas.push(alpha_area(&svg, w, h));
            if let Some(a) = rsvg_alpha_area(&svg) {
                rsvg.push(a);
            }
            d.background = Some([1.0; 3]);
            let svg = write_svg(&d, &SvgOptions::default());
            sizes.push(svg.len());
            let rgb = over_white(&rasterize(&svg, w, h));
            defects.push(seam_defects(
                &rgb, &reference, &covered, w as usize, h as usize,
            ));
        }
        let pct = |a: f64| format!("{:+.3} %", 100.0 * (a - exact) / exact);
        let share = |n: usize, d: usize| format!("{:.3} %", 100.0 * n as f64 / d.max(1) as f64);
        row.push(name);
        row.push(format!("{exact:.1}"));
        row.push(pct(alphas[0]));
        row.push(pct(alphas[1]));
        row.push(share(defects[0].1, defects[0].0));
        row.push(share(defects[1].1, defects[1].0));
        row.push(share(ideal_defects.1, ideal_defects.0));
        row.push(share(defects[0].2, defects[0].0));
        row.push(share(defects[1].2, defects[1].0));
        row.push(share(ideal_defects.2, ideal_defects.0));
        row.push(match rsvg[..] {
            [b, a] => format!("{} / {}", pct(b), pct(a)),
            _ => "-".into(),
        });
        row.push(sizes[0].to_string());
        row.push(format!(
            "{} ({:+.1} %)",
            sizes[1],
            100.0 * (sizes[1] as f64 / sizes[0] as f64 - 1.0)
        ));
        println!("| {} |", row.join(" | "));
    }
}

/// (a) with `rsvg-convert`, if it is on the PATH.
fn rsvg_alpha_area(svg: &str) -> Option<f64> {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new("rsvg-convert")
        .args(["-f", "png"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .ok()?;
    child.stdin.take()?.write_all(svg.as_bytes()).ok()?;
    let out = child.wait_with_output().ok()?;
    let img = image::load_from_memory(&out.stdout).ok()?.to_rgba8();
    Some(img.pixels().map(|p| p.0[3] as f64 / 255.0).sum())
}
