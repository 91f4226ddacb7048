//! Unit tests of `src/model/lattice.rs`, moved out of the library (one test binary).

use mdsolids::model::SquareLattice;

fn lattice(nx: usize, ny: usize, k_diag: f64) -> SquareLattice {
    SquareLattice { nx, ny, spacing: 0.1, k_x: 3.0, k_y: 3.0, k_rising: k_diag, k_falling: k_diag, periodic_x: false }
}

#[test]
fn n_by_one_lattice_is_the_chain() {
    let chain = lattice(5, 1, 1.0).bonds();
    assert_eq!(chain.i, vec![0, 1, 2, 3]);
    assert_eq!(chain.j, vec![1, 2, 3, 4]);
    assert!(chain.rest.iter().all(|&r| r == 0.1));
}

#[test]
fn bond_count_matches_the_list() {
    // nx(ny−1) + ny(nx−1) axial bonds and 2(nx−1)(ny−1) diagonals.
    for (nx, ny, k_diag) in [(4, 3, 0.5), (4, 3, 0.0), (1, 5, 0.5), (7, 1, 0.5)] {
        let l = lattice(nx, ny, k_diag);
        assert_eq!(l.bond_count(), l.bonds().len());
    }
    assert_eq!(lattice(4, 3, 0.5).bond_count(), 4 * 2 + 3 * 3 + 2 * 3 * 2);
    let periodic = SquareLattice { periodic_x: true, ..lattice(4, 3, 0.5) };
    assert_eq!(periodic.bond_count(), periodic.bonds().len());
    // Periodic: nx(ny − 1) vertical, nx ny horizontal and 2 nx (ny − 1) diagonal bonds.
    assert_eq!(periodic.bond_count(), 4 * 2 + 4 * 3 + 2 * 4 * 2);
}

#[test]
fn wrapped_bonds_have_their_rest_length() {
    // Every bond of the periodic lattice at rest has |x_i − x_j + shift| = its rest length.
    let l = SquareLattice { periodic_x: true, ..lattice(5, 3, 0.5) };
    l.for_each_bond(|i, j, rest, _, shift| {
        let (xi, yi) = ((i % 5) as f64 * 0.1, (i / 5) as f64 * 0.1);
        let (xj, yj) = ((j % 5) as f64 * 0.1, (j / 5) as f64 * 0.1);
        let r = ((xi - xj + shift).powi(2) + (yi - yj).powi(2)).sqrt();
        assert!((r - rest).abs() < 1e-12, "bond {i}–{j}: {r} against rest {rest}");
    });
}
