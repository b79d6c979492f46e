//! JSON output of a [`Drawing`], grouped by input face.
//!
//! Schema (keys in this order; pretty-printed; the same input gives the same bytes):
//!
//! ```text
//! {
//!   "width": W, "height": H,                  image size in pixels
//!   "faces": [                                one entry per face id drawn, ids ascending
//!     {
//!       "id": 12,                             input face id (provenance)
//!       "material": { "name": "...", "diffuse": [r,g,b], "emissive": [r,g,b],
//!                     "transparency": t, "two_sided": false },
//!       "regions": [                          this face's items, in painter order
//!         [ [ [x,y], [x,y], ... ], ... ]      one region: its rings (even-odd), each ring
//!       ],                                    closed implicitly (last point not repeated)
//!       "draw_order": [ k, ... ]              per region, its index in the whole drawing's
//!     }                                       back-to-front order (needed for translucency)
//!   ],
//!   "stats": { ... }                          the method's counters, keys sorted
//! }
//! ```
//!
//! A region is a list of rings rather than a single ring so that a region with holes keeps its
//! even-odd meaning and two regions of one face are never mistaken for one ring set.
//! Coordinates are pixels, y down, written as the shortest decimal that parses back to the same
//! f64 (serde_json's); -0 is written as 0.

use super::drawing::{DrawItem, Drawing};
use crate::scene::{FaceId, Scene};
use serde::Serialize;
use std::collections::BTreeMap;

#[derive(Serialize)]
struct Doc<'a> {
    width: u32,
    height: u32,
    faces: Vec<FaceOut<'a>>,
    stats: &'a serde_json::Map<String, serde_json::Value>,
}

#[derive(Serialize)]
struct FaceOut<'a> {
    id: FaceId,
    material: MaterialOut<'a>,
    regions: Vec<Region<'a>>,
    draw_order: Vec<usize>,
}

#[derive(Serialize)]
struct MaterialOut<'a> {
    name: &'a str,
    diffuse: [f64; 3],
    emissive: [f64; 3],
    transparency: f64,
    two_sided: bool,
}

/// A region's rings, serialized with -0 normalized.
struct Region<'a>(&'a DrawItem);

impl Serialize for Region<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        // `x + 0.0` turns -0 into +0 and leaves every other value alone.
        let rings: Vec<Vec<[f64; 2]>> = self
            .0
            .rings
            .iter()
            .map(|r| r.iter().map(|p| [p[0] + 0.0, p[1] + 0.0]).collect())
            .collect();
        rings.serialize(s)
    }
}

/// The JSON document of `drawing`; `scene` supplies the materials, `stats` the counters.
pub fn write_json(
    drawing: &Drawing,
    scene: &Scene,
    stats: &serde_json::Map<String, serde_json::Value>,
) -> String {
    let mut by_face: BTreeMap<FaceId, Vec<usize>> = BTreeMap::new();
    for (k, it) in drawing.items.iter().enumerate() {
        by_face.entry(it.face).or_default().push(k);
    }
    let faces = by_face
        .into_iter()
        .map(|(id, order)| {
            // The pieces of one face share its material; take the first item's.
            let m = &scene.materials[drawing.items[order[0]].material as usize];
            FaceOut {
                id,
                material: MaterialOut {
                    name: &m.name,
                    diffuse: m.diffuse,
                    emissive: m.emissive,
                    transparency: m.transparency,
                    two_sided: m.two_sided,
                },
                regions: order.iter().map(|&k| Region(&drawing.items[k])).collect(),
                draw_order: order,
            }
        })
        .collect();
    let doc = Doc {
        width: drawing.width,
        height: drawing.height,
        faces,
        stats,
    };
    let mut out = serde_json::to_string_pretty(&doc).expect("JSON of plain data cannot fail");
    out.push('\n');
    out
}
