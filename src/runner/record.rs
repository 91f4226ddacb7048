//! The stored result of one run: its spec, outcome, measurements and sampled series.

use serde::{Deserialize, Serialize};

use crate::sim::Trace;
use crate::spec::RunSpec;

/// Measured quantities with their analytical twins; `None` where the scene has no such
/// quantity or no exact answer exists.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    /// Contact duration (s), crossings located inside the step.
    pub contact_duration: Option<f64>,
    /// Analytical contact duration (s).
    pub contact_duration_theory: Option<f64>,
    /// Restitution coefficient.
    pub restitution: Option<f64>,
    /// Analytical restitution.
    pub restitution_theory: Option<f64>,
    /// max |E(t) − E(0)| / E(0) with E = kinetic + potential + dissipated.
    pub energy_error: Option<f64>,
    /// Chain: largest phase-space deviation from the normal-mode solution, relative (see
    /// `measure::normal_mode_error`).
    pub chain_mode_error: Option<f64>,
    /// The run's error against the most exact reference it has (see `error_measure`), ≥ 0.
    pub error: Option<f64>,
    /// What `error` measures: `contact_duration`, `restitution`, `normal_modes`,
    /// `reference_dt/R` (a run at dt/R) or `energy`.
    pub error_measure: Option<String>,
    /// Chain wave: arrival time (s) at the receiver by each criterion.
    #[serde(default)]
    pub arrival_times: std::collections::BTreeMap<String, f64>,
    /// Chain wave: the recommended criterion.
    pub arrival_criterion: Option<String>,
    /// Chain wave: distance from the excited particle to the receiver (m).
    pub wave_distance: Option<f64>,
    /// Chain wave: the coursework's estimate t_s = N_s t_c (N_s springs between them) (s).
    pub arrival_time_tc_estimate: Option<f64>,
    /// Chain wave: the long-wavelength (and front) speed a√(k/m) of a linear chain (m/s).
    pub sound_speed_theory: Option<f64>,
    /// Angular frequency of the fastest mode (rad/s), estimated before the run.
    pub omega_max: Option<f64>,
    /// dt · ω_max.
    pub dt_omega_max: Option<f64>,
    /// Damping ratio of the fastest mode.
    pub mode_damping_ratio: Option<f64>,
    /// Largest dt · ω_max the integrator survives at that damping ratio.
    pub stability_limit: Option<f64>,
    /// Lattice, tensile: Young's modulus E (Pa) of the relaxed MD lattice.
    pub youngs_modulus: Option<f64>,
    /// Lattice, tensile: ν = −(ΔL_x/L_x)/(ΔL_y/L_y).
    pub poisson_ratio: Option<f64>,
    /// Lattice, tensile: the coursework's ΔL_x/ΔL_y.
    pub poisson_ratio_coursework: Option<f64>,
    /// Lattice, shear: shear modulus G (Pa).
    pub shear_modulus: Option<f64>,
    /// Lattice: largest deviation of the side columns from straight lines, relative to their
    /// mean lateral displacement.
    pub homogeneity: Option<f64>,
    /// Lattice: time (s) from which the relaxation criterion held.
    pub dissipation_time: Option<f64>,
    /// Lattice: the relaxation criterion, in words.
    pub dissipation_criterion: Option<String>,
    /// Lattice: largest difference between the non-linear and the linear static answers,
    /// relative for E and G, absolute for ν (how far the load is from the linear regime).
    pub static_nonlinearity: Option<f64>,
    /// Lattice: E of the static solution of the same network, solved non-linearly like MD (Pa).
    pub youngs_modulus_fem: Option<f64>,
    /// Lattice: ν of the static solution.
    pub poisson_ratio_fem: Option<f64>,
    /// Lattice: G of the static solution (Pa).
    pub shear_modulus_fem: Option<f64>,
    /// Lattice: continuum E = (C11 − C12²/C11)/d (Pa).
    pub youngs_modulus_theory: Option<f64>,
    /// Lattice: continuum ν = C12/C11.
    pub poisson_ratio_theory: Option<f64>,
    /// Lattice: continuum G = C44/d (Pa).
    pub shear_modulus_theory: Option<f64>,
    /// Lattice with a tangent step: tangent E = ΔF/d/L_x / Δε (Pa) from the MD increments.
    #[serde(default)]
    pub youngs_modulus_tangent: Option<f64>,
    /// Lattice with a tangent step: ν from the MD increments.
    #[serde(default)]
    pub poisson_ratio_tangent: Option<f64>,
    /// Lattice with a tangent step: tangent G (Pa) from the MD increments.
    #[serde(default)]
    pub shear_modulus_tangent: Option<f64>,
    /// Tangent E (Pa) of the static answer, from its tangent stiffness K_t Δu = Δf.
    #[serde(default)]
    pub youngs_modulus_tangent_fem: Option<f64>,
    /// Tangent ν of the static answer.
    #[serde(default)]
    pub poisson_ratio_tangent_fem: Option<f64>,
    /// Tangent G (Pa) of the static answer.
    #[serde(default)]
    pub shear_modulus_tangent_fem: Option<f64>,
    /// Random lattice: fraction of the bonds kept after cutting.
    #[serde(default)]
    pub bond_fraction_kept: Option<f64>,
    /// Relaxing chain: mean gap (m) of all springs but the last (which starts with the whole
    /// wall displacement).
    #[serde(default)]
    pub equilibrium_spacing: Option<f64>,
    /// Relaxing chain: equilibrium gap W/(n + 1) (m).
    #[serde(default)]
    pub equilibrium_spacing_theory: Option<f64>,
    /// Relaxing chain: largest minus smallest gap (m); 0 at equilibrium.
    #[serde(default)]
    pub spacing_spread: Option<f64>,
    /// Relaxing chain: tension (N) of the spring at the left wall, s(δ₁); negative in
    /// compression.
    #[serde(default)]
    pub wall_force: Option<f64>,
    /// Relaxing chain: s(ΔW/(n + 1)) (N).
    #[serde(default)]
    pub wall_force_theory: Option<f64>,
    /// Relaxing chain: secant stiffness of the whole chain, wall force / ΔW (N/m).
    #[serde(default)]
    pub secant_stiffness: Option<f64>,
    /// Relaxing chain: s(δ)/ΔW (N/m).
    #[serde(default)]
    pub secant_stiffness_theory: Option<f64>,
    /// Relaxing chain with a tangent step: ΔF/ΔW (N/m) from the MD increments.
    #[serde(default)]
    pub tangent_stiffness: Option<f64>,
    /// Relaxing chain: s′(δ)/(n + 1) (N/m).
    #[serde(default)]
    pub tangent_stiffness_theory: Option<f64>,
}

/// Everything one run produced.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    /// Stable id (scene name + content hash of the spec).
    pub run_id: String,
    /// The resolved run.
    pub spec: RunSpec,
    /// `ok` or a failure word (`unstable`, `panicked`).
    pub status: String,
    /// Explanation of a failure or a caveat; empty otherwise.
    pub message: String,
    /// Wall time of the simulation (s).
    pub wall_s: f64,
    /// Steps taken.
    pub steps: u64,
    /// Measurements.
    pub metrics: Metrics,
    /// Sampled series.
    pub trace: Trace,
    /// The movie's frames, when the run asked for one: written by the runner as
    /// `runs/<run_id>.gif`, never stored in the record.
    #[serde(skip)]
    pub movie: Option<Movie>,
}

/// What a movie shows: the frames, the bonds between the particles, the size.
#[derive(Clone, Debug, PartialEq)]
pub struct Movie {
    /// Frames in time order.
    pub frames: Vec<crate::sim::Frame>,
    /// Bonds drawn as lines (i, j, rest length in m); bonds across a periodic side are left out.
    pub bonds: Vec<(usize, usize, f64)>,
    /// Frame count and size.
    pub spec: crate::spec::MovieSpec,
    /// Title drawn on every frame.
    pub title: String,
    /// The run's deadline: encoding the movie is part of the run (its time budget).
    pub deadline: Option<std::time::Instant>,
}

impl Metrics {
    /// Arrival time (s) by the recommended criterion.
    pub fn arrival_time(&self) -> Option<f64> {
        self.arrival_criterion.as_ref().and_then(|c| self.arrival_times.get(c).copied())
    }

    /// Sound speed L / t_s (m/s) from the arrival time by `criterion`.
    pub fn sound_speed(&self, criterion: &str) -> Option<f64> {
        self.wave_distance.zip(self.arrival_times.get(criterion)).map(|(l, t)| l / t)
    }
}
