//! Rasterizing a drawing to PNG costs memory per strip of rows, not per pixel of the image, and
//! shows the same pixels as a per-pixel reference.
//!
//! A counting global allocator measures the peak heap of this test binary, so this file holds
//! one large test only; the others allocate a few kilobytes.

use sightline::output::drawing::{DrawItem, Drawing};
use sightline::output::raster_drawing::{
    color_strips, colors, face_id_strips, face_ids, write_png,
};
use sightline::paint::to_u8;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static CURRENT: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = CURRENT.fetch_add(layout.size(), Ordering::SeqCst) + layout.size();
            PEAK.fetch_max(now, Ordering::SeqCst);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        CURRENT.fetch_sub(layout.size(), Ordering::SeqCst);
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

/// A few faces over a `w` x `h` image: a cube's three visible faces, a translucent triangle over
/// them and a ring with a hole, some crossing the image border.
fn few_faces(w: f64, h: f64) -> Drawing {
    let p = |x: f64, y: f64| [x * w, y * h];
    Drawing {
        width: w as u32,
        height: h as u32,
        background: Some([1.0, 1.0, 1.0]),
        seams: Default::default(),
        opaque_disjoint: false,
        items: vec![
            DrawItem::new(
                0,
                vec![vec![p(0.5, 0.1), p(0.9, 0.3), p(0.5, 0.5), p(0.1, 0.3)]],
                [0.8, 0.2, 0.2],
                1.0,
            ),
            DrawItem::new(
                1,
                vec![vec![p(0.1, 0.3), p(0.5, 0.5), p(0.5, 0.93), p(0.1, 0.7)]],
                [0.2, 0.7, 0.2],
                1.0,
            ),
            DrawItem::new(
                2,
                vec![vec![p(0.5, 0.5), p(0.9, 0.3), p(0.9, 0.7), p(0.5, 0.93)]],
                [0.2, 0.3, 0.9],
                1.0,
            ),
            DrawItem::new(
                3,
                vec![vec![p(-0.2, 0.8), p(0.7, -0.1), p(1.3, 1.2)]],
                [0.9, 0.9, 0.1],
                0.4,
            ),
            DrawItem::new(
                4,
                vec![
                    vec![p(0.6, 0.6), p(0.97, 0.6), p(0.97, 0.97), p(0.6, 0.97)],
                    vec![p(0.7, 0.7), p(0.85, 0.7), p(0.85, 0.85), p(0.7, 0.85)],
                ],
                [0.1, 0.1, 0.1],
                0.75,
            ),
        ],
    }
}

#[test]
fn an_8192_square_png_of_a_few_faces_takes_a_few_megabytes() {
    let d = few_faces(8192.0, 8192.0);
    let mut png = Vec::new();
    let before = CURRENT.load(Ordering::SeqCst);
    PEAK.store(before, Ordering::SeqCst);
    write_png(&d, &mut png).unwrap();
    let peak = PEAK.load(Ordering::SeqCst) - before;
    // The PNG itself (flat colours compress well) is part of the peak: it lives in memory here.
    let pixels = 8192 * 8192;
    eprintln!("peak heap {} kB for {pixels} pixels", peak >> 10);
    assert!(
        peak < 32 << 20,
        "peak heap {} MB for {pixels} pixels ({:.2} bytes per pixel; PNG {} kB)",
        peak >> 20,
        peak as f64 / pixels as f64,
        png.len() >> 10
    );
    let img = image::load_from_memory(&png).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (8192, 8192));
}

/// Even-odd over all rings at (x, y), with the rasterizer's half-open conventions: an edge
/// counts when `y` is in `(y_top, y_bottom]`, a centre is inside from a crossing `x0 <= x`.
fn inside(rings: &[Vec<[f64; 2]>], x: f64, y: f64) -> bool {
    let mut odd = false;
    for r in rings {
        for n in 0..r.len() {
            let (a, b) = (r[n], r[(n + 1) % r.len()]);
            let (p, q) = if a[1] < b[1] { (a, b) } else { (b, a) };
            if p[1] < y && y <= q[1] && p[0] + (y - p[1]) * ((q[0] - p[0]) / (q[1] - p[1])) <= x {
                odd = !odd;
            }
        }
    }
    odd
}

/// Pixel by pixel: the blended colour and the topmost face at each centre.
fn reference(d: &Drawing) -> (Vec<[f64; 3]>, Vec<Option<u32>>) {
    let mut cols = Vec::new();
    let mut ids = Vec::new();
    for j in 0..d.height {
        for i in 0..d.width {
            let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
            let mut c = d.background.unwrap_or([0.0; 3]);
            let mut id = None;
            for it in d.items.iter().filter(|it| inside(&it.rings, x, y)) {
                c = std::array::from_fn(|k| c[k] * (1.0 - it.opacity) + it.color[k] * it.opacity);
                id = Some(it.face);
            }
            cols.push(c);
            ids.push(id);
        }
    }
    (cols, ids)
}

#[test]
fn strips_show_the_pixels_of_a_per_pixel_reference() {
    let d = few_faces(61.0, 47.0);
    let (cols, ids) = reference(&d);
    assert_eq!(colors(&d), cols);
    assert_eq!(face_ids(&d), ids);
    let mut png = Vec::new();
    write_png(&d, &mut png).unwrap();
    let img = image::load_from_memory(&png).unwrap().to_rgb8();
    let decoded: Vec<[u8; 3]> = img.pixels().map(|p| p.0).collect();
    let expected: Vec<[u8; 3]> = cols.into_iter().map(to_u8).collect();
    assert_eq!(decoded, expected);
}

#[test]
fn any_strip_height_gives_the_same_pixels() {
    let d = few_faces(61.0, 47.0);
    let (cols, ids) = reference(&d);
    for rows in [1, 2, 3, 7, 46, 47, 100] {
        let mut c = Vec::new();
        let mut starts = Vec::new();
        color_strips(&d, rows, |r0, strip| {
            starts.push(r0);
            c.extend_from_slice(strip);
            Ok::<(), ()>(())
        })
        .unwrap();
        assert_eq!(c, cols, "{rows} rows per strip");
        assert_eq!(starts, (0..47).step_by(rows).collect::<Vec<_>>());
        let mut f = Vec::new();
        face_id_strips(&d, rows, |_, strip| {
            f.extend_from_slice(strip);
            Ok::<(), ()>(())
        })
        .unwrap();
        assert_eq!(f, ids, "{rows} rows per strip");
    }
}
