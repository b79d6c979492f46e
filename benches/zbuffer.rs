//! Load + project + cull + z-buffer at 1024x1024, on generated spheres of 10k, 100k and 1M
//! triangles (OBJ text generated in memory, so the load is measured too), and on the meshes of
//! `../shared/meshes` with their cameras when that directory is present.
//!
//! `cargo bench --bench zbuffer`; `cargo bench --bench zbuffer -- sphere` for the spheres only.

mod common;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use sightline::pipeline::render_zbuffer;
use sightline::project::CullMode;
use sightline::scene::{Format, Scene, load_bytes, primitives::sphere_scene};
use std::hint::black_box;
use std::time::Duration;

fn to_obj(scene: &Scene) -> Vec<u8> {
    use std::io::Write;
    let mut out = Vec::with_capacity(scene.faces.len() * 40);
    for p in &scene.positions {
        writeln!(out, "v {} {} {}", p.x, p.y, p.z).unwrap();
    }
    for f in &scene.faces {
        out.extend_from_slice(b"f");
        for c in scene.face_corners(f) {
            write!(out, " {}", c + 1).unwrap();
        }
        out.push(b'\n');
    }
    out
}

fn spheres(c: &mut Criterion) {
    let mut g = c.benchmark_group("sphere");
    g.sample_size(10).measurement_time(Duration::from_secs(8));
    for n in [10_000usize, 100_000, 1_000_000] {
        let scene = sphere_scene(n);
        let obj = to_obj(&scene);
        let cam = common::iso_1024(&scene);
        g.throughput(Throughput::Elements(scene.faces.len() as u64));
        g.bench_function(format!("load+zbuffer/{n}"), |b| {
            b.iter(|| {
                let s = load_bytes(&obj, Format::Obj, "sphere.obj", None).unwrap();
                let (p, zb) = render_zbuffer(&s, &cam, CullMode::Auto, |_| {});
                black_box((p.screen.polys.len(), zb.stats.fragments))
            })
        });
        g.bench_function(format!("zbuffer/{n}"), |b| {
            b.iter(|| {
                let (p, zb) = render_zbuffer(&scene, &cam, CullMode::Auto, |_| {});
                black_box((p.screen.polys.len(), zb.stats.fragments))
            })
        });
    }
    g.finish();
}

fn shared_meshes(c: &mut Criterion) {
    common::mesh_group(c, 4, |g, stem, scene, cam| {
        g.bench_function(format!("zbuffer/{stem}"), |b| {
            b.iter(|| {
                let (p, zb) = render_zbuffer(&scene, &cam, CullMode::Auto, |_| {});
                black_box((p.screen.polys.len(), zb.stats.fragments))
            })
        });
    });
}

criterion_group!(benches, spheres, shared_meshes);
criterion_main!(benches);
