//! Every method, object-space and image-space, listed once with what it can do.
//!
//! The CLI's `--method` values, `compare --against`, `bench --method`, their help text and the
//! conformance tests are all made from [`METHODS`]: a method listed here is reachable
//! everywhere, and one that is not listed is reachable nowhere. Adding a method is one file (a
//! [`Strategy`] or a [`Renderer`]) plus one entry here.
//!
//! Invariant, checked by the tests: every method marked [`Method::exact`] shows the z-buffer's
//! face id at every interior pixel of every fixture (a pixel whose 3x3 neighbourhood in the
//! z-buffer image holds one face).

use crate::camera::Camera;
use crate::draw::{DrawOptions, picture};
use crate::output::raster_drawing;
use crate::paint::{Fill, screen_paints};
use crate::progress::Report;
use crate::project::ScreenScene;
use crate::raster::renderer::{
    ABufferRenderer, RasterOptions, Renderer, ScanlineRenderer, WarnockRenderer, ZBufferRenderer,
};
use crate::scene::Scene;
use crate::visibility::{
    Auto, BspTree, CoverageMap, Newell, Painter, Strategy, WarnockExact, WeilerAtherton,
};

/// What computes a method's result.
#[derive(Clone, Copy)]
pub enum Engine {
    /// Object space: a visible set, drawn as polygons ([`crate::draw`]).
    Object(&'static dyn Strategy),
    /// Image space: a face per pixel.
    Image(&'static dyn Renderer),
}

/// An output format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Output {
    /// Vector drawing: one path per visible region (object-space methods).
    Svg,
    /// Per face: its visible regions as rings, and the run's counters (object-space methods).
    Json,
    /// Pixels, 8-bit RGB (every method).
    Png,
}

/// One registered method and its capabilities.
#[derive(Clone, Copy)]
pub struct Method {
    /// Short name, as the CLI spells it.
    pub name: &'static str,
    /// One line for the help text.
    pub summary: &'static str,
    /// What computes its result.
    pub engine: Engine,
    /// Interior mismatch against the z-buffer is 0 (see the module docs). Approximate methods
    /// are measured, not trusted.
    pub exact: bool,
    /// The outputs it writes.
    pub outputs: &'static [Output],
    /// Translucent faces blend over what lies behind them (otherwise every face is drawn as
    /// opaque).
    pub blends: bool,
    /// Per-pixel shading and textures (`--shading gouraud|phong`, texture maps).
    pub shading: bool,
    /// A depth image (`--depth`).
    pub depth: bool,
}

const VECTOR: &[Output] = &[Output::Svg, Output::Json, Output::Png];
const PIXELS: &[Output] = &[Output::Png];

/// Every method, in the order the CLI lists them.
pub static METHODS: [Method; 11] = [
    Method {
        name: "zbuffer",
        summary: "z-buffer with exact coverage and depth at pixel centres: the reference (PNG)",
        engine: Engine::Image(&ZBufferRenderer),
        exact: true,
        outputs: PIXELS,
        blends: false,
        shading: true,
        depth: true,
    },
    Method {
        name: "abuffer",
        summary: "A-buffer: per-pixel fragment lists, translucent faces blended back to front (PNG)",
        engine: Engine::Image(&ABufferRenderer),
        exact: true,
        outputs: PIXELS,
        blends: true,
        shading: false,
        depth: false,
    },
    Method {
        name: "scanline",
        summary: "Watkins scanline: edge tables, active edges, spans (PNG)",
        engine: Engine::Image(&ScanlineRenderer),
        exact: true,
        outputs: PIXELS,
        blends: false,
        shading: true,
        depth: false,
    },
    Method {
        name: "warnock",
        summary: "Warnock area subdivision down to a pixel (PNG)",
        engine: Engine::Image(&WarnockRenderer),
        exact: true,
        outputs: PIXELS,
        blends: false,
        shading: true,
        depth: false,
    },
    Method {
        name: "auto",
        summary: "exact visible polygons, only the stages the scene needs: pieces that overlap nothing skip ordering, the rest go to the coverage map (SVG, JSON, PNG; the default for SVG and JSON)",
        engine: Engine::Object(&Auto),
        exact: true,
        outputs: VECTOR,
        blends: true,
        shading: false,
        depth: false,
    },
    Method {
        name: "coverage",
        summary: "exact visible polygons: a depth-aware coverage map, overlaps split where planes meet (SVG, JSON, PNG)",
        engine: Engine::Object(&CoverageMap),
        exact: true,
        outputs: VECTOR,
        blends: true,
        shading: false,
        depth: false,
    },
    Method {
        name: "bsp",
        summary: "exact visible polygons through a 3D BSP tree walked front to back (SVG, JSON, PNG)",
        engine: Engine::Object(&BspTree),
        exact: true,
        outputs: VECTOR,
        blends: true,
        shading: false,
        depth: false,
    },
    Method {
        name: "newell",
        summary: "exact visible polygons: Newell's depth sort, pieces cut where the order cycles or faces cross, painted exactly back to front (SVG, JSON, PNG)",
        engine: Engine::Object(&Newell),
        exact: true,
        outputs: VECTOR,
        blends: true,
        shading: false,
        depth: false,
    },
    Method {
        name: "weiler-atherton",
        summary: "exact visible polygons: Weiler-Atherton, the nearest polygon clips the rest, recursing where something inside is in front (SVG, JSON, PNG)",
        engine: Engine::Object(&WeilerAtherton),
        exact: true,
        outputs: VECTOR,
        blends: true,
        shading: false,
        depth: false,
    },
    Method {
        name: "warnock-exact",
        summary: "exact visible polygons: Warnock's quadtree at object precision, areas settled where one face is in front, leaves clipped exactly (SVG, JSON, PNG)",
        engine: Engine::Object(&WarnockExact),
        exact: true,
        outputs: VECTOR,
        blends: true,
        shading: false,
        depth: false,
    },
    Method {
        name: "painter",
        summary: "APPROXIMATE: whole faces sorted by farthest depth, as matplotlib and GL2PS do; wrong on cyclic overlap and interpenetration (SVG, JSON, PNG)",
        engine: Engine::Object(&Painter),
        exact: false,
        outputs: VECTOR,
        blends: true,
        shading: false,
        depth: false,
    },
];

/// The method called `name`, if any.
pub fn method(name: &str) -> Option<&'static Method> {
    METHODS.iter().find(|m| m.name == name)
}

/// The names of the registered methods with a capability, for messages: "a, b or c".
pub fn names_with(capable: impl Fn(&Method) -> bool) -> String {
    let names: Vec<&str> = METHODS
        .iter()
        .filter(|m| capable(m))
        .map(|m| m.name)
        .collect();
    match names.split_last() {
        Some((last, [])) => last.to_string(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// The method used when none is asked for: the exact visible set for vector output, the
/// reference z-buffer for pixels.
pub fn default_for(output: Output) -> &'static Method {
    let name = match output {
        Output::Svg | Output::Json => "auto",
        Output::Png => "zbuffer",
    };
    method(name).expect("the defaults are registered")
}

impl Method {
    /// Does it write `output`?
    pub fn writes(&self, output: Output) -> bool {
        self.outputs.contains(&output)
    }

    /// Does it draw pixels rather than polygons?
    pub fn is_image_space(&self) -> bool {
        matches!(self.engine, Engine::Image(_))
    }

    /// The input face id it shows at every pixel centre of `screen` (row-major, row 0 at the
    /// top; `None` for background): the common ground on which methods are compared.
    pub fn face_ids(
        &self,
        scene: &Scene,
        screen: &ScreenScene,
        camera: &Camera,
        report: Option<Report>,
    ) -> Vec<Option<u32>> {
        match self.engine {
            Engine::Object(strategy) => {
                let p = picture(
                    strategy,
                    scene,
                    screen,
                    camera,
                    Fill::Id,
                    DrawOptions::per_face(),
                    report,
                );
                raster_drawing::face_ids(&p.drawing)
            }
            Engine::Image(renderer) => {
                let paints = screen_paints(scene, screen, camera, Fill::Id);
                let options = RasterOptions {
                    paints: &paints,
                    background: [0.0; 3],
                    blend: false,
                    depth: false,
                };
                renderer.render(screen, &options, report).face_ids(screen)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_found() {
        for (i, m) in METHODS.iter().enumerate() {
            assert!(METHODS[..i].iter().all(|o| o.name != m.name), "{}", m.name);
            assert!(std::ptr::eq(method(m.name).unwrap(), m));
            assert!(!m.outputs.is_empty(), "{}", m.name);
        }
        assert!(method("nope").is_none());
    }

    #[test]
    fn names_with_lists_the_capable_methods_in_registry_order() {
        assert_eq!(names_with(|m| m.depth), "zbuffer");
        assert_eq!(names_with(|m| m.shading), "zbuffer, scanline or warnock");
        assert_eq!(names_with(|_| false), "");
    }

    #[test]
    fn defaults_write_their_output() {
        for o in [Output::Svg, Output::Json, Output::Png] {
            assert!(default_for(o).writes(o));
        }
    }

    #[test]
    fn image_space_methods_write_pixels_only_and_only_they_shade_per_pixel() {
        for m in &METHODS {
            if m.is_image_space() {
                assert_eq!(m.outputs, &[Output::Png], "{}", m.name);
            } else {
                assert!(!m.shading && !m.depth, "{}", m.name);
            }
        }
    }
}
