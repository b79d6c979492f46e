//! The command line as users run it.

mod support;

use std::path::{Path, PathBuf};
use support::cli::{
    decode_png, on_a_terminal, render_ok, run_err, run_ok, sightline, spawn_piped, wait_with_stderr,
};
use support::fixtures::fixture_paths;

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sightline-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn render_writes_a_png_of_the_requested_size() {
    let out = tmp("cube.png");
    render_ok("fixtures/cube.obj", &out, &["--size", "64x48"]);
    let img = decode_png(&std::fs::read(&out).unwrap());
    assert_eq!((img.width(), img.height()), (64, 48));
}

#[test]
fn negative_values_work_with_and_without_equals() {
    let render = ["render", "fixtures/cube.obj", "-o", "-", "--size", "32x32"];
    let a = run_ok(&[&render[..], &["--eye", "-3,2,4", "--fill", "id"]].concat());
    let b = run_ok(&[&render[..], &["--eye=-3,2,4", "--fill", "id"]].concat());
    assert_eq!(a.stdout, b.stdout);
    // Some pixel shows the cube.
    let img = decode_png(&a.stdout).to_rgb8();
    assert!(img.pixels().any(|p| p.0 != [0, 0, 0]));
}

#[test]
fn output_is_deterministic() {
    let args = [
        "render",
        "fixtures/cube.obj",
        "-o",
        "-",
        "--size",
        "80x60",
        "--view",
        "iso",
    ];
    let a = run_ok(&args);
    let b = sightline(&args);
    assert_eq!(a.stdout, b.stdout, "same input, same bytes");
}

#[test]
fn seed_depth_png_through_the_cli() {
    let out = tmp("seed.png");
    let depth = tmp("seed_depth.png");
    run_ok(&[
        "render",
        "fixtures/seed_two_triangles.x3d",
        "--near",
        "5",
        "--far",
        "10",
        "--size",
        "120x100",
        "--depth",
        depth.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let d = decode_png(&std::fs::read(&depth).unwrap()).to_luma16();
    let mut values: Vec<u16> = d.pixels().map(|p| p.0[0]).collect();
    values.sort_unstable();
    values.dedup();
    assert_eq!(values, vec![49151, 58253, 65535]);
}

#[test]
fn bad_input_names_the_file_exits_nonzero_and_writes_nothing() {
    let bad = tmp("broken.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").unwrap();
    let out = tmp("never.png");
    let o = sightline(&["render", bad.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("broken.obj:4"), "names file and line: {err}");
    assert!(o.stdout.is_empty());
    assert!(!out.exists(), "no output file for a failed run");
}

#[test]
fn missing_file_and_unknown_extension_are_errors_not_panics() {
    let o = sightline(&["info", "no/such/file.obj"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no/such/file.obj"));
    let o = sightline(&["info", "README.md"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown file format"));
}

#[test]
fn bad_camera_is_an_error() {
    let o = sightline(&[
        "render",
        "fixtures/cube.obj",
        "-o",
        "-",
        "--near",
        "2",
        "--far",
        "1",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("near"));
    let o = sightline(&["render", "fixtures/cube.obj", "-o", "-", "--eye", "1,2"]);
    assert_eq!(o.status.code(), Some(2), "clap usage error");
}

#[test]
fn help_has_examples() {
    let o = sightline(&["render", "--help"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("Examples:") && text.contains("--eye -1,2,3"));
}

#[test]
fn info_reports_closedness_culling_and_stages() {
    let o = run_ok(&["info", "fixtures/cube.obj", "--view", "iso"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("1 closed, 0 open"), "{text}");
    assert!(
        text.contains("3 back faces culled"),
        "iso view of a cube: 3 of 6 faces culled\n{text}"
    );
    // cube.obj's right face uses the translucent "blue_glass" material.
    assert!(
        text.contains("blending (translucency): yes, 1 translucent faces"),
        "{text}"
    );
    let o = sightline(&["info", "fixtures/seed_two_triangles.x3d"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("blending (translucency): no"), "{text}");
    assert!(
        text.contains("2 open"),
        "single triangles are open meshes: {text}"
    );
    let o = sightline(&["info", "fixtures/seed_transparent.x3d"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("blending (translucency): yes, 1 translucent faces"),
        "{text}"
    );
}

#[test]
fn writes_into_the_target_directory_only() {
    // The temporary file lives beside the output and is renamed: nothing else is left behind.
    let dir = tmp("atomic");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("a.png");
    render_ok("fixtures/cube.obj", &out, &["--size", "16x16"]);
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, vec![std::ffi::OsString::from("a.png")]);
    assert!(Path::new(&out).exists());
}

#[test]
fn every_malformed_fixture_fails_cleanly_through_the_cli() {
    let mut checked = 0;
    let mut entries: Vec<PathBuf> = std::fs::read_dir("fixtures/bad")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e != "mtl"))
        .collect();
    entries.sort();
    for path in entries {
        let p = path.to_str().unwrap();
        let o = sightline(&["info", p]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{p}: {err}");
        // An error inside an OBJ's material library names the .mtl file.
        let named = err.contains(p) || err.contains(&p.replace(".obj", ".mtl"));
        assert!(
            err.starts_with("error: ") && named,
            "{p}: names the file: {err}"
        );
        assert!(!err.contains("panicked"), "{p}: {err}");
        assert!(o.stdout.is_empty(), "{p}: nothing on stdout");
        checked += 1;
    }
    assert!(
        checked >= 10,
        "at least 10 kinds of malformed file, found {checked}"
    );
}

fn compare_interior_mismatch(file: &str, method: &str, extra: &[&str]) -> usize {
    let mut args = vec!["compare", file, "--method", method, "--size", "160x120"];
    args.extend_from_slice(extra);
    let o = run_ok(&args);
    let text = String::from_utf8_lossy(&o.stdout).to_string();
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with("interior pixels"))
        .unwrap_or_else(|| panic!("{file}: no interior line in {text}"));
    // "interior pixels N  mismatched M (p%)"
    let words: Vec<&str> = line.split_whitespace().collect();
    let at = words.iter().position(|w| *w == "mismatched").unwrap();
    words[at + 1].parse().unwrap()
}

#[test]
fn compare_bsp_has_no_interior_mismatch_on_any_fixture() {
    for f in &fixture_paths() {
        let f = f.to_str().unwrap();
        for view in ["iso", "front", "top"] {
            assert_eq!(
                compare_interior_mismatch(f, "bsp", &["--view", view]),
                0,
                "{f} {view}"
            );
        }
    }
}

#[test]
fn compare_painter_fails_on_cyclic_and_interpenetrating_scenes() {
    for f in ["fixtures/cyclic_bars.obj", "fixtures/interpenetrating.obj"] {
        assert!(
            compare_interior_mismatch(f, "painter", &["--view", "front"]) > 0,
            "{f}"
        );
        assert_eq!(
            compare_interior_mismatch(f, "bsp", &["--view", "front"]),
            0,
            "{f}"
        );
    }
}

#[test]
fn render_bsp_writes_svg_and_json() {
    let o = run_ok(&[
        "render",
        "fixtures/cube.obj",
        "--method",
        "bsp",
        "-o",
        "-",
        "--size",
        "64x64",
    ]);
    let svg = String::from_utf8(o.stdout).unwrap();
    let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
    let faces: Vec<&str> = doc
        .descendants()
        .filter_map(|n| n.attribute("data-face"))
        .collect();
    assert!(!faces.is_empty() && faces.len() <= 6 * 4, "{faces:?}");
    let out = tmp("cube.json");
    run_ok(&[
        "render",
        "fixtures/cube.obj",
        "--method",
        "bsp",
        "-o",
        out.to_str().unwrap(),
        "--size",
        "64x64",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert!(
        v["faces"].as_array().is_some_and(|f| f.len() == 3),
        "iso view of a cube: 3 faces"
    );
    let o = sightline(&[
        "render",
        "fixtures/cube.obj",
        "--method",
        "zbuffer",
        "-o",
        "x.svg",
    ]);
    assert_eq!(o.status.code(), Some(1), "the z-buffer cannot write SVG");
}

/// Every pair of image-space methods agrees at every covered pixel of the tangled fixtures, both
/// ways round (`--against` takes any method), and the painter differs from each of them.
#[test]
fn compare_takes_any_two_methods() {
    let covered_mismatch = |file: &str, method: &str, against: &str| -> usize {
        let args = [
            "compare",
            file,
            "--method",
            method,
            "--against",
            against,
            "--size",
            "96x72",
            "--view",
            "front",
        ];
        let o = run_ok(&args);
        let text = String::from_utf8_lossy(&o.stdout).to_string();
        assert!(
            text.starts_with(&format!("{method} vs {against}")),
            "{text}"
        );
        let line = text
            .lines()
            .find(|l| l.trim_start().starts_with("covered pixels"))
            .unwrap();
        let words: Vec<&str> = line.split_whitespace().collect();
        let at = words.iter().position(|w| *w == "mismatched").unwrap();
        words[at + 1].parse().unwrap()
    };
    for f in ["fixtures/cyclic_bars.obj", "fixtures/interpenetrating.obj"] {
        for (m, a) in [
            ("scanline", "zbuffer"),
            ("warnock", "scanline"),
            ("abuffer", "warnock"),
            ("zbuffer", "abuffer"),
        ] {
            assert_eq!(covered_mismatch(f, m, a), 0, "{f}: {m} vs {a}");
        }
        assert!(covered_mismatch(f, "painter", "warnock") > 0, "{f}");
    }
}

/// The image-space methods draw PNGs only, and say so.
#[test]
fn image_space_methods_render_png_and_refuse_svg() {
    let dir = tempfile::tempdir().unwrap();
    for m in ["abuffer", "scanline", "warnock"] {
        let png = dir.path().join(format!("{m}.png"));
        run_ok(&[
            "render",
            "fixtures/seed_transparent.x3d",
            "--method",
            m,
            "-o",
            png.to_str().unwrap(),
        ]);
        assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
        let svg = dir.path().join(format!("{m}.svg"));
        let o = sightline(&[
            "render",
            "fixtures/cube.obj",
            "--method",
            m,
            "-o",
            svg.to_str().unwrap(),
        ]);
        assert!(!o.status.success());
        assert!(String::from_utf8_lossy(&o.stderr).contains("write it as PNG"));
        assert!(!svg.exists(), "no output file on error");
    }
}

/// A reader that stops early (`| head -1`) ends the run quietly, not with a panic.
#[test]
fn closed_standard_output_is_not_a_panic() {
    let mut child = spawn_piped(&["info", "fixtures/cube.obj"]);
    // Close our end of standard output before it writes.
    drop(child.stdout.take());
    let (status, err) = wait_with_stderr(child);
    assert!(!err.contains("panicked"), "{err}");
    assert!(status.success(), "{status:?}: {err}");
}

/// `--light` adds a light (both spellings of a negative value), `--specular` adds highlights,
/// and each changes the SVG's fills; bad values and `--shading` on a flat method are errors.
#[test]
fn lights_and_specular_change_the_fills() {
    let dir = tempfile::tempdir().unwrap();
    let fills = |extra: &[&str]| -> Vec<String> {
        let out = dir.path().join("x.svg");
        let mut args = vec!["render", "fixtures/cube.obj", "--method", "bsp", "-o"];
        args.push(out.to_str().unwrap());
        args.extend_from_slice(extra);
        run_ok(&args);
        let svg = std::fs::read_to_string(&out).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        // The filled regions (seam strokes under them have no fill of their own).
        doc.descendants()
            .filter(|n| n.has_tag_name("path") && n.attribute("data-face").is_some())
            .map(|n| n.attribute("fill").unwrap().to_string())
            .collect()
    };
    let plain = fills(&[]);
    let lit = fills(&["--light", "-1,0.5,0.2"]);
    assert_eq!(lit, fills(&["--light=-1,0.5,0.2"]));
    assert_ne!(plain, lit);
    // The headlight's mirror direction is the view: a face seen head-on takes the highlight (the
    // iso view's faces, 55° off, reflect it away).
    assert_ne!(
        fills(&["--view", "front", "--headlight"]),
        fills(&["--view", "front", "--headlight", "--specular", "0.5"])
    );
    // The default key and fill light the two red faces (top and left) differently; the
    // headlight sees them at the same angle.
    let head = fills(&["--headlight"]);
    assert_ne!(plain[0], plain[1], "the cube's two red faces");
    assert_eq!(head[0], head[1], "the cube's two red faces");
    assert_ne!(head, plain);
    // Without any light only the ambient term is left: darker in every channel, and the same
    // on faces of one material whatever their direction (the two red faces).
    let dark = fills(&["--no-headlight"]);
    let rgb = |h: &str| {
        (0..3)
            .map(|k| u8::from_str_radix(&h[1 + 2 * k..3 + 2 * k], 16).unwrap())
            .collect::<Vec<_>>()
    };
    for (d, p) in dark.iter().zip(plain.iter().chain(&head)) {
        assert!(
            rgb(d).iter().zip(rgb(p)).all(|(a, b)| *a <= b),
            "{d} vs {p}"
        );
    }
    assert_ne!(dark, plain);
    assert_eq!(dark[0], dark[1]);
    for bad in [
        &["--specular", "-1"][..],
        &["--light", "0,0,0"],
        &["--shading", "phong"],
        &["--headlight", "--no-headlight"],
    ] {
        let mut args = vec![
            "render",
            "fixtures/cube.obj",
            "--method",
            "bsp",
            "-o",
            "x.svg",
        ];
        args.extend_from_slice(bad);
        let o = sightline(&args);
        assert!(!o.status.success(), "{bad:?} accepted");
        assert!(!String::from_utf8_lossy(&o.stderr).contains("panicked"));
    }
}

/// Phong and Gouraud shading smooth a sphere's facets in the PNG: fewer distinct colours than
/// flat shading has faces would give, and different images.
#[test]
fn shading_modes_change_the_png() {
    let dir = tempfile::tempdir().unwrap();
    let render = |mode: &str| -> Vec<u8> {
        let out = dir.path().join(format!("{mode}.png"));
        run_ok(&[
            "render",
            "fixtures/primitives.x3d",
            "--shading",
            mode,
            "--size",
            "64x48",
            "-o",
            out.to_str().unwrap(),
        ]);
        image::open(&out).unwrap().to_rgb8().into_raw()
    };
    let (flat, gouraud, phong) = (render("flat"), render("gouraud"), render("phong"));
    assert_ne!(flat, gouraud);
    assert_ne!(flat, phong);
    assert_ne!(gouraud, phong);
}

/// `-o -` into a reader that stopped early ends quietly with success, like a printed report.
#[test]
fn png_to_a_closed_standard_output_is_not_an_error() {
    use std::io::Read;
    let mut child = spawn_piped(&[
        "render",
        "fixtures/primitives.x3d",
        "--size",
        "3000x3000",
        "-o",
        "-",
    ]);
    // Read a few bytes of the PNG (> 64 KiB, more than a pipe holds), then hang up.
    let mut stdout = child.stdout.take().unwrap();
    let mut head = [0u8; 8];
    stdout.read_exact(&mut head).unwrap();
    assert_eq!(&head, b"\x89PNG\r\n\x1a\n");
    drop(stdout);
    let (status, err) = wait_with_stderr(child);
    assert!(status.success(), "{status:?}: {err}");
    assert!(!err.contains("error") && !err.contains("panicked"), "{err}");
}

/// The same input and flags give the same bytes: timings go to `--stats` (stderr), never into
/// the output (JSON carried `visibility_seconds` and the painter's `sort_seconds`).
#[test]
fn outputs_are_byte_identical_across_runs() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &[&str]); 6] = [
        ("a.svg", &[]),
        ("a.json", &[]),
        ("p.json", &["--method", "painter"]),
        ("z.png", &["--method", "zbuffer"]),
        ("b.png", &["--method", "bsp"]),
        ("s.json", &["--stats"]),
    ];
    for (name, extra) in cases {
        let run = |k: usize| -> Vec<u8> {
            let out = dir.path().join(format!("{k}{name}"));
            let mut args = vec!["render", "fixtures/cyclic_bars.obj", "--size", "96x72"];
            args.extend_from_slice(extra);
            args.extend(["-o", out.to_str().unwrap()]);
            run_ok(&args);
            std::fs::read(&out).unwrap()
        };
        let first = run(0);
        assert!(first.len() > 100, "{name}");
        assert!(
            !String::from_utf8_lossy(&first).contains("seconds"),
            "{name}: no timing in the output"
        );
        assert_eq!(first, run(1), "{name}: two runs, same bytes");
    }
}

/// `fovy 0` in a camera file is orthographic with its `ortho_height` (as
/// `../shared/compare/scenes.py` writes them): the fixture renders as the same camera given by
/// flags, and `info` says orthographic.
#[test]
fn orthographic_cam_file_renders_orthographically() {
    let by_file = run_ok(&[
        "render",
        "fixtures/cyclic_bars.obj",
        "--cam",
        "fixtures/cyclic_bars.cam",
        "-o",
        "-",
        "--fill",
        "id",
    ]);
    let by_flags = run_ok(&[
        "render",
        "fixtures/cyclic_bars.obj",
        "--eye",
        "0,0,10",
        "--target",
        "0,0,0",
        "--up",
        "0,1,0",
        "--ortho",
        "6",
        "--near",
        "0.5",
        "--far",
        "100",
        "--size",
        "160x160",
        "-o",
        "-",
        "--fill",
        "id",
    ]);
    assert_eq!(by_file.stdout, by_flags.stdout);
    let img = decode_png(&by_file.stdout).to_rgb8();
    assert_eq!(img.dimensions(), (160, 160));
    assert!(img.pixels().any(|p| p.0 != [0, 0, 0]), "the bars are seen");
    let o = sightline(&[
        "info",
        "fixtures/cyclic_bars.obj",
        "--cam",
        "fixtures/cyclic_bars.cam",
    ]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("camera: orthographic, height 6"), "{text}");
}

/// A bad value in a camera file is reported with the file and its line; a BOM and CRLF line
/// ends are read as the plain file.
#[test]
fn cam_file_errors_name_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.cam");
    std::fs::write(
        &bad,
        "eye 0 0 10\ntarget 0 0 0\nup 0 1 0\nfovy 200\nnear 1\nfar 9\n",
    )
    .unwrap();
    let (code, err) = run_err(&["info", "fixtures/cube.obj", "--cam", bad.to_str().unwrap()]);
    assert_eq!(code, Some(1));
    assert!(err.contains("bad.cam:4") && err.contains("fovy"), "{err}");
    let dos = dir.path().join("dos.cam");
    let text = std::fs::read_to_string("fixtures/cyclic_bars.cam").unwrap();
    std::fs::write(&dos, format!("\u{feff}{}", text.replace('\n', "\r\n"))).unwrap();
    let o = run_ok(&[
        "info",
        "fixtures/cyclic_bars.obj",
        "--cam",
        dos.to_str().unwrap(),
    ]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("orthographic, height 6"));
    // An orthographic file may put its near plane behind the eye; --fov makes it perspective,
    // and the file's near is then the error, named with the file.
    let ortho = dir.path().join("ortho.cam");
    std::fs::write(
        &ortho,
        "eye 0 0 5\ntarget 0 0 0\nup 0 1 0\nfovy 0\northo_height 3\nnear -5\nfar 10\n",
    )
    .unwrap();
    let cam = ortho.to_str().unwrap();
    assert!(
        sightline(&["info", "fixtures/cube.obj", "--cam", cam])
            .status
            .success()
    );
    let (code, err) = run_err(&["info", "fixtures/cube.obj", "--cam", cam, "--fov", "30"]);
    assert_eq!(code, Some(1));
    assert!(err.contains("ortho.cam: near -5 is not > 0"), "{err}");
    run_ok(&[
        "info",
        "fixtures/cube.obj",
        "--cam",
        cam,
        "--fov",
        "30",
        "--near",
        "1",
    ]);
}

/// Every camera file of the shared benchmark meshes loads and makes a valid camera.
#[test]
fn every_shared_cam_file_loads() {
    let dir = Path::new("../shared/meshes/cams");
    if !dir.is_dir() {
        println!(
            "{} is absent: skipping the shared camera files",
            dir.display()
        );
        return;
    }
    let mut n = 0;
    for e in std::fs::read_dir(dir).unwrap() {
        let path = e.unwrap().path();
        if path.extension().is_some_and(|x| x == "cam") {
            let text = std::fs::read_to_string(&path).unwrap();
            let name = path.display().to_string();
            let cam = sightline::camera::CamFile::parse(&text, &name)
                .unwrap_or_else(|e| panic!("{e}"))
                .camera();
            cam.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
            n += 1;
        }
    }
    assert!(n > 0, "no .cam file in {}", dir.display());
}

/// A negative number after a space is a value (not an unknown flag) for every numeric flag, and
/// each bad value reaches its own range check, whose message names the flag.
#[test]
fn negative_values_reach_each_flags_range_check() {
    // Every case fails before rendering: no --size needed (the --size case tests it).
    let render = ["render", "fixtures/cube.obj", "-o", "-"];
    let cases: [(&[&str], &str); 14] = [
        (
            &["--threads", "-1"],
            "invalid value '-1' for '--threads <N>'",
        ),
        (&["--fov", "-40"], "--fov must be in (0, 180)"),
        (&["--fov=-40"], "--fov must be in (0, 180)"),
        (&["--fov", "0"], "--fov must be in (0, 180)"),
        (&["--ortho", "-2"], "--ortho must be a view height > 0"),
        (&["--specular", "-1"], "--specular must be"),
        (&["--shininess", "-3"], "--shininess must be"),
        (&["--near", "-1"], "--near must be > 0"),
        (&["--far", "-1"], "--far must be > 0"),
        (
            &["--near", "3", "--far", "2"],
            "--near must be less than --far",
        ),
        (
            &["--size", "-3x4"],
            "'-3' is not an image side in 1..=16384",
        ),
        (&["--size", "0x10"], "'0' is not an image side in 1..=16384"),
        (&["--background", "-1,0,0"], "'-1' is not in 0..=255"),
        (&["--light", "-1,0"], "three numbers"),
    ];
    for (flags, want) in cases {
        let mut args = render.to_vec();
        args.extend_from_slice(flags);
        let (code, err) = run_err(&args);
        assert!(code.is_some_and(|c| c != 0), "{flags:?} accepted");
        assert!(
            err.contains(want) && !err.contains("unexpected argument"),
            "{flags:?}: {err}"
        );
    }
    for flags in [["--sphere", "-4"], ["--repeat", "-2"]] {
        let mut args = vec!["bench", "--tori", "8"];
        if flags[0] == "--sphere" {
            args = vec!["bench"];
        }
        args.extend_from_slice(&flags);
        let (code, err) = run_err(&args);
        assert_eq!(code, Some(2), "{flags:?}");
        assert!(
            err.contains(flags[0]) && err.contains(">= 1"),
            "{flags:?}: {err}"
        );
    }
    // Valid negative values work both ways.
    let a = sightline(
        &[
            &render[..],
            &[
                "--size", "16x16", "--ortho", "3", "--near", "-5", "--fill", "id",
            ],
        ]
        .concat(),
    );
    let b = sightline(
        &[
            &render[..],
            &["--size=16x16", "--ortho=3", "--near=-5", "--fill", "id"],
        ]
        .concat(),
    );
    assert!(a.status.success(), "{}", String::from_utf8_lossy(&a.stderr));
    assert_eq!(a.stdout, b.stdout);
}

/// An eye so far that the scene's depth rounds away says so, not that near/far (never given)
/// are wrong.
#[test]
fn a_far_eye_is_the_reported_problem() {
    let (code, err) = run_err(&[
        "render",
        "fixtures/cube.obj",
        "-o",
        "-",
        "--eye",
        "1e30,1e30,1e30",
    ]);
    assert_eq!(code, Some(1));
    assert!(
        err.contains("eye is too far") && !err.contains("near"),
        "{err}"
    );
}

/// A camera looking away from the scene writes the empty picture (background PNG, SVG with no
/// region, JSON with no face), warns on stderr, and succeeds.
#[test]
fn a_camera_that_sees_nothing_writes_empty_output_and_warns() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["e.png", "e.svg", "e.json"] {
        let out = dir.path().join(name);
        let o = sightline(&[
            "render",
            "fixtures/cube.obj",
            "--eye",
            "10,0,0",
            "--target",
            "20,0,0",
            "--size",
            "8x8",
            "-o",
            out.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{name}: {err}");
        assert!(
            err.contains("warning: the camera sees none"),
            "{name}: {err}"
        );
        let bytes = std::fs::read(&out).unwrap();
        match name {
            "e.png" => assert!(
                decode_png(&bytes)
                    .to_rgb8()
                    .pixels()
                    .all(|p| p.0 == [255; 3])
            ),
            "e.svg" => assert!(!String::from_utf8_lossy(&bytes).contains("<path")),
            _ => {
                let v: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
                assert_eq!(v["faces"], serde_json::json!([]));
            }
        }
    }
}

/// Point 12 of issue 8: the README's first command shows the cube's form, its three visible
/// faces in three clearly different colours (the top and the left one are both red), as does
/// the cube with one material.
#[test]
fn the_first_command_shows_three_shades_of_the_cube() {
    let dir = tempfile::tempdir().unwrap();
    for input in ["fixtures/cube.obj", "fixtures/cube_ascii.stl"] {
        let out = dir.path().join("cube.png");
        run_ok(&["render", input, "-o", out.to_str().unwrap()]);
        let img = decode_png(&std::fs::read(&out).unwrap()).to_rgb8();
        let mut count = std::collections::HashMap::<[u8; 3], usize>::new();
        for p in img.pixels().filter(|p| p.0 != [255; 3]) {
            *count.entry(p.0).or_default() += 1;
        }
        let mut by_count: Vec<([u8; 3], usize)> = count.into_iter().collect();
        by_count.sort_by_key(|&(c, n)| (std::cmp::Reverse(n), c));
        // Each visible face covers more than an eighth of the image.
        let faces: Vec<[u8; 3]> = by_count[..3].iter().map(|&(c, _)| c).collect();
        assert!(by_count[2].1 > 1024 * 1024 / 8, "{input}: {by_count:?}");
        for i in 0..3 {
            let (a, b) = (faces[i], faces[(i + 1) % 3]);
            let d: i32 = (0..3).map(|k| (a[k] as i32 - b[k] as i32).abs()).sum();
            assert!(d > 20, "{input}: {faces:?}");
        }
    }
}

/// `-o -` on a terminal refuses a binary PNG (text formats are fine). Runs the binary under
/// `script`, which gives it a pseudo-terminal, when `script` is installed.
#[test]
fn png_is_not_written_onto_a_terminal() {
    let bin = env!("CARGO_BIN_EXE_sightline");
    let Some(o) = on_a_terminal(&format!("{bin} render fixtures/cube.obj --size 8x8 -o -")) else {
        println!("`script` is not installed: the terminal decision is tested in main.rs only");
        return;
    };
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(!o.status.success(), "{text}");
    assert!(
        text.contains("not writing a binary PNG to a terminal"),
        "{text}"
    );
    assert!(!text.contains("PNG\r\n\u{1a}"), "no PNG bytes: {text}");
    // Named as a path, the terminal is refused too.
    let o = on_a_terminal(&format!(
        "{bin} render fixtures/cube.obj --size 8x8 --to png -o /dev/stdout"
    ))
    .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(!o.status.success(), "{text}");
    assert!(
        text.contains("not writing a binary PNG to a terminal"),
        "{text}"
    );
    let o = on_a_terminal(&format!(
        "{bin} render fixtures/cube.obj --size 8x8 --to svg -o -"
    ))
    .unwrap();
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("<svg"));
}

/// A flag the output would ignore is an error that says so.
#[test]
fn flags_that_do_not_apply_to_the_output_are_errors() {
    let cases: [(&str, &[&str], &str); 6] = [
        (
            "x.png",
            &["--stroke"],
            "--stroke applies to SVG output only",
        ),
        ("x.json", &["--crisp"], "--crisp applies to SVG output only"),
        (
            "x.png",
            &["--fill", "id", "--specular", "0.5"],
            "--specular",
        ),
        (
            "x.svg",
            &["--fill", "id", "--no-headlight"],
            "--no-headlight",
        ),
        (
            "x.png",
            &["--fill", "id", "--shading", "phong"],
            "--shading",
        ),
        ("x.json", &["--light", "1,2,3"], "does not apply to JSON"),
    ];
    let dir = tempfile::tempdir().unwrap();
    for (name, flags, want) in cases {
        let out = dir.path().join(name);
        let mut args = vec!["render", "fixtures/cube.obj", "--size", "16x16", "-o"];
        args.push(out.to_str().unwrap());
        args.extend_from_slice(flags);
        let (code, err) = run_err(&args);
        assert_eq!(code, Some(1), "{name} {flags:?}");
        assert!(err.contains(want), "{name} {flags:?}: {err}");
        assert!(!out.exists());
    }
    // Where they apply, they are accepted.
    let out = dir.path().join("ok.svg");
    run_ok(&[
        "render",
        "fixtures/cube.obj",
        "--stroke",
        "--crisp",
        "-o",
        out.to_str().unwrap(),
    ]);
}

/// Without --method the output chooses: the exact visible set for SVG and JSON, the z-buffer for
/// PNG.
#[test]
fn default_method_follows_the_output() {
    let dir = tempfile::tempdir().unwrap();
    let path = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    for (name, method) in [("d.svg", "auto"), ("d.json", "auto"), ("d.png", "zbuffer")] {
        run_ok(&[
            "render",
            "fixtures/cube.obj",
            "--size",
            "32x32",
            "-o",
            &path(name),
        ]);
        let explicit = format!("m{name}");
        run_ok(&[
            "render",
            "fixtures/cube.obj",
            "--size",
            "32x32",
            "--method",
            method,
            "-o",
            &path(&explicit),
        ]);
        assert_eq!(
            std::fs::read(path(name)).unwrap(),
            std::fs::read(path(&explicit)).unwrap(),
            "{name}"
        );
    }
}

/// A loader warning names the file once.
#[test]
fn warnings_name_the_file_once() {
    let dir = tempfile::tempdir().unwrap();
    let junk = dir.path().join("junk.obj");
    std::fs::write(&junk, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\njunk\n").unwrap();
    let (code, err) = run_err(&["info", junk.to_str().unwrap()]);
    assert_eq!(code, Some(0), "{err}");
    let line = err
        .lines()
        .find(|l| l.starts_with("warning:"))
        .expect("a warning");
    assert_eq!(line.matches("junk.obj").count(), 1, "{line}");
    assert!(line.contains("junk.obj:5"), "{line}");
}

/// (covered, interior) of `compare`'s report.
fn compare_counts(args: &[&str]) -> (usize, usize) {
    let o = run_ok(args);
    let text = String::from_utf8_lossy(&o.stdout).to_string();
    let count = |label: &str| -> usize {
        let line = text
            .lines()
            .find(|l| l.trim_start().starts_with(label))
            .unwrap();
        line.split_whitespace().nth(2).unwrap().parse().unwrap()
    };
    (count("covered pixels"), count("interior pixels"))
}

/// Interior pixels are covered pixels: background never counts as interior.
#[test]
fn compare_counts_interior_within_covered() {
    for f in ["fixtures/cube.obj", "fixtures/cyclic_bars.obj"] {
        let (covered, interior) = compare_counts(&["compare", f, "--size", "160x120"]);
        assert!(
            0 < interior && interior < covered,
            "{f}: {interior} of {covered}"
        );
    }
}

/// `compare --diff` draws mismatches in red over the reference in grey: none for the exact set
/// against the z-buffer, some for the painter on cyclic bars.
#[test]
fn compare_diff_marks_mismatched_pixels_in_red() {
    let dir = tempfile::tempdir().unwrap();
    let red_pixels = |file: &str, method: &str| -> usize {
        let out = dir.path().join(format!("{method}.png"));
        run_ok(&[
            "compare",
            file,
            "--method",
            method,
            "--view",
            "front",
            "--size",
            "96x72",
            "--diff",
            out.to_str().unwrap(),
        ]);
        let img = decode_png(&std::fs::read(&out).unwrap()).to_rgb8();
        assert_eq!(img.dimensions(), (96, 72));
        assert!(img.pixels().any(|p| p.0 == [255; 3]), "white background");
        assert!(
            img.pixels()
                .any(|p| p.0[0] == p.0[1] && p.0[1] == p.0[2] && p.0[0] < 255),
            "grey faces"
        );
        img.pixels().filter(|p| p.0 == [255, 0, 0]).count()
    };
    assert_eq!(red_pixels("fixtures/cyclic_bars.obj", "bsp"), 0);
    assert!(red_pixels("fixtures/cyclic_bars.obj", "painter") > 0);
}

/// Point 9 of issue 8: progress bars ("visible set", "painter order", "rendering") are drawn
/// only when stderr is a terminal; piped, a render's stderr carries nothing.
#[test]
fn progress_is_silent_when_stderr_is_not_a_terminal() {
    let dir = tempfile::tempdir().unwrap();
    for (input, method, out) in [
        ("fixtures/interpenetrating.obj", "bsp", "x.svg"),
        ("fixtures/cube.obj", "bsp", "x.svg"),
        ("fixtures/cube_ascii.stl", "zbuffer", "x.png"),
    ] {
        let out = dir.path().join(out);
        let o = run_ok(&[
            "render",
            input,
            "--method",
            method,
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(
            o.stderr.is_empty(),
            "{input} {method}: {:?}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

/// The other half of point 9: on a terminal, the long stages show labelled bars. The binary
/// runs under `script` (a pseudo-terminal) on a generated grid of 20,000 triangles.
#[test]
fn progress_bars_are_labelled_on_a_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("grid.obj");
    let n = 100;
    let mut text = String::new();
    for j in 0..=n {
        for i in 0..=n {
            // A wavy surface: faces of many planes, nothing merges.
            let z = ((i * 7 + j * 13) % 5) as f64 * 0.01;
            text.push_str(&format!("v {i} {j} {z}\n"));
        }
    }
    for j in 0..n {
        for i in 0..n {
            let v = |i: usize, j: usize| j * (n + 1) + i + 1;
            text.push_str(&format!(
                "f {} {} {}\n",
                v(i, j),
                v(i + 1, j),
                v(i + 1, j + 1)
            ));
            text.push_str(&format!(
                "f {} {} {}\n",
                v(i, j),
                v(i + 1, j + 1),
                v(i, j + 1)
            ));
        }
    }
    std::fs::write(&mesh, text).unwrap();
    let out = dir.path().join("grid.svg");
    let cmd = format!(
        "{} render {} -o {}",
        env!("CARGO_BIN_EXE_sightline"),
        mesh.display(),
        out.display()
    );
    let Some(o) = on_a_terminal(&cmd) else {
        println!("`script` is not installed: bars on a terminal not checked");
        return;
    };
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stdout));
    let shown = String::from_utf8_lossy(&o.stdout);
    for label in ["loading", "visible set", "regions"] {
        assert!(shown.contains(label), "no '{label}' bar: {shown:?}");
    }
    assert!(std::fs::read_to_string(&out).unwrap().contains("<path"));
}

/// A method that draws translucent faces as opaque says so, and names the methods that blend
/// (from the registry); a method that blends, or `--fill id`, says nothing.
#[test]
fn translucent_faces_drawn_opaque_are_warned_about() {
    let out = tmp("glass.png");
    let out = out.to_str().unwrap();
    let stderr = |flags: &[&str]| {
        let mut args = vec![
            "render",
            "fixtures/tinted_glass.obj",
            "--size",
            "32x24",
            "-o",
            out,
        ];
        args.extend_from_slice(flags);
        String::from_utf8(run_ok(&args).stderr).unwrap()
    };
    let warned = stderr(&["--method", "zbuffer"]);
    assert!(
        warned.contains("--method zbuffer draws translucent faces as opaque (1 on screen)")
            && warned.contains(
                "abuffer, auto, coverage, bsp, newell, weiler-atherton, warnock-exact or painter"
            ),
        "{warned}"
    );
    assert_eq!(stderr(&["--method", "abuffer"]), "");
    assert_eq!(stderr(&["--method", "coverage"]), "");
    assert_eq!(stderr(&["--method", "zbuffer", "--fill", "id"]), "");
}
