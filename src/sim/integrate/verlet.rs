//! The Verlet family: position (Störmer) Verlet, the coursework's scheme; velocity Verlet; and
//! Forest–Ruth, three velocity-Verlet sub-steps composed to fourth order.
//!
//! Damping forces depend on the velocity at the time the force is evaluated, which an explicit
//! Verlet step does not know yet. Using the half-step velocity there makes damped runs first
//! order (r off by ~1.5 % at t_c/50). Both Verlet integrators instead give the force loop the
//! predicted velocity v(t + dt) ≈ v(t) + dt · a(t), whose error is O(dt²); the force error
//! is then O(dt²) and the step error O(dt³), so damped bonded runs stay second order. The
//! prediction is written by the pass that moves the particles, which reads v and f anyway
//! (a pass of its own cost a tenth of a damped lattice step).
//!
//! Particle loops treat both axes in one pass over memory, are split over threads for large
//! systems ([`for_chunks`]), and never allocate. These are the production schemes; the others
//! are written plainly for accuracy studies.

use super::{evaluate_and_account, finish_step, start_forces};
use crate::sim::field::ForceField;
use crate::sim::integrate::Integrator;
use crate::sim::parallel::{InverseMass, Uniform, for_chunks};
use crate::sim::state::State;

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
    /// The arrays, sized for `n` particles, when `field` is damped, for the pass that moves
    /// the particles to fill with [`predict`].
    fn arrays<F: ForceField>(&mut self, field: &F, n: usize) -> Option<(&mut [f64], &mut [f64])> {
        if !field.uses_velocity() {
            return None;
        }
        self.vx.resize(n, 0.0);
        self.vy.resize(n, 0.0);
        Some((&mut self.vx, &mut self.vy))
    }

    /// The predicted velocities for the force loop, when `field` is damped.
    fn velocities<F: ForceField>(&self, field: &F) -> Option<(&[f64], &[f64])> {
        field.uses_velocity().then_some((&self.vx, &self.vy))
    }
}

/// The velocity v + dt · f/m predicted for the end of a step from velocity `v`, force `f` and
/// inverse mass `im` at its start.
#[inline(always)]
fn predict(v: f64, f: f64, im: f64, dt: f64) -> f64 {
    v + dt * f * im
}

/// One axis of one particle in the first half of a velocity-Verlet step: v += f/m · dt/2,
/// x += v dt, then f = 0 for the next force evaluation.
#[inline(always)]
fn kick_drift_clear_axis(x: &mut f64, v: &mut f64, f: &mut f64, im: f64, dt: f64) {
    *v += 0.5 * dt * *f * im;
    *x += dt * *v;
    *f = 0.0;
}

/// Velocity Verlet (kick–drift–kick).
#[derive(Clone, Debug, Default)]
pub struct VelocityVerlet {
    prediction: Prediction,
    uniform_inverse_mass: Option<f64>,
}

/// First half of a velocity-Verlet step in one pass over memory ([`kick_drift_clear_axis`]).
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
            kick_drift_clear_axis(&mut x[i], &mut vx[i], &mut fx[i], im.at(i), dt);
            kick_drift_clear_axis(&mut y[i], &mut vy[i], &mut fy[i], im.at(i), dt);
        }
    };
    for_chunks!(kernel, [x, y, vx, vy, fx, fy], []);
}

/// [`kick_drift_clear`] of a damped field, which first writes the predicted velocities
/// ([`predict`]) into `(px, py)` in the same pass.
fn predict_kick_drift_clear<M: InverseMass>(state: &mut State, im: M, dt: f64, px: &mut [f64], py: &mut [f64]) {
    let p = &mut state.particles;
    let (x, y, vx, vy, fx, fy) =
        (&mut p.x[..], &mut p.y[..], &mut p.vx[..], &mut p.vy[..], &mut state.fx[..], &mut state.fy[..]);
    let kernel = |offset: usize,
                  x: &mut [f64],
                  y: &mut [f64],
                  vx: &mut [f64],
                  vy: &mut [f64],
                  fx: &mut [f64],
                  fy: &mut [f64],
                  px: &mut [f64],
                  py: &mut [f64]| {
        let n = x.len();
        let (y, vx, vy, fx, fy, im) =
            (&mut y[..n], &mut vx[..n], &mut vy[..n], &mut fx[..n], &mut fy[..n], im.part(offset, n));
        let (px, py) = (&mut px[..n], &mut py[..n]);
        for i in 0..n {
            px[i] = predict(vx[i], fx[i], im.at(i), dt);
            py[i] = predict(vy[i], fy[i], im.at(i), dt);
            kick_drift_clear_axis(&mut x[i], &mut vx[i], &mut fx[i], im.at(i), dt);
            kick_drift_clear_axis(&mut y[i], &mut vy[i], &mut fy[i], im.at(i), dt);
        }
    };
    for_chunks!(kernel, [x, y, vx, vy, fx, fy, px, py], []);
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

impl VelocityVerlet {
    /// One kick–drift–kick step of length `h` (s) ending at `time` (s); `h` may be negative
    /// (Forest–Ruth's middle sub-step).
    fn kick_drift_kick<F: ForceField>(&mut self, state: &mut State, field: &mut F, h: f64, time: f64) {
        with_inverse_mass!(state, self.uniform_inverse_mass, |im| {
            let n = state.particles.len();
            match self.prediction.arrays(field, n) {
                Some((px, py)) => predict_kick_drift_clear(state, im, h, px, py),
                None => kick_drift_clear(state, im, h),
            }
            evaluate_and_account(state, field, self.prediction.velocities(field), h, time);
            kick(state, im, h);
        });
    }
}

impl Integrator for VelocityVerlet {
    fn start<F: ForceField>(&mut self, state: &mut State, field: &mut F, _dt: f64) {
        self.uniform_inverse_mass = state.particles.uniform_inverse_mass();
        start_forces(state, field);
    }

    fn step<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        self.kick_drift_kick(state, field, dt, (state.steps + 1) as f64 * dt);
        finish_step(state, dt);
    }

    fn substep<F: ForceField>(&mut self, state: &mut State, field: &mut F, h: f64, _dt: f64) {
        self.kick_drift_kick(state, field, h, state.time + h);
    }
}

/// Forest–Ruth: velocity-Verlet sub-steps θ dt, (1 − 2θ) dt, θ dt with θ = 1/(2 − 2^{1/3}) ≈
/// 1.3512, so the middle one runs backwards (−1.7024 dt). The composition cancels the
/// symmetric second-order error of velocity Verlet: order 4, still symplectic, three force
/// evaluations per step. Its stability limit, ω dt < 1.573, is narrower than velocity Verlet's
/// 2 because of the long sub-steps (`crate::plan::stability` measures it).
#[derive(Clone, Debug, Default)]
pub struct ForestRuth {
    verlet: VelocityVerlet,
}

impl ForestRuth {
    /// θ = 1/(2 − 2^{1/3}).
    const THETA: f64 = 1.351_207_191_959_657_8;

    /// The three sub-steps of a step of length `dt` (s) ending at `time`.
    fn compose<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64, time: f64) {
        let t = state.time;
        let theta = Self::THETA;
        self.verlet.kick_drift_kick(state, field, theta * dt, t + theta * dt);
        self.verlet.kick_drift_kick(state, field, (1.0 - 2.0 * theta) * dt, t + (1.0 - theta) * dt);
        self.verlet.kick_drift_kick(state, field, theta * dt, time);
    }
}

impl Integrator for ForestRuth {
    fn start<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        self.verlet.start(state, field, dt);
    }

    fn step<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        self.compose(state, field, dt, (state.steps + 1) as f64 * dt);
        finish_step(state, dt);
    }

    fn substep<F: ForceField>(&mut self, state: &mut State, field: &mut F, h: f64, _dt: f64) {
        self.compose(state, field, h, state.time + h);
    }
}

/// Position (Störmer) Verlet, as in the coursework's pseudo-code,
/// x_{n+1} = 2x_n − x_{n−1} + a_n dt², in its summed form: it keeps the increment
/// s_n = x_{n+1} − x_n and updates s_n = s_{n−1} + a_n dt², x_{n+1} = x_n + s_n. Identical in
/// exact arithmetic, but 2x_n − x_{n−1} cancels all digits the small displacement of a stiff,
/// loaded solid shares with its position (x ~ 1 m, u ~ 1e-7 m): the textbook form loses
/// about ε|x|/|u| per step and its error grew as dt shrank (1.2e-3 at t_c/80 on a 10 × 10
/// lattice against 1.7e-6 for velocity Verlet). The state's velocity is the central difference
/// v_n = (x_{n+1} − x_{n−1})/(2 dt) = (s_n + s_{n−1})/(2 dt), at the same time as its positions.
///
/// A step split where a contact switches is taken in velocity Verlet's sub-steps (the same
/// scheme in exact arithmetic, and one that takes steps of any length), after which the
/// increment is rebuilt from the velocity and force as at the start.
#[derive(Clone, Debug, Default)]
pub struct PositionVerlet {
    /// s = x_{n+1} − x_n, one step ahead of the state.
    step_x: Vec<f64>,
    step_y: Vec<f64>,
    /// Its predicted velocities and inverse mass serve both forms; its steps the split ones.
    verlet: VelocityVerlet,
}

/// x += s, then f = 0 for the next force evaluation, in one pass.
fn drift_clear(state: &mut State, step_x: &[f64], step_y: &[f64]) {
    let p = &mut state.particles;
    let (x, y, fx, fy) = (&mut p.x[..], &mut p.y[..], &mut state.fx[..], &mut state.fy[..]);
    let kernel =
        |_offset: usize, x: &mut [f64], y: &mut [f64], fx: &mut [f64], fy: &mut [f64], sx: &[f64], sy: &[f64]| {
            let n = x.len();
            let (y, fx, fy, sx, sy) = (&mut y[..n], &mut fx[..n], &mut fy[..n], &sx[..n], &sy[..n]);
            for i in 0..n {
                x[i] += sx[i];
                y[i] += sy[i];
                fx[i] = 0.0;
                fy[i] = 0.0;
            }
        };
    for_chunks!(kernel, [x, y, fx, fy], [step_x, step_y]);
}

/// [`drift_clear`] of a damped field, which first writes the predicted velocities ([`predict`],
/// step `dt`) into `(px, py)` in the same pass; `step` is (s_x, s_y).
fn predict_drift_clear<M: InverseMass>(
    state: &mut State,
    step: (&[f64], &[f64]),
    im: M,
    dt: f64,
    prediction: (&mut [f64], &mut [f64]),
) {
    let p = &mut state.particles;
    let (x, y, fx, fy, vx, vy) =
        (&mut p.x[..], &mut p.y[..], &mut state.fx[..], &mut state.fy[..], &p.vx[..], &p.vy[..]);
    let ((sx, sy), (px, py)) = (step, prediction);
    let kernel = |offset: usize,
                  x: &mut [f64],
                  y: &mut [f64],
                  fx: &mut [f64],
                  fy: &mut [f64],
                  px: &mut [f64],
                  py: &mut [f64],
                  sx: &[f64],
                  sy: &[f64],
                  vx: &[f64],
                  vy: &[f64]| {
        let n = x.len();
        let (y, fx, fy, px, py, im) =
            (&mut y[..n], &mut fx[..n], &mut fy[..n], &mut px[..n], &mut py[..n], im.part(offset, n));
        let (sx, sy, vx, vy) = (&sx[..n], &sy[..n], &vx[..n], &vy[..n]);
        for i in 0..n {
            px[i] = predict(vx[i], fx[i], im.at(i), dt);
            py[i] = predict(vy[i], fy[i], im.at(i), dt);
            x[i] += sx[i];
            y[i] += sy[i];
            fx[i] = 0.0;
            fy[i] = 0.0;
        }
    };
    for_chunks!(kernel, [x, y, fx, fy, px, py], [sx, sy, vx, vy]);
}

impl PositionVerlet {
    /// s = x_{n+1} − x_n = v dt + (f/m) dt²/2 from the state's velocities and forces: the
    /// start, and again after a split step.
    fn taylor_increments(&mut self, state: &State, dt: f64) {
        let p = &state.particles;
        let taylor = |v: &[f64], f: &[f64]| -> Vec<f64> {
            (0..v.len()).map(|i| dt * v[i] + 0.5 * dt * dt * f[i] * p.inv_mass[i]).collect()
        };
        self.step_x = taylor(&p.vx, &state.fx);
        self.step_y = taylor(&p.vy, &state.fy);
    }

    /// s_new = s + f/m · dt², the central velocity v = (s + s_new)/(2 dt), s ← s_new.
    fn advance<M: InverseMass>(&mut self, state: &mut State, im: M, dt: f64) {
        let p = &mut state.particles;
        let (step_x, step_y, vx, vy) = (&mut self.step_x[..], &mut self.step_y[..], &mut p.vx[..], &mut p.vy[..]);
        let (fx, fy) = (&state.fx[..], &state.fy[..]);
        let kernel = |offset: usize,
                      step_x: &mut [f64],
                      step_y: &mut [f64],
                      vx: &mut [f64],
                      vy: &mut [f64],
                      fx: &[f64],
                      fy: &[f64]| {
            let n = step_x.len();
            let (step_y, vx, vy, fx, fy, im) =
                (&mut step_y[..n], &mut vx[..n], &mut vy[..n], &fx[..n], &fy[..n], im.part(offset, n));
            for i in 0..n {
                let next_x = step_x[i] + dt * dt * fx[i] * im.at(i);
                let next_y = step_y[i] + dt * dt * fy[i] * im.at(i);
                vx[i] = (step_x[i] + next_x) / (2.0 * dt);
                vy[i] = (step_y[i] + next_y) / (2.0 * dt);
                step_x[i] = next_x;
                step_y[i] = next_y;
            }
        };
        for_chunks!(kernel, [step_x, step_y, vx, vy], [fx, fy]);
    }
}

impl Integrator for PositionVerlet {
    fn start<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        self.verlet.start(state, field, dt);
        self.taylor_increments(state, dt);
    }

    fn step<F: ForceField>(&mut self, state: &mut State, field: &mut F, dt: f64) {
        with_inverse_mass!(state, self.verlet.uniform_inverse_mass, |im| {
            let n = state.particles.len();
            match self.verlet.prediction.arrays(field, n) {
                Some(prediction) => predict_drift_clear(state, (&self.step_x, &self.step_y), im, dt, prediction),
                None => drift_clear(state, &self.step_x, &self.step_y),
            }
            let prediction = self.verlet.prediction.velocities(field);
            evaluate_and_account(state, field, prediction, dt, (state.steps + 1) as f64 * dt);
            self.advance(state, im, dt);
        });
        finish_step(state, dt);
    }

    fn substep<F: ForceField>(&mut self, state: &mut State, field: &mut F, h: f64, dt: f64) {
        self.verlet.kick_drift_kick(state, field, h, state.time + h);
        self.taylor_increments(state, dt);
    }
}
