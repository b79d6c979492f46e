//! sightline: exact object-space visibility.
//!
//! The pipeline (see `DESIGN.md`): load a [`scene::Scene`], place a [`camera::Camera`], project and
//! clip every face into exact screen polygons ([`project`]), cull and analyse them, then render
//! (the z-buffer reference in [`raster`]) or, in later stages, compute exact visible sets.

pub mod error;
pub mod scene;

pub use error::{Error, LoadError, Location, Result};
pub use scene::{Face, FaceId, Material, Mesh, Scene, load};
pub mod camera;
pub mod draw;
pub mod exact;
pub mod methods;
pub mod output;
pub mod paint;
pub mod pipeline;
pub mod progress;
pub mod project;
pub mod raster;
pub mod visibility;
