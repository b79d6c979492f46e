//! `sightline sheet` and `sightline::sheet`: the scale from the standard series, the views'
//! places in third- and first-angle projection, their exact alignment, reproducible bytes,
//! the title block's date, and the errors of bad flags.

mod support;

use glam::DVec3;
use sightline::camera::NamedView;
use sightline::scene::{Scene, SceneBuilder};
use sightline::sheet::{self, ProjectionMethod, Scale, Sheet, SheetDate, SheetOptions, Units};
use std::path::{Path, PathBuf};
use support::cli::{run_err, run_ok};
use support::generated::{CUBE_QUADS, CUBE_VERTICES};
use support::scenes::add_box;

fn box_scene(lo: DVec3, hi: DVec3) -> Scene {
    let mut b = SceneBuilder::new("box");
    add_box(&mut b, lo, hi, "box");
    b.finish().unwrap()
}

/// A box as an OBJ file in `dir`: the unit cube of the generated fixtures, stretched.
fn box_obj(dir: &Path, name: &str, lo: [f64; 3], hi: [f64; 3]) -> PathBuf {
    let mut text = String::new();
    for v in CUBE_VERTICES {
        let c = |i: usize| lo[i] + v[i] * (hi[i] - lo[i]);
        text += &format!("v {} {} {}\n", c(0), c(1), c(2));
    }
    for q in CUBE_QUADS {
        text += &format!("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn options(views: &[NamedView], method: ProjectionMethod) -> SheetOptions {
    SheetOptions {
        views: views.to_vec(),
        method,
        title: "box.obj".into(),
        ..SheetOptions::default()
    }
}

const ORTHO3: [NamedView; 3] = [NamedView::Front, NamedView::Top, NamedView::Right];

fn view(s: &Sheet, v: NamedView) -> &sheet::PlacedView {
    s.views.iter().find(|p| p.view == v).unwrap()
}

/// The extent of a view's lines on paper, mm: (min x, min y, max x, max y).
fn paper_extent(v: &sheet::PlacedView) -> [f64; 4] {
    let mut e = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];
    for s in &v.drawing.strokes {
        for &p in &s.points {
            let [x, y] = v.to_paper(p);
            e = [e[0].min(x), e[1].min(y), e[2].max(x), e[3].max(y)];
        }
    }
    e
}

/// On A3 a 100 x 50 x 40 mm box's three views fit at 2:1 (298 x 214 mm with gaps and labels)
/// but not at 5:1, so 2:1, the largest of the series that fits; a
/// tenth of the box is 20:1 in mm, and 2:1 again in centimetres.
#[test]
fn the_scale_is_the_largest_standard_one_that_fits() {
    let big = box_scene(DVec3::ZERO, DVec3::new(100.0, 50.0, 40.0));
    let small = box_scene(DVec3::ZERO, DVec3::new(10.0, 5.0, 4.0));
    let o = options(&ORTHO3, ProjectionMethod::Third);
    let two = Scale { paper: 2, model: 1 };
    assert_eq!(sheet::sheet(&big, &o, None).unwrap().scale, two);
    let s = sheet::sheet(&small, &o, None).unwrap();
    assert_eq!(
        s.scale,
        Scale {
            paper: 20,
            model: 1
        }
    );
    let cm = SheetOptions {
        units: Units::Cm,
        ..o.clone()
    };
    assert_eq!(sheet::sheet(&small, &cm, None).unwrap().scale, two);
    // 5:1 is refused, naming the scale that fits.
    let five = SheetOptions {
        scale: Some(Scale { paper: 5, model: 1 }),
        ..o.clone()
    };
    let e = sheet::sheet(&big, &five, None).unwrap_err().to_string();
    assert!(
        e.contains("A3 landscape") && e.contains("at 5:1") && e.contains("be 2:1"),
        "{e}"
    );
    // A scale outside the series, asked for, is kept.
    let three = SheetOptions {
        scale: Some(Scale { paper: 1, model: 3 }),
        ..o
    };
    let s = sheet::sheet(&big, &three, None).unwrap();
    assert_eq!(s.scale, Scale { paper: 1, model: 3 });
    // The front view's frame is the box (and its 1 % pads) at the scale: 102 mm / 3.
    let f = view(&s, NamedView::Front).frame;
    assert!((f.width() - 102.0 / 3.0).abs() < 1e-9, "{f:?}");
}

/// Third angle: the top view above the front view and the right view to its right; first
/// angle: the top view below and the right view to its left.
#[test]
fn views_are_placed_by_the_projection_method() {
    let scene = box_scene(DVec3::ZERO, DVec3::new(50.0, 30.0, 20.0));
    let views = [
        NamedView::Front,
        NamedView::Top,
        NamedView::Right,
        NamedView::Iso,
    ];
    for method in [ProjectionMethod::Third, ProjectionMethod::First] {
        let s = sheet::sheet(&scene, &options(&views, method), None).unwrap();
        let (front, top, right) = (
            view(&s, NamedView::Front).frame,
            view(&s, NamedView::Top).frame,
            view(&s, NamedView::Right).frame,
        );
        match method {
            ProjectionMethod::Third => {
                assert!(top.y1 < front.y0 && right.x0 > front.x1, "{method:?}");
            }
            ProjectionMethod::First => {
                assert!(top.y0 > front.y1 && right.x1 < front.x0, "{method:?}");
            }
        }
        let inside = |r: &sheet::Rect| {
            s.frame.x0 < r.x0 && r.x1 < s.frame.x1 && s.frame.y0 < r.y0 && r.y1 < s.frame.y1
        };
        for v in &s.views {
            assert!(inside(&v.frame), "{:?} {:?}", v.view, v.frame);
            assert!(!v.frame.overlaps(&s.title_block), "{:?}", v.view);
        }
    }
}

/// A box's front and top views share their x extents exactly, front and right their y
/// extents, in mm on the sheet, whatever the box's coordinates; and a view's lines lie in
/// its frame.
#[test]
fn aligned_views_share_their_extents_exactly() {
    for (lo, hi) in [
        (DVec3::ZERO, DVec3::new(100.0, 50.0, 40.0)),
        (DVec3::new(0.3, -1.7, 2.9), DVec3::new(41.1, 13.3, 20.05)),
        (
            DVec3::new(-1e3 / 7.0, 0.1, -3.3),
            DVec3::new(1e3 / 9.0, 77.7, 0.01),
        ),
    ] {
        let scene = box_scene(lo, hi);
        for method in [ProjectionMethod::Third, ProjectionMethod::First] {
            let all = [
                NamedView::Front,
                NamedView::Top,
                NamedView::Bottom,
                NamedView::Right,
                NamedView::Left,
                NamedView::Back,
            ];
            let s = sheet::sheet(&scene, &options(&all, method), None).unwrap();
            let e = |v| paper_extent(view(&s, v));
            let front = e(NamedView::Front);
            for v in [NamedView::Top, NamedView::Bottom] {
                let o = e(v);
                assert_eq!(
                    [o[0], o[2]].map(f64::to_bits),
                    [front[0], front[2]].map(f64::to_bits),
                    "{v:?} {lo} {hi}"
                );
            }
            for v in [NamedView::Right, NamedView::Left, NamedView::Back] {
                let o = e(v);
                assert_eq!(
                    [o[1], o[3]].map(f64::to_bits),
                    [front[1], front[3]].map(f64::to_bits),
                    "{v:?} {lo} {hi}"
                );
            }
            for v in &s.views {
                let [x0, y0, x1, y1] = paper_extent(v);
                let f = v.frame;
                assert!(
                    f.x0 < x0 && x1 < f.x1 && f.y0 < y0 && y1 < f.y1,
                    "{:?}",
                    v.view
                );
                // The pads are 1 % of the largest extent each side: the lines fill the rest, to
                // the exact grid's snapping (2^-24 of the view's side).
                let size = (hi - lo).max_element() * v.factor;
                let (pad, tol) = (0.01 * size, 1e-6 * size);
                assert!(
                    (x0 - f.x0 - pad).abs() < tol && (f.y1 - y1 - pad).abs() < tol,
                    "{:?}: lines {:?}, frame {f:?}, pad {pad}",
                    v.view,
                    [x0, y0, x1, y1]
                );
            }
        }
    }
}

#[test]
fn the_svg_is_in_millimetres_with_the_issue_classes() {
    let scene = box_scene(DVec3::ZERO, DVec3::new(100.0, 50.0, 40.0));
    let s = sheet::sheet(&scene, &options(&ORTHO3, ProjectionMethod::Third), None).unwrap();
    let svg = s.svg();
    assert!(svg.starts_with(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"420mm\" height=\"297mm\" viewBox=\"0 0 420 297\">"
    ));
    assert!(svg.contains(&format!(
        "<g class=\"view\" id=\"view-front\" data-view=\"front\" data-scale=\"{}\">",
        s.scale
    )));
    assert!(svg.contains("<g class=\"visible silhouette\" stroke-width=\"0.5\">"));
    assert!(svg.contains("<path data-kind=\"silhouette\" d=\"M"));
    assert!(svg.contains("aria-label=\"THIRD ANGLE\""));
    assert!(svg.contains("data-method=\"third\""));
    // No text element: every letter is strokes.
    assert!(!svg.contains("<text"));
}

/// Same input and flags, same bytes; the date appears only when given, and is all that
/// changes.
#[test]
fn sheets_are_reproducible_and_dated_only_on_request() {
    let dir = tempfile::tempdir().unwrap();
    let obj = box_obj(dir.path(), "part.obj", [0.0, 0.0, 0.0], [80.0, 50.0, 30.0]);
    let obj = obj.to_str().unwrap();
    let run = |extra: &[&str]| {
        let o = run_ok(&[&["sheet", obj, "-o", "-"][..], extra].concat());
        String::from_utf8(o.stdout).unwrap()
    };
    let a = run(&[]);
    assert_eq!(a, run(&[]));
    assert!(a.starts_with("<svg") && a.contains("aria-label=\"part.obj\""));
    assert!(!a.contains("data-field=\"date\""));
    let dated = run(&["--date", "2026-02-28"]);
    assert!(dated.contains("data-field=\"date\" aria-label=\"2026-02-28\""));
    let undated: String = dated
        .lines()
        .filter(|l| !l.contains("data-field=\"date\""))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_eq!(undated, a);
    // Written to a file, the same bytes.
    let out = dir.path().join("sheet.svg");
    run_ok(&["sheet", obj, "-o", out.to_str().unwrap()]);
    assert_eq!(std::fs::read_to_string(&out).unwrap(), a);
    // The library makes the same document.
    let scene = sightline::load(Path::new(obj), None).unwrap();
    let o = SheetOptions {
        title: "part.obj".into(),
        date: Some(SheetDate::parse("2026-02-28").unwrap()),
        ..SheetOptions::default()
    };
    assert_eq!(sheet::sheet(&scene, &o, None).unwrap().svg(), dated);
}

/// Bad flags fail with a message naming what is wrong, never a panic.
#[test]
fn bad_flags_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let obj = box_obj(
        dir.path(),
        "part.obj",
        [0.0, 0.0, 0.0],
        [300.0, 200.0, 100.0],
    );
    let obj = obj.to_str().unwrap();
    let out = dir.path().join("s.svg");
    let out = out.to_str().unwrap();
    let cases: [(&[&str], &[&str]); 8] = [
        (&["--views", "front,frnt"], &["unknown view 'frnt'"]),
        (&["--views", "top,top"], &["'top' is given twice"]),
        (
            &["--scale", "3:7"],
            &["'3:7' is not a drawing scale", "1:N or N:1"],
        ),
        (&["--scale", "1:0"], &["'1:0'"]),
        (&["--date", "2026-02-30"], &["'2026-02-30'", "no day 30"]),
        (&["--paper", "b5"], &["b5"]),
        (
            &["--crease", "200"],
            &["--crease must be in [0, 180] degrees, got '200'"],
        ),
        (
            &["--scale", "5:1"],
            &["A3 landscape", "do not fit at 5:1", "1:2"],
        ),
    ];
    for (flags, words) in cases {
        let (code, err) = run_err(&[&["sheet", obj, "-o", out][..], flags].concat());
        assert!(
            matches!(code, Some(1) | Some(2)),
            "{flags:?}: {code:?} {err}"
        );
        assert!(!err.contains("panicked"), "{flags:?}: {err}");
        for w in words {
            assert!(err.contains(w), "{flags:?}: no '{w}' in {err}");
        }
    }
    assert!(!Path::new(out).exists(), "no output after an error");
    let (code, err) = run_err(&["sheet", "missing.obj", "-o", out]);
    assert_eq!(code, Some(1));
    assert!(err.contains("missing.obj"), "{err}");
}

#[test]
fn a_sheet_is_written_as_a_vector_pdf_with_its_text_as_strokes() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sheet.pdf");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_sightline"))
        .args(["sheet", "fixtures/cube.obj", "--date", "2026-12-02", "-o"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let pdf = std::fs::read(&out).unwrap();
    assert!(pdf.starts_with(b"%PDF-"));
    // No font and no raster image: the title block's text is strokes, the lines are paths.
    let text = String::from_utf8_lossy(&pdf);
    assert!(!text.contains("/Type /Font") && !text.contains("/Subtype /Image"));
}
