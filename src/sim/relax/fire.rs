//! FIRE 2.0 (Guénolé, Nöhring, Vaid, Houllé, Xie, Prakash, Bitzek, Comput. Mater. Sci. 175
//! (2020) 109584, Algorithm 2) with semi-implicit Euler and the published parameters: inertia
//! moves the particles downhill, the velocity is mixed towards the force direction
//! (v ← (1 − α) v + α |v| F̂) and the step grows while the power P = F·v stays positive; at
//! P ≤ 0 the particles go back half a step, stop, and the step shrinks.

use super::{Gradient, Minimiser, dot};
use crate::sim::field::ForceField;
use crate::sim::state::State;

/// Steps with P > 0 before Δt may grow and α shrink (N_delaystep).
const DELAY_STEPS: u32 = 20;
/// Consecutive steps with P ≤ 0 after which FIRE gives up (N_negmax).
const MAX_UPHILL_STEPS: u32 = 2000;
/// Δt growth factor (f_inc) ...
const DT_GROW: f64 = 1.1;
/// ... and shrink factor (f_dec).
const DT_SHRINK: f64 = 0.5;
/// Mixing at a restart (α_start) ...
const ALPHA_START: f64 = 0.25;
/// ... and its decay per growing step (f_α).
const ALPHA_DECAY: f64 = 0.99;
/// Δt_max = 10 Δt and Δt_min = 0.02 Δt, of the run's time step Δt.
const DT_MAX_FACTOR: f64 = 10.0;
const DT_MIN_FACTOR: f64 = 0.02;

/// FIRE's state between iterations.
pub(super) struct Fire {
    dt: f64,
    dt_max: f64,
    dt_min: f64,
    alpha: f64,
    /// Steps taken, for the initial delay (no Δt shrink during the first N_delaystep steps).
    steps: u64,
    downhill: u32,
    uphill: u32,
}

impl Fire {
    /// FIRE starting at the time step `dt` (s), bounded by 0.02 dt and 10 dt.
    pub(super) fn new(dt: f64) -> Fire {
        Fire {
            dt,
            dt_max: DT_MAX_FACTOR * dt,
            dt_min: DT_MIN_FACTOR * dt,
            alpha: ALPHA_START,
            steps: 0,
            downhill: 0,
            uphill: 0,
        }
    }
}

impl Minimiser for Fire {
    fn iterate<F: ForceField>(
        &mut self,
        state: &mut State,
        field: &mut F,
        force: &mut Gradient,
    ) -> Result<u64, String> {
        self.steps += 1;
        let p = &mut state.particles;
        let power = dot(&force.fx, &force.fy, &p.vx, &p.vy);
        if power > 0.0 {
            self.downhill += 1;
            self.uphill = 0;
            if self.downhill > DELAY_STEPS {
                self.dt = (self.dt * DT_GROW).min(self.dt_max);
                self.alpha *= ALPHA_DECAY;
            }
        } else {
            self.downhill = 0;
            self.uphill += 1;
            if self.uphill > MAX_UPHILL_STEPS {
                return Err(format!("FIRE found P = F·v ≤ 0 at {MAX_UPHILL_STEPS} steps in a row"));
            }
            // Initial delay: no shrinking during the first N_delaystep steps.
            if self.steps >= u64::from(DELAY_STEPS) {
                if self.dt * DT_SHRINK >= self.dt_min {
                    self.dt *= DT_SHRINK;
                }
                self.alpha = ALPHA_START;
            }
            // The half-step correction: back to where the uphill move started, at rest.
            for i in 0..p.len() {
                p.x[i] -= 0.5 * self.dt * p.vx[i];
                p.y[i] -= 0.5 * self.dt * p.vy[i];
            }
            p.vx.fill(0.0);
            p.vy.fill(0.0);
        }
        // Semi-implicit Euler with the mixing after the velocity update: v += Δt F/m,
        // v ← (1 − α) v + α |v| F/|F|, x += Δt v. Held axes have F = 0 and stay at rest.
        for i in 0..p.len() {
            p.vx[i] += self.dt * force.fx[i] * p.inv_mass[i];
            p.vy[i] += self.dt * force.fy[i] * p.inv_mass[i];
        }
        let speed = dot(&p.vx, &p.vy, &p.vx, &p.vy).sqrt();
        let force_norm = force.norm();
        let mix = if force_norm > 0.0 { self.alpha * speed / force_norm } else { 0.0 };
        for i in 0..p.len() {
            p.vx[i] = (1.0 - self.alpha) * p.vx[i] + mix * force.fx[i];
            p.vy[i] = (1.0 - self.alpha) * p.vy[i] + mix * force.fy[i];
            p.x[i] += self.dt * p.vx[i];
            p.y[i] += self.dt * p.vy[i];
        }
        state.time += self.dt;
        force.evaluate(state, field);
        Ok(1)
    }
}
