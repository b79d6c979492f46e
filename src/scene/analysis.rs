//! What a scene is made of, independent of the camera: which meshes are closed and consistently
//! oriented (so back faces may be culled), which are wound inside-out, and whether any face is
//! translucent or two-sided.
//!
//! Decisions here are exact or conservative: edges are matched by exact vertex position, and a
//! mesh counts as inside-out only when the sign of its signed volume is certain under a proven
//! f64 summation bound; when it is not, the mesh is treated as open (never culled).

use super::{Face, Scene};
use glam::DVec3;
use rayon::prelude::*;

/// Faces per chunk of the signed volume's partial sums: fixed, so the sum is the same whatever
/// the number of threads.
const VOLUME_CHUNK: usize = 1 << 14;

/// Closedness and orientation of one mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshAnalysis {
    /// Undirected edges used by exactly one face.
    pub boundary_edges: usize,
    /// Undirected edges used by more than two faces.
    pub nonmanifold_edges: usize,
    /// Edges shared by two faces that run the same way (inconsistent winding).
    pub inconsistent_edges: usize,
    /// Signed volume (positive for outward winding).
    pub signed_volume: f64,
    /// The sign of `signed_volume` is certain (beyond the summation error bound).
    pub volume_sign_certain: bool,
}

impl MeshAnalysis {
    /// Every edge shared by exactly two faces with opposite winding.
    pub fn closed(&self) -> bool {
        self.boundary_edges == 0 && self.nonmanifold_edges == 0 && self.inconsistent_edges == 0
    }

    /// Closed with a certain orientation: back faces may be culled (unless the camera cuts it).
    pub fn cullable(&self) -> bool {
        self.closed() && self.volume_sign_certain && self.signed_volume != 0.0
    }

    /// Closed and wound inside-out: its faces are treated as flipped.
    pub fn inside_out(&self) -> bool {
        self.cullable() && self.signed_volume < 0.0
    }

    /// Wound inwards, closed or not: the signed volume (about the mesh's first vertex) is
    /// certainly negative. For an open mesh this is a guess at which side is outside (a sphere
    /// exported without its poles and inside out says so clearly; a lone square says nothing),
    /// good for deciding what to try first, never for what may be dropped unseen.
    pub fn wound_inwards(&self) -> bool {
        self.volume_sign_certain && self.signed_volume < 0.0
    }
}

/// Camera-independent facts about a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneAnalysis {
    /// One per mesh, in the scene's order.
    pub meshes: Vec<MeshAnalysis>,
    /// Faces whose material is not opaque.
    pub translucent_faces: usize,
    /// Faces whose material is seen from both sides.
    pub two_sided_faces: usize,
    /// Pairs of meshes whose bounding boxes overlap: they may interpenetrate.
    pub overlapping_mesh_pairs: usize,
    /// Axis-aligned bounds of each mesh.
    pub mesh_bounds: Vec<(DVec3, DVec3)>,
}

/// Analyses every mesh of the scene.
pub fn analyse(scene: &Scene) -> SceneAnalysis {
    let canon = weld(&scene.positions);
    let meshes: Vec<MeshAnalysis> = scene
        .meshes
        .iter()
        .map(|m| analyse_mesh(scene, &scene.faces[m.faces.clone()], &canon))
        .collect();
    // Min and max are exact, so the split across threads changes nothing.
    let mesh_bounds: Vec<(DVec3, DVec3)> = scene
        .meshes
        .iter()
        .map(|m| {
            let empty = || (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
            (scene.faces[m.faces.clone()].par_iter())
                .fold(empty, |(lo, hi), f| {
                    (scene.face_positions(f)).fold((lo, hi), |(lo, hi), p| (lo.min(p), hi.max(p)))
                })
                .reduce(empty, |(la, ha), (lb, hb)| (la.min(lb), ha.max(hb)))
        })
        .collect();
    let mut overlapping_mesh_pairs = 0;
    for a in 0..mesh_bounds.len() {
        for b in a + 1..mesh_bounds.len() {
            let (la, ha) = mesh_bounds[a];
            let (lb, hb) = mesh_bounds[b];
            if la.cmple(hb).all() && lb.cmple(ha).all() {
                overlapping_mesh_pairs += 1;
            }
        }
    }
    let material = |f: &Face| &scene.materials[f.material as usize];
    SceneAnalysis {
        meshes,
        translucent_faces: scene
            .faces
            .iter()
            .filter(|f| material(f).opacity() < 1.0)
            .count(),
        two_sided_faces: scene.faces.iter().filter(|f| material(f).two_sided).count(),
        overlapping_mesh_pairs,
        mesh_bounds,
    }
}

/// Canonical vertex index per vertex: vertices at exactly the same position share one.
fn weld(positions: &[DVec3]) -> Vec<u32> {
    // +0.0 and -0.0 are the same point.
    let bits = |v: f64| if v == 0.0 { 0u64 } else { v.to_bits() };
    let mut keyed: Vec<((u64, u64, u64), u32)> = positions
        .iter()
        .enumerate()
        .map(|(i, p)| ((bits(p.x), bits(p.y), bits(p.z)), i as u32))
        .collect();
    // Keys are unique (the index breaks ties): one sorted order, on any number of threads.
    keyed.par_sort_unstable();
    let mut canon = vec![0u32; positions.len()];
    let mut rep = 0u32;
    for k in 0..keyed.len() {
        if k == 0 || keyed[k].0 != keyed[k - 1].0 {
            rep = keyed[k].1;
        }
        canon[keyed[k].1 as usize] = rep;
    }
    canon
}

fn analyse_mesh(scene: &Scene, faces: &[Face], canon: &[u32]) -> MeshAnalysis {
    // `edge_counts` may pack each directed edge as (low vertex: 31 bits, high vertex: 32 bits,
    // direction: 1 bit) in one u64. A scene with 2^31 vertices or more (48 GB of positions) is
    // beyond that packing: its meshes are reported as open, which only turns culling off.
    if scene.positions.len() >= 1 << 31 {
        return MeshAnalysis {
            boundary_edges: 1,
            nonmanifold_edges: 0,
            inconsistent_edges: 0,
            signed_volume: 0.0,
            volume_sign_certain: false,
        };
    }
    let (boundary, nonmanifold, inconsistent) = edge_counts(scene, faces, canon);

    // Signed volume about the mesh's first vertex, with a running bound on the summation error:
    // each term a·(b×c) is computed with relative error <= 4U over the magnitudes of its products,
    // and summing n terms adds at most n·U·Σ|term| (Higham's γ_n bound, first order).
    let origin = faces
        .first()
        .map(|f| scene.positions[scene.face_corners(f)[0] as usize])
        .unwrap_or(DVec3::ZERO);
    // Summed chunk by chunk, then the chunks' sums in order: the bound below holds for any
    // order of summation, and a fixed one gives the same volume on any number of threads.
    let partial: Vec<(f64, f64, usize)> = (faces.par_chunks(VOLUME_CHUNK))
        .map(|chunk| {
            let (mut volume, mut magnitude, mut terms) = (0.0, 0.0, 0usize);
            for f in chunk {
                let c = scene.face_corners(f);
                let p = |k: usize| scene.positions[c[k] as usize] - origin;
                for k in 1..c.len() - 1 {
                    let (a, b, cc) = (p(0), p(k), p(k + 1));
                    volume += a.dot(b.cross(cc));
                    magnitude += a.abs().dot(abs_cross_bound(b, cc));
                    terms += 1;
                }
            }
            (volume, magnitude, terms)
        })
        .collect();
    let (mut volume, mut magnitude, mut terms) = (0.0, 0.0, 0usize);
    for (v, m, t) in partial {
        volume += v;
        magnitude += m;
        terms += t;
    }
    let bound = (terms as f64 + 8.0) * crate::exact::U * 2.0 * magnitude;
    MeshAnalysis {
        boundary_edges: boundary,
        nonmanifold_edges: nonmanifold,
        inconsistent_edges: inconsistent,
        signed_volume: volume / 6.0,
        volume_sign_certain: volume.abs() > bound,
    }
}

/// The undirected edges of `faces` (vertices by `canon`) used by one face, by more than two,
/// and by two that run the same way: (boundary, nonmanifold, inconsistent).
fn edge_counts(scene: &Scene, faces: &[Face], canon: &[u32]) -> (usize, usize, usize) {
    edge_counts_by(scene, faces, canon, true)
}

/// [`edge_counts`], by buckets where `buckets` allows and the mesh suits them, else by one sort.
fn edge_counts_by(
    scene: &Scene,
    faces: &[Face],
    canon: &[u32],
    buckets: bool,
) -> (usize, usize, usize) {
    // Each directed edge of a face as (low vertex, high vertex, whether it runs upward).
    let edges_of = |f: &Face| {
        let c = scene.face_corners(f);
        (0..c.len()).map(move |k| {
            let u = canon[c[k] as usize];
            let v = canon[c[(k + 1) % c.len()] as usize];
            (u.min(v), u.max(v), u < v)
        })
    };
    let (lowest, highest) = (faces.par_iter())
        .map(|f| {
            let ids = scene.face_corners(f).iter().map(|&k| canon[k as usize]);
            (
                ids.clone().min().unwrap_or(u32::MAX),
                ids.max().unwrap_or(0),
            )
        })
        .reduce(|| (u32::MAX, 0), |a, b| (a.0.min(b.0), a.1.max(b.1)));
    if lowest > highest {
        return (0, 0, 0);
    }
    let span = (highest - lowest) as usize + 1;
    let edge_count: usize = faces.iter().map(|f| f.len as usize).sum();
    let tally = |groups: &mut dyn Iterator<Item = &[u64]>| {
        let mut counts = (0, 0, 0);
        for group in groups {
            match group {
                [_] => counts.0 += 1,
                [a, b] if a == b => counts.2 += 1,
                [_, _] => {}
                _ => counts.1 += 1,
            }
        }
        counts
    };
    let add =
        |a: (usize, usize, usize), b: (usize, usize, usize)| (a.0 + b.0, a.1 + b.1, a.2 + b.2);
    if !buckets || span > 2 * edge_count || edge_count >= u32::MAX as usize {
        // Few vertices of a large id range (one mesh among many), or more edges than the
        // counting sort's u32 offsets hold: one sort of the packed edges (low vertex: 31 bits,
        // high vertex: 32 bits, direction: 1 bit).
        let mut packed: Vec<u64> = (faces.par_iter())
            .flat_map_iter(|f| {
                edges_of(f).map(|(lo, hi, up)| (lo as u64) << 33 | (hi as u64) << 1 | up as u64)
            })
            .collect();
        packed.par_sort_unstable();
        return tally(&mut packed.chunk_by(|a, b| a >> 1 == b >> 1));
    }
    // The mesh's vertices are about as many as its edges: a counting sort by the low end puts
    // the uses of each edge in one bucket of a few (a sort of all the edges took longer). On
    // all cores: each chunk of faces sorts its own edges so, then each bucket gathers its
    // entries from every chunk. Entries: the high end, then the direction.
    let sorted: Vec<(Vec<u32>, Vec<u64>)> = (faces
        .par_chunks(faces.len().div_ceil(rayon::current_num_threads()).max(1)))
    .map(|chunk| {
        let mut start = vec![0u32; span + 1];
        for (lo, _, _) in chunk.iter().flat_map(edges_of) {
            start[(lo - lowest) as usize + 1] += 1;
        }
        for b in 1..start.len() {
            start[b] += start[b - 1];
        }
        let mut next = start.clone();
        let mut entries = vec![0u64; start[span] as usize];
        for (lo, hi, up) in chunk.iter().flat_map(edges_of) {
            let at = &mut next[(lo - lowest) as usize];
            entries[*at as usize] = (hi as u64) << 1 | up as u64;
            *at += 1;
        }
        (start, entries)
    })
    .collect();
    (0..span)
        .into_par_iter()
        .with_min_len(4096)
        .fold(
            || ((0, 0, 0), Vec::new()),
            |(counts, mut bucket), b| {
                bucket.clear();
                for (start, entries) in &sorted {
                    bucket.extend_from_slice(&entries[start[b] as usize..start[b + 1] as usize]);
                }
                bucket.sort_unstable();
                let more = tally(&mut bucket.chunk_by(|a, b| a >> 1 == b >> 1));
                (add(counts, more), bucket)
            },
        )
        .map(|(counts, _)| counts)
        .reduce(|| (0, 0, 0), add)
}

/// Component-wise |b.y·c.z| + |b.z·c.y|, ...: bounds the magnitude of the products in b × c.
fn abs_cross_bound(b: DVec3, c: DVec3) -> DVec3 {
    let (b, c) = (b.abs(), c.abs());
    DVec3::new(
        b.y * c.z + b.z * c.y,
        b.z * c.x + b.x * c.z,
        b.x * c.y + b.y * c.x,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::SceneBuilder;

    /// The buckets count what the sort of all edges counts: random faces over a few vertices,
    /// some at one position (welded), so edges repeat both ways, the same way, and thrice.
    #[test]
    fn edge_counts_by_buckets_are_those_by_one_sort() {
        let mut rng = crate::stress::rng::Rng::of(&[0xed9e_c0de]);
        let (mut boundary, mut inconsistent, mut nonmanifold) = (0, 0, 0);
        for case in 0..200 {
            let mut b = SceneBuilder::new("soup");
            let vertices = 4 + rng.next_u64() % 8;
            for k in 0..vertices {
                // Vertices 0 and 1 at one position.
                let k = if k == 1 { 0 } else { k };
                b.add_vertex(DVec3::new(k as f64, (k * k % 5) as f64, (k % 3) as f64));
            }
            let m = b.default_material();
            for _ in 0..1 + rng.next_u64() % 12 {
                let mut face: Vec<u32> = Vec::new();
                while face.len() < 3 {
                    let v = (rng.next_u64() % vertices) as u32;
                    if !face.contains(&v) {
                        face.push(v);
                    }
                }
                b.add_face(&face, m);
            }
            let Some(scene) = b.finish() else { continue };
            let canon = weld(&scene.positions);
            let want = edge_counts_by(&scene, &scene.faces, &canon, false);
            assert_eq!(
                edge_counts_by(&scene, &scene.faces, &canon, true),
                want,
                "case {case}"
            );
            boundary += want.0;
            nonmanifold += want.1;
            inconsistent += want.2;
        }
        assert!(boundary > 100 && nonmanifold > 20 && inconsistent > 20);
    }

    fn cube(flip: bool, drop_one: bool) -> Scene {
        let mut b = SceneBuilder::new("cube");
        for k in 0..8 {
            b.add_vertex(DVec3::new(
                (k & 1) as f64,
                ((k >> 1) & 1) as f64,
                ((k >> 2) & 1) as f64,
            ));
        }
        let m = b.default_material();
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        for (k, q) in quads.iter().enumerate() {
            if drop_one && k == 5 {
                continue;
            }
            let mut q = q.to_vec();
            if flip {
                q.reverse();
            }
            b.add_face(&q, m);
        }
        b.finish().unwrap()
    }

    #[test]
    fn closed_cube_is_cullable_with_unit_volume() {
        let a = analyse(&cube(false, false));
        assert!(a.meshes[0].closed() && a.meshes[0].cullable());
        assert!((a.meshes[0].signed_volume - 1.0).abs() < 1e-12);
        assert!(!a.meshes[0].inside_out());
    }

    #[test]
    fn inverted_cube_is_inside_out() {
        let a = analyse(&cube(true, false));
        assert!(a.meshes[0].inside_out());
        assert!((a.meshes[0].signed_volume + 1.0).abs() < 1e-12);
    }

    #[test]
    fn open_box_is_not_cullable() {
        let a = analyse(&cube(false, true));
        assert_eq!(a.meshes[0].boundary_edges, 4);
        assert!(!a.meshes[0].cullable());
        assert!(!a.meshes[0].wound_inwards());
        // Open and flipped: not culled, but its winding says which side is outside.
        let a = analyse(&cube(true, true));
        assert!(!a.meshes[0].cullable() && !a.meshes[0].inside_out());
        assert!(a.meshes[0].wound_inwards());
    }

    #[test]
    fn a_sphere_exported_open_and_inside_out_is_wound_inwards_but_never_culled() {
        let a = analyse(&crate::scene::primitives::exported_sphere_scene(2_000));
        assert!(a.meshes[0].boundary_edges > 0 && !a.meshes[0].cullable());
        assert!(a.meshes[0].wound_inwards());
        let a = analyse(&crate::scene::primitives::sphere_scene(2_000));
        assert!(a.meshes[0].cullable() && !a.meshes[0].wound_inwards());
    }

    #[test]
    fn duplicated_vertices_are_welded_by_position() {
        // Two triangles sharing an edge through distinct but coincident vertices, plus their
        // mirror images: a closed (flat, zero-volume) double-sided sheet.
        let mut b = SceneBuilder::new("sheet");
        let pts = [
            [0., 0., 0.],
            [1., 0., 0.],
            [0., 1., 0.],
            [1., 0., -0.0],
            [0., 1., 0.],
        ];
        for p in pts {
            b.add_vertex(DVec3::from_array(p));
        }
        let m = b.default_material();
        b.add_face(&[0, 1, 2], m);
        b.add_face(&[0, 4, 3], m);
        let a = analyse(&b.finish().unwrap());
        assert!(a.meshes[0].closed());
        assert!(
            !a.meshes[0].cullable(),
            "zero volume: orientation unknown, never culled"
        );
    }
}
