//! Large scenes are solved strip by strip on all cores (issue 13, point 3): every output is the
//! same, byte for byte, whatever the number of threads (counters included), and the drawings
//! are the ones of the scene solved whole (the strip cuts leave no trace: no extra vertex, no
//! line). Strips are forced onto small scenes here (`with_strip_size`), so that the check is
//! cheap and every exact strategy goes through many cuts.

mod support;

use sightline::camera::{Camera, NamedView};
use sightline::draw::DrawOptions;
use sightline::lines::{LineOptions, line_drawing};
use sightline::methods::{Engine, METHODS};
use sightline::output::json::write_json;
use sightline::output::line_svg::{LineSvgOptions, write_line_svg};
use sightline::output::svg::{SvgOptions, write_svg};
use sightline::pipeline::{Fill, prepare};
use sightline::project::CullMode;
use sightline::scene::Scene;
use sightline::scene::primitives::{
    exported_sphere_scene, interpenetrating_tori, random_triangle_soup,
};
use sightline::visibility::strips::with_strip_size;
use support::camera::fit;
use support::strategy::{Strategy, drawing_of};

/// Everything a strategy's run writes: the picture's SVG, the per-face JSON with the run's
/// counters, and the counters alone.
#[derive(Debug, PartialEq)]
struct Outputs {
    svg: String,
    json: String,
    stats: serde_json::Map<String, serde_json::Value>,
}

fn outputs(strategy: &dyn Strategy, scene: &Scene, camera: &Camera) -> Outputs {
    let prepared = prepare(scene, camera, CullMode::Auto);
    let draw = |options| {
        drawing_of(
            strategy,
            scene,
            &prepared.screen,
            camera,
            Fill::Shade,
            options,
        )
    };
    let picture = draw(DrawOptions::picture());
    let per_face = draw(DrawOptions::per_face());
    Outputs {
        svg: write_svg(&picture.drawing, &SvgOptions::default()),
        json: write_json(&per_face.drawing, scene, &per_face.stats),
        stats: per_face.stats,
    }
}

/// Runs `run` on a pool of `threads` threads, with strips of `strip_size` pieces.
fn on_threads<T: Send>(threads: usize, strip_size: usize, run: impl FnOnce() -> T + Send) -> T {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    // The strip size is a setting of the thread that calls the strategy: the pool's.
    pool.install(|| with_strip_size(strip_size, run))
}

fn scenes() -> Vec<(&'static str, Scene, Camera)> {
    let with_camera = |name, scene: Scene| {
        let camera = fit(&scene, NamedView::Iso, false, 160, 120);
        (name, scene, camera)
    };
    vec![
        with_camera("interpenetrating tori", interpenetrating_tori(16, 8)),
        with_camera("soup of 60", random_triangle_soup(60, 7)),
        // Open poles, wound inwards: the occlusion cells drop its far half.
        with_camera("exported sphere", exported_sphere_scene(800)),
    ]
}

#[test]
fn every_exact_strategy_writes_the_same_bytes_on_1_2_and_7_threads_and_as_if_solved_whole() {
    let coverage = METHODS.iter().find(|m| m.name == "coverage").unwrap();
    let Engine::Object(coverage) = coverage.engine else {
        panic!("the coverage map is an object-space strategy");
    };
    // The per-face regions; only the counters tell runs apart.
    let regions = |json: &str| {
        let mut v: serde_json::Value = serde_json::from_str(json).unwrap();
        v.as_object_mut().unwrap().remove("stats");
        v
    };
    for (name, scene, camera) in scenes() {
        // The reference: the scene solved whole by the coverage map, which every exact strategy
        // draws byte for byte (tests/strategies_agree.rs).
        let whole = on_threads(1, usize::MAX, || outputs(coverage, &scene, &camera));
        assert_eq!(whole.stats["strips"], 1, "{name}");
        for m in METHODS.iter().filter(|m| m.exact) {
            let Engine::Object(strategy) = m.engine else {
                continue;
            };
            let striped: Vec<Outputs> = [1, 2, 7]
                .into_iter()
                .map(|t| on_threads(t, 16, || outputs(strategy, &scene, &camera)))
                .collect();
            let method = m.name;
            // Newell's list and Warnock's areas are solved whole (see `WarnockExact`).
            let chosen = striped[0].stats.get("chosen").and_then(|c| c.as_str());
            if method != "newell" && method != "warnock-exact" && chosen != Some("warnock-exact") {
                let strips = striped[0].stats.get("strips").and_then(|s| s.as_u64());
                assert!(
                    strips.is_some_and(|s| s >= 3),
                    "{name}, {method}: {strips:?} strips"
                );
            }
            for (t, s) in [2, 7].iter().zip(&striped[1..]) {
                assert!(
                    *s == striped[0],
                    "{name}, {method}: {t} threads differ from one\n{:?}\n{:?}",
                    s.stats,
                    striped[0].stats
                );
            }
            assert!(
                striped[0].svg == whole.svg,
                "{name}, {method}: the strips' SVG is not the whole scene's"
            );
            assert_eq!(
                regions(&striped[0].json),
                regions(&whole.json),
                "{name}, {method}"
            );
        }
    }
}

#[test]
fn hidden_line_drawings_show_no_strip_cut_and_do_not_depend_on_the_threads() {
    for (name, scene, camera) in scenes() {
        let options = LineOptions::default();
        let svg = |threads, size| {
            on_threads(threads, size, || {
                let lines = line_drawing(&scene, &camera, &options, None).unwrap();
                write_line_svg(&lines.drawing, &LineSvgOptions::default())
            })
        };
        let whole = svg(1, usize::MAX);
        for threads in [1, 2, 7] {
            assert!(
                svg(threads, 16) == whole,
                "{name}: the lines on {threads} threads with strips differ from the whole scene's"
            );
        }
    }
}
