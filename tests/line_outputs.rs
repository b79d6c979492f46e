//! The writers of line drawings, on drawings made by hand: the SVG's groups, paths and style,
//! and the SVG as a viewer draws it (resvg: ISO weights and dashes), the DXF read back with the
//! `dxf` crate (layers, linetype, polylines, coordinates, reproducible header), and the PDF
//! (vector, dashes kept, reproducible).

use sightline::lines::{LineDrawing, LineKind, Stroke, Visibility};
use sightline::output::dxf::{DxfOptions, HIDDEN_LAYER, HIDDEN_LINETYPE, VISIBLE_LAYER, write_dxf};
use sightline::output::line_svg::{LineSvgOptions, PX_PER_MM, write_line_svg};
use sightline::output::pdf::pdf_of_svg;
use sightline::output::svg::num;
use std::io::Read;

fn stroke(visibility: Visibility, kind: LineKind, points: &[[f64; 2]], closed: bool) -> Stroke {
    Stroke {
        visibility,
        kind,
        qi: (visibility == Visibility::Hidden) as u32,
        points: points.to_vec(),
        closed,
    }
}

/// A 120 x 40 drawing: a visible horizontal line at y = 10 and a hidden one at y = 30, both
/// from x = 10 to x = 110.
fn two_lines() -> LineDrawing {
    LineDrawing {
        width: 120,
        height: 40,
        strokes: vec![
            stroke(
                Visibility::Visible,
                LineKind::Silhouette,
                &[[10.0, 10.0], [110.0, 10.0]],
                false,
            ),
            stroke(
                Visibility::Hidden,
                LineKind::Crease,
                &[[10.0, 30.0], [110.0, 30.0]],
                false,
            ),
        ],
    }
}

/// A drawing with every feature of the formats: both visibilities, open and closed strokes,
/// coordinates that need all their digits.
fn mixed() -> LineDrawing {
    LineDrawing {
        width: 300,
        height: 200,
        strokes: vec![
            stroke(
                Visibility::Visible,
                LineKind::Silhouette,
                &[[10.5, 20.25], [290.0, 20.25], [150.0 + 1.0 / 3.0, 180.125]],
                true,
            ),
            stroke(
                Visibility::Visible,
                LineKind::Crease,
                &[[0.1 + 0.2, 199.9], [123.456789012, 0.0]],
                false,
            ),
            stroke(
                Visibility::Hidden,
                LineKind::Boundary,
                &[[50.0, 60.0], [70.0, 80.0], [90.0, 60.0]],
                false,
            ),
        ],
    }
}

/// The `d` values of the paths of the group of this class, in order.
fn paths_of(svg: &str, class: &str) -> Vec<String> {
    let start = svg
        .find(&format!("<g class=\"{class}\">"))
        .unwrap_or_else(|| panic!("no group {class}: {svg}"));
    let group = &svg[start..start + svg[start..].find("</g>").unwrap()];
    group
        .split(" d=\"")
        .skip(1)
        .map(|s| s[..s.find('"').unwrap()].to_string())
        .collect()
}

#[test]
fn groups_are_per_visibility_and_kind_hidden_first_in_kind_order() {
    let drawing = LineDrawing {
        width: 10,
        height: 8,
        strokes: vec![
            stroke(
                Visibility::Visible,
                LineKind::Crease,
                &[[0.0, 0.0], [1.0, 1.0]],
                false,
            ),
            stroke(
                Visibility::Visible,
                LineKind::Silhouette,
                &[[1.0, 0.0], [2.0, 1.0]],
                false,
            ),
            stroke(
                Visibility::Hidden,
                LineKind::Crease,
                &[[3.0, 0.0], [4.0, 1.0]],
                false,
            ),
            stroke(
                Visibility::Visible,
                LineKind::Crease,
                &[[5.0, 0.0], [6.0, 1.0]],
                false,
            ),
        ],
    };
    let svg = write_line_svg(&drawing, &LineSvgOptions::default());
    let classes: Vec<&str> = svg
        .split("<g class=\"")
        .skip(1)
        .map(|s| &s[..s.find('"').unwrap()])
        .collect();
    assert_eq!(
        classes,
        ["hidden crease", "visible silhouette", "visible crease"]
    );
    // Within a group, the drawing's order; every path names its kind.
    assert_eq!(paths_of(&svg, "visible crease"), ["M0 0L1 1", "M5 0L6 1"]);
    assert_eq!(svg.matches("data-kind=\"crease\"").count(), 3);
    assert_eq!(svg.matches("data-kind=\"silhouette\"").count(), 1);
}

#[test]
fn coordinates_round_trip_and_closed_strokes_end_with_z() {
    let (a, b) = (0.1 + 0.2, 1234.5678901234567);
    let drawing = LineDrawing {
        width: 2000,
        height: 2000,
        strokes: vec![
            stroke(
                Visibility::Visible,
                LineKind::Silhouette,
                &[[a, b], [b, -0.0], [1.0 / 3.0, 7.0]],
                true,
            ),
            stroke(
                Visibility::Hidden,
                LineKind::Boundary,
                &[[a, a], [b, b]],
                false,
            ),
        ],
    };
    let svg = write_line_svg(&drawing, &LineSvgOptions::default());
    let d = &paths_of(&svg, "visible silhouette")[0];
    assert_eq!(
        d,
        "M0.30000000000000004 1234.5678901234567L1234.5678901234567 0L0.3333333333333333 7Z"
    );
    // Every number parses back to the f64 it came from (f32 would keep about 7 digits).
    let numbers: Vec<f64> = d
        .split(['M', 'L', 'Z', ' '])
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap())
        .collect();
    assert_eq!(numbers, [a, b, b, 0.0, 1.0 / 3.0, 7.0]);
    assert!(!paths_of(&svg, "hidden boundary")[0].ends_with('Z'));
}

#[test]
fn the_style_gives_iso_weights_and_dashes_and_a_background_only_when_asked() {
    let options = LineSvgOptions::default();
    assert_eq!(options.visible_width, 2.0 * options.hidden_width);
    // 0.5 mm at 96 dpi.
    assert!((options.visible_width - 1.889_763_779_527_559).abs() < 1e-12);
    // As drawn with round caps: dash 12·d, gap 3·d.
    let [dash, gap] = options.hidden_dashes();
    let d = options.hidden_width;
    assert!((dash + d - 12.0 * d).abs() < 1e-12 && (gap - d - 3.0 * d).abs() < 1e-12);
    let empty = LineDrawing {
        width: 4,
        height: 3,
        strokes: Vec::new(),
    };
    let svg = write_line_svg(&empty, &options);
    assert!(svg.contains(&format!(
        ".hidden{{stroke-width:{}px;stroke-dasharray:{}px {}px}}",
        num(d),
        num(dash),
        num(gap)
    )));
    assert!(svg.contains("vector-effect:non-scaling-stroke"));
    assert!(!svg.contains("<rect") && !svg.contains("<g"));
    let white = LineSvgOptions {
        background: Some([1.0; 3]),
        ..options
    };
    assert!(write_line_svg(&empty, &white).contains("<rect fill=\"#ffffff\" height=\"3\""));
}

/// How much [`column_coverage`] magnifies: enough that dash lengths are measured to a
/// fraction of a drawing pixel.
const ZOOM: u32 = 4;

/// Per column of `svg` rasterized by resvg at [`ZOOM`] times its size, the alpha coverage
/// summed over the rows `rows` (of the zoomed image), in drawing pixels.
fn column_coverage(svg: &str, d: &LineDrawing, rows: std::ops::Range<usize>) -> Vec<f64> {
    use resvg::{tiny_skia, usvg};
    let w = (d.width * ZOOM) as usize;
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default()).unwrap();
    let mut pixmap = tiny_skia::Pixmap::new(d.width * ZOOM, d.height * ZOOM).unwrap();
    let zoom = tiny_skia::Transform::from_scale(ZOOM as f32, ZOOM as f32);
    resvg::render(&tree, zoom, &mut pixmap.as_mut());
    let alpha: Vec<u8> = pixmap.data().chunks_exact(4).map(|c| c[3]).collect();
    (0..w)
        .map(|x| {
            let sum: f64 = rows.clone().map(|y| alpha[y * w + x] as f64 / 255.0).sum();
            sum / ZOOM as f64
        })
        .collect()
}

/// Lengths of the runs of `true` and of `false` strictly inside `on` (the runs touching either
/// end are left out).
fn runs(on: &[bool]) -> (Vec<usize>, Vec<usize>) {
    let (mut dashes, mut gaps) = (Vec::new(), Vec::new());
    let mut start = 0;
    for k in 1..=on.len() {
        if k == on.len() || on[k] != on[start] {
            if start > 0 && k < on.len() {
                if on[start] { &mut dashes } else { &mut gaps }.push(k - start);
            }
            start = k;
        }
    }
    (dashes, gaps)
}

#[test]
fn svg_lines_are_drawn_with_iso_weights_and_hidden_dashes() {
    let drawing = two_lines();
    let options = LineSvgOptions::default();
    let svg = write_line_svg(&drawing, &options);
    // Along the visible line: its width in every column, no gap.
    let z = ZOOM as usize;
    let visible = column_coverage(&svg, &drawing, 0..20 * z);
    for (x, c) in visible.iter().enumerate().take(105 * z).skip(15 * z) {
        assert!(
            (c - options.visible_width).abs() <= 0.1,
            "visible line at x = {x}: {c} px wide, not {}",
            options.visible_width
        );
    }
    // Along the hidden line: half the width, dashed 12·d on and 3·d off as drawn.
    let hidden = column_coverage(&svg, &drawing, 20 * z..40 * z);
    let d = options.hidden_width;
    let peak = hidden[15 * z..105 * z].iter().cloned().fold(0.0, f64::max);
    assert!(
        (peak - d).abs() <= 0.1,
        "hidden line {peak} px wide, not {d}"
    );
    let on: Vec<bool> = hidden[12 * z..105 * z]
        .iter()
        .map(|&c| c > d / 10.0)
        .collect();
    let (dashes, gaps) = runs(&on);
    assert!(dashes.len() >= 4 && gaps.len() >= 4, "{on:?}");
    // Run lengths to a zoomed pixel (a quarter of a pixel) and a little more where a round cap
    // crosses the threshold: dashes drawn without allowing for their caps would be d (0.94 px)
    // longer, gaps d shorter.
    let px = |n: usize| n as f64 / ZOOM as f64;
    for &dash in &dashes {
        assert!((px(dash) - 12.0 * d).abs() <= 0.3, "dash {} px", px(dash));
    }
    for &gap in &gaps {
        assert!((px(gap) - 3.0 * d).abs() <= 0.3, "gap {} px", px(gap));
    }
}

#[test]
fn svg_bytes_are_reproducible() {
    let drawing = mixed();
    let options = LineSvgOptions::default();
    assert_eq!(
        write_line_svg(&drawing, &options),
        write_line_svg(&drawing.clone(), &options.clone())
    );
}

fn read_dxf(bytes: &[u8]) -> dxf::Drawing {
    dxf::Drawing::load(&mut &bytes[..]).expect("the dxf crate reads what it wrote")
}

/// The polylines of a DXF drawing: (layer, closed, vertices).
fn polylines(drawing: &dxf::Drawing) -> Vec<(String, bool, Vec<[f64; 2]>)> {
    drawing
        .entities()
        .map(|e| match &e.specific {
            dxf::entities::EntityType::LwPolyline(p) => (
                e.common.layer.clone(),
                p.is_closed(),
                p.vertices.iter().map(|v| [v.x, v.y]).collect(),
            ),
            other => panic!("not a polyline: {other:?}"),
        })
        .collect()
}

/// The DXF coordinates of an image point: y flipped, scaled.
fn dxf_point(p: [f64; 2], height: u32, scale: f64) -> [f64; 2] {
    [p[0] * scale, (height as f64 - p[1]) * scale]
}

/// `a` and `b` agree to the crate's 12 decimals.
fn close(a: [f64; 2], b: [f64; 2]) -> bool {
    (a[0] - b[0]).abs() <= 1e-12 * a[0].abs().max(1.0)
        && (a[1] - b[1]).abs() <= 1e-12 * a[1].abs().max(1.0)
}

#[test]
fn dxf_has_visible_and_hidden_layers_the_hidden_linetype_and_one_polyline_per_stroke() {
    let drawing = mixed();
    for (options, scale, per_mm) in [
        (DxfOptions::default(), 1.0, PX_PER_MM),
        (
            DxfOptions {
                mm_per_px: Some(0.25),
            },
            0.25,
            1.0,
        ),
    ] {
        let back = read_dxf(&write_dxf(&drawing, &options).unwrap());
        let layer = |name: &str| back.layers().find(|l| l.name == name).unwrap();
        assert_eq!(layer(VISIBLE_LAYER).line_type_name, "CONTINUOUS");
        assert_eq!(layer(VISIBLE_LAYER).line_weight.raw_value(), 50);
        assert_eq!(layer(HIDDEN_LAYER).line_type_name, HIDDEN_LINETYPE);
        assert_eq!(layer(HIDDEN_LAYER).line_weight.raw_value(), 25);
        // The crate's layer 0 gets the default lineweight, not 0 mm.
        assert_eq!(layer("0").line_weight.raw_value(), -3);
        // ISO 128 type 02 for d = 0.25 mm: dash 3 mm, gap 0.75 mm, in file units.
        let hidden = back
            .line_types()
            .find(|t| t.name == HIDDEN_LINETYPE)
            .unwrap();
        let (dash, gap) = (3.0 * per_mm, 0.75 * per_mm);
        assert_eq!(hidden.element_count, 2);
        assert!(close(
            [
                hidden.dash_dot_space_lengths[0],
                hidden.dash_dot_space_lengths[1]
            ],
            [dash, -gap]
        ));
        assert!((hidden.total_pattern_length - (dash + gap)).abs() < 1e-9);
        let units = back.header.default_drawing_units;
        match options.mm_per_px {
            Some(_) => assert_eq!(units, dxf::enums::Units::Millimeters),
            None => assert_eq!(units, dxf::enums::Units::Unitless),
        }
        // Hidden strokes first, then visible ones in the drawing's order.
        let order = [2, 0, 1];
        let polys = polylines(&back);
        assert_eq!(polys.len(), drawing.strokes.len());
        for (poly, &k) in polys.iter().zip(&order) {
            let s = &drawing.strokes[k];
            let layer = match s.visibility {
                Visibility::Visible => VISIBLE_LAYER,
                Visibility::Hidden => HIDDEN_LAYER,
            };
            assert_eq!((poly.0.as_str(), poly.1), (layer, s.closed));
            assert_eq!(poly.2.len(), s.points.len());
            for (&got, &p) in poly.2.iter().zip(&s.points) {
                let want = dxf_point(p, drawing.height, scale);
                assert!(close(got, want), "{got:?} != {want:?}");
            }
        }
    }
}

#[test]
fn dxf_bytes_are_reproducible_with_no_clock_date_and_no_random_guid() {
    let drawing = mixed();
    let a = write_dxf(&drawing, &DxfOptions::default()).unwrap();
    let b = write_dxf(&drawing, &DxfOptions::default()).unwrap();
    assert!(a == b, "two writes differ");
    let text = String::from_utf8(a).unwrap();
    let pairs: Vec<&str> = text.split("\r\n").collect();
    let value = |name: &str| {
        let k = pairs.iter().position(|p| *p == name).unwrap();
        pairs[k + 2]
    };
    for date in ["$TDCREATE", "$TDUCREATE", "$TDUPDATE", "$TDUUPDATE"] {
        assert_eq!(value(date), "2415021.0", "{date}");
    }
    for guid in ["$FINGERPRINTGUID", "$VERSIONGUID"] {
        assert_eq!(
            value(guid),
            "00000000-0000-0000-0000-000000000000",
            "{guid}"
        );
    }
}

/// The decompressed content of every stream of a PDF (as svg2pdf writes them: FlateDecode),
/// and the bytes outside the streams.
fn pdf_parts(pdf: &[u8]) -> (Vec<String>, String) {
    let text = String::from_utf8_lossy(pdf).to_string();
    let (mut streams, mut outside) = (Vec::new(), String::new());
    let mut rest = pdf;
    while let Some(start) = find(rest, b"stream\n") {
        outside.push_str(&String::from_utf8_lossy(&rest[..start]));
        let body = &rest[start + 7..];
        let end = find(body, b"endstream").unwrap();
        let mut out = Vec::new();
        if flate2::read::ZlibDecoder::new(&body[..end])
            .read_to_end(&mut out)
            .is_ok()
        {
            streams.push(String::from_utf8_lossy(&out).to_string());
        }
        rest = &body[end + 9..];
    }
    outside.push_str(&String::from_utf8_lossy(rest));
    assert!(text.starts_with("%PDF-"));
    (streams, outside)
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

#[test]
fn pdf_is_vector_with_the_dash_pattern_kept_and_reproducible() {
    let drawing = two_lines();
    let options = LineSvgOptions::default();
    let pdf = pdf_of_svg(&write_line_svg(&drawing, &options)).unwrap();
    assert!(pdf == pdf_of_svg(&write_line_svg(&drawing, &options)).unwrap());
    let (streams, outside) = pdf_parts(&pdf);
    // No raster image (as an XObject or inline), no date from the clock.
    for absent in ["/Subtype /Image", "/XObject", "/CreationDate", "/ModDate"] {
        assert!(!outside.contains(absent), "{absent} in {outside}");
    }
    let content = streams
        .iter()
        .find(|s| s.contains(" m\n"))
        .expect("a content stream with paths");
    assert!(!content.contains("\nBI\n"), "an inline image: {content}");
    // Both lines stroked (`S`), the hidden one with its dash array (`[dash gap] phase d`), f32
    // as svg2pdf writes numbers.
    let [dash, gap] = options.hidden_dashes();
    let dashed = format!("[{} {}] 0 d", dash as f32, gap as f32);
    assert!(content.contains(&dashed), "no `{dashed}` in {content}");
    assert!(content.contains("[] 0 d"), "{content}");
    assert_eq!(content.matches("\nS\n").count(), 2, "{content}");
    let widths = [options.visible_width as f32, options.hidden_width as f32];
    for w in widths {
        assert!(
            content.contains(&format!("{w} w")),
            "no width {w}: {content}"
        );
    }
    // One page at 96 CSS pixels per inch: 120 x 40 px is 90 x 30 pt.
    assert!(outside.contains("/MediaBox [0 0 90 30]"), "{outside}");
}

#[cfg(not(feature = "pdf-text"))]
#[test]
fn pdf_of_an_svg_with_text_is_an_error_without_text_support() {
    let svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\">\
               <text x=\"1\" y=\"9\">A</text></svg>";
    let e = pdf_of_svg(svg).unwrap_err().to_string();
    assert!(e.contains("--features pdf-text"), "{e}");
}
