//! `lattice.type`: the fields a lattice of another type than the square takes (one spring k
//! between nearest neighbours, no diagonal families, no probes of the square grid), the sizes
//! each type needs, every type's top row and a network's wave. It takes plain values and
//! knows nothing of `LatticeSpec`, so that it stands below `lattice.rs`, which calls it.

use crate::model::{LatticeType, Layout, PlanarLattice};
use crate::spec::issue::{Issue, require};
use crate::spec::raw::{RawLattice, Supports};
use crate::spec::shared::WaveSpec;

/// The type a lattice asks for, checked against its other fields, its size and whether it is
/// `probed`.
pub(super) fn resolve_type(
    lattice: &RawLattice,
    (nx, ny): (usize, usize),
    supports: Supports,
    probed: bool,
) -> Result<LatticeType, Issue> {
    let kind = lattice.lattice_type.unwrap_or_default();
    if kind.is_square() {
        return Ok(kind);
    }
    let square_only = format!(
        "only for lattice.type: square (a {} lattice has one spring k between nearest neighbours)",
        kind.name()
    );
    for (present, path) in [
        (lattice.diagonals.is_some(), "lattice.diagonals"),
        (lattice.k_diag.is_some(), "lattice.k_diag"),
        (lattice.k_diag_ratio.is_some(), "lattice.k_diag_ratio"),
        (lattice.k_x_ratio.is_some(), "lattice.k_x_ratio"),
        (lattice.k_y_ratio.is_some(), "lattice.k_y_ratio"),
    ] {
        require(!present, path, "(set)", &square_only)?;
    }
    require(
        !probed,
        "probes",
        "(set)",
        "only for lattice.type: square (probes name the rows and columns of the square grid)",
    )?;
    if let Some((field, rule)) = PlanarLattice::size_problem(kind, nx, ny, supports.periodic_x()) {
        let size = if field == "nx" { nx } else { ny };
        require(false, &format!("lattice.{field}"), size, rule)?;
    }
    Ok(kind)
}

/// The top row of a lattice of `kind`, left to right (node indices do not depend on the
/// spacing, so any will do).
pub(super) fn top_row(kind: LatticeType, nx: usize, ny: usize, periodic_x: bool) -> Vec<usize> {
    match kind {
        LatticeType::Square => ((ny - 1) * nx..ny * nx).collect(),
        _ => PlanarLattice { kind, nx, ny, spacing: 1.0, k: 1.0, periodic_x }.layout().edges.top,
    }
}

/// The wave of an impulse lattice of another type than square, of `ny` rows laid out as
/// `layout`: from the kicked top-row node `source` straight down to the bottom row (its
/// distance the node's height, m), N_s = ny − 1 rows.
pub(super) fn network_wave(layout: Layout, source: usize, ny: usize, threshold: f64) -> WaveSpec {
    WaveSpec { source, distance: layout.y[source], receivers: layout.edges.bottom, springs: ny - 1, threshold }
}
