//! Rasterizing a [`Drawing`] at pixel centres, without anti-aliasing: what a drawing shows, pixel
//! by pixel, to compare with the exact z-buffer.
//!
//! Invariants:
//! - **Sampling**: pixel (i, j) shows what covers its centre (i + 0.5, j + 0.5); nothing else.
//! - **Fill rule**: even-odd over all rings of an item. An edge counts for a row when the row's
//!   centre lies in its half-open span `(y_top, y_bottom]` and a pixel is inside a crossing pair
//!   `[x0, x1)`: the z-buffer's convention (grid y up is pixel y down), so abutting items neither
//!   both cover nor both miss a centre on their shared edge.
//! - **Order**: later items are drawn over earlier ones.
//!
//! Crossings are computed in f64 from the drawing's coordinates: exact decisions are the
//! z-buffer's job; these images are compared with it at interior pixels only, where a rounding
//! at an edge cannot matter.
//!
//! Cost: an active edge table walked row by row (edges bucketed by their first row), so each
//! edge is visited once per row it spans and each covered pixel once per item covering it.

use super::drawing::Drawing;
use crate::scene::FaceId;

/// The face id of the topmost item covering each pixel centre (opaque or not), row-major, row 0
/// at the top; `None` where no item covers.
pub fn face_ids(drawing: &Drawing) -> Vec<Option<FaceId>> {
    let w = drawing.width as usize;
    let mut out = vec![None; w * drawing.height as usize];
    for_each_span(drawing, |j, item, i0, i1| {
        let face = Some(drawing.items[item].face);
        out[j * w + i0..j * w + i1].fill(face);
    });
    out
}

/// The colour of each pixel centre, row-major: items blended back to front over the background
/// (black when `None`) by `new = old·(1 - opacity) + color·opacity`.
pub fn colors(drawing: &Drawing) -> Vec<[f64; 3]> {
    let w = drawing.width as usize;
    let bg = drawing.background.unwrap_or([0.0; 3]);
    let mut out = vec![bg; w * drawing.height as usize];
    for_each_span(drawing, |j, item, i0, i1| {
        let it = &drawing.items[item];
        let a = it.opacity;
        for px in &mut out[j * w + i0..j * w + i1] {
            *px = std::array::from_fn(|k| px[k] * (1.0 - a) + it.color[k] * a);
        }
    });
    out
}

/// One edge of one item, lower end first in pixel rows (y down: `y0 < y1`).
struct Edge {
    item: u32,
    x0: f64,
    y0: f64,
    dxdy: f64,
    /// Rows `first..end` have their centre in `(y0, y1]`.
    first: u32,
    end: u32,
}

/// Calls `span(row, item, i0, i1)` for every run of covered pixels `i0..i1` (non-empty, inside
/// the image), rows in order and, within a row, items in drawing order.
fn for_each_span(drawing: &Drawing, mut span: impl FnMut(usize, usize, usize, usize)) {
    let (w, h) = (drawing.width as f64, drawing.height as usize);
    if h == 0 || drawing.width == 0 {
        return;
    }
    // The edge table, bucketed by first row (a counting sort keeps drawing order in a bucket).
    let mut edges: Vec<Edge> = Vec::new();
    for (k, it) in drawing.items.iter().enumerate() {
        for ring in &it.rings {
            for (n, &a) in ring.iter().enumerate() {
                let b = ring[(n + 1) % ring.len()];
                if a[1] == b[1] {
                    continue; // horizontal: crosses no row centre's half-open span
                }
                let (p, q) = if a[1] < b[1] { (a, b) } else { (b, a) };
                // Centre j + 0.5 in (p.y, q.y]  <=>  p.y - 0.5 < j <= q.y - 0.5.
                let first = ((p[1] - 0.5).floor() + 1.0).clamp(0.0, h as f64) as u32;
                let end = ((q[1] - 0.5).floor() + 1.0).clamp(0.0, h as f64) as u32;
                if first < end {
                    edges.push(Edge {
                        item: k as u32,
                        x0: p[0],
                        y0: p[1],
                        dxdy: (q[0] - p[0]) / (q[1] - p[1]),
                        first,
                        end,
                    });
                }
            }
        }
    }
    let mut bucket_start = vec![0usize; h + 1];
    for e in &edges {
        bucket_start[e.first as usize + 1] += 1;
    }
    for j in 0..h {
        bucket_start[j + 1] += bucket_start[j];
    }
    let mut order = vec![0u32; edges.len()];
    let mut fill = bucket_start.clone();
    for (k, e) in edges.iter().enumerate() {
        order[fill[e.first as usize]] = k as u32;
        fill[e.first as usize] += 1;
    }

    let mut active: Vec<u32> = Vec::new();
    let mut crossings: Vec<(u32, f64)> = Vec::new();
    for j in 0..h {
        active.retain(|&e| edges[e as usize].end as usize > j);
        active.extend_from_slice(&order[bucket_start[j]..bucket_start[j + 1]]);
        if active.is_empty() {
            continue;
        }
        let yc = j as f64 + 0.5;
        crossings.clear();
        crossings.extend(active.iter().map(|&e| {
            let e = &edges[e as usize];
            (e.item, e.x0 + (yc - e.y0) * e.dxdy)
        }));
        crossings.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        for group in crossings.chunk_by(|a, b| a.0 == b.0) {
            for pair in group.chunks_exact(2) {
                // Centre i + 0.5 in [x0, x1)  <=>  x0 - 0.5 <= i < x1 - 0.5.
                let i0 = (pair[0].1 - 0.5).ceil().clamp(0.0, w) as usize;
                let i1 = (pair[1].1 - 0.5).ceil().clamp(0.0, w) as usize;
                if i0 < i1 {
                    span(j, group[0].0 as usize, i0, i1);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::drawing::DrawItem;

    fn item(face: FaceId, rings: Vec<Vec<[f64; 2]>>, color: [f64; 3], opacity: f64) -> DrawItem {
        DrawItem {
            face,
            material: 0,
            rings,
            color,
            opacity,
        }
    }

    #[test]
    fn half_open_rule_at_centres_on_edges() {
        // A square whose edges pass through pixel centres: x in [1.5, 3.5), y in (1.5, 3.5].
        let d = Drawing {
            width: 5,
            height: 5,
            background: None,
            items: vec![item(
                7,
                vec![vec![[1.5, 1.5], [3.5, 1.5], [3.5, 3.5], [1.5, 3.5]]],
                [1.0; 3],
                1.0,
            )],
        };
        let ids = face_ids(&d);
        let covered: Vec<(usize, usize)> = (0..25)
            .filter(|&k| ids[k].is_some())
            .map(|k| (k % 5, k / 5))
            .collect();
        assert_eq!(covered, vec![(1, 2), (2, 2), (1, 3), (2, 3)]);
    }

    #[test]
    fn abutting_items_cover_each_centre_once() {
        // Two triangles sharing a diagonal through pixel centres.
        let a = vec![vec![[0.0, 0.0], [8.0, 0.0], [0.0, 8.0]]];
        let b = vec![vec![[8.0, 0.0], [8.0, 8.0], [0.0, 8.0]]];
        let mk = |rings, c: [f64; 3]| item(0, rings, c, 0.5);
        let d = Drawing {
            width: 8,
            height: 8,
            background: None,
            items: vec![mk(a, [1.0, 0.0, 0.0]), mk(b, [0.0, 1.0, 0.0])],
        };
        // Half opacity each over black: a pixel covered twice would show both colours.
        for c in colors(&d) {
            assert!(c == [0.5, 0.0, 0.0] || c == [0.0, 0.5, 0.0], "{c:?}");
        }
    }

    #[test]
    fn items_outside_the_image_are_clipped() {
        let d = Drawing {
            width: 4,
            height: 3,
            background: Some([0.25; 3]),
            items: vec![item(
                1,
                vec![vec![[-100.0, -50.0], [100.0, -50.0], [100.0, 50.0], [-100.0, 50.0]]],
                [1.0; 3],
                1.0,
            )],
        };
        assert!(face_ids(&d).iter().all(|&f| f == Some(1)));
        assert!(colors(&d).iter().all(|&c| c == [1.0; 3]));
    }
}
