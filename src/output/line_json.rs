//! JSON output of a hidden-line drawing ([`LineDrawing`]).
//!
//! Schema (keys in this order; pretty-printed, each stroke's points on one line; the same
//! drawing gives the same bytes):
//!
//! ```text
//! {
//!   "schema": "sightline/lines",           what this document is ([`SCHEMA`])
//!   "version": 1,                          its version ([`VERSION`])
//!   "width": W, "height": H,               image size in pixels
//!   "strokes": [                           in the drawing's order
//!     {
//!       "visibility": "visible",           or "hidden"
//!       "kind": "silhouette",              boundary, intersection, crease, material
//!       "qi": 0,                           faces in front (hidden: at least 1)
//!       "closed": false,                   the last point joins the first
//!       "points": [[x,y],[x,y],...]        pixels, y down; a closed stroke does not repeat
//!     }                                    its first point
//!   ]
//! }
//! ```
//!
//! Coordinates are written as the shortest decimal that parses back to the same f64
//! (serde_json's), -0 as 0. The version follows the rule of [`super::json`]: it goes up when a
//! field is removed, renamed or changes type, unit or meaning; a new field does not change it.
//! The README's "Output contract" lists every field.

use super::json::pretty_inline;
use crate::lines::{LineDrawing, LineKind, Stroke, Visibility};
use serde::Serialize;

/// The `schema` of every line document.
pub const SCHEMA: &str = "sightline/lines";

/// The `version` of the schema this writer follows.
pub const VERSION: u32 = 1;

#[derive(Serialize)]
struct Doc {
    schema: &'static str,
    version: u32,
    width: u32,
    height: u32,
    strokes: Vec<StrokeOut>,
}

#[derive(Serialize)]
struct StrokeOut {
    visibility: Visibility,
    kind: LineKind,
    qi: u32,
    closed: bool,
    points: Vec<[f64; 2]>,
}

impl From<&Stroke> for StrokeOut {
    fn from(s: &Stroke) -> Self {
        StrokeOut {
            visibility: s.visibility,
            kind: s.kind,
            qi: s.qi,
            closed: s.closed,
            // `x + 0.0` turns -0 into +0 and leaves every other value alone.
            points: s.points.iter().map(|p| [p[0] + 0.0, p[1] + 0.0]).collect(),
        }
    }
}

/// Container depth of a stroke's `points` array (the document, `strokes`, the stroke, then
/// `points`): written on one line with its points.
const POINTS_DEPTH: usize = 4;

/// The JSON document of `drawing`.
pub fn write_line_json(drawing: &LineDrawing) -> String {
    let doc = Doc {
        schema: SCHEMA,
        version: VERSION,
        width: drawing.width,
        height: drawing.height,
        strokes: drawing.strokes.iter().map(StrokeOut::from).collect(),
    };
    pretty_inline(&doc, POINTS_DEPTH)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_document_lists_strokes_with_full_precision_points_on_one_line() {
        let drawing = LineDrawing {
            width: 7,
            height: 5,
            strokes: vec![
                Stroke {
                    visibility: Visibility::Hidden,
                    kind: LineKind::Intersection,
                    qi: 2,
                    points: vec![[0.1 + 0.2, -0.0], [1.0 / 3.0, 4.5]],
                    closed: true,
                },
                Stroke {
                    visibility: Visibility::Visible,
                    kind: LineKind::Material,
                    qi: 0,
                    points: vec![[1.0, 2.0], [3.0, 4.0]],
                    closed: false,
                },
            ],
        };
        let text = write_line_json(&drawing);
        assert_eq!(
            text,
            "{\n  \"schema\": \"sightline/lines\",\n  \"version\": 1,\n  \"width\": 7,\n  \
             \"height\": 5,\n  \"strokes\": [\n    {\n      \"visibility\": \"hidden\",\n      \
             \"kind\": \"intersection\",\n      \"qi\": 2,\n      \"closed\": true,\n      \
             \"points\": [[0.30000000000000004,0.0],[0.3333333333333333,4.5]]\n    },\n    {\n      \
             \"visibility\": \"visible\",\n      \"kind\": \"material\",\n      \"qi\": 0,\n      \
             \"closed\": false,\n      \"points\": [[1.0,2.0],[3.0,4.0]]\n    }\n  ]\n}\n"
        );
        let back: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(back["strokes"][0]["points"][1][0].as_f64(), Some(1.0 / 3.0));
    }
}
