//! The time-versus-error benchmark (`sightline bench --suite`): every method on every scene of a
//! suite at several square image sizes, with its time, peak memory and error.
//!
//! **Error** of a method at a size: the fraction of the image area given to the wrong face. The
//! truth is the exact visible set (the coverage map, every face opaque): each visible piece's
//! pixel ring (its exact vertices rounded once, [`crate::visibility::pixel_ring`]) is cut to
//! the squares of the pixels it covers (Sutherland–Hodgman in f64 against the four sides of
//! each pixel of its bounding box), and the areas are added per (pixel, face); background is
//! the rest of the pixel. A method answers one face (or background) per pixel, the one at the
//! pixel centre ([`crate::methods::Method::face_ids`]); its pixel error is 1 − the area
//! fraction of that face in the pixel, and its image error the mean over pixels
//! ([`truth::error_of`]).
//!
//! Invariants: the error is in [0, 1]; it depends only on the scene, the camera and the face
//! ids (no clock, no thread order); an exact object-space method (registry `exact` and
//! [`Engine::Object`]) computes the visible set itself, so its error is 0 by definition and is
//! recorded as 0, not measured. Image-space methods and the approximate painter are measured.
//!
//! **Bound of the area computation** (it is not exact). Let u = 2^-53, S the image side and k
//! the number of pieces meeting a pixel. Each ring vertex is within δ_in < 6e-12 px of the
//! exact vertex (the rounding of `pixel_ring`, below 4e-12 px, plus one grid unit, S·2^-53
//! px, for a crossing vertex rounded to f64). Each Sutherland–Hodgman crossing
//! `p + (q − p)·t` takes the clipped coordinate exactly and the other within 6u·M of the
//! crossing of the computed edge, M ≤ 3S px the largest coordinate of a piece (the guard
//! band); crossings are convex combinations, so four cuts (row strip, then column) move a
//! vertex by at most δ = δ_in + 72u·S px (3.9e-11 px at S = 4096). A convex polygon inside the
//! unit square has perimeter ≤ 4, so moving its vertices by δ changes its area by at most
//! 4δ + O(δ²). The shoelace sum is taken about the pixel corner (differences exact by Sterbenz
//! inside the pixel) over m ≤ n + 4 vertices of coordinates in [0, 1]: its error is at most
//! γ_{m+2}·Σ(|x_k·y_{k+1}| + |x_{k+1}·y_k|)/2 ≤ (m + 2)·m·u. So each (pixel, piece) area is
//! within 4δ + (m + 2)·m·u of the exact one (about 1.6e-10 at S = 4096), a pixel's total
//! within k times that, and the image error, summed over N pixels in f64, within the mean of
//! those plus N·u relative (2e-9 at S = 4096): below 2e-8 when no pixel meets more than 100
//! pieces at S ≤ 4096, far below the errors plotted (10^-4 and up).
//!
//! **Time**: the method's computation after load and projection, as `sightline bench` times it
//! ([`crate::render::compute`]), the median of a few runs. An object-space method's result does
//! not depend on the image size (the grid does not), so it is timed once per scene, at the
//! first size, and that time is reused for every size. **Peak memory**: the peak resident set
//! of a child process doing one measurement (load, projection, the method), read from
//! `/proc/self/status` (`VmHWM`) on Linux; `None` elsewhere.

pub mod child;
pub mod plot;
pub mod truth;

use crate::camera::{CamFile, Camera, NamedView};
use crate::error::{Error, Result};
use crate::methods::{Engine, METHODS, Method};
use crate::paint::{Fill, screen_paints};
use crate::pipeline;
use crate::project::{CullMode, ScreenScene};
use crate::raster::renderer::RasterOptions;
use crate::scene::{self, Scene, primitives};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// A benchmark suite.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Suite {
    /// The loadable files of `fixtures/` (not `fixtures/bad/`), iso view, or the camera file
    /// `NAME.cam` beside `NAME.obj` when there is one (`cyclic_bars.cam`).
    Fixtures,
    /// Generated scenes: triangle soups, tori, a sphere, iso view.
    Generated,
    /// `../shared/meshes/*.obj[.gz]` with their cameras `cams/NAME.cam`.
    Meshes,
}

/// Where a suite's scene comes from: enough to load it again in a child process.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// A file, framed by the iso view, or by a camera file.
    File {
        /// The scene file.
        path: PathBuf,
        /// Its camera file (its size replaced by each benchmark size).
        cam: Option<PathBuf>,
    },
    /// A generated scene by name (see [`generated`]).
    Generated(String),
}

/// One scene of a suite.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchScene {
    /// Its name in the results (file name, or the generated scene's name).
    pub name: String,
    /// How to load it.
    pub source: Source,
}

/// The generated suite's scene names.
pub const GENERATED: [&str; 5] = [
    "soup-100",
    "soup-1000",
    "interlocked-tori-24",
    "interpenetrating-tori-24",
    "sphere-5000",
];

/// The generated scene called `name`, if any.
pub fn generated(name: &str) -> Option<Scene> {
    Some(match name {
        "soup-100" => primitives::random_triangle_soup(100, 1),
        "soup-1000" => primitives::random_triangle_soup(1000, 1),
        "interlocked-tori-24" => primitives::interlocked_tori(24, 12),
        "interpenetrating-tori-24" => primitives::interpenetrating_tori(24, 12),
        "sphere-5000" => primitives::sphere_scene(5000),
        _ => return None,
    })
}

/// The scenes of `suite`, sorted by name. `fixtures` and `meshes` are the folders the fixtures
/// and meshes suites read; a missing meshes folder is an error.
pub fn scenes(suite: Suite, fixtures: &Path, meshes: &Path) -> Result<Vec<BenchScene>> {
    let list = |dir: &Path, keep: &dyn Fn(&str) -> bool| -> Result<Vec<PathBuf>> {
        let entries = std::fs::read_dir(dir).map_err(|source| Error::Io {
            path: dir.display().to_string(),
            source,
        })?;
        let mut out: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| {
                p.is_file()
                    && p.file_name()
                        .and_then(|n| n.to_str())
                        .is_some_and(|n| keep(&n.to_ascii_lowercase()))
            })
            .collect();
        out.sort();
        Ok(out)
    };
    let name_of = |p: &Path| {
        p.file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
    };
    Ok(match suite {
        Suite::Fixtures => list(fixtures, &|n| {
            [".obj", ".stl", ".ply", ".x3d"]
                .iter()
                .any(|e| n.ends_with(e))
        })?
        .into_iter()
        .map(|path| {
            // A fixture with a camera file beside it (cyclic_bars.cam) is seen through it.
            let cam = path.with_extension("cam");
            BenchScene {
                name: name_of(&path),
                source: Source::File {
                    cam: cam.is_file().then_some(cam),
                    path,
                },
            }
        })
        .collect(),
        Suite::Generated => GENERATED
            .iter()
            .map(|n| BenchScene {
                name: n.to_string(),
                source: Source::Generated(n.to_string()),
            })
            .collect(),
        Suite::Meshes => {
            if !meshes.is_dir() {
                return Err(Error::Options(format!(
                    "--suite meshes: the meshes folder {} is missing",
                    meshes.display()
                )));
            }
            list(meshes, &|n| n.ends_with(".obj") || n.ends_with(".obj.gz"))?
                .into_iter()
                .map(|path| {
                    let name = name_of(&path);
                    let stem = name.strip_suffix(".gz").unwrap_or(&name);
                    let stem = stem.strip_suffix(".obj").unwrap_or(stem).to_string();
                    let cam = meshes.join("cams").join(format!("{stem}.cam"));
                    BenchScene {
                        name,
                        source: Source::File {
                            path,
                            cam: cam.is_file().then_some(cam),
                        },
                    }
                })
                .collect()
        }
    })
}

/// A loaded benchmark scene and how to frame it at any size.
pub struct Loaded {
    /// The scene.
    pub scene: Scene,
    cam: Option<CamFile>,
}

impl BenchScene {
    /// Loads the scene (and its camera file).
    pub fn load(&self) -> Result<Loaded> {
        match &self.source {
            Source::File { path, cam } => {
                let scene = scene::load(path, None)?;
                let cam = cam.as_deref().map(CamFile::read).transpose()?;
                Ok(Loaded { scene, cam })
            }
            Source::Generated(name) => Ok(Loaded {
                scene: generated(name)
                    .ok_or_else(|| Error::Options(format!("no generated scene '{name}'")))?,
                cam: None,
            }),
        }
    }
}

impl Loaded {
    /// The camera at `size x size`: the camera file's with its size replaced, or the iso view
    /// fitted to the scene's bounds (40 degrees, perspective).
    pub fn camera(&self, size: u32) -> Result<Camera> {
        if let Some(c) = &self.cam {
            let mut cam = c.camera();
            cam.width = size;
            cam.height = size;
            return Ok(cam);
        }
        let bounds = self
            .scene
            .bounds()
            .ok_or_else(|| Error::Camera(format!("{}: no face to look at", self.scene.source)))?;
        Ok(Camera::fit(NamedView::Iso, bounds, false, 40.0, size, size))
    }
}

/// Is `method` exact and object-space (its error 0 by definition)?
pub fn is_exact_object(method: &Method) -> bool {
    method.exact && matches!(method.engine, Engine::Object(_))
}

/// `--methods`: `all`, or comma-separated registered names (each at most once), in the order
/// given.
pub fn parse_methods(s: &str) -> std::result::Result<Vec<&'static Method>, String> {
    if s.trim() == "all" {
        return Ok(METHODS.iter().collect());
    }
    let mut out: Vec<&'static Method> = Vec::new();
    for name in s.split(',').map(str::trim) {
        let m = crate::methods::method(name).ok_or_else(|| {
            format!(
                "unknown method '{name}' (known: all, {})",
                METHODS
                    .iter()
                    .map(|m| m.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        })?;
        if out.iter().any(|o| std::ptr::eq(*o, m)) {
            return Err(format!("method '{name}' is given twice"));
        }
        out.push(m);
    }
    Ok(out)
}

/// `--sizes`: comma-separated image sides in 1..=MAX_IMAGE_SIDE, increasing.
pub fn parse_sizes(s: &str) -> std::result::Result<Vec<u32>, String> {
    use crate::camera::MAX_IMAGE_SIDE;
    let mut out: Vec<u32> = Vec::new();
    for t in s.split(',').map(str::trim) {
        let v = t
            .parse::<u32>()
            .ok()
            .filter(|v| (1..=MAX_IMAGE_SIDE).contains(v))
            .ok_or_else(|| format!("'{t}' is not an image side in 1..={MAX_IMAGE_SIDE}"))?;
        if out.last().is_some_and(|&l| l >= v) {
            return Err(format!(
                "sizes must increase, got {v} after {}",
                out[out.len() - 1]
            ));
        }
        out.push(v);
    }
    Ok(out)
}

/// One timed run: the method's computation on `screen`, as `sightline bench` runs it (shaded
/// paints, so that translucent faces take the path they take in `render`; blending on), in
/// seconds, with what it computed.
pub fn timed_compute(
    method: &Method,
    scene: &Scene,
    screen: &ScreenScene,
    camera: &Camera,
) -> (f64, crate::render::Computed) {
    let paints = screen_paints(scene, screen, camera, Fill::Shade);
    let options = RasterOptions {
        paints: &paints,
        background: [1.0; 3],
        blend: true,
        depth: false,
    };
    let t = Instant::now();
    let computed = crate::render::compute(method, screen, &options, None);
    (t.elapsed().as_secs_f64(), computed)
}

/// [`timed_compute`]'s time only.
pub fn time_once(method: &Method, scene: &Scene, screen: &ScreenScene, camera: &Camera) -> f64 {
    timed_compute(method, scene, screen, camera).0
}

/// What one `bench-one` measurement reports besides the peak memory.
#[derive(Clone, Debug, PartialEq)]
pub struct Timing {
    /// The median seconds.
    pub time_s: f64,
    /// Visible pieces of an object-space method (its `visible_pieces` statistic).
    pub pieces: Option<u64>,
    /// What `auto` ran (its `chosen` statistic).
    pub chosen: Option<String>,
}

/// The median time of `method` on `scene` at `camera`: up to 5 runs, fewer when a run takes
/// over a second (at least 1), after one projection; with the last run's piece count and
/// choice.
pub fn time_median(method: &Method, scene: &Scene, camera: &Camera) -> Timing {
    let prepared = pipeline::prepare(scene, camera, CullMode::Auto);
    let mut times = Vec::new();
    let mut total = 0.0;
    let (mut pieces, mut chosen) = (None, None);
    while times.len() < 5 && (times.is_empty() || total < 2.0) {
        let (t, computed) = timed_compute(method, scene, &prepared.screen, camera);
        if let crate::render::Computed::Visible(v) = &computed {
            pieces = v.stats.get("visible_pieces").and_then(|p| p.as_u64());
            chosen = v
                .stats
                .get("chosen")
                .and_then(|c| c.as_str())
                .map(str::to_string);
        }
        total += t;
        times.push(t);
    }
    times.sort_by(f64::total_cmp);
    Timing {
        time_s: times[times.len() / 2],
        pieces,
        chosen,
    }
}

/// This process's peak resident set in kB (`VmHWM` of `/proc/self/status`), on Linux.
pub fn peak_rss_kb() -> Option<u64> {
    status_kb(
        &std::fs::read_to_string("/proc/self/status").ok()?,
        "VmHWM:",
    )
}

/// The kB value of the line starting with `key` in a `/proc/PID/status` text.
fn status_kb(status: &str, key: &str) -> Option<u64> {
    status
        .lines()
        .find_map(|l| l.strip_prefix(key))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
}

/// One result row: a method on a scene at one size.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Row {
    /// The scene's name.
    pub scene: String,
    /// The method's registry name.
    pub method: &'static str,
    /// "object" or "image".
    pub engine: &'static str,
    /// Registry `exact`.
    pub exact: bool,
    /// Image side (square images).
    pub size: u32,
    /// Median seconds after load and projection.
    pub time_s: f64,
    /// Peak resident set of the measuring child, kB (`None` when unknown).
    pub peak_rss_kb: Option<u64>,
    /// Fraction of the image area given to the wrong face (0 by definition for exact
    /// object-space methods).
    pub error: f64,
    /// Time and memory measured at another size and reused (object-space methods).
    pub reused: bool,
    /// Visible pieces (object-space methods: their `visible_pieces` statistic).
    pub pieces: Option<u64>,
    /// What `auto` ran (its `chosen` statistic); `None` for the other methods.
    pub chosen: Option<String>,
}

/// The CSV header of [`Row`]s.
pub const CSV_HEADER: &str =
    "scene,method,engine,exact,size,time_s,peak_rss_kb,error,reused,pieces,chosen";

/// `rows` as CSV (header, one line per row; scene names quoted when they need it).
pub fn csv(rows: &[Row]) -> String {
    let quote = |s: &str| {
        if s.contains([',', '"', '\n']) {
            format!("\"{}\"", s.replace('"', "\"\""))
        } else {
            s.to_string()
        }
    };
    let mut out = String::from(CSV_HEADER);
    out.push('\n');
    for r in rows {
        out.push_str(&format!(
            "{},{},{},{},{},{:.6e},{},{:.6e},{},{},{}\n",
            quote(&r.scene),
            r.method,
            r.engine,
            r.exact,
            r.size,
            r.time_s,
            r.peak_rss_kb.map_or(String::new(), |k| k.to_string()),
            r.error,
            r.reused,
            r.pieces.map_or(String::new(), |k| k.to_string()),
            quote(r.chosen.as_deref().unwrap_or(""))
        ));
    }
    out
}

/// Per scene and image-space (raster) method: the smallest size from which the exact method
/// (`coverage`) is faster than it at that size and every larger size measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Crossover {
    /// The scene.
    pub scene: String,
    /// The method compared with the exact one.
    pub method: &'static str,
    /// The exact method's time.
    pub exact_time_s: f64,
    /// The size, or `None` when the exact method is slower at the largest size.
    pub from_size: Option<u32>,
}

/// The exact method the crossovers are measured against.
pub const EXACT_REFERENCE: &str = "coverage";

/// The crossovers of `rows` (empty without [`EXACT_REFERENCE`] rows), in row order.
pub fn crossovers(rows: &[Row]) -> Vec<Crossover> {
    let mut out = Vec::new();
    let mut scenes: Vec<&str> = Vec::new();
    for r in rows {
        if !scenes.contains(&r.scene.as_str()) {
            scenes.push(&r.scene);
        }
    }
    for scene in scenes {
        let of = |m: &str| -> Vec<&Row> {
            let mut v: Vec<&Row> = rows
                .iter()
                .filter(|r| r.scene == scene && r.method == m)
                .collect();
            v.sort_by_key(|r| r.size);
            v
        };
        let Some(exact) = of(EXACT_REFERENCE).first().map(|r| r.time_s) else {
            continue;
        };
        let mut methods: Vec<&'static str> = Vec::new();
        for r in rows.iter().filter(|r| r.scene == scene) {
            if r.engine == "image" && !methods.contains(&r.method) {
                methods.push(r.method);
            }
        }
        for m in methods {
            let runs = of(m);
            // The first size from which every run is slower than the exact method.
            let mut from = None;
            for r in runs.iter().rev() {
                if r.time_s > exact {
                    from = Some(r.size);
                } else {
                    break;
                }
            }
            out.push(Crossover {
                scene: scene.to_string(),
                method: m,
                exact_time_s: exact,
                from_size: from,
            });
        }
    }
    out
}

/// A measurement with no result: which, and why (a limit or an error).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FailedRow {
    /// The scene's name.
    pub scene: String,
    /// The method's registry name.
    pub method: &'static str,
    /// Image side.
    pub size: u32,
    /// Why.
    pub failure: child::Failure,
}

/// The JSON document of a run: suite, sizes, rows, crossovers, and the measurements that
/// failed.
pub fn json(suite: Suite, sizes: &[u32], rows: &[Row], failed: &[FailedRow]) -> String {
    #[derive(Serialize)]
    struct Doc<'a> {
        suite: Suite,
        sizes: &'a [u32],
        error_definition: &'static str,
        rows: &'a [Row],
        crossovers: Vec<Crossover>,
        failed: &'a [FailedRow],
    }
    let doc = Doc {
        suite,
        sizes,
        error_definition: "fraction of the image area given to the wrong face: mean over pixels of 1 - the area fraction of the face shown at the pixel centre; 0 by definition for exact object-space methods",
        rows,
        crossovers: crossovers(rows),
        failed,
    };
    let mut s = serde_json::to_string_pretty(&doc).unwrap_or_else(|_| "{}".into());
    s.push('\n');
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(
        scene: &str,
        method: &'static str,
        engine: &'static str,
        exact: bool,
        size: u32,
        t: f64,
    ) -> Row {
        Row {
            scene: scene.into(),
            method,
            engine,
            exact,
            size,
            time_s: t,
            peak_rss_kb: None,
            error: 0.0,
            reused: false,
            pieces: None,
            chosen: None,
        }
    }

    #[test]
    fn a_sliver_between_pixel_centres_fools_every_method_but_not_the_area() {
        use crate::scene::SceneBuilder;
        use glam::DVec3;
        // A 4x4 orthographic view of [-2, 2]^2 (one world unit a pixel): a quad filling it at
        // z = 0, and in front of it a sliver over x in [0.1, 0.2], between the centres of
        // columns 2 (x = 0.5) and 1 (x = -0.5).
        let mut b = SceneBuilder::new("sliver");
        let m = b.default_material();
        b.begin_mesh("m");
        for (x0, x1, z) in [(-2.0, 2.0, 0.0), (0.1, 0.2, 1.0)] {
            let v: Vec<u32> = [(x0, -2.0), (x1, -2.0), (x1, 2.0), (x0, 2.0)]
                .iter()
                .map(|&(x, y)| b.add_vertex(DVec3::new(x, y, z)))
                .collect();
            b.add_face(&v, m);
        }
        let scene = b.finish().unwrap();
        let cam = CamFile::parse(
            "eye 0 0 10\ntarget 0 0 0\nup 0 1 0\nfovy 0\northo_height 4\nnear 0.5\nfar 100\nsize 4 4\n",
            "sliver.cam",
        )
        .unwrap()
        .camera();
        let screen = pipeline::prepare(&scene, &cam, CullMode::Auto).screen;
        let rings = truth::truth_rings(&screen);
        let covered = truth::covered_areas(&rings, 4, 4);
        assert!(
            covered.iter().all(|a| (a - 1.0).abs() < 1e-9),
            "{covered:?}"
        );
        let zbuffer = crate::methods::method("zbuffer").unwrap();
        let want = zbuffer.face_ids(&scene, &screen, &cam, None);
        assert!(
            want.iter().all(|&i| i.is_some() && i == want[0]),
            "{want:?}"
        );
        for m in &METHODS {
            let ids = m.face_ids(&scene, &screen, &cam, None);
            assert_eq!(ids, want, "{}", m.name);
            // Right at every centre, wrong on the sliver's area: 4 x 0.1 px of 16.
            let e = truth::error_of(&rings, 4, 4, &ids);
            assert!((e - 0.4 / 16.0).abs() < 1e-9, "{}: {e}", m.name);
        }
    }

    #[test]
    fn sizes_and_methods_parse_or_say_why_not() {
        assert_eq!(parse_sizes("32, 64,128"), Ok(vec![32, 64, 128]));
        assert!(parse_sizes("64,32").unwrap_err().contains("increase"));
        assert!(parse_sizes("0").is_err());
        assert!(parse_sizes("x").unwrap_err().contains("'x'"));
        assert!(parse_sizes("").is_err());
        assert_eq!(parse_methods("all").unwrap().len(), METHODS.len());
        let m = parse_methods("zbuffer,coverage").unwrap();
        assert_eq!(
            m.iter().map(|m| m.name).collect::<Vec<_>>(),
            ["zbuffer", "coverage"]
        );
        assert!(
            parse_methods("zbuffer,nope")
                .err()
                .unwrap()
                .contains("unknown method 'nope'")
        );
        assert!(parse_methods("zbuffer,zbuffer").is_err());
    }

    #[test]
    fn the_crossover_is_the_first_size_from_which_coverage_stays_faster() {
        let rows = vec![
            row("a", "coverage", "object", true, 64, 0.5),
            row("a", "zbuffer", "image", true, 64, 0.6),
            row("a", "zbuffer", "image", true, 128, 0.4),
            row("a", "zbuffer", "image", true, 256, 0.7),
            row("a", "zbuffer", "image", true, 512, 1.5),
            row("a", "scanline", "image", true, 64, 0.1),
            row("a", "bsp", "object", true, 64, 9.0),
            row("a", "painter", "object", false, 64, 9.0),
        ];
        let c = crossovers(&rows);
        assert_eq!(c.len(), 2);
        assert_eq!((c[0].method, c[0].from_size), ("zbuffer", Some(256)));
        assert_eq!((c[1].method, c[1].from_size), ("scanline", None));
        assert!(csv(&rows).starts_with(CSV_HEADER));
        assert_eq!(csv(&rows).lines().count(), rows.len() + 1);
    }
}
