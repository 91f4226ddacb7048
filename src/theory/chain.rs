//! Normal modes of a linear chain of N equal masses m and springs k between fixed walls.

use std::f64::consts::PI;

/// ω_n = 2 √(k/m) sin(nπ / (2(N+1))) (rad/s), n = 1..N.
pub fn chain_mode_frequency(n_particles: usize, k: f64, m: f64, mode: usize) -> f64 {
    2.0 * (k / m).sqrt() * (mode as f64 * PI / (2.0 * (n_particles as f64 + 1.0))).sin()
}

/// Exact displacements u_j(t), j = 1..N, of a chain starting at rest positions with initial
/// velocities `v0` (m/s):
/// u_j(t) = Σ_n B_n sin(ω_n t) sin(n j π/(N+1)), B_n = (2/(N+1)) Σ_j v0_j sin(n j π/(N+1)) / ω_n.
pub fn chain_normal_mode_displacements(k: f64, m: f64, v0: &[f64], t: f64) -> Vec<f64> {
    let n = v0.len();
    let shape = |mode: usize, j: usize| (mode as f64 * j as f64 * PI / (n as f64 + 1.0)).sin();
    let amplitudes: Vec<f64> = (1..=n)
        .map(|mode| {
            let projection: f64 = (1..=n).map(|j| v0[j - 1] * shape(mode, j)).sum();
            2.0 / (n as f64 + 1.0) * projection / chain_mode_frequency(n, k, m, mode)
        })
        .collect();
    (1..=n)
        .map(|j| {
            (1..=n)
                .map(|mode| amplitudes[mode - 1] * (chain_mode_frequency(n, k, m, mode) * t).sin() * shape(mode, j))
                .sum()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn initial_velocity_is_reproduced() {
        // du/dt at t = 0 equals v0: check by a central difference (error ~ ω² h² ≈ 1e-12).
        let v0 = [0.0, 0.3, -0.1, 0.0, 0.2];
        let h = 1e-6;
        let plus = chain_normal_mode_displacements(2.0, 0.5, &v0, h);
        let minus = chain_normal_mode_displacements(2.0, 0.5, &v0, -h);
        for j in 0..v0.len() {
            assert!(((plus[j] - minus[j]) / (2.0 * h) - v0[j]).abs() < 1e-8);
        }
    }
}
