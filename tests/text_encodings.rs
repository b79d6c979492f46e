//! Every text format (OBJ, MTL, ASCII PLY, ASCII STL, X3D) reads the same with a leading UTF-8
//! byte-order mark and with CRLF line ends as without, and errors keep naming the right line.

mod support;

use sightline::error::{LoadError, Location};
use sightline::scene::{Scene, load};
use std::path::Path;
use support::fixtures::fixtures_dir;

const BOM: &str = "\u{feff}";

/// The text with a BOM, with CRLF line ends, and with both.
fn variants(text: &str) -> [(&'static str, String); 3] {
    let crlf = text.replace('\n', "\r\n");
    [
        ("BOM", format!("{BOM}{text}")),
        ("CRLF", crlf.clone()),
        ("BOM and CRLF", format!("{BOM}{crlf}")),
    ]
}

fn fixture_text(name: &str) -> String {
    std::fs::read_to_string(fixtures_dir().join(name)).unwrap()
}

/// Writes the files into `dir` and loads the first one.
fn load_files(dir: &Path, files: &[(&str, &str)]) -> Result<Scene, LoadError> {
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    load(&dir.join(files[0].0), None)
}

fn assert_same(got: &Scene, want: &Scene, what: &str) {
    assert_eq!(got.positions, want.positions, "{what}: positions");
    assert_eq!(got.corners, want.corners, "{what}: corners");
    assert_eq!(got.faces.len(), want.faces.len(), "{what}: faces");
    assert_eq!(got.meshes, want.meshes, "{what}: meshes");
    assert_eq!(got.materials, want.materials, "{what}: materials");
    assert_eq!(got.corner_normals, want.corner_normals, "{what}: normals");
    assert_eq!(got.stats.warnings, want.stats.warnings, "{what}: warnings");
}

/// Loads `text` as file `name` plainly and in every variant, and compares.
fn check_variants(name: &str, text: &str) {
    let dir = tempfile::tempdir().unwrap();
    let want = load_files(dir.path(), &[(name, text)]).unwrap_or_else(|e| panic!("{e}"));
    for (what, t) in variants(text) {
        let got = load_files(dir.path(), &[(name, &t)])
            .unwrap_or_else(|e| panic!("{name} with {what}: {e}"));
        assert_same(&got, &want, &format!("{name} with {what}"));
    }
}

/// The error of `text` (as file `name`) is at `line` in every variant.
fn check_error_line(name: &str, text: &str, line: usize) {
    let dir = tempfile::tempdir().unwrap();
    let plain = load_files(dir.path(), &[(name, text)]).unwrap_err();
    assert_eq!(plain.location, Location::Line(line), "{plain}");
    for (what, t) in variants(text) {
        let e = load_files(dir.path(), &[(name, &t)]).unwrap_err();
        assert_eq!(e.location, plain.location, "{name} with {what}: {e}");
        assert_eq!(e.message, plain.message, "{name} with {what}");
    }
}

#[test]
fn obj_keeps_its_first_vertex_after_a_bom() {
    let dir = tempfile::tempdir().unwrap();
    let s = load_files(
        dir.path(),
        &[(
            "t.obj",
            &format!("{BOM}v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        )],
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.positions.len(), 3);
    assert_eq!(s.faces.len(), 1);
    assert!(s.stats.warnings.is_empty(), "{:?}", s.stats.warnings);
}

#[test]
fn obj_reads_the_same_with_bom_and_crlf() {
    check_variants("cube.obj", &fixture_text("cube.obj"));
    check_variants("tetra.obj", &fixture_text("tetra_neg_indices.obj"));
    // A continuation line (backslash before the CRLF) joins as with LF.
    check_variants("cont.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 \\\n 2 3\n");
}

#[test]
fn mtl_reads_the_same_with_bom_and_crlf() {
    let dir = tempfile::tempdir().unwrap();
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
    // The first line is a statement, so a BOM left in place would hide it.
    let mtl = "newmtl red\nKd 1 0 0\nd 0.5\n";
    let want = load_files(dir.path(), &[("t.obj", obj), ("m.mtl", mtl)]).unwrap();
    assert_eq!(want.materials[0].diffuse, [1.0, 0.0, 0.0]);
    assert!(want.stats.warnings.is_empty(), "{:?}", want.stats.warnings);
    for (what, m) in variants(mtl) {
        let got = load_files(dir.path(), &[("t.obj", obj), ("m.mtl", &m)])
            .unwrap_or_else(|e| panic!("mtl with {what}: {e}"));
        assert_same(&got, &want, &format!("mtl with {what}"));
    }
    for (what, o) in variants(obj) {
        let got = load_files(dir.path(), &[("t.obj", &o), ("m.mtl", mtl)])
            .unwrap_or_else(|e| panic!("obj with {what}: {e}"));
        assert_same(&got, &want, &format!("obj with {what}"));
    }
}

#[test]
fn ascii_ply_reads_the_same_with_bom_and_crlf() {
    check_variants("cube.ply", &fixture_text("cube_ascii.ply"));
}

#[test]
fn binary_ply_header_may_start_with_a_bom() {
    let dir = tempfile::tempdir().unwrap();
    let plain = std::fs::read(fixtures_dir().join("cube_binary_le.ply")).unwrap();
    let mut with_bom = BOM.as_bytes().to_vec();
    with_bom.extend_from_slice(&plain);
    std::fs::write(dir.path().join("a.ply"), &plain).unwrap();
    std::fs::write(dir.path().join("b.ply"), &with_bom).unwrap();
    let want = load(&dir.path().join("a.ply"), None).unwrap();
    let got = load(&dir.path().join("b.ply"), None).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(got.positions, want.positions);
    assert_eq!(got.corners, want.corners);
}

#[test]
fn ascii_stl_reads_the_same_with_bom_and_crlf() {
    check_variants("cube.stl", &fixture_text("cube_ascii.stl"));
}

#[test]
fn x3d_reads_the_same_with_bom_and_crlf() {
    check_variants("seed.x3d", &fixture_text("seed_transparent.x3d"));
    check_variants("indexed.x3d", &fixture_text("indexed.x3d"));
}

#[test]
fn error_lines_are_the_same_with_bom_and_crlf() {
    check_error_line("t.obj", "v 0 0 0\nv 1 0 0\n\nv 0 1 x\n", 4);
    check_error_line(
        "t.ply",
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 x\n",
        8,
    );
    check_error_line("h.ply", "ply\nformat ascii 1.0\nbogus\n", 3);
    check_error_line(
        "t.stl",
        "solid s\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 x\n",
        5,
    );
    // An MTL error names the .mtl and its line.
    let dir = tempfile::tempdir().unwrap();
    let mtl = "newmtl red\nKd 1 0 0\nKd 1 x 0\n";
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    for (what, m) in variants(mtl) {
        let e = load_files(dir.path(), &[("t.obj", obj), ("m.mtl", &m)]).unwrap_err();
        assert_eq!(e.location, Location::Line(3), "mtl with {what}: {e}");
        assert!(e.file.ends_with("m.mtl"), "mtl with {what}: {e}");
    }
    // X3D errors name the element and the line it starts on.
    let x3d = "<Scene>\n<Shape>\n<TriangleSet>\n<Coordinate\n point='0 0 x'/>\n</TriangleSet>\n</Shape>\n</Scene>\n";
    let plain = load_files(dir.path(), &[("t.x3d", x3d)]).unwrap_err();
    assert_eq!(
        plain.location,
        Location::Element {
            name: "Coordinate".into(),
            line: 4
        },
        "{plain}"
    );
    for (what, t) in variants(x3d) {
        let e = load_files(dir.path(), &[("t.x3d", &t)]).unwrap_err();
        assert_eq!(e.location, plain.location, "x3d with {what}: {e}");
    }
}
