//! The sparse machinery of the static solve: the pattern of a network's stiffness over its free
//! degrees of freedom (lower triangle, compressed columns) and its symbolic Cholesky analysis,
//! made once per network and shared through [`Analyses`]; the numeric factor, made into memory
//! kept for the run; and the conjugate gradients that reuse one factor for every tangent near
//! it. Pure: no I/O.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

use super::kept::Kept;
use super::ordering::nested_dissection;
use crate::sim::euclidean_norm;

/// A network's sparsity and symbolic factorisation: what every stiffness matrix of the same
/// nodes, bonds and held axes shares, whatever its springs' stiffness or stretch.
pub(super) struct Analysis {
    /// Column starts of the lower triangle (row ≥ column) over the free dofs.
    col_ptr: Vec<usize>,
    /// Row of each stored entry, sorted within its column.
    row_idx: Vec<usize>,
    /// The elimination order (nested dissection) and the factor's structure.
    symbolic: SymbolicCholesky<usize>,
}

/// The networks analysed so far in one process (or one campaign), at most [`KEPT_ANALYSES`],
/// by a blake3 hash of their structure: the runs of a grid that share a network share its
/// analysis, and one that is being made is waited for, not made twice.
#[derive(Default)]
pub struct Analyses {
    kept: Kept<Analysis, KEPT_ANALYSES>,
}

impl std::fmt::Debug for Analyses {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Analyses({} networks)", self.len())
    }
}

/// Analyses kept: at 10⁶ nodes one holds ~0.3 GB (the pattern and the factor's row indices).
const KEPT_ANALYSES: usize = 2;

impl Analyses {
    /// How many networks have been analysed and are still kept.
    pub fn len(&self) -> usize {
        self.kept.len()
    }

    /// Whether no network has been analysed yet.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The analysis of the network hashed as `key`, made by `make` on a miss.
    pub(super) fn get(&self, key: [u8; 32], make: impl FnOnce() -> Analysis) -> Arc<Analysis> {
        self.kept.get(key, make)
    }
}

impl Analysis {
    /// The analysis of the lower-triangle pattern `columns` (the sorted rows ≥ c of each column
    /// c) over the free dofs, whose nodes lie at `positions` (x, y, one pair per free dof):
    /// nested dissection on the node coordinates, then faer's symbolic Cholesky.
    pub(super) fn of(columns: Vec<Vec<usize>>, positions: &[(f64, f64)]) -> Analysis {
        let mut col_ptr = Vec::with_capacity(columns.len() + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::with_capacity(columns.iter().map(Vec::len).sum());
        for column in columns {
            row_idx.extend(column);
            col_ptr.push(row_idx.len());
        }
        let size = col_ptr.len() - 1;
        let (forward, inverse) = nested_dissection(&col_ptr, &row_idx, positions);
        let pattern = SymbolicSparseColMatRef::new_checked(size, size, &col_ptr, None, &row_idx);
        let permutation = PermRef::new_checked(&forward, &inverse, size);
        let ordering = SymmetricOrdering::Custom(permutation);
        let symbolic = factorize_symbolic_cholesky(pattern, Side::Lower, ordering, CholeskySymbolicParams::default())
            .expect("the symbolic analysis of a stiffness pattern fits in memory");
        Analysis { col_ptr, row_idx, symbolic }
    }

    /// Free degrees of freedom.
    pub(super) fn size(&self) -> usize {
        self.col_ptr.len() - 1
    }

    /// Stored entries of the lower triangle.
    pub(super) fn entries(&self) -> usize {
        self.row_idx.len()
    }

    /// Where entry (row, column), row ≥ column, is stored.
    pub(super) fn slot(&self, row: usize, column: usize) -> usize {
        let start = self.col_ptr[column];
        let rows = &self.row_idx[start..self.col_ptr[column + 1]];
        start + rows.binary_search(&row).expect("every bond's entry is in the pattern")
    }

    /// The diagonal entry of every column in `values`.
    pub(super) fn diagonal<'v>(&self, values: &'v [f64]) -> impl Iterator<Item = f64> + 'v {
        // The diagonal is the first stored row of each column (rows ≥ column, sorted).
        let starts: Vec<usize> = self.col_ptr[..self.size()].to_vec();
        starts.into_iter().map(move |start| values[start])
    }

    /// K v with K the symmetric matrix whose lower triangle is `values`.
    pub(super) fn multiply(&self, values: &[f64], v: &[f64]) -> Vec<f64> {
        let mut product = vec![0.0; v.len()];
        for column in 0..self.size() {
            let (mut sum, v_column) = (0.0, v[column]);
            let stored = self.col_ptr[column]..self.col_ptr[column + 1];
            for (&row, &value) in self.row_idx[stored.clone()].iter().zip(&values[stored]) {
                product[row] += value * v_column;
                if row != column {
                    sum += value * v[row];
                }
            }
            product[column] += sum;
        }
        product
    }
}

/// The sparse Cholesky factor of (K + εI)/s over one [`Analysis`], s the power of two nearest
/// K's largest diagonal entry: factored at unit scale, so that stiffnesses near the ends of the
/// floating-point range (1e±300 N/m) neither overflow nor underflow inside the factorisation,
/// and scaled by a power of two, which is exact both ways. Its values and the work memory of
/// factorising and solving are allocated once and reused by every factorisation of the run.
pub(super) struct Factor {
    analysis: Arc<Analysis>,
    /// L's values.
    values: Vec<f64>,
    /// The shifted, scaled K handed to faer.
    shifted: Vec<f64>,
    /// Work memory of factorising and of solving.
    work: MemBuffer,
    /// s (N/m); 0 until a factorisation succeeded.
    scale: f64,
}

/// Diagonal shift, relative to the largest diagonal entry, that lets Cholesky factor a
/// semi-definite K (zero-energy motions the load does not drive).
pub(super) const REGULARISATION: f64 = 1e-12;

impl Factor {
    /// Room for the factors of `analysis`, nothing factored yet.
    pub(super) fn new(analysis: Arc<Analysis>) -> Factor {
        let symbolic = &analysis.symbolic;
        let work = StackReq::any_of(&[
            symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        ]);
        Factor {
            values: vec![0.0; symbolic.len_val()],
            shifted: vec![0.0; analysis.entries()],
            work: MemBuffer::new(work),
            scale: 0.0,
            analysis,
        }
    }

    /// Factors K + εI (ε = `shift` times the largest diagonal entry, at least
    /// [`REGULARISATION`]), K's lower triangle given by `stiffness`; `false` when K + εI is not
    /// positive definite or not finite.
    pub(super) fn factorise(&mut self, stiffness: &[f64], shift: f64) -> bool {
        self.scale = 0.0;
        let largest = self.analysis.diagonal(stiffness).fold(0.0f64, f64::max);
        if !(largest > 0.0 && largest.is_finite()) {
            return false;
        }
        let scale = 2.0f64.powi(largest.log2().round() as i32);
        self.shifted.iter_mut().zip(stiffness).for_each(|(shifted, k)| *shifted = k / scale);
        for start in &self.analysis.col_ptr[..self.analysis.size()] {
            self.shifted[*start] += shift.max(REGULARISATION) * largest / scale;
        }
        let analysis = &*self.analysis;
        let size = analysis.size();
        let pattern = SymbolicSparseColMatRef::new_checked(size, size, &analysis.col_ptr, None, &analysis.row_idx);
        let factored = analysis.symbolic.factorize_numeric_llt(
            &mut self.values,
            SparseColMatRef::new(pattern, &self.shifted),
            Side::Lower,
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut self.work),
            Default::default(),
        );
        if factored.is_ok() {
            self.scale = scale;
        }
        factored.is_ok()
    }

    /// Whether the last factorisation succeeded.
    pub(super) fn is_factored(&self) -> bool {
        self.scale != 0.0
    }

    /// K⁻¹ `force` = ((K + εI)/s)⁻¹ (force/s); `None` before a factorisation or when the answer is
    /// not finite.
    pub(super) fn solve(&mut self, force: &[f64]) -> Option<Vec<f64>> {
        if self.scale == 0.0 {
            return None;
        }
        let mut u: Vec<f64> = force.iter().map(|f| f / self.scale).collect();
        let factor = LltRef::new(&self.analysis.symbolic, &self.values);
        let column = MatMut::from_column_major_slice_mut(&mut u, force.len(), 1);
        factor.solve_in_place_with_conj(Conj::No, column, Par::Seq, MemStack::new(&mut self.work));
        u.iter().all(|v| v.is_finite()).then_some(u)
    }
}

/// What [`conjugate_gradients`] reached.
pub(super) struct Solved {
    /// The answer.
    pub u: Vec<f64>,
    /// Whether its (recurrence) residual fell to the tolerance asked.
    pub converged: bool,
    /// Solves with the factor it took.
    pub solves: usize,
}

/// Conjugate gradients with the preconditioner `factor` (of a nearby stiffness) stop here: each
/// iteration with a factor of K itself gains ~6 digits, with one of a tangent at a strain of
/// 1e-3 ~3, so more means the factor is too far from K to be worth keeping.
const ITERATIONS: usize = 25;

/// Solves K u = `force` (K's lower triangle `stiffness` over `analysis`) by conjugate gradients
/// preconditioned with `factor`, until the residual ‖f − K u‖ (by the recurrence) is at most
/// `relative` ‖f‖ or [`ITERATIONS`] pass. With the factor of K itself the first iteration is the
/// direct solve and the next ones its iterative refinement; with the factor of a tangent near K
/// (the same network at a strain ε) each iteration gains about log₁₀(1/ε) digits. Stops early,
/// unconverged, where K is not positive along a search direction (pᵀK p ≤ 0) or a solve is not
/// finite. `None` when the first solve is not finite.
pub(super) fn conjugate_gradients(
    analysis: &Analysis,
    stiffness: &[f64],
    factor: &mut Factor,
    force: &[f64],
    relative: f64,
) -> Option<Solved> {
    let target = relative * euclidean_norm(force.iter());
    let mut u = vec![0.0; force.len()];
    let mut residual = force.to_vec();
    if euclidean_norm(residual.iter()) <= target {
        return Some(Solved { u, converged: true, solves: 0 });
    }
    let mut preconditioned = factor.solve(&residual)?;
    let mut direction = preconditioned.clone();
    let mut product: f64 = dot(&residual, &preconditioned);
    let mut solves = 1;
    for _ in 0..ITERATIONS {
        let image = analysis.multiply(stiffness, &direction);
        let curvature = dot(&direction, &image);
        if !(curvature > 0.0 && curvature.is_finite()) {
            break;
        }
        let step = product / curvature;
        u.iter_mut().zip(&direction).for_each(|(u, p)| *u += step * p);
        residual.iter_mut().zip(&image).for_each(|(r, q)| *r -= step * q);
        // Judged before the next solve: with a good factor one iteration is all a correction takes.
        if euclidean_norm(residual.iter()) <= target {
            return Some(Solved { u, converged: true, solves });
        }
        solves += 1;
        let Some(next) = factor.solve(&residual) else { break };
        preconditioned = next;
        let next_product = dot(&residual, &preconditioned);
        let beta = next_product / product;
        product = next_product;
        direction.iter_mut().zip(&preconditioned).for_each(|(p, z)| *p = z + beta * *p);
    }
    Some(Solved { u, converged: false, solves })
}

/// aᵀb.
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(a, b)| a * b).sum()
}
