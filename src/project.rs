//! From world-space faces to exact screen polygons: transform, clip, project, snap, cull.
//!
//! Invariants of every [`ScreenPoly`] produced:
//! - its corners lie on the integer grid of [`crate::exact`], inside the guard band and the depth
//!   range, with no two consecutive corners at the same (x, y);
//! - its projection has non-zero area and it has a support [`Plane`] through every one of its
//!   corners: a face whose snapped corners do not lie in one plane (a quad after rounding,
//!   almost always) is split into triangles, each a polygon of its own with the face's id, so
//!   that two faces sharing an edge agree exactly on its depth;
//! - it was not culled: it lies at least partly inside the view frustum and, if its mesh is
//!   cullable, it faces the camera.
//!
//! Clipping is done in f64 homogeneous clip space before the divide (Sutherland–Hodgman, one
//! plane at a time), against the near and far planes and a guard band twice the view's width:
//! a face crossing the near plane is cut there, never dropped. The f64 clip points carry a
//! relative error of a few ulps, far below the snapping bound they then go through.
//!
//! Culling:
//! - frustum: a face whose corners are all outside one plane of the view frustum is dropped;
//! - back faces (`CullMode::Auto`): dropped only for meshes that are closed and consistently
//!   oriented (see [`crate::scene::analysis`]), whose faces are not two-sided, and that the near
//!   plane does not cut (a cut mesh shows its inside). The facing test is the exact sign of the
//!   snapped polygon's projected area, so it agrees with every later stage.

use crate::camera::Camera;
use crate::exact::{GUARD, GridPoint, Plane, twice_signed_area};
use crate::scene::analysis::SceneAnalysis;
use crate::scene::{FaceId, Scene};
use glam::DVec4;
use rayon::prelude::*;
use smallvec::SmallVec;

/// When back faces are removed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum CullMode {
    /// Cull closed, consistently oriented, one-sided meshes the near plane does not cut.
    #[default]
    Auto,
    /// Cull every back face whose material is not two-sided, closed mesh or not.
    On,
    /// Never cull back faces.
    Off,
}

/// A face on screen. Its corners are `ScreenScene::corner_points[start..start + len]`
/// ([`ScreenScene::corners`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ScreenPoly {
    /// Index into `Scene::faces`.
    pub face: u32,
    /// Provenance: the input face id.
    pub id: FaceId,
    /// Index into `Scene::meshes` of the face's mesh.
    pub mesh: u32,
    /// Index of its first corner in `ScreenScene::corner_points` (and `sides`).
    pub start: u32,
    /// Number of corners.
    pub len: u32,
    /// Seen from its front: counter-clockwise on screen, or clockwise in a mesh wound inwards
    /// (closed and inside-out, or open with a certainly negative signed volume:
    /// [`crate::scene::analysis::MeshAnalysis::wound_inwards`]). Culling drops only the back
    /// faces of closed meshes; for open ones this is where the surface most likely faces the eye.
    pub front: bool,
}

/// What projection did, counted.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ProjectStats {
    /// Faces in the scene.
    pub faces: usize,
    /// Faces wholly outside one plane of the view frustum, dropped.
    pub frustum_culled: usize,
    /// Faces cut by the near or far plane or the guard band.
    pub clipped: usize,
    /// Back faces dropped.
    pub backface_culled: usize,
    /// Faces whose snapped projection has no area (edge-on, or smaller than the grid).
    pub degenerate_after_snap: usize,
    /// Faces whose snapped corners are not coplanar, split into triangles.
    pub split_nonplanar: usize,
    /// Meshes whose back faces were culled.
    pub culled_meshes: usize,
    /// Closed meshes not culled because the near plane cuts them.
    pub meshes_cut_by_near: usize,
    /// Screen polygons made.
    pub visible_polys: usize,
}

/// Where a side of a screen polygon comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Side {
    /// Edge k of the face, from its corner k to corner k + 1 in `Scene::face_corners` (or the
    /// part of it that clipping left).
    Edge(u32),
    /// Where clipping cut the face.
    Clip(ClipPlane),
    /// Inside the face: a diagonal where a face whose snapped corners are not coplanar was
    /// split into triangles.
    Diagonal,
}

/// The planes faces are clipped by (in homogeneous clip space, before the divide).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ClipPlane {
    /// The near plane: where a face comes closer to the eye than the camera's near distance.
    Near,
    /// The far plane.
    Far,
    /// The guard band around the view: it lies outside the image, so these sides are never
    /// seen.
    Guard,
}

/// How a face of the scene lies on screen, decided exactly on the snapped grid: the sign of its
/// projected polygon's area (after clipping), as culling and every later stage see it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Orientation {
    /// Wholly outside one plane of the view frustum (dropped before snapping).
    Outside,
    /// No projected area after snapping: edge-on, or smaller than the grid.
    Flat,
    /// Counter-clockwise on screen (y up): its corners' order turns left.
    Ccw,
    /// Clockwise on screen.
    Cw,
}

/// A polygon's corners, copied out of [`ScreenScene::grid_points`].
pub type Corners = smallvec::SmallVec<[GridPoint; 4]>;

/// Where a polygon's sides come from ([`ScreenScene::sides`]).
pub type Sides = smallvec::SmallVec<[Side; 4]>;

/// All faces of a scene on screen, for one camera.
#[derive(Clone, Debug, Default)]
pub struct ScreenScene {
    /// The polygons, in face order.
    pub polys: Vec<ScreenPoly>,
    /// The grid points that corners name, in the order kept faces first name them: each scene
    /// vertex's snap once, whichever faces share it (a mesh's vertex is the corner of six
    /// triangles on average), and the points clipping made (one per clipped corner).
    pub grid_points: Vec<GridPoint>,
    /// Every polygon's corners, one run per polygon: indices into `grid_points`.
    pub corner_points: Vec<u32>,
    /// Where the sides of the polygons come from ([`ScreenScene::sides`]), listed only for the
    /// polygons whose side k is not simply their face's edge k (`Side::Edge(k)`): clipped
    /// faces, faces that lost a corner to the snap, the triangles of split faces. One entry per
    /// corner of such a polygon, (index into `corner_points`, the side from that corner to the
    /// next), in corner order. A mesh in view lists none: 8 bytes a corner saved (24 MB on a
    /// million triangles).
    pub listed_sides: Vec<(u32, Side)>,
    /// For every face of the scene (`Scene::faces` order, culled ones included): how it lies on
    /// screen. Feature lines read it: a silhouette edge is one whose two faces lie on the same
    /// side of it on screen, whatever the stored winding.
    pub orientation: Vec<Orientation>,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// What projection did.
    pub stats: ProjectStats,
}

impl ScreenScene {
    /// The corners of `p`, in order (copied out of the shared points; on the stack up to four).
    #[inline]
    pub fn corners(&self, p: &ScreenPoly) -> Corners {
        self.corner_indices(p)
            .iter()
            .map(|&i| self.grid_points[i as usize])
            .collect()
    }

    /// The grid (x, y) of face `poly`'s corners when it is a triangle: a convex outline that
    /// contains every piece of the face, so that pieces of faces apart are apart
    /// ([`crate::exact::polygon::corners_separated`]) whatever their cuts.
    #[inline]
    pub fn triangle_xy(&self, poly: u32) -> Option<[[i64; 2]; 3]> {
        let p = &self.polys[poly as usize];
        let c: &[u32; 3] = self.corner_indices(p).try_into().ok()?;
        Some(c.map(|i| {
            let g = self.grid_points[i as usize];
            [g.x, g.y]
        }))
    }

    /// Corner k of `p`.
    #[inline]
    pub fn corner(&self, p: &ScreenPoly, k: usize) -> GridPoint {
        self.grid_points[self.corner_indices(p)[k] as usize]
    }

    /// The corners of `p` as indices into `grid_points`.
    #[inline]
    pub fn corner_indices(&self, p: &ScreenPoly) -> &[u32] {
        &self.corner_points[p.start as usize..(p.start + p.len) as usize]
    }

    /// Appends the corners of a polygon, each its own new grid point (no sharing: for scenes
    /// made by hand), and returns the polygon's `start`; its sides are its face's edges in
    /// order.
    pub fn push_corners(&mut self, corners: &[GridPoint]) -> u32 {
        let start = self.corner_points.len() as u32;
        for &c in corners {
            self.corner_points.push(self.grid_points.len() as u32);
            self.grid_points.push(c);
        }
        start
    }

    /// Where the sides of `p` come from: side k runs from corner k to corner k + 1.
    pub fn sides(&self, p: &ScreenPoly) -> Sides {
        sides_of(&self.listed_sides, p.start, p.len).1
    }

    /// The support plane of `p`, through its exact grid corners (`c > 0`):
    /// [`Plane::of_polygon`] of them, computed on each call (a few 128-bit products). Not
    /// stored: 80 bytes per polygon, a third of the scene's size, that only the first steps of
    /// an algorithm read (pieces share theirs); an algorithm that reads them often keeps
    /// [`ScreenScene::planes`].
    pub fn plane(&self, p: &ScreenPoly) -> Plane {
        Plane::of_polygon(&self.corners(p))
            .expect("a screen polygon has a support plane: `project` drops those without")
    }

    /// Every polygon's support plane ([`ScreenScene::plane`]), in polygon order.
    pub fn planes(&self) -> Vec<Plane> {
        self.polys.iter().map(|p| self.plane(p)).collect()
    }
}

// Outcode bits. The first six are the view frustum (for culling); the guard bits are the
// guard band (for clipping).
const NEAR: u16 = 1;
const FAR: u16 = 2;
const LEFT: u16 = 4;
const RIGHT: u16 = 8;
const BOTTOM: u16 = 16;
const TOP: u16 = 32;
const G_LEFT: u16 = 64;
const G_RIGHT: u16 = 128;
const G_BOTTOM: u16 = 256;
const G_TOP: u16 = 512;
const FRUSTUM: u16 = NEAR | FAR | LEFT | RIGHT | BOTTOM | TOP;
const CLIP: u16 = NEAR | FAR | G_LEFT | G_RIGHT | G_BOTTOM | G_TOP;

#[inline]
fn outcode(p: DVec4) -> u16 {
    let mut c = 0;
    let w = p.w;
    if p.z < -w {
        c |= NEAR;
    }
    if p.z > w {
        c |= FAR;
    }
    if p.x < -w {
        c |= LEFT;
    }
    if p.x > w {
        c |= RIGHT;
    }
    if p.y < -w {
        c |= BOTTOM;
    }
    if p.y > w {
        c |= TOP;
    }
    let g = GUARD * w;
    if p.x < -g {
        c |= G_LEFT;
    }
    if p.x > g {
        c |= G_RIGHT;
    }
    if p.y < -g {
        c |= G_BOTTOM;
    }
    if p.y > g {
        c |= G_TOP;
    }
    c
}

/// Signed distance-like value of a clip-space point to a clip plane (>= 0 inside).
#[inline]
fn plane_value(bit: u16, p: DVec4) -> f64 {
    match bit {
        NEAR => p.z + p.w,
        FAR => p.w - p.z,
        G_LEFT => p.x + GUARD * p.w,
        G_RIGHT => GUARD * p.w - p.x,
        G_BOTTOM => p.y + GUARD * p.w,
        G_TOP => GUARD * p.w - p.y,
        _ => unreachable!(),
    }
}

/// Sutherland–Hodgman against one plane, in homogeneous coordinates. Each point carries the
/// side that starts at it: a kept point keeps its side, a point where an edge leaves the inside
/// starts a side along the clip plane, a point where it comes back starts the rest of that edge.
fn clip_polygon(input: &[(DVec4, Side)], bit: u16, out: &mut Vec<(DVec4, Side)>) {
    out.clear();
    let n = input.len();
    let along_plane = Side::Clip(match bit {
        NEAR => ClipPlane::Near,
        FAR => ClipPlane::Far,
        _ => ClipPlane::Guard,
    });
    for k in 0..n {
        let (a, side) = input[k];
        let b = input[(k + 1) % n].0;
        let da = plane_value(bit, a);
        let db = plane_value(bit, b);
        if da >= 0.0 {
            out.push((a, side));
        }
        if (da >= 0.0) != (db >= 0.0) {
            // Interpolate from the inside point so the same edge clipped from either face gives
            // the same point.
            let (p, q, dp, dq) = if da >= 0.0 {
                (a, b, da, db)
            } else {
                (b, a, db, da)
            };
            let t = dp / (dp - dq);
            let leaving = da >= 0.0;
            out.push((p + (q - p) * t, if leaving { along_plane } else { side }));
        }
    }
}

/// The snapped ends of the segment between two world points as the faces that share it see
/// them: clipped by the same planes in the same order with the same arithmetic as
/// `clip_polygon` (interpolating from the inside end), so a face edge clipped alone ends at the
/// same grid points as the clipped sides of its faces. `None` when the segment lies outside the
/// view frustum or is clipped away.
pub fn snap_segment(m: &glam::DMat4, a: glam::DVec3, b: glam::DVec3) -> Option<[GridPoint; 2]> {
    let (mut p, mut q) = (*m * a.extend(1.0), *m * b.extend(1.0));
    let (cp, cq) = (outcode(p), outcode(q));
    if cp & cq & FRUSTUM != 0 {
        return None;
    }
    for bit in [NEAR, FAR, G_LEFT, G_RIGHT, G_BOTTOM, G_TOP] {
        if (cp | cq) & bit == 0 {
            continue;
        }
        let (dp, dq) = (plane_value(bit, p), plane_value(bit, q));
        match (dp >= 0.0, dq >= 0.0) {
            (true, true) => {}
            (false, false) => return None,
            (true, false) => q = p + (q - p) * (dp / (dp - dq)),
            (false, true) => p = q + (p - q) * (dq / (dq - dp)),
        }
    }
    Some([snap_clip(p), snap_clip(q)])
}

/// The grid point of a world point as an unclipped face corner snaps to it; `None` when a
/// face with that corner would be clipped there (outside the near or far plane or the guard
/// band).
pub fn snap_point(m: &glam::DMat4, a: glam::DVec3) -> Option<GridPoint> {
    let p = *m * a.extend(1.0);
    (outcode(p) & CLIP == 0).then(|| snap_clip(p))
}

/// A clip-space point (inside the clipping planes) divided and snapped to the grid.
fn snap_clip(p: DVec4) -> GridPoint {
    GridPoint::snap(p.x / p.w, p.y / p.w, p.z / p.w)
}

/// The sides of the polygon whose corners start at `start` (`len` of them) in `listed`
/// ([`ScreenScene::listed_sides`]): the listed ones, or its face's edges in order where none
/// are listed; and where its entries start in `listed` (`listed.len()` or past them when none).
fn sides_of(listed: &[(u32, Side)], start: u32, len: u32) -> (usize, Sides) {
    let at = listed.partition_point(|&(corner, _)| corner < start);
    let sides = match listed.get(at) {
        Some(&(corner, _)) if corner == start => (listed[at..at + len as usize].iter())
            .map(|&(_, side)| side)
            .collect(),
        _ => (0..len).map(Side::Edge).collect(),
    };
    (at, sides)
}

/// Replaces `poly`, the last polygon of `corner_points` and `listed_sides`, by triangles of its
/// snapped corners, each with the support plane through its own three corners. The triangles
/// keep the polygon's orientation (`area`); a triangle side that is not a side of the polygon
/// is a [`Side::Diagonal`].
fn split_into_triangles(
    poly: ScreenPoly,
    area: std::cmp::Ordering,
    grid_points: &[GridPoint],
    corner_points: &mut Vec<u32>,
    listed_sides: &mut Vec<(u32, Side)>,
    polys: &mut Vec<ScreenPoly>,
) {
    let start = poly.start as usize;
    let ring: Vec<u32> = corner_points.drain(start..).collect();
    let (listed, ring_sides) = sides_of(listed_sides, poly.start, poly.len);
    listed_sides.truncate(listed);
    let n = ring.len();
    let point = |k: usize| grid_points[ring[k] as usize];
    // Triangulate counter-clockwise (reversing a clockwise ring), then map back.
    let ccw = area.is_gt();
    let at = |k: usize| if ccw { k } else { n - 1 - k };
    let ordered: Vec<GridPoint> = (0..n).map(|k| point(at(k))).collect();
    for t in crate::exact::polygon::ear_triangles(&ordered) {
        let mut t = t.map(at);
        if !ccw {
            t.reverse();
        }
        // A triangle of no area on the grid goes (its plane, `ScreenScene::plane`, is this).
        if Plane::through(point(t[0]), point(t[1]), point(t[2])).is_none() {
            continue;
        }
        let tri_start = corner_points.len();
        for j in 0..3 {
            let (a, b) = (t[j], t[(j + 1) % 3]);
            let side = if b == (a + 1) % n {
                ring_sides[a]
            } else {
                Side::Diagonal
            };
            listed_sides.push((corner_points.len() as u32, side));
            corner_points.push(ring[a]);
        }
        polys.push(ScreenPoly {
            start: tri_start as u32,
            len: 3,
            ..poly
        });
    }
}

/// Faces per chunk of [`project`]'s parallel pass.
const FACE_CHUNK: usize = 1 << 14;

/// What [`project`] makes of one face on its own (16 bytes: the common kept face, unclipped
/// and planar with every corner, is read from the scene again when its corners enter the
/// tables).
enum Made {
    /// Not kept: outside the frustum, flat after snapping, or a culled back face.
    Dropped {
        orientation: Orientation,
        clipped: bool,
    },
    /// Kept as it is: its corners are its face's, in order, each the snap of its vertex.
    Whole {
        orientation: Orientation,
        front: bool,
    },
    /// Kept, clipped or with corners gone (snapped onto the one before) or not planar.
    Ring {
        orientation: Orientation,
        clipped: bool,
        ring: Box<KeptRing>,
    },
}

/// A kept face's snapped ring: per corner the grid point, the scene vertex it is the snap of
/// (an unclipped corner) and the side leaving it.
struct KeptRing {
    points: SmallVec<[GridPoint; 4]>,
    ring: SmallVec<[(Option<u32>, Side); 4]>,
    front: bool,
    /// Its corners lie in one plane (else it is split into triangles).
    planar: bool,
}

/// What [`project`] reads to make a face's ring.
struct FaceContext<'a, C: Fn(usize) -> bool> {
    scene: &'a Scene,
    analysis: &'a SceneAnalysis,
    /// Per scene vertex: its clip-space point, outcode, and snapped grid point (when its
    /// outcode has no clip bit).
    clip: &'a [DVec4],
    codes: &'a [u16],
    snapped: &'a [GridPoint],
    may_cull: &'a C,
}

impl<C: Fn(usize) -> bool> FaceContext<'_, C> {
    /// Face `fi` clipped, snapped and tested for culling.
    fn made(&self, fi: usize) -> Made {
        let (scene, codes) = (self.scene, self.codes);
        let face = &scene.faces[fi];
        let corners = scene.face_corners(face);
        let mut and = u16::MAX;
        let mut or = 0u16;
        for &c in corners {
            let code = codes[c as usize];
            and &= code;
            or |= code;
        }
        if and & FRUSTUM != 0 {
            return Made::Dropped {
                orientation: Orientation::Outside,
                clipped: false,
            };
        }
        let clipped = or & CLIP != 0;
        let mut points: SmallVec<[GridPoint; 4]> = SmallVec::new();
        let mut ring: SmallVec<[(Option<u32>, Side); 4]> = SmallVec::new();
        // A corner at the (x, y) of the one before it ends a side of no length: the side that
        // starts there is the one that goes on.
        let mut push = |g: GridPoint, vertex: Option<u32>, side: Side| {
            if let Some(last) = points.last()
                && last.x == g.x
                && last.y == g.y
            {
                ring.last_mut().expect("parallel to the points").1 = side;
                return;
            }
            points.push(g);
            ring.push((vertex, side));
        };
        if !clipped {
            for (k, &c) in corners.iter().enumerate() {
                push(self.snapped[c as usize], Some(c), Side::Edge(k as u32));
            }
        } else {
            let mut buf_a: Vec<(DVec4, Side)> = (corners.iter().enumerate())
                .map(|(k, &c)| (self.clip[c as usize], Side::Edge(k as u32)))
                .collect();
            let mut buf_b = Vec::new();
            for bit in [NEAR, FAR, G_LEFT, G_RIGHT, G_BOTTOM, G_TOP] {
                if or & bit != 0 {
                    clip_polygon(&buf_a, bit, &mut buf_b);
                    std::mem::swap(&mut buf_a, &mut buf_b);
                }
            }
            for &(p, side) in &buf_a {
                push(snap_clip(p), None, side);
            }
        }
        // Close the ring: the last corner may repeat the first (its side, of no length, goes).
        while points.len() > 1 {
            let (f, l) = (points[0], points[points.len() - 1]);
            if f.x == l.x && f.y == l.y {
                points.pop();
                ring.pop();
            } else {
                break;
            }
        }
        let area = if points.len() >= 3 {
            twice_signed_area(&points)
        } else {
            std::cmp::Ordering::Equal
        };
        let orientation = match area {
            std::cmp::Ordering::Greater => Orientation::Ccw,
            std::cmp::Ordering::Less => Orientation::Cw,
            std::cmp::Ordering::Equal => Orientation::Flat,
        };
        let dropped = Made::Dropped {
            orientation,
            clipped,
        };
        if area.is_eq() {
            return dropped;
        }
        let front = area.is_gt() != self.analysis.meshes[face.mesh as usize].wound_inwards();
        let two_sided = scene.materials[face.material as usize].two_sided;
        if !front && !two_sided && (self.may_cull)(face.mesh as usize) {
            return dropped;
        }
        // Three corners always are; more must lie in the plane of three of them (which exists:
        // a projection with area has three corners not on one line).
        let planar = points.len() == 3 || {
            let plane = Plane::of_polygon(&points).expect("a polygon with area has a plane");
            points.iter().all(|c| plane.sign_at(*c).is_eq())
        };
        if !clipped && planar && points.len() == corners.len() {
            return Made::Whole { orientation, front };
        }
        Made::Ring {
            orientation,
            clipped,
            ring: Box::new(KeptRing {
                points,
                ring,
                front,
                planar,
            }),
        }
    }
}

/// Projects, clips, snaps and culls every face of `scene`.
pub fn project(
    scene: &Scene,
    analysis: &SceneAnalysis,
    camera: &Camera,
    cull: CullMode,
) -> ScreenScene {
    let m = camera.view_projection();
    let clip: Vec<DVec4> = scene
        .positions
        .par_iter()
        .map(|p| m * p.extend(1.0))
        .collect();
    let codes: Vec<u16> = clip.par_iter().map(|&p| outcode(p)).collect();

    let mut stats = ProjectStats {
        faces: scene.faces.len(),
        ..ProjectStats::default()
    };

    // Which meshes may lose their back faces.
    let mut mesh_cull: Vec<bool> = analysis.meshes.iter().map(|a| a.cullable()).collect();
    for (k, mesh) in scene.meshes.iter().enumerate() {
        if !mesh_cull[k] || cull != CullMode::Auto {
            continue;
        }
        let cut = scene.faces[mesh.faces.clone()].iter().any(|f| {
            scene
                .face_corners(f)
                .iter()
                .any(|&c| codes[c as usize] & NEAR != 0)
        });
        if cut {
            mesh_cull[k] = false;
            stats.meshes_cut_by_near += 1;
        }
    }
    let mesh_may_cull = |mesh: usize| match cull {
        CullMode::Auto => mesh_cull[mesh],
        CullMode::On => true,
        CullMode::Off => false,
    };
    stats.culled_meshes = (0..scene.meshes.len())
        .filter(|&k| mesh_may_cull(k))
        .count();

    // Each face on its own first, in parallel, chunk by chunk (a chunk's results are small and
    // gone two chunks later); then in face order, one thread, each kept face's corners enter
    // the tables, so the tables are the same on any number of threads.
    let snapped: Vec<GridPoint> = (clip.par_iter().zip(&codes))
        .map(|(&p, &code)| {
            if code & CLIP == 0 {
                snap_clip(p)
            } else {
                GridPoint { x: 0, y: 0, z: 0 }
            }
        })
        .collect();
    let faces = FaceContext {
        scene,
        analysis,
        clip: &clip,
        codes: &codes,
        snapped: &snapped,
        may_cull: &mesh_may_cull,
    };
    let mut polys = Vec::with_capacity(scene.faces.len());
    // Each scene vertex's index in `grid_points`, once a kept face has it as an unclipped
    // corner.
    let mut point_of_vertex: Vec<u32> = vec![u32::MAX; scene.positions.len()];
    let mut grid_points: Vec<GridPoint> = Vec::with_capacity(scene.positions.len());
    let mut corner_points: Vec<u32> = Vec::with_capacity(scene.corners.len());
    let mut listed_sides: Vec<(u32, Side)> = Vec::new();
    let mut orientation_of = Vec::with_capacity(scene.faces.len());
    let n = scene.faces.len();
    let make = |first: usize, made: &mut Vec<Made>| {
        ((first..(first + FACE_CHUNK).min(n)).into_par_iter())
            .map(|fi| faces.made(fi))
            .collect_into_vec(made);
    };
    let mut enter_chunk = |first: usize, made: &mut Vec<Made>| {
        for (fi, m) in (first..).zip(made.drain(..)) {
            let face = &scene.faces[fi];
            let start = corner_points.len();
            // Kept: its corners enter the tables, a vertex's point once for all its faces.
            let mut enter = |g: GridPoint, vertex: Option<u32>| {
                let known = vertex.map_or(u32::MAX, |v| point_of_vertex[v as usize]);
                let index = if known != u32::MAX {
                    known
                } else {
                    grid_points.push(g);
                    let index = (grid_points.len() - 1) as u32;
                    if let Some(v) = vertex {
                        point_of_vertex[v as usize] = index;
                    }
                    index
                };
                corner_points.push(index);
            };
            let (orientation, front, planar) = match m {
                Made::Dropped {
                    orientation,
                    clipped,
                } => {
                    orientation_of.push(orientation);
                    stats.clipped += clipped as usize;
                    match orientation {
                        Orientation::Outside => stats.frustum_culled += 1,
                        Orientation::Flat => stats.degenerate_after_snap += 1,
                        Orientation::Ccw | Orientation::Cw => stats.backface_culled += 1,
                    }
                    continue;
                }
                Made::Whole { orientation, front } => {
                    for &c in scene.face_corners(face) {
                        enter(snapped[c as usize], Some(c));
                    }
                    (orientation, front, true)
                }
                Made::Ring {
                    orientation,
                    clipped,
                    ring,
                } => {
                    stats.clipped += clipped as usize;
                    let edges_in_order = (ring.ring.iter().enumerate())
                        .all(|(k, &(_, side))| side == Side::Edge(k as u32));
                    for (k, (&g, &(vertex, side))) in ring.points.iter().zip(&ring.ring).enumerate()
                    {
                        if !edges_in_order {
                            listed_sides.push(((start + k) as u32, side));
                        }
                        enter(g, vertex);
                    }
                    (orientation, ring.front, ring.planar)
                }
            };
            orientation_of.push(orientation);
            let poly = ScreenPoly {
                face: fi as u32,
                id: face.id,
                mesh: face.mesh,
                start: start as u32,
                len: (corner_points.len() - start) as u32,
                front,
            };
            if planar {
                polys.push(poly);
            } else {
                stats.split_nonplanar += 1;
                let area = match orientation {
                    Orientation::Ccw => std::cmp::Ordering::Greater,
                    _ => std::cmp::Ordering::Less,
                };
                split_into_triangles(
                    poly,
                    area,
                    &grid_points,
                    &mut corner_points,
                    &mut listed_sides,
                    &mut polys,
                );
            }
        }
    };
    // A chunk's corners enter the tables while the next chunk is made.
    let (mut made, mut next) = (
        Vec::with_capacity(FACE_CHUNK),
        Vec::with_capacity(FACE_CHUNK),
    );
    make(0, &mut made);
    for first in (0..n).step_by(FACE_CHUNK) {
        let after = first + FACE_CHUNK;
        rayon::join(
            || {
                if after < n {
                    make(after, &mut next)
                }
            },
            || enter_chunk(first, &mut made),
        );
        std::mem::swap(&mut made, &mut next);
    }
    stats.visible_polys = polys.len();
    // Reserved for every face (and vertex); culling leaves about half of a closed mesh's.
    // (Shrinking a large block gives its pages back in place: no copy.)
    polys.shrink_to_fit();
    grid_points.shrink_to_fit();
    corner_points.shrink_to_fit();
    listed_sides.shrink_to_fit();
    ScreenScene {
        polys,
        grid_points,
        corner_points,
        listed_sides,
        orientation: orientation_of,
        width: camera.width,
        height: camera.height,
        stats,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::NamedView;
    use crate::scene::analysis::analyse;
    use crate::scene::primitives::{exported_sphere_scene, sphere_scene};
    use std::collections::BTreeSet;

    /// Projection (and the analysis before it) runs on all cores in chunks; the tables it makes
    /// are the same on one thread and on four, over more than two chunks of faces, with and
    /// without culling.
    #[test]
    fn a_scene_projects_the_same_on_one_thread_and_on_four() {
        for scene in [sphere_scene(40_000), exported_sphere_scene(40_000)] {
            assert!(scene.faces.len() > 2 * FACE_CHUNK);
            let bounds = scene.bounds().expect("a sphere has bounds");
            let camera = Camera::fit(NamedView::Front, bounds, false, 40.0, 64, 64);
            let run = |threads: usize| {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .expect("a pool");
                pool.install(|| {
                    let analysis = analyse(&scene);
                    let screen = project(&scene, &analysis, &camera, CullMode::Auto);
                    (analysis, screen)
                })
            };
            let ((a1, s1), (a4, s4)) = (run(1), run(4));
            assert_eq!(a1, a4);
            assert_eq!(s1.polys, s4.polys);
            assert_eq!(s1.grid_points, s4.grid_points);
            assert_eq!(s1.corner_points, s4.corner_points);
            assert_eq!(s1.listed_sides, s4.listed_sides);
            assert_eq!(s1.orientation, s4.orientation);
            assert_eq!(s1.stats, s4.stats);
            assert!(!s1.polys.is_empty());
        }
    }

    /// The parallel pass's per-face result stays 16 bytes (a chunk's worth is made at once):
    /// only a clipped, shortened or non-planar face boxes its ring.
    #[test]
    fn a_face_made_on_its_own_is_sixteen_bytes() {
        assert_eq!(std::mem::size_of::<Made>(), 16);
    }

    /// Corners name shared grid points: each is the snap of its face's vertex, the faces of a
    /// vertex share one point, and a face that is not kept (culled) adds none: the points are
    /// exactly one per vertex of the kept faces.
    #[test]
    fn a_vertex_is_snapped_once_for_all_its_kept_faces() {
        for scene in [sphere_scene(2000), exported_sphere_scene(2000)] {
            let bounds = scene.bounds().expect("a sphere has bounds");
            let camera = Camera::fit(NamedView::Front, bounds, false, 40.0, 64, 64);
            let screen = project(&scene, &analyse(&scene), &camera, CullMode::Auto);
            let m = camera.view_projection();
            let mut kept_vertices = BTreeSet::new();
            let mut named = vec![false; screen.grid_points.len()];
            for p in &screen.polys {
                let face_corners = scene.face_corners(&scene.faces[p.face as usize]);
                for (k, &i) in screen.corner_indices(p).iter().enumerate() {
                    named[i as usize] = true;
                    let Side::Edge(j) = screen.sides(p)[k] else {
                        panic!("nothing is clipped in this view");
                    };
                    let vertex = face_corners[j as usize];
                    kept_vertices.insert(vertex);
                    let snapped = snap_point(&m, scene.positions[vertex as usize]);
                    assert_eq!(Some(screen.grid_points[i as usize]), snapped);
                }
            }
            assert!(
                named.iter().all(|&n| n),
                "every point is some kept corner's"
            );
            assert_eq!(screen.grid_points.len(), kept_vertices.len());
            assert_eq!(screen.corner_points.len(), 3 * screen.polys.len());
            assert!(
                screen.listed_sides.is_empty(),
                "no side of a mesh in view is listed"
            );
        }
    }

    /// A planar quad whose snapped corners are not coplanar on the grid is split into two
    /// triangles, each side a side of the quad (its edge) or the diagonal, listed; the triangle
    /// after it lists nothing and still reads its edges in order.
    #[test]
    fn the_triangles_of_a_split_face_list_their_sides_and_the_others_need_not() {
        let mut b = crate::scene::SceneBuilder::new("split");
        let m = b.default_material();
        b.begin_mesh("quad and triangle");
        // On the plane z = x/4 + y/2 (exactly, in f64), tilted: its snapped corners leave it.
        let quad = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
            .map(|[x, y]| b.add_vertex(glam::DVec3::new(x, y, 0.25 * x + 0.5 * y)));
        let tri = [[1.5, 0.0, 0.0], [2.5, 0.0, 0.1], [2.0, 1.0, 0.2]]
            .map(|[x, y, z]| b.add_vertex(glam::DVec3::new(x, y, z)));
        b.add_face(&quad, m);
        b.add_face(&tri, m);
        let scene = b.finish().expect("two faces");
        let bounds = scene.bounds().expect("bounds");
        let camera = Camera::fit(NamedView::Front, bounds, false, 40.0, 997, 991);
        let screen = project(&scene, &analyse(&scene), &camera, CullMode::Off);
        assert_eq!(screen.stats.split_nonplanar, 1);
        assert_eq!(screen.polys.len(), 3);
        let (halves, last) = (&screen.polys[..2], &screen.polys[2]);
        let mut edges = Vec::new();
        for p in halves {
            assert_eq!(p.face, 0);
            let sides = screen.sides(p);
            assert_eq!(sides.iter().filter(|&&s| s == Side::Diagonal).count(), 1);
            edges.extend(sides.iter().filter_map(|s| match s {
                Side::Edge(k) => Some(*k),
                _ => None,
            }));
        }
        edges.sort_unstable();
        assert_eq!(edges, [0, 1, 2, 3], "each edge of the quad on one triangle");
        assert_eq!(
            screen.listed_sides.len(),
            6,
            "the halves' corners, no other"
        );
        assert_eq!(last.face, 1);
        assert_eq!(
            screen.sides(last)[..],
            (0..3).map(Side::Edge).collect::<Vec<_>>()[..]
        );
    }
}
