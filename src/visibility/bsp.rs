//! The BSP strategy: exact visible sets by binary space partitioning in screen space.
//!
//! 1. Every screen polygon becomes convex [`Piece`]s (non-convex faces are decomposed exactly).
//! 2. A 3D BSP tree is built on the grid with the pieces' support planes as splitters; a piece
//!    that straddles a splitter is split exactly (interpenetration and cyclic overlap resolve
//!    here). After perspective the view is orthographic along +z, so for every support plane
//!    (c > 0) the viewer is on its negative side: walking negative subtree, then the node's own
//!    pieces, then the positive subtree visits pieces front to back.
//! 3. Pieces, front to back, are filtered through a 2D BSP of the covered screen (the coverage
//!    map): the parts landing in uncovered cells are visible and then carve their cell.
//!
//! Invariants of the [`VisibleSet`]: its pieces are convex, have disjoint interiors, each lies in
//! the projection of its own face, and at every point of a piece no other face is nearer. Pieces
//! lying in one plane and overlapping are ordered by the larger face id first (then the later
//! polygon), the z-buffer's tie rule: output never depends on input order.

use crate::camera::Camera;
use crate::exact::polygon::{Piece, Split, convex_pieces, separated};
use crate::exact::predicates::{Line, line_side};
use crate::exact::{GridPoint, Plane, Samples};
use crate::output::drawing::{DrawItem, Drawing};
use crate::pipeline::Fill;
use crate::project::ScreenScene;
use crate::scene::Scene;
use std::cmp::Ordering;
use std::time::Instant;

/// Counters of one BSP run.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BspStats {
    /// Screen polygons in.
    pub polygons: usize,
    /// Convex pieces before any split.
    pub pieces: usize,
    /// Pieces after the 3D BSP (each split adds one).
    pub fragments: usize,
    /// 3D BSP nodes.
    pub nodes: usize,
    /// Depth of the 3D BSP.
    pub depth: usize,
    /// Visible pieces after the coverage pass.
    pub visible_pieces: usize,
    /// Nodes of the 2D coverage tree.
    pub coverage_nodes: usize,
}

/// A splitter's node. The viewer is on every support plane's negative side, so the walk needs
/// no plane test: the plane is only used while building.
struct Node {
    /// Pieces lying in `plane`, front to back (tie rule applied).
    on: Vec<Piece>,
    neg: Option<u32>,
    pos: Option<u32>,
}

/// A 3D BSP tree of the pieces of a screen scene.
pub struct Bsp {
    nodes: Vec<Node>,
    pub stats: BspStats,
}

/// Exact visible regions: disjoint convex pieces, each with its screen polygon.
#[derive(Clone, Debug, Default)]
pub struct VisibleSet {
    pub pieces: Vec<Piece>,
}

/// The convex pieces of every screen polygon.
pub fn initial_pieces(screen: &ScreenScene) -> Vec<Piece> {
    let mut out = Vec::with_capacity(screen.polys.len());
    for (i, p) in screen.polys.iter().enumerate() {
        let pts = screen.corners(p);
        // Pieces are counter-clockwise (y up): back faces seen from behind run the other way.
        let ccw: Vec<GridPoint> = if crate::exact::twice_signed_area(pts) > 0 {
            pts.to_vec()
        } else {
            pts.iter().rev().copied().collect()
        };
        for convex in convex_pieces(&ccw) {
            out.push(Piece::from_convex(i as u32, p.plane, &convex));
        }
    }
    out
}

/// What a node splits by.
#[derive(Clone, Copy, Debug)]
enum Splitter {
    /// A piece's support plane: the viewer is on its negative side.
    Support(Plane),
    /// A vertical plane (a screen line): its two sides do not overlap on screen, so their order
    /// does not matter. These keep the tree balanced where support planes would not (the faces
    /// of a convex mesh never separate one another).
    Screen(Line),
}

impl Splitter {
    fn split(&self, p: &Piece) -> Split {
        match self {
            Splitter::Support(q) => p.split_by_plane(q),
            Splitter::Screen(l) => p.split_by_line(l),
        }
    }

    /// (reaches the negative side, reaches the positive side), without splitting.
    fn sides(&self, p: &Piece) -> (bool, bool) {
        match self {
            Splitter::Support(q) => p.sides_of_plane(q),
            Splitter::Screen(l) => p.sides_of_line(l),
        }
    }
}

/// Screen bounds (grid units) that certainly contain the piece, widened by a unit so that
/// touching pieces also meet: a filter for candidate pairs, never a decision.
fn bounds(p: &Piece) -> [f64; 4] {
    let b = p.bounds();
    [b[0] - 1.0, b[1] - 1.0, b[2] + 1.0, b[3] + 1.0]
}

/// How many splits and how unbalanced a partition would be, over a sample: lower is better.
fn score(splitter: &Splitter, sample: &[&Piece]) -> i64 {
    let (mut neg, mut pos, mut split) = (0i64, 0i64, 0i64);
    for p in sample {
        match splitter.sides(p) {
            (true, false) => neg += 1,
            (false, true) => pos += 1,
            (true, true) => split += 1,
            (false, false) => {}
        }
    }
    8 * split + (neg - pos).abs()
}

/// The vertical line x = m (or y = m), positive on the larger side.
fn screen_line(axis: usize, m: i64) -> Line {
    let (a, b) = if axis == 0 { (1, 0) } else { (0, 1) };
    Line::Edge(Plane {
        a,
        b,
        c: 0,
        d: -(m as i128),
    })
}

/// Candidate splitters: a few support planes spread through the list, and the screen lines
/// through the median of the sample's centres in x and in y. The best on a sample wins.
fn candidates<'a>(pieces: &'a [Piece], boxes: &[[f64; 4]]) -> (Vec<Splitter>, Vec<&'a Piece>) {
    const CANDIDATES: usize = 6;
    const SAMPLE: usize = 48;
    let step = pieces.len().div_ceil(SAMPLE).max(1);
    let sample: Vec<&Piece> = pieces.iter().step_by(step).take(SAMPLE).collect();
    let cstep = pieces.len().div_ceil(CANDIDATES).max(1);
    let mut out: Vec<Splitter> = (0..pieces.len())
        .step_by(cstep)
        .map(|i| Splitter::Support(pieces[i].support))
        .collect();
    if pieces.len() > 2 {
        let centres: Vec<[f64; 2]> = boxes
            .iter()
            .step_by(step)
            .take(SAMPLE)
            .map(|b| [(b[0] + b[2]) / 2.0, (b[1] + b[3]) / 2.0])
            .collect();
        for axis in 0..2 {
            let mut v: Vec<f64> = centres.iter().map(|c| c[axis]).collect();
            v.sort_by(f64::total_cmp);
            let m = v[v.len() / 2].round() as i64;
            out.push(Splitter::Screen(screen_line(axis, m)));
        }
    }
    (out, sample)
}

/// The tie order of coplanar pieces, front first: larger face id, then later polygon.
fn tie_key(screen: &ScreenScene, p: &Piece) -> (std::cmp::Reverse<u32>, std::cmp::Reverse<u32>) {
    (
        std::cmp::Reverse(screen.polys[p.poly as usize].id),
        std::cmp::Reverse(p.poly),
    )
}

/// Do the pieces pairwise have disjoint interiors on screen? Then no piece can hide another and
/// their order does not matter: the node needs no splitter. A sweep over x on f64 bounds finds the
/// candidate pairs; the exact separation test decides each. Stops at the first overlap.
fn pairwise_separated(list: &[Piece], boxes: &[[f64; 4]]) -> bool {
    let mut order: Vec<(f64, usize, [f64; 4])> = boxes
        .iter()
        .enumerate()
        .map(|(i, b)| (b[0], i, *b))
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut active: Vec<(usize, [f64; 4])> = Vec::new();
    for (_, i, b) in order {
        active.retain(|(_, a)| a[2] > b[0]);
        for (j, a) in &active {
            if a[1] < b[3] && b[1] < a[3] && !separated(&list[i], &list[*j]) {
                return false;
            }
        }
        active.push((i, b));
    }
    true
}

/// Partitions `list` by `splitter`: (negative, on, positive).
fn partition(splitter: &Splitter, list: Vec<Piece>) -> (Vec<Piece>, Vec<Piece>, Vec<Piece>) {
    let (mut neg, mut on, mut pos) = (Vec::new(), Vec::new(), Vec::new());
    for p in list {
        match splitter.split(&p) {
            Split::Negative => neg.push(p),
            Split::Positive => pos.push(p),
            Split::On => on.push(p),
            Split::Both(n, q) => {
                neg.push(n);
                pos.push(q);
            }
        }
    }
    (neg, on, pos)
}

impl Bsp {
    /// Builds the 3D BSP of a screen scene.
    pub fn build(screen: &ScreenScene) -> Bsp {
        let pieces = initial_pieces(screen);
        let mut stats = BspStats {
            polygons: screen.polys.len(),
            pieces: pieces.len(),
            ..BspStats::default()
        };
        let mut nodes: Vec<Node> = Vec::new();
        if pieces.is_empty() {
            return Bsp { nodes, stats };
        }
        enum Link {
            Root,
            Neg(u32),
            Pos(u32),
        }
        let mut work: Vec<(Link, usize, Vec<Piece>)> = vec![(Link::Root, 1, pieces)];
        while let Some((link, depth, list)) = work.pop() {
            let n = list.len();
            let boxes: Vec<[f64; 4]> = if n == 1 {
                Vec::new()
            } else {
                list.iter().map(bounds).collect()
            };
            let (mut neg, mut on, mut pos) = if n == 1 || pairwise_separated(&list, &boxes) {
                // Nothing here can hide anything else: keep the pieces together, in input order.
                (Vec::new(), list, Vec::new())
            } else {
                let (cands, sample) = candidates(&list, &boxes);
                let mut ranked: Vec<(i64, usize)> = cands
                    .iter()
                    .enumerate()
                    .map(|(i, c)| (score(c, &sample), i))
                    .collect();
                ranked.sort_unstable();
                let best = cands[ranked[0].1];
                let (neg, on, pos) = partition(&best, list);
                if matches!(best, Splitter::Screen(_)) && (neg.len() >= n || pos.len() >= n) {
                    // The screen line did not separate anything: use the first support plane,
                    // which always removes at least its own piece.
                    let mut all = neg;
                    all.extend(pos);
                    let first = all[0].support;
                    partition(&Splitter::Support(first), all)
                } else {
                    (neg, on, pos)
                }
            };
            // Coplanar pieces that overlap resolve by the tie rule; in a separated bag the order
            // is free, and the same key keeps it deterministic.
            on.sort_by_key(|p| tie_key(screen, p));
            stats.fragments += on.len();
            stats.depth = stats.depth.max(depth);
            let index = nodes.len() as u32;
            nodes.push(Node {
                on,
                neg: None,
                pos: None,
            });
            match link {
                Link::Root => {}
                Link::Neg(parent) => nodes[parent as usize].neg = Some(index),
                Link::Pos(parent) => nodes[parent as usize].pos = Some(index),
            }
            if !neg.is_empty() {
                work.push((Link::Neg(index), depth + 1, std::mem::take(&mut neg)));
            }
            if !pos.is_empty() {
                work.push((Link::Pos(index), depth + 1, std::mem::take(&mut pos)));
            }
        }
        stats.nodes = nodes.len();
        Bsp { nodes, stats }
    }

    /// Visits every piece front to back.
    pub fn front_to_back(&self, mut visit: impl FnMut(&Piece)) {
        if self.nodes.is_empty() {
            return;
        }
        // Explicit stack: a node is expanded into (neg subtree, own pieces, pos subtree).
        enum Step {
            Node(u32),
            Own(u32),
        }
        let mut stack = vec![Step::Node(0)];
        while let Some(step) = stack.pop() {
            match step {
                Step::Own(n) => self.nodes[n as usize].on.iter().for_each(&mut visit),
                Step::Node(n) => {
                    let node = &self.nodes[n as usize];
                    if let Some(p) = node.pos {
                        stack.push(Step::Node(p));
                    }
                    stack.push(Step::Own(n));
                    if let Some(q) = node.neg {
                        stack.push(Step::Node(q));
                    }
                }
            }
        }
    }

    /// Every piece back to front: painter order, for translucent output.
    pub fn back_to_front(&self) -> Vec<Piece> {
        let mut all = Vec::with_capacity(self.stats.fragments);
        self.front_to_back(|p| all.push(p.clone()));
        all.reverse();
        all
    }

    /// The exact visible set: pieces front to back, each minus the visible pieces in front.
    pub fn visible_set(&mut self) -> VisibleSet {
        let mut order = Vec::with_capacity(self.stats.fragments);
        self.front_to_back(|p| order.push(p.clone()));
        let mut coverage = Coverage::new(&order);
        for p in order {
            coverage.insert(p);
        }
        self.stats.visible_pieces = coverage.visible.len();
        VisibleSet {
            pieces: coverage.visible,
        }
    }
}

/// What is already visible, bucketed on a uniform screen grid so that a new piece meets only the
/// pieces whose bounds overlap its own. Subtraction is exact: a piece is split by the lines of
/// each visible piece it may overlap, and the part inside all of them is hidden.
struct Coverage {
    visible: Vec<Piece>,
    bounds: Vec<[f64; 4]>,
    origin: [f64; 2],
    cell: [f64; 2],
    cells: usize,
    buckets: Vec<Vec<u32>>,
    /// Per visible piece, the last query that met it (dedupes across buckets).
    seen: Vec<u32>,
    query: u32,
}

impl Coverage {
    fn new(pieces: &[Piece]) -> Coverage {
        let mut all = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];
        for p in pieces {
            let b = bounds(p);
            all = [
                all[0].min(b[0]),
                all[1].min(b[1]),
                all[2].max(b[2]),
                all[3].max(b[3]),
            ];
        }
        let cells = ((pieces.len() as f64).sqrt() as usize).clamp(1, 512);
        let size = [
            ((all[2] - all[0]) / cells as f64).max(1.0),
            ((all[3] - all[1]) / cells as f64).max(1.0),
        ];
        Coverage {
            visible: Vec::new(),
            bounds: Vec::new(),
            origin: [all[0], all[1]],
            cell: size,
            cells,
            buckets: vec![Vec::new(); cells * cells],
            seen: Vec::new(),
            query: 0,
        }
    }

    fn cell_range(&self, b: &[f64; 4]) -> (usize, usize, usize, usize) {
        let c =
            |v: f64, o: f64, s: f64| (((v - o) / s).floor().max(0.0) as usize).min(self.cells - 1);
        (
            c(b[0], self.origin[0], self.cell[0]),
            c(b[2], self.origin[0], self.cell[0]),
            c(b[1], self.origin[1], self.cell[1]),
            c(b[3], self.origin[1], self.cell[1]),
        )
    }

    fn insert(&mut self, piece: Piece) {
        let b = bounds(&piece);
        let (i0, i1, j0, j1) = self.cell_range(&b);
        self.query += 1;
        let mut near: Vec<u32> = Vec::new();
        for j in j0..=j1 {
            for i in i0..=i1 {
                for &v in &self.buckets[j * self.cells + i] {
                    let vb = &self.bounds[v as usize];
                    if self.seen[v as usize] != self.query
                        && vb[0] < b[2]
                        && b[0] < vb[2]
                        && vb[1] < b[3]
                        && b[1] < vb[3]
                    {
                        self.seen[v as usize] = self.query;
                        near.push(v);
                    }
                }
            }
        }
        near.sort_unstable();
        let mut parts = vec![piece];
        for v in near {
            let front = &self.visible[v as usize];
            let mut next = Vec::with_capacity(parts.len());
            for part in parts {
                subtract(part, front, &mut next);
            }
            parts = next;
            if parts.is_empty() {
                return;
            }
        }
        for part in parts {
            let pb = bounds(&part);
            let index = self.visible.len() as u32;
            let (i0, i1, j0, j1) = self.cell_range(&pb);
            for j in j0..=j1 {
                for i in i0..=i1 {
                    self.buckets[j * self.cells + i].push(index);
                }
            }
            self.visible.push(part);
            self.bounds.push(pb);
            self.seen.push(0);
        }
    }
}

/// Pushes the parts of `piece` outside the convex `front` (exactly; touching is outside).
fn subtract(piece: Piece, front: &Piece, out: &mut Vec<Piece>) {
    if separated(&piece, front) {
        out.push(piece);
        return;
    }
    let mut inside = piece;
    for line in &front.lines {
        match inside.split_by_line(line) {
            // Entirely outside this line of `front`: nothing of it is hidden.
            Split::Negative => {
                out.push(inside);
                return;
            }
            Split::Positive => {}
            Split::Both(outside, rest) => {
                out.push(outside);
                inside = rest;
            }
            // No area: nothing to keep.
            Split::On => return,
        }
    }
    // What is left is inside every line of `front`: hidden.
}

impl VisibleSet {
    /// The face id at every pixel centre (row-major, row 0 at the top), decided exactly: a
    /// sample on a boundary between pieces goes to the earlier piece.
    pub fn face_ids(&self, screen: &ScreenScene) -> Vec<Option<u32>> {
        let (w, h) = (screen.width as i64, screen.height as i64);
        let s = Samples::new(screen.width, screen.height);
        let mut ids: Vec<Option<u32>> = vec![None; (w * h) as usize];
        for piece in &self.pieces {
            let v = piece.vertices_f64();
            let (mut c0, mut c1, mut r0, mut r1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
            for [x, y] in &v {
                c0 = c0.min(s.col_of(*x));
                c1 = c1.max(s.col_of(*x));
                r0 = r0.min(s.row_of(*y));
                r1 = r1.max(s.row_of(*y));
            }
            let i0 = ((c0 - 1.0).floor() as i64).clamp(0, w);
            let i1 = ((c1 + 1.0).ceil() as i64).clamp(0, w);
            let j0 = ((r0 - 1.0).floor() as i64).clamp(0, h);
            let j1 = ((r1 + 1.0).ceil() as i64).clamp(0, h);
            let id = screen.polys[piece.poly as usize].id;
            for j in j0..j1 {
                // The sample row y = y_num/H as the line H·y - y_num = 0.
                let row = Line::Edge(Plane {
                    a: 0,
                    b: h,
                    c: 0,
                    d: -(s.y_num(j) as i128),
                });
                for i in i0..i1 {
                    let k = (j * w + i) as usize;
                    if ids[k].is_some() {
                        continue;
                    }
                    let col = Line::Edge(Plane {
                        a: w,
                        b: 0,
                        c: 0,
                        d: -(s.x_num(i) as i128),
                    });
                    let inside = piece
                        .lines
                        .iter()
                        .all(|l| line_side([&col, &row], l) != Some(Ordering::Less));
                    if inside {
                        ids[k] = Some(id);
                    }
                }
            }
        }
        ids
    }

    /// The pieces' vertices in pixel coordinates (y down), rounded once: for drawing.
    pub fn pixel_rings(&self, screen: &ScreenScene) -> Vec<(u32, Vec<[f64; 2]>)> {
        let s = Samples::new(screen.width, screen.height);
        self.pieces
            .iter()
            .map(|p| {
                let ring = p
                    .vertices_f64()
                    .into_iter()
                    .map(|[x, y]| [s.col_of(x), s.row_of(y)])
                    .collect();
                (p.poly, ring)
            })
            .collect()
    }
}

/// The BSP strategy behind the common trait. Opaque scenes draw the exact visible set; a scene
/// with translucent faces (under `Fill::Shade`) draws every fragment back to front, in the BSP's
/// exact order, so each translucent fragment blends over what lies behind it.
pub struct BspMethod;

impl super::VisibilityMethod for BspMethod {
    fn name(&self) -> &'static str {
        "bsp"
    }

    fn exact(&self) -> bool {
        true
    }

    fn run(
        &self,
        scene: &Scene,
        screen: &ScreenScene,
        camera: &Camera,
        fill: Fill,
    ) -> super::VisibilityResult {
        let fallbacks = crate::exact::predicates::fallback_count();
        let t = Instant::now();
        let mut bsp = Bsp::build(screen);
        let t_build = t.elapsed().as_secs_f64();
        let translucent = fill == Fill::Shade
            && screen.polys.iter().any(|p| {
                scene.materials[scene.faces[p.face as usize].material as usize].transparency > 0.0
            });
        let t = Instant::now();
        let pieces = if translucent {
            bsp.back_to_front()
        } else {
            bsp.visible_set().pieces
        };
        let t_visible = t.elapsed().as_secs_f64();
        let s = Samples::new(screen.width, screen.height);
        let ring = |p: &Piece| -> Vec<[f64; 2]> {
            p.vertices_f64()
                .into_iter()
                .map(|[x, y]| [s.col_of(x), s.row_of(y)])
                .collect()
        };
        let item = |p: &Piece, rings: Vec<Vec<[f64; 2]>>| {
            let poly = &screen.polys[p.poly as usize];
            let (color, opacity) = super::face_paint(scene, poly.face as usize, camera, fill);
            DrawItem {
                face: poly.id,
                material: scene.faces[poly.face as usize].material,
                rings,
                color,
                opacity,
            }
        };
        let items: Vec<DrawItem> = if translucent {
            // Painter order matters: one item per fragment.
            pieces.iter().map(|p| item(p, vec![ring(p)])).collect()
        } else {
            // Disjoint pieces: merge each face's into regions with holes.
            let mut by_face: std::collections::BTreeMap<u32, Vec<&Piece>> = Default::default();
            for p in &pieces {
                by_face
                    .entry(screen.polys[p.poly as usize].id)
                    .or_default()
                    .push(p);
            }
            by_face
                .into_values()
                .flat_map(|group| {
                    let first = group[0];
                    merge_rings(conforming_rings(&group, &s))
                        .into_iter()
                        .map(move |rings| item(first, rings))
                        .collect::<Vec<_>>()
                })
                .collect()
        };
        let st = &bsp.stats;
        let mut stats = serde_json::Map::new();
        let mut put = |k: &str, v: serde_json::Value| {
            stats.insert(k.to_string(), v);
        };
        put("polygons", st.polygons.into());
        put("pieces", st.pieces.into());
        put("fragments", st.fragments.into());
        put(
            "fragments_per_polygon",
            (st.fragments as f64 / st.polygons.max(1) as f64).into(),
        );
        put("bsp_nodes", st.nodes.into());
        put("bsp_depth", st.depth.into());
        put("visible_pieces", st.visible_pieces.into());
        put("translucent_painter_order", translucent.into());
        put(
            "exact_fallbacks",
            (crate::exact::predicates::fallback_count() - fallbacks).into(),
        );
        put("build_seconds", t_build.into());
        put("visible_seconds", t_visible.into());
        super::VisibilityResult {
            drawing: Drawing {
                width: screen.width,
                height: screen.height,
                background: super::background(fill),
                items,
            },
            stats,
        }
    }
}

/// The pixel rings of one face's pieces, made conforming: where a vertex of one piece lies on an
/// edge of another (a T-junction, decided exactly), it is inserted into that edge with the very
/// same f64 coordinates, so shared boundaries are identical segments and the union below closes
/// them without slivers.
fn conforming_rings(pieces: &[&Piece], s: &Samples) -> Vec<Vec<[f64; 2]>> {
    let px = |[x, y]: [f64; 2]| [s.col_of(x), s.row_of(y)];
    let boxes: Vec<[f64; 4]> = pieces.iter().map(|p| bounds(p)).collect();
    pieces
        .iter()
        .enumerate()
        .map(|(a, pa)| {
            let n = pa.len();
            let mut ring = Vec::with_capacity(n);
            for k in 0..n {
                let start = pa.vertex_f64(k);
                ring.push(px(start));
                // Vertices of other pieces strictly inside edge k (line k, between vertices k
                // and k+1): on line k, strictly inside every other line.
                let edge = &pa.lines[k];
                let mut on_edge: Vec<(f64, [f64; 2])> = Vec::new();
                for (b, pb) in pieces.iter().enumerate() {
                    let (ba, bb) = (&boxes[a], &boxes[b]);
                    if b == a || ba[0] > bb[2] || bb[0] > ba[2] || ba[1] > bb[3] || bb[1] > ba[3] {
                        continue;
                    }
                    for v in 0..pb.len() {
                        if pb.vertex_line_sign(v, edge) != Ordering::Equal {
                            continue;
                        }
                        let inside =
                            pa.lines.iter().enumerate().all(|(j, l)| {
                                j == k || pb.vertex_line_sign(v, l) == Ordering::Greater
                            });
                        if inside {
                            let q = pb.vertex_f64(v);
                            let t = (q[0] - start[0]).abs() + (q[1] - start[1]).abs();
                            on_edge.push((t, q));
                        }
                    }
                }
                on_edge.sort_by(|x, y| x.0.total_cmp(&y.0));
                on_edge.dedup_by(|x, y| x.1 == y.1);
                ring.extend(on_edge.into_iter().map(|(_, q)| px(q)));
            }
            ring
        })
        .collect()
}

/// The union of one face's disjoint convex rings (pixel coordinates) as regions, each an outer
/// ring followed by its holes. geo's boolean union works in f64 on coordinates already rounded for
/// output, and its snapping moves a point by far less than a millionth of a pixel: within the
/// output-rounding approximation. A single ring is returned as it is.
fn merge_rings(rings: Vec<Vec<[f64; 2]>>) -> Vec<Vec<Vec<[f64; 2]>>> {
    use geo::{LineString, Polygon};
    if rings.len() == 1 {
        return vec![rings];
    }
    let polys: Vec<Polygon<f64>> = rings
        .into_iter()
        .map(|r| {
            Polygon::new(
                LineString::from(r.into_iter().map(|[x, y]| (x, y)).collect::<Vec<_>>()),
                vec![],
            )
        })
        .collect();
    let merged = geo::algorithm::bool_ops::unary_union(&polys);
    let open = |ls: &LineString<f64>| -> Vec<[f64; 2]> {
        let mut v: Vec<[f64; 2]> = ls.coords().map(|c| [c.x, c.y]).collect();
        // geo closes rings by repeating the first point; drawings do not.
        if v.len() > 1 && v.first() == v.last() {
            v.pop();
        }
        v
    };
    merged
        .0
        .iter()
        .map(|poly| {
            std::iter::once(open(poly.exterior()))
                .chain(poly.interiors().iter().map(open))
                .collect()
        })
        .collect()
}
