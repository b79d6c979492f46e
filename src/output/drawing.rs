//! The drawable form of a visibility result: filled regions in image coordinates, back to front.
//!
//! Coordinates are pixels with y growing downward (NDC [-1,1]² maps to [0,W] x [0,H]), rounded
//! once from the exact result: the output-rounding approximation of the exactness contract.
//! Items are in painter order: an item is drawn over every item before it. Rings of one item are
//! filled with the even-odd rule (outer boundaries and holes alike).

use crate::scene::FaceId;

/// One filled region of one face.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawItem {
    /// Provenance: the input face id.
    pub face: FaceId,
    /// Other input faces the region also covers, ascending: coplanar faces of the same paint
    /// drawn as one surface (empty unless asked for).
    pub merged: Vec<FaceId>,
    /// Index into `Scene::materials`.
    pub material: u32,
    /// Closed rings (the last point is not repeated), pixels, y down; even-odd fill.
    pub rings: Vec<Vec<[f64; 2]>>,
    /// Fill colour, linear RGB in [0,1].
    pub color: [f64; 3],
    /// 1 - transparency.
    pub opacity: f64,
}

/// A whole picture.
#[derive(Clone, Debug, PartialEq)]
pub struct Drawing {
    pub width: u32,
    pub height: u32,
    /// Background colour, or `None` for transparent.
    pub background: Option<[f64; 3]>,
    /// Back to front.
    pub items: Vec<DrawItem>,
}
