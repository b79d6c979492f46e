//! The background of a render (issue 8, point 13): an X3D scene's own (its Background's
//! skyColor, black when it has none, as X3D specifies), white for other formats, or
//! `--background R,G,B|none`. The seed's transparent scene then shows the course material's
//! colours: green with transparency 0.4 over black (0, 153, 0), over the blue (0, 153, 102).

mod support;

use std::collections::HashMap;
use support::cli::{render_ok, run_err};
use support::seam_measure;

/// Renders to a file in a temporary directory and returns its bytes.
fn render(input: &str, name: &str, extra: &[&str]) -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join(name);
    render_ok(input, &out, &[&["--size", "256x256"][..], extra].concat());
    std::fs::read(out).unwrap()
}

/// Pixel colours by how many pixels have them, most first.
fn colours(pixels: impl Iterator<Item = [u8; 3]>) -> Vec<([u8; 3], usize)> {
    let mut count: HashMap<[u8; 3], usize> = HashMap::new();
    for p in pixels {
        *count.entry(p).or_default() += 1;
    }
    let mut v: Vec<_> = count.into_iter().collect();
    v.sort_by_key(|&(c, n)| (std::cmp::Reverse(n), c));
    v
}

fn png_colours(bytes: &[u8]) -> Vec<([u8; 3], usize)> {
    let img = image::load_from_memory(bytes).unwrap().to_rgb8();
    colours(img.pixels().map(|p| p.0))
}

fn svg_colours(bytes: &[u8]) -> Vec<([u8; 3], usize)> {
    let svg = String::from_utf8(bytes.to_vec()).unwrap();
    let rgba = seam_measure::rasterize(&svg, 256, 256);
    assert!(rgba.iter().all(|p| p[3] == 255), "an opaque background");
    colours(rgba.iter().map(|p| [p[0], p[1], p[2]]))
}

/// The three largest colours: background, green alone, green over blue.
fn assert_seed_colours(found: &[([u8; 3], usize)], what: &str) {
    let top: Vec<[u8; 3]> = found.iter().take(4).map(|&(c, _)| c).collect();
    for want in [[0, 0, 0], [0, 153, 0], [0, 153, 102], [0, 0, 255]] {
        assert!(top.contains(&want), "{what}: {want:?} not among {top:?}");
    }
}

#[test]
fn the_seed_scene_shows_the_course_colours_over_x3d_black() {
    let scene = "fixtures/seed_transparent.x3d";
    for method in ["abuffer", "bsp"] {
        let png = render(scene, "seed.png", &["--method", method]);
        assert_seed_colours(&png_colours(&png), method);
    }
    let svg = render(scene, "seed.svg", &[]);
    assert_seed_colours(&svg_colours(&svg), "svg");
}

#[test]
fn an_x3d_background_sky_colour_is_the_default_and_the_flag_overrides_it() {
    // fixtures/background.x3d: the first Background's first skyColor, 0.2 0.4 0.6.
    let png = render("fixtures/background.x3d", "b.png", &[]);
    assert_eq!(png_colours(&png)[0].0, [51, 102, 153]);
    let png = render(
        "fixtures/background.x3d",
        "b.png",
        &["--background", "10,20,30"],
    );
    assert_eq!(png_colours(&png)[0].0, [10, 20, 30]);
}

#[test]
fn other_formats_keep_white() {
    let png = render("fixtures/cube.obj", "c.png", &[]);
    assert_eq!(png_colours(&png)[0].0, [255, 255, 255]);
}

#[test]
fn background_none_gives_an_svg_without_a_background() {
    let svg = render("fixtures/cube.obj", "c.svg", &["--background", "none"]);
    let text = String::from_utf8(svg).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    assert!(!doc.descendants().any(|n| n.has_tag_name("rect")), "{text}");
    let rgba = seam_measure::rasterize(&text, 256, 256);
    assert_eq!(rgba[0][3], 0, "the corner is transparent");
    // With a background, the rectangle comes first.
    let svg = render("fixtures/cube.obj", "c.svg", &[]);
    assert!(
        String::from_utf8(svg)
            .unwrap()
            .contains("<rect fill=\"#ffffff\"")
    );
    // PNG has no transparency here: refused, not ignored.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c.png");
    let (code, err) = run_err(&[
        "render",
        "fixtures/cube.obj",
        "--background",
        "none",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_ne!(code, Some(0));
    assert!(
        err.contains("--background none applies to SVG output"),
        "{err}"
    );
}
