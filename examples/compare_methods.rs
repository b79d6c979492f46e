//! Runs every registered method on scene files seen from the front, and compares the face it
//! shows at every pixel centre with the z-buffer's: mismatches over covered pixels and over
//! interior ones (one face in the z-buffer's 3x3 neighbourhood). Exact methods show 0 interior
//! mismatches; the painter does not where faces overlap cyclically or interpenetrate.
//!
//! `cargo run --release --example compare_methods -- [INPUT...]` (default: the fixtures
//! `cyclic_bars.obj` and `interpenetrating.obj`).

use sightline::camera::NamedView;
use sightline::pipeline::{self, compare_ids};
use sightline::project::CullMode;
use sightline::{CameraSpec, METHODS, methods};
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut inputs: Vec<String> = std::env::args().skip(1).collect();
    if inputs.is_empty() {
        inputs = ["fixtures/cyclic_bars.obj", "fixtures/interpenetrating.obj"]
            .map(String::from)
            .into();
    }
    let reference = methods::method("zbuffer").expect("the z-buffer is registered");
    for input in &inputs {
        let scene = sightline::load(Path::new(input), None)?;
        let spec = CameraSpec {
            size: Some((200, 150)),
            view: Some(NamedView::Front),
            ..CameraSpec::default()
        };
        let camera = spec.resolve_for(&scene)?;
        let screen = pipeline::prepare(&scene, &camera, CullMode::Auto).screen;
        let (w, h) = (camera.width as usize, camera.height as usize);
        let want = reference.face_ids(&scene, &screen, &camera, None);
        println!("{input} at {w}x{h}, against {}:", reference.name);
        println!("  method       exact   covered  mismatch   interior  mismatch");
        for method in &METHODS {
            let ids = method.face_ids(&scene, &screen, &camera, None);
            let c = compare_ids(&want, &ids, w, h);
            println!(
                "  {:10} {:>7} {:9} {:9} {:10} {:9}",
                method.name,
                if method.exact { "yes" } else { "no" },
                c.covered,
                c.covered_mismatch,
                c.interior,
                c.interior_mismatch
            );
        }
    }
    Ok(())
}
