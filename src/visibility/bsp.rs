//! The 3D BSP tree of a screen scene's pieces: an exact painter order, and a second way to the
//! exact visible set.
//!
//! The pieces' support planes are the splitters; a piece that straddles a splitter is split
//! exactly (interpenetration and cyclic overlap resolve here). After perspective the view is
//! orthographic along +z, so for every support plane (c > 0) the viewer is on its negative side:
//! negative subtree, the node's own pieces, positive subtree is front to back, with no plane test
//! in the walk. Vertical screen lines also serve as splitters where support planes would leave
//! the tree unbalanced (the faces of a convex mesh never separate one another).
//!
//! Invariant of the tree: walking it front to back ([`Bsp::front_to_back`]) visits every
//! fragment after every fragment that can hide part of it. Coplanar overlapping pieces are
//! ordered by the larger face id first (then the later polygon), the z-buffer's tie rule.
//!
//! Used by the [`super::BspTree`] strategy (the whole visible set through the tree) and by every
//! exact strategy for the back-to-front order of translucent faces.

use super::coverage::{Coverage, bounds, tie_key};
use super::initial_pieces;
use super::strips::Counters;
use super::visible_set::{Fragment, VisibleSet};
use crate::exact::Plane;
use crate::exact::polygon::{Boundary, Piece, Split, separated};
use crate::exact::predicates::Line;
use crate::progress::{Report, Ticker};
use crate::project::ScreenScene;
use std::sync::Arc;

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
}

impl Counters for BspStats {
    fn add(&mut self, o: &Self) {
        self.polygons = self.polygons.max(o.polygons);
        self.pieces += o.pieces;
        self.fragments += o.fragments;
        self.nodes += o.nodes;
        self.depth = self.depth.max(o.depth);
        self.visible_pieces += o.visible_pieces;
    }
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
    /// Counters of the build (and of the visible set, once computed).
    pub stats: BspStats,
}

/// What a node splits by.
#[derive(Clone, Debug)]
enum Splitter {
    /// A support plane and the polygon it is the plane of: the viewer is on its negative side.
    Support(Arc<Plane>, u32),
    /// A vertical plane (a screen line): its two sides do not overlap on screen, so their order
    /// does not matter. These keep the tree balanced where support planes would not (the faces
    /// of a convex mesh never separate one another).
    Screen(Line),
}

impl Splitter {
    fn split(&self, p: &Piece) -> Split {
        match self {
            Splitter::Support(q, by) => p.split_by_plane(q, *by),
            Splitter::Screen(l) => p.split_by_line(l, Boundary::ScreenSplit),
        }
    }

    /// (reaches the negative side, reaches the positive side), without splitting.
    fn sides(&self, p: &Piece) -> (bool, bool) {
        match self {
            Splitter::Support(q, _) => p.sides_of_plane(q),
            Splitter::Screen(l) => p.sides_of_line(l),
        }
    }
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
pub(crate) fn screen_line(axis: usize, m: i64) -> Line {
    let (a, b) = if axis == 0 { (1, 0) } else { (0, 1) };
    Line::vertical(&Plane {
        a,
        b,
        c: 0,
        d: crate::exact::w256(-(m as i128)),
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
        .map(|i| Splitter::Support(pieces[i].support.clone(), pieces[i].poly))
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
        Self::build_with_progress(screen, None)
    }

    /// [`Self::build`], reporting stage "painter order": fragments placed in nodes of the
    /// fragments known so far (the total grows as pieces are split).
    pub fn build_with_progress(screen: &ScreenScene, report: Option<Report>) -> Bsp {
        Self::build_from(screen, initial_pieces(screen), report)
    }

    /// Builds the 3D BSP of some of a screen scene's pieces, reporting as
    /// [`Self::build_with_progress`].
    pub fn build_from(screen: &ScreenScene, pieces: Vec<Piece>, report: Option<Report>) -> Bsp {
        let mut ticker = Ticker::new(report, "painter order", pieces.len() as u64);
        // Pieces waiting in `work`: fragments placed + pending is every fragment known so far.
        let mut pending = pieces.len();
        let mut stats = BspStats {
            polygons: screen.polys.len(),
            pieces: pieces.len(),
            ..BspStats::default()
        };
        let mut nodes: Vec<Node> = Vec::new();
        if pieces.is_empty() {
            ticker.finish();
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
            pending -= n;
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
                let best = cands[ranked[0].1].clone();
                let (neg, on, pos) = partition(&best, list);
                if matches!(best, Splitter::Screen(_)) && (neg.len() >= n || pos.len() >= n) {
                    // The screen line did not separate anything: use the first support plane,
                    // which always removes at least its own piece.
                    let mut all = neg;
                    all.extend(pos);
                    let first = Splitter::Support(all[0].support.clone(), all[0].poly);
                    partition(&first, all)
                } else {
                    (neg, on, pos)
                }
            };
            // Coplanar pieces that overlap resolve by the tie rule; in a separated bag the order
            // is free, and the same key keeps it deterministic.
            on.sort_by_key(|p| tie_key(screen, p));
            // The node keeps its pieces for the whole walk: no spare room (a vector of pieces
            // grows by doubling from four, and a piece is a few hundred bytes inline).
            on.shrink_to_fit();
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
            pending += neg.len() + pos.len();
            if !neg.is_empty() {
                work.push((Link::Neg(index), depth + 1, std::mem::take(&mut neg)));
            }
            if !pos.is_empty() {
                work.push((Link::Pos(index), depth + 1, std::mem::take(&mut pos)));
            }
            let placed = stats.fragments as u64;
            ticker.tick_of(placed, placed + pending as u64);
        }
        ticker.finish();
        stats.nodes = nodes.len();
        Bsp { nodes, stats }
    }

    /// The nodes in walk order: the fragments of node `order[0]`, then `order[1]`'s, ... are
    /// every fragment front to back.
    fn walk_order(&self) -> Vec<u32> {
        let mut order = Vec::with_capacity(self.nodes.len());
        if self.nodes.is_empty() {
            return order;
        }
        // Explicit stack: a node is expanded into (neg subtree, own pieces, pos subtree).
        enum Step {
            Node(u32),
            Own(u32),
        }
        let mut stack = vec![Step::Node(0)];
        while let Some(step) = stack.pop() {
            match step {
                Step::Own(n) => order.push(n),
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
        order
    }

    /// Visits every piece front to back.
    pub fn front_to_back(&self, mut visit: impl FnMut(&Piece)) {
        for n in self.walk_order() {
            self.nodes[n as usize].on.iter().for_each(&mut visit);
        }
    }

    /// Every piece front to back, moved out of the tree: each node's pieces are freed as they
    /// move, so the tree and the list are never both whole in memory.
    pub fn into_front_to_back(mut self) -> Vec<Piece> {
        let mut all = Vec::with_capacity(self.stats.fragments);
        for n in self.walk_order() {
            all.append(&mut std::mem::take(&mut self.nodes[n as usize].on));
        }
        all
    }

    /// Every piece back to front: painter order, for translucent output.
    pub fn back_to_front(&self) -> Vec<Piece> {
        let mut all = Vec::with_capacity(self.stats.fragments);
        self.front_to_back(|p| all.push(p.clone()));
        all.reverse();
        all
    }

    /// The coverage map of every piece, inserted front to back: each minus the visible pieces
    /// in front ([`Coverage::insert_behind`]). Consumes the tree (its pieces move into the map).
    pub fn into_coverage(self, screen: &ScreenScene) -> Coverage<'_> {
        let order = self.into_front_to_back();
        let mut coverage = Coverage::new(screen, &order);
        for p in order {
            coverage.insert_behind(p);
        }
        coverage
    }

    /// The exact visible set: pieces front to back, each minus the visible pieces in front.
    pub fn visible_set(self, screen: &ScreenScene) -> (VisibleSet, BspStats) {
        let mut stats = self.stats.clone();
        let pieces = self.into_coverage(screen).into_pieces();
        stats.visible_pieces = pieces.len();
        (VisibleSet::of_pieces(pieces), stats)
    }
}

/// The parts of the translucent pieces `see_through` that no piece of `opaque` (the opaque
/// faces' coverage map) hides, back to front in the exact order of a 3D BSP of the translucent
/// pieces alone: each blends over everything drawn before it, and over nothing that should hide
/// it. Reports stage "painter order".
pub fn translucent_layer(
    screen: &ScreenScene,
    opaque: &mut Coverage,
    see_through: Vec<Piece>,
    report: Option<Report>,
) -> (Vec<Fragment>, BspStats) {
    let bsp = Bsp::build_from(screen, see_through, report);
    let stats = bsp.stats.clone();
    let mut back_to_front = bsp.into_front_to_back();
    back_to_front.reverse();
    let mut parts = Vec::new();
    for f in back_to_front {
        opaque.unhidden_parts(f, &mut parts);
    }
    let layer = parts
        .into_iter()
        .map(|p| Fragment::Piece(Box::new(p)))
        .collect();
    (layer, stats)
}
