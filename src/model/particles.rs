//! Particle state as structure of arrays: each quantity one contiguous `Vec<f64>`.

/// Which axes of a particle are held fixed (its velocity on that axis never changes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Axes {
    /// x is constrained.
    pub x: bool,
    /// y is constrained.
    pub y: bool,
}

impl Axes {
    /// Free in both directions.
    pub const FREE: Axes = Axes { x: false, y: false };
    /// Fixed in both directions (a wall particle).
    pub const FIXED: Axes = Axes { x: true, y: true };
    /// Only y fixed: the motion stays on a line along x (the 1D scenes).
    pub const ONLY_X_MOVES: Axes = Axes { x: false, y: true };
}

/// Positions (m), velocities (m/s) and masses (kg) of all particles, in 2D.
///
/// A constrained axis is a particle listed in `held_x` or `held_y`: the integrators zero the
/// force on that axis after every force evaluation, so the particle keeps its velocity there
/// (zero for a support, a prescribed value for a driven boundary). Keeping constraints out of
/// the per-particle arrays keeps the particle loops to the arrays every particle needs.
#[derive(Clone, Debug, Default)]
pub struct Particles {
    /// x positions (m).
    pub x: Vec<f64>,
    /// y positions (m).
    pub y: Vec<f64>,
    /// x velocities (m/s).
    pub vx: Vec<f64>,
    /// y velocities (m/s).
    pub vy: Vec<f64>,
    /// Masses (kg).
    pub mass: Vec<f64>,
    /// 1/m (1/kg).
    pub inv_mass: Vec<f64>,
    /// Particles whose x is held (increasing order).
    pub held_x: Vec<usize>,
    /// Particles whose y is held (increasing order).
    pub held_y: Vec<usize>,
}

impl Particles {
    /// Number of particles.
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// True when there are no particles.
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// Appends a particle at rest at `(x, y)` with mass `mass` and the given constraints;
    /// returns its index.
    pub fn push(&mut self, x: f64, y: f64, mass: f64, fixed: Axes) -> usize {
        let index = self.len();
        self.x.push(x);
        self.y.push(y);
        self.vx.push(0.0);
        self.vy.push(0.0);
        self.mass.push(mass);
        self.inv_mass.push(1.0 / mass);
        if fixed.x {
            self.held_x.push(index);
        }
        if fixed.y {
            self.held_y.push(index);
        }
        index
    }

    /// Holds `particle` along y (`along_y`) or x, keeping the held list sorted.
    pub fn hold(&mut self, particle: usize, along_y: bool) {
        let held = if along_y { &mut self.held_y } else { &mut self.held_x };
        if let Err(slot) = held.binary_search(&particle) {
            held.insert(slot, particle);
        }
    }

    /// 1/m when every particle has the same mass, so the particle loops need not read an array.
    pub fn uniform_inverse_mass(&self) -> Option<f64> {
        let first = *self.inv_mass.first()?;
        self.inv_mass.iter().all(|&m| m == first).then_some(first)
    }

    /// Kinetic energy Σ ½ m v² (J).
    pub fn kinetic_energy(&self) -> f64 {
        (0..self.len()).map(|i| 0.5 * self.mass[i] * (self.vx[i] * self.vx[i] + self.vy[i] * self.vy[i])).sum()
    }

    /// Total momentum Σ m v (kg m/s) of the particles free on each axis.
    pub fn momentum(&self) -> (f64, f64) {
        (0..self.len()).fold((0.0, 0.0), |(px, py), i| (px + self.mass[i] * self.vx[i], py + self.mass[i] * self.vy[i]))
    }
}
