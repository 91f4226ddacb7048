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
/// A constrained axis is expressed by a zero inverse mass on that axis, so the integrators treat
/// every particle alike: `a = f · inv_mass` is zero there and the particle keeps its velocity
/// (zero for a support, a prescribed value for a driven boundary).
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
    /// Masses (kg), used for kinetic energy and momentum.
    pub mass: Vec<f64>,
    /// 1/m on the x axis (1/kg), zero where x is constrained.
    pub inv_mass_x: Vec<f64>,
    /// 1/m on the y axis (1/kg), zero where y is constrained.
    pub inv_mass_y: Vec<f64>,
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
        let inverse = |held: bool| if held { 0.0 } else { 1.0 / mass };
        self.x.push(x);
        self.y.push(y);
        self.vx.push(0.0);
        self.vy.push(0.0);
        self.mass.push(mass);
        self.inv_mass_x.push(inverse(fixed.x));
        self.inv_mass_y.push(inverse(fixed.y));
        self.len() - 1
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
