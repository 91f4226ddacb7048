//! The dispersion relation ω(q) of a line of nodes measured from its motion: a space–time
//! Fourier transform of the sampled series along the line (the probes of a lattice).

use std::f64::consts::PI;

/// One standing wave of a line of nodes, measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModePeak {
    /// Wavenumber q = nπ/(N a) (rad/m) of mode n of N nodes a apart.
    pub q: f64,
    /// Frequency (rad/s) at the peak of the mode's power spectrum; 0 when the mode does not
    /// oscillate (its power peaks at ω = 0: a ramp or a constant).
    pub omega: f64,
}

/// The measured modes of a line of N nodes `spacing` (m) apart with free ends, from `rows`
/// (one row per sample at `times` (s), evenly spaced; one value per node along the line,
/// velocities best: a displacement's offset puts power near ω = 0). In space, the projection on
/// the free line's modes cos(q a (j + ½)), q = nπ/(N a), n = 1..N−1 (the DCT-II; mode 0, the
/// line moving as one, has no frequency); in time, each mode's power |Σ_s w_s A_n(t_s)
/// e^(−iωt_s)|² with a Hann window w over a grid of half the resolution 2π/T up to the Nyquist
/// frequency π/Δt, its peak placed between grid points by a parabola through the logarithms
/// (exact for the Hann window's Gaussian-like main lobe to about 1 % of the grid step). A free
/// chain's modes are exactly these standing waves, so its peaks fall on its branch ω(q).
/// Empty with fewer than 4 samples or 2 nodes.
pub fn free_line_modes(times: &[f64], rows: &[Vec<f64>], spacing: f64) -> Vec<ModePeak> {
    let nodes = rows.first().map_or(0, Vec::len);
    let samples = times.len().min(rows.len());
    if samples < 4 || nodes < 2 {
        return Vec::new();
    }
    let duration = times[samples - 1] - times[0];
    let step = PI / duration;
    // The Nyquist frequency π/Δt = (samples − 1) grid steps of π/T.
    let grid = samples - 1;
    let amplitudes = windowed_modes(&rows[..samples], nodes);
    let power = spectra(&times[..samples], &amplitudes, step, grid);
    power
        .iter()
        .enumerate()
        .map(|(n, spectrum)| ModePeak {
            q: (n + 1) as f64 * PI / (nodes as f64 * spacing),
            omega: step * peak_position(spectrum),
        })
        .collect()
}

/// The Hann-windowed amplitude A_n(t_s) w_s of modes n = 1..N−1 at every sample:
/// A_n = Σ_j u_j cos(πn(j + ½)/N).
fn windowed_modes(rows: &[Vec<f64>], nodes: usize) -> Vec<Vec<f64>> {
    let samples = rows.len();
    let window = |s: usize| 0.5 - 0.5 * (2.0 * PI * s as f64 / (samples - 1) as f64).cos();
    (1..nodes)
        .map(|n| {
            let shape: Vec<f64> = (0..nodes).map(|j| (PI * n as f64 * (j as f64 + 0.5) / nodes as f64).cos()).collect();
            rows.iter()
                .enumerate()
                .map(|(s, row)| window(s) * row.iter().zip(&shape).map(|(u, c)| u * c).sum::<f64>())
                .collect()
        })
        .collect()
}

/// Each mode's power at the frequencies i·`step`, i = 0..=`grid` (the phases computed once per
/// frequency and sample, shared by the modes).
fn spectra(times: &[f64], amplitudes: &[Vec<f64>], step: f64, grid: usize) -> Vec<Vec<f64>> {
    let by_frequency: Vec<Vec<f64>> = (0..=grid)
        .map(|i| {
            let omega = i as f64 * step;
            let phases: Vec<(f64, f64)> = times.iter().map(|t| (omega * (t - times[0])).sin_cos()).collect();
            amplitudes
                .iter()
                .map(|series| {
                    let (re, im) = series
                        .iter()
                        .zip(&phases)
                        .fold((0.0, 0.0), |(re, im), (a, (sin, cos))| (re + a * cos, im - a * sin));
                    re * re + im * im
                })
                .collect()
        })
        .collect();
    (0..amplitudes.len()).map(|mode| by_frequency.iter().map(|power| power[mode]).collect()).collect()
}

/// The position of a spectrum's largest value in grid steps, between grid points by a parabola
/// through the logarithms of it and its neighbours; 0 at the first point (a spectrum that
/// peaks at ω = 0 is symmetric about it).
fn peak_position(spectrum: &[f64]) -> f64 {
    let top = (0..spectrum.len()).max_by(|&a, &b| spectrum[a].total_cmp(&spectrum[b])).unwrap_or(0);
    if top == 0 || top + 1 == spectrum.len() || spectrum[top] <= 0.0 {
        return top as f64;
    }
    let [left, middle, right] =
        [spectrum[top - 1], spectrum[top], spectrum[top + 1]].map(|p| p.max(f64::MIN_POSITIVE).ln());
    let curvature = left - 2.0 * middle + right;
    if curvature >= 0.0 { top as f64 } else { top as f64 + 0.5 * (left - right) / curvature }
}

/// The stiffness k_eff (N/m) of the branch ω = 2√(k_eff/m)|sin(qa/2)| nearest the measured
/// `peaks` of masses `m` (kg) `spacing` (m) apart, by least squares in ω²:
/// k_eff = m Σ ω² s² / (4 Σ s⁴), s = sin(qa/2). `None` without peaks.
pub fn branch_stiffness(peaks: &[ModePeak], m: f64, spacing: f64) -> Option<f64> {
    let s2 = |p: &ModePeak| (0.5 * p.q * spacing).sin().powi(2);
    let (numerator, denominator) =
        peaks.iter().fold((0.0, 0.0), |(a, b), p| (a + p.omega * p.omega * s2(p), b + s2(p) * s2(p)));
    (denominator > 0.0).then(|| m * numerator / (4.0 * denominator))
}
