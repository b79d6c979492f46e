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
//!
//! Memory: rows are rasterized in strips of about `STRIP_PIXELS` pixels ([`color_strips`],
//! [`face_id_strips`]; an item is scan-converted once per strip it meets), so [`write_png`]
//! needs a strip's buffers and the drawing, never a buffer per pixel of the image. Strips do not
//! change a pixel: an edge's crossing with a row is computed from the edge alone.

use super::drawing::Drawing;
use crate::scene::FaceId;
use std::io::{self, Write};

/// Pixels per strip: rows are rasterized in strips of about this many pixels, so the memory of
/// a rasterization is a strip's, not the image's (at least one row per strip).
const STRIP_PIXELS: usize = 1 << 18;

/// Rows per strip for an image `width` pixels wide.
pub fn strip_rows(width: u32) -> usize {
    (STRIP_PIXELS / width.max(1) as usize).max(1)
}

/// Writes the drawing's [`colors`] as an 8-bit RGB PNG into `out`, strip by strip: memory per
/// strip, whatever the image size.
pub fn write_png(drawing: &Drawing, out: &mut dyn Write) -> io::Result<()> {
    let mut px = Vec::new();
    super::png::write_rgb_rows(out, drawing.width, drawing.height, |sink| {
        color_strips(drawing, strip_rows(drawing.width), |_, strip| {
            px.clear();
            px.extend(strip.iter().map(|&c| crate::paint::to_u8(c)));
            sink(&px)
        })
    })
}

/// The face id of the topmost item covering each pixel centre (opaque or not), row-major, row 0
/// at the top; `None` where no item covers.
pub fn face_ids(drawing: &Drawing) -> Vec<Option<FaceId>> {
    let mut out = Vec::with_capacity(drawing.width as usize * drawing.height as usize);
    let rows = strip_rows(drawing.width);
    face_id_strips(drawing, rows, |_, strip| {
        out.extend_from_slice(strip);
        Ok::<(), std::convert::Infallible>(())
    })
    .unwrap_or_else(|never| match never {});
    out
}

/// [`face_ids`] by strips of `rows` rows: calls `strip(first_row, ids)` for each strip, top to
/// bottom (`ids` row-major), stopping at the first error.
pub fn face_id_strips<E>(
    drawing: &Drawing,
    rows: usize,
    mut strip: impl FnMut(usize, &[Option<FaceId>]) -> Result<(), E>,
) -> Result<(), E> {
    let (w, rows) = (drawing.width as usize, rows.max(1));
    let mut out = Vec::new();
    let mut next = Vec::new();
    let mut spans = Spans::default();
    let mut bands = Bands::new(drawing, rows);
    while let Some((r0, r1, items)) = bands.next_band() {
        out.clear();
        out.resize((r1 - r0) * w, None);
        // Only the topmost item counts, so items are taken front to back and every pixel is
        // written once: in each row, `next[i]` leads to the first pixel at or after i not yet
        // written (a path-compressed skip list), so deep stacks of items cost per span, not per
        // pixel.
        next.clear();
        next.extend((r0..r1).flat_map(|_| 0..=w as u32));
        for &k in items.iter().rev() {
            let face = Some(drawing.items[k as usize].face);
            spans.for_each(drawing, k as usize, r0..r1, |j, i0, i1| {
                let j = j - r0;
                let row = &mut next[j * (w + 1)..(j + 1) * (w + 1)];
                let mut i = find(row, i0);
                while i < i1 {
                    out[j * w + i] = face;
                    row[i] = (i + 1) as u32;
                    i = find(row, i + 1);
                }
            });
        }
        strip(r0, &out)?;
    }
    Ok(())
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
    let mut out = Vec::with_capacity(drawing.width as usize * drawing.height as usize);
    let rows = strip_rows(drawing.width);
    color_strips(drawing, rows, |_, strip| {
        out.extend_from_slice(strip);
        Ok::<(), std::convert::Infallible>(())
    })
    .unwrap_or_else(|never| match never {});
    out
}

/// [`colors`] by strips of `rows` rows: calls `strip(first_row, colors)` for each strip, top to
/// bottom (`colors` row-major), stopping at the first error.
pub fn color_strips<E>(
    drawing: &Drawing,
    rows: usize,
    mut strip: impl FnMut(usize, &[[f64; 3]]) -> Result<(), E>,
) -> Result<(), E> {
    let (w, rows) = (drawing.width as usize, rows.max(1));
    let bg = drawing.background.unwrap_or([0.0; 3]);
    let mut out = Vec::new();
    let mut spans = Spans::default();
    let mut bands = Bands::new(drawing, rows);
    while let Some((r0, r1, items)) = bands.next_band() {
        out.clear();
        out.resize((r1 - r0) * w, bg);
        for &k in items {
            let it = &drawing.items[k as usize];
            let a = it.opacity;
            spans.for_each(drawing, k as usize, r0..r1, |j, i0, i1| {
                let j = j - r0;
                for px in &mut out[j * w + i0..j * w + i1] {
                    *px = std::array::from_fn(|c| px[c] * (1.0 - a) + it.color[c] * a);
                }
            });
        }
        strip(r0, &out)?;
    }
    Ok(())
}

/// The image's rows cut into strips, each with the items whose rows meet it, in drawing order:
/// an item is visited once per strip it spans, never for strips it misses.
struct Bands {
    height: usize,
    rows: usize,
    /// First row of the next strip.
    r0: usize,
    /// Per item: the rows its centres may cover, `first..end`.
    span: Vec<(u32, u32)>,
    /// Items by the strip of their first row, each list in drawing order.
    starting: Vec<Vec<u32>>,
    /// Items meeting the current strip, in drawing order.
    active: Vec<u32>,
    merged: Vec<u32>,
}

impl Bands {
    fn new(drawing: &Drawing, rows: usize) -> Self {
        let height = drawing.height as usize;
        let strips = height.div_ceil(rows);
        let mut starting = vec![Vec::new(); strips];
        let span: Vec<(u32, u32)> = drawing
            .items
            .iter()
            .map(|it| {
                let ys = it.rings.iter().flatten().map(|p| p[1]);
                let lo = ys.clone().fold(f64::INFINITY, f64::min);
                let hi = ys.fold(f64::NEG_INFINITY, f64::max);
                // The rows of `Spans::for_each`'s edges lie within these (same formula).
                row_range(lo, hi, height)
            })
            .collect();
        for (k, &(first, end)) in span.iter().enumerate() {
            if first < end {
                starting[first as usize / rows].push(k as u32);
            }
        }
        Bands {
            height,
            rows,
            r0: 0,
            span,
            starting,
            active: Vec::new(),
            merged: Vec::new(),
        }
    }

    /// The next strip's rows `r0..r1` and the items meeting it, in drawing order.
    fn next_band(&mut self) -> Option<(usize, usize, &[u32])> {
        let r0 = self.r0;
        if r0 >= self.height {
            return None;
        }
        let r1 = (r0 + self.rows).min(self.height);
        self.r0 = r1;
        let span = &self.span;
        self.active.retain(|&k| span[k as usize].1 as usize > r0);
        // Merge the items starting here into the active ones, both in drawing order.
        let new = std::mem::take(&mut self.starting[r0 / self.rows]);
        self.merged.clear();
        let (mut a, mut b) = (self.active.iter().peekable(), new.iter().peekable());
        while let (Some(&&x), Some(&&y)) = (a.peek(), b.peek()) {
            if x < y {
                self.merged.push(x);
                a.next();
            } else {
                self.merged.push(y);
                b.next();
            }
        }
        self.merged.extend(a);
        self.merged.extend(b);
        std::mem::swap(&mut self.active, &mut self.merged);
        Some((r0, r1, &self.active))
    }
}

/// The rows `first..end` (clamped to `0..height`) whose centre `j + 0.5` lies in `(lo, hi]`.
fn row_range(lo: f64, hi: f64, height: usize) -> (u32, u32) {
    // Centre j + 0.5 in (lo, hi]  <=>  lo - 0.5 < j <= hi - 0.5.
    let h = height as f64;
    let first = ((lo - 0.5).floor() + 1.0).clamp(0.0, h) as u32;
    let end = ((hi - 0.5).floor() + 1.0).clamp(0.0, h) as u32;
    (first, end)
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
    /// whose centres item `k` covers in rows `rows`, rows in order.
    fn for_each(
        &mut self,
        drawing: &Drawing,
        k: usize,
        rows: std::ops::Range<usize>,
        mut span: impl FnMut(usize, usize, usize),
    ) {
        let w = drawing.width as f64;
        let (r0, r1) = (rows.start as u32, rows.end as u32);
        self.edges.clear();
        for ring in &drawing.items[k].rings {
            for (n, &a) in ring.iter().enumerate() {
                let b = ring[(n + 1) % ring.len()];
                if a[1] == b[1] {
                    continue; // horizontal: crosses no row centre's half-open span
                }
                let (p, q) = if a[1] < b[1] { (a, b) } else { (b, a) };
                let (first, end) = row_range(p[1], q[1], drawing.height as usize);
                // Only this strip's rows; the crossings do not depend on where rows start.
                let (first, end) = (first.max(r0), end.min(r1));
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

    #[test]
    fn half_open_rule_at_centres_on_edges() {
        // A square whose edges pass through pixel centres: x in [1.5, 3.5), y in (1.5, 3.5].
        let d = Drawing {
            width: 5,
            height: 5,
            background: None,
            items: vec![DrawItem::new(
                7,
                vec![vec![[1.5, 1.5], [3.5, 1.5], [3.5, 3.5], [1.5, 3.5]]],
                [1.0; 3],
                1.0,
            )],
            seams: Default::default(),
            opaque_disjoint: false,
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
        let mk = |rings, c: [f64; 3]| DrawItem::new(0, rings, c, 0.5);
        let d = Drawing {
            width: 8,
            height: 8,
            background: None,
            items: vec![mk(a, [1.0, 0.0, 0.0]), mk(b, [0.0, 1.0, 0.0])],
            seams: Default::default(),
            opaque_disjoint: false,
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
                DrawItem::new(k as FaceId, rings, [rnd(0.0, 1.0); 3], rnd(0.0, 1.0))
            })
            .collect();
        let d = Drawing {
            width: w,
            height: h,
            background: Some([0.5, 0.25, 1.0]),
            items,
            seams: Default::default(),
            opaque_disjoint: false,
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
            items: vec![DrawItem::new(
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
            opaque_disjoint: false,
        };
        assert!(face_ids(&d).iter().all(|&f| f == Some(1)));
        assert!(colors(&d).iter().all(|&c| c == [1.0; 3]));
    }
}
