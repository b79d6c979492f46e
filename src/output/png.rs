//! PNG encoding (png crate): 8-bit RGB colour images and 16-bit grey depth images, streamed row
//! by row into any writer, so an image never needs to be held whole in memory to be encoded.
//!
//! Every PNG is encoded alike: fast deflate with adaptive filtering (the `image` crate's
//! defaults, which these files used before streaming), IDAT chunks of `CHUNK_BYTES`.

use std::io::{self, Write};

/// Compressed bytes per IDAT chunk.
const CHUNK_BYTES: usize = 1 << 16;

/// Writes a `width` x `height` 8-bit RGB PNG into `out`, its pixels given by `rows`: `rows`
/// passes the image's pixels, row-major from the top, to the sink it is given, in pieces of any
/// size (whole rows or not). An error if fewer pixels are given than the image has.
pub fn write_rgb_rows(
    out: &mut dyn Write,
    width: u32,
    height: u32,
    rows: impl FnOnce(&mut dyn FnMut(&[[u8; 3]]) -> io::Result<()>) -> io::Result<()>,
) -> io::Result<()> {
    let mut bytes = Vec::new();
    let format = (png::ColorType::Rgb, png::BitDepth::Eight);
    write_stream(out, width, height, format, |stream| {
        rows(&mut |pixels| {
            bytes.clear();
            bytes.extend(pixels.iter().flatten());
            stream.write_all(&bytes)
        })
    })
}

/// Writes row-major RGB pixels (row 0 at the top) as a PNG into `out`.
pub fn write_rgb(
    out: &mut dyn Write,
    width: u32,
    height: u32,
    pixels: &[[u8; 3]],
) -> io::Result<()> {
    check_len(pixels.len(), width, height)?;
    write_rgb_rows(out, width, height, |sink| {
        pixels.chunks(width.max(1) as usize).try_for_each(sink)
    })
}

/// Writes normalized depths in [0, 1] as a 16-bit grey PNG into `out`: `round(depth · 65535)`.
pub fn write_depth16(
    out: &mut dyn Write,
    width: u32,
    height: u32,
    depth: &[f64],
) -> io::Result<()> {
    check_len(depth.len(), width, height)?;
    let mut row = Vec::new();
    let format = (png::ColorType::Grayscale, png::BitDepth::Sixteen);
    write_stream(out, width, height, format, |stream| {
        depth.chunks(width.max(1) as usize).try_for_each(|depths| {
            row.clear();
            row.extend(depths.iter().flat_map(|&d| depth_to_u16(d).to_be_bytes()));
            stream.write_all(&row)
        })
    })
}

/// A PNG of this format whose raw (unfiltered) image bytes `data` writes into the stream it is
/// given, row after row.
fn write_stream(
    out: &mut dyn Write,
    width: u32,
    height: u32,
    (color, depth): (png::ColorType, png::BitDepth),
    data: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> io::Result<()> {
    let mut encoder = png::Encoder::new(out, width, height);
    encoder.set_color(color);
    encoder.set_depth(depth);
    encoder.set_compression(png::Compression::Fast);
    encoder.set_filter(png::Filter::Adaptive);
    let mut png = encoder.write_header().map_err(to_io)?;
    let mut stream = png.stream_writer_with_size(CHUNK_BYTES).map_err(to_io)?;
    data(&mut stream)?;
    stream.finish().map_err(to_io)?;
    png.finish().map_err(to_io)
}

/// A normalized depth as the 16-bit value written to depth PNGs.
pub fn depth_to_u16(d: f64) -> u16 {
    (d.clamp(0.0, 1.0) * 65535.0).round() as u16
}

fn check_len(len: usize, width: u32, height: u32) -> io::Result<()> {
    if len as u64 == width as u64 * height as u64 {
        Ok(())
    } else {
        Err(io::Error::other(
            "pixel count does not match the image size",
        ))
    }
}

/// The png crate's errors as I/O errors, keeping the kind of a real I/O error (a closed pipe
/// must stay recognisable).
fn to_io(e: png::EncodingError) -> io::Error {
    match e {
        png::EncodingError::IoError(e) => e,
        other => io::Error::other(format!("PNG encoding failed: {other}")),
    }
}
