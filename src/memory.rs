//! Giving freed memory back to the system between stages.
//!
//! glibc's allocator keeps what a program frees in its arenas (one per thread that allocated),
//! resident, for later allocations. A stage that makes and drops hundreds of megabytes of
//! pieces (the convex pieces of every polygon, a BSP's fragments, the drawing's edges) leaves
//! them counted in the process's memory while the next stage allocates more beside them.
//! `malloc_trim` hands the free pages back and keeps what is in use. Elsewhere (other
//! allocators or systems) nothing is done.
//!
//! Called where a stage's freed room would otherwise sit beside the next stage's peak (the 1M
//! sphere file under `--method bsp`, VmRSS by probes): between the visible set and the drawing
//! (`render::compute`: 215 MB of the visible set's room was still resident there); after the
//! pieces the occlusion cells leave (`occlusion::unhidden_pieces`: ~100 MB of cells and
//! dropped pieces); as strips are solved, every [`LARGE`] pieces their solvers consumed ([`GiveBackEvery`] in
//! `strips::solve_strips`: each strip's input is freed into the arena of the thread that cut
//! it, where the solving threads cannot reuse it; the solve's high-water 512-518 -> 434 MB);
//! while the strips' visible pieces are joined into one list (481 -> 682 MB otherwise); and in
//! the drawing after the vertices are named and after the seam strokes (their maps' room,
//! ~55 MB, resident while the regions grow to the drawing's peak). Trimming after every stage
//! of the drawing did not lower the peak further and cost igea's render 20 % more system time
//! (the pages handed back are faulted in again by the next allocations).

/// A stage over at least this many pieces or polygons (a few hundred bytes each: about 10 MB)
/// frees enough to be worth handing back; below it the allocator's walk costs more than it
/// returns.
pub const LARGE: usize = 1 << 15;

/// At the end of a stage over `count` pieces or polygons: hands the allocator's free pages back
/// to the system if `count` is at least [`LARGE`] (glibc's `malloc_trim(0)`; nothing
/// elsewhere).
pub fn give_back_after(count: usize) {
    if count < LARGE {
        return;
    }
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: `malloc_trim` has no preconditions: it only releases memory no allocation uses.
    unsafe {
        libc::malloc_trim(0);
    }
}

/// Pieces freed by several threads, counted: every [`LARGE`] of them the free room goes back
/// ([`give_back_after`]).
#[derive(Debug, Default)]
pub struct GiveBackEvery(std::sync::atomic::AtomicUsize);

impl GiveBackEvery {
    /// `count` more pieces (or polygons) freed.
    pub fn freed(&self, count: usize) {
        use std::sync::atomic::Ordering::Relaxed;
        if self.0.fetch_add(count, Relaxed) + count >= LARGE {
            // Whichever thread takes the count hands the room back (a thread that finds it
            // taken already has nothing to do).
            give_back_after(self.0.swap(0, Relaxed));
        }
    }
}
