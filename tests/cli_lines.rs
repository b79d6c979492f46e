//! `sightline lines` and `sightline render --lines` as users run them.

mod support;

use std::path::PathBuf;
use support::cli::{run_err, run_ok};

/// A fresh temporary directory for one test's outputs.
fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

fn path_in(dir: &tempfile::TempDir, name: &str) -> PathBuf {
    dir.path().join(name)
}

/// `sightline lines fixtures/cube.obj --size 64x48 -o OUT FLAGS...`, which must succeed; its
/// stderr.
fn lines_ok(out: &str, flags: &[&str]) -> String {
    let o = run_ok(
        &[
            &["lines", "fixtures/cube.obj", "--size", "64x48", "-o", out],
            flags,
        ]
        .concat(),
    );
    String::from_utf8(o.stderr).unwrap()
}

/// What `sightline COMMAND fixtures/cube.obj --size 64x48 -o - FLAGS...`, which must succeed,
/// writes to standard output.
fn cube_stdout(command: &str, flags: &[&str]) -> Vec<u8> {
    let args = [command, "fixtures/cube.obj", "--size", "64x48", "-o", "-"];
    run_ok(&[&args[..], flags].concat()).stdout
}

#[test]
fn every_format_writes_from_its_extension() {
    let dir = tmp();
    let out = |ext: &str| path_in(&dir, &format!("cube.{ext}"));
    let svg = lines_ok(out("svg").to_str().unwrap(), &[]);
    // The summary counts strokes by visibility and kind.
    assert!(svg.contains(" strokes: visible "), "{svg}");
    let text = std::fs::read_to_string(out("svg")).unwrap();
    assert!(text.starts_with("<svg") && text.contains("<g class=\"visible silhouette\">"));
    lines_ok(out("json").to_str().unwrap(), &[]);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out("json")).unwrap()).unwrap();
    assert_eq!(json["schema"], "sightline/lines");
    assert!(!json["strokes"].as_array().unwrap().is_empty());
    // Upper-case extensions too.
    lines_ok(out("DXF").to_str().unwrap(), &[]);
    let dxf = dxf::Drawing::load_file(out("DXF")).unwrap();
    assert_eq!(
        dxf.entities().count(),
        json["strokes"].as_array().unwrap().len()
    );
    lines_ok(out("pdf").to_str().unwrap(), &[]);
    assert!(std::fs::read(out("pdf")).unwrap().starts_with(b"%PDF-"));
}

#[test]
fn dash_writes_svg_to_stdout_and_to_picks_another_format() {
    assert!(cube_stdout("lines", &[]).starts_with(b"<svg"));
    let json = cube_stdout("lines", &["--to", "json"]);
    assert!(json.starts_with(b"{\n  \"schema\": \"sightline/lines\""));
}

#[test]
fn an_unknown_extension_is_an_error_naming_it() {
    let dir = tmp();
    let out = path_in(&dir, "cube.png");
    let (code, err) = run_err(&["lines", "fixtures/cube.obj", "-o", out.to_str().unwrap()]);
    assert_eq!(code, Some(1));
    assert!(
        err.contains("cube.png: unknown output extension for lines"),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn crease_angles_out_of_range_are_errors_naming_the_range() {
    for bad in ["200", "-5", "nan"] {
        let (code, err) = run_err(&["lines", "fixtures/cube.obj", "-o", "-", "--crease", bad]);
        // A usage error (clap's exit code).
        assert_eq!(code, Some(2), "--crease {bad}: {err}");
        assert!(
            err.contains("--crease must be in [0, 180] degrees"),
            "--crease {bad}: {err}"
        );
    }
    // `=` form, and the ends of the range are fine.
    let (code, err) = run_err(&["lines", "fixtures/cube.obj", "-o", "-", "--crease=-5"]);
    assert_eq!(code, Some(2));
    assert!(err.contains("got '-5'"), "{err}");
    for ok in ["0", "180"] {
        run_ok(&[
            "lines",
            "fixtures/cube.obj",
            "--size",
            "8x8",
            "-o",
            "-",
            "--crease",
            ok,
        ]);
    }
}

#[test]
fn flags_that_would_do_nothing_are_errors() {
    let (_, err) = run_err(&[
        "lines",
        "fixtures/cube.obj",
        "-o",
        "-",
        "--hidden",
        "off",
        "--qi-max",
        "2",
    ]);
    assert!(err.contains("--qi-max applies to hidden lines"), "{err}");
    let (_, err) = run_err(&["lines", "fixtures/cube.obj", "-o", "-", "--qi-max", "-1"]);
    assert!(err.contains("'-1' is not a whole number >= 0"), "{err}");
    let (_, err) = run_err(&[
        "lines",
        "fixtures/cube.obj",
        "-o",
        "x.dxf",
        "--background",
        "255,255,255",
    ]);
    assert!(
        err.contains("--background applies to SVG and PDF output only"),
        "{err}"
    );
}

#[test]
fn the_background_is_drawn_only_when_asked() {
    let plain = String::from_utf8(cube_stdout("lines", &[])).unwrap();
    assert!(!plain.contains("<rect"));
    let white = cube_stdout("lines", &["--background", "255,255,255"]);
    let white = String::from_utf8(white).unwrap();
    assert!(white.contains("<rect fill=\"#ffffff\" height=\"48\" width=\"64\"/>"));
}

#[test]
fn output_bytes_are_the_same_run_after_run() {
    for to in ["svg", "json", "dxf", "pdf"] {
        let args = [
            "lines",
            "fixtures/interpenetrating.obj",
            "--size",
            "64x48",
            "-o",
            "-",
            "--to",
            to,
        ];
        assert!(run_ok(&args).stdout == run_ok(&args).stdout, "{to}");
    }
}

#[test]
fn render_lines_overlays_the_line_groups_on_the_filled_drawing() {
    let plain = String::from_utf8(cube_stdout("render", &["--to", "svg"])).unwrap();
    let overlaid = cube_stdout("render", &["--to", "svg", "--lines"]);
    let overlaid = String::from_utf8(overlaid).unwrap();
    // The filled drawing is all there, then the style and the line groups over it.
    let filled = plain.trim_end().trim_end_matches("</svg>");
    assert!(overlaid.starts_with(filled), "{overlaid}");
    let rest = &overlaid[filled.len()..];
    assert!(rest.starts_with("<style>"), "{rest}");
    assert!(rest.contains("<g class=\"visible silhouette\">"), "{rest}");
    assert!(rest.contains("data-kind=\"silhouette\""), "{rest}");
    assert!(plain.contains("data-face=") && !plain.contains("class="));
    // The shaded-with-edges view draws no hidden lines.
    assert!(!rest.contains("class=\"hidden"), "{rest}");
}

#[test]
fn render_lines_is_refused_for_other_outputs_than_svg() {
    for out in ["x.png", "x.json"] {
        let (code, err) = run_err(&["render", "fixtures/cube.obj", "-o", out, "--lines"]);
        assert_eq!(code, Some(1));
        assert!(
            err.contains("--lines applies to SVG output only"),
            "{out}: {err}"
        );
    }
}

#[test]
fn plotter_order_reports_pen_up_travel_that_does_not_grow() {
    let o = run_ok(&[
        "lines",
        "fixtures/cyclic_bars.obj",
        "--cam",
        "fixtures/cyclic_bars.cam",
        "--order",
        "plotter",
        "-o",
        "-",
    ]);
    let (out, err) = (
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
    );
    assert!(out.starts_with("<svg"), "{out}");
    let line = err
        .lines()
        .find(|l| l.starts_with("pen-up travel:"))
        .unwrap_or_else(|| panic!("no travel in {err}"));
    let numbers: Vec<f64> = line
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .filter_map(|w| w.parse().ok())
        .collect();
    assert_eq!(numbers.len(), 2, "{line}");
    assert!(numbers[1] <= numbers[0], "{line}");
}
