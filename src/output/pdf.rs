//! PDF output of an SVG document through `svg2pdf` (and `usvg`, which parses the SVG).
//!
//! Invariants:
//! - **Vector**: paths stay paths, strokes keep their widths, caps, joins and dash arrays (a
//!   dashed SVG stroke is a PDF dash pattern, operator `d`); nothing is rasterized for what
//!   our writers produce (no filters, no images).
//! - **Size**: one page of the SVG's size at 96 CSS pixels per inch (a 1024 px wide drawing is
//!   768 pt, 10.67 in), so the lines' millimetre widths print as such.
//! - **Reproducible bytes**: svg2pdf writes no creation date and no document id; the same SVG
//!   gives the same bytes.
//! - **Text is never dropped in silence**. With the `pdf-text` feature, `<text>` is laid out
//!   with the system's fonts (loaded only when the SVG has text) and embedded as font subsets;
//!   a family that is not installed falls back to an installed serif font (the bytes then
//!   depend on the fonts installed), and a system with no font at all is an error. Without
//!   the feature (the default build: svg2pdf's text support takes minutes to compile) an SVG
//!   with text is an error saying so; usvg would leave the text out.

use crate::error::{Error, Result};
use svg2pdf::usvg;
use svg2pdf::{ConversionOptions, PageOptions};

/// CSS pixels per inch: the page is the SVG's size at this resolution.
const CSS_DPI: f32 = 96.0;

/// The PDF of `svg` (an SVG document's text).
pub fn pdf_of_svg(svg: &str) -> Result<Vec<u8>> {
    let mut options = usvg::Options::default();
    // `<text` also starts `<textPath`, which is text too.
    if svg.contains("<text") {
        load_fonts(&mut options)?;
    }
    let tree = usvg::Tree::from_str(svg, &options)
        .map_err(|e| Error::Output(format!("SVG for PDF: {e}")))?;
    svg2pdf::to_pdf(
        &tree,
        ConversionOptions::default(),
        PageOptions { dpi: CSS_DPI },
    )
    .map_err(|e| Error::Output(format!("writing PDF: {e}")))
}

/// The system's fonts, for an SVG with text, with the generic families (`serif`, which usvg
/// falls back to when no family asked for is installed, `sans-serif`, `monospace`) mapped to
/// installed fonts: usvg's defaults (Times New Roman, Arial, Courier New) are often missing,
/// and text in no installed font would be dropped.
#[cfg(feature = "pdf-text")]
fn load_fonts(options: &mut usvg::Options) -> Result<()> {
    let fonts = options.fontdb_mut();
    fonts.load_system_fonts();
    let mut families: Vec<String> = fonts
        .faces()
        .flat_map(|face| face.families.iter().map(|(name, _)| name.clone()))
        .collect();
    // Sorted: the order fonts are found in depends on the file system.
    families.sort();
    families.dedup();
    let pick = |preferred: &[&str]| {
        preferred
            .iter()
            .map(|p| p.to_string())
            .find(|p| families.contains(p))
            .or_else(|| families.first().cloned())
    };
    let (Some(serif), Some(sans), Some(mono)) = (
        pick(&[
            "DejaVu Serif",
            "Liberation Serif",
            "Times New Roman",
            "Noto Serif",
        ]),
        pick(&[
            "DejaVu Sans",
            "Liberation Sans",
            "Arial",
            "Helvetica",
            "Noto Sans",
        ]),
        pick(&[
            "DejaVu Sans Mono",
            "Liberation Mono",
            "Courier New",
            "Noto Sans Mono",
        ]),
    ) else {
        return Err(Error::Output(
            "PDF: the SVG has text, and no system font was found to write it with".into(),
        ));
    };
    fonts.set_serif_family(serif);
    fonts.set_sans_serif_family(sans);
    fonts.set_monospace_family(mono);
    Ok(())
}

/// This build writes no text to PDF.
#[cfg(not(feature = "pdf-text"))]
fn load_fonts(_options: &mut usvg::Options) -> Result<()> {
    Err(Error::Output(
        "PDF: the SVG has text, and this build of sightline writes no text to PDF (build it \
         with `--features pdf-text`)"
            .into(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_svg_that_does_not_parse_is_an_error() {
        let e = pdf_of_svg("<svg").unwrap_err().to_string();
        assert!(e.starts_with("SVG for PDF: "), "{e}");
    }
}
