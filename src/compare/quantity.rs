//! What a column of the results table is, for the comparison: a cost (timings), a set-up value
//! (an input or what follows from the inputs before any step is taken), a deviation (an error
//! or spread, ideally 0) or a measured result; its unit; and the noise below which two
//! campaigns' values of it count as equal.

/// Relative difference below which two values of a result count as equal: well above the
/// round-off of a measurement (≈ 1e-15 relative for one run, ≈ 1e-12 accumulated over a
/// run's steps) and well below any physical difference worth a sentence.
pub(super) const NOISE: f64 = 1e-6;

/// Two inputs count as equal when they differ by less than this, relative: the same input
/// resolved along two paths (dt·ω_max of a linear and of a Hertz law) differs in its last bits,
/// 1e-16 relative, and inputs chosen differently differ by far more.
pub(super) const ROUND_OFF: f64 = 1e-12;

/// The text column that says how a metric was measured, where a table says it: two values of
/// `error` are comparable only where both are against the same reference (`normal_modes`,
/// `energy`, ...).
const MEASURED_BY: [(&str, &str); 1] = [("error", "error_measure")];

/// The column that says how metric `name` was measured.
pub(super) fn measure_column(name: &str) -> Option<&'static str> {
    MEASURED_BY.iter().find(|(metric, _)| *metric == name).map(|(_, column)| *column)
}

/// The floor of a quantity whose floor is the same for every run: a static solve's residual
/// stops at Newton's tolerance ‖R‖ ≤ 1e-12 ‖f‖, and below that it is round-off. (A run's own
/// floor, such as a packing's `pressure_floor`, is a column of its own.)
pub(super) fn floor(name: &str) -> Option<f64> {
    (name == "static_residual").then_some(crate::fem::NEWTON_TOLERANCE)
}

/// What kind of quantity a column holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    /// What a run cost: timings and step counts, machine-dependent, never a result.
    Cost,
    /// An input, or what follows from the inputs before the run (t_c, dt, ω_max, the analytical
    /// references `*_theory`): two campaigns differ there by construction, or are equal exactly.
    Setup,
    /// An error or a spread, ideally 0: compared by its absolute difference, since a ratio of two
    /// round-off-sized numbers means nothing.
    Deviation,
    /// A measured result.
    Result,
}

/// Timings and step counts.
const COSTS: [&str; 5] = ["wall_s", "loop_s", "solve_s", "steps", "relax_steps"];

/// The inputs and the values resolved from them before a run (besides `*_theory`).
const SETUP: [&str; 31] = [
    "mass",
    "spacing",
    "k",
    "beta",
    "gamma",
    "gamma_background",
    "dt",
    "dt_per_tc",
    "t_c",
    "duration",
    "n",
    "v0",
    "gap",
    "wall_distance",
    "nx",
    "ny",
    "k_diag",
    "k_x",
    "k_y",
    "cut_fraction",
    "stiffness_spread",
    "seed",
    "depth",
    "drive_strain",
    "load_per_node",
    "wall_displacement",
    "omega_max",
    "dt_omega_max",
    "mode_damping_ratio",
    "stability_limit",
    "arrival_time_tc_estimate",
];

/// Errors and spreads besides the `*_error` columns.
const DEVIATIONS: [&str; 5] = ["error", "spacing_spread", "static_nonlinearity", "static_residual", "homogeneity"];

/// The class of column `name`.
pub fn class(name: &str) -> Class {
    if COSTS.contains(&name) {
        Class::Cost
    } else if SETUP.contains(&name) || name.ends_with("_theory") {
        Class::Setup
    } else if DEVIATIONS.contains(&name) || name.ends_with("_error") {
        Class::Deviation
    } else {
        Class::Result
    }
}

/// Units by column name, or by its first words for families (`sound_speed_<criterion>`,
/// `youngs_modulus_tangent_fem`), a grid path (`damping.background`) by its last field; the
/// first match counts, so longer names come first. k and its kin are C in N/m^β for power-law
/// springs: written N/m^β for both. Pure numbers (ratios, counts, relative errors) are listed
/// as "1" like any other unit: a column not listed has no unit shown, never a wrong one.
const UNITS: [(&str, &str); 91] = [
    // Costs and counts.
    ("wall_s", "s"),
    ("loop_s", "s"),
    ("relax_steps", "1"),
    ("critical_bound_steps", "1"),
    ("steps", "1"),
    ("seed", "1"),
    ("nx", "1"),
    ("ny", "1"),
    ("n", "1"),
    ("size", "1"),
    ("samples", "1"),
    ("coordination", "1"),
    // Inputs.
    ("mass", "kg"),
    ("density", "kg/m³"),
    ("spacing_spread", "m"),
    ("spacing", "m"),
    ("k_diag_ratio", "1"),
    ("k_y_ratio", "1"),
    ("k_diag", "N/m^β"),
    ("k_x", "N/m^β"),
    ("k_y", "N/m^β"),
    ("k", "N/m^β"),
    ("beta", "1"),
    ("gamma", "N s/m"),
    ("background", "N s/m"),
    ("restitution", "1"),
    ("dt_omega_max", "1"),
    ("dt_per_tc", "1"),
    ("dt", "s"),
    ("t_c", "s"),
    ("duration_tc", "1"),
    ("max_tc", "1"),
    ("ramp_tc", "1"),
    ("duration", "s"),
    ("v0", "m/s"),
    ("velocity", "m/s"),
    ("gap", "m"),
    ("wall_distance", "m"),
    ("wall_displacement", "m"),
    ("depth", "m"),
    ("cut_fraction", "1"),
    ("stiffness_spread", "1"),
    ("bond_fraction_kept", "1"),
    ("drive_strain", "1"),
    ("load_per_node", "N"),
    ("per_node", "N"),
    ("force", "N"),
    ("kinetic_ratio", "1"),
    ("residual_force", "1"),
    ("relax_tolerance", "1"),
    ("tolerance", "1"),
    ("relax_error_bound", "1"),
    // Stability and measurements.
    ("omega_max", "rad/s"),
    ("mode_damping_ratio", "1"),
    ("stability_limit", "1"),
    ("arrival_time", "s"),
    ("contact_duration", "s"),
    ("sound_speed", "m/s"),
    // A packing's moduli and pressure are 2D: force per length.
    ("bulk_modulus_2d", "N/m"),
    ("shear_modulus_2d", "N/m"),
    ("pressure", "N/m"),
    ("energy", "J"),
    ("box_side", "m"),
    ("discs", "1"),
    ("radius_ratio", "1"),
    ("packing_fraction", "1"),
    ("own_jamming_fraction", "1"),
    ("fraction", "1"),
    ("contacts", "1"),
    ("backbone_coordination", "1"),
    ("rattler_fraction", "1"),
    ("bulk_strain_contact_changes", "1"),
    ("shear_strain_contact_changes", "1"),
    ("packing_relax_steps", "1"),
    ("decompressions", "1"),
    ("youngs_modulus", "Pa"),
    ("shear_modulus", "Pa"),
    ("poisson_ratio", "1"),
    ("dissipation_time", "s"),
    ("equilibrium_spacing", "m"),
    ("wall_force", "N"),
    ("secant_stiffness", "N/m"),
    ("tangent_stiffness", "N/m"),
    ("stiffness_min", "N/m"),
    ("extension_sensitivity", "m/N"),
    ("error", "1"),
    ("homogeneity", "1"),
    ("static_nonlinearity", "1"),
    ("static_residual", "1"),
    ("static_descent_steps", "1"),
    ("threshold", "1"),
];

/// The unit of column `name`, "1" for a pure number (a ratio, a count, a relative error);
/// `None` for a column whose unit is not known here.
pub fn unit(name: &str) -> Option<&'static str> {
    if name.ends_with("_error") {
        return Some("1");
    }
    let name = name.rsplit('.').next().unwrap_or(name);
    let matches = |start: &str| name.strip_prefix(start).is_some_and(|rest| rest.is_empty() || rest.starts_with('_'));
    UNITS.iter().find(|(start, _)| matches(start)).map(|(_, unit)| *unit)
}
