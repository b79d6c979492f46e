//! Renders the tests predict pixel by pixel.

use super::camera::front_ortho;
use sightline::pipeline::render_zbuffer;
use sightline::project::CullMode;
use sightline::raster::lighting::{Lighting, Shading, Textures, shade_zbuffer};
use sightline::scene::Scene;

/// `scene` through the front orthographic camera (view height 2) at `size` x `size`, z-buffered
/// and shaded flat and matte (flat shading takes a highlight when Ks > 0) under the headlight,
/// over black, with its textures: the checker quads' render. Every texture must load and every
/// pixel be covered.
pub fn flat_headlight(scene: &Scene, size: u32) -> Vec<[f64; 3]> {
    let cam = front_ortho(2.0, size, size);
    let textures = Textures::load(scene);
    assert!(textures.warnings.is_empty(), "{:?}", textures.warnings);
    let (prep, zb) = render_zbuffer(scene, &cam, CullMode::Auto, |_| {});
    assert!(zb.poly.iter().all(|&p| p != sightline::raster::EMPTY));
    shade_zbuffer(
        scene,
        &prep.screen,
        &zb,
        &cam,
        &Lighting {
            specular: 0.0,
            ..Lighting::headlight(&cam)
        },
        Shading::Flat,
        &textures,
        [0.0; 3],
    )
}
