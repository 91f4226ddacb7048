//! Relaxation by minimisation: instead of integrating damped motion in time, walk the
//! positions down the potential energy minus the loads' work, Π(x) = U(x) − Σ F·(x − x₀), whose
//! gradient is minus the static force (springs and loads, holds applied) that
//! `integrate::static_forces` gives for every force field and spring law. Two methods:
//! FIRE 2.0 ([`fire`]) and non-linear conjugate gradients ([`cg`]). Both stop on the
//! relaxation's static criterion (the displacement bound ‖r‖₂ ≤ `residual_norm`, else the
//! largest force ≤ `residual_force`); neither has a physical time. Pure: no I/O.

mod cg;
mod fire;

use serde::{Deserialize, Serialize};
use std::sync::Arc;
use std::time::Instant;

use super::field::ForceField;
use super::integrate::static_forces;
use super::run::{Relaxation, RunStatus, Sampling, Start, Trace};
use super::state::State;

/// How a loaded structure is brought to rest.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RelaxMethod {
    /// Damped molecular dynamics in time (the dissipation the coursework asks about).
    #[default]
    Damped,
    /// FIRE 2.0 (Guénolé et al., Comput. Mater. Sci. 175 (2020) 109584), semi-implicit Euler.
    Fire,
    /// Non-linear conjugate gradients, Polak–Ribière+, with a secant line search.
    Cg,
    /// No relaxation: the positions are set to the static solution of the same network
    /// ([`crate::fem::Solver::solve_static`], which every loaded lattice solves beside its
    /// run) and measured there, for scenes that ask what a network does at rest (isotropy,
    /// rigidity percolation) and gain nothing from MD.
    Static,
}

impl RelaxMethod {
    /// Every method, in the order docs/campaigns.md lists them (`relax.method`).
    pub const ALL: [RelaxMethod; 4] = [RelaxMethod::Damped, RelaxMethod::Fire, RelaxMethod::Cg, RelaxMethod::Static];

    /// The word in YAML and in the results table.
    pub fn name(self) -> &'static str {
        match self {
            RelaxMethod::Damped => "damped",
            RelaxMethod::Fire => "fire",
            RelaxMethod::Cg => "cg",
            RelaxMethod::Static => "static",
        }
    }

    /// True for the minimisers, FIRE and CG: with no time and no static answer to stop at, they
    /// stop only on the static criterion, so a relaxation by one needs a tolerance (the spec
    /// gives it one by default). Every method is named here, so that a new one must say
    /// whether it is a minimiser.
    pub fn is_minimiser(self) -> bool {
        match self {
            RelaxMethod::Fire | RelaxMethod::Cg => true,
            RelaxMethod::Damped | RelaxMethod::Static => false,
        }
    }
}

/// What FIRE may move in instead of the particles' masses (`relax.preconditioner`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PreconditionerKind {
    /// The masses: m v̇ = F, FIRE as published.
    #[default]
    None,
    /// The network's tangent stiffness K_t at the static answer the run solves beside it, whose
    /// factor the error bound makes: K_t v̇ = F (preconditioned FIRE: Packwood et al., J. Chem.
    /// Phys. 144 (2016) 164109).
    Stiffness,
}

impl PreconditionerKind {
    /// The word in YAML and in the results table.
    pub fn name(self) -> &'static str {
        match self {
            PreconditionerKind::None => "none",
            PreconditionerKind::Stiffness => "stiffness",
        }
    }
}

/// A symmetric positive definite P (N/m) over the particles' axes that a minimiser moves in:
/// z = P⁻¹ f. Held axes have f = 0 and z = 0. Made outside the physics core (the static
/// solver's factor), used here.
pub trait Preconditioner: std::fmt::Debug + Send + Sync {
    /// z = P⁻¹ f (m) for the force f (N) on every particle's x and y; `None` when the answer
    /// is not finite.
    fn solve(&self, fx: &[f64], fy: &[f64]) -> Option<(Vec<f64>, Vec<f64>)>;
}

/// Every particle's x and y (m).
type Positions = (Vec<f64>, Vec<f64>);

/// The preconditioner a scene's minimiser moves in, shared by the runs of one relaxation (the
/// tangent step's second one too).
pub type SharedPreconditioner = Arc<dyn Preconditioner>;

/// The static force (springs and loads, no damping, held axes zero) at the state's positions,
/// −∇Π, with scratch for the zero velocities the force field is called with.
#[derive(Default)]
struct Gradient {
    fx: Vec<f64>,
    fy: Vec<f64>,
    zeros: Vec<f64>,
}

impl Gradient {
    /// Evaluates the static force at `state`'s positions.
    fn evaluate<F: ForceField>(&mut self, state: &State, field: &mut F) {
        static_forces(state, field, &mut self.fx, &mut self.fy, &mut self.zeros);
    }

    /// ‖r‖₂ (N) over every axis (held axes are zero).
    fn norm(&self) -> f64 {
        euclidean_norm(self.fx.iter().chain(&self.fy))
    }

    /// The largest |r| (N) on any axis.
    fn largest(&self) -> f64 {
        largest(&self.fx, &self.fy)
    }
}

/// One method's iteration: from positions whose static force is `force`, a move that ends with
/// `force` evaluated at the new positions. Returns the force evaluations it took, or why it
/// cannot go on.
trait Minimiser {
    fn iterate<F: ForceField>(&mut self, state: &mut State, field: &mut F, force: &mut Gradient)
    -> Result<u64, String>;

    /// At rest after its first move by construction (the static solution), whatever the static
    /// criterion says; otherwise it stops on that criterion.
    const SETTLES_IN_ONE_MOVE: bool = false;
}

/// [`RelaxMethod::Static`]: one move, to the positions (m, x and y) of the static solution.
struct Settle<'a>(&'a Positions);

impl Minimiser for Settle<'_> {
    const SETTLES_IN_ONE_MOVE: bool = true;

    fn iterate<F: ForceField>(
        &mut self,
        state: &mut State,
        field: &mut F,
        force: &mut Gradient,
    ) -> Result<u64, String> {
        state.particles.x.clone_from(&self.0.0);
        state.particles.y.clone_from(&self.0.1);
        force.evaluate(state, field);
        Ok(1)
    }
}

/// True when the static force `force` meets the relaxation's static criterion, with the name of
/// that criterion: ‖r‖₂ ≤ `residual_norm` (the displacement bound) when set, else the largest
/// |r| ≤ `residual_force`; `None` when the rule has neither (minimisers have no kinetic ratio).
fn static_criterion(rule: &Relaxation, force: &Gradient) -> Option<(bool, &'static str)> {
    match (rule.residual_norm, rule.residual_force) {
        (Some(limit), _) => Some((force.norm() <= limit, "displacement_bound")),
        (None, Some(limit)) => Some((force.largest() <= limit, "residual_force")),
        (None, None) => None,
    }
}

/// Relaxes `state` under `field` by `method` (to `rest`, the static solution's positions, for
/// `Static`; FIRE in the metric of `preconditioner` when given) for at
/// most `sampling.steps` force evaluations, until the static criterion of
/// `sampling.relaxation` holds or `sampling.deadline` passes. The trace holds the start and the
/// end; `steps` counts force evaluations (an MD step costs one), `time` FIRE's pseudo-time.
/// The energy the minimiser took out is booked as dissipated, so that
/// E_kin + E_pot + dissipated = E(0) + the loads' work holds at the end. `None` for `Damped`,
/// which is the time loop's.
pub fn minimise<F: ForceField>(
    method: RelaxMethod,
    (rest, preconditioner): (Option<&Positions>, Option<&SharedPreconditioner>),
    state: &mut State,
    field: &mut F,
    sampling: &Sampling,
) -> Option<Trace> {
    match (method, rest) {
        (RelaxMethod::Damped, _) => None,
        (RelaxMethod::Fire, _) => {
            let mut fire = match preconditioner {
                Some(p) => fire::Fire::preconditioned(p.clone()),
                None => fire::Fire::new(sampling.dt),
            };
            Some(run(&mut fire, state, field, sampling))
        }
        (RelaxMethod::Cg, _) => Some(run(&mut cg::ConjugateGradients::new(&*field), state, field, sampling)),
        (RelaxMethod::Static, Some(rest)) => Some(run(&mut Settle(rest), state, field, sampling)),
        (RelaxMethod::Static, None) => Some(Trace {
            status: RunStatus::NoEquilibrium,
            message: "relax.method: static, but the static solver found no equilibrium to set the positions to".into(),
            ..Trace::default()
        }),
    }
}

fn run<F: ForceField, M: Minimiser>(method: &mut M, state: &mut State, field: &mut F, sampling: &Sampling) -> Trace {
    let start = Start::of(state);
    let mut trace = Trace::default();
    let mut force = Gradient::default();
    force.evaluate(state, field);
    let energy_0 = state.particles.kinetic_energy() + field.potential_energy(&state.particles.x, &state.particles.y);
    if let Err(reason) = trace.sample(state, &*field, &start, sampling.displacements) {
        trace.status = RunStatus::Unstable;
        trace.message = format!("{reason} at the start");
        return trace;
    }
    let started = Instant::now();
    let (evaluations, stop) = descend(method, state, field, &mut force, sampling, started);
    let relaxed_by = match stop {
        Stop::Relaxed(criterion) => Some(criterion),
        Stop::Failed(status, message) => {
            (trace.status, trace.message) = (status, message);
            None
        }
    };
    trace.loop_s = started.elapsed().as_secs_f64();
    state.account_load_work(1.0);
    let p = &state.particles;
    state.dissipated = energy_0 + state.load_work() - p.kinetic_energy() - field.potential_energy(&p.x, &p.y);
    state.steps = evaluations;
    if let Err(reason) = trace.sample(state, &*field, &start, sampling.displacements) {
        trace.status = RunStatus::Unstable;
        trace.message = format!("{reason} at the end of the minimisation");
    }
    if trace.status == RunStatus::Ok {
        trace.relaxed_at = Some(state.time);
        trace.relaxed_by = relaxed_by.map(str::to_string);
    }
    trace.residual_norm = Some(force.norm());
    trace.steps = evaluations;
    trace
}

/// Why a minimisation stopped.
enum Stop {
    /// At rest, by the criterion named.
    Relaxed(&'static str),
    /// Not at rest: the run's status and why.
    Failed(RunStatus, String),
}

/// Moves `state` by `method` from positions whose static force is `force` until it is at rest
/// or cannot go on; returns the force evaluations taken (the start's one counted) and why it
/// stopped.
fn descend<F: ForceField, M: Minimiser>(
    method: &mut M,
    state: &mut State,
    field: &mut F,
    force: &mut Gradient,
    sampling: &Sampling,
    started: Instant,
) -> (u64, Stop) {
    let mut evaluations = 1;
    loop {
        if let Some(stop) = stop_before_move::<M>(force, evaluations, sampling, started) {
            return (evaluations, stop);
        }
        match method.iterate(state, field, force) {
            Ok(used) => evaluations += used,
            Err(reason) => {
                let why = format!("{reason} after {evaluations} force evaluations");
                return (evaluations, Stop::Failed(RunStatus::NoEquilibrium, why));
            }
        }
        if !force.norm().is_finite() {
            let why = format!("the force became non-finite after {evaluations} force evaluations");
            return (evaluations, Stop::Failed(RunStatus::Unstable, why));
        }
    }
}

/// Why a minimisation at the static force `force` after `evaluations` force evaluations stops
/// before its next move, if it does: at rest, with no criterion to stop at, out of evaluations
/// or past its deadline.
fn stop_before_move<M: Minimiser>(
    force: &Gradient,
    evaluations: u64,
    sampling: &Sampling,
    started: Instant,
) -> Option<Stop> {
    // The start is one evaluation; a later one is a move.
    if M::SETTLES_IN_ONE_MOVE && evaluations > 1 {
        return Some(Stop::Relaxed("static_solution"));
    }
    match sampling.relaxation.as_ref().and_then(|rule| static_criterion(rule, force)) {
        Some((true, criterion)) => return Some(Stop::Relaxed(criterion)),
        None if !M::SETTLES_IN_ONE_MOVE => {
            // The displacement bound needs K_t⁻¹, so k_min > 0: a floppy network (a diluted
            // one past its rigidity threshold) has none, and no bound on its error.
            let why = "no static criterion to stop at: the displacement bound needs a network whose softest \
                       stiffness k_min is > 0 (this one is floppy); give relax.residual_force";
            return Some(Stop::Failed(RunStatus::NoEquilibrium, why.into()));
        }
        Some((false, _)) | None => {}
    }
    if evaluations >= sampling.steps {
        // A line search may finish its last move past the budget: both counts are said.
        let why = format!(
            "the static criterion did not hold within its budget of {} force evaluations (relax.max_tc t_c/dt; \
             stopped after {evaluations})",
            sampling.steps
        );
        return Some(Stop::Failed(RunStatus::NoEquilibrium, why));
    }
    if sampling.deadline.is_some_and(|deadline| Instant::now() > deadline) {
        let why = format!(
            "stopped at its deadline after {:.3} s of minimisation ({evaluations} force evaluations)",
            started.elapsed().as_secs_f64()
        );
        return Some(Stop::Failed(RunStatus::Budget, why));
    }
    None
}

/// ‖v‖₂: the plain sum of squares, or, where that overflows (forces of springs up to 1e300
/// N/m), the same scaled by the largest |vᵢ|.
pub fn euclidean_norm<'a>(v: impl Iterator<Item = &'a f64> + Clone) -> f64 {
    let plain = v.clone().map(|x| x * x).sum::<f64>().sqrt();
    if plain.is_finite() {
        return plain;
    }
    let largest = v.clone().fold(0.0f64, |m, x| m.max(x.abs()));
    if !largest.is_finite() {
        return plain;
    }
    largest * v.map(|x| (x / largest).powi(2)).sum::<f64>().sqrt()
}

/// The largest |a| over both axes.
fn largest(ax: &[f64], ay: &[f64]) -> f64 {
    ax.iter().chain(ay).fold(0.0f64, |m, a| m.max(a.abs()))
}

/// Σ a·b over both axes.
fn dot(ax: &[f64], ay: &[f64], bx: &[f64], by: &[f64]) -> f64 {
    ax.iter().zip(bx).map(|(a, b)| a * b).sum::<f64>() + ay.iter().zip(by).map(|(a, b)| a * b).sum::<f64>()
}
