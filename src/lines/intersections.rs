//! Intersection lines: where two faces pass through each other, exactly.
//!
//! On the grid a face is its screen polygon with the depth of its support plane, so faces a and
//! b meet exactly on the screen line where their planes are at the same depth (`Line::Cut`), at
//! the points of that line inside both polygons. The segment where they meet is that line
//! clipped to both (convex parts of) polygons, decided exactly ([`clip_to_convex`]).
//!
//! Which pairs: every two screen polygons (back faces included: a hidden intersection is drawn
//! too) whose boxes overlap on screen and in depth, that share no edge (two welded vertices),
//! and whose meeting line passes strictly through both polygons. Pairs sharing one vertex are
//! included where they cross beyond it. Every screen polygon lies exactly in its support plane
//! (`project` splits a face whose snapped corners left one plane into triangles), so faces
//! around a shared vertex agree on its depth exactly. Coplanar faces have no meeting line and
//! make none.
//!
//! A face seen exactly edge-on ([`FlatFace`]: no area on screen, so no screen polygon) still
//! meets the faces that pass through it, along its screen line: there the meeting is the part
//! of that line where the other face's plane lies within the edge-on face (found exactly from
//! where the plane crosses the face's sides in 3D) and inside the other face's polygon. Edge-on
//! faces that are not convex, or are clipped, are left out.

use super::along::{At, Carrier};
use super::tracks::clip_to_convex;
use crate::exact::polygon::convex_piece_indices;
use crate::exact::predicates::Line;
use crate::exact::{GridPoint, Plane, PlaneApprox};
use crate::project::{ScreenPoly, ScreenScene};
use crate::scene::Scene;
use std::cmp::Ordering;

/// Two faces passing through each other.
#[derive(Clone, Debug)]
pub struct Meeting {
    /// The faces (`Scene::faces` indices), `faces[0] < faces[1]`.
    pub faces: [u32; 2],
    /// The planes of the two screen polygons that meet, in the order of `faces` (a face may
    /// be several polygons: `project` splits faces that are not planar on the grid); `None`
    /// for an edge-on face, which has no polygon.
    pub planes: Option<[Plane; 2]>,
    /// The screen line where their planes meet.
    pub line: Line,
    /// A support plane holding the meeting in 3D.
    pub depth: Plane,
    /// Where on it they meet: inside both polygons.
    pub extent: Vec<(At, At)>,
    /// One of the faces is seen edge-on (it has no visible pieces to tell where the meeting is
    /// seen).
    pub edge_on: bool,
}

/// A face seen exactly edge-on: its snapped corners, all on one screen line.
#[derive(Clone, Debug)]
pub struct FlatFace {
    /// Index into `Scene::faces`.
    pub face: u32,
    /// Its snapped corners, in order.
    pub corners: Vec<GridPoint>,
}

/// Every meeting of two faces of `screen` (see the module docs). `weld` gives each scene
/// position its welded vertex id.
pub fn meetings(
    scene: &Scene,
    screen: &ScreenScene,
    flats: &[FlatFace],
    weld: &[u32],
) -> Vec<Meeting> {
    let polys = &screen.polys;
    // Every pair reads them: made once.
    let planes = screen.planes();
    // Each face's box on screen and in depth (x0, y0, z0, x1, y1, z1), made in one list: a
    // list per part, then joined, cost their pages' faults twice over (a million faces).
    let box_of = |b: [f64; 4], d: [f64; 2]| [b[0], b[1], d[0], b[2], b[3], d[1]];
    let boxes: Vec<[f64; 6]> = (polys.iter().zip(&planes))
        .map(|(p, plane)| box_of(screen_box(screen, p), depth_range(screen, p, plane)))
        .chain(flats.iter().map(|f| {
            let z = f.corners.iter().map(|c| c.z as f64);
            let depths = [
                z.clone().fold(f64::MAX, f64::min) - 1.0,
                z.fold(f64::MIN, f64::max) + 1.0,
            ];
            box_of(points_box(&f.corners), depths)
        }))
        .collect();
    let approx: Vec<PlaneApprox> = planes.iter().map(PlaneApprox::of).collect();
    // Each face's welded vertex ids (distinct, in corner order), made once: every pair asks.
    let mut weld_start = Vec::with_capacity(scene.faces.len() + 1);
    let mut welds: Vec<u32> = Vec::with_capacity(3 * scene.faces.len());
    weld_start.push(0);
    for face in &scene.faces {
        let start = welds.len();
        for &c in scene.face_corners(face) {
            let v = weld[c as usize];
            if !welds[start..].contains(&v) {
                welds.push(v);
            }
        }
        weld_start.push(welds.len());
    }
    let welds_of = |f: u32| &welds[weld_start[f as usize]..weld_start[f as usize + 1]];
    // How many welded vertices two faces share.
    let shared = |fa: u32, fb: u32| {
        let of_a = welds_of(fa);
        welds_of(fb).iter().filter(|v| of_a.contains(v)).count()
    };
    let share_an_edge = |fa: u32, fb: u32| shared(fa, fb) >= 2;
    let n = polys.len();
    // Where two faces whose boxes meet pass through each other. Convex parts are made per
    // pair: only pairs whose planes cross inside both polygons need them, a few in a mesh.
    let meeting = |a: usize, b: usize| -> Option<Meeting> {
        if a >= n && b >= n {
            return None;
        }
        if b >= n {
            // An edge-on face and a polygon.
            let flat = &flats[b - n];
            if share_an_edge(flat.face, polys[a].face) {
                return None;
            }
            let parts_a = convex_parts(screen, &polys[a]);
            return edge_on_meeting(flat, &polys[a], &planes[a], &parts_a);
        }
        let (pa, pb) = (&polys[a], &polys[b]);
        // Faces sharing an edge meet along it only (most pairs of a mesh): decided on welded
        // ids before any plane is evaluated.
        let shared_corners = shared(pa.face, pb.face);
        if shared_corners >= 2 {
            return None;
        }
        // Every polygon lies in its plane (`project` splits the others), so the meeting line's
        // side at a corner is the side of the other plane the corner lies on.
        let (plane_a, plane_b) = (&planes[a], &planes[b]);
        if !straddles(screen, pb, pa, plane_a, &approx[a])
            || !straddles(screen, pa, pb, plane_b, &approx[b])
        {
            return None;
        }
        let line = Line::cut(*plane_a, *plane_b);
        if shared_corners == 1 && apart_beyond_corner(screen, pa, pb, &line) == Some(true) {
            return None;
        }
        let carrier = Carrier::new(line.clone());
        let mut extent = Vec::new();
        let (parts_a, parts_b) = (convex_parts(screen, pa), convex_parts(screen, pb));
        for part_a in &parts_a {
            let Some(ia) = clip_to_convex(&carrier, part_a) else {
                continue;
            };
            for part_b in &parts_b {
                if let Some(ib) = clip_to_convex(&carrier, part_b)
                    && let Some(both) = overlap(&carrier, ia.clone(), ib)
                {
                    extent.push(both);
                }
            }
        }
        if extent.is_empty() {
            return None;
        }
        let (fa, fb) = (pa.face.min(pb.face), pa.face.max(pb.face));
        let in_face_order = if pa.face < pb.face {
            [*plane_a, *plane_b]
        } else {
            [*plane_b, *plane_a]
        };
        Some(Meeting {
            faces: [fa, fb],
            planes: Some(in_face_order),
            line,
            depth: *plane_a,
            extent,
            edge_on: false,
        })
    };
    overlapping_pairs(&boxes, &meeting)
}

/// What `decide(a, b)` (`a < b`) finds for every two boxes of `boxes` (x0, y0, z0, x1, y1, z1)
/// whose closed extents meet, each pair once (a filter: `decide` tests exactly): a
/// bounding-volume hierarchy (median splits of the box centres on the longest axis, leaves of
/// a few boxes) joined with itself, which copes with boxes of every size (long thin CAD
/// triangles and fine ones). Large parts of the join run on all cores; the results come in
/// the order of the sequential walk whatever the thread count.
fn overlapping_pairs<T: Send>(
    boxes: &[[f64; 6]],
    decide: &(impl Fn(usize, usize) -> Option<T> + Sync),
) -> Vec<T> {
    overlapping_pairs_splitting_at(boxes, PARALLEL_BOXES, decide)
}

/// [`overlapping_pairs`], splitting joins of at least `parallel_boxes` boxes across cores.
fn overlapping_pairs_splitting_at<T: Send>(
    boxes: &[[f64; 6]],
    parallel_boxes: usize,
    decide: &(impl Fn(usize, usize) -> Option<T> + Sync),
) -> Vec<T> {
    if boxes.is_empty() {
        return Vec::new();
    }
    let mut ids: Vec<u32> = (0..boxes.len() as u32).collect();
    // Twice the box centres, made once (the median splits compare them many times).
    let centres: Vec<[f64; 3]> = boxes
        .iter()
        .map(|b| [b[0] + b[3], b[1] + b[4], b[2] + b[5]])
        .collect();
    let empty = Node {
        bounds: [0.0; 6],
        children: None,
        run: (0, 0),
    };
    let mut nodes = vec![empty; node_count(boxes.len())];
    let tree = Subtree {
        boxes,
        centres: &centres,
        parallel_boxes,
    };
    tree.build(&mut ids, 0, &mut nodes, 0);
    let tree = Hierarchy {
        nodes: &nodes,
        ids: &ids,
        boxes,
        parallel_boxes,
    };
    tree.join_self(0, decide)
}

/// A node of the hierarchy: its box, and either its two children or its run of `ids`.
#[derive(Clone)]
struct Node {
    bounds: [f64; 6],
    children: Option<(usize, usize)>,
    run: (usize, usize),
}

const LEAF: usize = 8;

/// Joins of nodes holding at least this many boxes between them are split across cores.
const PARALLEL_BOXES: usize = 4096;

fn union(boxes: &[[f64; 6]], ids: &[u32]) -> [f64; 6] {
    ids.iter()
        .fold(EMPTY_BOX, |u, &i| joined(&u, &boxes[i as usize]))
}

/// The box holding no point: the identity of [`joined`].
const EMPTY_BOX: [f64; 6] = [f64::MAX, f64::MAX, f64::MAX, f64::MIN, f64::MIN, f64::MIN];

/// The smallest box holding both.
fn joined(a: &[f64; 6], b: &[f64; 6]) -> [f64; 6] {
    let mut u = *a;
    for k in 0..3 {
        u[k] = u[k].min(b[k]);
        u[k + 3] = u[k + 3].max(b[k + 3]);
    }
    u
}

fn meet(a: &[f64; 6], b: &[f64; 6]) -> bool {
    (0..3).all(|k| a[k] <= b[k + 3] && b[k] <= a[k + 3])
}

/// How many nodes the hierarchy over `boxes` boxes has: one, or one and its halves'.
fn node_count(boxes: usize) -> usize {
    if boxes <= LEAF {
        1
    } else {
        1 + node_count(boxes / 2) + node_count(boxes - boxes / 2)
    }
}

/// What building a hierarchy reads.
struct Subtree<'a> {
    boxes: &'a [[f64; 6]],
    centres: &'a [[f64; 3]],
    /// Subtrees of at least this many boxes build their halves side by side.
    parallel_boxes: usize,
}

impl Subtree<'_> {
    /// Builds the subtree over `ids` (starting at `offset` in the whole list) into `nodes`, its
    /// [`node_count`] nodes in pre-order, the first numbered `at` in the whole hierarchy: the
    /// numbering of building it depth first, with each half's nodes known in advance, so the
    /// halves build side by side into their own parts of the list.
    fn build(&self, ids: &mut [u32], offset: usize, nodes: &mut [Node], at: usize) {
        let run = (offset, offset + ids.len());
        if ids.len() <= LEAF {
            nodes[0] = Node {
                bounds: union(self.boxes, ids),
                children: None,
                run,
            };
            return;
        }
        let centre = |i: u32, k: usize| self.centres[i as usize][k];
        // The axis along which the box centres spread most.
        let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
        for &i in ids.iter() {
            for k in 0..3 {
                lo[k] = lo[k].min(centre(i, k));
                hi[k] = hi[k].max(centre(i, k));
            }
        }
        let axis = (0..3)
            .max_by(|&j, &k| (hi[j] - lo[j]).total_cmp(&(hi[k] - lo[k])))
            .expect("three axes");
        let mid = ids.len() / 2;
        ids.select_nth_unstable_by(mid, |&a, &b| {
            centre(a, axis).total_cmp(&centre(b, axis)).then(a.cmp(&b))
        });
        let parallel = ids.len() >= self.parallel_boxes;
        let (left, right) = ids.split_at_mut(mid);
        let (root, below) = nodes.split_first_mut().expect("a node for the root");
        let (left_nodes, right_nodes) = below.split_at_mut(node_count(mid));
        let (l, r) = (at + 1, at + 1 + left_nodes.len());
        if parallel {
            rayon::join(
                || self.build(left, offset, left_nodes, l),
                || self.build(right, offset + mid, right_nodes, r),
            );
        } else {
            self.build(left, offset, left_nodes, l);
            self.build(right, offset + mid, right_nodes, r);
        }
        // Min and max are exact: the halves' bounds joined are the union of all the boxes.
        *root = Node {
            bounds: joined(&left_nodes[0].bounds, &right_nodes[0].bounds),
            children: Some((l, r)),
            run,
        };
    }
}

/// A built hierarchy, read by the joins.
struct Hierarchy<'a> {
    nodes: &'a [Node],
    ids: &'a [u32],
    boxes: &'a [[f64; 6]],
    /// Joins of at least this many boxes run their halves side by side.
    parallel_boxes: usize,
}

impl Hierarchy<'_> {
    fn size(&self, n: usize) -> usize {
        self.nodes[n].run.1 - self.nodes[n].run.0
    }

    fn run(&self, n: usize) -> &[u32] {
        &self.ids[self.nodes[n].run.0..self.nodes[n].run.1]
    }

    /// `first` then `second`, side by side on all cores when `parallel`, concatenated in that
    /// order.
    fn both<T: Send>(
        parallel: bool,
        first: impl FnOnce() -> Vec<T> + Send,
        second: impl FnOnce() -> Vec<T> + Send,
    ) -> Vec<T> {
        let (mut a, b) = if parallel {
            rayon::join(first, second)
        } else {
            (first(), second())
        };
        a.extend(b);
        a
    }

    /// The pairs within node `n`'s boxes: within each child, then across them.
    fn join_self<T: Send>(
        &self,
        n: usize,
        decide: &(impl Fn(usize, usize) -> Option<T> + Sync),
    ) -> Vec<T> {
        let Some((l, r)) = self.nodes[n].children else {
            let run = self.run(n);
            let mut out = Vec::new();
            for (k, &a) in run.iter().enumerate() {
                for &b in &run[k + 1..] {
                    if meet(&self.boxes[a as usize], &self.boxes[b as usize]) {
                        out.extend(decide(a.min(b) as usize, a.max(b) as usize));
                    }
                }
            }
            return out;
        };
        let parallel = self.size(n) >= self.parallel_boxes;
        Self::both(
            parallel,
            || {
                Self::both(
                    parallel,
                    || self.join_self(l, decide),
                    || self.join_self(r, decide),
                )
            },
            || self.join(l, r, decide),
        )
    }

    /// The pairs of a box of node `a` and one of node `b`.
    fn join<T: Send>(
        &self,
        a: usize,
        b: usize,
        decide: &(impl Fn(usize, usize) -> Option<T> + Sync),
    ) -> Vec<T> {
        if !meet(&self.nodes[a].bounds, &self.nodes[b].bounds) {
            return Vec::new();
        }
        let parallel = self.size(a) + self.size(b) >= self.parallel_boxes;
        match (self.nodes[a].children, self.nodes[b].children) {
            (None, None) => {
                let mut out = Vec::new();
                for &p in self.run(a) {
                    for &q in self.run(b) {
                        if meet(&self.boxes[p as usize], &self.boxes[q as usize]) {
                            out.extend(decide(p.min(q) as usize, p.max(q) as usize));
                        }
                    }
                }
                out
            }
            // Split the node that has more boxes (or the only inner one).
            (Some((l, r)), None) => Self::both(
                parallel,
                || self.join(l, b, decide),
                || self.join(r, b, decide),
            ),
            (None, Some((l, r))) => Self::both(
                parallel,
                || self.join(a, l, decide),
                || self.join(a, r, decide),
            ),
            (Some((al, ar)), Some((bl, br))) => {
                if self.size(a) >= self.size(b) {
                    Self::both(
                        parallel,
                        || self.join(al, b, decide),
                        || self.join(ar, b, decide),
                    )
                } else {
                    Self::both(
                        parallel,
                        || self.join(a, bl, decide),
                        || self.join(a, br, decide),
                    )
                }
            }
        }
    }
}

/// For two triangles with a common corner V that the meeting line of their planes passes
/// through: do they go apart from V (each meets the line on a different side of V, so they do
/// not cross beyond it)? Exact, on grid integers; `None` when they are not two triangles with
/// a common corner. Seen from V, the line runs into a triangle (V, p, q) on the side where the
/// segment p-q crosses it: with p on the line's positive side, that is along the line's
/// direction exactly when the triangle turns clockwise.
fn apart_beyond_corner(
    screen: &ScreenScene,
    pa: &ScreenPoly,
    pb: &ScreenPoly,
    line: &Line,
) -> Option<bool> {
    let (ca, cb) = (&screen.corners(pa), &screen.corners(pb));
    if ca.len() != 3 || cb.len() != 3 {
        return None;
    }
    let (i, j) = (0..3)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .find(|&(i, j)| ca[i] == cb[j])?;
    let direction = |c: &[GridPoint], k: usize| -> Option<i32> {
        let (v, p, q) = (c[k], c[(k + 1) % 3], c[(k + 2) % 3]);
        let turn = crate::exact::predicates::orient2d(v, p, q);
        match (side_at(line, p), turn) {
            (Ordering::Equal, _) | (_, Ordering::Equal) => None,
            (sp, turn) => Some(if (sp == Ordering::Greater) == (turn == Ordering::Less) {
                1
            } else {
                -1
            }),
        }
    };
    Some(direction(ca, i)? != direction(cb, j)?)
}

/// Where the edge-on face `flat` meets polygon `b` (support plane `plane`, convex parts
/// `parts`), if they cross.
fn edge_on_meeting(
    flat: &FlatFace,
    b: &ScreenPoly,
    plane: &Plane,
    parts: &[Vec<Line>],
) -> Option<Meeting> {
    let c = &flat.corners;
    // The screen line: through the two corners farthest apart along it.
    let (lo, hi) = (c.iter().min()?, c.iter().max()?);
    let line = Line::edge(*lo, *hi)?;
    let carrier = Carrier::new(line.clone());
    // Where b's plane crosses the face's sides in 3D, exactly.
    let sign = |p: &GridPoint| plane.sign_at(*p);
    let signs: Vec<Ordering> = c.iter().map(sign).collect();
    if !signs.contains(&Ordering::Less) || !signs.contains(&Ordering::Greater) {
        return None;
    }
    let k = c.len();
    let mut crossings = Vec::new();
    for i in 0..k {
        let j = (i + 1) % k;
        if signs[i] == Ordering::Equal {
            crossings.push(At::Grid([c[i].x, c[i].y]));
        } else if signs[j] != Ordering::Equal && signs[i] != signs[j] {
            if (c[i].x, c[i].y) == (c[j].x, c[j].y) {
                crossings.push(At::Grid([c[i].x, c[i].y]));
            } else {
                crossings.push(At::Cross(Line::cut(*plane, plane_along(c[i], c[j]))));
            }
        }
    }
    // A convex face is crossed at exactly two points.
    let [p, q] = &crossings[..] else { return None };
    let [p, q] = carrier.ordered(p.clone(), q.clone())?;
    let inside = (p.at(), q.at());
    let extent: Vec<(At, At)> = parts
        .iter()
        .filter_map(|part| overlap(&carrier, inside.clone(), clip_to_convex(&carrier, part)?))
        .collect();
    (!extent.is_empty()).then(|| Meeting {
        faces: [flat.face.min(b.face), flat.face.max(b.face)],
        planes: None,
        line,
        depth: *plane,
        extent,
        edge_on: true,
    })
}

/// A support plane holding the 3D segment p-q (distinct on screen): through p, q and the grid
/// point beside p at p's depth, square to the segment on screen.
pub fn plane_along(p: GridPoint, q: GridPoint) -> Plane {
    let r = GridPoint {
        x: p.x - (q.y - p.y),
        y: p.y + (q.x - p.x),
        z: p.z,
    };
    Plane::through(p, q, r).expect("r is off the segment's line on screen")
}

/// The box of some grid points, one grid unit wider each way (a filter).
pub(crate) fn points_box(points: &[GridPoint]) -> [f64; 4] {
    let mut b = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];
    for c in points {
        b = [
            b[0].min(c.x as f64),
            b[1].min(c.y as f64),
            b[2].max(c.x as f64),
            b[3].max(c.y as f64),
        ];
    }
    [b[0] - 1.0, b[1] - 1.0, b[2] + 1.0, b[3] + 1.0]
}

/// The polygon's screen box, one grid unit wider each way (a filter).
fn screen_box(screen: &ScreenScene, p: &ScreenPoly) -> [f64; 4] {
    points_box(&screen.corners(p))
}

/// The depth range of the polygon's plane `pl` over its corners (a filter): the plane's depth
/// at a corner, `-(a·x + b·y + d) / c`, in f64 widened by its error bound (each coefficient
/// rounded once, the products, the sum and the quotient once each: below `8·U` of the terms'
/// magnitudes over `c`) and one grid unit.
fn depth_range(screen: &ScreenScene, p: &ScreenPoly, pl: &Plane) -> [f64; 2] {
    let (a, b, c, d) = (
        pl.a as f64,
        pl.b as f64,
        pl.c as f64,
        crate::exact::i256_to_f64(pl.d),
    );
    let (mut lo, mut hi) = (f64::MAX, f64::MIN);
    for q in screen.corners(p) {
        let (ax, by) = (a * q.x as f64, b * q.y as f64);
        let z = -(ax + by + d) / c;
        let err = 8.0 * crate::exact::U * (ax.abs() + by.abs() + d.abs()) / c + 1.0;
        lo = lo.min(z - err);
        hi = hi.max(z + err);
    }
    [lo, hi]
}

/// Do the corners of `p` lie strictly on both sides of `other`'s plane? Exact. A corner that
/// is also a corner of `other` lies in its plane (every polygon lies exactly in its plane), so
/// it is skipped: it is where the filter would always fall back to exact arithmetic.
/// `plane` is `other`'s plane, `approx` it rounded.
fn straddles(
    screen: &ScreenScene,
    p: &ScreenPoly,
    other: &ScreenPoly,
    plane: &Plane,
    approx: &PlaneApprox,
) -> bool {
    let theirs = screen.corners(other);
    let (mut pos, mut neg) = (false, false);
    for c in &screen.corners(p) {
        if theirs.contains(c) {
            continue;
        }
        match approx.sign_at(plane, *c) {
            Ordering::Greater => pos = true,
            Ordering::Less => neg = true,
            Ordering::Equal => {}
        }
    }
    pos && neg
}

/// The sign of `line` at a grid point, exactly.
fn side_at(line: &Line, c: GridPoint) -> Ordering {
    line.sign_at_grid(c.x, c.y)
}

/// The polygon's convex parts, each as its side lines with the inside positive.
pub(crate) fn convex_parts(screen: &ScreenScene, p: &ScreenPoly) -> Vec<Vec<Line>> {
    let corners = &screen.corners(p);
    // Work counter-clockwise.
    let ccw: Vec<GridPoint> = if crate::exact::twice_signed_area(corners).is_gt() {
        corners.to_vec()
    } else {
        corners.iter().rev().copied().collect()
    };
    let lines_of = |ring: &[GridPoint]| -> Vec<Line> {
        (0..ring.len())
            .filter_map(|i| Line::edge(ring[i], ring[(i + 1) % ring.len()]))
            .collect()
    };
    if ccw.len() == 3 {
        return vec![lines_of(&ccw)];
    }
    convex_piece_indices(&ccw)
        .iter()
        .map(|ring| lines_of(&ring.iter().map(|&i| ccw[i]).collect::<Vec<_>>()))
        .collect()
}

/// The common part of two spans of `carrier`, if it has length.
pub(crate) fn overlap(carrier: &Carrier, a: (At, At), b: (At, At)) -> Option<(At, At)> {
    let lo = carrier.param(&a.0).max(carrier.param(&b.0));
    let hi = carrier.param(&a.1).min(carrier.param(&b.1));
    (lo < hi).then(|| (lo.at(), hi.at()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Camera, NamedView};
    use crate::project::{CullMode, project};
    use crate::scene::analysis::analyse;
    use crate::scene::primitives::interpenetrating_tori;

    /// The join split across cores at every size finds every pair of meeting boxes once, in
    /// the order of the sequential walk, on four threads.
    #[test]
    fn the_parallel_join_is_the_sequential_walk() {
        let mut rng = crate::scene::primitives::SplitMix64(5);
        let mut next = || rng.next_f64();
        let boxes: Vec<[f64; 6]> = (0..3000)
            .map(|_| {
                let (x, y, z, s) = (next(), next(), next(), 0.1 * next());
                [x, y, z, x + s, y + s, z + s]
            })
            .collect();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(4)
            .build()
            .expect("a pool");
        let pair = |a: usize, b: usize| Some((a, b));
        let sequential = overlapping_pairs_splitting_at(&boxes, usize::MAX, &pair);
        let parallel = pool.install(|| overlapping_pairs_splitting_at(&boxes, 2, &pair));
        assert_eq!(parallel, sequential);
        let mut sorted = sequential.clone();
        sorted.sort();
        let brute: Vec<(usize, usize)> = (0..boxes.len())
            .flat_map(|a| (a + 1..boxes.len()).map(move |b| (a, b)))
            .filter(|&(a, b)| meet(&boxes[a], &boxes[b]))
            .collect();
        assert_eq!(sorted, brute);
        assert!(brute.len() > 1000, "{} pairs", brute.len());
    }

    /// Two interpenetrating tori of 10,240 triangles: the hierarchy's join splits across cores
    /// above [`PARALLEL_BOXES`], and the meetings found on one thread and on four are the same
    /// list, in the same order.
    #[test]
    fn meetings_are_the_same_on_one_thread_and_on_four() {
        let scene = interpenetrating_tori(64, 40);
        assert!(scene.faces.len() > 2 * PARALLEL_BOXES);
        let bounds = scene.bounds().expect("tori have bounds");
        let camera = Camera::fit(NamedView::Iso, bounds, false, 40.0, 256, 256);
        let screen = project(&scene, &analyse(&scene), &camera, CullMode::Off);
        let weld: Vec<u32> = (0..scene.positions.len() as u32).collect();
        let on = |threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a pool");
            let found = pool.install(|| meetings(&scene, &screen, &[], &weld));
            found
                .iter()
                .map(|m| format!("{:?} {:?} {:?}", m.faces, m.line, m.extent))
                .collect::<Vec<_>>()
        };
        let one = on(1);
        assert!(one.len() > 100, "{} meetings", one.len());
        assert_eq!(one, on(4));
    }
}
