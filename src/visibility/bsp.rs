//! The 3D BSP tree of a screen scene's pieces: an exact painter order, and a second way to the
//! exact visible set.
//!
//! A node first looks for its pieces' front layer (`front_layer`): the pieces nothing else in
//! the node can hide, which go first, unsplit, and the rest behind them (a convex surface's
//! front faces, then the faces behind). Where no piece may go first (cyclic overlap,
//! interpenetration), or the layer is thin and a splitter divides the pieces, the pieces'
//! support planes are the splitters; a piece that straddles a splitter is split exactly. After
//! perspective the view is orthographic along +z, so for every support plane (c > 0) the viewer
//! is on its negative side: negative subtree, the node's own pieces, positive subtree is front to
//! back, with no plane test in the walk. Vertical screen lines also serve as splitters where
//! support planes would leave the tree unbalanced.
//!
//! Invariant of the tree: walking it front to back ([`Bsp::front_to_back`]) visits every
//! fragment after every fragment that can hide part of it. Coplanar overlapping pieces are
//! ordered by the larger face id first (then the later polygon), the z-buffer's tie rule.
//!
//! Used by the [`super::BspTree`] strategy (the whole visible set through the tree) and by every
//! exact strategy for the back-to-front order of translucent faces.

use super::coverage::{Coverage, bounds, tie_key};
use super::covered::{CoverTries, covered};
use super::depth::{self, cannot_hide};
use super::grid::{BoxGrid, NO_BOX, joined};
use super::live::overlap;
use super::strips::Counters;
use super::visible_set::{Fragment, Stats, VisibleSet};
use super::{CornerTable, Outline, initial_pieces, separated_on};
use crate::exact::Plane;
use crate::exact::polygon::{Boundary, Piece, Split, separated_by_lines};
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
    /// Pairs of pieces with overlapping screen boxes tested exactly while planning nodes (the
    /// front layer's and the separation checks' tests): the tree's main cost.
    pub pair_tests: usize,
    /// Visible pieces after the coverage pass.
    pub visible_pieces: usize,
    /// Pieces proven hidden whole, uncut ([`super::covered`]): under a front layer while the
    /// tree is built, or by the coverage pass
    /// ([`super::coverage::CoverageStats::covers`]).
    pub covered: usize,
}

impl BspStats {
    /// Writes the tree's own counters (fragments, nodes, depth, pair tests) into a strategy's
    /// stats; the strategy counts its pieces itself (occluded ones never reach a tree).
    pub(crate) fn put_tree(&self, stats: &mut Stats) {
        stats.insert("fragments".into(), self.fragments.into());
        stats.insert("bsp_nodes".into(), self.nodes.into());
        stats.insert("bsp_depth".into(), self.depth.into());
        stats.insert("bsp_pair_tests".into(), self.pair_tests.into());
    }
}

impl Counters for BspStats {
    fn add(&mut self, o: &Self) {
        self.polygons = self.polygons.max(o.polygons);
        self.pieces += o.pieces;
        self.fragments += o.fragments;
        self.nodes += o.nodes;
        self.depth = self.depth.max(o.depth);
        self.pair_tests += o.pair_tests;
        self.visible_pieces += o.visible_pieces;
        self.covered += o.covered;
    }
}

/// A splitter's node. The viewer is on every support plane's negative side, so the walk needs
/// no plane test: the plane is only used while building.
struct Node {
    /// The node's own pieces: those lying in its splitter's plane (tie rule applied), or a
    /// front layer, or a bag of pieces none of which can hide another.
    on: Vec<Piece>,
    /// Do the pieces of `on` have pairwise disjoint interiors on screen (a front layer or a
    /// bag)? Then none clips another in the coverage map ([`Coverage::insert_disjoint`]).
    disjoint: bool,
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

/// How a splitter would partition a sample of pieces.
#[derive(Clone, Copy, Debug)]
struct Tally {
    /// Pieces wholly on one side, on the other, and split.
    neg: i64,
    pos: i64,
    split: i64,
}

impl Tally {
    fn of(splitter: &Splitter, sample: &[&Piece]) -> Tally {
        let (mut neg, mut pos, mut split) = (0i64, 0i64, 0i64);
        for p in sample {
            match splitter.sides(p) {
                (true, false) => neg += 1,
                (false, true) => pos += 1,
                (true, true) => split += 1,
                (false, false) => {}
            }
        }
        Tally { neg, pos, split }
    }

    /// How many splits and how unbalanced, weighed: lower is better.
    fn cost(&self) -> i64 {
        8 * self.split + (self.neg - self.pos).abs()
    }

    /// Does the splitter divide the sample, leaving each side at most three quarters of it and
    /// splitting at most one piece in sixteen? Such a splitter shrinks a crowd geometrically.
    fn divides(&self) -> bool {
        let all = self.neg + self.pos + self.split;
        16 * self.split <= all && 4 * self.neg.max(self.pos) <= 3 * all
    }
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
/// their order does not matter: the node needs no splitter. The sweep of [`box_pairs`] finds the
/// candidate pairs; the exact separation test decides each (counted in `tests`). Stops at the
/// first overlap.
fn pairwise_separated(
    screen: &ScreenScene,
    list: &[Piece],
    boxes: &[[f64; 4]],
    tests: &mut usize,
) -> bool {
    box_pairs(boxes, &vec![true; list.len()], |i, j| {
        *tests += 1;
        separated_on(screen, &list[i], &list[j])
    })
}

/// A crowd: past this many pairs per piece that may hide one another (overlapping on screen,
/// one not provably behind the other), a node looks for its [`front_layer`] only when no
/// splitter divides it ([`Tally::divides`]). A stack of parallel squares has such a pair for
/// all but one of the others and gives up early; a surface's pieces have few, however many
/// boxes they meet: a sphere's polar slivers seen edge-on meet 60 (100k triangles) to 170
/// (1M) neighbours' boxes, but the corners they share settle almost every pair. Counting box
/// pairs instead gave up on the 1M sphere's strips after 7.6M pair tests (a quarter of all)
/// that were then thrown away, and split them into 2.8k more pieces. Pieces whose boxes
/// overlap but which all lie apart cost a test a pair either way: giving up, the node would
/// sweep them all again to learn that they are pairwise separated.
const LAYER_PAIRS_PER_PIECE: usize = 32;

/// A front layer with fewer than one piece in this many is thin: the node takes a splitter
/// instead (shingles overlapping in a chain would otherwise be peeled one per level).
const THIN_LAYER: usize = 32;

/// A piece whose place the layer search decides at its node; otherwise a piece's entry is the
/// index, in its node's list, of a piece that may hide part of it (found by the parent's search;
/// the two are the same pieces, unsplit, so the piece is still not in the layer).
const OPEN: u32 = u32::MAX;

/// Sweeps the boxes' interiors, calling `meet(i, j)` (`i < j`) for each overlapping pair with
/// at least one open piece (`open[k]`), until it returns `false`; returns whether the sweep ran
/// to the end. Pairs of settled pieces are never visited: a stack of layers costs each level
/// the pairs of its open pieces, not all pairs.
///
/// The sweep runs along the axis the boxes are shortest on relative to the list's extent:
/// the boxes a sweep line crosses, each tested against every new box, are then fewest (a
/// screen strip is tall and narrow: swept in x, its line would cross a whole column).
fn box_pairs(
    boxes: &[[f64; 4]],
    open: &[bool],
    mut meet: impl FnMut(usize, usize) -> bool,
) -> bool {
    // Box corners by sweep axis: (start, end) along it, then (start, end) across it.
    let [lo, hi, across_lo, across_hi] = if sweeps_in_x(boxes) {
        [0, 2, 1, 3]
    } else {
        [1, 3, 0, 2]
    };
    let mut order: Vec<u32> = (0..boxes.len() as u32).collect();
    order.sort_by(|&a, &b| {
        boxes[a as usize][lo]
            .total_cmp(&boxes[b as usize][lo])
            .then(a.cmp(&b))
    });
    // The boxes the sweep line crosses: open ones, and settled ones.
    let mut crossing: [Vec<u32>; 2] = [Vec::new(), Vec::new()];
    for i in order {
        let b = &boxes[i as usize];
        let is_open = open[i as usize];
        for list in &mut crossing {
            list.retain(|&j| boxes[j as usize][hi] > b[lo]);
        }
        let met = if is_open {
            &crossing[..]
        } else {
            &crossing[..1]
        };
        for &j in met.iter().flatten() {
            let a = &boxes[j as usize];
            if a[across_lo] < b[across_hi]
                && b[across_lo] < a[across_hi]
                && !meet(j.min(i) as usize, j.max(i) as usize)
            {
                return false;
            }
        }
        crossing[usize::from(!is_open)].push(i);
    }
    true
}

/// Should [`box_pairs`] sweep in x? When the boxes' mean width is a smaller share of the
/// list's width than their mean height is of its height: a line across the sweep then
/// crosses fewer boxes.
fn sweeps_in_x(boxes: &[[f64; 4]]) -> bool {
    let mut all = NO_BOX;
    let (mut widths, mut heights) = (0.0, 0.0);
    for b in boxes {
        all = joined(all, b);
        widths += b[2] - b[0];
        heights += b[3] - b[1];
    }
    // widths / width <= heights / height, multiplied out (no division by an empty extent).
    widths * (all[3] - all[1]) <= heights * (all[2] - all[0])
}

/// The pieces that may go first, before every other piece of `list`: those whose screen
/// interior meets no other piece's that may hide part of it ([`cannot_hide`]). Two pieces of
/// the layer never overlap on screen (neither hiding the other would make them equally deep on
/// their common part, where each is as deep as the other only on a line), so the layer needs no
/// order among its pieces and no split; a convex surface's front faces are one layer, the faces
/// behind them the next. All of `list` when its pieces are pairwise separated on screen.
/// `depths`: the pieces' [`depth::range`]s.
///
/// Decides the open pieces of `blockers` (see [`OPEN`]): each stays open (in the layer) or
/// gets the index of a piece that may hide part of it. Gives up (`false`, `blockers` partly
/// decided) past `most_pairs` pairs that may hide one another. Adds its pair tests to `tests`.
fn front_layer(
    screen: &ScreenScene,
    list: &[Piece],
    boxes: &[[f64; 4]],
    depths: &[[f64; 2]],
    blockers: &mut [u32],
    most_pairs: usize,
    tests: &mut usize,
) -> bool {
    let open: Vec<bool> = blockers.iter().map(|&b| b == OPEN).collect();
    // Each piece's grid corners and their edge lines, found once (a piece meets a dozen boxes),
    // none when a vertex is off the grid and its face is not a triangle. A cut piece (off the
    // grid) has its triangle's corners instead (`exact[k]` false): it lies within them, so
    // triangles apart have pieces apart.
    let mut outlines = CornerTable::with_capacity(list.len());
    let mut exact = Vec::with_capacity(list.len());
    for p in list {
        match p.grid_corners() {
            Some(c) => {
                outlines.push(&c);
                exact.push(true);
            }
            None => {
                outlines.push(screen.triangle_xy(p.poly).as_ref().map_or(&[], |t| &t[..]));
                exact.push(false);
            }
        }
    }
    let mut pairs = 0;
    box_pairs(boxes, &open, |i, j| {
        *tests += 1;
        // Uncut neighbours on a surface share corners and never overlap: their corners settle
        // it before any plane test. Cut ones are apart when their triangles are.
        let apart = (outlines.get(i))
            .zip(outlines.get(j))
            .map(|(a, b)| a.separated(b))
            .filter(|&apart| apart || (exact[i] && exact[j]));
        if apart == Some(true) {
            return true;
        }
        let (pi, pj) = ((&list[i], depths[i]), (&list[j], depths[j]));
        let fails_i = blockers[i] == OPEN && !cannot_hide(pj, pi);
        let fails_j = blockers[j] == OPEN && !cannot_hide(pi, pj);
        if (fails_i || fails_j) && !apart.unwrap_or_else(|| separated_by_lines(&list[i], &list[j]))
        {
            if fails_i {
                blockers[i] = j as u32;
            }
            if fails_j {
                blockers[j] = i as u32;
            }
            pairs += 1;
            if pairs > most_pairs {
                return false;
            }
        }
        true
    })
}

/// Which pieces of the rest of a front layer (those not [`OPEN`] in `blockers`) lie wholly
/// under the layer's pieces ([`covered`]), of those `tries` says are worth trying. The layer's
/// pieces have disjoint interiors on screen, and none can be hidden by a piece of the list:
/// wherever a piece of the rest overlaps one, it lies behind it. So a piece of the rest within
/// their union is hidden.
fn under_layer(
    screen: &ScreenScene,
    list: &[Piece],
    boxes: &[[f64; 4]],
    blockers: &[u32],
    tries: &mut CoverTries,
) -> Vec<bool> {
    let layer: Vec<usize> = (0..list.len()).filter(|&k| blockers[k] == OPEN).collect();
    let grid = BoxGrid::holding(&layer.iter().map(|&k| boxes[k]).collect::<Vec<_>>());
    // The layer's grid corners and their lines, found once (each is tested against many): none
    // for a piece with a vertex off the grid.
    let mut outlines = CornerTable::with_capacity(layer.len());
    for &k in &layer {
        outlines.push(list[k].grid_corners().as_deref().unwrap_or(&[]));
    }
    // Per layer piece, the last piece of the rest that met it (a box lies in several cells):
    // `covered` takes the fronts in any order, so they need no sort.
    let mut seen = vec![usize::MAX; layer.len()];
    let mut fronts: Vec<&Piece> = Vec::new();
    (0..list.len())
        .map(|k| {
            if blockers[k] == OPEN || !tries.worth_trying() {
                return false;
            }
            let outline = Outline::of(&list[k]);
            fronts.clear();
            grid.visit_all(&boxes[k], |e| {
                let (e, j) = (e as usize, layer[e as usize]);
                if seen[e] != k
                    && overlap(&boxes[j], &boxes[k])
                    && !outline.separated_from_with(screen, &list[j], outlines.get(e))
                {
                    fronts.push(&list[j]);
                }
                seen[e] = k;
            });
            !fronts.is_empty() && tries.record(covered(&list[k], &fronts))
        })
        .collect()
}

/// What a node does with its pieces.
enum Plan {
    /// Nothing can hide anything else: the pieces stay together.
    Bag,
    /// The pieces left open go first, the others behind them ([`front_layer`]); the entries are
    /// as `front_layer` leaves them.
    Layer(Vec<u32>),
    /// Partition by a splitter.
    Split(Splitter),
}

/// The node's plan: the front layer, unless the pieces are a crowd that a sampled splitter
/// divides; a splitter when no piece, or only a thin layer, may go first. `blockers`: see
/// [`OPEN`]. Adds its pair tests to `tests`.
fn plan(
    screen: &ScreenScene,
    list: &[Piece],
    boxes: &[[f64; 4]],
    mut blockers: Vec<u32>,
    tests: &mut usize,
) -> Plan {
    if list.len() == 1 {
        return Plan::Bag;
    }
    let depths: Vec<[f64; 2]> = list.iter().map(|p| depth::range(screen, p)).collect();
    let mut best = None;
    let given = blockers.clone();
    let most_pairs = LAYER_PAIRS_PER_PIECE * list.len();
    if !front_layer(
        screen,
        list,
        boxes,
        &depths,
        &mut blockers,
        most_pairs,
        tests,
    ) {
        // A crowd: split it if a splitter divides it, else find its layer whatever the cost.
        if pairwise_separated(screen, list, boxes, tests) {
            return Plan::Bag;
        }
        let (splitter, tally) = best_splitter(list, boxes);
        if tally.divides() {
            return Plan::Split(splitter);
        }
        best = Some(splitter);
        blockers = given;
        front_layer(
            screen,
            list,
            boxes,
            &depths,
            &mut blockers,
            usize::MAX,
            tests,
        );
    }
    let layer = blockers.iter().filter(|&&b| b == OPEN).count();
    if layer == list.len() {
        return Plan::Bag;
    }
    if THIN_LAYER * layer >= list.len() {
        Plan::Layer(blockers)
    } else {
        // None or a thin layer: peeling pieces a few at a time would take as many levels as
        // the stack is deep, each sweeping the rest (a splitter also cuts fewer pieces in
        // soups, where the layers are thin).
        Plan::Split(best.unwrap_or_else(|| best_splitter(list, boxes).0))
    }
}

/// The candidate splitter with the lowest cost on the sample.
fn best_splitter(list: &[Piece], boxes: &[[f64; 4]]) -> (Splitter, Tally) {
    let (cands, sample) = candidates(list, boxes);
    cands
        .into_iter()
        .map(|c| {
            let tally = Tally::of(&c, &sample);
            (c, tally)
        })
        .min_by_key(|(_, tally)| tally.cost())
        .expect("a list of pieces has a support plane")
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
        Self::build_reporting(screen, pieces, report, "painter order")
    }

    /// The visible pieces of some of a screen scene's pieces through their BSP
    /// ([`Self::build_from`], [`Self::into_visible_pieces`]), reporting stage "visible set" as
    /// the tree is built: what the `bsp` strategy and `auto` run per strip.
    pub fn visible_pieces_of(
        screen: &ScreenScene,
        pieces: Vec<Piece>,
        report: Option<Report>,
    ) -> (Vec<Piece>, BspStats) {
        Self::build_reporting(screen, pieces, report, "visible set").into_visible_pieces(screen)
    }

    /// [`Self::build_from`], reporting as stage `stage`.
    fn build_reporting(
        screen: &ScreenScene,
        pieces: Vec<Piece>,
        report: Option<Report>,
        stage: &'static str,
    ) -> Bsp {
        let mut ticker = Ticker::new(report, stage, pieces.len() as u64);
        // Pieces waiting in `work`: fragments placed + pending is every fragment known so far.
        let mut pending = pieces.len();
        let mut stats = BspStats {
            polygons: screen.polys.len(),
            pieces: pieces.len(),
            ..BspStats::default()
        };
        let mut nodes: Vec<Node> = Vec::new();
        // Tries of the rest of a front layer against it, on this tree's pieces.
        let mut covers = CoverTries::default();
        if pieces.is_empty() {
            ticker.finish();
            return Bsp { nodes, stats };
        }
        enum Link {
            Root,
            Neg(u32),
            Pos(u32),
        }
        // A list's blockers (see [`OPEN`]) are known after a layer; empty means all open.
        let mut work: Vec<(Link, usize, Vec<Piece>, Vec<u32>)> =
            vec![(Link::Root, 1, pieces, Vec::new())];
        while let Some((link, depth, list, mut blockers)) = work.pop() {
            let n = list.len();
            pending -= n;
            let boxes: Vec<[f64; 4]> = if n == 1 {
                Vec::new()
            } else {
                list.iter().map(bounds).collect()
            };
            if blockers.is_empty() {
                blockers = vec![OPEN; n];
            }
            let mut rest_blockers = Vec::new();
            let plan = plan(screen, &list, &boxes, blockers, &mut stats.pair_tests);
            let disjoint = !matches!(plan, Plan::Split(_));
            let (mut neg, mut on, mut pos) = match plan {
                // Nothing here can hide anything else: keep the pieces together, in input order.
                Plan::Bag => (Vec::new(), list, Vec::new()),
                // The front layer first, the rest behind it: no plane, no split. A piece of the
                // rest stays settled while the piece that may hide it is in the rest too.
                Plan::Layer(blockers) => {
                    // The rest's pieces wholly under the layer are hidden: they leave the tree.
                    let hidden = under_layer(screen, &list, &boxes, &blockers, &mut covers);
                    let kept = |k: usize| blockers[k] != OPEN && !hidden[k];
                    let mut index_in_rest = vec![OPEN; n];
                    let mut rest_count = 0;
                    for k in (0..n).filter(|&k| kept(k)) {
                        index_in_rest[k] = rest_count;
                        rest_count += 1;
                    }
                    // A piece whose blocker left is open again.
                    rest_blockers = (0..n)
                        .filter(|&k| kept(k))
                        .map(|k| index_in_rest[blockers[k] as usize])
                        .collect();
                    let (mut on, mut rest) = (Vec::new(), Vec::with_capacity(rest_count as usize));
                    for (k, p) in list.into_iter().enumerate() {
                        if blockers[k] == OPEN {
                            on.push(p);
                        } else if !hidden[k] {
                            rest.push(p);
                        }
                    }
                    (Vec::new(), on, rest)
                }
                Plan::Split(best) => {
                    let (neg, on, pos) = partition(&best, list);
                    if matches!(best, Splitter::Screen(_)) && (neg.len() >= n || pos.len() >= n) {
                        // The screen line did not separate anything: use the first support
                        // plane, which always removes at least its own piece.
                        let mut all = neg;
                        all.extend(pos);
                        let first = Splitter::Support(all[0].support.clone(), all[0].poly);
                        partition(&first, all)
                    } else {
                        (neg, on, pos)
                    }
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
                disjoint,
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
                work.push((
                    Link::Neg(index),
                    depth + 1,
                    std::mem::take(&mut neg),
                    Vec::new(),
                ));
            }
            if !pos.is_empty() {
                work.push((
                    Link::Pos(index),
                    depth + 1,
                    std::mem::take(&mut pos),
                    rest_blockers,
                ));
            }
            let placed = stats.fragments as u64;
            ticker.tick_of(placed, placed + pending as u64);
        }
        ticker.finish();
        stats.nodes = nodes.len();
        stats.covered = covers.hits;
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
    ///
    /// No occlusion cells: front to back, a hidden piece meets what hides it in the map at
    /// once, and the BSP strategy has dropped what the cells prove hidden before building the
    /// tree (`occlusion::unhidden_pieces`). Making cells again per strip cost more than
    /// they saved: 1M sphere file visible set 4.03 -> 3.61 s, same bytes, no scene slower.
    pub fn into_coverage(mut self, screen: &ScreenScene) -> Coverage<'_> {
        let order = self.walk_order();
        let nodes = &self.nodes;
        let pieces = order.iter().flat_map(|&n| &nodes[n as usize].on);
        let mut coverage = Coverage::with_occlusion(screen, pieces, false);
        for n in order {
            let node = &mut self.nodes[n as usize];
            let on = std::mem::take(&mut node.on);
            if node.disjoint {
                coverage.insert_disjoint(on);
            } else {
                on.into_iter().for_each(|p| coverage.insert_behind(p));
            }
        }
        coverage
    }

    /// The exact visible set: pieces front to back, each minus the visible pieces in front.
    pub fn visible_set(self, screen: &ScreenScene) -> (VisibleSet, BspStats) {
        let (pieces, stats) = self.into_visible_pieces(screen);
        (VisibleSet::of_pieces(pieces), stats)
    }

    /// The visible pieces ([`Self::into_coverage`]'s), with the tree's counters and the
    /// coverage pass's (visible pieces, pieces it proved covered).
    pub fn into_visible_pieces(self, screen: &ScreenScene) -> (Vec<Piece>, BspStats) {
        let mut stats = self.stats.clone();
        let coverage = self.into_coverage(screen);
        stats.covered += coverage.stats.covers.hits;
        let pieces = coverage.into_pieces();
        stats.visible_pieces = pieces.len();
        (pieces, stats)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::GridPoint;
    use crate::exact::polygon::separated_at_corners;
    use crate::visibility::screen_of_polygons;

    fn point([x, y, z]: [i64; 3]) -> GridPoint {
        GridPoint { x, y, z }
    }

    /// A parallelepiped seen obliquely, one quad per face: three faces in front, three behind.
    fn parallelepiped() -> ScreenScene {
        let (u, v, w) = ([40, 8, -12], [12, 44, 16], [16, -12, 48]);
        let corner = |i: i64, j: i64, k: i64| {
            point(std::array::from_fn(|a| {
                200 + i * u[a] + j * v[a] + k * w[a]
            }))
        };
        let mut faces = Vec::new();
        for side in 0..2 {
            faces.push([(0, 0), (1, 0), (1, 1), (0, 1)].map(|(j, k)| corner(side, j, k)));
            faces.push([(0, 0), (1, 0), (1, 1), (0, 1)].map(|(i, k)| corner(i, side, k)));
            faces.push([(0, 0), (1, 0), (1, 1), (0, 1)].map(|(i, j)| corner(i, j, side)));
        }
        screen_of_polygons(faces.into_iter().map(Vec::from))
    }

    /// The faces of a convex body: the front faces are one layer, with no split (no support
    /// plane of a convex body separates its faces, and screen lines would cut them), and the
    /// faces behind lie wholly under it ([`under_layer`]): they leave the tree uncut.
    #[test]
    fn a_convex_bodys_front_faces_are_a_layer_and_the_faces_behind_leave_uncut() {
        let screen = parallelepiped();
        let bsp = Bsp::build(&screen);
        assert_eq!((bsp.stats.pieces, bsp.stats.fragments), (6, 3));
        assert_eq!(bsp.stats.covered, 3);
        assert_eq!((bsp.stats.nodes, bsp.stats.depth), (1, 1));
        let (visible, _) = bsp.visible_set(&screen);
        let mut polys: Vec<u32> = visible.pieces.iter().map(|p| p.poly).collect();
        polys.sort();
        polys.dedup();
        assert_eq!(polys.len(), 3, "the three front faces, whole: {polys:?}");
    }

    /// A face behind a layer that covers it only in part (a hole in the layer above it) stays
    /// in the tree and shows through the hole; one under the whole layer leaves.
    #[test]
    fn a_face_behind_a_hole_in_the_layer_stays_in_the_tree() {
        // A 4 x 4 sheet of squares at depth 100 less the square at (1, 1); behind it at depth
        // 200, a small square under the hole and one under the sheet's last square.
        let mut faces: Vec<Vec<GridPoint>> = Vec::new();
        for j in 0..4 {
            for i in (0..4).filter(|&i| (i, j) != (1, 1)) {
                let (x, y) = (100 * i, 100 * j);
                faces.push(
                    [[x, y], [x + 100, y], [x + 100, y + 100], [x, y + 100]]
                        .map(|[x, y]| point([x, y, 100]))
                        .to_vec(),
                );
            }
        }
        for (x, y) in [(120, 120), (320, 320)] {
            faces.push(
                [[x, y], [x + 60, y], [x + 60, y + 60], [x, y + 60]]
                    .map(|[x, y]| point([x - 40, y - 40, 200]))
                    .to_vec(),
            );
        }
        let screen = screen_of_polygons(faces);
        let bsp = Bsp::build(&screen);
        assert_eq!(
            bsp.stats.covered, 1,
            "the square under the sheet's corner square"
        );
        let (visible, _) = bsp.visible_set(&screen);
        let behind: Vec<&Piece> = visible.pieces.iter().filter(|p| p.poly == 15).collect();
        assert!(
            !behind.is_empty(),
            "the square under the hole shows through it"
        );
        assert!(visible.pieces.iter().all(|p| p.poly != 16));
    }

    /// The corners' separation test is the lines' one, touching and shared corners included.
    #[test]
    fn separation_at_corners_is_separation_by_lines() {
        let mut seed = 7u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 33) % 7) as i64
        };
        let triangles: Vec<Vec<GridPoint>> = (0..300)
            .map(|k| (0..3).map(|_| point([next(), next(), k])).collect())
            .filter(|t: &Vec<GridPoint>| crate::exact::Plane::of_polygon(t).is_some())
            .collect();
        let screen = screen_of_polygons(triangles);
        let pieces = crate::visibility::initial_pieces(&screen);
        let (mut apart, mut pairs) = (0, 0);
        for p in &pieces {
            for q in &pieces {
                let by_lines = crate::exact::polygon::separated_by_lines(p, q);
                assert_eq!(separated_at_corners(p, q), Some(by_lines));
                pairs += 1;
                apart += usize::from(by_lines);
            }
        }
        assert!(
            apart > pairs / 10 && apart < pairs * 9 / 10,
            "{apart} of {pairs}"
        );
    }

    /// Inserting a node's front layer or bag as one disjoint group leaves the same map as
    /// inserting the tree's pieces front to back one by one, on a convex body (layers), a
    /// stack of overlapping squares (splits, coplanar pieces) and a soup of crossing triangles
    /// (splits, bags, cut pieces).
    #[test]
    fn disjoint_groups_cover_as_pieces_one_by_one_do() {
        let mut rng = crate::scene::primitives::SplitMix64(11);
        let mut next = |m: i64| (rng.next_u64() % m as u64) as i64;
        let soup: Vec<Vec<GridPoint>> = (0..120)
            .map(|_| {
                (0..3)
                    .map(|_| point([next(900), next(900), next(900)]))
                    .collect()
            })
            .filter(|t: &Vec<GridPoint>| crate::exact::Plane::of_polygon(t).is_some())
            .collect();
        // Two overlapping squares in each plane: the tie rule hides part of one.
        let stack = (0..80).map(|k| {
            let (z, dx) = (500 - 5 * (k / 2), 20 * (k % 2));
            [[k, 3 * k], [k + 80, k], [k + 80, k + 80], [k, k + 80]]
                .map(|[x, y]| point([x + dx, y, z]))
                .to_vec()
        });
        let mut groups = 0;
        for screen in [
            parallelepiped(),
            screen_of_polygons(stack),
            screen_of_polygons(soup),
        ] {
            let bsp = Bsp::build(&screen);
            groups += bsp
                .nodes
                .iter()
                .filter(|n| n.disjoint && n.on.len() > 1)
                .count();
            let grouped = bsp.into_coverage(&screen).into_pieces();
            let order = Bsp::build(&screen).into_front_to_back();
            let mut one_by_one = Coverage::new(&screen, &order);
            order.into_iter().for_each(|p| one_by_one.insert_behind(p));
            assert_eq!(grouped, one_by_one.into_pieces());
        }
        assert!(groups > 20, "{groups} groups of two pieces or more");
    }

    /// A cone seen from its apex: 256 slivers whose screen boxes all meet at the apex, every
    /// pair apart on screen by the corners they share, and the base behind them. The slivers
    /// are the front layer, found in one pass testing each pair once: only the base may be
    /// hidden, so it is no crowd, and it lies wholly under them. (Counting every box pair
    /// against the crowd budget gave up a quarter of the way, then tested them all again.)
    #[test]
    fn slivers_whose_boxes_all_overlap_are_a_layer_not_a_crowd() {
        let n = 256;
        let rim: Vec<GridPoint> = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                let r = 1_000_000.0;
                point([
                    (r * a.cos()).round() as i64,
                    (r * a.sin()).round() as i64,
                    3000,
                ])
            })
            .collect();
        let apex = point([0, 0, 1000]);
        let mut faces: Vec<Vec<GridPoint>> = (0..n)
            .map(|k| vec![apex, rim[k], rim[(k + 1) % n]])
            .collect();
        faces.push(rim.iter().rev().copied().collect());
        let screen = screen_of_polygons(faces);
        let bsp = Bsp::build(&screen);
        // The base lies wholly under the slivers: it leaves the tree.
        assert_eq!((bsp.stats.pieces, bsp.stats.fragments), (n + 1, n));
        assert_eq!(bsp.stats.covered, 1);
        assert_eq!((bsp.stats.nodes, bsp.stats.depth), (1, 1));
        assert_eq!(bsp.stats.pair_tests, (n + 1) * n / 2, "every pair once");
    }

    /// Parallel squares stacked in depth all overlap on screen: a crowd. A support plane in the
    /// middle of the stack divides it, so the tree halves it level by level (peeling at most
    /// [`THIN_LAYER`] squares one per level at the bottom) instead of peeling one square per
    /// level from the top, and still walks the squares front to back.
    #[test]
    fn a_crowd_that_a_plane_divides_is_split_not_peeled() {
        let squares = (0..400).map(|k| {
            let z = 5000 - 5 * k;
            [[k, k], [k + 800, k], [k + 800, k + 800], [k, k + 800]]
                .map(|[x, y]| point([x, y, z]))
                .to_vec()
        });
        let screen = screen_of_polygons(squares);
        let bsp = Bsp::build(&screen);
        assert_eq!((bsp.stats.pieces, bsp.stats.fragments), (400, 400));
        assert!(bsp.stats.depth <= 40, "depth {}", bsp.stats.depth);
        let mut depths = Vec::new();
        bsp.front_to_back(|p| depths.push(screen.corner(&screen.polys[p.poly as usize], 0).z));
        assert!(depths.is_sorted(), "front to back: {depths:?}");
    }
}
