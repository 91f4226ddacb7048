//! Unit tests of `src/alloc.rs`, moved out of the library (one test binary).

use std::alloc::{GlobalAlloc, Layout};

use mdsolids::alloc::{COLOUR_STRIDE, COLOURED_FROM, COLOURS, Coloured};

/// Twelve large blocks in a row start at twelve different offsets within their pages (what the
/// force loop gains from), each cache-line aligned; every byte is theirs to write and read; a
/// zeroed one reads zero. Small blocks and large alignments go to the system untouched.
#[test]
fn large_blocks_start_at_distinct_offsets_in_their_pages() {
    let layout = Layout::from_size_align(800_000, 8).unwrap();
    let blocks: Vec<*mut u8> = (0..COLOURS).map(|_| unsafe { Coloured.alloc(layout) }).collect();
    let offsets: std::collections::BTreeSet<usize> = blocks.iter().map(|&b| b as usize % 4096).collect();
    assert_eq!(offsets.len(), COLOURS, "offsets {offsets:?}");
    for (index, &block) in blocks.iter().enumerate() {
        assert_eq!(block as usize % 64, 0);
        let bytes = unsafe { std::slice::from_raw_parts_mut(block, layout.size()) };
        bytes.fill(index as u8);
        assert!(bytes.iter().all(|&b| b == index as u8));
    }
    blocks.into_iter().for_each(|block| unsafe { Coloured.dealloc(block, layout) });
    let zeroed = unsafe { Coloured.alloc_zeroed(layout) };
    assert!(unsafe { std::slice::from_raw_parts(zeroed, layout.size()) }.iter().all(|&b| b == 0));
    unsafe { Coloured.dealloc(zeroed, layout) };
    for layout in [Layout::from_size_align(100, 8).unwrap(), Layout::from_size_align(COLOURED_FROM, 4096).unwrap()] {
        let block = unsafe { Coloured.alloc(layout) };
        assert_eq!(block as usize % layout.align(), 0);
        unsafe { Coloured.dealloc(block, layout) };
    }
    const { assert!(64 + (COLOURS - 1) * COLOUR_STRIDE < 4096) };
    // In this test, not beside it: the colours are handed out in turn, process-wide.
    reallocation_keeps_contents_across_the_coloured_threshold();
}

/// Growing and shrinking keeps the contents: large to larger (the system's realloc), small to large and large to small (copied), for a `Vec` as it grows from
/// one element to 10⁶ and back.
fn reallocation_keeps_contents_across_the_coloured_threshold() {
    let mut block = unsafe { Coloured.alloc(Layout::from_size_align(64, 8).unwrap()) };
    let mut size = 64;
    unsafe { std::slice::from_raw_parts_mut(block, size) }.iter_mut().enumerate().for_each(|(i, b)| *b = i as u8);
    for new_size in [COLOURED_FROM * 2, COLOURED_FROM * 40, COLOURED_FROM * 40 + 1, 1000, 64] {
        let old = Layout::from_size_align(size, 8).unwrap();
        block = unsafe { Coloured.realloc(block, old, new_size) };
        let kept = size.min(new_size);
        let bytes = unsafe { std::slice::from_raw_parts_mut(block, new_size) };
        assert!(bytes[..kept].iter().enumerate().all(|(i, &b)| b == i as u8), "{size} → {new_size}");
        bytes.iter_mut().enumerate().for_each(|(i, b)| *b = i as u8);
        size = new_size;
    }
    unsafe { Coloured.dealloc(block, Layout::from_size_align(size, 8).unwrap()) };
}
