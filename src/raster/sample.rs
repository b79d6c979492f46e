//! What every image-space renderer decides at one pixel sample, written once so that the
//! A-buffer, the scanline and Warnock decide it exactly as the z-buffer does.
//!
//! Invariants (the z-buffer's, see [`super::zbuffer`]):
//! - **Coverage** ([`row_crossings`], [`covers`]): a polygon covers sample (i, j) when an odd
//!   number of its edges cross row j at a column `<= i`, where an edge covers rows whose sample y
//!   lies in `[y_low, y_high)` and "crosses at column c" means c is the first column whose sample
//!   lies at or to the right of the crossing ([`Samples::first_column_at_or_right`], exact).
//! - **Depth order** ([`DepthOrder::wins`]): at a sample, polygon `a` beats polygon `b` when its
//!   support plane is strictly nearer there, or exactly as near and `(face id, polygon index)` of
//!   `a` is the larger. Decided by the f64 filter of [`DepthPlane`] with the exact 256-bit
//!   [`compare_depth_exact`] behind it. This is a strict total order at every sample, so "the
//!   nearest covering polygon" is well defined and independent of the order polygons come in.
//! - **Linearity** ([`DepthOrder::wins_on_rect`]): the depth difference of two planes is affine in
//!   (i, j), and for either outcome of the tie rule the set of samples where `a` beats `b` is
//!   `{d <= 0}` or `{d < 0}` of that affine `d`: a convex set. So if `a` beats `b` at the corners of
//!   a rectangle of samples it beats `b` at every sample inside. The scanline's span coherence and
//!   Warnock's "surrounding polygon in front" rest on this.

use crate::exact::{DepthPlane, Fallbacks, GridPoint, Samples, compare_depth_exact};
use crate::project::ScreenScene;
use std::cell::Cell;
use std::cmp::Ordering;

use super::EMPTY;

/// Does edge `p → q` cover sample row `j`: `y_low <= y_j < y_high`, exactly?
#[inline]
pub fn edge_covers_row(s: &Samples, p: GridPoint, q: GridPoint, j: i64) -> bool {
    let (lo, hi) = if p.y <= q.y { (p.y, q.y) } else { (q.y, p.y) };
    let yn = s.y_num(j);
    // y_j = yn / H, so lo <= y_j < hi  <=>  lo·H <= yn < hi·H.
    let h = s.height as i128;
    lo as i128 * h <= yn && yn < hi as i128 * h
}

/// The sorted crossing columns of polygon `pts` with sample row `j` (see the module docs): the
/// polygon covers the samples of row j in `[c0, c1) ∪ [c2, c3) ∪ …` (before clipping to the
/// image). Computed edge by edge exactly as the z-buffer does.
pub fn row_crossings(
    s: &Samples,
    pts: &[GridPoint],
    j: i64,
    fallbacks: &Fallbacks,
    out: &mut Vec<i64>,
) {
    out.clear();
    for k in 0..pts.len() {
        let (p, q) = (pts[k], pts[(k + 1) % pts.len()]);
        if edge_covers_row(s, p, q, j) {
            out.push(s.first_column_at_or_right(p, q, j, fallbacks));
        }
    }
    out.sort_unstable();
}

/// Does polygon `pts` cover sample (i, j)? The parity of its crossings of row j at columns
/// `<= i`: the same answer [`row_crossings`] gives, one sample at a time.
pub fn covers(s: &Samples, pts: &[GridPoint], i: i64, j: i64, fallbacks: &Fallbacks) -> bool {
    let mut inside = false;
    for k in 0..pts.len() {
        let (p, q) = (pts[k], pts[(k + 1) % pts.len()]);
        if edge_covers_row(s, p, q, j) && s.first_column_at_or_right(p, q, j, fallbacks) <= i {
            inside = !inside;
        }
    }
    inside
}

/// Rows `[j0, j1)` that may hold samples of polygon `pts`: a superset computed in f64 from its
/// extent in y (the rows the z-buffer scans); the exact edge test decides within it.
pub fn candidate_rows(s: &Samples, pts: &[GridPoint]) -> (i64, i64) {
    let (mut ylo, mut yhi) = (i64::MAX, i64::MIN);
    for p in pts {
        ylo = ylo.min(p.y);
        yhi = yhi.max(p.y);
    }
    let j0 = (s.row_of(yhi as f64) - 1.0).floor().max(0.0) as i64;
    let j1 = (s.row_of(ylo as f64) + 1.0).ceil().min(s.height as f64) as i64;
    (j0, j1)
}

/// The z-buffer's depth order of polygons at samples (see the module docs), with its counters.
pub struct DepthOrder<'a> {
    screen: &'a ScreenScene,
    /// The image's pixel centres.
    pub samples: Samples,
    planes: Vec<DepthPlane>,
    /// Comparisons the f64 filter could not decide.
    pub fallbacks: Cell<u64>,
    /// Exact depth ties settled by the id rule.
    pub ties: Cell<u64>,
}

impl<'a> DepthOrder<'a> {
    /// The depth order of `screen`'s polygons, counters at zero.
    pub fn new(screen: &'a ScreenScene) -> DepthOrder<'a> {
        let samples = Samples::new(screen.width, screen.height);
        let planes = screen
            .polys
            .iter()
            .map(|p| DepthPlane::new(&screen.plane(p), &samples))
            .collect();
        DepthOrder {
            screen,
            samples,
            planes,
            fallbacks: Cell::new(0),
            ties: Cell::new(0),
        }
    }

    /// f64 depth (grid units) of polygon `p` at sample (i, j), within the plane's `err`.
    #[inline]
    pub fn depth(&self, p: u32, i: i64, j: i64) -> f64 {
        self.planes[p as usize].at(i, j)
    }

    /// Does polygon `a` (f64 depth `za` at the sample) beat polygon `b` (`zb`) at sample (i, j)?
    #[inline]
    pub fn wins(&self, a: u32, za: f64, b: u32, zb: f64, i: i64, j: i64) -> bool {
        let diff = za - zb;
        let bound = self.planes[a as usize].err + self.planes[b as usize].err;
        if diff < -bound {
            return true;
        }
        if diff > bound {
            return false;
        }
        self.fallbacks.set(self.fallbacks.get() + 1);
        let (pa, pb) = (
            &self.screen.polys[a as usize],
            &self.screen.polys[b as usize],
        );
        let (plane_a, plane_b) = (self.screen.plane(pa), self.screen.plane(pb));
        match compare_depth_exact(&plane_a, &plane_b, &self.samples, i, j) {
            Ordering::Less => true,
            Ordering::Greater => false,
            Ordering::Equal => {
                self.ties.set(self.ties.get() + 1);
                (pa.id, a) > (pb.id, b)
            }
        }
    }

    /// [`Self::wins`], computing both depths.
    #[inline]
    pub fn wins_at(&self, a: u32, b: u32, i: i64, j: i64) -> bool {
        self.wins(a, self.depth(a, i, j), b, self.depth(b, i, j), i, j)
    }

    /// Does `a` beat `b` at every sample of the rectangle `[i0, i1] x [j0, j1]` (inclusive)?
    /// Checking the corners is enough (linearity, see the module docs).
    pub fn wins_on_rect(&self, a: u32, b: u32, i0: i64, j0: i64, i1: i64, j1: i64) -> bool {
        self.wins_at(a, b, i0, j0)
            && (i1 == i0 || self.wins_at(a, b, i1, j0))
            && (j1 == j0 || self.wins_at(a, b, i0, j1))
            && (i1 == i0 || j1 == j0 || self.wins_at(a, b, i1, j1))
    }

    /// The polygon among `polys` (not empty) that beats all the others at sample (i, j).
    pub fn nearest(&self, polys: impl IntoIterator<Item = u32>, i: i64, j: i64) -> u32 {
        let mut it = polys.into_iter();
        let mut best = it.next().expect("nearest of no polygon");
        let mut zbest = self.depth(best, i, j);
        for p in it {
            let z = self.depth(p, i, j);
            if self.wins(p, z, best, zbest, i, j) {
                (best, zbest) = (p, z);
            }
        }
        best
    }
}

/// The input face id at every pixel of a per-pixel polygon index image (`None` for background).
pub fn face_ids(poly: &[u32], screen: &ScreenScene) -> Vec<Option<u32>> {
    poly.iter()
        .map(|&p| (p != EMPTY).then(|| screen.polys[p as usize].id))
        .collect()
}
