//! The binary's global allocator: the system allocator, with transparent huge pages asked for on
//! the large arrays of a run.
//!
//! A contact or surface node at the measured size (3512² points) allocates and frees arrays of
//! about 100 MB many times. The system allocator maps each of them afresh, and the kernel then
//! faults it in one 4 KiB page at a time, zeroing each: about 24 000 faults per array touched,
//! paid in system time, plus a TLB miss per page on every scattered read (the coefficient table
//! behind the restricted contact matrix). Where the kernel leaves transparent huge pages to the
//! program (`/sys/kernel/mm/transparent_hugepage/enabled` = `madvise`, the common default), an
//! `madvise(MADV_HUGEPAGE)` on the fresh, still untouched mapping makes it fault in 2 MiB pages
//! instead. Where the kernel already uses them everywhere, or has them disabled, or on another
//! operating system, the advice changes nothing. Results never depend on it: only where the
//! memory comes from changes, not a value in it. Measured figures: `docs/studies.md`.
//!
//! Only the part of a block between its first and last 2 MiB boundaries is advised, and only
//! for blocks of at least [`MIN_ADVISED_BYTES`], which are mostly touched whole (grids and their
//! spectra), so a huge page is never taken for a few small objects.

use std::alloc::{GlobalAlloc, Layout, System};
use std::ops::Range;

/// The size of a transparent huge page on x86-64 and aarch64 with 4 KiB base pages.
const HUGE_PAGE_BYTES: usize = 2 << 20;

/// Blocks smaller than this are left to the system allocator unchanged: 4 huge pages, i.e. a
/// 1024² `f64` grid is advised and a 512² one is not.
const MIN_ADVISED_BYTES: usize = 4 * HUGE_PAGE_BYTES;

/// [`System`] plus `madvise(MADV_HUGEPAGE)` on blocks of at least [`MIN_ADVISED_BYTES`].
pub struct HugePageAllocator;

// SAFETY: every call is forwarded to `System` with the caller's arguments unchanged; the advice
// only concerns whole pages inside the block just returned, which the caller now owns.
unsafe impl GlobalAlloc for HugePageAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: forwarded with the caller's guarantees for `layout`.
        let block = unsafe { System.alloc(layout) };
        advise_huge_pages(block, layout.size());
        block
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: as in `alloc`. A fresh mapping is zero without being written, so its pages are
        // still untouched when advised.
        let block = unsafe { System.alloc_zeroed(layout) };
        advise_huge_pages(block, layout.size());
        block
    }

    unsafe fn dealloc(&self, block: *mut u8, layout: Layout) {
        // SAFETY: forwarded with the caller's guarantees (`block` came from this allocator, which
        // is `System`'s).
        unsafe { System.dealloc(block, layout) }
    }

    unsafe fn realloc(&self, block: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: forwarded with the caller's guarantees.
        let moved = unsafe { System.realloc(block, layout, new_size) };
        advise_huge_pages(moved, new_size);
        moved
    }
}

/// Advises the whole 2 MiB pages inside the block `[start, start + size)` for transparent huge
/// pages (Linux); a no-op elsewhere. The advice is a hint: its failure (an old kernel, a kernel
/// without transparent huge pages) leaves the block as it was.
fn advise_huge_pages(start: *mut u8, size: usize) {
    if start.is_null() {
        return;
    }
    if let Some(pages) = advised_range(start as usize, size) {
        madvise_huge(pages.start, pages.len());
    }
}

/// The whole 2 MiB pages inside the block `[start, start + size)`, if it is at least
/// [`MIN_ADVISED_BYTES`] long and holds any.
fn advised_range(start: usize, size: usize) -> Option<Range<usize>> {
    if size < MIN_ADVISED_BYTES {
        return None;
    }
    let first = start.next_multiple_of(HUGE_PAGE_BYTES);
    let end = (start + size) / HUGE_PAGE_BYTES * HUGE_PAGE_BYTES;
    (end > first).then_some(first..end)
}

#[cfg(target_os = "linux")]
fn madvise_huge(first: usize, length: usize) {
    // SAFETY: `[first, first + length)` lies inside a block the caller owns and is page-aligned;
    // MADV_HUGEPAGE neither reads nor changes its contents.
    unsafe {
        libc::madvise(first as *mut libc::c_void, length, libc::MADV_HUGEPAGE);
    }
}

#[cfg(not(target_os = "linux"))]
fn madvise_huge(_first: usize, _length: usize) {}

/// Blocks of at least this size are mapped afresh by the system allocator and unmapped when
/// freed ([`return_freed_blocks`]): every grid of 512² points or more.
const MMAP_THRESHOLD_BYTES: i32 = 1 << 20;

/// The system allocator's arenas (heaps of blocks below [`MMAP_THRESHOLD_BYTES`]): one, shared
/// by all threads ([`return_freed_blocks`]).
const ARENAS: i32 = 1;

/// Makes the system allocator (glibc) give freed memory back, so the resident set follows what
/// the process holds and `--memory-mib` can bound it:
/// * fixes the mmap threshold at [`MMAP_THRESHOLD_BYTES`], so a freed grid goes back to the
///   system at once. Left to itself, glibc raises the threshold to the size of each mapped block
///   freed (up to 32 MiB): the next grids of that size then come from its heap, which keeps their
///   pages after they are freed;
/// * keeps [`ARENAS`] arena. Left to itself, glibc gives each thread that allocates its own arena
///   (up to 8 per core), and each keeps the pages of the small blocks freed in it: the resident
///   set then grows with `--jobs` beyond what the process holds.
///
/// Measured figures: `docs/robustness.md`, "Memory". Elsewhere (musl, other systems) this does
/// nothing.
pub fn return_freed_blocks() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: `mallopt` only changes tuning parameters of the allocator, called before any
    // thread of ours starts.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD_BYTES);
        libc::mallopt(libc::M_ARENA_MAX, ARENAS);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_whole_huge_pages_inside_large_blocks_are_advised() {
        let page = HUGE_PAGE_BYTES;
        assert_eq!(advised_range(3 * page, MIN_ADVISED_BYTES - 1), None);
        assert_eq!(
            advised_range(3 * page, MIN_ADVISED_BYTES),
            Some(3 * page..3 * page + MIN_ADVISED_BYTES)
        );
        // A block starting 16 bytes past a page boundary (a mapping's allocator header): its
        // first and last partial pages stay out.
        let start = 5 * page + 16;
        assert_eq!(advised_range(start, 10 * page), Some(6 * page..15 * page));
    }

    /// The advice reaches the kernel: the mapping of a fresh 64 MiB vector is flagged for huge
    /// pages (`hg` in `/proc/self/smaps`) where the kernel has transparent huge pages at all.
    #[cfg(target_os = "linux")]
    #[test]
    fn a_large_vector_is_mapped_for_huge_pages() {
        if !std::path::Path::new("/sys/kernel/mm/transparent_hugepage/enabled").exists() {
            return;
        }
        let block = vec![0u8; 64 << 20];
        let address = block.as_ptr() as usize + (32 << 20);
        let smaps = std::fs::read_to_string("/proc/self/smaps").unwrap();
        let mut inside = false;
        let mut flags = None;
        for line in smaps.lines() {
            if let Some((range, _)) = line.split_once(' ') {
                if let Some((lo, hi)) = range.split_once('-') {
                    if let (Ok(lo), Ok(hi)) =
                        (usize::from_str_radix(lo, 16), usize::from_str_radix(hi, 16))
                    {
                        inside = (lo..hi).contains(&address);
                        continue;
                    }
                }
            }
            if inside {
                if let Some(f) = line.strip_prefix("VmFlags:") {
                    flags = Some(f.to_string());
                }
            }
        }
        let flags = flags.expect("the vector's mapping is in /proc/self/smaps");
        assert!(
            flags.split_whitespace().any(|f| f == "hg"),
            "VmFlags:{flags}"
        );
        drop(block);
    }
}
