//! When a wave arrives: named criteria on the receiver's motion, relative to the source's.

use crate::sim::WaveRecord;

/// The arrival criteria, in the order the report lists them; the first is the recommended one.
pub const ARRIVAL_CRITERIA: [&str; 4] =
    ["speed_threshold", "displacement_threshold", "kinetic_energy", "first_maximum"];

/// Arrival time (s) of the wave at the receiver by `criterion` (one of [`ARRIVAL_CRITERIA`]),
/// with threshold θ:
/// - `speed_threshold`: the receiver's speed first reaches θ × the source's peak speed;
/// - `displacement_threshold`: its displacement first reaches θ × the source's peak displacement;
/// - `kinetic_energy`: its kinetic energy first reaches θ × the source's peak kinetic energy
///   (θ on energy is √θ on speed: later than the speed threshold);
/// - `first_maximum`: the first maximum of its speed once past the speed threshold (the crest).
///
/// Threshold crossings are interpolated linearly between records. `None` when the criterion is
/// never met.
pub fn arrival_time(record: &WaveRecord, criterion: &str, threshold: f64) -> Option<f64> {
    let peak = |series: &[f64]| series.iter().copied().fold(0.0, f64::max);
    let crossing = |series: &[f64], level: f64| -> Option<f64> {
        let i = series.iter().position(|&v| v >= level)?;
        if i == 0 {
            return Some(record.time[0]);
        }
        let (a, b) = (series[i - 1], series[i]);
        let (t0, t1) = (record.time[i - 1], record.time[i]);
        Some(t0 + (level - a) / (b - a) * (t1 - t0))
    };
    let speed_level = threshold * peak(&record.source_speed);
    match criterion {
        "speed_threshold" => crossing(&record.receiver_speed, speed_level),
        "displacement_threshold" => {
            crossing(&record.receiver_displacement, threshold * peak(&record.source_displacement))
        }
        "kinetic_energy" => crossing(&record.receiver_kinetic, threshold * peak(&record.source_kinetic)),
        "first_maximum" => {
            let v = &record.receiver_speed;
            let start = v.iter().position(|&s| s >= speed_level)?;
            (start.max(1)..v.len().saturating_sub(1))
                .find(|&i| v[i] >= v[i - 1] && v[i] > v[i + 1])
                .map(|i| record.time[i])
        }
        _ => None,
    }
}
