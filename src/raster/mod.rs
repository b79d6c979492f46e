//! Image-space renderers and shading. The z-buffer is the reference; the other classic methods
//! (A-buffer, scanline, Warnock) join it here.

pub mod abuffer;
pub mod interpolate;
pub mod lighting;
pub mod renderer;
pub mod sample;
pub mod scanline;
pub mod texture;
pub mod warnock;
pub mod zbuffer;

pub use zbuffer::{EMPTY, ZBuffer, ZBufferStats};
