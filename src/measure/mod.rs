//! Measurements: pure functions from a run's trace and crossings to numbers.

pub use self::chain::normal_mode_error;
pub use self::contact::{ContactTiming, contact_timing};
pub use self::energy::energy_error;
pub use self::moduli::{LatticeShape, TensileModuli, continuum_moduli, homogeneity, shear_modulus, tensile_moduli};

mod chain;
mod contact;
mod energy;
mod moduli;

/// Order of convergence p in |error| ∝ dt^p: least-squares slope of ln|error| against ln dt
/// over `points` = (dt, error); `None` with fewer than two usable (non-zero, finite) points.
pub fn convergence_order(points: &[(f64, f64)]) -> Option<f64> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(dt, e)| *dt > 0.0 && e.abs() > 0.0 && e.is_finite())
        .map(|(dt, e)| (dt.ln(), e.abs().ln()))
        .collect();
    if logs.len() < 2 {
        return None;
    }
    let n = logs.len() as f64;
    let (mx, my) = logs.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (sxy, sxx) = logs.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + (x - mx) * (y - my), b + (x - mx) * (x - mx)));
    (sxx > 0.0).then(|| sxy / sxx)
}
