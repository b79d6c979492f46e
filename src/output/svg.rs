//! SVG output of a [`Drawing`]: one `<path>` per item, in painter order.
//!
//! Invariants:
//! - **No second rounding**: every coordinate is written with Rust's shortest round-trip f64
//!   formatting, so parsing the file back gives the drawing's f64 values bit for bit (-0 is
//!   written as 0). The `svg` crate would store path numbers as f32 (about 7 digits), so the path
//!   data string is built here and handed to it whole.
//! - **Provenance**: every path carries `data-face="ID"`, the input face id of its item; a region
//!   merged from coplanar faces of one paint also lists them all, `data-faces="ID ID ..."`.
//! - **Fill**: `fill-rule="evenodd"` (holes are rings of the same path), `fill="#rrggbb"` (8-bit,
//!   rounded), `fill-opacity` only when below 1.
//! - **Deterministic**: the same drawing and options give the same bytes (the `svg` crate writes
//!   attributes sorted by name).
//! - **Streamed**: elements are written as they are made ([`super::svg_stream`]); the document
//!   never exists whole in memory, only one path's text at a time.
//!
//! Paths are written as the drawing has them: canonicalize it first
//! ([`super::canonical::canonicalize`], as the CLI does) for bytes that depend only on what is
//! drawn. The README's "Output contract" lists every element and attribute.

use super::drawing::{Drawing, Seams};
use super::line_svg::{LineSvgOptions, write_line_layers};
use super::svg_stream::SvgStream;
use crate::lines::LineDrawing;
use crate::paint::to_u8;
use ::svg::Document;
use ::svg::node::element::{ClipPath, Definitions, Group, Path, Rectangle};
use std::fmt::Write;

/// How the SVG is written.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SvgOptions {
    /// Outline every region with this colour (linear RGB, 0 to 1) and width (pixels).
    pub stroke: Option<([f64; 3], f64)>,
    /// `shape-rendering="crispEdges"`: no anti-aliasing in viewers that honour it, so face-id
    /// colours stay exact up to the region edges.
    pub crisp: bool,
}

/// The SVG document of `drawing`. Coordinates must be finite (as every [`Drawing`] keeps them).
pub fn write_svg(drawing: &Drawing, options: &SvgOptions) -> String {
    let mut out = Vec::new();
    write_document(&mut out, drawing, options, None).expect("writing into memory cannot fail");
    String::from_utf8(out).expect("the document is UTF-8")
}

/// Writes the SVG document of `drawing` to `out` as it goes (see [`super::svg_stream`]), with
/// `lines` laid over it when given (as `render --lines` does, [`write_line_layers`]).
pub fn write_document(
    out: &mut dyn std::io::Write,
    drawing: &Drawing,
    options: &SvgOptions,
    lines: Option<(&LineDrawing, &LineSvgOptions)>,
) -> std::io::Result<()> {
    let (w, h) = (drawing.width, drawing.height);
    let mut doc = pixel_document(w, h);
    if options.crisp {
        doc = doc.set("shape-rendering", "crispEdges");
    }
    let mut s = SvgStream::new(out, doc);
    if let Some(bg) = drawing.background {
        s.child(background(w, h, bg))?;
    }
    if !drawing.seams.is_empty() {
        write_seams(&mut s, &drawing.seams)?;
    }
    // Outlines go on one group rather than on every path: the same look, fewer bytes.
    let mut group = Group::new();
    if let Some((color, width)) = options.stroke {
        group = group
            .set("stroke", hex(color))
            .set("stroke-width", num(width))
            .set("stroke-linejoin", "round");
    }
    s.open(group)?;
    for item in &drawing.items {
        let mut d = String::new();
        write_rings(&mut d, &item.rings, push_num);
        let mut path = Path::new()
            .set("d", d)
            .set("fill", hex(item.color))
            .set("fill-rule", "evenodd")
            .set("data-face", item.face);
        if !item.merged.is_empty() {
            let all: Vec<String> = std::iter::once(item.face)
                .chain(item.merged.iter().copied())
                .map(|f| f.to_string())
                .collect();
            path = path.set("data-faces", all.join(" "));
        }
        if item.opacity < 1.0 {
            path = path.set("fill-opacity", num(item.opacity.max(0.0)));
        }
        s.child(path)?;
    }
    s.close()?;
    if let Some((lines, line_options)) = lines {
        write_line_layers(&mut s, lines, line_options)?;
    }
    s.finish()
}

/// The root of a document `w` x `h` pixels, one user unit a pixel.
pub(super) fn pixel_document(w: u32, h: u32) -> Document {
    Document::new()
        .set("viewBox", format!("0 0 {w} {h}"))
        .set("width", w)
        .set("height", h)
}

/// A rectangle of `color` over the whole document, `w` x `h` pixels.
pub(super) fn background(w: u32, h: u32, color: [f64; 3]) -> Rectangle {
    Rectangle::new()
        .set("width", w)
        .set("height", h)
        .set("fill", hex(color))
}

/// Width of the seam strokes, in screen pixels whatever the zoom (`non-scaling-stroke`): wide
/// enough that two anti-aliased edges crossing a pixel at any angle leave nothing of it
/// uncovered (1 px leaves up to 9 % of a pixel on a diagonal edge).
pub const SEAM_WIDTH: f64 = 1.5;

/// The id of the seams' clip path, specific enough not to clash when SVGs are inlined in one
/// page.
const SEAM_CLIP_ID: &str = "sightline-opaque";

/// The seams under the fills (see [`Seams`]): the outline of the opaque items as a clip path,
/// then one path of segments per colour, butt ends. Both are written to a thousandth of a pixel:
/// they fill gaps under exact boundaries and bound no region; a clip a thousandth of a pixel
/// off the silhouette lets through at most that much of a stroke along it.
fn write_seams(s: &mut SvgStream, seams: &Seams) -> std::io::Result<()> {
    let mut outline = String::new();
    write_rings(&mut outline, &seams.outline, push_milli);
    s.open(Definitions::new())?;
    s.child(
        ClipPath::new()
            .set("id", SEAM_CLIP_ID)
            .add(Path::new().set("d", outline).set("clip-rule", "evenodd")),
    )?;
    s.close()?;
    s.open(
        Group::new()
            .set("clip-path", format!("url(#{SEAM_CLIP_ID})"))
            .set("fill", "none")
            .set("stroke-width", num(SEAM_WIDTH))
            .set("stroke-linecap", "butt"),
    )?;
    for stroke in &seams.strokes {
        let mut d = String::new();
        for [p, q] in &stroke.segments {
            let start = d.len();
            d.push('M');
            push_milli(&mut d, p[0]);
            d.push(' ');
            push_milli(&mut d, p[1]);
            let mid = d.len();
            d.push('L');
            push_milli(&mut d, q[0]);
            d.push(' ');
            push_milli(&mut d, q[1]);
            // Shorter than the rounding: a butt-ended stroke of no length draws nothing.
            if d[start + 1..mid] == d[mid + 1..] {
                d.truncate(start);
            }
        }
        // vector-effect is not inherited: it goes on every path.
        s.child(
            Path::new()
                .set("d", d)
                .set("stroke", hex(stroke.color))
                .set("vector-effect", "non-scaling-stroke"),
        )?;
    }
    s.close()
}

/// Path data of closed rings, each coordinate written by `num` (into the string, after what it
/// holds).
fn write_rings(d: &mut String, rings: &[Vec<[f64; 2]>], num: fn(&mut String, f64)) {
    for ring in rings {
        for (k, p) in ring.iter().enumerate() {
            debug_assert!(p[0].is_finite() && p[1].is_finite());
            d.push(if k == 0 { 'M' } else { 'L' });
            num(d, p[0]);
            d.push(' ');
            num(d, p[1]);
        }
        if !ring.is_empty() {
            d.push('Z');
        }
    }
}

/// [`num`], written into `d`.
fn push_num(d: &mut String, x: f64) {
    let _ = write!(d, "{}", x + 0.0);
}

/// `x` to three decimals, without trailing zeros (-0 written as 0), written into `d` after
/// what it holds.
fn push_milli(d: &mut String, x: f64) {
    let start = d.len();
    let _ = write!(d, "{:.3}", x + 0.0);
    let kept = d[start..].trim_end_matches('0').trim_end_matches('.').len();
    d.truncate(start + kept);
    if &d[start..] == "-0" {
        d.truncate(start);
        d.push('0');
    }
}

/// Shortest round-trip decimal of `x`, with -0 written as 0 (`-0 + 0 = +0`).
pub fn num(x: f64) -> String {
    format!("{}", x + 0.0)
}

/// `#rrggbb` of a linear colour (0 to 1), 8-bit rounded.
pub fn hex(c: [f64; 3]) -> String {
    let [r, g, b] = to_u8(c);
    format!("#{r:02x}{g:02x}{b:02x}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_trip_and_negative_zero_is_zero() {
        for x in [0.1 + 0.2, 1234.5678901234567, 1e-7, 5e20, -3.25, 1.0 / 3.0] {
            assert_eq!(num(x).parse::<f64>().unwrap(), x);
            assert!(!num(x).contains('e'));
        }
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(0.30000000000000004), "0.30000000000000004");
    }

    #[test]
    fn thousandths_drop_trailing_zeros_and_negative_zero() {
        let milli = |x: f64| {
            let mut d = String::from("M");
            push_milli(&mut d, x);
            d
        };
        assert_eq!(milli(1.5), "M1.5");
        assert_eq!(milli(2.0), "M2");
        assert_eq!(milli(10.0004), "M10");
        assert_eq!(milli(-0.0004), "M0");
        assert_eq!(milli(-1.2345), "M-1.234");
        assert_eq!(milli(100.0), "M100");
    }

    #[test]
    fn hex_rounds_to_8_bits() {
        assert_eq!(hex([1.0, 0.5, 0.0]), "#ff8000");
        assert_eq!(hex([0.0, 0.6, 2.0]), "#0099ff");
    }
}
