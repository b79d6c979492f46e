//! Renders a scene file as SVG, as `sightline render IN -o OUT.svg` does: the exact visible
//! polygons (the coverage map), one path per visible region, `data-face` naming its face.
//!
//! `cargo run --release --example render_svg -- [INPUT] [OUT.svg]` (defaults:
//! `fixtures/cyclic_bars.obj`, standard output).

use sightline::methods::Output;
use sightline::output::write_with;
use sightline::project::CullMode;
use sightline::{CameraSpec, RenderOptions, pipeline, render};
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let input = args.next().unwrap_or("fixtures/cyclic_bars.obj".into());
    let output = args.next().unwrap_or("-".into());

    let scene = sightline::load(Path::new(&input), None)?;
    let spec = CameraSpec {
        size: Some((480, 360)),
        ..CameraSpec::default() // the iso view, fitted to the scene
    };
    let camera = spec.resolve_for(&scene)?;
    let prepared = pipeline::prepare(&scene, &camera, CullMode::Auto);

    let options = RenderOptions::new(Output::Svg);
    let rendered = render::render(&scene, &camera, &prepared.screen, &options, None)?;
    for w in &rendered.warnings {
        eprintln!("warning: {w}");
    }
    // `-` is standard output; a file is replaced atomically.
    write_with(Path::new(&output), |w| rendered.write(w))?;
    Ok(())
}
