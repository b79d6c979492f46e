//! Feature edges: which edges of the mesh are lines of the drawing, and of which kind.
//!
//! Invariants:
//! - **Welding**: vertices at identical positions (exact f64 equality, -0 equal to 0) are one
//!   vertex, whatever mesh or index they come from; an edge is an unordered pair of welded
//!   vertices, and its faces are every face with a side between them.
//! - **One kind per edge**, the first that applies in [`LineKind`] order: silhouette, boundary,
//!   crease, material (intersections are not edges: see `intersections`).
//! - **Silhouette, exactly and whatever the winding**: an edge of two faces is a silhouette when
//!   both faces lie on the same side of it on screen, or exactly one of them is edge-on. The side
//!   a face lies on is its exact orientation on the snapped grid
//!   ([`crate::project::Orientation`]) read along the edge's direction in that face: for a
//!   triangle, the exact side of its opposite corner, so the test is the one through the eye
//!   and the edge's two opposite corners, on the grid every other stage uses. Two faces that
//!   both lie flat on screen make no silhouette (their edge is inside the contour they form).
//! - **Crease** compares the faces' Newell normals (made consistent when the two faces run along
//!   the edge the same way, as inconsistently wound meshes do) with the crease angle: a
//!   threshold on the input data chosen by the user, not a visibility decision; an edge within
//!   a rounding error of the threshold may go either way.
//! - Edges whose faces lie wholly outside the view (one frustum plane) are not features of this
//!   view.

use super::drawing::LineKind;
use crate::buckets::sorted_by_low;
use crate::project::{Orientation, ScreenScene};
use crate::scene::Scene;
use glam::DVec3;
use rustc_hash::FxHashMap as HashMap;

/// A side of a face: corner `k` of `face` to corner `k + 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct FaceSide {
    /// Index into `Scene::faces`.
    pub face: u32,
    /// The side's first corner, within the face.
    pub k: u32,
}

/// A feature edge.
#[derive(Clone, Debug, PartialEq)]
pub struct FeatureEdge {
    /// Its two ends, as indices into `Scene::positions` (the first position of each welded
    /// vertex), `a` the one of the smaller welded id.
    pub ends: [u32; 2],
    /// Its kind.
    pub kind: LineKind,
    /// The face sides along it (at least one), in face order.
    pub sides: Vec<FaceSide>,
}

/// The feature edges of a scene for one view.
#[derive(Clone, Debug, Default)]
pub struct Features {
    /// The feature edges, in order of their (welded) ends.
    pub edges: Vec<FeatureEdge>,
    /// For each corner of the scene (`Scene::corners` index of a face side's first corner): the
    /// feature edge that side lies on, or `u32::MAX`.
    pub edge_of_side: Vec<u32>,
    /// Welded vertices.
    pub vertices: usize,
    /// Each scene position's welded vertex id.
    pub weld: Vec<u32>,
}

/// Welded vertex ids: one per distinct position, numbered in order of first appearance.
/// Returns the id of every position and, per id, its first position.
pub fn weld(positions: &[DVec3]) -> (Vec<u32>, Vec<u32>) {
    let key = |p: DVec3| {
        // -0 and 0 are the same position.
        let bits = |v: f64| if v == 0.0 { 0 } else { v.to_bits() };
        [bits(p.x), bits(p.y), bits(p.z)]
    };
    let mut ids: HashMap<[u64; 3], u32> =
        HashMap::with_capacity_and_hasher(positions.len(), Default::default());
    let mut first = Vec::new();
    let id = positions
        .iter()
        .enumerate()
        .map(|(i, &p)| {
            *ids.entry(key(p)).or_insert_with(|| {
                first.push(i as u32);
                (first.len() - 1) as u32
            })
        })
        .collect();
    (id, first)
}

/// The feature edges of `scene` seen on `screen`, with creases sharper than `crease_deg`
/// degrees.
pub fn features(scene: &Scene, screen: &ScreenScene, crease_deg: f64) -> Features {
    let (weld_id, first) = weld(&scene.positions);
    // (smaller id, larger id, face, k, the side runs from the smaller to the larger), sorted.
    let sides = sorted_sides(scene, &weld_id, first.len());
    let cos_crease = crease_deg.to_radians().cos();
    let normals: Vec<DVec3> = scene.faces.iter().map(|f| scene.face_normal(f)).collect();
    let mut edges = Vec::new();
    let mut edge_of_side = vec![u32::MAX; scene.corners.len()];
    for group in sides.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        let outside = group
            .iter()
            .any(|s| screen.orientation[s.2 as usize] == Orientation::Outside);
        if outside {
            continue;
        }
        let kind = match group {
            [_] => Some(LineKind::Boundary),
            [s, t] => classify_two(scene, screen, &normals, s, t, cos_crease),
            _ => Some(LineKind::Boundary),
        };
        let Some(kind) = kind else { continue };
        let index = edges.len() as u32;
        for s in group {
            edge_of_side[(scene.faces[s.2 as usize].start + s.3) as usize] = index;
        }
        edges.push(FeatureEdge {
            ends: [first[group[0].0 as usize], first[group[0].1 as usize]],
            kind,
            sides: group
                .iter()
                .map(|s| FaceSide { face: s.2, k: s.3 })
                .collect(),
        });
    }
    Features {
        edges,
        edge_of_side,
        vertices: first.len(),
        weld: weld_id,
    }
}

/// Every face side between two welded vertices (`weld_id`, below `ids`) as (smaller id,
/// larger id, face, k, whether it runs from the smaller to the larger), in ascending order
/// ([`sorted_by_low`] on the smaller id: a sort of all the sides took most of the feature
/// search).
fn sorted_sides(scene: &Scene, weld_id: &[u32], ids: usize) -> Vec<(u32, u32, u32, u32, bool)> {
    let sides = || {
        scene.faces.iter().enumerate().flat_map(|(fi, face)| {
            let corners = scene.face_corners(face);
            let n = corners.len();
            (0..n).filter_map(move |k| {
                let a = weld_id[corners[k] as usize];
                let b = weld_id[corners[(k + 1) % n] as usize];
                (a != b).then_some((a.min(b), a.max(b), fi as u32, k as u32, a < b))
            })
        })
    };
    sorted_by_low(ids, sides, |s| s.0)
}

/// The kind of an edge of two faces, if it is a feature.
fn classify_two(
    scene: &Scene,
    screen: &ScreenScene,
    normals: &[DVec3],
    s: &(u32, u32, u32, u32, bool),
    t: &(u32, u32, u32, u32, bool),
    cos_crease: f64,
) -> Option<LineKind> {
    // Which side of the edge (directed from the smaller welded id) a face lies on: left when
    // it turns counter-clockwise and runs along the edge forward, or clockwise and backward.
    let left = |(_, _, f, _, forward): &(u32, u32, u32, u32, bool)| match screen.orientation
        [*f as usize]
    {
        Orientation::Ccw => Some(*forward),
        Orientation::Cw => Some(!*forward),
        Orientation::Flat | Orientation::Outside => None,
    };
    match (left(s), left(t)) {
        (Some(a), Some(b)) if a == b => return Some(LineKind::Silhouette),
        (Some(_), None) | (None, Some(_)) => return Some(LineKind::Silhouette),
        _ => {}
    }
    let (fs, ft) = (&scene.faces[s.2 as usize], &scene.faces[t.2 as usize]);
    let (ns, mut nt) = (normals[s.2 as usize], normals[t.2 as usize]);
    // Consistently wound neighbours run along their shared edge in opposite directions.
    if s.4 == t.4 {
        nt = -nt;
    }
    let (ls, lt) = (ns.length(), nt.length());
    if ls > 0.0 && lt > 0.0 && ns.dot(nt) < cos_crease * ls * lt {
        return Some(LineKind::Crease);
    }
    if fs.material != ft.material {
        return Some(LineKind::Material);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The counting sort gives the order of one sort of every side: random faces over a few
    /// welded vertices, sides repeated both ways and degenerate ones (two corners welded).
    #[test]
    fn sides_come_sorted_as_one_sort_sorts_them() {
        use crate::scene::SceneBuilder;
        let mut rng = crate::stress::rng::Rng::of(&[0x51de5]);
        for case in 0..200 {
            let mut b = SceneBuilder::new("soup");
            let vertices = 3 + rng.next_u64() % 9;
            for k in 0..vertices {
                b.add_vertex(DVec3::new(
                    (k % 5) as f64,
                    (k * k % 7) as f64,
                    0.5 * k as f64,
                ));
            }
            let m = b.default_material();
            for _ in 0..1 + rng.next_u64() % 10 {
                let face: Vec<u32> = (0..3 + rng.next_u64() % 2)
                    .map(|_| (rng.next_u64() % vertices) as u32)
                    .collect();
                b.add_face(&face, m);
            }
            let Some(scene) = b.finish() else { continue };
            let (weld_id, first) = weld(&scene.positions);
            let mut want = Vec::new();
            for (fi, face) in scene.faces.iter().enumerate() {
                let c = scene.face_corners(face);
                for k in 0..c.len() {
                    let (a, b) = (
                        weld_id[c[k] as usize],
                        weld_id[c[(k + 1) % c.len()] as usize],
                    );
                    if a != b {
                        want.push((a.min(b), a.max(b), fi as u32, k as u32, a < b));
                    }
                }
            }
            want.sort_unstable();
            assert_eq!(
                sorted_sides(&scene, &weld_id, first.len()),
                want,
                "case {case}"
            );
        }
    }

    #[test]
    fn welding_joins_identical_positions_and_signed_zeros() {
        let p = |x, y, z| DVec3::new(x, y, z);
        let (ids, first) = weld(&[p(0.0, 1.0, 2.0), p(-0.0, 1.0, 2.0), p(0.0, 1.0, 2.5)]);
        assert_eq!(ids, vec![0, 0, 1]);
        assert_eq!(first, vec![0, 2]);
    }
}
