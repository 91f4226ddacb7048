//! Symplectic (semi-implicit) Euler: the simplest scheme that does not drift in energy.

use super::{Integrator, clear_forces, evaluate_and_account, finish_step, start_forces};
use crate::sim::field::ForceField;
use crate::sim::state::State;

/// v_{n+1} = v_n + (f(x_n, v_n)/m) dt, then x_{n+1} = x_n + v_{n+1} dt. First order; symplectic,
/// so the energy error stays bounded (it oscillates at O(dt)) instead of drifting. Dashpots see
/// the velocity of the step's start, which is first order too.
#[derive(Clone, Debug, Default)]
pub struct SymplecticEuler;

impl Integrator for SymplecticEuler {
    fn start<F: ForceField>(&mut self, state: &mut State, field: &mut F, _dt: f64) {
        start_forces(state, field);
    }

    fn step<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        advance(state, field, dt, (state.steps + 1) as f64 * dt);
        finish_step(state, dt);
    }

    fn substep<F: ForceField>(&mut self, state: &mut State, field: &mut F, h: f64, _dt: f64) {
        advance(state, field, h, state.time + h);
    }
}

/// v += (f/m) h, x += v h, then the forces at `time`, the end of the step of length `h` (s).
fn advance<F: ForceField>(state: &mut State, field: &mut F, h: f64, time: f64) {
    let p = &mut state.particles;
    for i in 0..p.len() {
        p.vx[i] += h * state.fx[i] * p.inv_mass[i];
        p.vy[i] += h * state.fy[i] * p.inv_mass[i];
        p.x[i] += h * p.vx[i];
        p.y[i] += h * p.vy[i];
    }
    clear_forces(state);
    evaluate_and_account(state, field, None, h, time);
}
