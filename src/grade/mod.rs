//! Grading a face-id image made by any renderer (`sightline compare --image`) against the
//! exact visible set at the same camera.
//!
//! The truth is the exact visible set of the screen scene with every face opaque (the coverage
//! map, as for `--fill id`), as a set of closed convex pieces, each of one face.
//!
//! **Pixel error.** A pixel is right when the face id it shows is a face whose closed piece
//! contains the pixel centre, or when it shows background and the centre is not inside the
//! union of the pieces (outside every piece, or on the outline of the union). Deciding this is
//! exact: the centre is tested against every line of every piece with the kernel's predicates
//! (no epsilon), and where it lies on some pieces' lines, the union of those pieces' tangent
//! cones at the centre decides whether it covers a neighbourhood ([`cones_cover_every_direction`]).
//! So a correct renderer with a different tie rule for a centre exactly on an edge or a vertex
//! scores 0 wrong pixels, and a crack between two faces that meet at a centre does not. A pixel
//! is wrong otherwise; wrong pixels are one of: a wrong face (a face of the scene, not one at
//! the centre, where the truth covers it), a missing face (background where the truth covers
//! the centre's neighbourhood), an extra face (a face where the truth has only background), or
//! an unknown id (a number that is no face id of the scene; wrong wherever it is).
//!
//! **Area error**: the fraction of the image area given to the wrong face, as the benchmark
//! measures it ([`crate::benchmark::truth::error_of`], with its stated f64 bound): each pixel
//! counts 1 − the area fraction of the face it shows (an unknown id: 1).
//!
//! Invariants: the counts depend only on the scene, the camera and the image; the categories
//! are disjoint and add up to the wrong pixels; the image of our exact z-buffer (which samples
//! pixel centres exactly) has no wrong pixel.

pub mod id_png;

use crate::exact::Samples;
use crate::exact::predicates::{Wide, line_side};
use crate::pipeline::{DIFF_COVERAGE, DIFF_MISMATCH, diff_grey};
use crate::project::ScreenScene;
use crate::scene::Scene;
use crate::visibility::{CoverageMap, Strategy, VisibleSet};
use bnum::cast::As;
use std::cmp::Ordering;

/// What the exact visible set holds at one pixel centre.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CentreTruth {
    /// No piece contains the centre: only background is right.
    Background,
    /// The centre is inside one piece of this face, off its boundary: only this face is right.
    Face(u32),
    /// The centre lies on the boundary of some pieces: any of their faces is right, and so is
    /// background when `background_right` (the centre is on the outline of the union).
    Tie {
        /// The faces whose closed pieces contain the centre, increasing.
        faces: Vec<u32>,
        /// The centre is not inside the union of the pieces.
        background_right: bool,
    },
}

impl CentreTruth {
    /// Is showing `shown` (`None`: background) at this centre right?
    pub fn accepts(&self, shown: Option<u32>) -> bool {
        match (self, shown) {
            (CentreTruth::Background, None) => true,
            (CentreTruth::Face(f), Some(g)) => *f == g,
            (CentreTruth::Tie { faces, .. }, Some(g)) => faces.binary_search(&g).is_ok(),
            (
                CentreTruth::Tie {
                    background_right, ..
                },
                None,
            ) => *background_right,
            _ => false,
        }
    }

    /// Does some closed piece contain the centre?
    pub fn covered(&self) -> bool {
        !matches!(self, CentreTruth::Background)
    }

    /// One face right at the centre (the least id at a tie), for pictures.
    pub fn face(&self) -> Option<u32> {
        match self {
            CentreTruth::Background => None,
            CentreTruth::Face(f) => Some(*f),
            CentreTruth::Tie { faces, .. } => faces.first().copied(),
        }
    }
}

/// [`CentreTruth`] at every pixel centre of an image (row-major, row 0 at the top), 8 bytes a
/// pixel: centres on a boundary, which are rare, keep their faces in a side table.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CentreTruths {
    cells: Vec<Cell>,
    ties: Vec<(Vec<u32>, bool)>,
}

/// One centre: background, one face, or a tie (index into `CentreTruths::ties`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Cell {
    Background,
    Face(u32),
    Tie(u32),
}

impl CentreTruths {
    /// The number of centres.
    pub fn len(&self) -> usize {
        self.cells.len()
    }

    /// No centres at all (an empty image).
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }

    /// The truth at centre `k`.
    pub fn get(&self, k: usize) -> CentreTruth {
        match self.cells[k] {
            Cell::Background => CentreTruth::Background,
            Cell::Face(f) => CentreTruth::Face(f),
            Cell::Tie(t) => {
                let (faces, background_right) = &self.ties[t as usize];
                CentreTruth::Tie {
                    faces: faces.clone(),
                    background_right: *background_right,
                }
            }
        }
    }

    /// Is showing `shown` (`None`: background) at centre `k` right? ([`CentreTruth::accepts`])
    pub fn accepts(&self, k: usize, shown: Option<u32>) -> bool {
        match (self.cells[k], shown) {
            (Cell::Background, None) => true,
            (Cell::Face(f), Some(g)) => f == g,
            (Cell::Tie(t), shown) => {
                let (faces, background_right) = &self.ties[t as usize];
                match shown {
                    Some(g) => faces.binary_search(&g).is_ok(),
                    None => *background_right,
                }
            }
            _ => false,
        }
    }

    /// Does some closed piece contain centre `k`?
    pub fn covered(&self, k: usize) -> bool {
        self.cells[k] != Cell::Background
    }

    /// Does centre `k` lie on a boundary of the truth?
    pub fn is_tie(&self, k: usize) -> bool {
        matches!(self.cells[k], Cell::Tie(_))
    }
}

/// How one pixel of the graded image compares with the truth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// A face (or background) right at the centre.
    Right,
    /// A face of the scene that is not one at the centre, where the truth covers it.
    WrongFace,
    /// Background where the truth covers the centre's neighbourhood.
    MissingFace,
    /// A face of the scene where the truth has only background.
    ExtraFace,
    /// A number that is no face id of the scene.
    UnknownId,
}

/// The counts of a graded image. See the module docs for the definitions.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Grade {
    /// Pixels in the image.
    pub pixels: usize,
    /// Pixels the image gives a face (any non-background value).
    pub image_covered: usize,
    /// Pixels whose centre some closed piece of the truth contains.
    pub exact_covered: usize,
    /// Pixels whose centre lies on a boundary of the truth, where more than one answer is right.
    pub ties: usize,
    /// Wrong pixels: the sum of the four kinds below.
    pub wrong: usize,
    /// Wrong pixels showing a wrong face where the truth covers the centre.
    pub wrong_face: usize,
    /// Wrong pixels showing background where the truth covers the centre's neighbourhood.
    pub missing_face: usize,
    /// Wrong pixels showing a face where the truth has background.
    pub extra_face: usize,
    /// Wrong pixels showing a number that is no face id of the scene.
    pub unknown_id: usize,
    /// The fraction of the image area given to the wrong face, in [0, 1].
    pub area_error: f64,
}

/// A graded image: the counts, and each pixel's truth and verdict (row-major, row 0 at the top).
#[derive(Clone, Debug)]
pub struct Graded {
    /// The counts.
    pub grade: Grade,
    /// The truth at each pixel centre.
    pub truth: CentreTruths,
    /// Each pixel's verdict.
    pub verdicts: Vec<Verdict>,
}

/// Colour of a pixel whose id is no face of the scene, in [`Graded::diff_image`].
pub const DIFF_UNKNOWN: [u8; 3] = [255, 0, 255];

impl Graded {
    /// A picture of where the image is wrong (row-major RGB), in `compare --diff`'s colours:
    /// [`DIFF_MISMATCH`] (red) for a wrong face, [`DIFF_COVERAGE`] (blue) for a missing or
    /// extra face, [`DIFF_UNKNOWN`] (magenta) for an unknown id; right pixels show the face
    /// they show in grey (one level per face id, as [`crate::pipeline::diff_image`]), or white
    /// for background.
    pub fn diff_image(&self, ids: &[Option<u32>]) -> Vec<[u8; 3]> {
        self.verdicts
            .iter()
            .zip(ids)
            .map(|(v, id)| match (v, id) {
                (Verdict::WrongFace, _) => DIFF_MISMATCH,
                (Verdict::MissingFace | Verdict::ExtraFace, _) => DIFF_COVERAGE,
                (Verdict::UnknownId, _) => DIFF_UNKNOWN,
                (Verdict::Right, Some(id)) => diff_grey(*id),
                (Verdict::Right, None) => [255; 3],
            })
            .collect()
    }
}

/// Grades `ids` (the face id at each pixel of a `screen.width x screen.height` image, row-major
/// from the top; `None` for background) against the exact visible set of `screen`, every face
/// opaque. `scene` tells which ids are faces. An image of another size is graded as if its
/// pixels were cut to the screen's (callers check the size first).
pub fn grade(scene: &Scene, screen: &ScreenScene, ids: &[Option<u32>]) -> Graded {
    let visible = CoverageMap.visible_set(screen, &|_| false, None);
    grade_against(scene, screen, &visible, ids)
}

/// [`grade`] against a visible set already computed (exact, pieces disjoint).
pub fn grade_against(
    scene: &Scene,
    screen: &ScreenScene,
    visible: &VisibleSet,
    ids: &[Option<u32>],
) -> Graded {
    let (w, h) = (screen.width, screen.height);
    let n = w as usize * h as usize;
    let truth = centre_truth(screen, visible);
    let mut known = Vec::new();
    for f in &scene.faces {
        let k = f.id as usize;
        if known.len() <= k {
            known.resize(k + 1, false);
        }
        known[k] = true;
    }
    let is_face = |id: u32| known.get(id as usize).copied().unwrap_or(false);
    let mut g = Grade {
        pixels: n,
        ..Grade::default()
    };
    let mut verdicts = Vec::with_capacity(n);
    for (k, &shown) in ids.iter().enumerate().take(truth.len()) {
        let covered = truth.covered(k);
        g.image_covered += shown.is_some() as usize;
        g.exact_covered += covered as usize;
        g.ties += truth.is_tie(k) as usize;
        let v = match shown {
            Some(id) if !is_face(id) => Verdict::UnknownId,
            _ if truth.accepts(k, shown) => Verdict::Right,
            None => Verdict::MissingFace,
            Some(_) if covered => Verdict::WrongFace,
            Some(_) => Verdict::ExtraFace,
        };
        match v {
            Verdict::Right => {}
            Verdict::WrongFace => g.wrong_face += 1,
            Verdict::MissingFace => g.missing_face += 1,
            Verdict::ExtraFace => g.extra_face += 1,
            Verdict::UnknownId => g.unknown_id += 1,
        }
        verdicts.push(v);
    }
    g.wrong = g.wrong_face + g.missing_face + g.extra_face + g.unknown_id;
    // The truth's pieces as pixel rings with their face ids, as `benchmark::truth` makes them.
    let rings: Vec<(u32, Vec<[f64; 2]>)> = visible
        .pixel_rings(screen)
        .into_iter()
        .map(|(poly, ring)| (screen.polys[poly as usize].id, ring))
        .collect();
    g.area_error = if ids.len() == n {
        crate::benchmark::truth::error_of(&rings, w, h, ids)
    } else {
        f64::NAN
    };
    Graded {
        grade: g,
        truth,
        verdicts,
    }
}

/// One piece's hold on a centre: its face, and the normals (a, b) of its lines through the
/// centre (none: the centre is inside it).
type Hold = (u32, Vec<[Wide; 2]>);

/// What the exact visible set holds at every pixel centre of the screen (row-major, row 0 at
/// the top), decided exactly: each centre is tested against every line of each piece whose
/// bounds come near it.
pub fn centre_truth(screen: &ScreenScene, visible: &VisibleSet) -> CentreTruths {
    let (w, h) = (screen.width as i64, screen.height as i64);
    let s = Samples::new(screen.width, screen.height);
    // A centre inside one piece, off its boundary, is the usual case and is stored directly;
    // a centre on some boundary (or, which disjoint pieces never do, inside two) keeps every
    // piece that holds it until the end.
    let mut cells = vec![Cell::Background; (w * h) as usize];
    let mut holds: Vec<Vec<Hold>> = Vec::new();
    for piece in &visible.pieces {
        let [x0, y0, x1, y1] = piece.bounds();
        let (c0, c1) = (s.col_of(x0), s.col_of(x1));
        let (r0, r1) = (s.row_of(y1), s.row_of(y0));
        if !(c0.is_finite() && c1.is_finite() && r0.is_finite() && r1.is_finite()) {
            continue;
        }
        // A margin of a pixel covers the rounding of the conversion to pixels.
        let i0 = ((c0 - 1.0).floor().max(0.0) as i64).min(w);
        let i1 = ((c1 + 1.0).ceil().max(0.0) as i64).min(w);
        let j0 = ((r0 - 1.0).floor().max(0.0) as i64).min(h);
        let j1 = ((r1 + 1.0).ceil().max(0.0) as i64).min(h);
        let face = screen.polys[piece.poly as usize].id;
        for j in j0..j1 {
            let y = s.y(j);
            let row = s.row_line(j);
            for i in i0..i1 {
                let x = s.x(i);
                // x and y are rounded once from exact quotients: within U·|x| (U·|y|).
                let e = (x.abs() + y.abs()) * f64::EPSILON;
                let mut on = Vec::new();
                let mut outside = false;
                for (line, approx) in piece.lines_with_approx() {
                    let side = approx
                        .sign_at([x, y, e])
                        .or_else(|| line_side([&s.column_line(i), &row], line));
                    match side {
                        Some(Ordering::Less) => {
                            outside = true;
                            break;
                        }
                        Some(Ordering::Equal) => {
                            let [a, b, _] = line.exact();
                            on.push([a, b]);
                        }
                        // `None` only for parallel sample lines, which a column and a row never
                        // are.
                        _ => {}
                    }
                }
                if outside {
                    continue;
                }
                let cell = &mut cells[(j * w + i) as usize];
                let list = match *cell {
                    Cell::Background if on.is_empty() => {
                        *cell = Cell::Face(face);
                        continue;
                    }
                    Cell::Background => {
                        *cell = Cell::Tie(holds.len() as u32);
                        holds.push(Vec::new());
                        holds.last_mut().expect("just pushed")
                    }
                    Cell::Face(f) => {
                        *cell = Cell::Tie(holds.len() as u32);
                        holds.push(vec![(f, Vec::new())]);
                        holds.last_mut().expect("just pushed")
                    }
                    Cell::Tie(t) => &mut holds[t as usize],
                };
                list.push((face, on));
            }
        }
    }
    let ties = holds
        .into_iter()
        .map(|list| {
            let mut faces: Vec<u32> = list.iter().map(|(f, _)| *f).collect();
            faces.sort_unstable();
            faces.dedup();
            let cones: Vec<Vec<[Wide; 2]>> = list.into_iter().map(|(_, c)| c).collect();
            (faces, !cones_cover_every_direction(&cones))
        })
        .collect();
    CentreTruths { cells, ties }
}

/// Do closed convex cones with a common apex cover every direction of the plane? Each cone is
/// the normals (a, b) of its lines through the apex: direction d is in it when
/// `a·d.x + b·d.y >= 0` for each (no normal: the whole plane).
///
/// Exact: the cones' boundary rays (`±(b, -a)`) and the four axis directions are sorted by
/// angle; between two consecutive rays no cone has a boundary, so each cone holds all of the
/// open sector between them or none of it, and the sum of the two rays (inside the sector, as
/// consecutive rays are less than a half-turn apart once the axes are among them) tells which.
/// The union of closed cones holding every open sector holds their closures too. Entries are
/// below 2^220 (cut lines' coefficients, see `exact::predicates`), products below 2^442: the
/// 768-bit integers never overflow.
pub fn cones_cover_every_direction(cones: &[Vec<[Wide; 2]>]) -> bool {
    if cones.iter().any(|c| c.is_empty()) {
        return true;
    }
    let zero: Wide = 0i32.as_();
    let one: Wide = 1i32.as_();
    let mut rays: Vec<[Wide; 2]> = vec![[one, zero], [zero, one], [-one, zero], [zero, -one]];
    for &[a, b] in cones.iter().flatten() {
        if a != zero || b != zero {
            rays.push([b, -a]);
            rays.push([-b, a]);
        }
    }
    // Angle order from +x counter-clockwise: the upper half (y > 0, or y = 0 and x > 0) first.
    let half = |d: &[Wide; 2]| !(d[1] > zero || (d[1] == zero && d[0] > zero));
    let cross = |p: &[Wide; 2], q: &[Wide; 2]| p[0] * q[1] - p[1] * q[0];
    rays.sort_by(|p, q| half(p).cmp(&half(q)).then_with(|| zero.cmp(&cross(p, q))));
    rays.dedup_by(|q, p| half(p) == half(q) && cross(p, q) == zero);
    let n = rays.len();
    (0..n).all(|k| {
        let (p, q) = (&rays[k], &rays[(k + 1) % n]);
        let mid = [p[0] + q[0], p[1] + q[1]];
        cones
            .iter()
            .any(|c| c.iter().all(|[a, b]| *a * mid[0] + *b * mid[1] >= zero))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Camera, Projection};
    use crate::pipeline::prepare;
    use crate::project::CullMode;
    use crate::raster::zbuffer;
    use crate::scene::{Format, load_bytes};
    use glam::DVec3;

    fn wide(v: i64) -> Wide {
        v.as_()
    }

    fn cone(normals: &[[i64; 2]]) -> Vec<[Wide; 2]> {
        normals.iter().map(|&[a, b]| [wide(a), wide(b)]).collect()
    }

    #[test]
    fn two_half_planes_cover_the_plane_only_when_opposite() {
        // x >= 0 and x <= 0: an edge between two pieces.
        assert!(cones_cover_every_direction(&[
            cone(&[[1, 0]]),
            cone(&[[-1, 0]])
        ]));
        // x >= 0 twice: the outline.
        assert!(!cones_cover_every_direction(&[
            cone(&[[1, 0]]),
            cone(&[[1, 0]])
        ]));
        // One half-plane: a silhouette edge.
        assert!(!cones_cover_every_direction(&[cone(&[[3, -7]])]));
        // A piece with the centre inside covers everything.
        assert!(cones_cover_every_direction(&[cone(&[])]));
    }

    #[test]
    fn quadrants_at_a_vertex_cover_the_plane_only_all_four() {
        let q = [
            cone(&[[1, 0], [0, 1]]),
            cone(&[[-1, 0], [0, 1]]),
            cone(&[[-1, 0], [0, -1]]),
            cone(&[[1, 0], [0, -1]]),
        ];
        assert!(cones_cover_every_direction(&q));
        for k in 0..4 {
            let mut three = q.to_vec();
            three.remove(k);
            assert!(!cones_cover_every_direction(&three), "without {k}");
        }
        // Three 120° wedges about the apex (normals of the lines at 0°, 120°, 240°, scaled to
        // integers): wedge k lies between rays at angles 90° + 120°·k and 210° + 120°·k.
        let r = [[0, 1000], [-866, -500], [866, -500]];
        let wedge = |k: usize| {
            let (u, v) = (r[k], r[(k + 1) % 3]);
            // Inward normals: u rotated clockwise, v rotated counter-clockwise.
            cone(&[[u[1], -u[0]], [-v[1], v[0]]])
        };
        assert!(cones_cover_every_direction(&[wedge(0), wedge(1), wedge(2)]));
        assert!(!cones_cover_every_direction(&[wedge(0), wedge(1)]));
    }

    #[test]
    fn a_thin_gap_between_wedges_is_found() {
        // The upper half-plane, the lower left quadrant, and the lower right quadrant but for
        // a sliver next to +x (below the ray (1000, -1)): the sliver is uncovered.
        let upper = cone(&[[0, 1]]);
        let lower_left = cone(&[[0, -1], [-1, 0]]);
        let lower_right_but_a_sliver = cone(&[[0, -1], [1, 1000]]);
        assert!(!cones_cover_every_direction(&[
            upper.clone(),
            lower_left.clone(),
            lower_right_but_a_sliver
        ]));
        let lower_right = cone(&[[0, -1], [1, 0]]);
        assert!(cones_cover_every_direction(&[
            upper,
            lower_left,
            lower_right
        ]));
    }

    #[test]
    fn accepts_follows_the_truth() {
        assert!(CentreTruth::Background.accepts(None));
        assert!(!CentreTruth::Background.accepts(Some(0)));
        assert!(CentreTruth::Face(3).accepts(Some(3)));
        assert!(!CentreTruth::Face(3).accepts(Some(4)));
        assert!(!CentreTruth::Face(3).accepts(None));
        let tie = |background_right| CentreTruth::Tie {
            faces: vec![2, 5],
            background_right,
        };
        assert!(tie(false).accepts(Some(2)) && tie(false).accepts(Some(5)));
        assert!(!tie(false).accepts(Some(3)) && !tie(false).accepts(None));
        assert!(tie(true).accepts(None));
    }

    /// The square [-1.5, 1.5]² as two triangles split along y = x (face 0 above it, face 1
    /// below), seen from the front orthographically over 6x4 pixels: pixel (i, j) has its
    /// centre at x = i - 2.5, y = 1.5 - j, so the outline runs through the 12 border centres
    /// of columns 1..=4 and the diagonal through (1, 3), (2, 2), (3, 1), (4, 0); columns 0 and
    /// 5 are background.
    fn split_square() -> (Scene, ScreenScene) {
        let obj = "v -1.5 -1.5 0\nv 1.5 -1.5 0\nv 1.5 1.5 0\nv -1.5 1.5 0\nf 1 3 4\nf 1 2 3\n";
        let scene = load_bytes(obj.as_bytes(), Format::Obj, "square.obj", None).unwrap();
        let camera = Camera {
            eye: DVec3::new(0.0, 0.0, 5.0),
            target: DVec3::ZERO,
            up: DVec3::Y,
            projection: Projection::Orthographic { height: 4.0 },
            near: 1.0,
            far: 10.0,
            width: 6,
            height: 4,
        };
        let screen = prepare(&scene, &camera, CullMode::Auto).screen;
        (scene, screen)
    }

    #[test]
    fn centres_on_edges_are_ties_and_only_the_outline_accepts_background() {
        let (_, screen) = split_square();
        let visible = CoverageMap.visible_set(&screen, &|_| false, None);
        let truth = centre_truth(&screen, &visible);
        let at = |i: usize, j: usize| truth.get(j * 6 + i);
        let tie = |faces: &[u32], background_right| CentreTruth::Tie {
            faces: faces.to_vec(),
            background_right,
        };
        // Inside, off the diagonal: one face.
        assert_eq!(at(2, 1), CentreTruth::Face(0));
        assert_eq!(at(3, 2), CentreTruth::Face(1));
        // On the diagonal inside the square: either face, never background.
        assert_eq!(at(2, 2), tie(&[0, 1], false));
        assert_eq!(at(3, 1), tie(&[0, 1], false));
        // Corners on the diagonal: either face, or background.
        assert_eq!(at(1, 3), tie(&[0, 1], true));
        assert_eq!(at(4, 0), tie(&[0, 1], true));
        // The other border centres: their face, or background.
        assert_eq!(at(1, 0), tie(&[0], true));
        assert_eq!(at(2, 0), tie(&[0], true));
        assert_eq!(at(4, 3), tie(&[1], true));
        assert_eq!(at(4, 2), tie(&[1], true));
        // Off the square.
        for j in 0..4 {
            assert_eq!(at(0, j), CentreTruth::Background);
            assert_eq!(at(5, j), CentreTruth::Background);
        }
    }

    #[test]
    fn the_exact_zbuffer_has_no_wrong_pixel_and_each_kind_of_error_is_counted() {
        let (scene, screen) = split_square();
        let zb = zbuffer::render(&screen, |_| {});
        let ids: Vec<Option<u32>> = zb
            .poly
            .iter()
            .map(|&p| (p != crate::raster::EMPTY).then(|| screen.polys[p as usize].id))
            .collect();
        let graded = grade(&scene, &screen, &ids);
        let g = graded.grade;
        let base = g.area_error;
        assert_eq!((g.pixels, g.wrong, g.ties), (24, 0, 14), "{g:?}");
        assert_eq!(g.exact_covered, 16);
        assert_eq!(g.image_covered, ids.iter().flatten().count());
        // Two point samples per pixel split 50/50 at most: the area error is positive but
        // below the share of the pixels on edges (14 ties of 24).
        assert!(g.area_error > 0.0 && g.area_error < 14.0 / 24.0, "{g:?}");

        // Another tie rule: every tie shows its other face, or background where allowed.
        let other: Vec<Option<u32>> = ids
            .iter()
            .enumerate()
            .map(|(k, id)| match (graded.truth.get(k), id) {
                (
                    CentreTruth::Tie {
                        background_right: true,
                        ..
                    },
                    _,
                ) => None,
                (CentreTruth::Tie { faces, .. }, Some(f)) => faces.iter().copied().find(|g| g != f),
                _ => *id,
            })
            .collect();
        assert_ne!(other, ids);
        assert_eq!(grade(&scene, &screen, &other).grade.wrong, 0);

        // One of each error: a wrong face inside, a missing face on the diagonal (inside the
        // union), an extra face off the square, an unknown id.
        let mut bad = ids.clone();
        bad[6 + 2] = Some(1); // (2, 1): face 0 is right
        bad[2 * 6 + 2] = None; // (2, 2): on the diagonal, inside the square
        bad[0] = Some(0); // (0, 0): background
        bad[3 * 6 + 5] = Some(9); // no face 9
        let graded = grade(&scene, &screen, &bad);
        let g = graded.grade;
        assert_eq!(
            (
                g.wrong,
                g.wrong_face,
                g.missing_face,
                g.extra_face,
                g.unknown_id
            ),
            (4, 1, 1, 1, 1),
            "{g:?}"
        );
        let diff = graded.diff_image(&bad);
        assert_eq!(diff[6 + 2], DIFF_MISMATCH);
        assert_eq!(diff[2 * 6 + 2], DIFF_COVERAGE);
        assert_eq!(diff[0], DIFF_COVERAGE);
        assert_eq!(diff[3 * 6 + 5], DIFF_UNKNOWN);
        assert_eq!(diff[5], [255; 3]);
        assert_eq!(diff[2 * 6 + 3], diff_grey(1)); // (3, 2), inside face 1
        // Every wrong pixel is a whole pixel of area error at most.
        assert!(g.area_error > base && g.area_error <= base + 4.0 / 24.0 + 1e-12);
    }
}
