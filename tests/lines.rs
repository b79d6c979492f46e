//! Hidden-line drawings: worked cases (a cube's nine visible and three hidden lines, the closed
//! intersection loops of two crossing tori), the exact visibility of every drawn segment checked
//! against a brute-force point query over all faces, strategies that agree, strokes that cover
//! the segments with the fewest paths, and every fixture drawn.

mod support;

use glam::{DMat4, DVec3};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive};
use proptest::prelude::*;
use sightline::camera::{Camera, NamedView};
use sightline::exact::Samples;
use sightline::exact::predicates::Line;
use sightline::lines::along::At;
use sightline::lines::tracks::{SeenRule, Segment};
use sightline::lines::{
    ExactLines, LineKind, LineOptions, Lines, Visibility, exact_lines, lines_of,
};
use sightline::pipeline::{Prepared, prepare};
use sightline::project::ScreenScene;
use sightline::scene::{Scene, SceneBuilder, primitives};
use sightline::visibility::{CoverageMap, Strategy};
use std::collections::HashMap;
use support::camera::{fit, random_cameras, spec_camera};
use support::scenes::random_triangles;
use support::strategy::exact_strategies;

fn exact(scene: &Scene, camera: &Camera, options: &LineOptions) -> (Prepared, ExactLines) {
    let prepared = prepare(scene, camera, options.cull);
    let visible = CoverageMap.visible_set(&prepared.screen, &|_| false, None);
    let (lines, _) = exact_lines(scene, camera, &prepared, &visible.pieces, options);
    (prepared, lines)
}

fn drawing_with(strategy: &dyn Strategy, scene: &Scene, camera: &Camera) -> Lines {
    let options = LineOptions::default();
    let prepared = prepare(scene, camera, options.cull);
    let visible = strategy.visible_set(&prepared.screen, &|_| false, None);
    lines_of(scene, camera, &prepared, &visible.pieces, &options)
}

fn count(lines: &ExactLines, visibility: Visibility, kind: LineKind) -> usize {
    lines
        .segments
        .iter()
        .filter(|s| s.label.visibility == visibility && s.label.kind == kind)
        .count()
}

#[test]
fn a_cube_in_an_iso_view_shows_nine_lines_and_hides_three() {
    let scene = sightline::load("fixtures/cube.obj".as_ref(), None).unwrap();
    let camera = fit(&scene, NamedView::Iso, false, 400, 300);
    let (_, lines) = exact(&scene, &camera, &LineOptions::default());
    // The outline (six silhouette edges) and the three edges where the seen faces meet.
    assert_eq!(count(&lines, Visibility::Visible, LineKind::Silhouette), 6);
    assert_eq!(count(&lines, Visibility::Visible, LineKind::Crease), 3);
    // The three edges of the far corner.
    assert_eq!(count(&lines, Visibility::Hidden, LineKind::Crease), 3);
    assert_eq!(lines.segments.len(), 12);
    // Drawn: the outline as one closed stroke, the visible Y as two, the hidden Y as two.
    let drawing = drawing_with(&CoverageMap, &scene, &camera).drawing;
    assert_eq!(drawing.strokes.len(), 5);
    let outline: Vec<_> = drawing
        .strokes
        .iter()
        .filter(|s| s.kind == LineKind::Silhouette)
        .collect();
    assert_eq!(outline.len(), 1);
    assert!(outline[0].closed && outline[0].points.len() == 6);
}

#[test]
fn a_cube_face_on_draws_its_outline_once_and_no_hidden_line_over_it() {
    // Front orthographic view: the back face's edges project exactly onto the front face's
    // and the side faces are edge-on. A visible line hides the hidden one behind it.
    let scene = sightline::load("fixtures/cube.obj".as_ref(), None).unwrap();
    let camera = fit(&scene, NamedView::Front, true, 300, 300);
    let drawing = drawing_with(&CoverageMap, &scene, &camera).drawing;
    assert_eq!(drawing.strokes.len(), 1, "{:?}", drawing.strokes);
    let s = &drawing.strokes[0];
    assert_eq!(s.visibility, Visibility::Visible);
    assert!(s.closed && s.points.len() == 4);
}

/// Two tori whose tubes cross each other.
fn crossing_tori() -> Scene {
    let mut b = SceneBuilder::new("tori");
    let m = b.default_material();
    b.begin_mesh("a");
    primitives::torus(&mut b, &DMat4::IDENTITY, 1.0, 0.3, 40, 14, m);
    b.begin_mesh("b");
    let turn = DMat4::from_translation(DVec3::new(0.5, 0.2, 0.0)) * primitives::quarter_turn_x();
    primitives::torus(&mut b, &turn, 1.0, 0.3, 40, 14, m);
    b.finish().unwrap()
}

/// Vertex degrees and connected components of a set of segments (by output points).
fn degrees_and_components(segments: &[&Segment]) -> (Vec<usize>, usize) {
    let mut ids: HashMap<[u64; 2], usize> = HashMap::new();
    let mut edges = Vec::new();
    for s in segments {
        let [a, b] = s.ends.map(|p| {
            let n = ids.len();
            *ids.entry(p.map(f64::to_bits)).or_insert(n)
        });
        edges.push((a, b));
    }
    let mut degree = vec![0; ids.len()];
    let mut parent: Vec<usize> = (0..ids.len()).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            i = p[i];
        }
        i
    }
    for &(a, b) in &edges {
        degree[a] += 1;
        degree[b] += 1;
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        parent[ra] = rb;
    }
    let roots = (0..ids.len())
        .filter(|&i| find(&mut parent, i) == i)
        .count();
    (degree, roots)
}

#[test]
fn two_crossing_tori_meet_in_closed_loops() {
    let scene = crossing_tori();
    for (view, ortho) in [
        (NamedView::Iso, false),
        (NamedView::Front, false),
        (NamedView::Top, false),
        // Faces of the first torus seen exactly edge-on: meetings along their screen lines.
        (NamedView::Front, true),
    ] {
        let camera = fit(&scene, view, ortho, 500, 400);
        let (_, lines) = exact(&scene, &camera, &LineOptions::default());
        // Where the faces meet, visible or not: closed curves, every point with an even number
        // of neighbours (four where the orthographic view lays the back half of a symmetric
        // loop exactly on its front half).
        let samples = Samples::new(500, 400);
        let meeting: Vec<Segment> = lines
            .tracks
            .iter()
            .enumerate()
            .filter(|(_, t)| t.kind == LineKind::Intersection)
            .flat_map(|(i, t)| {
                t.extent.iter().map(move |(a, b)| Segment {
                    label: sightline::lines::tracks::Label {
                        visibility: Visibility::Visible,
                        kind: LineKind::Intersection,
                        qi: 0,
                    },
                    track: i as u32,
                    at: [a.clone(), b.clone()],
                    ends: [t.carrier.pixel(a, &samples), t.carrier.pixel(b, &samples)],
                })
            })
            .collect();
        assert!(!meeting.is_empty());
        let (degree, loops) = degrees_and_components(&meeting.iter().collect::<Vec<_>>());
        assert!(
            degree.iter().all(|&d| d % 2 == 0),
            "{view:?} ortho {ortho}: open ends {:?}",
            degree.iter().filter(|&&d| d % 2 == 1).count()
        );
        // Drawn, a visible line hides the hidden one it lies on: no hidden piece of a meeting
        // has the ends of a visible one.
        let ends = |s: &Segment, v: Visibility| {
            (s.label.kind == LineKind::Intersection && s.label.visibility == v).then(|| {
                let mut e = s.ends.map(|p| p.map(f64::to_bits));
                e.sort();
                e
            })
        };
        let visible: Vec<_> = lines
            .segments
            .iter()
            .filter_map(|s| ends(s, Visibility::Visible))
            .collect();
        assert!(
            lines
                .segments
                .iter()
                .filter_map(|s| ends(s, Visibility::Hidden))
                .all(|e| !visible.contains(&e)),
            "{view:?} ortho {ortho}: a hidden meeting drawn on a visible one"
        );
        // The tube of each torus passes through the other's once on each side of its hole.
        assert_eq!(loops, 2, "{view:?}");
    }
}

/// An exact integer of a kernel integer (any width).
fn big(v: impl std::fmt::Display) -> BigInt {
    v.to_string().parse().unwrap()
}

fn rat(v: impl Into<BigInt>) -> BigRational {
    BigRational::from_integer(v.into())
}

/// The exact screen point `at` on the line `carrier`.
fn point(carrier: &Line, at: &At) -> [BigRational; 2] {
    match at {
        At::Grid([x, y]) => [rat(*x), rat(*y)],
        At::Cross(m) => {
            let [a0, b0, d0] = carrier.exact().map(big);
            let [a1, b1, d1] = m.exact().map(big);
            let den = &a0 * &b1 - &a1 * &b0;
            [
                BigRational::new(&b0 * &d1 - &b1 * &d0, den.clone()),
                BigRational::new(&a1 * &d0 - &a0 * &d1, den),
            ]
        }
    }
}

/// The depth of `plane` at screen point `p`.
fn depth(plane: &sightline::exact::Plane, p: &[BigRational; 2]) -> BigRational {
    let n = rat(plane.a) * &p[0] + rat(plane.b) * &p[1] + rat(big(plane.d));
    -n / rat(plane.c)
}

/// How many faces of `screen` other than `own` cover point `p` strictly inside and strictly in
/// front of depth `z`: the brute-force quantitative invisibility of a line point. A face is the
/// union of its screen polygons (`project` splits a face whose snapped corners are not coplanar
/// into triangles): `p` is strictly inside it when it lies in one of them, on no side that is
/// part of the face's outline (a diagonal between two of them is inside the face).
fn faces_in_front(screen: &ScreenScene, own: &[u32], p: &[BigRational; 2], z: &BigRational) -> u32 {
    use sightline::project::Side;
    let mut depth_of_face: HashMap<u32, Option<BigRational>> = HashMap::new();
    // A filter only: polygons whose grid box is clearly away from p cannot hold it (p in f64
    // is within a few units of the exact point, grid coordinates being below 2^53).
    let near = [&p[0], &p[1]].map(|v| v.to_f64().expect("finite"));
    for poly in &screen.polys {
        if own.contains(&poly.face) {
            continue;
        }
        let c = screen.corners(poly);
        let away = |k: usize, get: fn(&sightline::exact::GridPoint) -> i64| {
            let lo = c.iter().map(get).min().unwrap() as f64 - 16.0;
            let hi = c.iter().map(get).max().unwrap() as f64 + 16.0;
            near[k] < lo || near[k] > hi
        };
        if away(0, |g| g.x) || away(1, |g| g.y) {
            continue;
        }
        let k = c.len();
        let side = |i: usize| {
            let (a, b) = (&c[i], &c[(i + 1) % k]);
            let v = rat(b.x - a.x) * (&p[1] - rat(a.y)) - rat(b.y - a.y) * (&p[0] - rat(a.x));
            if v.is_positive() {
                1
            } else if v.is_negative() {
                -1
            } else {
                0
            }
        };
        let signs: Vec<i32> = (0..k).map(side).collect();
        let closed = signs.iter().all(|&s| s >= 0) || signs.iter().all(|&s| s <= 0);
        if !closed {
            continue;
        }
        let sides = screen.sides(poly);
        let on_outline = (0..k).any(|i| signs[i] == 0 && sides[i] != Side::Diagonal);
        let entry = depth_of_face
            .entry(poly.face)
            .or_insert(Some(depth(&screen.plane(poly), p)));
        if on_outline {
            *entry = None;
        }
    }
    depth_of_face
        .values()
        .filter(|d| d.as_ref().is_some_and(|d| d < z))
        .count() as u32
}

/// Every drawn segment's visibility is the brute-force answer at exact interior points of it
/// (its midpoint and the points a third of the way from each end), and so is its quantitative
/// invisibility (the lines counted with `--qi-max`).
fn check_visibility(scene: &Scene, camera: &Camera) -> usize {
    let options = LineOptions {
        qi_max: Some(u32::MAX),
        ..LineOptions::default()
    };
    let (prepared, lines) = exact(scene, camera, &options);
    let mut checked = 0;
    for s in &lines.segments {
        let track = &lines.tracks[s.track as usize];
        let line = &track.carrier.line;
        let [a, b] = [0, 1].map(|k| point(line, &s.at[k]));
        for (wa, wb) in [(1, 1), (2, 1), (1, 2)] {
            let t = |u: &BigRational, v: &BigRational| (u * rat(wa) + v * rat(wb)) / rat(wa + wb);
            let p = [t(&a[0], &b[0]), t(&a[1], &b[1])];
            let z = depth(&track.depth, &p);
            let qi = faces_in_front(&prepared.screen, &track.faces, &p, &z);
            let want = if qi == 0 {
                Visibility::Visible
            } else {
                Visibility::Hidden
            };
            assert_eq!(
                s.label.visibility, want,
                "segment {s:?} of {:?} {:?}: {qi} faces in front",
                track.kind, track.faces
            );
            assert_eq!(s.label.qi, qi, "segment {s:?}: quantitative invisibility");
            checked += 1;
        }
    }
    checked
}

#[test]
fn every_segment_of_the_fixtures_and_the_tori_is_seen_exactly_where_nothing_is_in_front() {
    let mut checked = 0;
    for name in [
        "cube.obj",
        "interpenetrating.obj",
        "two_objects.obj",
        "cyclic_bars.obj",
    ] {
        let scene = sightline::load(format!("fixtures/{name}").as_ref(), None).unwrap();
        for (view, ortho) in [
            (NamedView::Iso, false),
            (NamedView::Left, false),
            (NamedView::Front, true),
            (NamedView::Top, true),
        ] {
            checked += check_visibility(&scene, &fit(&scene, view, ortho, 300, 200));
        }
    }
    let tori = crossing_tori();
    checked += check_visibility(&tori, &fit(&tori, NamedView::Iso, false, 300, 200));
    assert!(checked > 1000, "{checked}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn every_segment_of_a_soup_is_seen_exactly_where_nothing_is_in_front(
        seed in any::<u64>(),
        n in 2usize..14,
        camera in random_cameras(0.5f64..2.0),
    ) {
        let Some(camera) = camera else { return Ok(()) };
        let scene = random_triangles(n, seed);
        check_visibility(&scene, &camera);
    }

    #[test]
    fn every_exact_strategy_draws_the_coverage_maps_lines(
        seed in any::<u64>(),
        n in 2usize..14,
        camera in random_cameras(0.5f64..2.0),
    ) {
        let Some(camera) = camera else { return Ok(()) };
        let scene = random_triangles(n, seed);
        let a = drawing_with(&CoverageMap, &scene, &camera).drawing;
        for (name, strategy) in exact_strategies() {
            let b = drawing_with(strategy, &scene, &camera).drawing;
            prop_assert_eq!(&a, &b, "{}", name);
        }
    }

    #[test]
    fn strokes_cover_every_segment_once_with_the_fewest_paths(
        seed in any::<u64>(),
        n in 2usize..14,
        camera in random_cameras(0.5f64..2.0),
    ) {
        let Some(camera) = camera else { return Ok(()) };
        let scene = random_triangles(n, seed);
        let options = LineOptions::default();
        let prepared = prepare(&scene, &camera, options.cull);
        let visible = CoverageMap.visible_set(&prepared.screen, &|_| false, None);
        let (exact, _) = exact_lines(&scene, &camera, &prepared, &visible.pieces, &options);
        let lines = lines_of(&scene, &camera, &prepared, &visible.pieces, &options);
        let key = |a: [f64; 2], b: [f64; 2]| {
            let (a, b) = (a.map(f64::to_bits), b.map(f64::to_bits));
            if a < b { (a, b) } else { (b, a) }
        };
        let mut want: Vec<_> = exact
            .segments
            .iter()
            .map(|s| (s.label.visibility, s.label.kind, key(s.ends[0], s.ends[1])))
            .collect();
        let mut got = Vec::new();
        for s in &lines.drawing.strokes {
            let n = s.points.len();
            let m = if s.closed { n } else { n - 1 };
            for i in 0..m {
                got.push((s.visibility, s.kind, key(s.points[i], s.points[(i + 1) % n])));
            }
        }
        want.sort();
        got.sort();
        prop_assert_eq!(got, want);
        prop_assert_eq!(lines.drawing.strokes.len(), lines.stats.paths_minimum);
    }
}

#[test]
fn every_fixture_draws_its_lines() {
    for entry in std::fs::read_dir("fixtures").unwrap() {
        let path = entry.unwrap().path();
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        if !["obj", "stl", "ply", "x3d"].contains(&ext) {
            continue;
        }
        let scene = sightline::load(&path, None).unwrap();
        let camera = spec_camera(&scene, (200, 150));
        let draw = || {
            sightline::lines::line_drawing(&scene, &camera, &LineOptions::default(), None).unwrap()
        };
        let lines = draw();
        let name = path.display();
        assert!(!lines.drawing.strokes.is_empty(), "{name}");
        assert_eq!(
            lines.drawing.strokes.len(),
            lines.stats.paths_minimum,
            "{name}"
        );
        for s in &lines.drawing.strokes {
            assert!(s.points.len() >= 2 && s.points.iter().flatten().all(|v| v.is_finite()));
            assert!(
                s.points.windows(2).all(|w| w[0] != w[1]),
                "{name}: a repeated point"
            );
        }
        // The same input gives the same drawing (a second thread makes the lines).
        assert_eq!(lines.drawing, draw().drawing, "{name}");
    }
}

#[test]
fn a_face_seen_edge_on_still_meets_the_face_it_passes_through() {
    // In a front orthographic view, a triangle in the plane x = 0 is seen edge-on; it passes
    // through a triangle facing the camera at z = 0 along x = 0, and a square in front (z = 0.5)
    // covers the meeting's lower part (y < 0).
    let p = DVec3::new;
    let mut b = SceneBuilder::new("edge-on");
    support::scenes::add_triangle(
        &mut b,
        [p(0.0, -1.0, -1.0), p(0.0, 1.0, 0.0), p(0.0, -1.0, 0.3)],
    );
    support::scenes::add_triangle(
        &mut b,
        [p(-1.0, -0.8, 0.0), p(1.0, -0.8, 0.0), p(0.0, 0.9, 0.0)],
    );
    support::scenes::add_polygon(
        &mut b,
        &[
            p(-0.5, -2.0, 0.5),
            p(0.5, -2.0, 0.5),
            p(0.5, 0.0, 0.5),
            p(-0.5, 0.0, 0.5),
        ],
    );
    let scene = b.finish().unwrap();
    let camera = support::camera::front_ortho(4.0, 200, 200);
    let (prepared, lines) = exact(&scene, &camera, &LineOptions::default());
    assert_eq!(
        prepared.screen.orientation[0],
        sightline::project::Orientation::Flat
    );
    // The edge-on triangle's own edges lie on the same screen line and, by precedence, are
    // drawn there instead: the meeting is checked on its own.
    let tracks: Vec<_> = lines
        .tracks
        .iter()
        .filter(|t| t.kind == LineKind::Intersection)
        .cloned()
        .collect();
    assert_eq!(tracks.len(), 1);
    assert_eq!(tracks[0].rule, SeenRule::Unoccluded);
    let segments = sightline::lines::tracks::segments(
        &tracks,
        &Samples::new(200, 200),
        &LineOptions::default(),
    );
    let meeting: Vec<&Segment> = segments.iter().collect();
    let visible: Vec<_> = meeting
        .iter()
        .filter(|s| s.label.visibility == Visibility::Visible)
        .collect();
    let hidden: Vec<_> = meeting
        .iter()
        .filter(|s| s.label.visibility == Visibility::Hidden)
        .collect();
    assert_eq!((visible.len(), hidden.len()), (1, 1), "{meeting:?}");
    // On screen x = 0 is column 100 and row = 100 - 50·y. The edge-on triangle crosses z = 0
    // for y in [-1, 1], the front triangle spans y in [-0.8, 0.9] at x = 0, and the square
    // hides y < 0.
    let rows = |s: &&&Segment| {
        let mut r = [s.ends[0][1], s.ends[1][1]];
        r.sort_by(f64::total_cmp);
        r
    };
    assert!(
        visible
            .iter()
            .chain(&hidden)
            .all(|s| s.ends.iter().all(|e| e[0] == 100.0))
    );
    let [top, bottom] = rows(&visible[0]);
    assert!(
        (top - 55.0).abs() < 1e-4 && bottom == 100.0,
        "{top} {bottom}"
    );
    let [top, bottom] = rows(&hidden[0]);
    assert!(
        top == 100.0 && (bottom - 140.0).abs() < 1e-4,
        "{top} {bottom}"
    );
    check_visibility(&scene, &camera);
}

#[test]
fn faces_sharing_a_corner_meet_only_where_they_cross_beyond_it() {
    let p = DVec3::new;
    let v = p(0.0, 0.0, 0.0);
    let meetings = |other_side: f64| {
        let mut b = SceneBuilder::new("corner");
        support::scenes::add_triangle(&mut b, [v, p(2.0, 1.0, 0.0), p(2.0, -1.0, 0.0)]);
        let x = 2.0 * other_side;
        support::scenes::add_triangle(&mut b, [v, p(x, 0.0, 1.0), p(x, 0.0, -1.0)]);
        let scene = b.finish().unwrap();
        let camera = fit(&scene, NamedView::Iso, false, 300, 200);
        let (_, lines) = exact(&scene, &camera, &LineOptions::default());
        lines
            .tracks
            .iter()
            .filter(|t| t.kind == LineKind::Intersection)
            .count()
    };
    // Both run from V along +x: they pass through each other along the x axis.
    assert_eq!(meetings(1.0), 1);
    // One runs along +x, the other along -x: their planes meet on the x axis, they only touch.
    assert_eq!(meetings(-1.0), 0);
}

#[test]
fn qi_max_keeps_hidden_lines_up_to_that_many_faces_deep() {
    let scene = random_triangles(30, 7);
    let camera = support::camera::soup_camera((300, 200));
    let qi_of = |qi_max| {
        let options = LineOptions {
            qi_max,
            ..LineOptions::default()
        };
        let (_, lines) = exact(&scene, &camera, &options);
        lines.segments.iter().map(|s| s.label.qi).max().unwrap_or(0)
    };
    let deepest = qi_of(Some(u32::MAX));
    assert!(deepest >= 3, "the soup has lines {deepest} faces deep");
    assert_eq!(qi_of(Some(1)), 1);
    assert_eq!(qi_of(Some(2)), 2);
    // Without --qi-max, hidden lines say "at least one".
    assert_eq!(qi_of(None), 1);
}

#[test]
fn an_edge_on_face_behind_a_surface_cut_along_its_line_is_hidden() {
    // Front orthographic view: a big square at z = 0, a small square in front (z = 0.5) whose
    // right side is x = 0.2, so the visible set cuts the big square's region along x = 0.2;
    // and a triangle in the plane x = 0.2, seen edge-on, behind the big square (z < 0). Its
    // edges run exactly along the cut, between two pieces of the big square: hidden.
    let p = DVec3::new;
    let mut b = SceneBuilder::new("edge-on behind");
    support::scenes::add_polygon(
        &mut b,
        &[
            p(-1.0, -1.0, 0.0),
            p(1.0, -1.0, 0.0),
            p(1.0, 1.0, 0.0),
            p(-1.0, 1.0, 0.0),
        ],
    );
    support::scenes::add_polygon(
        &mut b,
        &[
            p(-0.5, -0.5, 0.5),
            p(0.2, -0.5, 0.5),
            p(0.2, 0.5, 0.5),
            p(-0.5, 0.5, 0.5),
        ],
    );
    support::scenes::add_triangle(
        &mut b,
        [p(0.2, -0.3, -1.0), p(0.2, 0.3, -1.0), p(0.2, 0.0, -0.5)],
    );
    let scene = b.finish().unwrap();
    let camera = support::camera::front_ortho(4.0, 200, 200);
    let (prepared, lines) = exact(&scene, &camera, &LineOptions::default());
    assert_eq!(
        prepared.screen.orientation[2],
        sightline::project::Orientation::Flat
    );
    let edge_on: Vec<_> = lines
        .tracks
        .iter()
        .filter(|t| t.faces == [2])
        .cloned()
        .collect();
    assert_eq!(edge_on.len(), 3);
    assert!(edge_on.iter().all(|t| t.rule == SeenRule::Unoccluded));
    let segments = sightline::lines::tracks::segments(
        &edge_on,
        &Samples::new(200, 200),
        &LineOptions::default(),
    );
    assert!(!segments.is_empty());
    assert!(
        segments
            .iter()
            .all(|s| s.label.visibility == Visibility::Hidden),
        "{segments:?}"
    );
}
