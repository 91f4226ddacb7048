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

/// The rate (1/s) at which a decaying positive quantity falls over the second half of its
/// decay, from `points` (t, y) in time order: the least-squares slope of ln y over its upper
/// envelope (each point above every later one: an oscillation's crests, every point of a
/// monotonic decay), on the envelope points in the second half of the span from the first of
/// them to the last sample, where the slowest decay alone remains. `None` with fewer than two
/// such points.
pub fn decay_rate(points: &[(f64, f64)]) -> Option<f64> {
    let mut envelope: Vec<(f64, f64)> = Vec::new();
    for &(t, y) in points.iter().rev() {
        if y > 0.0 && envelope.last().is_none_or(|&(_, later)| y > later) {
            envelope.push((t, y));
        }
    }
    envelope.reverse();
    let (start, end) = (envelope.first()?.0, points.last()?.0);
    let late: Vec<(f64, f64)> =
        envelope.into_iter().filter(|(t, _)| *t >= 0.5 * (start + end)).map(|(t, y)| (t, y.ln())).collect();
    let n = late.len() as f64;
    let (mean_t, mean_y) = late.iter().fold((0.0, 0.0), |(a, b), (t, y)| (a + t / n, b + y / n));
    let (sty, stt) = late
        .iter()
        .fold((0.0, 0.0), |(a, b), (t, y)| (a + (t - mean_t) * (y - mean_y), b + (t - mean_t) * (t - mean_t)));
    (late.len() >= 2 && stt > 0.0).then(|| -sty / stt)
}
