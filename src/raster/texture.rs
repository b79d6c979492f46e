//! Textures: a mipmap pyramid with level selection from the screen-space derivatives of (u, v)
//! and trilinear filtering (seed 002).
//!
//! Invariants:
//! - level 0 is the image; level k+1 is level k averaged over 2x2 blocks (a side of odd length
//!   rounds up, the missing row or column repeating the last), down to 1x1, so every level's
//!   average colour is the image's (exactly, for power-of-two sides);
//! - texture coordinates wrap (repeat); v = 0 is the bottom row of the image (OBJ and X3D);
//!   texel (x, y) of a w x h level has its centre at u = (x + 0.5)/w, v = 1 - (y + 0.5)/h, and a
//!   sample at a texel centre returns that texel exactly;
//! - the level of detail is `D = log2 L`, `L = max(|∂(u,v)/∂x|, |∂(u,v)/∂y|)` in texels of level
//!   0 per pixel; trilinear filtering blends levels ⌊D⌋ and ⌊D⌋+1 by the fraction of D (clamped
//!   to the pyramid; D < 0, magnification, uses level 0 alone).
//!
//! Colours are 8-bit values / 255, taken as they are (no sRGB decoding), like material colours.

use std::path::Path;

/// One level of the pyramid: RGB in [0, 1], row-major, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    /// Width in texels.
    pub width: usize,
    /// Height in texels.
    pub height: usize,
    /// `width · height` colours.
    pub texels: Vec<[f64; 3]>,
}

/// A mipmapped texture.
#[derive(Clone, Debug, PartialEq)]
pub struct Mipmap {
    /// The full-size image first, then each level half the size of the one before
    /// (rounded up), down to 1x1.
    pub levels: Vec<Level>,
}

impl Level {
    fn at(&self, x: i64, y: i64) -> [f64; 3] {
        // Repeat addressing.
        let x = x.rem_euclid(self.width as i64) as usize;
        let y = y.rem_euclid(self.height as i64) as usize;
        self.texels[y * self.width + x]
    }

    /// Bilinear sample at (u, v), wrapping.
    pub fn bilinear(&self, u: f64, v: f64) -> [f64; 3] {
        let x = u * self.width as f64 - 0.5;
        let y = (1.0 - v) * self.height as f64 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let (a, b) = (self.at(x0, y0), self.at(x0 + 1, y0));
        let (c, d) = (self.at(x0, y0 + 1), self.at(x0 + 1, y0 + 1));
        std::array::from_fn(|k| {
            let top = a[k] + (b[k] - a[k]) * fx;
            let bottom = c[k] + (d[k] - c[k]) * fx;
            top + (bottom - top) * fy
        })
    }

    /// The next level: 2x2 box average.
    fn half(&self) -> Level {
        let (w, h) = (
            self.width.div_ceil(2).max(1),
            self.height.div_ceil(2).max(1),
        );
        let mut texels = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let (x0, y0) = (2 * x, 2 * y);
                let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
                let t = [
                    self.texels[y0 * self.width + x0],
                    self.texels[y0 * self.width + x1],
                    self.texels[y1 * self.width + x0],
                    self.texels[y1 * self.width + x1],
                ];
                texels.push(std::array::from_fn(|k| {
                    (t[0][k] + t[1][k] + t[2][k] + t[3][k]) / 4.0
                }));
            }
        }
        Level {
            width: w,
            height: h,
            texels,
        }
    }
}

/// The level of detail of seed 002 from the derivatives of (u, v) per pixel, already in texels
/// of level 0: `(L, D)` with `L = max(√(dudx² + dvdx²), √(dudy² + dvdy²))` and `D = log2 L`.
pub fn level_of_detail(dudx: f64, dvdx: f64, dudy: f64, dvdy: f64) -> (f64, f64) {
    let l = dudx.hypot(dvdx).max(dudy.hypot(dvdy));
    (l, l.log2())
}

impl Mipmap {
    /// The pyramid of an image given as RGB rows (row 0 at the top).
    pub fn new(width: usize, height: usize, texels: Vec<[f64; 3]>) -> Mipmap {
        assert!(width > 0 && height > 0 && texels.len() == width * height);
        let mut levels = vec![Level {
            width,
            height,
            texels,
        }];
        while levels.last().is_some_and(|l| l.width > 1 || l.height > 1) {
            let next = levels.last().unwrap().half();
            levels.push(next);
        }
        Mipmap { levels }
    }

    /// Reads an image file (any format the `image` crate was built with: PNG).
    pub fn load(path: &Path) -> Result<Mipmap, String> {
        let img = image::open(path)
            .map_err(|e| format!("texture {}: {e}", path.display()))?
            .to_rgb8();
        let (w, h) = (img.width() as usize, img.height() as usize);
        if w == 0 || h == 0 {
            return Err(format!("texture {}: empty image", path.display()));
        }
        let texels = img
            .pixels()
            .map(|p| p.0.map(|c| c as f64 / 255.0))
            .collect();
        Ok(Mipmap::new(w, h, texels))
    }

    /// Width of the full-size image.
    pub fn width(&self) -> usize {
        self.levels[0].width
    }

    /// Height of the full-size image.
    pub fn height(&self) -> usize {
        self.levels[0].height
    }

    /// The level of detail at a pixel from the derivatives of (u, v) per pixel, in uv units.
    pub fn lod(&self, dudx: f64, dvdx: f64, dudy: f64, dvdy: f64) -> f64 {
        let (w, h) = (self.width() as f64, self.height() as f64);
        level_of_detail(dudx * w, dvdx * h, dudy * w, dvdy * h).1
    }

    /// Trilinear sample at (u, v) with level of detail `d` (see the module docs).
    pub fn trilinear(&self, u: f64, v: f64, d: f64) -> [f64; 3] {
        let last = self.levels.len() - 1;
        if d.is_nan() || d <= 0.0 {
            // Magnification, or no usable derivative (NaN): the finest level.
            return self.levels[0].bilinear(u, v);
        }
        let l0 = (d.floor() as usize).min(last);
        if l0 == last {
            return self.levels[last].bilinear(u, v);
        }
        let f = d - d.floor();
        let a = self.levels[l0].bilinear(u, v);
        let b = self.levels[l0 + 1].bilinear(u, v);
        std::array::from_fn(|k| a[k] + (b[k] - a[k]) * f)
    }
}
