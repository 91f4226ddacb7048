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
        let p = &mut state.particles;
        for i in 0..p.len() {
            p.vx[i] += dt * state.fx[i] * p.inv_mass[i];
            p.vy[i] += dt * state.fy[i] * p.inv_mass[i];
            p.x[i] += dt * p.vx[i];
            p.y[i] += dt * p.vy[i];
        }
        clear_forces(state);
        evaluate_and_account(state, field, None, dt, (state.steps + 1) as f64 * dt);
        finish_step(state, dt);
    }
}
