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
//! - [`reference`](mod@reference): the nearest polygon at a point on the kernel's grid, and the band;
//! - [`check`]: sample points and count failures; [`shrink`]: smaller failing cases, fixtures;
//! - [`world`]: the measured cases and the world reference;
//! - [`rng`]: the deterministic random numbers.
//!
//! Invariant of a run ([`run`]): the same families, case count, seed and point count give the
//! same cases, the same points and the same report, times aside, whatever the number of jobs:
//! case k of a family runs whole on one thread (the kernel's fallback counter is per thread),
//! thread j of `jobs` taking the cases k with k mod jobs = j, and the failing cases are reported
//! in case order.

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
use std::sync::atomic::{AtomicU64, Ordering as AtomicOrdering};

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
    /// Threads running cases (at least 1).
    pub jobs: usize,
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
    /// Kernel fallbacks over all its cases (the thread's counter around projection and the
    /// visible set).
    pub fallbacks: u64,
    /// The fallbacks the strategy reported (its `exact_fallbacks` stat) over all its cases.
    pub strategy_fallbacks: u64,
    /// The most fallbacks of one case.
    pub max_fallbacks: u64,
    /// Seconds projecting and computing visible sets.
    pub engine_seconds: f64,
    /// Seconds for everything (reference, checks, shrinking included).
    pub seconds: f64,
    /// The failing cases.
    pub failed: Vec<FailedCase>,
}

impl FamilyReport {
    /// No case yet.
    fn new(family: Family) -> Self {
        FamilyReport {
            family,
            cases: 0,
            tally: Tally::default(),
            fallbacks: 0,
            strategy_fallbacks: 0,
            max_fallbacks: 0,
            engine_seconds: 0.0,
            seconds: 0.0,
            failed: Vec::new(),
        }
    }

    /// Counts one more case (its failure, if any, is added by the caller, with its fixture).
    fn add_case(&mut self, o: &CaseOutcome) {
        self.cases += 1;
        self.tally.add(&o.checked.tally);
        self.fallbacks += o.fallbacks;
        self.strategy_fallbacks += o.strategy_fallbacks;
        self.max_fallbacks = self.max_fallbacks.max(o.fallbacks);
        self.engine_seconds += o.engine_seconds;
    }

    /// Adds another report's counts, times and failures.
    fn merge(&mut self, o: &FamilyReport) {
        self.cases += o.cases;
        self.tally.add(&o.tally);
        self.fallbacks += o.fallbacks;
        self.strategy_fallbacks += o.strategy_fallbacks;
        self.max_fallbacks = self.max_fallbacks.max(o.max_fallbacks);
        self.engine_seconds += o.engine_seconds;
        self.seconds += o.seconds;
        self.failed.extend(o.failed.iter().cloned());
    }
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
    let jobs = options.jobs.max(1) as u64;
    let done = AtomicU64::new(0);
    let slices: Vec<(FamilyReport, Vec<(u64, FailedCase)>)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..jobs)
            .map(|j| {
                let done = &done;
                // The main thread's stack size, not a spawned thread's 2 MiB: the strategies
                // recurse (the BSP) as they do under the CLI.
                let worker = std::thread::Builder::new().stack_size(8 << 20);
                worker
                    .spawn_scoped(scope, move || {
                        let mut r = FamilyReport::new(family);
                        let mut failed = Vec::new();
                        for index in (j..options.cases).step_by(jobs as usize) {
                            let case = family.case(options.seed, index);
                            let outcome = check_case(&case, strategy, options.points);
                            r.add_case(&outcome);
                            if outcome.failed() {
                                let written = shrink_and_write(
                                    &case,
                                    &outcome,
                                    strategy,
                                    options.points,
                                    &options.failures,
                                );
                                failed.push((index, written));
                            }
                            done.fetch_add(1, AtomicOrdering::Relaxed);
                        }
                        (r, failed)
                    })
                    .expect("a stress worker thread starts")
            })
            .collect();
        // Progress from this thread, as the workers count cases.
        let mut shown = 0;
        while handles.iter().any(|h| !h.is_finished()) {
            std::thread::sleep(std::time::Duration::from_millis(50));
            shown = tick_to(done.load(AtomicOrdering::Relaxed), shown, tick);
        }
        tick_to(done.load(AtomicOrdering::Relaxed), shown, tick);
        handles
            .into_iter()
            .map(|h| h.join().expect("a stress case panicked"))
            .collect()
    });
    let mut r = FamilyReport::new(family);
    let mut failed = Vec::new();
    for (slice, f) in slices {
        r.merge(&slice);
        failed.extend(f);
    }
    failed.sort_by_key(|(index, _)| *index);
    r.failed = failed.into_iter().map(|(_, f)| f).collect();
    r.seconds = start.elapsed().as_secs_f64();
    r
}

/// Calls `tick` once per case done since `shown`; returns the new count shown.
fn tick_to(done: u64, shown: u64, tick: &mut dyn FnMut()) -> u64 {
    for _ in shown..done {
        tick();
    }
    done.max(shown)
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
        "{} faces shrunk to {}; see it: sightline render NAME.obj --cam NAME.cam -o NAME.svg\n",
        case.faces.len(),
        small.faces.len(),
    );
    if let Some((family, seed, index)) = case.origin {
        let _ = writeln!(
            note,
            "the whole case is the last of: sightline stress --family {} --seed {seed} --cases {} --points {points}",
            family.name(),
            index + 1
        );
    }
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

/// A table's columns: names and widths.
type Columns = [(&'static str, usize)];

/// One line of a table: the first cell left-aligned to its width, the others right-aligned,
/// then `tail`.
fn table_row(s: &mut String, columns: &Columns, cells: &[String], tail: &str) {
    for (k, ((_, width), cell)) in columns.iter().zip(cells).enumerate() {
        let _ = match k {
            0 => write!(s, "{cell:<width$}"),
            _ => write!(s, " {cell:>width$}"),
        };
    }
    let _ = writeln!(s, "{tail}");
}

/// A table's header line.
fn table_header(s: &mut String, columns: &Columns, tail: &str) {
    let names: Vec<String> = columns.iter().map(|(n, _)| n.to_string()).collect();
    table_row(s, columns, &names, tail);
}

const FAMILY_COLUMNS: [(&str, usize); 12] = [
    ("family", 12),
    ("cases", 8),
    ("failed", 7),
    ("points", 10),
    ("in band", 8),
    ("wrong", 9),
    ("fallbacks", 10),
    ("fb/case", 9),
    ("fb max", 7),
    ("time s", 9),
    ("ms/case", 9),
    ("engine ms", 10),
];

/// The report of a run: one line per family, a total, then the failing cases and their
/// fixtures.
pub fn format_report(reports: &[FamilyReport]) -> String {
    let mut s = String::new();
    table_header(&mut s, &FAMILY_COLUMNS, "  scale");
    let mut total = FamilyReport::new(Family::Grazing);
    let line = |s: &mut String, name: &str, r: &FamilyReport, scale: &str| {
        let per = |v: f64| v / r.cases.max(1) as f64;
        let cells = [
            name.to_string(),
            r.cases.to_string(),
            r.failed.len().to_string(),
            r.tally.points.to_string(),
            r.tally.in_band.to_string(),
            r.tally.failures().to_string(),
            r.fallbacks.to_string(),
            format!("{:.2}", per(r.fallbacks as f64)),
            r.max_fallbacks.to_string(),
            format!("{:.2}", r.seconds),
            format!("{:.2}", per(r.seconds * 1e3)),
            format!("{:.2}", per(r.engine_seconds * 1e3)),
        ];
        table_row(s, &FAMILY_COLUMNS, &cells, &format!("  {scale}"));
    };
    for r in reports {
        let (lo, hi, what) = r.family.range();
        line(
            &mut s,
            r.family.name(),
            r,
            &format!("{lo:e}..{hi:e} ({what})"),
        );
        total.merge(r);
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
    let _ = writeln!(
        s,
        "fallbacks: {} counted around projection and visible set, {} reported by the strategy",
        total.fallbacks, total.strategy_fallbacks
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

const MEASURED_COLUMNS: [(&str, usize); 11] = [
    ("case", 48),
    ("samples", 8),
    ("wrong", 8),
    ("in band", 8),
    ("wrong %", 10),
    ("rho_xy", 10),
    ("rho_z", 10),
    ("grid xy", 10),
    ("grid z", 9),
    ("fallbacks", 10),
    ("time s", 7),
];

/// The report of the measured cases: per case, the wrong fraction outside the band, the band's
/// roundings, the kernel's grid rounding of the same vertices, fallbacks and time.
pub fn format_measurements(ms: &[world::Measurement]) -> String {
    let mut s = String::new();
    table_header(&mut s, &MEASURED_COLUMNS, "");
    for m in ms {
        let cells = [
            m.name.clone(),
            m.samples.to_string(),
            m.wrong.to_string(),
            m.in_band.to_string(),
            format!("{:.4}", 100.0 * m.wrong_fraction()),
            format!("{:.2e}", m.band.rho_xy),
            format!("{:.2e}", m.band.rho_z),
            format!("{:.2e}", m.grid_rounding[0]),
            format!("{:.2e}", m.grid_rounding[1]),
            m.fallbacks.to_string(),
            format!("{:.2}", m.seconds),
        ];
        table_row(&mut s, &MEASURED_COLUMNS, &cells, "");
    }
    s
}
