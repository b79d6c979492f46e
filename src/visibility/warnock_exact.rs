//! Warnock's area subdivision at object precision (`warnock-exact`): a quadtree of screen
//! areas, each settled as soon as one polygon is in front of all the others there, instead of
//! at pixels; the areas where no such decision comes resolved by exact clipping.
//!
//! Following the course notes (section 7): the potentially visible list of an area holds the
//! pieces that meet it, classified exactly against the area (a rectangle of grid lines) as
//! surrounding it, meeting it (intersecting or contained), or disjoint (dropped). Then:
//! 1. a piece wholly behind the plane of a surrounding piece within the area is hidden there and
//!    leaves the list (the notes' key observation), nearest surrounding piece first;
//! 2. one piece left: it shows, clipped to the area (the notes' cases ii to iv, exactly);
//! 3. a few pieces left ([`LEAF_PIECES`]), a list that halving has not shortened for a few levels
//!    ([`STALLED_LEVELS`]), or an area that can no longer be halved: the leaf is resolved by
//!    exact clipping (Weiler–Atherton, [`super::weiler_atherton`], on the pieces
//!    clipped to the area) where the raster version would sample a pixel;
//! 4. otherwise the area is cut into four at its integer midpoints and each is done the same way.
//!
//! Nothing depends on the image size: the quadtree stops where the scene is simple, not at pixels.
//! Every classification and clip is exact (grid-point signs of piece lines, splits by the area's
//! lines); areas share only their sides, so the pieces written out are disjoint. Output pieces
//! carry the area lines they were clipped by as [`Boundary::ScreenSplit`]. Translucent faces are
//! layered over the result as the coverage map layers them.

use super::coverage::{nearest_first, tie_key};
use super::strips::Counters;
use super::visible_set::{VisibleSet, put_counts};
use super::weiler_atherton;
use super::{Strategy, opaque_then_layered};
use crate::exact::polygon::{Boundary, Piece, Split};
use crate::exact::predicates::Line;
use crate::exact::{Plane, w256};
use crate::progress::{Report, Ticker};
use crate::project::ScreenScene;
use std::cmp::Ordering;

/// Warnock at object precision. See the module docs.
#[derive(Clone, Copy, Debug, Default)]
pub struct WarnockExact;

/// An area whose list has at most this many pieces is a leaf (resolved by exact clipping).
pub const LEAF_PIECES: usize = 16;

/// An area whose list has not shrunk for this many levels is a leaf: pieces that all meet at
/// one point (a fan, a cone's apex) would otherwise be halved down to single grid units.
pub const STALLED_LEVELS: usize = 3;

/// Counters of one run.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct WarnockExactStats {
    /// Areas visited.
    pub areas: usize,
    /// Areas settled by one piece left in front of all others.
    pub settled: usize,
    /// Areas resolved by exact clipping.
    pub leaves: usize,
    /// Pieces dropped from an area's list as hidden behind a surrounding piece.
    pub hidden: usize,
    /// The deepest level of the quadtree.
    pub deepest: usize,
}

impl Counters for WarnockExactStats {
    fn add(&mut self, o: &Self) {
        self.areas += o.areas;
        self.settled += o.settled;
        self.leaves += o.leaves;
        self.hidden += o.hidden;
        self.deepest = self.deepest.max(o.deepest);
    }
}

impl Strategy for WarnockExact {
    fn visible_set(
        &self,
        screen: &ScreenScene,
        translucent: &dyn Fn(u32) -> bool,
        report: Option<Report>,
    ) -> VisibleSet {
        // Not in strips: an area along a strip's edge is never surrounded by a piece (the
        // pieces end at the edge), so it would be divided down to its smallest areas.
        opaque_then_layered(
            screen,
            translucent,
            report,
            false,
            |opaque, report| visible_pieces(screen, &opaque, report),
            |st, stats| {
                put_counts(
                    stats,
                    [
                        ("areas", st.areas),
                        ("areas_settled", st.settled),
                        ("leaves_clipped", st.leaves),
                        ("hidden_in_areas", st.hidden),
                        ("deepest_area", st.deepest),
                    ],
                );
            },
        )
    }
}

/// A closed screen rectangle of grid coordinates: (x0, y0, x1, y1), x0 < x1, y0 < y1.
type Area = [i64; 4];

/// The area's four sides as lines positive inside it, with their corners.
fn sides(a: &Area) -> [Line; 4] {
    let line = |a: i128, b: i128, d: i64| {
        Line::vertical(&Plane {
            a,
            b,
            c: 0,
            d: w256(d as i128),
        })
    };
    [
        line(1, 0, -a[0]),
        line(-1, 0, a[2]),
        line(0, 1, -a[1]),
        line(0, -1, a[3]),
    ]
}

fn corners(a: &Area) -> [[i64; 2]; 4] {
    [[a[0], a[1]], [a[2], a[1]], [a[2], a[3]], [a[0], a[3]]]
}

/// How a piece lies with respect to an area.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Class {
    /// No interior point in common.
    Disjoint,
    /// The piece contains the area.
    Surrounding,
    /// Anything else: it meets the area and does not contain it.
    Meeting,
}

/// Classifies `p` against `area`, exactly.
fn classify(p: &Piece, area: &Area, sides: &[Line; 4]) -> Class {
    let b = p.bounds();
    let r = area.map(|v| v as f64);
    if b[2] <= r[0] || b[0] >= r[2] || b[3] <= r[1] || b[1] >= r[3] {
        return Class::Disjoint;
    }
    let mut surrounds = true;
    for l in p.lines() {
        let signs = corners(area).map(|[x, y]| l.sign_at_grid(x, y));
        if signs.iter().all(|&s| s != Ordering::Greater) {
            return Class::Disjoint;
        }
        surrounds &= signs.iter().all(|&s| s != Ordering::Less);
    }
    if surrounds {
        return Class::Surrounding;
    }
    if sides.iter().any(|l| !p.sides_of_line(l).1) {
        return Class::Disjoint;
    }
    Class::Meeting
}

/// The part of `p` inside `area`, if it has area.
fn clip_to(p: &Piece, sides: &[Line; 4]) -> Option<Piece> {
    let mut inside = p.clone();
    for l in sides {
        match inside.split_by_line(l, Boundary::ScreenSplit) {
            Split::Positive => {}
            Split::Both(_, pos) => inside = pos,
            Split::Negative | Split::On => return None,
        }
    }
    Some(inside)
}

/// Is `p` hidden by `front` (which surrounds the area) everywhere in the area: wholly behind
/// `front`'s plane there, or coplanar and behind by the tie rule?
fn hidden_by(screen: &ScreenScene, p: &Piece, front: &Piece, sides: &[Line; 4]) -> bool {
    let behind_on_tie = || tie_key(screen, p) > tie_key(screen, front);
    match p.sides_of_plane(&front.support) {
        (false, false) => behind_on_tie(),
        (false, true) => true,
        // Part of p is in front of the plane somewhere: perhaps not in the area.
        _ => match clip_to(p, sides) {
            Some(q) => !q.sides_of_plane(&front.support).0,
            None => true,
        },
    }
}

/// The visible parts of opaque `pieces`: see the module docs. `report` gets stage "visible set"
/// (the fraction of the screen settled).
pub fn visible_pieces(
    screen: &ScreenScene,
    pieces: &[Piece],
    report: Option<Report>,
) -> (Vec<Piece>, WarnockExactStats) {
    let mut run = Run {
        screen,
        st: WarnockExactStats::default(),
        out: Vec::new(),
        ticker: Ticker::new(report, "visible set", 1 << 20),
        settled: 0.0,
        root_size: 1.0,
    };
    if let Some(root) = pieces.iter().map(Piece::grid_frame).reduce(|a, b| {
        [
            a[0].min(b[0]),
            a[1].min(b[1]),
            a[2].max(b[2]),
            a[3].max(b[3]),
        ]
    }) && root[0] < root[2]
        && root[1] < root[3]
    {
        run.root_size = ((root[2] - root[0]) as f64) * ((root[3] - root[1]) as f64);
        let list: Vec<&Piece> = pieces.iter().collect();
        run.area(root, list, 0, 0);
    }
    let Run {
        st, out, ticker, ..
    } = run;
    ticker.finish();
    (out, st)
}

/// One subdivision in progress.
struct Run<'a> {
    screen: &'a ScreenScene,
    st: WarnockExactStats,
    out: Vec<Piece>,
    ticker: Ticker<'a>,
    /// Settled screen area so far, and the root's (for progress only).
    settled: f64,
    root_size: f64,
}

impl Run<'_> {
    /// Resolves `area`, whose list `list` holds every piece that meets it (and perhaps some
    /// that do not); its list has not shrunk for `stalled` levels before it.
    fn area(&mut self, area: Area, list: Vec<&Piece>, depth: usize, stalled: usize) {
        let parent = list.len();
        self.st.areas += 1;
        self.st.deepest = self.st.deepest.max(depth);
        let sides = sides(&area);
        let mut list: Vec<(&Piece, Class)> = list
            .into_iter()
            .map(|p| (p, classify(p, &area, &sides)))
            .filter(|&(_, c)| c != Class::Disjoint)
            .collect();
        // Hidden behind a surrounding piece: out of the list, nearest surrounding piece first.
        let mut surrounding: Vec<&Piece> = list
            .iter()
            .filter(|(_, c)| *c == Class::Surrounding)
            .map(|&(p, _)| p)
            .collect();
        surrounding.sort_by_cached_key(|p| nearest_first(self.screen, p.poly));
        for front in surrounding {
            if !list.iter().any(|(p, _)| std::ptr::eq(*p, front)) {
                continue;
            }
            let before = list.len();
            list.retain(|(p, _)| {
                std::ptr::eq(*p, front) || !hidden_by(self.screen, p, front, &sides)
            });
            self.st.hidden += before - list.len();
        }
        let halves = area[2] - area[0] >= 2 || area[3] - area[1] >= 2;
        let stalled = if list.len() < parent { 0 } else { stalled + 1 };
        match list.len() {
            0 => {}
            1 => {
                self.st.settled += 1;
                self.out.extend(clip_to(list[0].0, &sides));
            }
            n if n <= LEAF_PIECES || stalled >= STALLED_LEVELS || !halves => {
                self.st.leaves += 1;
                let clipped: Vec<Piece> = list
                    .iter()
                    .filter_map(|(p, _)| clip_to(p, &sides))
                    .collect();
                let (visible, _) = weiler_atherton::visible_pieces(self.screen, clipped, None);
                self.out.extend(visible);
            }
            _ => {
                let list: Vec<&Piece> = list.into_iter().map(|(p, _)| p).collect();
                for child in quarters(&area) {
                    self.area(child, list.clone(), depth + 1, stalled);
                }
                return;
            }
        }
        self.settled += ((area[2] - area[0]) as f64) * ((area[3] - area[1]) as f64);
        self.ticker
            .tick(((self.settled / self.root_size) * (1 << 20) as f64) as u64);
    }
}

/// The area cut at its integer midpoints: four quarters, or two halves when one side is a
/// single grid unit.
fn quarters(a: &Area) -> Vec<Area> {
    let xs = if a[2] - a[0] >= 2 {
        let m = a[0] + (a[2] - a[0]) / 2;
        vec![(a[0], m), (m, a[2])]
    } else {
        vec![(a[0], a[2])]
    };
    let ys = if a[3] - a[1] >= 2 {
        let m = a[1] + (a[3] - a[1]) / 2;
        vec![(a[1], m), (m, a[3])]
    } else {
        vec![(a[1], a[3])]
    };
    ys.iter()
        .flat_map(|&(y0, y1)| xs.iter().map(move |&(x0, x1)| [x0, y0, x1, y1]))
        .collect()
}
