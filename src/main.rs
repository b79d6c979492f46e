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
use sightline::camera::{CamFile, Camera, CameraSpec, NamedView};
use sightline::lines::{LineDrawing, LineKind, LineOptions, Visibility};
use sightline::methods::{self, METHODS, Method, Output};
use sightline::output::{png, write_with};
use sightline::pipeline::{self, Fill};
use sightline::project::CullMode;
use sightline::render::{self, Background, RenderOptions};
use sightline::report::SceneReport;
use sightline::scene::{self, CameraLights, DEFAULT_SHININESS, Format, Light, Scene, SceneLights};
use sightline::sheet;
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

const COMPARE_HELP: &str = "\
Examples:
  sightline compare fixtures/cube.obj --method coverage
  sightline compare scene.obj --method painter --size 512x512
  sightline compare scene.obj --method warnock --against scanline
  sightline compare fixtures/cyclic_bars.obj --method painter --view front --diff diff.png
  sightline compare fixtures/cube.obj --image theirs.png --view iso --diff where.png
  sightline compare bunny.obj --image blender.png --cam bunny.cam

With --image: the PNG holds at each pixel the id of the face seen at the pixel centre, plus
one, as 24-bit RGB (r = (id+1)>>16 & 255, g = (id+1)>>8 & 255, b = (id+1) & 255), black (or
alpha 0) for background, one sample at each pixel centre, no anti-aliasing, no colour
management: what `render --fill id` writes (docs/compare_image.md: how to make one with OpenGL
or Blender). 8-bit RGB, RGBA or palette; any alpha other than 0 or 255 is refused. The camera
is given by the camera flags as for render; its size is the image's (a --size that disagrees
is an error). Every face counts as opaque.
A pixel is wrong when the face it shows is not one whose visible piece contains the pixel
centre (exactly; a centre on a boundary accepts each face there, and background where the
boundary is the outline of what the faces cover), or when it shows background where faces
cover the centre. Reported: wrong pixels by kind (wrong face, missing face, extra face, ids
that are no face of the scene), covered pixels in the image and in the exact set, and the area
error: the fraction of the image area given to the wrong face (each pixel's area split among
the faces visible in it). --diff draws wrong faces red, missing or extra faces blue, unknown
ids magenta, over the image's right faces in grey on white.";

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
    /// Threads for the exact visible set of large scenes, solved strip by strip (0: one per
    /// core, or RAYON_NUM_THREADS). The output is the same, byte for byte, whatever the number.
    #[arg(
        long,
        global = true,
        default_value_t = 0,
        value_name = "N",
        allow_negative_numbers = true
    )]
    threads: usize,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene: PNG by an image-space method (the z-buffer is the reference), or exact
    /// visible polygons as SVG, JSON or PNG.
    #[command(after_help = EXAMPLES)]
    Render(RenderArgs),
    /// Describe a scene: counts, closedness, bounds, culling, and which stages it needs.
    #[command(after_help = EXAMPLES)]
    Info(InfoArgs),
    /// Compare two methods' face ids at pixel centres (the z-buffer by default), and time both;
    /// or, with --image, grade a face-id image made by any renderer against the exact visible
    /// set. Methods: covered pixels are covered by either method; interior pixels are covered
    /// by the reference, with one face and no background in their 3x3 neighbourhood there
    /// (edges sampled differently by two correct methods are left out).
    #[command(after_help = COMPARE_HELP)]
    Compare(CompareArgs),
    /// Time each stage (load, project + cull, then one method) and report triangles per second.
    #[command(
        after_help = "Examples:\n  sightline bench fixtures/cube.obj --repeat 20\n  sightline bench --sphere 1000000 --size 1024x1024\n  sightline bench --soup 1000 --method coverage --repeat 3\n  sightline bench --sphere 100000 --method warnock --size 4096x4096\n  sightline bench --suite generated --methods zbuffer,scanline,coverage,painter --sizes 256,512,1024,2048 --out bench-out\n  sightline bench --suite fixtures --methods zbuffer,coverage,painter --sizes 64,128 --out out\n\nWith --suite: every method on every scene of the suite at every size (square images), written\nto --out as results.csv, results.json and one plot per scene (plot-SCENE.svg and .png) of\nerror (fraction of the image area given to the wrong face) against time, log-log."
    )]
    Bench(BenchArgs),
    /// One measurement of `bench --suite`, in a child process: prints one JSON line.
    #[command(hide = true)]
    BenchOne(BenchOneArgs),
    /// Draw the scene's feature lines (silhouettes, boundaries, intersections, creases,
    /// material edges), visible ones solid and hidden ones dashed, as SVG, JSON, DXF or PDF.
    #[command(after_help = LINES_EXAMPLES)]
    Lines(LinesArgs),
    /// Lay out a drawing sheet: aligned orthographic hidden-line views and one pictorial view
    /// at a standard scale, with border and title block, as SVG in millimetres.
    #[command(after_help = SHEET_EXAMPLES)]
    Sheet(SheetArgs),
    /// Check the exact visible set on generated hard scenes (grazing faces, near-parallel
    /// stacks, deep perspective, far offsets, tiny scales, ...) against a slow big-rational
    /// reference at random points; or measure the cases against a world reference.
    #[command(after_help = STRESS_EXAMPLES)]
    Stress(StressArgs),
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

/// `--method`: any registered method ([`methods::METHODS`]), listed with its summary in the help.
fn method_arg() -> impl clap::builder::TypedValueParser<Value = &'static Method> {
    use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
    PossibleValuesParser::new(
        METHODS
            .iter()
            .map(|m| PossibleValue::new(m.name).help(m.summary)),
    )
    .map(|name| methods::method(&name).expect("only registered names parse"))
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
type OutputFormat = Output;

#[derive(Args)]
struct RenderArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    camera: CameraArgs,
    /// Output file (.png, .svg or .json), or - for standard output.
    #[arg(short, long, value_name = "OUT")]
    output: PathBuf,
    #[arg(long, value_enum, help = format!(
        "Output format (default: from the output's extension; for -, PNG unless --method is {}, then SVG)",
        methods::names_with(|m| !m.is_image_space())
    ))]
    to: Option<OutputFormat>,
    #[arg(long, value_parser = method_arg(), help = format!(
        "Rendering method (default: {} for SVG and JSON, {} for PNG)",
        methods::default_for(Output::Svg).name,
        methods::default_for(Output::Png).name
    ))]
    method: Option<&'static Method>,
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
    background: Option<Background>,
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
    #[arg(long, value_enum, default_value_t = ShadingArg::Flat, help = format!(
        "How light varies across a face in image-space output ({}): flat (one colour per face), gouraud (corners, interpolated) or phong (per pixel)",
        methods::names_with(|m| m.shading)
    ))]
    shading: ShadingArg,
    /// Print timings and counters to stderr (never into the output, whose bytes depend only on
    /// the input and the flags).
    #[arg(long)]
    stats: bool,
    /// Draw the visible feature lines over the filled drawing (shaded with edges), as `sightline
    /// lines --hidden off` draws them. SVG only.
    #[arg(long)]
    lines: bool,
}

#[derive(Args)]
struct CompareArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    camera: CameraArgs,
    /// The method to check.
    #[arg(long, value_parser = method_arg(), default_value = "coverage")]
    method: &'static Method,
    /// The method to check it against (interior pixels: see `compare --help`).
    #[arg(long, value_parser = method_arg(), default_value = "zbuffer")]
    against: &'static Method,
    /// Instead of a method, grade this face-id image (made by any renderer, `render --fill id`'s
    /// colours) against the exact visible set: see `compare --help`.
    #[arg(long, value_name = "THEIRS.png", conflicts_with_all = ["method", "against"])]
    image: Option<PathBuf>,
    /// Also write a PNG of the differences: red where the two cover a pixel with different faces,
    /// blue where only one covers it, over the reference in grey (one level per face) on white;
    /// with --image, magenta for ids that are no face of the scene.
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
    #[arg(required_unless_present_any = ["sphere", "exported_sphere", "soup", "tori", "suite"])]
    input: Option<PathBuf>,
    /// Instead of one scene, a suite: every method of --methods on every scene at every size of
    /// --sizes, written to --out (fixtures: fixtures/, iso view or NAME.cam; generated: soups, tori, a
    /// sphere; meshes: ../shared/meshes/*.obj[.gz] with cams/NAME.cam).
    #[arg(long, value_enum, conflicts_with_all = ["input", "sphere", "exported_sphere", "soup", "tori", "lines"], requires = "out")]
    suite: Option<sightline::benchmark::Suite>,
    /// With --suite: `all`, or registered method names, comma-separated.
    #[arg(long, value_parser = parse_methods, default_value = "all", requires = "suite")]
    methods: MethodList,
    /// With --suite: square image sides, comma-separated, increasing.
    #[arg(long, value_parser = parse_sizes, default_value = "256,512,1024,2048,4096", requires = "suite", allow_hyphen_values = true)]
    sizes: SizeList,
    /// With --suite: the folder the results and plots are written to (created if missing).
    #[arg(long, value_name = "DIR", requires = "suite")]
    out: Option<PathBuf>,
    /// With --suite: the folder of the suite's scene files (default fixtures/ for fixtures,
    /// ../shared/meshes for meshes).
    #[arg(long, value_name = "DIR", requires = "suite")]
    dir: Option<PathBuf>,
    /// With --suite: a measurement (one method on one scene at one size, in a child process)
    /// taking longer is stopped and recorded as failed.
    #[arg(long, value_name = "SECONDS", default_value_t = 600.0, requires = "suite", value_parser = parse_positive_seconds, allow_negative_numbers = true)]
    time_limit: f64,
    /// With --suite: a measurement whose resident memory grows past this is stopped and
    /// recorded as failed.
    #[arg(long, value_name = "MB", default_value_t = 8192, requires = "suite", value_parser = parse_count, allow_negative_numbers = true)]
    memory_limit: usize,
    /// Read the input as this format, whatever its extension.
    #[arg(long, value_enum)]
    format: Option<Format>,
    /// Instead of a file, a generated closed UV sphere of about this many triangles.
    #[arg(long, value_name = "TRIANGLES", conflicts_with_all = ["input", "exported_sphere", "soup", "tori"], value_parser = parse_count, allow_negative_numbers = true)]
    sphere: Option<usize>,
    /// Instead of a file, that sphere as many tools export it and `../shared/compare/scenes.py`
    /// writes its benchmark spheres: without the pole fans (open) and wound inwards (inside out).
    #[arg(long, value_name = "TRIANGLES", conflicts_with_all = ["input", "soup", "tori"], value_parser = parse_count, allow_negative_numbers = true)]
    exported_sphere: Option<usize>,
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
    #[arg(long, value_parser = method_arg(), default_value = "zbuffer")]
    method: &'static Method,
    /// Also time the hidden-line drawing: the visible set with every face opaque, then the
    /// lines read off it (`sightline lines`), with the line counts.
    #[arg(long)]
    lines: bool,
    #[command(flatten)]
    camera: CameraArgs,
}

/// `--methods` of `bench --suite`.
#[derive(Clone)]
struct MethodList(Vec<&'static Method>);

fn parse_methods(s: &str) -> Result<MethodList, String> {
    sightline::benchmark::parse_methods(s).map(MethodList)
}

/// `--sizes` of `bench --suite`.
#[derive(Clone)]
struct SizeList(Vec<u32>);

fn parse_sizes(s: &str) -> Result<SizeList, String> {
    sightline::benchmark::parse_sizes(s).map(SizeList)
}

#[derive(Args)]
struct BenchOneArgs {
    #[arg(long, value_enum)]
    suite: sightline::benchmark::Suite,
    #[arg(long)]
    scene: String,
    #[arg(long, value_parser = method_arg())]
    method: &'static Method,
    #[arg(long)]
    size: u32,
    #[arg(long)]
    dir: Option<PathBuf>,
}

const SHEET_EXAMPLES: &str = "\
Examples:
  sightline sheet part.obj -o part.svg                        (A3, third angle: front, top, right, iso)
  sightline sheet part.obj -o part.svg --projection first --paper a4 --date 2026-01-31
  sightline sheet part.stl -o part.svg --views front,right,top --scale 1:2 --hidden off
  sightline sheet part.obj --units in -o - > part.svg

Model coordinates are mm unless --units says otherwise; the scale is the largest of 1:1, 1:2,
1:5, 1:10, ... and 2:1, 5:1, 10:1, ... at which the views fit, or --scale. Third angle puts the
top view above the front view and the right view to its right; first angle puts the top view
below and the right view to its left.";

#[derive(Args)]
struct SheetArgs {
    #[command(flatten)]
    input: InputArgs,
    /// Output file (.svg), or - for standard output.
    #[arg(short, long, value_name = "OUT")]
    output: PathBuf,
    /// The views, comma-separated, each at most once: front, back, top, bottom, left, right
    /// (orthographic) and iso (pictorial).
    #[arg(long, value_parser = parse_sheet_views, default_value = "front,top,right,iso")]
    views: SheetViews,
    /// Where the views go around the front view: third angle (top above, right to the right)
    /// or first angle (top below, right to the left).
    #[arg(long, value_enum, default_value_t = sheet::ProjectionMethod::Third)]
    projection: sheet::ProjectionMethod,
    /// Paper size (landscape unless --portrait).
    #[arg(long, value_enum, default_value_t = sheet::Paper::A3)]
    paper: sheet::Paper,
    /// Portrait paper.
    #[arg(long)]
    portrait: bool,
    /// Scale paper:model, 1:N or N:1 (default: the largest of the standard series that fits).
    #[arg(long, value_parser = sheet::Scale::parse, value_name = "1:N|N:1")]
    scale: Option<sheet::Scale>,
    /// The unit of the model's coordinates.
    #[arg(long, value_enum, default_value_t = sheet::Units::Mm)]
    units: sheet::Units,
    /// The date in the title block (left blank without it: the output never depends on the
    /// clock).
    #[arg(long, value_parser = sheet::SheetDate::parse, value_name = "YYYY-MM-DD")]
    date: Option<sheet::SheetDate>,
    /// An edge is a crease line when its faces' normals differ by more than this, degrees.
    #[arg(long, value_name = "DEG", default_value_t = 30.0, value_parser = parse_crease, allow_negative_numbers = true)]
    crease: f64,
    /// Hidden lines: dashed, or not drawn.
    #[arg(long, value_enum, default_value_t = HiddenArg::Dashed)]
    hidden: HiddenArg,
}

const STRESS_EXAMPLES: &str = "\
Examples:
  sightline stress --family grazing --cases 100 --seed 1
  sightline stress --family all --cases 91000 --points 64 --jobs 2   (a million cases)
  sightline stress --family measured                           (issue 11's cases, world reference)

Families: grazing, stacks, decals, far-offsets, tiny, t-junctions, needles, fans, edge-on,
touching, cyclic. A failing case is shrunk and written as OBJ + .cam into --failures; the exit
status is 1 when any case fails.";

#[derive(Args)]
struct StressArgs {
    /// A family, all of them, or measured (the cases against a world reference).
    #[arg(long, value_parser = sightline::stress::Selection::parse, default_value = "all")]
    family: sightline::stress::Selection,
    /// Cases per family.
    #[arg(long, default_value_t = 10, value_parser = parse_count, allow_negative_numbers = true)]
    cases: usize,
    /// The run's seed: the same seed gives the same cases and the same report (times aside).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Where shrunk failing cases are written (OBJ + .cam).
    #[arg(long, value_name = "DIR", default_value = "stress-failures")]
    failures: PathBuf,
    /// Sample points per case (default 256; measured: pixel centres per case, default all).
    #[arg(long, value_name = "K", value_parser = parse_count, allow_negative_numbers = true)]
    points: Option<usize>,
    /// Threads running cases (the report is the same for any number).
    #[arg(long, default_value_t = 1, value_parser = parse_count, allow_negative_numbers = true)]
    jobs: usize,
}

/// `--views` of `sheet`.
#[derive(Clone, Debug)]
struct SheetViews(Vec<NamedView>);

fn parse_sheet_views(s: &str) -> Result<SheetViews, String> {
    sheet::parse_views(s).map(SheetViews)
}

/// `--crease`: an angle in [0, 180] degrees.
fn parse_crease(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|d| (0.0..=180.0).contains(d))
        .ok_or_else(|| format!("--crease must be in [0, 180] degrees, got '{s}'"))
}

/// The comma-separated values of a flag, or an error naming the first that does not parse
/// (`'{value}' is {not_one}`).
fn parse_list<T: std::str::FromStr>(s: &str, not_one: &str) -> Result<Vec<T>, String> {
    s.split(',')
        .map(|t| {
            t.trim()
                .parse::<T>()
                .map_err(|_| format!("'{t}' is {not_one}"))
        })
        .collect()
}

fn parse_vec3(s: &str) -> Result<DVec3, String> {
    let v: Vec<f64> = parse_list(s, "not a number")?;
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

fn parse_positive_seconds(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|&t| t > 0.0 && t <= 1e6)
        .ok_or_else(|| format!("'{s}' is not a number of seconds above 0 (at most 1000000)"))
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
fn parse_background(s: &str) -> Result<Background, String> {
    match s.trim() {
        "none" => Ok(Background::None),
        rgb => parse_rgb(rgb).map(Background::Color),
    }
}

fn parse_rgb(s: &str) -> Result<[u8; 3], String> {
    let v: Vec<u8> = parse_list(s, "not in 0..=255")?;
    v.try_into()
        .map_err(|_| "expected r,g,b (three values in 0..=255)".to_string())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if cli.threads > 0 {
        // Fails only if a pool was already made: none is before this point.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(cli.threads)
            .build_global();
    }
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
        Command::Bench(a) => match a.suite {
            Some(suite) => bench_suite(suite, a),
            None => bench(a),
        },
        Command::BenchOne(a) => bench_one(a),
        Command::Lines(a) => lines(a),
        Command::Sheet(a) => sheet_command(a),
        Command::Stress(a) => stress(a),
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
    bar: std::sync::Mutex<Option<(&'static str, ProgressBar)>>,
}

impl StageBars {
    fn report(&self, stage: &'static str, done: u64, total: u64) {
        let mut current = self.bar.lock().unwrap_or_else(|e| e.into_inner());
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
    camera_of_size(args, scene, args.size)
}

/// The camera of the flags with the image size `size` instead of `--size`'s.
fn camera_of_size(
    args: &CameraArgs,
    scene: &Scene,
    size: Option<(u32, u32)>,
) -> sightline::Result<Camera> {
    let spec = CameraSpec {
        cam_file: args.cam.as_deref().map(CamFile::read).transpose()?,
        view: args.view,
        eye: args.eye,
        target: args.target,
        up: args.up,
        fovy_deg: args.fov,
        ortho_height: args.ortho,
        near: args.near,
        far: args.far,
        size,
    };
    spec.check(args.cam.as_deref())?;
    spec.resolve_for(scene)
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

/// Progress bars for the library's long stages when standard error is a terminal; `None`
/// otherwise (no cost, no output).
fn with_bars<T>(run: impl FnOnce(Option<sightline::progress::Report>) -> T) -> T {
    let bars = StageBars::default();
    let report = |stage: &'static str, done, total| bars.report(stage, done, total);
    run(std::io::stderr().is_terminal().then_some(&report))
}

fn render(a: RenderArgs) -> sightline::Result<()> {
    let format = match a.to {
        Some(f) => f,
        None => render::output_for(&a.output, a.method)?,
    };
    let options = RenderOptions {
        format,
        method: a.method,
        fill: a.fill,
        background: a.background.unwrap_or_default(),
        shading: a.shading.into(),
        depth: a.depth.is_some(),
        stroke: a.stroke,
        crisp: a.crisp,
        lines: a.lines.then(|| LineOptions {
            hidden: false,
            cull: a.camera.cull,
            ..LineOptions::default()
        }),
    };
    if refuses_binary_output(format, &a.output, std::io::stdout().is_terminal())
        || (format == OutputFormat::Png && is_terminal_path(&a.output))
    {
        return Err(sightline::Error::Output(
            "not writing a binary PNG to a terminal: redirect standard output (-o - > out.png), or give a file (-o out.png)".into(),
        ));
    }
    let lights = SceneLights {
        camera: match (a.headlight, a.no_headlight) {
            (true, _) => CameraLights::Headlight,
            (_, true) => CameraLights::None,
            _ => CameraLights::KeyFill,
        },
        lights: a
            .light
            .iter()
            .map(|&from| Light::white_from(from))
            .collect(),
        specular: a.specular,
        shininess: a.shininess,
    };
    let method = options.check(&lights)?;
    let t0 = Instant::now();
    let mut scene = load_scene(&a.input)?;
    let t_load = t0.elapsed();
    scene.lights = lights;
    let camera = camera_for(&a.camera, &scene)?;
    let t1 = Instant::now();
    let prepared = pipeline::prepare(&scene, &camera, a.camera.cull);
    let t_project = t1.elapsed();
    let t2 = Instant::now();
    let rendered =
        with_bars(|report| render::render(&scene, &camera, &prepared.screen, &options, report))?;
    let t_method = t2.elapsed();
    for w in &rendered.warnings {
        eprintln!("warning: {w}");
    }
    if let (Some(depth_path), Some(depth)) = (&a.depth, &rendered.depth) {
        write_with(depth_path, |w| {
            png::write_depth16(w, camera.width, camera.height, depth)
        })?;
    }
    let t3 = Instant::now();
    write_with(&a.output, |w| rendered.write(w))?;
    let t_write = t3.elapsed();
    if a.stats {
        let s = &prepared.screen.stats;
        let stages: Vec<String> = (rendered.stage_seconds.iter())
            .map(|(name, t)| format!("{name} {t:.3}s"))
            .collect();
        eprintln!(
            "load {:.3}s, project+cull {:.3}s, {} {:.3}s ({}), write {:.3}s",
            t_load.as_secs_f64(),
            t_project.as_secs_f64(),
            method.name,
            t_method.as_secs_f64(),
            stages.join(", "),
            t_write.as_secs_f64()
        );
        eprintln!(
            "faces {} -> on screen {} (frustum culled {}, back faces culled {}, clipped {}, degenerate after snap {}, split off their plane by the snap {})",
            s.faces,
            s.visible_polys,
            s.frustum_culled,
            s.backface_culled,
            s.clipped,
            s.degenerate_after_snap,
            s.split_nonplanar
        );
        eprintln!("{}", rendered.detail);
    }
    Ok(())
}

fn sheet_command(a: SheetArgs) -> sightline::Result<()> {
    let pdf = a
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("pdf"));
    let scene = load_scene(&a.input)?;
    let title = a
        .input
        .input
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let options = sheet::SheetOptions {
        views: a.views.0,
        method: a.projection,
        paper: a.paper,
        portrait: a.portrait,
        scale: a.scale,
        units: a.units,
        date: a.date,
        title,
        lines: sightline::lines::LineOptions {
            crease_deg: a.crease,
            hidden: a.hidden == HiddenArg::Dashed,
            ..Default::default()
        },
    };
    let sheet = with_bars(|report| sheet::sheet(&scene, &options, report))?;
    let svg = sheet.svg();
    if pdf {
        // The sheet's text is drawn as strokes: no font is needed.
        let bytes = sightline::output::pdf::pdf_of_svg(&svg)?;
        return write_with(&a.output, |w| w.write_all(&bytes));
    }
    write_with(&a.output, |w| w.write_all(svg.as_bytes()))
}

/// A method's face id at every pixel centre, and its time after projection.
fn face_ids_of(
    method: &Method,
    scene: &Scene,
    prepared: &pipeline::Prepared,
    camera: &Camera,
) -> (Vec<Option<u32>>, f64) {
    let t = Instant::now();
    let ids = with_bars(|report| method.face_ids(scene, &prepared.screen, camera, report));
    (ids, t.elapsed().as_secs_f64())
}

fn compare(a: CompareArgs) -> sightline::Result<()> {
    if let Some(image) = &a.image {
        return compare_image(&a, image);
    }
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
        a.method.name, a.against.name, camera.width, camera.height
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
        a.method.name, t_method, a.against.name, t_ref
    );
    Ok(())
}

/// `compare --image`: grades a face-id image against the exact visible set (`grade`).
fn compare_image(a: &CompareArgs, image_path: &Path) -> sightline::Result<()> {
    use sightline::grade;
    let image = grade::id_png::read(image_path)?;
    let size = (image.width, image.height);
    if let Some((w, h)) = a.camera.size.filter(|&s| s != size) {
        return Err(sightline::Error::Options(format!(
            "--size {w}x{h} disagrees with {}, which is {}x{}: the image's size is the camera's (leave --size out, or give the image's)",
            image_path.display(),
            size.0,
            size.1
        )));
    }
    let scene = load_scene(&a.input)?;
    let camera = camera_of_size(&a.camera, &scene, Some(size))?;
    let prepared = pipeline::prepare(&scene, &camera, a.camera.cull);
    let graded = grade::grade(&scene, &prepared.screen, &image.ids);
    if let Some(path) = &a.diff {
        let picture = graded.diff_image(&image.ids);
        write_with(path, |w| png::write_rgb(w, size.0, size.1, &picture))?;
    }
    let g = &graded.grade;
    if g.unknown_id > 0 {
        let largest = scene.faces.iter().map(|f| f.id).max();
        eprintln!(
            "warning: {}: {} pixels hold ids that are no face of the scene (its largest face id is {}): was the image colour-managed (sRGB, gamma), dithered, blended or anti-aliased?",
            image_path.display(),
            g.unknown_id,
            largest.map_or_else(|| "none".into(), |m| m.to_string()),
        );
    }
    let pct = |n: usize| 100.0 * n as f64 / g.pixels.max(1) as f64;
    println!(
        "{} against the exact visible set at {}x{} ({} pixels):",
        image_path.display(),
        size.0,
        size.1,
        g.pixels
    );
    println!(
        "  covered pixels  image {}, exact {} (centre inside or on a visible piece)",
        g.image_covered, g.exact_covered
    );
    println!(
        "  wrong pixels    {} ({:.4}% of the pixels)",
        g.wrong,
        pct(g.wrong)
    );
    for (label, n, what) in [
        (
            "wrong face  ",
            g.wrong_face,
            "a face not seen at the centre",
        ),
        (
            "missing face",
            g.missing_face,
            "background where faces cover the centre",
        ),
        (
            "extra face  ",
            g.extra_face,
            "a face where the exact set has background",
        ),
        ("unknown id  ", g.unknown_id, "no face id of the scene"),
    ] {
        println!("    {label}  {n} ({what})");
    }
    println!(
        "  tie pixels      {} (centre on a boundary: each face there is right, and background on the outline)",
        g.ties
    );
    println!(
        "  area error      {:.6}% (of the image area given to the wrong face)",
        100.0 * g.area_error
    );
    Ok(())
}

fn info(a: InfoArgs) -> sightline::Result<()> {
    let scene = load_scene(&a.input)?;
    let camera = camera_for(&a.camera, &scene)?;
    let prepared = pipeline::prepare(&scene, &camera, a.camera.cull);
    let report = SceneReport {
        file: &a.input.input,
        scene: &scene,
        camera: &camera,
        prepared: &prepared,
    };
    print!("{report}");
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
        (None, None) => match (a.exported_sphere, a.soup, a.tori) {
            (Some(n), _, _) => scene::primitives::exported_sphere_scene(n),
            (None, Some(n), _) => scene::primitives::random_triangle_soup(n, 1),
            (None, None, Some(n)) => scene::primitives::interlocked_tori(n, (n / 2).max(3)),
            (None, None, None) => {
                unreachable!(
                    "clap requires an input, --sphere, --exported-sphere, --soup or --tori"
                )
            }
        },
    };
    let camera = camera_for(&a.camera, &scene)?;
    let (mut project_times, mut method_times) = (Vec::new(), Vec::new());
    // Exact methods: the drawing after the visible set too, as `render -o x.svg` makes it.
    let draws = a.method.outputs.contains(&Output::Svg);
    let (mut region_times, mut write_times) = (Vec::new(), Vec::new());
    let mut report = String::new();
    let bar = progress_bar(repeat as u64, "bench");
    let mut screen_stats = None;
    for k in 0..repeat {
        let t = Instant::now();
        let prepared = pipeline::prepare(&scene, &camera, a.camera.cull);
        project_times.push(t.elapsed().as_secs_f64());
        if draws {
            let options = RenderOptions::new(Output::Svg).with_method(a.method);
            let rendered = render::render(&scene, &camera, &prepared.screen, &options, None)?;
            let stage = |name: &str| {
                (rendered.stage_seconds.iter())
                    .find(|(n, _)| *n == name)
                    .map_or(0.0, |(_, t)| *t)
            };
            method_times.push(stage("visible set"));
            region_times.push(stage("regions"));
            let t = Instant::now();
            rendered
                .write(&mut std::io::sink())
                .expect("writing to nowhere cannot fail");
            write_times.push(t.elapsed().as_secs_f64());
            report = rendered.detail;
        } else {
            let (seconds, computed) =
                sightline::benchmark::timed_compute(a.method, &scene, &prepared.screen, &camera);
            method_times.push(seconds);
            report = computed.detail();
        }
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
    let name = a.method.name;
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
    let mut total = tp + tm;
    if draws {
        let (tr, tw) = (median(region_times), median(write_times));
        println!(
            "  regions          {tr:9.4} s  {:12.0} triangles/s  (merge, seams, canonical form)",
            tris as f64 / tr
        );
        println!(
            "  SVG              {tw:9.4} s  {:12.0} triangles/s  (written to nowhere)",
            tris as f64 / tw
        );
        println!(
            "  after the visible set: {:.0} % of it",
            100.0 * (tr + tw) / tm
        );
        total += tr + tw;
    }
    println!(
        "  total            {:9.4} s  {:12.0} triangles/s",
        total,
        tris as f64 / total
    );
    if let Some(kb) = sightline::benchmark::peak_rss_kb() {
        println!(
            "  peak memory      {:9.1} MB  {:12.0} bytes/triangle",
            kb as f64 / 1024.0,
            kb as f64 * 1024.0 / tris.max(1) as f64
        );
    }
    println!(
        "  on screen {} (back faces culled {}, frustum culled {}); {}",
        st.visible_polys, st.backface_culled, st.frustum_culled, report
    );
    if a.lines {
        bench_lines(&scene, &camera, a.camera.cull, repeat, median);
    }
    Ok(())
}

/// `bench --lines`: the visible set every line drawing starts from, and the lines stage after
/// it, medians of `repeat` runs in one process.
fn bench_lines(
    scene: &Scene,
    camera: &Camera,
    cull: CullMode,
    repeat: usize,
    median: impl Fn(Vec<f64>) -> f64,
) {
    use sightline::visibility::Strategy;
    let options = sightline::lines::LineOptions {
        cull,
        ..Default::default()
    };
    let prepared = pipeline::prepare(scene, camera, cull);
    let (mut visible_times, mut line_times) = (Vec::new(), Vec::new());
    let mut lines = None;
    for _ in 0..repeat {
        let t = Instant::now();
        let visible =
            sightline::visibility::CoverageMap.visible_set(&prepared.screen, &|_| false, None);
        visible_times.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        lines = Some(sightline::lines::lines_of(
            scene,
            camera,
            &prepared,
            &visible.pieces,
            &options,
        ));
        line_times.push(t.elapsed().as_secs_f64());
    }
    let lines = lines.expect("repeat >= 1");
    let (tv, tl) = (median(visible_times), median(line_times));
    println!("  visible set      {tv:9.4} s  (coverage map, every face opaque)");
    println!(
        "  lines            {tl:9.4} s  ({:.2}x the visible set)",
        tl / tv.max(1e-9)
    );
    let f = &lines.stats.features;
    println!(
        "  features: silhouette {}, boundary {}, intersection {}, crease {}, material {}",
        f[0], f[1], f[2], f[3], f[4]
    );
    println!(
        "  strokes {} (fewest possible {})",
        lines.drawing.strokes.len(),
        lines.stats.paths_minimum
    );
}

fn stress(a: StressArgs) -> sightline::Result<()> {
    use sightline::stress::{self, RunOptions, Selection};
    if a.family == Selection::Measured {
        let points = a.points.unwrap_or(usize::MAX);
        let ms = with_bars(|report| stress::measure_all(points, a.seed, report));
        print!("{}", stress::format_measurements(&ms));
        return Ok(());
    }
    let options = RunOptions {
        cases: a.cases as u64,
        seed: a.seed,
        points: a.points.unwrap_or(stress::DEFAULT_POINTS),
        failures: a.failures,
        jobs: a.jobs,
    };
    let reports = with_bars(|report| stress::run(&a.family.families(), &options, report));
    print!("{}", stress::format_report(&reports));
    let failed: usize = reports.iter().map(|r| r.failed.len()).sum();
    if failed > 0 {
        eprintln!(
            "error: {failed} case(s) failed; shrunk fixtures in {}",
            options.failures.display()
        );
        use std::io::Write as _;
        let _ = std::io::stdout().flush();
        std::process::exit(1);
    }
    Ok(())
}

const LINES_EXAMPLES: &str = "\
Examples:
  sightline lines fixtures/cube.obj -o cube.svg               (visible solid, hidden dashed)
  sightline lines part.stl --view front --ortho 60 -o front.dxf
  sightline lines part.obj --crease 45 --hidden off -o part.pdf
  sightline lines part.obj --qi-max 2 -o part.json            (hidden lines up to 2 faces deep)
  sightline lines part.obj --order plotter -o part.svg        (short pen-up moves for a plotter)
  sightline lines bunny.obj --cam bunny.cam --background 255,255,255 -o - | rsvg-convert > b.png
  sightline render part.obj --lines -o shaded.svg             (lines over the filled drawing)";

/// The file formats of `sightline lines`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum LineFormat {
    Svg,
    Json,
    Dxf,
    Pdf,
}

/// `--hidden`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum HiddenArg {
    Dashed,
    Off,
}

#[derive(Args)]
struct LinesArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    camera: CameraArgs,
    /// Output file (.svg, .json, .dxf or .pdf), or - for standard output (SVG unless --to).
    #[arg(short, long, value_name = "OUT")]
    output: PathBuf,
    /// Output format (default: from the output's extension).
    #[arg(long, value_enum)]
    to: Option<LineFormat>,
    /// An edge is a crease where the normals of its two faces differ by more than DEG degrees
    /// (0 to 180).
    #[arg(long, value_name = "DEG", default_value_t = 30.0, value_parser = parse_crease, allow_negative_numbers = true)]
    crease: f64,
    /// Hidden lines: dashed (ISO 128 type 02, half the visible width), or off.
    #[arg(long, value_enum, default_value_t = HiddenArg::Dashed)]
    hidden: HiddenArg,
    /// Draw hidden lines only up to N faces deep, counting exactly the faces in front of each
    /// piece (may take longer).
    #[arg(long, value_name = "N", value_parser = parse_depth, allow_negative_numbers = true)]
    qi_max: Option<u32>,
    /// A background rectangle behind the lines, r,g,b in 0..=255 (SVG and PDF; default: none,
    /// so that the lines can be laid over other content).
    #[arg(long, value_parser = parse_background, value_name = "R,G,B", allow_hyphen_values = true)]
    background: Option<Background>,
    /// Stroke order: as chained, or for a pen plotter (greedy nearest neighbour, then 2-opt;
    /// the pen-up travel before and after goes to stderr).
    #[arg(long, value_enum, default_value_t = StrokeOrder::Chained)]
    order: StrokeOrder,
}

/// The order strokes are written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum StrokeOrder {
    /// As the chaining made them, grouped by visibility and kind.
    Chained,
    /// Short pen-up moves between strokes (within each visibility and kind).
    Plotter,
}

/// A count of at least 0.
fn parse_depth(s: &str) -> Result<u32, String> {
    s.trim()
        .parse::<u32>()
        .map_err(|_| format!("'{s}' is not a whole number >= 0"))
}

/// The format of `sightline lines`'s output: `--to`, else the extension (any case); standard
/// output gets SVG.
fn line_format_for(path: &Path, to: Option<LineFormat>) -> sightline::Result<LineFormat> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    Ok(match (to, ext.as_deref()) {
        (Some(format), _) => format,
        (None, Some("svg")) => LineFormat::Svg,
        (None, Some("json")) => LineFormat::Json,
        (None, Some("dxf")) => LineFormat::Dxf,
        (None, Some("pdf")) => LineFormat::Pdf,
        _ if path.as_os_str() == "-" => LineFormat::Svg,
        _ => {
            return Err(sightline::Error::Output(format!(
                "{}: unknown output extension for lines (use .svg, .json, .dxf or .pdf, or --to)",
                path.display()
            )));
        }
    })
}

/// The strokes of `drawing` counted by visibility and kind, one line: `12 strokes: visible 9
/// (silhouette 6, crease 3), hidden 3 (crease 3)`.
fn stroke_summary(drawing: &LineDrawing) -> String {
    let mut parts = Vec::new();
    for visibility in [Visibility::Visible, Visibility::Hidden] {
        let of = |kind| {
            drawing
                .strokes
                .iter()
                .filter(|s| (s.visibility, s.kind) == (visibility, kind))
                .count()
        };
        let kinds: Vec<String> = LineKind::ALL
            .iter()
            .filter(|&&k| of(k) > 0)
            .map(|&k| format!("{} {}", k.name(), of(k)))
            .collect();
        if !kinds.is_empty() {
            let total: usize = LineKind::ALL.iter().map(|&k| of(k)).sum();
            parts.push(format!(
                "{} {total} ({})",
                visibility.name(),
                kinds.join(", ")
            ));
        }
    }
    let n = drawing.strokes.len();
    match parts.is_empty() {
        true => format!("{n} strokes"),
        false => format!("{n} strokes: {}", parts.join(", ")),
    }
}

fn lines(a: LinesArgs) -> sightline::Result<()> {
    use sightline::output::{dxf, line_json, line_svg, pdf};
    let bad = |m: String| Err(sightline::Error::Options(m));
    let format = line_format_for(&a.output, a.to)?;
    if a.qi_max.is_some() && a.hidden == HiddenArg::Off {
        return bad("--qi-max applies to hidden lines: it does nothing with --hidden off".into());
    }
    if a.background.is_some() && matches!(format, LineFormat::Json | LineFormat::Dxf) {
        return bad("--background applies to SVG and PDF output only".into());
    }
    if format == LineFormat::Pdf
        && ((a.output.as_os_str() == "-" && std::io::stdout().is_terminal())
            || is_terminal_path(&a.output))
    {
        return Err(sightline::Error::Output(
            "not writing a binary PDF to a terminal: redirect standard output (-o - > out.pdf), or give a file (-o out.pdf)".into(),
        ));
    }
    let scene = load_scene(&a.input)?;
    let camera = camera_for(&a.camera, &scene)?;
    let options = LineOptions {
        crease_deg: a.crease,
        hidden: a.hidden == HiddenArg::Dashed,
        qi_max: a.qi_max,
        cull: a.camera.cull,
    };
    let mut lines =
        with_bars(|report| sightline::lines::line_drawing(&scene, &camera, &options, report))?;
    if a.order == StrokeOrder::Plotter {
        let travel = sightline::lines::plot_order::plot_order(&mut lines.drawing);
        eprintln!(
            "pen-up travel: {:.1} px as chained, {:.1} px in plotter order",
            travel.before, travel.after
        );
    }
    let svg_options = line_svg::LineSvgOptions {
        background: match a.background {
            Some(Background::Color(c)) => Some(c.map(|v| v as f64 / 255.0)),
            _ => None,
        },
        ..line_svg::LineSvgOptions::default()
    };
    let drawing = &lines.drawing;
    let bytes = match format {
        LineFormat::Svg => line_svg::write_line_svg(drawing, &svg_options).into_bytes(),
        LineFormat::Json => line_json::write_line_json(drawing).into_bytes(),
        LineFormat::Dxf => dxf::write_dxf(drawing, &dxf::DxfOptions::default())?,
        LineFormat::Pdf => pdf::pdf_of_svg(&line_svg::write_line_svg(drawing, &svg_options))?,
    };
    write_with(&a.output, |w| w.write_all(&bytes))?;
    eprintln!("{}", stroke_summary(drawing));
    Ok(())
}

/// The default folder of a suite's scene files.
fn suite_dir(suite: sightline::benchmark::Suite, dir: Option<&Path>) -> PathBuf {
    use sightline::benchmark::Suite;
    match (dir, suite) {
        (Some(d), _) => d.to_path_buf(),
        (None, Suite::Meshes) => PathBuf::from("../shared/meshes"),
        (None, _) => PathBuf::from("fixtures"),
    }
}

/// The hidden `bench-one`: loads one scene of a suite, times one method at one size (median of
/// a few runs) and prints `{"time_s": .., "peak_rss_kb": .., "pieces": .., "chosen": ..}`, the
/// peak read at its end.
fn bench_one(a: BenchOneArgs) -> sightline::Result<()> {
    use sightline::benchmark;
    let dir = suite_dir(a.suite, a.dir.as_deref());
    let scenes = benchmark::scenes(a.suite, &dir, &dir)?;
    let scene = scenes
        .iter()
        .find(|s| s.name == a.scene)
        .ok_or_else(|| sightline::Error::Options(format!("no scene '{}' in the suite", a.scene)))?;
    let loaded = scene.load()?;
    let camera = loaded.camera(a.size)?;
    let timing = benchmark::time_median(a.method, &loaded.scene, &camera);
    let line = serde_json::json!({
        "time_s": timing.time_s,
        "peak_rss_kb": benchmark::peak_rss_kb(),
        "pieces": timing.pieces,
        "chosen": timing.chosen,
    });
    println!("{line}");
    Ok(())
}

/// Runs `bench-one` in a child process under `limits`.
fn measure_in_child(
    suite: sightline::benchmark::Suite,
    dir: &Path,
    scene: &str,
    method: &Method,
    size: u32,
    limits: sightline::benchmark::child::Limits,
) -> Result<sightline::benchmark::child::Measured, sightline::benchmark::child::Failure> {
    use clap::ValueEnum as _;
    use sightline::benchmark::child::{self, Failure};
    let exe = std::env::current_exe().map_err(|e| Failure::Failed {
        message: format!("no executable path: {e}"),
    })?;
    let suite_name = suite
        .to_possible_value()
        .map_or_else(String::new, |v| v.get_name().to_string());
    let mut command = std::process::Command::new(exe);
    command
        .arg("bench-one")
        .args([
            "--suite",
            &suite_name,
            "--scene",
            scene,
            "--method",
            method.name,
        ])
        .args(["--size", &size.to_string()])
        .arg("--dir")
        .arg(dir);
    child::measure(command, limits)
}

/// A scene name as a file name part: letters, digits, '-' and '_' kept, the rest '_'.
fn file_part(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// `bench --suite`: every method on every scene at every size; results.csv, results.json and
/// one plot per scene in --out.
fn bench_suite(suite: sightline::benchmark::Suite, a: BenchArgs) -> sightline::Result<()> {
    use sightline::benchmark::{self, FailedRow, Row, child, plot, truth};
    let limits = child::Limits {
        time: std::time::Duration::from_secs_f64(a.time_limit),
        memory_kb: a.memory_limit as u64 * 1024,
    };
    let out_dir = a.out.clone().expect("clap requires --out with --suite");
    let (methods, sizes) = (a.methods.0, a.sizes.0);
    let dir = suite_dir(suite, a.dir.as_deref());
    let scenes = benchmark::scenes(suite, &dir, &dir)?;
    if scenes.is_empty() {
        return Err(sightline::Error::Options(format!(
            "--suite: no scene found in {}",
            dir.display()
        )));
    }
    // The output folder must be writable before hours of measuring.
    let unwritable = |e: std::io::Error| sightline::Error::Io {
        path: out_dir.display().to_string(),
        source: e,
    };
    std::fs::create_dir_all(&out_dir).map_err(unwritable)?;
    tempfile::tempfile_in(&out_dir).map_err(unwritable)?;

    let bar = labelled_bar(
        (scenes.len() * sizes.len() * methods.len()) as u64,
        "bench",
        "{pos}/{len}",
    );
    let mut rows: Vec<Row> = Vec::new();
    let mut failed: Vec<FailedRow> = Vec::new();
    for bs in &scenes {
        let loaded = match bs.load() {
            Ok(l) => l,
            Err(e) => {
                bar.suspend(|| eprintln!("warning: {}: skipped: {e}", bs.name));
                bar.inc((sizes.len() * methods.len()) as u64);
                continue;
            }
        };
        // Object-space methods' time and memory do not depend on the size: measured once.
        let mut once: Vec<(&str, child::Measured)> = Vec::new();
        let mut failed_once: Vec<&str> = Vec::new();
        for (k, &size) in sizes.iter().enumerate() {
            bar.set_message(format!("{} {size}", bs.name));
            let camera = loaded.camera(size)?;
            let measured = methods.iter().any(|m| !benchmark::is_exact_object(m));
            let prepared = pipeline::prepare(&loaded.scene, &camera, CullMode::Auto);
            let rings = if measured {
                truth::truth_rings(&prepared.screen)
            } else {
                Vec::new()
            };
            for &m in &methods {
                let object = !m.is_image_space();
                if failed_once.contains(&m.name) {
                    bar.inc(1);
                    continue;
                }
                let measured = match once.iter().find(|o| o.0 == m.name) {
                    Some((_, measured)) => measured.clone(),
                    None => match measure_in_child(suite, &dir, &bs.name, m, size, limits) {
                        Ok(measured) => {
                            if object {
                                once.push((m.name, measured.clone()));
                            }
                            measured
                        }
                        // A child stopped at a limit, say: the other measurements go on.
                        Err(failure) => {
                            bar.suspend(|| {
                                eprintln!(
                                    "warning: {} on {} at {size}x{size}: {failure}",
                                    m.name, bs.name
                                )
                            });
                            failed.push(FailedRow {
                                scene: bs.name.clone(),
                                method: m.name,
                                size,
                                failure,
                            });
                            if object {
                                failed_once.push(m.name);
                            }
                            bar.inc(1);
                            continue;
                        }
                    },
                };
                let error = if benchmark::is_exact_object(m) {
                    0.0
                } else {
                    let ids = m.face_ids(&loaded.scene, &prepared.screen, &camera, None);
                    truth::error_of(&rings, size, size, &ids)
                };
                rows.push(Row {
                    scene: bs.name.clone(),
                    method: m.name,
                    engine: if object { "object" } else { "image" },
                    exact: m.exact,
                    size,
                    time_s: measured.time_s,
                    peak_rss_kb: measured.peak_rss_kb,
                    error,
                    reused: object && k > 0,
                    pieces: measured.pieces,
                    chosen: measured.chosen,
                });
                bar.inc(1);
            }
        }
    }
    bar.finish_and_clear();
    write_with(&out_dir.join("results.csv"), |w| {
        w.write_all(benchmark::csv(&rows).as_bytes())
    })?;
    write_with(&out_dir.join("results.json"), |w| {
        w.write_all(benchmark::json(suite, &sizes, &rows, &failed).as_bytes())
    })?;
    let crossovers = benchmark::crossovers(&rows);
    let mut plotted = Vec::new();
    for bs in &scenes {
        if !rows.iter().any(|r| r.scene == bs.name) {
            continue;
        }
        match plot::plot_scene(&bs.name, &rows, &crossovers) {
            Ok((svg, pixels)) => {
                let base = out_dir.join(format!("plot-{}", file_part(&bs.name)));
                write_with(&base.with_extension("svg"), |w| w.write_all(svg.as_bytes()))?;
                let (w, h) = plot::FIGURE;
                write_with(&base.with_extension("png"), |out| {
                    png::write_rgb(out, w, h, &pixels)
                })?;
                plotted.push(base);
            }
            Err(e) => {
                eprintln!("warning: no plots: {e}");
                break;
            }
        }
    }
    // The summary: per scene and method, time and error at each size.
    for bs in &scenes {
        let scene_rows: Vec<&Row> = rows.iter().filter(|r| r.scene == bs.name).collect();
        if scene_rows.is_empty() {
            continue;
        }
        println!("{}:", bs.name);
        for &m in &methods {
            let runs: Vec<String> = scene_rows
                .iter()
                .filter(|r| r.method == m.name)
                .map(|r| format!("{} {:.2e} s err {:.2e}", r.size, r.time_s, r.error))
                .collect();
            let chosen = scene_rows
                .iter()
                .find(|r| r.method == m.name)
                .and_then(|r| r.chosen.as_deref())
                .map_or_else(String::new, |c| format!(" (ran {c})"));
            let stopped = failed
                .iter()
                .find(|f| f.scene == bs.name && f.method == m.name)
                .map_or_else(String::new, |f| format!(" {}", f.failure));
            println!("  {:16} {}{chosen}{stopped}", m.name, runs.join(", "));
        }
        for c in crossovers.iter().filter(|c| c.scene == bs.name) {
            match c.from_size {
                Some(s) => println!(
                    "  {} faster than {} from {s}x{s}",
                    benchmark::EXACT_REFERENCE,
                    c.method
                ),
                None => println!(
                    "  {} not faster than {} at any size measured",
                    benchmark::EXACT_REFERENCE,
                    c.method
                ),
            }
        }
    }
    println!(
        "wrote {} ({} rows), {} and {} plot(s)",
        out_dir.join("results.csv").display(),
        rows.len(),
        out_dir.join("results.json").display(),
        plotted.len()
    );
    if !failed.is_empty() {
        return Err(sightline::Error::Output(format!(
            "{} measurement(s) failed (see the warnings above and `failed` in results.json); \
             the results hold the others",
            failed.len()
        )));
    }
    Ok(())
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
