//! A guard against slowing down that timing noise cannot fool: the work every exact object-space
//! strategy does on a few reference scenes, counted (pieces, splits, clips, overlap tests, exact
//! fallbacks, ...: every integer counter of its `--stats`), is held to the counts recorded in
//! `tests/golden/work_counts.json`. A counter that grows past its record fails the test, naming
//! the strategy, scene, counter, record and count; counters that say how much work was saved
//! (`SAVINGS`) fail when they shrink instead. The counts are deterministic (one thread, exact
//! arithmetic), so any change is a change of the code.
//!
//! After a change that moves counts on purpose (fewer, or more for a reason the commit gives),
//! rewrite the record: `SIGHTLINE_BLESS=1 cargo test --release --test work_counts`.

use serde_json::{Map, Value};
use sightline::camera::{Camera, NamedView};
use sightline::methods::{Engine, METHODS};
use sightline::pipeline::prepare;
use sightline::project::CullMode;
use sightline::scene::Scene;
use sightline::scene::primitives::{
    exported_sphere_scene, holed_sphere_scene, interpenetrating_tori, random_triangle_soup,
    sphere_scene,
};

const RECORD: &str = "tests/golden/work_counts.json";

/// Counters of work saved or of the scene: larger is better, or neither.
const SAVINGS: &[&str] = &[
    "occluded",
    "covered",
    "clear",
    "pieces_placed_whole",
    "meshes_placed_whole",
    "meshes_apart",
];

/// Counters that describe the scene, not the work: not guarded.
const SCENE: &[&str] = &["polygons", "meshes_on_screen"];

/// The reference scenes, each with its camera (256 x 256).
fn scenes() -> Vec<(&'static str, Scene, Camera)> {
    let fit = |s: &Scene, view| Camera::fit(view, s.bounds().unwrap(), false, 40.0, 256, 256);
    let mut out = Vec::new();
    let sphere = sphere_scene(4_000);
    out.push(("sphere_4000", fit(&sphere, NamedView::Iso), sphere));
    let open = holed_sphere_scene(48, 24);
    out.push(("open_sphere", fit(&open, NamedView::Iso), open));
    let inside_out = exported_sphere_scene(2_000);
    out.push((
        "inside_out_sphere",
        fit(&inside_out, NamedView::Iso),
        inside_out,
    ));
    let tori = interpenetrating_tori(32, 12);
    out.push(("interpenetrating_tori", fit(&tori, NamedView::Iso), tori));
    let soup = random_triangle_soup(60, 7);
    out.push(("soup_60", fit(&soup, NamedView::Front), soup));
    let bars = sightline::load(std::path::Path::new("fixtures/cyclic_bars.obj"), None).unwrap();
    out.push(("cyclic_bars", fit(&bars, NamedView::Front), bars));
    out.into_iter().map(|(n, c, s)| (n, s, c)).collect()
}

/// Every guarded counter of every exact object-space strategy on every reference scene:
/// {scene: {strategy: {counter: n}}}.
fn counts() -> Map<String, Value> {
    let mut all = Map::new();
    for (name, scene, camera) in scenes() {
        let screen = prepare(&scene, &camera, CullMode::Auto).screen;
        let mut per_scene = Map::new();
        for m in METHODS.iter().filter(|m| m.exact) {
            let Engine::Object(strategy) = m.engine else {
                continue;
            };
            let set = strategy.visible_set(&screen, &|_| false, None);
            let guarded: Map<String, Value> = set
                .stats
                .iter()
                .filter(|(k, v)| v.is_u64() && !SCENE.contains(&k.as_str()))
                .map(|(k, v)| (k.clone(), v.clone()))
                .collect();
            assert!(!guarded.is_empty(), "{} on {name}: no counters", m.name);
            per_scene.insert(m.name.to_string(), Value::Object(guarded));
        }
        all.insert(name.to_string(), Value::Object(per_scene));
    }
    all
}

/// (worse, better): the counters of `now` that moved the wrong way from `record` (or are not
/// in it), and those that moved the right way, each as "strategy on scene: counter was -> now".
fn judge(now: &Map<String, Value>, record: &Map<String, Value>) -> (Vec<String>, Vec<String>) {
    let mut worse = Vec::new();
    let mut better = Vec::new();
    for (scene, strategies) in now {
        for (strategy, counters) in strategies.as_object().unwrap() {
            let was = record
                .get(scene)
                .and_then(|s| s.get(strategy))
                .and_then(Value::as_object);
            for (counter, n) in counters.as_object().unwrap() {
                let n = n.as_u64().unwrap();
                let what = format!("{strategy} on {scene}: {counter}");
                let Some(r) = was.and_then(|w| w.get(counter)).and_then(Value::as_u64) else {
                    worse.push(format!("{what} = {n}, not in the record"));
                    continue;
                };
                let saving = SAVINGS.contains(&counter.as_str());
                if (n > r && !saving) || (n < r && saving) {
                    worse.push(format!("{what} {r} -> {n}"));
                } else if n != r {
                    better.push(format!("{what} {r} -> {n}"));
                }
            }
        }
    }
    (worse, better)
}

fn record() -> Map<String, Value> {
    serde_json::from_str(
        &std::fs::read_to_string(RECORD).unwrap_or_else(|e| panic!("{RECORD}: {e}")),
    )
    .unwrap_or_else(|e| panic!("{RECORD}: {e}"))
}

#[test]
fn work_counts_do_not_grow_past_their_record() {
    let now = counts();
    if std::env::var_os("SIGHTLINE_BLESS").is_some() {
        let text = serde_json::to_string_pretty(&Value::Object(now)).unwrap() + "\n";
        std::fs::write(RECORD, text).unwrap();
        return;
    }
    let (worse, better) = judge(&now, &record());
    if !better.is_empty() {
        eprintln!(
            "work counts improved on their record (lower it with SIGHTLINE_BLESS=1 cargo test \
             --release --test work_counts): {better:#?}"
        );
    }
    assert!(
        worse.is_empty(),
        "work counts worse than {RECORD}: {worse:#?}\nif this is meant, say why in the commit and \
         run SIGHTLINE_BLESS=1 cargo test --release --test work_counts"
    );
}

/// The judge catches a count above its record, a saving below its record and a counter missing
/// from the record, and lets an unchanged record pass.
#[test]
fn the_judge_catches_growth_lost_savings_and_unrecorded_counters() {
    let now = record();
    assert_eq!(judge(&now, &now), (vec![], vec![]));
    let mut lowered = now.clone();
    let tests = &mut lowered["sphere_4000"]["coverage"]["overlap_tests"];
    *tests = (tests.as_u64().expect("recorded") - 1).into();
    let (worse, better) = judge(&now, &lowered);
    assert_eq!(worse.len(), 1, "{worse:?}");
    assert!(worse[0].contains("coverage on sphere_4000: overlap_tests"));
    assert!(better.is_empty());
    // More occlusion is better, less is worse.
    let mut raised = now.clone();
    let occluded = &mut raised["open_sphere"]["coverage"]["occluded"];
    *occluded = (occluded.as_u64().expect("recorded") + 1).into();
    assert_eq!(judge(&now, &raised).0.len(), 1);
    assert_eq!(judge(&raised, &now).1.len(), 1);
    let mut missing = now.clone();
    missing["soup_60"]["auto"]
        .as_object_mut()
        .unwrap()
        .remove("exact_fallbacks");
    assert_eq!(judge(&now, &missing).0.len(), 1);
}
