//! Unit tests of `src/measure/dispersion.rs` and `measure::curve_deviation`.

use mdsolids::measure::{branch_stiffness, curve_deviation, free_line_modes};
use std::f64::consts::PI;

/// The velocities of a free chain of `nodes` masses m = 1 and springs `k` (spacing 1) in its
/// exact standing modes, every mode n ≥ 1 at amplitude 1/n, sampled `samples` times over `length`.
fn free_chain(nodes: usize, k: f64, samples: usize, length: f64) -> (Vec<f64>, Vec<Vec<f64>>) {
    let times: Vec<f64> = (0..samples).map(|s| length * s as f64 / (samples - 1) as f64).collect();
    let omega = |n: usize| 2.0 * k.sqrt() * (PI * n as f64 / (2.0 * nodes as f64)).sin();
    let rows = times
        .iter()
        .map(|&t| {
            (0..nodes)
                .map(|j| {
                    (1..nodes)
                        .map(|n| {
                            (omega(n) * t).sin() * (PI * n as f64 * (j as f64 + 0.5) / nodes as f64).cos() / n as f64
                        })
                        .sum()
                })
                .collect()
        })
        .collect();
    (times, rows)
}

#[test]
fn a_free_chain_gives_back_its_branch() {
    // Every mode's peak within 5 % of the resolution 2π/T of ω_n = 2√(k/m) sin(nπ/(2N)) (the
    // Hann window's parabolic peak errs by about 1 % of a grid step π/T); k fitted to 1e-3.
    let (nodes, k, length) = (12, 1.5, 400.0);
    let (times, rows) = free_chain(nodes, k, 900, length);
    let peaks = free_line_modes(&times, &rows, 1.0);
    assert_eq!(peaks.len(), nodes - 1);
    for (n, peak) in peaks.iter().enumerate().map(|(i, p)| (i + 1, p)) {
        assert!((peak.q - PI * n as f64 / nodes as f64).abs() < 1e-12);
        let exact = 2.0 * k.sqrt() * (0.5 * peak.q).sin();
        assert!((peak.omega - exact).abs() < 0.05 * 2.0 * PI / length, "mode {n}: {} against {exact}", peak.omega);
    }
    let fitted = branch_stiffness(&peaks, 1.0, 1.0).unwrap();
    assert!((fitted / k - 1.0).abs() < 1e-3, "{fitted}");
}

#[test]
fn a_line_that_does_not_oscillate_peaks_at_zero() {
    // One end node accelerating alone (the top row of a lattice without diagonals pushed
    // sideways): every mode ramps, none oscillates.
    let times: Vec<f64> = (0..200).map(|s| s as f64 * 0.5).collect();
    let rows: Vec<Vec<f64>> =
        times.iter().map(|&t| (0..8).map(|j| if j == 7 { 1e-3 * t } else { 0.0 }).collect()).collect();
    let peaks = free_line_modes(&times, &rows, 1.0);
    assert!(peaks.iter().all(|p| p.omega == 0.0), "{peaks:?}");
    assert_eq!(branch_stiffness(&peaks, 1.0, 1.0), Some(0.0));
}

#[test]
fn a_curve_on_its_twin_deviates_by_nothing() {
    let points: Vec<(f64, f64)> = (0..10).map(|i| (i as f64, (i as f64).sin())).collect();
    assert_eq!(curve_deviation(&points, |t| Some(t.sin())), Some(0.0));
    // Shifted by 0.01: 0.01 of the twin's largest |value| over the points.
    let shifted: Vec<(f64, f64)> = points.iter().map(|&(t, y)| (t, y + 0.01)).collect();
    let deviation = curve_deviation(&shifted, |t| Some(t.sin())).unwrap();
    let scale = points.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    assert!((deviation - 0.01 / scale).abs() < 1e-12, "{deviation}");
    assert_eq!(curve_deviation(&points, |_| None), None);
}
