//! Huge pages for large arrays: those traversal reads at random (BVH nodes and triangle packs),
//! where with 4 KiB pages almost every node visit of an incoherent ray also misses the TLB, and
//! films, whose fresh memory would otherwise arrive one 4 KiB fault at a time (a 1000x1000
//! film is 160 MB: about 40,000 faults, each charged and cleared by the kernel). Linux backs a
//! range with 2 MiB pages when asked with `madvise(MADV_HUGEPAGE)` before the memory is first
//! touched (transparent huge pages in `madvise` mode, the common default); elsewhere this is a
//! no-op. Nothing depends on it but speed.

/// Huge page size on x86_64 and aarch64 Linux.
#[cfg(target_os = "linux")]
const HUGE_PAGE: usize = 2 << 20;

/// Smaller arrays are left alone. The advice stays on an address range after the `Vec` is freed.
/// glibc serves allocations below its largest mmap threshold (32 MiB on 64-bit) from heaps it
/// keeps and reuses, so advised ranges went on to back films and other buffers with huge pages:
/// the viewer benchmark's RSS grew from 85 MB to 220 MB. Allocations this large are always
/// their own mapping, which is unmapped when freed. Meshes below it gain little anyway: their
/// arrays fit the TLB's reach.
#[cfg(target_os = "linux")]
const MIN_BYTES: usize = 32 << 20;

/// `Vec::with_capacity(capacity)`, with room to spare so that the 2 MiB-aligned part of a
/// large allocation covers at least `capacity` elements, and that part backed by huge pages
/// where the system allows it (before anything is written, as the kernel wants).
pub(crate) fn vec_on_huge_pages<T>(capacity: usize) -> Vec<T> {
    #[cfg(target_os = "linux")]
    {
        let bytes = capacity.saturating_mul(size_of::<T>().max(1));
        if bytes < MIN_BYTES {
            return Vec::with_capacity(capacity);
        }
        let v = Vec::with_capacity(capacity + HUGE_PAGE.div_ceil(size_of::<T>().max(1)));
        let start = v.as_ptr() as usize;
        let first = start.next_multiple_of(HUGE_PAGE);
        let last = (start + v.capacity() * size_of::<T>()) / HUGE_PAGE * HUGE_PAGE;
        if last > first {
            // SAFETY: `[first, last)` lies inside `v`'s allocation; MADV_HUGEPAGE only changes
            // how the kernel backs those pages, never their contents or validity. A failure (no
            // THP support) leaves the mapping as it was, which is fine.
            unsafe {
                libc::madvise(
                    first as *mut libc::c_void,
                    last - first,
                    libc::MADV_HUGEPAGE,
                );
            }
        }
        v
    }
    #[cfg(not(target_os = "linux"))]
    Vec::with_capacity(capacity)
}

/// `len` zeroed elements (`vec![T::zeroed(); len]`), the 2 MiB-aligned part of a large one
/// advised onto huge pages. The allocator takes memory this large straight from the system as
/// zero pages (calloc), so nothing is written here: each page is faulted in (and cleared by the
/// kernel) when it is first written, by whichever thread writes it.
pub(crate) fn zeroed_vec_on_huge_pages<T: bytemuck::Zeroable>(len: usize) -> Vec<T> {
    let v: Vec<T> = bytemuck::zeroed_vec(len);
    #[cfg(target_os = "linux")]
    {
        let bytes = len.saturating_mul(size_of::<T>());
        let start = v.as_ptr() as usize;
        let first = start.next_multiple_of(HUGE_PAGE);
        let last = (start + bytes) / HUGE_PAGE * HUGE_PAGE;
        if bytes >= MIN_BYTES && last > first {
            // SAFETY: as in `vec_on_huge_pages`: `[first, last)` lies inside `v`'s allocation,
            // and the advice changes only how the kernel backs untouched pages.
            unsafe {
                libc::madvise(
                    first as *mut libc::c_void,
                    last - first,
                    libc::MADV_HUGEPAGE,
                );
            }
        }
    }
    v
}

/// Hands memory the allocator holds but no longer uses back to the system. A scene's build
/// frees large temporaries on many threads (the BVH build's parts, the smoothing's tables);
/// glibc keeps what was allocated below its mmap threshold in per-thread heaps, about 15 bytes
/// a triangle of a 10-million-triangle scene left resident for the life of the scene. A no-op
/// elsewhere.
pub(crate) fn release_free_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: `malloc_trim` only returns free memory of the allocator's heaps to the kernel;
    // it touches no memory in use and is safe to call from any thread at any time.
    unsafe {
        libc::malloc_trim(0);
    }
}
