//! Connectivity: which particle pairs are joined by a spring, with rest length and stiffness.
//! Builders lay bonds out in particle order (row by row) so the force loop reads memory
//! sequentially.

/// Which diagonal springs a square lattice has.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Diagonals {
    /// Nearest neighbours only (no shear stiffness).
    None,
    /// Both diagonals of every cell.
    Both,
}

/// Bond list in structure-of-arrays form: bond `b` joins particles `i[b]` and `j[b]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bonds {
    /// First particle of each bond.
    pub i: Vec<usize>,
    /// Second particle of each bond.
    pub j: Vec<usize>,
    /// Rest length x_e (m): δ = |x_i − x_j| − x_e.
    pub rest: Vec<f64>,
    /// Stiffness constant of each bond: k (N/m) for linear, C (N/m^β) for power-law springs.
    pub stiffness: Vec<f64>,
}

impl Bonds {
    /// Number of bonds.
    pub fn len(&self) -> usize {
        self.i.len()
    }

    /// True when there are no bonds.
    pub fn is_empty(&self) -> bool {
        self.i.is_empty()
    }

    /// Appends a bond between `i` and `j`.
    pub fn push(&mut self, i: usize, j: usize, rest: f64, stiffness: f64) {
        self.i.push(i);
        self.j.push(j);
        self.rest.push(rest);
        self.stiffness.push(stiffness);
    }

    /// Square lattice of `nx × ny` nodes, node `(ix, iy)` at index `iy·nx + ix`, spacing `a`:
    /// springs `k` to the right and upper neighbours (rest `a`) and, with
    /// [`Diagonals::Both`], springs `k_diag` across both diagonals of each cell (rest `a√2`).
    /// An `n × 1` lattice is the linear chain (bonds `(p, p+1)`).
    pub fn square_lattice(nx: usize, ny: usize, a: f64, k: f64, diagonals: Diagonals, k_diag: f64) -> Bonds {
        let node = |ix: usize, iy: usize| iy * nx + ix;
        let mut bonds = Bonds::default();
        for iy in 0..ny {
            for ix in 0..nx {
                if ix + 1 < nx {
                    bonds.push(node(ix, iy), node(ix + 1, iy), a, k);
                }
                if iy + 1 < ny {
                    bonds.push(node(ix, iy), node(ix, iy + 1), a, k);
                }
                if diagonals == Diagonals::Both && ix + 1 < nx && iy + 1 < ny {
                    bonds.push(node(ix, iy), node(ix + 1, iy + 1), a * std::f64::consts::SQRT_2, k_diag);
                    bonds.push(node(ix + 1, iy), node(ix, iy + 1), a * std::f64::consts::SQRT_2, k_diag);
                }
            }
        }
        bonds
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn n_by_one_lattice_is_the_chain() {
        let lattice = Bonds::square_lattice(5, 1, 0.1, 3.0, Diagonals::Both, 1.0);
        assert_eq!(lattice.i, vec![0, 1, 2, 3]);
        assert_eq!(lattice.j, vec![1, 2, 3, 4]);
        assert!(lattice.rest.iter().all(|&r| r == 0.1));
    }

    #[test]
    fn lattice_bond_count() {
        // nx(ny−1) + ny(nx−1) axial bonds and 2(nx−1)(ny−1) diagonals.
        let (nx, ny) = (4, 3);
        let bonds = Bonds::square_lattice(nx, ny, 1.0, 1.0, Diagonals::Both, 0.5);
        assert_eq!(bonds.len(), nx * (ny - 1) + ny * (nx - 1) + 2 * (nx - 1) * (ny - 1));
    }
}
