//! One render, as `sightline render` does it: the options checked against the method and the
//! output ([`RenderOptions::check`]), the method run ([`compute`]), and its result made into the
//! output ([`render`]): an image-space method's pixels coloured into an image ([`image_of`]), an
//! object-space method's visible set drawn ([`crate::draw`]) and written as SVG, JSON or PNG
//! ([`Rendered::write`]).
//!
//! Invariants: an option that the output or the method would ignore is an error, never dropped
//! in silence; the bytes written depend only on the scene, the camera and the options (timings
//! and progress never reach them).

use crate::camera::Camera;
use crate::draw::{DrawOptions, draw};
use crate::error::{Error, Result};
use crate::lines::LineDrawing;
use crate::lines::LineOptions;
use crate::methods::{self, Engine, Method, Output, names_with};
use crate::output::drawing::Drawing;
use crate::output::line_svg::LineSvgOptions;
use crate::output::{json, png, raster_drawing, svg};
use crate::paint::{Fill, Paint, screen_paints, to_u8};
use crate::pipeline::colorize_painted;
use crate::progress::Report;
use crate::project::ScreenScene;
use crate::raster::lighting::{Lighting, Shading, Textures, shade_polys};
use crate::raster::renderer::{Raster, RasterOptions};
use crate::scene::{CameraLights, Material, Scene, SceneLights};
use crate::visibility::VisibleSet;
use std::io::{self, Write};
use std::path::Path;
use std::time::Instant;

/// What is drawn behind the scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Background {
    /// The scene's own: an X3D Background's sky colour (black when the X3D file has none), white
    /// for the formats that have no such notion.
    #[default]
    Scene,
    /// This colour, 8-bit RGB.
    Color([u8; 3]),
    /// Nothing: an SVG without a background rectangle, for a figure placed over other content.
    None,
}

impl Background {
    /// The colour drawn behind `scene`, `None` for nothing at all.
    pub fn color(self, scene: &Scene) -> Option<[u8; 3]> {
        match self {
            Background::Scene => Some(scene.background.map(to_u8).unwrap_or([255; 3])),
            Background::Color(c) => Some(c),
            Background::None => None,
        }
    }
}

/// What a render writes, and how. Each field is a flag of `sightline render`.
#[derive(Clone)]
pub struct RenderOptions {
    /// The output format (`--to`, or [`output_for`] the output's name).
    pub format: Output,
    /// The method (`--method`); `None`: the format's default ([`methods::default_for`]).
    pub method: Option<&'static Method>,
    /// Shaded colours, or face ids as colours (`--fill`).
    pub fill: Fill,
    /// `--background`.
    pub background: Background,
    /// How light varies across a face, for the methods that shade per pixel (`--shading`).
    pub shading: Shading,
    /// Also compute the depth image ([`Rendered::depth`], `--depth`).
    pub depth: bool,
    /// Outline every region, black, half a pixel wide (SVG, `--stroke`).
    pub stroke: bool,
    /// Ask viewers not to anti-alias (SVG, `--crisp`).
    pub crisp: bool,
    /// Draw the line drawing of the same scene and camera over the filled one (SVG,
    /// `--lines`: the shaded-with-edges view). Its `cull` should be the one `screen` was
    /// prepared with.
    pub lines: Option<LineOptions>,
}

impl RenderOptions {
    /// `format` by its default method: shaded flat fills on the scene's background.
    pub fn new(format: Output) -> RenderOptions {
        RenderOptions {
            format,
            method: None,
            fill: Fill::Shade,
            background: Background::Scene,
            shading: Shading::Flat,
            depth: false,
            stroke: false,
            crisp: false,
            lines: None,
        }
    }

    /// The same, by `method`.
    pub fn with_method(self, method: &'static Method) -> RenderOptions {
        RenderOptions {
            method: Some(method),
            ..self
        }
    }

    /// The method that runs: the one asked for, else the format's default.
    pub fn method(&self) -> &'static Method {
        self.method
            .unwrap_or_else(|| methods::default_for(self.format))
    }

    /// Checks that every option applies, for a scene lit by `lights` (lights other than the
    /// default ones change shaded colours, like an option), and returns the method. In this
    /// order: an option the output ignores, a method that does not write the format, a depth
    /// image or a shading the method has none of, then the lights ([`SceneLights::check`]).
    /// The messages name the command line's flags.
    pub fn check(&self, lights: &SceneLights) -> Result<&'static Method> {
        let bad = |m: String| Err(Error::Options(m));
        let method = self.method();
        if let Some(message) = self.ignored(lights) {
            return bad(message);
        }
        if !method.writes(self.format) {
            return bad(format!(
                "--method {} draws pixels: write it as PNG (for SVG or JSON use --method {})",
                method.name,
                names_with(|m| m.writes(self.format))
            ));
        }
        if self.depth && !method.depth {
            return bad(format!(
                "--depth needs --method {}",
                names_with(|m| m.depth)
            ));
        }
        if self.shading != Shading::Flat && !method.shading {
            return bad(format!(
                "--shading {} needs --method {} ({} draws flat colours)",
                self.shading.name(),
                names_with(|m| m.shading),
                method.name
            ));
        }
        lights.check()?;
        Ok(method)
    }

    /// The first option given that this output would ignore, with why; `None` when all apply.
    fn ignored(&self, lights: &SceneLights) -> Option<String> {
        let format = self.format;
        let name = match format {
            Output::Png => "PNG",
            Output::Svg => "SVG",
            Output::Json => "JSON",
        };
        let svg_only = [
            ("--stroke", self.stroke),
            ("--crisp", self.crisp),
            ("--background none", self.background == Background::None),
            ("--lines", self.lines.is_some()),
        ];
        if let Some((flag, _)) = svg_only.iter().find(|(_, given)| *given)
            && format != Output::Svg
        {
            return Some(format!(
                "{flag} applies to SVG output only (this run writes {name})"
            ));
        }
        // What changes the shaded colours (values other than the defaults).
        let default = SceneLights::default();
        let lighting = [
            ("--specular", lights.specular != default.specular),
            ("--shininess", lights.shininess != default.shininess),
            ("--light", lights.lights != default.lights),
            ("--headlight", lights.camera == CameraLights::Headlight),
            ("--no-headlight", lights.camera == CameraLights::None),
            ("--background", self.background != Background::Scene),
            ("--shading", self.shading != Shading::Flat),
        ];
        let (flag, _) = lighting.iter().find(|(_, given)| *given)?;
        if self.fill == Fill::Id {
            return Some(format!(
                "{flag} changes shaded colours: it does not apply to --fill id (face ids as colours)"
            ));
        }
        if format == Output::Json {
            return Some(format!(
                "{flag} changes colours: it does not apply to JSON output (regions and materials, no colours)"
            ));
        }
        None
    }
}

/// The format an output path asks for by its extension (`.png`, `.svg`, `.json`, any case);
/// standard output (`-`) gets PNG unless `method` draws polygons, then SVG.
pub fn output_for(path: &Path, method: Option<&Method>) -> Result<Output> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    Ok(match ext.as_deref() {
        Some("png") => Output::Png,
        Some("svg") => Output::Svg,
        Some("json") => Output::Json,
        _ if path.as_os_str() == "-" => match method.is_none_or(Method::is_image_space) {
            true => Output::Png,
            false => Output::Svg,
        },
        _ => {
            return Err(Error::Output(format!(
                "{}: unknown output extension (use .png, .svg or .json, or --to)",
                path.display()
            )));
        }
    })
}

/// What a method computed, before it is coloured or drawn.
pub enum Computed {
    /// An image-space method's polygon at every pixel (and what else it was asked for).
    Raster(Raster),
    /// An object-space method's visible set.
    Visible(VisibleSet),
}

impl Computed {
    /// The method's counters: one line (a JSON object for a visible set), after a line per
    /// stage that a strategy explains (`stage_*` entries: what was done or why it was skipped).
    pub fn detail(&self) -> String {
        match self {
            Computed::Raster(r) => r.detail.clone(),
            Computed::Visible(v) => {
                let mut counters = v.stats.clone();
                let mut lines = String::new();
                // The pipeline's stages in their order, then any other.
                let mut stages: Vec<&str> = vec!["cull", "order", "split", "blend"];
                stages.extend(v.stats.keys().filter_map(|k| k.strip_prefix("stage_")));
                for stage in stages {
                    let key = format!("stage_{stage}");
                    if let Some(serde_json::Value::String(why)) = counters.remove(&key) {
                        lines.push_str(&format!("{stage}: {why}\n"));
                    }
                }
                lines + &serde_json::Value::Object(counters).to_string()
            }
        }
    }
}

/// Runs `method` on `screen`. A strategy reads only `options.paints` (a face whose paint is not
/// opaque is layered, not hidden). `report` gets the progress of the long stages.
pub fn compute(
    method: &Method,
    screen: &ScreenScene,
    options: &RasterOptions,
    report: Option<Report>,
) -> Computed {
    match method.engine {
        Engine::Image(renderer) => Computed::Raster(renderer.render(screen, options, report)),
        Engine::Object(strategy) => {
            let paints = options.paints;
            let translucent = |k: u32| !paints[k as usize].is_opaque();
            let visible = strategy.visible_set(screen, &translucent, report);
            // The strategy's working pieces are gone: their room goes back before drawing.
            crate::memory::give_back_after(screen.polys.len());
            Computed::Visible(visible)
        }
    }
}

/// How an image-space method's pixels are coloured ([`image_of`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ImageStyle {
    /// Shaded colours or face ids.
    pub fill: Fill,
    /// How light varies across a face.
    pub shading: Shading,
    /// The colour of pixels that show no face (ignored under `Fill::Id`: black).
    pub background: [u8; 3],
}

/// The image (8-bit RGB, row-major, row 0 at the top) of `raster`, an image-space method's
/// result for `screen`: its blended colours where it blended (the A-buffer); else, when
/// shading per pixel or with textures, the lighting model along the ray through each pixel
/// centre ([`shade_polys`]); else each polygon's flat paint (`paints[k]` for `screen.polys[k]`,
/// [`colorize_painted`]). A texture that cannot be read is a warning (its faces are drawn
/// untextured).
pub fn image_of(
    scene: &Scene,
    screen: &ScreenScene,
    camera: &Camera,
    paints: &[Paint],
    raster: &Raster,
    style: ImageStyle,
    warnings: &mut Vec<String>,
) -> Vec<[u8; 3]> {
    let textured = scene.material_textures.iter().any(Option::is_some);
    match &raster.blended {
        Some(colors) => colors.iter().map(|&c| to_u8(c)).collect(),
        None if style.fill == Fill::Shade && (style.shading != Shading::Flat || textured) => {
            let textures = Textures::load(scene);
            warnings.extend(textures.warnings.iter().cloned());
            shade_polys(
                scene,
                screen,
                &raster.poly,
                camera.width,
                camera,
                &Lighting::of_scene(scene, camera),
                style.shading,
                &textures,
                style.background.map(|c| c as f64 / 255.0),
            )
            .into_iter()
            .map(to_u8)
            .collect()
        }
        None => colorize_painted(paints, &raster.poly, style.fill, style.background),
    }
}

/// A finished render, ready to write.
pub struct Rendered {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    body: Body,
    /// Depth per pixel in \[0, 1\] (1 for background), when asked for
    /// ([`png::write_depth16`] writes it).
    pub depth: Option<Vec<f64>>,
    /// The method's counters, one line.
    pub detail: String,
    /// What the user should know, in the order it was found (an empty view, textures not
    /// applied or not read).
    pub warnings: Vec<String>,
    /// Seconds spent in each stage, in order: "visible set" or "image", then for drawings
    /// "regions" (merge, seams, canonical form), then "lines" for SVG with hidden lines. SVG and
    /// JSON are written as they are made, by [`Rendered::write`].
    pub stage_seconds: Vec<(&'static str, f64)>,
}

/// The bytes of a render, or what streams them.
enum Body {
    /// A drawing, written as JSON as it goes: the scene's materials and the method's counters.
    Json(
        Box<(
            Drawing,
            Vec<Material>,
            serde_json::Map<String, serde_json::Value>,
        )>,
    ),
    /// A drawing, written as SVG element by element, with hidden lines over it if asked.
    Svg(Box<(Drawing, svg::SvgOptions, Option<LineDrawing>)>),
    /// A drawing, rasterized by strips as its PNG is written.
    Drawing(Drawing),
    /// An image-space method's image.
    Pixels(Vec<[u8; 3]>),
}

impl Rendered {
    /// Writes the output: the SVG (streamed as it is made) or JSON text, or the PNG (a
    /// drawing's is rasterized in strips of rows as it streams out).
    pub fn write(&self, out: &mut dyn Write) -> io::Result<()> {
        match &self.body {
            Body::Json(json) => {
                let (drawing, materials, stats) = &**json;
                json::write_json_to(out, drawing, materials, stats)
            }
            Body::Svg(svg) => {
                let (drawing, options, lines) = &**svg;
                let line_options = LineSvgOptions::default();
                let lines = lines.as_ref().map(|l| (l, &line_options));
                svg::write_document(out, drawing, options, lines)
            }
            Body::Drawing(drawing) => raster_drawing::write_png(drawing, out),
            Body::Pixels(rgb) => png::write_rgb(out, self.width, self.height, rgb),
        }
    }
}

/// Renders `screen`, the projection of `scene` by `camera` ([`crate::pipeline::prepare`]), as
/// `options` ask, after checking them against the scene's lights ([`RenderOptions::check`]).
/// `report` gets the progress of the long stages.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    screen: &ScreenScene,
    options: &RenderOptions,
    report: Option<Report>,
) -> Result<Rendered> {
    let method = options.check(&scene.lights)?;
    let mut warnings = Vec::new();
    if screen.polys.is_empty() {
        let st = &screen.stats;
        warnings.push(format!(
            "the camera sees none of the {} faces ({} outside the view, {} back faces culled): the output shows only the background",
            st.faces, st.frustum_culled, st.backface_culled
        ));
    }
    let fill = options.fill;
    let background = options.background.color(scene);
    // Pixels always have a background (`--background none` is refused for PNG).
    let background_rgb = background.unwrap_or([255; 3]);
    let paints = screen_paints(scene, screen, camera, fill);
    let translucent = paints.iter().filter(|p| !p.is_opaque()).count();
    if translucent > 0 && !method.blends {
        warnings.push(format!(
            "--method {} draws translucent faces as opaque ({translucent} on screen): use --method {} to blend them",
            method.name,
            names_with(|m| m.blends)
        ));
    }
    let raster_options = RasterOptions {
        paints: &paints,
        background: match fill {
            Fill::Id => [0.0; 3],
            Fill::Shade => background_rgb.map(|c| c as f64 / 255.0),
        },
        blend: fill == Fill::Shade,
        depth: options.depth,
    };
    let mut clock = Instant::now();
    let mut stage_seconds = Vec::new();
    let mut lap = |name: &'static str| {
        stage_seconds.push((name, clock.elapsed().as_secs_f64()));
        clock = Instant::now();
    };
    let computed = compute(method, screen, &raster_options, report);
    lap(match computed {
        Computed::Raster(_) => "image",
        Computed::Visible(_) => "visible set",
    });
    let detail = computed.detail();
    let (body, depth) = match computed {
        Computed::Raster(raster) => {
            let textured = scene.material_textures.iter().any(Option::is_some);
            if textured && !method.shading && fill == Fill::Shade {
                warnings.push(format!(
                    "--method {} fills flat colours: textures are not applied (use --method {})",
                    method.name,
                    names_with(|m| m.shading)
                ));
            }
            let style = ImageStyle {
                fill,
                shading: options.shading,
                background: background_rgb,
            };
            let rgb = image_of(
                scene,
                screen,
                camera,
                &paints,
                &raster,
                style,
                &mut warnings,
            );
            (Body::Pixels(rgb), raster.depth)
        }
        Computed::Visible(visible) => {
            // Pictures merge the regions of one surface and fill their seams; JSON keeps faces
            // apart.
            let draw_options = match options.format {
                Output::Json => DrawOptions::per_face(),
                Output::Svg | Output::Png => DrawOptions::picture(),
            };
            let mut drawing = draw(
                scene,
                screen,
                camera,
                &paints,
                &visible,
                draw_options.with_background(fill, None),
                report,
            );
            if drawing.background.is_none() {
                drawing.background = background.map(|c| c.map(|v| v as f64 / 255.0));
            }
            lap("regions");
            let body = match options.format {
                Output::Svg => {
                    let svg_options = svg::SvgOptions {
                        stroke: options.stroke.then_some(([0.0; 3], 0.5)),
                        crisp: options.crisp,
                    };
                    let lines = match &options.lines {
                        Some(line_options) => Some(
                            crate::lines::line_drawing(scene, camera, line_options, report)?
                                .drawing,
                        ),
                        None => None,
                    };
                    if lines.is_some() {
                        lap("lines");
                    }
                    Body::Svg(Box::new((drawing, svg_options, lines)))
                }
                Output::Json => {
                    let mut stats = visible.stats;
                    stats.insert("method".into(), method.name.into());
                    Body::Json(Box::new((drawing, scene.materials.clone(), stats)))
                }
                Output::Png => Body::Drawing(drawing),
            };
            (body, None)
        }
    };
    Ok(Rendered {
        width: camera.width,
        height: camera.height,
        body,
        depth,
        detail,
        warnings,
        stage_seconds,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::CameraSpec;
    use crate::methods::method;
    use crate::pipeline::prepare;
    use crate::project::CullMode;

    fn fixture(name: &str) -> Scene {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("fixtures")
            .join(name);
        crate::scene::load(&path, None).unwrap()
    }

    /// The library's render of `scene` at the golden files' size, as bytes.
    fn render_bytes(scene: &Scene, options: &RenderOptions) -> Vec<u8> {
        let camera = CameraSpec {
            size: Some((96, 72)),
            ..CameraSpec::default()
        }
        .resolve_for(scene)
        .unwrap();
        let prepared = prepare(scene, &camera, CullMode::Auto);
        let rendered = render(scene, &camera, &prepared.screen, options, None).unwrap();
        // The z-buffer's renders of translucent scenes warn that they draw them opaque; nothing
        // else warns.
        let opaque_drawing = |w: &String| w.contains("draws translucent faces as opaque");
        assert!(
            rendered.warnings.iter().all(opaque_drawing),
            "{:?}",
            rendered.warnings
        );
        let mut bytes = Vec::new();
        rendered.write(&mut bytes).unwrap();
        bytes
    }

    fn golden(name: &str) -> Vec<u8> {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/golden")
            .join(name);
        std::fs::read(path).unwrap()
    }

    /// Called as a library, a render writes the bytes `sightline render` writes (the golden
    /// files), on every path: SVG, JSON and a drawing's PNG; flat, blended and per-pixel shaded
    /// images.
    #[test]
    fn the_library_writes_what_the_command_line_writes() {
        let cube = fixture("cube.obj");
        let svg = RenderOptions::new(Output::Svg);
        assert!(render_bytes(&cube, &svg) == golden("cube.svg"));
        let json = RenderOptions::new(Output::Json);
        assert!(render_bytes(&cube, &json) == golden("cube.json"));
        let png = RenderOptions::new(Output::Png);
        assert!(render_bytes(&cube, &png) == golden("cube_zbuffer.png"));
        let bsp = png.clone().with_method(method("bsp").unwrap());
        let bars = fixture("cyclic_bars.obj");
        assert!(render_bytes(&bars, &bsp) == golden("cyclic_bars_bsp.png"));
        let abuffer = png.clone().with_method(method("abuffer").unwrap());
        let glass = fixture("seed_transparent.x3d");
        assert!(render_bytes(&glass, &abuffer) == golden("seed_transparent_abuffer.png"));
        let mut primitives = fixture("primitives.x3d");
        primitives.lights.specular = 0.4;
        let phong = RenderOptions {
            shading: Shading::Phong,
            ..png
        };
        assert!(render_bytes(&primitives, &phong) == golden("primitives_phong.png"));
    }

    /// Each option the output or the method would ignore is refused, naming the flag.
    #[test]
    fn check_refuses_what_would_be_ignored() {
        let lights = SceneLights::default();
        let err = |o: RenderOptions, l: &SceneLights| o.check(l).err().unwrap().to_string();
        let png = RenderOptions::new(Output::Png);
        let stroked = RenderOptions {
            stroke: true,
            ..png.clone()
        };
        assert!(err(stroked, &lights).starts_with("--stroke applies to SVG output only"));
        let ids = RenderOptions {
            fill: Fill::Id,
            ..png.clone()
        };
        let shiny = SceneLights {
            specular: 0.5,
            ..SceneLights::default()
        };
        assert!(err(ids, &shiny).starts_with("--specular changes shaded colours"));
        let headlit = SceneLights {
            camera: CameraLights::Headlight,
            ..SceneLights::default()
        };
        let json = RenderOptions::new(Output::Json);
        assert!(err(json, &headlit).contains("does not apply to JSON output"));
        let zbuffer_svg = RenderOptions::new(Output::Svg).with_method(method("zbuffer").unwrap());
        assert!(err(zbuffer_svg, &lights).starts_with("--method zbuffer draws pixels"));
        let depth = RenderOptions {
            depth: true,
            ..png.clone().with_method(method("coverage").unwrap())
        };
        assert_eq!(err(depth, &lights), "--depth needs --method zbuffer");
        let gouraud = RenderOptions {
            shading: Shading::Gouraud,
            ..png.clone().with_method(method("abuffer").unwrap())
        };
        assert!(err(gouraud, &lights).starts_with("--shading gouraud needs --method"));
        let dull = SceneLights {
            specular: -1.0,
            ..SceneLights::default()
        };
        assert!(err(png.clone(), &dull).starts_with("--specular must be"));
        // What applies passes, and the method is the format's default.
        assert_eq!(png.check(&shiny).unwrap().name, "zbuffer");
        assert_eq!(
            RenderOptions::new(Output::Svg).check(&lights).unwrap().name,
            "auto"
        );
    }

    #[test]
    fn the_output_format_follows_the_extension_or_the_method() {
        let of = |p: &str, m: Option<&str>| output_for(Path::new(p), m.and_then(method));
        assert_eq!(of("a.PNG", None).unwrap(), Output::Png);
        assert_eq!(of("a.svg", Some("zbuffer")).unwrap(), Output::Svg);
        assert_eq!(of("a.json", None).unwrap(), Output::Json);
        assert_eq!(of("-", None).unwrap(), Output::Png);
        assert_eq!(of("-", Some("scanline")).unwrap(), Output::Png);
        assert_eq!(of("-", Some("painter")).unwrap(), Output::Svg);
        let e = of("a.txt", None).unwrap_err().to_string();
        assert!(e.starts_with("a.txt: unknown output extension"), "{e}");
    }

    #[test]
    fn the_default_background_is_the_scenes_else_white() {
        let cube = fixture("cube.obj");
        assert_eq!(Background::Scene.color(&cube), Some([255; 3]));
        let seed = fixture("seed_two_triangles.x3d");
        assert_eq!(Background::Scene.color(&seed), Some([0; 3]));
        assert_eq!(Background::Color([1, 2, 3]).color(&seed), Some([1, 2, 3]));
        assert_eq!(Background::None.color(&cube), None);
    }
}
