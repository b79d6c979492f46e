//! Hidden-line drawings: the feature lines of a scene, split exactly where their visibility
//! changes, chained into strokes.
//!
//! Stages, one module each:
//! 1. [`features`]: which mesh edges are lines, and of which kind (silhouette, boundary,
//!    crease, material), with vertices at identical positions welded.
//! 2. [`intersections`]: where faces pass through each other, exactly.
//! 3. [`tracks`]: where each line is seen, read off the exact visible set, split exactly where
//!    that changes, with quantitative invisibility when asked ([`along`]: exact points on a
//!    line and their order).
//! 4. [`chain`]: strokes, as few as the graph allows; [`plot_order`] for pen plotters.
//!
//! The result is a [`LineDrawing`], written by `crate::output` as SVG, JSON, DXF or PDF.

pub mod along;
pub mod chain;
pub mod drawing;
pub mod features;
pub mod intersections;
pub mod plot_order;
pub mod tracks;

pub use drawing::{LineDrawing, LineKind, Stroke, Visibility};

use crate::camera::Camera;
use crate::exact::polygon::Piece;
use crate::exact::predicates::Line;
use crate::exact::{GridPoint, Plane, Samples};
use crate::pipeline::Prepared;
use crate::progress::Report;
use crate::project::{CullMode, Orientation, ScreenScene, Side, project, snap_point, snap_segment};
use crate::scene::Scene;
use crate::visibility::{CoverageMap, Strategy};
use along::At;
use intersections::FlatFace;
use rustc_hash::FxHashMap as HashMap;
use tracks::{SeenRule, Segment, Track, TrackIndex, mark_occluded, mark_seen};

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
    /// The least number of strokes that could draw the lines (per visibility and kind).
    pub paths_minimum: usize,
}

/// A line drawing with its counters.
#[derive(Clone, Debug, Default)]
pub struct Lines {
    /// The drawing.
    pub drawing: LineDrawing,
    /// What it took.
    pub stats: LineStats,
}

/// The line drawing of `scene` seen by `camera`: the exact visible set (the coverage map,
/// every face opaque), then [`lines_of`].
pub fn line_drawing(
    scene: &Scene,
    camera: &Camera,
    options: &LineOptions,
    report: Option<Report>,
) -> crate::Result<Lines> {
    let prepared = crate::pipeline::prepare(scene, camera, options.cull);
    // The lines themselves need no visible set: made on a second thread meanwhile.
    let (visible, lines) = std::thread::scope(|s| {
        let lines = s.spawn(|| line_tracks(scene, camera, &prepared, options));
        let visible = CoverageMap.visible_set(&prepared.screen, &|_| false, report);
        (
            visible,
            lines.join().expect("the line tracks thread does not panic"),
        )
    });
    let (exact, stats) = read_visibility(lines, camera, &prepared.screen, &visible.pieces, options);
    Ok(drawn(exact, stats, camera))
}

/// Chains the segments into strokes.
fn drawn(exact: ExactLines, mut stats: LineStats, camera: &Camera) -> Lines {
    let (strokes, minimum) = chain::strokes_and_minimum(&exact.segments);
    stats.paths_minimum = minimum;
    Lines {
        drawing: LineDrawing {
            width: camera.width,
            height: camera.height,
            strokes,
        },
        stats,
    }
}

/// The line drawing of `scene` seen by `camera`, read off `pieces`: the exact visible pieces
/// of `prepared.screen` (projected with `options.cull`) with every face opaque (any exact
/// strategy's `VisibleSet::pieces`).
pub fn lines_of(
    scene: &Scene,
    camera: &Camera,
    prepared: &Prepared,
    pieces: &[Piece],
    options: &LineOptions,
) -> Lines {
    let (exact, stats) = exact_lines(scene, camera, prepared, pieces, options);
    drawn(exact, stats, camera)
}

/// The lines before chaining: every track and the segments drawn, with exact ends.
#[derive(Clone, Debug, Default)]
pub struct ExactLines {
    /// Every line of the view: feature edges that show on screen, then intersections.
    pub tracks: Vec<Track>,
    /// The segments drawn, each with the track it draws.
    pub segments: Vec<Segment>,
}

/// The tracks and segments of [`lines_of`], before chaining.
pub fn exact_lines(
    scene: &Scene,
    camera: &Camera,
    prepared: &Prepared,
    pieces: &[Piece],
    options: &LineOptions,
) -> (ExactLines, LineStats) {
    let lines = line_tracks(scene, camera, prepared, options);
    read_visibility(lines, camera, &prepared.screen, pieces, options)
}

/// Every line of the view, before any visibility: what [`line_tracks`] gives
/// [`read_visibility`]. It needs no visible set, so it can be made while one is computed.
pub struct LineTracks {
    tracks: Vec<Track>,
    of_side: Vec<u32>,
    of_cut: HashMap<[Plane; 2], u32>,
    stats: LineStats,
}

/// The tracks of the feature edges and intersections of `scene` seen by `camera`.
pub fn line_tracks(
    scene: &Scene,
    camera: &Camera,
    prepared: &Prepared,
    options: &LineOptions,
) -> LineTracks {
    let screen = &prepared.screen;
    let features = features::features(scene, screen, options.crease_deg);
    let m = camera.view_projection();
    let mut stats = LineStats {
        vertices: features.vertices,
        ..LineStats::default()
    };
    let mut on_screen = vec![false; scene.faces.len()];
    for poly in &screen.polys {
        on_screen[poly.face as usize] = true;
    }
    // One track per feature edge that shows on screen.
    let mut tracks = Vec::new();
    let mut track_of_edge = vec![u32::MAX; features.edges.len()];
    for (e, edge) in features.edges.iter().enumerate() {
        stats.features[edge.kind as usize] += 1;
        let [a, b] = edge.ends.map(|i| scene.positions[i as usize]);
        let Some([p, q]) = snap_segment(&m, a, b) else {
            continue;
        };
        let Some(line) = Line::edge(p, q) else {
            continue;
        };
        track_of_edge[e] = tracks.len() as u32;
        let ends = (At::Grid([p.x, p.y]), At::Grid([q.x, q.y]));
        let mut faces: Vec<u32> = edge.sides.iter().map(|s| s.face).collect();
        faces.dedup();
        let rule = if faces.iter().any(|&f| on_screen[f as usize]) {
            SeenRule::BesideAFace
        } else if options.cull == CullMode::Auto
            && !faces
                .iter()
                .any(|&f| screen.orientation[f as usize] == Orientation::Flat)
        {
            // Every face of it is a back face culled by `--cull auto`, which culls only closed,
            // consistently oriented meshes the near plane does not cut: it lies on the far
            // side of a closed mesh.
            SeenRule::Behind
        } else {
            SeenRule::Unoccluded
        };
        tracks.push(Track::new(
            line,
            edge.kind,
            faces,
            intersections::plane_along(p, q),
            vec![ends],
            rule,
        ));
    }
    // Every screen side's track.
    let mut of_side = vec![u32::MAX; screen.corner_points.len()];
    for poly in &screen.polys {
        let face = &scene.faces[poly.face as usize];
        for (j, side) in screen.sides(poly).iter().enumerate() {
            if let Side::Edge(k) = side {
                let e = features.edge_of_side[(face.start + k) as usize];
                if e != u32::MAX {
                    of_side[poly.start as usize + j] = track_of_edge[e as usize];
                }
            }
        }
    }
    // Intersections, back faces included: a hidden one is drawn too.
    let all_faces;
    let unculled = if options.cull == CullMode::Off {
        screen
    } else {
        // This runs beside the visible set, which has the rayon pool: `project`'s parallel
        // chunks would each wait there behind a strip. A pool of one thread of its own runs
        // it through, as on one core.
        let unculled = || project(scene, &prepared.analysis, camera, CullMode::Off);
        all_faces = match rayon::ThreadPoolBuilder::new().num_threads(1).build() {
            Ok(pool) => pool.install(unculled),
            Err(_) => unculled(),
        };
        &all_faces
    };
    let flats = flat_faces(scene, screen, &m);
    let mut of_cut = HashMap::default();
    for meeting in intersections::meetings(scene, unculled, &flats, &features.weld) {
        stats.features[LineKind::Intersection as usize] += 1;
        let t = tracks.len() as u32;
        if let Some(planes) = meeting.planes {
            of_cut.insert(planes, t);
        }
        tracks.push(Track::new(
            meeting.line,
            LineKind::Intersection,
            meeting.faces.to_vec(),
            meeting.depth,
            meeting.extent,
            if meeting.edge_on {
                SeenRule::Unoccluded
            } else {
                SeenRule::BesideBothFaces
            },
        ));
    }
    LineTracks {
        tracks,
        of_side,
        of_cut,
        stats,
    }
}

/// Where the lines are seen, read off `pieces` (the visible set of `screen`), and the segments
/// drawn.
pub fn read_visibility(
    lines: LineTracks,
    camera: &Camera,
    screen: &ScreenScene,
    pieces: &[Piece],
    options: &LineOptions,
) -> (ExactLines, LineStats) {
    let LineTracks {
        mut tracks,
        of_side,
        of_cut,
        stats,
    } = lines;
    let samples = Samples::new(camera.width, camera.height);
    let index = TrackIndex {
        of_side: &of_side,
        of_cut: &of_cut,
    };
    mark_seen(screen, pieces, &index, &mut tracks);
    mark_occluded(pieces, &mut tracks);
    if options.hidden && options.qi_max.is_some() {
        tracks::mark_faces_in_front(screen, &mut tracks);
    }
    let segments = tracks::segments(&tracks, &samples, options);
    (ExactLines { tracks, segments }, stats)
}

/// The faces seen exactly edge-on whose corners are all unclipped, with their snapped corners
/// (at least two distinct on screen).
fn flat_faces(scene: &Scene, screen: &ScreenScene, m: &glam::DMat4) -> Vec<FlatFace> {
    let mut out = Vec::new();
    for (f, face) in scene.faces.iter().enumerate() {
        if screen.orientation[f] != Orientation::Flat {
            continue;
        }
        let corners: Option<Vec<GridPoint>> = scene
            .face_positions(face)
            .map(|p| snap_point(m, p))
            .collect();
        let Some(corners) = corners else { continue };
        // Edge-on: every corner on one screen line (no area can also mean a bow tie).
        let Some(&far) = corners
            .iter()
            .find(|c| (c.x, c.y) != (corners[0].x, corners[0].y))
        else {
            continue;
        };
        let on_line =
            |c: &GridPoint| crate::exact::predicates::orient2d(corners[0], far, *c).is_eq();
        if corners.iter().all(on_line) {
            out.push(FlatFace {
                face: f as u32,
                corners,
            });
        }
    }
    out
}
