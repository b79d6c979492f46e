//! The numerical stress suite (issue 11, `sightline::stress`): every family briefly with every
//! exact strategy, the check shown able to fail, shrinking, determinism, the command line; and
//! the measured cases against the world reference (ignored until the wide kernel).

mod support;

use sightline::methods::{Engine, METHODS};
use sightline::project::ScreenScene;
use sightline::stress::check::{Kind, check_visible};
use sightline::stress::rng::Rng;
use sightline::stress::world::{self, MeasuredCase};
use sightline::stress::{Case, Family, RunOptions, check_case, default_strategy, shrink};
use sightline::visibility::{CoverageMap, Strategy, VisibleSet};
use support::cli::{run_err, run_ok};

/// Cases per family and strategy in the normal run.
const CASES: u64 = 20;
/// Sample points per case.
const POINTS: usize = 256;

/// Every exact object-space strategy of the registry.
fn exact_strategies() -> Vec<(&'static str, &'static dyn Strategy)> {
    METHODS
        .iter()
        .filter(|m| m.exact)
        .filter_map(|m| match m.engine {
            Engine::Object(s) => Some((m.name, s)),
            Engine::Image(_) => None,
        })
        .collect()
}

/// `CASES` cases of `family` at scales drawn from its range, and two at the ends of the range,
/// each with every exact strategy: no failing point.
fn check_family(family: Family) {
    let strategies = exact_strategies();
    assert!(strategies.len() >= 2, "coverage and bsp at least");
    let (lo, hi, _) = family.range();
    let mut cases: Vec<Case> = (0..CASES).map(|k| family.case(1, k)).collect();
    cases.push(family.case_at(1, CASES, lo));
    cases.push(family.case_at(1, CASES + 1, hi));
    for (name, strategy) in strategies {
        for case in &cases {
            let out = check_case(case, strategy, POINTS);
            let t = out.checked.tally;
            assert_eq!(t.points, POINTS as u64);
            assert!(
                !out.failed(),
                "{name} on {} (scale {:e}): {t:?}, first failures {:?}",
                case.label,
                case.scale,
                out.checked.failures
            );
        }
    }
}

#[test]
fn grazing_faces_show_no_failure() {
    check_family(Family::Grazing);
}

#[test]
fn near_parallel_stacks_show_no_failure() {
    check_family(Family::Stacks);
}

#[test]
fn decals_in_deep_perspective_show_no_failure() {
    check_family(Family::Decals);
}

#[test]
fn far_offsets_show_no_failure() {
    check_family(Family::FarOffsets);
}

#[test]
fn tiny_scales_show_no_failure() {
    check_family(Family::Tiny);
}

#[test]
fn t_junctions_show_no_failure() {
    check_family(Family::TJunctions);
}

#[test]
fn needles_show_no_failure() {
    check_family(Family::Needles);
}

#[test]
fn fans_show_no_failure() {
    check_family(Family::Fans);
}

#[test]
fn edge_on_faces_show_no_failure() {
    check_family(Family::EdgeOn);
}

#[test]
fn touching_faces_show_no_failure() {
    check_family(Family::Touching);
}

#[test]
fn cyclic_rings_show_no_failure() {
    check_family(Family::Cyclic);
}

/// A grazing case, projected, with its exact visible set.
fn projected(index: u64) -> (Case, ScreenScene, VisibleSet) {
    let case = Family::Grazing.case(5, index);
    let scene = case.scene().unwrap();
    let screen = sightline::pipeline::prepare(&scene, &case.camera, Default::default()).screen;
    let visible = CoverageMap.visible_set(&screen, &|_| false, None);
    (case, screen, visible)
}

/// The largest pieces of two different polygons (by the f64 area of their vertices).
fn two_big_pieces(v: &VisibleSet) -> (usize, usize) {
    let area = |k: usize| {
        let p = v.pieces[k].vertices_f64();
        let n = p.len();
        (0..n)
            .map(|i| p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1])
            .sum::<f64>()
    };
    let mut order: Vec<usize> = (0..v.pieces.len()).collect();
    order.sort_by(|&a, &b| area(b).total_cmp(&area(a)));
    let a = order[0];
    let b = *order
        .iter()
        .find(|&&k| v.pieces[k].poly != v.pieces[a].poly)
        .expect("two faces visible");
    (a, b)
}

/// The check finds each kind of wrong visible set: two pieces' polygons swapped (wrong
/// polygon), a piece dropped (a polygon and no piece), a piece twice (overlap); the true set
/// passes at the same points.
#[test]
fn the_check_reports_wrong_visible_sets() {
    let (case, screen, visible) = projected(0);
    let points = 400;
    let run = |v: &VisibleSet| check_visible(&screen, v, points, &mut Rng(case.stream)).tally;
    assert_eq!(run(&visible).failures(), 0);
    let (a, b) = two_big_pieces(&visible);

    let mut swapped = visible.clone();
    let (pa, pb) = (swapped.pieces[a].poly, swapped.pieces[b].poly);
    swapped.pieces[a].poly = pb;
    swapped.pieces[b].poly = pa;
    let t = run(&swapped);
    assert!(t.wrong > 0, "swapped polygons not seen: {t:?}");

    let mut dropped = visible.clone();
    dropped.pieces.remove(a);
    let t = run(&dropped);
    assert!(t.coverage > 0, "a dropped piece not seen: {t:?}");

    let mut doubled = visible.clone();
    doubled.pieces.push(visible.pieces[a].clone());
    let t = run(&doubled);
    assert!(t.overlaps > 0, "overlapping pieces not seen: {t:?}");
}

/// A failure names the point and both answers, with its kind.
#[test]
fn a_failure_names_its_kind_and_both_answers() {
    let (case, screen, visible) = projected(1);
    let (a, _) = two_big_pieces(&visible);
    let mut dropped = visible.clone();
    dropped.pieces.remove(a);
    let out = check_visible(&screen, &dropped, 400, &mut Rng(case.stream));
    let f = out.failures.first().expect("failures kept");
    assert_eq!(f.kind, Kind::Coverage);
    assert_eq!(f.engine, None);
    assert!(f.reference.is_some());
    assert!(f.ndc[0].abs() <= 2.0 && f.ndc[1].abs() <= 2.0);
}

/// A strategy that loses the largest piece of the coverage map's set: wrong on purpose.
struct DropsAPiece;

impl Strategy for DropsAPiece {
    fn visible_set(
        &self,
        screen: &ScreenScene,
        translucent: &dyn Fn(u32) -> bool,
        report: Option<sightline::progress::Report>,
    ) -> VisibleSet {
        let mut v = CoverageMap.visible_set(screen, translucent, report);
        if !v.pieces.is_empty() {
            let (a, _) = two_big_pieces_or_first(&v);
            v.pieces.remove(a);
        }
        v
    }
}

fn two_big_pieces_or_first(v: &VisibleSet) -> (usize, usize) {
    if v.pieces.iter().any(|p| p.poly != v.pieces[0].poly) {
        two_big_pieces(v)
    } else {
        (0, 0)
    }
}

/// Shrinking keeps a failing case failing with fewer faces; the fixture it writes loads back
/// (`scene::load`, the `.cam` reader) as the same faces and camera, and still fails.
#[test]
fn shrinking_gives_a_smaller_failing_fixture_that_loads_back() {
    let case = Family::Stacks.case(3, 2);
    assert!(case.faces.len() >= 3, "{} faces", case.faces.len());
    let fails = |c: &Case| check_case(c, &DropsAPiece, POINTS).failed();
    assert!(fails(&case));
    let small = shrink::shrink(&case, &fails);
    assert!(small.faces.len() < case.faces.len());
    assert!(fails(&small));

    let dir = tempfile::tempdir().unwrap();
    let obj = shrink::write_fixture(&small, dir.path(), "a test").unwrap();
    assert!(obj.starts_with(dir.path()));
    let scene = sightline::load(&obj, None).unwrap();
    let cam = sightline::camera::CamFile::read(&obj.with_extension("cam")).unwrap();
    assert_eq!(cam.camera(), small.camera);
    let back = Case::of_scene("loaded", &scene, cam.camera(), small.stream);
    assert_eq!(back.faces, small.faces);
    assert!(fails(&back));
}

/// A run whose strategy is wrong reports each failing case, shrinks it and writes its fixture
/// where asked, with how to see it and how to run the whole case again.
#[test]
fn a_failing_run_writes_its_shrunk_cases_and_reports_them() {
    let dir = tempfile::tempdir().unwrap();
    let options = RunOptions {
        cases: 2,
        seed: 4,
        points: POINTS,
        failures: dir.path().join("failures"),
        jobs: 2,
    };
    let r = sightline::stress::run_family(Family::Touching, &options, &DropsAPiece, &mut || {});
    assert_eq!(r.failed.len(), 2, "{r:?}");
    let report = sightline::stress::format_report(std::slice::from_ref(&r));
    for f in &r.failed {
        let obj = f.fixture.as_ref().unwrap();
        assert!(obj.starts_with(&options.failures) && obj.with_extension("cam").exists());
        assert!(f.faces.1 <= f.faces.0);
        assert!(report.contains(&format!("FAILED {}", f.label)), "{report}");
        assert!(report.contains(&obj.display().to_string()), "{report}");
        let text = std::fs::read_to_string(obj).unwrap();
        assert!(text.contains("sightline render"), "{text}");
        assert!(
            text.contains("sightline stress --family touching --seed 4"),
            "{text}"
        );
    }
}

/// The same options give the same report, times aside, whatever the number of jobs.
#[test]
fn a_run_is_deterministic_with_any_number_of_jobs() {
    let run = |jobs: usize| {
        let options = RunOptions {
            cases: 5,
            seed: 9,
            points: 64,
            failures: std::env::temp_dir().join("sightline-stress-unused"),
            jobs,
        };
        let mut ticks = 0;
        let r =
            sightline::stress::run_family(Family::Fans, &options, default_strategy(), &mut || {
                ticks += 1
            });
        assert_eq!(ticks, 5, "one tick per case with {jobs} jobs");
        r
    };
    let (a, b, c) = (run(1), run(1), run(3));
    for other in [&b, &c] {
        assert_eq!(a.cases, other.cases);
        assert_eq!(a.tally, other.tally);
        assert_eq!(a.fallbacks, other.fallbacks);
        assert_eq!(a.strategy_fallbacks, other.strategy_fallbacks);
        assert_eq!(a.max_fallbacks, other.max_fallbacks);
    }
    assert!(a.fallbacks > 0, "fans reach the exact fallbacks: {a:?}");
    assert_eq!(a.failed.len(), 0);
}

#[test]
fn the_command_reports_every_family_it_runs() {
    let out = run_ok(&[
        "stress", "--family", "touching", "--cases", "2", "--points", "32",
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("family"), "{text}");
    let line = text
        .lines()
        .find(|l| l.starts_with("touching"))
        .expect(&text);
    let cols: Vec<&str> = line.split_whitespace().collect();
    assert_eq!(
        &cols[1..4],
        ["2", "0", "64"],
        "cases, failed, points: {line}"
    );
    let (code, err) = run_err(&["stress", "--family", "nope"]);
    assert_eq!(code, Some(2));
    assert!(err.contains("grazing") && err.contains("measured"), "{err}");
}

// ------------------------------------------------------------------------------------------------
// The measured cases, against the world reference
// ------------------------------------------------------------------------------------------------

/// Samples per measured case (random pixel centres); the plates take every pixel, as they
/// cover a few hundred.
const MEASURED_POINTS: usize = 20_000;

/// Asserts that no sample outside the band differs from the world reference.
///
/// The band (`stress::world::Band`), in NDC, with `rho_xy`, `rho_z` the largest difference over
/// the case's vertices between the f64 NDC the kernel starts from and the exact rational NDC,
/// plus 2^-53: a sample is left out when it lies within `2e-9 + √2·rho_xy` of a reference edge,
/// or when another face G containing it lies behind the nearest face N by at most
/// `2·rho_z + rho_xy·(|∇z_N|₁ + |∇z_G|₁) + 2e-9·|∇z_N - ∇z_G|`, which near their meeting line is
/// a distance `2e-9 + (2·rho_z + rho_xy·(|∇z_N|₁ + |∇z_G|₁)) / |∇z_N - ∇z_G|`: the projection's
/// own rounding divided by the angle between the surfaces (their NDC depth gradients).
fn assert_measured(case: MeasuredCase, points: usize) {
    let m = world::measure(&case, default_strategy(), points, 1);
    eprintln!(
        "{}: {} of {} samples wrong ({:.4} %), {} in the band",
        m.name,
        m.wrong,
        m.samples,
        100.0 * m.wrong_fraction(),
        m.in_band
    );
    assert_eq!(
        m.wrong,
        0,
        "{}: {:.4} % of the samples show the wrong face (band {:?}, grid rounding {:?})",
        m.name,
        100.0 * m.wrong_fraction(),
        m.band,
        m.grid_rounding
    );
}

#[test]
fn triangles_crossing_at_a_microradian_match_the_world_reference() {
    assert_measured(world::crossing(1e-6), MEASURED_POINTS);
}

#[test]
fn triangles_crossing_at_a_nanoradian_match_the_world_reference() {
    assert_measured(world::crossing(1e-9), MEASURED_POINTS);
}

#[test]
fn forty_stacked_quads_match_the_world_reference() {
    assert_measured(world::stack(), MEASURED_POINTS);
}

#[test]
fn a_plate_a_tenth_of_a_millimetre_above_the_floor_matches_the_world_reference() {
    assert_measured(world::plate(1e-4), usize::MAX);
}

#[test]
fn a_plate_ten_micrometres_above_the_floor_matches_the_world_reference() {
    assert_measured(world::plate(1e-5), usize::MAX);
}

#[test]
fn a_plate_a_micrometre_above_the_floor_matches_the_world_reference() {
    assert_measured(world::plate(1e-6), usize::MAX);
}

#[test]
fn six_sheets_seen_at_45_degrees_match_the_world_reference() {
    assert_measured(world::sheets(), MEASURED_POINTS);
}

/// The world reference agrees with the engine where depth is not in question: two triangles
/// crossing at a wide angle (0.3 rad) show no wrong sample even on a coarse grid, so a wrong
/// sample in the measured cases is the depth the grid lost, not the reference.
#[test]
fn the_world_reference_agrees_where_the_grid_loses_nothing_that_matters() {
    let m = world::measure(&world::crossing(0.3), default_strategy(), 4000, 2);
    assert_eq!(m.wrong, 0, "{m:?}");
    assert!(m.in_band < m.samples / 100, "{m:?}");
}
