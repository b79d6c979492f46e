//! The stages chained: scene + camera → analysis → screen polygons → z-buffer → image.
//! The CLI, the tests and the benchmarks all go through here, so they run the same code.

use crate::camera::Camera;
use crate::paint::{Paint, screen_paints, to_u8};
use crate::project::{CullMode, ScreenScene, project};
use crate::raster::{EMPTY, ZBuffer, zbuffer};
use crate::scene::Scene;
use crate::scene::analysis::{SceneAnalysis, analyse};

pub use crate::paint::Fill;

/// A scene seen by a camera: analysed, projected, culled.
pub struct Prepared {
    /// Camera-independent facts: closed meshes, translucency, overlapping meshes.
    pub analysis: SceneAnalysis,
    /// The faces the camera sees, projected and snapped to the exact grid.
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
    colorize_painted(
        &screen_paints(scene, screen, camera, fill),
        poly,
        fill,
        background,
    )
}

/// [`colorize_polys`] with the polygons' paints already made ([`screen_paints`]).
pub fn colorize_painted(
    paints: &[Paint],
    poly: &[u32],
    fill: Fill,
    background: [u8; 3],
) -> Vec<[u8; 3]> {
    // One 8-bit colour per screen polygon, converted once.
    let colors: Vec<[u8; 3]> = paints.iter().map(|p| to_u8(p.color)).collect();
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
    let boxes: Vec<[i64; 4]> = screen
        .polys
        .iter()
        .map(|p| {
            let pts = screen.corners(p);
            let mut b = [i64::MAX, i64::MAX, i64::MIN, i64::MIN];
            for q in pts {
                b = [b[0].min(q.x), b[1].min(q.y), b[2].max(q.x), b[3].max(q.y)];
            }
            b
        })
        .collect();
    let mut overlap = false;
    crate::visibility::grid::sweep_overlapping(&boxes, |_, _| {
        overlap = true;
        false
    });
    overlap
}

/// How two face-id images differ.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct IdComparison {
    /// Pixels covered in either image.
    pub covered: usize,
    /// Covered pixels whose ids differ.
    pub covered_mismatch: usize,
    /// Pixels the reference covers whose 3x3 neighbourhood (clipped to the image) holds one face
    /// id and no background in the reference: a subset of the covered pixels.
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
            // Background around background is not interior: only covered pixels count.
            let interior = v.is_some()
                && (j.saturating_sub(1)..(j + 2).min(h)).all(|y| {
                    (i.saturating_sub(1)..(i + 2).min(w)).all(|x| reference[y * w + x] == v)
                });
            if interior {
                c.interior += 1;
                c.interior_mismatch += differ as usize;
            }
        }
    }
    c
}

/// Colour of a pixel where the two images cover different faces.
pub const DIFF_MISMATCH: [u8; 3] = [255, 0, 0];
/// Colour of a pixel that only one of the two images covers.
pub const DIFF_COVERAGE: [u8; 3] = [0, 96, 255];

/// A picture of where `ids` differs from `reference` (row-major RGB): [`DIFF_MISMATCH`] where both
/// cover the pixel with different faces, [`DIFF_COVERAGE`] where only one covers it; elsewhere
/// the reference in grey, one level per face id (so face boundaries show), background white.
pub fn diff_image(reference: &[Option<u32>], ids: &[Option<u32>]) -> Vec<[u8; 3]> {
    reference
        .iter()
        .zip(ids)
        .map(|(r, m)| match (r, m) {
            (Some(a), Some(b)) if a != b => DIFF_MISMATCH,
            (Some(_), None) | (None, Some(_)) => DIFF_COVERAGE,
            (Some(id), _) => diff_grey(*id),
            (None, None) => [255; 3],
        })
        .collect()
}

/// The grey a face is drawn in under a difference picture's marks: one level per face id in
/// 96..=207 (a hash of the id, so neighbouring faces differ and face boundaries show).
pub fn diff_grey(id: u32) -> [u8; 3] {
    let g = 96 + (id.wrapping_mul(0x9E37_79B1) >> 24) % 112;
    [g as u8; 3]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An 8x8 reference with face 7 on the 4x4 block at (2..6, 2..6).
    fn block() -> Vec<Option<u32>> {
        (0..64)
            .map(|k| {
                let (i, j) = (k % 8, k / 8);
                ((2..6).contains(&i) && (2..6).contains(&j)).then_some(7)
            })
            .collect()
    }

    /// Interior pixels are covered ones: the 2x2 middle of the block, never the background.
    #[test]
    fn interior_pixels_are_covered_pixels_away_from_edges() {
        let r = block();
        let c = compare_ids(&r, &r, 8, 8);
        assert_eq!((c.covered, c.interior), (16, 4));
        assert_eq!((c.covered_mismatch, c.interior_mismatch), (0, 0));
        // A wrong id in the middle is an interior mismatch; a stray pixel on the background is a
        // covered mismatch only.
        let mut m = r.clone();
        m[3 * 8 + 3] = Some(9);
        m[0] = Some(7);
        let c = compare_ids(&r, &m, 8, 8);
        assert_eq!((c.covered, c.covered_mismatch), (17, 2));
        assert_eq!((c.interior, c.interior_mismatch), (4, 1));
    }

    #[test]
    fn diff_image_marks_mismatch_and_coverage() {
        let r = block();
        let mut m = r.clone();
        m[3 * 8 + 3] = Some(9);
        m[0] = Some(7);
        m[2 * 8 + 2] = None;
        let d = diff_image(&r, &m);
        assert_eq!(d[3 * 8 + 3], DIFF_MISMATCH);
        assert_eq!(d[0], DIFF_COVERAGE);
        assert_eq!(d[2 * 8 + 2], DIFF_COVERAGE);
        assert_eq!(d[1], [255; 3], "background");
        let g = d[4 * 8 + 4];
        assert!(
            g[0] == g[1] && g[1] == g[2] && (96..208).contains(&g[0]),
            "{g:?}"
        );
    }
}
