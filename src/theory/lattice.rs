//! Plane waves of the square spring lattice: the dispersion relation ω(q) of a wave along one
//! of its axes.

/// The two stiffnesses k_eff (N/m) of a square lattice's plane waves along one of its axes,
/// the smaller first: the wave sees the springs along it (`k_along`, the row springs for a
/// wave along x) and the two diagonal families (`k_rising`, `k_falling`); the springs across
/// it do not stretch. The dynamical matrix Σ_b k_b n̂n̂ (1 − cos q·r_b) over the neighbours
/// is 4 sin²(qa/2) K with K = ½ [[k_r + k_f, k_r − k_f], [k_r − k_f, 2k + k_r + k_f]]
/// (across, along), whose eigenvalues are (k + k_r + k_f)/2 ∓ √(k²/4 + (k_r − k_f)²/4). Both
/// diagonals k_d: k_T = k_d (transverse) and k_L = k + k_d (longitudinal); no diagonals: k_T =
/// 0, a transverse wave has no restoring force; one family mixes the two polarisations.
///
/// ```
/// let [t, l] = mdsolids::theory::square_branch_stiffnesses(1.0, 0.5, 0.5);
/// assert_eq!((t, l), (0.5, 1.5));
/// ```
pub fn square_branch_stiffnesses(k_along: f64, k_rising: f64, k_falling: f64) -> [f64; 2] {
    let middle = 0.5 * (k_along + k_rising + k_falling);
    let split = (0.25 * k_along * k_along + 0.25 * (k_rising - k_falling).powi(2)).sqrt();
    [(middle - split).max(0.0), middle + split]
}

/// ω(q) = 2 √(k_eff/m) |sin(q a/2)| (rad/s) of a branch of stiffness `k_eff` (N/m), masses `m`
/// (kg), spacing `a` (m), at wavenumber `q` (rad/m): the chain's dispersion relation, whose
/// slope at q → 0 is the sound speed a √(k_eff/m).
///
/// ```
/// let w = mdsolids::theory::branch_frequency(1.0, 1.0, std::f64::consts::PI, 1.0);
/// assert!((w - 2.0).abs() < 1e-15);
/// ```
pub fn branch_frequency(k_eff: f64, m: f64, q: f64, a: f64) -> f64 {
    2.0 * (k_eff / m).sqrt() * (0.5 * q * a).sin().abs()
}
