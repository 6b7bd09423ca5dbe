//! A global allocator that counts the bytes in use and refuses an allocation that would
//! take them past a cap (set by the `tribo` command to 90 % of the memory available at
//! its start, see `crate::memory::available`).
//!
//! Why: a model whose solve outgrows the machine was killed by the kernel's OOM killer
//! (SIGKILL: no message, no results.json; the SSNP154 D set-up at size 0.0225 reached
//! 24 GB). With the cap, the failure happens inside the process: faer's fallible
//! workspace allocations turn into "out of memory factorising …", any other allocation
//! into Rust's "memory allocation of N bytes failed" abort. The count is of requested
//! bytes, which bound the resident size from above (allocator overhead aside). The
//! system allocator does the work; a maintained crate offers no cap of this kind
//! (cap-style crates count, but leave the limit's source and message to us anyway).

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

static IN_USE: AtomicUsize = AtomicUsize::new(0);
static CAP: AtomicUsize = AtomicUsize::new(usize::MAX);

/// The system allocator with a cap on the bytes in use.
pub struct Capped;

/// Takes n bytes from the cap; false (nothing taken) if that would pass it.
fn take(n: usize) -> bool {
    let before = IN_USE.fetch_add(n, Ordering::Relaxed);
    if before.saturating_add(n) > CAP.load(Ordering::Relaxed) {
        IN_USE.fetch_sub(n, Ordering::Relaxed);
        return false;
    }
    true
}

fn give(n: usize) {
    IN_USE.fetch_sub(n, Ordering::Relaxed);
}

/// Caps the bytes in use at `bytes` beyond those in use now.
pub fn cap_from_now(bytes: u64) {
    let now = IN_USE.load(Ordering::Relaxed);
    CAP.store(
        now.saturating_add(usize::try_from(bytes).unwrap_or(usize::MAX)),
        Ordering::Relaxed,
    );
}

/// Bytes in use (requested and not freed).
pub fn in_use() -> usize {
    IN_USE.load(Ordering::Relaxed)
}

// SAFETY: every call is passed on to the system allocator with the same layout and
// pointer; the count only decides whether an allocation is attempted at all (a refused
// one returns null, which callers handle as an allocation failure).
unsafe impl GlobalAlloc for Capped {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !take(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: the caller's layout, as GlobalAlloc requires.
        let p = unsafe { System.alloc(layout) };
        if p.is_null() {
            give(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !take(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: as `alloc`.
        let p = unsafe { System.alloc_zeroed(layout) };
        if p.is_null() {
            give(layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: ptr was allocated by `alloc` with this layout.
        unsafe { System.dealloc(ptr, layout) };
        give(layout.size());
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = layout.size();
        if new_size > old && !take(new_size - old) {
            return std::ptr::null_mut();
        }
        // SAFETY: ptr and layout come from this allocator, as GlobalAlloc requires.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if p.is_null() {
            if new_size > old {
                give(new_size - old);
            }
        } else if new_size < old {
            give(old - new_size);
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_count_follows_takes_and_gives_and_refuses_past_the_cap() {
        // (the test binary uses the system allocator: only the counting rules here)
        let start = IN_USE.load(Ordering::Relaxed);
        assert!(take(100));
        assert_eq!(IN_USE.load(Ordering::Relaxed), start + 100);
        give(100);
        assert_eq!(IN_USE.load(Ordering::Relaxed), start);
        CAP.store(start + 50, Ordering::Relaxed);
        assert!(!take(51));
        assert_eq!(IN_USE.load(Ordering::Relaxed), start);
        assert!(take(50));
        give(50);
        CAP.store(usize::MAX, Ordering::Relaxed);
    }
}
