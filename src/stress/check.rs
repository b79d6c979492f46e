//! The check of one case: the engine's visible set against the reference at sample points.
//!
//! Invariant: a point counts as a failure exactly when, decided in exact arithmetic,
//! (a) it lies inside two pieces, or inside one and on the boundary of another (the pieces
//!     overlap: a failure wherever it happens, band or not, since disjointness needs no
//!     reference);
//! (b) a piece contains it and no polygon does, or a polygon does and no piece;
//! (c) the piece's polygon is not the reference's nearest polygon;
//! and, for (b) and (c), the point lies outside the reference's band (see
//! [`super::reference`]). A point on a piece boundary and inside no piece names no polygon: it
//! is counted, not compared.
//!
//! Points are drawn from the case's own stream: a quarter uniform over the view, the rest
//! concentrated near the polygons' corners, along their edges and along the lines where two
//! polygons' planes meet (where defects are), at distances log-uniform from a quarter of the
//! view down to 2^-40 of it, some exactly on the feature.

use super::geometry::{Convex, Line, Loc, Point, rational};
use super::kernel;
use super::reference::Reference;
use super::rng::Rng;
use crate::project::ScreenScene;
use crate::visibility::VisibleSet;
use num_rational::BigRational;
use num_traits::Zero;

/// What went wrong at a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// (a) Two pieces contain the point.
    Overlap,
    /// (b) A piece and no polygon, or a polygon and no piece.
    Coverage,
    /// (c) The piece's polygon is not the nearest.
    WrongPolygon,
}

/// A failing point.
#[derive(Clone, Debug)]
pub struct Failure {
    /// What went wrong.
    pub kind: Kind,
    /// The point in NDC, rounded.
    pub ndc: [f64; 2],
    /// The engine's polygon there (index into the screen polygons).
    pub engine: Option<usize>,
    /// The reference's nearest polygon there.
    pub reference: Option<usize>,
}

/// Counts over the points of one or more cases.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    /// Points checked.
    pub points: u64,
    /// Points in the reference's band (not compared for (b) and (c)).
    pub in_band: u64,
    /// Points in the band where the engine and the reference disagree.
    pub excused: u64,
    /// Points on a piece boundary and inside no piece (no engine answer to compare).
    pub on_piece_boundary: u64,
    /// Failures (a).
    pub overlaps: u64,
    /// Failures (b).
    pub coverage: u64,
    /// Failures (c).
    pub wrong: u64,
}

impl Tally {
    /// Failing points.
    pub fn failures(&self) -> u64 {
        self.overlaps + self.coverage + self.wrong
    }

    /// Adds another tally.
    pub fn add(&mut self, o: &Tally) {
        self.points += o.points;
        self.in_band += o.in_band;
        self.excused += o.excused;
        self.on_piece_boundary += o.on_piece_boundary;
        self.overlaps += o.overlaps;
        self.coverage += o.coverage;
        self.wrong += o.wrong;
    }
}

/// The result of checking a visible set at sample points.
#[derive(Clone, Debug, Default)]
pub struct Checked {
    /// The counts.
    pub tally: Tally,
    /// The first few failing points.
    pub failures: Vec<Failure>,
}

/// Failing points kept per check.
const KEEP: usize = 8;

/// Checks `visible` (a strategy's result on `screen`) against the reference at `points` sample
/// points drawn from `rng`.
pub fn check_visible(
    screen: &ScreenScene,
    visible: &VisibleSet,
    points: usize,
    rng: &mut Rng,
) -> Checked {
    let reference = Reference::of_screen(screen);
    let margin = reference.extent * 1e-12;
    let pieces: Vec<Convex> = kernel::pieces(visible)
        .into_iter()
        .map(|p| Convex::new(p.poly, p.lines, margin))
        .collect();
    let sampler = Sampler::new(&reference);
    let mut out = Checked::default();
    for _ in 0..points {
        let p = sampler.sample(rng);
        check_point(&reference, &pieces, &p, &mut out);
    }
    out
}

/// Checks one point, adding to `out`.
fn check_point(reference: &Reference, pieces: &[Convex], p: &Point, out: &mut Checked) {
    let q = p.to_f64();
    let err = reference.err(q);
    let (mut inside, mut on) = (Vec::new(), 0usize);
    for piece in pieces {
        match piece.locate(p, q, err) {
            Loc::Inside => inside.push(piece.poly),
            Loc::Boundary => on += 1,
            Loc::Outside => {}
        }
    }
    let t = &mut out.tally;
    t.points += 1;
    let answer = reference.answer(p);
    t.in_band += answer.in_band as u64;
    let engine = inside.first().copied();
    let kind = if inside.len() >= 2 || (inside.len() == 1 && on > 0) {
        Some(Kind::Overlap)
    } else if inside.is_empty() && on > 0 {
        t.on_piece_boundary += 1;
        None
    } else if engine == answer.nearest {
        None
    } else if answer.in_band {
        t.excused += 1;
        None
    } else if engine.is_none() || answer.nearest.is_none() {
        Some(Kind::Coverage)
    } else {
        Some(Kind::WrongPolygon)
    };
    let Some(kind) = kind else { return };
    match kind {
        Kind::Overlap => t.overlaps += 1,
        Kind::Coverage => t.coverage += 1,
        Kind::WrongPolygon => t.wrong += 1,
    }
    if out.failures.len() < KEEP {
        out.failures.push(Failure {
            kind,
            ndc: [q[0] / reference.view, q[1] / reference.view],
            engine,
            reference: answer.nearest,
        });
    }
}

/// Draws sample points for one reference.
struct Sampler<'a> {
    reference: &'a Reference,
    /// Pairs of polygons whose bounds overlap and whose planes meet on screen.
    meetings: Vec<Line>,
}

impl<'a> Sampler<'a> {
    fn new(reference: &'a Reference) -> Self {
        let polys = &reference.polys;
        let mut meetings = Vec::new();
        'pairs: for i in 0..polys.len() {
            for j in i + 1..polys.len() {
                let (a, b) = (&polys[i].bounds, &polys[j].bounds);
                if a[0] > b[2] || b[0] > a[2] || a[1] > b[3] || b[1] > a[3] {
                    continue;
                }
                let l = polys[i].plane.meeting(&polys[j].plane);
                if !(l[0].is_zero() && l[1].is_zero()) {
                    meetings.push(l);
                }
                if meetings.len() >= 4096 {
                    break 'pairs;
                }
            }
        }
        Sampler {
            reference,
            meetings,
        }
    }

    fn sample(&self, rng: &mut Rng) -> Point {
        let polys = &self.reference.polys;
        let view = self.reference.view;
        let kind = if polys.is_empty() { 0 } else { rng.below(4) };
        let base = match kind {
            1 => {
                let g = &polys[rng.below(polys.len())];
                g.corners[rng.below(g.corners.len())].rationals()
            }
            2 => {
                let g = &polys[rng.below(polys.len())];
                let k = rng.below(g.corners.len());
                let [ax, ay] = g.corners[k].rationals();
                let [bx, by] = g.corners[(k + 1) % g.corners.len()].rationals();
                let t = rational(rng.unit());
                [&ax + &t * (&bx - &ax), &ay + &t * (&by - &ay)]
            }
            3 if !self.meetings.is_empty() => {
                let l = &self.meetings[rng.below(self.meetings.len())];
                let g = &polys[rng.below(polys.len())];
                let near = g.corners[rng.below(g.corners.len())].rationals();
                foot(l, &near)
            }
            _ => [
                rational(rng.range(-view, view)),
                rational(rng.range(-view, view)),
            ],
        };
        if kind == 0 || rng.chance(0.125) {
            return Point::of(&base[0], &base[1]);
        }
        let r = view * (-rng.range(2.0, 40.0)).exp2();
        let a = rng.range(0.0, std::f64::consts::TAU);
        let (dx, dy) = (rational(r * a.cos()), rational(r * a.sin()));
        Point::of(&(&base[0] + dx), &(&base[1] + dy))
    }
}

/// The foot of the perpendicular from p to the line l (not degenerate), exactly.
fn foot(l: &Line, p: &[BigRational; 2]) -> [BigRational; 2] {
    let [a, b, d] = l.clone().map(BigRational::from_integer);
    let v = &a * &p[0] + &b * &p[1] + &d;
    let n = &a * &a + &b * &b;
    let t = v / n;
    [&p[0] - &t * &a, &p[1] - &t * &b]
}

/// One case checked.
#[derive(Clone, Debug, Default)]
pub struct CaseOutcome {
    /// The points' counts and the first failures.
    pub checked: Checked,
    /// Kernel fallbacks while projecting and computing the visible set.
    pub fallbacks: u64,
    /// The fallbacks the strategy reported (its `exact_fallbacks` stat).
    pub strategy_fallbacks: u64,
    /// Screen polygons.
    pub polygons: usize,
    /// Visible pieces.
    pub pieces: usize,
    /// Seconds spent projecting and computing the visible set (not checking it).
    pub engine_seconds: f64,
}

impl CaseOutcome {
    /// Did any point fail?
    pub fn failed(&self) -> bool {
        self.checked.tally.failures() > 0
    }
}

/// Checks `case`: projects it, computes its visible set with `strategy` (every face opaque)
/// and checks the set at `points` points drawn from the case's own stream.
pub fn check_case(
    case: &super::Case,
    strategy: &dyn crate::Strategy,
    points: usize,
) -> CaseOutcome {
    let Some(scene) = case.scene() else {
        return CaseOutcome::default();
    };
    let start = std::time::Instant::now();
    let before = kernel::fallbacks();
    let prepared = crate::pipeline::prepare(&scene, &case.camera, crate::project::CullMode::Auto);
    let visible = strategy.visible_set(&prepared.screen, &|_| false, None);
    let fallbacks = kernel::fallbacks() - before;
    let engine_seconds = start.elapsed().as_secs_f64();
    let mut rng = Rng(case.stream);
    CaseOutcome {
        checked: check_visible(&prepared.screen, &visible, points, &mut rng),
        fallbacks,
        strategy_fallbacks: kernel::strategy_fallbacks(&visible),
        polygons: prepared.screen.polys.len(),
        pieces: visible.pieces.len(),
        engine_seconds,
    }
}
