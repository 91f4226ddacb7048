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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn criteria_on_a_ramp_and_a_bump() {
        // Receiver speed rises linearly from t = 1 (0 → 1 at t = 2), peaks at t = 2.225 and falls.
        let time: Vec<f64> = (0..=40).map(|i| i as f64 * 0.1).collect();
        let speed: Vec<f64> =
            time.iter().map(|&t| if t < 1.0 { 0.0 } else { (t - 1.0).min(3.45 - t).max(0.0) }).collect();
        let record = WaveRecord {
            source_speed: vec![10.0; time.len()],
            source_displacement: vec![1.0; time.len()],
            source_kinetic: vec![50.0; time.len()],
            receiver_displacement: speed.clone(),
            receiver_kinetic: speed.iter().map(|v| 0.5 * v * v).collect(),
            receiver_speed: speed,
            time,
        };
        // θ = 0.05: speed level 0.5 is reached at t = 1.5 (exact on a linear ramp).
        assert!((arrival_time(&record, "speed_threshold", 0.05).unwrap() - 1.5).abs() < 1e-12);
        // displacement level 0.05 at t = 1.05.
        assert!((arrival_time(&record, "displacement_threshold", 0.05).unwrap() - 1.05).abs() < 1e-12);
        // kinetic level 2.5 = ½ v² at v = √5 > peak: never.
        assert_eq!(arrival_time(&record, "kinetic_energy", 0.05), None);
        assert!((arrival_time(&record, "first_maximum", 0.05).unwrap() - 2.2).abs() < 1e-9);
    }
}
