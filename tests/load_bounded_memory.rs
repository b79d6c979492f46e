//! Loading streams the file: a gzipped OBJ whose text is hundreds of megabytes (comment lines,
//! then a triangle) is read with a peak heap that does not grow with the file, and the triangle
//! at its end is loaded. The heap is measured by a counting global allocator (this file holds one
//! test so that nothing else allocates meanwhile).

use flate2::Compression;
use flate2::write::GzEncoder;
use std::alloc::{GlobalAlloc, Layout, System};
use std::io::{BufWriter, Write};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

struct Counting;

static CURRENT: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

fn grew(by: usize) {
    let now = CURRENT.fetch_add(by, Relaxed) + by;
    PEAK.fetch_max(now, Relaxed);
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            grew(layout.size());
        }
        p
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            grew(layout.size());
        }
        p
    }
    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        unsafe { System.dealloc(p, layout) };
        CURRENT.fetch_sub(layout.size(), Relaxed);
    }
    unsafe fn realloc(&self, p: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let q = unsafe { System.realloc(p, layout, new_size) };
        if !q.is_null() {
            if new_size > layout.size() {
                grew(new_size - layout.size());
            } else {
                CURRENT.fetch_sub(layout.size() - new_size, Relaxed);
            }
        }
        q
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

const MB: usize = 1 << 20;
/// Decompressed size of the comments.
const TEXT_MB: usize = 256;
/// Peak heap allowed for loading it: buffers and the scene, far below the text.
const LIMIT_MB: usize = 32;

#[test]
fn gzipped_obj_of_comments_loads_in_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("comments.obj.gz");
    {
        let file = std::fs::File::create(&path).unwrap();
        let mut gz = GzEncoder::new(BufWriter::new(file), Compression::fast());
        let line = format!("# {}\n", "comment ".repeat(12));
        let block = line.repeat(MB / line.len());
        for _ in 0..TEXT_MB * MB / block.len() {
            gz.write_all(block.as_bytes()).unwrap();
        }
        gz.write_all(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
            .unwrap();
        gz.finish().unwrap().flush().unwrap();
    }
    let before = CURRENT.load(Relaxed);
    PEAK.store(before, Relaxed);
    let scene = sightline::scene::load(&path, None).unwrap_or_else(|e| panic!("{e}"));
    let peak = PEAK.load(Relaxed) - before;
    eprintln!(
        "peak heap while loading {TEXT_MB} MB of gzipped OBJ text: {:.1} MB",
        peak as f64 / MB as f64
    );
    assert_eq!(scene.positions.len(), 3);
    assert_eq!(scene.faces.len(), 1);
    assert!(
        peak < LIMIT_MB * MB,
        "peak heap {peak} bytes while loading, limit {LIMIT_MB} MB"
    );

    // One line of 256 MB: refused at the line cap (16 MiB), naming the file and the line,
    // without holding the line (in this same test: nothing else allocates meanwhile).
    let path = dir.path().join("one_line.obj.gz");
    {
        let file = std::fs::File::create(&path).unwrap();
        let mut gz = GzEncoder::new(BufWriter::new(file), Compression::fast());
        gz.write_all(b"v 0 0 0\n#").unwrap();
        let block = "comment ".repeat(MB / 8);
        for _ in 0..TEXT_MB * MB / block.len() {
            gz.write_all(block.as_bytes()).unwrap();
        }
        gz.finish().unwrap().flush().unwrap();
    }
    let before = CURRENT.load(Relaxed);
    PEAK.store(before, Relaxed);
    let err = sightline::scene::load(&path, None)
        .expect_err("a 256 MB line is refused")
        .to_string();
    let peak = PEAK.load(Relaxed) - before;
    eprintln!(
        "peak heap while refusing one {TEXT_MB} MB line: {:.1} MB",
        peak as f64 / MB as f64
    );
    assert!(err.contains("one_line.obj.gz"), "{err}");
    assert!(err.contains("line 2 is longer than 16 MiB"), "{err}");
    assert!(
        peak < 2 * LIMIT_MB * MB,
        "peak heap {peak} bytes for one long line, limit {} MB",
        2 * LIMIT_MB
    );
}
