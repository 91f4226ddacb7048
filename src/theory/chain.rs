//! Normal modes of a linear chain of N equal masses m and springs k between fixed walls.

use std::f64::consts::PI;

/// ω_n = 2 √(k/m) sin(nπ / (2(N+1))) (rad/s), n = 1..N.
pub fn chain_mode_frequency(n_particles: usize, k: f64, m: f64, mode: usize) -> f64 {
    2.0 * (k / m).sqrt() * (mode as f64 * PI / (2.0 * (n_particles as f64 + 1.0))).sin()
}

/// The exact motion of a chain of N equal masses m and springs k between fixed walls, starting
/// at rest positions with initial velocities `v0` (m/s):
/// u_j(t) = Σ_n B_n sin(ω_n t) sin(n j π/(N+1)), B_n = (2/(N+1)) Σ_j v0_j sin(n j π/(N+1)) / ω_n,
/// u̇_j(t) = Σ_n B_n ω_n cos(ω_n t) sin(n j π/(N+1)). The amplitudes and mode shapes are
/// computed once; each time then costs N sines and cosines and 2N multiply-adds per particle
/// asked for ([`ChainModes::motion_of`]).
pub struct ChainModes {
    omega: Vec<f64>,
    amplitudes: Vec<f64>,
    /// `shape[mode][j]` = sin((mode+1)(j+1)π/(N+1)).
    shape: Vec<Vec<f64>>,
}

impl ChainModes {
    /// The modes of the chain with springs `k`, masses `m` and initial velocities `v0`.
    pub fn new(k: f64, m: f64, v0: &[f64]) -> ChainModes {
        let n = v0.len();
        let shape: Vec<Vec<f64>> = (1..=n)
            .map(|mode| (1..=n).map(|j| (mode as f64 * j as f64 * PI / (n as f64 + 1.0)).sin()).collect())
            .collect();
        let omega: Vec<f64> = (1..=n).map(|mode| chain_mode_frequency(n, k, m, mode)).collect();
        let amplitudes = (0..n)
            .map(|mode| {
                let projection: f64 = (0..n).map(|j| v0[j] * shape[mode][j]).sum();
                2.0 / (n as f64 + 1.0) * projection / omega[mode]
            })
            .collect();
        ChainModes { omega, amplitudes, shape }
    }

    /// Displacements u_j(t) (m) and velocities u̇_j(t) (m/s), j = 1..N, at time `t` (s).
    pub fn at(&self, t: f64) -> (Vec<f64>, Vec<f64>) {
        let everyone: Vec<usize> = (1..=self.omega.len()).collect();
        self.motion_of(&everyone, t).into_iter().unzip()
    }

    /// The displacement u_j(t) (m) and velocity u̇_j(t) (m/s) of each particle j (1..N) of
    /// `particles` at time `t` (s): N sines and cosines shared by all of them, then N
    /// multiply-adds per particle, so one particle costs O(N), not the O(N²) of all of them.
    pub fn motion_of(&self, particles: &[usize], t: f64) -> Vec<(f64, f64)> {
        let mut motion = vec![(0.0, 0.0); particles.len()];
        for (mode, shape) in self.shape.iter().enumerate() {
            let (sin, cos) = (self.omega[mode] * t).sin_cos();
            let (a, b) = (self.amplitudes[mode] * sin, self.amplitudes[mode] * self.omega[mode] * cos);
            for ((u, v), &j) in motion.iter_mut().zip(particles) {
                *u += a * shape[j - 1];
                *v += b * shape[j - 1];
            }
        }
        motion
    }
}
