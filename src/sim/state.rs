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

/// Particles driven along one axis at constant velocity until `stop_time`, then held still
/// (a velocity boundary condition). Their axis is held: the forces there are the supports'.
#[derive(Clone, Debug, PartialEq)]
pub struct Drive {
    /// Driven particles.
    pub particles: Vec<usize>,
    /// Driven along y (else along x).
    pub along_y: bool,
    /// Drive velocity (m/s).
    pub velocity: f64,
    /// When the drive stops (s).
    pub stop_time: f64,
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
    /// External forces, added after every force evaluation (times the load factor).
    pub loads: Vec<Load>,
    /// Time (s) over which the loads rise linearly from zero to their full value; 0 applies
    /// them at once.
    pub load_ramp: f64,
    /// Work done by the loads so far (J), summed at every force evaluation.
    work_done: f64,
    /// Positions of the loaded particles and the load factor at the last force evaluation.
    load_last: Vec<(f64, f64)>,
    load_factor_last: f64,
    /// The velocity boundary condition, if any.
    pub drive: Option<Drive>,
    /// Force (N) the drive applies to its particles along its axis, at the current time.
    pub drive_force: f64,
    drive_start: Vec<f64>,
    drive_stopped: bool,
    /// In a step split at contact switches, when (s) the current sub-step judges its damped
    /// contacts: its middle, where none switches, so each sub-step keeps one side of every
    /// switch. `None`: every evaluation judges them at its own time.
    pub contacts_judged_at: Option<f64>,
}

impl State {
    /// A state at t = 0 with zero forces and the given loads, ramped up over `load_ramp` (s).
    pub fn with_loads(particles: Particles, loads: Vec<Load>, load_ramp: f64) -> State {
        let load_last = loads.iter().map(|l| (particles.x[l.particle], particles.y[l.particle])).collect();
        let load_factor_last = if load_ramp > 0.0 { 0.0 } else { 1.0 };
        State { loads, load_ramp, load_last, load_factor_last, ..State::new(particles) }
    }

    /// Drives `drive.particles` along its axis: holds that axis and gives them its velocity.
    pub fn with_drive(mut self, drive: Drive) -> State {
        let p = &mut self.particles;
        for &i in &drive.particles {
            p.hold(i, drive.along_y);
            let (position, velocity) = if drive.along_y { (p.y[i], &mut p.vy[i]) } else { (p.x[i], &mut p.vx[i]) };
            *velocity = drive.velocity;
            self.drive_start.push(position);
        }
        self.drive = Some(drive);
        self
    }

    /// Time from which the structure may be judged at rest: after the load ramp and the drive.
    pub fn settling_from(&self) -> f64 {
        self.drive.as_ref().map_or(0.0, |d| d.stop_time).max(self.load_ramp)
    }

    /// Stops the drive once its time is up: the driven particles are put exactly where the drive
    /// takes them (x₀ + v t_stop) and held still.
    pub fn advance_drive(&mut self) {
        let Some(drive) = self.drive.as_ref().filter(|d| !self.drive_stopped && self.time >= d.stop_time) else {
            return;
        };
        let p = &mut self.particles;
        for (&i, start) in drive.particles.iter().zip(&self.drive_start) {
            let (position, velocity) =
                if drive.along_y { (&mut p.y[i], &mut p.vy[i]) } else { (&mut p.x[i], &mut p.vx[i]) };
            *position = start + drive.velocity * drive.stop_time;
            *velocity = 0.0;
        }
        self.drive_stopped = true;
    }

    /// Adds the drive's work over a step of length `dt` whose mean drive force is `mean` (N),
    /// F̄ v dt while it moves, and records `end`, the force at the new time.
    pub fn account_drive(&mut self, mean: f64, end: f64, dt: f64) {
        if let Some(drive) = &self.drive
            && !self.drive_stopped
        {
            self.work_done += mean * drive.velocity * dt;
        }
        self.drive_force = end;
    }

    /// The fraction of the loads applied at `time`: t / ramp during the ramp, then 1.
    pub fn load_factor(&self, time: f64) -> f64 {
        if self.load_ramp > 0.0 { (time / self.load_ramp).min(1.0) } else { 1.0 }
    }

    /// Work done by the loads since t = 0 (J).
    pub fn load_work(&self) -> f64 {
        self.work_done
    }

    /// Adds the loads' work since the last force evaluation, by the trapezoidal rule in the
    /// load factor: ½ (λ_prev + λ) Σ F · (x − x_prev) (exact for constant loads).
    pub fn account_load_work(&mut self, factor: f64) {
        let p = &self.particles;
        let mut work = 0.0;
        for (l, last) in self.loads.iter().zip(self.load_last.iter_mut()) {
            let now = (p.x[l.particle], p.y[l.particle]);
            work += l.fx * (now.0 - last.0) + l.fy * (now.1 - last.1);
            *last = now;
        }
        self.work_done += 0.5 * (self.load_factor_last + factor) * work;
        self.load_factor_last = factor;
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
            load_ramp: 0.0,
            work_done: 0.0,
            load_last: Vec::new(),
            load_factor_last: 1.0,
            drive: None,
            drive_force: 0.0,
            drive_start: Vec::new(),
            drive_stopped: false,
            contacts_judged_at: None,
        }
    }
}
