//! What the integration tests share, one submodule per job: cameras, generated scenes, the RNG,
//! the fixtures (and the generated ones), references to check renderers against, renders
//! predicted pixel by pixel, the visibility strategies as the tests call them, running the binary, and the SVG seam measures.
//!
//! Every test file includes it with `mod support;` (a test target in a directory of its own
//! with `#[path]`); each uses a part of it, hence `dead_code` is allowed here.
#![allow(dead_code)]

pub mod camera;
pub mod cli;
pub mod fixtures;
pub mod generated;
pub mod oracle;
pub mod render;
pub mod rng;
pub mod scenes;
pub mod seam_measure;
pub mod strategy;
