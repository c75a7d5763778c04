//! The binary's global allocator: the system allocator, asking Linux to back large blocks
//! with transparent huge pages.
//!
//! A simulation of a million bodies keeps about 160 MB of state and every event touches a few
//! dozen cache lines somewhere random in it. With 4 KiB pages nearly every one of those
//! accesses also misses the TLB; with 2 MiB pages the whole working set fits the TLB's reach.
//! Many kernels (this machine kind included) give huge pages only to memory advised with
//! `madvise(MADV_HUGEPAGE)`, which no Rust collection asks for, so this allocator does it for
//! every block of at least [`HUGE_BLOCK`] bytes. Small blocks are left alone: a 2 MiB page
//! behind a small, short-lived block would only inflate the resident set.
//!
//! Measured with `ccdsim bench gas --dim 2 --n 1000000 --packing 0.5 --collisions 2000000`,
//! alternating binaries with and without the advice: see the commit that added this file.
//! On other systems, or when the kernel refuses, the advice is a no-op and nothing changes.

use std::alloc::{GlobalAlloc, Layout, System};

/// Blocks at least this large (bytes) are advised to use huge pages.
pub const HUGE_BLOCK: usize = 4 << 20;

/// Size of a transparent huge page on x86-64 and most aarch64 kernels (bytes). Only the
/// whole 2 MiB-aligned pages inside a block are advised.
const HUGE_PAGE: usize = 2 << 20;

/// [`System`], plus the huge-page advice on large blocks.
pub struct HugePageAlloc;

/// Advises the kernel to back the whole huge pages inside `len` bytes from `ptr` with huge
/// pages. Errors are ignored: the advice is only a hint.
#[cfg(target_os = "linux")]
fn advise(ptr: *mut u8, len: usize) {
    let start = (ptr as usize).next_multiple_of(HUGE_PAGE);
    let end = (ptr as usize).saturating_add(len) & !(HUGE_PAGE - 1);
    if end > start {
        // SAFETY: `madvise` with `MADV_HUGEPAGE` changes only how the kernel backs the pages of
        // the range (which page size serves future faults, and whether khugepaged may merge
        // them); it never changes their contents, their protection or whether they are
        // mapped, so no Rust object can observe it. The range lies inside a block the system
        // allocator just handed out (start ≥ ptr, end ≤ ptr + len), and both ends are
        // page-aligned, as madvise requires; a failure (EINVAL on kernels without THP) is
        // harmless and ignored.
        unsafe {
            libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn advise(_ptr: *mut u8, _len: usize) {}

// SAFETY: every method forwards to `System` with the same arguments and returns its result
// unchanged, so the `GlobalAlloc` contract holds as it does for `System`; the only addition,
// `advise`, does not touch the block's memory (see above).
unsafe impl GlobalAlloc for HugePageAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: forwarded unchanged; the caller upholds `alloc`'s contract.
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() && layout.size() >= HUGE_BLOCK {
            advise(p, layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: forwarded unchanged; the caller upholds `alloc_zeroed`'s contract.
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() && layout.size() >= HUGE_BLOCK {
            advise(p, layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded unchanged; the caller upholds `dealloc`'s contract.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: forwarded unchanged; the caller upholds `realloc`'s contract.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() && new_size >= HUGE_BLOCK {
            advise(p, new_size);
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn large_blocks_keep_their_contents_through_realloc() {
        let a = HugePageAlloc;
        let layout = Layout::from_size_align(HUGE_BLOCK, 8).unwrap();
        // SAFETY: a non-zero layout; the block is freed with the size it has.
        unsafe {
            let p = a.alloc_zeroed(layout);
            assert!(!p.is_null());
            assert!((0..HUGE_BLOCK).step_by(4096).all(|k| *p.add(k) == 0));
            for k in (0..HUGE_BLOCK).step_by(4096) {
                *p.add(k) = (k / 4096) as u8;
            }
            let q = a.realloc(p, layout, 3 * HUGE_BLOCK);
            assert!(!q.is_null());
            for k in (0..HUGE_BLOCK).step_by(4096) {
                assert_eq!(*q.add(k), (k / 4096) as u8);
            }
            a.dealloc(q, Layout::from_size_align(3 * HUGE_BLOCK, 8).unwrap());
        }
    }

    /// The `VmFlags` of the mapping of this process that contains `addr`, from
    /// `/proc/self/smaps`.
    #[cfg(target_os = "linux")]
    fn vm_flags_at(addr: usize) -> Option<String> {
        let smaps = std::fs::read_to_string("/proc/self/smaps").ok()?;
        let mut inside = false;
        for line in smaps.lines() {
            let first = line.split_whitespace().next().unwrap_or("");
            if let Some((lo, hi)) = first.split_once('-') {
                if let (Ok(lo), Ok(hi)) =
                    (usize::from_str_radix(lo, 16), usize::from_str_radix(hi, 16))
                {
                    inside = lo <= addr && addr < hi;
                    continue;
                }
            }
            if inside {
                if let Some(flags) = line.strip_prefix("VmFlags:") {
                    return Some(flags.trim().to_string());
                }
            }
        }
        None
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn large_blocks_are_advised() {
        let thp = std::fs::read_to_string("/sys/kernel/mm/transparent_hugepage/enabled")
            .unwrap_or_default();
        if thp.is_empty() || thp.contains("[never]") {
            // No transparent huge pages in this kernel: madvise refuses, nothing to check.
            return;
        }
        let a = HugePageAlloc;
        let big = Layout::from_size_align(HUGE_BLOCK, 8).unwrap();
        // SAFETY: non-zero layouts; each block is freed with its own layout.
        unsafe {
            let p = a.alloc(big);
            assert!(!p.is_null());
            let inner = (p as usize).next_multiple_of(HUGE_PAGE);
            let flags = vm_flags_at(inner).expect("the block is mapped");
            assert!(
                flags.split_whitespace().any(|f| f == "hg"),
                "a {HUGE_BLOCK}-byte block is not advised: VmFlags {flags}"
            );
            a.dealloc(p, big);
        }
    }
}
