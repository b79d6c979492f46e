//! Strokes from segments: segments of one label (visibility and kind) are chained into maximal
//! polylines through the points where they meet, with as few strokes as the graph allows.
//!
//! Invariants:
//! - **Vertices** are output points: two segment ends meet when their pixel coordinates are
//!   the same bits. Equal exact points always are (each coordinate is correctly rounded from
//!   the exact point); two distinct exact points that round to the same bits are drawn at the
//!   same place anyway.
//! - **Coverage**: every segment is in exactly one stroke, once, in one direction or the other.
//! - **Minimum**: per label, each connected component of the graph gives exactly
//!   max(1, odd / 2) strokes, `odd` its number of vertices of odd degree: the least number of
//!   pen strokes that draw it ([`minimum_strokes`]).
//! - **Pairing rule at junctions**: at a vertex where several segments meet, the pairs that
//!   continue each other are chosen greedily by straightness (the pair that turns least first,
//!   ties by segment order); at an odd vertex the segment left over ends a stroke there. Where
//!   that makes closed loops inside a component that also has other strokes, each loop is
//!   spliced into a stroke through one of its vertices (the first in stroke order), which is
//!   what brings the count down to the minimum.
//! - **Deterministic**: the result depends only on the segments and their order.

use super::drawing::Stroke;
use super::tracks::{Label, Segment};
use rustc_hash::FxHashMap as HashMap;
use std::collections::BTreeMap;

/// Vertex ids of segment ends (by output bits) and, per label, the segments as vertex pairs.
struct Graph {
    points: Vec<[f64; 2]>,
    by_label: BTreeMap<Label, Vec<[u32; 2]>>,
}

fn graph(segments: &[Segment]) -> Graph {
    let mut ids: HashMap<[u64; 2], u32> = HashMap::default();
    let mut points = Vec::new();
    let mut id = |p: [f64; 2]| {
        // -0 and 0 are one point.
        let bits = p.map(|v| if v == 0.0 { 0 } else { v.to_bits() });
        *ids.entry(bits).or_insert_with(|| {
            points.push(p);
            (points.len() - 1) as u32
        })
    };
    let mut by_label: BTreeMap<Label, Vec<[u32; 2]>> = BTreeMap::new();
    for s in segments {
        let (a, b) = (id(s.ends[0]), id(s.ends[1]));
        if a != b {
            by_label.entry(s.label).or_default().push([a, b]);
        }
    }
    Graph { points, by_label }
}

/// The strokes of `segments`, ordered by label, then as chained.
pub fn strokes(segments: &[Segment]) -> Vec<Stroke> {
    strokes_of(&graph(segments))
}

/// The least number of strokes that draw `segments` (see the module docs), per label summed.
pub fn minimum_strokes(segments: &[Segment]) -> usize {
    minimum_of(&graph(segments))
}

/// [`strokes`] and [`minimum_strokes`] from one graph.
pub fn strokes_and_minimum(segments: &[Segment]) -> (Vec<Stroke>, usize) {
    let g = graph(segments);
    (strokes_of(&g), minimum_of(&g))
}

fn strokes_of(g: &Graph) -> Vec<Stroke> {
    let mut out = Vec::new();
    for (label, edges) in &g.by_label {
        for (ids, closed) in chain(&g.points, edges) {
            out.push(Stroke {
                visibility: label.visibility,
                kind: label.kind,
                qi: label.qi,
                points: ids.iter().map(|&v| g.points[v as usize]).collect(),
                closed,
            });
        }
    }
    out
}

fn minimum_of(g: &Graph) -> usize {
    g.by_label
        .values()
        .map(|edges| {
            let mut uf = UnionFind::new(g.points.len());
            let mut degree = vec![0u32; g.points.len()];
            for &[a, b] in edges {
                uf.union(a as usize, b as usize);
                degree[a as usize] += 1;
                degree[b as usize] += 1;
            }
            let mut odd: HashMap<usize, usize> = HashMap::default();
            for &[a, b] in edges {
                for v in [a, b] {
                    let root = uf.find(v as usize);
                    odd.entry(root).or_insert(0);
                }
            }
            for (v, &d) in degree.iter().enumerate() {
                if d % 2 == 1 {
                    *odd.get_mut(&uf.find(v)).expect("an edge's end") += 1;
                }
            }
            odd.values().map(|&o| (o / 2).max(1)).sum::<usize>()
        })
        .sum()
}

/// Chains the edges of one label: polylines of vertex ids, and whether each is closed.
fn chain(points: &[[f64; 2]], edges: &[[u32; 2]]) -> Vec<(Vec<u32>, bool)> {
    // Incident edges per vertex, in edge order.
    let mut incident: HashMap<u32, Vec<usize>> = HashMap::default();
    let mut order: Vec<u32> = Vec::new();
    for (e, &[a, b]) in edges.iter().enumerate() {
        for v in [a, b] {
            incident
                .entry(v)
                .or_insert_with(|| {
                    order.push(v);
                    Vec::new()
                })
                .push(e);
        }
    }
    // partner[(e, end)]: the edge continuing e through its end `end` (0: a, 1: b).
    let mut partner: HashMap<(usize, usize), (usize, usize)> = HashMap::default();
    for &v in &order {
        let inc = &incident[&v];
        let ends: Vec<(usize, usize)> = inc
            .iter()
            .flat_map(|&e| {
                // A loop edge (a == b) cannot happen: ends are distinct.
                let end = if edges[e][0] == v { 0 } else { 1 };
                [(e, end)]
            })
            .collect();
        for (x, y) in pair_straightest(points, edges, v, &ends) {
            partner.insert(x, y);
            partner.insert(y, x);
        }
    }
    let mut used = vec![false; edges.len()];
    let mut strokes: Vec<(Vec<u32>, bool)> = Vec::new();
    // Walk from edge e leaving through end `from_end`'s opposite: returns the vertices.
    let walk = |start: usize, start_end: usize, used: &mut Vec<bool>| -> (Vec<u32>, bool) {
        // Leave edge `start` at the vertex of `start_end`, travelling away from it.
        let mut path = vec![edges[start][start_end]];
        let (mut e, mut enter) = (start, start_end);
        loop {
            used[e] = true;
            let exit = 1 - enter;
            path.push(edges[e][exit]);
            match partner.get(&(e, exit)) {
                Some(&(next, next_end)) if !used[next] => {
                    e = next;
                    enter = next_end;
                }
                Some(&(next, _)) if next == start => {
                    path.pop();
                    return (path, true);
                }
                _ => return (path, false),
            }
        }
    };
    // Open strokes start at unpaired ends.
    for &v in &order {
        for &e in &incident[&v] {
            let end = if edges[e][0] == v { 0 } else { 1 };
            if !used[e] && !partner.contains_key(&(e, end)) {
                strokes.push(walk(e, end, &mut used));
            }
        }
    }
    // What is left are loops.
    for e in 0..edges.len() {
        if !used[e] {
            strokes.push(walk(e, 0, &mut used));
        }
    }
    splice_loops(strokes)
}

/// Pairs the ends meeting at `v` by straightness: the pair whose directions away from `v` are
/// the most opposite first.
fn pair_straightest(
    points: &[[f64; 2]],
    edges: &[[u32; 2]],
    v: u32,
    ends: &[(usize, usize)],
) -> Vec<((usize, usize), (usize, usize))> {
    if ends.len() == 2 {
        return vec![(ends[0], ends[1])];
    }
    if ends.len() < 2 {
        return Vec::new();
    }
    let at = points[v as usize];
    let dir = |&(e, end): &(usize, usize)| {
        let other = points[edges[e][1 - end] as usize];
        let (dx, dy) = (other[0] - at[0], other[1] - at[1]);
        let l = dx.hypot(dy);
        [dx / l, dy / l]
    };
    let dirs: Vec<[f64; 2]> = ends.iter().map(dir).collect();
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for i in 0..ends.len() {
        for j in i + 1..ends.len() {
            // cos of the angle between the two directions: -1 is straight on.
            let c = dirs[i][0] * dirs[j][0] + dirs[i][1] * dirs[j][1];
            pairs.push((c, i, j));
        }
    }
    pairs.sort_by(|x, y| x.0.total_cmp(&y.0).then((x.1, x.2).cmp(&(y.1, y.2))));
    let mut taken = vec![false; ends.len()];
    let mut out = Vec::new();
    for (_, i, j) in pairs {
        if !taken[i] && !taken[j] {
            taken[i] = true;
            taken[j] = true;
            out.push((ends[i], ends[j]));
        }
    }
    out
}

/// Splices every closed stroke into another stroke it shares a vertex with, until no closed
/// stroke shares a vertex with any other stroke.
fn splice_loops(mut strokes: Vec<(Vec<u32>, bool)>) -> Vec<(Vec<u32>, bool)> {
    let mut alive = vec![true; strokes.len()];
    // The strokes through each vertex, in stroke order.
    let mut through: HashMap<u32, Vec<usize>> = HashMap::default();
    for (s, (path, _)) in strokes.iter().enumerate() {
        for &v in path {
            let list = through.entry(v).or_default();
            if list.last() != Some(&s) {
                list.push(s);
            }
        }
    }
    let mut changed = true;
    while changed {
        changed = false;
        for c in 0..strokes.len() {
            if !alive[c] || !strokes[c].1 {
                continue;
            }
            // The first vertex of the loop that another live stroke passes through.
            let found = strokes[c].0.iter().enumerate().find_map(|(i, v)| {
                through[v]
                    .iter()
                    .find(|&&s| s != c && alive[s])
                    .map(|&s| (i, *v, s))
            });
            let Some((i, v, s)) = found else { continue };
            let (loop_path, _) = std::mem::take(&mut strokes[c]);
            alive[c] = false;
            // The loop from v around back to v.
            let mut detour: Vec<u32> = loop_path[i..]
                .iter()
                .chain(&loop_path[..i])
                .copied()
                .collect();
            detour.push(v);
            let target = &mut strokes[s].0;
            let at = target
                .iter()
                .position(|&u| u == v)
                .expect("s passes through v");
            // target[..=at] then the loop after v then target[at + 1..].
            let tail = target.split_off(at + 1);
            target.extend_from_slice(&detour[1..]);
            target.extend(tail);
            for &u in &loop_path {
                let list = through.get_mut(&u).expect("listed");
                if !list.contains(&s) {
                    list.push(s);
                }
            }
            changed = true;
        }
    }
    strokes
        .into_iter()
        .zip(alive)
        .filter_map(|(s, a)| a.then_some(s))
        .collect()
}

/// Disjoint sets of vertices.
struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n).collect(),
        }
    }

    fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra.max(rb)] = ra.min(rb);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lines::along::At;
    use crate::lines::{LineKind, Visibility};

    fn seg(a: [f64; 2], b: [f64; 2]) -> Segment {
        Segment {
            label: Label {
                visibility: Visibility::Visible,
                kind: LineKind::Silhouette,
                qi: 0,
            },
            track: 0,
            at: [At::Grid([0, 0]), At::Grid([0, 0])],
            ends: [a, b],
        }
    }

    fn covered(strokes: &[Stroke]) -> Vec<[[u64; 2]; 2]> {
        let key = |p: [f64; 2]| p.map(f64::to_bits);
        let mut out = Vec::new();
        for s in strokes {
            let n = s.points.len();
            let m = if s.closed { n } else { n - 1 };
            for i in 0..m {
                let (a, b) = (key(s.points[i]), key(s.points[(i + 1) % n]));
                out.push(if a < b { [a, b] } else { [b, a] });
            }
        }
        out.sort();
        out
    }

    fn check(segments: &[Segment]) -> Vec<Stroke> {
        let strokes = strokes(segments);
        let mut want: Vec<[[u64; 2]; 2]> = segments
            .iter()
            .map(|s| {
                let (a, b) = (s.ends[0].map(f64::to_bits), s.ends[1].map(f64::to_bits));
                if a < b { [a, b] } else { [b, a] }
            })
            .collect();
        want.sort();
        assert_eq!(covered(&strokes), want, "every segment exactly once");
        assert_eq!(strokes.len(), minimum_strokes(segments));
        strokes
    }

    #[test]
    fn a_square_in_shuffled_pieces_is_one_closed_stroke() {
        let s = check(&[
            seg([1.0, 0.0], [1.0, 1.0]),
            seg([0.0, 0.0], [1.0, 0.0]),
            seg([0.0, 1.0], [0.0, 0.0]),
            seg([1.0, 1.0], [0.0, 1.0]),
        ]);
        assert_eq!(s.len(), 1);
        assert!(s[0].closed);
        assert_eq!(s[0].points.len(), 4);
    }

    #[test]
    fn a_cross_goes_straight_through_its_centre() {
        let c = [0.0, 0.0];
        let s = check(&[
            seg(c, [1.0, 0.0]),
            seg(c, [0.0, 1.0]),
            seg([-1.0, 0.0], c),
            seg([0.0, -1.0], c),
        ]);
        assert_eq!(s.len(), 2);
        for stroke in &s {
            let [a, b] = [stroke.points[0], stroke.points[2]];
            assert!(a[0] == -b[0] && a[1] == -b[1], "straight on: {stroke:?}");
        }
    }

    #[test]
    fn a_figure_eight_and_a_loop_touching_a_path_reach_the_minimum() {
        // Two squares sharing a corner: all degrees even, one stroke.
        let s = check(&[
            seg([0.0, 0.0], [1.0, 0.0]),
            seg([1.0, 0.0], [1.0, 1.0]),
            seg([1.0, 1.0], [0.0, 1.0]),
            seg([0.0, 1.0], [0.0, 0.0]),
            seg([1.0, 1.0], [2.0, 1.0]),
            seg([2.0, 1.0], [2.0, 2.0]),
            seg([2.0, 2.0], [1.0, 2.0]),
            seg([1.0, 2.0], [1.0, 1.0]),
        ]);
        assert_eq!(s.len(), 1);
        // A square with a tail: two odd vertices, one open stroke.
        let s = check(&[
            seg([0.0, 0.0], [1.0, 0.0]),
            seg([1.0, 0.0], [1.0, 1.0]),
            seg([1.0, 1.0], [0.0, 1.0]),
            seg([0.0, 1.0], [0.0, 0.0]),
            seg([1.0, 1.0], [3.0, 3.0]),
        ]);
        assert_eq!(s.len(), 1);
        assert!(!s[0].closed);
    }

    #[test]
    fn labels_are_chained_apart() {
        let mut hidden = seg([1.0, 0.0], [2.0, 0.0]);
        hidden.label.visibility = Visibility::Hidden;
        let s = check(&[seg([0.0, 0.0], [1.0, 0.0]), hidden]);
        assert_eq!(s.len(), 2);
        assert_eq!(s[0].visibility, Visibility::Visible);
    }
}
