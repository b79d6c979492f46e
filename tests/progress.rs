//! Progress reports of the exact visible set and of the painter order (issue 8, point 9): each
//! stage's reports are labelled, monotone, few, and end at their total; reporting changes no
//! result.

mod support;

use sightline::camera::{Camera, NamedView};
use sightline::pipeline::{Fill, prepare};
use sightline::progress::{Report, Ticker};
use sightline::project::{CullMode, ScreenScene};
use sightline::scene::Scene;
use sightline::scene::primitives::{random_triangle_soup, sphere_scene};
use sightline::visibility::coverage_map::visible_set_with_progress;
use std::sync::Mutex;
use support::camera::named_view;
use support::strategy::{Bsp, CoverageMap, coverage_map};

type Call = (&'static str, u64, u64);

fn iso(scene: &Scene) -> Camera {
    named_view(scene, NamedView::Iso, (256, 256))
}

fn screen_of(scene: &Scene) -> ScreenScene {
    prepare(scene, &iso(scene), CullMode::Auto).screen
}

/// Runs `run` with a progress report that records its calls; returns its result and the calls.
fn recorded<T>(run: impl FnOnce(Report) -> T) -> (T, Vec<Call>) {
    let calls = Mutex::new(Vec::new());
    let report = |s: &'static str, d: u64, t: u64| calls.lock().unwrap().push((s, d, t));
    let out = run(&report);
    (out, calls.into_inner().unwrap())
}

/// Checks one stage's calls and returns its final total. A stage whose total grows may report
/// about `Ticker::STEPS` more times per doubling.
fn check_stage(calls: &[Call], stage: &str) -> u64 {
    assert!(calls.len() >= 2, "{calls:?}");
    let (first, last) = (calls[0].2 as f64, calls[calls.len() - 1].2 as f64);
    let doublings = (last / first.max(1.0)).log2().ceil() as usize;
    let most = (Ticker::STEPS as usize + 2) * (1 + doublings);
    assert!(calls.len() <= most, "{} calls, at most {most}", calls.len());
    assert!(calls.iter().all(|c| c.0 == stage), "{calls:?}");
    assert!(calls.iter().all(|c| c.1 <= c.2), "done > total: {calls:?}");
    for w in calls.windows(2) {
        assert!(w[0].1 <= w[1].1 && w[0].2 <= w[1].2, "not monotone: {w:?}");
    }
    let last = calls.last().unwrap();
    assert_eq!(last.1, last.2, "the stage ends at its total");
    last.2
}

#[test]
fn the_visible_set_reports_pieces_inserted_up_to_the_total() {
    let scene = random_triangle_soup(400, 11);
    let screen = screen_of(&scene);
    let ((visible, stats), calls) =
        recorded(|report| visible_set_with_progress(&screen, Some(report)));
    let total = check_stage(&calls, "visible set");
    assert_eq!(total, stats.inserted as u64);
    assert!(total >= 400, "{total}");
    let (plain, plain_stats) = coverage_map(&screen);
    assert_eq!(plain_stats, stats);
    assert_eq!(plain.pieces.len(), visible.pieces.len());
}

#[test]
fn the_painter_order_reports_fragments_placed_as_the_bsp_grows() {
    let scene = random_triangle_soup(300, 5);
    let screen = screen_of(&scene);
    let (bsp, calls) = recorded(|report| Bsp::build_with_progress(&screen, Some(report)));
    let total = check_stage(&calls, "painter order");
    assert_eq!(total, bsp.stats.fragments as u64);
    // The soup's triangles split one another: the total grew from the pieces to the fragments.
    assert_eq!(calls[0], ("painter order", 0, bsp.stats.pieces as u64));
    assert!(bsp.stats.fragments > bsp.stats.pieces, "{:?}", bsp.stats);
    assert_eq!(Bsp::build(&screen).stats, bsp.stats);
}

#[test]
fn the_bsp_method_reports_the_stages_it_runs_and_draws_the_same() {
    let opaque = sphere_scene(500);
    let mut translucent = random_triangle_soup(100, 3);
    translucent.materials[0].transparency = 0.5;
    // Translucent scenes run the opaque faces' visible set (none here), then the painter order
    // of the translucent ones; the opaque pieces are then merged into regions.
    for (scene, stages) in [
        (opaque, &["visible set", "regions"][..]),
        (
            translucent,
            &["visible set", "painter order", "regions"][..],
        ),
    ] {
        let cam = iso(&scene);
        let screen = prepare(&scene, &cam, CullMode::Auto).screen;
        let run = |report: Option<sightline::progress::Report>| {
            sightline::draw::picture(
                &CoverageMap,
                &scene,
                &screen,
                &cam,
                Fill::Shade,
                sightline::draw::DrawOptions::picture(),
                report,
            )
        };
        let (with, calls) = recorded(|report| run(Some(report)));
        let mut seen: Vec<&str> = calls.iter().map(|c| c.0).collect();
        seen.dedup();
        assert_eq!(seen, stages, "each stage once, in order");
        for stage in stages {
            let of_stage: Vec<Call> = calls.iter().filter(|c| c.0 == *stage).copied().collect();
            check_stage(&of_stage, stage);
        }
        let without = run(None);
        assert_eq!(with.drawing, without.drawing);
    }
}
