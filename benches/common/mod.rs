//! What the benchmarks share: the meshes of `../shared/meshes` with their cameras.

use sightline::camera::{CamFile, Camera};
use sightline::scene::Scene;
use std::path::Path;

/// Every mesh of `../shared/meshes` that has a camera in `cams/`, by name, loaded; empty (and
/// said on stderr) when the directory is not present.
pub fn shared_meshes() -> Vec<(String, Scene, Camera)> {
    let dir = Path::new("../shared/meshes");
    if !dir.is_dir() {
        eprintln!("../shared/meshes is not present: skipping the real-mesh benchmarks");
        return Vec::new();
    }
    let mut cams: Vec<_> = std::fs::read_dir(dir.join("cams"))
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .collect();
    cams.sort();
    let mut out = Vec::new();
    for cam_path in cams {
        let stem = cam_path.file_stem().unwrap().to_string_lossy().to_string();
        let mesh = [
            dir.join(format!("{stem}.obj")),
            dir.join(format!("{stem}.obj.gz")),
        ]
        .into_iter()
        .find(|p| p.exists());
        let Some(mesh) = mesh else { continue };
        let text = std::fs::read_to_string(&cam_path).unwrap();
        let cam = CamFile::parse(&text, &stem).unwrap().camera();
        let scene = sightline::load(&mesh, None).unwrap();
        out.push((stem, scene, cam));
    }
    out
}
