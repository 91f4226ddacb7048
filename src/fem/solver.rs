//! The static problems of one network, on one symbolic analysis and in one factor's memory: the
//! linear answer (a fresh factor of K, refined), Newton–Raphson's corrections and the responses
//! of the tangent (conjugate gradients preconditioned with the factor at hand, a fresh factor
//! of the tangent only where they stall), and what bounds a relaxation's error (k_min by inverse
//! iteration and ‖K_t⁻¹ g‖ on a fresh factor of the tangent, in the same memory). Pure: no I/O.

use std::sync::{Arc, Mutex};
use std::time::Instant;

use super::sparse::{Analysis, Factor, REGULARISATION, conjugate_gradients, dot};
use super::{Dofs, ErrorBounds, Floppy, StaticAnswer, StaticSolution, Truss, refined_solve};
use crate::model::{ForceLaw, Linear};
use crate::sim::{Preconditioner, euclidean_norm};

/// Residuals above this fraction of the load mean the equations have no solution.
const MECHANISM_RESIDUAL: f64 = 1e-6;

/// Out-of-balance force below this fraction of the load ends the Newton–Raphson iteration ...
pub const NEWTON_TOLERANCE: f64 = 1e-12;
/// ... and so does a correction below this fraction of the displacement: the residual has then
/// reached round-off (k · ε · r per spring), which for stiff springs and small loads can sit
/// above the force tolerance.
const NEWTON_STEP_TOLERANCE: f64 = 1e-14;
/// Newton–Raphson gives up after this many iterations (it converges quadratically: a handful).
const NEWTON_ITERATIONS: usize = 50;
/// A descent from an unstable state ([`Solver::descend`]) first shifts K_t by this fraction of
/// its largest diagonal entry: a floppy mode's only stiffness is the pre-stress s/r, 5e-6 of a
/// steel lattice's k at 1 kN per node (1e3 N / 0.1 m against 2e9 N/m), so the first shift lies
/// well below the negative curvatures met in practice and the factors climb to them (×4 each)
/// in a few tries, and no lower than needed: a shift of 1e-12 (the factor's own) is round-off.
const SMALLEST_DESCENT_SHIFT: f64 = 1e-8;
/// Newton–Raphson gives up after this many steps down Π from unstable states: the buckled
/// networks of the coursework (10 × 10) settle in 4 and 6, 30 diluted networks of the
/// lattice-types study in 1 to 8; the 152 others there that Newton leaves without an answer
/// keep their linear one, as before the descent. Each step costs a factorisation or more: the
/// 8 steps cost that campaign ~10 of its ~16 CPU-s.
const DESCENT_STEPS: usize = 8;
/// A descent stays within this strain of every bond (|δ|/rest): it finds the buckled state of
/// small strains, not one of large rotations and bonds passed through each other, which a
/// network near a mechanism could otherwise fall to under its load.
const DESCENT_STRAIN: f64 = 0.01;
/// A response K_t Δu = f (the tangent moduli, the sensitivity) is solved to this fraction of ‖f‖.
const RESPONSE_TOLERANCE: f64 = 1e-12;
/// A Newton correction is solved to at most this fraction of its ‖R‖ (see [`forcing`]).
const LARGEST_FORCING: f64 = 1e-4;

/// How far a Newton correction K_t Δu = R is solved, as a fraction η of ‖R‖, when the
/// out-of-balance force is `residual` ‖f‖ (inexact Newton: ‖R⁺‖ ≲ η‖R‖ + C‖R‖², so the root is
/// the same and only the work differs). η = ‖R‖/‖f‖ keeps the convergence quadratic, and no
/// tighter than what brings ‖R⁺‖ to a tenth of the tolerance (0.1 · 1e-12 ‖f‖/‖R‖) is needed;
/// at most 1e-4, so each step stays within 1e-4 of the exact Newton step (1e-2 let corrections
/// on diluted, nearly floppy networks wander to another equilibrium). On the 500² lattice at
/// a strain of 1e-3: ‖R‖ = 1e-4 then 1e-8 ‖f‖, η = 1e-4 then 1e-5, two conjugate-gradient solves
/// on the linear factor each, where solving to 1e-12 took four to five.
fn forcing(residual: f64) -> f64 {
    residual.max(0.1 * NEWTON_TOLERANCE / residual).clamp(RESPONSE_TOLERANCE, LARGEST_FORCING)
}

/// Inverse iteration for the softest stiffness stops once its Rayleigh quotient changes by
/// less than this fraction ...
const SOFTEST_TOLERANCE: f64 = 1e-6;
/// ... or after this many solves (each a pair of triangular solves on one factor).
const SOFTEST_ITERATIONS: usize = 200;

/// How a static solve converged: what the run records of it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Convergence {
    /// ‖R‖/‖f‖ at the answer: the out-of-balance force left over the load's norm (NaN
    /// without a load: then the correction's size ended the iteration).
    pub residual: f64,
    /// Numeric factorisations made (each on the one symbolic analysis).
    pub factorisations: usize,
    /// Solves with a factor (pairs of triangular solves), conjugate gradients' included.
    pub solves: usize,
    /// Steps down the potential energy from states whose tangent was not positive definite
    /// ([`Solver::descend`]); 0 where Newton–Raphson alone found the answer.
    pub descents: usize,
}

/// A drive's part of the linear answer over the free degrees of freedom ([`Solver::solve_drive`]):
/// its force −K_fp u_p (N) and the displacements u_f = −K_ff⁻¹K_fp u_p it causes (m).
type DriveAnswer = (Vec<f64>, Vec<f64>);

/// The static problems of one [`Truss`] ([`Truss::solver`]).
pub struct Solver<'a> {
    truss: &'a Truss<'a>,
    dofs: Dofs,
    /// The network's analysis; `None` when nothing is free.
    analysis: Option<Arc<Analysis>>,
    /// The numeric factor, made at the first solve and kept.
    factor: Option<Factor>,
    /// Whether the factor is of `stiffness` as it stands.
    fresh: bool,
    /// The lower triangle of the stiffness last assembled.
    stiffness: Vec<f64>,
    convergence: Convergence,
}

impl<'a> Solver<'a> {
    pub(super) fn new(truss: &'a Truss<'a>, dofs: Dofs, analysis: Option<Arc<Analysis>>) -> Solver<'a> {
        let stiffness = vec![0.0; analysis.as_ref().map_or(0, |a| a.entries())];
        Solver { truss, dofs, analysis, factor: None, fresh: false, stiffness, convergence: Convergence::default() }
    }

    /// How the last Newton–Raphson iteration converged, and the factorisations and solves so far.
    pub fn convergence(&self) -> Convergence {
        self.convergence
    }

    /// The static answer under `law`: the linear answer, then Newton's from it where the springs
    /// are linear (`linear_law`: the linearised network is the network), else from the network
    /// linearised at `linearised_at` ([`Solver::solve_nonlinear`]); Newton is not tried on a
    /// mechanism. Shared between runs through [`super::Answers`].
    pub fn solve_static<L: ForceLaw>(
        &mut self,
        law: &L,
        (linear_law, linearised_at): (bool, f64),
        deadline: Instant,
    ) -> StaticAnswer {
        let linear = self.solve_linear();
        let nonlinear = match (&linear, linear_law) {
            (StaticSolution::Displacements { ux, uy }, true) => {
                self.solve_nonlinear_from(law, ux.clone(), uy.clone(), Some(deadline))
            }
            (StaticSolution::Displacements { .. }, false) => self.solve_nonlinear(law, linearised_at, Some(deadline)),
            _ => None,
        };
        StaticAnswer { linear, nonlinear, residual: self.convergence.residual, descents: self.convergence.descents }
    }

    /// Solves the linear problem about the rest geometry (every spring at its rest length and
    /// direction, first order in the displacements): K_ff u_f = f − K_fp u_p, f the loads and any
    /// pre-stress's forces at rest (N), u_p the imposed displacements (m), on one fresh factor of
    /// K, refined, and checks the answer against the equations. By superposition the drive's
    /// part, −K_ff⁻¹K_fp u_p, is solved on its own, since it tells a drive that a zero-energy
    /// motion takes ([`Solver::solve_drive`]), and the loads' part is added where f ≠ 0: a
    /// velocity drive alone (f = 0) costs one factorisation and one refined solve. Assembled
    /// about the driven state instead, K would carry the driven bonds' tension as geometric
    /// stiffness s/r and f a second-order part: E of a 12 × 11 periodic square strip with
    /// diagonals pulled to a strain of 1e-4 came out 1.8e-3 high (3.0055e11 Pa against the
    /// 3e11 Pa of its first-order answer, which the same strip under force control gives), and
    /// a 300 × 300 one pulled to 1e-3 56 % high: the driven state stretches the top row's bonds
    /// by the whole travel, strain · L_y, there 30 % of a spacing.
    pub fn solve_linear(&mut self) -> StaticSolution {
        let rest = vec![0.0; self.truss.x.len()];
        let loads = self.assemble(&Linear, &rest, &rest);
        let (drive, driven) = match self.solve_drive() {
            Ok(Some((drive, u))) => (drive, Some(u)),
            Ok(None) => (vec![0.0; self.dofs.free], None),
            Err(floppy) => return StaticSolution::Mechanism(floppy),
        };
        let loaded = match &driven {
            Some(_) if loads.iter().all(|f| *f == 0.0) => Some(vec![0.0; self.dofs.free]),
            _ => self.solve_free(&loads),
        };
        let solution = loaded.map(|mut u| {
            if let Some(d) = &driven {
                u.iter_mut().zip(d).for_each(|(u, d)| *u += d);
            }
            u
        });
        let force: Vec<f64> = loads.iter().zip(&drive).map(|(f, d)| f + d).collect();
        let residual = solution.as_ref().map_or(f64::INFINITY, |u| self.relative_residual(u, &force));
        match solution {
            Some(u) if residual <= MECHANISM_RESIDUAL => {
                let (ux, uy) = self.truss.displaced(&self.dofs, &u);
                StaticSolution::Displacements { ux, uy }
            }
            _ => StaticSolution::Mechanism(Floppy::Load { residual }),
        }
    }

    /// The drive's part of the linear answer, with K as assembled at the rest geometry: the
    /// free displacements u_f = −K_ff⁻¹K_fp u_p (m) and their force −K_fp u_p (N); `Ok(None)`
    /// where nothing is imposed. `Err` where the drive meets no stiffness, which the residual
    /// cannot show (K u = f has a solution for every drive, [`Floppy::Drive`]), or where K cannot
    /// be factored ([`Floppy::Load`] with an infinite residual). The stiffness the answer shows
    /// the drive is k_drive = 2E₁/‖u_p‖² (N/m): the answer minimises ½uᵀK u with u_p held, so
    /// k_drive is the Rayleigh quotient along u_p of the stiffness the held nodes feel
    /// (S = K_pp − K_pf K_ff⁻¹ K_fp), 0 exactly when a zero-energy motion takes the drive. It is
    /// judged against εs (N/m), the shift of the factor of K + εI (ε = 1e-12, s the largest
    /// diagonal entry): no stiffness below it is resolved. A floppy drive's round-off lies far
    /// below: the refined residual r ≈ 0.5 ε_mach s ‖u‖ leaves at most ‖r‖²/(4εs) of energy in
    /// the modes the shift blurs, k_drive ≤ ‖r‖²/(2εs‖u_p‖²) ≈ 6e-9 εs ‖u‖²/‖u_p‖²
    /// (ε_mach²/ε² = 5e-8; ‖u‖²/‖u_p‖² ~ the rows the drive moves, 1 to 82 measured). Measured
    /// (12 × 11 of every type, diluted triangular 16² to 64² near p_c and square 16², 32² near
    /// 1/2): floppy drives at most 1e-9 εs, each below its own bound; rigid ones 1.3e4 εs and
    /// more (5e9 εs undiluted).
    fn solve_drive(&mut self) -> Result<Option<DriveAnswer>, Floppy> {
        let imposed = euclidean_norm(self.truss.prescribed.iter().flat_map(|(_, ux, uy)| [ux, uy]));
        if imposed == 0.0 {
            return Ok(None);
        }
        let drive = self.truss.imposed_force(&self.dofs);
        let free = self.solve_free(&drive).ok_or(Floppy::Load { residual: f64::INFINITY })?;
        let (ux, uy) = self.truss.displaced(&self.dofs, &free);
        let stiffness = 2.0 * self.truss.first_order_energy(&ux, &uy) / (imposed * imposed);
        let largest = self.analysis.as_ref().map_or(0.0, |a| a.diagonal(&self.stiffness).fold(0.0, f64::max));
        let resolution = REGULARISATION * largest;
        if stiffness <= resolution {
            return Err(Floppy::Drive { stiffness, resolution });
        }
        Ok(Some((drive, free)))
    }

    /// Solves the full non-linear problem (large rotations, any force law) by Newton–Raphson
    /// from the linear answer of the same network with every spring at its tangent stiffness
    /// at extension `linearised_at` (m; 0 for linear springs; a power law, which has no
    /// stiffness at δ = 0, is linearised at the deformation the load is expected to cause),
    /// whose factor then serves the iteration ([`Solver::solve_nonlinear_from`]). A mechanism of
    /// the linear problem is reported as one.
    pub fn solve_nonlinear<L: ForceLaw>(
        &mut self,
        law: &L,
        linearised_at: f64,
        deadline: Option<Instant>,
    ) -> Option<StaticSolution> {
        if deadline.is_some_and(|deadline| Instant::now() > deadline) {
            return Some(StaticSolution::PastDeadline);
        }
        let mut linearised = self.truss.bonds.clone();
        for k in &mut linearised.stiffness {
            *k = law.tangent_stiffness(*k, linearised_at);
        }
        let truss = Truss { bonds: &linearised, ..*self.truss };
        let mut inner = Solver::new(&truss, self.dofs.clone(), self.analysis.clone());
        inner.factor = self.factor.take();
        let linear = inner.solve_linear();
        (self.factor, self.fresh) = (inner.factor.take(), false);
        self.convergence.factorisations += inner.convergence.factorisations;
        self.convergence.solves += inner.convergence.solves;
        match linear {
            StaticSolution::Displacements { ux, uy } => self.solve_nonlinear_from(law, ux, uy, deadline),
            mechanism => Some(mechanism),
        }
    }

    /// The factor at hand, taken out of this solver as a minimiser's metric: after
    /// [`Solver::error_bounds`], the tangent stiffness K_t at the static answer (positive
    /// definite where k_min > 0). `None` when there is none.
    pub fn take_preconditioner(&mut self) -> Option<StiffnessPreconditioner> {
        let factor = self.factor.take().filter(Factor::is_factored)?;
        self.fresh = false;
        Some(StiffnessPreconditioner { dofs: self.dofs.clone(), factor: Mutex::new(factor) })
    }

    /// Newton–Raphson from displacements `(ux, uy)`: R(u) = f + Σ spring forces at x + u,
    /// K_t Δu = R, until ‖R‖ ≤ 1e-12 ‖f‖ or ‖Δu‖ ≤ 1e-14 ‖u‖. The tangent of a spring with
    /// tension s along n̂ at length r is s′(δ) n̂ n̂ᵀ + (s/r)(I − n̂ n̂ᵀ). Each correction is
    /// solved to [`forcing`]'s fraction of ‖R‖ by conjugate gradients preconditioned with the
    /// factor at hand (the linear K's: the tangent differs from it by terms of the order of the
    /// strain, so each solve gains ~log₁₀(1/strain) digits), and with a fresh factor of K_t on
    /// the network's one symbolic analysis, in the same memory, where they stall (diluted,
    /// nearly floppy networks). An iteration that does not converge returns `None`; once the wall
    /// clock passes `deadline` (looked at before every correction) it stops with `PastDeadline`.
    pub fn solve_nonlinear_from<L: ForceLaw>(
        &mut self,
        law: &L,
        mut ux: Vec<f64>,
        mut uy: Vec<f64>,
        deadline: Option<Instant>,
    ) -> Option<StaticSolution> {
        let load_norm = euclidean_norm(self.truss.load_vector(&self.dofs).iter());
        let (mut iterations, mut shift) = (0, SMALLEST_DESCENT_SHIFT);
        // The descents of this solve: they choose its solves and count against its cap.
        self.convergence.descents = 0;
        while iterations < NEWTON_ITERATIONS {
            let residual = self.assemble(law, &ux, &uy);
            let norm = euclidean_norm(residual.iter());
            self.convergence.residual = norm / load_norm;
            if norm <= NEWTON_TOLERANCE * load_norm {
                return Some(StaticSolution::Displacements { ux, uy });
            }
            if deadline.is_some_and(|deadline| Instant::now() > deadline) {
                return Some(StaticSolution::PastDeadline);
            }
            // Once the iteration has met an unstable state, each Newton step needs K_t itself
            // factored (positive definite): conjugate gradients on an older factor could step
            // back up to the saddle.
            let solved = if self.convergence.descents == 0 {
                self.solve(&residual, forcing(norm / load_norm))
            } else {
                self.solve_fresh(&residual)
            };
            let Some(step) = solved else {
                if self.convergence.descents == DESCENT_STEPS {
                    return None;
                }
                self.descend(law, (&mut ux, &mut uy), &residual, &mut shift)?;
                continue;
            };
            iterations += 1;
            let (dx, dy) = self.dofs.expand(&step);
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

    /// One step down the total potential energy Π from `(ux, uy)`, where the tangent K_t
    /// (assembled there) is not positive definite: an unstable state, such as a floppy mode
    /// under compression at the linear answer, which a Newton step would only find again. The
    /// step solves (K_t + μ s I) Δu = R (R = −∇Π the out-of-balance force, s the largest diagonal
    /// entry) with the least μ of `shift` · 4ⁿ that factors, lowers Π and keeps every bond's
    /// strain within [`DESCENT_STRAIN`]: a trust region, each larger μ a shorter step more nearly
    /// along R. The next step starts from μ/2. `None` when no μ up to 1 does.
    fn descend<L: ForceLaw>(
        &mut self,
        law: &L,
        (ux, uy): (&mut Vec<f64>, &mut Vec<f64>),
        residual: &[f64],
        shift: &mut f64,
    ) -> Option<()> {
        let (before, strained) = self.truss.potential(law, ux, uy, &self.dofs);
        let analysis = self.analysis.clone()?;
        let Solver { truss, dofs, factor, stiffness, convergence, .. } = self;
        let factor = factor.get_or_insert_with(|| Factor::new(analysis));
        // The factor is about to hold K_t + μ s I, not K_t: no solve may take it for K_t's.
        self.fresh = false;
        convergence.descents += 1;
        // A state already strained beyond the limit (a power law's, a pre-stretched bond's)
        // may keep its strain, not grow it.
        let strain_limit = DESCENT_STRAIN.max(strained);
        while *shift <= 1.0 {
            convergence.factorisations += 1;
            if factor.factorise(stiffness, *shift) {
                convergence.solves += 1;
                let (dx, dy) = dofs.expand(&factor.solve(residual)?);
                let tried_x: Vec<f64> = ux.iter().zip(&dx).map(|(u, d)| u + d).collect();
                let tried_y: Vec<f64> = uy.iter().zip(&dy).map(|(u, d)| u + d).collect();
                let (after, strain) = truss.potential(law, &tried_x, &tried_y, dofs);
                if after < before && strain <= strain_limit {
                    (*ux, *uy, *shift) = (tried_x, tried_y, (*shift / 2.0).max(SMALLEST_DESCENT_SHIFT));
                    return Some(());
                }
            }
            *shift *= 4.0;
        }
        None
    }

    /// The displacement increment (m) per unit increase of the load factor at the equilibrium
    /// `(ux, uy)`: K_t Δu = f with the tangent stiffness there (the tangent moduli of a
    /// non-linear network); `None` when K_t cannot be solved.
    pub fn tangent_response<L: ForceLaw>(&mut self, law: &L, ux: &[f64], uy: &[f64]) -> Option<(Vec<f64>, Vec<f64>)> {
        self.assemble(law, ux, uy);
        let load = self.truss.load_vector(&self.dofs);
        let step = if self.dofs.free == 0 { Vec::new() } else { self.solve(&load, RESPONSE_TOLERANCE)? };
        (self.relative_residual(&step, &load) <= MECHANISM_RESIDUAL).then(|| self.dofs.expand(&step))
    }

    /// What bounds the error of a relaxation near the equilibrium `(ux, uy)`, from one fresh
    /// factor of the tangent stiffness K_t there over the free degrees of freedom; `None` when
    /// K_t cannot be factored or nothing is free.
    ///
    /// `measured` is the measured quantity Q = gᵀu as (dof, weight) pairs (dof 2i is x of node
    /// i, 2i + 1 its y; held dofs drop out, they do not move): for an out-of-balance force r
    /// the state of rest is u* = u + K_t⁻¹ r (exactly for linear springs and small rotations, to
    /// first order in r otherwise), so δQ = gᵀK_t⁻¹ r = zᵀr with z = K_t⁻¹ g, and
    /// |δQ| ≤ ‖z‖₂ ‖r‖₂ (Cauchy–Schwarz). This is at least as tight as ‖g‖₂ ‖r‖₂/k_min and
    /// about √N tighter on an N × N block pulled on its top row, whose ΔL is carried by the
    /// stiff stretching modes, not the soft sway that sets k_min.
    pub fn error_bounds<L: ForceLaw>(
        &mut self,
        law: &L,
        ux: &[f64],
        uy: &[f64],
        measured: &[(usize, f64)],
    ) -> Option<ErrorBounds> {
        if self.dofs.free == 0 {
            return None;
        }
        self.assemble(law, ux, uy);
        // A fresh factor of K_t (on the same analysis, in the same memory): a factor of the
        // linear K does not serve inverse iteration where the two differ most, in the soft
        // modes whose only stiffness is geometric (a ladder's sway, a honeycomb's shear).
        if !self.factorise() {
            return None;
        }
        let stiffness_min = self.softest_stiffness()?;
        let mut weights = vec![0.0; self.dofs.free];
        for &(dof, weight) in measured {
            if let Some(&free) = self.dofs.index.get(dof).filter(|free| **free != usize::MAX) {
                weights[free] += weight;
            }
        }
        // A singular K_t (k_min = 0) has no inverse to bound by, and a quantity of held dofs
        // alone has no error.
        let sensitivity = (stiffness_min > 0.0 && weights.iter().any(|w| *w != 0.0))
            .then(|| self.solve(&weights, RESPONSE_TOLERANCE).map(|z| euclidean_norm(z.iter())))
            .flatten();
        Some(ErrorBounds { stiffness_min, sensitivity })
    }

    /// Assembles the tangent stiffness at `(ux, uy)` into `stiffness` and returns the
    /// out-of-balance force there.
    fn assemble<L: ForceLaw>(&mut self, law: &L, ux: &[f64], uy: &[f64]) -> Vec<f64> {
        self.fresh = false;
        match &self.analysis {
            Some(analysis) => self.truss.tangent_and_residual(law, (ux, uy), &self.dofs, analysis, &mut self.stiffness),
            None => Vec::new(),
        }
    }

    /// Factors the stiffness as it stands (memory allocated at the first factorisation, reused
    /// after); `false` when it is not positive definite.
    fn factorise(&mut self) -> bool {
        let Some(analysis) = &self.analysis else { return false };
        let factor = self.factor.get_or_insert_with(|| Factor::new(analysis.clone()));
        self.convergence.factorisations += 1;
        self.fresh = factor.factorise(&self.stiffness, 0.0);
        self.fresh
    }

    /// K u = `force` with the stiffness as it stands: by conjugate gradients on the factor at
    /// hand to `relative` ‖f‖, else with a fresh factor ([`Solver::solve_fresh`]).
    fn solve(&mut self, force: &[f64], relative: f64) -> Option<Vec<f64>> {
        if !self.fresh
            && let (Some(analysis), Some(factor)) = (&self.analysis, &mut self.factor)
            && let Some(solved) = conjugate_gradients(analysis, &self.stiffness, factor, force, relative)
        {
            self.convergence.solves += solved.solves;
            if solved.converged {
                return Some(solved.u);
            }
        }
        self.solve_fresh(force)
    }

    /// K u = `force` over the free degrees of freedom with a fresh factor ([`Solver::solve_fresh`]);
    /// nothing to solve where none is free.
    fn solve_free(&mut self, force: &[f64]) -> Option<Vec<f64>> {
        if self.dofs.free == 0 { Some(Vec::new()) } else { self.solve_fresh(force) }
    }

    /// K u = `force` with a fresh factor of K + εI (ε = 1e-12 of the largest diagonal entry),
    /// refined ([`refined_solve`]); `None` when the factorisation fails.
    fn solve_fresh(&mut self, force: &[f64]) -> Option<Vec<f64>> {
        if !self.fresh && !self.factorise() {
            return None;
        }
        let Solver { analysis, stiffness, factor, convergence, .. } = self;
        let analysis = analysis.as_ref()?;
        refined_solve(
            force,
            |f| {
                convergence.solves += 1;
                factor.as_mut()?.solve(f)
            },
            |u| analysis.multiply(stiffness, u).iter().zip(force).map(|(ku, f)| f - ku).collect(),
        )
    }

    /// One solve with the factor.
    fn factor_solve(&mut self, force: &[f64]) -> Option<Vec<f64>> {
        self.convergence.solves += 1;
        self.factor.as_mut()?.solve(force)
    }

    /// A lower bound (N/m) on the smallest eigenvalue k_min of the stiffness as it stands, the
    /// network's softest stiffness, by inverse iteration on its fresh factor,
    /// v ← K⁻¹ v/‖·‖ from the uniform displacement (which overlaps the lowest, smooth mode),
    /// until the Rayleigh quotient ρ = vᵀK v settles to 1e-6, then lowered by the residual
    /// η = ‖K v − ρ v‖: some eigenvalue lies in [ρ − η, ρ + η] (Krylov–Bogoliubov), the lowest
    /// one once the iteration has found it. 0 when K is singular (a floppy network); `None`
    /// when a solve is not finite.
    fn softest_stiffness(&mut self) -> Option<f64> {
        let unit = |v: Vec<f64>| {
            let length = euclidean_norm(v.iter());
            v.into_iter().map(|x| x / length).collect::<Vec<f64>>()
        };
        let analysis = self.analysis.clone()?;
        let mut v = unit(vec![1.0; self.dofs.free]);
        let mut rayleigh = f64::INFINITY;
        for iteration in 1..=SOFTEST_ITERATIONS {
            v = unit(self.factor_solve(&v)?);
            let kv = analysis.multiply(&self.stiffness, &v);
            let next = dot(&kv, &v);
            let settled = (rayleigh - next).abs() <= SOFTEST_TOLERANCE * next.abs();
            rayleigh = next;
            if settled || iteration == SOFTEST_ITERATIONS {
                let residual: Vec<f64> = kv.iter().zip(&v).map(|(a, b)| a - rayleigh * b).collect();
                return Some((rayleigh - euclidean_norm(residual.iter())).max(0.0));
            }
        }
        None
    }

    /// f − K u with the stiffness as it stands.
    fn out_of_balance(&self, u: &[f64], force: &[f64]) -> Vec<f64> {
        let Some(analysis) = &self.analysis else { return Vec::new() };
        analysis.multiply(&self.stiffness, u).iter().zip(force).map(|(ku, f)| f - ku).collect()
    }

    /// ‖K u − f‖ / ‖f‖ with the stiffness as it stands.
    fn relative_residual(&self, u: &[f64], force: &[f64]) -> f64 {
        euclidean_norm(self.out_of_balance(u, force).iter()) / euclidean_norm(force.iter()).max(f64::MIN_POSITIVE)
    }
}

/// A network's factored stiffness as a minimiser's metric ([`Solver::take_preconditioner`]):
/// z = K⁻¹ f over the free axes, one pair of triangular solves each. The factor's work memory
/// is one per preconditioner, hence the lock.
pub struct StiffnessPreconditioner {
    dofs: Dofs,
    factor: Mutex<Factor>,
}

impl std::fmt::Debug for StiffnessPreconditioner {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StiffnessPreconditioner").field("free", &self.dofs.free).finish_non_exhaustive()
    }
}

impl Preconditioner for StiffnessPreconditioner {
    fn solve(&self, fx: &[f64], fy: &[f64]) -> Option<(Vec<f64>, Vec<f64>)> {
        let force = self.dofs.gather(fx, fy);
        let z = self.factor.lock().ok()?.solve(&force)?;
        Some(self.dofs.expand(&z))
    }
}
