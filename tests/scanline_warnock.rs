//! The scanline (Watkins) and Warnock renderers against the z-buffer: the same polygon, hence the
//! same face id, at every pixel (not only interior ones) of every fixture from several cameras,
//! of generated spheres, tori and soups, and of random scenes built around shared edges, edges
//! through pixel centres and exact coplanar overlaps.

mod support;

use proptest::prelude::*;
use sightline::camera::Camera;
use sightline::pipeline::prepare;
use sightline::project::{CullMode, ScreenScene};
use sightline::raster::scanline::{self, ScanlineStats};
use sightline::raster::warnock::{self, WarnockStats};
use sightline::raster::{EMPTY, zbuffer};
use sightline::scene::{Scene, primitives};
use support::camera::{cameras, lattice_camera, random_cameras};
use support::fixtures::fixture_paths;
use support::scenes::tricky_faces;

/// The first pixel where `got` differs from the z-buffer's `want`, described.
fn first_difference(screen: &ScreenScene, want: &[u32], got: &[u32]) -> Option<String> {
    let w = screen.width as usize;
    let id = |p: u32| (p != EMPTY).then(|| screen.polys[p as usize].id);
    let bad: Vec<usize> = (0..want.len()).filter(|&k| want[k] != got[k]).collect();
    bad.first().map(|&k| {
        format!(
            "{} pixels differ; first ({}, {}): z-buffer polygon {} (face {:?}), got {} (face {:?})",
            bad.len(),
            k % w,
            k / w,
            want[k],
            id(want[k]),
            got[k],
            id(got[k])
        )
    })
}

/// Renders with all three and checks scanline and Warnock against the z-buffer at every pixel.
/// Returns their stats and the number of covered pixels.
fn check_screen(screen: &ScreenScene) -> (ScanlineStats, WarnockStats, usize) {
    let zb = zbuffer::render(screen, |_| {});
    let sl = scanline::render(screen);
    if let Some(d) = first_difference(screen, &zb.poly, &sl.poly) {
        panic!("scanline: {d}; stats {:?}", sl.stats);
    }
    let wa = warnock::render(screen);
    if let Some(d) = first_difference(screen, &zb.poly, &wa.poly) {
        panic!("warnock: {d}; stats {:?}", wa.stats);
    }
    assert_eq!(sl.face_ids(screen), zb.face_ids(screen));
    assert_eq!(wa.face_ids(screen), zb.face_ids(screen));
    let covered = zb.poly.iter().filter(|&&p| p != EMPTY).count();
    (sl.stats, wa.stats, covered)
}

fn check(scene: &Scene, cam: &Camera, cull: CullMode) -> (ScanlineStats, WarnockStats, usize) {
    check_screen(&prepare(scene, cam, cull).screen)
}

#[test]
fn every_fixture_from_four_cameras() {
    let mut covered = 0;
    for path in fixture_paths() {
        let scene = sightline::load(&path, None).unwrap();
        // A flat fixture (one quad) is edge-on from some camera: ask that some camera sees it.
        let mut seen = 0;
        for cam in cameras(&scene, 96, 72).iter() {
            for cull in [CullMode::Auto, CullMode::Off] {
                let (_, _, c) = check(&scene, cam, cull);
                seen += c;
            }
        }
        assert!(seen > 0, "{}: no camera sees anything", path.display());
        covered += seen;
    }
    assert!(covered > 100_000, "{covered}");
}

#[test]
fn spheres_tori_and_soups() {
    let sphere = primitives::sphere_scene(4000);
    let tori = primitives::interlocked_tori(40, 16);
    let soups: Vec<Scene> = (1..=3)
        .map(|seed| primitives::random_triangle_soup(150, seed))
        .collect();
    let mut totals = (0u64, 0u64, 0u64);
    for scene in [&sphere, &tori].into_iter().chain(soups.iter()) {
        for cam in cameras(scene, 160, 120) {
            let (sl, wa, covered) = check(scene, &cam, CullMode::Auto);
            assert!(covered > 1_000, "{}: {covered}", scene.source);
            totals.0 += sl.coherent_spans;
            totals.1 += sl.span_splits;
            totals.2 += wa.surrounding_in_front;
        }
    }
    // The fast paths are taken (coherent spans, surrounding polygons in front) and the soups'
    // interpenetration forces span splits.
    assert!(
        totals.0 > 1000 && totals.1 > 10 && totals.2 > 100,
        "{totals:?}"
    );
}

#[test]
fn tiled_lattice_scenes_take_the_exact_paths() {
    // Triangles with corners on pixel centres: crossings land exactly on samples (exact column
    // fallbacks), duplicates tie exactly in depth (id rule); stars are non-convex.
    let mut fallbacks = 0;
    let mut ties = 0;
    let mut stars = 0;
    for seed in 0..40 {
        let scene = tricky_faces(seed, 24, false);
        let screen = prepare(&scene, &lattice_camera(), CullMode::Auto).screen;
        stars += screen.polys.iter().filter(|p| p.len >= 5).count();
        let (sl, wa, _) = check_screen(&screen);
        fallbacks += sl.column_fallbacks + wa.column_fallbacks;
        ties += sl.depth_ties + wa.depth_ties;
    }
    assert!(fallbacks > 100 && ties > 100, "{fallbacks} {ties}");
    assert!(stars > 20, "non-convex polygons on screen: {stars}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

    /// Random tricky scenes under the lattice camera (samples exactly on edges and corners) and
    /// under random perspective and orthographic cameras, some with the eye among the triangles.
    #[test]
    fn scanline_and_warnock_match_the_zbuffer_at_every_pixel(
        seed in any::<u64>(),
        n in 1usize..30,
        cam in random_cameras(0.05f64..1.0),
    ) {
        let scene = tricky_faces(seed, n, false);
        check(&scene, &lattice_camera(), CullMode::Auto);
        if let Some(cam) = cam {
            check(&scene, &cam, CullMode::Auto);
        }
    }
}
