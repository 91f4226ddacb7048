//! The evolving state of a simulation: particles, forces, time and dissipated energy.

use crate::model::Particles;

/// A constant external force on one particle (a load), with the particle's start position
/// for the work it does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Load {
    /// Loaded particle.
    pub particle: usize,
    /// Force (N), x component.
    pub fx: f64,
    /// Force (N), y component.
    pub fy: f64,
}

/// Particles plus the forces acting on them at the current time.
#[derive(Clone, Debug)]
pub struct State {
    /// Positions, velocities, masses and constraints.
    pub particles: Particles,
    /// x force on each particle (N) at the current positions.
    pub fx: Vec<f64>,
    /// y force on each particle (N).
    pub fy: Vec<f64>,
    /// Steps taken.
    pub steps: u64,
    /// Simulated time (s) = steps · dt.
    pub time: f64,
    /// Energy taken out by dashpots and background damping so far (J).
    pub dissipated: f64,
    /// Dissipated power (W) at the current time, for the trapezoidal sum of `dissipated`.
    pub dissipation_power: f64,
    /// Constant external forces, added after every force evaluation.
    pub loads: Vec<Load>,
    /// Start positions (x, y) of the loaded particles, for the work of the loads.
    load_origins: Vec<(f64, f64)>,
}

impl State {
    /// A state at t = 0 with zero forces and the given loads.
    pub fn with_loads(particles: Particles, loads: Vec<Load>) -> State {
        let load_origins = loads.iter().map(|l| (particles.x[l.particle], particles.y[l.particle])).collect();
        State { loads, load_origins, ..State::new(particles) }
    }

    /// Work done by the loads since t = 0, Σ F · (x − x₀) (J).
    pub fn load_work(&self) -> f64 {
        let p = &self.particles;
        self.loads
            .iter()
            .zip(&self.load_origins)
            .map(|(l, (x0, y0))| l.fx * (p.x[l.particle] - x0) + l.fy * (p.y[l.particle] - y0))
            .sum()
    }

    /// A state at t = 0 with zero forces.
    pub fn new(particles: Particles) -> State {
        let n = particles.len();
        State {
            particles,
            fx: vec![0.0; n],
            fy: vec![0.0; n],
            steps: 0,
            time: 0.0,
            dissipated: 0.0,
            dissipation_power: 0.0,
            loads: Vec::new(),
            load_origins: Vec::new(),
        }
    }
}
