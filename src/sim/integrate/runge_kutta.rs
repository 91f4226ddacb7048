//! Classical fourth-order Runge–Kutta on the first-order system (x, v)' = (v, f(x, v, t)/m).

use super::{Evaluation, Integrator, account, clear_forces, evaluate, finish_step, start_forces};
use crate::sim::field::ForceField;
use crate::sim::state::State;

/// RK4: four force evaluations per step (the fourth at the end of the step doubles as the
/// first of the next), order 4 in positions, velocities and, through the same quadrature
/// weights 1/6, 1/3, 1/3, 1/6, in the dissipated energy and the drive's work. Not symplectic:
/// the energy of an undamped run drifts (slowly, as dt⁴). Dashpots see each stage's own
/// velocity, so damped runs keep the full order without a velocity prediction.
#[derive(Clone, Debug, Default)]
pub struct RungeKutta4 {
    /// State at the start of the step.
    x0: Vec<f64>,
    y0: Vec<f64>,
    vx0: Vec<f64>,
    vy0: Vec<f64>,
    /// Weighted sums of the stage velocities (1, 2, 2, 1) and accelerations.
    sum_vx: Vec<f64>,
    sum_vy: Vec<f64>,
    sum_ax: Vec<f64>,
    sum_ay: Vec<f64>,
}

impl Integrator for RungeKutta4 {
    fn start<F: ForceField>(&mut self, state: &mut State, field: &mut F, _dt: f64) {
        start_forces(state, field);
    }

    fn step<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        self.advance(state, field, dt);
        finish_step(state, dt);
    }

    fn substep<F: ForceField>(&mut self, state: &mut State, field: &mut F, h: f64, _dt: f64) {
        self.advance(state, field, h);
    }
}

impl RungeKutta4 {
    /// Sizes the buffers for `n` particles (a scheme made by `default`, as Gear's scout is, has
    /// none).
    fn size_for(&mut self, n: usize) {
        for buffer in [
            &mut self.x0,
            &mut self.y0,
            &mut self.vx0,
            &mut self.vy0,
            &mut self.sum_vx,
            &mut self.sum_vy,
            &mut self.sum_ax,
            &mut self.sum_ay,
        ] {
            buffer.resize(n, 0.0);
        }
    }

    /// One step of length `dt` (s) from `state.time`, from the forces the state holds; time and
    /// step count are left alone.
    fn advance<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        let t = state.time;
        self.size_for(state.particles.len());
        let p = &state.particles;
        self.x0.copy_from_slice(&p.x);
        self.y0.copy_from_slice(&p.y);
        self.vx0.copy_from_slice(&p.vx);
        self.vy0.copy_from_slice(&p.vy);
        // Stage 1: the derivative at the step's start, whose forces the state already holds.
        for i in 0..p.len() {
            self.sum_vx[i] = p.vx[i];
            self.sum_vy[i] = p.vy[i];
            self.sum_ax[i] = state.fx[i] * p.inv_mass[i];
            self.sum_ay[i] = state.fy[i] * p.inv_mass[i];
        }
        let first = Evaluation { power: state.dissipation_power, drive_force: state.drive_force };
        let mut evaluations = vec![(1.0 / 6.0, first)];
        // Stages 2–4 at t + c dt from the previous stage's derivative: (x0 + c dt v, v0 + c dt a).
        for (c, weight) in [(0.5, 2.0), (0.5, 2.0), (1.0, 1.0)] {
            let h = c * dt;
            let p = &mut state.particles;
            for i in 0..p.len() {
                p.x[i] = self.x0[i] + h * p.vx[i];
                p.y[i] = self.y0[i] + h * p.vy[i];
                p.vx[i] = self.vx0[i] + h * state.fx[i] * p.inv_mass[i];
                p.vy[i] = self.vy0[i] + h * state.fy[i] * p.inv_mass[i];
                self.sum_vx[i] += weight * p.vx[i];
                self.sum_vy[i] += weight * p.vy[i];
            }
            clear_forces(state);
            evaluations.push((weight / 6.0, evaluate(state, field, None, t + h)));
            let p = &state.particles;
            for i in 0..p.len() {
                self.sum_ax[i] += weight * state.fx[i] * p.inv_mass[i];
                self.sum_ay[i] += weight * state.fy[i] * p.inv_mass[i];
            }
        }
        let p = &mut state.particles;
        for i in 0..p.len() {
            p.x[i] = self.x0[i] + dt / 6.0 * self.sum_vx[i];
            p.y[i] = self.y0[i] + dt / 6.0 * self.sum_vy[i];
            p.vx[i] = self.vx0[i] + dt / 6.0 * self.sum_ax[i];
            p.vy[i] = self.vy0[i] + dt / 6.0 * self.sum_ay[i];
        }
        clear_forces(state);
        let end = evaluate(state, field, None, t + dt);
        account(state, dt, t + dt, Evaluation::weighted(&evaluations), end);
    }
}
