//! Stroke order for a pen plotter: the pen lifts between strokes, so the order and direction of
//! the strokes decide how far it travels in the air.
//!
//! Invariants of [`plot_order`] and [`order_strokes`]:
//! - the strokes out are the strokes in, each exactly once, with the same visibility, kind,
//!   quantitative invisibility and points: an open stroke may be reversed, a closed one may
//!   start at another of its points (same cycle, same direction);
//! - the pen-up travel ([`pen_up_travel`]: from the origin (0, 0) to the first stroke, between
//!   strokes, and from the last stroke back to the origin) is never more than the input order's;
//! - the result depends only on the input (no hashing, no randomness, ties broken by index).
//!
//! How: greedy nearest neighbour (from the pen's position, the nearest free entry point: either
//! end of an open stroke, any point of a closed one, found in an R*-tree of the free entry
//! points, so a step costs O(log n)), then local search on the order, in passes until a pass
//! shortens the travel by less than [`MIN_PASS_GAIN`] of it, or [`MAX_PASSES`] passes ran:
//! - 2-opt restricted to a window: reversing a run of at most [`TWO_OPT_WINDOW`] consecutive
//!   strokes (each stroke in it turned around), `O(n · TWO_OPT_WINDOW)` per pass;
//! - Or-opt in a window: moving a run of one to [`OR_OPT_LEN`] strokes, possibly turned
//!   around, at most [`OR_OPT_WINDOW`] places earlier or later, `O(n · OR_OPT_WINDOW ·
//!   OR_OPT_LEN)` per pass;
//! - the start of each closed stroke moved to its point nearest its neighbours, `O(points)`.
//!
//! So the whole costs `O(n log n + MAX_PASSES · (n · W + points))`: linear in the drawing for
//! the local search (100,000 random strokes in about a second, most of it the greedy step: see
//! the ignored test `hundred_thousand_strokes_in_reasonable_time`). The window cannot undo a long jump of the
//! greedy tour; full 2-opt could, at O(n²) per pass.

use super::drawing::{LineDrawing, Stroke};
use rstar::RTree;
use rstar::primitives::GeomWithData;

/// The pen-up travel of an order, before and after [`plot_order`], in the drawing's units
/// (pixels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Travel {
    /// The input order's.
    pub before: f64,
    /// The order made.
    pub after: f64,
}

/// Passes of local search at most.
pub const MAX_PASSES: usize = 12;
/// Local search stops after a pass that shortened the travel by less than this fraction.
pub const MIN_PASS_GAIN: f64 = 1e-3;
/// The longest run of strokes a 2-opt move reverses.
pub const TWO_OPT_WINDOW: usize = 48;
/// The farthest an Or-opt move carries a run, in places.
pub const OR_OPT_WINDOW: usize = 24;
/// The longest run an Or-opt move carries.
pub const OR_OPT_LEN: usize = 3;

type Point = [f64; 2];

const ORIGIN: Point = [0.0, 0.0];

/// Euclidean distance (pixel coordinates never come near overflow, so no `hypot`, which is
/// several times slower).
fn dist(a: Point, b: Point) -> f64 {
    let (dx, dy) = (a[0] - b[0], a[1] - b[1]);
    (dx * dx + dy * dy).sqrt()
}

/// Where the pen enters and leaves a stroke drawn as it is stored (a closed stroke ends where
/// it starts); `None` for a stroke without points.
fn ends(s: &Stroke) -> Option<(Point, Point)> {
    let first = *s.points.first()?;
    let last = if s.closed { first } else { *s.points.last()? };
    Some((first, last))
}

/// The pen-up travel of drawing `strokes` in this order and direction, from the origin back to
/// the origin (strokes without points are skipped).
pub fn pen_up_travel(strokes: &[Stroke]) -> f64 {
    let mut pen = ORIGIN;
    let mut total = 0.0;
    for (a, b) in strokes.iter().filter_map(ends) {
        total += dist(pen, a);
        pen = b;
    }
    total + dist(pen, ORIGIN)
}

/// Orders a drawing's strokes for a plotter, keeping its groups: each maximal run of strokes of
/// one (visibility, kind) stays where it is (the drawing's order by visibility then kind; a
/// plotter may change pens between them) and is ordered within, the pen going on from where
/// the previous run ended and coming back to the origin after the last.
pub fn plot_order(drawing: &mut LineDrawing) -> Travel {
    let before = pen_up_travel(&drawing.strokes);
    let input = drawing.strokes.clone();
    let mut runs = Vec::new();
    let mut start = 0;
    for i in 1..=drawing.strokes.len() {
        let s = &drawing.strokes;
        if i == s.len() || (s[i].visibility, s[i].kind) != (s[start].visibility, s[start].kind) {
            runs.push(start..i);
            start = i;
        }
    }
    let mut pen = ORIGIN;
    let last = runs.len().saturating_sub(1);
    for (k, run) in runs.into_iter().enumerate() {
        let end = (k == last).then_some(ORIGIN);
        pen = order_path(&mut drawing.strokes[run], pen, end).unwrap_or(pen);
    }
    keep_the_better(&mut drawing.strokes, input, before)
}

/// Orders `strokes` as one tour for a plotter, from the origin back to the origin.
pub fn order_strokes(strokes: &mut [Stroke]) -> Travel {
    let before = pen_up_travel(strokes);
    let input = strokes.to_vec();
    order_path(strokes, ORIGIN, Some(ORIGIN));
    keep_the_better(strokes, input, before)
}

/// The travel of the new order, or the input back when rounding made the new one longer.
fn keep_the_better(strokes: &mut [Stroke], input: Vec<Stroke>, before: f64) -> Travel {
    let after = pen_up_travel(strokes);
    if after > before {
        strokes.clone_from_slice(&input);
        return Travel {
            before,
            after: before,
        };
    }
    Travel { before, after }
}

/// A stroke placed in the order: which stroke, turned around or not, starting where.
#[derive(Clone, Copy, Debug)]
struct Node {
    stroke: usize,
    /// Open strokes: drawn from the last point to the first.
    reversed: bool,
    /// Closed strokes: the point the pen enters at.
    start: usize,
    /// Where the pen enters.
    a: Point,
    /// Where it leaves.
    b: Point,
}

impl Node {
    fn turned(self) -> Node {
        Node {
            reversed: !self.reversed,
            a: self.b,
            b: self.a,
            ..self
        }
    }
}

/// Orders `strokes` (in place) as a path from `start` to `end` (`None`: the path may end
/// anywhere) and returns where the pen ends, `None` when no stroke has points.
fn order_path(strokes: &mut [Stroke], start: Point, end: Option<Point>) -> Option<Point> {
    let mut nodes = greedy(strokes, start);
    nodes.last()?;
    let mut tour = Tour {
        strokes,
        nodes: &mut nodes,
        start,
        end,
    };
    tour.improve();
    let finish = nodes.last().map(|n| n.b);
    apply(strokes, &nodes);
    finish
}

/// The greedy nearest-neighbour order from `start`.
fn greedy(strokes: &[Stroke], start: Point) -> Vec<Node> {
    // Entry points: (stroke, point index) for both ends of an open stroke, every point of a
    // closed one.
    let mut entries = Vec::new();
    for (i, s) in strokes.iter().enumerate() {
        let n = s.points.len();
        if n == 0 {
            continue;
        }
        if s.closed {
            entries.extend((0..n).map(|k| GeomWithData::new(s.points[k], (i, k))));
        } else {
            entries.push(GeomWithData::new(s.points[0], (i, 0)));
            if n > 1 {
                entries.push(GeomWithData::new(s.points[n - 1], (i, n - 1)));
            }
        }
    }
    let mut tree = RTree::bulk_load(entries);
    let mut nodes = Vec::with_capacity(strokes.len());
    let mut pen = start;
    loop {
        // The nearest entry; among equally near ones the smallest (stroke, point).
        let mut it = tree.nearest_neighbor_iter_with_distance_2(&pen);
        let Some((first, d2)) = it.next() else { break };
        let mut best = first.data;
        for (e, d) in it {
            if d != d2 {
                break;
            }
            best = best.min(e.data);
        }
        let (i, k) = best;
        let s = &strokes[i];
        let node = if s.closed {
            Node {
                stroke: i,
                reversed: false,
                start: k,
                a: s.points[k],
                b: s.points[k],
            }
        } else {
            let (a, b) = (s.points[0], s.points[s.points.len() - 1]);
            let forward = Node {
                stroke: i,
                reversed: false,
                start: 0,
                a,
                b,
            };
            if k == 0 { forward } else { forward.turned() }
        };
        // Take the stroke's entries out of the tree.
        let points: Vec<(Point, usize)> = if s.closed {
            s.points.iter().copied().zip(0..).collect()
        } else {
            let n = s.points.len();
            let mut v = vec![(s.points[0], 0)];
            if n > 1 {
                v.push((s.points[n - 1], n - 1));
            }
            v
        };
        for (p, k) in points {
            tree.remove(&GeomWithData::new(p, (i, k)));
        }
        pen = node.b;
        nodes.push(node);
    }
    nodes
}

/// Rewrites `strokes` in the order and direction of `nodes` (one node per stroke with points;
/// strokes without points go last, in their order).
fn apply(strokes: &mut [Stroke], nodes: &[Node]) {
    let mut used = vec![false; strokes.len()];
    let mut out = Vec::with_capacity(strokes.len());
    for n in nodes {
        used[n.stroke] = true;
        let mut s = strokes[n.stroke].clone();
        if s.closed {
            s.points.rotate_left(n.start);
        } else if n.reversed {
            s.points.reverse();
        }
        out.push(s);
    }
    out.extend(
        strokes
            .iter()
            .zip(&used)
            .filter(|(_, u)| !**u)
            .map(|(s, _)| s.clone()),
    );
    strokes.clone_from_slice(&out);
}

/// The local search's state: the order, and the path's fixed ends.
struct Tour<'a> {
    strokes: &'a [Stroke],
    nodes: &'a mut Vec<Node>,
    start: Point,
    end: Option<Point>,
}

/// A gain smaller than this fraction of the travel is no gain: it keeps rounding from making
/// moves that undo each other.
const MIN_GAIN: f64 = 1e-12;

impl Tour<'_> {
    /// Where the pen is before node `i` (the start for `i == 0`).
    fn exit_before(&self, i: usize) -> Point {
        if i == 0 {
            self.start
        } else {
            self.nodes[i - 1].b
        }
    }

    /// The cost from `p` to the entry of node `i` (to the end, or nothing when the end is
    /// free, for `i == len`).
    fn to_entry(&self, p: Point, i: usize) -> f64 {
        match self.nodes.get(i) {
            Some(n) => dist(p, n.a),
            None => self.end.map_or(0.0, |e| dist(p, e)),
        }
    }

    fn travel(&self) -> f64 {
        let mut pen = self.start;
        let mut total = 0.0;
        for n in self.nodes.iter() {
            total += dist(pen, n.a);
            pen = n.b;
        }
        total + self.to_entry(pen, self.nodes.len())
    }

    fn improve(&mut self) {
        for _ in 0..MAX_PASSES {
            let before = self.travel();
            let threshold = before * MIN_GAIN;
            let mut gained = self.two_opt(threshold);
            gained |= self.or_opt(threshold);
            gained |= self.rotate_closed(threshold);
            if !gained || before - self.travel() < before * MIN_PASS_GAIN {
                break;
            }
        }
    }

    /// Windowed 2-opt: reverse nodes `i..=j` (each turned around) when that shortens the path.
    fn two_opt(&mut self, threshold: f64) -> bool {
        let n = self.nodes.len();
        let mut gained = false;
        for i in 0..n {
            for j in i..n.min(i + TWO_OPT_WINDOW) {
                let p = self.exit_before(i);
                let (ai, bj) = (self.nodes[i].a, self.nodes[j].b);
                let old = dist(p, ai) + self.to_entry(bj, j + 1);
                let new = dist(p, bj) + self.to_entry(ai, j + 1);
                if old - new > threshold {
                    self.nodes[i..=j].reverse();
                    for node in &mut self.nodes[i..=j] {
                        *node = node.turned();
                    }
                    gained = true;
                }
            }
        }
        gained
    }

    /// Windowed Or-opt: move a run of `len` nodes from `i` to another place nearby, either way
    /// round, when that shortens the path.
    fn or_opt(&mut self, threshold: f64) -> bool {
        let mut gained = false;
        for len in 1..=OR_OPT_LEN {
            let mut i = 0;
            while i + len <= self.nodes.len() {
                gained |= self.move_run(i, len, threshold);
                i += 1;
            }
        }
        gained
    }

    /// Tries the best move of the run `i..i + len`; true when one was made.
    fn move_run(&mut self, i: usize, len: usize, threshold: f64) -> bool {
        let n = self.nodes.len();
        let (first, last) = (self.nodes[i], self.nodes[i + len - 1]);
        let before = self.exit_before(i);
        // Cutting the run out joins its neighbours.
        let removed =
            dist(before, first.a) + self.to_entry(last.b, i + len) - self.to_entry(before, i + len);
        let mut best: Option<(f64, usize, bool)> = None;
        // Insert between the pen position q (exit of node g - 1, or the start) and node g, for
        // g outside the run: g in [i - W, i) or (i + len, i + len + W].
        let lo = i.saturating_sub(OR_OPT_WINDOW);
        let hi = (i + len + OR_OPT_WINDOW).min(n);
        for g in (lo..i).chain(i + len + 1..=hi) {
            let q = self.exit_before(g);
            let next = |p: Point| self.to_entry(p, g);
            let base = next(q);
            for turned in [false, true] {
                let (a, b) = if turned {
                    (last.b, first.a)
                } else {
                    (first.a, last.b)
                };
                let added = dist(q, a) + next(b) - base;
                let gain = removed - added;
                if gain > threshold && best.is_none_or(|(g0, _, _)| gain > g0) {
                    best = Some((gain, g, turned));
                }
            }
        }
        let Some((_, g, turned)) = best else {
            return false;
        };
        // Rotating the slice between the two places moves the run in O(window).
        let at = if g > i {
            self.nodes[i..g].rotate_left(len);
            g - len
        } else {
            self.nodes[g..i + len].rotate_right(len);
            g
        };
        if turned {
            let run = &mut self.nodes[at..at + len];
            run.reverse();
            for node in run {
                *node = node.turned();
            }
        }
        true
    }

    /// Moves the entry of every closed stroke to its point nearest the strokes around it.
    fn rotate_closed(&mut self, threshold: f64) -> bool {
        let mut gained = false;
        for i in 0..self.nodes.len() {
            let node = self.nodes[i];
            let s = &self.strokes[node.stroke];
            if !s.closed {
                continue;
            }
            let before = self.exit_before(i);
            let cost = |p: Point| dist(before, p) + self.to_entry(p, i + 1);
            let mut best = (cost(node.a), node.start);
            for (k, &p) in s.points.iter().enumerate() {
                let c = cost(p);
                if c < best.0 - threshold {
                    best = (c, k);
                }
            }
            if best.1 != node.start {
                let p = s.points[best.1];
                self.nodes[i] = Node {
                    start: best.1,
                    a: p,
                    b: p,
                    ..node
                };
                gained = true;
            }
        }
        gained
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lines::drawing::{LineKind, Visibility};

    fn open(points: &[Point]) -> Stroke {
        Stroke {
            visibility: Visibility::Visible,
            kind: LineKind::Crease,
            qi: 0,
            points: points.to_vec(),
            closed: false,
        }
    }

    fn closed(points: &[Point]) -> Stroke {
        Stroke {
            closed: true,
            ..open(points)
        }
    }

    /// A small deterministic generator (xorshift), so the tests need no crate.
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn point(&mut self, size: f64) -> Point {
            [self.next() * size, self.next() * size]
        }
    }

    fn random_strokes(n: usize, seed: u64) -> Vec<Stroke> {
        let mut rng = Rng(seed);
        (0..n)
            .map(|k| {
                let p = rng.point(1000.0);
                let q = [p[0] + rng.next() * 40.0, p[1] + rng.next() * 40.0];
                match k % 5 {
                    0 => closed(&[p, [q[0], p[1]], q, [p[0], q[1]]]),
                    1 => open(&[p, [q[0], p[1]], q]),
                    _ => open(&[p, q]),
                }
            })
            .collect()
    }

    /// A stroke's shape whatever its direction (open) or start (closed), to compare sets.
    fn canonical(s: &Stroke) -> (bool, Vec<[u64; 2]>) {
        let bits = |p: &Point| [p[0].to_bits(), p[1].to_bits()];
        let pts: Vec<[u64; 2]> = s.points.iter().map(bits).collect();
        let form = if s.closed {
            (0..pts.len())
                .map(|k| {
                    let mut r = pts.clone();
                    r.rotate_left(k);
                    r
                })
                .min()
                .unwrap()
        } else {
            let mut r = pts.clone();
            r.reverse();
            pts.min(r)
        };
        (s.closed, form)
    }

    fn sorted_shapes(strokes: &[Stroke]) -> Vec<(bool, Vec<[u64; 2]>)> {
        let mut v: Vec<_> = strokes.iter().map(canonical).collect();
        v.sort();
        v
    }

    #[test]
    fn travel_never_increases_and_every_stroke_is_kept() {
        for seed in 1..40u64 {
            let n = 1 + (seed as usize * 7) % 60;
            let input = random_strokes(n, seed);
            let mut strokes = input.clone();
            let t = order_strokes(&mut strokes);
            assert_eq!(t.before, pen_up_travel(&input));
            assert_eq!(t.after, pen_up_travel(&strokes));
            assert!(t.after <= t.before, "seed {seed}: {t:?}");
            assert_eq!(
                sorted_shapes(&strokes),
                sorted_shapes(&input),
                "seed {seed}"
            );
            // A closed stroke keeps its direction: only its start moves.
            for s in strokes.iter().filter(|s| s.closed) {
                let k = input.iter().find(|t| canonical(t) == canonical(s)).unwrap();
                let start = k.points.iter().position(|p| *p == s.points[0]).unwrap();
                let mut r = k.points.clone();
                r.rotate_left(start);
                assert_eq!(r, s.points);
            }
        }
    }

    /// An order already optimal stays optimal.
    #[test]
    fn the_known_optimum_is_kept() {
        // Four segments along x, drawn left to right: the pen goes 0 -> 1, 2 -> 3, 4 -> 5,
        // 6 -> 7 and 8 -> 0, 12 in all, the least any order can do (it must reach x = 8 and
        // come back, 16, of which the strokes draw 4).
        let input: Vec<Stroke> = (0..4)
            .map(|k| open(&[[1.0 + 2.0 * k as f64, 0.0], [2.0 + 2.0 * k as f64, 0.0]]))
            .collect();
        let mut strokes = input.clone();
        let t = order_strokes(&mut strokes);
        assert_eq!(
            t,
            Travel {
                before: 12.0,
                after: 12.0
            }
        );
    }

    /// A scrambled, wrongly directed input of the case above reaches its optimum, 12.
    #[test]
    fn a_scrambled_line_of_segments_reaches_the_known_optimum() {
        let seg = |k: f64, rev: bool| {
            let (a, b) = ([1.0 + 2.0 * k, 0.0], [2.0 + 2.0 * k, 0.0]);
            if rev { open(&[b, a]) } else { open(&[a, b]) }
        };
        let input = vec![
            seg(3.0, false),
            seg(1.0, true),
            seg(2.0, false),
            seg(0.0, true),
        ];
        let mut strokes = input.clone();
        let t = order_strokes(&mut strokes);
        // 0 -> 7, 8 -> 4, 3 -> 5, 6 -> 2, 1 -> 0.
        assert_eq!(t.before, 7.0 + 4.0 + 2.0 + 4.0 + 1.0);
        assert_eq!(t.after, 12.0);
    }

    /// The local search finds what greedy misses: from the origin greedy takes the near
    /// square first and leaves the far one for a long trip back; the path through both with one
    /// return is shorter. Checked against every order and start by brute force.
    #[test]
    fn local_search_matches_brute_force_on_small_cases() {
        for seed in 1..25u64 {
            let input = random_strokes(5, seed);
            let mut strokes = input.clone();
            let t = order_strokes(&mut strokes);
            let best = brute_force(&input);
            assert!(
                t.after <= best * 1.15 + 1e-9,
                "seed {seed}: {} vs {best}",
                t.after
            );
        }
    }

    /// The least travel over every order, direction and start of `strokes` (few of them).
    fn brute_force(strokes: &[Stroke]) -> f64 {
        fn go(strokes: &[Stroke], used: &mut Vec<bool>, pen: Point, so_far: f64, best: &mut f64) {
            if so_far >= *best {
                return;
            }
            if used.iter().all(|u| *u) {
                *best = best.min(so_far + dist(pen, ORIGIN));
                return;
            }
            for i in 0..strokes.len() {
                if used[i] {
                    continue;
                }
                used[i] = true;
                let s = &strokes[i];
                let choices: Vec<(Point, Point)> = if s.closed {
                    s.points.iter().map(|&p| (p, p)).collect()
                } else {
                    let (a, b) = (s.points[0], *s.points.last().unwrap());
                    vec![(a, b), (b, a)]
                };
                for (a, b) in choices {
                    go(strokes, used, b, so_far + dist(pen, a), best);
                }
                used[i] = false;
            }
        }
        let mut best = f64::INFINITY;
        go(
            strokes,
            &mut vec![false; strokes.len()],
            ORIGIN,
            0.0,
            &mut best,
        );
        best
    }

    #[test]
    fn ordering_is_deterministic() {
        let input = random_strokes(500, 7);
        let (mut a, mut b) = (input.clone(), input);
        assert_eq!(order_strokes(&mut a), order_strokes(&mut b));
        assert_eq!(a, b);
    }

    /// A drawing keeps its (visibility, kind) groups in place; the travel runs through them.
    #[test]
    fn a_drawing_keeps_its_groups() {
        let mut strokes = random_strokes(60, 3);
        for (k, s) in strokes.iter_mut().enumerate() {
            s.visibility = if k < 30 {
                Visibility::Visible
            } else {
                Visibility::Hidden
            };
            s.kind = if k % 30 < 10 {
                LineKind::Silhouette
            } else {
                LineKind::Crease
            };
        }
        strokes.sort_by_key(|s| (s.visibility, s.kind));
        let mut drawing = LineDrawing {
            width: 1000,
            height: 1000,
            strokes: strokes.clone(),
        };
        let t = plot_order(&mut drawing);
        assert!(t.after < t.before, "{t:?}");
        assert_eq!(t.after, pen_up_travel(&drawing.strokes));
        let groups = |v: &[Stroke]| v.iter().map(|s| (s.visibility, s.kind)).collect::<Vec<_>>();
        assert_eq!(groups(&drawing.strokes), groups(&strokes));
        for (lo, hi) in [(0, 10), (10, 30), (30, 40), (40, 60)] {
            assert_eq!(
                sorted_shapes(&drawing.strokes[lo..hi]),
                sorted_shapes(&strokes[lo..hi])
            );
        }
    }

    #[test]
    fn empty_and_pointless_inputs_are_left_alone() {
        let mut none: Vec<Stroke> = Vec::new();
        assert_eq!(
            order_strokes(&mut none),
            Travel {
                before: 0.0,
                after: 0.0
            }
        );
        let mut drawing = LineDrawing::default();
        assert_eq!(plot_order(&mut drawing).after, 0.0);
    }

    /// `cargo test --release --lib hundred_thousand -- --ignored --nocapture`: the time and
    /// the travel on 100,000 random strokes.
    #[test]
    #[ignore]
    fn hundred_thousand_strokes_in_reasonable_time() {
        let mut strokes = random_strokes(100_000, 11);
        let t0 = std::time::Instant::now();
        let t = order_strokes(&mut strokes);
        let secs = t0.elapsed().as_secs_f64();
        println!(
            "100000 strokes: {secs:.2} s, travel {:.0} -> {:.0} px ({:.1}x shorter)",
            t.before,
            t.after,
            t.before / t.after
        );
        assert!(secs < 10.0);
    }
}
