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
//!   never exists whole in memory, only one batch of paths' text at a time (rendered on all
//!   cores, written in order).
//!
//! Paths are written as the drawing has them: canonicalize it first
//! ([`super::canonical::canonicalize`], as the CLI does) for bytes that depend only on what is
//! drawn. The README's "Output contract" lists every element and attribute.

use super::drawing::{DrawItem, Drawing, SeamStroke, Seams};
use super::line_svg::{LineSvgOptions, write_line_layers};
use super::svg_stream::{SvgStream, render_leaf};
use crate::lines::LineDrawing;
use crate::paint::to_u8;
use ::svg::Document;
use ::svg::node::element::{ClipPath, Definitions, Group, Path, Rectangle};
use rayon::prelude::*;
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
    // One path per item (`render_leaf`: the crate's bytes), rendered on all cores a batch at a
    // time and written in order: only a batch's text exists at once.
    for batch in drawing.items.chunks(LEAVES_PER_BATCH) {
        let rendered: Vec<Vec<u8>> = batch.par_chunks(LEAVES_PER_TASK).map(item_paths).collect();
        for r in &rendered {
            s.rendered_leaves(r)?;
        }
    }
    s.close()?;
    if let Some((lines, line_options)) = lines {
        write_line_layers(&mut s, lines, line_options)?;
    }
    s.finish()
}

/// Items' paths rendered per batch ([`write_document`]): enough for both cores to share
/// evenly, a few megabytes of text.
const LEAVES_PER_BATCH: usize = 16_384;
/// Items' paths rendered by one task of a batch.
const LEAVES_PER_TASK: usize = 512;

/// The path elements of `items`, one after another ([`render_leaf`]).
fn item_paths(items: &[DrawItem]) -> Vec<u8> {
    // The strings are reused from item to item.
    let (mut d, mut face, mut faces) = (String::new(), String::new(), String::new());
    let mut rendered = Vec::new();
    for item in items {
        d.clear();
        write_rings(&mut d, &item.rings, push_num);
        let fill = hex(item.color);
        face.clear();
        let _ = write!(face, "{}", item.face);
        let mut attributes = vec![
            ("d", d.as_str()),
            ("fill", fill.as_str()),
            ("fill-rule", "evenodd"),
            ("data-face", face.as_str()),
        ];
        if !item.merged.is_empty() {
            faces.clear();
            faces.push_str(&face);
            for f in &item.merged {
                let _ = write!(faces, " {f}");
            }
            attributes.push(("data-faces", faces.as_str()));
        }
        let opacity = (item.opacity < 1.0).then(|| num(item.opacity.max(0.0)));
        if let Some(opacity) = &opacity {
            attributes.push(("fill-opacity", opacity.as_str()));
        }
        render_leaf(&mut rendered, "path", &mut attributes);
    }
    rendered
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
    // A path per colour, rendered on all cores a few at a time and written in order.
    for batch in seams.strokes.chunks(rayon::current_num_threads().max(1)) {
        let rendered: Vec<Vec<u8>> = batch.par_iter().map(stroke_path).collect();
        for r in &rendered {
            s.rendered_leaves(r)?;
        }
    }
    s.close()
}

/// The path of one seam stroke ([`write_seams`], [`render_leaf`]).
fn stroke_path(stroke: &SeamStroke) -> Vec<u8> {
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
    let stroke_color = hex(stroke.color);
    let mut rendered = Vec::with_capacity(d.len() + 80);
    // vector-effect is not inherited: it goes on every path.
    let mut attributes = [
        ("d", d.as_str()),
        ("stroke", stroke_color.as_str()),
        ("vector-effect", "non-scaling-stroke"),
    ];
    render_leaf(&mut rendered, "path", &mut attributes);
    rendered
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

/// [`num`], written into `d`: the same characters, made faster. zmij writes the shortest
/// round-trip digits as `{}` does, except that it breaks an exact tie between two shortest
/// candidates to even where `{}` rounds up, and writes exponents and ".0" differently; ties
/// need a value whose exact decimal expansion has at most 18 significant digits
/// ([`may_tie`]), and those, exponents and integers go through `{}`.
fn push_num(d: &mut String, x: f64) {
    let x = x + 0.0;
    if !may_tie(x) {
        let mut buffer = zmij::Buffer::new();
        let z = buffer.format_finite(x);
        if !z.contains('e') {
            d.push_str(z.strip_suffix(".0").unwrap_or(z));
            return;
        }
    }
    let _ = write!(d, "{x}");
}

/// Could two shortest decimals of `x` be exactly equally near it? Only if `x` is the midpoint
/// of two decimals of at most 17 significant digits, so its exact expansion has at most 18:
/// with `x = m·2^e`, `m` odd and `e < 0`, that expansion's digits are those of `m·5^-e` (odd,
/// so no trailing zeros), which must then be below 10^18. Integers, zero and non-finite values
/// count as possible ties (they take the slow path).
fn may_tie(x: f64) -> bool {
    let Some((mut m, mut e)) = integer_and_exponent(x).filter(|&(m, _)| m != 0) else {
        return true;
    };
    let zeros = m.trailing_zeros();
    m >>= zeros;
    e += zeros as i64;
    if e >= 0 {
        return true;
    }
    // 5^27 > 10^18: more digits than a tie can have.
    if -e > 27 {
        return false;
    }
    (m as u128) * 5u128.pow((-e) as u32) < 10u128.pow(18)
}

/// `x` to three decimals, without trailing zeros (-0 written as 0), written into `d` after
/// what it holds: the characters of `{:.3}` (which rounds the exact binary value half to even)
/// so trimmed, made in integers: `x·1000 = m·1000·2^e` rounded half to even exactly.
fn push_milli(d: &mut String, x: f64) {
    // Integers beyond 2^53 (and non-finite values) the formatter's own way.
    let Some((m, e)) = integer_and_exponent(x).filter(|&(_, e)| e <= 0) else {
        return push_milli_slow(d, x);
    };
    let product = m as u128 * 1000;
    let shift = (-e) as u32;
    let n: u128 = if shift >= 128 {
        0
    } else if shift == 0 {
        product
    } else {
        let (q, r) = (product >> shift, product & ((1u128 << shift) - 1));
        let half = 1u128 << (shift - 1);
        q + (r > half || (r == half && q & 1 == 1)) as u128
    };
    if n == 0 {
        d.push('0');
        return;
    }
    if x.is_sign_negative() {
        d.push('-');
    }
    let (whole, thousandths) = (n / 1000, (n % 1000) as u16);
    d.push_str(itoa::Buffer::new().format(whole));
    if thousandths != 0 {
        d.push('.');
        let digits = [thousandths / 100, thousandths / 10 % 10, thousandths % 10];
        let kept = if digits[2] != 0 {
            3
        } else if digits[1] != 0 {
            2
        } else {
            1
        };
        d.extend(digits[..kept].iter().map(|&k| char::from(b'0' + k as u8)));
    }
}

/// `|x| = m·2^e` exactly (`m` below 2^53), or `None` for infinities and NaN.
fn integer_and_exponent(x: f64) -> Option<(u64, i64)> {
    let bits = x.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i64;
    let fraction = bits & ((1 << 52) - 1);
    match exponent {
        0x7ff => None,
        0 => Some((fraction, -1074)),
        _ => Some((fraction | (1 << 52), exponent - 1075)),
    }
}

/// [`push_milli`] by the formatter.
fn push_milli_slow(d: &mut String, x: f64) {
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

    /// Values of every kind a drawing writes, and the awkward ones: exact dyadics (ties of
    /// the shortest digits, ties of the thousandths), tiny, huge, negative, subnormal.
    fn awkward_values() -> Vec<f64> {
        let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut out = Vec::new();
        for k in 0..400_000u64 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let unit = (s >> 11) as f64 / (1u64 << 53) as f64;
            let x = match k % 6 {
                0 => unit * 4096.0,
                1 => f64::from_bits(s >> 1),
                2 => (s >> 20) as f64 / 1024.0,
                3 => (s >> 40) as f64 / 16.0 - 4096.0,
                4 => unit * 1e-3,
                _ => (s % 100_000) as f64 / 2000.0,
            };
            out.push(if s & 1 == 1 { -x } else { x });
        }
        out.extend([
            0.0625,
            0.1875,
            -0.3125,
            4007143549.5664063,
            1e-7,
            5e-324,
            1e300,
            2.0,
        ]);
        out.extend([-0.0, 0.0, 0.0005, 1e15, 1e16, 123456789012345680.0]);
        out.into_iter().filter(|x| x.is_finite()).collect()
    }

    #[test]
    fn fast_numbers_are_the_formatters_characters() {
        for x in awkward_values() {
            let mut fast = String::new();
            push_num(&mut fast, x);
            assert_eq!(fast, format!("{}", x + 0.0), "{x:e}");
            let mut fast = String::new();
            push_milli(&mut fast, x);
            let mut slow = String::new();
            push_milli_slow(&mut slow, x);
            assert_eq!(fast, slow, "{x:e}");
        }
    }

    #[test]
    fn hex_rounds_to_8_bits() {
        assert_eq!(hex([1.0, 0.5, 0.0]), "#ff8000");
        assert_eq!(hex([0.0, 0.6, 2.0]), "#0099ff");
    }
}
