//! The drawable form of a visibility result: filled regions in image coordinates, back to front.
//!
//! Coordinates are pixels with y growing downward (NDC \[-1,1\]² maps to \[0,W\] x \[0,H\]), rounded
//! once from the exact result: the output-rounding approximation of the exactness contract.
//! Items are in painter order: an item is drawn over every item before it. Rings of one item are
//! filled with the even-odd rule (outer boundaries and holes alike). Seams are painted under every
//! item: they only show where anti-aliased fills leave a boundary pixel partly uncovered.

use crate::scene::FaceId;

/// A closed ring of points in pixels (y down), the last point not repeated.
pub type Ring = Vec<[f64; 2]>;

/// The rings of an item: the first inline (most regions are one outer ring: a list of one on
/// the heap cost 32 bytes more a region, 8 MB on a million triangles), more on the heap.
pub type Rings = smallvec::SmallVec<[Ring; 1]>;

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
    pub rings: Rings,
    /// Fill colour, linear RGB in \[0,1\].
    pub color: [f64; 3],
    /// 1 - transparency.
    pub opacity: f64,
}

impl DrawItem {
    /// A region of one face in material 0, merging no other face.
    pub fn new(face: FaceId, rings: Vec<Ring>, color: [f64; 3], opacity: f64) -> Self {
        DrawItem {
            face,
            merged: Vec::new(),
            material: 0,
            rings: Rings::from_vec(rings),
            color,
            opacity,
        }
    }
}

/// A whole picture.
#[derive(Clone, Debug, PartialEq)]
pub struct Drawing {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Background colour, or `None` for transparent.
    pub background: Option<[f64; 3]>,
    /// Back to front.
    pub items: Vec<DrawItem>,
    /// Boundaries that opaque items share, painted under all items (empty unless asked for).
    pub seams: Seams,
    /// True when the opaque items (opacity 1) before the first translucent one have pairwise
    /// disjoint interiors, so that their order does not change the picture and
    /// [`canonicalize`](super::canonical::canonicalize) may sort them. False, the safe value,
    /// promises nothing and keeps every item in place (a painter's drawing overlaps).
    pub opaque_disjoint: bool,
}

/// What fills the seams of a drawing: the boundary segments shared by two opaque items, stroked
/// in the colour of one of them under every fill, and clipped to the outline of the opaque
/// items. Where two fills' anti-aliased edges each cover part of a pixel, the strokes fill
/// what they leave, so no background shows through ("conflation"); the fills themselves keep
/// the exact boundaries. The clip keeps the strokes inside the opaque items: off the silhouette
/// and off translucent items over the background (a stroke along a sliver face at the
/// silhouette would otherwise widen it).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Seams {
    /// Rings of the union of the opaque items (even-odd), pixels, y down: the strokes' clip.
    pub outline: Vec<Vec<[f64; 2]>>,
    /// The shared segments, by colour.
    pub strokes: Vec<SeamStroke>,
}

impl Seams {
    /// No seam to stroke.
    pub fn is_empty(&self) -> bool {
        self.strokes.is_empty()
    }
}

/// Shared boundary segments stroked in one colour.
#[derive(Clone, Debug, PartialEq)]
pub struct SeamStroke {
    /// Stroke colour, linear RGB in \[0,1\]: the colour of one of the two items.
    pub color: [f64; 3],
    /// Segments, pixels, y down.
    pub segments: Vec<[[f64; 2]; 2]>,
}
