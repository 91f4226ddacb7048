//! Unit tests of `src/draw/movie.rs`, moved out of the library (one test binary).

use mdsolids::draw::movie::{Palette, UNCHANGED, force_line_width, gif_frame, magnification, readable};

/// Sub-micron waves in a 0.1 m lattice are magnified to a third of the spacing at most, by
/// a round factor; visible displacements and a still picture are drawn as they are.
#[test]
fn small_displacements_are_magnified_by_a_round_factor() {
    assert_eq!(magnification(1e-6, 0.1), 20000.0); // target 30 000
    assert_eq!(magnification(4e-4, 0.1), 50.0); // target 75
    assert_eq!(magnification(1e-4, 0.1), 200.0); // target 300
    assert_eq!(magnification(0.02, 0.1), 1.0); // target 1.5: already visible
    assert_eq!(magnification(0.0, 0.1), 1.0);
}

#[test]
fn time_stamps_read_at_a_glance() {
    assert_eq!(readable(22.570), "22.57");
    assert_eq!(readable(0.0044429), "0.004443");
    assert_eq!(readable(12345.6), "12346");
    assert_eq!(readable(1.2344e-7), "1.234e-7");
    assert_eq!(readable(0.0), "0");
}

/// The first frame is whole; a later one is the box of pixels that changed, the unchanged
/// ones in it transparent; colours go to the nearest of the 32 of the palette.
#[test]
fn later_frames_hold_only_what_changed() {
    let mut palette = Palette::default();
    assert_eq!(palette.colours.len(), 3 * 32, "32 colours: LZW codes start at 6 bits");
    let white = [255u8; 3 * 4 * 3]; // 4 × 3 pixels
    let first = palette.indices(&white);
    let whole = gif_frame(&first, None, 4);
    assert_eq!((whole.width, whole.height, whole.transparent), (4, 3, None));
    assert!(whole.buffer.iter().all(|&i| i != UNCHANGED));
    let mut next = white;
    next[3 * 5..3 * 5 + 3].copy_from_slice(&[250, 250, 250]); // (1, 1): rounds to white, no change
    next[3 * 6..3 * 6 + 3].copy_from_slice(&[0, 0, 0]); // (2, 1): black
    next[3 * 7..3 * 7 + 3].copy_from_slice(&[200, 30, 30]); // (3, 1): red
    let next = palette.indices(&next);
    let frame = gif_frame(&next, Some(&first), 4);
    assert_eq!((frame.left, frame.top, frame.width, frame.height), (2, 1, 2, 1));
    assert_eq!(frame.transparent, Some(UNCHANGED));
    let rgb = |i: u8| &palette.colours[3 * usize::from(i)..3 * usize::from(i) + 3];
    assert_eq!((rgb(frame.buffer[0]), rgb(frame.buffer[1])), ([0, 0, 0].as_slice(), [200, 30, 30].as_slice()));
    let same = gif_frame(&next, Some(&next), 4);
    assert_eq!((same.width, same.height, same.buffer.as_ref()), (1, 1, [UNCHANGED].as_slice()));
}

/// A frame's indices are looked up once per run of equal pixels: a colour that comes back
/// after another (A A B A), or that differs from the one before in one channel only, gets its
/// own index again, the same as each pixel looked up alone.
#[test]
fn palette_indices_by_runs_are_those_of_each_pixel_alone() {
    // Black, blue and green share their red channel, blue and cyan their red and blue.
    let colours = [[0u8, 0, 0], [0, 0, 255], [0, 255, 0], [0, 255, 255], [255, 255, 255]];
    let order = [0, 0, 1, 1, 0, 2, 3, 3, 2, 4, 0, 4, 1, 3, 0];
    let pixels: Vec<u8> = order.iter().flat_map(|&c| colours[c]).collect();
    let by_runs = Palette::default().indices(&pixels);
    let alone: Vec<u8> = colours.iter().map(|c| Palette::default().indices(c)[0]).collect();
    // Not vacuous: every colour has an index of its own in the palette.
    assert_eq!(alone.iter().collect::<std::collections::BTreeSet<_>>().len(), colours.len(), "{alone:?}");
    assert_eq!(by_runs, order.iter().map(|&c| alone[c]).collect::<Vec<_>>());
}

#[test]
fn a_contact_line_grows_with_its_force_up_to_half_the_smallest_disc() {
    // 1 px at no force, 1 + (w − 1) f/f_max in between, w = half the smallest disc's pixels
    // (at most 8): discs of 10 px give w = 5; of 40 px, 8; of 1 px, 1 (a line, not nothing).
    assert_eq!(force_line_width(0.0, 2.0, 10.0), 1);
    assert_eq!(force_line_width(1.0, 2.0, 10.0), 3);
    assert_eq!(force_line_width(2.0, 2.0, 10.0), 5);
    assert_eq!(force_line_width(4.0, 2.0, 10.0), 5, "clamped at the largest");
    assert_eq!(force_line_width(2.0, 2.0, 40.0), 8);
    assert_eq!(force_line_width(2.0, 2.0, 1.0), 1);
    assert_eq!(force_line_width(1.0, 0.0, 10.0), 1, "no forces at all");
}
