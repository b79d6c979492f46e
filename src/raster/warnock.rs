//! Warnock's area subdivision (seed 001), exact.
//!
//! An area is a rectangle of pixels, and what it shows is what lies at its pixel centres (the
//! samples): its geometry is the closed rectangle `R` spanned by its first and last sample. Each
//! polygon in the area's list (the seed's PVPL) is classified against `R`:
//! - **disjoint**: it covers no sample of the area: its bounding box misses `R`, or no edge meets
//!   `R` and one sample of `R` is outside it;
//! - **surrounding**: it covers every sample: no edge meets `R` and one sample is inside it (then
//!   all of `R` is strictly inside);
//! - **crossing** (the seed's intersecting and contained): an edge meets `R`.
//!
//! Segment against rectangle is exact: sample coordinates are rationals `x_num / W`, `y_num / H`,
//! so scaling grid x by W and y by H makes everything integer (below 2^68, i128), and the side
//! of a rectangle corner relative to an edge is a cross product below 2^139: decided in f64 with
//! a proven bound, in 256-bit integers when the bound cannot.
//!
//! Disjoint polygons leave the list; surrounding ones stay surrounding in every sub-area and are
//! not classified again. The seed's trivial cases, then:
//! 1. empty list: background;
//! 2. one polygon: it alone decides the area: filled if surrounding, otherwise scan-converted
//!    inside the area with the z-buffer's fill rule (the seed's "clip it and paint it");
//! 3. a surrounding polygon `S` (the nearest surrounding one at the area's first sample) removes
//!    every polygon it beats at the four corner samples: those it beats at every sample
//!    (linearity, see [`sample`]); if `S` is left alone, the area is filled with it;
//! 4. one pixel: among the polygons of the list that cover its centre (fill rule), the nearest
//!    ([`DepthOrder`]), exactly as the z-buffer decides;
//! 5. otherwise: split the area into four and recurse.
//!
//! **Invariant**: every pixel shows exactly the polygon the z-buffer shows there: a polygon
//! leaves an area's list only when it covers none of its samples or loses at all of them, and
//! every fill is either a single polygon's own exact coverage or a polygon that covers and wins
//! at every sample of the area.

use super::EMPTY;
use super::sample::{self, DepthOrder};
use crate::exact::{Fallbacks, GridPoint, Samples};
use crate::project::ScreenScene;

/// The result: per pixel the index of the visible [`ScreenPoly`](crate::project::ScreenPoly)
/// (or [`EMPTY`]), as [`ZBuffer::poly`](super::ZBuffer).
#[derive(Clone, Debug)]
pub struct Warnock {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Row-major, row 0 at the top: index into `ScreenScene::polys`, or [`EMPTY`].
    pub poly: Vec<u32>,
    /// Counters of the run.
    pub stats: WarnockStats,
}

/// Work counters.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct WarnockStats {
    /// Areas visited (the root included).
    pub areas: u64,
    /// Areas split into sub-areas.
    pub subdivisions: u64,
    /// Polygon-against-area classifications.
    pub classifications: u64,
    /// Areas left to the background (empty list).
    pub empty_areas: u64,
    /// Areas decided by a single polygon in the list (filled or scan-converted).
    pub single_polygon_areas: u64,
    /// Areas filled by a surrounding polygon in front of all the others.
    pub surrounding_in_front: u64,
    /// Polygons removed from a list because a surrounding polygon hides them in the whole area.
    pub hidden_removed: u64,
    /// One-pixel areas decided at the pixel centre.
    pub pixel_areas: u64,
    /// Crossings the f64 filter could not decide (exact computation).
    pub column_fallbacks: u64,
    /// Depth comparisons the f64 filter could not decide.
    pub depth_fallbacks: u64,
    /// Exact depth ties resolved by the id rule.
    pub depth_ties: u64,
}

impl Warnock {
    /// The input face id at every pixel (`None` for background).
    pub fn face_ids(&self, screen: &ScreenScene) -> Vec<Option<u32>> {
        sample::face_ids(&self.poly, screen)
    }
}

/// A polygon in an area's list.
#[derive(Clone, Copy, Debug)]
struct Entry {
    poly: u32,
    surrounding: bool,
}

/// How a polygon lies against an area.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Class {
    Disjoint,
    Surrounding,
    Crossing,
}

/// An area: pixel columns `[i0, i1)`, rows `[j0, j1)`, both non-empty.
#[derive(Clone, Copy, Debug)]
struct Area {
    i0: i64,
    j0: i64,
    i1: i64,
    j1: i64,
}

/// The closed rectangle spanned by an area's samples, scaled (x by W, y by H) to integers.
#[derive(Clone, Copy, Debug)]
struct Rect {
    x0: i128,
    x1: i128,
    y0: i128,
    y1: i128,
}

impl Area {
    fn rect(&self, s: &Samples) -> Rect {
        // y_num decreases as the row index grows.
        Rect {
            x0: s.x_num(self.i0),
            x1: s.x_num(self.i1 - 1),
            y0: s.y_num(self.j1 - 1),
            y1: s.y_num(self.j0),
        }
    }
}

/// Does the closed segment `p q` (scaled grid points) meet the closed rectangle `r`? Exact:
/// separating axes x, y and the segment's normal.
fn segment_meets_rect(p: [i128; 2], q: [i128; 2], r: &Rect) -> bool {
    if p[0].max(q[0]) < r.x0 || p[0].min(q[0]) > r.x1 {
        return false;
    }
    if p[1].max(q[1]) < r.y0 || p[1].min(q[1]) > r.y1 {
        return false;
    }
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let side = |x: i128, y: i128| {
        let (u, v) = (y - p[1], x - p[0]);
        // Each difference is exact in i128 and rounded once to f64, each product once more and
        // the difference once: the f64 value is within 4·U of the products' magnitudes.
        let (l, r) = (dx as f64 * u as f64, dy as f64 * v as f64);
        let approx = l - r;
        if approx.abs() > 4.0 * crate::exact::U * (l.abs() + r.abs()) * 1.01 {
            return approx.signum() as i32;
        }
        let w = crate::exact::w256;
        match (w(dx) * w(u)).cmp(&(w(dy) * w(v))) {
            std::cmp::Ordering::Less => -1,
            std::cmp::Ordering::Equal => 0,
            std::cmp::Ordering::Greater => 1,
        }
    };
    let s = [
        side(r.x0, r.y0),
        side(r.x1, r.y0),
        side(r.x0, r.y1),
        side(r.x1, r.y1),
    ];
    // Separated by the segment's line only when all four corners are strictly on one side.
    !(s.iter().all(|&v| v > 0) || s.iter().all(|&v| v < 0))
}

struct Renderer<'a> {
    screen: &'a ScreenScene,
    order: DepthOrder<'a>,
    s: Samples,
    fb: Fallbacks,
    /// Per polygon its scaled bounding box `[x0, y0, x1, y1]`.
    bounds: Vec<[i128; 4]>,
    out: Vec<u32>,
    stats: WarnockStats,
    /// The lists of all areas on the current path, one after the other.
    lists: Vec<Entry>,
    crossings: Vec<i64>,
}

/// Renders `screen` by area subdivision.
pub fn render(screen: &ScreenScene) -> Warnock {
    let order = DepthOrder::new(screen);
    let s = order.samples;
    let (w, h) = (s.width, s.height);
    let bounds = screen
        .polys
        .iter()
        .map(|p| {
            let mut b = [i128::MAX, i128::MAX, i128::MIN, i128::MIN];
            for q in screen.corners(p) {
                let (x, y) = (q.x as i128 * w as i128, q.y as i128 * h as i128);
                b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
            }
            b
        })
        .collect();
    let mut r = Renderer {
        screen,
        order,
        s,
        fb: Fallbacks::default(),
        bounds,
        out: vec![EMPTY; (w * h) as usize],
        stats: WarnockStats::default(),
        lists: (0..screen.polys.len() as u32)
            .map(|poly| Entry {
                poly,
                surrounding: false,
            })
            .collect(),
        crossings: Vec::new(),
    };
    let all = 0..r.lists.len();
    if w > 0 && h > 0 {
        r.area(
            Area {
                i0: 0,
                j0: 0,
                i1: w,
                j1: h,
            },
            all,
        );
    }
    r.stats.column_fallbacks = r.fb.column.get();
    r.stats.depth_fallbacks = r.order.fallbacks.get();
    r.stats.depth_ties = r.order.ties.get();
    Warnock {
        width: screen.width,
        height: screen.height,
        poly: r.out,
        stats: r.stats,
    }
}

impl Renderer<'_> {
    fn classify(&mut self, poly: u32, a: &Area, r: &Rect) -> Class {
        self.stats.classifications += 1;
        let b = self.bounds[poly as usize];
        if b[2] < r.x0 || b[0] > r.x1 || b[3] < r.y0 || b[1] > r.y1 {
            return Class::Disjoint;
        }
        let pts = &self.screen.corners(&self.screen.polys[poly as usize]);
        let (w, h) = (self.s.width, self.s.height);
        let scaled = |g: GridPoint| [g.x as i128 * w as i128, g.y as i128 * h as i128];
        for k in 0..pts.len() {
            let (p, q) = (scaled(pts[k]), scaled(pts[(k + 1) % pts.len()]));
            if segment_meets_rect(p, q, r) {
                return Class::Crossing;
            }
        }
        // No edge meets the rectangle: all of it is strictly inside or strictly outside, and
        // the fill rule agrees with that at any of its samples.
        if sample::covers(&self.s, pts, a.i0, a.j0, &self.fb) {
            Class::Surrounding
        } else {
            Class::Disjoint
        }
    }

    fn fill(&mut self, a: &Area, poly: u32) {
        let w = self.s.width;
        for j in a.j0..a.j1 {
            self.out[(j * w + a.i0) as usize..(j * w + a.i1) as usize].fill(poly);
        }
    }

    /// Scan-converts one polygon inside the area with the z-buffer's fill rule.
    fn scan_convert(&mut self, a: &Area, poly: u32) {
        let pts = &self.screen.corners(&self.screen.polys[poly as usize]);
        let w = self.s.width;
        for j in a.j0..a.j1 {
            sample::row_crossings(&self.s, pts, j, &self.fb, &mut self.crossings);
            for pair in self.crossings.chunks_exact(2) {
                let (c0, c1) = (pair[0].max(a.i0), pair[1].min(a.i1));
                if c0 < c1 {
                    self.out[(j * w + c0) as usize..(j * w + c1) as usize].fill(poly);
                }
            }
        }
    }

    /// Renders area `a`, whose parent's list is `self.lists[parent]`.
    fn area(&mut self, a: Area, parent: std::ops::Range<usize>) {
        self.stats.areas += 1;
        let r = a.rect(&self.s);
        let start = self.lists.len();
        for k in parent {
            let e = self.lists[k];
            if e.surrounding {
                self.lists.push(e);
                continue;
            }
            match self.classify(e.poly, &a, &r) {
                Class::Disjoint => {}
                Class::Surrounding => self.lists.push(Entry {
                    poly: e.poly,
                    surrounding: true,
                }),
                Class::Crossing => self.lists.push(e),
            }
        }
        self.decide(a, start);
        self.lists.truncate(start);
    }

    /// The trivial cases, or subdivision, for area `a` whose list is `self.lists[start..]`.
    fn decide(&mut self, a: Area, start: usize) {
        let corners = (a.i0, a.j0, a.i1 - 1, a.j1 - 1);
        // Case 3: the nearest surrounding polygon at the first sample hides what it beats at the
        // four corners.
        let front = self.lists[start..]
            .iter()
            .filter(|e| e.surrounding)
            .map(|e| e.poly)
            .reduce(|best, p| {
                if self.order.wins_at(p, best, a.i0, a.j0) {
                    p
                } else {
                    best
                }
            });
        let mut hidden_here = 0;
        if let Some(front) = front {
            let mut keep = start;
            for k in start..self.lists.len() {
                let e = self.lists[k];
                let (i0, j0, i1, j1) = corners;
                if e.poly != front && self.order.wins_on_rect(front, e.poly, i0, j0, i1, j1) {
                    hidden_here += 1;
                } else {
                    self.lists[keep] = e;
                    keep += 1;
                }
            }
            self.lists.truncate(keep);
            self.stats.hidden_removed += hidden_here;
        }
        let n = self.lists.len() - start;
        if n == 0 {
            // Case 1.
            self.stats.empty_areas += 1;
            return;
        }
        if n == 1 {
            // Case 2 (or case 3 with the surrounding polygon left alone).
            let e = self.lists[start];
            if e.surrounding {
                if hidden_here > 0 {
                    self.stats.surrounding_in_front += 1;
                } else {
                    self.stats.single_polygon_areas += 1;
                }
                self.fill(&a, e.poly);
            } else {
                self.stats.single_polygon_areas += 1;
                self.scan_convert(&a, e.poly);
            }
            return;
        }
        if a.i1 - a.i0 == 1 && a.j1 - a.j0 == 1 {
            // Case 4: one pixel, decided at its centre.
            self.stats.pixel_areas += 1;
            let (i, j) = (a.i0, a.j0);
            let mut best: Option<u32> = None;
            for k in start..self.lists.len() {
                let e = self.lists[k];
                let pts = &self.screen.corners(&self.screen.polys[e.poly as usize]);
                if !e.surrounding && !sample::covers(&self.s, pts, i, j, &self.fb) {
                    continue;
                }
                best = Some(match best {
                    Some(b) if !self.order.wins_at(e.poly, b, i, j) => b,
                    _ => e.poly,
                });
            }
            if let Some(b) = best {
                self.out[(j * self.s.width + i) as usize] = b;
            }
            return;
        }
        // Case 5: four sub-areas (two when the area is one pixel thin).
        self.stats.subdivisions += 1;
        let im = a.i0 + (a.i1 - a.i0 + 1) / 2;
        let jm = a.j0 + (a.j1 - a.j0 + 1) / 2;
        let list = start..self.lists.len();
        for (i0, i1) in [(a.i0, im), (im, a.i1)] {
            for (j0, j1) in [(a.j0, jm), (jm, a.j1)] {
                if i0 < i1 && j0 < j1 {
                    self.area(Area { i0, j0, i1, j1 }, list.clone());
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An independent reference for "the closed segment meets the closed rectangle": an endpoint
    /// inside it, or the segment meeting one of its sides (exact orientation tests).
    fn reference(p: [i128; 2], q: [i128; 2], r: &Rect) -> bool {
        let inside = |v: [i128; 2]| r.x0 <= v[0] && v[0] <= r.x1 && r.y0 <= v[1] && v[1] <= r.y1;
        if inside(p) || inside(q) {
            return true;
        }
        let w = crate::exact::w256;
        let orient = |a: [i128; 2], b: [i128; 2], c: [i128; 2]| match (w(b[0] - a[0])
            * w(c[1] - a[1]))
        .cmp(&(w(b[1] - a[1]) * w(c[0] - a[0])))
        {
            std::cmp::Ordering::Less => -1,
            std::cmp::Ordering::Equal => 0,
            std::cmp::Ordering::Greater => 1,
        };
        let on = |a: [i128; 2], b: [i128; 2], c: [i128; 2]| {
            orient(a, b, c) == 0
                && a[0].min(b[0]) <= c[0]
                && c[0] <= a[0].max(b[0])
                && a[1].min(b[1]) <= c[1]
                && c[1] <= a[1].max(b[1])
        };
        let meets = |a: [i128; 2], b: [i128; 2], c: [i128; 2], d: [i128; 2]| {
            let (d1, d2, d3, d4) = (
                orient(c, d, a),
                orient(c, d, b),
                orient(a, b, c),
                orient(a, b, d),
            );
            (d1 * d2 < 0 && d3 * d4 < 0) || on(c, d, a) || on(c, d, b) || on(a, b, c) || on(a, b, d)
        };
        let c = [[r.x0, r.y0], [r.x1, r.y0], [r.x1, r.y1], [r.x0, r.y1]];
        (0..4).any(|k| meets(p, q, c[k], c[(k + 1) % 4]))
    }

    #[test]
    fn segment_against_rectangle_is_exact_on_touching_cases() {
        let mut seed = 3u64;
        let mut rnd = |m: i128| {
            let mut next = || {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                seed >> 11
            };
            let v = ((next() as u128) << 53) | next() as u128;
            (v % (2 * m as u128 + 1)) as i128 - m
        };
        let mut hits = [0usize; 2];
        for k in 0..200_000 {
            // Small coordinates make touching (corners, sides, collinear) cases common; large
            // ones check the magnitudes.
            let m = if k % 2 == 0 { 6 } else { 1 << 67 };
            let (mut x0, mut x1, mut y0, mut y1) = (rnd(m), rnd(m), rnd(m), rnd(m));
            if x0 > x1 {
                std::mem::swap(&mut x0, &mut x1);
            }
            if y0 > y1 {
                std::mem::swap(&mut y0, &mut y1);
            }
            let r = Rect { x0, x1, y0, y1 };
            let (p, q) = ([rnd(m), rnd(m)], [rnd(m), rnd(m)]);
            let got = segment_meets_rect(p, q, &r);
            assert_eq!(got, reference(p, q, &r), "{p:?} {q:?} {r:?}");
            hits[got as usize] += 1;
        }
        assert!(hits[0] > 10_000 && hits[1] > 10_000, "{hits:?}");
    }
}
