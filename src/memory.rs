//! Giving freed memory back to the system between stages.
//!
//! glibc's allocator keeps what a program frees in its arenas (one per thread that allocated),
//! resident, for later allocations. A stage that makes and drops hundreds of megabytes of
//! pieces (the convex pieces of every polygon, a BSP's fragments, the drawing's edges) leaves
//! them counted in the process's memory while the next stage allocates more beside them.
//! `malloc_trim` hands the free pages back and keeps what is in use. Elsewhere (other
//! allocators or systems) nothing is done.
//!
//! Called between the visible set and the drawing (`render::compute`): on the 1M-sphere file
//! 215 MB of the visible set's freed room was still resident there (VmRSS 724 -> 509 MB by the
//! trim); and while the strips' visible pieces are joined into one list
//! (`strips::solve_strips`), every few strips, where the strips' room and the whole list were
//! the process's peak (481 -> 682 MB on that sphere). Trimming after every large strip and
//! stage of the drawing as well did not lower the peak further and cost igea's render 20 %
//! more system time (the pages handed back are faulted in again by the next allocations).

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
