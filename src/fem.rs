//! The static truss answer: the linear stiffness matrix of the same spring network with the
//! same supports and loads, solved directly (sparse Cholesky, faer). Pure: no I/O.
//!
//! Each spring of stiffness k along the unit vector n̂ between its nodes contributes
//! k n̂ n̂ᵀ to the 2 × 2 blocks (i, i) and (j, j) and −k n̂ n̂ᵀ to (i, j) and (j, i).
//! Held degrees of freedom are removed. A network with zero-energy motions (a square lattice
//! without diagonals under shear, a diluted network that lost rigidity) has a singular K; a
//! factorisation may then return garbage instead of failing, so the answer is accepted only if
//! it satisfies the unregularised equations: ‖K u − f‖ ≤ 1e-6 ‖f‖. Otherwise the load drives a
//! mechanism.

use faer::prelude::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};
use std::time::Instant;

use crate::model::{Bonds, ForceLaw, Linear};
use crate::sim::{Load, euclidean_norm};

/// What the static solver found.
#[derive(Clone, Debug, PartialEq)]
pub enum StaticSolution {
    /// Node displacements (m).
    Displacements {
        /// x displacement of every node.
        ux: Vec<f64>,
        /// y displacement of every node.
        uy: Vec<f64>,
    },
    /// The load drives a zero-stiffness motion; the relative residual ‖K u − f‖/‖f‖ of the best
    /// attempt says by how much the equations fail.
    Mechanism {
        /// ‖K u − f‖ / ‖f‖.
        residual: f64,
    },
    /// The deadline passed before the iteration converged.
    PastDeadline,
}

/// A spring network at rest: node positions, springs (linear, stiffness per bond), held axes
/// and loads.
pub struct Truss<'a> {
    /// Node x positions (m).
    pub x: &'a [f64],
    /// Node y positions (m).
    pub y: &'a [f64],
    /// Springs.
    pub bonds: &'a Bonds,
    /// Nodes held in x.
    pub held_x: &'a [usize],
    /// Nodes held in y.
    pub held_y: &'a [usize],
    /// External forces.
    pub loads: &'a [Load],
    /// Displacements (m) imposed on held axes, as (node, ux, uy); other held axes stay at 0.
    pub prescribed: &'a [(usize, f64, f64)],
}

/// What bounds a relaxation's error, from the tangent stiffness K_t at the static answer
/// ([`Truss::error_bounds`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorBounds {
    /// k_min (N/m): a lower bound on the smallest eigenvalue of K_t, the softest stiffness
    /// (ω_min² = k_min/m sets critical damping and the critically damped bound); 0 when K_t
    /// is singular (a floppy network).
    pub stiffness_min: f64,
    /// ‖K_t⁻¹ g‖₂ (m/N) of the measured quantity gᵀu: its error is at most this × ‖r‖₂ for an
    /// out-of-balance force r; `None` when k_min = 0 or every measured dof is held.
    pub sensitivity: Option<f64>,
}

/// Residuals above this fraction of the load mean the equations have no solution.
const MECHANISM_RESIDUAL: f64 = 1e-6;
/// Diagonal shift, relative to the largest diagonal entry, that lets Cholesky factor a
/// semi-definite K (zero-energy motions the load does not drive).
const REGULARISATION: f64 = 1e-12;

/// Iterative refinements of a solve with the shifted K, at most (each one more solve with the
/// same factor; two are usually all the shift needs).
const REFINEMENTS: usize = 3;

/// Out-of-balance force below this fraction of the load ends the Newton–Raphson iteration ...
pub const NEWTON_TOLERANCE: f64 = 1e-12;
/// ... and so does a correction below this fraction of the displacement: the residual has then
/// reached round-off (k · ε · r per spring), which for stiff springs and small loads can sit
/// above the force tolerance.
const NEWTON_STEP_TOLERANCE: f64 = 1e-14;
/// Newton–Raphson gives up after this many iterations (it converges quadratically: a handful).
const NEWTON_ITERATIONS: usize = 50;

/// Inverse iteration for the softest stiffness stops once its Rayleigh quotient changes by
/// less than this fraction ...
const SOFTEST_TOLERANCE: f64 = 1e-6;
/// ... or after this many solves (each a pair of triangular solves on one factor).
const SOFTEST_ITERATIONS: usize = 200;

/// Numbering of the free degrees of freedom: dof 2i is x of node i, 2i + 1 its y;
/// `index[dof]` is its row in the reduced system, `usize::MAX` when held.
struct Dofs {
    index: Vec<usize>,
    free: usize,
}

impl Truss<'_> {
    /// Solves the linear problem K u = f (springs at their rest geometry) by sparse Cholesky
    /// and checks the answer against the equations.
    pub fn solve_linear(&self) -> StaticSolution {
        let dofs = self.dofs();
        let (mut ux, mut uy) = self.imposed();
        let (mut entries, force) = self.tangent_and_residual(&Linear, &ux, &uy, &dofs);
        let solution = factor_and_solve(dofs.free, &mut entries, &force);
        let residual = solution.as_ref().map_or(f64::INFINITY, |u| relative_residual(&entries, u, &force));
        match solution {
            Some(u) if residual <= MECHANISM_RESIDUAL => {
                let (dx, dy) = self.expand(&dofs, &u);
                for i in 0..ux.len() {
                    ux[i] += dx[i];
                    uy[i] += dy[i];
                }
                StaticSolution::Displacements { ux, uy }
            }
            _ => StaticSolution::Mechanism { residual },
        }
    }

    /// The imposed displacements: zero everywhere but on the prescribed held axes.
    fn imposed(&self) -> (Vec<f64>, Vec<f64>) {
        let (mut ux, mut uy) = (vec![0.0; self.x.len()], vec![0.0; self.x.len()]);
        for &(node, dx, dy) in self.prescribed {
            ux[node] = dx;
            uy[node] = dy;
        }
        (ux, uy)
    }

    /// The force (N, x and y) the supports apply to `nodes` to hold them at displacements
    /// `(ux, uy)`: minus the sum of the spring forces on them.
    pub fn reaction<L: ForceLaw>(&self, law: &L, ux: &[f64], uy: &[f64], nodes: &[usize]) -> (f64, f64) {
        let mut total = (0.0, 0.0);
        for b in 0..self.bonds.len() {
            let (i, j) = (self.bonds.i[b], self.bonds.j[b]);
            let (n, _, tension, _) = self.bond_state(law, b, ux, uy);
            // Spring force on i is −s n̂, on j +s n̂; the support supplies the opposite.
            for (node, sign) in [(i, -1.0), (j, 1.0)] {
                if nodes.contains(&node) {
                    total.0 -= sign * tension * n[0];
                    total.1 -= sign * tension * n[1];
                }
            }
        }
        total
    }

    /// Unit vector n̂ from j to i, length r, tension s and tangent s′ of bond `b` at `(ux, uy)`.
    ///
    /// The extension is taken from the displacements, not from the displaced positions: with
    /// d₀ = xᵢ − xⱼ the bond at rest and Δu = uᵢ − uⱼ, δ = |d₀ + Δu| − |d₀| + δ₀ is computed as
    /// (2 d₀·Δu + |Δu|²)/(|d₀ + Δu| + |d₀|) + δ₀, exact to ε of δ. Summing x + u first would
    /// round u to ε·|x| (7e-15 m at 32 m), and the spring would carry that ulp times k: a
    /// steel block (k = 2e9 N/m) at 10 N per node then never met Newton's 1e-10 of the load.
    /// δ₀ = |d₀| − rest is a spring's pre-stretch ([`pre_stretch`]).
    fn bond_state<L: ForceLaw>(&self, law: &L, b: usize, ux: &[f64], uy: &[f64]) -> ([f64; 2], f64, f64, f64) {
        let (i, j, k, rest) = (self.bonds.i[b], self.bonds.j[b], self.bonds.stiffness[b], self.bonds.rest[b]);
        let (rest_x, rest_y) = (self.x[i] - self.x[j] + self.bonds.shift_x[b], self.y[i] - self.y[j]);
        let (move_x, move_y) = (ux[i] - ux[j], uy[i] - uy[j]);
        let (dx, dy) = (rest_x + move_x, rest_y + move_y);
        let (r, r0) = (dx.hypot(dy), rest_x.hypot(rest_y));
        let stretch = (2.0 * (rest_x * move_x + rest_y * move_y) + move_x * move_x + move_y * move_y) / (r + r0);
        let resolution = f64::EPSILON * (self.x[i].abs() + self.x[j].abs() + self.y[i].abs() + self.y[j].abs());
        let extension = stretch + pre_stretch(r0, rest, resolution);
        ([dx / r, dy / r], r, law.elastic_force(k, extension), law.tangent_stiffness(k, extension))
    }

    /// Solves the full non-linear problem (large rotations, any force law) by Newton–Raphson
    /// from the linear answer of the same network with every spring at its tangent stiffness
    /// at extension `linearised_at` (m; 0 for linear springs; a power law, which has no
    /// stiffness at δ = 0, is linearised at the deformation the load is expected to cause):
    /// R(u) = f + Σ spring forces at x + u, K_t Δu = R, until ‖R‖ ≤ 1e-12 ‖f‖ or
    /// ‖Δu‖ ≤ 1e-14 ‖u‖. The tangent of a spring with tension s along n̂ at length r is
    /// s′(δ) n̂ n̂ᵀ + (s/r)(I − n̂ n̂ᵀ). A mechanism of the linear problem is reported as one;
    /// an iteration that does not converge returns `None`; once the wall clock passes
    /// `deadline` (looked at before every factorisation) it stops with `PastDeadline`.
    pub fn solve_nonlinear<L: ForceLaw>(
        &self,
        law: &L,
        linearised_at: f64,
        deadline: Option<Instant>,
    ) -> Option<StaticSolution> {
        let past = || deadline.is_some_and(|deadline| Instant::now() > deadline);
        if past() {
            return Some(StaticSolution::PastDeadline);
        }
        let mut linearised = self.bonds.clone();
        for k in &mut linearised.stiffness {
            *k = law.tangent_stiffness(*k, linearised_at);
        }
        match (Truss { bonds: &linearised, ..*self }).solve_linear() {
            StaticSolution::Displacements { ux, uy } => self.solve_nonlinear_from(law, ux, uy, deadline),
            mechanism => Some(mechanism),
        }
    }

    /// [`Truss::solve_nonlinear`]'s Newton–Raphson iteration from displacements `(ux, uy)`: for
    /// linear springs, whose tangent at δ = 0 is k itself, from the linear answer the caller
    /// already has (one factorisation fewer, the same answer to the bit).
    pub fn solve_nonlinear_from<L: ForceLaw>(
        &self,
        law: &L,
        mut ux: Vec<f64>,
        mut uy: Vec<f64>,
        deadline: Option<Instant>,
    ) -> Option<StaticSolution> {
        let past = || deadline.is_some_and(|deadline| Instant::now() > deadline);
        let dofs = self.dofs();
        let load_norm = euclidean_norm(self.load_vector(&dofs).iter());
        for _ in 0..NEWTON_ITERATIONS {
            let (mut entries, residual) = self.tangent_and_residual(law, &ux, &uy, &dofs);
            if euclidean_norm(residual.iter()) <= NEWTON_TOLERANCE * load_norm {
                return Some(StaticSolution::Displacements { ux, uy });
            }
            if past() {
                return Some(StaticSolution::PastDeadline);
            }
            let step = factor_and_solve(dofs.free, &mut entries, &residual)?;
            let (dx, dy) = self.expand(&dofs, &step);
            for i in 0..ux.len() {
                ux[i] += dx[i];
                uy[i] += dy[i];
            }
            if euclidean_norm(step.iter())
                <= NEWTON_STEP_TOLERANCE * (euclidean_norm(ux.iter()) + euclidean_norm(uy.iter()))
            {
                return Some(StaticSolution::Displacements { ux, uy });
            }
        }
        None
    }

    /// The displacement increment (m) per unit increase of the load factor at the equilibrium
    /// `(ux, uy)`: K_t Δu = f with the tangent stiffness there (the tangent moduli of a
    /// non-linear network); `None` when K_t cannot be factored.
    pub fn tangent_response<L: ForceLaw>(&self, law: &L, ux: &[f64], uy: &[f64]) -> Option<(Vec<f64>, Vec<f64>)> {
        let dofs = self.dofs();
        let (mut entries, _) = self.tangent_and_residual(law, ux, uy, &dofs);
        let load = self.load_vector(&dofs);
        let step = factor_and_solve(dofs.free, &mut entries, &load)?;
        (relative_residual(&entries, &step, &load) <= MECHANISM_RESIDUAL).then(|| self.expand(&dofs, &step))
    }

    /// What bounds the error of a relaxation near the equilibrium `(ux, uy)`, from one factor
    /// of the tangent stiffness K_t there over the free degrees of freedom; `None` when K_t
    /// cannot be factored or nothing is free.
    ///
    /// `measured` is the measured quantity Q = gᵀu as (dof, weight) pairs (dof 2i is x of node
    /// i, 2i + 1 its y; held dofs drop out, they do not move): for an out-of-balance force r
    /// the state of rest is u* = u + K_t⁻¹ r (exactly for linear springs and small rotations, to
    /// first order in r otherwise), so δQ = gᵀK_t⁻¹ r = zᵀr with z = K_t⁻¹ g, and
    /// |δQ| ≤ ‖z‖₂ ‖r‖₂ (Cauchy–Schwarz). This is at least as tight as ‖g‖₂ ‖r‖₂/k_min and
    /// about √N tighter on an N × N block pulled on its top row, whose ΔL is carried by the
    /// stiff stretching modes, not the soft sway that sets k_min.
    pub fn error_bounds<L: ForceLaw>(
        &self,
        law: &L,
        ux: &[f64],
        uy: &[f64],
        measured: &[(usize, f64)],
    ) -> Option<ErrorBounds> {
        let dofs = self.dofs();
        if dofs.free == 0 {
            return None;
        }
        let (mut entries, _) = self.tangent_and_residual(law, ux, uy, &dofs);
        let factor = Factor::of(dofs.free, &mut entries)?;
        let stiffness_min = softest_stiffness(&factor, &entries, dofs.free)?;
        let mut weights = vec![0.0; dofs.free];
        for &(dof, weight) in measured {
            if let Some(&free) = dofs.index.get(dof).filter(|free| **free != usize::MAX) {
                weights[free] += weight;
            }
        }
        // A singular K_t (k_min = 0) has no inverse to bound by, and a quantity of held dofs
        // alone has no error.
        let sensitivity = (stiffness_min > 0.0 && weights.iter().any(|w| *w != 0.0))
            .then(|| factor.solve(&weights).map(|z| euclidean_norm(z.iter())))
            .flatten();
        Some(ErrorBounds { stiffness_min, sensitivity })
    }

    fn dofs(&self) -> Dofs {
        let mut index = vec![usize::MAX; 2 * self.x.len()];
        let mut free = 0;
        for (dof, slot) in index.iter_mut().enumerate() {
            let held = if dof % 2 == 0 { self.held_x } else { self.held_y };
            if held.binary_search(&(dof / 2)).is_err() {
                *slot = free;
                free += 1;
            }
        }
        Dofs { index, free }
    }

    /// The loads on the free degrees of freedom.
    fn load_vector(&self, dofs: &Dofs) -> Vec<f64> {
        let mut force = vec![0.0; dofs.free];
        for load in self.loads {
            for (dof, value) in [(2 * load.particle, load.fx), (2 * load.particle + 1, load.fy)] {
                if dofs.index[dof] != usize::MAX {
                    force[dofs.index[dof]] += value;
                }
            }
        }
        force
    }

    /// Node displacements from the free ones (held ones are zero).
    fn expand(&self, dofs: &Dofs, u: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let at = |dof: usize| if dofs.index[dof] == usize::MAX { 0.0 } else { u[dofs.index[dof]] };
        ((0..self.x.len()).map(|i| at(2 * i)).collect(), (0..self.x.len()).map(|i| at(2 * i + 1)).collect())
    }

    /// The tangent stiffness entries (row, column, value; repeated pairs add up) over the free
    /// degrees of freedom and the out-of-balance force R = loads + spring forces, at
    /// displacements `(ux, uy)`. Room is kept for one more entry per degree of freedom, the
    /// shift [`factor`] appends.
    fn tangent_and_residual<L: ForceLaw>(
        &self,
        law: &L,
        ux: &[f64],
        uy: &[f64],
        dofs: &Dofs,
    ) -> (Vec<Entry>, Vec<f64>) {
        let mut entries = Vec::with_capacity(16 * self.bonds.len() + dofs.free);
        let mut residual = self.load_vector(dofs);
        for b in 0..self.bonds.len() {
            let (i, j) = (self.bonds.i[b], self.bonds.j[b]);
            let (n, r, tension, tangent) = self.bond_state(law, b, ux, uy);
            // Block A = s′ n̂ n̂ᵀ + (s/r)(I − n̂ n̂ᵀ); the force on i is −s n̂, on j +s n̂.
            let block = |p: usize, q: usize| {
                let identity = if p == q { 1.0 } else { 0.0 };
                tangent * n[p] * n[q] + tension / r * (identity - n[p] * n[q])
            };
            for (a, sign_a) in [(i, 1.0), (j, -1.0)] {
                for (p, n_p) in n.iter().enumerate() {
                    let row = dofs.index[2 * a + p];
                    if row == usize::MAX {
                        continue;
                    }
                    residual[row] -= sign_a * tension * n_p;
                    for (c, sign_c) in [(i, 1.0), (j, -1.0)] {
                        for q in 0..2 {
                            let column = dofs.index[2 * c + q];
                            if column != usize::MAX {
                                entries.push(Triplet { row, col: column, val: sign_a * sign_c * block(p, q) });
                            }
                        }
                    }
                }
            }
        }
        (entries, residual)
    }
}

/// A spring's stretch at the reference positions, |d₀| − rest (m), or 0 where that is below
/// the resolution of the positions, `resolution` = ε(|xᵢ| + |xⱼ| + |yᵢ| + |yⱼ|) (m): a lattice's
/// springs are at rest there by construction, and what differs is the rounding of the
/// positions, which taken literally would pre-stress every spring by k·ε·|x| (1e14 N for
/// k = 1e30 N/m at 1 m, against a load of 1 kN).
fn pre_stretch(length: f64, rest: f64, resolution: f64) -> f64 {
    let stretch = length - rest;
    if stretch.abs() <= 4.0 * (resolution + f64::EPSILON * rest) { 0.0 } else { stretch }
}

/// One entry (row, column, value) of a stiffness matrix over the free degrees of freedom.
pub type Entry = Triplet<usize, usize, f64>;

/// Factors K + εI (ε = 1e-12 of the largest diagonal entry) and solves K u = `force`; `None`
/// when the factorisation fails. The shift leaves u off by about ε‖K⁻¹‖ (6e-11 of E on a
/// 10 × 10 steel block), which iterative refinement with the unshifted K takes off:
/// u ← u + (K + εI)⁻¹(f − K u), while the residual falls at least twofold, at most
/// [`REFINEMENTS`] times (a load on a mechanism's zero mode never lets it fall).
pub fn factor_and_solve(size: usize, entries: &mut Vec<Entry>, force: &[f64]) -> Option<Vec<f64>> {
    if size == 0 {
        return Some(Vec::new());
    }
    let factor = Factor::of(size, entries)?;
    let mut u = factor.solve(force)?;
    let mut residual = out_of_balance(entries, &u, force);
    for _ in 0..REFINEMENTS {
        let correction = factor.solve(&residual)?;
        let refined: Vec<f64> = u.iter().zip(&correction).map(|(a, b)| a + b).collect();
        let left = out_of_balance(entries, &refined, force);
        if euclidean_norm(left.iter()) >= 0.5 * euclidean_norm(residual.iter()) {
            break;
        }
        (u, residual) = (refined, left);
    }
    Some(u)
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

/// A lower bound (N/m) on the smallest eigenvalue k_min of K (given by its `entries` and its
/// `cholesky` factor, `size` free dofs), the network's softest stiffness, by inverse iteration
/// v ← K⁻¹ v/‖·‖ from the uniform displacement (which overlaps the lowest, smooth mode) until
/// the Rayleigh quotient ρ = vᵀK v settles to 1e-6, then lowered by the residual
/// η = ‖K v − ρ v‖: some eigenvalue lies in [ρ − η, ρ + η] (Krylov–Bogoliubov), the lowest one
/// once the iteration has found it. 0 when K is singular (a floppy network); `None` when a
/// solve is not finite.
fn softest_stiffness(factor: &Factor, entries: &[Entry], size: usize) -> Option<f64> {
    let unit = |v: Vec<f64>| {
        let length = euclidean_norm(v.iter());
        v.into_iter().map(|x| x / length).collect::<Vec<f64>>()
    };
    let mut v = unit(vec![1.0; size]);
    let mut rayleigh = f64::INFINITY;
    for iteration in 1..=SOFTEST_ITERATIONS {
        v = unit(factor.solve(&v)?);
        let kv = multiply(entries, &v);
        let next: f64 = kv.iter().zip(&v).map(|(a, b)| a * b).sum();
        let settled = (rayleigh - next).abs() <= SOFTEST_TOLERANCE * next.abs();
        rayleigh = next;
        if settled || iteration == SOFTEST_ITERATIONS {
            let residual: Vec<f64> = kv.iter().zip(&v).map(|(a, b)| a - rayleigh * b).collect();
            return Some((rayleigh - euclidean_norm(residual.iter())).max(0.0));
        }
    }
    None
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

/// ‖K u − f‖ / ‖f‖ with K given by its entries.
fn relative_residual(entries: &[Entry], u: &[f64], force: &[f64]) -> f64 {
    euclidean_norm(out_of_balance(entries, u, force).iter()) / euclidean_norm(force.iter()).max(f64::MIN_POSITIVE)
}
