//! The fixture files: where they are, which of them load, loading one by name; and what every
//! loaded scene keeps, whatever the input.

use sightline::scene::Scene;
use std::path::{Path, PathBuf};

/// `fixtures/`, wherever the tests run from.
pub fn fixtures_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures")
}

/// Loads `fixtures/{name}`; a load error fails the test with its message.
pub fn fixture(name: &str) -> Scene {
    sightline::load(&fixtures_dir().join(name), None).unwrap_or_else(|e| panic!("{e}"))
}

/// Every loadable fixture (`fixtures/`, not `fixtures/bad`), by path, in name order.
pub fn fixture_paths() -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(fixtures_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.is_file()
                && matches!(
                    p.extension().and_then(|e| e.to_str()),
                    Some("obj" | "stl" | "ply" | "x3d")
                )
        })
        .collect();
    out.sort();
    assert!(out.len() >= 15, "fixtures missing: {out:?}");
    out
}

/// Per-corner attributes of a loaded scene are absent or parallel to the corners, and finite.
pub fn assert_corner_attributes(s: &Scene) {
    for len in [s.corner_uvs.len(), s.corner_normals.len()] {
        assert!(len == 0 || len == s.corners.len());
    }
    assert!(
        s.corner_uvs
            .iter()
            .flatten()
            .flatten()
            .all(|x| x.is_finite())
    );
    assert!(s.corner_normals.iter().flatten().all(|n| n.is_finite()));
}
