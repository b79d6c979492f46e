//! Hidden-line drawings: the feature lines of a scene, split exactly where their visibility
//! changes, chained into strokes.
//!
//! Stages, one module each:
//! 1. [`features`]: which mesh edges are lines, and of which kind (silhouette, boundary,
//!    crease, material), with vertices at identical positions welded.
//! 2. visibility along the lines, read off the exact visible set (work in progress: see
//!    PROGRESS.md).
//! 3. chaining into strokes.
//!
//! The result is a [`LineDrawing`], written by `crate::output` as SVG, JSON, DXF or PDF.

pub mod drawing;
pub mod features;
pub mod plot_order;

pub use drawing::{LineDrawing, LineKind, Stroke, Visibility};

use crate::camera::Camera;
use crate::exact::Samples;
use crate::progress::Report;
use crate::project::{CullMode, snap_segment};
use crate::scene::Scene;

/// What a line drawing shows.
#[derive(Clone, Debug, PartialEq)]
pub struct LineOptions {
    /// An edge is a crease when its faces' normals differ by more than this many degrees.
    pub crease_deg: f64,
    /// Draw the hidden parts of lines.
    pub hidden: bool,
    /// Draw hidden parts only up to this many faces deep, with their exact quantitative
    /// invisibility; `None`: every hidden part, as "at least one face in front".
    pub qi_max: Option<u32>,
    /// Back-face culling for the visible set the lines are read from.
    pub cull: CullMode,
}

impl Default for LineOptions {
    fn default() -> Self {
        LineOptions {
            crease_deg: 30.0,
            hidden: true,
            qi_max: None,
            cull: CullMode::Auto,
        }
    }
}

/// What the lines stage did, counted.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LineStats {
    /// Welded vertices of the scene.
    pub vertices: usize,
    /// Feature edges of each kind, in [`LineKind::ALL`] order (intersections: segments).
    pub features: [usize; 5],
}

/// A line drawing with its counters.
#[derive(Clone, Debug, Default)]
pub struct Lines {
    /// The drawing.
    pub drawing: LineDrawing,
    /// What it took.
    pub stats: LineStats,
}

/// The line drawing of `scene` seen by `camera`.
pub fn line_drawing(
    scene: &Scene,
    camera: &Camera,
    options: &LineOptions,
    _report: Option<Report>,
) -> crate::Result<Lines> {
    let prepared = crate::pipeline::prepare(scene, camera, options.cull);
    let features = features::features(scene, &prepared.screen, options.crease_deg);
    let samples = Samples::new(camera.width, camera.height);
    let m = camera.view_projection();
    let mut stats = LineStats {
        vertices: features.vertices,
        ..LineStats::default()
    };
    let mut strokes = Vec::new();
    for edge in &features.edges {
        stats.features[edge.kind as usize] += 1;
        let [a, b] = edge.ends.map(|i| scene.positions[i as usize]);
        let Some([p, q]) = snap_segment(&m, a, b) else {
            continue;
        };
        if (p.x, p.y) == (q.x, q.y) {
            continue;
        }
        let px =
            |g: crate::exact::GridPoint| [samples.col_of(g.x as f64), samples.row_of(g.y as f64)];
        strokes.push(Stroke {
            visibility: Visibility::Visible,
            kind: edge.kind,
            qi: 0,
            points: vec![px(p), px(q)],
            closed: false,
        });
    }
    strokes.sort_by_key(|s| (s.visibility, s.kind));
    Ok(Lines {
        drawing: LineDrawing {
            width: camera.width,
            height: camera.height,
            strokes,
        },
        stats,
    })
}
