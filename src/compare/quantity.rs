//! What a column of the results table is, for the comparison: a cost (timings), a set-up value
//! (an input or what follows from the inputs before any step is taken), a deviation (an error
//! or spread, ideally 0) or a measured result; its unit; and the noise below which two
//! campaigns' values of it count as equal.

/// Relative difference below which two values of a result count as equal: well above the
/// round-off of a measurement (≈ 1e-15 relative for one run, ≈ 1e-12 accumulated over a
/// run's steps) and well below any physical difference worth a sentence.
pub(super) const NOISE: f64 = 1e-6;

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
const COSTS: [&str; 4] = ["wall_s", "loop_s", "steps", "relax_steps"];

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
const DEVIATIONS: [&str; 4] = ["error", "spacing_spread", "static_nonlinearity", "homogeneity"];

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
/// `youngs_modulus_tangent_fem`); the first match counts, so longer names come first. k and
/// its kin are C in N/m^β for power-law springs: written N/m^β for both.
const UNITS: [(&str, &str); 32] = [
    ("wall_s", "s"),
    ("loop_s", "s"),
    ("mass", "kg"),
    ("spacing_spread", "m"),
    ("spacing", "m"),
    ("k_diag", "N/m^β"),
    ("k_x", "N/m^β"),
    ("k_y", "N/m^β"),
    ("k", "N/m^β"),
    ("gamma", "N s/m"),
    ("dt_omega_max", "1"),
    ("dt_per_tc", "1"),
    ("dt", "s"),
    ("t_c", "s"),
    ("duration", "s"),
    ("v0", "m/s"),
    ("gap", "m"),
    ("wall_distance", "m"),
    ("depth", "m"),
    ("load_per_node", "N"),
    ("wall_displacement", "m"),
    ("omega_max", "rad/s"),
    ("arrival_time", "s"),
    ("contact_duration", "s"),
    ("sound_speed", "m/s"),
    ("youngs_modulus", "Pa"),
    ("shear_modulus", "Pa"),
    ("dissipation_time", "s"),
    ("equilibrium_spacing", "m"),
    ("wall_force", "N"),
    ("secant_stiffness", "N/m"),
    ("tangent_stiffness", "N/m"),
];

/// The unit of column `name`; "1" for a pure number (a ratio, a count, a relative error).
pub fn unit(name: &str) -> &'static str {
    if name.ends_with("_error") {
        return "1";
    }
    let matches = |start: &str| name.strip_prefix(start).is_some_and(|rest| rest.is_empty() || rest.starts_with('_'));
    UNITS.iter().find(|(start, _)| matches(start)).map_or("1", |(_, unit)| unit)
}
