//! The evolving state of a simulation: particles, forces, time and dissipated energy.

use crate::model::Particles;

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
}

impl State {
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
        }
    }
}
