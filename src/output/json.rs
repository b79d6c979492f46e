//! JSON output of a [`Drawing`], grouped by input face.
//!
//! Schema (keys in this order; pretty-printed, but each region and colour on one line, so a
//! drawing stays near the size of its numbers; the same input gives the same bytes):
//!
//! ```text
//! {
//!   "schema": "sightline/visible-set",        what this document is ([`SCHEMA`])
//!   "version": 1,                             its version ([`VERSION`])
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
//!   "stats": { ... }                          the method's counters, keys sorted (no timings:
//!                                             they go to `--stats` on stderr)
//! }
//! ```
//!
//! The README's "Output contract" lists every field, as a contract: a reader of version N
//! reads every document of version N. [`VERSION`] goes up when a field is removed, renamed or
//! changes type, unit or meaning, or an ordering guarantee is dropped; a new field does not
//! change it (readers ignore fields they do not know).
//!
//! Regions are written as the drawing has them: canonicalize it first
//! ([`super::canonical::canonicalize`], as the CLI does) for bytes that depend only on what is
//! drawn.
//!
//! JSON is per face: write it from a drawing made without surface merging (the CLI does); an
//! item merged across faces would be listed under its first face only.
//!
//! A region is a list of rings rather than a single ring so that a region with holes keeps its
//! even-odd meaning and two regions of one face are never mistaken for one ring set.
//! Coordinates are pixels, y down, written as the shortest decimal that parses back to the same
//! f64 (serde_json's); -0 is written as 0.

use super::drawing::{DrawItem, Drawing};
use crate::scene::{FaceId, Material, Scene};
use serde::Serialize;
use serde_json::ser::{Formatter, PrettyFormatter};
use std::collections::BTreeMap;
use std::io::{self, Write};

/// The `schema` of every document: what it is.
pub const SCHEMA: &str = "sightline/visible-set";

/// The `version` of the schema this writer follows (see the module docs for when it changes).
pub const VERSION: u32 = 1;

#[derive(Serialize)]
struct Doc<'a> {
    // First, so that a reader knows what it reads before anything else.
    schema: &'static str,
    version: u32,
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
        s.collect_seq(self.0.rings.iter().map(|r| Ring(r)))
    }
}

/// A ring's points, -0 written as 0 (`x + 0.0` turns -0 into +0 and leaves every other value
/// alone), without copying the ring.
struct Ring<'a>(&'a [[f64; 2]]);

impl Serialize for Ring<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.0.iter().map(|p| [p[0] + 0.0, p[1] + 0.0]))
    }
}

/// The JSON document of `drawing`; `scene` supplies the materials, `stats` the counters.
pub fn write_json(
    drawing: &Drawing,
    scene: &Scene,
    stats: &serde_json::Map<String, serde_json::Value>,
) -> String {
    let mut out = Vec::new();
    write_json_to(&mut out, drawing, &scene.materials, stats)
        .expect("JSON of plain data into memory cannot fail");
    String::from_utf8(out).expect("serde_json writes UTF-8")
}

/// Writes the JSON document of `drawing` to `out` as it goes (nothing of it is held in memory
/// but the per-face index); `materials` are the scene's.
pub fn write_json_to(
    out: &mut dyn Write,
    drawing: &Drawing,
    materials: &[Material],
    stats: &serde_json::Map<String, serde_json::Value>,
) -> io::Result<()> {
    let mut by_face: BTreeMap<FaceId, Vec<usize>> = BTreeMap::new();
    for (k, it) in drawing.items.iter().enumerate() {
        by_face.entry(it.face).or_default().push(k);
    }
    let faces = by_face
        .into_iter()
        .map(|(id, order)| {
            // The pieces of one face share its material; take the first item's.
            let m = &materials[drawing.items[order[0]].material as usize];
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
        schema: SCHEMA,
        version: VERSION,
        width: drawing.width,
        height: drawing.height,
        faces,
        stats,
    };
    write_pretty_inline(out, &doc, INLINE_DEPTH)
}

/// `doc` as JSON in the layout of [`RingsInline`] with arrays `inline_depth` containers deep or
/// more on one line, ending with a newline.
pub(super) fn pretty_inline<T: Serialize>(doc: &T, inline_depth: usize) -> String {
    let mut out = Vec::new();
    write_pretty_inline(&mut out, doc, inline_depth)
        .expect("JSON of plain data into memory cannot fail");
    String::from_utf8(out).expect("serde_json writes UTF-8")
}

/// [`pretty_inline`], written to `out` as it goes.
fn write_pretty_inline<T: Serialize>(
    out: &mut dyn Write,
    doc: &T,
    inline_depth: usize,
) -> io::Result<()> {
    let formatter = RingsInline {
        inline_depth,
        ..RingsInline::default()
    };
    let mut ser = serde_json::Serializer::with_formatter(&mut *out, formatter);
    doc.serialize(&mut ser).map_err(io::Error::other)?;
    out.write_all(b"\n")
}

/// serde_json's pretty layout, except that an array nested `inline_depth` containers deep or
/// more ([`INLINE_DEPTH`] by default), and everything inside it, is written compactly on one
/// line.
struct RingsInline {
    pretty: PrettyFormatter<'static>,
    /// The container depth from which arrays are written on one line.
    inline_depth: usize,
    /// Containers (arrays and objects) open.
    depth: usize,
    /// The container depth at which compact writing began.
    compact_from: Option<usize>,
}

/// Container nesting (objects and arrays, the document itself 1) from which arrays are written
/// on one line: in our schema a face's colours and each of its regions.
const INLINE_DEPTH: usize = 5;

impl Default for RingsInline {
    fn default() -> Self {
        RingsInline {
            pretty: PrettyFormatter::default(),
            inline_depth: INLINE_DEPTH,
            depth: 0,
            compact_from: None,
        }
    }
}

impl Formatter for RingsInline {
    fn begin_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.depth += 1;
        if self.compact_from.is_none() && self.depth >= self.inline_depth {
            self.compact_from = Some(self.depth);
        }
        match self.compact_from {
            Some(_) => w.write_all(b"["),
            None => self.pretty.begin_array(w),
        }
    }

    fn end_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        let r = match self.compact_from {
            Some(_) => w.write_all(b"]"),
            None => self.pretty.end_array(w),
        };
        self.close();
        r
    }

    fn begin_array_value<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        match self.compact_from {
            Some(_) if first => Ok(()),
            Some(_) => w.write_all(b","),
            None => self.pretty.begin_array_value(w, first),
        }
    }

    fn end_array_value<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        match self.compact_from {
            Some(_) => Ok(()),
            None => self.pretty.end_array_value(w),
        }
    }

    fn begin_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.depth += 1;
        match self.compact_from {
            Some(_) => w.write_all(b"{"),
            None => self.pretty.begin_object(w),
        }
    }

    fn end_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        let r = match self.compact_from {
            Some(_) => w.write_all(b"}"),
            None => self.pretty.end_object(w),
        };
        self.close();
        r
    }

    fn begin_object_key<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        match self.compact_from {
            Some(_) if first => Ok(()),
            Some(_) => w.write_all(b","),
            None => self.pretty.begin_object_key(w, first),
        }
    }

    fn begin_object_value<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        match self.compact_from {
            Some(_) => w.write_all(b":"),
            None => self.pretty.begin_object_value(w),
        }
    }

    fn end_object_value<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        match self.compact_from {
            Some(_) => Ok(()),
            None => self.pretty.end_object_value(w),
        }
    }
}

impl RingsInline {
    /// Leaves a container: compact writing ends with the container that began it.
    fn close(&mut self) {
        if self.compact_from == Some(self.depth) {
            self.compact_from = None;
        }
        self.depth -= 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layout(v: &serde_json::Value) -> String {
        let mut out = Vec::new();
        let mut ser = serde_json::Serializer::with_formatter(&mut out, RingsInline::default());
        v.serialize(&mut ser).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn the_document_begins_with_its_schema_and_version() {
        let d = Drawing {
            width: 4,
            height: 3,
            background: None,
            items: Vec::new(),
            seams: Default::default(),
            opaque_disjoint: false,
        };
        let text = write_json(&d, &Scene::default(), &serde_json::Map::new());
        assert!(
            text.starts_with(
                "{\n  \"schema\": \"sightline/visible-set\",\n  \"version\": 1,\n  \"width\": 4,"
            ),
            "{text}"
        );
    }

    #[test]
    fn deep_arrays_are_inline_the_rest_pretty_and_it_parses_back() {
        let v = serde_json::json!({
            "a": [{"b": [[1.5, -2], [3, {"k": [4]}]], "c": {"d": [1]}}, [[2]]],
            "e": [],
            "f": {}
        });
        let text = layout(&v);
        // Arrays in 5 containers or more (the document, a, a's object, b or c, ...) are inline.
        assert_eq!(
            text,
            "{\n  \"a\": [\n    {\n      \"b\": [\n        [1.5,-2],\n        [3,{\"k\":[4]}]\n      \
             ],\n      \"c\": {\n        \"d\": [1]\n      }\n    },\n    [\n      [\n        \
             2\n      ]\n    ]\n  ],\n  \"e\": [],\n  \"f\": {}\n}"
        );
        assert_eq!(serde_json::from_str::<serde_json::Value>(&text).unwrap(), v);
    }
}
