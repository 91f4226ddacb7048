//! `lattice.type`: the fields a lattice of another type than the square takes (one spring k
//! between nearest neighbours, no diagonal families, no probes of the square grid), the sizes
//! each type needs, and every type's layout and wave.

use super::lattice::{LatticeSpec, ProbeLine};
use crate::model::{LatticeType, Layout, PlanarLattice};
use crate::spec::issue::{Issue, require};
use crate::spec::raw::{RawLattice, Supports};
use crate::spec::shared::WaveSpec;

/// The type a lattice asks for, checked against its other fields and its size.
pub(super) fn resolve_type(
    lattice: &RawLattice,
    (nx, ny): (usize, usize),
    supports: Supports,
    probes: &[ProbeLine],
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
        probes.is_empty(),
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

impl LatticeSpec {
    /// The network of a lattice of another type than square, its springs `spacing` (m)
    /// long; `None` for the square lattice (`SquareLattice`, with its families).
    pub fn planar(&self, spacing: f64) -> Option<PlanarLattice> {
        (!self.lattice_type.is_square()).then_some(PlanarLattice {
            kind: self.lattice_type,
            nx: self.nx,
            ny: self.ny,
            spacing,
            k: self.k_x,
            periodic_x: self.supports.periodic_x(),
        })
    }

    /// Node positions and edges as simulated, spacing `spacing` (m): a lattice of another
    /// type loaded along x (`tensile-x`) turned by 90° (the square one is turned in its
    /// resolution, by its families).
    pub fn layout(&self, spacing: f64) -> Layout {
        match self.planar(spacing) {
            None => Layout::square(self.nx, self.ny, spacing, self.supports.periodic_x()),
            Some(planar) if self.rotated => planar.layout().turned(),
            Some(planar) => planar.layout(),
        }
    }
}

/// The wave of an impulse lattice of another type than square: from the kicked top-row node
/// straight down to the bottom row (its distance the node's height, m), N_s = ny − 1 rows.
pub(super) fn network_wave(l: &LatticeSpec, source: usize, spacing: f64, threshold: f64) -> WaveSpec {
    let layout = l.layout(spacing);
    WaveSpec { source, distance: layout.y[source], receivers: layout.edges.bottom, springs: l.ny - 1, threshold }
}
