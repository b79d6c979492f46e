//! Prints what a camera sees of each face of a scene: the number of exact visible pieces and
//! their area in pixels, from an object-space strategy's `VisibleSet` (every face taken as
//! opaque), seen from the front.
//!
//! `cargo run --release --example visible_set -- [INPUT] [METHOD]` (defaults:
//! `fixtures/cyclic_bars.obj`, `coverage`; `bsp` is the other exact strategy; the approximate
//! `painter` only orders whole faces and has no visible pieces).

use sightline::camera::NamedView;
use sightline::methods::{self, Engine};
use sightline::project::CullMode;
use sightline::{CameraSpec, FaceId, pipeline};
use std::collections::BTreeMap;
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let input = args.next().unwrap_or("fixtures/cyclic_bars.obj".into());
    let name = args.next().unwrap_or("coverage".into());
    let exact_strategy = |m: &methods::Method| m.exact && !m.is_image_space();
    let Some(Engine::Object(strategy)) = methods::method(&name)
        .filter(|m| exact_strategy(m))
        .map(|m| m.engine)
    else {
        let strategies = methods::names_with(exact_strategy);
        eprintln!("{name} computes no exact visible pieces: use {strategies}");
        std::process::exit(2);
    };

    let scene = sightline::load(Path::new(&input), None)?;
    let spec = CameraSpec {
        size: Some((256, 256)),
        view: Some(NamedView::Front),
        ..CameraSpec::default()
    };
    let camera = spec.resolve_for(&scene)?;
    let prepared = pipeline::prepare(&scene, &camera, CullMode::Auto);
    let visible = strategy.visible_set(&prepared.screen, &|_| false, None);

    // Each piece belongs to a screen polygon, which knows its input face.
    let mut faces: BTreeMap<FaceId, (usize, f64)> = BTreeMap::new();
    for (poly, ring) in visible.pixel_rings(&prepared.screen) {
        let face = faces
            .entry(prepared.screen.polys[poly as usize].id)
            .or_default();
        face.0 += 1;
        face.1 += area(&ring);
    }
    println!("{name} on {input}, {}x{}:", camera.width, camera.height);
    println!("   face  pieces   area (px)");
    for (id, (pieces, area)) in &faces {
        println!("{id:7}  {pieces:6}  {area:10.2}");
    }
    let total: f64 = faces.values().map(|f| f.1).sum();
    println!(
        "{} faces seen of {}, {total:.2} px",
        faces.len(),
        scene.faces.len()
    );
    Ok(())
}

/// The area of a simple polygon (shoelace formula).
fn area(ring: &[[f64; 2]]) -> f64 {
    let twice: f64 = ring
        .iter()
        .zip(ring.iter().cycle().skip(1))
        .map(|(a, b)| a[0] * b[1] - b[0] * a[1])
        .sum();
    twice.abs() / 2.0
}
