//! The visibility strategies as the tests reach them: the exact visible set by its two paths, the
//! drawings of the coverage and painter methods, and the comparison of two face-id images. Tests
//! go through these few functions and re-exports, so that renaming the library's items is one
//! edit here rather than one in every test.

use sightline::camera::Camera;
use sightline::draw::{DrawOptions, Picture, picture};
use sightline::exact::polygon::Piece;
use sightline::pipeline::{Fill, compare_ids};
use sightline::project::ScreenScene;
use sightline::scene::Scene;
use sightline::visibility::bsp::BspStats;
use sightline::visibility::coverage::CoverageStats;

pub use sightline::pipeline::IdComparison;
pub use sightline::visibility::bsp::Bsp;
pub use sightline::visibility::{CoverageMap, Painter, Strategy, VisibleSet};

/// The exact visible set `--method coverage` draws for an opaque scene: the depth-aware
/// coverage map.
pub fn coverage_map(screen: &ScreenScene) -> (VisibleSet, CoverageStats) {
    sightline::visibility::coverage_map::visible_set(screen)
}

/// The other exact path: the BSP built, then walked front to back through the ordered coverage
/// map; with the tree's counters.
pub fn bsp_walk(screen: &ScreenScene) -> (VisibleSet, BspStats) {
    Bsp::build(screen).visible_set(screen)
}

/// Every fragment of the BSP, back to front (the painter order of translucent parts).
pub fn bsp_fragments(screen: &ScreenScene) -> Vec<Piece> {
    Bsp::build(screen).back_to_front()
}

/// The convex pieces every screen polygon is cut into before any visibility is decided.
pub fn initial_pieces(screen: &ScreenScene) -> Vec<Piece> {
    sightline::visibility::initial_pieces(screen)
}

/// `strategy`'s drawing with `options`, as `render` makes it.
pub fn drawing_of(
    strategy: &dyn Strategy,
    scene: &Scene,
    screen: &ScreenScene,
    camera: &Camera,
    fill: Fill,
    options: DrawOptions,
) -> Picture {
    picture(strategy, scene, screen, camera, fill, options, None)
}

/// `--method coverage`'s drawing face by face (no merged surfaces, no seams), as the JSON has it.
pub fn exact_drawing(scene: &Scene, screen: &ScreenScene, camera: &Camera, fill: Fill) -> Picture {
    drawing_of(
        &CoverageMap,
        scene,
        screen,
        camera,
        fill,
        DrawOptions::per_face(),
    )
}

/// `render --method coverage -o X.svg`'s picture: coplanar surfaces merged, seams stroked.
pub fn exact_picture(scene: &Scene, screen: &ScreenScene, camera: &Camera, fill: Fill) -> Picture {
    drawing_of(
        &CoverageMap,
        scene,
        screen,
        camera,
        fill,
        DrawOptions::picture(),
    )
}

/// The painter's drawing (approximate: whole faces, farthest corner first).
pub fn painter_drawing(
    scene: &Scene,
    screen: &ScreenScene,
    camera: &Camera,
    fill: Fill,
) -> Picture {
    drawing_of(
        &Painter,
        scene,
        screen,
        camera,
        fill,
        DrawOptions::per_face(),
    )
}

/// `ids` against `reference` over covered and over interior pixels (`compare`'s counts).
pub fn compare(reference: &[Option<u32>], ids: &[Option<u32>], w: usize, h: usize) -> IdComparison {
    compare_ids(reference, ids, w, h)
}

/// Every exact object-space strategy of the method registry, with its name: the coverage map,
/// the BSP, Newell, Weiler–Atherton, Warnock at object precision, and any added later.
pub fn exact_strategies() -> Vec<(&'static str, &'static dyn Strategy)> {
    use sightline::methods::{Engine, METHODS};
    METHODS
        .iter()
        .filter(|m| m.exact)
        .filter_map(|m| match m.engine {
            Engine::Object(s) => Some((m.name, s)),
            Engine::Image(_) => None,
        })
        .collect()
}
