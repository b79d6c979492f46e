//! The scene report `sightline info` prints: what was loaded, what the camera sees, what culling
//! removes, and which later stages the scene needs (depth ordering, splitting, blending).
//!
//! Invariant: the report is a function of the scene, the camera and the culling mode only (no
//! timings), so the same input and flags print the same text.

use crate::camera::{Camera, Projection};
use crate::pipeline::{Prepared, screen_extents_overlap};
use crate::scene::Scene;
use glam::DVec3;
use std::fmt;
use std::path::Path;

/// Meshes listed one by one; the rest are counted.
const MESHES_LISTED: usize = 20;

/// The report on `scene`, loaded from `file` and seen by `camera` (`prepared` by
/// [`crate::pipeline::prepare`]), as text (`Display`).
pub struct SceneReport<'a> {
    /// The file the scene came from, as the user named it.
    pub file: &'a Path,
    /// The scene.
    pub scene: &'a Scene,
    /// The camera.
    pub camera: &'a Camera,
    /// The scene analysed and projected by the camera.
    pub prepared: &'a Prepared,
}

impl fmt::Display for SceneReport<'_> {
    fn fmt(&self, o: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (scene, camera) = (self.scene, self.camera);
        let an = &self.prepared.analysis;
        let st = &self.prepared.screen.stats;
        let v3 = |v: DVec3| format!("({}, {}, {})", v.x, v.y, v.z);
        writeln!(o, "file: {}", self.file.display())?;
        writeln!(
            o,
            "faces: {} polygons from {} input faces ({} degenerate dropped, {} non-planar triangulated)",
            scene.faces.len(),
            scene.input_faces,
            scene.stats.degenerate_dropped,
            scene.stats.nonplanar_triangulated
        )?;
        writeln!(o, "vertices: {}", scene.positions.len())?;
        let closed = an.meshes.iter().filter(|m| m.closed()).count();
        writeln!(
            o,
            "meshes: {} ({} closed, {} open)",
            scene.meshes.len(),
            closed,
            scene.meshes.len() - closed
        )?;
        for (m, ma) in scene.meshes.iter().zip(&an.meshes).take(MESHES_LISTED) {
            let state = if ma.closed() {
                if ma.inside_out() {
                    "closed, inside-out (flipped)".to_string()
                } else if ma.cullable() {
                    "closed".to_string()
                } else {
                    "closed, orientation uncertain (zero volume)".to_string()
                }
            } else {
                format!(
                    "open ({} boundary, {} non-manifold, {} inconsistent edges)",
                    ma.boundary_edges, ma.nonmanifold_edges, ma.inconsistent_edges
                )
            };
            writeln!(
                o,
                "  {}: {} faces, {}, volume {:.6e}",
                m.name,
                m.faces.len(),
                state,
                ma.signed_volume
            )?;
        }
        if scene.meshes.len() > MESHES_LISTED {
            writeln!(o, "  ... {} more", scene.meshes.len() - MESHES_LISTED)?;
        }
        if let Some((lo, hi)) = scene.bounds() {
            writeln!(o, "bounds: min {} max {}", v3(lo), v3(hi))?;
        }
        let proj = match camera.projection {
            Projection::Perspective { fovy_deg } => format!("perspective, fovy {fovy_deg} deg"),
            Projection::Orthographic { height } => format!("orthographic, height {height}"),
        };
        writeln!(
            o,
            "camera: {proj}, eye {}, target {}, up {}, near {}, far {}, {}x{}",
            v3(camera.eye),
            v3(camera.target),
            v3(camera.up),
            camera.near,
            camera.far,
            camera.width,
            camera.height
        )?;
        writeln!(
            o,
            "culling: {} frustum culled, {} back faces culled ({} meshes cullable, {} cut by the near plane), {} clipped, {} degenerate after snapping, {} split into triangles (snapped corners off their plane)",
            st.frustum_culled,
            st.backface_culled,
            st.culled_meshes,
            st.meshes_cut_by_near,
            st.clipped,
            st.degenerate_after_snap,
            st.split_nonplanar
        )?;
        writeln!(o, "on screen: {} polygons", st.visible_polys)?;
        writeln!(o, "stages needed:")?;
        let overlap = screen_extents_overlap(&self.prepared.screen);
        writeln!(
            o,
            "  depth ordering (overlapping screen extents): {}",
            if overlap { "yes" } else { "no" }
        )?;
        writeln!(
            o,
            "  splitting (interpenetration possible between meshes): {}",
            if an.overlapping_mesh_pairs > 0 {
                format!(
                    "yes, {} pairs of meshes with overlapping bounds",
                    an.overlapping_mesh_pairs
                )
            } else {
                "no (self-intersection within a mesh is not checked)".to_string()
            }
        )?;
        writeln!(
            o,
            "  blending (translucency): {}",
            if an.translucent_faces > 0 {
                format!("yes, {} translucent faces", an.translucent_faces)
            } else {
                "no".to_string()
            }
        )?;
        writeln!(o, "two-sided faces: {}", an.two_sided_faces)?;
        writeln!(o, "warnings: {}", scene.stats.warnings.len())
    }
}
