//! Unit tests of `src/model/lattice.rs`, moved out of the library (one test binary).

use mdsolids::model::SquareLattice;

fn lattice(nx: usize, ny: usize, k_diag: f64) -> SquareLattice {
    SquareLattice {
        nx,
        ny,
        spacing: 0.1,
        k_x: 3.0,
        k_y: 3.0,
        k_rising: k_diag,
        k_falling: k_diag,
        periodic_x: false,
        staggered: false,
    }
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

/// The staggered stencil is the triangular lattice `model::planar` builds on its own: the same
/// springs (ends, rest a, k, and the period across a periodic side), free and periodic, at even
/// and odd row counts; and its count is that of its list.
#[test]
fn the_staggered_stencil_is_the_triangular_lattice() {
    use mdsolids::model::{Bonds, LatticeType, PlanarLattice};
    let springs = |bonds: &Bonds| {
        let mut list: Vec<(usize, usize, u64, u64, i64)> = (0..bonds.len())
            .map(|b| {
                let (i, j, shift) = (bonds.i[b], bonds.j[b], bonds.shift_x[b]);
                // One orientation: from the lower index, the shift turning with the bond.
                let (low, high, shift) = if i < j { (i, j, shift) } else { (j, i, -shift) };
                (low, high, bonds.rest[b].to_bits(), bonds.stiffness[b].to_bits(), shift.round() as i64)
            })
            .collect();
        list.sort_unstable();
        list
    };
    for (nx, ny, periodic_x) in [(5, 4, false), (6, 5, false), (6, 4, true), (5, 5, true)] {
        let stencil = SquareLattice::triangular(nx, ny, 1.0, 2.0, periodic_x);
        let planar = PlanarLattice { kind: LatticeType::Triangular, nx, ny, spacing: 1.0, k: 2.0, periodic_x };
        assert_eq!(springs(&stencil.bonds()), springs(&planar.bonds()), "{nx} x {ny}, periodic {periodic_x}");
        assert_eq!(stencil.bond_count(), stencil.bonds().len());
    }
}
