//! The image-space renderers behind one trait, so the method registry ([`crate::methods`]), the
//! CLI and the tests run any of them alike.
//!
//! Invariant of every [`Raster`]: `poly` holds, at every pixel centre (row-major, row 0 at the
//! top), the screen polygon seen there or [`EMPTY`], decided exactly (the four renderers agree
//! with one another at every pixel, which the tests check).

use super::{EMPTY, abuffer, scanline, warnock, zbuffer};
use crate::paint::Paint;
use crate::progress::{Report, Ticker};
use crate::project::ScreenScene;

/// What a renderer is asked for besides the screen scene.
#[derive(Clone, Copy, Debug)]
pub struct RasterOptions<'a> {
    /// `paints[k]` fills `screen.polys[k]` ([`crate::paint::screen_paints`]).
    pub paints: &'a [Paint],
    /// Linear RGB the A-buffer blends translucent faces over where nothing opaque is.
    pub background: [f64; 3],
    /// Blend translucent faces into colours ([`Raster::blended`]), where the renderer can.
    pub blend: bool,
    /// Also return normalized depths ([`Raster::depth`]), where the renderer can.
    pub depth: bool,
}

/// What an image-space renderer produced.
#[derive(Clone, Debug, Default)]
pub struct Raster {
    /// The polygon at each pixel centre, [`EMPTY`] for none.
    pub poly: Vec<u32>,
    /// Blended linear RGB per pixel, when asked for and the renderer blends (the A-buffer).
    pub blended: Option<Vec<[f64; 3]>>,
    /// Depth per pixel in \[0, 1\] (1 for background), when asked for and the renderer keeps it.
    pub depth: Option<Vec<f64>>,
    /// The renderer's counters, one line.
    pub detail: String,
}

/// An image-space renderer.
pub trait Renderer: Send + Sync {
    /// Renders `screen`. `report` gets the progress of the long stages.
    fn render(
        &self,
        screen: &ScreenScene,
        options: &RasterOptions,
        report: Option<Report>,
    ) -> Raster;
}

/// The exact z-buffer, the reference ([`zbuffer`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct ZBufferRenderer;

impl Renderer for ZBufferRenderer {
    fn render(
        &self,
        screen: &ScreenScene,
        options: &RasterOptions,
        report: Option<Report>,
    ) -> Raster {
        let mut ticker = Ticker::new(report, "rendering", screen.polys.len() as u64);
        let zb = zbuffer::render(screen, |n| ticker.tick(n as u64));
        ticker.finish();
        let detail = format!(
            "fragments {}, exact fallbacks: edge {} depth {}, depth ties {}",
            zb.stats.fragments,
            zb.stats.column_fallbacks,
            zb.stats.depth_fallbacks,
            zb.stats.depth_ties
        );
        Raster {
            depth: options.depth.then(|| zb.normalized_depth(screen)),
            poly: zb.poly,
            blended: None,
            detail,
        }
    }
}

/// The A-buffer: per-pixel fragment lists, translucent faces blended ([`abuffer`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct ABufferRenderer;

impl Renderer for ABufferRenderer {
    fn render(&self, screen: &ScreenScene, options: &RasterOptions, _: Option<Report>) -> Raster {
        let ab = abuffer::render(
            screen,
            options.paints,
            options.background,
            abuffer::Options::default(),
        );
        Raster {
            detail: format!("{:?}", ab.stats),
            blended: options.blend.then_some(ab.color),
            poly: ab.poly,
            depth: None,
        }
    }
}

/// Watkins' scanline ([`scanline`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct ScanlineRenderer;

impl Renderer for ScanlineRenderer {
    fn render(&self, screen: &ScreenScene, _: &RasterOptions, _: Option<Report>) -> Raster {
        let r = scanline::render(screen);
        Raster {
            detail: format!("{:?}", r.stats),
            poly: r.poly,
            ..Raster::default()
        }
    }
}

/// Warnock's area subdivision ([`warnock`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct WarnockRenderer;

impl Renderer for WarnockRenderer {
    fn render(&self, screen: &ScreenScene, _: &RasterOptions, _: Option<Report>) -> Raster {
        let r = warnock::render(screen);
        Raster {
            detail: format!("{:?}", r.stats),
            poly: r.poly,
            ..Raster::default()
        }
    }
}

impl Raster {
    /// The input face id at every pixel (`None` for background).
    pub fn face_ids(&self, screen: &ScreenScene) -> Vec<Option<u32>> {
        self.poly
            .iter()
            .map(|&p| (p != EMPTY).then(|| screen.polys[p as usize].id))
            .collect()
    }
}
