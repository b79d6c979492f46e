//! Reading a face-id image (the `--fill id` colour contract) from a PNG made by any renderer.
//!
//! The contract: each pixel holds the id of the face seen at its centre plus one, as a 24-bit
//! number in RGB (`r = (id+1)>>16 & 255`, `g = (id+1)>>8 & 255`, `b = (id+1) & 255`,
//! [`crate::paint::id_color`]); black is the background. Values are taken as stored: no gamma,
//! ICC profile or other colour management is applied, as none is in writing them.
//!
//! Accepted: 8-bit RGB; 8-bit RGBA whose alpha is 255 (a face or black) or 0 (background,
//! whatever the colour: a renderer's transparent film); palette images (their entries are
//! exact 8-bit colours), with the same alpha rule for a `tRNS` chunk; an RGB image's `tRNS`
//! colour key is background. Refused, with the file and what was found: 16-bit channels (not
//! the contract's 8-bit values), grey images (not 24-bit ids), and any alpha strictly between
//! 0 and 255, which only blending or anti-aliasing makes (the first such pixel is named).
//! Invariant: a successful read holds one entry per pixel, `None` exactly for background.

use crate::camera::MAX_IMAGE_SIDE;
use crate::error::{Error, LoadError, Result};
use crate::paint::id_from_color;
use std::io::BufReader;
use std::path::Path;

/// A face-id image: the face id shown at each pixel, row-major, row 0 at the top.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IdImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `None` for background (black, or alpha 0), else the id the colour encodes.
    pub ids: Vec<Option<u32>>,
}

/// Reads a face-id PNG. See the module docs for what is accepted; every refusal is an error
/// naming `path`, never a panic.
pub fn read(path: &Path) -> Result<IdImage> {
    let name = path.display().to_string();
    let file = std::fs::File::open(path).map_err(|source| Error::Io {
        path: name.clone(),
        source,
    })?;
    let bad = |message: String| Error::Load(LoadError::file(&name, message));
    // Room for the largest image the camera allows, as RGBA, plus ancillary chunks.
    let limits = png::Limits {
        bytes: (MAX_IMAGE_SIDE as usize).pow(2) * 4 + (64 << 20),
    };
    let mut decoder = png::Decoder::new_with_limits(BufReader::new(file), limits);
    // Palette to RGB(A), tRNS to an alpha channel; 16-bit samples are kept (and refused).
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder
        .read_info()
        .map_err(|e| bad(format!("not a readable PNG: {e}")))?;
    let info = reader.info();
    let (width, height) = (info.width, info.height);
    let (color, depth) = (info.color_type, info.bit_depth);
    use png::ColorType::*;
    match color {
        Grayscale | GrayscaleAlpha => {
            return Err(bad(format!(
                "a grey PNG ({depth:?}-bit {color:?}): a face-id image is 8-bit RGB or RGBA, id + 1 in 24 bits (render --fill id)"
            )));
        }
        Rgb | Rgba if depth != png::BitDepth::Eight => {
            return Err(bad(format!(
                "a {}-bit {color:?} PNG: a face-id image has 8-bit channels (id + 1 in 24 bits, render --fill id)",
                depth as u8
            )));
        }
        _ => {}
    }
    if width > MAX_IMAGE_SIDE || height > MAX_IMAGE_SIDE {
        return Err(bad(format!(
            "{width}x{height} pixels: larger than {MAX_IMAGE_SIDE} on a side"
        )));
    }
    let (out_color, out_depth) = reader.output_color_type();
    let channels = match (out_color, out_depth) {
        (Rgb, png::BitDepth::Eight) => 3,
        (Rgba, png::BitDepth::Eight) => 4,
        (c, d) => {
            return Err(bad(format!(
                "a PNG that decodes to {}-bit {c:?}: a face-id image is 8-bit RGB or RGBA",
                d as u8
            )));
        }
    };
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| bad("too large to decode".into()))?;
    let mut buf = vec![0u8; size];
    let frame = reader
        .next_frame(&mut buf)
        .map_err(|e| bad(format!("not a readable PNG: {e}")))?;
    let stride = frame.line_size;
    let mut ids = Vec::with_capacity(width as usize * height as usize);
    for (j, row) in buf.chunks_exact(stride).take(height as usize).enumerate() {
        for (i, px) in row[..width as usize * channels]
            .chunks_exact(channels)
            .enumerate()
        {
            let alpha = if channels == 4 { px[3] } else { 255 };
            match alpha {
                255 => ids.push(id_from_color([px[0], px[1], px[2]])),
                0 => ids.push(None),
                a => {
                    return Err(bad(format!(
                        "pixel ({i}, {j}) (column, row from the top) has alpha {a}: partial alpha means blending or anti-aliasing, which a face-id image must not have (alpha 255 for faces and 0 or 255 for background)"
                    )));
                }
            }
        }
    }
    if ids.len() != width as usize * height as usize {
        return Err(bad("truncated image data".into()));
    }
    Ok(IdImage { width, height, ids })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::paint::id_color;

    /// Writes a PNG with the png crate's encoder; `setup` sets its format and chunks.
    fn write_png(
        path: &Path,
        w: u32,
        h: u32,
        data: &[u8],
        setup: impl FnOnce(&mut png::Encoder<'_, std::fs::File>),
    ) {
        let file = std::fs::File::create(path).unwrap();
        let mut enc = png::Encoder::new(file, w, h);
        setup(&mut enc);
        let mut writer = enc.write_header().unwrap();
        writer.write_image_data(data).unwrap();
    }

    fn rgb(enc: &mut png::Encoder<'_, std::fs::File>) {
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
    }

    #[test]
    fn rgb_ids_and_black_background_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ids.png");
        let ids = [
            None,
            Some(0),
            Some(255),
            Some(70_000),
            Some(0xFF_FFFE),
            None,
        ];
        let data: Vec<u8> = ids
            .iter()
            .flat_map(|id| id.map_or([0, 0, 0], id_color))
            .collect();
        write_png(&path, 3, 2, &data, rgb);
        let img = read(&path).unwrap();
        assert_eq!((img.width, img.height), (3, 2));
        assert_eq!(img.ids, ids);
    }

    #[test]
    fn rgba_alpha_zero_is_background_and_partial_alpha_is_refused_by_pixel() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ids.png");
        let rgba = |enc: &mut png::Encoder<'_, std::fs::File>| {
            enc.set_color(png::ColorType::Rgba);
            enc.set_depth(png::BitDepth::Eight);
        };
        // A coloured pixel with alpha 0 is background; alpha 255 keeps its id.
        write_png(&path, 2, 1, &[0, 0, 5, 0, 0, 0, 5, 255], rgba);
        assert_eq!(read(&path).unwrap().ids, vec![None, Some(4)]);
        // Partial alpha: refused, naming the file and the first such pixel.
        write_png(
            &path,
            2,
            2,
            &[0, 0, 5, 255, 0, 0, 5, 255, 0, 0, 5, 255, 0, 0, 5, 128],
            rgba,
        );
        let e = read(&path).unwrap_err().to_string();
        assert!(
            e.contains("ids.png") && e.contains("pixel (1, 1)") && e.contains("alpha 128"),
            "{e}"
        );
    }

    #[test]
    fn sixteen_bit_and_grey_images_are_refused_naming_what_was_found() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("deep.png");
        write_png(&path, 1, 1, &[0, 0, 0, 1, 0, 2], |enc| {
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Sixteen);
        });
        let e = read(&path).unwrap_err().to_string();
        assert!(e.contains("deep.png") && e.contains("16-bit Rgb"), "{e}");
        let path = dir.path().join("grey.png");
        write_png(&path, 1, 1, &[7], |enc| {
            enc.set_color(png::ColorType::Grayscale);
            enc.set_depth(png::BitDepth::Eight);
        });
        let e = read(&path).unwrap_err().to_string();
        assert!(e.contains("grey.png") && e.contains("grey PNG"), "{e}");
    }

    #[test]
    fn palette_entries_are_exact_colours_and_partial_transparency_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("pal.png");
        let palette = |trns: Option<Vec<u8>>| {
            move |enc: &mut png::Encoder<'_, std::fs::File>| {
                enc.set_color(png::ColorType::Indexed);
                enc.set_depth(png::BitDepth::Eight);
                enc.set_palette(vec![0, 0, 0, 0, 1, 2, 0, 0, 9]);
                if let Some(t) = trns {
                    enc.set_trns(t);
                }
            }
        };
        write_png(&path, 3, 1, &[0, 1, 2], palette(None));
        assert_eq!(read(&path).unwrap().ids, vec![None, Some(257), Some(8)]);
        // Entry 2 fully transparent: background.
        write_png(&path, 3, 1, &[0, 1, 2], palette(Some(vec![255, 255, 0])));
        assert_eq!(read(&path).unwrap().ids, vec![None, Some(257), None]);
        write_png(&path, 3, 1, &[0, 1, 2], palette(Some(vec![255, 200, 255])));
        let e = read(&path).unwrap_err().to_string();
        assert!(e.contains("pixel (1, 0)") && e.contains("alpha 200"), "{e}");
    }

    #[test]
    fn missing_and_corrupt_files_are_errors_naming_the_path() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("missing.png");
        let e = read(&missing).unwrap_err().to_string();
        assert!(e.contains("missing.png"), "{e}");
        let junk = dir.path().join("junk.png");
        std::fs::write(&junk, b"not a png at all").unwrap();
        let e = read(&junk).unwrap_err().to_string();
        assert!(
            e.contains("junk.png") && e.contains("not a readable PNG"),
            "{e}"
        );
        // A valid header cut short.
        let cut = dir.path().join("cut.png");
        write_png(&cut, 4, 4, &[9; 48], rgb);
        let bytes = std::fs::read(&cut).unwrap();
        std::fs::write(&cut, &bytes[..bytes.len() - 20]).unwrap();
        let e = read(&cut).unwrap_err().to_string();
        assert!(e.contains("cut.png"), "{e}");
    }
}
