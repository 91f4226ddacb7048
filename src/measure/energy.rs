//! Energy bookkeeping of a run.

use crate::sim::Trace;

/// Largest relative deviation of the energy balance over the samples:
/// max_t |E(t) − E(0)| / max_t (E_kin + E_pot + E_dissipated), with
/// E = E_kin + E_pot + E_dissipated − W_loads. The scale is the largest energy in play: E(0) for
/// a free run, about the work of the loads for a structure loaded from rest.
/// `None` without samples or without any energy.
pub fn energy_error(trace: &Trace) -> Option<f64> {
    let samples = trace.time.len();
    let stored = |s: usize| trace.kinetic[s] + trace.potential[s] + trace.dissipated[s];
    let total = |s: usize| stored(s) - trace.work[s];
    let scale = (0..samples).map(stored).fold(0.0, f64::max);
    (scale > 0.0).then(|| (0..samples).map(|s| (total(s) - total(0)).abs() / scale).fold(0.0, f64::max))
}
