//! Exact strategies compute the same visible point set, cut into different convex pieces; the
//! drawing stage must write the same bytes for all of them (issue 9, point 5). Every exact
//! object-space strategy of the method registry is held to the coverage map's output on every
//! fixture from two views and on generated scenes: the SVG picture (surfaces merged, seams
//! stroked) byte for byte, and the per-face JSON byte for byte apart from its run statistics.

mod support;

use sightline::camera::{Camera, NamedView};
use sightline::draw::DrawOptions;
use sightline::methods::{Engine, METHODS};
use sightline::output::json::write_json;
use sightline::output::svg::{SvgOptions, write_svg};
use sightline::pipeline::{Fill, prepare};
use sightline::project::CullMode;
use sightline::scene::Scene;
use sightline::scene::primitives::{interlocked_tori, interpenetrating_tori, random_triangle_soup};
use support::camera::{fit, named_view};
use support::fixtures::fixture_paths;
use support::strategy::{CoverageMap, Strategy, drawing_of};

/// (SVG of the picture, JSON of the per-face drawing without statistics) by `strategy`.
fn outputs(strategy: &dyn Strategy, scene: &Scene, camera: &Camera) -> (String, String) {
    let prepared = prepare(scene, camera, CullMode::Auto);
    let screen = &prepared.screen;
    let draw = |options| drawing_of(strategy, scene, screen, camera, Fill::Shade, options).drawing;
    let mut picture = draw(DrawOptions::picture());
    picture.background = Some([1.0; 3]);
    let svg = write_svg(&picture, &SvgOptions::default());
    let json = write_json(&draw(DrawOptions::per_face()), scene, &Default::default());
    (svg, json)
}

/// Asserts that every exact strategy writes the coverage map's SVG and JSON for `scene` seen by
/// `camera`; returns whether anything was drawn.
fn assert_same_bytes(name: &str, scene: &Scene, camera: &Camera) -> bool {
    let (svg_c, json_c) = outputs(&CoverageMap, scene, camera);
    let mut others = 0;
    for m in METHODS.iter().filter(|m| m.exact && m.name != "coverage") {
        let Engine::Object(strategy) = m.engine else {
            continue;
        };
        let (svg, json) = outputs(strategy, scene, camera);
        let other = m.name;
        assert!(
            svg_c == svg,
            "{name}: SVGs differ\ncoverage: {svg_c}\n{other}: {svg}"
        );
        assert!(
            json_c == json,
            "{name}: JSONs differ\ncoverage: {json_c}\n{other}: {json}"
        );
        others += 1;
    }
    assert!(
        others >= 3,
        "exact strategies besides the coverage map: {others}"
    );
    svg_c.contains("data-face")
}

#[test]
fn every_exact_strategy_writes_the_coverage_maps_bytes_on_every_fixture() {
    let mut drawn = 0;
    for path in fixture_paths() {
        let scene = sightline::load(&path, None).unwrap();
        for view in [NamedView::Front, NamedView::Iso] {
            let camera = named_view(&scene, view, (96, 72));
            let name = format!("{} {view:?}", path.display());
            drawn += assert_same_bytes(&name, &scene, &camera) as usize;
        }
    }
    assert!(drawn >= 20, "only {drawn} renders drew anything");
}

#[test]
fn every_exact_strategy_writes_the_coverage_maps_bytes_on_generated_scenes() {
    let scenes = [
        ("interlocked tori", interlocked_tori(16, 8)),
        ("interpenetrating tori", interpenetrating_tori(12, 6)),
    ];
    for (name, scene) in &scenes {
        for (view, ortho) in [(NamedView::Iso, false), (NamedView::Front, true)] {
            let camera = fit(scene, view, ortho, 120, 90);
            assert!(assert_same_bytes(name, scene, &camera), "{name}: empty");
        }
    }
    for seed in 1..=4 {
        let scene = random_triangle_soup(24, seed);
        let name = format!("triangle soup seed {seed}");
        for (view, ortho) in [(NamedView::Iso, false), (NamedView::Front, true)] {
            let camera = fit(&scene, view, ortho, 100, 80);
            assert!(assert_same_bytes(&name, &scene, &camera), "{name}: empty");
        }
    }
}

/// On these tori the BSP's pieces have a vertex an ulp from a corner of the visible set, on a
/// seam going up to the right, and cut it where the coverage map does not: the union of the
/// seam's parts must still reach the same end (it used to stop an ulp short under the BSP:
/// ends with the same x were ordered by increasing y whichever way the line went).
#[test]
fn seams_do_not_depend_on_a_cut_vertex_next_to_a_corner() {
    let scene = interpenetrating_tori(24, 10);
    let camera = fit(&scene, NamedView::Iso, false, 160, 120);
    assert!(assert_same_bytes(
        "interpenetrating tori 24x10",
        &scene,
        &camera
    ));
}
