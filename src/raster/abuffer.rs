//! The A-buffer (seeds 000 and 002): per pixel a list of fragments (polygon, depth, colour,
//! transparency), an opaque fragment removing the fragments behind it, and a final blend from
//! back to front over the background with the seed's rule `new = old·t + colour·(1 - t)`.
//!
//! Invariants of the [`ABuffer`] it produces:
//! - **Coverage and depth order are the z-buffer's**: fragments are the samples each polygon
//!   covers by the z-buffer's fill rule, and fragments at a pixel are ordered by the z-buffer's
//!   exact depth order with its tie rule ([`DepthOrder`]). So [`ABuffer::poly`], the nearest
//!   fragment at each pixel (translucent or not), is exactly [`ZBuffer::poly`](super::ZBuffer);
//!   in an opaque scene the colours are the z-buffer's colours too.
//! - **Order independence**: the depth order is a strict total order at each pixel, so the list
//!   a pixel ends with, the blend and its f64 roundings are the same whatever order the polygons
//!   come in.
//!
//! # Memory
//!
//! A pixel does not keep a full list: it keeps its nearest opaque fragment (polygon index and f64
//! depth: 12 bytes, as a z-buffer) and a list, sorted from back to front, of the translucent
//! fragments in front of it (4-byte head index). A translucent fragment arriving behind the
//! opaque one is never stored; an opaque fragment arriving in front of it replaces it and unlinks
//! the translucent fragments it hides. The lists live in one arena of 16-byte nodes
//! (polygon, next, f64 depth) with a free list, so unlinked nodes are reused. With `A` the
//! arena's length ([`ABufferStats::arena_peak`]), the largest number of translucent fragments
//! stored at once:
//! - rasterizing takes `16·W·H + 16·A` bytes;
//! - resolving trades the depths for the f64 colours of the result, so the peak is
//!   `32·W·H + 16·A` bytes, and the result keeps `28·W·H` (its polygon image reuses the opaque
//!   layer's storage).
//!
//! `A` does not grow with the number of polygons, only with the translucent fragments kept. With
//! [`Options::opaque_first`] (the default: the seed's "draw the transparent triangle last") every
//! pixel's opaque fragment is final before any translucent one arrives, so nothing stored is ever
//! removed and `A` is exactly the number of translucent fragments blended in the end (the blend
//! needs each of them). In input order `A` is at most the number of translucent samples covered.
//! So an opaque scene of 1M triangles at 4096 x 4096 rasterizes in 256 MiB with no arena at all
//! (512 MiB at the peak of resolving). The arena is indexed by `u32`: storing more than
//! 2^32 - 1 fragments at once is refused with a panic rather than wrapped.

use super::EMPTY;
use super::sample::{self, DepthOrder};
use crate::exact::Fallbacks;
use crate::paint::Paint;
use crate::project::ScreenScene;

/// In which order polygons are rasterized. The image does not depend on it; memory does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// Opaque polygons first, then translucent ones (each group in input order); otherwise
    /// input order.
    pub opaque_first: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options { opaque_first: true }
    }
}

/// The result of the A-buffer.
#[derive(Clone, Debug)]
pub struct ABuffer {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Row-major, row 0 at the top: the nearest fragment's polygon (index into
    /// `ScreenScene::polys`), or [`EMPTY`]. The z-buffer's, see the module docs.
    pub poly: Vec<u32>,
    /// Row-major blended colour (linear RGB).
    pub color: Vec<[f64; 3]>,
    /// Counters of the run.
    pub stats: ABufferStats,
}

/// Work counters.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ABufferStats {
    /// Samples covered by some polygon (fragments produced).
    pub fragments: u64,
    /// Of those, fragments of translucent polygons.
    pub translucent_fragments: u64,
    /// Fragments that arrived behind the pixel's nearest opaque fragment: never stored.
    pub hidden_on_arrival: u64,
    /// Opaque fragments replaced, and translucent fragments unlinked, by a nearer opaque one.
    pub removed: u64,
    /// Largest number of translucent fragments stored at once (the arena's length).
    pub arena_peak: u64,
    /// Translucent fragments blended in the end.
    pub blended: u64,
    /// Longest list of translucent fragments at one pixel in the end.
    pub max_list: u64,
    /// Edge-crossing computations the f64 filter could not decide.
    pub column_fallbacks: u64,
    /// Depth comparisons the f64 filter could not decide.
    pub depth_fallbacks: u64,
    /// Exact depth ties resolved by the id rule.
    pub depth_ties: u64,
}

impl ABuffer {
    /// The input face id of the nearest fragment at every pixel (`None` for background).
    pub fn face_ids(&self, screen: &ScreenScene) -> Vec<Option<u32>> {
        sample::face_ids(&self.poly, screen)
    }
}

/// End of a list.
const NIL: u32 = u32::MAX;

/// A stored translucent fragment.
#[derive(Clone, Copy, Debug)]
struct Node {
    poly: u32,
    next: u32,
    z: f64,
}

/// The per-pixel state while rasterizing.
struct Pixels<'a> {
    order: DepthOrder<'a>,
    /// Nearest opaque fragment per pixel, and its f64 depth.
    opaque: Vec<u32>,
    opaque_z: Vec<f64>,
    /// Translucent fragments in front of it, farthest first.
    head: Vec<u32>,
    arena: Vec<Node>,
    free: u32,
    stats: ABufferStats,
}

impl Pixels<'_> {
    fn alloc(&mut self, node: Node) -> u32 {
        if self.free != NIL {
            let k = self.free;
            self.free = self.arena[k as usize].next;
            self.arena[k as usize] = node;
            k
        } else {
            assert!(
                self.arena.len() < NIL as usize,
                "A-buffer: more than 2^32 - 1 translucent fragments stored"
            );
            self.arena.push(node);
            self.stats.arena_peak = self.arena.len() as u64;
            (self.arena.len() - 1) as u32
        }
    }

    fn release(&mut self, k: u32) {
        self.arena[k as usize].next = self.free;
        self.free = k;
    }

    /// An opaque fragment of `poly` at pixel `idx` = sample (i, j).
    fn opaque(&mut self, idx: usize, poly: u32, i: i64, j: i64) {
        let z = self.order.depth(poly, i, j);
        let cur = self.opaque[idx];
        if cur != EMPTY {
            if self.order.wins(cur, self.opaque_z[idx], poly, z, i, j) {
                self.stats.hidden_on_arrival += 1;
                return;
            }
            self.stats.removed += 1;
        }
        self.opaque[idx] = poly;
        self.opaque_z[idx] = z;
        // The list runs from back to front: what the new opaque fragment hides is a prefix.
        loop {
            let k = self.head[idx];
            if k == NIL {
                break;
            }
            let n = self.arena[k as usize];
            if !self.order.wins(poly, z, n.poly, n.z, i, j) {
                break;
            }
            self.head[idx] = n.next;
            self.release(k);
            self.stats.removed += 1;
        }
    }

    /// A translucent fragment of `poly` at pixel `idx` = sample (i, j).
    fn translucent(&mut self, idx: usize, poly: u32, i: i64, j: i64) {
        let z = self.order.depth(poly, i, j);
        let cur = self.opaque[idx];
        if cur != EMPTY && self.order.wins(cur, self.opaque_z[idx], poly, z, i, j) {
            self.stats.hidden_on_arrival += 1;
            return;
        }
        // After every fragment it beats (they are farther), before the first that beats it.
        let mut prev = NIL;
        let mut k = self.head[idx];
        while k != NIL {
            let n = self.arena[k as usize];
            if !self.order.wins(poly, z, n.poly, n.z, i, j) {
                break;
            }
            prev = k;
            k = n.next;
        }
        let new = self.alloc(Node { poly, next: k, z });
        if prev == NIL {
            self.head[idx] = new;
        } else {
            self.arena[prev as usize].next = new;
        }
    }
}

/// Renders `screen` into an A-buffer. `paints[k]` is the paint of `screen.polys[k]` (see
/// [`crate::paint::screen_paints`]); `background` is the colour blending starts from.
pub fn render(
    screen: &ScreenScene,
    paints: &[Paint],
    background: [f64; 3],
    options: Options,
) -> ABuffer {
    assert_eq!(paints.len(), screen.polys.len(), "one paint per polygon");
    let (w, h) = (screen.width as usize, screen.height as usize);
    let order = DepthOrder::new(screen);
    let s = order.samples;
    let mut px = Pixels {
        order,
        opaque: vec![EMPTY; w * h],
        opaque_z: vec![0.0; w * h],
        head: vec![NIL; w * h],
        arena: Vec::new(),
        free: NIL,
        stats: ABufferStats::default(),
    };
    let fallbacks = Fallbacks::default();
    let mut crossings: Vec<i64> = Vec::with_capacity(8);

    let sequence: Vec<u32> = if options.opaque_first {
        let (mut first, mut last): (Vec<u32>, Vec<u32>) =
            (0..screen.polys.len() as u32).partition(|&p| paints[p as usize].is_opaque());
        first.append(&mut last);
        first
    } else {
        (0..screen.polys.len() as u32).collect()
    };
    for &pi in &sequence {
        let poly = &screen.polys[pi as usize];
        let pts = &screen.corners(poly);
        let opaque = paints[pi as usize].is_opaque();
        let (j0, j1) = sample::candidate_rows(&s, pts);
        for j in j0..j1 {
            sample::row_crossings(&s, pts, j, &fallbacks, &mut crossings);
            for pair in crossings.chunks_exact(2) {
                let (i0, i1) = (pair[0].max(0), pair[1].min(w as i64));
                for i in i0..i1 {
                    px.stats.fragments += 1;
                    let idx = j as usize * w + i as usize;
                    if opaque {
                        px.opaque(idx, pi, i, j);
                    } else {
                        px.stats.translucent_fragments += 1;
                        px.translucent(idx, pi, i, j);
                    }
                }
            }
        }
    }

    // Resolve: blend each list from back to front over the opaque fragment or the background.
    // The opaque layer becomes the nearest-fragment image in place; depths are no longer needed.
    px.opaque_z = Vec::new();
    let mut poly_out = std::mem::take(&mut px.opaque);
    let mut color = vec![background; w * h];
    for idx in 0..w * h {
        let mut c = background;
        let mut nearest = poly_out[idx];
        if nearest != EMPTY {
            c = blend(c, &paints[nearest as usize]);
        }
        let mut len = 0u64;
        let mut k = px.head[idx];
        while k != NIL {
            let n = px.arena[k as usize];
            c = blend(c, &paints[n.poly as usize]);
            nearest = n.poly;
            len += 1;
            k = n.next;
        }
        px.stats.blended += len;
        px.stats.max_list = px.stats.max_list.max(len);
        poly_out[idx] = nearest;
        color[idx] = c;
    }
    let mut stats = px.stats;
    stats.column_fallbacks = fallbacks.column.get();
    stats.depth_fallbacks = px.order.fallbacks.get();
    stats.depth_ties = px.order.ties.get();
    ABuffer {
        width: screen.width,
        height: screen.height,
        poly: poly_out,
        color,
        stats,
    }
}

/// The seed's rule `new = old·t + colour·(1 - t)` for transparency `t`, with opacity
/// `a = 1 - t`: `new = old·(1 - a) + colour·a`.
#[inline]
fn blend(old: [f64; 3], paint: &Paint) -> [f64; 3] {
    let a = paint.opacity;
    std::array::from_fn(|k| old[k] * (1.0 - a) + paint.color[k] * a)
}
