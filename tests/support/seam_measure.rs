//! Measures of how an SVG drawing looks in an anti-aliasing viewer (resvg), for the seam tests
//! and `examples/seams.rs`.
//!
//! - [`alpha_area`]: the SVG rasterized onto transparency; the sum of alpha is the area it
//!   covers in pixels. Seams (background showing through shared boundaries) make it smaller than
//!   the exact visible area, outlines drawn outside the silhouette make it larger.
//! - [`seam_defects`]: over white, the pixels inside the silhouette whose colour no z-buffer
//!   colour around them explains.
#![allow(dead_code)]

use resvg::{tiny_skia, usvg};

/// Premultiplied RGBA pixels of `svg` at its own size (`w` x `h`), anti-aliased.
pub fn rasterize(svg: &str, w: u32, h: u32) -> Vec<[u8; 4]> {
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default()).expect("valid SVG");
    let mut pixmap = tiny_skia::Pixmap::new(w, h).expect("non-empty image");
    resvg::render(
        &tree,
        tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    pixmap
        .data()
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect()
}

/// The covered area of a background-less SVG: the sum of alpha over its pixels, in pixels.
pub fn alpha_area(svg: &str, w: u32, h: u32) -> f64 {
    rasterize(svg, w, h)
        .iter()
        .map(|p| p[3] as f64 / 255.0)
        .sum()
}

/// The area of a set of items' rings (outer ring then holes, even-odd, disjoint items), by the
/// shoelace formula.
pub fn rings_area<'a>(rings: impl IntoIterator<Item = &'a Vec<[f64; 2]>>) -> f64 {
    rings
        .into_iter()
        .map(|ring| {
            let n = ring.len();
            let twice: f64 = (0..n)
                .map(|k| {
                    let (p, q) = (ring[k], ring[(k + 1) % n]);
                    p[0] * q[1] - q[0] * p[1]
                })
                .sum();
            twice / 2.0
        })
        // Holes run the other way round from their outer ring: signed areas subtract them.
        .sum::<f64>()
        .abs()
}

/// Seam defects of an RGB image (over white) against the z-buffer's flat colours `reference`
/// and its covered pixels `covered`: (pixels inside the silhouette, defects as the issue counts
/// them, defects outside the colours' box). A pixel is inside when its 3x3 neighbourhood is
/// covered. A defect differs by more than 24 in R+G+B from all nine reference colours around
/// it; a box defect is farther than 24 (R+G+B) from the per-channel range of those nine
/// colours, so a blend of neighbouring colours (an anti-aliased crease) is not one, and a blend
/// with the background (a seam) is.
pub fn seam_defects(
    image: &[[u8; 3]],
    reference: &[[u8; 3]],
    covered: &[bool],
    w: usize,
    h: usize,
) -> (usize, usize, usize) {
    let (mut inside, mut defects, mut box_defects) = (0, 0, 0);
    for j in 1..h.saturating_sub(1) {
        for i in 1..w.saturating_sub(1) {
            let around: Vec<usize> = (j - 1..=j + 1)
                .flat_map(|y| (i - 1..=i + 1).map(move |x| y * w + x))
                .collect();
            if !around.iter().all(|&k| covered[k]) {
                continue;
            }
            inside += 1;
            let px = image[j * w + i];
            let dist =
                |c: [u8; 3]| -> i32 { (0..3).map(|ch| (px[ch] as i32 - c[ch] as i32).abs()).sum() };
            if around.iter().all(|&k| dist(reference[k]) > 24) {
                defects += 1;
            }
            let outside_box: i32 = (0..3)
                .map(|ch| {
                    let lo = around.iter().map(|&k| reference[k][ch]).min().unwrap() as i32;
                    let hi = around.iter().map(|&k| reference[k][ch]).max().unwrap() as i32;
                    let v = px[ch] as i32;
                    (lo - v).max(v - hi).max(0)
                })
                .sum();
            if outside_box > 24 {
                if std::env::var("DIAG").is_ok() && box_defects < 12 {
                    eprintln!(
                        "box defect at ({i}, {j}): {px:?} vs {:?}",
                        around.iter().map(|&k| reference[k]).collect::<Vec<_>>()
                    );
                }
                box_defects += 1;
            }
        }
    }
    (inside, defects, box_defects)
}

/// Un-premultiplied RGB of a pixmap composited over white.
pub fn over_white(rgba: &[[u8; 4]]) -> Vec<[u8; 3]> {
    rgba.iter()
        .map(|p| {
            // Premultiplied: colour + white · (1 - alpha).
            let a = p[3] as u32;
            [0, 1, 2].map(|c| (p[c] as u32 + (255 - a)).min(255) as u8)
        })
        .collect()
}
