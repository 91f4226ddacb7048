//! Integrators: position (Störmer) Verlet, the coursework's scheme, and velocity Verlet.
//!
//! Damping forces depend on the velocity at the time the force is evaluated, which an explicit
//! Verlet step does not know yet. Using the half-step velocity there makes damped runs first
//! order (r off by ~1.5 % at t_c/50). Both integrators instead give the force loop the
//! predicted velocity v(t + dt) ≈ v(t) + dt · a(t), whose error is O(dt²); the force error
//! is then O(dt²) and the step error O(dt³), so damped bonded runs stay second order at the
//! cost of one particle loop (only when something is damped).
//!
//! Particle loops treat both axes in one pass over memory, are split over threads for large
//! systems ([`for_chunks`]), and never allocate. Held axes are handled by zeroing their force
//! after each evaluation ([`hold`]).

use super::field::ForceField;
use super::parallel::{InverseMass, Uniform, for_chunks};
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
    fn start<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64);
    /// Advances by one step `dt` (s); afterwards positions, velocities and forces all refer to
    /// the new `state.time`.
    fn step<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64);
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

/// Evaluates the forces (which must be zero on entry) at the current positions, which belong to
/// `time`, with velocities `(vx, vy)`; adds the loads, holds the constrained axes, and adds the
/// step's dissipated energy and the loads' work by the trapezoidal rule.
fn add_forces<F: ForceField>(
    state: &mut State,
    field: &mut F,
    velocities: Option<(&[f64], &[f64])>,
    dt: f64,
    time: f64,
) {
    let factor = state.load_factor(time);
    state.account_load_work(factor);
    let p = &state.particles;
    let (vx, vy) = velocities.unwrap_or((&p.vx, &p.vy));
    let (mut fx, mut fy) = (std::mem::take(&mut state.fx), std::mem::take(&mut state.fy));
    let power = field.add_forces(&p.x, &p.y, vx, vy, &mut fx, &mut fy);
    let drive_force = load_and_hold(state, factor, &mut fx, &mut fy);
    (state.fx, state.fy) = (fx, fy);
    state.account_drive(drive_force, dt);
    state.dissipated += 0.5 * dt * (state.dissipation_power + power);
    state.dissipation_power = power;
}

/// Runs `$body` with the particles' inverse masses as `$im`: one value when all masses are
/// equal (`$uniform`, found once at the start), the array otherwise.
macro_rules! with_inverse_mass {
    ($state:expr, $uniform:expr, |$im:ident| $body:expr) => {
        match $uniform {
            Some(value) => {
                let $im = Uniform(value);
                $body
            }
            None => {
                let inverse = std::mem::take(&mut $state.particles.inv_mass);
                let $im: &[f64] = &inverse;
                let result = $body;
                $state.particles.inv_mass = inverse;
                result
            }
        }
    };
}

/// Scratch arrays for the predicted velocities (empty when nothing is damped).
#[derive(Clone, Debug, Default)]
struct Prediction {
    vx: Vec<f64>,
    vy: Vec<f64>,
}

impl Prediction {
    /// Fills the prediction v + dt · f/m from the state when the field is damped; returns it
    /// for the force loop.
    fn update<F: ForceField, M: InverseMass>(
        &mut self,
        state: &State,
        field: &F,
        im: M,
        dt: f64,
    ) -> Option<(&[f64], &[f64])> {
        if !field.uses_velocity() {
            return None;
        }
        let p = &state.particles;
        self.vx.resize(p.len(), 0.0);
        self.vy.resize(p.len(), 0.0);
        let (px, py, vx, vy, fx, fy) = (&mut self.vx, &mut self.vy, &p.vx, &p.vy, &state.fx, &state.fy);
        let kernel = |offset: usize, px: &mut [f64], py: &mut [f64], vx: &[f64], vy: &[f64], fx: &[f64], fy: &[f64]| {
            let n = px.len();
            let (py, vx, vy, fx, fy, im) = (&mut py[..n], &vx[..n], &vy[..n], &fx[..n], &fy[..n], im.part(offset, n));
            for i in 0..n {
                px[i] = vx[i] + dt * fx[i] * im.at(i);
                py[i] = vy[i] + dt * fy[i] * im.at(i);
            }
        };
        let (px, py): (&mut [f64], &mut [f64]) = (px, py);
        let (vx, vy, fx, fy): (&[f64], &[f64], &[f64], &[f64]) = (vx, vy, fx, fy);
        for_chunks!(kernel, [px, py], [vx, vy, fx, fy]);
        Some((&self.vx, &self.vy))
    }
}

/// Velocity Verlet (kick–drift–kick).
#[derive(Clone, Debug, Default)]
pub struct VelocityVerlet {
    prediction: Prediction,
    uniform_inverse_mass: Option<f64>,
}

/// First half of a velocity-Verlet step in one pass over memory: v += f/m · dt/2,
/// x += v dt, then f = 0 for the next force evaluation.
fn kick_drift_clear<M: InverseMass>(state: &mut State, im: M, dt: f64) {
    let p = &mut state.particles;
    let (x, y, vx, vy, fx, fy) =
        (&mut p.x[..], &mut p.y[..], &mut p.vx[..], &mut p.vy[..], &mut state.fx[..], &mut state.fy[..]);
    let kernel = |offset: usize,
                  x: &mut [f64],
                  y: &mut [f64],
                  vx: &mut [f64],
                  vy: &mut [f64],
                  fx: &mut [f64],
                  fy: &mut [f64]| {
        let n = x.len();
        let (y, vx, vy, fx, fy, im) =
            (&mut y[..n], &mut vx[..n], &mut vy[..n], &mut fx[..n], &mut fy[..n], im.part(offset, n));
        for i in 0..n {
            vx[i] += 0.5 * dt * fx[i] * im.at(i);
            vy[i] += 0.5 * dt * fy[i] * im.at(i);
            x[i] += dt * vx[i];
            y[i] += dt * vy[i];
            fx[i] = 0.0;
            fy[i] = 0.0;
        }
    };
    for_chunks!(kernel, [x, y, vx, vy, fx, fy], []);
}

/// Second half kick v += f/m · dt/2.
fn kick<M: InverseMass>(state: &mut State, im: M, dt: f64) {
    let p = &mut state.particles;
    let (vx, vy, fx, fy) = (&mut p.vx[..], &mut p.vy[..], &state.fx[..], &state.fy[..]);
    let kernel = |offset: usize, vx: &mut [f64], vy: &mut [f64], fx: &[f64], fy: &[f64]| {
        let n = vx.len();
        let (vy, fx, fy, im) = (&mut vy[..n], &fx[..n], &fy[..n], im.part(offset, n));
        for i in 0..n {
            vx[i] += 0.5 * dt * fx[i] * im.at(i);
            vy[i] += 0.5 * dt * fy[i] * im.at(i);
        }
    };
    for_chunks!(kernel, [vx, vy], [fx, fy]);
}

impl Integrator for VelocityVerlet {
    fn start<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        self.uniform_inverse_mass = state.particles.uniform_inverse_mass();
        state.fx.fill(0.0);
        state.fy.fill(0.0);
        add_forces(state, field, None, dt, 0.0);
        state.dissipated = 0.0;
    }

    fn step<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        with_inverse_mass!(state, self.uniform_inverse_mass, |im| {
            let velocities = self.prediction.update(state, field, im, dt);
            kick_drift_clear(state, im, dt);
            add_forces(state, field, velocities, dt, (state.steps + 1) as f64 * dt);
            kick(state, im, dt);
        });
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
    uniform_inverse_mass: Option<f64>,
}

impl PositionVerlet {
    /// x_next = 2x − x_previous + f/m · dt², and the central velocity
    /// v = (x_next − x_previous)/(2 dt).
    fn advance<M: InverseMass>(&mut self, state: &mut State, im: M, dt: f64) {
        let p = &mut state.particles;
        let (next_x, next_y, vx, vy) = (&mut self.x_next[..], &mut self.y_next[..], &mut p.vx[..], &mut p.vy[..]);
        let (x, y, previous_x, previous_y, fx, fy) =
            (&p.x[..], &p.y[..], &self.x_previous[..], &self.y_previous[..], &state.fx[..], &state.fy[..]);
        let kernel = |offset: usize,
                      next_x: &mut [f64],
                      next_y: &mut [f64],
                      vx: &mut [f64],
                      vy: &mut [f64],
                      x: &[f64],
                      y: &[f64],
                      previous_x: &[f64],
                      previous_y: &[f64],
                      fx: &[f64],
                      fy: &[f64]| {
            let n = next_x.len();
            let (next_y, vx, vy, x, y) = (&mut next_y[..n], &mut vx[..n], &mut vy[..n], &x[..n], &y[..n]);
            let (previous_x, previous_y, fx, fy, im) =
                (&previous_x[..n], &previous_y[..n], &fx[..n], &fy[..n], im.part(offset, n));
            for i in 0..n {
                next_x[i] = 2.0 * x[i] - previous_x[i] + dt * dt * fx[i] * im.at(i);
                next_y[i] = 2.0 * y[i] - previous_y[i] + dt * dt * fy[i] * im.at(i);
                vx[i] = (next_x[i] - previous_x[i]) / (2.0 * dt);
                vy[i] = (next_y[i] - previous_y[i]) / (2.0 * dt);
            }
        };
        for_chunks!(kernel, [next_x, next_y, vx, vy], [x, y, previous_x, previous_y, fx, fy]);
    }
}

impl Integrator for PositionVerlet {
    fn start<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        self.uniform_inverse_mass = state.particles.uniform_inverse_mass();
        state.fx.fill(0.0);
        state.fy.fill(0.0);
        add_forces(state, field, None, dt, 0.0);
        state.dissipated = 0.0;
        let p = &state.particles;
        // Taylor start: x_1 = x_0 + v_0 dt + a_0 dt²/2.
        let taylor = |x: &[f64], v: &[f64], f: &[f64]| -> Vec<f64> {
            (0..x.len()).map(|i| x[i] + dt * v[i] + 0.5 * dt * dt * f[i] * p.inv_mass[i]).collect()
        };
        self.x_next = taylor(&p.x, &p.vx, &state.fx);
        self.y_next = taylor(&p.y, &p.vy, &state.fy);
        self.x_previous = p.x.clone();
        self.y_previous = p.y.clone();
    }

    fn step<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        with_inverse_mass!(state, self.uniform_inverse_mass, |im| {
            let velocities = self.prediction.update(state, field, im, dt);
            let p = &mut state.particles;
            // Shift the history without copying: previous ← x_n, x ← x_{n+1}.
            std::mem::swap(&mut self.x_previous, &mut p.x);
            std::mem::swap(&mut p.x, &mut self.x_next);
            std::mem::swap(&mut self.y_previous, &mut p.y);
            std::mem::swap(&mut p.y, &mut self.y_next);
            state.fx.fill(0.0);
            state.fy.fill(0.0);
            add_forces(state, field, velocities, dt, (state.steps + 1) as f64 * dt);
            self.advance(state, im, dt);
        });
        state.steps += 1;
        state.time = state.steps as f64 * dt;
    }
}
