//! Times the stages of the z-buffer pipeline on a generated sphere: `cargo run --release --example
//! stage_times -- 1000000`.
use sightline::camera::{Camera, NamedView};
use sightline::project::{CullMode, project};
use sightline::scene::analysis::analyse;
use sightline::scene::primitives::sphere_scene;
use std::time::Instant;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1_000_000);
    let scene = sphere_scene(n);
    let cam = Camera::fit(
        NamedView::Iso,
        scene.bounds().unwrap(),
        false,
        40.0,
        1024,
        1024,
    );
    let t = Instant::now();
    let analysis = analyse(&scene);
    let ta = t.elapsed();
    let t = Instant::now();
    let screen = project(&scene, &analysis, &cam, CullMode::Auto);
    let tp = t.elapsed();
    let t = Instant::now();
    let zb = sightline::raster::zbuffer::render(&screen, |_| {});
    let tz = t.elapsed();
    println!(
        "{} faces: analyse {:.3}s, project {:.3}s, z-buffer {:.3}s ({} fragments)",
        scene.faces.len(),
        ta.as_secs_f64(),
        tp.as_secs_f64(),
        tz.as_secs_f64(),
        zb.stats.fragments
    );
}
