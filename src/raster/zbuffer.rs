//! The z-buffer: the reference every other method is checked against.
//!
//! Invariants of the [`ZBuffer`] it produces:
//! - **Sampling**: pixel (i, j) shows what lies at its centre, exactly (see
//!   [`Samples`]); no anti-aliasing.
//! - **Fill rule**: a sample is inside a polygon when an odd number of its edges cross the
//!   sample's row strictly to the right of it, an edge covering rows `[y_low, y_high)`. Polygons
//!   that share an edge therefore never both cover, nor both miss, a sample on it: no cracks and
//!   no double coverage (the sample goes to the polygon on its right, or above it for a horizontal
//!   edge).
//! - **Depth**: the nearest polygon at the sample wins, decided exactly from the polygons'
//!   support planes (f64 filter, exact 256-bit fallback). Exactly equal depths (coplanar overlap)
//!   go to the larger face id, then the later polygon: deterministic whatever the input order.

use crate::exact::{DepthPlane, Fallbacks, Samples, compare_depth_exact, depth_ndc};
use crate::project::ScreenScene;
use std::cmp::Ordering;

/// Marks a pixel that no polygon covers.
pub const EMPTY: u32 = u32::MAX;

/// The result of z-buffering: per pixel the index of the winning [`ScreenPoly`] (or [`EMPTY`]).
///
/// [`ScreenPoly`]: crate::project::ScreenPoly
#[derive(Clone, Debug)]
pub struct ZBuffer {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Row-major, row 0 at the top: index into `ScreenScene::polys`, or [`EMPTY`].
    pub poly: Vec<u32>,
    /// f64 depth (grid units) of the winner; only meaningful where `poly` is not `EMPTY`.
    depth: Vec<f64>,
    /// Counters of the run.
    pub stats: ZBufferStats,
}

/// Work counters.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ZBufferStats {
    /// Samples covered by some polygon (before the depth test).
    pub fragments: u64,
    /// Edge-crossing computations the f64 filter could not decide.
    pub column_fallbacks: u64,
    /// Depth comparisons the f64 filter could not decide.
    pub depth_fallbacks: u64,
    /// Exact depth ties resolved by the id rule.
    pub depth_ties: u64,
}

/// Renders `screen` into a z-buffer. `progress` is called with the number of polygons done.
pub fn render(screen: &ScreenScene, mut progress: impl FnMut(usize)) -> ZBuffer {
    let (w, h) = (screen.width as usize, screen.height as usize);
    let s = Samples::new(screen.width, screen.height);
    let mut zb = ZBuffer {
        width: screen.width,
        height: screen.height,
        poly: vec![EMPTY; w * h],
        depth: vec![0.0; w * h],
        stats: ZBufferStats::default(),
    };
    let planes: Vec<DepthPlane> = screen
        .polys
        .iter()
        .map(|p| DepthPlane::new(&screen.plane(p), &s))
        .collect();
    let fallbacks = Fallbacks::default();
    let mut crossings: Vec<i64> = Vec::with_capacity(8);

    for (pi, poly) in screen.polys.iter().enumerate() {
        if pi % 65536 == 0 {
            progress(pi);
        }
        let pts = &screen.corners(poly);
        let (mut ylo, mut yhi) = (i64::MAX, i64::MIN);
        for p in pts {
            ylo = ylo.min(p.y);
            yhi = yhi.max(p.y);
        }
        // Rows whose sample y may lie in [ylo, yhi); the exact edge test below decides.
        let j0 = (s.row_of(yhi as f64) - 1.0).floor().max(0.0) as i64;
        let j1 = (s.row_of(ylo as f64) + 1.0).ceil().min(h as f64) as i64;
        let dp = &planes[pi];
        for j in j0..j1 {
            let yn = s.y_num(j);
            crossings.clear();
            for k in 0..pts.len() {
                let (p, q) = (pts[k], pts[(k + 1) % pts.len()]);
                let (lo, hi) = if p.y <= q.y { (p.y, q.y) } else { (q.y, p.y) };
                // lo <= y_j < hi, with y_j = yn / H.
                if lo as i128 * s.height as i128 <= yn && yn < hi as i128 * s.height as i128 {
                    crossings.push(s.first_column_at_or_right(p, q, j, &fallbacks));
                }
            }
            if crossings.len() < 2 {
                continue;
            }
            crossings.sort_unstable();
            for pair in crossings.chunks_exact(2) {
                let i0 = pair[0].max(0);
                let i1 = pair[1].min(w as i64);
                let row = j as usize * w;
                for i in i0..i1 {
                    zb.stats.fragments += 1;
                    let idx = row + i as usize;
                    let z = dp.at(i, j);
                    let cur = zb.poly[idx];
                    let wins = if cur == EMPTY {
                        true
                    } else {
                        let diff = z - zb.depth[idx];
                        let bound = dp.err + planes[cur as usize].err;
                        if diff < -bound {
                            true
                        } else if diff > bound {
                            false
                        } else {
                            zb.stats.depth_fallbacks += 1;
                            let other = &screen.polys[cur as usize];
                            let (mine, theirs) = (screen.plane(poly), screen.plane(other));
                            match compare_depth_exact(&mine, &theirs, &s, i, j) {
                                Ordering::Less => true,
                                Ordering::Greater => false,
                                Ordering::Equal => {
                                    zb.stats.depth_ties += 1;
                                    (poly.id, pi) > (other.id, cur as usize)
                                }
                            }
                        }
                    };
                    if wins {
                        zb.poly[idx] = pi as u32;
                        zb.depth[idx] = z;
                    }
                }
            }
        }
    }
    progress(screen.polys.len());
    zb.stats.column_fallbacks = fallbacks.column.get();
    zb
}

impl ZBuffer {
    /// The input face id at every pixel (`None` for background).
    pub fn face_ids(&self, screen: &ScreenScene) -> Vec<Option<u32>> {
        self.poly
            .iter()
            .map(|&p| (p != EMPTY).then(|| screen.polys[p as usize].id))
            .collect()
    }

    /// Normalized depth in [0, 1] (0 at the near plane, 1 at the far plane) at every pixel,
    /// computed exactly from the winner's plane and rounded once; background is 1.
    pub fn normalized_depth(&self, screen: &ScreenScene) -> Vec<f64> {
        let s = Samples::new(self.width, self.height);
        let w = self.width as usize;
        let planes = screen.planes();
        self.poly
            .iter()
            .enumerate()
            .map(|(idx, &p)| {
                if p == EMPTY {
                    1.0
                } else {
                    let (i, j) = ((idx % w) as i64, (idx / w) as i64);
                    let z = depth_ndc(&planes[p as usize], &s, i, j);
                    ((z + 1.0) / 2.0).clamp(0.0, 1.0)
                }
            })
            .collect()
    }
}
