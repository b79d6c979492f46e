//! Filled SVGs look right in an anti-aliasing viewer (resvg): no background shows through the
//! boundaries regions share, and nothing is drawn outside the visible opaque area.
//!
//! Measure (a) of issue 8: the SVG without background, rasterized onto transparency, covers the
//! exact visible area of the opaque faces within 0.1 %. Without the seam strokes the same
//! drawings lose several per cent through their shared boundaries (the test checks that too,
//! so that it can tell seams apart from their absence).

mod support;

use sightline::camera::{Camera, NamedView};
use sightline::output::drawing::Drawing;
use sightline::output::svg::{SvgOptions, write_svg};
use sightline::pipeline::{Fill, colorize_polys, prepare};
use sightline::project::CullMode;
use sightline::raster::{EMPTY, zbuffer};
use sightline::scene::Scene;
use sightline::scene::primitives::{interlocked_tori, random_triangle_soup, sphere_scene};
use support::camera::{named_view, scene_camera};
use support::fixtures::fixture;
use support::seam_measure::{alpha_area, over_white, rasterize, rings_area, seam_defects};
use support::strategy::{exact_drawing, exact_picture};

/// The picture as `render --method coverage -o X.svg` draws it, and the exact opaque visible area
/// (the per-face drawing, as the JSON holds it).
fn picture_and_exact_area(scene: &Scene, camera: &Camera) -> (Drawing, f64) {
    let screen = prepare(scene, camera, CullMode::Auto).screen;
    let picture = exact_picture(scene, &screen, camera, Fill::Shade).drawing;
    let per_face = exact_drawing(scene, &screen, camera, Fill::Shade).drawing;
    let area = per_face
        .items
        .iter()
        .filter(|i| i.opacity >= 1.0)
        .map(|i| rings_area(&i.rings))
        .sum();
    (picture, area)
}

fn covered_alpha(d: &Drawing) -> f64 {
    let mut d = d.clone();
    d.background = None;
    alpha_area(&write_svg(&d, &SvgOptions::default()), d.width, d.height)
}

/// (a), with and without the seams, as relative errors against the exact area.
fn alpha_errors(scene: &Scene, camera: &Camera) -> (f64, f64) {
    let (picture, exact) = picture_and_exact_area(scene, camera);
    assert!(exact > 1000.0, "the scene fills part of the image");
    assert!(!picture.seams.strokes.is_empty(), "these scenes have seams");
    let mut bare = picture.clone();
    bare.seams = Default::default();
    let rel = |a: f64| (a - exact) / exact;
    (rel(covered_alpha(&picture)), rel(covered_alpha(&bare)))
}

/// (a) for `scene` seen from `view` at `size`: within 0.1 % with the seams, short by more than
/// 0.5 % without them.
fn check(name: &str, scene: &Scene, view: NamedView, size: (u32, u32)) {
    let (with, without) = alpha_errors(scene, &named_view(scene, view, size));
    eprintln!("{name}: alpha vs exact area {with:+.5} with seams, {without:+.5} without");
    assert!(
        with.abs() < 0.001,
        "{name}: the anti-aliased SVG covers {:+.3} % of the exact area",
        100.0 * with
    );
    assert!(
        without < -0.005,
        "{name}: without seam strokes the test sees the seams ({:+.3} %)",
        100.0 * without
    );
}

#[test]
fn a_closed_sphere_covers_its_exact_area_with_no_seams() {
    let scene = sphere_scene(3000);
    check("sphere", &scene, NamedView::Iso, (1024, 1024));
}

#[test]
fn interlocked_tori_cover_their_exact_area_through_occlusion_boundaries() {
    // Occlusion boundaries: T-junctions where one torus passes in front of the other.
    let scene = interlocked_tori(40, 16);
    check("tori", &scene, NamedView::Front, (1024, 768));
    check("tori iso", &scene, NamedView::Iso, (1024, 768));
}

#[test]
fn an_interpenetrating_soup_covers_its_exact_area() {
    // Two-sided triangles cut by each other's planes: seams along intersection lines.
    let scene = random_triangle_soup(60, 5);
    check("soup", &scene, NamedView::Iso, (1024, 1024));
}

#[test]
fn no_pixel_inside_the_silhouette_shows_the_background() {
    // Measure (b'): over white, a pixel inside the silhouette that is farther than 24 (R+G+B)
    // from the range of the z-buffer colours around it shows something no face there has: the
    // background, through a seam. Blends of neighbouring faces (anti-aliased creases) are not.
    let scene = sphere_scene(3000);
    let camera = named_view(&scene, NamedView::Iso, (320, 320));
    let screen = prepare(&scene, &camera, CullMode::Auto).screen;
    let zb = zbuffer::render(&screen, |_| {});
    let reference = colorize_polys(&scene, &screen, &zb.poly, &camera, Fill::Shade, [255; 3]);
    let covered: Vec<bool> = zb.poly.iter().map(|&p| p != EMPTY).collect();
    let (picture, _) = picture_and_exact_area(&scene, &camera);
    let defects = |d: &Drawing| {
        let mut d = d.clone();
        d.background = Some([1.0; 3]);
        let rgb = over_white(&rasterize(&write_svg(&d, &SvgOptions::default()), 320, 320));
        seam_defects(&rgb, &reference, &covered, 320, 320)
    };
    let (inside, _, after) = defects(&picture);
    let mut bare = picture.clone();
    bare.seams = Default::default();
    let (_, _, before) = defects(&bare);
    assert!(inside > 20_000);
    assert_eq!(after, 0, "pixels showing the background through a seam");
    assert!(
        before > inside / 100,
        "without seam strokes the background shows ({before} of {inside})"
    );
}

#[test]
fn seams_are_clipped_to_the_opaque_outline_and_written_under_the_fills() {
    let scene = sphere_scene(500);
    let camera = named_view(&scene, NamedView::Iso, (200, 200));
    let (picture, _) = picture_and_exact_area(&scene, &camera);
    let svg = write_svg(&picture, &SvgOptions::default());
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let clip = doc
        .descendants()
        .find(|n| n.has_tag_name("clipPath"))
        .expect("a clip path");
    let id = clip.attribute("id").unwrap();
    let group = doc
        .descendants()
        .find(|n| n.attribute("clip-path") == Some(&format!("url(#{id})")[..]))
        .expect("the seams' group uses the clip");
    // Under the fills: the seams come before every filled region in document order.
    let first_fill = doc
        .descendants()
        .position(|n| n.attribute("data-face").is_some())
        .unwrap();
    let seams_at = doc.descendants().position(|n| n == group).unwrap();
    assert!(seams_at < first_fill);
    assert_eq!(group.attribute("fill"), Some("none"));
    assert_eq!(group.attribute("stroke-linecap"), Some("butt"));
    for path in group.children().filter(|n| n.has_tag_name("path")) {
        assert!(path.attribute("stroke").unwrap().starts_with('#'));
        assert_eq!(path.attribute("vector-effect"), Some("non-scaling-stroke"));
    }
    // Every seam colour is the colour of some region.
    let fills: std::collections::BTreeSet<&str> = doc
        .descendants()
        .filter(|n| n.attribute("data-face").is_some())
        .filter_map(|n| n.attribute("fill"))
        .collect();
    for path in group.children().filter(|n| n.has_tag_name("path")) {
        assert!(fills.contains(path.attribute("stroke").unwrap()));
    }
}

#[test]
fn translucent_faces_are_drawn_over_a_seamless_opaque_set() {
    // The seed's scene: blue opaque behind, green translucent in front. The opaque faces come
    // first (with their seams), then the translucent parts in front of them, one item per run
    // of fragments of one face.
    let scene = fixture("seed_transparent.x3d");
    let camera = scene_camera(&scene);
    let (picture, _) = picture_and_exact_area(&scene, &camera);
    let first_translucent = picture
        .items
        .iter()
        .position(|i| i.opacity < 1.0)
        .expect("a translucent item");
    assert!(first_translucent > 0, "opaque items first");
    assert!(
        picture.items[first_translucent..]
            .iter()
            .all(|i| i.opacity < 1.0)
    );
    let faces: Vec<u32> = picture.items[first_translucent..]
        .iter()
        .map(|i| i.face)
        .collect();
    let mut runs = faces.clone();
    runs.dedup();
    assert_eq!(runs, faces, "one item per run of one face's fragments");
}
