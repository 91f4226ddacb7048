//! Unit tests of `src/model/planar.rs`, moved out of the library (one test binary).

use mdsolids::model::{LatticeType, PlanarLattice};

fn lattice(kind: LatticeType, nx: usize, ny: usize, periodic_x: bool) -> PlanarLattice {
    PlanarLattice { kind, nx, ny, spacing: 0.1, k: 2.0, periodic_x }
}

/// Bonds per node of every node.
fn coordination(l: &PlanarLattice) -> Vec<usize> {
    let mut z = vec![0; l.layout().len()];
    l.bonds().for_each(|i, j, _, _, _| {
        z[i] += 1;
        z[j] += 1;
    });
    z
}

/// Every bond at rest is a nearest-neighbour pair: |x_i − x_j + shift| = a to 1e-12 of a
/// (round-off of √3), for every type, open and periodic.
#[test]
fn every_bond_is_a_nearest_neighbour_pair() {
    for kind in [LatticeType::Triangular, LatticeType::Honeycomb, LatticeType::Kagome] {
        for periodic in [false, true] {
            let l = lattice(kind, 6, 5, periodic);
            let layout = l.layout();
            l.bonds().for_each(|i, j, rest, _, shift| {
                let r = (layout.x[i] - layout.x[j] + shift).hypot(layout.y[i] - layout.y[j]);
                assert!((r - rest).abs() < 1e-12 && rest == 0.1, "{kind:?} {i}–{j}: {r}");
            });
        }
    }
}

/// A periodic strip's interior rows have the bulk coordination of their type (Maxwell's
/// z: 6, 3, 4), and no pair is bonded twice.
#[test]
fn periodic_interior_has_the_bulk_coordination() {
    for (kind, z_bulk) in [(LatticeType::Triangular, 6), (LatticeType::Honeycomb, 3), (LatticeType::Kagome, 4)] {
        let l = lattice(kind, 8, 9, true);
        let (layout, z) = (l.layout(), coordination(&l));
        let interior = |n: usize| layout.y[n] > 0.1 && layout.y[n] < layout.edges.height - 0.1;
        assert!((0..z.len()).filter(|&n| interior(n)).all(|n| z[n] == z_bulk), "{kind:?}: {z:?}");
        assert_eq!(z_bulk as f64, kind.coordination());
        let bonds = l.bonds();
        let mut pairs: Vec<(usize, usize)> = (0..bonds.len()).map(|b| (bonds.i[b], bonds.j[b])).collect();
        pairs.iter_mut().for_each(|p| *p = (p.0.min(p.1), p.0.max(p.1)));
        pairs.sort_unstable();
        pairs.dedup();
        assert_eq!(pairs.len(), bonds.len(), "{kind:?}");
    }
}

/// The area per node is the block's area over its nodes, to O(1/n) of the edges: a
/// periodic strip of nx × ny nodes covers nx·pitch × (ny − 1)·row distance plus one row.
#[test]
fn area_per_node_is_the_block_area_over_its_nodes() {
    for kind in [LatticeType::Triangular, LatticeType::Honeycomb, LatticeType::Kagome] {
        let l = lattice(kind, 40, 41, true);
        let layout = l.layout();
        let area = layout.edges.width * layout.edges.height * 41.0 / 40.0;
        let per_node = area / layout.len() as f64;
        let expected = kind.area_per_node(0.1);
        // Kagome's 41 rows are 21 full and 20 sparse: the extra full row is the 1/41 off.
        let tolerance = if kind == LatticeType::Kagome { 0.03 } else { 1e-9 };
        assert!((per_node / expected - 1.0).abs() < tolerance, "{kind:?}: {per_node} against {expected}");
    }
}

/// Edges: the bottom row sits at y = 0 and the top at the height; the columns run
/// bottom to top; turned, the old left column is the new bottom row.
#[test]
fn edges_name_the_rows_and_columns() {
    let layout = lattice(LatticeType::Triangular, 4, 3, false).layout();
    assert_eq!(layout.edges.bottom, vec![0, 1, 2, 3]);
    assert_eq!(layout.edges.top, vec![8, 9, 10, 11]);
    assert_eq!(layout.edges.left, vec![0, 4, 8]);
    assert_eq!(layout.edges.right, vec![3, 7, 11]);
    assert!((layout.edges.height - 0.1 * 3.0_f64.sqrt()).abs() < 1e-15);
    let turned = layout.clone().turned();
    assert_eq!(turned.edges.bottom, layout.edges.left);
    assert!(turned.edges.bottom.iter().all(|&n| turned.y[n] <= 0.05 + 1e-15));
    assert!(turned.edges.top.iter().all(|&n| (turned.y[n] - 0.3).abs() <= 0.05 + 1e-15));
    let kagome = lattice(LatticeType::Kagome, 5, 5, false).layout();
    // Rows: 5 full, 2 sparse (over bonds 0–1, 2–3), 5 full, 2 sparse (1–2, 3–4), 5 full.
    assert_eq!(kagome.len(), 19);
    assert_eq!(kagome.edges.left, vec![0, 7, 14]);
    assert_eq!(kagome.edges.top, (14..19).collect::<Vec<_>>());
}
