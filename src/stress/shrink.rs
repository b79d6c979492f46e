//! Shrinking a failing case and writing it as a fixture.
//!
//! Invariant: [`shrink`] returns a case for which the predicate still holds (it only keeps a
//! change the predicate accepts), with no more faces than it was given and coordinates no
//! longer than they were; [`write_fixture`] writes an OBJ and a `.cam` file that
//! `scene::load` and `--cam` read back to the same faces (shortest round-trip digits) and the
//! same camera.

use super::Case;
use crate::camera::Projection;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Checks the predicate runs at most this many times while shrinking, so a big failing case
/// still finishes.
const BUDGET: usize = 400;

/// A smaller case for which `fails` still holds: faces dropped by delta debugging (halves,
/// quarters, ... down to single faces, while the case fails without them), then every
/// coordinate rounded to the fewest significant digits (of 1, 2, 3, 4, 6, 8, 10, 12, 15) with
/// which it still fails, the faces' points first, then the camera's. `fails(case)` must hold.
pub fn shrink(case: &Case, fails: &dyn Fn(&Case) -> bool) -> Case {
    let mut calls = 0;
    let mut test = |c: &Case| {
        calls += 1;
        calls <= BUDGET && fails(c)
    };
    let mut best = case.clone();
    let mut chunks = 2;
    while best.faces.len() > 1 {
        let n = best.faces.len();
        let size = n.div_ceil(chunks.min(n));
        let mut removed = false;
        for start in (0..n).step_by(size) {
            let mut smaller = best.clone();
            smaller.faces.drain(start..(start + size).min(n));
            if !smaller.faces.is_empty() && test(&smaller) {
                best = smaller;
                chunks = (chunks - 1).max(2);
                removed = true;
                break;
            }
        }
        if !removed {
            if size == 1 {
                break;
            }
            chunks = (chunks * 2).min(n);
        }
    }
    for digits in [1, 2, 3, 4, 6, 8, 10, 12, 15] {
        let mut rounded = best.clone();
        for p in rounded.faces.iter_mut().flatten() {
            *p = p.map(|v| round(v, digits));
        }
        if rounded.faces != best.faces && test(&rounded) {
            best = rounded;
            break;
        }
    }
    for digits in [1, 2, 3, 4, 6, 8, 10, 12, 15] {
        let mut rounded = best.clone();
        let c = &mut rounded.camera;
        c.eye = c.eye.map(|v| round(v, digits));
        c.target = c.target.map(|v| round(v, digits));
        c.up = c.up.map(|v| round(v, digits));
        if rounded.camera.validate().is_ok() && rounded.camera != best.camera && test(&rounded) {
            best = rounded;
            break;
        }
    }
    best
}

/// `v` rounded to `digits` significant decimal digits.
fn round(v: f64, digits: usize) -> f64 {
    format!("{v:.*e}", digits - 1).parse().unwrap_or(v)
}

/// Writes `case` as `DIR/NAME.obj` and `DIR/NAME.cam` (NAME from its label), creating `dir`;
/// `note` goes into the OBJ's header. Returns the OBJ's path.
pub fn write_fixture(case: &Case, dir: &Path, note: &str) -> std::io::Result<PathBuf> {
    std::fs::create_dir_all(dir)?;
    let name: String = case
        .label
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    let obj = dir.join(format!("{name}.obj"));
    let mut out = std::io::BufWriter::new(std::fs::File::create(&obj)?);
    writeln!(
        out,
        "# sightline stress: {} (scale {})",
        case.label, case.scale
    )?;
    for line in note.lines() {
        writeln!(out, "# {line}")?;
    }
    let (positions, faces) = case.indexed();
    for p in positions {
        writeln!(out, "v {} {} {}", p.x, p.y, p.z)?;
    }
    for f in faces {
        let corners: Vec<String> = f.iter().map(|v| (v + 1).to_string()).collect();
        writeln!(out, "f {}", corners.join(" "))?;
    }
    out.flush()?;
    let c = &case.camera;
    let projection = match c.projection {
        Projection::Perspective { fovy_deg } => format!("fovy {fovy_deg}\n"),
        Projection::Orthographic { height } => format!("fovy 0\northo_height {height}\n"),
    };
    let cam = format!(
        "eye {} {} {}\ntarget {} {} {}\nup {} {} {}\n{projection}near {}\nfar {}\nsize {} {}\n",
        c.eye.x,
        c.eye.y,
        c.eye.z,
        c.target.x,
        c.target.y,
        c.target.z,
        c.up.x,
        c.up.y,
        c.up.z,
        c.near,
        c.far,
        c.width,
        c.height
    );
    std::fs::write(obj.with_extension("cam"), cam)?;
    Ok(obj)
}
