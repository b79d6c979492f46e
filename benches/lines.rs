//! Hidden-line drawings: for each scene, the visible set every line drawing starts from
//! (`visible set`: the coverage map, every face opaque) and the whole line drawing
//! (`lines`: `sightline::lines::line_drawing`, which makes the lines on a second thread while
//! the visible set is computed, then reads their visibility and chains them), so the two can be
//! compared in one run. Scenes: a 100k-triangle sphere, crossing tori (intersection lines),
//! a 1,000-triangle soup, and the meshes of `../shared/meshes` with their cameras when that
//! directory is present (it says so on stderr when it is not). Before each scene one line on
//! stderr gives its line counts.
//!
//! `cargo bench --bench lines`; `cargo bench --bench lines -- mesh` for the shared meshes.
//! The process-level ratio the issue asks for: `sightline bench MESH --cam CAM --lines`.

mod common;

use criterion::{BenchmarkGroup, Criterion, criterion_group, criterion_main};
use sightline::camera::Camera;
use sightline::lines::{LineOptions, line_drawing};
use sightline::pipeline::prepare;
use sightline::project::CullMode;
use sightline::scene::Scene;
use sightline::scene::primitives::{interpenetrating_tori, random_triangle_soup, sphere_scene};
use sightline::visibility::{CoverageMap, Strategy};
use std::hint::black_box;
use std::time::Duration;

fn visible_set(scene: &Scene, cam: &Camera) -> usize {
    let prepared = prepare(scene, cam, CullMode::Auto);
    CoverageMap
        .visible_set(&prepared.screen, &|_| false, None)
        .pieces
        .len()
}

fn lines(scene: &Scene, cam: &Camera) -> usize {
    line_drawing(scene, cam, &LineOptions::default(), None)
        .expect("a line drawing")
        .drawing
        .strokes
        .len()
}

fn add(
    g: &mut BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    scene: &Scene,
    cam: &Camera,
) {
    let l = line_drawing(scene, cam, &LineOptions::default(), None).expect("a line drawing");
    eprintln!(
        "{name}: features (silhouette, boundary, intersection, crease, material) {:?}, {} strokes, fewest possible {}",
        l.stats.features,
        l.drawing.strokes.len(),
        l.stats.paths_minimum
    );
    g.bench_function(format!("{name}/visible set"), |b| {
        b.iter(|| black_box(visible_set(scene, cam)))
    });
    g.bench_function(format!("{name}/lines"), |b| {
        b.iter(|| black_box(lines(scene, cam)))
    });
}

fn generated(c: &mut Criterion) {
    let mut g = c.benchmark_group("lines");
    g.sample_size(10).measurement_time(Duration::from_secs(8));
    for (name, scene) in [
        ("sphere/100000", sphere_scene(100_000)),
        ("tori/200", interpenetrating_tori(200, 100)),
        ("soup/1000", random_triangle_soup(1_000, 1)),
    ] {
        let cam = common::iso_1024(&scene);
        add(&mut g, name, &scene, &cam);
    }
    g.finish();
}

fn shared_meshes(c: &mut Criterion) {
    if common::shared_meshes().is_empty() {
        eprintln!("lines/mesh: ../shared/meshes is absent: no shared meshes measured");
    }
    common::mesh_group(c, 5, |g, stem, scene, cam| add(g, &stem, &scene, &cam));
}

criterion_group!(benches, generated, shared_meshes);
criterion_main!(benches);
