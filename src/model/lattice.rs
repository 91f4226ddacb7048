//! The square lattice as a stencil: node (ix, iy) at index iy·nx + ix, and four bond families
//! with one stiffness each. Regular lattices keep this compact form (no bond list: the force
//! loop walks rows), irregular networks use [`Bonds`].

use super::bonds::Bonds;

/// An nx × ny square lattice with spacing a and per-family stiffness (0 = family absent):
/// `k_x` to the right neighbour and `k_y` to the upper one (rest a), `k_rising` across
/// (ix, iy)–(ix+1, iy+1) and `k_falling` across (ix+1, iy)–(ix, iy+1) (rest a√2).
/// An n × 1 lattice is the linear chain.
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
}

impl SquareLattice {
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

    /// Rest length of the diagonals, a√2 (m).
    pub fn diagonal_rest(&self) -> f64 {
        self.spacing * std::f64::consts::SQRT_2
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
        present(self.k_x) * ny * columns
            + present(self.k_y) * nx * ny.saturating_sub(1)
            + (present(self.k_rising) + present(self.k_falling)) * columns * ny.saturating_sub(1)
    }

    /// Calls `visit(i, j, rest, k, shift_x)` for every bond, in node order; the bond's
    /// separation is x_i − x_j + shift_x (shift_x = ∓ period for bonds that wrap, else 0).
    pub fn for_each_bond(&self, mut visit: impl FnMut(usize, usize, f64, f64, f64)) {
        let (a, d) = (self.spacing, self.diagonal_rest());
        let columns = if self.periodic_x { self.nx } else { self.nx - 1 };
        for iy in 0..self.ny {
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
                if up && self.k_rising != 0.0 {
                    visit(here, self.node(right, iy + 1), d, self.k_rising, shift);
                }
                if up && self.k_falling != 0.0 {
                    visit(self.node(right, iy), self.node(ix, iy + 1), d, self.k_falling, -shift);
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
