//! Damped motion: the linear pair's overlap δ(t) in closed form, the slowest energy decay of a
//! network under background damping, and a power-law contact with a dashpot, which has no
//! closed form, integrated on its own (fourth-order Runge–Kutta in its own variables, no code
//! shared with the simulation), with the dashpot that gives it a restitution asked for.

use super::two_body::{Overdamped, pair_omega, power_law_contact_duration};

/// Overlap δ(t) (m, compression positive) of two masses `m` (kg) joined by a linear spring `k`
/// (N/m) and dashpot `gamma` (N s/m), starting at the rest length and approaching at relative
/// speed `v` (m/s): the reduced mass m/2 obeys (m/2) δ̈ = −k δ − γ δ̇, so
/// δ(t) = (v/ω_d) e^(−γt/m) sin(ω_d t), ω_d = √(2k/m − (γ/m)²) (the decay rate γ/(2 m_eff) with
/// m_eff = m/2).
///
/// ```
/// // Undamped, a quarter period in: the largest overlap v/ω = v √(m/(2k)).
/// let w = 2f64.sqrt();
/// let d = mdsolids::theory::linear_pair_overlap(1.0, 1.0, 0.0, 0.5, std::f64::consts::FRAC_PI_2 / w).unwrap();
/// assert!((d - 0.5 / w).abs() < 1e-15);
/// ```
pub fn linear_pair_overlap(k: f64, m: f64, gamma: f64, v: f64, t: f64) -> Result<f64, Overdamped> {
    let omega = pair_omega(k, m, gamma)?;
    Ok(v / omega * (-gamma * t / m).exp() * (omega * t).sin())
}

/// The rate (1/s) at which the kinetic energy of a network of masses `m` (kg) under background
/// damping `gamma_g` (N s/m) alone falls at late times, its softest stiffness `k_min` (N/m):
/// each mode obeys m ẍ = −k x − γ_g ẋ, so below γ_crit = 2√(k_min m) every mode's energy falls
/// as e^(−γ_g t/m), and above it the slowest mode's as e^(−2λt),
/// λ = γ_g/(2m) − √((γ_g/(2m))² − k_min/m): together γ_g/m − Re √((γ_g/m)² − 4k_min/m).
///
/// ```
/// use mdsolids::theory::background_decay_rate;
/// assert_eq!(background_decay_rate(1.0, 1.0, 1.0), 1.0); // below γ_crit = 2: γ_g/m
/// let overdamped = background_decay_rate(10.0, 1.0, 1.0);
/// assert!((overdamped - (10.0 - 96f64.sqrt())).abs() < 1e-12);
/// ```
pub fn background_decay_rate(gamma_g: f64, m: f64, k_min: f64) -> f64 {
    let rate = gamma_g / m;
    rate - (rate * rate - 4.0 * k_min / m).max(0.0).sqrt()
}

/// Runge–Kutta steps per undamped contact duration: the error of the restitution (∝ h⁴) is
/// below 1e-12 at 20 000; the crossing of δ = 0 is found by Newton's method on steps from the
/// last state inside, so it is as accurate.
const STEPS_PER_CONTACT: f64 = 20_000.0;

/// Contact durations after which a contact that has not opened counts as stuck: a heavily
/// damped power-law contact creeps apart as δ ∝ t^(−1/(β−1)) and never opens.
const LONGEST_CONTACT: f64 = 50.0;

/// Restitution of a collision of two masses `m` (kg) at relative speed `v` (m/s) through a
/// contact spring s = C δ^β (`c` in N/m^β, compression only) and a dashpot `gamma` (N s/m)
/// that is not clamped (the force may pull while δ > 0): (m/2) δ̈ = −C δ^β − γ δ̇ from δ = 0,
/// δ̇ = v, integrated until δ returns to 0; r = −δ̇/v there. `None` if the contact does not
/// open within 50 undamped contact durations. For β = 1 it is the closed form
/// exp(−γ t_c/m).
///
/// ```
/// use mdsolids::theory::{linear_restitution, power_law_restitution};
/// let r = power_law_restitution(1.0, 1.0, 1.0, 0.3, 0.7).unwrap();
/// assert!((r - linear_restitution(1.0, 1.0, 0.3).unwrap()).abs() < 1e-11);
/// ```
pub fn power_law_restitution(c: f64, beta: f64, m: f64, gamma: f64, v: f64) -> Option<f64> {
    let mu = 0.5 * m;
    // Hertz's δ^(3/2) as δ√δ, ~10× faster than `powf` and as accurate: 20 000 steps per
    // contact, and a bisection on γ takes dozens of collisions. Written here, not borrowed from
    // the springs (`model::law`), so that the answer shares no code with what it checks.
    let spring = |d: f64| if beta == 1.5 { d * d.sqrt() } else { d.powf(beta) };
    let acceleration = |d: f64, s: f64| -(c * spring(d.max(0.0)) + gamma * s) / mu;
    // One classical Runge–Kutta step of length h from (δ, δ̇).
    let step = |d: f64, s: f64, h: f64| {
        let (k1d, k1s) = (s, acceleration(d, s));
        let (k2d, k2s) = (s + 0.5 * h * k1s, acceleration(d + 0.5 * h * k1d, s + 0.5 * h * k1s));
        let (k3d, k3s) = (s + 0.5 * h * k2s, acceleration(d + 0.5 * h * k2d, s + 0.5 * h * k2s));
        let (k4d, k4s) = (s + h * k3s, acceleration(d + h * k3d, s + h * k3s));
        (d + h / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d), s + h / 6.0 * (k1s + 2.0 * k2s + 2.0 * k3s + k4s))
    };
    let h = power_law_contact_duration(c, beta, m, v) / STEPS_PER_CONTACT;
    let (mut d, mut s) = (0.0f64, v);
    for _ in 0..(LONGEST_CONTACT * STEPS_PER_CONTACT) as usize {
        let (next_d, next_s) = step(d, s, h);
        if next_d <= 0.0 && d > 0.0 {
            // Where δ crosses 0 within the step: Newton's method on the step's length.
            let mut tau = h * d / (d - next_d);
            for _ in 0..4 {
                let (end_d, end_s) = step(d, s, tau);
                tau -= end_d / end_s;
            }
            return Some(-step(d, s, tau).1 / v);
        }
        (d, s) = (next_d, next_s);
    }
    None
}

/// The dashpot γ (N s/m) that gives the power-law collision of [`power_law_restitution`] the
/// restitution `r` in (0, 1), by bisection (r falls as γ grows); `None` if no γ below the
/// one at which the contact sticks gives it.
///
/// ```
/// use mdsolids::theory::{gamma_for_restitution, power_law_gamma_for_restitution};
/// let g = power_law_gamma_for_restitution(0.5, 1.0, 1.0, 1.0, 0.7).unwrap();
/// assert!((g - gamma_for_restitution(0.5, 1.0, 1.0)).abs() < 1e-8);
/// ```
pub fn power_law_gamma_for_restitution(r: f64, c: f64, beta: f64, m: f64, v: f64) -> Option<f64> {
    let restitution = |gamma: f64| power_law_restitution(c, beta, m, gamma, v).unwrap_or(0.0);
    // Start from the dashpot that halves the speed over one contact duration, μ/t_c, and double.
    let mut high = 0.5 * m / power_law_contact_duration(c, beta, m, v);
    while restitution(high) > r {
        high *= 2.0;
        if high > 1e6 * m / power_law_contact_duration(c, beta, m, v) {
            return None;
        }
    }
    let mut low = 0.0;
    for _ in 0..60 {
        let middle = 0.5 * (low + high);
        if restitution(middle) > r { low = middle } else { high = middle }
    }
    Some(0.5 * (low + high))
}
