//! Per-step probes: observers that must see every step (not just the sampled ones), such as
//! the clock that times a contact to a fraction of a step.

use super::state::State;

/// Observes the state after the start and after every step.
pub trait StepProbe {
    /// Called with the state at `state.time`.
    fn observe(&mut self, state: &State);
}

impl StepProbe for () {
    #[inline(always)]
    fn observe(&mut self, _state: &State) {}
}

impl<P: StepProbe> StepProbe for Option<P> {
    #[inline(always)]
    fn observe(&mut self, state: &State) {
        if let Some(probe) = self {
            probe.observe(state);
        }
    }
}

/// A zero crossing of a bond's extension δ, located inside the step by linear interpolation.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Crossing {
    /// Interpolated time of δ = 0 (s).
    pub time: f64,
    /// Interpolated normal rate δ̇ (m/s) at that time.
    pub rate: f64,
    /// True when δ goes from tension to compression (a contact closes).
    pub closing: bool,
}

/// Watches one bond's δ and δ̇ and records when δ changes sign.
#[derive(Clone, Debug)]
pub struct ContactClock {
    i: usize,
    j: usize,
    rest: f64,
    last: Option<(f64, f64, f64)>,
    /// Crossings so far, in time order.
    pub crossings: Vec<Crossing>,
}

impl ContactClock {
    /// A clock on the bond between `i` and `j` with rest length `rest` (m).
    pub fn new(i: usize, j: usize, rest: f64) -> ContactClock {
        ContactClock { i, j, rest, last: None, crossings: Vec::new() }
    }
}

impl StepProbe for ContactClock {
    fn observe(&mut self, state: &State) {
        let p = &state.particles;
        let (dx, dy) = (p.x[self.i] - p.x[self.j], p.y[self.i] - p.y[self.j]);
        let r = (dx * dx + dy * dy).sqrt();
        let delta = r - self.rest;
        let rate = (dx * (p.vx[self.i] - p.vx[self.j]) + dy * (p.vy[self.i] - p.vy[self.j])) / r;
        let now = (state.time, delta, rate);
        match self.last {
            // Starting exactly at δ = 0 and closing: the contact starts now.
            None if delta == 0.0 && rate < 0.0 => {
                self.crossings.push(Crossing { time: state.time, rate, closing: true });
            }
            Some((t0, d0, u0)) if (d0 > 0.0 && delta <= 0.0) || (d0 < 0.0 && delta >= 0.0) => {
                let theta = d0 / (d0 - delta);
                self.crossings.push(Crossing {
                    time: t0 + theta * (state.time - t0),
                    rate: u0 + theta * (rate - u0),
                    closing: d0 > 0.0,
                });
            }
            _ => {}
        }
        self.last = Some(now);
    }
}
