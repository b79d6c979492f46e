//! PNG encoding (image crate): 8-bit RGB colour images and 16-bit grey depth images.

use crate::error::Error;
use image::{ImageBuffer, ImageFormat, Luma, Rgb};
use std::io::Cursor;

/// Encodes row-major RGB pixels (row 0 at the top) as PNG.
pub fn encode_rgb(width: u32, height: u32, pixels: Vec<[u8; 3]>) -> Result<Vec<u8>, Error> {
    let flat: Vec<u8> = pixels.into_iter().flatten().collect();
    let img = ImageBuffer::<Rgb<u8>, _>::from_raw(width, height, flat)
        .ok_or_else(|| Error::Output("pixel count does not match the image size".into()))?;
    encode(img)
}

/// Encodes normalized depths in [0, 1] as 16-bit grey: `round(depth · 65535)`.
pub fn encode_depth16(width: u32, height: u32, depth: &[f64]) -> Result<Vec<u8>, Error> {
    let px: Vec<u16> = depth.iter().map(|&d| depth_to_u16(d)).collect();
    let img = ImageBuffer::<Luma<u16>, _>::from_raw(width, height, px)
        .ok_or_else(|| Error::Output("pixel count does not match the image size".into()))?;
    encode(img)
}

/// A normalized depth as the 16-bit value written to depth PNGs.
pub fn depth_to_u16(d: f64) -> u16 {
    (d.clamp(0.0, 1.0) * 65535.0).round() as u16
}

fn encode<P>(img: ImageBuffer<P, Vec<P::Subpixel>>) -> Result<Vec<u8>, Error>
where
    P: image::Pixel + image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
{
    let mut out = Cursor::new(Vec::new());
    img.write_to(&mut out, ImageFormat::Png)
        .map_err(|e| Error::Output(format!("PNG encoding failed: {e}")))?;
    Ok(out.into_inner())
}
