//! Drawing sheets: aligned orthographic views and one pictorial view of a scene, at a standard
//! scale, on a paper size, with a border and a title block, written as SVG in millimetres.
//!
//! Conventions (stated here and in the README):
//! - **Units**: model coordinates are millimetres unless [`SheetOptions::units`] says
//!   otherwise; the scale is paper mm to model mm (`1:2`: one paper mm for two model mm).
//! - **Views**: the named views of [`NamedView`] (front from +z with y up, top from +y with -z
//!   up, right from +x with y up, ...), each an orthographic [`line_drawing`] of the scene.
//!   Third-angle projection puts the top view above the front view and the right view to its
//!   right; first-angle puts the top view below and the right view to its left (ISO 5456-2);
//!   [`layout`] gives every place. The pictorial view (`iso`, along (1, 1, 1)) is drawn in the
//!   largest free area, without hidden lines (as pictorial views usually are), at the sheet's
//!   scale when it fits there, else smaller and labelled "NOT TO SCALE".
//! - **Paper**: landscape unless [`SheetOptions::portrait`]; the frame is 20 mm from the left
//!   edge (for filing) and 10 mm from the others (ISO 5457), with centring marks; the title
//!   block (ISO 7200-like, 180 mm wide) sits in the frame's bottom-right corner.
//!
//! Invariants of a [`Sheet`]:
//! - **Aligned exactly**: the orthographic views are drawn by cameras built from the model's
//!   bounding box, not fitted per view: every camera's image is the same square of
//!   [`IMAGE_SIDE`] pixels covering the same width of the model, centred on the box's centre,
//!   so a model point has the same bits of pixel x in the front, top, bottom and back views and
//!   the same pixel y in the front, left, right and back views; pixels map to paper by one
//!   scale and each column's (row's) one centre, so aligned points have identical mm.
//! - **Reproducible**: the bytes depend only on the scene and the options (no clock: the date
//!   is given or left blank).
//! - Text is drawn as strokes ([`font`]), so the SVG needs no font to show or convert to PDF.

pub mod font;
pub mod layout;
pub mod paper;
mod svg;

pub use layout::{Layout, Rect};
pub use paper::{Paper, ProjectionMethod, Scale, SheetDate, Units, parse_views, view_name};

use crate::camera::{Camera, NamedView, Projection, bounding_sphere};
use crate::error::Error;
use crate::lines::{LineDrawing, LineOptions, line_drawing};
use crate::progress::Report;
use crate::scene::Scene;
use glam::DVec3;

/// The side of every view's camera image, pixels: the exact grid has 2^22 units per half
/// image whatever this is, so it only sets the pixel scale of the line drawings.
pub const IMAGE_SIDE: u32 = 4096;
/// Space around the model in each view, as a fraction of the model's largest extent.
const PAD: f64 = 0.01;
/// Frame distance from the left edge (filing margin) and from the other edges, mm (ISO 5457).
const MARGIN_LEFT: f64 = 20.0;
const MARGIN: f64 = 10.0;
/// Views keep this far inside the frame, mm.
const INSET: f64 = 5.0;
/// Title block size, mm (ISO 7200: at most 180 mm wide).
const TITLE_W: f64 = 180.0;
const TITLE_H: f64 = 28.0;
/// View labels' cap height, mm (ISO 3098 sizes).
const LABEL_H: f64 = 3.5;
/// The "NOT TO SCALE" note's cap height under a label, mm.
const NOTE_H: f64 = 2.5;
/// The space under a view for its label, mm; a note adds [`NOTE_SPACE`].
const LABEL_SPACE: f64 = 8.0;
const NOTE_SPACE: f64 = 4.0;
/// The note under a pictorial view not at the sheet's scale.
const NOT_TO_SCALE: &str = "NOT TO SCALE";

/// What a sheet shows and how.
#[derive(Clone, Debug, PartialEq)]
pub struct SheetOptions {
    /// The views, each at most once; `Iso` is the pictorial view.
    pub views: Vec<NamedView>,
    /// Third- or first-angle arrangement.
    pub method: ProjectionMethod,
    /// The paper size.
    pub paper: Paper,
    /// Portrait instead of landscape.
    pub portrait: bool,
    /// The scale; `None`: the largest standard one that fits.
    pub scale: Option<Scale>,
    /// The unit of the model's coordinates.
    pub units: Units,
    /// The date in the title block; `None` leaves it blank.
    pub date: Option<SheetDate>,
    /// The title (the input's file name).
    pub title: String,
    /// The lines of each view (crease angle, hidden lines).
    pub lines: LineOptions,
}

impl Default for SheetOptions {
    fn default() -> Self {
        SheetOptions {
            views: vec![
                NamedView::Front,
                NamedView::Top,
                NamedView::Right,
                NamedView::Iso,
            ],
            method: ProjectionMethod::Third,
            paper: Paper::A3,
            portrait: false,
            scale: None,
            units: Units::Mm,
            date: None,
            title: String::new(),
            lines: LineOptions::default(),
        }
    }
}

/// A view placed on the sheet.
#[derive(Clone, Debug)]
pub struct PlacedView {
    /// Which view.
    pub view: NamedView,
    /// The model's box (orthographic) or the drawing's extent (pictorial), padded, on paper.
    pub frame: Rect,
    /// Paper mm per model mm.
    pub factor: f64,
    /// Is it at the sheet's scale?
    pub to_scale: bool,
    /// Its lines, in its camera's pixels.
    pub drawing: LineDrawing,
    /// The pixel at `centre_mm`.
    centre_px: [f64; 2],
    /// Where `centre_px` lands on paper.
    centre_mm: [f64; 2],
    /// Paper mm per pixel.
    mm_per_px: f64,
}

impl PlacedView {
    /// A point of the drawing (pixels) on paper (mm).
    pub fn to_paper(&self, p: [f64; 2]) -> [f64; 2] {
        [
            self.centre_mm[0] + (p[0] - self.centre_px[0]) * self.mm_per_px,
            self.centre_mm[1] + (p[1] - self.centre_px[1]) * self.mm_per_px,
        ]
    }

    /// Its label: `FRONT`, `TOP`, ..., `ISO`.
    pub fn label(&self) -> String {
        view_name(self.view).to_uppercase()
    }

    /// The note under its label: "NOT TO SCALE" when it is not at the sheet's scale.
    pub fn note(&self) -> Option<&'static str> {
        (!self.to_scale).then_some(NOT_TO_SCALE)
    }
}

/// A laid-out sheet, ready to write ([`Sheet::svg`]).
#[derive(Clone, Debug)]
pub struct Sheet {
    /// Paper width, mm.
    pub width: f64,
    /// Paper height, mm.
    pub height: f64,
    /// The border.
    pub frame: Rect,
    /// The title block.
    pub title_block: Rect,
    /// The orthographic views' scale.
    pub scale: Scale,
    /// The views, in the order asked for.
    pub views: Vec<PlacedView>,
    /// What the title block says.
    pub title: String,
    /// The paper.
    pub paper: Paper,
    /// The arrangement.
    pub method: ProjectionMethod,
    /// The date, if given.
    pub date: Option<SheetDate>,
}

/// The progress stage of a view, as the command line's bars label it.
fn stage(view: NamedView) -> &'static str {
    match view {
        NamedView::Front => "FRONT view",
        NamedView::Back => "BACK view",
        NamedView::Top => "TOP view",
        NamedView::Bottom => "BOTTOM view",
        NamedView::Left => "LEFT view",
        NamedView::Right => "RIGHT view",
        NamedView::Iso => "ISO view",
    }
}

/// The world axes (0 x, 1 y, 2 z) across and up an orthographic view's image.
fn image_axes(view: NamedView) -> (usize, usize) {
    match view {
        NamedView::Front | NamedView::Back | NamedView::Iso => (0, 1),
        NamedView::Top | NamedView::Bottom => (0, 2),
        NamedView::Left | NamedView::Right => (2, 1),
    }
}

/// An orthographic camera along `view`, its square image `side` world units across, centred
/// on the box's centre.
fn camera(view: NamedView, bounds: (DVec3, DVec3), side: f64) -> Camera {
    let (dir, up) = view.direction_and_up();
    let (centre, radius) = bounding_sphere(bounds);
    let mut cam = Camera {
        eye: centre + dir * (2.0 * radius),
        target: centre,
        up,
        projection: Projection::Orthographic { height: side },
        near: 0.0,
        far: 1.0,
        width: IMAGE_SIDE,
        height: IMAGE_SIDE,
    };
    cam.fit_depth_range(bounds);
    cam
}

/// The extent of a drawing's points, pixels, `None` when it has none.
fn extent(d: &LineDrawing) -> Option<Rect> {
    let mut pts = d.strokes.iter().flat_map(|s| s.points.iter());
    let first = pts.next()?;
    let r = Rect {
        x0: first[0],
        y0: first[1],
        x1: first[0],
        y1: first[1],
    };
    Some(pts.fold(r, |r, p| Rect {
        x0: r.x0.min(p[0]),
        y0: r.y0.min(p[1]),
        x1: r.x1.max(p[0]),
        y1: r.y1.max(p[1]),
    }))
}

/// Lays out the sheet of `scene`: draws every view, chooses the scale and the places, and
/// returns the sheet. Progress: one stage per view ("FRONT view", ...), the line drawing's own
/// stages in between.
pub fn sheet(
    scene: &Scene,
    options: &SheetOptions,
    report: Option<Report>,
) -> crate::Result<Sheet> {
    let bounds = scene
        .bounds()
        .ok_or_else(|| Error::Camera(format!("{}: no face to draw", scene.source)))?;
    if options.views.is_empty() {
        return Err(Error::Options("no view to draw".into()));
    }
    let units = options.units.mm();
    let ext = bounds.1 - bounds.0;
    let pad = PAD * ext.max_element();
    // Every view's camera sees a square this wide: the largest extent and the pads.
    let side = ext.max_element() + 2.0 * pad;
    let world_per_px = side / f64::from(IMAGE_SIDE);
    let (_, radius) = bounding_sphere(bounds);

    let mut drawn = Vec::new();
    for &view in &options.views {
        let st = stage(view);
        if let Some(r) = report {
            r(st, 0, 1);
        }
        let (cam, lines) = if view == NamedView::Iso {
            // The box seen along a diagonal fits in its bounding sphere's disc.
            let side = 2.0 * radius * (1.0 + PAD);
            let lines = LineOptions {
                hidden: false,
                ..options.lines.clone()
            };
            (camera(view, bounds, side), lines)
        } else {
            (camera(view, bounds, side), options.lines.clone())
        };
        let drawing = line_drawing(scene, &cam, &lines, report)?.drawing;
        if let Some(r) = report {
            r(st, 1, 1);
        }
        drawn.push((view, cam, drawing));
    }

    // Frames: each orthographic view's box extent and pads (model mm); the pictorial view's
    // drawn extent and pads.
    let half = f64::from(IMAGE_SIDE) / 2.0;
    let mut ortho = Vec::new();
    let mut iso = None;
    for (view, cam, drawing) in &drawn {
        if *view == NamedView::Iso {
            let Projection::Orthographic { height } = cam.projection else {
                unreachable!("sheet cameras are orthographic")
            };
            let wpp = height / f64::from(IMAGE_SIDE);
            let pad_px = pad / wpp;
            let e = extent(drawing).unwrap_or(Rect {
                x0: half,
                y0: half,
                x1: half,
                y1: half,
            });
            let e = e.grown(pad_px);
            iso = Some((e, wpp));
        } else {
            let (ax, ay) = image_axes(*view);
            let name = view_name(*view).to_uppercase();
            ortho.push(layout::Item {
                view: *view,
                size: [(ext[ax] + 2.0 * pad) * units, (ext[ay] + 2.0 * pad) * units],
                label: [font::text_width(&name, LABEL_H), LABEL_SPACE],
            });
        }
    }

    let (width, height) = {
        let (w, h) = options.paper.landscape_mm();
        if options.portrait { (h, w) } else { (w, h) }
    };
    let frame = Rect {
        x0: MARGIN_LEFT,
        y0: MARGIN,
        x1: width - MARGIN,
        y1: height - MARGIN,
    };
    let title_block = Rect::at(frame.x1 - TITLE_W, frame.y1 - TITLE_H, TITLE_W, TITLE_H);
    let area = Rect {
        x0: frame.x0 + INSET,
        y0: frame.y0 + INSET,
        x1: frame.x1 - INSET,
        y1: frame.y1 - INSET,
    };
    let request = layout::Request {
        ortho: &ortho,
        // Room for the note too, whether or not the view ends up at the sheet's scale.
        iso: iso.map(|(e, wpp)| layout::Item {
            view: NamedView::Iso,
            size: [e.width() * wpp * units, e.height() * wpp * units],
            label: [
                font::text_width("ISO", LABEL_H).max(font::text_width(NOT_TO_SCALE, NOTE_H)),
                LABEL_SPACE + NOTE_SPACE,
            ],
        }),
        method: options.method,
        area,
        keep_out: title_block,
        scale: options.scale,
    };
    let placed = layout::layout(&request).map_err(|e| {
        Error::Options(format!(
            "{} {}: {e}",
            options.paper.name(),
            if options.portrait {
                "portrait"
            } else {
                "landscape"
            }
        ))
    })?;

    let factor = placed.scale.factor();
    let mut views = Vec::new();
    let mut next_ortho = placed.ortho.iter();
    for (view, _, drawing) in drawn {
        let place = if view == NamedView::Iso {
            let ((rect, f), (e, wpp)) = (placed.iso.expect("laid out"), iso.expect("drawn"));
            PlacedView {
                view,
                frame: rect,
                factor: f,
                to_scale: placed.iso_to_scale(),
                drawing,
                centre_px: e.centre(),
                centre_mm: rect.centre(),
                mm_per_px: wpp * units * f,
            }
        } else {
            let rect = *next_ortho.next().expect("one frame per view");
            PlacedView {
                view,
                frame: rect,
                factor,
                to_scale: true,
                drawing,
                centre_px: [half, half],
                centre_mm: rect.centre(),
                mm_per_px: world_per_px * units * factor,
            }
        };
        views.push(place);
    }
    Ok(Sheet {
        width,
        height,
        frame,
        title_block,
        scale: placed.scale,
        views,
        title: options.title.clone(),
        paper: options.paper,
        method: options.method,
        date: options.date.clone(),
    })
}

impl Sheet {
    /// The sheet as an SVG document in millimetres.
    pub fn svg(&self) -> String {
        svg::write(self)
    }
}
