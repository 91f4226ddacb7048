//! Energy bookkeeping of a run.

use crate::sim::Trace;

/// Largest relative deviation max_t |E(t) − E(0)| / E(0) of the total energy
/// E = E_kin + E_pot + E_dissipated over the samples; `None` when E(0) = 0 or no samples.
pub fn energy_error(trace: &Trace) -> Option<f64> {
    let total = |s: usize| trace.kinetic[s] + trace.potential[s] + trace.dissipated[s];
    let initial = total(0);
    if trace.time.is_empty() || initial == 0.0 {
        return None;
    }
    (0..trace.time.len()).map(|s| (total(s) - initial).abs() / initial.abs()).reduce(f64::max)
}
