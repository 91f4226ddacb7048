//! Unit tests of `src/measure/wave.rs`, moved out of the library (one test binary).

use mdsolids::measure::arrival_time;
use mdsolids::sim::WaveRecord;

#[test]
fn criteria_on_a_ramp_and_a_bump() {
    // Receiver speed rises linearly from t = 1 (0 → 1 at t = 2), peaks at t = 2.225 and falls.
    let time: Vec<f64> = (0..=40).map(|i| i as f64 * 0.1).collect();
    let speed: Vec<f64> = time.iter().map(|&t| if t < 1.0 { 0.0 } else { (t - 1.0).min(3.45 - t).max(0.0) }).collect();
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
