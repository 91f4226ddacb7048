//! Steps across contact switches. A damped contact's force jumps by γ δ̇ where it closes or
//! opens (δ = 0). A step over the switch integrates that jump with the scheme's quadrature,
//! which misplaces part of the impulse (velocity Verlet's trapezoid: γ δ̇ (½ − θ) dt for a
//! switch at θ dt), an O(dt) error per switch: the damped contact pair converged at order
//! 0.8–1 (r off by 1.2e-2 at t_c/50). Split at the switch, each sub-step lies on one side of it,
//! where the force is smooth, and every scheme keeps its order there.

use super::{Integrator, finish_step, forces_at};
use crate::sim::field::ForceField;
use crate::sim::probe::StepProbe;
use crate::sim::state::State;

/// Sub-steps shorter than this fraction of dt are not taken: a switch predicted that near the
/// current time has already happened within its prediction's error, and one that near the end
/// of the step is left to the step's last evaluation. Keeps sub-steps of zero length (round-off)
/// out, at a cost of at most γ δ̇ · 1e-9 dt of misplaced impulse.
const SHORTEST_SUBSTEP: f64 = 1e-9;

/// One step of `dt`: as `integrator` takes it, unless a damped contact switches inside it; then
/// in sub-steps that end at each switch ([`next_switch`]), each judging its contacts at its own
/// middle, with the forces evaluated anew on the far side of each switch and the state there
/// shown to `probe` (the contact clock reads the crossing where it happens). Fields that cannot
/// switch (bonded, undamped) compile to the plain step.
pub fn take_step<F: ForceField, I: Integrator, P: StepProbe>(
    integrator: &mut I,
    state: &mut State,
    field: &mut F,
    dt: f64,
    probe: &mut P,
) {
    let first = if F::SWITCH_JUMPS { next_switch(state, field, dt, dt) } else { None };
    if first.is_none() {
        return integrator.step(state, field, dt);
    }
    let end = (state.steps + 1) as f64 * dt;
    let mut next = first;
    loop {
        let h = next.unwrap_or(end - state.time);
        state.contacts_judged_at = Some(state.time + 0.5 * h);
        integrator.substep(state, field, h, dt);
        if next.is_none() {
            break;
        }
        state.time += h;
        probe.observe_switch(state);
        next = next_switch(state, field, end - state.time, dt);
        // The forces on the far side of the switch, as the next sub-step judges its contacts.
        state.contacts_judged_at = Some(state.time + 0.5 * next.unwrap_or(end - state.time));
        forces_at(state, field, state.time);
    }
    state.contacts_judged_at = None;
    field.judge_contacts_ahead(0.0); // as every evaluation outside a split step (static forces too)
    finish_step(state, dt);
}

/// Time (s) from now to the first switch of a contact within (ε, horizon − ε], ε =
/// [`SHORTEST_SUBSTEP`] · dt, or `None`. Each bond's extension is followed by its Taylor
/// polynomial δ + δ̇ s + δ̈ s²/2 from the state's positions, velocities and forces, with
/// δ̈ = n̂ · (a_i − a_j) + (|v_i − v_j|² − δ̇²)/|x_i − x_j|: exact in free flight (a contact
/// closes where straight paths meet), else off by O(s³), so a switch is placed within O(dt³) of
/// where the scheme crosses and O(dt³) of impulse lands on the wrong side: globally below a
/// second-order scheme's error. A switch placed early is met again by a short sub-step.
fn next_switch<F: ForceField>(state: &State, field: &F, horizon: f64, dt: f64) -> Option<f64> {
    let p = &state.particles;
    let margin = SHORTEST_SUBSTEP * dt;
    let acceleration = |i: usize| (state.fx[i] * p.inv_mass[i], state.fy[i] * p.inv_mass[i]);
    let mut first: Option<f64> = None;
    field.for_each_bond(&mut |i, j, rest, _k, shift| {
        let (dx, dy) = (p.x[i] - p.x[j] + shift, p.y[i] - p.y[j]);
        let (dvx, dvy) = (p.vx[i] - p.vx[j], p.vy[i] - p.vy[j]);
        let ((aix, aiy), (ajx, ajy)) = (acceleration(i), acceleration(j));
        let r = (dx * dx + dy * dy).sqrt();
        let (nx, ny) = (dx / r, dy / r);
        let rate = nx * dvx + ny * dvy;
        let curvature = nx * (aix - ajx) + ny * (aiy - ajy) + (dvx * dvx + dvy * dvy - rate * rate) / r;
        for s in quadratic_roots(r - rest, rate, curvature) {
            if s > margin && s <= horizon - margin && first.is_none_or(|t| s < t) {
                first = Some(s);
            }
        }
    });
    first
}

/// The roots s of c + b s + a s²/2 = 0, computed without cancellation: q = −(b + sign(b) √(b² −
/// 2ac))/2, s = c/q and 2q/a. Not-a-number or infinite where a root does not exist (no real root,
/// or a = 0: the one root is then c/q = −c/b), which every comparison refuses.
fn quadratic_roots(c: f64, b: f64, a: f64) -> [f64; 2] {
    let q = -0.5 * (b + (b * b - 2.0 * a * c).sqrt().copysign(b));
    [c / q, 2.0 * q / a]
}
