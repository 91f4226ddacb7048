//! Integrators behind one interface ([`Integrator`]), chosen per run by [`IntegratorKind`]:
//! the Verlet family (position Verlet, the coursework's; velocity Verlet; the fourth-order
//! symplectic Forest–Ruth composition of velocity-Verlet steps), symplectic Euler, classical
//! Runge–Kutta 4 and the Gear predictor–corrector of DEM codes.
//!
//! Every scheme evaluates forces through [`evaluate`] (springs, dashpots, loads, held axes) and
//! books the step's load work, drive work and dissipated energy through [`account`], so the
//! energy balance of a run means the same thing whatever integrates it.
//!
//! A step in which a damped contact switches is split there ([`take_step`]): every scheme can
//! take a sub-step of any length ([`Integrator::substep`]).
//!
//! Held axes (supports and the velocity drive) work with every scheme: their force is zeroed
//! after each evaluation, so they keep their velocity. Velocity-dependent forces (dashpots,
//! background damping) work with every scheme except Forest–Ruth, whose backward sub-step
//! (negative time step) would run a dashpot backwards; that combination is refused when the
//! campaign is read.

mod euler;
mod gear;
mod runge_kutta;
mod switch;
mod verlet;

pub use self::euler::SymplecticEuler;
pub use self::gear::Gear;
pub use self::runge_kutta::RungeKutta4;
pub use self::switch::take_step;
pub use self::verlet::{ForestRuth, PositionVerlet, VelocityVerlet};

use super::field::ForceField;
use super::state::State;

/// Which integrator a run uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum IntegratorKind {
    /// x_{n+1} = 2x_n − x_{n−1} + a_n dt², v_n = (x_{n+1} − x_{n−1})/(2 dt). Order 2.
    PositionVerlet,
    /// v_{n+½} = v_n + a_n dt/2, x_{n+1} = x_n + v_{n+½} dt, v_{n+1} = v_{n+½} + a_{n+1} dt/2.
    /// Order 2.
    VelocityVerlet,
    /// v_{n+1} = v_n + a(x_n, v_n) dt, x_{n+1} = x_n + v_{n+1} dt. Order 1, symplectic.
    SymplecticEuler,
    /// Classical four-stage Runge–Kutta on (x, v). Order 4, not symplectic: energy drifts.
    Rk4,
    /// Forest–Ruth (Yoshida's triple jump): three velocity-Verlet sub-steps θ dt, (1 − 2θ) dt,
    /// θ dt with θ = 1/(2 − 2^{1/3}). Order 4, symplectic.
    ForestRuth,
    /// Gear's six-value predictor–corrector for second-order equations (Allen & Tildesley).
    Gear,
}

impl IntegratorKind {
    /// The name used in campaign files and tables.
    pub fn name(self) -> &'static str {
        match self {
            IntegratorKind::PositionVerlet => "position-verlet",
            IntegratorKind::VelocityVerlet => "velocity-verlet",
            IntegratorKind::SymplecticEuler => "symplectic-euler",
            IntegratorKind::Rk4 => "rk4",
            IntegratorKind::ForestRuth => "forest-ruth",
            IntegratorKind::Gear => "gear",
        }
    }

    /// Force evaluations per step.
    pub fn evaluations_per_step(self) -> u64 {
        match self {
            IntegratorKind::Rk4 => 4,
            IntegratorKind::ForestRuth => 3,
            _ => 1,
        }
    }

    /// Order in dt of the energy balance's error: 1 for symplectic Euler, 2 for the Verlet
    /// schemes and for Gear (its dissipated energy is booked by the trapezoidal rule), 4 for RK4
    /// and Forest–Ruth (docs/physics.md, "Integrators, accuracy and stability").
    pub fn energy_order(self) -> u32 {
        match self {
            IntegratorKind::SymplecticEuler => 1,
            IntegratorKind::PositionVerlet | IntegratorKind::VelocityVerlet | IntegratorKind::Gear => 2,
            IntegratorKind::Rk4 | IntegratorKind::ForestRuth => 4,
        }
    }

    /// Whether velocity-dependent forces (dashpots, background damping) are allowed.
    pub fn allows_damping(self) -> bool {
        self != IntegratorKind::ForestRuth
    }
}

/// Advances a [`State`] in time under a [`ForceField`].
pub trait Integrator {
    /// Computes the forces at t = 0 and prepares any history the scheme needs.
    fn start<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64);
    /// Advances by one step `dt` (s); afterwards positions and velocities refer to the new
    /// `state.time`, and so do the forces, except for Gear's, which belong to its prediction.
    fn step<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64);
    /// Advances by `h` (s), a part of a step of `dt` split where a contact switches, from
    /// `state.time` to `state.time + h`, starting from the forces the state holds (those of
    /// the sub-step's side of the switch); leaves time and step count to the caller.
    fn substep<F: ForceField>(&mut self, state: &mut State, field: &mut F, h: f64, dt: f64);
}

/// Adds the loads times `factor` to `(fx, fy)` and zeroes every held axis, so held particles
/// keep their velocity there. Returns the force a drive applies to its particles along its
/// axis: minus what the springs exert on them there.
fn load_and_hold(state: &State, factor: f64, fx: &mut [f64], fy: &mut [f64]) -> f64 {
    for load in &state.loads {
        fx[load.particle] += factor * load.fx;
        fy[load.particle] += factor * load.fy;
    }
    let drive_force = state.drive.as_ref().map_or(0.0, |d| {
        let axis: &[f64] = if d.along_y { fy } else { fx };
        -d.particles.iter().map(|&i| axis[i]).sum::<f64>()
    });
    for &i in &state.particles.held_x {
        fx[i] = 0.0;
    }
    for &i in &state.particles.held_y {
        fy[i] = 0.0;
    }
    drive_force
}

/// The static force on every free axis, springs and loads without any damping, into
/// `(fx, fy)` (resized to the particles): what is left of it measures how far a relaxing
/// structure is from equilibrium. `zeros` is scratch for the zero velocities.
pub fn static_forces<F: ForceField>(
    state: &State,
    field: &mut F,
    fx: &mut Vec<f64>,
    fy: &mut Vec<f64>,
    zeros: &mut Vec<f64>,
) {
    let p = &state.particles;
    for buffer in [&mut *fx, &mut *fy, &mut *zeros] {
        buffer.clear();
        buffer.resize(p.len(), 0.0);
    }
    field.add_forces(&p.x, &p.y, zeros, zeros, fx, fy);
    load_and_hold(state, state.load_factor(state.time), fx, fy);
}

/// What a force evaluation reports besides the forces: the power the dampers dissipate (W)
/// and the force the drive applies to its particles (N).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Evaluation {
    /// Dissipated power (W).
    pub power: f64,
    /// Force of the drive on its particles along its axis (N).
    pub drive_force: f64,
}

impl Evaluation {
    /// Σ wᵢ eᵢ: the quadrature of a step's evaluations with weights `w` (summing to 1).
    fn weighted(parts: &[(f64, Evaluation)]) -> Evaluation {
        parts.iter().fold(Evaluation::default(), |sum, (w, e)| Evaluation {
            power: sum.power + w * e.power,
            drive_force: sum.drive_force + w * e.drive_force,
        })
    }
}

/// Evaluates the forces (which must be zero on entry) at the current positions, which belong
/// to `time`, with velocities `(vx, vy)` (the state's when `None`); adds the loads and holds
/// the constrained axes. Books nothing: see [`account`].
fn evaluate<F: ForceField>(
    state: &mut State,
    field: &mut F,
    velocities: Option<(&[f64], &[f64])>,
    time: f64,
) -> Evaluation {
    if F::SWITCH_JUMPS {
        field.judge_contacts_ahead(state.contacts_judged_at.map_or(0.0, |at| at - time));
    }
    let p = &state.particles;
    let (vx, vy) = velocities.unwrap_or((&p.vx, &p.vy));
    let (mut fx, mut fy) = (std::mem::take(&mut state.fx), std::mem::take(&mut state.fy));
    let power = field.add_forces(&p.x, &p.y, vx, vy, &mut fx, &mut fy);
    let drive_force = load_and_hold(state, state.load_factor(time), &mut fx, &mut fy);
    (state.fx, state.fy) = (fx, fy);
    Evaluation { power, drive_force }
}

/// Books a step of length `dt` that ends now, at `time`: the loads' work up to the current
/// positions, and the drive's work and the dissipated energy as `dt` times the step's `mean`
/// evaluation; `end` is the evaluation at the new time, which the next trapezoid starts from.
fn account(state: &mut State, dt: f64, time: f64, mean: Evaluation, end: Evaluation) {
    state.account_load_work(state.load_factor(time));
    state.account_drive(mean.drive_force, end.drive_force, dt);
    state.dissipated += dt * mean.power;
    state.dissipation_power = end.power;
}

/// The trapezoidal mean of the state's last evaluation and `end`: second order, which is all a
/// one-evaluation scheme can offer.
fn trapezoid(state: &State, end: Evaluation) -> Evaluation {
    Evaluation {
        power: 0.5 * (state.dissipation_power + end.power),
        drive_force: 0.5 * (state.drive_force + end.drive_force),
    }
}

/// [`evaluate`] then [`account`] by the trapezoidal rule: the step of every one-evaluation
/// scheme.
fn evaluate_and_account<F: ForceField>(
    state: &mut State,
    field: &mut F,
    velocities: Option<(&[f64], &[f64])>,
    dt: f64,
    time: f64,
) {
    let end = evaluate(state, field, velocities, time);
    account(state, dt, time, trapezoid(state, end), end);
}

/// The start of every scheme: forces at t = 0 (zeroed first), nothing dissipated yet.
fn start_forces<F: ForceField>(state: &mut State, field: &mut F) {
    forces_at(state, field, 0.0);
}

/// The forces (zeroed first) at the current positions and velocities, which belong to `time`,
/// with the dissipated power and the drive's force there; books nothing.
fn forces_at<F: ForceField>(state: &mut State, field: &mut F, time: f64) {
    clear_forces(state);
    let now = evaluate(state, field, None, time);
    state.dissipation_power = now.power;
    state.drive_force = now.drive_force;
}

/// Zeroes the forces before an evaluation.
fn clear_forces(state: &mut State) {
    state.fx.fill(0.0);
    state.fy.fill(0.0);
}

/// Ends a step: counts it and sets the time to steps · dt (no drift from summing dt).
fn finish_step(state: &mut State, dt: f64) {
    state.steps += 1;
    state.time = state.steps as f64 * dt;
}
