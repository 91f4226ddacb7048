//! The program's memory allocator: the system's (glibc malloc), with large blocks "coloured",
//! each started at its own offset within a 4 KiB page.
//!
//! glibc serves every block of 128 KiB or more by `mmap`, so the per-particle arrays of a large
//! scene (x, y, v_x, v_y, f_x, f_y: 800 KB each at 10⁵ particles) all start at the same
//! offset in their pages. The force loop then loads `x[i]`, `y[i]` and stores `f_x[i]`, `f_y[i]` at
//! addresses equal in their low 12 bits, which the load–store unit takes for a dependency
//! ("4K aliasing"), and the six streams fall into the same L1 sets. Measured on the kernel
//! workload (N = 316, one thread, AVX-512 machine): 150–185 M particle-steps/s depending on
//! where the arrays happened to land, 192–200 M with colouring in every repetition, the C
//! stencil 155 M beside it (docs/performance.md, "The reference workload"). Results do not
//! depend on addresses, so they are the same bit for bit.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Blocks of at least this many bytes are coloured; smaller ones go to the system untouched.
pub const COLOURED_FROM: usize = 1 << 16;

/// Distinct starting offsets (colours) of coloured blocks, used in turn.
pub const COLOURS: usize = 12;

/// Bytes between two colours: five cache lines, so the twelve offsets 64, 384, …, 3584 differ
/// in their low 12 bits and spread over the L1 sets.
pub const COLOUR_STRIDE: usize = 5 * 64;

/// The cache-line alignment every coloured block has (a larger requested alignment goes to
/// the system untouched).
const LINE: usize = 64;

/// The allocator: [`System`] for small blocks; a large one is allocated two pages larger and
/// handed out at the next colour's offset in its page, with its distance from the system's
/// block stored in the word before it.
pub struct Coloured;

/// The next colour to hand out.
static NEXT_COLOUR: AtomicUsize = AtomicUsize::new(0);

/// True when `layout` is coloured.
fn coloured(layout: Layout) -> bool {
    layout.size() >= COLOURED_FROM && layout.align() <= LINE
}

/// Bytes in a page: what a colour is an offset within.
const PAGE: usize = 4096;

/// Bytes a coloured block takes beyond its own: room to reach any colour past the stored
/// offset.
const PADDING: usize = 2 * PAGE;

/// The system's layout of a coloured block of `layout`: [`PADDING`] more, cache-line aligned.
fn padded(layout: Layout) -> Layout {
    Layout::from_size_align(layout.size() + PADDING, LINE).expect("a size that fit two pages less")
}

impl Coloured {
    /// The user's block within `base` (null passes through): the first address past its first
    /// word whose offset within its page is the next colour, 64 + k · [`COLOUR_STRIDE`] (the
    /// system's own offset of `base` varies: `mmap`ed blocks, heap blocks); the distance from
    /// `base` is stored in the word before it.
    unsafe fn place(base: *mut u8) -> *mut u8 {
        if base.is_null() {
            return base;
        }
        let colour = LINE + (NEXT_COLOUR.fetch_add(1, Ordering::Relaxed) % COLOURS) * COLOUR_STRIDE;
        let mut offset = (colour + PAGE - base as usize % PAGE) % PAGE;
        if offset < size_of::<usize>() {
            offset += PAGE;
        }
        // SAFETY: `base` holds [`PADDING`] bytes more than the user asked for and
        // 8 ≤ offset < PADDING − PAGE + 8.
        unsafe {
            let user = base.add(offset);
            user.cast::<usize>().sub(1).write(offset);
            user
        }
    }
}

// SAFETY: every block comes from `System` with a layout of at least the requested size and
// alignment; a coloured block is returned to `System` with the padded layout it came with,
// found again from the offset stored just before it.
unsafe impl GlobalAlloc for Coloured {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !coloured(layout) {
            return unsafe { System.alloc(layout) };
        }
        unsafe { Coloured::place(System.alloc(padded(layout))) }
    }

    /// Zeroed by the system (fresh `mmap` pages cost nothing until touched), then coloured.
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !coloured(layout) {
            return unsafe { System.alloc_zeroed(layout) };
        }
        unsafe { Coloured::place(System.alloc_zeroed(padded(layout))) }
    }

    /// A coloured block that stays coloured is resized by the system's `realloc` (glibc moves
    /// large blocks with `mremap`: no copy, no second block at the peak) at the same distance
    /// from the system's block, so its colour may change (the arrays the force loop reads are
    /// allocated once at their size); any other change of size allocates, copies and frees.
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: the caller's `new_size` with `layout`'s alignment is a valid layout.
        let new_layout = unsafe { Layout::from_size_align_unchecked(new_size, layout.align()) };
        match (coloured(layout), coloured(new_layout)) {
            (false, false) => unsafe { System.realloc(ptr, layout, new_size) },
            (true, true) => unsafe {
                let offset = ptr.cast::<usize>().sub(1).read();
                let base = System.realloc(ptr.sub(offset), padded(layout), padded(new_layout).size());
                if base.is_null() { base } else { base.add(offset) }
            },
            _ => unsafe {
                let moved = self.alloc(new_layout);
                if !moved.is_null() {
                    std::ptr::copy_nonoverlapping(ptr, moved, layout.size().min(new_size));
                    self.dealloc(ptr, layout);
                }
                moved
            },
        }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        if !coloured(layout) {
            return unsafe { System.dealloc(ptr, layout) };
        }
        unsafe {
            let offset = ptr.cast::<usize>().sub(1).read();
            System.dealloc(ptr.sub(offset), padded(layout));
        }
    }
}
