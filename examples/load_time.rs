//! Loads each mesh file given on the command line and prints how long it took and what it holds.
//!
//! `cargo run --release --example load_time -- FILE...` (a `.gz` suffix is looked through; the
//! time includes reading and decompressing the file).

use std::time::Instant;

fn main() {
    let paths: Vec<String> = std::env::args().skip(1).collect();
    if paths.is_empty() {
        eprintln!("usage: load_time FILE...");
        std::process::exit(2);
    }
    let mut failed = false;
    for p in paths {
        let t = Instant::now();
        let r = sightline::scene::load(std::path::Path::new(&p), None);
        let secs = t.elapsed().as_secs_f64();
        match r {
            Ok(s) => println!(
                "{p}: {secs:.3} s, {} vertices, {} faces ({} input), {} meshes, {} degenerate dropped, {} triangulated, {} warnings",
                s.positions.len(),
                s.faces.len(),
                s.input_faces,
                s.meshes.len(),
                s.stats.degenerate_dropped,
                s.stats.nonplanar_triangulated,
                s.stats.warnings.len()
            ),
            Err(e) => {
                println!("{p}: {secs:.3} s, error: {e}");
                failed = true;
            }
        }
    }
    if failed {
        std::process::exit(1);
    }
}
