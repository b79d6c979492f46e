//! The stages chained: scene + camera → analysis → screen polygons → z-buffer → image.
//! The CLI, the tests and the benchmarks all go through here, so they run the same code.

use crate::camera::Camera;
use crate::project::{CullMode, ScreenScene, project};
use crate::raster::shade::{face_paint, to_u8};
use crate::raster::{EMPTY, ZBuffer, zbuffer};
use crate::scene::Scene;
use crate::scene::analysis::{SceneAnalysis, analyse};

/// How pixels are coloured.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Fill {
    /// Flat shading under the scene's lights (by default the camera's key and fill lights).
    #[default]
    Shade,
    /// Face id + 1 as 24-bit RGB on black: the contract used to compare methods.
    Id,
}

/// A scene seen by a camera: analysed, projected, culled.
pub struct Prepared {
    pub analysis: SceneAnalysis,
    pub screen: ScreenScene,
}

/// Analyses and projects a scene.
pub fn prepare(scene: &Scene, camera: &Camera, cull: CullMode) -> Prepared {
    let analysis = analyse(scene);
    let screen = project(scene, &analysis, camera, cull);
    Prepared { analysis, screen }
}

/// Analyses, projects and z-buffers a scene. `progress` gets the number of polygons rasterized.
pub fn render_zbuffer(
    scene: &Scene,
    camera: &Camera,
    cull: CullMode,
    progress: impl FnMut(usize),
) -> (Prepared, ZBuffer) {
    let prepared = prepare(scene, camera, cull);
    let zb = zbuffer::render(&prepared.screen, progress);
    (prepared, zb)
}

/// The image of a z-buffer: row-major RGB, row 0 at the top.
pub fn colorize(
    scene: &Scene,
    screen: &ScreenScene,
    zb: &ZBuffer,
    camera: &Camera,
    fill: Fill,
    background: [u8; 3],
) -> Vec<[u8; 3]> {
    colorize_polys(scene, screen, &zb.poly, camera, fill, background)
}

/// The image of any per-pixel polygon index (`EMPTY` for background), as [`colorize`].
pub fn colorize_polys(
    scene: &Scene,
    screen: &ScreenScene,
    poly: &[u32],
    camera: &Camera,
    fill: Fill,
    background: [u8; 3],
) -> Vec<[u8; 3]> {
    // One colour per screen polygon, computed once.
    let colors: Vec<[u8; 3]> = screen
        .polys
        .iter()
        .map(|p| to_u8(face_paint(scene, p.face as usize, camera, fill).0))
        .collect();
    let background = match fill {
        Fill::Id => [0, 0, 0],
        Fill::Shade => background,
    };
    poly.iter()
        .map(|&p| {
            if p == EMPTY {
                background
            } else {
                colors[p as usize]
            }
        })
        .collect()
}

/// Do the screen bounding boxes of any two polygons overlap with positive area? (Newell's first
/// two tests fail for some pair: depth order matters.) Sweep over x; stops at the first pair.
pub fn screen_extents_overlap(screen: &ScreenScene) -> bool {
    let mut boxes: Vec<[i32; 4]> = screen
        .polys
        .iter()
        .map(|p| {
            let pts = screen.corners(p);
            let mut b = [i32::MAX, i32::MAX, i32::MIN, i32::MIN];
            for q in pts {
                b = [b[0].min(q.x), b[1].min(q.y), b[2].max(q.x), b[3].max(q.y)];
            }
            b
        })
        .collect();
    boxes.sort_unstable();
    let mut active: Vec<[i32; 4]> = Vec::new();
    for b in boxes {
        active.retain(|a| a[2] > b[0]);
        if active.iter().any(|a| a[1] < b[3] && b[1] < a[3]) {
            return true;
        }
        active.push(b);
    }
    false
}

/// How two face-id images differ.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct IdComparison {
    /// Pixels covered in either image.
    pub covered: usize,
    /// Covered pixels whose ids differ.
    pub covered_mismatch: usize,
    /// Pixels whose 3x3 neighbourhood (clipped to the image) holds one id in the reference.
    pub interior: usize,
    /// Interior pixels whose ids differ.
    pub interior_mismatch: usize,
}

/// Compares a method's face ids with a reference's, over covered and over interior pixels.
pub fn compare_ids(
    reference: &[Option<u32>],
    ids: &[Option<u32>],
    w: usize,
    h: usize,
) -> IdComparison {
    let mut c = IdComparison::default();
    for j in 0..h {
        for i in 0..w {
            let k = j * w + i;
            let differ = reference[k] != ids[k];
            if reference[k].is_some() || ids[k].is_some() {
                c.covered += 1;
                c.covered_mismatch += differ as usize;
            }
            let v = reference[k];
            let interior = (j.saturating_sub(1)..(j + 2).min(h))
                .all(|y| (i.saturating_sub(1)..(i + 2).min(w)).all(|x| reference[y * w + x] == v));
            if interior {
                c.interior += 1;
                c.interior_mismatch += differ as usize;
            }
        }
    }
    c
}
