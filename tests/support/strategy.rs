//! The visibility strategies as the tests reach them: the exact visible set by its two paths, the
//! drawings of the bsp and painter methods, and the comparison of two face-id images. Tests go
//! through these few functions and re-exports, so that renaming the library's items is one edit
//! here rather than one in every test.

use sightline::camera::Camera;
use sightline::exact::polygon::Piece;
use sightline::pipeline::{Fill, compare_ids};
use sightline::project::ScreenScene;
use sightline::scene::Scene;
use sightline::visibility::bsp::BspStats;
use sightline::visibility::coverage::CoverageStats;

pub use sightline::pipeline::IdComparison;
pub use sightline::visibility::bsp::{Bsp, VisibleSet};
pub use sightline::visibility::{BspMethod, Painter, VisibilityMethod, VisibilityResult};

/// The exact visible set `--method bsp` draws for an opaque scene: the depth-aware coverage map.
pub fn coverage_map(screen: &ScreenScene) -> (VisibleSet, CoverageStats) {
    sightline::visibility::bsp::visible_set(screen)
}

/// The other exact path: the BSP built, then walked front to back through the ordered coverage
/// map; with the tree's counters.
pub fn bsp_walk(screen: &ScreenScene) -> (VisibleSet, BspStats) {
    let mut bsp = Bsp::build(screen);
    let visible = bsp.visible_set(screen);
    (visible, bsp.stats)
}

/// Every fragment of the BSP, back to front (the painter order of translucent parts).
pub fn bsp_fragments(screen: &ScreenScene) -> Vec<Piece> {
    Bsp::build(screen).back_to_front()
}

/// The convex pieces every screen polygon is cut into before any visibility is decided.
pub fn initial_pieces(screen: &ScreenScene) -> Vec<Piece> {
    sightline::visibility::bsp::initial_pieces(screen)
}

/// `--method bsp`'s drawing face by face (no merged surfaces, no seams), as the JSON has it.
pub fn exact_drawing(
    scene: &Scene,
    screen: &ScreenScene,
    camera: &Camera,
    fill: Fill,
) -> VisibilityResult {
    BspMethod::default().run(scene, screen, camera, fill)
}

/// `render --method bsp -o X.svg`'s picture: coplanar surfaces merged, seams stroked.
pub fn exact_picture(
    scene: &Scene,
    screen: &ScreenScene,
    camera: &Camera,
    fill: Fill,
) -> VisibilityResult {
    BspMethod {
        merge_surfaces: true,
        seams: true,
    }
    .run(scene, screen, camera, fill)
}

/// The painter's drawing (approximate: whole faces, farthest corner first).
pub fn painter_drawing(
    scene: &Scene,
    screen: &ScreenScene,
    camera: &Camera,
    fill: Fill,
) -> VisibilityResult {
    Painter.run(scene, screen, camera, fill)
}

/// `ids` against `reference` over covered and over interior pixels (`compare`'s counts).
pub fn compare(reference: &[Option<u32>], ids: &[Option<u32>], w: usize, h: usize) -> IdComparison {
    compare_ids(reference, ids, w, h)
}

/// Every object-space strategy, in the order the CLI lists them.
pub fn methods() -> Vec<Box<dyn VisibilityMethod>> {
    sightline::visibility::methods()
}

/// The strategy the CLI calls `name`, if any.
pub fn method_by_name(name: &str) -> Option<Box<dyn VisibilityMethod>> {
    sightline::visibility::method_by_name(name)
}
