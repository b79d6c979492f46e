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
//! - a line none of whose faces is on screen, one of them seen edge-on (or where an edge-on face
//!   meets another), is visible where no visible piece lies strictly in front of it: the pieces
//!   whose interior it crosses are compared with its depth exactly;
//! - an edge of culled back faces only lies on the far side of a closed mesh: hidden;
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

use super::LineOptions;
use super::along::{At, Carrier, Param};
use super::drawing::{LineKind, Visibility};
use crate::exact::polygon::{Boundary, Piece};
use crate::exact::predicates::{Line, Wide, depth_order_at};
use crate::exact::{GRID_MAX, GridPoint, Plane, Samples, w256};
use crate::project::ScreenScene;
use crate::visibility::grid::BoxGrid;
use rustc_hash::FxHashMap as HashMap;
use std::cmp::Ordering;

/// One line to draw.
#[derive(Clone, Debug)]
pub struct Track {
    /// The line it lies on.
    pub carrier: Carrier,
    /// What it is.
    pub kind: LineKind,
    /// Provenance: the faces it belongs to (`Scene::faces` indices, ascending): an edge's
    /// faces, or the two faces that meet.
    pub faces: Vec<u32>,
    /// A support plane (c > 0) holding the line in 3D: its depth at every point of the line.
    pub depth: Plane,
    /// Where it exists on screen.
    pub extent: Vec<(At, At)>,
    /// Spans read off the visible pieces, as its [`SeenRule`] says.
    pub seen: [Vec<(At, At)>; 2],
    /// For [`SeenRule::Unoccluded`]: spans where a piece in front lies along the track, beside
    /// it on its left (`[0]`) or right (`[1]`); in front on both sides, it is hidden.
    pub beside: [Vec<(At, At)>; 2],
    /// For quantitative invisibility: one span per face in front of the track, where that
    /// face lies strictly in front of it ([`mark_faces_in_front`]); `None` when not counted.
    pub in_front: Option<Vec<(At, At)>>,
    /// How the spans decide where it is seen.
    pub rule: SeenRule,
}

/// How a track's spans decide where it is seen (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SeenRule {
    /// A face edge: seen where a piece of one of its faces lies along it (`seen[0]`).
    BesideAFace,
    /// An intersection: seen where pieces of both faces lie along it (`seen[0]` beside the
    /// first face, `seen[1]` beside the second).
    BesideBothFaces,
    /// A line none of whose faces is on screen, one of them edge-on: seen except where a
    /// piece lies in front of it (`seen[1]` holds the spans where it crosses one's interior,
    /// `beside` those where pieces in front lie along it, hiding it when on both sides).
    Unoccluded,
    /// An edge of culled back faces only: on the far side of a closed mesh (culling removes
    /// only back faces of closed, consistently oriented meshes the near plane does not cut),
    /// where the mesh's own front faces lie in front of it. Never seen.
    Behind,
}

impl Track {
    /// A track with nothing seen yet.
    pub fn new(
        line: Line,
        kind: LineKind,
        faces: Vec<u32>,
        depth: Plane,
        extent: Vec<(At, At)>,
        rule: SeenRule,
    ) -> Track {
        Track {
            carrier: Carrier::new(line),
            kind,
            faces,
            depth,
            extent,
            seen: [Vec::new(), Vec::new()],
            beside: [Vec::new(), Vec::new()],
            in_front: None,
            rule,
        }
    }
}

/// Which track each piece side belongs to.
pub struct TrackIndex<'a> {
    /// Per screen side (`ScreenScene::sides` index): the track of the face edge it lies on, or
    /// `u32::MAX`.
    pub of_side: &'a [u32],
    /// The track of the intersection of two screen polygons, by their planes in the order of
    /// their faces (`Scene::faces` indices; see [`super::intersections::Meeting::planes`]).
    pub of_cut: &'a HashMap<[Plane; 2], u32>,
}

/// Vertex k of `piece` as a point of the line of its side k or k - 1: a grid corner, or where
/// the other line of the vertex crosses that line.
fn vertex_at(piece: &Piece, k: usize, other_line: usize) -> At {
    match piece.corner(k) {
        Some(c) => At::Grid(c),
        None => At::Cross(piece.line(other_line).clone()),
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
            match piece.boundary(k) {
                Boundary::Outline { poly: p, side } if p == piece.poly => {
                    // Along the run of collinear outline sides from `side`.
                    let line = piece.line(k);
                    let mut j = side as usize;
                    loop {
                        let t = index.of_side[poly.start as usize + j];
                        if t != u32::MAX {
                            tracks[t as usize].seen[0].push(span.clone());
                        }
                        let next = (j + 1) % m;
                        let after = corners[(next + 1) % m];
                        if next == side as usize || !on_line(line, after) {
                            break;
                        }
                        j = next;
                    }
                }
                Boundary::Cut { a, b } if a == piece.poly || b == piece.poly => {
                    let [pa, pb] = [a, b].map(|p| &screen.polys[p as usize]);
                    let (fa, fb) = (pa.face, pb.face);
                    let key = if fa < fb {
                        [screen.plane(pa), screen.plane(pb)]
                    } else {
                        [screen.plane(pb), screen.plane(pa)]
                    };
                    if let Some(&t) = index.of_cut.get(&key) {
                        let which = (poly.face == fa.max(fb)) as usize;
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
                        let edge = &tracks[t as usize].carrier.line;
                        let along = match (
                            piece.line(k).vertical_coefficients(),
                            edge.vertical_coefficients(),
                        ) {
                            (Some(p), Some(q)) => same_edge_line(p, q),
                            _ => {
                                piece.vertex_line_sign(k, edge) == Ordering::Equal
                                    && piece.vertex_line_sign((k + 1) % n, edge) == Ordering::Equal
                            }
                        };
                        if along {
                            tracks[t as usize].seen[0].push(span.clone());
                        }
                    }
                }
            }
        }
    }
}

/// Are two edge lines (vertical planes through grid points, coefficients (a, b, d)) the same
/// line? Exact: their coefficients are proportional (products below 2^55 · 2^55 in i128, and
/// 2^55 · 2^108 in 256 bits).
fn same_edge_line([pa, pb, pd]: [i128; 3], [qa, qb, qd]: [i128; 3]) -> bool {
    pa * qb == pb * qa
        && w256(pa) * w256(qd) == w256(qa) * w256(pd)
        && w256(pb) * w256(qd) == w256(qb) * w256(pd)
}

/// Does grid point `p` lie on the line `l`? Exact.
fn on_line(l: &Line, p: GridPoint) -> bool {
    l.sign_at_grid(p.x, p.y) == Ordering::Equal
}

/// What a drawn segment is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Label {
    /// Seen or not.
    pub visibility: Visibility,
    /// Its kind.
    pub kind: LineKind,
    /// Quantitative invisibility: 0 when seen; when hidden, the number of faces in front if it
    /// was counted ([`mark_faces_in_front`]), else 1 ("at least one").
    pub qi: u32,
}

/// A drawn segment.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// What it is.
    pub label: Label,
    /// The track drawn here (of the tracks on this screen line, the one the label comes from).
    pub track: u32,
    /// Its ends, exactly, on that track's carrier, in the carrier's direction.
    pub at: [At; 2],
    /// Its ends in pixels.
    pub ends: [[f64; 2]; 2],
}

/// The lines of the view rectangle (|x|, |y| <= 2^52 on the grid), inside positive.
fn view_lines() -> [Line; 4] {
    let h = GRID_MAX / 2;
    let g = |x, y| GridPoint { x, y, z: 0 };
    let edge = |p, q| Line::edge(p, q).expect("distinct points");
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
    clip_to_region(carrier, lines, true)
}

/// [`clip_to_convex`], a carrier along one of the lines counting as inside when `closed`.
fn clip_to_region<'a>(
    carrier: &Carrier,
    lines: impl IntoIterator<Item = &'a Line>,
    closed: bool,
) -> Option<(At, At)> {
    let mut lo: Option<(Param, &Line)> = None;
    let mut hi: Option<(Param, &Line)> = None;
    for m in lines {
        match carrier.heading(m) {
            Ordering::Greater => {
                let p = carrier.param(&At::Cross(m.clone()));
                if lo.as_ref().is_none_or(|(q, _)| p > *q) {
                    lo = Some((p, m));
                }
            }
            Ordering::Less => {
                let p = carrier.param(&At::Cross(m.clone()));
                if hi.as_ref().is_none_or(|(q, _)| p < *q) {
                    hi = Some((p, m));
                }
            }
            Ordering::Equal => match carrier.side_of_parallel(m) {
                Ordering::Less => return None,
                Ordering::Equal if !closed => return None,
                _ => {}
            },
        }
    }
    let ((pl, l), (ph, h)) = (lo?, hi?);
    (pl < ph).then(|| (At::Cross(l.clone()), At::Cross(h.clone())))
}

/// The drawn segments of `tracks`: each screen line's tracks resolved together (see the module
/// docs), clipped to the view, hidden parts left out unless `hidden`.
pub fn segments(tracks: &[Track], samples: &Samples, options: &LineOptions) -> Vec<Segment> {
    let view = view_lines();
    let groups = same_line_groups(tracks);
    let mut out = Vec::new();
    for group in &groups {
        let carrier = tracks[group[0]].carrier.clone();
        // Lines whose ends are grid points inside the view need no clipping.
        let inside = group.iter().all(|&t| {
            tracks[t]
                .extent
                .iter()
                .all(|(p, q)| in_view(p) && in_view(q))
        });
        let window = if inside {
            let (p, q) = tracks[group[0]].extent[0].clone();
            Some(extent_window(&carrier, group, tracks).unwrap_or((p, q)))
        } else {
            clip_to_convex(&carrier, &view)
        };
        let Some(window) = window else {
            continue;
        };
        resolve(&carrier, window, group, tracks, samples, options, &mut out);
    }
    out
}

/// Is `at` a grid point inside the view rectangle?
fn in_view(at: &At) -> bool {
    let h = GRID_MAX / 2;
    matches!(at, At::Grid([x, y]) if x.abs() <= h && y.abs() <= h)
}

/// The first and last points of the extents of the tracks of a group: a window holding them
/// all.
fn extent_window(carrier: &Carrier, group: &[usize], tracks: &[Track]) -> Option<(At, At)> {
    let mut lo: Option<(Param, At)> = None;
    let mut hi: Option<(Param, At)> = None;
    for &t in group {
        for (p, q) in &tracks[t].extent {
            for at in [p, q] {
                let v = carrier.param(at);
                if lo.as_ref().is_none_or(|(l, _)| v < *l) {
                    lo = Some((v.clone(), at.clone()));
                }
                if hi.as_ref().is_none_or(|(h, _)| v > *h) {
                    hi = Some((v, at.clone()));
                }
            }
        }
    }
    Some((lo?.1, hi?.1))
}

/// The tracks grouped by the screen line they lie on, exactly, groups in order of their first
/// track. Edge lines are grouped by their reduced coefficients; each meeting line (`Line::Cut`)
/// is then put with the edge lines or meeting lines it equals, found by sorting them in an
/// exact order of lines.
fn same_line_groups(tracks: &[Track]) -> Vec<Vec<usize>> {
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut group_of: HashMap<LineKey, usize> = HashMap::default();
    let mut cuts = Vec::new();
    for (t, track) in tracks.iter().enumerate() {
        match line_key(&track.carrier.line) {
            Some(key) => {
                let g = *group_of.entry(key).or_insert_with(|| {
                    groups.push(Vec::new());
                    groups.len() - 1
                });
                groups[g].push(t);
            }
            None => cuts.push(t),
        }
    }
    if cuts.is_empty() {
        return groups;
    }
    // Each edge group once (by its first track), then every meeting line, in line order.
    // Exact coefficients computed once per line, not per comparison.
    let mut lines: Vec<(Normalized, Option<usize>, usize)> = groups
        .iter()
        .enumerate()
        .map(|(g, members)| (members[0], Some(g)))
        .chain(cuts.iter().map(|&t| (t, None)))
        .map(|(t, g)| (normalized(&tracks[t].carrier.line), g, t))
        .collect();
    lines.sort_by(|x, y| cmp_lines(&x.0, &y.0).then(x.2.cmp(&y.2)));
    for run in lines.chunk_by(|x, y| cmp_lines(&x.0, &y.0) == Ordering::Equal) {
        let target = match run.iter().find_map(|x| x.1) {
            Some(g) => g,
            None => {
                groups.push(Vec::new());
                groups.len() - 1
            }
        };
        groups[target].extend(run.iter().filter(|x| x.1.is_none()).map(|x| x.2));
    }
    for g in &mut groups {
        g.sort_unstable();
    }
    groups.sort_by_key(|g| g[0]);
    groups
}

/// A line's exact coefficients with its normal turned into the half-plane a > 0, or a = 0 and
/// b > 0 (the same line), and the same rounded to f64 for the filter of [`cmp_lines`].
struct Normalized {
    exact: [Wide; 3],
    approx: [f64; 3],
}

fn normalized(l: &Line) -> Normalized {
    let [a, b, d] = l.exact();
    let exact = if a.is_negative() || (a.is_zero() && b.is_negative()) {
        [-a, -b, -d]
    } else {
        [a, b, d]
    };
    Normalized {
        exact,
        approx: exact.map(|v| crate::exact::int_to_f64(v.to_le_bytes())),
    }
}

/// An exact total order of screen lines as point sets, given [`normalized`]: by the direction
/// of their normal, then by their offset along it. `Equal` exactly when they are the same line.
///
/// Each comparison is the sign of `p·q - r·s` for four coefficients; in f64 (each coefficient
/// rounded once, relative error at most U, each product and the difference rounded once) it
/// errs by less than `6·U·(|p·q| + |r·s|)`, so beyond twice that the f64 sign is exact.
fn cmp_lines(l: &Normalized, m: &Normalized) -> Ordering {
    let sign = |[p, q, r, t]: [usize; 4], [lp, lq]: [&Normalized; 2]| {
        let (x, y) = (lp.approx[p] * lq.approx[q], lq.approx[r] * lp.approx[t]);
        let bound = 12.0 * crate::exact::U * (x.abs() + y.abs());
        if x - y > bound {
            Ordering::Greater
        } else if y - x > bound {
            Ordering::Less
        } else {
            (lp.exact[p] * lq.exact[q]).cmp(&(lq.exact[r] * lp.exact[t]))
        }
    };
    // The second normal turned counter-clockwise from the first (b0·a1 < a0·b1): the first
    // comes first.
    match sign([1, 0, 1, 0], [l, m]) {
        Ordering::Equal => {}
        turn => return turn,
    }
    // Parallel, normals in the same direction: compare d / |n| through the positive ratio
    // (d0·a1 against d1·a0, or with b when a = 0).
    if !l.exact[0].is_zero() {
        sign([2, 0, 2, 0], [l, m])
    } else {
        sign([2, 1, 2, 1], [l, m])
    }
}

/// An edge line's exact identity: its coefficients divided by their gcd, the first non-zero of
/// (a, b) positive. Lines of two planes' meeting are not grouped (`None`).
type LineKey = (i128, i128, i128);

fn line_key(l: &Line) -> Option<LineKey> {
    let [a, b, d] = l.vertical_coefficients()?;
    let g = gcd(gcd(a.unsigned_abs(), b.unsigned_abs()), d.unsigned_abs()) as i128;
    let (mut a, mut b, mut d) = (a / g, b / g, d / g);
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
    /// One more face lies in front of track `t` from here (+1), or one fewer (-1).
    Front(usize, i32),
    /// A piece in front lies along track `t` on its side `side` from here (+1), or no more (-1).
    Beside(usize, usize, i32),
}

#[allow(clippy::too_many_arguments)]
fn resolve(
    carrier: &Carrier,
    window: (At, At),
    group: &[usize],
    tracks: &[Track],
    samples: &Samples,
    options: &LineOptions,
    out: &mut Vec<Segment>,
) {
    let mut events: Vec<(Param, Change)> = Vec::new();
    let span = |(a, b): (At, At), open: Change, close: Change, events: &mut Vec<_>| {
        if let Some([from, to]) = carrier.ordered(a, b) {
            events.push((from, open));
            events.push((to, close));
        }
    };
    span(window, Change::Window(1), Change::Window(-1), &mut events);
    for &t in group {
        for e in &tracks[t].extent {
            span(
                e.clone(),
                Change::Extent(t, 1),
                Change::Extent(t, -1),
                &mut events,
            );
        }
        for which in 0..2 {
            for s in &tracks[t].seen[which] {
                span(
                    s.clone(),
                    Change::Seen(t, which, 1),
                    Change::Seen(t, which, -1),
                    &mut events,
                );
            }
        }
        for s in tracks[t].in_front.iter().flatten() {
            span(
                s.clone(),
                Change::Front(t, 1),
                Change::Front(t, -1),
                &mut events,
            );
        }
        for side in 0..2 {
            for s in &tracks[t].beside[side] {
                span(
                    s.clone(),
                    Change::Beside(t, side, 1),
                    Change::Beside(t, side, -1),
                    &mut events,
                );
            }
        }
    }
    events.sort_by(|a, b| a.0.cmp(&b.0));
    let slot = |t: usize| group.iter().position(|&u| u == t).expect("in the group");
    let mut window_open = 0;
    let mut extent = vec![0i32; group.len()];
    let mut seen = vec![[0i32; 2]; group.len()];
    let mut front = vec![0i32; group.len()];
    let mut beside = vec![[0i32; 2]; group.len()];
    // The segment being built: its label and first point.
    let mut open: Option<((Label, usize), At)> = None;
    let mut i = 0;
    while i < events.len() {
        let here = events[i].0.clone();
        let at = here.at();
        while i < events.len() && events[i].0 == here {
            match events[i].1 {
                Change::Window(d) => window_open += d,
                Change::Extent(t, d) => extent[slot(t)] += d,
                Change::Seen(t, w, d) => seen[slot(t)][w] += d,
                Change::Front(t, d) => front[slot(t)] += d,
                Change::Beside(t, side, d) => beside[slot(t)][side] += d,
            }
            i += 1;
        }
        // The label from here to the next point, and the track it comes from.
        let label = if window_open > 0 {
            group
                .iter()
                .enumerate()
                .filter(|&(s, _)| extent[s] > 0)
                .map(|(s, &t)| {
                    let track = &tracks[t];
                    let [s0, s1] = seen[s];
                    let is_seen = match track.rule {
                        SeenRule::BesideAFace => s0 > 0 || s1 > 0,
                        SeenRule::BesideBothFaces => s0 > 0 && s1 > 0,
                        SeenRule::Unoccluded => s1 == 0 && !(beside[s][0] > 0 && beside[s][1] > 0),
                        SeenRule::Behind => false,
                    };
                    let (visibility, qi) = if is_seen {
                        (Visibility::Visible, 0)
                    } else if track.in_front.is_some() {
                        // A degenerate tie the visible set broke the other way may count none.
                        (Visibility::Hidden, front[s].max(1) as u32)
                    } else {
                        (Visibility::Hidden, 1)
                    };
                    let label = Label {
                        visibility,
                        kind: track.kind,
                        qi,
                    };
                    (label, t)
                })
                .filter(|(l, _)| {
                    l.visibility == Visibility::Visible
                        || (options.hidden && options.qi_max.is_none_or(|m| l.qi <= m))
                })
                .min()
        } else {
            None
        };
        if open.as_ref().map(|(l, _)| *l) != label {
            if let Some(((l, t), from)) = open.take() {
                push(&tracks[t].carrier, l, t, [from, at.clone()], samples, out);
            }
            open = label.map(|l| (l, at));
        }
    }
    debug_assert!(open.is_none(), "every span closes");
}

fn push(
    carrier: &Carrier,
    label: Label,
    track: usize,
    at: [At; 2],
    samples: &Samples,
    out: &mut Vec<Segment>,
) {
    // In the track's own direction.
    let [a, b] = at;
    let Some(ordered) = carrier.ordered(a, b) else {
        return;
    };
    let at = ordered.map(|p| p.at());
    let ends = [0, 1].map(|k| carrier.pixel(&at[k], samples));
    // Two exact points a rounding apart draw as one point.
    if ends[0] != ends[1] {
        out.push(Segment {
            label,
            track: track as u32,
            at,
            ends,
        });
    }
}

/// For the [`SeenRule::Unoccluded`] tracks among `tracks`: the spans where a visible piece lies
/// strictly in front of them (in `seen[1]`). A piece occludes the part of the carrier that
/// crosses its interior where its plane is nearer than the track's depth plane, decided exactly
/// at the span's ends and split where the two planes meet.
pub fn mark_occluded(pieces: &[Piece], tracks: &mut [Track]) {
    let which: Vec<usize> = (0..tracks.len())
        .filter(|&t| tracks[t].rule == SeenRule::Unoccluded)
        .collect();
    if which.is_empty() {
        return;
    }
    let boxes: Vec<[f64; 4]> = pieces
        .iter()
        .map(crate::visibility::coverage::bounds)
        .collect();
    let grid = BoxGrid::holding(&boxes);
    let mut near: Vec<u32> = Vec::new();
    for t in which {
        let track = &tracks[t];
        grid.entries_near(&track_box(track), &mut near);
        let mut occluded = Vec::new();
        let mut beside: [Vec<(At, At)>; 2] = [Vec::new(), Vec::new()];
        for &i in &near {
            let piece = &pieces[i as usize];
            if let Some(inside) = clip_to_region(&track.carrier, piece.lines(), false) {
                occluded.extend(in_front(track, inside, &piece.support));
            } else if let Some(side) = side_along(&track.carrier, piece)
                && let Some(along) = clip_to_region(&track.carrier, piece.lines(), true)
            {
                // A piece with a side on the line: in front there, it hides the line only
                // together with one on the other side (the line then runs under a surface).
                beside[side].extend(in_front(track, along, &piece.support));
            }
        }
        tracks[t].seen[1] = occluded;
        tracks[t].beside = beside;
    }
}

/// When one of `piece`'s lines lies on the carrier: the carrier's side the piece lies on (0:
/// left, where the carrier's equation is positive; 1: right). Exact.
fn side_along(carrier: &Carrier, piece: &Piece) -> Option<usize> {
    let line = piece.lines().find(|l| {
        carrier.heading(l) == Ordering::Equal && carrier.side_of_parallel(l) == Ordering::Equal
    })?;
    // The piece lies on its line's positive side: the carrier's too when their normals agree.
    let ([a0, b0, _], [a1, b1, _]) = (carrier.line.exact(), line.exact());
    let same = (a0 * a1 + b0 * b1).is_positive();
    Some(if same { 0 } else { 1 })
}

/// The part of span `(lo, hi)` of the track where plane `s` is strictly nearer than the track.
fn in_front(track: &Track, (lo, hi): (At, At), s: &Plane) -> Option<(At, At)> {
    let d = &track.depth;
    if crate::exact::polygon::same_plane(s, d) {
        return None;
    }
    let order = |at: &At| depth_order_on(&track.carrier, at, s, d);
    match (order(&lo), order(&hi)) {
        (Ordering::Less, Ordering::Less | Ordering::Equal) | (Ordering::Equal, Ordering::Less) => {
            Some((lo, hi))
        }
        (Ordering::Less, Ordering::Greater) => Some((lo, At::Cross(Line::cut(*d, *s)))),
        (Ordering::Greater, Ordering::Less) => Some((At::Cross(Line::cut(*d, *s)), hi)),
        _ => None,
    }
}

/// The depth order of planes `s` and `t` at point `at` of the carrier (`Less`: `s` nearer).
fn depth_order_on(carrier: &Carrier, at: &At, s: &Plane, t: &Plane) -> Ordering {
    let other = match at {
        At::Cross(m) => m.clone(),
        At::Grid([x, y]) => {
            // A grid line through the point, across the carrier.
            let p = GridPoint { x: *x, y: *y, z: 0 };
            let vertical = Line::edge(p, GridPoint { y: y + 1, ..p }).expect("distinct");
            if carrier.crosses(&vertical) {
                vertical
            } else {
                Line::edge(p, GridPoint { x: x + 1, ..p }).expect("distinct")
            }
        }
    };
    depth_order_at([&carrier.line, &other], s, t).expect("the lines cross")
}

/// A box around the track's extent in grid units, widened (a filter).
fn track_box(track: &Track) -> [f64; 4] {
    let mut b = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];
    for (p, q) in &track.extent {
        for at in [p, q] {
            // Correctly rounded: within half an ulp of the exact point.
            let [x, y] = match at {
                At::Grid([x, y]) => [*x as f64, *y as f64],
                At::Cross(m) => crate::exact::predicates::crossing_rounded(&track.carrier.line, m)
                    .expect("a crossing line is not parallel"),
            };
            b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
        }
    }
    [b[0] - 2.0, b[1] - 2.0, b[2] + 2.0, b[3] + 2.0]
}

/// Counts, for every track, the faces of `screen` strictly in front of it (quantitative
/// invisibility): for each face other than its own whose box meets the track's, the span where
/// the track crosses the face's interior (each convex part) and the face's plane is nearer
/// than the track, decided exactly. The spans go to `in_front`.
pub fn mark_faces_in_front(screen: &ScreenScene, tracks: &mut [Track]) {
    let polys = &screen.polys;
    let boxes: Vec<[f64; 4]> = polys
        .iter()
        .map(|p| super::intersections::points_box(&screen.corners(p)))
        .collect();
    let grid = BoxGrid::holding(&boxes);
    // Each face's convex parts and plane, made when a track first needs them.
    let mut parts: Vec<Option<(Vec<Vec<Line>>, Plane)>> = vec![None; polys.len()];
    let mut near: Vec<u32> = Vec::new();
    for track in tracks.iter_mut() {
        grid.entries_near(&track_box(track), &mut near);
        let mut spans = Vec::new();
        for &i in &near {
            let poly = &polys[i as usize];
            if track.faces.contains(&poly.face) {
                continue;
            }
            let (parts, plane) = parts[i as usize].get_or_insert_with(|| {
                (
                    super::intersections::convex_parts(screen, poly),
                    screen.plane(poly),
                )
            });
            // Each convex part's open interior once (the parts are disjoint); outside the
            // track's extent nothing is drawn, so no clipping to it is needed.
            for part in parts.iter() {
                if let Some(inside) = clip_to_region(&track.carrier, part, false) {
                    spans.extend(in_front(track, inside, plane));
                }
            }
        }
        track.in_front = Some(spans);
    }
}
