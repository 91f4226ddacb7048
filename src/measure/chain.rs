//! Comparison of a simulated chain with its exact normal-mode solution.

use crate::sim::Trace;
use crate::theory::ChainModes;

/// Largest deviation of the movable particles from the exact normal-mode solution over all
/// samples, in phase space: the larger of max |u_MD − u_exact| / max |u_exact| and
/// max |v_MD − v_exact| / max |v_exact|. Velocities count because positions alone can hide an
/// integrator's order (symplectic Euler's positions are position Verlet's when the run starts
/// from equilibrium; its velocities are first order). `movable` are the particle indices of
/// the chain (walls excluded), `v0` their initial velocities (m/s). `None` without samples.
pub fn normal_mode_error(trace: &Trace, movable: &[usize], v0: &[f64], k: f64, m: f64) -> Option<f64> {
    let modes = ChainModes::new(k, m, v0);
    let (mut error_u, mut error_v, mut largest_u, mut largest_v) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for ((t, displacement), velocity) in trace.time.iter().zip(&trace.displacement_x).zip(&trace.velocity_x) {
        let (exact_u, exact_v) = modes.at(*t);
        for ((&p, u), v) in movable.iter().zip(exact_u).zip(exact_v) {
            error_u = error_u.max((displacement[p] - u).abs());
            error_v = error_v.max((velocity[p] - v).abs());
            largest_u = largest_u.max(u.abs());
            largest_v = largest_v.max(v.abs());
        }
    }
    (largest_u > 0.0 && largest_v > 0.0).then(|| (error_u / largest_u).max(error_v / largest_v))
}
