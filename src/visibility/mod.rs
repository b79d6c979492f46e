//! Visibility strategies: object-space methods that turn screen polygons into exact visible sets.

pub mod bsp;
