//! Cache prefetch hints: ask the memory system for a line before the code that needs it
//! gets there, so that the misses of independent loads overlap instead of queueing behind
//! each other's branches.
//!
//! A hint never changes a result: it is not a load, it cannot fault, and on targets without
//! one it compiles to nothing.

/// Hints that `x`'s cache line will be read soon (into every cache level).
#[inline(always)]
pub(crate) fn prefetch<T>(x: &T) {
    #[cfg(all(
        any(target_arch = "x86", target_arch = "x86_64"),
        target_feature = "sse"
    ))]
    safe_arch::prefetch_t0(x);
    #[cfg(not(all(
        any(target_arch = "x86", target_arch = "x86_64"),
        target_feature = "sse"
    )))]
    let _ = x;
}
