//! A stiffness matrix given as triplets, factored and solved once: for small systems assembled
//! by hand (a packing's stiffness moduli, `study::packing`), where a network's cached
//! analysis ([`super::Analyses`]) has nothing to share. Pure: no I/O.

use faer::prelude::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

use super::refined_solve;
use super::sparse::REGULARISATION;

/// One entry (row, column, value) of a stiffness matrix over the free degrees of freedom.
pub type Entry = Triplet<usize, usize, f64>;

/// Factors K + εI (ε = 1e-12 of the largest diagonal entry) and solves K u = `force`, refined
/// ([`refined_solve`]); `None` when the factorisation fails.
pub fn factor_and_solve(size: usize, entries: &mut Vec<Entry>, force: &[f64]) -> Option<Vec<f64>> {
    if size == 0 {
        return Some(Vec::new());
    }
    let factor = Factor::of(size, entries)?;
    refined_solve(force, |f| factor.solve(f), |u| out_of_balance(entries, u, force))
}

/// The sparse Cholesky factor of (K + εI)/s, s the power of two nearest K's largest diagonal
/// entry: factored at unit scale, so that stiffnesses near the ends of the floating-point range
/// (1e±300 N/m) neither overflow nor underflow inside the factorisation, and scaled by a power
/// of two, which is exact both ways.
struct Factor {
    cholesky: faer::sparse::linalg::solvers::Llt<usize, f64>,
    /// s (N/m).
    scale: f64,
}

impl Factor {
    /// The factor over `size` free degrees of freedom; `None` when the factorisation fails.
    /// The shift ε = 1e-12 of the largest diagonal entry is appended to K's `entries`, and
    /// every entry divided by s, for the assembly, then both undone, instead of assembling from
    /// a copy: at 10⁶ nodes the entries alone are 1.5 GB (16 per bond, 24 bytes each).
    fn of(size: usize, entries: &mut Vec<Entry>) -> Option<Factor> {
        let mut diagonal = vec![0.0f64; size];
        for entry in entries.iter().filter(|e| e.row == e.col) {
            diagonal[entry.row] += entry.val;
        }
        let largest = diagonal.iter().fold(0.0f64, |m, d| m.max(*d));
        if !(largest > 0.0 && largest.is_finite()) {
            return None;
        }
        let scale = 2.0f64.powi(largest.log2().round() as i32);
        let stiffness_entries = entries.len();
        entries.extend((0..size).map(|d| Triplet { row: d, col: d, val: REGULARISATION * largest }));
        entries.iter_mut().for_each(|e| e.val /= scale);
        let matrix = SparseColMat::<usize, f64>::try_new_from_triplets(size, size, entries);
        entries.truncate(stiffness_entries);
        entries.iter_mut().for_each(|e| e.val *= scale);
        Some(Factor { cholesky: matrix.ok()?.sp_cholesky(Side::Lower).ok()?, scale })
    }

    /// K⁻¹ `force` = ((K + εI)/s)⁻¹ (force/s); `None` when the answer is not finite.
    fn solve(&self, force: &[f64]) -> Option<Vec<f64>> {
        let solution = self.cholesky.solve(Mat::from_fn(force.len(), 1, |i, _| force[i] / self.scale));
        let u: Vec<f64> = (0..force.len()).map(|i| solution[(i, 0)]).collect();
        u.iter().all(|v| v.is_finite()).then_some(u)
    }
}

/// K v with K given by its entries.
fn multiply(entries: &[Entry], v: &[f64]) -> Vec<f64> {
    let mut product = vec![0.0; v.len()];
    for entry in entries {
        product[entry.row] += entry.val * v[entry.col];
    }
    product
}

/// f − K u with K given by its entries.
fn out_of_balance(entries: &[Entry], u: &[f64], force: &[f64]) -> Vec<f64> {
    multiply(entries, u).iter().zip(force).map(|(ku, f)| f - ku).collect()
}
