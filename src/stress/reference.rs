//! The slow reference on the kernel's own projected coordinates: the screen polygons' grid
//! corners and support planes (read through [`super::kernel`]), in big rationals.
//!
//! Invariant: at an exact rational point, [`Reference::answer`] names the polygon that contains
//! the point (closed) and is nearest there by the exact depth of its support plane (ties between
//! coplanar polygons by the kernel's rule: the larger face id, then the later polygon), or none;
//! and says whether the point lies in the comparison band: within [`BAND`] of the view width of
//! a polygon edge, or of a line where the nearest polygon's depth equals that of another polygon
//! containing the point (the second nearest's among them). Distances are exact values rounded
//! once; the band only excludes points from the comparison, it decides nothing.

use super::geometry::{Point, Polygon, distance_to_line, nearest};
use super::kernel;
use crate::project::ScreenScene;

/// The band's half-width, as a fraction of the view width.
pub const BAND: f64 = 1e-9;

/// The reference for one screen scene.
pub struct Reference {
    /// The screen polygons, exactly.
    pub polys: Vec<Polygon>,
    /// The band's half-width in grid units.
    pub band: f64,
    /// Half the view's width in grid units (the view is `[-view, view]²`).
    pub view: f64,
    /// The largest |coordinate| of a corner, in grid units (at least the view).
    pub extent: f64,
}

/// The reference's answer at a point.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Answer {
    /// The nearest polygon containing the point (index into the screen polygons).
    pub nearest: Option<usize>,
    /// Is the point within the band of an edge or of a line where the nearest polygon meets
    /// another containing it?
    pub in_band: bool,
}

impl Reference {
    /// The reference of `screen`.
    pub fn of_screen(screen: &ScreenScene) -> Reference {
        let grid = kernel::polygons(screen);
        let view = kernel::grid_scale().0;
        let extent = grid
            .iter()
            .flat_map(|p| p.corners.iter().flatten())
            .map(|c| {
                use num_traits::ToPrimitive;
                c.to_f64().unwrap_or(f64::INFINITY).abs()
            })
            .fold(view, f64::max);
        let margin = extent * 1e-12;
        let polys = grid
            .into_iter()
            .map(|g| {
                let corners = g
                    .corners
                    .into_iter()
                    .map(|[x, y]| Point::integer(x, y))
                    .collect();
                let plane = super::geometry::Plane::new(g.plane);
                Polygon::new(g.face, g.id, corners, plane, margin)
            })
            .collect();
        Reference {
            polys,
            band: BAND * 2.0 * view,
            view,
            extent,
        }
    }

    /// The f64 rounding bound of a point's coordinates (many times over), for prefilters.
    pub fn err(&self, q: [f64; 2]) -> f64 {
        (q[0].abs().max(q[1].abs()) + self.extent) * 1e-12
    }

    /// The answer at p.
    pub fn answer(&self, p: &Point) -> Answer {
        let q = p.to_f64();
        let err = self.err(q);
        let (best, containing) = nearest(&self.polys, p, q, err);
        let on_edge = || {
            self.polys
                .iter()
                .any(|g| g.edge_within(p, q, err, self.band))
        };
        let on_meeting = || {
            let Some(n) = best else { return false };
            let pn = &self.polys[n].plane;
            containing.iter().any(|&g| {
                let pg = &self.polys[g].plane;
                g != n && !pn.same(pg) && distance_to_line(&pn.meeting(pg), p) <= self.band
            })
        };
        Answer {
            nearest: best,
            in_band: on_edge() || on_meeting(),
        }
    }
}
