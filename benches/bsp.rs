//! The exact visible set (`render --method coverage` on an opaque scene: projection, culling and the
//! depth-aware coverage map) at 1024x1024 on generated spheres of 1k, 10k, 100k and 1M
//! triangles, interlocked and interpenetrating tori, random triangle soups of 100 and 1,000, and
//! the meshes of `../shared/meshes` with their cameras when that directory is present. Before
//! each benchmark one line on stderr gives its visible pieces per polygon and exact fallbacks.
//! The 10,000-triangle soup takes minutes a run: time it with
//! `sightline bench --soup 10000 --method coverage --repeat 1`.
//!
//! `cargo bench --bench bsp`; `cargo bench --bench bsp -- soup` for the soups only.

mod common;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use sightline::camera::Camera;
use sightline::exact::predicates::fallback_count;
use sightline::pipeline::prepare;
use sightline::project::CullMode;
use sightline::scene::Scene;
use sightline::scene::primitives::{
    interlocked_tori, interpenetrating_tori, random_triangle_soup, sphere_scene,
};
use sightline::visibility::coverage_map::visible_set;
use std::hint::black_box;
use std::time::Duration;

/// Projection, culling and the exact visible set: what `render --method coverage` computes before
/// drawing. Returns the visible piece count.
fn run(scene: &Scene, cam: &Camera) -> usize {
    let prepared = prepare(scene, cam, CullMode::Auto);
    visible_set(&prepared.screen).0.pieces.len()
}

/// One untimed run, reported: what the timed runs do.
fn report(name: &str, scene: &Scene, cam: &Camera) {
    let before = fallback_count();
    let prepared = prepare(scene, cam, CullMode::Auto);
    let (visible, stats) = visible_set(&prepared.screen);
    let polys = prepared.screen.polys.len();
    eprintln!(
        "{name}: {} faces, {polys} on screen, {} visible pieces ({:.3} per polygon), {} replaced, \
         {} exact fallbacks",
        scene.faces.len(),
        visible.pieces.len(),
        visible.pieces.len() as f64 / polys.max(1) as f64,
        stats.replaced,
        fallback_count() - before
    );
}

fn bench(c: &mut Criterion, group: &str, cases: Vec<(String, Scene)>, seconds: u64) {
    let mut g = c.benchmark_group(group);
    g.sample_size(10)
        .measurement_time(Duration::from_secs(seconds));
    for (name, scene) in cases {
        let cam = common::iso_1024(&scene);
        report(&format!("{group}/{name}"), &scene, &cam);
        g.throughput(Throughput::Elements(scene.faces.len() as u64));
        g.bench_function(name, |b| b.iter(|| black_box(run(&scene, &cam))));
    }
    g.finish();
}

fn spheres(c: &mut Criterion) {
    let cases = [1_000usize, 10_000, 100_000, 1_000_000]
        .into_iter()
        .map(|n| (n.to_string(), sphere_scene(n)))
        .collect();
    bench(c, "sphere", cases, 10);
}

fn tori(c: &mut Criterion) {
    let cases = vec![
        ("interlocked/200".to_string(), interlocked_tori(200, 100)),
        (
            "interpenetrating/200".to_string(),
            interpenetrating_tori(200, 100),
        ),
    ];
    bench(c, "tori", cases, 8);
}

fn soups(c: &mut Criterion) {
    let cases = [100usize, 1_000]
        .into_iter()
        .map(|n| (n.to_string(), random_triangle_soup(n, 1)))
        .collect();
    bench(c, "soup", cases, 20);
}

fn shared_meshes(c: &mut Criterion) {
    common::mesh_group(c, 5, |g, stem, scene, cam| {
        report(&format!("mesh/{stem}"), &scene, &cam);
        g.bench_function(stem, |b| b.iter(|| black_box(run(&scene, &cam))));
    });
}

criterion_group!(benches, spheres, tori, soups, shared_meshes);
criterion_main!(benches);
