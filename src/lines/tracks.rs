//! Where each line is seen, read off the exact visible set, and the drawn segments that follow.
//!
//! A [`Track`] is one line to draw (a feature edge, or a segment where two faces meet) on its
//! [`Carrier`]: its extent, and the spans along it where it is seen. The rule, exact and
//! independent of how the visible set was cut into pieces:
//! - a face edge is **visible** where a visible piece of one of its own faces has a side along
//!   it: the face is seen right beside the edge, so nothing lies in front of the edge there (its
//!   own faces never hide it, and a face passing exactly through it is not in front);
//! - an intersection of faces a and b is visible where a piece of a lies along it on one side
//!   and a piece of b on the other;
//! - everywhere else on its extent a line is **hidden**.
//!
//! A piece side names its line by its [`Boundary`]; a side along a line of another polygon (an
//! occluder's outline that a piece inherited) is checked exactly against the piece's own edges,
//! so a coincidence of lines is never missed.
//!
//! Tracks on the same screen line (a back edge projecting onto a front one, the coincident
//! edges of an orthographic view) are resolved together ([`segments`]): at every point of the
//! line, the first of the lines there in the order (visible before hidden, then the kind's
//! precedence) is drawn, once. That is the drafting rule that a visible line hides a hidden
//! line behind it.

use super::along::{At, Carrier, Param};
use super::drawing::{LineKind, Visibility};
use crate::exact::polygon::{Boundary, Piece};
use crate::exact::predicates::Line;
use crate::exact::{GRID_MAX, GridPoint, Plane, Samples};
use crate::project::ScreenScene;
use std::cmp::Ordering;
use std::collections::HashMap;

/// One line to draw.
#[derive(Clone, Debug)]
pub struct Track {
    /// The line it lies on.
    pub carrier: Carrier,
    /// What it is.
    pub kind: LineKind,
    /// Where it exists on screen.
    pub extent: Vec<(At, At)>,
    /// Where it is seen beside its faces: `seen[0]` for an edge (any of its faces); for an
    /// intersection, `seen[0]` beside its first polygon and `seen[1]` beside its second.
    pub seen: [Vec<(At, At)>; 2],
    /// An intersection: seen only where both of its polygons lie along it.
    pub needs_both: bool,
}

impl Track {
    /// A track with nothing seen yet.
    pub fn new(line: Line, kind: LineKind, extent: Vec<(At, At)>, needs_both: bool) -> Track {
        Track {
            carrier: Carrier::new(line),
            kind,
            extent,
            seen: [Vec::new(), Vec::new()],
            needs_both,
        }
    }
}

/// Which track each piece side belongs to.
pub struct TrackIndex<'a> {
    /// Per screen side (`ScreenScene::points` index): the track of the face edge it lies on, or
    /// `u32::MAX`.
    pub of_side: &'a [u32],
    /// The track of the intersection of polygons (a, b), a < b.
    pub of_cut: &'a HashMap<(u32, u32), u32>,
}

/// Vertex k of `piece` as a point of the line of its side k or k - 1: a grid corner, or where
/// the other line of the vertex crosses that line.
fn vertex_at(piece: &Piece, k: usize, other_line: usize) -> At {
    match piece.corners[k] {
        Some(c) => At::Grid(c),
        None => At::Cross(piece.lines[other_line]),
    }
}

/// Records, on the tracks, where the visible pieces show them seen (see the module docs).
pub fn mark_seen(screen: &ScreenScene, pieces: &[Piece], index: &TrackIndex, tracks: &mut [Track]) {
    for piece in pieces {
        let poly = &screen.polys[piece.poly as usize];
        let corners = screen.corners(poly);
        let n = piece.len();
        let m = corners.len();
        for k in 0..n {
            // Side k runs from vertex k (lines k-1, k) to vertex k+1 (lines k, k+1).
            let span = (
                vertex_at(piece, k, (k + n - 1) % n),
                vertex_at(piece, (k + 1) % n, (k + 1) % n),
            );
            match piece.boundaries[k] {
                Boundary::Outline { poly: p, side } if p == piece.poly => {
                    // Along the run of collinear outline sides from `side`.
                    let line = piece.lines[k];
                    let mut j = side as usize;
                    loop {
                        let t = index.of_side[poly.start as usize + j];
                        if t != u32::MAX {
                            tracks[t as usize].seen[0].push(span);
                        }
                        let next = (j + 1) % m;
                        let after = corners[(next + 1) % m];
                        if next == side as usize || !on_line(&line, after) {
                            break;
                        }
                        j = next;
                    }
                }
                Boundary::Cut { a, b } if a == piece.poly || b == piece.poly => {
                    if let Some(&t) = index.of_cut.get(&(a.min(b), a.max(b))) {
                        let which = (piece.poly == a.max(b)) as usize;
                        tracks[t as usize].seen[which].push(span);
                    }
                }
                _ => {
                    // A line another polygon named: it may still run along an own edge.
                    for j in 0..m {
                        let t = index.of_side[poly.start as usize + j];
                        if t == u32::MAX {
                            continue;
                        }
                        let edge = tracks[t as usize].carrier.line;
                        if piece.vertex_line_sign(k, &edge) == Ordering::Equal
                            && piece.vertex_line_sign((k + 1) % n, &edge) == Ordering::Equal
                        {
                            tracks[t as usize].seen[0].push(span);
                        }
                    }
                }
            }
        }
    }
}

/// Does grid point `p` lie on the edge line `l`? Exact.
fn on_line(l: &Line, p: GridPoint) -> bool {
    match l {
        Line::Edge(e) => e.value_at(GridPoint { z: 0, ..p }) == 0,
        Line::Cut(..) => l.sign_at_grid(p.x, p.y) == Some(Ordering::Equal),
    }
}

/// What a drawn segment is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Label {
    /// Seen or not.
    pub visibility: Visibility,
    /// Its kind.
    pub kind: LineKind,
}

/// A drawn segment, in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// What it is.
    pub label: Label,
    /// Its ends.
    pub ends: [[f64; 2]; 2],
}

/// The lines of the view rectangle (|x|, |y| <= 2^22 on the grid), inside positive.
fn view_lines() -> [Line; 4] {
    let h = (GRID_MAX / 2) as i32;
    let g = |x, y| GridPoint { x, y, z: 0 };
    let edge = |p, q| Line::Edge(Plane::edge(p, q).expect("distinct points"));
    [
        edge(g(-h, -h), g(h, -h)),
        edge(g(h, -h), g(h, h)),
        edge(g(h, h), g(-h, h)),
        edge(g(-h, h), g(-h, -h)),
    ]
}

/// The part of `carrier` inside the convex region bounded by `lines` (inside positive), as two
/// points; `None` when it is empty or a point. A carrier lying along one of the lines counts as
/// inside it.
pub fn clip_to_convex(carrier: &Carrier, lines: &[Line]) -> Option<(At, At)> {
    let mut lo: Option<(Param, Line)> = None;
    let mut hi: Option<(Param, Line)> = None;
    for m in lines {
        match carrier.heading(m) {
            Ordering::Greater => {
                let p = carrier.param(&At::Cross(*m));
                if lo.as_ref().is_none_or(|(q, _)| p > *q) {
                    lo = Some((p, *m));
                }
            }
            Ordering::Less => {
                let p = carrier.param(&At::Cross(*m));
                if hi.as_ref().is_none_or(|(q, _)| p < *q) {
                    hi = Some((p, *m));
                }
            }
            Ordering::Equal => {
                if carrier.side_of_parallel(m) == Ordering::Less {
                    return None;
                }
            }
        }
    }
    let ((pl, l), (ph, h)) = (lo?, hi?);
    (pl < ph).then_some((At::Cross(l), At::Cross(h)))
}

/// The drawn segments of `tracks`: each screen line's tracks resolved together (see the module
/// docs), clipped to the view, hidden parts left out unless `hidden`.
pub fn segments(tracks: &[Track], samples: &Samples, hidden: bool) -> Vec<Segment> {
    let view = view_lines();
    // Tracks on the same screen line, in order of first appearance.
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut group_of: HashMap<LineKey, usize> = HashMap::new();
    for (t, track) in tracks.iter().enumerate() {
        match line_key(&track.carrier.line) {
            Some(key) => {
                let g = *group_of.entry(key).or_insert_with(|| {
                    groups.push(Vec::new());
                    groups.len() - 1
                });
                groups[g].push(t);
            }
            None => groups.push(vec![t]),
        }
    }
    let mut out = Vec::new();
    for group in &groups {
        let carrier = tracks[group[0]].carrier;
        let Some(window) = clip_to_convex(&carrier, &view) else {
            continue;
        };
        resolve(&carrier, window, group, tracks, samples, hidden, &mut out);
    }
    out
}

/// An edge line's exact identity: its coefficients divided by their gcd, the first non-zero of
/// (a, b) positive. Lines of two planes' meeting are not grouped (`None`).
type LineKey = (i64, i64, i128);

fn line_key(l: &Line) -> Option<LineKey> {
    let Line::Edge(p) = l else { return None };
    let g = gcd(
        gcd(p.a.unsigned_abs() as u128, p.b.unsigned_abs() as u128),
        p.d.unsigned_abs(),
    );
    let (mut a, mut b, mut d) = (p.a / g as i64, p.b / g as i64, p.d / g as i128);
    if a < 0 || (a == 0 && b < 0) {
        (a, b, d) = (-a, -b, -d);
    }
    Some((a, b, d))
}

fn gcd(mut a: u128, mut b: u128) -> u128 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// What changes at a point of a line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Change {
    /// The view window opens (+1) or closes (-1).
    Window(i32),
    /// Track `t` exists from here (+1) or ends (-1).
    Extent(usize, i32),
    /// Track `t` is seen beside its polygon `which` from here (+1) or not (-1).
    Seen(usize, usize, i32),
}

#[allow(clippy::too_many_arguments)]
fn resolve(
    carrier: &Carrier,
    window: (At, At),
    group: &[usize],
    tracks: &[Track],
    samples: &Samples,
    hidden: bool,
    out: &mut Vec<Segment>,
) {
    let mut events: Vec<(Param, At, Change)> = Vec::new();
    let span = |(a, b): (At, At), open: Change, close: Change, events: &mut Vec<_>| {
        let (pa, pb) = (carrier.param(&a), carrier.param(&b));
        match pa.cmp(&pb) {
            Ordering::Less => {
                events.push((pa, a, open));
                events.push((pb, b, close));
            }
            Ordering::Greater => {
                events.push((pb, b, open));
                events.push((pa, a, close));
            }
            Ordering::Equal => {}
        }
    };
    span(window, Change::Window(1), Change::Window(-1), &mut events);
    for &t in group {
        for &e in &tracks[t].extent {
            span(e, Change::Extent(t, 1), Change::Extent(t, -1), &mut events);
        }
        for which in 0..2 {
            for &s in &tracks[t].seen[which] {
                span(
                    s,
                    Change::Seen(t, which, 1),
                    Change::Seen(t, which, -1),
                    &mut events,
                );
            }
        }
    }
    events.sort_by(|x, y| x.0.cmp(&y.0));
    let slot = |t: usize| group.iter().position(|&u| u == t).expect("in the group");
    let mut window_open = 0;
    let mut extent = vec![0i32; group.len()];
    let mut seen = vec![[0i32; 2]; group.len()];
    // The segment being built: its label and first point.
    let mut open: Option<(Label, At)> = None;
    let mut i = 0;
    while i < events.len() {
        let here = events[i].0;
        let at = events[i].1;
        while i < events.len() && events[i].0 == here {
            match events[i].2 {
                Change::Window(d) => window_open += d,
                Change::Extent(t, d) => extent[slot(t)] += d,
                Change::Seen(t, w, d) => seen[slot(t)][w] += d,
            }
            i += 1;
        }
        // The label from here to the next point.
        let label = if window_open > 0 {
            group
                .iter()
                .enumerate()
                .filter(|&(s, _)| extent[s] > 0)
                .map(|(s, &t)| {
                    let track = &tracks[t];
                    let [s0, s1] = seen[s];
                    let is_seen = if track.needs_both {
                        s0 > 0 && s1 > 0
                    } else {
                        s0 > 0 || s1 > 0
                    };
                    Label {
                        visibility: if is_seen {
                            Visibility::Visible
                        } else {
                            Visibility::Hidden
                        },
                        kind: track.kind,
                    }
                })
                .filter(|l| hidden || l.visibility == Visibility::Visible)
                .min()
        } else {
            None
        };
        if open.map(|(l, _)| l) != label {
            if let Some((l, from)) = open.take() {
                push(carrier, l, from, at, samples, out);
            }
            open = label.map(|l| (l, at));
        }
    }
    debug_assert!(open.is_none(), "every span closes");
}

fn push(
    carrier: &Carrier,
    label: Label,
    from: At,
    to: At,
    samples: &Samples,
    out: &mut Vec<Segment>,
) {
    let ends = [carrier.pixel(&from, samples), carrier.pixel(&to, samples)];
    // Two exact points a rounding apart draw as one point.
    if ends[0] != ends[1] {
        out.push(Segment { label, ends });
    }
}
