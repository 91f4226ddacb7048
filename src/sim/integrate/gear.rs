//! Gear's predictor–corrector, the classic integrator of DEM codes.

use super::{Integrator, RungeKutta4, account, clear_forces, evaluate, finish_step, start_forces, trapezoid};
use crate::sim::field::ForceField;
use crate::sim::state::State;

/// Gear's six-value predictor–corrector for second-order equations (Allen & Tildesley,
/// appendix E). The state is the vector of scaled derivatives r_k = (dt^k / k!) d^k x/dt^k,
/// k = 0…5: r₀ and r₁ are the particles' positions and dt × velocities (kept in the state, so
/// supports and the drive act on them directly), r₂…r₅ live here. A step predicts all six by
/// their Taylor series (Pascal's triangle), evaluates the force once at the prediction, and
/// corrects each r_k by c_k Δ with Δ = (dt²/2) f/m − r₂ᵖ. Corrector weights
/// c = (3/20, 251/360, 1, 11/18, 1/6, 1/60), with c₀ = 3/16 when forces depend on velocity.
/// The forces the state holds after a step are those of the prediction. The start is scouted
/// with RK4 (see `start`).
#[derive(Clone, Debug, Default)]
pub struct Gear {
    /// r₂…r₅ for x and for y.
    higher_x: [Vec<f64>; 4],
    higher_y: [Vec<f64>; 4],
    /// c₀, the corrector weight of positions.
    c0: f64,
}

impl Gear {
    const C: [f64; 5] = [251.0 / 360.0, 1.0, 11.0 / 18.0, 1.0 / 6.0, 1.0 / 60.0];
}

/// Predicts `(r₀, r₁, r₂…r₅)` in place by the Taylor series over one step.
#[inline(always)]
fn predict(r0: &mut f64, r1: &mut f64, r: [&mut f64; 4]) {
    let [r2, r3, r4, r5] = r;
    *r0 += *r1 + *r2 + *r3 + *r4 + *r5;
    *r1 += 2.0 * *r2 + 3.0 * *r3 + 4.0 * *r4 + 5.0 * *r5;
    *r2 += 3.0 * *r3 + 6.0 * *r4 + 10.0 * *r5;
    *r3 += 4.0 * *r4 + 10.0 * *r5;
    *r4 += 5.0 * *r5;
}

/// Classical RK4 sub-steps per Gear step when the start is scouted.
const SCOUT_SUBSTEPS: u64 = 4;

impl Integrator for Gear {
    /// Starts from accurate derivatives ([`Gear::scout`]). Zero higher derivatives, the usual
    /// start, cost the scheme its order: an O(dt³) error in r₃ alone makes the run second order
    /// (measured on the chain).
    fn start<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        start_forces(state, field);
        self.c0 = if field.uses_velocity() { 3.0 / 16.0 } else { 3.0 / 20.0 };
        self.scout(state, field, dt);
    }

    fn step<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        self.advance(state, field, dt, (state.steps + 1) as f64 * dt, 4);
        finish_step(state, dt);
    }

    /// The scaled derivatives rescaled to `h` (r_k by (h/dt)^k) and back after it. A sub-step
    /// that starts at a switch (inside the step: the first starts at steps · dt) starts afresh,
    /// as at t = 0, on its side of the switch: the derivatives jump with the force there, and
    /// the near side's r₃…r₅ made Gear second order. The corrector leaves r₃…r₅ alone: its
    /// change c_k Δ, Δ = O(h³), would move x⁽ᵏ⁾ by O(h^(3−k)) and, scaled back by (dt/h)^k
    /// after a short sub-step, blow up (a sub-step of 10⁻⁶ dt: r₅ × 10³⁰).
    fn substep<F: ForceField>(&mut self, state: &mut State, field: &mut F, h: f64, dt: f64) {
        if state.time != state.steps as f64 * dt {
            self.scout(state, field, dt);
        }
        self.rescale(h / dt);
        self.advance(state, field, h, state.time + h, 1);
        self.rescale(dt / h);
    }
}

impl Gear {
    /// r₂…r₅ for steps of `dt` from the motion ahead of `state`: a cubic through the
    /// accelerations now and dt, 2 dt, 3 dt on, found by RK4 (dt/4 sub-steps) on a copy of the
    /// state from the forces it holds. The copy judges damped contacts as the state does now:
    /// the derivatives are those of the smooth motion Gear is on, not of a cubic through the
    /// jump of a contact switching within 3 dt (which gave free flight nonzero r₃…r₅).
    fn scout<F: ForceField>(&mut self, state: &State, field: &mut F, dt: f64) {
        let n = state.particles.len();
        let acceleration = |s: &State| -> (Vec<f64>, Vec<f64>) {
            let p = &s.particles;
            ((0..n).map(|i| s.fx[i] * p.inv_mass[i]).collect(), (0..n).map(|i| s.fy[i] * p.inv_mass[i]).collect())
        };
        let mut samples = vec![acceleration(state)];
        let mut scout = state.clone();
        scout.contacts_judged_at = Some(state.contacts_judged_at.unwrap_or(state.time));
        let mut runge_kutta = RungeKutta4::default();
        let h = dt / SCOUT_SUBSTEPS as f64;
        for k in 1..=3 * SCOUT_SUBSTEPS {
            runge_kutta.substep(&mut scout, field, h, h);
            scout.time = state.time + k as f64 * h;
            if k % SCOUT_SUBSTEPS == 0 {
                samples.push(acceleration(&scout));
            }
        }
        // Newton forward differences Δᵏ of a at 0, dt, 2dt, 3dt give dt a' = Δ − Δ²/2 + Δ³/3,
        // dt² a'' = Δ² − Δ³ and dt³ a''' = Δ³; then r_k = dt^k/k! x^(k) with x'' = a.
        let derivatives = |a: [f64; 4]| -> [f64; 4] {
            let d1 = a[1] - a[0];
            let d2 = a[2] - 2.0 * a[1] + a[0];
            let d3 = a[3] - 3.0 * a[2] + 3.0 * a[1] - a[0];
            let h2 = dt * dt;
            [h2 / 2.0 * a[0], h2 / 6.0 * (d1 - d2 / 2.0 + d3 / 3.0), h2 / 24.0 * (d2 - d3), h2 / 120.0 * d3]
        };
        self.higher_x = std::array::from_fn(|_| vec![0.0; n]);
        self.higher_y = std::array::from_fn(|_| vec![0.0; n]);
        for i in 0..n {
            let rx = derivatives(std::array::from_fn(|s| samples[s].0[i]));
            let ry = derivatives(std::array::from_fn(|s| samples[s].1[i]));
            for k in 0..4 {
                self.higher_x[k][i] = rx[k];
                self.higher_y[k][i] = ry[k];
            }
        }
    }

    /// r_k ← ratio^k r_k for k = 2…5: the scaled derivatives of a step `ratio` times as long.
    fn rescale(&mut self, ratio: f64) {
        for (k, (x, y)) in self.higher_x.iter_mut().zip(&mut self.higher_y).enumerate() {
            let factor = ratio.powi(k as i32 + 2);
            x.iter_mut().chain(y.iter_mut()).for_each(|r| *r *= factor);
        }
    }

    /// One predict–evaluate–correct step of length `dt` (s) ending at `time`, whose corrector
    /// updates r₀, r₁ and the first `corrected` of r₂…r₅; time and step count are left alone.
    fn advance<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64, time: f64, corrected: usize) {
        let p = &mut state.particles;
        let [a2, a3, a4, a5] = &mut self.higher_x;
        let [b2, b3, b4, b5] = &mut self.higher_y;
        for i in 0..p.len() {
            let mut r1 = dt * p.vx[i];
            predict(&mut p.x[i], &mut r1, [&mut a2[i], &mut a3[i], &mut a4[i], &mut a5[i]]);
            p.vx[i] = r1 / dt;
            let mut r1 = dt * p.vy[i];
            predict(&mut p.y[i], &mut r1, [&mut b2[i], &mut b3[i], &mut b4[i], &mut b5[i]]);
            p.vy[i] = r1 / dt;
        }
        clear_forces(state);
        let end = evaluate(state, field, None, time);
        let p = &mut state.particles;
        let c = Self::C;
        for (position, velocity, force, higher) in
            [(&mut p.x, &mut p.vx, &state.fx, &mut self.higher_x), (&mut p.y, &mut p.vy, &state.fy, &mut self.higher_y)]
        {
            for i in 0..position.len() {
                let delta = 0.5 * dt * dt * force[i] * p.inv_mass[i] - higher[0][i];
                position[i] += self.c0 * delta;
                velocity[i] += c[0] * delta / dt;
                for k in 0..corrected {
                    higher[k][i] += c[k + 1] * delta;
                }
            }
        }
        account(state, dt, time, trapezoid(state, end), end);
    }

    /// The amplification matrix G of one step on a linear test problem, in the scaled
    /// derivatives r = (r₀ … r₅) of the particle `moving` along x: r after a step = G r.
    /// `state` holds that particle at its equilibrium at rest; `field` is linear in its
    /// displacement and velocity. Column j is what [`Gear::step`] itself makes of r_j = 1/8
    /// alone, so G is the scheme as coded (its c₀ included), not a transcription of it.
    pub fn amplification_matrix<F: ForceField>(state: &State, field: &mut F, moving: usize, dt: f64) -> [[f64; 6]; 6] {
        // 1/8 is exact in binary: the predictor's Pascal sums of it carry no rounding.
        const UNIT: f64 = 0.125;
        let rest = state.particles.x[moving];
        let mut matrix = [[0.0; 6]; 6];
        for j in 0..6 {
            let mut s = state.clone();
            let mut gear = Gear::default();
            gear.start(&mut s, field, dt);
            let mut r = [0.0; 6];
            r[j] = UNIT;
            s.particles.x[moving] = rest + r[0];
            s.particles.vx[moving] = r[1] / dt;
            for k in 0..4 {
                gear.higher_x[k][moving] = r[k + 2];
            }
            gear.step(&mut s, field, dt);
            let h = &gear.higher_x;
            let after = [
                s.particles.x[moving] - rest,
                dt * s.particles.vx[moving],
                h[0][moving],
                h[1][moving],
                h[2][moving],
                h[3][moving],
            ];
            for (row, value) in matrix.iter_mut().zip(after) {
                row[j] = value / UNIT;
            }
        }
        matrix
    }
}
