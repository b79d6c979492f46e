//! DXF output of a hidden-line drawing ([`LineDrawing`]), through the `dxf` crate.
//!
//! Invariants:
//! - **Layers**: `VISIBLE` (linetype `CONTINUOUS`, lineweight 0.50 mm) and `HIDDEN` (linetype
//!   `HIDDEN`, lineweight 0.25 mm), colour 7 (black on white, white on black), beside the
//!   crate's layer `0` (empty, default lineweight). The `HIDDEN` linetype is defined in the
//!   file as ISO 128 line type 02 for the hidden lineweight d: dash 12·d, gap 3·d (3 mm and
//!   0.75 mm), in the file's units. Entities take their linetype and lineweight from their
//!   layer.
//! - **One `LWPOLYLINE` per stroke**, closed flag set for a closed stroke; hidden strokes first
//!   (so visible ones are drawn over them), each group in the drawing's order.
//! - **Coordinates** y up, as DXF has them: a point (x, y) of the image (pixels, y down) is
//!   written as (s·x, s·(H - y)) with H the image height and s [`DxfOptions::mm_per_px`] (1 when
//!   `None`). Units: pixels ($INSUNITS 0, unitless) or millimetres ($INSUNITS 4). The crate
//!   writes numbers with 12 decimals: a coordinate moves by at most 5·10^-13 units.
//! - **Reproducible bytes**: the header's dates ($TDCREATE, $TDUCREATE, $TDUPDATE,
//!   $TDUUPDATE), which the crate takes from the clock, are the format's epoch (Julian day
//!   2415021, 1900-01-01: no date, whatever the time zone), its GUIDs ($FINGERPRINTGUID,
//!   $VERSIONGUID), random in the crate, are nil; handles are numbered in order.

use crate::error::{Error, Result};
use crate::lines::{LineDrawing, Stroke, Visibility};
use chrono::{Local, TimeZone, Utc};
use dxf::entities::{Entity, EntityType, LwPolyline};
use dxf::enums::{AcadVersion, DrawingUnits, Units};
use dxf::tables::{Layer, LineType};
use dxf::{Color, Drawing, LineWeight, LwPolylineVertex, Point};

/// The layer of visible strokes.
pub const VISIBLE_LAYER: &str = "VISIBLE";
/// The layer of hidden strokes.
pub const HIDDEN_LAYER: &str = "HIDDEN";
/// The dashed linetype of the hidden layer.
pub const HIDDEN_LINETYPE: &str = "HIDDEN";

/// Lineweight of visible lines, hundredths of a millimetre (ISO 128: 0.5 mm).
const VISIBLE_WEIGHT: i16 = 50;
/// Lineweight of hidden lines, hundredths of a millimetre (half the visible one).
const HIDDEN_WEIGHT: i16 = 25;
/// The lineweight enum value that means "as the layer" (AutoCAD's `kLnWtByLayer`).
const WEIGHT_BY_LAYER: i16 = -1;
/// The lineweight enum value that means "the viewer's default" (`kLnWtByLwDefault`).
const WEIGHT_DEFAULT: i16 = -3;

/// What the file's units are.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DxfOptions {
    /// `None` (the default): coordinates in image pixels, unitless. `Some(k)`: in millimetres,
    /// `k` millimetres per pixel (a sheet at its printed size).
    pub mm_per_px: Option<f64>,
}

impl DxfOptions {
    /// File units per image pixel.
    fn scale(&self) -> f64 {
        self.mm_per_px.unwrap_or(1.0)
    }

    /// File units per millimetre (pixels: 96 per inch, as CSS has them).
    fn units_per_mm(&self) -> f64 {
        match self.mm_per_px {
            Some(_) => 1.0,
            None => super::line_svg::PX_PER_MM,
        }
    }
}

/// The DXF (ASCII, AutoCAD R2000) of `drawing`.
pub fn write_dxf(drawing: &LineDrawing, options: &DxfOptions) -> Result<Vec<u8>> {
    let mut dxf = Drawing::new();
    set_header(&mut dxf, drawing, options);
    // The crate's layer 0 has lineweight 0 (the thinnest), not the default.
    for layer in dxf.layers_mut() {
        layer.line_weight = line_weight(WEIGHT_DEFAULT);
    }
    dxf.add_line_type(hidden_linetype(options));
    dxf.add_layer(layer(VISIBLE_LAYER, "CONTINUOUS", VISIBLE_WEIGHT));
    dxf.add_layer(layer(HIDDEN_LAYER, HIDDEN_LINETYPE, HIDDEN_WEIGHT));
    for visibility in [Visibility::Hidden, Visibility::Visible] {
        for stroke in drawing
            .strokes
            .iter()
            .filter(|s| s.visibility == visibility)
        {
            dxf.add_entity(polyline(stroke, drawing.height, options.scale()));
        }
    }
    let mut out = Vec::new();
    dxf.save(&mut out)
        .map_err(|e| Error::Output(format!("writing DXF: {e}")))?;
    Ok(out)
}

/// Version, units, extents and limits (the image's frame), lineweights shown, and the fields
/// the crate fills from the clock or at random fixed (see the module docs).
fn set_header(dxf: &mut Drawing, drawing: &LineDrawing, options: &DxfOptions) {
    let h = &mut dxf.header;
    h.version = AcadVersion::R2000;
    h.default_drawing_units = match options.mm_per_px {
        Some(_) => Units::Millimeters,
        None => Units::Unitless,
    };
    h.drawing_units = DrawingUnits::Metric;
    let s = options.scale();
    let corner = Point::new(drawing.width as f64 * s, drawing.height as f64 * s, 0.0);
    h.minimum_drawing_extents = Point::origin();
    h.maximum_drawing_extents = corner.clone();
    h.minimum_drawing_limits = Point::origin();
    h.maximum_drawing_limits = corner;
    h.display_linewieght_in_model_and_layout_tab = true;
    // The crate writes a date as the days since its 1900-01-01 in the same zone, so that day
    // itself is the same number in every time zone.
    if let Some(epoch) = Local.with_ymd_and_hms(1900, 1, 1, 0, 0, 0).single() {
        h.creation_date = epoch;
        h.update_date = epoch;
    }
    let epoch = Utc.with_ymd_and_hms(1900, 1, 1, 0, 0, 0).unwrap();
    h.creation_date_universal = epoch;
    h.update_date_universal = epoch;
    h.fingerprint_guid = uuid::Uuid::nil();
    h.version_guid = uuid::Uuid::nil();
}

/// ISO 128 line type 02 for the hidden lineweight: dash 12·d, gap 3·d, in file units.
fn hidden_linetype(options: &DxfOptions) -> LineType {
    let d = HIDDEN_WEIGHT as f64 / 100.0 * options.units_per_mm();
    let (dash, gap) = (super::line_svg::ISO_DASH * d, super::line_svg::ISO_GAP * d);
    LineType {
        name: HIDDEN_LINETYPE.into(),
        description: "ISO 128 dashed __ __ __ __".into(),
        element_count: 2,
        total_pattern_length: dash + gap,
        // Positive: a dash; negative: a gap.
        dash_dot_space_lengths: vec![dash, -gap],
        ..LineType::default()
    }
}

fn layer(name: &str, linetype: &str, weight: i16) -> Layer {
    Layer {
        name: name.into(),
        color: Color::from_index(7),
        line_type_name: linetype.into(),
        line_weight: line_weight(weight),
        ..Layer::default()
    }
}

/// A `LineWeight` of `hundredths` of a millimetre. The crate (0.6) has no public constructor
/// for one but reads one from a layer's group 370, so it is read from a one-layer file.
fn line_weight(hundredths: i16) -> LineWeight {
    let text = format!(
        "0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n0\nLAYER\n2\nW\n370\n{hundredths}\n\
         0\nENDTAB\n0\nENDSEC\n0\nEOF\n"
    );
    Drawing::load(&mut text.as_bytes())
        .ok()
        .and_then(|d| {
            d.layers()
                .find(|l| l.name == "W")
                .map(|l| l.line_weight.clone())
        })
        .unwrap_or_default()
}

/// The polyline of `stroke` on its visibility's layer, y flipped and scaled.
fn polyline(stroke: &Stroke, height: u32, scale: f64) -> Entity {
    let mut poly = LwPolyline {
        vertices: stroke
            .points
            .iter()
            .map(|p| LwPolylineVertex {
                x: p[0] * scale,
                y: (height as f64 - p[1]) * scale,
                ..LwPolylineVertex::default()
            })
            .collect(),
        ..LwPolyline::default()
    };
    poly.set_is_closed(stroke.closed);
    let mut entity = Entity::new(EntityType::LwPolyline(poly));
    entity.common.layer = match stroke.visibility {
        Visibility::Visible => VISIBLE_LAYER,
        Visibility::Hidden => HIDDEN_LAYER,
    }
    .into();
    entity.common.lineweight_enum_value = WEIGHT_BY_LAYER;
    entity
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_weights_are_read_back_as_given() {
        assert_eq!(line_weight(50).raw_value(), 50);
        assert_eq!(line_weight(25).raw_value(), 25);
        assert_eq!(line_weight(-3).raw_value(), -3);
    }
}
