//! `redundant-ik`: the command-line shell over the library (simulation,
//! figures, training, evaluation, benchmarks). All mathematics lives in the
//! library.

#[cfg(not(target_family = "wasm"))]
mod counting {
    //! The system allocator, counting allocations so that `bench` can report
    //! heap allocations per step (one relaxed atomic add per allocation).
    use std::alloc::{GlobalAlloc, Layout, System};
    use std::sync::atomic::{AtomicU64, Ordering};

    pub static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

    pub struct Counting;

    // SAFETY: every call is forwarded unchanged to the system allocator.
    unsafe impl GlobalAlloc for Counting {
        unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
            System.alloc(layout)
        }
        unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
            System.dealloc(ptr, layout)
        }
        unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
            System.alloc_zeroed(layout)
        }
        unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
            System.realloc(ptr, layout, new_size)
        }
    }
}

#[cfg(not(target_family = "wasm"))]
#[global_allocator]
static GLOBAL: counting::Counting = counting::Counting;

/// Heap allocations (including reallocations) since the program started.
#[cfg(not(target_family = "wasm"))]
fn allocations() -> u64 {
    counting::ALLOCATIONS.load(std::sync::atomic::Ordering::Relaxed)
}

#[cfg(not(target_family = "wasm"))]
fn main() {
    std::process::exit(redundant_ik::cli::main(Some(allocations)));
}

/// The command-line tool is native only; the wasm build is the library.
#[cfg(target_family = "wasm")]
fn main() {}
