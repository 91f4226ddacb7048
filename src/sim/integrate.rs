//! Integrators: position (Störmer) Verlet, the coursework's scheme, and velocity Verlet.
//!
//! Damping forces depend on the velocity at the time the force is evaluated, which an explicit
//! Verlet step does not know yet. Using the half-step velocity there makes damped runs first
//! order (r off by ~1.5 % at t_c/50). Both integrators instead give the force loop the
//! predicted velocity v(t + dt) ≈ v(t) + dt · a(t), whose error is O(dt²); the force error
//! is then O(dt²) and the step error O(dt³), so damped bonded runs stay second order at the
//! cost of one particle loop (only when something is damped).

use super::field::ForceField;
use super::state::State;

/// Which integrator a run uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum IntegratorKind {
    /// x_{n+1} = 2x_n − x_{n−1} + a_n dt², v_n = (x_{n+1} − x_{n−1})/(2 dt).
    PositionVerlet,
    /// v_{n+½} = v_n + a_n dt/2, x_{n+1} = x_n + v_{n+½} dt, v_{n+1} = v_{n+½} + a_{n+1} dt/2.
    VelocityVerlet,
}

impl IntegratorKind {
    /// The name used in campaign files and tables.
    pub fn name(self) -> &'static str {
        match self {
            IntegratorKind::PositionVerlet => "position-verlet",
            IntegratorKind::VelocityVerlet => "velocity-verlet",
        }
    }
}

/// Advances a [`State`] in time under a [`ForceField`].
pub trait Integrator {
    /// Computes the forces at t = 0 and prepares any history the scheme needs.
    fn start<F: ForceField>(&mut self, state: &mut State, field: &F, dt: f64);
    /// Advances by one step `dt` (s); afterwards positions, velocities and forces all refer to
    /// the new `state.time`.
    fn step<F: ForceField>(&mut self, state: &mut State, field: &F, dt: f64);
}

/// Predicted velocity v + dt · f · inv_mass on one axis, for the damping forces.
fn predict(prediction: &mut [f64], v: &[f64], f: &[f64], inv_mass: &[f64], dt: f64) {
    for i in 0..prediction.len() {
        prediction[i] = v[i] + dt * f[i] * inv_mass[i];
    }
}

/// Zeroes the forces and evaluates them at the current positions with velocities `(vx, vy)`;
/// accumulates the dissipated energy by the trapezoidal rule over the step `dt`.
fn evaluate_forces<F: ForceField>(state: &mut State, field: &F, velocities: Option<(&[f64], &[f64])>, dt: f64) {
    state.fx.fill(0.0);
    state.fy.fill(0.0);
    let p = &state.particles;
    let (vx, vy) = velocities.unwrap_or((&p.vx, &p.vy));
    let power = field.add_forces(&p.x, &p.y, vx, vy, &mut state.fx, &mut state.fy);
    state.dissipated += 0.5 * dt * (state.dissipation_power + power);
    state.dissipation_power = power;
}

/// Scratch arrays for the predicted velocities (empty when nothing is damped).
#[derive(Clone, Debug, Default)]
struct Prediction {
    vx: Vec<f64>,
    vy: Vec<f64>,
}

impl Prediction {
    /// Fills the prediction from the state when the field is damped; returns it for the force loop.
    fn update<F: ForceField>(&mut self, state: &State, field: &F, dt: f64) -> Option<(&[f64], &[f64])> {
        if !field.uses_velocity() {
            return None;
        }
        let p = &state.particles;
        self.vx.resize(p.len(), 0.0);
        self.vy.resize(p.len(), 0.0);
        predict(&mut self.vx, &p.vx, &state.fx, &p.inv_mass_x, dt);
        predict(&mut self.vy, &p.vy, &state.fy, &p.inv_mass_y, dt);
        Some((&self.vx, &self.vy))
    }
}

/// Velocity Verlet (kick–drift–kick).
#[derive(Clone, Debug, Default)]
pub struct VelocityVerlet {
    prediction: Prediction,
}

/// Half kick v += f · inv_mass · dt/2 on one axis.
fn kick(v: &mut [f64], f: &[f64], inv_mass: &[f64], half_dt: f64) {
    for i in 0..v.len() {
        v[i] += half_dt * f[i] * inv_mass[i];
    }
}

/// Drift x += v dt on one axis.
fn drift(x: &mut [f64], v: &[f64], dt: f64) {
    for i in 0..x.len() {
        x[i] += dt * v[i];
    }
}

impl Integrator for VelocityVerlet {
    fn start<F: ForceField>(&mut self, state: &mut State, field: &F, dt: f64) {
        evaluate_forces(state, field, None, dt);
        state.dissipated = 0.0;
    }

    fn step<F: ForceField>(&mut self, state: &mut State, field: &F, dt: f64) {
        let velocities = self.prediction.update(state, field, dt);
        let p = &mut state.particles;
        kick(&mut p.vx, &state.fx, &p.inv_mass_x, 0.5 * dt);
        kick(&mut p.vy, &state.fy, &p.inv_mass_y, 0.5 * dt);
        drift(&mut p.x, &p.vx, dt);
        drift(&mut p.y, &p.vy, dt);
        evaluate_forces(state, field, velocities, dt);
        let p = &mut state.particles;
        kick(&mut p.vx, &state.fx, &p.inv_mass_x, 0.5 * dt);
        kick(&mut p.vy, &state.fy, &p.inv_mass_y, 0.5 * dt);
        state.steps += 1;
        state.time = state.steps as f64 * dt;
    }
}

/// Position (Störmer) Verlet, as in the coursework's pseudo-code. It keeps x_{n−1} and,
/// one step ahead, x_{n+1}, so that the state's velocity is the central difference
/// v_n = (x_{n+1} − x_{n−1})/(2 dt) at the same time as its positions.
#[derive(Clone, Debug, Default)]
pub struct PositionVerlet {
    x_previous: Vec<f64>,
    y_previous: Vec<f64>,
    x_next: Vec<f64>,
    y_next: Vec<f64>,
    prediction: Prediction,
}

/// x_next = 2x − x_previous + f · inv_mass · dt², and the central velocity, on one axis.
fn stoermer(next: &mut [f64], v: &mut [f64], x: &[f64], previous: &[f64], f: &[f64], inv_mass: &[f64], dt: f64) {
    for i in 0..x.len() {
        next[i] = 2.0 * x[i] - previous[i] + dt * dt * f[i] * inv_mass[i];
        v[i] = (next[i] - previous[i]) / (2.0 * dt);
    }
}

impl Integrator for PositionVerlet {
    fn start<F: ForceField>(&mut self, state: &mut State, field: &F, dt: f64) {
        evaluate_forces(state, field, None, dt);
        state.dissipated = 0.0;
        let p = &state.particles;
        // Taylor start: x_1 = x_0 + v_0 dt + a_0 dt²/2.
        let taylor = |x: &[f64], v: &[f64], f: &[f64], inv_mass: &[f64]| -> Vec<f64> {
            (0..x.len()).map(|i| x[i] + dt * v[i] + 0.5 * dt * dt * f[i] * inv_mass[i]).collect()
        };
        self.x_next = taylor(&p.x, &p.vx, &state.fx, &p.inv_mass_x);
        self.y_next = taylor(&p.y, &p.vy, &state.fy, &p.inv_mass_y);
        self.x_previous = p.x.clone();
        self.y_previous = p.y.clone();
    }

    fn step<F: ForceField>(&mut self, state: &mut State, field: &F, dt: f64) {
        let velocities = self.prediction.update(state, field, dt);
        let p = &mut state.particles;
        // Shift the history without copying: previous ← x_n, x ← x_{n+1}.
        std::mem::swap(&mut self.x_previous, &mut p.x);
        std::mem::swap(&mut p.x, &mut self.x_next);
        std::mem::swap(&mut self.y_previous, &mut p.y);
        std::mem::swap(&mut p.y, &mut self.y_next);
        evaluate_forces(state, field, velocities, dt);
        let p = &mut state.particles;
        stoermer(&mut self.x_next, &mut p.vx, &p.x, &self.x_previous, &state.fx, &p.inv_mass_x, dt);
        stoermer(&mut self.y_next, &mut p.vy, &p.y, &self.y_previous, &state.fy, &p.inv_mass_y, dt);
        state.steps += 1;
        state.time = state.steps as f64 * dt;
    }
}
