//! The one place where the stress suite reads the kernel's types: grid points, support planes,
//! piece lines, the grid's scale and the fallback counter, each turned into big integers by the
//! narrowest generic route (an integer cast to `i128`, or a coefficient's decimal digits).
//!
//! Invariant: every value leaves this file exact (no rounding, no truncation), whatever the
//! width of the kernel's integers; nothing else in `stress` names a kernel type, so a change of
//! representation (wider grid points, planes in a table) is adapted here alone.

use crate::camera::Camera;
use crate::project::ScreenScene;
use crate::visibility::VisibleSet;
use num_bigint::BigInt;

/// A screen polygon in exact integers.
#[derive(Clone, Debug)]
pub struct GridPolygon {
    /// Index into `Scene::faces`.
    pub face: u32,
    /// The input face id (the tie rule: the larger id is in front of a coplanar polygon).
    pub id: u32,
    /// Its corners' grid (x, y).
    pub corners: Vec<[BigInt; 2]>,
    /// Its support plane `a·x + b·y + c·z + d = 0` on the grid (`c > 0`), as the kernel holds
    /// it (for a quad: through three of its snapped corners).
    pub plane: [BigInt; 4],
}

/// A visible piece: its polygon (index into the screen polygons) and its boundary lines
/// `a·x + b·y + d = 0`, inside on the positive side of every one.
#[derive(Clone, Debug)]
pub struct PieceLines {
    /// Index into `ScreenScene::polys`.
    pub poly: usize,
    /// The exact coefficients (a, b, d) of each line.
    pub lines: Vec<[BigInt; 3]>,
}

/// A kernel integer of any width, exactly.
fn big(v: impl ToString) -> BigInt {
    v.to_string()
        .parse()
        .expect("a kernel integer prints as decimal digits")
}

fn coordinate(v: impl Into<i128>) -> BigInt {
    BigInt::from(v.into())
}

/// Grid units per NDC unit: (x and y, z).
pub fn grid_scale() -> (f64, f64) {
    (crate::exact::XY_SCALE, crate::exact::Z_SCALE)
}

/// The screen polygons of `screen`, in order.
pub fn polygons(screen: &ScreenScene) -> Vec<GridPolygon> {
    screen
        .polys
        .iter()
        .map(|p| GridPolygon {
            face: p.face,
            id: p.id,
            corners: screen
                .corners(p)
                .iter()
                .map(|c| [coordinate(c.x), coordinate(c.y)])
                .collect(),
            plane: {
                let plane = screen.plane(p);
                [big(plane.a), big(plane.b), big(plane.c), big(plane.d)]
            },
        })
        .collect()
}

/// The visible pieces of the opaque faces, as exact lines.
pub fn pieces(visible: &VisibleSet) -> Vec<PieceLines> {
    visible
        .pieces
        .iter()
        .map(|p| PieceLines {
            poly: p.poly as usize,
            lines: p.lines().map(|l| l.exact().map(big)).collect(),
        })
        .collect()
}

/// The grid point (x, y, z) a world point snaps to as an unclipped face corner, `None` when a
/// face with that corner would be clipped there.
pub fn snapped_vertex(camera: &Camera, p: glam::DVec3) -> Option<[BigInt; 3]> {
    crate::project::snap_point(&camera.view_projection(), p)
        .map(|g| [coordinate(g.x), coordinate(g.y), coordinate(g.z)])
}

/// The kernel's fallback count on this thread (predicates its f64 filters could not decide).
pub fn fallbacks() -> u64 {
    crate::exact::predicates::fallback_count()
}

/// The fallbacks a strategy reports in its stats (`exact_fallbacks`), 0 when it reports none.
pub fn strategy_fallbacks(visible: &VisibleSet) -> u64 {
    visible
        .stats
        .get("exact_fallbacks")
        .and_then(|v| v.as_u64())
        .unwrap_or(0)
}
