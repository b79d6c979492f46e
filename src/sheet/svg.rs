//! A sheet as SVG: user units are millimetres (`viewBox` in mm, `width`/`height` with `mm`),
//! line weights after ISO 128 (visible 0.5 mm; hidden 0.25 mm, dashed 3 mm with 0.75 mm
//! gaps; border and title block outline 0.7 mm; title block lines 0.25 mm; text strokes a
//! tenth of their height, ISO 3098), each view's lines grouped by visibility and kind with
//! `class="visible silhouette"` and `data-kind` on each path, hidden lines under visible ones.
//!
//! Numbers: view geometry at full precision (shortest round-trip f64, so aligned points have
//! the same digits); border, title block and text to 0.001 mm.

use super::font::{self, Anchor};
use super::{LABEL_H, NOTE_H, PlacedView, Sheet};
use crate::lines::{LineKind, Visibility};
use std::fmt::Write;

const VISIBLE_MM: f64 = 0.5;
const HIDDEN_MM: f64 = 0.25;
const HIDDEN_DASH: &str = "3 0.75";
const BORDER_MM: f64 = 0.7;
const THIN_MM: f64 = 0.25;

/// Full precision (shortest digits that read back the same f64; -0 as 0).
fn num(v: f64) -> String {
    if v == 0.0 { "0".into() } else { format!("{v}") }
}

/// To 0.001 mm.
fn num3(v: f64) -> String {
    num((v * 1000.0).round() / 1000.0)
}

/// Escapes text for an attribute value.
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            c if (c as u32) < 0x20 => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// Path data of polylines, `fmt` writing each number.
fn path_data<'a>(
    lines: impl IntoIterator<Item = (&'a [[f64; 2]], bool)>,
    fmt: fn(f64) -> String,
) -> String {
    let mut d = String::new();
    for (points, closed) in lines {
        for (k, p) in points.iter().enumerate() {
            let _ = write!(
                d,
                "{}{} {}",
                if k == 0 { 'M' } else { 'L' },
                fmt(p[0]),
                fmt(p[1])
            );
        }
        if closed {
            d.push('Z');
        }
    }
    d
}

/// A text as one stroked path, labelled with its words for readers and search.
fn text(out: &mut String, field: &str, s: &str, x: f64, y: f64, h: f64, anchor: Anchor) {
    let lines = font::text_polylines(s, x, y, h, anchor);
    let d = path_data(lines.iter().map(|l| (l.as_slice(), false)), num3);
    let _ = writeln!(
        out,
        "<g class=\"text\" data-field=\"{field}\" aria-label=\"{}\" stroke-width=\"{}\"><path d=\"{d}\"/></g>",
        escape(s),
        num3(h / 10.0)
    );
}

pub(super) fn write(sheet: &Sheet) -> String {
    let mut out = String::new();
    let (w, h) = (num3(sheet.width), num3(sheet.height));
    let _ = writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}mm\" height=\"{h}mm\" viewBox=\"0 0 {w} {h}\">"
    );
    let _ = writeln!(out, "<rect width=\"{w}\" height=\"{h}\" fill=\"#ffffff\"/>");
    out.push_str(
        "<g fill=\"none\" stroke=\"#000000\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n",
    );
    border(&mut out, sheet);
    for v in &sheet.views {
        view(&mut out, sheet, v);
    }
    title_block(&mut out, sheet);
    out.push_str("</g>\n</svg>\n");
    out
}

/// The frame and its centring marks.
fn border(out: &mut String, sheet: &Sheet) {
    let f = &sheet.frame;
    let (mx, my) = (sheet.width / 2.0, sheet.height / 2.0);
    let t = &sheet.title_block;
    // Each mark runs from the paper's edge to 5 mm inside the frame, but not into the title
    // block.
    let bottom_end = if t.x0 < mx && mx < t.x1 {
        f.y1
    } else {
        f.y1 - 5.0
    };
    let marks: [[[f64; 2]; 2]; 4] = [
        [[0.0, my], [f.x0 + 5.0, my]],
        [[sheet.width, my], [f.x1 - 5.0, my]],
        [[mx, 0.0], [mx, f.y0 + 5.0]],
        [[mx, sheet.height], [mx, bottom_end]],
    ];
    let d = path_data(marks.iter().map(|m| (&m[..], false)), num3);
    let _ = writeln!(
        out,
        "<g class=\"border\" stroke-width=\"{}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/><path d=\"{d}\"/></g>",
        num3(BORDER_MM),
        num3(f.x0),
        num3(f.y0),
        num3(f.width()),
        num3(f.height())
    );
}

/// One view: its hidden lines, its visible lines over them, its label below.
fn view(out: &mut String, sheet: &Sheet, v: &PlacedView) {
    let name = super::view_name(v.view);
    let scale = if v.to_scale {
        format!(" data-scale=\"{}\"", sheet.scale)
    } else {
        String::new()
    };
    let _ = writeln!(
        out,
        "<g class=\"view\" id=\"view-{name}\" data-view=\"{name}\"{scale}>"
    );
    for vis in [Visibility::Hidden, Visibility::Visible] {
        for kind in LineKind::ALL {
            let strokes: Vec<_> = v
                .drawing
                .strokes
                .iter()
                .filter(|s| s.visibility == vis && s.kind == kind)
                .collect();
            if strokes.is_empty() {
                continue;
            }
            let style = match vis {
                Visibility::Visible => format!("stroke-width=\"{}\"", num(VISIBLE_MM)),
                Visibility::Hidden => format!(
                    "stroke-width=\"{}\" stroke-dasharray=\"{HIDDEN_DASH}\" stroke-linecap=\"butt\"",
                    num(HIDDEN_MM)
                ),
            };
            let _ = writeln!(out, "<g class=\"{} {}\" {style}>", vis.name(), kind.name());
            for s in strokes {
                let paper: Vec<[f64; 2]> = s.points.iter().map(|&p| v.to_paper(p)).collect();
                let d = path_data([(paper.as_slice(), s.closed)], num);
                let _ = writeln!(out, "<path data-kind=\"{}\" d=\"{d}\"/>", kind.name());
            }
            out.push_str("</g>\n");
        }
    }
    let f = &v.frame;
    let (cx, base) = ((f.x0 + f.x1) / 2.0, f.y1 + 2.0 + LABEL_H);
    text(out, "label", &v.label(), cx, base, LABEL_H, Anchor::Middle);
    if let Some(note) = v.note() {
        text(
            out,
            "note",
            note,
            cx,
            base + 1.5 + NOTE_H,
            NOTE_H,
            Anchor::Middle,
        );
    }
    out.push_str("</g>\n");
}

/// The title block: outline, cells, field names and values, the projection symbol.
fn title_block(out: &mut String, sheet: &Sheet) {
    let t = &sheet.title_block;
    let (x, y) = (t.x0, t.y0);
    let row = t.height() / 2.0;
    out.push_str("<g class=\"title-block\">\n");
    let _ = writeln!(
        out,
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" stroke-width=\"{}\"/>",
        num3(x),
        num3(y),
        num3(t.width()),
        num3(t.height()),
        num3(BORDER_MM)
    );
    // Cells: TITLE | SCALE above; PROJECTION | SIZE | DATE | SHEET below.
    let top = [(0.0, 130.0, "TITLE"), (130.0, 180.0, "SCALE")];
    let bottom = [
        (0.0, 70.0, "PROJECTION"),
        (70.0, 100.0, "SIZE"),
        (100.0, 150.0, "DATE"),
        (150.0, 180.0, "SHEET"),
    ];
    let mut rules: Vec<[[f64; 2]; 2]> = vec![[[x, y + row], [t.x1, y + row]]];
    rules.extend(top[1..].iter().map(|c| [[x + c.0, y], [x + c.0, y + row]]));
    rules.extend(
        bottom[1..]
            .iter()
            .map(|c| [[x + c.0, y + row], [x + c.0, t.y1]]),
    );
    let d = path_data(rules.iter().map(|r| (&r[..], false)), num3);
    let _ = writeln!(out, "<path stroke-width=\"{}\" d=\"{d}\"/>", num3(THIN_MM));
    for (cells, y0) in [(&top[..], y), (&bottom[..], y + row)] {
        for &(c0, _, name) in cells {
            let field = format!("{}-name", name.to_lowercase());
            text(
                out,
                &field,
                name,
                x + c0 + 1.5,
                y0 + 3.3,
                1.8,
                Anchor::Start,
            );
        }
    }
    // Values: the title shrunk to fit its cell when long.
    let base = |y0: f64| y0 + row - 2.5;
    let room = 130.0 - 6.0;
    let title_h = (room / font::text_width(&sheet.title, 1.0)).min(5.0);
    text(
        out,
        "title",
        &sheet.title,
        x + 3.0,
        base(y),
        title_h,
        Anchor::Start,
    );
    let scale = sheet.scale.to_string();
    text(
        out,
        "scale",
        &scale,
        x + 155.0,
        base(y),
        5.0,
        Anchor::Middle,
    );
    let y1 = y + row;
    // The symbol's axis at the middle of the values' capitals.
    projection_symbol(out, sheet.method, x + 4.0, base(y1) - 1.75);
    text(
        out,
        "projection",
        sheet.method.name(),
        x + 24.0,
        base(y1),
        3.5,
        Anchor::Start,
    );
    text(
        out,
        "size",
        sheet.paper.name(),
        x + 85.0,
        base(y1),
        3.5,
        Anchor::Middle,
    );
    if let Some(date) = &sheet.date {
        text(
            out,
            "date",
            date.as_str(),
            x + 125.0,
            base(y1),
            3.5,
            Anchor::Middle,
        );
    }
    text(
        out,
        "sheet",
        "1/1",
        x + 165.0,
        base(y1),
        3.5,
        Anchor::Middle,
    );
    out.push_str("</g>\n");
}

/// The ISO 5456-2 symbol, a truncated cone seen from the side (a trapezoid, narrow end to the
/// right) and from its narrow end (two circles): the circles right of the trapezoid for third
/// angle, left of it for first angle. `(x, cy)`: its left end and axis; proportions of
/// ISO 5456-2 for lettering height `h` (large diameter 2h), sized to fit the cell.
fn projection_symbol(out: &mut String, method: super::ProjectionMethod, x: f64, cy: f64) {
    let h = 3.0;
    let big = h; // radius of the large end (diameter 2h)
    let small = h / 2.0;
    let (trap_x, circle_x) = match method {
        super::ProjectionMethod::Third => (x, x + 2.0 * h + h + big),
        super::ProjectionMethod::First => (x + 2.0 * big + h, x + big),
    };
    let len = 2.0 * h;
    let trapezoid = [
        [trap_x, cy - big],
        [trap_x + len, cy - small],
        [trap_x + len, cy + small],
        [trap_x, cy + big],
    ];
    let d = path_data([(&trapezoid[..], true)], num3);
    let _ = writeln!(
        out,
        "<g class=\"projection-symbol\" data-method=\"{}\" stroke-width=\"{}\"><path d=\"{d}\"/><circle cx=\"{}\" cy=\"{}\" r=\"{}\"/><circle cx=\"{}\" cy=\"{}\" r=\"{}\"/>",
        sheet_method_name(method),
        num3(h / 10.0),
        num3(circle_x),
        num3(cy),
        num3(big),
        num3(circle_x),
        num3(cy),
        num3(small)
    );
    // Centre lines, thin chain.
    let (x0, x1) = (x - 1.0, x + 4.0 * h + 2.0 * big - h + 1.0);
    let axes = [
        [[x0, cy], [x1, cy]],
        [[circle_x, cy - big - 0.6], [circle_x, cy + big + 0.6]],
    ];
    let d = path_data(axes.iter().map(|a| (&a[..], false)), num3);
    let _ = writeln!(
        out,
        "<path stroke-width=\"0.18\" stroke-dasharray=\"2.5 0.6 0.3 0.6\" stroke-linecap=\"butt\" d=\"{d}\"/></g>"
    );
}

fn sheet_method_name(m: super::ProjectionMethod) -> &'static str {
    match m {
        super::ProjectionMethod::Third => "third",
        super::ProjectionMethod::First => "first",
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Paper, ProjectionMethod, Rect, Scale};
    use super::*;
    use crate::camera::NamedView;
    use crate::lines::{LineDrawing, Stroke};

    fn stroke(visibility: Visibility, kind: LineKind, points: &[[f64; 2]]) -> Stroke {
        Stroke {
            visibility,
            kind,
            qi: u32::from(visibility == Visibility::Hidden),
            points: points.to_vec(),
            closed: false,
        }
    }

    /// A one-view sheet of hand-made strokes: 2 pixels per mm, pixel (50, 50) at (100, 80).
    fn sheet_of(strokes: Vec<Stroke>) -> Sheet {
        Sheet {
            width: 297.0,
            height: 210.0,
            frame: Rect {
                x0: 20.0,
                y0: 10.0,
                x1: 287.0,
                y1: 200.0,
            },
            title_block: Rect::at(107.0, 172.0, 180.0, 28.0),
            scale: Scale { paper: 1, model: 2 },
            views: vec![PlacedView {
                view: NamedView::Front,
                frame: Rect::at(75.0, 55.0, 50.0, 50.0),
                factor: 0.5,
                to_scale: true,
                drawing: LineDrawing {
                    width: 100,
                    height: 100,
                    strokes,
                },
                centre_px: [50.0, 50.0],
                centre_mm: [100.0, 80.0],
                mm_per_px: 0.5,
            }],
            title: "x.obj".into(),
            paper: Paper::A4,
            method: ProjectionMethod::First,
            date: None,
        }
    }

    /// Hidden lines are dashed 3/0.75 at 0.25 mm and drawn before (under) the visible ones at
    /// 0.5 mm; each group carries its visibility and kind; points are mapped to mm at full
    /// precision.
    #[test]
    fn hidden_lines_are_dashed_under_the_visible_ones() {
        let s = sheet_of(vec![
            stroke(
                Visibility::Visible,
                LineKind::Silhouette,
                &[[0.0, 0.0], [100.0, 0.0]],
            ),
            stroke(
                Visibility::Hidden,
                LineKind::Crease,
                &[[10.0, 10.0], [10.0, 90.0]],
            ),
            stroke(
                Visibility::Hidden,
                LineKind::Silhouette,
                &[[1.0 / 3.0, 5.0], [9.0, 5.0]],
            ),
        ]);
        let svg = s.svg();
        let at = |needle: &str| {
            svg.find(needle)
                .unwrap_or_else(|| panic!("no {needle} in {svg}"))
        };
        let hidden_sil = at(
            "<g class=\"hidden silhouette\" stroke-width=\"0.25\" stroke-dasharray=\"3 0.75\" stroke-linecap=\"butt\">",
        );
        let hidden_crease =
            at("<g class=\"hidden crease\" stroke-width=\"0.25\" stroke-dasharray=\"3 0.75\"");
        let visible = at("<g class=\"visible silhouette\" stroke-width=\"0.5\">");
        assert!(hidden_sil < hidden_crease && hidden_crease < visible);
        assert!(svg.contains("<path data-kind=\"silhouette\" d=\"M75 55L125 55\"/>"));
        assert!(svg.contains("<path data-kind=\"crease\" d=\"M80 60L80 100\"/>"));
        // (100 + (1/3 - 50) / 2, 80 + (5 - 50) / 2), at full precision.
        let x = 100.0 + (1.0 / 3.0 - 50.0) * 0.5;
        assert!(svg.contains(&format!("d=\"M{x} 57.5L")), "{x}");
        assert!(svg.contains("data-method=\"first\""));
        assert!(svg.contains("aria-label=\"FIRST ANGLE\""));
    }

    /// The projection symbol: third angle puts the circles right of the trapezoid, first
    /// angle left of it.
    #[test]
    fn the_projection_symbol_follows_the_method() {
        let circles_right_of_trapezoid = |method| {
            let mut out = String::new();
            projection_symbol(&mut out, method, 0.0, 0.0);
            let cx: f64 = out
                .split("cx=\"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap()
                .parse()
                .unwrap();
            let trap_x: f64 = out
                .split("d=\"M")
                .nth(1)
                .unwrap()
                .split(' ')
                .next()
                .unwrap()
                .parse()
                .unwrap();
            cx > trap_x
        };
        assert!(circles_right_of_trapezoid(ProjectionMethod::Third));
        assert!(!circles_right_of_trapezoid(ProjectionMethod::First));
    }
}
