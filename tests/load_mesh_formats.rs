//! Every good fixture loads with the expected counts, materials and ids, and the cube reads the
//! same in every format.

mod support;

use glam::DVec3;
use sightline::scene::{Format, Scene, load, load_bytes};
use support::fixtures::{fixture, fixtures_dir};
use support::generated::{CUBE_QUADS, binary_stl, cube_binary_stl, cube_triangles};

fn ids(s: &Scene) -> Vec<u32> {
    s.faces.iter().map(|f| f.id).collect()
}

/// The scene's faces fan-split into triangles, each rotated to start at its smallest corner
/// (orientation kept), sorted: equal for two scenes with the same oriented surface written with the
/// same quad split.
fn triangle_set(s: &Scene) -> Vec<[[u64; 3]; 3]> {
    let key = |p: DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
    let mut out = Vec::new();
    for f in &s.faces {
        let p: Vec<_> = s.face_positions(f).map(key).collect();
        for k in 1..p.len() - 1 {
            let mut t = [p[0], p[k], p[k + 1]];
            let m = (0..3).min_by_key(|&i| t[i]).unwrap();
            t.rotate_left(m);
            out.push(t);
        }
    }
    out.sort();
    out
}

/// Volume by the divergence theorem: positive for a closed, outward-oriented surface.
fn volume(s: &Scene) -> f64 {
    s.faces
        .iter()
        .map(|f| {
            let p: Vec<_> = s.face_positions(f).collect();
            (1..p.len() - 1)
                .map(|k| p[0].dot(p[k].cross(p[k + 1])) / 6.0)
                .sum::<f64>()
        })
        .sum()
}

fn cube_checks(s: &Scene, faces: usize) {
    assert_eq!(s.positions.len(), 8, "{}", s.source);
    assert_eq!(s.faces.len(), faces, "{}", s.source);
    assert_eq!(s.meshes.len(), 1, "{}", s.source);
    assert_eq!(s.bounds(), Some((DVec3::ZERO, DVec3::ONE)));
    assert!(
        (volume(s) - 1.0).abs() < 1e-12,
        "{}: volume {}",
        s.source,
        volume(s)
    );
}

#[test]
fn cube_obj_with_materials() {
    let s = fixture("cube.obj");
    cube_checks(&s, 6);
    assert!(s.stats.warnings.is_empty(), "{:?}", s.stats.warnings);
    assert_eq!(ids(&s), (0..6).collect::<Vec<_>>());
    assert_eq!(s.meshes[0].name, "cube");
    let mat = |k: usize| &s.materials[s.faces[k].material as usize];
    for k in 0..5 {
        assert_eq!(mat(k).name, "red");
        assert_eq!(mat(k).diffuse, [1.0, 0.0, 0.0]);
        assert_eq!(mat(k).transparency, 0.0);
    }
    let glass = mat(5);
    assert_eq!(glass.name, "blue_glass");
    assert_eq!(glass.diffuse, [0.0, 0.0, 1.0]);
    assert_eq!(glass.emissive, [0.1, 0.1, 0.1]);
    assert_eq!(glass.transparency, 0.25, "Tr after d wins");
    // Quads in file order, corners as written.
    assert_eq!(s.face_corners(&s.faces[0]), &[0, 3, 2, 1]);
    assert_eq!(s.face_corners(&s.faces[5]), &[1, 2, 6, 5]);
}

#[test]
fn obj_from_memory_does_not_follow_mtllib() {
    let bytes = std::fs::read(fixtures_dir().join("cube.obj")).unwrap();
    let s = load_bytes(&bytes, Format::Obj, "mem", None).unwrap();
    assert!(s.materials.iter().all(|m| m.name == "default"));
    assert!(s.stats.warnings.iter().any(|w| w.contains("mtllib")));
}

#[test]
fn cube_stl_ascii_and_binary() {
    for name in ["cube_ascii.stl", "cube_binary.stl"] {
        let s = fixture(name);
        cube_checks(&s, 12);
        assert_eq!(ids(&s), (0..12).collect::<Vec<_>>(), "{name}");
        assert!(s.stats.warnings.is_empty(), "{:?}", s.stats.warnings);
    }
    assert_eq!(fixture("cube_ascii.stl").meshes[0].name, "cube");
}

#[test]
fn stl_welding_shares_vertices() {
    let s = fixture("cube_binary.stl");
    // 36 corners over 8 positions; every undirected edge is used by exactly two triangles, in
    // opposite directions (closed and consistently oriented), which needs shared indices.
    assert_eq!(s.corners.len(), 36);
    let mut directed = std::collections::HashMap::new();
    for f in &s.faces {
        let c = s.face_corners(f);
        for k in 0..3 {
            *directed.entry((c[k], c[(k + 1) % 3])).or_insert(0) += 1;
        }
    }
    for (&(a, b), &n) in &directed {
        assert_eq!(n, 1, "edge {a}->{b} used twice in one direction");
        assert_eq!(directed.get(&(b, a)), Some(&1), "edge {a}->{b} has no twin");
    }
    let mut used: Vec<u32> = s.corners.clone();
    used.sort();
    used.dedup();
    assert_eq!(used, (0..8).collect::<Vec<_>>());
}

#[test]
fn cube_ply_all_encodings() {
    for name in ["cube_ascii.ply", "cube_binary_le.ply", "cube_binary_be.ply"] {
        let s = fixture(name);
        cube_checks(&s, 6);
        assert_eq!(ids(&s), (0..6).collect::<Vec<_>>(), "{name}");
        assert_eq!(s.meshes[0].name, name);
        for (k, q) in CUBE_QUADS.iter().enumerate() {
            let want: Vec<u32> = q.iter().map(|&i| i as u32).collect();
            assert_eq!(s.face_corners(&s.faces[k]), &want[..], "{name}");
        }
    }
}

#[test]
fn the_cube_is_the_same_in_every_format() {
    let reference = triangle_set(&fixture("cube.obj"));
    assert_eq!(reference.len(), 12);
    for name in [
        "cube_ascii.stl",
        "cube_binary.stl",
        "cube_ascii.ply",
        "cube_binary_le.ply",
        "cube_binary_be.ply",
    ] {
        assert_eq!(triangle_set(&fixture(name)), reference, "{name}");
    }
}

#[test]
fn tetrahedron_with_negative_indices() {
    let s = fixture("tetra_neg_indices.obj");
    assert_eq!(s.positions.len(), 4);
    assert_eq!(ids(&s), vec![0, 1, 2, 3]);
    let corners: Vec<&[u32]> = s.faces.iter().map(|f| s.face_corners(f)).collect();
    assert_eq!(
        corners,
        vec![&[0, 2, 1][..], &[0, 1, 3], &[0, 3, 2], &[1, 2, 3]]
    );
    assert!((volume(&s) - 1.0 / 6.0).abs() < 1e-15);
}

#[test]
fn objects_groups_triangulation_and_degenerates() {
    let s = fixture("two_objects.obj");
    assert!(s.stats.warnings.is_empty(), "{:?}", s.stats.warnings);
    assert_eq!(s.input_faces, 5);
    assert_eq!(s.stats.nonplanar_triangulated, 1);
    assert_eq!(s.stats.degenerate_dropped, 1);
    let names: Vec<&str> = s.meshes.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, vec!["wedge", "flat"], "g does not start a mesh");
    // The non-planar quad became two triangles sharing id 0; id 2 (degenerate) is missing.
    assert_eq!(ids(&s), vec![0, 0, 1, 3, 4]);
    assert_eq!(s.meshes[0].faces, 0..3);
    assert_eq!(s.meshes[1].faces, 3..5);
    assert!(s.faces[..2].iter().all(|f| f.len == 3));
    assert_eq!(s.faces[3].len, 4);
    // The two pieces cover the quad's projection and keep its (upward) winding.
    let area: f64 = s.faces[..2].iter().map(|f| s.face_normal(f).z / 2.0).sum();
    assert!((area - 4.0).abs() < 1e-12, "{area}");
}

/// Gzips `bytes` into `dir/name`.
fn write_gz(dir: &std::path::Path, name: &str, bytes: &[u8]) -> std::path::PathBuf {
    use std::io::Write;
    let path = dir.join(name);
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    gz.write_all(bytes).unwrap();
    std::fs::write(&path, gz.finish().unwrap()).unwrap();
    path
}

#[test]
fn gzipped_fixtures_load_as_the_plain_ones() {
    // A .gz is decompressed as it is parsed, without knowing its decompressed size in advance.
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(fixtures_dir().join("cube.mtl"), dir.path().join("cube.mtl")).unwrap();
    for name in [
        "cube.obj",
        "cube_ascii.stl",
        "cube_binary.stl",
        "cube_ascii.ply",
        "cube_binary_le.ply",
        "cube_binary_be.ply",
        "seed_transparent.x3d",
        "indexed.x3d",
    ] {
        let plain = fixture(name);
        let bytes = std::fs::read(fixtures_dir().join(name)).unwrap();
        let path = write_gz(dir.path(), &format!("{name}.gz"), &bytes);
        let gz = load(&path, None).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(gz.positions, plain.positions, "{name}");
        assert_eq!(gz.corners, plain.corners, "{name}");
        assert_eq!(ids(&gz), ids(&plain), "{name}");
        assert_eq!(
            gz.stats.warnings.len(),
            plain.stats.warnings.len(),
            "{name}"
        );
        assert_eq!(gz.background, plain.background, "{name}");
    }
}

#[test]
fn gzipped_binary_stl_with_a_solid_header_is_binary() {
    // Without the decompressed size, the rule is: `solid` and no NUL in the first KiB is ASCII.
    let dir = tempfile::tempdir().unwrap();
    let bytes = binary_stl("solid cube, but binary", &cube_triangles());
    let path = write_gz(dir.path(), "cube.stl.gz", &bytes);
    let s = load(&path, None).unwrap_or_else(|e| panic!("{e}"));
    cube_checks(&s, 12);
}

#[test]
fn gzipped_truncated_binary_stl_fails_as_the_plain_one() {
    let dir = tempfile::tempdir().unwrap();
    let mut bytes = cube_binary_stl();
    bytes.truncate(84 + 50 * 5 + 20);
    std::fs::write(dir.path().join("t.stl"), &bytes).unwrap();
    let plain = load(&dir.path().join("t.stl"), None).unwrap_err();
    let gz = load(&write_gz(dir.path(), "t.stl.gz", &bytes), None).unwrap_err();
    assert_eq!(plain.location, sightline::Location::Byte(84 + 50 * 5));
    assert_eq!(gz.location, plain.location);
    assert_eq!(gz.message, plain.message);
}

#[test]
fn broken_gzip_data_is_an_error_not_a_short_scene() {
    let dir = tempfile::tempdir().unwrap();
    let bytes = std::fs::read(fixtures_dir().join("cube.obj")).unwrap();
    let path = write_gz(dir.path(), "c.obj.gz", &bytes);
    let gz = std::fs::read(&path).unwrap();
    // Cut in the middle: the faces that are there must not load as a smaller scene.
    std::fs::write(&path, &gz[..gz.len() / 2]).unwrap();
    let e = load(&path, None).unwrap_err();
    assert_eq!(e.location, sightline::Location::File, "{e}");
    assert!(e.message.starts_with("bad gzip data"), "{e}");
    // A corrupted checksum.
    let mut bad = gz.clone();
    let n = bad.len();
    bad[n - 6] ^= 0xff;
    std::fs::write(&path, &bad).unwrap();
    let e = load(&path, None).unwrap_err();
    assert!(e.message.starts_with("bad gzip data"), "{e}");
}

#[test]
fn progress_counts_the_bytes_of_the_file_on_disk() {
    let dir = tempfile::tempdir().unwrap();
    let bytes = std::fs::read(fixtures_dir().join("cube.obj")).unwrap();
    let gz = write_gz(dir.path(), "c.obj.gz", &bytes);
    for path in [fixtures_dir().join("cube.obj"), gz] {
        let size = std::fs::metadata(&path).unwrap().len();
        let mut calls: Vec<(u64, u64)> = Vec::new();
        sightline::scene::load_with_progress(&path, None, &mut |read, total| {
            calls.push((read, total))
        })
        .unwrap();
        assert!(calls.iter().all(|&(_, t)| t == size), "{calls:?}");
        assert!(calls.windows(2).all(|w| w[0].0 <= w[1].0), "{calls:?}");
        assert_eq!(calls.last(), Some(&(size, size)), "{}", path.display());
    }
}

#[test]
fn only_x3d_scenes_have_a_background() {
    for name in ["cube.obj", "cube_ascii.stl", "cube_binary_le.ply"] {
        assert_eq!(fixture(name).background, None, "{name}");
    }
}
