//! Every malformed X3D fixture is refused with the file, the element, the line it starts on and a
//! message naming the problem.

use sightline::Location;
use std::path::Path;

/// (fixture, element, line, words the message must contain)
const CASES: &[(&str, &str, usize, &[&str])] = &[
    // The course material's unclosed `<Viewpoint position="0 0 8">`.
    (
        "x3d_syntax.x3d",
        "Viewpoint",
        2,
        &[
            "XML syntax error",
            "<Viewpoint> is never closed",
            "</Scene>",
            "13:1",
        ],
    ),
    (
        "x3d_syntax_attribute.x3d",
        "Coordinate",
        5,
        &["XML syntax error", "6:4"],
    ),
    (
        "x3d_truncated.x3d",
        "TriangleSet",
        5,
        &["XML syntax error", "ends inside <TriangleSet>"],
    ),
    (
        "x3d_bad_number.x3d",
        "Coordinate",
        5,
        &[
            "attribute 'point'",
            "'O'",
            "value 6",
            "not a number",
            "line 6",
        ],
    ),
    (
        "x3d_index_out_of_range.x3d",
        "IndexedFaceSet",
        4,
        &["coordIndex", "index 3", "out of range", "3 point"],
    ),
    (
        "x3d_index_negative.x3d",
        "IndexedFaceSet",
        4,
        &["coordIndex", "-2", "below -1"],
    ),
    (
        "x3d_nan.x3d",
        "Transform",
        3,
        &["attribute 'translation'", "'NaN'", "not a finite number"],
    ),
    (
        "x3d_inf.x3d",
        "Coordinate",
        5,
        &["attribute 'point'", "'1e400'", "not a finite number"],
    ),
    (
        "x3d_point_count.x3d",
        "Coordinate",
        5,
        &["attribute 'point'", "8 numbers", "not a multiple of 3"],
    ),
    (
        "x3d_bad_rotation.x3d",
        "Transform",
        3,
        &["attribute 'rotation'", "needs 4 numbers", "got 3"],
    ),
    (
        "x3d_negative_radius.x3d",
        "Sphere",
        4,
        &["attribute 'radius'", "negative"],
    ),
    (
        "x3d_bad_boolean.x3d",
        "Box",
        4,
        &["attribute 'solid'", "true or false", "'maybe'"],
    ),
    (
        "x3d_bad_fov.x3d",
        "Viewpoint",
        3,
        &["fieldOfView", "between 0 and π"],
    ),
    (
        "x3d_not_x3d.x3d",
        "html",
        2,
        &["not an X3D scene", "<html>"],
    ),
    ("x3d_empty.x3d", "Scene", 3, &["empty scene"]),
    ("x3d_no_scene.x3d", "X3D", 2, &["no <Scene>"]),
];

#[test]
fn each_bad_fixture_names_file_element_line_and_problem() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/bad");
    for &(file, element, line, words) in CASES {
        let path = dir.join(file);
        let e = match sightline::load(&path, None) {
            Ok(_) => panic!("{file}: loaded"),
            Err(e) => e,
        };
        assert_eq!(e.file, path.display().to_string(), "{file}");
        assert_eq!(
            e.location,
            Location::Element {
                name: element.to_string(),
                line
            },
            "{file}: {e}"
        );
        for w in words {
            assert!(e.message.contains(w), "{file}: {e:?} lacks {w:?}");
        }
    }
}

#[test]
fn every_x3d_fixture_in_bad_is_covered() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/bad");
    for entry in std::fs::read_dir(dir).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        if name.starts_with("x3d_") {
            assert!(
                CASES.iter().any(|c| c.0 == name),
                "{name} has no expectation"
            );
        }
    }
}

#[test]
fn bytes_that_are_not_text_or_not_xml() {
    use sightline::scene::{Format, load_bytes};
    for (bytes, name, line) in [
        (&b"<Scene>\n<Shape>\xff\xfe</Shape></Scene>"[..], "Shape", 2),
        (&b"\xff\xff\xff"[..], "xml", 1),
        (&b""[..], "xml", 1),
        (&b"just text"[..], "xml", 1),
        (
            &b"<Scene>\n<Shape><Box/></Shape>\n</Scene>\n<Scene/>"[..],
            "xml",
            4,
        ),
    ] {
        let e = load_bytes(bytes, Format::X3d, "b.x3d", None).unwrap_err();
        assert_eq!(
            e.location,
            Location::Element {
                name: name.into(),
                line
            },
            "{e}"
        );
    }
}
