//! Per-step probes: observers that must see every step (not just the sampled ones), such as
//! the clock that times a contact to a fraction of a step.

use super::state::State;

/// Observes the state after the start and after every step.
pub trait StepProbe {
    /// Called with the state at `state.time`.
    fn observe(&mut self, state: &State);
    /// Called with the state at a contact switch inside a step, at `state.time`, where the step
    /// was split (`integrate::take_step`); for probes that time switches, nothing otherwise.
    fn observe_switch(&mut self, _state: &State) {}
    /// Whether the probe has seen all it needs: the run then ends after this step (a stability
    /// trial once its amplitude has escaped). Runs a user asked for never end this way.
    #[inline(always)]
    fn seen_enough(&self) -> bool {
        false
    }
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

    fn observe_switch(&mut self, state: &State) {
        if let Some(probe) = self {
            probe.observe_switch(state);
        }
    }

    #[inline(always)]
    fn seen_enough(&self) -> bool {
        self.as_ref().is_some_and(P::seen_enough)
    }
}

/// A zero crossing of a bond's extension δ, located by linear interpolation between the states
/// the clock sees: after every step and, where a damped contact switches, at the switch.
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

    /// A damped contact's switch: the crossing itself (δ ≈ 0), where the interpolation above
    /// then lands, with no error from the kink of δ̇ inside a step (O(dt) for the rate).
    fn observe_switch(&mut self, state: &State) {
        self.observe(state);
    }
}

/// Watches a wave travel from a source particle to a set of receivers, every step: the
/// source's displacement and speed, and over the receivers the largest displacement, the
/// largest speed and their kinetic energy. Displacements are from the start positions.
#[derive(Clone, Debug, Default)]
pub struct WaveProbe {
    source: usize,
    receivers: Vec<usize>,
    /// Record every this many observations (1: every step).
    every: u64,
    seen: u64,
    start: Vec<(f64, f64)>,
    /// The recorded series, one entry per observed step.
    pub record: WaveRecord,
}

/// What a [`WaveProbe`] recorded, one entry per step.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WaveRecord {
    /// Time (s).
    pub time: Vec<f64>,
    /// |u| of the source (m).
    pub source_displacement: Vec<f64>,
    /// |v| of the source (m/s).
    pub source_speed: Vec<f64>,
    /// ½ m v² of the source (J).
    pub source_kinetic: Vec<f64>,
    /// max |u| over the receivers (m).
    pub receiver_displacement: Vec<f64>,
    /// max |v| over the receivers (m/s).
    pub receiver_speed: Vec<f64>,
    /// Σ ½ m v² over the receivers (J).
    pub receiver_kinetic: Vec<f64>,
}

impl WaveRecord {
    /// Appends the sample at `time` (s) of the source's and each receiver's motion, each as
    /// (|u| m, |v| m/s, ½ m v² J): the source's as it is, the receivers' largest |u| and |v| and
    /// their summed kinetic energy.
    pub fn push(
        &mut self,
        time: f64,
        (u, v, kinetic): (f64, f64, f64),
        receivers: impl Iterator<Item = (f64, f64, f64)> + Clone,
    ) {
        self.time.push(time);
        self.source_displacement.push(u);
        self.source_speed.push(v);
        self.source_kinetic.push(kinetic);
        self.receiver_displacement.push(receivers.clone().map(|m| m.0).fold(0.0, f64::max));
        self.receiver_speed.push(receivers.clone().map(|m| m.1).fold(0.0, f64::max));
        self.receiver_kinetic.push(receivers.map(|m| m.2).sum());
    }
}

impl WaveProbe {
    /// A probe from particle `source` to the particles `receivers`, recording every `every`-th
    /// step (arrival times are then known to `every` steps).
    pub fn new(source: usize, receivers: Vec<usize>, every: u64) -> WaveProbe {
        WaveProbe { source, receivers, every: every.max(1), ..WaveProbe::default() }
    }
}

impl StepProbe for WaveProbe {
    fn observe(&mut self, state: &State) {
        self.seen += 1;
        if !(self.seen - 1).is_multiple_of(self.every) {
            return;
        }
        let p = &state.particles;
        if self.start.is_empty() {
            self.start = p.x.iter().zip(&p.y).map(|(&x, &y)| (x, y)).collect();
        }
        let start = &self.start;
        let motion = |i: usize| {
            let speed = p.vx[i].hypot(p.vy[i]);
            ((p.x[i] - start[i].0).hypot(p.y[i] - start[i].1), speed, 0.5 * speed.powi(2) / p.inv_mass[i])
        };
        self.record.push(state.time, motion(self.source), self.receivers.iter().map(|&i| motion(i)));
    }
}

impl<A: StepProbe, B: StepProbe> StepProbe for (A, B) {
    #[inline(always)]
    fn observe(&mut self, state: &State) {
        self.0.observe(state);
        self.1.observe(state);
    }

    fn observe_switch(&mut self, state: &State) {
        self.0.observe_switch(state);
        self.1.observe_switch(state);
    }

    /// Both: a run that one probe is done with still feeds the other.
    #[inline(always)]
    fn seen_enough(&self) -> bool {
        self.0.seen_enough() && self.1.seen_enough()
    }
}

/// One frame of a movie: every particle's position and speed at one time.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Time (s).
    pub time: f64,
    /// Positions (m).
    pub x: Vec<f64>,
    /// Positions (m).
    pub y: Vec<f64>,
    /// Speeds |v| (m/s).
    pub speed: Vec<f64>,
}

impl Frame {
    /// The frame of `state`: its time, positions and speeds.
    pub fn of(state: &State) -> Frame {
        let p = &state.particles;
        Frame {
            time: state.time,
            x: p.x.clone(),
            y: p.y.clone(),
            speed: p.vx.iter().zip(&p.vy).map(|(vx, vy)| vx.hypot(*vy)).collect(),
        }
    }
}

/// Records `frames` [`Frame`]s evenly spread over a run of `steps` steps (the first at the
/// start, the last at the end), for a movie; fewer when the run stops early.
#[derive(Clone, Debug, Default)]
pub struct FrameProbe {
    steps: u64,
    wanted: u64,
    seen: u64,
    /// The frames so far.
    pub frames: Vec<Frame>,
}

impl FrameProbe {
    /// A probe that keeps `frames` (≥ 2) states of a run of `steps` steps.
    pub fn new(steps: u64, frames: u64) -> FrameProbe {
        FrameProbe { steps, wanted: frames.max(2), ..FrameProbe::default() }
    }

    /// The step of frame `k`: round(k · steps / (frames − 1)).
    fn step_of(&self, k: u64) -> u64 {
        (k * self.steps + (self.wanted - 1) / 2) / (self.wanted - 1)
    }
}

impl StepProbe for FrameProbe {
    fn observe(&mut self, state: &State) {
        let step = self.seen;
        self.seen += 1;
        let k = self.frames.len() as u64;
        if k >= self.wanted || step != self.step_of(k) {
            return;
        }
        self.frames.push(Frame::of(state));
    }
}
