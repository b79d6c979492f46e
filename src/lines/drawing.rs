//! A hidden-line drawing: strokes (polylines) with their visibility and kind, in pixel
//! coordinates (y down, the camera's image), ready for the writers of [`crate::output`].
//!
//! Invariants of every [`LineDrawing`] the lines stage makes:
//! - every point is finite and is the correctly rounded f64 image of an exact grid point (one
//!   rounding per exact point: a point shared by strokes has the same bits in each);
//! - a stroke has at least two points and no two consecutive points equal; a closed stroke
//!   does not repeat its first point at the end;
//! - strokes are in a deterministic order: by (visibility, kind), then as the chaining made
//!   them (or as `--order plotter` put them).

use serde::Serialize;

/// What a line is, in order of precedence: an edge of two kinds is drawn once, as the first
/// kind it has in this order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LineKind {
    /// The contour: an edge between a face seen from the front and one seen from the back (or
    /// edge-on).
    Silhouette,
    /// An edge of one face only, or of three or more (non-manifold).
    Boundary,
    /// Where two faces pass through each other.
    Intersection,
    /// An edge where the normals of its two faces differ by more than the crease angle.
    Crease,
    /// An edge between two faces of different materials.
    Material,
}

impl LineKind {
    /// Every kind, in precedence order.
    pub const ALL: [LineKind; 5] = [
        LineKind::Silhouette,
        LineKind::Boundary,
        LineKind::Intersection,
        LineKind::Crease,
        LineKind::Material,
    ];

    /// The lowercase name used in SVG classes, `data-kind`, JSON and DXF.
    pub fn name(self) -> &'static str {
        match self {
            LineKind::Silhouette => "silhouette",
            LineKind::Boundary => "boundary",
            LineKind::Intersection => "intersection",
            LineKind::Crease => "crease",
            LineKind::Material => "material",
        }
    }
}

/// Whether a stroke is seen.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Visibility {
    /// No face lies in front of it.
    Visible,
    /// Some face lies in front of it.
    Hidden,
}

impl Visibility {
    /// `visible` or `hidden`, as in SVG classes and DXF layer names (upper case there).
    pub fn name(self) -> &'static str {
        match self {
            Visibility::Visible => "visible",
            Visibility::Hidden => "hidden",
        }
    }
}

/// One stroke: a polyline of one visibility and kind.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stroke {
    /// Seen or hidden.
    pub visibility: Visibility,
    /// What line it is.
    pub kind: LineKind,
    /// Quantitative invisibility: how many faces lie in front of it (0 when visible). Set when
    /// the drawing was asked for it (`--qi-max`), otherwise 1 for every hidden stroke, meaning
    /// "at least one".
    pub qi: u32,
    /// Its points in pixels (y down), at least two.
    pub points: Vec<[f64; 2]>,
    /// Whether the last point joins back to the first.
    pub closed: bool,
}

impl Stroke {
    /// Its length in pixels.
    pub fn length(&self) -> f64 {
        let seg = |a: &[f64; 2], b: &[f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
        let open: f64 = self.points.windows(2).map(|w| seg(&w[0], &w[1])).sum();
        match (self.closed, self.points.first(), self.points.last()) {
            (true, Some(f), Some(l)) => open + seg(l, f),
            _ => open,
        }
    }
}

/// A hidden-line drawing of one view.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct LineDrawing {
    /// Image width in pixels (the camera's).
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The strokes.
    pub strokes: Vec<Stroke>,
}
