//! Golden files: the outputs of a few renders, byte for byte (`tests/golden/`). The same input
//! and flags give the same bytes on every run and every machine (timings go to `--stats` only,
//! coordinates are written with shortest round-trip digits, PNGs by one encoder setting), and
//! an output changes only when a commit says why.
//!
//! After a deliberate change of output, rewrite them and look at the difference:
//! `SIGHTLINE_BLESS=1 cargo test --release --test golden`, then `git diff --stat tests/golden`.

use std::path::Path;
use std::process::Command;

/// (golden file, input, extra flags). Small images keep the files small. Every method is here
/// with the outputs it writes, so that a restructuring that changes no output can show it.
const CASES: &[(&str, &str, &[&str])] = &[
    ("cube.svg", "fixtures/cube.obj", &[]),
    ("cube.json", "fixtures/cube.obj", &[]),
    ("cube_zbuffer.png", "fixtures/cube.obj", &[]),
    (
        "cube_ids_zbuffer.png",
        "fixtures/cube.obj",
        &["--fill", "id"],
    ),
    (
        "cyclic_bars_bsp.png",
        "fixtures/cyclic_bars.obj",
        &["--method", "bsp"],
    ),
    (
        "cyclic_bars.svg",
        "fixtures/cyclic_bars.obj",
        &["--view", "front"],
    ),
    (
        "cyclic_bars_bsp.svg",
        "fixtures/cyclic_bars.obj",
        &["--view", "front", "--method", "bsp"],
    ),
    (
        "cyclic_bars_painter.svg",
        "fixtures/cyclic_bars.obj",
        &["--view", "front", "--method", "painter"],
    ),
    (
        "cyclic_bars_painter.json",
        "fixtures/cyclic_bars.obj",
        &["--view", "front", "--method", "painter"],
    ),
    ("interpenetrating.svg", "fixtures/interpenetrating.obj", &[]),
    (
        "interpenetrating.json",
        "fixtures/interpenetrating.obj",
        &[],
    ),
    (
        "interpenetrating_bsp.json",
        "fixtures/interpenetrating.obj",
        &["--method", "bsp"],
    ),
    ("t_junction.svg", "fixtures/t_junction.obj", &[]),
    (
        "two_objects_painter.png",
        "fixtures/two_objects.obj",
        &["--method", "painter"],
    ),
    ("seed_transparent.svg", "fixtures/seed_transparent.x3d", &[]),
    (
        "seed_transparent_bsp.svg",
        "fixtures/seed_transparent.x3d",
        &["--method", "bsp"],
    ),
    (
        "seed_transparent.json",
        "fixtures/seed_transparent.x3d",
        &[],
    ),
    (
        "seed_transparent_abuffer.png",
        "fixtures/seed_transparent.x3d",
        &["--method", "abuffer"],
    ),
    (
        "seed_two_triangles_scanline.png",
        "fixtures/seed_two_triangles.x3d",
        &["--method", "scanline"],
    ),
    (
        "primitives_ids.png",
        "fixtures/primitives.x3d",
        &["--fill", "id"],
    ),
    (
        "primitives_warnock.png",
        "fixtures/primitives.x3d",
        &["--method", "warnock"],
    ),
    (
        "primitives_phong.png",
        "fixtures/primitives.x3d",
        &["--shading", "phong", "--specular", "0.4"],
    ),
    (
        "primitives_gouraud_scanline.png",
        "fixtures/primitives.x3d",
        &["--method", "scanline", "--shading", "gouraud"],
    ),
    ("checker_quad_zbuffer.png", "fixtures/checker_quad.obj", &[]),
    (
        "tinted_glass_abuffer.png",
        "fixtures/tinted_glass.obj",
        &["--method", "abuffer"],
    ),
    (
        "tinted_glass_coverage.png",
        "fixtures/tinted_glass.obj",
        &["--method", "coverage"],
    ),
    (
        "indexed_headlight.svg",
        "fixtures/indexed.x3d",
        &["--headlight"],
    ),
];

/// Hidden-line drawings and sheets: (golden file, the command's arguments before `-o`).
const LINE_CASES: &[(&str, &[&str])] = &[
    (
        "cube_lines.svg",
        &["lines", "fixtures/cube.obj", "--size", "96x72"],
    ),
    (
        "cube_lines.json",
        &["lines", "fixtures/cube.obj", "--size", "96x72"],
    ),
    (
        "cube_lines.dxf",
        &["lines", "fixtures/cube.obj", "--size", "96x72"],
    ),
    (
        "interpenetrating_lines.svg",
        &["lines", "fixtures/interpenetrating.obj", "--size", "96x72"],
    ),
    (
        "cyclic_bars_lines_qi.json",
        &[
            "lines",
            "fixtures/cyclic_bars.obj",
            "--cam",
            "fixtures/cyclic_bars.cam",
            "--qi-max",
            "3",
        ],
    ),
    (
        "cube_sheet.svg",
        &[
            "sheet",
            "fixtures/cube.obj",
            "--date",
            "2026-12-02",
            "--paper",
            "a4",
        ],
    ),
];

/// Runs `sightline ARGS -o DIR/NAME` and compares the bytes with `tests/golden/NAME` (or
/// rewrites it when blessing); `Some(message)` when they differ.
fn differs_from_golden(dir: &Path, name: &str, args: &[&str], bless: bool) -> Option<String> {
    let out = dir.join(name);
    let o = Command::new(env!("CARGO_BIN_EXE_sightline"))
        .args(args)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let bytes = std::fs::read(&out).unwrap();
    let golden = Path::new("tests/golden").join(name);
    if bless {
        std::fs::write(&golden, &bytes).unwrap();
        return None;
    }
    match std::fs::read(&golden) {
        Ok(want) if want == bytes => None,
        _ => {
            // Keep what this build wrote, to compare by hand.
            let kept = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
            std::fs::write(&kept, &bytes).unwrap();
            Some(format!("{name} (this build's output: {})", kept.display()))
        }
    }
}

#[test]
fn outputs_match_their_golden_files() {
    let bless = std::env::var_os("SIGHTLINE_BLESS").is_some();
    let dir = tempfile::tempdir().unwrap();
    let mut changed = Vec::new();
    for (name, input, extra) in CASES {
        let args: Vec<&str> = ["render", input, "--size", "96x72"]
            .into_iter()
            .chain(extra.iter().copied())
            .collect();
        changed.extend(differs_from_golden(dir.path(), name, &args, bless));
    }
    for (name, args) in LINE_CASES {
        changed.extend(differs_from_golden(dir.path(), name, args, bless));
    }
    assert!(
        changed.is_empty(),
        "outputs differ from tests/golden: {changed:?}; if the change is meant, run \
         SIGHTLINE_BLESS=1 cargo test --release --test golden and say why in the commit"
    );
}

/// One opacity convention: the A-buffer and the exact drawing blend a translucent face over the
/// same colours with the same numbers, so their PNGs are the same bytes (before the convention,
/// the A-buffer blended with the transparency `t` and the drawing with `1 - (1 - t)`, and 280 of
/// these 6,912 pixels differed by one level).
#[test]
fn the_abuffer_and_the_exact_drawing_blend_alike() {
    let read = |name: &str| std::fs::read(Path::new("tests/golden").join(name)).unwrap();
    assert!(
        read("tinted_glass_abuffer.png") == read("tinted_glass_coverage.png"),
        "tinted_glass: the A-buffer's PNG and the coverage drawing's PNG differ"
    );
}
