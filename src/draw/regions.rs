//! From visible pieces to drawable regions: the pieces of a group (one face, or one surface of
//! coplanar faces with the same paint) are merged into regions with holes.
//!
//! Invariant: the regions of a group depend only on the point set its pieces cover, never on
//! how that set was cut into convex pieces, so two strategies that find the same visible set
//! draw the same regions. Every decision is exact; the only approximation is the output
//! rounding, one per exact vertex and a function of the exact point alone:
//! - **Vertices** ([`shared_vertices`]): every exact vertex gets an id (equal ids, same point,
//!   decided exactly with [`Piece::same_vertex`]) and its pixel coordinates, the exact grid
//!   coordinates correctly rounded to f64, then mapped to pixels. Whichever lines of whichever
//!   piece name a point, it gets the same bits.
//! - **Merge**: the pieces' edges, with every vertex of another piece of the group
//!   lying inside an edge inserted into it (a T-junction, decided exactly), are directed edges
//!   between vertex ids. An edge shared by two pieces runs both ways and cancels; the rest is
//!   the boundary of the union, each edge with the interior on its left. A boundary vertex
//!   where the boundary runs straight on (the next vertex lies on the incoming edge's kernel
//!   line, exactly) is dropped unless another boundary edge of the group meets it there: what
//!   is left are the true corners and the points where the group's boundary touches itself
//!   (within a region or between two regions of the group), which belong to the point set, not
//!   to the cut.
//! - **Cycles**: at a vertex with several outgoing boundary edges (the boundary touches itself
//!   there), the walk takes the one that turns most to the left, decided exactly. This walks
//!   the boundary of one connected interior at a time: two squares touching at a corner are
//!   two cycles, a hole touching the outer boundary at a point is part of the outer cycle
//!   (face tracing of a plane graph); either way the cycles are a function of the point set.
//! - **Regions**: pieces sharing an edge are one connected interior, one region, whose cycles
//!   are its outer ring and its holes (combinatorially: no containment test). Its outer ring
//!   is the cycle holding its smallest vertex (y, then x, in pixels): the top of a region lies
//!   on its outer boundary. A region lists the faces of its pieces and is painted by the piece
//!   of its smallest (face id, polygon).
//! - **Shortcuts** with the same result: a group of one piece is its ring; a group of two
//!   pieces sharing exactly one edge whole (a quad's two triangles, a face cut once) is one
//!   piece's ring joined to the other's, the edge's ends dropped where the boundary goes
//!   straight through them (the same exact test).

use crate::buckets::sorted_by_low;
use crate::exact::Samples;
use crate::exact::polygon::Piece;
use crate::exact::predicates::{Line, LineApprox, crossing_rounded};
use crate::output::drawing::Rings;
use crate::progress::{Report, Ticker};
use crate::project::ScreenScene;
use crate::scene::{FaceId, Scene, newell_normal};
use crate::visibility::grid::for_each_near_edges;
use glam::DVec3;
use rayon::prelude::*;
use rustc_hash::{FxBuildHasher, FxHashMap};
use smallvec::SmallVec;
use std::cmp::Ordering;
use std::collections::BTreeMap;
use std::hash::BuildHasher;

/// One drawable region of a group.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    /// Input face ids of the pieces in it, ascending, at least one (most regions have one: no
    /// allocation for it).
    pub faces: SmallVec<[FaceId; 2]>,
    /// Index of the piece of its smallest face id (then smallest polygon), whose face paints
    /// it.
    pub piece: usize,
    /// Rings, pixel coordinates, y down; even-odd. The first is the ring holding the smallest
    /// (y, x) rounded vertex, the outer ring unless a hole's top vertex rounds onto the outer
    /// ring's top row further left; [`crate::output::canonical`] decides holes by containment.
    pub rings: Rings,
}

/// The regions of `pieces` (disjoint), grouped by `key`: groups in key order, and within a
/// group regions in the order of their outer rings' smallest vertex (y, then x).
pub fn regions<K: Ord + Sync>(
    pieces: &[Piece],
    screen: &ScreenScene,
    key: impl Fn(&Piece) -> K,
) -> Vec<Region> {
    let vertices = shared_vertices(pieces, &Samples::new(screen.width, screen.height));
    regions_of(pieces, &vertices, screen, key, None)
}

/// [`regions`] of pieces whose [`shared_vertices`] are known, reporting stage "regions":
/// pieces merged of all.
pub fn regions_of<K: Ord + Sync>(
    pieces: &[Piece],
    vertices: &Vertices,
    screen: &ScreenScene,
    key: impl Fn(&Piece) -> K,
    report: Option<Report>,
) -> Vec<Region> {
    regions_into(pieces, vertices, screen, key, report, |r| r)
}

/// [`regions_of`], each region made into what the caller keeps (`make`) as it is found: a list
/// of regions beside the caller's list of what it makes of them was a drawing's peak (a
/// million regions on a million triangles).
pub fn regions_into<K: Ord + Sync, T: Send>(
    pieces: &[Piece],
    vertices: &Vertices,
    screen: &ScreenScene,
    key: impl Fn(&Piece) -> K,
    report: Option<Report>,
    make: impl Fn(Region) -> T + Sync,
) -> Vec<T> {
    use rayon::prelude::*;
    let mut ticker = Ticker::new(report, "regions", pieces.len() as u64);
    let mut merged_pieces = 0;
    // The pieces in group order (key, then index): each group a run of them.
    let keys: Vec<K> = pieces.iter().map(key).collect();
    let mut order: Vec<usize> = (0..pieces.len()).collect();
    order.sort_by(|&a, &b| keys[a].cmp(&keys[b]).then(a.cmp(&b)));
    let face_of = |i: usize| screen.polys[pieces[i].poly as usize].id;
    let same_group = |a: usize, b: usize| keys[a] == keys[b];
    let merge_into = |members: &[usize], out: &mut Vec<T>| {
        for m in merge(pieces, vertices, members) {
            let mut faces: SmallVec<[FaceId; 2]> = m.members.iter().map(|&i| face_of(i)).collect();
            faces.sort_unstable();
            faces.dedup();
            let piece = *m
                .members
                .iter()
                .min_by_key(|&&i| (face_of(i), pieces[i].poly, i))
                .expect("a region has pieces");
            out.push(make(Region {
                faces,
                piece,
                rings: m.rings,
            }));
        }
    };
    // Groups are merged independently, on all cores: runs of groups of about `RUN` pieces, a
    // wave of runs at a time, each wave's regions appended in group order (the same list as
    // one thread makes). A wave's lists are all that exists twice.
    const RUN: usize = 4096;
    let mut runs: Vec<&[usize]> = Vec::new();
    let mut rest: &[usize] = &order;
    while !rest.is_empty() {
        // The run ends where a group ends, at or past RUN pieces.
        let mut end = RUN.min(rest.len());
        while end < rest.len() && same_group(rest[end], rest[end - 1]) {
            end += 1;
        }
        let (run, after) = rest.split_at(end);
        runs.push(run);
        rest = after;
    }
    // At most a region per piece: room that is never touched is never resident, and the list
    // never grows by copying itself.
    let mut out = Vec::with_capacity(pieces.len());
    for wave in runs.chunks(4 * rayon::current_num_threads()) {
        ticker.tick(merged_pieces);
        merged_pieces += wave.iter().map(|r| r.len() as u64).sum::<u64>();
        let made: Vec<Vec<T>> = wave
            .par_iter()
            .map(|run| {
                let mut made = Vec::new();
                for members in run.chunk_by(|&a, &b| same_group(a, b)) {
                    merge_into(members, &mut made);
                }
                made
            })
            .collect();
        out.extend(made.into_iter().flatten());
    }
    ticker.finish();
    out.shrink_to_fit();
    out
}

/// A surface label per screen polygon: polygons with equal `paint(index)` whose faces' world planes
/// fall in the same bucket share a label (numbered in polygon order). The bucket is the plane's
/// unit normal, turned towards the eye, and its offset, each rounded to 2^-20 (the offset of
/// the scene's size): coplanar faces share it, and near-coplanar ones almost always do, except
/// the rare pair that a rounding boundary separates, which then stays two paths.
/// This is a drawing choice outside the exactness contract: it never changes which face shows
/// where, only which abutting regions of the same paint share a path. It is not exact
/// coplanarity on purpose: CAD files written as decimals put the triangles of one flat face a
/// rounding error off each other's plane, and their seams would show.
pub fn surfaces<P: Eq + std::hash::Hash + Send>(
    scene: &Scene,
    screen: &ScreenScene,
    eye: DVec3,
    paint: impl Fn(usize) -> P + Sync,
) -> Vec<u32> {
    let size = scene
        .bounds()
        .map(|(lo, hi)| (hi - lo).length())
        .filter(|s| *s > 0.0)
        .unwrap_or(1.0);
    let q = |v: f64| (v * (1u64 << 20) as f64).round() as i64;
    let key = |index: usize| {
        let face = &scene.faces[screen.polys[index].face as usize];
        let corners = scene.face_corners(face);
        let p0 = scene.positions[corners[0] as usize];
        let mut n = newell_normal(corners.iter().map(|&i| scene.positions[i as usize])).normalize();
        // Opposite windings of one plane give opposite normals: turn both towards the eye.
        if n.dot(eye - p0) < 0.0 {
            n = -n;
        }
        let d = n.dot(p0) / size;
        (paint(index), [q(n.x), q(n.y), q(n.z), q(d)])
    };
    labels_by_key(screen.polys.len(), key, |k| FxBuildHasher.hash_one(k))
}

/// Labels for items `0..n` by `key(index)`: equal keys, equal labels, numbered in order of first
/// appearance. The keys are computed on all cores, a block of items at a time; an item with the
/// key of the item before it (a quad's second triangle, a flat face's fan) takes its label. Each
/// other item is kept only as the top 32 bits of its key's `hash` beside its index: 8 bytes an
/// item (a table of the keys took 64 in [`surfaces`]: a curved surface of a million faces is a
/// million labels). Sorted, the items of one hash are neighbours, and only they are compared by
/// their full keys, computed again (most hashes name one item). One pass in item order then
/// numbers the keys. (Inserting the items one by one into a table of first items was a serial
/// stretch of the drawing: a cache miss an item.)
fn labels_by_key<K: Eq + Send>(
    n: usize,
    key: impl Fn(usize) -> K + Sync,
    hash: impl Fn(&K) -> u64 + Sync,
) -> Vec<u32> {
    assert!(n < u32::MAX as usize, "items are numbered in 32 bits");
    let starts: Vec<usize> = (0..n).step_by(LABEL_BLOCK).collect();
    let blocks: Vec<Vec<u64>> = (starts.into_par_iter())
        .map(|start| {
            let mut keyed = Vec::new();
            let mut last = None;
            for item in start..n.min(start + LABEL_BLOCK) {
                let k = key(item);
                if last.as_ref() != Some(&k) {
                    keyed.push(mixed(hash(&k)) >> 32 << 32 | item as u64);
                }
                last = Some(k);
            }
            keyed
        })
        .collect();
    let mut keyed: Vec<u64> = Vec::with_capacity(blocks.iter().map(Vec::len).sum());
    for block in blocks {
        keyed.extend(block);
    }
    keyed.par_sort_unstable();
    // Each run of one hash becomes (item, first item of its key) pairs, in place, in blocks
    // of whole runs on all cores (rayon's `par_chunk_by_mut` made a task of every run: 20
    // times slower on a million).
    let same_hash = |a: &u64, b: &u64| a >> 32 == b >> 32;
    let mut blocks: Vec<&mut [u64]> = Vec::new();
    let mut rest: &mut [u64] = &mut keyed;
    while !rest.is_empty() {
        let mut end = LABEL_BLOCK.min(rest.len());
        while end < rest.len() && same_hash(&rest[end - 1], &rest[end]) {
            end += 1;
        }
        let (block, after) = std::mem::take(&mut rest).split_at_mut(end);
        blocks.push(block);
        rest = after;
    }
    blocks.into_par_iter().for_each(|block| {
        for run in block.chunk_by_mut(same_hash) {
            if let [only] = run {
                let item = *only & u64::from(u32::MAX);
                *only = item << 32 | item;
                continue;
            }
            // Items ascend within a run: the first item of each distinct key names it.
            let mut distinct: Vec<(K, u64)> = Vec::new();
            for e in run {
                let item = *e & u64::from(u32::MAX);
                let k = key(item as usize);
                let named = match distinct.iter().find(|(d, _)| *d == k) {
                    Some(&(_, f)) => f,
                    None => {
                        distinct.push((k, item));
                        item
                    }
                };
                *e = item << 32 | named;
            }
        }
    });
    // Per item, the first item with its key (itself when it is the first), or `u32::MAX`:
    // the key of the item before it.
    let mut first = vec![u32::MAX; n];
    for &e in &keyed {
        first[(e >> 32) as usize] = e as u32;
    }
    drop(keyed);
    let mut labels: Vec<u32> = Vec::with_capacity(n);
    let mut next = 0u32;
    for (item, &f) in first.iter().enumerate() {
        let label = match f as usize {
            f if f == item => {
                next += 1;
                next - 1
            }
            f if f == u32::MAX as usize => labels[item - 1],
            f => labels[f],
        };
        labels.push(label);
    }
    labels
}

/// The bits of `h` mixed into its top 32 (splitmix64's finalizer, a bijection): FxHash's own
/// top bits come from the low bits of a product, and collided on a curved surface's keys.
fn mixed(mut h: u64) -> u64 {
    h = (h ^ (h >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    h = (h ^ (h >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    h ^ (h >> 31)
}

/// Sorted items that [`labels_by_key`] groups in one task (whole runs of one hash).
const LABEL_BLOCK: usize = 1 << 14;

/// The outline of disjoint pieces (with their [`shared_vertices`]): the rings of their union,
/// outer rings and holes, even-odd; merged as one group, so it too depends only on the point
/// set the pieces cover.
pub fn outline(pieces: &[Piece], vertices: &Vertices) -> Vec<Vec<[f64; 2]>> {
    debug_assert_eq!(pieces.len(), vertices.pixels.len());
    let all: Vec<usize> = (0..pieces.len()).collect();
    merge(pieces, vertices, &all)
        .into_iter()
        .flat_map(|m| m.rings)
        .collect()
}

/// The vertices of a list of pieces, each exact point named once.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Vertices {
    /// Per piece, per vertex: pixel coordinates (column, row; y down), the same bits wherever
    /// pieces share the exact point.
    pub pixels: PerVertex<[f64; 2]>,
    /// Per piece, per vertex: the id of its exact point; two vertices have the same id if and
    /// only if they are the same point (decided exactly).
    pub ids: PerVertex<u32>,
    /// Per piece, per vertex k: the piece that shares edge k (from vertex k to vertex k + 1)
    /// whole, its own edge running the other way between the same two points, or
    /// [`Vertices::ALONE`]; flat, in the order of `ids` (edge k of piece a is number
    /// `ids.first(a) + k`). Found once for the regions, the outline and the seams alike.
    pub partners: Vec<u32>,
    /// A bound on how far each pixel coordinate lies from its exact point's: f64 tests on
    /// the pixels that clear it by their own error decide exactly ([`surely_off_line`]).
    /// Zero in the empty default (no pixels); infinite where no bound is known.
    pub pixel_error: f64,
}

impl Vertices {
    /// No piece shares the edge whole.
    pub const ALONE: u32 = u32::MAX;

    /// The partners of piece a's edges, in edge order (see [`Vertices::partners`]).
    pub fn partners_of(&self, a: usize) -> &[u32] {
        let first = self.ids.first(a);
        &self.partners[first..first + self.ids[a].len()]
    }
}

/// One value per vertex of a list of pieces, in one flat list (no allocation per piece: a
/// drawing of a million pieces would make a million small lists): `self[a]` is piece a's, in
/// vertex order.
#[derive(Clone, Debug, PartialEq)]
pub struct PerVertex<T> {
    values: Vec<T>,
    /// Piece a's values are `values[start[a]..start[a + 1]]`; `start[0] == 0`.
    start: Vec<usize>,
}

impl<T> Default for PerVertex<T> {
    fn default() -> Self {
        PerVertex {
            values: Vec::new(),
            start: vec![0],
        }
    }
}

impl<T> PerVertex<T> {
    /// An empty list with room for `pieces` pieces of `vertices` vertices in all.
    pub fn with_capacity(pieces: usize, vertices: usize) -> Self {
        let mut start = Vec::with_capacity(pieces + 1);
        start.push(0);
        PerVertex {
            values: Vec::with_capacity(vertices),
            start,
        }
    }

    /// Appends piece `a = self.len()`'s values.
    pub fn push_piece(&mut self, values: impl IntoIterator<Item = T>) {
        self.values.extend(values);
        self.end_piece();
    }

    /// Appends a value of the piece being added, which [`Self::end_piece`] closes.
    pub fn push_value(&mut self, value: T) {
        self.values.push(value);
    }

    /// Closes the piece being added: its values are those pushed since the last piece.
    pub fn end_piece(&mut self) {
        self.start.push(self.values.len());
    }

    /// The number of pieces.
    pub fn len(&self) -> usize {
        self.start.len() - 1
    }

    /// No pieces?
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The number of vertices of all pieces.
    pub fn vertex_count(&self) -> usize {
        self.values.len()
    }

    /// Where piece a's values start in the flat list: vertex k of piece a is number
    /// `first(a) + k` of all, for the callers' own flat per-vertex lists.
    pub fn first(&self, a: usize) -> usize {
        self.start[a]
    }

    /// Per number of the flat list, the piece whose value it is (a table, for many look-ups).
    pub fn owners(&self) -> Vec<u32> {
        (0..self.len() as u32)
            .flat_map(|a| std::iter::repeat_n(a, self[a as usize].len()))
            .collect()
    }

    /// Every piece's values, in piece order.
    pub fn iter(&self) -> impl Iterator<Item = &[T]> {
        self.start.windows(2).map(|w| &self.values[w[0]..w[1]])
    }
}

impl<T> std::ops::Index<usize> for PerVertex<T> {
    type Output = [T];

    fn index(&self, a: usize) -> &[T] {
        &self.values[self.start[a]..self.start[a + 1]]
    }
}

/// Every piece's vertices named and rounded once (see [`Vertices`]): each exact point, the
/// first time a piece has it, gets a new id and its pixel coordinates ([`vertex_pixel`]); a
/// later piece with the same point (decided exactly) takes both.
///
/// Most vertices are grid points (input corners, and crossings that land on one): they are
/// named by their integer coordinates in a hash map, without looking at any other vertex. A
/// vertex that is not known to be a corner is compared exactly with the earlier points off the
/// grid (each entered once, by the vertex that named it) whose f64 points lie within both error
/// bounds of its own (found in a hash of square cells), and, if it turns out to be a grid
/// point, with the map, where it is entered when it is new: so a crossing and a corner at the
/// same point share an id whichever comes first.
pub fn shared_vertices(pieces: &[Piece], s: &Samples) -> Vertices {
    // Each exact point is entered once, where it is first named, as that (piece, vertex): a
    // grid point in `at_grid_point`, any other point in `near`. A later vertex of the point
    // takes its pixel and id from `out`. (Entering every vertex, with its pixel and id, made
    // these tables a third of the drawing's memory on a million triangles.)
    let mut at_grid_point: FxHashMap<[i64; 2], (u32, u32)> = FxHashMap::default();
    let mut near = NearVertices::default();
    let vertex_count = pieces.iter().map(Piece::len).sum();
    let mut out = Vertices {
        pixels: PerVertex::with_capacity(pieces.len(), vertex_count),
        ids: PerVertex::with_capacity(pieces.len(), vertex_count),
        partners: Vec::new(),
        pixel_error: 0.0,
    };
    let mut next = 0u32;
    let mut largest = 0.0f64;
    // The piece's vertices named first here that are no grid points (reused). Each vertex's
    // pixel and id go straight to `out`: the tables read only the pieces before this one.
    let mut new_off_grid = Vec::new();
    for (a, pa) in pieces.iter().enumerate() {
        new_off_grid.clear();
        for k in 0..pa.len() {
            let named = |(b, v): (u32, u32)| {
                (
                    out.pixels[b as usize][v as usize],
                    out.ids[b as usize][v as usize],
                )
            };
            let (known, grid_point) = match pa.corner(k) {
                Some(g) => (at_grid_point.get(&g).copied().map(named), Some(g)),
                None => {
                    let same = near.find(pa.point(k), |b, v| {
                        pa.same_vertex(k, &pieces[b], v)
                            .then(|| (out.pixels[b][v], out.ids[b][v]))
                    });
                    match same {
                        Some(named) => (Some(named), None),
                        None => {
                            let g = grid_point_of(pa, k);
                            (g.and_then(|g| at_grid_point.get(&g).copied().map(named)), g)
                        }
                    }
                }
            };
            let (p, id) = known.unwrap_or_else(|| {
                next += 1;
                match grid_point {
                    Some(g) => {
                        at_grid_point.insert(g, (a as u32, k as u32));
                    }
                    None => new_off_grid.push(k),
                }
                let p = vertex_pixel(pa, k, s);
                // A point whose f64 error exceeds the refinement bound (none: only parallel
                // lines would leave one) is outside what the bound covers: no bound then.
                let e = pa.point(k)[2];
                let loose = e.is_nan() || e > Piece::POINT_ERROR_MAX;
                largest = largest.max(p[0].abs()).max(p[1].abs());
                if loose {
                    largest = f64::INFINITY;
                }
                (p, next - 1)
            });
            out.pixels.push_value(p);
            out.ids.push_value(id);
        }
        // Entered after the piece: a piece's own vertices are distinct points.
        for &k in &new_off_grid {
            near.insert(pa.point(k), a, k);
        }
        out.pixels.end_piece();
        out.ids.end_piece();
    }
    out.partners = edge_partners(&out.ids, next as usize);
    out.pixel_error = pixel_error(s, largest);
    out
}

/// A bound on the error of [`vertex_pixel`]'s coordinates, each at most `largest` in size
/// (infinite: no bound). The grid point is correctly rounded, half an ulp; where no rounding
/// is made (two parallel lines: never adjacent lines of a piece) the f64 point is used,
/// within its own bound, which [`shared_vertices`] checks is at most [`Piece::POINT_ERROR_MAX`]
/// (2^16 units; a grid unit is W 2^-53 pixels, so W 2^-37 pixels). The three roundings of
/// the map to pixels and the half ulp add at most 2^-51 (|p| + W). Each term is taken twice
/// over.
fn pixel_error(s: &Samples, largest: f64) -> f64 {
    debug_assert_eq!(Piece::POINT_ERROR_MAX, 65536.0);
    let size = (s.width + s.height) as f64;
    size * 2f64.powi(-36) + (largest + size) * 2f64.powi(-50)
}

/// Whether `c` surely lies off the line through `a` and `b`, decided in f64 on pixels that
/// each lie within `error` (per coordinate) of their exact points: the orientation clears the
/// bound of both its rounding and the points' errors. `false` decides nothing.
pub fn surely_off_line(a: [f64; 2], b: [f64; 2], c: [f64; 2], error: f64) -> bool {
    let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
    let (uv, vu) = (u[0] * v[1], u[1] * v[0]);
    // Moving each point by `error` per coordinate moves each difference by 2 error and the
    // cross product by 2 error (|u| + |v|) + 8 error^2 (1-norms); its f64 evaluation errs by
    // less than 2^-51 (|uv| + |vu|) (Shewchuk's orient2d bound, the differences' rounding
    // included). Each taken twice over.
    let moved = 4.0 * error * (u[0].abs() + u[1].abs() + v[0].abs() + v[1].abs() + 4.0 * error);
    let rounding = 2f64.powi(-50) * (uv.abs() + vu.abs());
    (uv - vu).abs() > moved + rounding
}

/// [`Vertices::partners`] of pieces with vertex ids `ids` (below `id_count`): the edges that
/// run between the same two points the other way, paired as [`cancelling_pairs`] pairs them.
/// Disjoint pieces share an edge whole with at most one other piece (a third with either edge
/// would overlap the one with the same).
fn edge_partners(ids: &PerVertex<u32>, id_count: usize) -> Vec<u32> {
    let edge_count = ids.vertex_count();
    let mut partners = vec![Vertices::ALONE; edge_count];
    // Edges named by their flat number: fewer than 2^32, as the vertex ids are. Each edge's
    // piece from a table (a search per pair cost a tenth of naming the vertices).
    let piece_of = ids.owners();
    let edges = || {
        (0..ids.len()).flat_map(|a| {
            let (v, first) = (&ids[a], ids.first(a));
            (0..v.len()).map(move |k| (v[k], v[(k + 1) % v.len()], (first + k) as u32))
        })
    };
    // The edges as ((smaller end, larger end), whether the edge runs from the larger, the
    // edge), in the order `cancelling_pairs` sorts them: by a counting sort on the smaller end
    // (the ids are dense; a sort of all edges by both ends took three times as long).
    let sorted = sorted_by_low(
        id_count,
        || edges().map(|(a, b, e)| ((a.min(b), a.max(b)), a > b, e)),
        |edge| edge.0.0,
    );
    for (e, f) in paired_in_runs(&sorted) {
        let (e, f) = (e as usize, f as usize);
        partners[e] = piece_of[f];
        partners[f] = piece_of[e];
    }
    partners
}

/// Vertices by their f64 points ([`Piece::point`]: coordinates within an error bound of the
/// exact point) in square cells of [`NearVertices::CELL`] grid units: two vertices that may be
/// the same exact point lie within the sum of their bounds, at most
/// [`Piece::POINT_ERROR_MAX`] each, so in one cell or in neighbouring ones. A vertex with a
/// larger bound (none: piece vertices are refined below it) goes to a list every query reads.
#[derive(Default)]
struct NearVertices {
    /// Per cell, its last entry (an index into `entries`).
    cells: FxHashMap<[i64; 2], u32>,
    /// (piece, vertex, the cell's entry before it or [`NearVertices::END`]): one list per
    /// cell, threaded through one flat list (most cells hold one vertex: a list per cell cost
    /// an allocation each).
    entries: Vec<(u32, u32, u32)>,
    loose: Vec<(u32, u32)>,
}

impl NearVertices {
    /// Twice the largest distance between two f64 points of one exact point: a query box
    /// (that distance each way) meets two cells in each direction, rarely three.
    const CELL: f64 = 4.0 * Piece::POINT_ERROR_MAX;

    /// The end of a cell's list.
    const END: u32 = u32::MAX;

    fn cell(v: f64) -> i64 {
        (v / Self::CELL).floor() as i64
    }

    fn bounded([x, y, e]: [f64; 3]) -> bool {
        // Far inside i64 cells: the grid is below 2^60.
        e <= Piece::POINT_ERROR_MAX && x.abs() < 1e18 && y.abs() < 1e18
    }

    fn insert(&mut self, point: [f64; 3], piece: usize, vertex: usize) {
        let (piece, vertex) = (piece as u32, vertex as u32);
        if Self::bounded(point) {
            let [x, y, _] = point;
            let key = [Self::cell(x), Self::cell(y)];
            let index = self.entries.len() as u32;
            let before = self.cells.insert(key, index).unwrap_or(Self::END);
            self.entries.push((piece, vertex, before));
        } else {
            self.loose.push((piece, vertex));
        }
    }

    /// The entries of the cell whose list ends at `last`, last entered first.
    fn cell_entries(&self, mut last: u32) -> impl Iterator<Item = (u32, u32)> + '_ {
        std::iter::from_fn(move || {
            let &(piece, vertex, before) = self.entries.get(last as usize)?;
            last = before;
            Some((piece, vertex))
        })
    }

    /// The first `Some` of `same(piece, vertex)` over the vertices that may be `point`; every
    /// vertex entered so far is tried when `point`'s own bound is too large for the cells.
    fn find<T>(
        &self,
        point: [f64; 3],
        mut same: impl FnMut(usize, usize) -> Option<T>,
    ) -> Option<T> {
        let mut try_all = |list: &mut dyn Iterator<Item = (u32, u32)>| {
            for (b, v) in list {
                if let Some(t) = same(b as usize, v as usize) {
                    return Some(t);
                }
            }
            None
        };
        if let Some(t) = try_all(&mut self.loose.iter().copied()) {
            return Some(t);
        }
        if !Self::bounded(point) {
            return try_all(&mut self.entries.iter().map(|&(b, v, _)| (b, v)));
        }
        let [x, y, _] = point;
        // Both bounds, and a little for the rounding of x - reach and x + reach.
        let reach = 2.0 * Piece::POINT_ERROR_MAX + 16.0;
        let (x0, x1) = (Self::cell(x - reach), Self::cell(x + reach));
        let (y0, y1) = (Self::cell(y - reach), Self::cell(y + reach));
        (x0..=x1)
            .flat_map(|cx| (y0..=y1).map(move |cy| [cx, cy]))
            .find_map(|key| {
                let &last = self.cells.get(&key)?;
                try_all(&mut self.cell_entries(last))
            })
    }
}

/// Vertex k of `p` (not a corner) as a grid point, if it is one (decided exactly): the only
/// grid point its error bound allows (the exactly rounded crossing when the bound is half a
/// unit or more), tested on both its lines.
fn grid_point_of(p: &Piece, k: usize) -> Option<[i64; 2]> {
    let [x, y, e] = p.point(k);
    let n = p.len();
    let (l, m) = (p.line((k + n - 1) % n), p.line(k));
    // Within e < 1/2 of (x, y) lies one grid point at most, the nearest; else round exactly.
    let [x, y] = if e < 0.5 {
        [x.round(), y.round()]
    } else {
        crossing_rounded(l, m)?
    };
    let limit = crate::exact::GRID_MAX as f64;
    if x.fract() != 0.0 || y.fract() != 0.0 || x.abs() > limit || y.abs() > limit {
        return None;
    }
    let (gx, gy) = (x as i64, y as i64);
    (l.sign_at_grid(gx, gy) == Ordering::Equal && m.sign_at_grid(gx, gy) == Ordering::Equal)
        .then_some([gx, gy])
}

/// Vertex k of `p` in pixels: its exact grid coordinates correctly rounded to f64 (to nearest,
/// ties to even), then mapped to pixels. A function of the exact point only, whichever two
/// lines name it.
pub fn vertex_pixel(p: &Piece, k: usize, s: &Samples) -> [f64; 2] {
    let [x, y, e] = p.point(k);
    // A zero error bound: the point is exact (a grid corner).
    let [x, y] = if e == 0.0 {
        [x, y]
    } else {
        let n = p.len();
        crossing_rounded(p.line((k + n - 1) % n), p.line(k)).unwrap_or([x, y])
    };
    [s.col_of(x), s.row_of(y)]
}

/// One connected region of a merge: its pieces and its rings.
struct Merged {
    /// Indices of its pieces (into the slice given to [`merge`]), ascending.
    members: Vec<usize>,
    /// Outer ring, then holes (ordered by their smallest vertex); pixels, even-odd.
    rings: Rings,
}

/// A vertex of a piece: the exact point a boundary point is, to test it against lines.
#[derive(Clone, Copy, Debug)]
struct At {
    piece: usize,
    vertex: usize,
}

/// A directed edge between two exact points, along line `line` of piece `members[owner]`,
/// whose interior lies on its left.
#[derive(Clone, Copy, Debug)]
struct Edge {
    from: u32,
    to: u32,
    from_at: At,
    to_at: At,
    owner: usize,
    line: usize,
}

/// The regions of the union of `pieces[members]` (disjoint; `members` ascending), ordered by
/// their outer rings' smallest vertex. See the module docs.
fn merge(pieces: &[Piece], vertices: &Vertices, members: &[usize]) -> Vec<Merged> {
    let ring = match *members {
        // A strictly convex piece: every vertex is a corner.
        [only] => Some(vertices.pixels[only].to_vec()),
        // Two pieces sharing an edge whole (a quad's two triangles, a face cut once).
        [a, b] => joined_ring(pieces, vertices, a, b),
        _ => None,
    };
    match ring {
        Some(ring) => vec![Merged {
            members: members.to_vec(),
            rings: smallvec::smallvec![ring],
        }],
        None => merge_boundaries(pieces, vertices, members),
    }
}

/// The ring of the union of disjoint pieces `a` and `b` when they share exactly one edge whole,
/// with at least three corners; `None` otherwise. Each lies in its own closed half-plane of the
/// shared edge's line and meets that line only along the edge, so they touch nowhere else: the
/// ring is `a`'s vertices from the shared edge's end round to its start, then `b`'s others,
/// without the two ends where the boundary goes straight on through them (decided exactly,
/// as [`merge_boundaries`] decides them; every other vertex is a corner of a strictly convex
/// piece).
fn joined_ring(pieces: &[Piece], vertices: &Vertices, a: usize, b: usize) -> Option<Vec<[f64; 2]>> {
    let mut shared = (vertices.partners_of(a).iter().enumerate())
        .filter(|&(_, &p)| p as usize == b)
        .map(|(k, _)| k);
    let (Some(k), None) = (shared.next(), shared.next()) else {
        return None;
    };
    let (ia, ib) = (&vertices.ids[a], &vertices.ids[b]);
    let (na, nb) = (ia.len(), ib.len());
    // b's edge j runs from a's vertex k + 1 to a's vertex k.
    let j = (0..nb).find(|&j| ib[j] == ia[(k + 1) % na] && ib[(j + 1) % nb] == ia[k])?;
    // Does vertex v of piece p lie on line l of piece q?
    let on = |(p, v): (usize, usize), (q, l): (usize, usize)| {
        let q = &pieces[q];
        pieces[p].vertex_line_sign_with(v, q.line(l), &q.line_approx(l)) == Ordering::Equal
    };
    // At a's vertex k (b's j + 1) the boundary arrives along a's line k - 1 and leaves for b's
    // vertex j + 2; at a's vertex k + 1 (b's j) it arrives along b's line j - 1 and leaves for
    // a's vertex k + 2.
    let (before_k, after_j) = ((k + na - 1) % na, (j + 2) % nb);
    let straight_k = ib[after_j] != ia[before_k] && on((b, after_j), (a, before_k));
    let (before_j, after_k) = ((j + nb - 1) % nb, (k + 2) % na);
    let straight_k1 = ia[after_k] != ib[before_j] && on((a, after_k), (b, before_j));
    let mut ring = Vec::with_capacity(na + nb - 2);
    for v in (1..=na).map(|i| (k + i) % na) {
        if !(v == k && straight_k || v == (k + 1) % na && straight_k1) {
            ring.push(vertices.pixels[a][v]);
        }
    }
    ring.extend((2..nb).map(|i| vertices.pixels[b][(j + i) % nb]));
    (ring.len() >= 3).then_some(ring)
}

/// [`merge`] of any group: its boundary edges (T-junctions split, shared parts cancelled)
/// walked into cycles.
fn merge_boundaries(pieces: &[Piece], vertices: &Vertices, members: &[usize]) -> Vec<Merged> {
    let group = Group {
        pieces,
        vertices,
        members,
    };
    let (boundary, mut components) = group.boundary();
    let graph = Boundary::new(&group, boundary);
    let mut by_component: BTreeMap<usize, Rings> = BTreeMap::new();
    // A cycle of fewer than three corners bounds nothing (only overlapping input makes one).
    for (owner, ring) in graph.cycles(&group).into_iter().filter(|c| c.1.len() >= 3) {
        by_component
            .entry(components.find(owner))
            .or_default()
            .push(ring);
    }
    let mut pieces_of: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (i, &m) in members.iter().enumerate() {
        pieces_of.entry(components.find(i)).or_default().push(m);
    }
    let mut out: Vec<Merged> = by_component
        .into_iter()
        .map(|(root, mut rings)| {
            // The outer ring holds the region's smallest vertex; holes follow in that order.
            rings.sort_by(|a, b| cmp_points(&smallest(a), &smallest(b)));
            let mut members = pieces_of.remove(&root).unwrap_or_default();
            members.sort_unstable();
            Merged { members, rings }
        })
        .collect();
    out.sort_by(|a, b| cmp_points(&smallest(&a.rings[0]), &smallest(&b.rings[0])));
    out
}

/// (y, then x): the order of points in canonical drawings.
fn cmp_points(a: &[f64; 2], b: &[f64; 2]) -> Ordering {
    a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0]))
}

/// The smallest vertex of a ring (y, then x).
fn smallest(ring: &[[f64; 2]]) -> [f64; 2] {
    ring.iter()
        .copied()
        .min_by(cmp_points)
        .unwrap_or([f64::INFINITY; 2])
}

/// The pieces of one group, for the merge.
struct Group<'a> {
    pieces: &'a [Piece],
    vertices: &'a Vertices,
    members: &'a [usize],
}

impl Group<'_> {
    fn piece(&self, at: At) -> &Piece {
        &self.pieces[at.piece]
    }

    fn id(&self, at: At) -> u32 {
        self.vertices.ids[at.piece][at.vertex]
    }

    fn pixel(&self, at: At) -> [f64; 2] {
        self.vertices.pixels[at.piece][at.vertex]
    }

    /// The kernel line an edge runs along (positive on its left), as (piece, line index).
    fn line(&self, e: &Edge) -> (usize, usize) {
        (self.members[e.owner], e.line)
    }

    /// The side of line `line` of piece `piece` the exact point `at` lies on.
    fn side(&self, at: At, (piece, line): (usize, usize)) -> Ordering {
        let p = &self.pieces[piece];
        self.piece(at)
            .vertex_line_sign_with(at.vertex, p.line(line), &p.line_approx(line))
    }

    /// Of the two lines of `x`'s piece through `x`, one that `other` (another point) is not on,
    /// with the side `other` lies on; a line through x crossing the line from x to `other`.
    fn crossing_line(&self, x: At, other: At) -> Option<((usize, usize), Ordering)> {
        let n = self.piece(x).len();
        [(x.vertex + n - 1) % n, x.vertex]
            .into_iter()
            .map(|l| ((x.piece, l), self.side(other, (x.piece, l))))
            .find(|&(_, s)| s != Ordering::Equal)
    }

    /// The boundary of the group's union as directed edges, and its connected interiors
    /// (pieces joined by every edge that two pieces share, run both ways).
    ///
    /// An edge whose reverse is an edge of another piece (the same exact ends) is shared whole:
    /// no vertex lies inside it (it would belong to a piece overlapping one of the two). The
    /// other edges are split where a vertex of another piece of the group lies inside them
    /// (a T-junction, decided exactly), so that a boundary two pieces share is the same edges
    /// in both, run both ways, and cancels; what is left is the boundary. The vertices that can
    /// lie inside an edge are those of pieces with such an edge too (the first and the last
    /// piece around a T-junction vertex have one), found near it through the pieces' bounds.
    fn boundary(&self) -> (Vec<Edge>, UnionFind) {
        let (pieces, members) = (self.pieces, self.members);
        debug_assert!(members.is_sorted(), "members ascend");
        let mut components = UnionFind::new(members.len());
        // Edge k of member i is edge first[i] + k of the group; whole: shared whole with
        // another member (found by bisection: members ascend; all the pieces, as the outline
        // merges them, are each their own place).
        let all = members.len() == pieces.len();
        let mut first = Vec::with_capacity(members.len() + 1);
        let mut whole = Vec::new();
        for (i, &m) in members.iter().enumerate() {
            first.push(whole.len());
            for &b in self.vertices.partners_of(m) {
                let j = match b as usize {
                    _ if b == Vertices::ALONE => None,
                    b if all => Some(b),
                    b => members.binary_search(&b).ok(),
                };
                if let Some(j) = j {
                    components.union(i, j);
                }
                whole.push(j.is_some());
            }
        }
        first.push(whole.len());
        let open = |i: usize| whole[first[i]..first[i + 1]].iter().any(|w| !w);
        let at = |i: usize, k: usize| At {
            piece: members[i],
            vertex: k % pieces[members[i]].len(),
        };
        let mut edges = Vec::new();
        let pixels = |i: usize| &self.vertices.pixels[members[i]];
        let open_edge = |i: usize, k: usize| !whole[first[i] + k];
        for_each_near_edges(members.len(), pixels, open, open_edge, |i, near| {
            for k in (0..pieces[members[i]].len()).filter(|&k| open_edge(i, k)) {
                let mut points = self.inside_edge(i, k, near);
                points.push(at(i, k + 1));
                let mut from = at(i, k);
                for to in points {
                    edges.push(Edge {
                        from: self.id(from),
                        to: self.id(to),
                        from_at: from,
                        to_at: to,
                        owner: i,
                        line: k,
                    });
                    from = to;
                }
            }
        });
        let mut cancelled = vec![false; edges.len()];
        let named = edges.iter().enumerate().map(|(e, x)| ((x.from, x.to), e));
        for (f, b) in cancelling_pairs(named, edges.len()) {
            cancelled[f] = true;
            cancelled[b] = true;
            components.union(edges[f].owner, edges[b].owner);
        }
        let boundary = edges
            .into_iter()
            .zip(cancelled)
            .filter_map(|(e, c)| (!c).then_some(e))
            .collect();
        (boundary, components)
    }

    /// The vertices of pieces `near` strictly inside edge k of piece `members[i]` (on its line,
    /// strictly inside its other lines), each point once, in order from the edge's start.
    fn inside_edge(&self, i: usize, k: usize, near: &[usize]) -> Vec<At> {
        let pa = &self.pieces[self.members[i]];
        let (line, approx) = (pa.line(k), pa.line_approx(k));
        let start = At {
            piece: self.members[i],
            vertex: k,
        };
        let end = At {
            piece: self.members[i],
            vertex: (k + 1) % pa.len(),
        };
        let ends = [self.id(start), self.id(end)];
        // The edge's piece's lines, approximated once when a vertex first needs them.
        let mut lines: Option<SmallVec<[(&Line, LineApprox); 4]>> = None;
        let mut found: Vec<(f64, u32, At)> = Vec::new();
        for &j in near {
            let b = self.members[j];
            let pb = &self.pieces[b];
            for v in 0..pb.len() {
                let at = At {
                    piece: b,
                    vertex: v,
                };
                // The edge's own ends (the same exact point: most vertices on the line) are not
                // inside it, and a vertex the f64 filter puts off the line is not either: both
                // without exact arithmetic. Then the other lines (a vertex on the line beyond
                // the edge is off one of them, usually by the filter), and last the exact test
                // on the line, whose zero always takes the exact path.
                let id = self.id(at);
                if ends.contains(&id)
                    || approx
                        .sign_at(pb.point(v))
                        .is_some_and(|s| s != Ordering::Equal)
                {
                    continue;
                }
                let lines = lines.get_or_insert_with(|| pa.lines_with_approx().collect());
                let strictly_inside = lines.iter().enumerate().all(|(l, (m, ma))| {
                    l == k || pb.vertex_line_sign_with(v, m, ma) == Ordering::Greater
                });
                if strictly_inside && pb.vertex_line_sign_with(v, line, &approx) == Ordering::Equal
                {
                    let ([x0, y0], [x, y]) = (self.pixel(start), self.pixel(at));
                    found.push(((x - x0).abs() + (y - y0).abs(), id, at));
                }
            }
        }
        // The rounding is monotone along the edge: distances in pixels never order two points
        // the wrong way, and ties are decided exactly.
        found.sort_by(|p, q| {
            p.0.total_cmp(&q.0)
                .then_with(|| self.along_edge(start, (p.1, p.2), (q.1, q.2)))
        });
        found.dedup_by_key(|p| p.1);
        found.into_iter().map(|p| p.2).collect()
    }

    /// The order of two points strictly inside an edge that starts at `start`, exactly: p
    /// comes first if it lies on the start's side of a line through q that crosses the edge.
    fn along_edge(&self, start: At, p: (u32, At), q: (u32, At)) -> Ordering {
        if p.0 == q.0 {
            return Ordering::Equal;
        }
        match self.crossing_line(q.1, start) {
            Some((m, start_side)) if self.side(p.1, m) == start_side => Ordering::Less,
            Some(_) => Ordering::Greater,
            // Both lines through q contain the start: never for a piece whose vertex q lies
            // strictly inside the edge.
            None => p.0.cmp(&q.0),
        }
    }
}

/// The pairs of edges, given as ((from, to), name) with distinct names, that run between the
/// same two points in opposite directions: each edge pairs with at most one, in name order.
/// `count` is the number of edges (room made once: a list grown by doubling holds its old room
/// and its new one at once, on a million pieces 26 MB and 52).
fn cancelling_pairs<E: Copy + Ord + Send>(
    edges: impl Iterator<Item = ((u32, u32), E)>,
    count: usize,
) -> Vec<(E, E)> {
    use rayon::slice::ParallelSliceMut;
    // (the two ends, smaller first; whether the edge runs from the larger; the edge)
    let mut keyed: Vec<(u64, bool, E)> = Vec::with_capacity(count);
    keyed.extend(edges.map(|((a, b), e)| (((a.min(b) as u64) << 32) | a.max(b) as u64, a > b, e)));
    // The names are distinct: one order whatever the sort.
    keyed.par_sort_unstable();
    paired_in_runs(&keyed).collect()
}

/// The cancelling pairs of `sorted` edges, each (the two ends' name; whether the edge runs
/// from the larger end; the edge) in ascending order: within a run of one name, the k-th edge
/// running forward with the k-th running backward.
fn paired_in_runs<K: PartialEq, E: Copy>(
    sorted: &[(K, bool, E)],
) -> impl Iterator<Item = (E, E)> + '_ {
    sorted.chunk_by(|x, y| x.0 == y.0).flat_map(|run| {
        let (forward, backward) = run.split_at(run.partition_point(|x| !x.1));
        forward.iter().zip(backward).map(|(f, b)| (f.2, b.2))
    })
}

/// The boundary of a union as a graph: its vertices (exact ids), the edges leaving each, and
/// which vertices are straight (dropped).
struct Boundary {
    /// The boundary edges, by the id they leave from (then as they came).
    edges: Vec<Edge>,
    /// The vertices, ascending ids: one per id that a boundary edge leaves.
    ids: Vec<u32>,
    /// `edges[start[v]..start[v + 1]]` leave vertex v.
    start: Vec<usize>,
    straight: Vec<bool>,
}

impl Boundary {
    fn new(group: &Group, mut edges: Vec<Edge>) -> Self {
        edges.sort_by_key(|e| e.from);
        let mut ids: Vec<u32> = Vec::new();
        let mut start = Vec::new();
        for (k, e) in edges.iter().enumerate() {
            if ids.last() != Some(&e.from) {
                ids.push(e.from);
                start.push(k);
            }
        }
        start.push(edges.len());
        let mut graph = Boundary {
            edges,
            ids,
            start,
            straight: Vec::new(),
        };
        // Per vertex: how many boundary edges arrive, and the last of them.
        let mut arriving: Vec<(u32, usize)> = vec![(0, usize::MAX); graph.ids.len()];
        for (k, e) in graph.edges.iter().enumerate() {
            if let Some(v) = graph.vertex(e.to) {
                arriving[v] = (arriving[v].0 + 1, k);
            }
        }
        graph.straight = (0..graph.ids.len())
            .map(|v| {
                let ((1, e_in), 1) = (arriving[v], graph.start[v + 1] - graph.start[v]) else {
                    return false;
                };
                let (e_in, e_out) = (&graph.edges[e_in], &graph.edges[graph.start[v]]);
                // The boundary goes straight on through v: the next point lies on the line the
                // boundary arrives along (and is not where it came from).
                e_out.to != e_in.from
                    && group.side(e_out.to_at, group.line(e_in)) == Ordering::Equal
            })
            .collect();
        graph
    }

    /// The vertex of an id, if a boundary edge leaves it.
    fn vertex(&self, id: u32) -> Option<usize> {
        self.ids.binary_search(&id).ok()
    }

    /// Every cycle of the boundary through its kept vertices, as (a piece it bounds, by its
    /// index in the group; the ring in pixels). Cycles are walked from the edges in the order
    /// of their ids; where several edges leave a vertex, the walk turns most to the left.
    fn cycles(&self, group: &Group) -> Vec<(usize, Vec<[f64; 2]>)> {
        let mut used = vec![false; self.edges.len()];
        let mut cycles = Vec::new();
        for (v0, &s) in self.start[..self.ids.len()].iter().enumerate() {
            if self.straight[v0] {
                continue;
            }
            for e0 in s..self.start[v0 + 1] {
                if used[e0] {
                    continue;
                }
                used[e0] = true;
                let mut ring = Vec::new();
                let mut e = e0;
                // Every step marks an edge used, so the walk ends.
                loop {
                    let edge = &self.edges[e];
                    let Some(v) = self.vertex(edge.to) else {
                        break;
                    };
                    let leaving = self.start[v]..self.start[v + 1];
                    let next = if self.straight[v] {
                        leaving.start
                    } else {
                        ring.push(group.pixel(edge.to_at));
                        self.leftmost(group, edge, leaving)
                    };
                    if used[next] {
                        break;
                    }
                    used[next] = true;
                    e = next;
                }
                cycles.push((self.edges[e0].owner, ring));
            }
        }
        cycles
    }

    /// Of the edges leaving the end of `arrive`, the one that turns most to the left: the
    /// first met turning clockwise from the way back. The region left of `arrive` lies between
    /// the two, so the walk stays on the boundary of one connected interior. Exact: turns are
    /// sides of kernel lines (edges keep the interior on their left, positive side).
    fn leftmost(&self, group: &Group, arrive: &Edge, leaving: std::ops::Range<usize>) -> usize {
        // 0: a right turn, 1: straight on, 2: a left turn, 3: back (never on a valid union).
        let class = |e: &Edge| match group.side(e.to_at, group.line(arrive)) {
            Ordering::Less => 0,
            Ordering::Greater => 2,
            Ordering::Equal if self.goes_back(group, arrive, e) => 3,
            Ordering::Equal => 1,
        };
        leaving
            .max_by(|&i, &j| {
                let (ei, ej) = (&self.edges[i], &self.edges[j]);
                let (ci, cj) = (class(ei), class(ej));
                // Two turns the same way: i turns more to the left if it ends left of j.
                ci.cmp(&cj).then_with(|| match ci {
                    0 | 2 => group.side(ei.to_at, group.line(ej)),
                    _ => Ordering::Equal,
                })
            })
            .expect("an edge leaves every boundary vertex")
    }

    /// Does `e`, leaving the end of `arrive` along the same line, run back the way `arrive`
    /// came? Exact: compared with a line through their common point that crosses theirs.
    fn goes_back(&self, group: &Group, arrive: &Edge, e: &Edge) -> bool {
        group
            .crossing_line(arrive.to_at, arrive.from_at)
            .is_some_and(|(m, s)| group.side(e.to_at, m) == s)
    }
}

/// Disjoint sets of `0..n`, with path halving.
pub(super) struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    pub(super) fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n).collect(),
        }
    }

    pub(super) fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    pub(super) fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        // The smaller root wins: roots, and so the order of components, do not depend on the
        // order of the unions.
        if a != b {
            self.parent[a.max(b)] = a.min(b);
        }
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::exact::polygon::{Boundary, Split};
    use crate::exact::predicates::Line;
    use crate::exact::{GridPoint, Plane};

    /// The bucketed pairing is the sorted one's: random polygons over a few ids, so that edges
    /// repeat both ways and the same way, paired as [`cancelling_pairs`] pairs them.
    #[test]
    fn edge_partners_pair_edges_as_the_sort_of_all_edges_does() {
        let mut rng = crate::stress::rng::Rng::of(&[0x5eed_ed9e]);
        for case in 0..300 {
            let id_count = 3 + (rng.next_u64() % 12) as usize;
            let mut ids = PerVertex::with_capacity(0, 0);
            for _ in 0..1 + rng.next_u64() % 30 {
                let len = 3 + (rng.next_u64() % 4) as usize;
                ids.push_piece((0..len).map(|_| (rng.next_u64() % id_count as u64) as u32));
            }
            let piece_of = ids.owners();
            let edges = (0..ids.len()).flat_map(|a| {
                let (v, first) = (&ids[a], ids.first(a));
                (0..v.len()).map(move |k| ((v[k], v[(k + 1) % v.len()]), (first + k) as u32))
            });
            let mut want = vec![Vertices::ALONE; ids.vertex_count()];
            for (e, f) in cancelling_pairs(edges, ids.vertex_count()) {
                want[e as usize] = piece_of[f as usize];
                want[f as usize] = piece_of[e as usize];
            }
            assert_eq!(edge_partners(&ids, id_count), want, "case {case}");
        }
    }

    /// A piece of polygon `poly` in the plane z = 0 with these grid corners (counter-clockwise,
    /// y up), each side an outline side.
    pub(in crate::draw) fn grid_piece(poly: u32, corners: &[[i64; 2]]) -> Piece {
        let gp: Vec<GridPoint> = corners
            .iter()
            .map(|&[x, y]| GridPoint { x, y, z: 0 })
            .collect();
        let support = Plane {
            a: 0,
            b: 0,
            c: 1,
            d: crate::exact::w256(0),
        };
        Piece::from_convex(poly, support, &gp, |side| Boundary::Outline {
            poly,
            side: side as u32,
        })
    }

    /// Labels by key are numbered by first appearance, equal exactly for equal keys, whatever
    /// the hashes: with the real hash, with one that maps every key to a few values (in the
    /// 32 bits kept), and with one value for all (the keys are then told apart by comparing
    /// them alone). With runs of one key.
    #[test]
    fn labels_by_key_are_by_key_whatever_the_hash_collides() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut keys: Vec<(u8, [i64; 2])> = Vec::new();
        while keys.len() < 40_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let k = (
                (state % 5) as u8,
                [(state >> 8) as i64 % 7, (state >> 16) as i64 % 11],
            );
            let run = 1 + (state >> 40) as usize % 3;
            keys.extend(std::iter::repeat_n(k, run));
        }
        let mut expected = Vec::new();
        let mut seen: BTreeMap<(u8, [i64; 2]), u32> = BTreeMap::new();
        for k in &keys {
            let next = seen.len() as u32;
            expected.push(*seen.entry(*k).or_insert(next));
        }
        assert!(seen.len() > 100, "the keys repeat and differ");
        let key = |i: usize| keys[i];
        let real = labels_by_key(keys.len(), key, |k| FxBuildHasher.hash_one(k));
        let few = labels_by_key(keys.len(), key, |k| (FxBuildHasher.hash_one(k) % 3) << 32);
        let one = labels_by_key(keys.len(), key, |_| 7);
        assert_eq!(real, expected);
        assert_eq!(few, expected);
        assert_eq!(one, expected);
    }

    /// A 2^53-pixel-wide image: pixels are grid units up to an offset ([`to_grid`]). (No
    /// image is this wide; `Samples::new` would refuse it.)
    pub(in crate::draw) fn grid_samples() -> Samples {
        Samples {
            width: 1 << 53,
            height: 1 << 53,
        }
    }

    /// Pixels of [`grid_samples`] back to grid units (exact for small grid coordinates).
    pub(in crate::draw) fn to_grid([c, r]: [f64; 2]) -> [f64; 2] {
        [c - (1u64 << 52) as f64, (1u64 << 52) as f64 - r]
    }

    /// Rings in grid units.
    type Rings = Vec<Vec<[f64; 2]>>;

    /// The regions of all `pieces` as one group: per region, its pieces and its rings in grid
    /// units, each ring started at its smallest point (y, then x), as the merge gives them.
    fn merged(pieces: &[Piece]) -> Vec<(Vec<usize>, Rings)> {
        let vertices = shared_vertices(pieces, &grid_samples());
        let all: Vec<usize> = (0..pieces.len()).collect();
        merge(pieces, &vertices, &all)
            .into_iter()
            .map(|m| {
                let rings = m
                    .rings
                    .into_iter()
                    .map(|r| {
                        let mut r: Vec<[f64; 2]> = r.into_iter().map(to_grid).collect();
                        let k = (0..r.len())
                            .min_by(|&a, &b| cmp_points(&r[a], &r[b]))
                            .unwrap();
                        r.rotate_left(k);
                        r
                    })
                    .collect();
                (m.members, rings)
            })
            .collect()
    }

    /// The rings of the regions, without the pieces.
    fn rings(pieces: &[Piece]) -> Vec<Rings> {
        merged(pieces).into_iter().map(|m| m.1).collect()
    }

    fn rect(poly: u32, [x0, y0, x1, y1]: [i64; 4]) -> Piece {
        grid_piece(poly, &[[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
    }

    /// Rings of grid points as the merge gives them in grid units.
    fn ring_set(rings: &[&[[i64; 2]]]) -> Rings {
        rings
            .iter()
            .map(|r| r.iter().map(|p| p.map(|v| v as f64)).collect())
            .collect()
    }

    /// One region with these rings ([`ring_set`]).
    fn region(rings: &[&[[i64; 2]]]) -> Vec<Rings> {
        vec![ring_set(rings)]
    }

    /// Rectangles (x0, y0, x1, y1) of polygon 0.
    fn rects(boxes: &[[i64; 4]]) -> Vec<Piece> {
        boxes.iter().map(|&b| rect(0, b)).collect()
    }

    /// Pieces of 3, 4 and 3 vertices in one flat list: each piece's values, and the piece every
    /// flat index belongs to.
    #[test]
    fn per_vertex_values_are_found_by_piece_and_by_flat_index() {
        let mut v = PerVertex::with_capacity(3, 10);
        v.push_piece([10, 11, 12]);
        v.push_piece([20, 21, 22, 23]);
        v.push_piece([30, 31, 32]);
        assert_eq!(v.len(), 3);
        assert_eq!(v.vertex_count(), 10);
        assert_eq!(&v[1], &[20, 21, 22, 23]);
        let pieces: Vec<&[i32]> = v.iter().collect();
        assert_eq!(
            pieces,
            [&[10, 11, 12][..], &[20, 21, 22, 23], &[30, 31, 32]]
        );
        assert_eq!(v.owners(), [0, 0, 0, 1, 1, 1, 1, 2, 2, 2]);
        assert_eq!((v.first(0), v.first(1), v.first(2)), (0, 3, 7));
        assert!(PerVertex::<u32>::default().is_empty());
    }

    #[test]
    fn a_square_cut_three_ways_merges_to_its_four_corners() {
        let quadrants = rects(&[[0, 0, 4, 4], [4, 0, 8, 4], [4, 4, 8, 8], [0, 4, 4, 8]]);
        // A T-junction: the right strip's cut ends inside the left strip's edge.
        let strips = rects(&[[0, 0, 3, 8], [3, 0, 8, 5], [3, 5, 8, 8]]);
        let fan = [
            grid_piece(0, &[[0, 0], [8, 0], [4, 4]]),
            grid_piece(0, &[[8, 0], [8, 8], [4, 4]]),
            grid_piece(0, &[[8, 8], [0, 8], [4, 4]]),
            grid_piece(0, &[[0, 8], [0, 0], [4, 4]]),
        ];
        let square = region(&[&[[0, 0], [8, 0], [8, 8], [0, 8]]]);
        assert_eq!(rings(&quadrants), square);
        assert_eq!(rings(&strips), square);
        assert_eq!(rings(&fan), square);
        assert_eq!(merged(&strips)[0].0, vec![0, 1, 2]);
    }

    /// `merge`'s regions and those of the boundary walk, each ring from its smallest point.
    fn merged_both_ways(pieces: &[Piece]) -> [Vec<(Vec<usize>, Rings)>; 2] {
        let vertices = shared_vertices(pieces, &grid_samples());
        let all: Vec<usize> = (0..pieces.len()).collect();
        let normal = |m: Vec<Merged>| -> Vec<(Vec<usize>, Rings)> {
            (m.into_iter())
                .map(|m| {
                    let rings = (m.rings.into_iter())
                        .map(|mut r| {
                            let k = (0..r.len()).min_by(|&a, &b| cmp_points(&r[a], &r[b]));
                            r.rotate_left(k.unwrap());
                            r
                        })
                        .collect();
                    (m.members, rings)
                })
                .collect()
        };
        [
            normal(merge(pieces, &vertices, &all)),
            normal(merge_boundaries(pieces, &vertices, &all)),
        ]
    }

    proptest::proptest! {
        /// Three points exactly on a line, each moved by up to `error` in each coordinate
        /// (to the corners of that box, where the orientation moves most): never surely off
        /// the line. Points clearly off it are.
        #[test]
        fn points_moved_within_the_error_from_a_line_are_never_surely_off_it(
            a in proptest::array::uniform2(-2000i32..2000),
            d in proptest::array::uniform2(-2000i32..2000),
            k in -3i32..4,
            moves in proptest::array::uniform6(-1i32..=1),
            error_bits in 0i32..40,
        ) {
            proptest::prop_assume!(d != [0, 0] && k != 0 && k != 1);
            // A power of two: every moved coordinate (below 2^14) is exact.
            let error = 2f64.powi(-error_bits);
            let on = |t: i32| [0, 1].map(|i| f64::from(a[i] + t * d[i]));
            let moved = |t: i32, m: usize| {
                [0, 1].map(|i| on(t)[i] + f64::from(moves[m + i]) * error)
            };
            let (p, q, r) = (moved(0, 0), moved(1, 2), moved(k, 4));
            proptest::prop_assert!(!surely_off_line(p, q, r, error));
            // A unit or more off the line (across d).
            let off = [on(k)[0] - f64::from(d[1]), on(k)[1] + f64::from(d[0])];
            proptest::prop_assert!(surely_off_line(on(0), on(1), off, 1e-3));
        }
    }

    proptest::proptest! {
        /// Two triangles on either side of a common edge (often with a third corner on the
        /// line of a side of the other, so that the boundary goes straight through an end of
        /// the edge), and a triangle or a box cut once by a line: the joined ring is the
        /// boundary walk's.
        #[test]
        fn two_pieces_sharing_an_edge_merge_as_the_boundary_walk_merges_them(
            c in proptest::array::uniform4(proptest::array::uniform2(-5i64..5)),
            cut_line in proptest::array::uniform2(proptest::array::uniform2(-6i64..6)),
            boxed in proptest::array::uniform4(-6i64..6),
        ) {
            let [p, q, r, s] = c;
            let turn = |a: [i64; 2], b: [i64; 2], c: [i64; 2]| {
                (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
            };
            let mut cases = Vec::new();
            if turn(p, q, r) > 0 && turn(q, p, s) > 0 {
                cases.push(vec![grid_piece(0, &[p, q, r]), grid_piece(1, &[q, p, s])]);
            }
            if turn(p, q, r) > 0 && cut_line[0] != cut_line[1] {
                cases.push(cut(vec![grid_piece(0, &[p, q, r])], &[cut_line]));
            }
            let [x0, y0, x1, y1] = boxed;
            if x0 < x1 && y0 < y1 && cut_line[0] != cut_line[1] {
                cases.push(cut(vec![rect(0, boxed)], &[cut_line]));
            }
            for pieces in cases.into_iter().filter(|c| c.len() == 2) {
                let [fast, walked] = merged_both_ways(&pieces);
                proptest::prop_assert_eq!(fast, walked);
            }
        }
    }

    /// `pieces` each cut by every line through two grid points in `cuts`.
    pub(in crate::draw) fn cut(pieces: Vec<Piece>, cuts: &[[[i64; 2]; 2]]) -> Vec<Piece> {
        let g = |[x, y]: [i64; 2]| GridPoint { x, y, z: 0 };
        cuts.iter().fold(pieces, |pieces, &[a, b]| {
            let l = Line::edge(g(a), g(b)).unwrap();
            pieces
                .into_iter()
                .flat_map(|p| match p.split_by_line(&l, Boundary::ScreenSplit) {
                    Split::Both(a, b) => vec![a, b],
                    _ => vec![p],
                })
                .collect()
        })
    }

    #[test]
    fn a_quad_cut_across_its_slanted_sides_merges_to_its_four_corners_however_cut() {
        // The cuts cross the slanted sides between grid points: the pieces' vertices there are
        // rounded, and off the sides in f64, yet exactly on them.
        let quad = || vec![grid_piece(0, &[[0, 0], [70, 10], [90, 80], [10, 60]])];
        let once = cut(quad(), &[[[33, -5], [41, 100]]]);
        let thrice = cut(
            quad(),
            &[
                [[20, -5], [60, 100]],
                [[-5, 30], [100, 45]],
                [[0, 100], [100, 3]],
            ],
        );
        assert_eq!((once.len(), thrice.len()), (2, 7));
        let corners = region(&[&[[0, 0], [70, 10], [90, 80], [10, 60]]]);
        assert_eq!(rings(&once), corners);
        assert_eq!(rings(&thrice), corners);
    }

    #[test]
    fn an_l_shape_cut_three_ways_merges_to_its_six_corners() {
        let wide_bottom = rects(&[[0, 0, 8, 4], [0, 4, 4, 8]]);
        let tall_left = rects(&[[0, 0, 4, 8], [4, 0, 8, 4]]);
        let squares = rects(&[[4, 0, 8, 4], [0, 4, 4, 8], [0, 0, 4, 4]]);
        let l = region(&[&[[0, 0], [8, 0], [8, 4], [4, 4], [4, 8], [0, 8]]]);
        assert_eq!(rings(&wide_bottom), l);
        assert_eq!(rings(&tall_left), l);
        assert_eq!(rings(&squares), l);
    }

    #[test]
    fn a_ring_cut_three_ways_merges_to_an_outer_ring_and_a_hole() {
        let bands = rects(&[[0, 0, 6, 2], [0, 4, 6, 6], [0, 2, 2, 4], [4, 2, 6, 4]]);
        let pinwheel = rects(&[[0, 0, 4, 2], [4, 0, 6, 4], [2, 4, 6, 6], [0, 2, 2, 6]]);
        let trapezoids = [
            grid_piece(0, &[[0, 0], [6, 0], [4, 2], [2, 2]]),
            grid_piece(0, &[[6, 0], [6, 6], [4, 4], [4, 2]]),
            grid_piece(0, &[[6, 6], [0, 6], [2, 4], [4, 4]]),
            grid_piece(0, &[[0, 6], [0, 0], [2, 2], [2, 4]]),
        ];
        // Outer ring counter-clockwise (y up), the hole clockwise: the interior on the left.
        let ring = region(&[
            &[[0, 0], [6, 0], [6, 6], [0, 6]],
            &[[2, 2], [2, 4], [4, 4], [4, 2]],
        ]);
        assert_eq!(rings(&bands), ring);
        assert_eq!(rings(&pinwheel), ring);
        assert_eq!(rings(&trapezoids), ring);
    }

    #[test]
    fn squares_touching_at_a_corner_are_two_regions_however_cut() {
        let whole = rects(&[[0, 0, 4, 4], [4, 4, 8, 8]]);
        let halves = [
            grid_piece(0, &[[4, 4], [8, 4], [8, 8]]),
            grid_piece(0, &[[0, 0], [4, 0], [0, 4]]),
            grid_piece(0, &[[4, 0], [4, 4], [0, 4]]),
            grid_piece(0, &[[4, 4], [8, 8], [4, 8]]),
        ];
        // Regions in the order of their topmost vertex on screen (y down).
        let two = vec![
            ring_set(&[&[[4, 4], [8, 4], [8, 8], [4, 8]]]),
            ring_set(&[&[[0, 0], [4, 0], [4, 4], [0, 4]]]),
        ];
        assert_eq!(rings(&whole), two);
        assert_eq!(rings(&halves), two);
        let members: Vec<Vec<usize>> = merged(&halves).into_iter().map(|m| m.0).collect();
        assert_eq!(members, vec![vec![0, 3], vec![1, 2]]);
    }

    #[test]
    fn a_hole_touching_the_outer_boundary_is_one_ring_through_the_pinch_however_cut() {
        // A 6x6 square less the triangle (3,0), (4,2), (2,2), which touches its bottom side.
        let three = [
            grid_piece(0, &[[0, 0], [3, 0], [2, 2], [0, 2]]),
            grid_piece(0, &[[3, 0], [6, 0], [6, 2], [4, 2]]),
            rect(0, [0, 2, 6, 6]),
        ];
        let five = [
            grid_piece(0, &[[0, 0], [3, 0], [2, 2]]),
            grid_piece(0, &[[0, 0], [2, 2], [0, 2]]),
            grid_piece(0, &[[3, 0], [6, 0], [6, 2], [4, 2]]),
            rect(0, [0, 2, 3, 6]),
            rect(0, [3, 2, 6, 6]),
        ];
        // The walk turns most to the left at the pinch (3, 0): it takes the hole on the way.
        let pinched = region(&[&[
            [0, 0],
            [3, 0],
            [2, 2],
            [4, 2],
            [3, 0],
            [6, 0],
            [6, 6],
            [0, 6],
        ]]);
        assert_eq!(rings(&three), pinched);
        assert_eq!(rings(&five), pinched);
    }

    /// Two f64 points of one exact point lie up to twice the largest error bound apart, across
    /// cell borders; a point without a usable bound meets every other.
    #[test]
    fn near_vertices_finds_every_point_within_both_bounds() {
        let e = Piece::POINT_ERROR_MAX;
        let mut near = NearVertices::default();
        let edge = NearVertices::CELL;
        near.insert([edge - 1.0, -1.0, e], 0, 0);
        let found = |near: &NearVertices, p: [f64; 3]| {
            let mut all = Vec::new();
            near.find(p, |b, v| {
                all.push((b, v));
                None::<()>
            });
            all
        };
        // Just within reach, in the neighbouring cells on both axes.
        assert_eq!(
            found(&near, [edge - 1.0 + 2.0 * e, 2.0 * e - 1.5, e]),
            [(0, 0)]
        );
        assert_eq!(found(&near, [edge - 1.0 - 2.0 * e, -1.0, 0.0]), [(0, 0)]);
        // Far away: not even tried.
        assert!(found(&near, [edge - 1.0 + 3.0 * edge, -1.0, e]).is_empty());
        // Unbounded points meet everything, both ways.
        near.insert([1e300, 0.0, f64::INFINITY], 1, 2);
        assert_eq!(found(&near, [-5.0 * edge, 0.0, 0.0]), [(1, 2)]);
        assert_eq!(
            found(&near, [f64::NAN, 0.0, f64::INFINITY]),
            [(1, 2), (0, 0)]
        );
    }

    #[test]
    fn a_point_named_by_different_lines_rounds_to_the_same_bits() {
        // Three lines through (10/3, 10/3): y = x, x + 2y = 10 and 2x + y = 10.
        let line = |a: [i64; 2], b: [i64; 2]| {
            let g = |[x, y]: [i64; 2]| GridPoint { x, y, z: 0 };
            Line::edge(g(a), g(b)).unwrap()
        };
        let lines = [
            line([0, 0], [1, 1]),
            line([10, 0], [0, 5]),
            line([5, 0], [0, 10]),
        ];
        let third = 10.0 / 3.0;
        for (i, l) in lines.iter().enumerate() {
            for m in &lines[i + 1..] {
                assert_eq!(crossing_rounded(l, m), Some([third, third]));
            }
        }
        // Cut a square by the three lines: every piece's vertex there has the same pixels.
        let mut pieces = vec![rect(0, [0, 0, 10, 10])];
        for l in &lines {
            pieces = pieces
                .into_iter()
                .flat_map(|p| match p.split_by_line(l, Boundary::ScreenSplit) {
                    Split::Both(a, b) => vec![a, b],
                    _ => vec![p],
                })
                .collect();
        }
        let s = Samples::new(640, 480);
        let at_third: Vec<[f64; 2]> = pieces
            .iter()
            .flat_map(|p| (0..p.len()).map(move |k| (p, k)))
            .filter(|(p, k)| {
                let [x, y] = p.vertex_f64(*k);
                (x - third).abs() < 1e-9 && (y - third).abs() < 1e-9
            })
            .map(|(p, k)| vertex_pixel(p, k, &s))
            .collect();
        assert_eq!(at_third.len(), 6);
        assert!(
            at_third
                .iter()
                .all(|p| *p == [s.col_of(third), s.row_of(third)])
        );
    }

    #[test]
    fn a_crossing_on_a_grid_point_shares_the_id_of_the_corner_there_whichever_comes_first() {
        // The planes z = y and z = 5 meet above the line y = 5: a cut line, so the square's
        // vertices on it are crossings, not corners, though they are grid points.
        let g = |x, y, z| GridPoint { x, y, z };
        let p = Plane::of_polygon(&[g(0, 0, 0), g(10, 0, 0), g(0, 10, 10)]).unwrap();
        let q = Plane::of_polygon(&[g(0, 0, 5), g(10, 0, 5), g(0, 10, 5)]).unwrap();
        let Split::Both(below, above) =
            rect(0, [0, 0, 10, 10]).split_by_line(&Line::cut(p, q), Boundary::ScreenSplit)
        else {
            panic!("the line y = 5 splits the square");
        };
        let at = |pc: &Piece, x: f64, y: f64| {
            (0..pc.len())
                .find(|&k| pc.vertex_f64(k) == [x, y])
                .expect("a vertex there")
        };
        assert!(below.corner(at(&below, 0.0, 5.0)).is_none());
        // A rectangle to the left with a corner at (0, 5).
        let left = rect(1, [-10, 0, 0, 5]);
        for pieces in [
            vec![below.clone(), above.clone(), left.clone()],
            vec![left.clone(), below.clone(), above.clone()],
        ] {
            let v = shared_vertices(&pieces, &grid_samples());
            let ids: Vec<u32> = pieces
                .iter()
                .enumerate()
                .map(|(i, pc)| v.ids[i][at(pc, 0.0, 5.0)])
                .collect();
            assert!(ids.iter().all(|&id| id == ids[0]), "{ids:?}");
            // So the three merge into one region, with a corner there.
            let corners = [[-10, 0], [10, 0], [10, 10], [0, 10], [0, 5], [-10, 5]];
            assert_eq!(rings(&pieces), region(&[&corners]));
        }
    }

    /// Groups are merged on all cores in runs of about `RUN` pieces: the regions are each
    /// group's merge in group order, whatever the threads, and a group larger than a run
    /// (the left 60 columns of an 80 x 80 grid of squares: 4,800 pieces) stays one region.
    #[test]
    fn regions_merged_on_all_cores_are_each_groups_merge_in_group_order() {
        let side = 80;
        let squares: Vec<[[i64; 2]; 4]> = (0..side * side)
            .map(|i| {
                let (x, y) = (i % side, i / side);
                [[x, y], [x + 1, y], [x + 1, y + 1], [x, y + 1]]
            })
            .collect();
        let screen = crate::visibility::screen_of_polygons(
            (squares.iter()).map(|s| s.iter().map(|&[x, y]| GridPoint { x, y, z: 0 }).collect()),
        );
        let pieces: Vec<Piece> = (squares.iter().enumerate())
            .map(|(i, s)| grid_piece(i as u32, s))
            .collect();
        let vertices = shared_vertices(&pieces, &grid_samples());
        // The rest of the columns in three groups by diagonals: squares meeting at corners.
        let key = |p: &Piece| {
            let (x, y) = (p.poly as i64 % side, p.poly as i64 / side);
            if x < 60 { 0 } else { 1 + (x + y) % 3 }
        };
        let by_group: Vec<Vec<Merged>> = (0..4)
            .map(|k| {
                let members: Vec<usize> = (0..pieces.len())
                    .filter(|&i| key(&pieces[i]) == k)
                    .collect();
                merge(&pieces, &vertices, &members)
            })
            .collect();
        assert_eq!(by_group[0].len(), 1, "the left columns are one region");
        let expected: Vec<super::Rings> =
            (by_group.into_iter().flatten()).map(|m| m.rings).collect();
        assert!(expected.len() > 3, "{} regions", expected.len());
        for threads in [1, 2, 7] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let got: Vec<super::Rings> = pool
                .install(|| regions_of(&pieces, &vertices, &screen, key, None))
                .into_iter()
                .map(|r| r.rings)
                .collect();
            assert!(got == expected, "{threads} threads: other regions");
        }
    }
}
