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
//! Cost: each item is scan-converted on its own, with its own small active edge table (its edges
//! sorted by first row), so an edge is visited once per row it spans and no item is tested at
//! pixels outside its rows. [`colors`] touches each pixel once per item covering it (blending
//! needs every layer); [`face_ids`] walks items front to back and writes each pixel once.

use super::drawing::Drawing;
use crate::scene::FaceId;

/// The face id of the topmost item covering each pixel centre (opaque or not), row-major, row 0
/// at the top; `None` where no item covers.
pub fn face_ids(drawing: &Drawing) -> Vec<Option<FaceId>> {
    let (w, h) = (drawing.width as usize, drawing.height as usize);
    let mut out = vec![None; w * h];
    // Only the topmost item counts, so items are taken front to back and every pixel is written
    // once: in each row, `next[i]` leads to the first pixel at or after i not yet written (a
    // path-compressed skip list), so deep stacks of items cost per span, not per pixel.
    let mut next: Vec<u32> = (0..h).flat_map(|_| 0..=w as u32).collect();
    let mut spans = Spans::default();
    for (k, it) in drawing.items.iter().enumerate().rev() {
        let face = Some(it.face);
        spans.for_each(drawing, k, |j, i0, i1| {
            let row = &mut next[j * (w + 1)..(j + 1) * (w + 1)];
            let mut i = find(row, i0);
            while i < i1 {
                out[j * w + i] = face;
                row[i] = (i + 1) as u32;
                i = find(row, i + 1);
            }
        });
    }
    out
}

/// The first unwritten pixel at or after `i`, compressing the path behind it.
fn find(next: &mut [u32], i: usize) -> usize {
    let mut root = i;
    while next[root] as usize != root {
        root = next[root] as usize;
    }
    let mut k = i;
    while k != root {
        let n = next[k] as usize;
        next[k] = root as u32;
        k = n;
    }
    root
}

/// The colour of each pixel centre, row-major: items blended back to front over the background
/// (black when `None`) by `new = old·(1 - opacity) + color·opacity`.
pub fn colors(drawing: &Drawing) -> Vec<[f64; 3]> {
    let w = drawing.width as usize;
    let bg = drawing.background.unwrap_or([0.0; 3]);
    let mut out = vec![bg; w * drawing.height as usize];
    let mut spans = Spans::default();
    for (k, it) in drawing.items.iter().enumerate() {
        let a = it.opacity;
        spans.for_each(drawing, k, |j, i0, i1| {
            for px in &mut out[j * w + i0..j * w + i1] {
                *px = std::array::from_fn(|c| px[c] * (1.0 - a) + it.color[c] * a);
            }
        });
    }
    out
}

/// One edge of an item, upper end first in pixel rows (y down: `y0 < y1`).
struct Edge {
    x0: f64,
    y0: f64,
    dxdy: f64,
    /// Rows `first..end` have their centre in `(y0, y1]`.
    first: u32,
    end: u32,
}

/// Scratch space for scan-converting one item at a time (its own small active edge table).
#[derive(Default)]
struct Spans {
    edges: Vec<Edge>,
    active: Vec<u32>,
    crossings: Vec<f64>,
}

impl Spans {
    /// Calls `span(row, i0, i1)` for every run of pixels `i0..i1` (non-empty, inside the image)
    /// whose centres item `k` covers, rows in order.
    fn for_each(&mut self, drawing: &Drawing, k: usize, mut span: impl FnMut(usize, usize, usize)) {
        let (w, h) = (drawing.width as f64, drawing.height as f64);
        self.edges.clear();
        for ring in &drawing.items[k].rings {
            for (n, &a) in ring.iter().enumerate() {
                let b = ring[(n + 1) % ring.len()];
                if a[1] == b[1] {
                    continue; // horizontal: crosses no row centre's half-open span
                }
                let (p, q) = if a[1] < b[1] { (a, b) } else { (b, a) };
                // Centre j + 0.5 in (p.y, q.y]  <=>  p.y - 0.5 < j <= q.y - 0.5.
                let first = ((p[1] - 0.5).floor() + 1.0).clamp(0.0, h) as u32;
                let end = ((q[1] - 0.5).floor() + 1.0).clamp(0.0, h) as u32;
                if first < end {
                    self.edges.push(Edge {
                        x0: p[0],
                        y0: p[1],
                        dxdy: (q[0] - p[0]) / (q[1] - p[1]),
                        first,
                        end,
                    });
                }
            }
        }
        if self.edges.is_empty() {
            return;
        }
        self.edges.sort_unstable_by_key(|e| e.first);
        let last = self.edges.iter().map(|e| e.end).max().unwrap_or(0);
        self.active.clear();
        let mut pending = 0;
        for j in self.edges[0].first..last {
            let edges = &self.edges;
            self.active.retain(|&e| edges[e as usize].end > j);
            while pending < edges.len() && edges[pending].first == j {
                self.active.push(pending as u32);
                pending += 1;
            }
            let yc = j as f64 + 0.5;
            self.crossings.clear();
            self.crossings.extend(self.active.iter().map(|&e| {
                let e = &edges[e as usize];
                e.x0 + (yc - e.y0) * e.dxdy
            }));
            self.crossings.sort_unstable_by(f64::total_cmp);
            for pair in self.crossings.chunks_exact(2) {
                // Centre i + 0.5 in [x0, x1)  <=>  x0 - 0.5 <= i < x1 - 0.5.
                let i0 = (pair[0] - 0.5).ceil().clamp(0.0, w) as usize;
                let i1 = (pair[1] - 0.5).ceil().clamp(0.0, w) as usize;
                if i0 < i1 {
                    span(j as usize, i0, i1);
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
            merged: Vec::new(),
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
            seams: Default::default(),
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
            seams: Default::default(),
        };
        // Half opacity each over black: a pixel covered twice would show both colours.
        for c in colors(&d) {
            assert!(c == [0.5, 0.0, 0.0] || c == [0.0, 0.5, 0.0], "{c:?}");
        }
    }

    /// Per pixel, per item: is the centre inside (even-odd, the same half-open conventions)?
    fn inside(rings: &[Vec<[f64; 2]>], x: f64, y: f64) -> bool {
        let mut odd = false;
        for r in rings {
            for n in 0..r.len() {
                let (a, b) = (r[n], r[(n + 1) % r.len()]);
                let (p, q) = if a[1] < b[1] { (a, b) } else { (b, a) };
                if p[1] < y && y <= q[1] {
                    let xc = p[0] + (y - p[1]) * ((q[0] - p[0]) / (q[1] - p[1]));
                    if xc <= x {
                        odd = !odd;
                    }
                }
            }
        }
        odd
    }

    #[test]
    fn front_to_back_skip_lists_agree_with_a_per_pixel_test() {
        let mut seed = 7u64;
        let mut rnd = |lo: f64, hi: f64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            lo + (hi - lo) * (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (w, h) = (37, 29);
        let items: Vec<DrawItem> = (0..300)
            .map(|k| {
                let rings = (0..1 + k % 2)
                    .map(|_| {
                        let (cx, cy) = (rnd(-5.0, 42.0), rnd(-5.0, 34.0));
                        (0..3 + k % 4)
                            .map(|_| [cx + rnd(-9.0, 9.0), cy + rnd(-9.0, 9.0)])
                            .collect()
                    })
                    .collect();
                item(k as FaceId, rings, [rnd(0.0, 1.0); 3], rnd(0.0, 1.0))
            })
            .collect();
        let d = Drawing {
            width: w,
            height: h,
            background: Some([0.5, 0.25, 1.0]),
            items,
            seams: Default::default(),
        };
        let ids = face_ids(&d);
        let cols = colors(&d);
        for j in 0..h as usize {
            for i in 0..w as usize {
                let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
                let covering: Vec<&DrawItem> = d
                    .items
                    .iter()
                    .filter(|it| inside(&it.rings, x, y))
                    .collect();
                assert_eq!(ids[j * w as usize + i], covering.last().map(|it| it.face));
                let mut c = d.background.unwrap();
                for it in covering {
                    c = std::array::from_fn(|k| {
                        c[k] * (1.0 - it.opacity) + it.color[k] * it.opacity
                    });
                }
                assert_eq!(cols[j * w as usize + i], c);
            }
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
                vec![vec![
                    [-100.0, -50.0],
                    [100.0, -50.0],
                    [100.0, 50.0],
                    [-100.0, 50.0],
                ]],
                [1.0; 3],
                1.0,
            )],
            seams: Default::default(),
        };
        assert!(face_ids(&d).iter().all(|&f| f == Some(1)));
        assert!(colors(&d).iter().all(|&c| c == [1.0; 3]));
    }
}
