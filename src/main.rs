//! The `sightline` command line: parses flags and calls the library.

/// `print!` that ends the process quietly when standard output is closed early (`sightline info
/// X | head`), as Unix tools do, instead of panicking; any other write error is reported.
macro_rules! print {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        if let Err(e) = write!(std::io::stdout().lock(), $($arg)*) {
            if e.kind() == std::io::ErrorKind::BrokenPipe {
                std::process::exit(0);
            }
            eprintln!("error: writing to standard output: {e}");
            std::process::exit(1);
        }
    }};
}

/// `println!` through [`print!`].
macro_rules! println {
    () => {
        print!("\n")
    };
    ($($arg:tt)*) => {{
        print!("{}\n", format_args!($($arg)*))
    }};
}

use clap::{Args, Parser, Subcommand};
use glam::DVec3;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use sightline::camera::{CamFile, Camera, CameraSpec, NamedView, Projection};
use sightline::output::{png, write_with};
use sightline::pipeline::{self, Fill};
use sightline::project::CullMode;
use sightline::scene::{self, Format, Scene};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

const EXAMPLES: &str = "\
Examples:
  sightline render fixtures/cube.obj -o cube.png
  sightline render fixtures/cube.obj -o cube.svg          (SVG and JSON: exact visible set)
  sightline render fixtures/cyclic_bars.obj --cam fixtures/cyclic_bars.cam -o bars.svg
  sightline render fixtures/cube.obj --fov 25 --eye=-3,2,4 -o near.png
  sightline render fixtures/seed_two_triangles.x3d --near 5 --far 10 --depth depth.png -o out.png
  sightline render mesh.stl --view front --ortho 2.5 --size 800x600 -o front.png
  sightline render mesh.ply --eye -1,2,3 --target 0,0,0 --fill id -o ids.png
  sightline render bunny.obj --cam bunny.cam -o - > bunny.png
  sightline render part.obj --stroke --light -1,2,1 --specular 0.3 -o part.svg
  sightline render part.obj --headlight -o part.png     # the seed's headlight, not key + fill
  sightline render part.obj --background none -o figure.svg   # no background, for a figure
  sightline render bunny.obj --cam bunny.cam --shading phong --specular 0.3 -o bunny.png
  sightline render glass.x3d --method abuffer -o glass.png
  sightline info mesh.obj --view iso";

#[derive(Parser)]
#[command(
    name = "sightline",
    version,
    about = "Exact visibility: which parts of a 3D scene a camera sees",
    after_help = EXAMPLES
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene: PNG by an image-space method (the z-buffer is the reference), or exact
    /// visible polygons as SVG, JSON or PNG (--method bsp).
    #[command(after_help = EXAMPLES)]
    Render(RenderArgs),
    /// Describe a scene: counts, closedness, bounds, culling, and which stages it needs.
    #[command(after_help = EXAMPLES)]
    Info(InfoArgs),
    /// Compare two methods' face ids at pixel centres (the z-buffer by default), and time both.
    /// Covered pixels: covered by either method. Interior pixels: covered by the reference, with
    /// one face and no background in their 3x3 neighbourhood there (edges sampled differently
    /// by two correct methods are left out).
    #[command(
        after_help = "Examples:\n  sightline compare fixtures/cube.obj --method bsp\n  sightline compare scene.obj --method painter --size 512x512\n  sightline compare scene.obj --method warnock --against scanline\n  sightline compare fixtures/cyclic_bars.obj --method painter --view front --diff diff.png"
    )]
    Compare(CompareArgs),
    /// Time each stage (load, project + cull, then one method) and report triangles per second.
    #[command(
        after_help = "Examples:\n  sightline bench fixtures/cube.obj --repeat 20\n  sightline bench --sphere 1000000 --size 1024x1024\n  sightline bench --soup 1000 --method bsp --repeat 3\n  sightline bench --sphere 100000 --method warnock --size 4096x4096"
    )]
    Bench(BenchArgs),
}

#[derive(Args)]
struct InputArgs {
    /// Scene file: .obj, .stl, .ply or .x3d (optionally gzipped: .obj.gz, ...).
    input: PathBuf,
    /// Read the input as this format, whatever its extension.
    #[arg(long, value_enum)]
    format: Option<Format>,
}

#[derive(Args)]
struct CameraArgs {
    /// Camera position, x,y,z.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    eye: Option<DVec3>,
    /// Point looked at, x,y,z.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    target: Option<DVec3>,
    /// Up direction, x,y,z.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    up: Option<DVec3>,
    /// Perspective projection with this vertical field of view, degrees (default 40).
    #[arg(
        long,
        value_name = "DEG",
        conflicts_with = "ortho",
        allow_negative_numbers = true
    )]
    fov: Option<f64>,
    /// Orthographic projection with this view height, world units.
    #[arg(long, value_name = "HEIGHT", allow_negative_numbers = true)]
    ortho: Option<f64>,
    /// Near clipping distance (default: fitted to the scene).
    #[arg(long, allow_hyphen_values = true)]
    near: Option<f64>,
    /// Far clipping distance (default: fitted to the scene).
    #[arg(long, allow_hyphen_values = true)]
    far: Option<f64>,
    /// Image size, WxH (default 1024x1024).
    #[arg(long, value_parser = parse_size, value_name = "WxH", allow_hyphen_values = true)]
    size: Option<(u32, u32)>,
    /// A named view fitted to the scene's bounds.
    #[arg(long, value_enum)]
    view: Option<NamedView>,
    /// A camera file (lines: eye x y z, target x y z, up x y z, fovy DEG, ortho_height H,
    /// near N, far F, size W H); fovy 0 means orthographic with view height ortho_height.
    #[arg(long, value_name = "FILE")]
    cam: Option<PathBuf>,
    /// Back-face culling: auto culls closed, consistently oriented, one-sided meshes.
    #[arg(long, value_enum, default_value_t = CullMode::Auto)]
    cull: CullMode,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum Method {
    /// Z-buffer with exact coverage and depth at pixel centres (the reference). PNG only.
    Zbuffer,
    /// A-buffer: per-pixel fragment lists, translucent faces blended back to front. PNG only.
    Abuffer,
    /// Watkins scanline: edge tables, active edges, spans. PNG only.
    Scanline,
    /// Warnock area subdivision down to a pixel. PNG only.
    Warnock,
    /// Exact visible polygons (object space): depth-aware coverage map; a 3D BSP for the painter
    /// order of translucent faces.
    Bsp,
    /// APPROXIMATE baseline: whole faces sorted by farthest depth, no splitting (as matplotlib's
    /// mplot3d and GL2PS's simple sort do). Wrong on cyclic overlap and interpenetration.
    Painter,
}

impl Method {
    fn name(self) -> &'static str {
        match self {
            Method::Zbuffer => "zbuffer",
            Method::Abuffer => "abuffer",
            Method::Scanline => "scanline",
            Method::Warnock => "warnock",
            Method::Bsp => "bsp",
            Method::Painter => "painter",
        }
    }

    /// Does it draw pixels (rather than polygons)?
    fn is_raster(self) -> bool {
        matches!(
            self,
            Method::Zbuffer | Method::Abuffer | Method::Scanline | Method::Warnock
        )
    }
}

/// What an image-space method produced: per pixel the winning screen polygon (or `EMPTY`), the
/// A-buffer's blended colours when it shaded, and its counters for `--stats`.
struct RasterResult {
    poly: Vec<u32>,
    /// The z-buffer's normalized depths, when asked for.
    depth: Option<Vec<f64>>,
    blended: Option<Vec<[f64; 3]>>,
    detail: String,
}

/// Runs an image-space method on a prepared scene.
fn run_raster(
    method: Method,
    scene: &Scene,
    prepared: &pipeline::Prepared,
    camera: &Camera,
    fill: Fill,
    background: [u8; 3],
    want_depth: bool,
) -> RasterResult {
    use sightline::raster::{abuffer, scanline, warnock, zbuffer};
    let screen = &prepared.screen;
    match method {
        Method::Zbuffer => {
            let bar = progress_bar(screen.polys.len() as u64, "rendering");
            let zb = zbuffer::render(screen, |n| bar.set_position(n as u64));
            bar.finish_and_clear();
            let detail = format!(
                "fragments {}, exact fallbacks: edge {} depth {}, depth ties {}",
                zb.stats.fragments,
                zb.stats.column_fallbacks,
                zb.stats.depth_fallbacks,
                zb.stats.depth_ties
            );
            RasterResult {
                depth: want_depth.then(|| zb.normalized_depth(screen)),
                poly: zb.poly,
                blended: None,
                detail,
            }
        }
        Method::Abuffer => {
            let paints = abuffer::paints(scene, screen, camera, fill);
            let bg = match fill {
                Fill::Id => [0.0; 3],
                Fill::Shade => background.map(|c| c as f64 / 255.0),
            };
            let ab = abuffer::render(screen, &paints, bg, abuffer::Options::default());
            RasterResult {
                depth: None,
                detail: format!("{:?}", ab.stats),
                blended: (fill == Fill::Shade).then_some(ab.color),
                poly: ab.poly,
            }
        }
        Method::Scanline => {
            let r = scanline::render(screen);
            RasterResult {
                depth: None,
                detail: format!("{:?}", r.stats),
                poly: r.poly,
                blended: None,
            }
        }
        Method::Warnock => {
            let r = warnock::render(screen);
            RasterResult {
                depth: None,
                detail: format!("{:?}", r.stats),
                poly: r.poly,
                blended: None,
            }
        }
        Method::Bsp | Method::Painter => unreachable!("object-space methods draw polygons"),
    }
}

/// `--shading`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum ShadingArg {
    Flat,
    Gouraud,
    Phong,
}

impl From<ShadingArg> for sightline::raster::lighting::Shading {
    fn from(s: ShadingArg) -> Self {
        use sightline::raster::lighting::Shading;
        match s {
            ShadingArg::Flat => Shading::Flat,
            ShadingArg::Gouraud => Shading::Gouraud,
            ShadingArg::Phong => Shading::Phong,
        }
    }
}

/// What the output file holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum OutputFormat {
    Png,
    Svg,
    Json,
}

#[derive(Args)]
struct RenderArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    camera: CameraArgs,
    /// Output file (.png, .svg or .json), or - for standard output.
    #[arg(short, long, value_name = "OUT")]
    output: PathBuf,
    /// Output format (default: from the output's extension; for -, PNG unless --method is
    /// bsp or painter, then SVG).
    #[arg(long, value_enum)]
    to: Option<OutputFormat>,
    /// Rendering method (default: bsp, the exact visible set, for SVG and JSON; zbuffer for PNG).
    #[arg(long, value_enum)]
    method: Option<Method>,
    /// Outline every region in SVG output (black, 0.5 px). SVG only.
    #[arg(long)]
    stroke: bool,
    /// Ask SVG viewers not to anti-alias (shape-rendering="crispEdges"). SVG only.
    #[arg(long)]
    crisp: bool,
    /// Pixel colours: flat shading, or face id + 1 as 24-bit RGB on black.
    #[arg(long, value_enum, default_value_t = Fill::Shade)]
    fill: Fill,
    /// Background of shaded images: r,g,b in 0..=255, or `none` (SVG without a background
    /// rectangle, for figures placed over other content). Default: an X3D scene's Background
    /// skyColor (black when it has none, as X3D specifies), white for other formats.
    #[arg(long, value_parser = parse_background, value_name = "R,G,B|none", allow_hyphen_values = true)]
    background: Option<BackgroundArg>,
    /// Also write the depth buffer as 16-bit grey PNG (0 near, 65535 far and background).
    #[arg(long, value_name = "FILE.png")]
    depth: Option<PathBuf>,
    /// Add a white directional light shining from direction x,y,z (world space) towards the
    /// scene; repeat for more. It adds to the camera's lights (the default key + fill, or
    /// --headlight) unless --no-headlight.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    light: Vec<DVec3>,
    /// Light with one white light along the view direction instead of the default key light
    /// (above left of the view) + fill light (right): the seed's look, every face seen head-on
    /// equally bright.
    #[arg(long, conflicts_with = "no_headlight")]
    headlight: bool,
    /// No light attached to the camera (neither the default key + fill nor --headlight): only
    /// the --light lights and the ambient term.
    #[arg(long)]
    no_headlight: bool,
    /// Phong specular coefficient Ks (0 = matte); flat fills take each face's highlight at its
    /// centroid.
    #[arg(
        long,
        value_name = "KS",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    specular: f64,
    /// Phong exponent n of the highlight.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_SHININESS, allow_negative_numbers = true)]
    shininess: f64,
    /// How light varies across a face in image-space output (zbuffer, scanline, warnock):
    /// flat (one colour per face), gouraud (corners, interpolated) or phong (per pixel).
    #[arg(long, value_enum, default_value_t = ShadingArg::Flat)]
    shading: ShadingArg,
    /// Print timings and counters to stderr (never into the output, whose bytes depend only on
    /// the input and the flags).
    #[arg(long)]
    stats: bool,
}

/// `--shininess` when not given.
const DEFAULT_SHININESS: f64 = 32.0;

#[derive(Args)]
struct CompareArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    camera: CameraArgs,
    /// The method to check.
    #[arg(long, value_enum, default_value_t = Method::Bsp)]
    method: Method,
    /// The method to check it against (interior pixels: see `compare --help`).
    #[arg(long, value_enum, default_value_t = Method::Zbuffer)]
    against: Method,
    /// Also write a PNG of the differences: red where the two cover a pixel with different faces,
    /// blue where only one covers it, over the reference in grey (one level per face) on white.
    #[arg(long, value_name = "FILE.png")]
    diff: Option<PathBuf>,
}

#[derive(Args)]
struct InfoArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    camera: CameraArgs,
}

#[derive(Args)]
struct BenchArgs {
    /// Scene file (omit with --sphere).
    #[arg(required_unless_present_any = ["sphere", "soup", "tori"])]
    input: Option<PathBuf>,
    /// Read the input as this format, whatever its extension.
    #[arg(long, value_enum)]
    format: Option<Format>,
    /// Instead of a file, a generated closed UV sphere of about this many triangles.
    #[arg(long, value_name = "TRIANGLES", conflicts_with_all = ["input", "soup", "tori"], value_parser = parse_count, allow_negative_numbers = true)]
    sphere: Option<usize>,
    /// Instead of a file, this many random triangles in a unit cube (two-sided, interpenetrating).
    #[arg(long, value_name = "TRIANGLES", conflicts_with_all = ["input", "tori"], value_parser = parse_count, allow_negative_numbers = true)]
    soup: Option<usize>,
    /// Instead of a file, two interlocked tori with this many segments around each ring.
    #[arg(long, value_name = "SEGMENTS", conflicts_with = "input", value_parser = parse_count, allow_negative_numbers = true)]
    tori: Option<usize>,
    /// Runs per stage; the median is reported.
    #[arg(long, default_value_t = 5, value_parser = parse_count, allow_negative_numbers = true)]
    repeat: usize,
    /// Method to time after projection.
    #[arg(long, value_enum, default_value_t = BenchMethod::Zbuffer)]
    method: BenchMethod,
    #[command(flatten)]
    camera: CameraArgs,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum BenchMethod {
    /// The exact z-buffer.
    Zbuffer,
    /// The A-buffer (flat paints, translucency blended).
    Abuffer,
    /// Watkins scanline.
    Scanline,
    /// Warnock area subdivision.
    Warnock,
    /// The exact visible set, as `render --method bsp` computes it for opaque scenes.
    Bsp,
    /// The exact visible set through the full 3D BSP walked front to back (the painter order
    /// translucent scenes need); slow on interpenetrating soups.
    BspTree,
}

fn parse_vec3(s: &str) -> Result<DVec3, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|t| {
            t.trim()
                .parse::<f64>()
                .map_err(|_| format!("'{t}' is not a number"))
        })
        .collect::<Result<_, _>>()?;
    match v[..] {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(DVec3::new(x, y, z)),
        [_, _, _] => Err("values must be finite".into()),
        _ => Err(format!(
            "expected x,y,z (three numbers), got {} values",
            v.len()
        )),
    }
}

/// A count of at least 1.
fn parse_count(s: &str) -> Result<usize, String> {
    s.trim()
        .parse::<usize>()
        .ok()
        .filter(|&n| n >= 1)
        .ok_or_else(|| format!("'{s}' is not a whole number >= 1"))
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WxH, e.g. 1024x768, got '{s}'"))?;
    use sightline::camera::MAX_IMAGE_SIDE;
    let p = |t: &str| {
        t.trim()
            .parse::<u32>()
            .ok()
            .filter(|v| (1..=MAX_IMAGE_SIDE).contains(v))
            .ok_or_else(|| format!("'{t}' is not an image side in 1..={MAX_IMAGE_SIDE}"))
    };
    Ok((p(w)?, p(h)?))
}

/// `--background`: a colour, or none at all.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum BackgroundArg {
    Color([u8; 3]),
    None,
}

fn parse_background(s: &str) -> Result<BackgroundArg, String> {
    match s.trim() {
        "none" => Ok(BackgroundArg::None),
        rgb => parse_rgb(rgb).map(BackgroundArg::Color),
    }
}

/// The background a render draws: the flag's, else the scene's own (an X3D Background), else
/// white. `None`: no background (`--background none`, SVG only).
fn background_of(flag: Option<BackgroundArg>, scene: &Scene) -> Option<[u8; 3]> {
    match flag {
        Some(BackgroundArg::None) => None,
        Some(BackgroundArg::Color(c)) => Some(c),
        None => Some(
            scene
                .background
                .map(sightline::paint::to_u8)
                .unwrap_or([255; 3]),
        ),
    }
}

fn parse_rgb(s: &str) -> Result<[u8; 3], String> {
    let v: Vec<u8> = s
        .split(',')
        .map(|t| {
            t.trim()
                .parse::<u8>()
                .map_err(|_| format!("'{t}' is not in 0..=255"))
        })
        .collect::<Result<_, _>>()?;
    v.try_into()
        .map_err(|_| "expected r,g,b (three values in 0..=255)".to_string())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // Interrupted (Ctrl-C, SIGTERM, SIGHUP) while an output is written: leave no temporary file
    // beside it. The handler runs on a thread of its own, not in the signal's context.
    let _ = ctrlc::set_handler(|| {
        sightline::output::remove_unfinished_outputs();
        std::process::exit(130);
    });
    let result = match cli.command {
        Command::Render(a) => render(a),
        Command::Info(a) => info(a),
        Command::Compare(a) => compare(a),
        Command::Bench(a) => bench(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn progress_bar(len: u64, what: &str) -> ProgressBar {
    labelled_bar(len, what, "{pos}/{len}")
}

/// A bar labelled `what` showing `counts` (an indicatif template part) on a terminal, hidden
/// otherwise.
fn labelled_bar(len: u64, what: &str, counts: &str) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template(&format!("{{msg:10}} [{{bar:40}}] {counts} ({{elapsed}})"))
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    bar
}

/// One labelled bar per stage of the library's progress reports (`sightline::progress`), cleared
/// when the stage reaches its total.
#[derive(Default)]
struct StageBars {
    bar: std::cell::RefCell<Option<(&'static str, ProgressBar)>>,
}

impl StageBars {
    fn report(&self, stage: &'static str, done: u64, total: u64) {
        let mut current = self.bar.borrow_mut();
        if current.as_ref().is_none_or(|(s, _)| *s != stage) {
            if let Some((_, old)) = current.take() {
                old.finish_and_clear();
            }
            *current = Some((stage, progress_bar(total, stage)));
        }
        if let Some((_, bar)) = current.as_ref() {
            bar.set_length(total);
            bar.set_position(done);
            if done >= total {
                bar.finish_and_clear();
                *current = None;
            }
        }
    }
}

fn load_scene(input: &InputArgs) -> sightline::Result<Scene> {
    // Bytes of the file on disk (compressed for .gz), so the total is known from the start.
    let size = std::fs::metadata(&input.input).map_or(0, |m| m.len());
    let bar = labelled_bar(size, "loading", "{bytes}/{total_bytes}");
    let scene = scene::load_with_progress(&input.input, input.format, &mut |read, total| {
        bar.set_length(total);
        bar.set_position(read);
    });
    bar.finish_and_clear();
    let scene = scene?;
    let name = input.input.display();
    for w in &scene.stats.warnings {
        // Most loader warnings start with the file name and line already.
        if w.starts_with(&name.to_string()) {
            eprintln!("warning: {w}");
        } else {
            eprintln!("warning: {name}: {w}");
        }
    }
    Ok(scene)
}

fn camera_for(args: &CameraArgs, scene: &Scene) -> sightline::Result<Camera> {
    let cam_file = match &args.cam {
        Some(path) => {
            let name = path.display().to_string();
            let text = std::fs::read_to_string(path).map_err(|e| sightline::Error::Io {
                path: name.clone(),
                source: e,
            })?;
            Some(CamFile::parse(&text, &name)?)
        }
        None => None,
    };
    check_camera_flags(args, cam_file.as_ref())?;
    let spec = CameraSpec {
        cam_file,
        view: args.view,
        eye: args.eye,
        target: args.target,
        up: args.up,
        fovy_deg: args.fov,
        ortho_height: args.ortho,
        near: args.near,
        far: args.far,
        size: args.size,
    };
    let bounds = scene
        .bounds()
        .expect("a loaded scene has at least one face");
    spec.resolve(bounds, scene.viewpoint.as_ref())
}

/// Each numeric camera flag within its own range, named in the message (before the camera is
/// built, where a bad value would surface as some other part's error).
fn check_camera_flags(args: &CameraArgs, cam_file: Option<&CamFile>) -> sightline::Result<()> {
    let bad = |m: String| Err(sightline::Error::Camera(m));
    if let Some(f) = args.fov
        && !(f > 0.0 && f < 180.0)
    {
        return bad(format!("--fov must be in (0, 180) degrees (got {f})"));
    }
    if let Some(h) = args.ortho
        && !(h > 0.0 && h.is_finite())
    {
        return bad(format!("--ortho must be a view height > 0 (got {h})"));
    }
    for (flag, v) in [("--near", args.near), ("--far", args.far)] {
        if let Some(v) = v
            && !v.is_finite()
        {
            return bad(format!("{flag} must be a finite distance (got {v})"));
        }
    }
    let from_file_ortho =
        cam_file.is_some_and(|c| matches!(c.projection(), Projection::Orthographic { .. }));
    let perspective = args.ortho.is_none() && (args.fov.is_some() || !from_file_ortho);
    for (flag, v) in [("--near", args.near), ("--far", args.far)] {
        if let Some(v) = v
            && perspective
            && v <= 0.0
        {
            return bad(format!(
                "{flag} must be > 0 for a perspective camera (got {v}; orthographic views, --ortho, take any value)"
            ));
        }
    }
    if let (Some(n), Some(f)) = (args.near, args.far)
        && f <= n
    {
        return bad(format!(
            "--near must be less than --far (near {n}, far {f})"
        ));
    }
    // An orthographic camera file may put its near plane behind the eye; made perspective by
    // --fov, it needs a near plane in front.
    if let (Some(file), Some(path)) = (cam_file, &args.cam)
        && perspective
        && args.near.is_none()
        && file.near <= 0.0
    {
        return bad(format!(
            "{}: near {} is not > 0: --fov makes the camera perspective, which needs a near plane in front of the eye (give --near)",
            path.display(),
            file.near
        ));
    }
    Ok(())
}

fn output_format(a: &RenderArgs) -> sightline::Result<OutputFormat> {
    if let Some(f) = a.to {
        return Ok(f);
    }
    let ext = a
        .output
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    Ok(match ext.as_deref() {
        Some("png") => OutputFormat::Png,
        Some("svg") => OutputFormat::Svg,
        Some("json") => OutputFormat::Json,
        _ if a.output.as_os_str() == "-" => match a.method.is_none_or(Method::is_raster) {
            true => OutputFormat::Png,
            false => OutputFormat::Svg,
        },
        _ => {
            return Err(sightline::Error::Output(format!(
                "{}: unknown output extension (use .png, .svg or .json, or --to)",
                a.output.display()
            )));
        }
    })
}

/// Would this run dump a binary PNG onto a terminal (`-o -` with standard output a terminal)?
/// Text (SVG, JSON) is fine there.
fn refuses_binary_output(format: OutputFormat, output: &Path, stdout_is_terminal: bool) -> bool {
    format == OutputFormat::Png && output.as_os_str() == "-" && stdout_is_terminal
}

/// Is `path` a terminal (`/dev/tty`, `/dev/stdout` on one)? Only character devices are opened
/// to ask: opening a FIFO to write would wait for its reader.
fn is_terminal_path(path: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt;
    std::fs::metadata(path).is_ok_and(|m| m.file_type().is_char_device())
        && std::fs::OpenOptions::new()
            .write(true)
            .open(path)
            .is_ok_and(|f| f.is_terminal())
}

/// The first flag given that this output would ignore, with why; `None` when all apply.
fn ignored_flag(a: &RenderArgs, format: OutputFormat) -> Option<String> {
    let name = |f: OutputFormat| match f {
        OutputFormat::Png => "PNG",
        OutputFormat::Svg => "SVG",
        OutputFormat::Json => "JSON",
    };
    let svg_only = [
        ("--stroke", a.stroke),
        ("--crisp", a.crisp),
        (
            "--background none",
            a.background == Some(BackgroundArg::None),
        ),
    ];
    if let Some((flag, _)) = svg_only.iter().find(|(_, given)| *given)
        && format != OutputFormat::Svg
    {
        return Some(format!(
            "{flag} applies to SVG output only (this run writes {})",
            name(format)
        ));
    }
    // Flags that change the shaded colours (values other than the defaults).
    let lighting = [
        ("--specular", a.specular != 0.0),
        ("--shininess", a.shininess != DEFAULT_SHININESS),
        ("--light", !a.light.is_empty()),
        ("--headlight", a.headlight),
        ("--no-headlight", a.no_headlight),
        ("--background", a.background.is_some()),
        ("--shading", a.shading != ShadingArg::Flat),
    ];
    let (flag, _) = lighting.iter().find(|(_, given)| *given)?;
    if a.fill == Fill::Id {
        return Some(format!(
            "{flag} changes shaded colours: it does not apply to --fill id (face ids as colours)"
        ));
    }
    if format == OutputFormat::Json {
        return Some(format!(
            "{flag} changes colours: it does not apply to JSON output (regions and materials, no colours)"
        ));
    }
    None
}

/// The drawing of an object-space method, with its stats. `merge_surfaces`: draw coplanar faces
/// of one paint as one region (for pictures; per-face output such as JSON must not).
fn run_method(
    method: Method,
    scene: &Scene,
    prepared: &pipeline::Prepared,
    camera: &Camera,
    fill: Fill,
    merge_surfaces: bool,
) -> sightline::visibility::VisibilityResult {
    if method == Method::Bsp {
        // Seams are for vector drawings, which the pictures (merged surfaces) are.
        let m = sightline::visibility::BspMethod {
            merge_surfaces,
            seams: merge_surfaces,
        };
        let bars = StageBars::default();
        let report = |stage: &'static str, done, total| bars.report(stage, done, total);
        let report: Option<sightline::progress::Report> =
            std::io::stderr().is_terminal().then_some(&report);
        return m.run_with_progress(scene, &prepared.screen, camera, fill, report);
    }
    let m = sightline::visibility::method_by_name(method.name())
        .expect("every object-space CLI method is registered");
    m.run(scene, &prepared.screen, camera, fill)
}

fn render(a: RenderArgs) -> sightline::Result<()> {
    let format = output_format(&a)?;
    // The exact visible set for vector output; the reference z-buffer for pixels.
    let method = a.method.unwrap_or(match format {
        OutputFormat::Png => Method::Zbuffer,
        OutputFormat::Svg | OutputFormat::Json => Method::Bsp,
    });
    if refuses_binary_output(format, &a.output, std::io::stdout().is_terminal())
        || (format == OutputFormat::Png && is_terminal_path(&a.output))
    {
        return Err(sightline::Error::Output(
            "not writing a binary PNG to a terminal: redirect standard output (-o - > out.png), or give a file (-o out.png)".into(),
        ));
    }
    if let Some(message) = ignored_flag(&a, format) {
        return Err(sightline::Error::Output(message));
    }
    if method.is_raster() && format != OutputFormat::Png {
        return Err(sightline::Error::Output(format!(
            "--method {} draws pixels: write it as PNG (use --method bsp for SVG or JSON)",
            method.name()
        )));
    }
    if a.depth.is_some() && method != Method::Zbuffer {
        return Err(sightline::Error::Output(
            "--depth needs --method zbuffer".into(),
        ));
    }
    if a.shading != ShadingArg::Flat
        && !matches!(method, Method::Zbuffer | Method::Scanline | Method::Warnock)
    {
        return Err(sightline::Error::Output(format!(
            "--shading {} needs --method zbuffer, scanline or warnock ({} draws flat colours)",
            clap::ValueEnum::to_possible_value(&a.shading)
                .map(|v| v.get_name().to_string())
                .unwrap_or_default(),
            method.name()
        )));
    }
    for (name, v) in [("--specular", a.specular), ("--shininess", a.shininess)] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(sightline::Error::Output(format!(
                "{name} must be a finite number >= 0, not {v}"
            )));
        }
    }
    let t0 = Instant::now();
    let mut scene = load_scene(&a.input)?;
    let t_load = t0.elapsed();
    scene.lights.camera = match (a.headlight, a.no_headlight) {
        (true, _) => sightline::scene::CameraLights::Headlight,
        (_, true) => sightline::scene::CameraLights::None,
        _ => sightline::scene::CameraLights::KeyFill,
    };
    scene.lights.specular = a.specular;
    scene.lights.shininess = a.shininess;
    for l in &a.light {
        if *l == DVec3::ZERO {
            return Err(sightline::Error::Output(
                "--light 0,0,0 has no direction".into(),
            ));
        }
        scene
            .lights
            .lights
            .push(sightline::scene::Light::Directional {
                direction: -*l,
                intensity: [1.0; 3],
            });
    }
    let camera = camera_for(&a.camera, &scene)?;
    let t1 = Instant::now();
    let prepared = pipeline::prepare(&scene, &camera, a.camera.cull);
    let t_project = t1.elapsed();
    if prepared.screen.polys.is_empty() {
        let st = &prepared.screen.stats;
        eprintln!(
            "warning: the camera sees none of the {} faces ({} outside the view, {} back faces culled): the output shows only the background",
            st.faces, st.frustum_culled, st.backface_culled
        );
    }
    let background = background_of(a.background, &scene);
    // PNG pixels always have a background (`--background none` is refused for PNG above).
    let background_rgb = background.unwrap_or([255; 3]);
    let t2 = Instant::now();
    // What writes the output, streamed into the file (a drawing's PNG is rasterized by strips).
    type Emit<'a> = Box<dyn FnOnce(&mut dyn std::io::Write) -> std::io::Result<()> + 'a>;
    let (emit, detail): (Emit, _) = if method.is_raster() {
        let r = run_raster(
            method,
            &scene,
            &prepared,
            &camera,
            a.fill,
            background_rgb,
            a.depth.is_some(),
        );
        use sightline::raster::lighting;
        let textured = scene.material_textures.iter().any(Option::is_some);
        if textured && method == Method::Abuffer && a.fill == Fill::Shade {
            eprintln!(
                "warning: the A-buffer blends flat colours: textures are not applied (use --method zbuffer, scanline or warnock)"
            );
        }
        let image = match r.blended {
            Some(colors) => colors.into_iter().map(sightline::paint::to_u8).collect(),
            // Per-pixel lighting or textures: the ray through each pixel centre.
            None if a.fill == Fill::Shade && (a.shading != ShadingArg::Flat || textured) => {
                let textures = lighting::Textures::load(&scene);
                for w in &textures.warnings {
                    eprintln!("warning: {w}");
                }
                lighting::shade_polys(
                    &scene,
                    &prepared.screen,
                    &r.poly,
                    camera.width,
                    &camera,
                    &lighting::Lighting::of_scene(&scene, &camera),
                    a.shading.into(),
                    &textures,
                    background_rgb.map(|c| c as f64 / 255.0),
                )
                .into_iter()
                .map(sightline::paint::to_u8)
                .collect()
            }
            None => pipeline::colorize_polys(
                &scene,
                &prepared.screen,
                &r.poly,
                &camera,
                a.fill,
                background_rgb,
            ),
        };
        if let (Some(depth_path), Some(depth)) = (&a.depth, &r.depth) {
            write_with(depth_path, |w| {
                png::write_depth16(w, camera.width, camera.height, depth)
            })?;
        }
        let (width, height) = (camera.width, camera.height);
        (
            Box::new(move |w| png::write_rgb(w, width, height, &image)),
            r.detail,
        )
    } else {
        let merge = format != OutputFormat::Json;
        let mut result = run_method(method, &scene, &prepared, &camera, a.fill, merge);
        sightline::output::canonical::canonicalize(&mut result.drawing);
        if result.drawing.background.is_none() {
            result.drawing.background = background.map(|c| c.map(|v| v as f64 / 255.0));
        }
        let detail = serde_json::Value::Object(result.stats.clone()).to_string();
        let emit: Emit = match format {
            OutputFormat::Svg => {
                let options = sightline::output::svg::SvgOptions {
                    stroke: a.stroke.then_some(([0.0; 3], 0.5)),
                    crisp: a.crisp,
                };
                let svg = sightline::output::svg::write_svg(&result.drawing, &options);
                Box::new(move |w| w.write_all(svg.as_bytes()))
            }
            OutputFormat::Json => {
                let mut stats = result.stats.clone();
                stats.insert("method".into(), method.name().into());
                let json = sightline::output::json::write_json(&result.drawing, &scene, &stats);
                Box::new(move |w| w.write_all(json.as_bytes()))
            }
            OutputFormat::Png => {
                Box::new(move |w| sightline::output::raster_drawing::write_png(&result.drawing, w))
            }
        };
        (emit, detail)
    };
    let t_method = t2.elapsed();
    write_with(&a.output, emit)?;
    if a.stats {
        let s = &prepared.screen.stats;
        eprintln!(
            "load {:.3}s, project+cull {:.3}s, {} {:.3}s",
            t_load.as_secs_f64(),
            t_project.as_secs_f64(),
            method.name(),
            t_method.as_secs_f64()
        );
        eprintln!(
            "faces {} -> on screen {} (frustum culled {}, back faces culled {}, clipped {}, degenerate after snap {})",
            s.faces,
            s.visible_polys,
            s.frustum_culled,
            s.backface_culled,
            s.clipped,
            s.degenerate_after_snap
        );
        eprintln!("{detail}");
    }
    Ok(())
}

/// A method's face id at every pixel centre, and its time after projection.
fn face_ids_of(
    method: Method,
    scene: &Scene,
    prepared: &pipeline::Prepared,
    camera: &Camera,
) -> (Vec<Option<u32>>, f64) {
    let t = Instant::now();
    let ids = if method.is_raster() {
        let r = run_raster(method, scene, prepared, camera, Fill::Id, [0; 3], false);
        let polys = &prepared.screen.polys;
        r.poly
            .iter()
            .map(|&p| (p != sightline::raster::EMPTY).then(|| polys[p as usize].id))
            .collect()
    } else {
        let result = run_method(method, scene, prepared, camera, Fill::Id, false);
        sightline::output::raster_drawing::face_ids(&result.drawing)
    };
    (ids, t.elapsed().as_secs_f64())
}

fn compare(a: CompareArgs) -> sightline::Result<()> {
    let scene = load_scene(&a.input)?;
    let camera = camera_for(&a.camera, &scene)?;
    let prepared = pipeline::prepare(&scene, &camera, a.camera.cull);
    let (reference, t_ref) = face_ids_of(a.against, &scene, &prepared, &camera);
    let (ids, t_method) = face_ids_of(a.method, &scene, &prepared, &camera);
    let c = pipeline::compare_ids(
        &reference,
        &ids,
        camera.width as usize,
        camera.height as usize,
    );
    if let Some(path) = &a.diff {
        let image = pipeline::diff_image(&reference, &ids);
        write_with(path, |w| {
            png::write_rgb(w, camera.width, camera.height, &image)
        })?;
    }
    let pct = |n: usize, d: usize| 100.0 * n as f64 / d.max(1) as f64;
    println!(
        "{} vs {} at {}x{}:",
        a.method.name(),
        a.against.name(),
        camera.width,
        camera.height
    );
    println!(
        "  covered pixels  {:9}  mismatched {:9} ({:.4}%)",
        c.covered,
        c.covered_mismatch,
        pct(c.covered_mismatch, c.covered)
    );
    println!(
        "  interior pixels {:9}  mismatched {:9} ({:.4}%)",
        c.interior,
        c.interior_mismatch,
        pct(c.interior_mismatch, c.interior)
    );
    println!(
        "  time: {} {:.4} s, {} {:.4} s (after load and projection)",
        a.method.name(),
        t_method,
        a.against.name(),
        t_ref
    );
    Ok(())
}

fn info(a: InfoArgs) -> sightline::Result<()> {
    let scene = load_scene(&a.input)?;
    let camera = camera_for(&a.camera, &scene)?;
    let prepared = pipeline::prepare(&scene, &camera, a.camera.cull);
    print!("{}", describe(&a.input.input, &scene, &camera, &prepared));
    Ok(())
}

fn bench(a: BenchArgs) -> sightline::Result<()> {
    let repeat = a.repeat.max(1);
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let mut load_times = Vec::new();
    let scene = match (&a.input, a.sphere) {
        (Some(path), _) => {
            let mut scene = None;
            for _ in 0..repeat {
                let t = Instant::now();
                scene = Some(load_scene(&InputArgs {
                    input: path.clone(),
                    format: a.format,
                })?);
                load_times.push(t.elapsed().as_secs_f64());
            }
            scene.expect("repeat >= 1")
        }
        (None, Some(n)) => scene::primitives::sphere_scene(n),
        (None, None) => match (a.soup, a.tori) {
            (Some(n), _) => scene::primitives::random_triangle_soup(n, 1),
            (None, Some(n)) => scene::primitives::interlocked_tori(n, (n / 2).max(3)),
            (None, None) => unreachable!("clap requires an input, --sphere, --soup or --tori"),
        },
    };
    let camera = camera_for(&a.camera, &scene)?;
    let (mut project_times, mut method_times) = (Vec::new(), Vec::new());
    let mut report = String::new();
    let bar = progress_bar(repeat as u64, "bench");
    let mut screen_stats = None;
    for k in 0..repeat {
        let t = Instant::now();
        let prepared = pipeline::prepare(&scene, &camera, a.camera.cull);
        project_times.push(t.elapsed().as_secs_f64());
        let fallbacks_before = sightline::exact::predicates::fallback_count();
        let t = Instant::now();
        report = match a.method {
            BenchMethod::Zbuffer => {
                let zb = sightline::raster::zbuffer::render(&prepared.screen, |_| {});
                method_times.push(t.elapsed().as_secs_f64());
                format!(
                    "fragments {}, exact fallbacks: edge {} depth {}",
                    zb.stats.fragments, zb.stats.column_fallbacks, zb.stats.depth_fallbacks
                )
            }
            BenchMethod::Abuffer => {
                use sightline::raster::abuffer;
                let paints = abuffer::paints(&scene, &prepared.screen, &camera, Fill::Shade);
                let ab = abuffer::render(
                    &prepared.screen,
                    &paints,
                    [1.0; 3],
                    abuffer::Options::default(),
                );
                method_times.push(t.elapsed().as_secs_f64());
                format!("{:?}", ab.stats)
            }
            BenchMethod::Scanline => {
                let r = sightline::raster::scanline::render(&prepared.screen);
                method_times.push(t.elapsed().as_secs_f64());
                format!("{:?}", r.stats)
            }
            BenchMethod::Warnock => {
                let r = sightline::raster::warnock::render(&prepared.screen);
                method_times.push(t.elapsed().as_secs_f64());
                format!("{:?}", r.stats)
            }
            BenchMethod::Bsp => {
                let (visible, cs) = sightline::visibility::bsp::visible_set(&prepared.screen);
                method_times.push(t.elapsed().as_secs_f64());
                format!(
                    "pieces {} -> visible pieces {} ({:.3} per polygon), replaced {}, overlap tests {}, exact fallbacks {}",
                    cs.inserted,
                    visible.pieces.len(),
                    visible.pieces.len() as f64 / prepared.screen.polys.len().max(1) as f64,
                    cs.replaced,
                    cs.overlap_tests,
                    sightline::exact::predicates::fallback_count() - fallbacks_before
                )
            }
            BenchMethod::BspTree => {
                let mut bsp = sightline::visibility::bsp::Bsp::build(&prepared.screen);
                let visible = bsp.visible_set(&prepared.screen);
                method_times.push(t.elapsed().as_secs_f64());
                let st = &bsp.stats;
                format!(
                    "pieces {} -> fragments {} ({:.3} per polygon), BSP nodes {} depth {}, visible pieces {}, coverage nodes {}, exact fallbacks {}",
                    st.pieces,
                    st.fragments,
                    st.fragments as f64 / st.polygons.max(1) as f64,
                    st.nodes,
                    st.depth,
                    visible.pieces.len(),
                    st.coverage_nodes,
                    sightline::exact::predicates::fallback_count() - fallbacks_before
                )
            }
        };
        screen_stats = Some(prepared.screen.stats);
        bar.set_position(k as u64 + 1);
    }
    bar.finish_and_clear();
    let st = screen_stats.expect("repeat >= 1");
    let tris: usize = scene.faces.iter().map(|f| f.len as usize - 2).sum();
    let (tp, tm) = (median(project_times), median(method_times));
    println!(
        "scene: {} faces ({} triangles), {}x{}, {} runs, medians:",
        scene.faces.len(),
        tris,
        camera.width,
        camera.height,
        repeat
    );
    if !load_times.is_empty() {
        let tl = median(load_times);
        println!(
            "  load             {:9.4} s  {:12.0} triangles/s",
            tl,
            tris as f64 / tl
        );
    }
    let name = match a.method {
        BenchMethod::Zbuffer => "z-buffer",
        BenchMethod::Abuffer => "a-buffer",
        BenchMethod::Scanline => "scanline",
        BenchMethod::Warnock => "warnock",
        BenchMethod::Bsp => "bsp",
        BenchMethod::BspTree => "bsp-tree",
    };
    println!(
        "  project + cull   {:9.4} s  {:12.0} triangles/s",
        tp,
        tris as f64 / tp
    );
    println!(
        "  {name:16} {:9.4} s  {:12.0} triangles/s",
        tm,
        tris as f64 / tm
    );
    println!(
        "  total            {:9.4} s  {:12.0} triangles/s",
        tp + tm,
        tris as f64 / (tp + tm)
    );
    println!(
        "  on screen {} (back faces culled {}, frustum culled {}); {}",
        st.visible_polys, st.backface_culled, st.frustum_culled, report
    );
    Ok(())
}

fn describe(path: &Path, scene: &Scene, camera: &Camera, p: &pipeline::Prepared) -> String {
    use std::fmt::Write;
    let mut o = String::new();
    let an = &p.analysis;
    let st = &p.screen.stats;
    let (lo, hi) = scene.bounds().expect("non-empty scene");
    let v3 = |v: DVec3| format!("({}, {}, {})", v.x, v.y, v.z);
    let _ = writeln!(o, "file: {}", path.display());
    let _ = writeln!(
        o,
        "faces: {} polygons from {} input faces ({} degenerate dropped, {} non-planar triangulated)",
        scene.faces.len(),
        scene.input_faces,
        scene.stats.degenerate_dropped,
        scene.stats.nonplanar_triangulated
    );
    let _ = writeln!(o, "vertices: {}", scene.positions.len());
    let closed = an.meshes.iter().filter(|m| m.closed()).count();
    let _ = writeln!(
        o,
        "meshes: {} ({} closed, {} open)",
        scene.meshes.len(),
        closed,
        scene.meshes.len() - closed
    );
    for (m, ma) in scene.meshes.iter().zip(&an.meshes).take(20) {
        let state = if ma.closed() {
            if ma.inside_out() {
                "closed, inside-out (flipped)".to_string()
            } else if ma.cullable() {
                "closed".to_string()
            } else {
                "closed, orientation uncertain (zero volume)".to_string()
            }
        } else {
            format!(
                "open ({} boundary, {} non-manifold, {} inconsistent edges)",
                ma.boundary_edges, ma.nonmanifold_edges, ma.inconsistent_edges
            )
        };
        let _ = writeln!(
            o,
            "  {}: {} faces, {}, volume {:.6e}",
            m.name,
            m.faces.len(),
            state,
            ma.signed_volume
        );
    }
    if scene.meshes.len() > 20 {
        let _ = writeln!(o, "  ... {} more", scene.meshes.len() - 20);
    }
    let _ = writeln!(o, "bounds: min {} max {}", v3(lo), v3(hi));
    let proj = match camera.projection {
        Projection::Perspective { fovy_deg } => format!("perspective, fovy {fovy_deg} deg"),
        Projection::Orthographic { height } => format!("orthographic, height {height}"),
    };
    let _ = writeln!(
        o,
        "camera: {proj}, eye {}, target {}, up {}, near {}, far {}, {}x{}",
        v3(camera.eye),
        v3(camera.target),
        v3(camera.up),
        camera.near,
        camera.far,
        camera.width,
        camera.height
    );
    let _ = writeln!(
        o,
        "culling: {} frustum culled, {} back faces culled ({} meshes cullable, {} cut by the near plane), {} clipped, {} degenerate after snapping",
        st.frustum_culled,
        st.backface_culled,
        st.culled_meshes,
        st.meshes_cut_by_near,
        st.clipped,
        st.degenerate_after_snap
    );
    let _ = writeln!(o, "on screen: {} polygons", st.visible_polys);
    let _ = writeln!(o, "stages needed:");
    let overlap = pipeline::screen_extents_overlap(&p.screen);
    let _ = writeln!(
        o,
        "  depth ordering (overlapping screen extents): {}",
        if overlap { "yes" } else { "no" }
    );
    let _ = writeln!(
        o,
        "  splitting (interpenetration possible between meshes): {}",
        if an.overlapping_mesh_pairs > 0 {
            format!(
                "yes, {} pairs of meshes with overlapping bounds",
                an.overlapping_mesh_pairs
            )
        } else {
            "no (self-intersection within a mesh is not checked)".to_string()
        }
    );
    let _ = writeln!(
        o,
        "  blending (translucency): {}",
        if an.translucent_faces > 0 {
            format!("yes, {} translucent faces", an.translucent_faces)
        } else {
            "no".to_string()
        }
    );
    let _ = writeln!(o, "two-sided faces: {}", an.two_sided_faces);
    let _ = writeln!(o, "warnings: {}", scene.stats.warnings.len());
    o
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Only a PNG to standard output on a terminal is refused; files, pipes and text are fine.
    #[test]
    fn binary_png_is_refused_on_a_terminal_only() {
        let dash = Path::new("-");
        assert!(refuses_binary_output(OutputFormat::Png, dash, true));
        assert!(!refuses_binary_output(OutputFormat::Png, dash, false));
        assert!(!refuses_binary_output(
            OutputFormat::Png,
            Path::new("a.png"),
            true
        ));
        assert!(!refuses_binary_output(OutputFormat::Svg, dash, true));
        assert!(!refuses_binary_output(OutputFormat::Json, dash, true));
    }
}
