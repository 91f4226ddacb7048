//! FIRE 2.0 (Guénolé, Nöhring, Vaid, Houllé, Xie, Prakash, Bitzek, Comput. Mater. Sci. 175
//! (2020) 109584, Algorithm 2) with semi-implicit Euler and the published parameters: inertia
//! moves the particles downhill, the velocity is mixed towards the force direction
//! (v ← (1 − α) v + α |v| F̂) and the step grows while the power P = F·v stays positive; at
//! P ≤ 0 the particles go back half a step, stop, and the step shrinks.
//!
//! Preconditioned, the same algorithm runs in the metric of a stiffness P instead of the
//! masses (Packwood et al., J. Chem. Phys. 144 (2016) 164109): P v̇ = F, so v += Δt P⁻¹F,
//! and the mixing turns v towards z = P⁻¹F with the lengths measured by P,
//! v ← (1 − α) v + α (|v|_P/|z|_P) z, |v|_P = √(vᵀP v), |z|_P = √(Fᵀz). With P the network's
//! stiffness every mode of P⁻¹K has a frequency near 1, so the time step is dimensionless and
//! the evaluations no longer grow with the lattice's size (the slowest mode's period). P is the
//! tangent at the static answer (the factor the error bound makes): the linear stiffness at the
//! reference geometry would do for most networks, but is singular for those whose only stiffness
//! in some direction is the load's (a kagome pulled along its rows, a periodic honeycomb), where
//! P⁻¹F blew up.

use super::{Gradient, Minimiser, SharedPreconditioner, dot};
use crate::model::Particles;
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
/// The preconditioned start step Δt and its largest, Δt_max = 2 Δt (dimensionless: P⁻¹K's
/// frequencies are near 1, where semi-implicit Euler is stable below Δt = 2). Measured on 100²
/// and 300² linear blocks under tension and shear, to 1e-4: from Δt = 0.1, 58–85 evaluations;
/// from 0.5, 18–25; from 1.3, the blocks under shear went unstable.
const PRECONDITIONED_DT: f64 = 0.5;
const PRECONDITIONED_DT_MAX: f64 = 1.0;

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
    /// The stiffness FIRE moves in, `None` for the masses.
    metric: Option<StiffnessMetric>,
}

/// FIRE's metric P and P v, kept as v is made (P z = F for z = P⁻¹F), so that |v|_P costs no
/// product with P.
struct StiffnessMetric {
    preconditioner: SharedPreconditioner,
    /// P v (N), x and y.
    weighted_x: Vec<f64>,
    weighted_y: Vec<f64>,
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
            metric: None,
        }
    }

    /// FIRE in the metric of `preconditioner` (P v̇ = F), from the dimensionless step 0.5.
    pub(super) fn preconditioned(preconditioner: SharedPreconditioner) -> Fire {
        let metric = StiffnessMetric { preconditioner, weighted_x: Vec::new(), weighted_y: Vec::new() };
        Fire { metric: Some(metric), dt_max: PRECONDITIONED_DT_MAX, ..Fire::new(PRECONDITIONED_DT) }
    }

    /// The power P = F·v decides: downhill, Δt may grow and α shrink; uphill, back half a
    /// step, to rest, and Δt shrinks. `Err` after too many uphill steps in a row.
    fn steer(&mut self, p: &mut Particles, force: &Gradient) -> Result<(), String> {
        self.steps += 1;
        let power = dot(&force.fx, &force.fy, &p.vx, &p.vy);
        if power > 0.0 {
            self.downhill += 1;
            self.uphill = 0;
            if self.downhill > DELAY_STEPS {
                self.dt = (self.dt * DT_GROW).min(self.dt_max);
                self.alpha *= ALPHA_DECAY;
            }
            return Ok(());
        }
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
        if let Some(metric) = &mut self.metric {
            metric.weighted_x.fill(0.0);
            metric.weighted_y.fill(0.0);
        }
        Ok(())
    }

    /// Semi-implicit Euler with the mixing after the velocity update: v += Δt F/m,
    /// v ← (1 − α) v + α |v| F/|F|, x += Δt v. Held axes have F = 0 and stay at rest.
    fn move_by_masses(&self, p: &mut Particles, force: &Gradient) {
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
    }
}

impl StiffnessMetric {
    /// The same in the metric P: z = P⁻¹F, v += Δt z (P v += Δt F),
    /// v ← (1 − α) v + α (|v|_P/|z|_P) z, x += Δt v. Held axes have F = 0, so z = 0 there.
    fn advance(&mut self, (dt, alpha): (f64, f64), p: &mut Particles, force: &Gradient) -> Result<(), String> {
        let (zx, zy) =
            self.preconditioner.solve(&force.fx, &force.fy).ok_or("the preconditioner's solve P⁻¹F was not finite")?;
        self.weighted_x.resize(p.len(), 0.0);
        self.weighted_y.resize(p.len(), 0.0);
        let (wx, wy) = (&mut self.weighted_x, &mut self.weighted_y);
        for i in 0..p.len() {
            p.vx[i] += dt * zx[i];
            p.vy[i] += dt * zy[i];
            wx[i] += dt * force.fx[i];
            wy[i] += dt * force.fy[i];
        }
        // |v|_P = √(vᵀ P v) and |z|_P = √(zᵀ P z) = √(Fᵀ z), both ≥ 0 up to round-off.
        let speed = dot(&p.vx, &p.vy, wx, wy).max(0.0).sqrt();
        let force_norm = dot(&force.fx, &force.fy, &zx, &zy).max(0.0).sqrt();
        let mix = if force_norm > 0.0 { alpha * speed / force_norm } else { 0.0 };
        for i in 0..p.len() {
            p.vx[i] = (1.0 - alpha) * p.vx[i] + mix * zx[i];
            p.vy[i] = (1.0 - alpha) * p.vy[i] + mix * zy[i];
            wx[i] = (1.0 - alpha) * wx[i] + mix * force.fx[i];
            wy[i] = (1.0 - alpha) * wy[i] + mix * force.fy[i];
            p.x[i] += dt * p.vx[i];
            p.y[i] += dt * p.vy[i];
        }
        Ok(())
    }
}

impl Minimiser for Fire {
    fn iterate<F: ForceField>(
        &mut self,
        state: &mut State,
        field: &mut F,
        force: &mut Gradient,
    ) -> Result<u64, String> {
        self.steer(&mut state.particles, force)?;
        match &mut self.metric {
            Some(metric) => metric.advance((self.dt, self.alpha), &mut state.particles, force)?,
            None => self.move_by_masses(&mut state.particles, force),
        }
        state.time += self.dt;
        force.evaluate(state, field);
        Ok(1)
    }
}
