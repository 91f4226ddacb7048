//! Comparison of a simulated chain with its exact normal-mode solution.

use crate::sim::Trace;
use crate::theory::chain_normal_mode_displacements;

/// Largest deviation of the movable particles' displacements from the exact normal-mode
/// solution over all samples, relative to the largest exact displacement:
/// max |u_MD − u_exact| / max |u_exact|. `movable` are the particle indices of the chain
/// (walls excluded), `v0` their initial velocities (m/s). `None` without displacement samples.
pub fn normal_mode_error(trace: &Trace, movable: &[usize], v0: &[f64], k: f64, m: f64) -> Option<f64> {
    let mut largest_error: f64 = 0.0;
    let mut largest_amplitude: f64 = 0.0;
    for (t, displacement) in trace.time.iter().zip(&trace.displacement_x) {
        let exact = chain_normal_mode_displacements(k, m, v0, *t);
        for (&p, u) in movable.iter().zip(exact) {
            largest_error = largest_error.max((displacement[p] - u).abs());
            largest_amplitude = largest_amplitude.max(u.abs());
        }
    }
    (largest_amplitude > 0.0).then(|| largest_error / largest_amplitude)
}
