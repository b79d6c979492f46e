//! Every malformed fixture in `fixtures/bad` is refused with an error that names the file, the
//! exact line or byte, and the problem.

mod support;

use sightline::Location;
use sightline::scene::load;

/// Loads `fixtures/bad/{name}` and checks the error's file (`file`, default the fixture itself),
/// location, and that its message contains every one of `needles`.
fn check_in(name: &str, file: Option<&str>, location: Location, needles: &[&str]) {
    let dir = fixtures_dir().join("bad");
    let path = dir.join(name);
    let e = match load(&path, None) {
        Ok(s) => panic!("{name}: loaded {} faces, expected an error", s.faces.len()),
        Err(e) => e,
    };
    let want_file = dir.join(file.unwrap_or(name)).display().to_string();
    assert_eq!(e.file, want_file, "{name}: {e}");
    assert_eq!(e.location, location, "{name}: {e}");
    for n in needles {
        assert!(e.message.contains(n), "{name}: message lacks {n:?}: {e}");
    }
}

fn check(name: &str, location: Location, needles: &[&str]) {
    check_in(name, None, location, needles)
}

use Location::{Byte, File, Line};
use support::fixtures::fixtures_dir;

#[test]
fn obj_bad_number() {
    check("obj_bad_number.obj", Line(3), &["bad number", "abc"]);
}

#[test]
fn obj_index_out_of_range() {
    check(
        "obj_index_out_of_range.obj",
        Line(6),
        &["vertex index 7 out of range", "4 vertices"],
    );
}

#[test]
fn obj_negative_index_out_of_range() {
    check(
        "obj_negative_out_of_range.obj",
        Line(5),
        &["vertex index -4 out of range", "only 3 vertices"],
    );
}

#[test]
fn obj_index_zero() {
    check("obj_index_zero.obj", Line(5), &["index 0"]);
}

#[test]
fn obj_nan() {
    check("obj_nan.obj", Line(2), &["'nan'", "not finite"]);
}

#[test]
fn obj_inf() {
    check("obj_inf.obj", Line(3), &["'1e999'", "not finite"]);
}

#[test]
fn obj_short_face() {
    check("obj_short_face.obj", Line(5), &["2 corners", "at least 3"]);
}

#[test]
fn obj_bad_corner() {
    check(
        "obj_bad_corner.obj",
        Line(5),
        &["bad face corner", "3/1/2/3"],
    );
}

#[test]
fn obj_empty() {
    check("obj_empty.obj", File, &["empty scene", "no faces"]);
}

#[test]
fn mtl_bad_number_names_the_mtl_file() {
    check_in(
        "mtl_bad_number.obj",
        Some("mtl_bad_number.mtl"),
        Line(3),
        &["bad number", "zero", "Kd"],
    );
}

#[test]
fn obj_texture_coordinate_index_zero() {
    check(
        "obj_vt_index_zero.obj",
        Line(6),
        &["texture coordinate index 0", "start at 1"],
    );
}

#[test]
fn obj_normal_index_zero() {
    check(
        "obj_vn_index_zero.obj",
        Line(6),
        &["normal index 0", "start at 1"],
    );
}

#[test]
fn obj_texture_coordinate_out_of_range_names_the_face_line() {
    // Found only at the end of the file (a vt may follow the face), reported at the face.
    check(
        "obj_vt_out_of_range.obj",
        Line(8),
        &[
            "texture coordinate index 3 out of range",
            "the file has 2 texture coordinates",
        ],
    );
}

#[test]
fn obj_negative_normal_index_out_of_range() {
    check(
        "obj_vn_negative_out_of_range.obj",
        Line(7),
        &[
            "normal index -3 out of range",
            "only 1 normals are defined before this line",
        ],
    );
}

#[test]
fn obj_first_attribute_index_out_of_range_is_reported() {
    // A bad normal on line 6 and a bad texture coordinate on line 8: line 6 is reported.
    check(
        "obj_vn_out_of_range.obj",
        Line(6),
        &["normal index 2 out of range", "the file has 1 normals"],
    );
}

#[test]
fn obj_texture_coordinate_bad_number() {
    check("obj_vt_bad_number.obj", Line(4), &["bad number", "'0,5'"]);
}

#[test]
fn obj_texture_coordinate_without_numbers() {
    check("obj_vt_empty.obj", Line(4), &["vt has no coordinates"]);
}

#[test]
fn obj_normal_with_two_numbers() {
    check(
        "obj_vn_short.obj",
        Line(5),
        &["vn has 2 coordinates, needs 3"],
    );
}

#[test]
fn obj_normal_nan() {
    check("obj_vn_nan.obj", Line(4), &["'nan'", "not finite"]);
}

#[test]
fn mtl_texture_without_file_name_names_the_mtl_file() {
    check_in(
        "mtl_map_kd_no_file.obj",
        Some("mtl_map_kd_no_file.mtl"),
        Line(4),
        &["map_Kd without a file name"],
    );
}

#[test]
fn stl_truncated() {
    check(
        "stl_truncated.stl",
        Byte(334),
        &[
            "truncated",
            "expected 12 triangles (684 bytes), file has 364 bytes",
        ],
    );
}

#[test]
fn stl_nan_binary() {
    check(
        "stl_nan.stl",
        Byte(184),
        &["triangle 3 of 12", "not finite"],
    );
}

#[test]
fn stl_ascii_syntax() {
    check(
        "stl_ascii_syntax.stl",
        Line(3),
        &["expected 'loop'", "'lop'"],
    );
}

#[test]
fn stl_ascii_four_vertices() {
    check(
        "stl_ascii_four_vertices.stl",
        Line(7),
        &["more than 3 vertices"],
    );
}

#[test]
fn stl_ascii_inf() {
    check("stl_ascii_inf.stl", Line(12), &["'-inf'", "not finite"]);
}

#[test]
fn stl_ascii_unterminated() {
    check(
        "stl_ascii_unterminated.stl",
        Line(5),
        &["unexpected end of file"],
    );
}

#[test]
fn ply_truncated_binary() {
    check(
        "ply_truncated_binary.ply",
        Byte(595),
        &["truncated", "face 6 of 6"],
    );
}

#[test]
fn ply_truncated_ascii() {
    check(
        "ply_truncated_ascii.ply",
        Line(14),
        &[
            "unexpected end of data",
            "'face' declares 2 entries, only 1",
        ],
    );
}

#[test]
fn ply_bad_header() {
    check(
        "ply_bad_header.ply",
        Line(5),
        &["unknown property type", "'quad'"],
    );
}

#[test]
fn ply_bad_magic() {
    check("ply_bad_magic.ply", Line(1), &["not a PLY file"]);
}

#[test]
fn ply_unsupported_format() {
    check(
        "ply_unsupported_format.ply",
        Line(2),
        &["unsupported format", "binary_middle_endian"],
    );
}

#[test]
fn ply_no_end_header() {
    check("ply_no_end_header.ply", Line(8), &["end_header"]);
}

#[test]
fn ply_bad_count() {
    check("ply_bad_count.ply", Line(3), &["bad element count", "'-3'"]);
}

#[test]
fn ply_index_out_of_range() {
    check(
        "ply_index_out_of_range.ply",
        Line(15),
        &["face 2 of 2", "vertex index 4 out of range", "4 vertices"],
    );
}

#[test]
fn ply_nan() {
    check("ply_nan.ply", Line(12), &["vertex 3 of 3", "not finite"]);
}

#[test]
fn ply_no_faces() {
    check("ply_no_faces.ply", File, &["empty scene", "point cloud"]);
}

#[test]
fn ply_huge_count() {
    // The header claims 4e9 vertices (48 GB); the check against the 100 bytes present fails
    // before anything is allocated, naming the first vertex that is not there.
    check(
        "ply_huge_count.ply",
        Byte(331),
        &["4000000000 entries", "only 100 bytes are left"],
    );
}

#[test]
fn every_bad_fixture_has_a_test() {
    // OBJ, MTL, STL and PLY fixtures are tested here; X3D ones in malformed_x3d.rs.
    let src = include_str!("malformed_mesh_formats.rs");
    for entry in std::fs::read_dir(fixtures_dir().join("bad")).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        if name.ends_with(".x3d") {
            continue;
        }
        assert!(src.contains(&format!("\"{name}\"")), "{name} is not tested");
    }
}
