//! What the benchmarks share: the meshes of `../shared/meshes` with their cameras, the group
//! that measures them, and the tests' cameras (`tests/support/camera.rs`).

#[path = "../../tests/support/camera.rs"]
pub mod camera;

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput};
use sightline::camera::{CamFile, Camera, NamedView};
use sightline::scene::Scene;
use std::path::Path;
use std::time::Duration;

/// The iso view of `scene` at 1024x1024 (40-degree field of view), as the benchmarks see the
/// generated scenes.
pub fn iso_1024(scene: &Scene) -> Camera {
    camera::fit(scene, NamedView::Iso, false, 1024, 1024)
}

/// The benchmark group "mesh": for every shared mesh (none when the directory is absent),
/// `bench` adds its benchmarks, 10 samples over `seconds`, throughput in faces.
pub fn mesh_group(
    c: &mut Criterion,
    seconds: u64,
    mut bench: impl FnMut(&mut BenchmarkGroup<'_, WallTime>, String, Scene, Camera),
) {
    let meshes = shared_meshes();
    if meshes.is_empty() {
        return;
    }
    let mut g = c.benchmark_group("mesh");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(seconds));
    for (stem, scene, cam) in meshes {
        g.throughput(Throughput::Elements(scene.faces.len() as u64));
        bench(&mut g, stem, scene, cam);
    }
    g.finish();
}

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
