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

use crate::exact::polygon::{Piece, Split, convex_pieces};
use crate::exact::predicates::{Line, line_side};
use crate::exact::{GridPoint, Plane, Samples};
use crate::project::ScreenScene;
use std::cmp::Ordering;

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

/// How many splits and how unbalanced a partition by `plane` would be, over a sample.
fn score(plane: &Plane, sample: &[Piece]) -> i64 {
    let (mut neg, mut pos, mut split) = (0i64, 0i64, 0i64);
    for p in sample {
        match p.split_by_plane(plane) {
            Split::Negative => neg += 1,
            Split::Positive => pos += 1,
            Split::Both(..) => split += 1,
            Split::On => {}
        }
    }
    8 * split + (neg - pos).abs()
}

/// Picks a splitter: among a few candidates spread through the list, the one with the fewest
/// splits and the best balance on a sample.
fn choose_splitter(pieces: &[Piece]) -> usize {
    const CANDIDATES: usize = 6;
    const SAMPLE: usize = 48;
    if pieces.len() <= 2 {
        return 0;
    }
    let step = pieces.len().div_ceil(SAMPLE).max(1);
    let sample: Vec<Piece> = pieces.iter().step_by(step).take(SAMPLE).cloned().collect();
    let cstep = pieces.len().div_ceil(CANDIDATES).max(1);
    (0..pieces.len())
        .step_by(cstep)
        .min_by_key(|&i| (score(&pieces[i].support, &sample), i))
        .unwrap_or(0)
}

/// The tie order of coplanar pieces, front first: larger face id, then later polygon.
fn tie_key(screen: &ScreenScene, p: &Piece) -> (std::cmp::Reverse<u32>, std::cmp::Reverse<u32>) {
    (
        std::cmp::Reverse(screen.polys[p.poly as usize].id),
        std::cmp::Reverse(p.poly),
    )
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
        // Work list: (parent link to fill, depth, pieces).
        enum Link {
            Root,
            Neg(u32),
            Pos(u32),
        }
        let mut work: Vec<(Link, usize, Vec<Piece>)> = vec![(Link::Root, 1, pieces)];
        while let Some((link, depth, mut list)) = work.pop() {
            let s = choose_splitter(&list);
            let splitter = list.swap_remove(s);
            let plane = splitter.support;
            let mut on = vec![splitter];
            let (mut neg, mut pos) = (Vec::new(), Vec::new());
            for p in list {
                match p.split_by_plane(&plane) {
                    Split::Negative => neg.push(p),
                    Split::Positive => pos.push(p),
                    Split::On => on.push(p),
                    Split::Both(n, q) => {
                        neg.push(n);
                        pos.push(q);
                    }
                }
            }
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
                work.push((Link::Neg(index), depth + 1, neg));
            }
            if !pos.is_empty() {
                work.push((Link::Pos(index), depth + 1, pos));
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

    /// The exact visible set: pieces front to back through the coverage map.
    pub fn visible_set(&mut self) -> VisibleSet {
        let mut coverage = Coverage::new();
        let mut visible = Vec::new();
        self.front_to_back(|p| coverage.insert(p.clone(), &mut visible));
        self.stats.visible_pieces = visible.len();
        self.stats.coverage_nodes = coverage.nodes.len();
        VisibleSet { pieces: visible }
    }
}

/// The covered part of the screen as a 2D BSP: leaves are covered (`In`) or not (`Out`).
struct Coverage {
    nodes: Vec<Cell>,
}

enum Cell {
    Split { line: Line, neg: u32, pos: u32 },
    In,
    Out,
}

impl Coverage {
    fn new() -> Coverage {
        Coverage {
            nodes: vec![Cell::Out],
        }
    }

    /// Files `piece` down the tree: parts reaching uncovered cells are visible (pushed to `out`)
    /// and carve their cell.
    fn insert(&mut self, piece: Piece, out: &mut Vec<Piece>) {
        let mut work = vec![(0u32, piece)];
        while let Some((n, p)) = work.pop() {
            match &self.nodes[n as usize] {
                Cell::In => {}
                Cell::Out => {
                    self.carve(n, &p);
                    out.push(p);
                }
                Cell::Split { line, neg, pos } => {
                    let (neg, pos) = (*neg, *pos);
                    match p.split_by_line(line) {
                        Split::Negative => work.push((neg, p)),
                        Split::Positive => work.push((pos, p)),
                        Split::Both(a, b) => {
                            work.push((neg, a));
                            work.push((pos, b));
                        }
                        // No area on either side: nothing to draw.
                        Split::On => {}
                    }
                }
            }
        }
    }

    /// Replaces the uncovered leaf `n` by a chain of the piece's lines: outside each line an
    /// uncovered leaf, inside all of them a covered one.
    fn carve(&mut self, n: u32, p: &Piece) {
        let mut at = n;
        for (k, line) in p.lines.iter().enumerate() {
            let out = self.nodes.len() as u32;
            self.nodes.push(Cell::Out);
            let next = self.nodes.len() as u32;
            self.nodes.push(if k + 1 == p.lines.len() {
                Cell::In
            } else {
                Cell::Out
            });
            self.nodes[at as usize] = Cell::Split {
                line: *line,
                neg: out,
                pos: next,
            };
            at = next;
        }
    }
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
