//! The whole job of `render -o x.svg` after loading (projection and culling, the exact visible
//! set by the default method, regions, and the SVG written to nowhere) on the scenes issue 13
//! measures: the sphere of the benchmark file (1M triangles, generated here as
//! `../shared/compare/scenes.py` writes it: poles open, inside out), the 1,000-triangle soup,
//! and bunny, counter and dragon from `../shared/meshes` with their cameras (skipped, and said,
//! when that directory is not present). Before each benchmark one line on stderr gives the time
//! of each stage of one run, the pieces, the exact fallbacks and the process's peak memory so far.
//!
//! `cargo bench --bench drawing`; `cargo bench --bench drawing -- soup` for one scene.

#[allow(dead_code)] // the shared mesh group is for the per-method benches
mod common;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use sightline::camera::{CamFile, Camera};
use sightline::methods::Output;
use sightline::pipeline::prepare;
use sightline::project::CullMode;
use sightline::project::ScreenScene;
use sightline::render::{RenderOptions, Rendered, render};
use sightline::scene::Scene;
use sightline::scene::primitives::{exported_sphere_scene, random_triangle_soup};
use std::hint::black_box;
use std::path::Path;
use std::time::{Duration, Instant};

/// The SVG render of `scene` after projection (the visible set and the regions; the SVG is
/// written by `Rendered::write`).
fn rendered(scene: &Scene, cam: &Camera, screen: &ScreenScene) -> Rendered {
    let options = RenderOptions::new(Output::Svg);
    render(scene, cam, screen, &options, None).expect("an SVG of an opaque scene")
}

/// Projection, the visible set, the regions and the SVG: returns the bytes written.
fn run(scene: &Scene, cam: &Camera) -> usize {
    let prepared = prepare(scene, cam, CullMode::Auto);
    let rendered = rendered(scene, cam, &prepared.screen);
    let mut out = Vec::new();
    rendered.write(&mut out).expect("into memory");
    out.len()
}

/// One untimed run, reported stage by stage.
fn report(name: &str, scene: &Scene, cam: &Camera) {
    let t = Instant::now();
    let prepared = prepare(scene, cam, CullMode::Auto);
    let project = t.elapsed().as_secs_f64();
    let rendered = rendered(scene, cam, &prepared.screen);
    let t = Instant::now();
    rendered.write(&mut std::io::sink()).expect("to nowhere");
    let write = t.elapsed().as_secs_f64();
    let stages: Vec<String> = (rendered.stage_seconds.iter())
        .map(|(n, t)| format!("{n} {t:.3} s"))
        .collect();
    let peak = sightline::benchmark::peak_rss_kb().map_or("unknown".into(), |kb| {
        format!("{:.0} MB", kb as f64 / 1024.0)
    });
    eprintln!(
        "{name}: {} faces; project {project:.3} s, {}, SVG {write:.3} s; {}; peak memory so far {peak}",
        scene.faces.len(),
        stages.join(", "),
        rendered.detail.lines().last().unwrap_or_default(),
    );
}

fn issue_scenes(c: &mut Criterion) {
    let mut cases: Vec<(String, Scene, Camera)> = Vec::new();
    // The benchmark file's camera (`scenes.py`: eye (0.5, 1, 4), fovy 40, 800 x 800).
    let cam_text =
        "eye 0.5 1.0 4.0\ntarget 0 0 0\nup 0 1 0\nfovy 40\nnear 0.5\nfar 100\nsize 800 800\n";
    let sphere_cam = CamFile::parse(cam_text, "sphere").unwrap().camera();
    cases.push((
        "exported_sphere/1000000".into(),
        exported_sphere_scene(1_000_000),
        sphere_cam,
    ));
    let soup = random_triangle_soup(1_000, 1);
    let soup_cam = common::iso_1024(&soup);
    cases.push(("soup/1000".into(), soup, soup_cam));
    let dir = Path::new("../shared/meshes");
    for stem in ["bunny", "counter", "dragon"] {
        let mesh = [
            dir.join(format!("{stem}.obj")),
            dir.join(format!("{stem}.obj.gz")),
        ]
        .into_iter()
        .find(|p| p.exists());
        let cam = std::fs::read_to_string(dir.join("cams").join(format!("{stem}.cam")));
        match (mesh, cam) {
            (Some(mesh), Ok(cam)) => cases.push((
                format!("mesh/{stem}"),
                sightline::load(&mesh, None).unwrap(),
                CamFile::parse(&cam, stem).unwrap().camera(),
            )),
            _ => eprintln!("{stem}: not in ../shared/meshes (with cams/{stem}.cam): skipped"),
        }
    }
    let mut g = c.benchmark_group("drawing");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    for (name, scene, cam) in cases {
        report(&name, &scene, &cam);
        g.throughput(Throughput::Elements(scene.faces.len() as u64));
        g.bench_function(name, |b| b.iter(|| black_box(run(&scene, &cam))));
    }
    g.finish();
}

criterion_group!(benches, issue_scenes);
criterion_main!(benches);
