//! The numerical stress suite of issue 11: generated hard scenes (grazing interpenetration,
//! near-parallel stacks, decals in deep perspective, far offsets, tiny scales, T-junctions,
//! needles, fans, edge-on faces, faces touching, cyclic rings) whose visible sets are checked at
//! sample points against a slow big-rational reference on the same projected coordinates; and
//! the measured cases against a reference in world coordinates.
//!
//! One job per file:
//! - [`families`]: the generators, a case from (family, seed, index);
//! - [`kernel`]: the one adapter reading the kernel's types into big integers;
//! - [`geometry`]: exact points, lines, planes, polygons, distances;
//! - [`reference`]: the nearest polygon at a point on the kernel's grid, and the band;
//! - [`check`]: sample points and count failures; [`shrink`]: smaller failing cases, fixtures;
//! - [`world`]: the measured cases and the world reference;
//! - [`rng`]: the deterministic random numbers.
//!
//! Invariant of a run ([`run`]): the same families, case count, seed and point count give the
//! same cases, the same points and the same report, times aside. Cases run one after another on
//! the calling thread (the kernel's fallback counter is per thread).

pub mod check;
pub mod families;
pub mod geometry;
pub mod kernel;
pub mod reference;
pub mod rng;
pub mod shrink;
pub mod world;

pub use check::{CaseOutcome, Tally, check_case, check_visible};
pub use families::{Case, Family};

use crate::progress::{Report, Ticker};
use crate::visibility::Strategy;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// What `sightline stress --family` runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Selection {
    /// Every family.
    All,
    /// The measured cases, against the world reference.
    Measured,
    /// One family.
    One(Family),
}

impl Selection {
    /// `all`, `measured` or a family's name.
    pub fn parse(s: &str) -> Result<Selection, String> {
        match s.trim() {
            "all" => Ok(Selection::All),
            "measured" => Ok(Selection::Measured),
            name => Family::by_name(name).map(Selection::One).ok_or_else(|| {
                let names: Vec<&str> = Family::ALL.iter().map(|f| f.name()).collect();
                format!(
                    "unknown family '{name}': use all, measured or one of {}",
                    names.join(", ")
                )
            }),
        }
    }

    /// The families it runs (none for `measured`).
    pub fn families(self) -> Vec<Family> {
        match self {
            Selection::All => Family::ALL.to_vec(),
            Selection::Measured => Vec::new(),
            Selection::One(f) => vec![f],
        }
    }
}

/// The exact strategy `render` uses for vector output (the coverage map).
pub fn default_strategy() -> &'static dyn Strategy {
    use crate::methods::{Engine, Output, default_for};
    match default_for(Output::Svg).engine {
        Engine::Object(s) => s,
        Engine::Image(_) => unreachable!("vector output is drawn by an object-space strategy"),
    }
}

/// How a run goes.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Cases per family.
    pub cases: u64,
    /// The run's seed.
    pub seed: u64,
    /// Sample points per case.
    pub points: usize,
    /// Where shrunk failing cases are written.
    pub failures: PathBuf,
}

/// Sample points per case unless asked otherwise.
pub const DEFAULT_POINTS: usize = 256;

/// A failing case, shrunk and written.
#[derive(Clone, Debug)]
pub struct FailedCase {
    /// The case's label (family, seed, index).
    pub label: String,
    /// Its failing points' counts.
    pub tally: Tally,
    /// Faces before and after shrinking.
    pub faces: (usize, usize),
    /// The fixture's OBJ (its camera beside it, `.cam`), or why it could not be written.
    pub fixture: Result<PathBuf, String>,
}

/// One family's run.
#[derive(Clone, Debug)]
pub struct FamilyReport {
    /// The family.
    pub family: Family,
    /// Cases run.
    pub cases: u64,
    /// Points over all its cases.
    pub tally: Tally,
    /// Kernel fallbacks over all its cases.
    pub fallbacks: u64,
    /// The most fallbacks of one case.
    pub max_fallbacks: u64,
    /// Seconds projecting and computing visible sets.
    pub engine_seconds: f64,
    /// Seconds for everything (reference, checks, shrinking included).
    pub seconds: f64,
    /// The failing cases.
    pub failed: Vec<FailedCase>,
}

/// Runs `options.cases` cases of `family` with `strategy`; `tick` is called after each case.
/// A failing case is shrunk and written under `options.failures`.
pub fn run_family(
    family: Family,
    options: &RunOptions,
    strategy: &dyn Strategy,
    tick: &mut dyn FnMut(),
) -> FamilyReport {
    let start = std::time::Instant::now();
    let mut r = FamilyReport {
        family,
        cases: options.cases,
        tally: Tally::default(),
        fallbacks: 0,
        max_fallbacks: 0,
        engine_seconds: 0.0,
        seconds: 0.0,
        failed: Vec::new(),
    };
    for index in 0..options.cases {
        let case = family.case(options.seed, index);
        let outcome = check_case(&case, strategy, options.points);
        r.tally.add(&outcome.checked.tally);
        r.fallbacks += outcome.fallbacks;
        r.max_fallbacks = r.max_fallbacks.max(outcome.fallbacks);
        r.engine_seconds += outcome.engine_seconds;
        if outcome.failed() {
            r.failed.push(shrink_and_write(
                &case,
                &outcome,
                strategy,
                options.points,
                &options.failures,
            ));
        }
        tick();
    }
    r.seconds = start.elapsed().as_secs_f64();
    r
}

/// Shrinks a failing case and writes it as a fixture.
fn shrink_and_write(
    case: &Case,
    outcome: &CaseOutcome,
    strategy: &dyn Strategy,
    points: usize,
    dir: &Path,
) -> FailedCase {
    let fails = |c: &Case| check_case(c, strategy, points).failed();
    let small = shrink::shrink(case, &fails);
    let mut note = format!(
        "{} faces shrunk to {}; reproduce: sightline stress --family {} (see the label's seed and case)\n",
        case.faces.len(),
        small.faces.len(),
        case.label.split(' ').next().unwrap_or("all"),
    );
    for f in &outcome.checked.failures {
        let _ = writeln!(
            note,
            "{:?} at NDC ({:e}, {:e}): engine polygon {:?}, reference {:?}",
            f.kind, f.ndc[0], f.ndc[1], f.engine, f.reference
        );
    }
    FailedCase {
        label: case.label.clone(),
        tally: outcome.checked.tally,
        faces: (case.faces.len(), small.faces.len()),
        fixture: shrink::write_fixture(&small, dir, &note)
            .map_err(|e| format!("{}: {e}", dir.display())),
    }
}

/// Runs every family of `families` with the default exact strategy, reporting progress as one
/// stage ("stress": cases done of all).
pub fn run(families: &[Family], options: &RunOptions, report: Option<Report>) -> Vec<FamilyReport> {
    let total = families.len() as u64 * options.cases;
    let mut ticker = Ticker::new(report, "stress", total);
    let mut done = 0;
    let reports = families
        .iter()
        .map(|&f| {
            run_family(f, options, default_strategy(), &mut || {
                done += 1;
                ticker.tick(done);
            })
        })
        .collect();
    ticker.finish();
    reports
}

/// The report of a run: one line per family, a total, then the failing cases and their
/// fixtures.
pub fn format_report(reports: &[FamilyReport]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<12} {:>8} {:>7} {:>10} {:>8} {:>9} {:>10} {:>9} {:>9} {:>9}  scale",
        "family",
        "cases",
        "failed",
        "points",
        "in band",
        "wrong",
        "fallbacks",
        "fb/case",
        "time s",
        "ms/case"
    );
    let mut total = FamilyReport {
        family: Family::Grazing,
        cases: 0,
        tally: Tally::default(),
        fallbacks: 0,
        max_fallbacks: 0,
        engine_seconds: 0.0,
        seconds: 0.0,
        failed: Vec::new(),
    };
    let line = |s: &mut String, name: &str, r: &FamilyReport, scale: &str| {
        let per = |v: f64| v / r.cases.max(1) as f64;
        let _ = writeln!(
            s,
            "{:<12} {:>8} {:>7} {:>10} {:>8} {:>9} {:>10} {:>9.2} {:>9.2} {:>9.2}  {scale}",
            name,
            r.cases,
            r.failed.len(),
            r.tally.points,
            r.tally.in_band,
            r.tally.failures(),
            r.fallbacks,
            per(r.fallbacks as f64),
            r.seconds,
            per(r.seconds * 1e3),
        );
    };
    for r in reports {
        let (lo, hi, what) = r.family.range();
        line(
            &mut s,
            r.family.name(),
            r,
            &format!("{lo:e}..{hi:e} ({what})"),
        );
        total.cases += r.cases;
        total.tally.add(&r.tally);
        total.fallbacks += r.fallbacks;
        total.seconds += r.seconds;
        total.failed.extend(r.failed.iter().cloned());
    }
    if reports.len() > 1 {
        line(&mut s, "all", &total, "");
    }
    let t = &total.tally;
    let _ = writeln!(
        s,
        "failures by kind: overlap {}, coverage {}, wrong polygon {}; in the band and disagreeing: {}; on a piece boundary: {}",
        t.overlaps, t.coverage, t.wrong, t.excused, t.on_piece_boundary
    );
    for f in &total.failed {
        let _ = writeln!(
            s,
            "FAILED {}: {} of {} points (overlap {}, coverage {}, wrong polygon {}); {} faces shrunk to {}: {}",
            f.label,
            f.tally.failures(),
            f.tally.points,
            f.tally.overlaps,
            f.tally.coverage,
            f.tally.wrong,
            f.faces.0,
            f.faces.1,
            match &f.fixture {
                Ok(p) => p.display().to_string(),
                Err(e) => format!("not written: {e}"),
            }
        );
    }
    s
}

/// Measures every measured case with the default exact strategy at `points` pixel centres
/// each (all of them when `points` is at least the image's pixel count).
pub fn measure_all(points: usize, seed: u64, report: Option<Report>) -> Vec<world::Measurement> {
    let cases = world::cases();
    let mut ticker = Ticker::new(report, "measured", cases.len() as u64);
    let out = cases
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let m = world::measure(c, default_strategy(), points, seed);
            ticker.tick(k as u64 + 1);
            m
        })
        .collect();
    ticker.finish();
    out
}

/// The report of the measured cases: per case, the wrong fraction outside the band.
pub fn format_measurements(ms: &[world::Measurement]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<48} {:>8} {:>8} {:>8} {:>10} {:>10} {:>10} {:>10} {:>9} {:>7}",
        "case",
        "samples",
        "wrong",
        "in band",
        "wrong %",
        "rho_xy",
        "rho_z",
        "grid xy",
        "grid z",
        "time s"
    );
    for m in ms {
        let _ = writeln!(
            s,
            "{:<48} {:>8} {:>8} {:>8} {:>10.4} {:>10.2e} {:>10.2e} {:>10.2e} {:>9.2e} {:>9} {:>7.2}",
            m.name,
            m.samples,
            m.wrong,
            m.in_band,
            100.0 * m.wrong_fraction(),
            m.band.rho_xy,
            m.band.rho_z,
            m.grid_rounding[0],
            m.grid_rounding[1],
            m.fallbacks,
            m.seconds
        );
    }
    s
}
