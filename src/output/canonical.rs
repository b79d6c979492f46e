//! The canonical form of a [`Drawing`]: one way of writing a picture, so that two strategies
//! that find the same visible regions write the same bytes.
//!
//! Invariants of a canonical drawing (coordinates are pixels, y down, as everywhere):
//! - **Coordinates**: -0 is +0.
//! - **Ring orientation**: of an item's rings (and of the seams' outline), a ring inside an odd
//!   number of the others is a hole. Outer rings have a positive signed area
//!   `Σ (x_i·y_{i+1} - x_{i+1}·y_i)` computed on the numbers as written, holes a negative one:
//!   counter-clockwise and clockwise in the y-up sense that GeoJSON (RFC 7946's right-hand
//!   rule) and GIS libraries check on the numbers, which is clockwise and counter-clockwise as
//!   seen on a y-down screen. Items are filled even-odd, so orientation never changes the
//!   picture; it tells readers outer boundaries from holes. A ring of no area keeps whichever
//!   direction reads first in the order below.
//! - **Ring start**: every ring starts at its smallest vertex by (y, then x): its top-left
//!   corner on screen (of equal such vertices, the one whose ring then reads first).
//! - **Ring order**: by first vertex (y, then x), an outer ring before a hole starting at the
//!   same point, then by the following vertices. A region's outer ring thus comes before its
//!   holes.
//! - **Item order**: where [`Drawing::opaque_disjoint`] promises that the opaque items before
//!   the first translucent one have disjoint interiors, those items are sorted by face id, then
//!   rings, merged faces, material, colour and opacity. Every other item keeps its place: a
//!   translucent item blends over what is drawn before it, and a painter's items overlap.
//! - **Seams**: each segment runs from its smaller end (y, then x) to the other; a stroke's
//!   segments are sorted, strokes are sorted by colour.
//!
//! Vertices are never added, removed or moved (beyond -0): two drawings of the same regions
//! with different redundant vertices stay different. Containment, and the orientation of a
//! simple ring, are decided exactly on the f64 coordinates (robust predicates); the canonical
//! form never depends on the order, start or direction the rings came in.
//!
//! Sampled at pixel centres ([`super::raster_drawing`]) the picture does not change: orientation
//! and ring order mean nothing to an even-odd fill, and abutting opaque items share no centre.
//! A viewer that anti-aliases blends the edge pixels of two abutting items in the order they
//! are drawn, so sorting them can change those pixels slightly (by a fraction of the colour
//! difference); that order is now the defined one.

use super::drawing::{DrawItem, Drawing, SeamStroke};
use crate::visibility::grid::box_of;
use geo::coordinate_position::{CoordPos, coord_pos_relative_to_ring};
use geo::{Coord, LineString};
use std::cmp::Ordering;

/// Puts `drawing` in its canonical form (see the module docs). The picture does not change.
pub fn canonicalize(drawing: &mut Drawing) {
    // Item by item and stroke by stroke on all cores; the sorts are stable, so their order is
    // the sequential sorts' whatever the thread count.
    use rayon::prelude::*;
    (drawing.items.par_iter_mut()).for_each(|item| canonical_rings(&mut item.rings));
    if drawing.opaque_disjoint {
        // NaN opacity counts as translucent: it keeps its place.
        let opaque = drawing
            .items
            .iter()
            .position(|it| it.opacity.is_nan() || it.opacity < 1.0)
            .unwrap_or(drawing.items.len());
        drawing.items[..opaque].par_sort_by(cmp_items);
    }
    canonical_rings(&mut drawing.seams.outline);
    (drawing.seams.strokes.par_iter_mut()).for_each(|stroke| {
        for seg in &mut stroke.segments {
            *seg = seg.map(|p| p.map(|v| v + 0.0));
            if cmp_points(&seg[1], &seg[0]).is_lt() {
                seg.swap(0, 1);
            }
        }
        stroke.segments.par_sort_by(cmp_segments);
    });
    drawing.seams.strokes.sort_by(cmp_strokes);
}

/// Puts an even-odd ring set in canonical form: orientation by hole parity, start, order.
fn canonical_rings(rings: &mut [Vec<[f64; 2]>]) {
    // First a form that does not depend on how each ring came in (start at the top-left vertex,
    // positive area), so that the hole test, and so the result, does not either.
    for ring in rings.iter_mut() {
        for p in ring.iter_mut() {
            *p = p.map(|v| v + 0.0);
        }
        orient(ring, true);
    }
    // One ring (most regions) holds no hole and is in order: nothing more to find or allocate.
    if rings.len() < 2 {
        return;
    }
    let holes = holes(rings);
    for (ring, &hole) in rings.iter_mut().zip(&holes) {
        if hole {
            orient(ring, false);
        }
    }
    let mut keyed: Vec<(bool, Vec<[f64; 2]>)> = holes
        .into_iter()
        .zip(rings.iter_mut().map(std::mem::take))
        .collect();
    keyed.sort_by(|(ha, a), (hb, b)| {
        cmp_points_at(a, b, 0)
            .then_with(|| ha.cmp(hb))
            .then_with(|| cmp_rings(a, b))
    });
    for (slot, (_, ring)) in rings.iter_mut().zip(keyed) {
        *slot = ring;
    }
}

/// Orients `ring` (positive signed area when `outer`, negative otherwise) and rotates it to
/// start at its smallest vertex; a ring of no area takes whichever direction reads first.
fn orient(ring: &mut Vec<[f64; 2]>, outer: bool) {
    if ring.len() < 2 {
        return;
    }
    match signed_area_sign(ring) {
        Ordering::Equal => {
            let forward = smallest_rotation(ring);
            ring.reverse();
            let backward = smallest_rotation(ring);
            *ring = first_of(forward, backward);
            return;
        }
        sign => {
            if sign.is_gt() != outer {
                ring.reverse();
            }
        }
    }
    *ring = smallest_rotation(ring);
}

/// The one of two rings that reads first ([`cmp_rings`]), `a` when equal.
fn first_of(a: Vec<[f64; 2]>, b: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    if cmp_rings(&b, &a).is_lt() { b } else { a }
}

/// The rotation of `ring` that starts at its smallest vertex (y, then x); of several equal
/// smallest vertices, the rotation that reads first.
fn smallest_rotation(ring: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let Some(min) = ring.iter().min_by(|a, b| cmp_points(a, b)) else {
        return Vec::new();
    };
    let rotated =
        |k: usize| -> Vec<[f64; 2]> { ring[k..].iter().chain(&ring[..k]).copied().collect() };
    (0..ring.len())
        .filter(|&k| cmp_points(&ring[k], min).is_eq())
        .map(rotated)
        .reduce(first_of)
        .unwrap_or_default()
}

/// The sign of the ring's signed area `Σ (x_i·y_{i+1} - x_{i+1}·y_i)`. Exact for a simple
/// ring: the turn at its smallest vertex (y, then x), a corner of its convex hull, by the
/// robust orientation predicate. Where that turn says nothing (a spike there, or a ring passing
/// twice through it), the positive and the negative terms are summed apart, each in a fixed
/// order, and compared: not exact, but the same whatever the ring's start and direction.
fn signed_area_sign(ring: &[[f64; 2]]) -> Ordering {
    let n = ring.len();
    let Some(v) = ring.iter().copied().min_by(cmp_points) else {
        return Ordering::Equal;
    };
    // Where a run of (repeated) copies of the smallest vertex begins.
    let runs: Vec<usize> = (0..n)
        .filter(|&k| ring[k] == v && ring[(k + n - 1) % n] != v)
        .collect();
    if let [k] = runs[..] {
        let prev = ring[(k + n - 1) % n];
        let next = (1..n).map(|d| ring[(k + d) % n]).find(|p| *p != v);
        let c = |p: [f64; 2]| robust::Coord { x: p[0], y: p[1] };
        if let Some(next) = next {
            let turn = robust::orient2d(c(prev), c(v), c(next));
            if turn != 0.0 {
                return turn.total_cmp(&0.0);
            }
        }
    }
    // Reversing the ring negates every term exactly, so the two sums swap.
    let (pos, neg): (Vec<f64>, Vec<f64>) = (0..n)
        .map(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .partition(|t| *t > 0.0);
    let sum = |terms: Vec<f64>| {
        let mut m: Vec<f64> = terms.into_iter().map(f64::abs).collect();
        m.sort_by(f64::total_cmp);
        // From +0: an empty sum is +0 (`Sum` starts at -0).
        m.iter().fold(0.0, |a, b| a + b)
    };
    sum(pos).total_cmp(&sum(neg))
}

/// Per ring, whether it is a hole: whether it lies inside an odd number of the other rings.
fn holes(rings: &[Vec<[f64; 2]>]) -> Vec<bool> {
    holders(rings).iter().map(|h| h.len() % 2 == 1).collect()
}

/// An item's rings (of a canonical, or any non-crossing, ring set) as regions: per outer
/// boundary, its index then those of the holes directly inside it. A hole belongs to the
/// innermost ring holding it; an outer ring inside a hole (an island) is a region of its own.
pub fn regions_of_rings(rings: &[Vec<[f64; 2]>]) -> Vec<Vec<usize>> {
    let holders = holders(rings);
    let mut regions: Vec<Vec<usize>> = Vec::new();
    let mut region_of = vec![usize::MAX; rings.len()];
    for (i, h) in holders.iter().enumerate() {
        if h.len() % 2 == 0 {
            region_of[i] = regions.len();
            regions.push(vec![i]);
        }
    }
    for (i, h) in holders.iter().enumerate() {
        if h.len() % 2 == 1 {
            // The innermost holder is the one that is itself held by all the others.
            let parent = *h
                .iter()
                .find(|&&j| holders[j].len() == h.len() - 1)
                .expect("a hole lies inside its outer ring");
            regions[region_of[parent]].push(i);
        }
    }
    regions
}

/// Per ring, the other rings it lies inside.
fn holders(rings: &[Vec<[f64; 2]>]) -> Vec<Vec<usize>> {
    if rings.len() < 2 {
        return vec![Vec::new(); rings.len()];
    }
    let boxes: Vec<[f64; 4]> = rings.iter().map(|r| box_of(r)).collect();
    let mut closed: Vec<Option<LineString<f64>>> = vec![None; rings.len()];
    (0..rings.len())
        .map(|i| {
            let mut inside_of = Vec::new();
            for j in 0..rings.len() {
                let (a, b) = (boxes[i], boxes[j]);
                // Only a ring whose box holds this one's box can hold the ring.
                let boxed = b[0] <= a[0] && b[1] <= a[1] && a[2] <= b[2] && a[3] <= b[3];
                if i != j && boxed {
                    let outer = closed[j].get_or_insert_with(|| closed_ring(&rings[j]));
                    if inside(&rings[i], outer) {
                        inside_of.push(j);
                    }
                }
            }
            inside_of
        })
        .collect()
}

/// Is `ring` inside `outer`? Rings of one item do not cross, so the first of its vertices (then
/// edge midpoints) that is not on `outer` decides; a ring lying wholly on `outer` is not inside.
fn inside(ring: &[[f64; 2]], outer: &LineString<f64>) -> bool {
    let n = ring.len();
    let midpoints = (0..n).map(|i| {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0]
    });
    ring.iter()
        .copied()
        .chain(midpoints)
        .map(|p| coord_pos_relative_to_ring(Coord { x: p[0], y: p[1] }, outer))
        .find(|pos| *pos != CoordPos::OnBoundary)
        == Some(CoordPos::Inside)
}

/// `ring` as a closed geo line string (first point repeated at the end).
fn closed_ring(ring: &[[f64; 2]]) -> LineString<f64> {
    let mut coords: Vec<Coord<f64>> = ring.iter().map(|p| Coord { x: p[0], y: p[1] }).collect();
    if let Some(&first) = coords.first() {
        coords.push(first);
    }
    LineString(coords)
}

/// Points by y, then x (top to bottom, then left to right on screen).
fn cmp_points(a: &[f64; 2], b: &[f64; 2]) -> Ordering {
    a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0]))
}

/// The `k`-th points of two rings ([`cmp_points`]), a missing point first.
fn cmp_points_at(a: &[[f64; 2]], b: &[[f64; 2]], k: usize) -> Ordering {
    match (a.get(k), b.get(k)) {
        (Some(p), Some(q)) => cmp_points(p, q),
        (p, q) => p.is_some().cmp(&q.is_some()),
    }
}

/// Sequences element by element, a prefix of the other first.
fn cmp_seq<T>(a: &[T], b: &[T], cmp: impl Fn(&T, &T) -> Ordering) -> Ordering {
    a.iter()
        .zip(b)
        .map(|(p, q)| cmp(p, q))
        .find(|o| o.is_ne())
        .unwrap_or(a.len().cmp(&b.len()))
}

/// Rings point by point ([`cmp_points`]).
fn cmp_rings(a: &[[f64; 2]], b: &[[f64; 2]]) -> Ordering {
    cmp_seq(a, b, cmp_points)
}

/// Colours component by component.
fn cmp_colors(a: &[f64; 3], b: &[f64; 3]) -> Ordering {
    cmp_seq(a, b, f64::total_cmp)
}

/// Items by face id, then rings, merged faces, material, colour, opacity.
fn cmp_items(a: &DrawItem, b: &DrawItem) -> Ordering {
    a.face
        .cmp(&b.face)
        .then_with(|| cmp_seq(&a.rings, &b.rings, |p, q| cmp_rings(p, q)))
        .then_with(|| a.merged.cmp(&b.merged))
        .then(a.material.cmp(&b.material))
        .then_with(|| cmp_colors(&a.color, &b.color))
        .then(a.opacity.total_cmp(&b.opacity))
}

/// Segments by their first end, then their second ([`cmp_points`]).
fn cmp_segments(a: &[[f64; 2]; 2], b: &[[f64; 2]; 2]) -> Ordering {
    cmp_rings(a, b)
}

/// Strokes by colour, then segments.
fn cmp_strokes(a: &SeamStroke, b: &SeamStroke) -> Ordering {
    cmp_colors(&a.color, &b.color).then_with(|| cmp_seq(&a.segments, &b.segments, cmp_segments))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hole goes with the ring directly around it; an island in a hole is a region of its
    /// own, and so is a second outer ring with its own hole.
    #[test]
    fn regions_of_rings_give_each_outer_ring_its_own_holes() {
        let rings = vec![
            rect(0.0, 0.0, 10.0, 10.0),
            rect(20.0, 0.0, 30.0, 10.0),
            rect(2.0, 2.0, 8.0, 8.0),
            rect(22.0, 2.0, 24.0, 4.0),
            rect(4.0, 4.0, 6.0, 6.0),
        ];
        assert_eq!(
            regions_of_rings(&rings),
            vec![vec![0, 2], vec![1, 3], vec![4]]
        );
        assert_eq!(holes(&rings), vec![false, false, true, true, false]);
        assert_eq!(regions_of_rings(&rings[..1]), vec![vec![0]]);
    }
    use crate::output::drawing::Seams;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<[f64; 2]> {
        vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
    }

    /// Twice the signed area on the numbers as written.
    fn twice_area(ring: &[[f64; 2]]) -> f64 {
        let n = ring.len();
        (0..n)
            .map(|i| ring[i][0] * ring[(i + 1) % n][1] - ring[(i + 1) % n][0] * ring[i][1])
            .sum()
    }

    fn rotated(ring: &[[f64; 2]], k: usize) -> Vec<[f64; 2]> {
        let k = k % ring.len();
        ring[k..].iter().chain(&ring[..k]).copied().collect()
    }

    fn reversed(ring: &[[f64; 2]]) -> Vec<[f64; 2]> {
        ring.iter().rev().copied().collect()
    }

    fn drawing(items: Vec<DrawItem>, opaque_disjoint: bool) -> Drawing {
        Drawing {
            width: 40,
            height: 30,
            background: Some([1.0; 3]),
            items,
            seams: Seams::default(),
            opaque_disjoint,
        }
    }

    fn canonical(mut d: Drawing) -> Drawing {
        canonicalize(&mut d);
        d
    }

    /// A square with a square hole holding an island (a hole of the hole), and a triangle.
    fn nested() -> Vec<Vec<[f64; 2]>> {
        vec![
            rect(0.0, 0.0, 20.0, 20.0),
            rect(4.0, 4.0, 16.0, 16.0),
            rect(8.0, 8.0, 12.0, 12.0),
            vec![[30.0, 2.0], [38.0, 10.0], [25.0, 9.5]],
        ]
    }

    #[test]
    fn rotating_reversing_and_shuffling_rings_give_the_same_canonical_item() {
        let want = canonical(drawing(
            vec![DrawItem::new(1, nested(), [0.5; 3], 1.0)],
            true,
        ));
        for variant in 0..8 {
            let mut rings: Vec<Vec<[f64; 2]>> = nested()
                .iter()
                .enumerate()
                .map(|(k, r)| {
                    let r = rotated(r, k + variant);
                    if (k + variant) % 2 == 0 {
                        reversed(&r)
                    } else {
                        r
                    }
                })
                .collect();
            let n = rings.len();
            rings.rotate_left(variant % n);
            if variant >= 4 {
                rings.reverse();
            }
            let got = canonical(drawing(vec![DrawItem::new(1, rings, [0.5; 3], 1.0)], true));
            assert_eq!(got, want, "variant {variant}");
        }
    }

    #[test]
    fn holes_run_the_other_way_and_rings_start_top_left() {
        let d = canonical(drawing(
            vec![DrawItem::new(1, nested(), [0.5; 3], 1.0)],
            true,
        ));
        let rings = &d.items[0].rings;
        // By first vertex (y, x): the square (0,0), the triangle (30,2), the hole (4,4), the
        // island (8,8).
        let starts: Vec<[f64; 2]> = rings.iter().map(|r| r[0]).collect();
        assert_eq!(starts, [[0.0, 0.0], [30.0, 2.0], [4.0, 4.0], [8.0, 8.0]]);
        let outer: Vec<bool> = rings.iter().map(|r| twice_area(r) > 0.0).collect();
        assert_eq!(
            outer,
            [true, true, false, true],
            "the hole alone is negative"
        );
        // Positive area with y down: clockwise on screen, the top-left corner then the right.
        assert_eq!(rings[0][1], [20.0, 0.0]);
        assert_eq!(rings[2][1], [4.0, 16.0]);
    }

    #[test]
    fn a_hole_touching_its_outer_ring_is_still_a_hole_and_outer_comes_first() {
        // A notch hole sharing the outer ring's top-left corner.
        let rings = vec![rect(2.0, 2.0, 4.0, 4.0), rect(2.0, 2.0, 10.0, 10.0)];
        let d = canonical(drawing(vec![DrawItem::new(1, rings, [0.5; 3], 1.0)], true));
        let rings = &d.items[0].rings;
        assert_eq!(rings[0], rect(2.0, 2.0, 10.0, 10.0));
        assert!(twice_area(&rings[1]) < 0.0);
    }

    /// Disjoint opaque items, then two translucent ones and an opaque one after them.
    fn layered() -> Vec<DrawItem> {
        vec![
            DrawItem::new(7, vec![rect(0.0, 0.0, 5.0, 5.0)], [1.0, 0.0, 0.0], 1.0),
            DrawItem::new(2, vec![rect(5.0, 0.0, 9.0, 5.0)], [0.0, 1.0, 0.0], 1.0),
            DrawItem::new(2, vec![rect(0.0, 5.0, 9.0, 8.0)], [0.0, 1.0, 0.0], 1.0),
            DrawItem::new(4, vec![rect(0.0, 0.0, 9.0, 9.0)], [0.0, 0.0, 1.0], 1.0),
            DrawItem::new(9, vec![rect(1.0, 1.0, 3.0, 3.0)], [0.2; 3], 0.5),
            DrawItem::new(1, vec![rect(2.0, 2.0, 4.0, 4.0)], [0.8; 3], 0.5),
            DrawItem::new(0, vec![rect(2.0, 0.0, 4.0, 9.0)], [0.1; 3], 1.0),
        ]
    }

    #[test]
    fn disjoint_opaque_items_sort_by_face_and_translucent_ones_keep_their_order() {
        let mut items = layered();
        // Drop the overlapping opaque item 4: the others are disjoint.
        items.remove(3);
        let want = canonical(drawing(items.clone(), true));
        let faces: Vec<u32> = want.items.iter().map(|it| it.face).collect();
        assert_eq!(faces, [2, 2, 7, 9, 1, 0], "face 2's regions top to bottom");
        assert_eq!(want.items[0].rings[0][0], [5.0, 0.0]);
        for shuffle in [[2, 0, 1], [1, 2, 0], [2, 1, 0]] {
            let mut shuffled: Vec<DrawItem> = shuffle.iter().map(|&k| items[k].clone()).collect();
            shuffled.extend(items[3..].iter().cloned());
            assert_eq!(canonical(drawing(shuffled, true)), want, "{shuffle:?}");
        }
    }

    #[test]
    fn painter_drawings_keep_their_order() {
        let d = canonical(drawing(layered(), false));
        let faces: Vec<u32> = d.items.iter().map(|it| it.face).collect();
        assert_eq!(faces, [7, 2, 2, 4, 9, 1, 0]);
    }

    #[test]
    fn the_picture_does_not_change() {
        let mut items = layered();
        items.remove(3);
        let mut d = drawing(items, true);
        for it in &mut d.items {
            it.rings = it.rings.iter().map(|r| reversed(&rotated(r, 1))).collect();
        }
        d.items.swap(0, 2);
        let before = crate::output::raster_drawing::colors(&d);
        let after = crate::output::raster_drawing::colors(&canonical(d.clone()));
        assert_eq!(before, after);
        assert_ne!(canonical(d.clone()), d, "the test changes something");
    }

    #[test]
    fn seams_run_from_their_top_left_end_in_order() {
        let seg = |a: [f64; 2], b: [f64; 2]| [a, b];
        let stroke = |color: [f64; 3], segments| SeamStroke { color, segments };
        let mut d = drawing(Vec::new(), true);
        d.seams = Seams {
            outline: vec![reversed(&rotated(&rect(0.0, 0.0, 9.0, 9.0), 2))],
            strokes: vec![
                stroke(
                    [0.5; 3],
                    vec![seg([3.0, 4.0], [3.0, 1.0]), seg([0.0, 2.0], [-0.0, 0.0])],
                ),
                stroke([0.1; 3], vec![seg([9.0, 0.0], [1.0, 0.0])]),
            ],
        };
        let d = canonical(d);
        assert_eq!(d.seams.outline, vec![rect(0.0, 0.0, 9.0, 9.0)]);
        assert_eq!(
            d.seams.strokes,
            vec![
                stroke([0.1; 3], vec![seg([1.0, 0.0], [9.0, 0.0])]),
                stroke(
                    [0.5; 3],
                    vec![seg([0.0, 0.0], [0.0, 2.0]), seg([3.0, 1.0], [3.0, 4.0])]
                ),
            ]
        );
        assert!(
            d.seams.strokes[1].segments[0][0][0].is_sign_positive(),
            "-0 is 0"
        );
    }

    #[test]
    fn canonicalizing_twice_changes_nothing_and_spikes_are_defined() {
        // A ring of no area (a spike) and a ring with its top-left vertex twice.
        let spike = vec![[1.0, 1.0], [5.0, 5.0], [3.0, 3.0]];
        let twice = vec![
            [0.0, 0.0],
            [4.0, 0.0],
            [2.0, 2.0],
            [0.0, 0.0],
            [1.0, 3.0],
            [-1.0, 3.0],
        ];
        for ring in [spike, twice] {
            let once = canonical(drawing(
                vec![DrawItem::new(1, vec![ring.clone()], [0.5; 3], 1.0)],
                true,
            ));
            assert_eq!(canonical(once.clone()), once);
            for k in 0..ring.len() {
                for r in [rotated(&ring, k), reversed(&rotated(&ring, k))] {
                    let d = drawing(vec![DrawItem::new(1, vec![r], [0.5; 3], 1.0)], true);
                    assert_eq!(canonical(d), once, "{ring:?} from {k}");
                }
            }
        }
    }
}
