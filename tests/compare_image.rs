//! `sightline compare INPUT --image THEIRS.png`: grading a face-id image made by another
//! renderer against the exact visible set, through the command line.

mod support;

use image::{Rgb, RgbImage};
use sightline::paint::{id_color, id_from_color};
use std::path::Path;
use support::cli::{decode_png, run_err, run_ok, sightline};

/// Camera flags of the graded views (the image size comes from the PNG).
const CUBE_VIEW: [&str; 2] = ["--view", "iso"];

/// The counts of `compare --image`'s report, by label.
#[derive(Debug, Default, PartialEq)]
struct Report {
    image_covered: usize,
    exact_covered: usize,
    wrong: usize,
    wrong_face: usize,
    missing_face: usize,
    extra_face: usize,
    unknown_id: usize,
    ties: usize,
    area_error_pct: f64,
}

fn parse_report(stdout: &[u8]) -> Report {
    let text = String::from_utf8_lossy(stdout);
    let field = |label: &str| -> &str {
        let line = text
            .lines()
            .find(|l| l.trim_start().starts_with(label))
            .unwrap_or_else(|| panic!("no '{label}' in\n{text}"));
        line.trim_start()[label.len()..].trim_start()
    };
    let first = |label: &str| -> usize {
        field(label)
            .split_whitespace()
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    let covered = field("covered pixels");
    // "image N, exact M (...)"
    let words: Vec<&str> = covered.split_whitespace().collect();
    Report {
        image_covered: words[1].trim_end_matches(',').parse().unwrap(),
        exact_covered: words[3].parse().unwrap(),
        wrong: first("wrong pixels"),
        wrong_face: first("wrong face"),
        missing_face: first("missing face"),
        extra_face: first("extra face"),
        unknown_id: first("unknown id"),
        ties: first("tie pixels"),
        area_error_pct: field("area error")
            .split_whitespace()
            .next()
            .unwrap()
            .trim_end_matches('%')
            .parse()
            .unwrap(),
    }
}

/// Grades `image` as a face-id image of `input` with `flags`; fails unless it succeeds.
fn grade(input: &str, image: &Path, flags: &[&str]) -> Report {
    let o = run_ok(
        &[
            &["compare", input, "--image", image.to_str().unwrap()],
            flags,
        ]
        .concat(),
    );
    parse_report(&o.stdout)
}

/// Our own z-buffer's face-id image of `input`.
fn zbuffer_ids(input: &str, out: &Path, flags: &[&str]) -> RgbImage {
    run_ok(
        &[
            &[
                "render",
                input,
                "--method",
                "zbuffer",
                "--fill",
                "id",
                "-o",
                out.to_str().unwrap(),
            ],
            flags,
        ]
        .concat(),
    );
    decode_png(&std::fs::read(out).unwrap()).to_rgb8()
}

fn ids_of(img: &RgbImage) -> Vec<Option<u32>> {
    img.pixels().map(|p| id_from_color(p.0)).collect()
}

/// Our exact z-buffer samples pixel centres exactly: graded, it has no wrong pixel, covers
/// exactly what the exact set covers, and still has a small positive area error (pixels that
/// edges cross give part of their area to a face the centre does not show).
#[test]
fn our_zbuffer_image_has_no_wrong_pixel_and_a_small_area_error() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("ids.png");
    let img = zbuffer_ids(
        "fixtures/cube.obj",
        &png,
        &[&CUBE_VIEW[..], &["--size", "160x120"]].concat(),
    );
    let r = grade("fixtures/cube.obj", &png, &CUBE_VIEW);
    let covered = ids_of(&img).iter().flatten().count();
    assert_eq!(r.wrong, 0, "{r:?}");
    assert_eq!((r.image_covered, r.exact_covered), (covered, covered));
    assert!(covered > 1000, "{r:?}");
    assert!(r.area_error_pct > 0.0 && r.area_error_pct < 2.0, "{r:?}");
}

/// The same image shifted right by one pixel: every pixel whose id changed is wrong, of the
/// kind the change says (no centre lies on a boundary in this view, so the z-buffer's ids are
/// the only right ones), and the area error grows.
#[test]
fn an_image_shifted_by_a_pixel_is_wrong_exactly_where_it_changed() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("ids.png");
    let right = zbuffer_ids(
        "fixtures/cube.obj",
        &png,
        &[&CUBE_VIEW[..], &["--size", "160x120"]].concat(),
    );
    let base = grade("fixtures/cube.obj", &png, &CUBE_VIEW);
    assert_eq!(base.ties, 0, "the expectations below assume no ties");
    let (w, h) = right.dimensions();
    let shifted = RgbImage::from_fn(w, h, |x, y| {
        if x == 0 {
            Rgb([0, 0, 0])
        } else {
            *right.get_pixel(x - 1, y)
        }
    });
    let shifted_png = dir.path().join("shifted.png");
    shifted.save(&shifted_png).unwrap();
    let (a, b) = (ids_of(&right), ids_of(&shifted));
    let count = |f: &dyn Fn(Option<u32>, Option<u32>) -> bool| {
        a.iter().zip(&b).filter(|(r, s)| f(**r, **s)).count()
    };
    let expected = Report {
        image_covered: b.iter().flatten().count(),
        exact_covered: base.exact_covered,
        wrong: count(&|r, s| r != s),
        wrong_face: count(&|r, s| r.is_some() && s.is_some() && r != s),
        missing_face: count(&|r, s| r.is_some() && s.is_none()),
        extra_face: count(&|r, s| r.is_none() && s.is_some()),
        unknown_id: 0,
        ties: 0,
        area_error_pct: 0.0,
    };
    let diff = dir.path().join("diff.png");
    let o = run_ok(&[
        "compare",
        "fixtures/cube.obj",
        "--image",
        shifted_png.to_str().unwrap(),
        "--view",
        "iso",
        "--diff",
        diff.to_str().unwrap(),
    ]);
    let r = parse_report(&o.stdout);
    assert!(expected.wrong > 100 && expected.wrong_face > 0 && expected.missing_face > 0);
    assert_eq!(
        Report {
            area_error_pct: 0.0,
            ..r
        },
        expected
    );
    assert!(
        r.area_error_pct > 2.0 * base.area_error_pct,
        "{r:?} vs {base:?}"
    );
    // The picture: red for each wrong face, blue for each missing or extra one.
    let pic = decode_png(&std::fs::read(&diff).unwrap()).to_rgb8();
    assert_eq!(pic.dimensions(), (w, h));
    let of = |c: [u8; 3]| pic.pixels().filter(|p| p.0 == c).count();
    assert_eq!(of([255, 0, 0]), expected.wrong_face);
    assert_eq!(
        of([0, 96, 255]),
        expected.missing_face + expected.extra_face
    );
}

/// Two visible faces' ids swapped: every pixel of either is a wrong face; an id beyond the
/// scene's faces is an unknown id, with a warning about colour management.
#[test]
fn swapped_and_unknown_ids_are_counted_as_such() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("ids.png");
    let mut img = zbuffer_ids(
        "fixtures/cube.obj",
        &png,
        &[&CUBE_VIEW[..], &["--size", "96x72"]].concat(),
    );
    let ids = ids_of(&img);
    let mut faces: Vec<u32> = ids.iter().flatten().copied().collect();
    faces.sort_unstable();
    faces.dedup();
    assert!(faces.len() >= 2, "{faces:?}");
    let (f, g) = (faces[0], faces[1]);
    let swapped = ids
        .iter()
        .filter(|i| **i == Some(f) || **i == Some(g))
        .count();
    for p in img.pixels_mut() {
        match id_from_color(p.0) {
            Some(i) if i == f => p.0 = id_color(g),
            Some(i) if i == g => p.0 = id_color(f),
            _ => {}
        }
    }
    // One background pixel (the corner) given a number no face has.
    assert_eq!(img.get_pixel(0, 0).0, [0, 0, 0]);
    img.put_pixel(0, 0, Rgb([1, 2, 3]));
    let bad = dir.path().join("swapped.png");
    img.save(&bad).unwrap();
    let o = run_ok(&[
        "compare",
        "fixtures/cube.obj",
        "--image",
        bad.to_str().unwrap(),
        "--view",
        "iso",
    ]);
    let r = parse_report(&o.stdout);
    assert_eq!(
        (
            r.wrong,
            r.wrong_face,
            r.unknown_id,
            r.missing_face,
            r.extra_face
        ),
        (swapped + 1, swapped, 1, 0, 0),
        "{r:?}"
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("swapped.png")
            && err.contains("no face of the scene")
            && err.contains("colour-managed"),
        "{err}"
    );
}

/// A square split along its diagonal, seen so that its outline and its diagonal pass exactly
/// through pixel centres: our z-buffer has ties there and is graded right; a crack along the
/// diagonal (background where two faces meet) is not.
#[test]
fn centres_exactly_on_edges_accept_either_face_but_not_a_crack() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("square.obj");
    std::fs::write(
        &obj,
        "v -1.5 -1.5 0\nv 1.5 -1.5 0\nv 1.5 1.5 0\nv -1.5 1.5 0\nf 1 3 4\nf 1 2 3\n",
    )
    .unwrap();
    let obj = obj.to_str().unwrap();
    let camera = [
        "--eye", "0,0,5", "--target", "0,0,0", "--up", "0,1,0", "--ortho", "4", "--near", "1",
        "--far", "10",
    ];
    let png = dir.path().join("ids.png");
    let mut img = zbuffer_ids(obj, &png, &[&camera[..], &["--size", "6x4"]].concat());
    let r = grade(obj, &png, &camera);
    assert_eq!((r.wrong, r.ties, r.exact_covered), (0, 14, 16), "{r:?}");
    // Pixel (i, j) has its centre at (i - 2.5, 1.5 - j): (2, 2) and (3, 1) are on the diagonal
    // inside the square.
    for (i, j) in [(2, 2), (3, 1)] {
        assert_ne!(img.get_pixel(i, j).0, [0, 0, 0]);
        img.put_pixel(i, j, Rgb([0, 0, 0]));
    }
    img.save(&png).unwrap();
    let r = grade(obj, &png, &camera);
    assert_eq!((r.wrong, r.missing_face), (2, 2), "{r:?}");
}

#[test]
fn a_size_that_disagrees_with_the_image_is_an_error_naming_both() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("ids.png");
    zbuffer_ids("fixtures/cube.obj", &png, &["--size", "64x48"]);
    let (code, err) = run_err(&[
        "compare",
        "fixtures/cube.obj",
        "--image",
        png.to_str().unwrap(),
        "--size",
        "64x64",
    ]);
    assert_eq!(code, Some(1));
    assert!(
        err.contains("--size 64x64") && err.contains("64x48") && err.contains("ids.png"),
        "{err}"
    );
    // The image's own size is fine to repeat.
    run_ok(&[
        "compare",
        "fixtures/cube.obj",
        "--image",
        png.to_str().unwrap(),
        "--size",
        "64x48",
    ]);
}

/// Images that break the contract are refused with the file and what was found; missing and
/// corrupt files name the path; none panics, each exits with status 1.
#[test]
fn bad_images_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, w: u32, h: u32, color, depth, data: &[u8]| {
        let path = dir.path().join(name);
        let mut enc = png::Encoder::new(std::fs::File::create(&path).unwrap(), w, h);
        enc.set_color(color);
        enc.set_depth(depth);
        enc.write_header().unwrap().write_image_data(data).unwrap();
        path
    };
    use png::{BitDepth, ColorType};
    let deep = write("deep.png", 1, 1, ColorType::Rgb, BitDepth::Sixteen, &[0; 6]);
    let grey = write(
        "grey.png",
        1,
        1,
        ColorType::Grayscale,
        BitDepth::Eight,
        &[9],
    );
    let soft = write(
        "soft.png",
        2,
        1,
        ColorType::Rgba,
        BitDepth::Eight,
        &[0, 0, 1, 255, 0, 0, 1, 77],
    );
    let junk = dir.path().join("junk.png");
    std::fs::write(&junk, b"GIF89a, not a PNG").unwrap();
    let missing = dir.path().join("missing.png");
    for (path, says) in [
        (&deep, "16-bit"),
        (&grey, "grey"),
        (&soft, "pixel (1, 0)"),
        (&soft, "alpha 77"),
        (&junk, "not a readable PNG"),
        (&missing, "No such file"),
    ] {
        let o = sightline(&[
            "compare",
            "fixtures/cube.obj",
            "--image",
            path.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(
            err.contains(path.file_name().unwrap().to_str().unwrap()) && err.contains(says),
            "{path:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{err}");
        assert!(o.stdout.is_empty());
    }
}

#[test]
fn image_conflicts_with_methods() {
    let (code, err) = run_err(&[
        "compare",
        "fixtures/cube.obj",
        "--image",
        "x.png",
        "--against",
        "painter",
    ]);
    assert_eq!(code, Some(2));
    assert!(
        err.contains("--image") && err.contains("--against"),
        "{err}"
    );
}
