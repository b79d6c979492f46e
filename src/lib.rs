//! sightline: exact object-space visibility. It computes which parts of a 3D scene a camera
//! sees, as exact visible polygons that each know their source face, and renders the same
//! scene with image-space methods (the z-buffer is the reference) to check them against.
//!
//! # The pipeline
//!
//! 1. Load a [`Scene`] ([`load()`]: OBJ, STL, PLY, X3D, optionally gzipped).
//! 2. Place a [`Camera`] ([`CameraSpec`] resolved against the scene, or [`Camera::fit`]).
//! 3. Project, clip and cull it into exact screen polygons ([`pipeline::prepare`]).
//! 4. Run a method from the registry ([`methods::METHODS`], by name with [`methods::method`]):
//!    an object-space [`Strategy`] computes a [`VisibleSet`] (the exact visible pieces of every
//!    face); an image-space [`Renderer`](raster::renderer::Renderer) computes the face at every
//!    pixel.
//! 5. Draw and write: a visible set becomes a [`Drawing`](output::drawing::Drawing)
//!    ([`draw::picture`]), written as SVG ([`output::svg`]), JSON ([`output::json`]) or PNG
//!    ([`output::raster_drawing`]). [`render::render`] runs steps 4 and 5 as `sightline render`
//!    does, from [`RenderOptions`].
//!
//! ```
//! use sightline::methods::{Output, method};
//! use sightline::project::CullMode;
//! use sightline::{CameraSpec, RenderOptions, Strategy, pipeline};
//!
//! let scene = sightline::load("fixtures/cube.obj".as_ref(), None)?;
//! let camera = CameraSpec { size: Some((64, 48)), ..CameraSpec::default() }.resolve_for(&scene)?;
//! let prepared = pipeline::prepare(&scene, &camera, CullMode::Auto);
//!
//! // The exact visible set: which pieces of which faces the camera sees.
//! let visible = sightline::visibility::CoverageMap.visible_set(&prepared.screen, &|_| false, None);
//! // The iso view sees three faces of the cube (a face may be several pieces).
//! let faces: std::collections::BTreeSet<u32> =
//!     visible.pieces.iter().map(|p| prepared.screen.polys[p.poly as usize].face).collect();
//! assert_eq!(faces.len(), 3);
//!
//! // The same, drawn and written as SVG.
//! let options = RenderOptions::new(Output::Svg).with_method(method("coverage").unwrap());
//! let rendered = sightline::render::render(&scene, &camera, &prepared.screen, &options, None)?;
//! let mut svg = Vec::new();
//! rendered.write(&mut svg)?;
//! assert!(svg.starts_with(b"<svg"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! More in `examples/` (`cargo run --release --example render_svg`, `visible_set`,
//! `compare_methods`). Conventions (camera, face ids, winding, culling) and the exactness
//! argument: the README and `DESIGN.md`.
#![warn(missing_docs)]

pub mod error;
pub mod scene;

pub use camera::{Camera, CameraSpec};
pub use error::{Error, LoadError, Location, Result};
pub use methods::{METHODS, Method};
pub use render::RenderOptions;
pub use scene::{Face, FaceId, Material, Mesh, Scene, load};
pub use visibility::{Strategy, VisibleSet};
pub mod benchmark;
pub(crate) mod buckets;
pub mod camera;
pub mod draw;
pub mod exact;
pub mod grade;
pub mod lines;
pub(crate) mod memory;
pub mod methods;
pub mod output;
pub mod paint;
pub mod pipeline;
pub mod progress;
pub mod project;
pub mod raster;
pub mod render;
pub mod report;
pub mod sheet;
pub mod stress;
pub mod visibility;
