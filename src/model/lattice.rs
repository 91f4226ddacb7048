//! The square lattice as a stencil: node (ix, iy) at index iy·nx + ix, and four bond families
//! with one stiffness each; the triangular lattice is the same stencil with its odd rows
//! shifted by a/2 and one diagonal family between each pair of rows (`staggered`). Regular
//! lattices keep this compact form (no bond list: the force loop walks rows), irregular
//! networks use [`Bonds`].

use super::bonds::Bonds;

/// An nx × ny square lattice with spacing a and per-family stiffness (0 = family absent):
/// `k_x` to the right neighbour and `k_y` to the upper one (rest a), `k_rising` across
/// (ix, iy)–(ix+1, iy+1) and `k_falling` across (ix+1, iy)–(ix, iy+1) (rest a√2).
/// An n × 1 lattice is the linear chain.
///
/// `staggered`: the triangular lattice of spacing a, node (ix, iy) at ((ix + (iy mod 2)/2) a,
/// iy a√3/2) as `model::planar` lays it out. Node (ix, iy) of an even row meets (ix, iy+1) and
/// (ix−1, iy+1) above it, of an odd row (ix, iy+1) and (ix+1, iy+1): the "vertical" family and,
/// between rows iy and iy+1, only the falling diagonals (iy even) or only the rising ones
/// (iy odd), every bond of rest length a ([`SquareLattice::diagonals_above`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SquareLattice {
    /// Nodes per row.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
    /// Spacing a = rest length of the axial springs (m).
    pub spacing: f64,
    /// Stiffness constant of the horizontal springs.
    pub k_x: f64,
    /// Stiffness constant of the vertical springs.
    pub k_y: f64,
    /// Stiffness constant of the rising diagonals (ix, iy)–(ix+1, iy+1).
    pub k_rising: f64,
    /// Stiffness constant of the falling diagonals (ix+1, iy)–(ix, iy+1).
    pub k_falling: f64,
    /// Bonds wrap across the left and right sides (period nx · a), as if the lattice were a
    /// strip of an infinite one; needs nx ≥ 3.
    pub periodic_x: bool,
    /// The triangular lattice (type docs): rows shifted alternately, one diagonal family per
    /// pair of rows, all rests a.
    pub staggered: bool,
}

impl SquareLattice {
    /// The chain of `nodes` particles joined by springs `k` of rest length `spacing`: an
    /// `nodes × 1` lattice.
    pub fn chain(nodes: usize, spacing: f64, k: f64) -> SquareLattice {
        SquareLattice {
            nx: nodes,
            ny: 1,
            spacing,
            k_x: k,
            k_y: 0.0,
            k_rising: 0.0,
            k_falling: 0.0,
            periodic_x: false,
            staggered: false,
        }
    }

    /// The triangular lattice of `nx` × `ny` nodes, springs `k` of rest length `spacing` on
    /// every bond, as the staggered stencil (type docs).
    pub fn triangular(nx: usize, ny: usize, spacing: f64, k: f64, periodic_x: bool) -> SquareLattice {
        SquareLattice { nx, ny, spacing, k_x: k, k_y: k, k_rising: k, k_falling: k, periodic_x, staggered: true }
    }

    /// Index of node (ix, iy).
    pub fn node(&self, ix: usize, iy: usize) -> usize {
        iy * self.nx + ix
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// True for a lattice without nodes.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Rest length of the diagonals, a√2 (m); a for the staggered (triangular) lattice.
    pub fn diagonal_rest(&self) -> f64 {
        if self.staggered { self.spacing } else { self.spacing * std::f64::consts::SQRT_2 }
    }

    /// Stiffness (rising, falling) of the diagonals between rows `iy` and `iy + 1`: both
    /// families on the square lattice, one of them, the other 0, on the staggered one.
    #[inline(always)]
    pub fn diagonals_above(&self, iy: usize) -> (f64, f64) {
        match (self.staggered, iy % 2) {
            (false, _) => (self.k_rising, self.k_falling),
            (true, 0) => (0.0, self.k_falling),
            (true, _) => (self.k_rising, 0.0),
        }
    }

    /// Period along x, nx · a (m), of a periodic lattice.
    pub fn period(&self) -> f64 {
        self.nx as f64 * self.spacing
    }

    /// Number of bonds.
    pub fn bond_count(&self) -> usize {
        let (nx, ny) = (self.nx, self.ny);
        let present = |k: f64| usize::from(k != 0.0);
        let columns = if self.periodic_x { nx } else { nx.saturating_sub(1) };
        let diagonals: usize = (0..ny.saturating_sub(1))
            .map(|iy| {
                let (rising, falling) = self.diagonals_above(iy);
                present(rising) + present(falling)
            })
            .sum();
        present(self.k_x) * ny * columns + present(self.k_y) * nx * ny.saturating_sub(1) + diagonals * columns
    }

    /// Calls `visit(i, j, rest, k, shift_x)` for every bond, in node order; the bond's
    /// separation is x_i − x_j + shift_x (shift_x = ∓ period for bonds that wrap, else 0).
    pub fn for_each_bond(&self, mut visit: impl FnMut(usize, usize, f64, f64, f64)) {
        let (a, d) = (self.spacing, self.diagonal_rest());
        let columns = if self.periodic_x { self.nx } else { self.nx - 1 };
        for iy in 0..self.ny {
            let (k_rising, k_falling) = self.diagonals_above(iy);
            for ix in 0..self.nx {
                let here = self.node(ix, iy);
                let up = iy + 1 < self.ny;
                if ix >= columns {
                    continue;
                }
                // The right neighbour; across the right side it is node 0 one period on.
                let (right, shift) = if ix + 1 < self.nx { (ix + 1, 0.0) } else { (0, -self.period()) };
                if self.k_x != 0.0 {
                    visit(here, self.node(right, iy), a, self.k_x, shift);
                }
                if up && k_rising != 0.0 {
                    visit(here, self.node(right, iy + 1), d, k_rising, shift);
                }
                if up && k_falling != 0.0 {
                    visit(self.node(right, iy), self.node(ix, iy + 1), d, k_falling, -shift);
                }
            }
            if iy + 1 < self.ny && self.k_y != 0.0 {
                for ix in 0..self.nx {
                    visit(self.node(ix, iy), self.node(ix, iy + 1), a, self.k_y, 0.0);
                }
            }
        }
    }

    /// The same springs as an explicit bond list, in node order (for irregular variants of a
    /// lattice, and as the reference the stencil is tested against).
    pub fn bonds(&self) -> Bonds {
        let mut bonds = Bonds::default();
        self.for_each_bond(|i, j, rest, k, shift| bonds.push_shifted(i, j, rest, k, shift));
        bonds
    }
}
