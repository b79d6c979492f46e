//! Every registered method on every fixture, held to the reference z-buffer.
//!
//! The list of methods is the registry (`sightline::methods::METHODS`) and the list of scenes is
//! the `fixtures/` folder, both read at run time: a method added to the registry, or a fixture
//! added to the folder, is checked without touching this file. An exact method must show the
//! z-buffer's face id at every interior pixel (a covered pixel whose 3x3 neighbourhood holds one
//! face); an approximate one is only run. Each comparison asserts that it compared covered
//! interior pixels, so a scene that renders empty cannot pass.

use glam::{DMat4, DVec3};
use sightline::camera::{Camera, NamedView};
use sightline::methods::{Engine, METHODS, method};
use sightline::pipeline::{compare_ids, prepare};
use sightline::project::CullMode;
use sightline::scene::SceneBuilder;
use sightline::visibility::visible_set::VisibleSet;
use sightline::visibility::{CoverageMap, Strategy};
use std::path::PathBuf;

/// The loadable scenes in `fixtures/` (not `fixtures/bad/`), sorted.
fn fixtures() -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir("fixtures")
        .expect("fixtures/")
        .map(|e| e.expect("fixture entry").path())
        .filter(|p| {
            p.is_file()
                && p.extension()
                    .is_some_and(|e| ["obj", "stl", "ply", "x3d"].contains(&e.to_str().unwrap()))
        })
        .collect();
    out.sort();
    out
}

#[test]
fn every_exact_method_matches_the_zbuffer_inside_faces_on_every_fixture() {
    let reference = method("zbuffer").expect("the reference is registered");
    let files = fixtures();
    assert!(files.len() >= 15, "fixtures found: {files:?}");
    let mut compared = 0;
    for file in &files {
        let scene = sightline::load(file, None).unwrap_or_else(|e| panic!("{e}"));
        for view in [NamedView::Iso, NamedView::Front] {
            let camera = Camera::fit(view, scene.bounds().unwrap(), false, 40.0, 96, 80);
            let screen = prepare(&scene, &camera, CullMode::Auto).screen;
            let want = reference.face_ids(&scene, &screen, &camera, None);
            for m in &METHODS {
                let got = m.face_ids(&scene, &screen, &camera, None);
                let c = compare_ids(&want, &got, 96, 80);
                let what = format!("{} on {} ({view:?})", m.name, file.display());
                assert!(c.interior > 0, "{what}: no interior pixel compared");
                if m.exact {
                    assert_eq!(c.interior_mismatch, 0, "{what}: {c:?}");
                }
                compared += 1;
            }
        }
    }
    assert_eq!(compared, files.len() * 2 * METHODS.len());
}

/// Every exact object-space strategy computes the coverage map's visible set: the exact
/// symmetric difference of their regions (per polygon, opaque pieces and translucent layers) is
/// empty, on every fixture from two views, with every face opaque and with every fifth polygon
/// translucent. The check itself is shown able to fail: the coverage map's set less one piece
/// differs from it.
#[test]
fn every_exact_strategy_has_the_coverage_maps_visible_set_on_every_fixture() {
    let strategies: Vec<(&str, &dyn Strategy)> = METHODS
        .iter()
        .filter(|m| m.exact)
        .filter_map(|m| match m.engine {
            Engine::Object(s) => Some((m.name, s)),
            Engine::Image(_) => None,
        })
        .collect();
    assert!(
        strategies.len() >= 2,
        "exact strategies: {}",
        strategies.len()
    );
    let mut compared = 0;
    for file in &fixtures() {
        let scene = sightline::load(file, None).unwrap_or_else(|e| panic!("{e}"));
        for view in [NamedView::Iso, NamedView::Front] {
            let camera = Camera::fit(view, scene.bounds().unwrap(), false, 40.0, 96, 80);
            let screen = prepare(&scene, &camera, CullMode::Auto).screen;
            let every_fifth = |k: u32| k.is_multiple_of(5);
            let opaque = |_: u32| false;
            for (layers, translucent) in [
                ("opaque", &opaque as &dyn Fn(u32) -> bool),
                ("every fifth translucent", &every_fifth),
            ] {
                let want = CoverageMap.visible_set(&screen, translucent, None);
                assert!(!want.pieces.is_empty() || !want.layered.is_empty());
                let mut less = want.clone();
                if less.pieces.pop().is_some() {
                    assert!(!want.symmetric_difference(&less).is_empty());
                }
                for (name, strategy) in &strategies {
                    let got = strategy.visible_set(&screen, translucent, None);
                    let diff = want.symmetric_difference(&got);
                    assert!(
                        diff.is_empty(),
                        "{name} on {} ({view:?}, {layers}): {} parts differ from the coverage map",
                        file.display(),
                        diff.len()
                    );
                    compared += 1;
                }
            }
        }
    }
    assert_eq!(compared, fixtures().len() * 2 * 2 * strategies.len());
}

/// A square of side 0.4 at `centre` facing `normal`, in a mesh of its own (open: never culled).
fn add_square(b: &mut SceneBuilder, centre: DVec3, normal: DVec3) {
    let u = normal.any_orthonormal_vector() * 0.2;
    let v = normal.cross(u);
    // u x v = normal: counter-clockwise seen from where the normal points.
    let corners = [
        centre - u - v,
        centre + u - v,
        centre + u + v,
        centre - u + v,
    ];
    b.begin_mesh("square");
    let m = b.default_material();
    let ids: Vec<u32> = corners.iter().map(|&p| b.add_vertex(p)).collect();
    b.add_face(&ids, m);
}

/// The occlusion cells drop pieces seen from the back before any cut, and only those behind the
/// front: from three views, a closed sphere (its back faces culled; its front the cover) with two
/// squares turned away from the eye, one inside it (dropped) and one in front of it (within
/// covered cells, but kept by the depth test: it is visible). The coverage map's visible set is
/// that of Weiler–Atherton, Newell and Warnock's subdivision, which make no cells of their own.
#[test]
fn occlusion_cells_drop_back_pieces_without_changing_the_visible_set() {
    for view in [NamedView::Iso, NamedView::Front, NamedView::Top] {
        let (towards_eye, _) = view.direction_and_up();
        let mut b = SceneBuilder::new("sphere and squares");
        b.begin_mesh("sphere");
        let m = b.default_material();
        sightline::scene::primitives::add_sphere(&mut b, &DMat4::IDENTITY, 1.0, 32, 16, m);
        add_square(&mut b, DVec3::ZERO, -towards_eye);
        add_square(&mut b, 1.3 * towards_eye, -towards_eye);
        let scene = b.finish().unwrap();
        let camera = Camera::fit(view, scene.bounds().unwrap(), false, 40.0, 160, 120);
        let screen = prepare(&scene, &camera, CullMode::Auto).screen;
        let want = CoverageMap.visible_set(&screen, &|_| false, None);
        let occluded = want.stats["occluded"].as_u64().unwrap();
        assert_eq!(
            occluded, 1,
            "{view:?}: the square inside the sphere, and only it"
        );
        for name in ["weiler-atherton", "newell", "warnock-exact"] {
            let Engine::Object(strategy) = method(name).unwrap().engine else {
                panic!("{name} is an object-space strategy");
            };
            let got = strategy.visible_set(&screen, &|_| false, None);
            let diff = want.symmetric_difference(&got);
            assert!(
                diff.is_empty(),
                "{name} ({view:?}): {} parts differ",
                diff.len()
            );
        }
    }
}

/// The approximate painter is measured, not trusted: on the cyclic bars it is wrong, and the
/// comparison above would have let it pass only because it is marked approximate.
#[test]
fn the_painter_is_marked_approximate_because_it_is_wrong_on_cyclic_bars() {
    let painter = method("painter").unwrap();
    assert!(!painter.exact);
    let scene = sightline::load(std::path::Path::new("fixtures/cyclic_bars.obj"), None).unwrap();
    let camera = Camera::fit(
        NamedView::Front,
        scene.bounds().unwrap(),
        false,
        40.0,
        96,
        80,
    );
    let screen = prepare(&scene, &camera, CullMode::Auto).screen;
    let want = method("zbuffer")
        .unwrap()
        .face_ids(&scene, &screen, &camera, None);
    let got = painter.face_ids(&scene, &screen, &camera, None);
    let c = compare_ids(&want, &got, 96, 80);
    assert!(c.interior > 0 && c.interior_mismatch > 0, "{c:?}");
}

/// `auto` skips what a scene does not need and says so: a closed sphere seen from outside is one
/// mesh whose front faces cover its outline once, so its pieces are placed whole with no depth
/// comparison at all; interlocked tori overlap on screen and go to a BSP tree (culled: none
/// seen from the back). Either way the visible set is the coverage map's (exact symmetric
/// difference empty).
#[test]
fn auto_places_a_convex_mesh_whole_and_orders_what_overlaps() {
    use sightline::scene::primitives::{interlocked_tori, sphere_scene};
    let auto = method("auto").unwrap();
    let Engine::Object(auto) = auto.engine else {
        panic!("auto is an object-space method")
    };
    for (name, scene, whole) in [
        ("sphere", sphere_scene(2000), true),
        ("interlocked tori", interlocked_tori(16, 8), false),
    ] {
        let camera = Camera::fit(NamedView::Iso, scene.bounds().unwrap(), false, 40.0, 96, 80);
        let screen = prepare(&scene, &camera, CullMode::Auto).screen;
        let got = auto.visible_set(&screen, &|_| false, None);
        let want = CoverageMap.visible_set(&screen, &|_| false, None);
        assert!(got.symmetric_difference(&want).is_empty(), "{name}");
        let placed = got.stats["pieces_placed_whole"].as_u64().unwrap();
        let order = got.stats["stage_order"].as_str().unwrap();
        if whole {
            assert_eq!(placed as usize, got.pieces.len(), "{name}: {order}");
            assert_eq!(got.stats["overlap_tests"], 0, "{name}");
            assert!(order.contains("nothing left to order"), "{name}: {order}");
        } else {
            // Culled closed meshes: nothing overlapping is seen from the back.
            assert_eq!(placed, 0, "{name}: {order}");
            assert!(order.contains("done by a BSP tree"), "{name}: {order}");
        }
    }
}

/// `auto`'s visible set of `scene` seen from `view` (96 x 80 pixels), checked to be the coverage
/// map's, and its `stage_order` line.
fn auto_as_the_map(scene: &sightline::scene::Scene, view: NamedView) -> (VisibleSet, String) {
    let Engine::Object(auto) = method("auto").unwrap().engine else {
        panic!("auto is an object-space method")
    };
    let camera = Camera::fit(view, scene.bounds().unwrap(), false, 40.0, 96, 80);
    let screen = prepare(scene, &camera, CullMode::Auto).screen;
    let got = auto.visible_set(&screen, &|_| false, None);
    let want = CoverageMap.visible_set(&screen, &|_| false, None);
    assert!(got.symmetric_difference(&want).is_empty());
    let order = got.stats["stage_order"].as_str().unwrap().to_string();
    (got, order)
}

/// `auto` hands a soup of large crossing triangles to Warnock's subdivision (the coverage map
/// cuts each far piece by every nearer one there), and says so; the set is the map's.
#[test]
fn auto_subdivides_a_soup_of_large_crossing_faces() {
    use sightline::scene::primitives::random_triangle_soup;
    let (got, order) = auto_as_the_map(&random_triangle_soup(200, 3), NamedView::Iso);
    assert!(order.contains("Warnock"), "{order}");
    assert!(got.stats["depth_complexity_estimate"].as_f64().unwrap() > 8.0);
}

/// `auto` orders slivers (an exported sphere's polar triangles, its poles on the silhouette of
/// a front view) by a BSP tree per strip, and says so; the set is the map's.
#[test]
fn auto_orders_slivers_by_a_bsp_tree() {
    use sightline::scene::primitives::exported_sphere_scene;
    use sightline::visibility::auto::Orderer;
    let (got, order) = auto_as_the_map(&exported_sphere_scene(20_000), NamedView::Front);
    assert_eq!(got.stats["chosen"], Orderer::Bsp.name(), "{order}");
    assert!(order.contains("BSP tree"), "{order}");
    assert!(got.stats["bsp_pair_tests"].as_u64().unwrap() > 0, "{order}");
}

/// `auto` hands large faces lying over many small ones (a housing: three plates in front of a
/// grid of small spheres, the front row poking through the nearest plate) to Weiler–Atherton
/// clipping, and says so; the set is the map's.
#[test]
fn auto_clips_large_faces_over_many_small_ones() {
    use sightline::scene::SceneBuilder;
    use sightline::scene::primitives::{add_box, add_sphere};
    use sightline::visibility::auto::Orderer;
    type V = glam::DVec3;
    let mut b = SceneBuilder::new("housing");
    let m = b.default_material();
    b.begin_mesh("parts");
    for i in 0..5 {
        for j in 0..5 {
            let at = V::new(
                0.8 * i as f64 - 1.6,
                0.8 * j as f64 - 1.6,
                if i == 0 { 0.3 } else { 0.0 },
            );
            add_sphere(&mut b, &glam::DMat4::from_translation(at), 0.3, 12, 8, m);
        }
    }
    b.begin_mesh("housing");
    for z in [0.55, 0.9, 1.2] {
        let at = glam::DMat4::from_translation(V::new(0.1, 0.05, z));
        add_box(&mut b, &at, V::new(3.4, 3.2, 0.05), m);
    }
    let (got, order) = auto_as_the_map(&b.finish().unwrap(), NamedView::Front);
    assert_eq!(
        got.stats["chosen"],
        Orderer::WeilerAtherton.name(),
        "{order}"
    );
    assert!(order.contains("Weiler-Atherton clipping"), "{order}");
    assert!(got.stats["hidden_parts"].as_u64().unwrap() > 0, "{order}");
}

/// Weiler–Atherton under a recursion limit gives up (for `auto` to fall back on the map) exactly
/// when the scene needs deeper recursion: interpenetrating faces need one level, a culled
/// sphere none.
#[test]
fn weiler_atherton_gives_up_only_beyond_its_recursion_limit() {
    use sightline::visibility::initial_pieces;
    use sightline::visibility::weiler_atherton::{ClipBudget, visible_pieces_within};
    let levels = |deepest| ClipBudget {
        deepest,
        ..ClipBudget::UNLIMITED
    };
    let views = |scene: &sightline::scene::Scene| {
        let camera = Camera::fit(NamedView::Iso, scene.bounds().unwrap(), false, 40.0, 96, 80);
        prepare(scene, &camera, CullMode::Auto).screen
    };
    let crossing = views(
        &sightline::load(std::path::Path::new("fixtures/interpenetrating.obj"), None).unwrap(),
    );
    let pieces = initial_pieces(&crossing);
    assert!(visible_pieces_within(&crossing, pieces.clone(), None, levels(0)).is_none());
    let (_, st) =
        visible_pieces_within(&crossing, pieces, None, levels(1)).expect("one level is enough");
    assert_eq!((st.recursions > 0, st.deepest), (true, 1));
    let sphere = views(&sightline::scene::primitives::sphere_scene(500));
    let (_, st) = visible_pieces_within(&sphere, initial_pieces(&sphere), None, levels(0)).unwrap();
    assert_eq!(st.recursions, 0);
}
