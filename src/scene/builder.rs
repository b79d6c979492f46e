//! Building a [`Scene`] face by face. Every loader goes through this, so the scene invariants
//! (planar, non-degenerate faces with stable ids) are kept in one place.

use super::{Face, FaceId, LoadStats, Material, Mesh, Scene, Viewpoint, newell_normal};
use glam::DVec3;
use robust::{Coord, Coord3D, orient2d, orient3d};

/// What became of one input polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaceOutcome {
    /// Kept as one planar polygon.
    Kept,
    /// Not planar: split into this many triangles, all carrying the polygon's id.
    Triangulated(usize),
    /// Fewer than three distinct corners, or all corners collinear: dropped (the id is used up).
    Degenerate,
}

/// Per-corner attributes of one input polygon, parallel to its corner list.
#[derive(Clone, Copy, Debug, Default)]
pub struct CornerAttrs<'a> {
    /// The file's normal at each corner, if it gives them.
    pub normals: Option<&'a [DVec3]>,
    /// The file's texture coordinates at each corner, if it gives them.
    pub uvs: Option<&'a [[f64; 2]]>,
}

/// Accumulates vertices, materials, meshes and faces; see [`Scene`] for the invariants kept.
#[derive(Debug)]
pub struct SceneBuilder {
    scene: Scene,
    mesh_open: bool,
    default_material: Option<u32>,
    scratch: Vec<u32>,
    scratch_keep: Vec<usize>,
}

impl SceneBuilder {
    /// An empty scene read from `source` (a name for messages).
    pub fn new(source: &str) -> Self {
        SceneBuilder {
            scene: Scene {
                source: source.to_string(),
                ..Scene::default()
            },
            mesh_open: false,
            default_material: None,
            scratch: Vec::new(),
            scratch_keep: Vec::new(),
        }
    }

    /// Adds a material and returns its index.
    pub fn add_material(&mut self, material: Material) -> u32 {
        self.scene.materials.push(material);
        (self.scene.materials.len() - 1) as u32
    }

    /// The index of the default material (0.8 grey, opaque, one-sided), added on first use.
    pub fn default_material(&mut self) -> u32 {
        match self.default_material {
            Some(m) => m,
            None => {
                let m = self.add_material(Material::default());
                self.default_material = Some(m);
                m
            }
        }
    }

    /// Starts a new mesh; faces added from now on belong to it. An empty previous mesh is
    /// replaced rather than kept.
    pub fn begin_mesh(&mut self, name: impl Into<String>) {
        let start = self.scene.faces.len();
        if self.mesh_open
            && let Some(last) = self.scene.meshes.last_mut()
            && last.faces.is_empty()
        {
            last.name = name.into();
            return;
        }
        self.scene.meshes.push(Mesh {
            name: name.into(),
            faces: start..start,
        });
        self.mesh_open = true;
    }

    /// Adds a vertex. The caller has checked that it is finite (it knows the line to blame).
    pub fn add_vertex(&mut self, p: DVec3) -> u32 {
        debug_assert!(p.is_finite());
        self.scene.positions.push(p);
        (self.scene.positions.len() - 1) as u32
    }

    /// Adds finite vertices in order, as [`Self::add_vertex`] one by one would.
    pub fn add_vertices(&mut self, ps: &[DVec3]) {
        debug_assert!(ps.iter().all(|p| p.is_finite()));
        self.scene.positions.extend_from_slice(ps);
    }

    /// How many vertices were added.
    pub fn vertex_count(&self) -> usize {
        self.scene.positions.len()
    }

    /// The position of vertex `v`.
    pub fn position(&self, v: u32) -> DVec3 {
        self.scene.positions[v as usize]
    }

    /// Number of input faces so far (the id the next face will get).
    /// The id the next input face gets.
    pub fn next_face_id(&self) -> FaceId {
        self.scene.input_faces
    }

    /// Records a warning (see [`LoadStats::warnings`](super::LoadStats::warnings)).
    pub fn warn(&mut self, message: impl Into<String>) {
        self.scene.stats.warnings.push(message.into());
    }

    /// Sets the scene's own camera.
    pub fn set_viewpoint(&mut self, viewpoint: Viewpoint) {
        self.scene.viewpoint = Some(viewpoint);
    }

    /// Adds one input polygon (vertex indices, counter-clockwise seen from the front). The caller
    /// has checked that every index is in range. The polygon always uses up one id.
    pub fn add_face(&mut self, corners: &[u32], material: u32) -> FaceOutcome {
        self.add_face_with(corners, material, CornerAttrs::default())
    }

    /// Sets the texture image of a material.
    pub fn set_texture(&mut self, material: u32, path: std::path::PathBuf) {
        let t = &mut self.scene.material_textures;
        if t.len() <= material as usize {
            t.resize(material as usize + 1, None);
        }
        t[material as usize] = Some(path);
    }

    /// [`Self::add_face`] with per-corner normals and texture coordinates (each, when given, as
    /// long as `corners`). Every kept corner keeps the attributes of the input corner it is, even
    /// when the polygon visits one vertex twice: a dropped repeat (consecutive corners at one
    /// position, cyclically) gives way to the first of the run, and triangulated pieces take their
    /// corners' attributes.
    pub fn add_face_with(
        &mut self,
        corners: &[u32],
        material: u32,
        attrs: CornerAttrs,
    ) -> FaceOutcome {
        debug_assert!(attrs.normals.is_none_or(|n| n.len() == corners.len()));
        debug_assert!(attrs.uvs.is_none_or(|n| n.len() == corners.len()));
        debug_assert!(
            corners
                .iter()
                .all(|&c| (c as usize) < self.scene.positions.len())
        );
        let id = self.scene.input_faces;
        self.scene.input_faces += 1;
        if !self.mesh_open {
            self.begin_mesh("mesh");
        }

        // Drop consecutive repeats (by index or by position), cyclically. `keep` holds the
        // positions in `corners` of the corners kept, `clean` their vertex indices.
        let mut keep = std::mem::take(&mut self.scratch_keep);
        let mut clean = std::mem::take(&mut self.scratch);
        keep.clear();
        clean.clear();
        let pos = &self.scene.positions;
        for (k, &c) in corners.iter().enumerate() {
            if clean
                .last()
                .is_none_or(|&l| pos[l as usize] != pos[c as usize])
            {
                keep.push(k);
                clean.push(c);
            }
        }
        while clean.len() > 1 && pos[clean[0] as usize] == pos[*clean.last().unwrap() as usize] {
            clean.pop();
            keep.pop();
        }

        let outcome = match non_collinear_triple(pos, &clean) {
            None => {
                self.scene.stats.degenerate_dropped += 1;
                FaceOutcome::Degenerate
            }
            Some((a, b, c)) => {
                if clean.len() == 3 || is_planar(pos, &clean, a, b, c) {
                    self.push_face(id, material, &keep, corners, attrs);
                    FaceOutcome::Kept
                } else {
                    let triangles = triangulate(pos, &clean);
                    self.scene.stats.nonplanar_triangulated += 1;
                    let mut kept = 0;
                    for t in &triangles {
                        let vertices = t.map(|i| clean[i]);
                        if non_collinear_triple(&self.scene.positions, &vertices).is_some() {
                            self.push_face(id, material, &t.map(|i| keep[i]), corners, attrs);
                            kept += 1;
                        }
                    }
                    FaceOutcome::Triangulated(kept)
                }
            }
        };
        self.scratch = clean;
        self.scratch_keep = keep;
        outcome
    }

    /// Would [`Self::add_face_with`] keep this face whole, as it is, with no other test: three
    /// corners at distinct positions, not collinear (exactly)? It reads the vertices only, so a
    /// loader may ask it for many faces at once on all cores, then add those faces with
    /// [`Self::add_plain_triangle`].
    pub fn is_plain_triangle(&self, corners: &[u32]) -> bool {
        let pos = &self.scene.positions;
        let &[a, b, c] = corners else {
            return false;
        };
        let (a, b, c) = (pos[a as usize], pos[b as usize], pos[c as usize]);
        a != b && b != c && c != a && !collinear(a, b, c)
    }

    /// [`Self::add_face_with`] of a face that [`Self::is_plain_triangle`] says is plain: the
    /// same face, without the tests again.
    pub fn add_plain_triangle(
        &mut self,
        corners: &[u32],
        material: u32,
        attrs: CornerAttrs,
    ) -> FaceOutcome {
        debug_assert!(self.is_plain_triangle(corners));
        let id = self.scene.input_faces;
        self.scene.input_faces += 1;
        if !self.mesh_open {
            self.begin_mesh("mesh");
        }
        self.push_face(id, material, &[0, 1, 2], corners, attrs);
        FaceOutcome::Kept
    }

    /// [`Self::add_plain_triangle`] of each triangle of `corners` (three corners each, every
    /// triangle plain), all of `material` and without corner attributes: the same faces, added
    /// at once (a loader's run of them is most of a mesh; the OBJ loader's serial loop over
    /// dragon's 871k triangles took 23 ms adding them one by one, 12 ms so).
    pub fn add_plain_triangles(&mut self, corners: &[u32], material: u32) {
        debug_assert!(corners.chunks(3).all(|c| self.is_plain_triangle(c)));
        let count = corners.len() / 3;
        if count == 0 {
            return;
        }
        if !self.mesh_open {
            self.begin_mesh("mesh");
        }
        let (first_id, start) = (self.scene.input_faces, self.scene.corners.len() as u32);
        self.scene.input_faces += count as u32;
        self.scene.corners.extend_from_slice(&corners[..3 * count]);
        // Attribute vectors stay empty until some face has the attribute, then cover every
        // corner (as `push_face` keeps them).
        let n = self.scene.corners.len();
        if !self.scene.corner_normals.is_empty() {
            self.scene.corner_normals.resize(n, None);
        }
        if !self.scene.corner_uvs.is_empty() {
            self.scene.corner_uvs.resize(n, None);
        }
        let mesh = (self.scene.meshes.len() - 1) as u32;
        self.scene.faces.extend((0..count as u32).map(|j| Face {
            id: first_id + j,
            mesh,
            material,
            start: start + 3 * j,
            len: 3,
        }));
        self.scene.meshes.last_mut().unwrap().faces.end = self.scene.faces.len();
    }

    /// Adds the face made of the input corners at positions `picks` of `input`.
    fn push_face(
        &mut self,
        id: FaceId,
        material: u32,
        picks: &[usize],
        input: &[u32],
        attrs: CornerAttrs,
    ) {
        let start = self.scene.corners.len() as u32;
        self.scene.corners.extend(picks.iter().map(|&k| input[k]));
        // Attribute vectors stay empty until some face has the attribute, then cover every corner.
        let n = self.scene.corners.len();
        if let Some(normals) = attrs.normals {
            let cn = &mut self.scene.corner_normals;
            cn.resize(start as usize, None);
            cn.extend(picks.iter().map(|&k| Some(normals[k])));
        } else if !self.scene.corner_normals.is_empty() {
            self.scene.corner_normals.resize(n, None);
        }
        if let Some(uvs) = attrs.uvs {
            let cu = &mut self.scene.corner_uvs;
            cu.resize(start as usize, None);
            cu.extend(picks.iter().map(|&k| Some(uvs[k])));
        } else if !self.scene.corner_uvs.is_empty() {
            self.scene.corner_uvs.resize(n, None);
        }
        self.scene.faces.push(Face {
            id,
            mesh: (self.scene.meshes.len() - 1) as u32,
            material,
            start,
            len: picks.len() as u32,
        });
        self.scene.meshes.last_mut().unwrap().faces.end = self.scene.faces.len();
    }

    /// Finishes the scene. Returns `None` when it holds no face (the loader reports that, since it
    /// knows the file).
    pub fn finish(mut self) -> Option<Scene> {
        self.scene.meshes.retain(|m| !m.faces.is_empty());
        // Mesh indices in faces must follow the retained meshes.
        for (i, m) in self.scene.meshes.iter().enumerate() {
            for f in &mut self.scene.faces[m.faces.clone()] {
                f.mesh = i as u32;
            }
        }
        if self.scene.faces.is_empty() {
            None
        } else {
            Some(self.scene)
        }
    }

    /// The load statistics so far (for loaders that report them before finishing).
    pub fn stats(&self) -> &LoadStats {
        &self.scene.stats
    }
}

fn c3(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// Exact: are three points collinear? (All three axis-plane projections have zero area.)
fn collinear(a: DVec3, b: DVec3, c: DVec3) -> bool {
    let o = |(ax, ay): (f64, f64), (bx, by): (f64, f64), (cx, cy): (f64, f64)| {
        orient2d(
            Coord { x: ax, y: ay },
            Coord { x: bx, y: by },
            Coord { x: cx, y: cy },
        )
    };
    o((a.x, a.y), (b.x, b.y), (c.x, c.y)) == 0.0
        && o((a.y, a.z), (b.y, b.z), (c.y, c.z)) == 0.0
        && o((a.z, a.x), (b.z, b.x), (c.z, c.x)) == 0.0
}

/// Positions in `corners` of three points that are not collinear, chosen exactly; `None` when the
/// polygon is degenerate.
fn non_collinear_triple(pos: &[DVec3], corners: &[u32]) -> Option<(usize, usize, usize)> {
    if corners.len() < 3 {
        return None;
    }
    let p = |i: usize| pos[corners[i] as usize];
    let a = 0;
    let b = (1..corners.len()).find(|&i| p(i) != p(a))?;
    let c = (b + 1..corners.len()).find(|&i| !collinear(p(a), p(b), p(i)))?;
    Some((a, b, c))
}

/// Exact coplanarity of every corner with the plane through corners a, b, c.
fn is_planar(pos: &[DVec3], corners: &[u32], a: usize, b: usize, c: usize) -> bool {
    let p = |i: usize| c3(pos[corners[i] as usize]);
    (0..corners.len()).all(|i| orient3d(p(a), p(b), p(c), p(i)) == 0.0)
}

/// Triangulates a non-planar polygon: a constrained Delaunay triangulation (spade) of its
/// projection on the plane most perpendicular to its Newell normal, keeping the triangles inside
/// the projected polygon and the polygon's winding. Falls back to a fan when the projection is
/// not a simple polygon. Triangles are given as positions in `corners`.
fn triangulate(pos: &[DVec3], corners: &[u32]) -> Vec<[usize; 3]> {
    use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

    let n = newell_normal(corners.iter().map(|&c| pos[c as usize]));
    let (i, j) = match n.abs().max_position() {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    };
    let flip = n[3 - i - j] < 0.0;
    let proj: Vec<[f64; 2]> = corners
        .iter()
        .map(|&c| {
            let p = pos[c as usize];
            [p[i], p[j]]
        })
        .collect();
    let fan = || (1..corners.len() - 1).map(|k| [0, k, k + 1]).collect();

    let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
    let mut handle_corner: Vec<usize> = Vec::new();
    let mut handles = Vec::with_capacity(proj.len());
    for (k, q) in proj.iter().enumerate() {
        let Ok(h) = cdt.insert(Point2::new(q[0], q[1])) else {
            return fan();
        };
        if h.index() == handle_corner.len() {
            handle_corner.push(k);
        } else {
            // Two corners project to one point: not a simple projection.
            return fan();
        }
        handles.push(h);
    }
    for k in 0..handles.len() {
        let (a, b) = (handles[k], handles[(k + 1) % handles.len()]);
        if !cdt.can_add_constraint(a, b) {
            return fan();
        }
        cdt.add_constraint(a, b);
    }
    let mut out = Vec::new();
    for face in cdt.inner_faces() {
        let vs = face.vertices();
        let cx = vs.iter().map(|v| v.position().x).sum::<f64>() / 3.0;
        let cy = vs.iter().map(|v| v.position().y).sum::<f64>() / 3.0;
        if !inside_even_odd(&proj, cx, cy) {
            continue;
        }
        // spade's faces are counter-clockwise in the projection plane.
        let mut tri = vs.map(|v| handle_corner[v.fix().index()]);
        if flip {
            tri.reverse();
        }
        out.push(tri);
    }
    if out.is_empty() { fan() } else { out }
}

fn inside_even_odd(poly: &[[f64; 2]], x: f64, y: f64) -> bool {
    let mut inside = false;
    for k in 0..poly.len() {
        let a = poly[k];
        let b = poly[(k + 1) % poly.len()];
        if (a[1] > y) != (b[1] > y) {
            let xc = a[0] + (y - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if x < xc {
                inside = !inside;
            }
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;

    fn builder_with(points: &[[f64; 3]]) -> SceneBuilder {
        let mut b = SceneBuilder::new("test");
        for p in points {
            b.add_vertex(DVec3::from_array(*p));
        }
        b
    }

    /// A run of plain triangles added at once is the scene that adding them one by one makes:
    /// the faces, their ids and corners, the mesh, and attribute lists kept covering every
    /// corner once a face before the run had normals.
    #[test]
    fn plain_triangles_added_at_once_are_added_as_one_by_one() {
        let points = [
            [0., 0., 0.],
            [1., 0., 0.],
            [1., 1., 0.],
            [0., 1., 0.],
            [2., 0., 1.],
        ];
        let run = [0, 1, 2, 0, 2, 3, 1, 4, 2];
        let normal = [DVec3::Z; 3];
        for with_normals in [false, true] {
            let [mut one, mut all] = [builder_with(&points), builder_with(&points)];
            for b in [&mut one, &mut all] {
                let m = b.default_material();
                if with_normals {
                    let attrs = CornerAttrs {
                        normals: Some(&normal),
                        uvs: None,
                    };
                    b.add_plain_triangle(&[0, 1, 3], m, attrs);
                }
            }
            let m = one.default_material();
            for t in run.chunks(3) {
                one.add_plain_triangle(t, m, CornerAttrs::default());
            }
            all.add_plain_triangles(&run, m);
            let (one, all) = (one.finish().unwrap(), all.finish().unwrap());
            assert_eq!(one.faces, all.faces);
            assert_eq!(one.corners, all.corners);
            assert_eq!(one.corner_normals, all.corner_normals);
            assert_eq!(one.corner_uvs, all.corner_uvs);
            assert_eq!(one.meshes, all.meshes);
            assert_eq!(one.input_faces, all.input_faces);
        }
    }

    #[test]
    fn planar_quad_is_kept_whole() {
        let mut b = builder_with(&[[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]]);
        let m = b.default_material();
        assert_eq!(b.add_face(&[0, 1, 2, 3], m), FaceOutcome::Kept);
        let s = b.finish().unwrap();
        assert_eq!(s.faces.len(), 1);
        assert_eq!(s.face_corners(&s.faces[0]), &[0, 1, 2, 3]);
    }

    #[test]
    fn nonplanar_polygon_is_triangulated_with_one_id_and_its_winding() {
        // An L-shaped hexagon lifted at one corner: non-planar, non-convex.
        let mut b = builder_with(&[
            [0., 0., 0.],
            [2., 0., 0.],
            [2., 1., 0.],
            [1., 1., 0.],
            [1., 2., 0.5],
            [0., 2., 0.],
        ]);
        let m = b.default_material();
        assert_eq!(
            b.add_face(&[0, 1, 2, 3, 4, 5], m),
            FaceOutcome::Triangulated(4)
        );
        let s = b.finish().unwrap();
        assert_eq!(s.stats.nonplanar_triangulated, 1);
        let mut area = 0.0;
        for f in &s.faces {
            assert_eq!(f.id, 0);
            let n = s.face_normal(f);
            assert!(n.z > 0.0, "piece lost the polygon's winding");
            area += n.z / 2.0;
        }
        assert!(
            (area - 3.0).abs() < 1e-12,
            "pieces cover the projected L: {area}"
        );
    }

    #[test]
    fn degenerate_faces_use_up_their_id() {
        let mut b = builder_with(&[[0., 0., 0.], [1., 1., 1.], [2., 2., 2.], [0., 1., 0.]]);
        let m = b.default_material();
        assert_eq!(b.add_face(&[0, 1, 2], m), FaceOutcome::Degenerate);
        assert_eq!(b.add_face(&[0, 0, 1], m), FaceOutcome::Degenerate);
        assert_eq!(b.add_face(&[0, 1, 3], m), FaceOutcome::Kept);
        let s = b.finish().unwrap();
        assert_eq!(s.stats.degenerate_dropped, 2);
        assert_eq!(s.faces[0].id, 2);
        assert_eq!(s.input_faces, 3);
    }

    /// Attributes that name their input corner: uv (k, -k), normal (k, 1, 0) at corner k.
    fn tagged(n: usize) -> (Vec<DVec3>, Vec<[f64; 2]>) {
        (
            (0..n).map(|k| DVec3::new(k as f64, 1.0, 0.0)).collect(),
            (0..n).map(|k| [k as f64, -(k as f64)]).collect(),
        )
    }

    /// The input corner each scene corner of face `f` took its attributes from (checking that
    /// the normal and the uv agree).
    fn sources(s: &Scene, f: usize) -> Vec<usize> {
        let face = &s.faces[f];
        let uvs = s.face_corner_uvs(face).unwrap();
        let normals = s.face_corner_normals(face).unwrap();
        uvs.iter()
            .zip(&normals)
            .map(|(uv, n)| {
                assert_eq!(uv[0], n.x, "normal and uv from different corners");
                assert_eq!(uv[1], -uv[0]);
                uv[0] as usize
            })
            .collect()
    }

    #[test]
    fn attributes_survive_dropped_repeats_each_corner_its_own() {
        // A planar figure eight: the square 0 1 2 3 and the triangle 0 4 5 meeting at vertex 0,
        // visited twice (input corners 0 and 5); vertex 1 repeated (input corners 1 and 2),
        // vertex 6 sits at vertex 4's position (input corners 7 and 8), and the last corner
        // repeats the first, cyclically.
        let mut b = builder_with(&[
            [0., 0., 0.],
            [1., 0., 0.],
            [1., 1., 0.],
            [0., 1., 0.],
            [-1., 0., 0.],
            [-1., -1., 0.],
            [-1., 0., 0.],
        ]);
        let m = b.default_material();
        let input = [0, 1, 1, 2, 3, 0, 5, 4, 6, 0];
        let (normals, uvs) = tagged(input.len());
        let attrs = CornerAttrs {
            normals: Some(&normals),
            uvs: Some(&uvs),
        };
        assert_eq!(b.add_face_with(&input, m, attrs), FaceOutcome::Kept);
        // A face without attributes after it: its corners get none, the vectors stay parallel.
        assert_eq!(b.add_face(&[0, 1, 2], m), FaceOutcome::Kept);
        let s = b.finish().unwrap();
        assert_eq!(s.face_corners(&s.faces[0]), &[0, 1, 2, 3, 0, 5, 4]);
        // First of each run of repeats; the second visit of vertex 0 keeps its own corner (5).
        assert_eq!(sources(&s, 0), [0, 1, 3, 4, 5, 6, 7]);
        assert_eq!(s.corner_uvs.len(), s.corners.len());
        assert_eq!(s.corner_normals.len(), s.corners.len());
        assert!(s.face_corner_uvs(&s.faces[1]).is_none());
        assert!(s.corner_uvs[7..].iter().all(Option::is_none));
    }

    #[test]
    fn attributes_follow_their_corners_into_triangulated_pieces() {
        // The lifted L of the test above, with vertex 2 repeated (input corners 2 and 3) and a
        // trailing repeat of the first corner.
        let mut b = builder_with(&[
            [0., 0., 0.],
            [2., 0., 0.],
            [2., 1., 0.],
            [1., 1., 0.],
            [1., 2., 0.5],
            [0., 2., 0.],
        ]);
        let m = b.default_material();
        let input = [0, 1, 2, 2, 3, 4, 5, 0];
        let (normals, uvs) = tagged(input.len());
        let attrs = CornerAttrs {
            normals: Some(&normals),
            uvs: Some(&uvs),
        };
        assert_eq!(
            b.add_face_with(&input, m, attrs),
            FaceOutcome::Triangulated(4)
        );
        let s = b.finish().unwrap();
        // Vertex v came from input corner `from[v]`.
        let from = [0, 1, 2, 4, 5, 6];
        let mut seen = [false; 6];
        for (f, face) in s.faces.iter().enumerate() {
            let vs = s.face_corners(face);
            let want: Vec<usize> = vs.iter().map(|&v| from[v as usize]).collect();
            assert_eq!(sources(&s, f), want, "piece {f}: {vs:?}");
            for &v in vs {
                seen[v as usize] = true;
            }
        }
        assert_eq!(seen, [true; 6]);
    }

    #[test]
    fn empty_scene_is_none() {
        assert!(SceneBuilder::new("x").finish().is_none());
    }
}
