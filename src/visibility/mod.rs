//! Visibility strategies behind one trait, so the CLI, the tests and the benchmarks can run any of
//! them on the same projected scene and compare the results.
//!
//! Invariants of every [`VisibilityResult`]:
//! - its [`Drawing`] has the camera's size, pixel coordinates with y down, and items in painter
//!   order (each drawn over the ones before it), each carrying the input face id it came from;
//! - for a method whose [`VisibilityMethod::exact`] is true, the drawing rasterized at pixel
//!   centres ([`crate::output::raster_drawing::face_ids`]) shows the z-buffer's face id at every
//!   interior pixel (a pixel whose 3x3 neighbourhood in the z-buffer image holds one id).
//!   Approximate methods (the [`Painter`] baseline) make no such promise: they are measured.
//!
//! Grid polygons become pixel rings through [`pixel_ring`], which is exact: a grid coordinate
//! has at most 24 significant bits and the image side at most 15, so `Samples::col_of` and
//! `Samples::row_of` compute their products and sums without rounding.

pub mod bsp;
pub mod coverage;
mod grid;
pub mod painter;
pub mod regions;
pub mod seams;

pub use bsp::BspMethod;
pub use painter::Painter;

use crate::camera::Camera;
use crate::exact::{GridPoint, Samples};
use crate::output::drawing::Drawing;
use crate::paint::Fill;
use crate::project::ScreenScene;
use crate::scene::Scene;

/// A visibility strategy.
pub trait VisibilityMethod {
    /// Short name, as the CLI spells it.
    fn name(&self) -> &'static str;
    /// True for methods whose result is exact (interior mismatch against the z-buffer must be 0).
    fn exact(&self) -> bool;
    /// Computes the drawing of `screen` (the projection of `scene` by `camera`).
    fn run(
        &self,
        scene: &Scene,
        screen: &ScreenScene,
        camera: &Camera,
        fill: Fill,
    ) -> VisibilityResult;
}

/// What a method produced: the drawing and its own counters (timings, splits, fallbacks).
#[derive(Clone, Debug, PartialEq)]
pub struct VisibilityResult {
    pub drawing: Drawing,
    pub stats: serde_json::Map<String, serde_json::Value>,
}

/// Every strategy, in the order the CLI lists them.
pub fn methods() -> Vec<Box<dyn VisibilityMethod>> {
    vec![Box::new(BspMethod::default()), Box::new(Painter)]
}

/// The strategy called `name`, if any.
pub fn method_by_name(name: &str) -> Option<Box<dyn VisibilityMethod>> {
    methods().into_iter().find(|m| m.name() == name)
}

/// A grid polygon as a pixel ring (y down, the last point not repeated). Exact: see the module
/// docs.
pub fn pixel_ring(samples: &Samples, corners: &[GridPoint]) -> Vec<[f64; 2]> {
    corners
        .iter()
        .map(|p| [samples.col_of(p.x as f64), samples.row_of(p.y as f64)])
        .collect()
}

/// The colour and opacity every method gives a face ([`paint::face_paint`], with opacity
/// `1 - transparency`).
///
/// [`paint::face_paint`]: crate::paint::face_paint
pub fn face_paint(scene: &Scene, face: usize, camera: &Camera, fill: Fill) -> ([f64; 3], f64) {
    let (color, transparency) = crate::paint::face_paint(scene, face, camera, fill);
    (color, 1.0 - transparency)
}

/// The background every method uses: black for `Fill::Id` (the id contract), none otherwise
/// (the caller decides).
pub fn background(fill: Fill) -> Option<[f64; 3]> {
    match fill {
        Fill::Id => Some([0.0; 3]),
        Fill::Shade => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::{GRID_MAX, XY_SCALE};

    #[test]
    fn pixel_ring_is_exact_at_the_grid_extremes_and_flips_y() {
        let s = Samples::new(16384, 3);
        let gp = |x: i32, y: i32| GridPoint { x, y, z: 0 };
        let g = GRID_MAX as i32;
        let ring = pixel_ring(&s, &[gp(-g, g), gp(g - 1, -g + 1), gp(0, 0)]);
        // col = (x + 2^22)·W / 2^23, row = (2^22 - y)·H / 2^23, as exact rationals.
        let col = |x: i64| ((x + (1 << 22)) * 16384) as f64 / (1u64 << 23) as f64;
        let row = |y: i64| (((1i64 << 22) - y) * 3) as f64 / (1u64 << 23) as f64;
        assert_eq!(ring[0], [col(-(g as i64)), row(g as i64)]);
        assert_eq!(ring[1], [col(g as i64 - 1), row(-(g as i64) + 1)]);
        assert_eq!(ring[2], [8192.0, 1.5]);
        // The view's top edge (NDC y = 1) is row 0.
        assert_eq!(s.row_of(XY_SCALE), 0.0);
    }
}
