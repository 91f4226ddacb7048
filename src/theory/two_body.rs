//! Two equal particles of mass m joined by one spring (reduced mass μ = m/2).

use super::special::beta;
use std::f64::consts::PI;

/// The damping is at or above critical: there is no oscillation and no contact duration.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("overdamped: γ = {gamma} N s/m is at or above the critical value √(2km) = {critical} N s/m")]
pub struct Overdamped {
    /// The γ asked for (N s/m).
    pub gamma: f64,
    /// Critical damping √(2 k m) (N s/m).
    pub critical: f64,
}

/// Damped pair frequency ω = √(2k/m − (γ/m)²) (rad/s) for mass `m` (kg), stiffness `k`
/// (N/m) and dashpot `gamma` (N s/m).
///
/// ```
/// let w = mdsolids::theory::pair_omega(1.0, 1.0, 0.0).unwrap();
/// assert!((w - 2f64.sqrt()).abs() < 1e-15);
/// ```
pub fn pair_omega(k: f64, m: f64, gamma: f64) -> Result<f64, Overdamped> {
    let squared = 2.0 * k / m - (gamma / m).powi(2);
    if squared > 0.0 { Ok(squared.sqrt()) } else { Err(Overdamped { gamma, critical: (2.0 * k * m).sqrt() }) }
}

/// Contact duration t_c = π/ω (s) of the linear pair.
///
/// ```
/// // m = k = 1, γ = 0.304698 (r = 0.5): t_c = 2.274869 s (DESIGN.md).
/// let tc = mdsolids::theory::linear_contact_duration(1.0, 1.0, 0.304698).unwrap();
/// assert!((tc - 2.274869).abs() < 1e-6);
/// ```
pub fn linear_contact_duration(k: f64, m: f64, gamma: f64) -> Result<f64, Overdamped> {
    Ok(PI / pair_omega(k, m, gamma)?)
}

/// Restitution r = exp(−(γ/m) t_c): the relative normal speed after a half period over the
/// speed before. The decay rate is γ/m because the pair's equation is
/// (m/2) δ̈ = −k δ − γ δ̇.
pub fn linear_restitution(k: f64, m: f64, gamma: f64) -> Result<f64, Overdamped> {
    Ok((-(gamma / m) * linear_contact_duration(k, m, gamma)?).exp())
}

/// Restitution with the full mass m in place of the pair's reduced mass m/2, used consistently:
/// m δ̈ = −k δ − γ δ̇, so ω = √(k/m − (γ/2m)²), t_c = π/ω and r = exp(−γ t_c/(2m)) (the
/// pair's formulas with mass 2m). What a pair would give if its mass were mistaken for m.
///
/// ```
/// // The γ the reduced mass sets for r = 0.5 (m = k = 1) gives 0.616 with the full mass.
/// let g = mdsolids::theory::gamma_for_restitution(0.5, 1.0, 1.0);
/// let r = mdsolids::theory::full_mass_restitution(1.0, 1.0, g).unwrap();
/// assert!((r - 0.616146).abs() < 1e-6);
/// ```
pub fn full_mass_restitution(k: f64, m: f64, gamma: f64) -> Result<f64, Overdamped> {
    linear_restitution(k, 2.0 * m, gamma)
}

/// Restitution of the damped linear pair if its contact force k δ + γ δ̇ were clamped to stay
/// repulsive (δ the overlap): the pair then parts where that force first vanishes, before δ
/// does. With α = γ/m and ω_d = [`pair_omega`], δ = (v/ω_d) e^(−αt) sin ω_d t and
/// δ̇ = v e^(−αt) (cos ω_d t − (α/ω_d) sin ω_d t), so k δ + γ δ̇ = 0 at the phase θ = ω_d t in
/// (0, π] with tan θ = −γ ω_d/(k − γ α), θ = π + atan2(−γ ω_d, k − γ α); r = −δ̇/v there,
/// r = −e^(−αθ/ω_d) (cos θ − (α/ω_d) sin θ). Undamped, θ = π and r = 1.
///
/// ```
/// // The γ that gives r = 0.5 unclamped (m = k = 1) gives 0.550 clamped.
/// let g = mdsolids::theory::gamma_for_restitution(0.5, 1.0, 1.0);
/// let r = mdsolids::theory::clamped_restitution(1.0, 1.0, g).unwrap();
/// assert!((r - 0.550283).abs() < 1e-6);
/// assert_eq!(mdsolids::theory::clamped_restitution(1.0, 1.0, 0.0).unwrap(), 1.0);
/// ```
pub fn clamped_restitution(k: f64, m: f64, gamma: f64) -> Result<f64, Overdamped> {
    let (decay, omega) = (gamma / m, pair_omega(k, m, gamma)?);
    let phase = PI + (-gamma * omega).atan2(k - gamma * decay);
    Ok(-(-decay * phase / omega).exp() * (phase.cos() - decay / omega * phase.sin()))
}

/// Dashpot γ = −ln r · √(2km) / √(π² + ln² r) (N s/m) that gives restitution `r` in (0, 1].
///
/// ```
/// let g = mdsolids::theory::gamma_for_restitution(0.5, 1.0, 1.0);
/// assert!((g - 0.304698).abs() < 1e-6);
/// ```
pub fn gamma_for_restitution(r: f64, k: f64, m: f64) -> f64 {
    let ln_r = r.ln();
    // −ln r = |ln r| for r ≤ 1, and |·| keeps r = 1 from giving −0.
    ln_r.abs() * (2.0 * k * m).sqrt() / (PI * PI + ln_r * ln_r).sqrt()
}

/// Critical damping γ_crit = 2√(k m) = 2 m ω (N s/m) of a mass `m` (kg) on a stiffness `k`
/// (N/m), ω² = k/m: a dashpot of γ_crit on that mode neither rings nor creeps. The lattices'
/// `damping.background: critical` and the reports' γ/γ_crit take it at the slowest mode's k_min.
///
/// ```
/// assert_eq!(mdsolids::theory::critical_damping(4.0, 1.0), 4.0);
/// ```
pub fn critical_damping(k: f64, m: f64) -> f64 {
    2.0 * (k * m).sqrt()
}

/// Largest overlap δ_max = ((β+1) μ v² / (2C))^(1/(β+1)) (m) of an undamped power-law
/// collision of two masses `m` at relative speed `v` (energy balance μv²/2 = C δ^(β+1)/(β+1)).
pub fn power_law_max_overlap(c: f64, beta_exp: f64, m: f64, v: f64) -> f64 {
    let mu = 0.5 * m;
    ((beta_exp + 1.0) * mu * v * v / (2.0 * c)).powf(1.0 / (beta_exp + 1.0))
}

/// Exact contact duration (s) of an undamped collision through s = C δ^β:
/// t_c = 2 (δ_max / v) ∫₀¹ dx/√(1 − x^(β+1)) = 2 (δ_max / v) B(1/(β+1), ½)/(β+1).
/// For β = 1 this is π√(m/2k); for Hertz (β = 3/2) the integral is 1.4716.
///
/// ```
/// use mdsolids::theory::{linear_contact_duration, power_law_contact_duration};
/// let linear = linear_contact_duration(3.0, 2.0, 0.0).unwrap();
/// assert!((power_law_contact_duration(3.0, 1.0, 2.0, 0.7) - linear).abs() < 1e-12);
/// ```
pub fn power_law_contact_duration(c: f64, beta_exp: f64, m: f64, v: f64) -> f64 {
    let p = beta_exp + 1.0;
    2.0 * power_law_max_overlap(c, beta_exp, m, v) / v * beta(1.0 / p, 0.5) / p
}
