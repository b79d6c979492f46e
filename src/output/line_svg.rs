//! SVG output of a hidden-line drawing ([`LineDrawing`]), standalone ([`write_line_svg`]) or laid
//! over a filled drawing ([`write_line_layers`], `render --lines`).
//!
//! Invariants:
//! - **Layers by class**: one `<g class="VISIBILITY KIND">` per (visibility, kind) that has
//!   strokes, hidden groups first (drawn under the visible ones), kinds in [`LineKind::ALL`]
//!   order; within a group one `<path data-kind="KIND">` per stroke, in the drawing's order.
//!   No style is written on groups or paths: one `<style>` element styles them by class, so a
//!   reader restyles the drawing by editing or overriding its rules.
//! - **No second rounding**: coordinates are written with [`num`], the shortest decimal that
//!   parses back to the same f64 (never through f32), as the filled SVG writes them.
//! - **ISO 128 weights by default**: visible lines 0.5 mm, hidden lines 0.25 mm (2:1) and dashed
//!   as ISO 128 line type 02 (dashes 12·d, gaps 3·d for a line width d, as drawn: the dash
//!   array is shortened by the round caps), in CSS pixels (96 per inch). Paths carry
//!   `vector-effect: non-scaling-stroke`, so widths stay the same however the drawing is
//!   scaled by a viewer that implements it; the widths are also plain lengths in user units,
//!   and one user unit is one pixel, so viewers that ignore it (resvg, and so PDF through
//!   svg2pdf) draw the same widths at the drawing's own size.
//! - **Deterministic**: the same drawing and options give the same bytes.
//!
//! The README's "Output contract" lists every element, class and attribute.

use super::svg::{background, num, pixel_document};
use super::svg_stream::SvgStream;
use crate::lines::{LineDrawing, LineKind, Stroke, Visibility};
use ::svg::node::element::{Group, Style};
use std::fmt::Write;

/// CSS pixels per millimetre (96 per inch).
pub const PX_PER_MM: f64 = 96.0 / 25.4;

/// ISO 128 line type 02 (dashed): dash length, in line widths.
pub const ISO_DASH: f64 = 12.0;

/// ISO 128 line type 02 (dashed): gap length, in line widths.
pub const ISO_GAP: f64 = 3.0;

/// How a line drawing is styled.
#[derive(Clone, Debug, PartialEq)]
pub struct LineSvgOptions {
    /// Width of visible lines, CSS pixels (default 0.5 mm).
    pub visible_width: f64,
    /// Width of hidden lines, CSS pixels (default 0.25 mm, half the visible width).
    pub hidden_width: f64,
    /// A rectangle of this colour (linear RGB, 0 to 1) behind the lines; `None` (the default):
    /// nothing, so that the lines can be laid over other content.
    pub background: Option<[f64; 3]>,
}

impl Default for LineSvgOptions {
    fn default() -> Self {
        LineSvgOptions {
            visible_width: 0.5 * PX_PER_MM,
            hidden_width: 0.25 * PX_PER_MM,
            background: None,
        }
    }
}

impl LineSvgOptions {
    /// The dash array of hidden lines, `[dash, gap]` in CSS pixels: ISO 128's 12·d and 3·d as
    /// drawn, that is less and more by the line width that the two round caps of a dash add.
    pub fn hidden_dashes(&self) -> [f64; 2] {
        let d = self.hidden_width;
        [(ISO_DASH - 1.0) * d, (ISO_GAP + 1.0) * d]
    }

    /// The `<style>` rules: line colour and caps for both visibilities, then each one's width
    /// (and the hidden dashes), then the non-scaling stroke of every line path.
    fn css(&self) -> String {
        let [dash, gap] = self.hidden_dashes();
        format!(
            ".visible,.hidden{{fill:none;stroke:#000000;stroke-linecap:round;stroke-linejoin:round}}\n\
             .visible{{stroke-width:{}px}}\n\
             .hidden{{stroke-width:{}px;stroke-dasharray:{}px {}px}}\n\
             .visible path,.hidden path{{vector-effect:non-scaling-stroke}}",
            num(self.visible_width),
            num(self.hidden_width),
            num(dash),
            num(gap)
        )
    }
}

/// The standalone SVG document of `drawing`: size and viewBox in pixels, the style, the
/// background if asked for, then the line layers.
pub fn write_line_svg(drawing: &LineDrawing, options: &LineSvgOptions) -> String {
    let (w, h) = (drawing.width, drawing.height);
    let mut out = Vec::new();
    let mut s = SvgStream::new(&mut out, pixel_document(w, h));
    let written = (|| {
        if let Some(bg) = options.background {
            s.child(background(w, h, bg))?;
        }
        write_line_layers(&mut s, drawing, options)?;
        s.finish()
    })();
    written.expect("writing into memory cannot fail");
    String::from_utf8(out).expect("the document is UTF-8")
}

/// Writes the line layers of `drawing` into the open document `s`, over what it holds: the
/// `<style>` and one group per (visibility, kind), hidden first. `options.background` is not
/// drawn here (the document has its own).
pub fn write_line_layers(
    s: &mut SvgStream,
    drawing: &LineDrawing,
    options: &LineSvgOptions,
) -> std::io::Result<()> {
    s.child(Style::new(options.css()))?;
    for visibility in [Visibility::Hidden, Visibility::Visible] {
        for kind in LineKind::ALL {
            let mut strokes = drawing
                .strokes
                .iter()
                .filter(|s| (s.visibility, s.kind) == (visibility, kind))
                .peekable();
            if strokes.peek().is_none() {
                continue;
            }
            s.open(Group::new().set("class", format!("{} {}", visibility.name(), kind.name())))?;
            for stroke in strokes {
                let d = path_data(stroke);
                s.leaf("path", &mut [("d", &d), ("data-kind", kind.name())])?;
            }
            s.close()?;
        }
    }
    Ok(())
}

/// `Mx yLx y...`, then `Z` for a closed stroke; every coordinate by [`num`].
fn path_data(stroke: &Stroke) -> String {
    let mut d = String::new();
    for (k, p) in stroke.points.iter().enumerate() {
        debug_assert!(p[0].is_finite() && p[1].is_finite());
        let cmd = if k == 0 { 'M' } else { 'L' };
        let _ = write!(d, "{cmd}{} {}", num(p[0]), num(p[1]));
    }
    if stroke.closed {
        d.push('Z');
    }
    d
}
