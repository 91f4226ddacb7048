//! The stored result of one run: its spec, outcome, measurements and sampled series.

use serde::{Deserialize, Serialize};

use crate::draw::Movie;
use crate::sim::{RunStatus, Trace};
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

/// This build: the crate's version and the fingerprint of the source that computes results
/// (`build.rs`), e.g. `0.1.0+3f2a…`. A record made by another build may hold numbers an
/// earlier (or later) physics computed.
pub const BUILD: &str = concat!(env!("CARGO_PKG_VERSION"), "+", env!("MDSOLIDS_SOURCE_FINGERPRINT"));

/// Everything one run produced.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    /// Stable id (scene name + content hash of the spec).
    pub run_id: String,
    /// The build that made it, [`BUILD`] of that binary.
    pub build: String,
    /// The resolved run.
    pub spec: RunSpec,
    /// How the run ended.
    pub status: RunStatus,
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

impl RunRecord {
    /// Checks a record read from the store as the record of `spec` (whose id names its file):
    /// its own `run_id` is that id and the id of its own spec, its spec is `spec`, and its
    /// sampled series have the lengths the report indexes them by. Why not, if it is not.
    /// (Its numbers are finite: JSON has no NaN or infinity, and a number beyond the range of
    /// f64 does not parse.)
    pub fn check(&self, spec: &RunSpec) -> Result<(), String> {
        let run_id = spec.run_id();
        if self.run_id != run_id {
            return Err(format!("its run_id {:?} is not its file name {run_id:?}", self.run_id));
        }
        let own = self.spec.run_id();
        if own != run_id {
            return Err(format!("its spec is the spec of run {own}, not of {run_id}"));
        }
        if self.spec != *spec {
            return Err("its spec differs from the campaign's run of the same id".into());
        }
        check_trace(&self.trace, spec.particles())
    }
}

/// The lengths `trace` must have for a run of `particles` particles: one entry per sample in
/// every energy series, per-particle rows of `particles` entries (or none), and in each probed
/// line one row per sample with one entry per node, nodes inside the lattice; sample times in
/// order.
fn check_trace(trace: &Trace, particles: usize) -> Result<(), String> {
    let samples = trace.time.len();
    for (name, series) in [
        ("kinetic", &trace.kinetic),
        ("potential", &trace.potential),
        ("dissipated", &trace.dissipated),
        ("work", &trace.work),
    ] {
        if series.len() != samples {
            return Err(format!("trace.{name} has {} entries for {samples} sample times", series.len()));
        }
    }
    if trace.time.windows(2).any(|pair| pair[1] < pair[0]) {
        return Err("trace.time is not in increasing order".into());
    }
    let rows = |name: &str, series: &[Vec<f64>], allow_empty: bool, width: usize| -> Result<(), String> {
        if !(series.len() == samples || allow_empty && series.is_empty()) {
            return Err(format!("{name} has {} rows for {samples} sample times", series.len()));
        }
        match series.iter().position(|row| row.len() != width) {
            Some(s) => Err(format!("{name}[{s}] has {} entries, not {width}", series[s].len())),
            None => Ok(()),
        }
    };
    rows("trace.displacement_x", &trace.displacement_x, true, particles)?;
    rows("trace.displacement_y", &trace.displacement_y, true, particles)?;
    rows("trace.velocity_x", &trace.velocity_x, true, particles)?;
    rows("trace.velocity_y", &trace.velocity_y, true, particles)?;
    for (p, probe) in trace.probes.iter().enumerate() {
        if let Some(node) = probe.nodes.iter().find(|&&node| node >= particles) {
            return Err(format!("trace.probes[{p}] names node {node} of a run of {particles} particles"));
        }
        let width = probe.nodes.len();
        rows(&format!("trace.probes[{p}].displacement_x"), &probe.displacement_x, false, width)?;
        rows(&format!("trace.probes[{p}].displacement_y"), &probe.displacement_y, false, width)?;
        rows(&format!("trace.probes[{p}].velocity_x"), &probe.velocity_x, false, width)?;
        rows(&format!("trace.probes[{p}].velocity_y"), &probe.velocity_y, false, width)?;
    }
    Ok(())
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
