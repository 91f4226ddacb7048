//! Normal modes of a linear chain of N equal masses m and springs k between fixed walls.

use std::f64::consts::PI;

/// ω_n = 2 √(k/m) sin(nπ / (2(N+1))) (rad/s), n = 1..N.
pub fn chain_mode_frequency(n_particles: usize, k: f64, m: f64, mode: usize) -> f64 {
    2.0 * (k / m).sqrt() * (mode as f64 * PI / (2.0 * (n_particles as f64 + 1.0))).sin()
}

/// Exact displacements u_j(t) (m) and velocities u̇_j(t) (m/s), j = 1..N, of a chain starting at
/// rest positions with initial velocities `v0` (m/s):
/// u_j(t) = Σ_n B_n sin(ω_n t) sin(n j π/(N+1)), B_n = (2/(N+1)) Σ_j v0_j sin(n j π/(N+1)) / ω_n,
/// u̇_j(t) = Σ_n B_n ω_n cos(ω_n t) sin(n j π/(N+1)).
pub fn chain_normal_modes(k: f64, m: f64, v0: &[f64], t: f64) -> (Vec<f64>, Vec<f64>) {
    let n = v0.len();
    let shape = |mode: usize, j: usize| (mode as f64 * j as f64 * PI / (n as f64 + 1.0)).sin();
    let omega: Vec<f64> = (1..=n).map(|mode| chain_mode_frequency(n, k, m, mode)).collect();
    let amplitudes: Vec<f64> = (1..=n)
        .map(|mode| {
            let projection: f64 = (1..=n).map(|j| v0[j - 1] * shape(mode, j)).sum();
            2.0 / (n as f64 + 1.0) * projection / omega[mode - 1]
        })
        .collect();
    let sum = |j: usize, term: &dyn Fn(f64, f64) -> f64| -> f64 {
        (1..=n).map(|mode| amplitudes[mode - 1] * term(omega[mode - 1], t) * shape(mode, j)).sum()
    };
    let displacements = (1..=n).map(|j| sum(j, &|w, t| (w * t).sin())).collect();
    let velocities = (1..=n).map(|j| sum(j, &|w, t| w * (w * t).cos())).collect();
    (displacements, velocities)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn initial_velocity_is_reproduced_and_is_the_derivative() {
        let v0 = [0.0, 0.3, -0.1, 0.0, 0.2];
        let (_, at_start) = chain_normal_modes(2.0, 0.5, &v0, 0.0);
        // The mode sum inverts the sine transform exactly: only round-off (1e-15) remains.
        for j in 0..v0.len() {
            assert!((at_start[j] - v0[j]).abs() < 1e-12);
        }
        // u̇ is du/dt: a central difference has error ~ ω³ h² ≈ 1e-12, round-off ~1e-16/h.
        let (h, t) = (1e-6, 0.7);
        let (plus, _) = chain_normal_modes(2.0, 0.5, &v0, t + h);
        let (minus, _) = chain_normal_modes(2.0, 0.5, &v0, t - h);
        let (_, velocity) = chain_normal_modes(2.0, 0.5, &v0, t);
        for j in 0..v0.len() {
            assert!(((plus[j] - minus[j]) / (2.0 * h) - velocity[j]).abs() < 1e-8);
        }
    }
}
