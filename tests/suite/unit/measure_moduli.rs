//! Unit tests of `src/measure/moduli.rs`, moved out of the library (one test binary).

use mdsolids::measure::{LatticeShape, homogeneity};
use mdsolids::model::{Edges, Layout};

/// A 3 × 3 block's x displacements, row by row, with left and right columns `left`, `right`.
fn block(left: [f64; 3], right: [f64; 3]) -> (Edges, Vec<f64>) {
    let ux = (0..3).flat_map(|row| [left[row], 0.5 * (left[row] + right[row]), right[row]]).collect();
    (Layout::square(3, 3, 1.0, false).edges, ux)
}

/// Straight edges give 0, a bowed edge its deviation over the mean sideways displacement,
/// and edges that do not move sideways (ν = 0, round-off only) no number at all.
#[test]
fn homogeneity_is_defined_only_where_the_edges_move() {
    let shape = |edges| LatticeShape { edges, depth: 1.0 };
    let (edges, ux) = block([0.0, 0.0, 0.0], [-1e-3, -1e-3, -1e-3]);
    assert_eq!(homogeneity(&shape(&edges), &ux, 1e-2), Some(0.0));
    let (edges, ux) = block([0.0, 0.0, 0.0], [-1e-3, -2e-3, -1e-3]);
    // Line through (0, −1e-3), (1, −2e-3), (2, −1e-3): −4/3e-3, deviation 2/3e-3; mean |u| 2/3e-3.
    let h = homogeneity(&shape(&edges), &ux, 1e-2).unwrap();
    assert!((h - 1.0).abs() < 1e-12, "{h}");
    let (edges, ux) = block([1e-19, -2e-19, 0.0], [3e-19, 0.0, -1e-19]);
    assert_eq!(homogeneity(&shape(&edges), &ux, 1e-6), None);
}
