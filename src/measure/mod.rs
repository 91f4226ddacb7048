//! Measurements: pure functions from a run's trace and crossings to numbers.

pub use self::chain::normal_mode_error;
pub use self::contact::{ContactTiming, contact_timing};
pub use self::dispersion::{ModePeak, branch_stiffness, free_line_modes};
pub use self::energy::{decay_rate, energy_error};
pub use self::moduli::{
    ContinuumModuli, ElasticConstants, IsotropicConstants, LatticeShape, TensileModuli, anisotropic_moduli,
    constrained_modulus_y, constrained_shear_modulus, extension_error_allowed, homogeneity, lattice_constants,
    modulus_error_bound, network_constants, plane_wave_speeds, power_law_poisson_ratio, row_extension,
    row_extension_weights, shear_modulus, tensile_moduli, youngs_modulus_along,
};
pub use self::packing::{ContactForces, DiscFrame, Discs};
pub use self::wave::{ARRIVAL_CRITERIA, arrival_time};

mod chain;
mod contact;
mod dispersion;
mod energy;
mod moduli;
mod packing;
mod wave;

/// The smallest and largest of `values` (∞ and −∞ when there are none).
pub fn extremes<T: std::borrow::Borrow<f64>>(values: impl IntoIterator<Item = T>) -> (f64, f64) {
    values
        .into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), x| (low.min(*x.borrow()), high.max(*x.borrow())))
}

/// The median of `values` (the mean of the middle two for an even count); `None` when empty.
pub fn median(mut values: Vec<f64>) -> Option<f64> {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(values[n / 2]),
        _ => Some(0.5 * (values[n / 2 - 1] + values[n / 2])),
    }
}

/// Relative error (measured − reference)/reference, when both exist.
pub fn relative_error(measured: Option<f64>, reference: Option<f64>) -> Option<f64> {
    match (measured, reference) {
        (Some(m), Some(r)) if r != 0.0 => Some((m - r) / r),
        _ => None,
    }
}

/// How far a measured curve lies from its analytical twin: the largest |y − exact(t)| over
/// the `points` (t, y) where `exact` is defined, divided by the largest |exact(t)| there (a
/// relative distance, 0 when they coincide). `None` where `exact` is nowhere defined or zero.
pub fn curve_deviation(points: &[(f64, f64)], exact: impl Fn(f64) -> Option<f64>) -> Option<f64> {
    let (deviation, scale) = points
        .iter()
        .filter_map(|&(t, y)| exact(t).map(|e| ((y - e).abs(), e.abs())))
        .fold((0.0f64, 0.0f64), |(d, s), (dy, e)| (d.max(dy), s.max(e)));
    (scale > 0.0).then(|| deviation / scale)
}

/// Order of convergence p in |error| ∝ dt^p: least-squares slope of ln|error| against ln dt
/// over `points` = (dt, error); `None` with fewer than two usable points (finite, above the
/// round-off floor).
pub fn convergence_order(points: &[(f64, f64)]) -> Option<f64> {
    let usable: Vec<(f64, f64)> =
        points.iter().map(|&(dt, e)| (dt, e.abs())).filter(|(_, e)| *e > ROUND_OFF_FLOOR).collect();
    power_law_fit(&usable).map(|fit| fit.exponent)
}

/// A least-squares fit of y = c x^p on log–log axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PowerLawFit {
    /// The exponent p (slope of ln y against ln x).
    pub exponent: f64,
    /// R² of the straight line on log–log axes (1: every point on it).
    pub r_squared: f64,
    /// The prefactor c.
    pub prefactor: f64,
    /// How many points the line was fitted through (the positive, finite ones): through two, a
    /// line meets both and R² = 1 by construction ([`PowerLawFit::r_squared_measured`]).
    pub points: usize,
}

impl PowerLawFit {
    /// R² where it measures the fit: `None` through two points, which any straight line meets
    /// (R² = 1 whatever the data).
    ///
    /// ```
    /// use mdsolids::measure::power_law_fit;
    /// assert_eq!(power_law_fit(&[(1.0, 1.0), (4.0, 3.0)]).unwrap().r_squared_measured(), None);
    /// assert!(power_law_fit(&[(1.0, 1.0), (2.0, 3.0), (4.0, 3.0)]).unwrap().r_squared_measured().unwrap() < 1.0);
    /// ```
    pub fn r_squared_measured(&self) -> Option<f64> {
        (self.points > 2).then_some(self.r_squared)
    }
}

/// Fits y = c x^p to the positive, finite `points` (x, y); `None` with fewer than two of them
/// or a single x, x values within 1e-9 of each other counting as one (walls moved in and out
/// by 0.2 give |ΔW| = 0.19999999999999930 and 0.20000000000000018: a slope through their
/// round-off would be any number).
///
/// ```
/// use mdsolids::measure::power_law_fit;
/// assert!(power_law_fit(&[(0.19999999999999930, 1.0), (0.20000000000000018, 2.0)]).is_none());
/// assert!((power_law_fit(&[(1.0, 1.0), (4.0, 2.0)]).unwrap().exponent - 0.5).abs() < 1e-15);
/// ```
pub fn power_law_fit(points: &[(f64, f64)]) -> Option<PowerLawFit> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let (low, high) = extremes(logs.iter().map(|p| p.0));
    if high - low <= 1e-9 {
        return None;
    }
    line_fit(&logs).map(|line| PowerLawFit {
        exponent: line.slope,
        r_squared: line.r_squared,
        prefactor: line.intercept.exp(),
        points: logs.len(),
    })
}

/// A least-squares straight line y = a + b x.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineFit {
    /// The slope b.
    pub slope: f64,
    /// The intercept a (y at x = 0).
    pub intercept: f64,
    /// R² of the line (1: every point on it).
    pub r_squared: f64,
}

/// Fits y = a + b x to `points` (x, y) by least squares; `None` with fewer than two of them or
/// a single x.
pub fn line_fit(points: &[(f64, f64)]) -> Option<LineFit> {
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let (mx, my) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (sxy, sxx, syy) = points.iter().fold((0.0, 0.0, 0.0), |(a, b, c), (x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx), c + (y - my) * (y - my))
    });
    (sxx > 0.0).then(|| LineFit {
        slope: sxy / sxx,
        intercept: my - sxy / sxx * mx,
        r_squared: if syy > 0.0 { sxy * sxy / (sxx * syy) } else { 1.0 },
    })
}

/// Errors at or below this are round-off, not truncation: left out of orders and
/// recommendations.
pub const ROUND_OFF_FLOOR: f64 = 1e-12;

/// The largest time step whose error meets `target`, from a sweep of `points` = (dt, |error|):
/// interpolated on log–log axes between the last step that meets it and the next larger one
/// that does not, so dt* = dt_a (target/e_a)^(ln(dt_b/dt_a)/ln(e_b/e_a)). Returns the step and
/// how it was found: `Interpolated`, `AtLargest` (every step meets it: the largest does), or
/// `Extrapolated` with the measured `order` below the smallest step. `None` when no point is
/// usable or nothing can be said.
pub fn recommended_dt(points: &[(f64, f64)], target: f64, order: Option<f64>) -> Option<(f64, Recommendation)> {
    let mut sweep: Vec<(f64, f64)> =
        points.iter().copied().filter(|(dt, e)| *dt > 0.0 && e.is_finite() && *e > ROUND_OFF_FLOOR).collect();
    sweep.sort_by(|a, b| b.0.total_cmp(&a.0));
    let first_ok = sweep.iter().position(|&(_, e)| e <= target);
    match first_ok {
        Some(0) => Some((sweep[0].0, Recommendation::AtLargest)),
        Some(index) => {
            let ((dt_b, e_b), (dt_a, e_a)) = (sweep[index - 1], sweep[index]);
            let slope = (dt_b / dt_a).ln() / (e_b / e_a).ln();
            Some((dt_a * (target / e_a).powf(slope), Recommendation::Interpolated))
        }
        None => {
            let &(dt, e) = sweep.last()?;
            let order = order.filter(|p| *p > 0.0)?;
            Some((dt * (target / e).powf(1.0 / order), Recommendation::Extrapolated))
        }
    }
}

/// How [`recommended_dt`] found its answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Recommendation {
    /// Between two steps of the sweep.
    Interpolated,
    /// Every step meets the target; the largest is given (a larger one may do).
    AtLargest,
    /// No step meets it; extrapolated with the measured order.
    Extrapolated,
}

/// Mean and sample standard deviation of the values present (no deviation of a single value).
pub fn mean_spread(values: impl Iterator<Item = Option<f64>>) -> (Option<f64>, Option<f64>) {
    let v: Vec<f64> = values.flatten().collect();
    if v.is_empty() {
        return (None, None);
    }
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let spread =
        (v.len() > 1).then(|| (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt());
    (Some(mean), spread)
}

/// The distinct values of `values`, in increasing order.
pub fn sorted_distinct<T: Ord>(values: impl IntoIterator<Item = T>) -> Vec<T> {
    let mut distinct: Vec<T> = values.into_iter().collect();
    distinct.sort_unstable();
    distinct.dedup();
    distinct
}
