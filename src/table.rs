//! The results table: one row per run, as a Polars frame, written as CSV and Parquet.
//! Column names are a contract other tools read (README, "Results table").

use anyhow::Context as _;
use polars::prelude::*;
use serde_json::Value;
use std::collections::BTreeSet;

use crate::measure::relative_error;
use crate::output::{Layout, write_atomically};
use crate::runner::RunRecord;
use crate::spec::Diagonals;
use crate::summary::ScalingFit;

/// A column of numbers; a non-finite value (a blown-up run's measurement) becomes null, so no
/// NaN or infinity ever reaches a table.
fn floats(records: &[RunRecord], name: &str, get: impl Fn(&RunRecord) -> f64) -> Column {
    optional_floats(records, name, |r| Some(get(r)))
}

fn optional_floats(records: &[RunRecord], name: &str, get: impl Fn(&RunRecord) -> Option<f64>) -> Column {
    Column::new(name.into(), records.iter().map(|r| get(r).filter(|v| v.is_finite())).collect::<Vec<Option<f64>>>())
}

/// A column of one measured quantity.
fn metric(records: &[RunRecord], name: &str, get: fn(&crate::runner::Metrics) -> Option<f64>) -> Column {
    optional_floats(records, name, move |r| get(&r.metrics))
}

fn strings(records: &[RunRecord], name: &str, get: impl Fn(&RunRecord) -> String) -> Column {
    Column::new(name.into(), records.iter().map(get).collect::<Vec<String>>())
}

/// The results frame of `records`: identity, status and timing, the resolved physics, the
/// measurements with their analytical twins and relative errors, and one column per grid
/// path (numeric where every value is a number, text otherwise).
pub fn results_frame(records: &[RunRecord]) -> PolarsResult<DataFrame> {
    let mut columns = vec![
        strings(records, "run_id", |r| r.run_id.clone()),
        strings(records, "scene", |r| r.spec.scene.clone()),
        strings(records, "kind", |r| r.spec.kind().name().into()),
        strings(records, "status", |r| r.status.to_string()),
        strings(records, "message", |r| r.message.clone()),
        strings(records, "build", |r| r.build.clone()),
        Column::new(
            "other_build".into(),
            records.iter().map(|r| r.build != crate::runner::BUILD).collect::<Vec<bool>>(),
        ),
        floats(records, "wall_s", |r| r.wall_s),
        floats(records, "loop_s", |r| r.trace.loop_s),
        Column::new("steps".into(), records.iter().map(|r| r.steps).collect::<Vec<u64>>()),
        floats(records, "mass", |r| r.spec.mass),
        floats(records, "spacing", |r| r.spec.spacing),
        floats(records, "k", |r| r.spec.k),
        strings(records, "law", |r| r.spec.law.name().into()),
        floats(records, "beta", |r| r.spec.law.beta()),
        Column::new("contact".into(), records.iter().map(|r| r.spec.contact).collect::<Vec<bool>>()),
        floats(records, "gamma", |r| r.spec.gamma),
        floats(records, "gamma_background", |r| r.spec.gamma_background),
        strings(records, "integrator", |r| r.spec.integrator.name().into()),
        floats(records, "dt", |r| r.spec.dt),
        floats(records, "dt_per_tc", |r| r.spec.dt_per_tc()),
        floats(records, "t_c", |r| r.spec.t_c),
        floats(records, "duration", |r| r.spec.duration),
        Column::new(
            "n".into(),
            records.iter().map(|r| r.spec.chain().map(|c| c.n as u64)).collect::<Vec<Option<u64>>>(),
        ),
        floats(records, "v0", |r| r.spec.v0),
        optional_floats(records, "contact_duration", |r| r.metrics.pair.contact_duration),
        optional_floats(records, "contact_duration_theory", |r| r.metrics.pair.contact_duration_theory),
        optional_floats(records, "contact_duration_error", |r| {
            relative_error(r.metrics.pair.contact_duration, r.metrics.pair.contact_duration_theory)
        }),
        optional_floats(records, "restitution", |r| r.metrics.pair.restitution),
        optional_floats(records, "restitution_theory", |r| r.metrics.pair.restitution_theory),
        optional_floats(records, "restitution_error", |r| {
            relative_error(r.metrics.pair.restitution, r.metrics.pair.restitution_theory)
        }),
        optional_floats(records, "energy_error", |r| r.metrics.energy_error),
        optional_floats(records, "chain_mode_error", |r| r.metrics.chain.chain_mode_error),
        optional_floats(records, "error", |r| r.metrics.error),
        Column::new(
            "error_measure".into(),
            records.iter().map(|r| r.metrics.error_measure.clone()).collect::<Vec<Option<String>>>(),
        ),
        optional_floats(records, "omega_max", |r| r.metrics.omega_max),
        optional_floats(records, "arrival_time", |r| r.metrics.arrival_time()),
        optional_floats(records, "sound_speed", |r| {
            r.metrics.arrival_criterion.as_deref().and_then(|c| r.metrics.sound_speed(c))
        }),
        Column::new(
            "arrival_criterion".into(),
            records.iter().map(|r| r.metrics.arrival_criterion.clone()).collect::<Vec<Option<String>>>(),
        ),
        optional_floats(records, "arrival_time_tc_estimate", |r| r.metrics.arrival_time_tc_estimate),
        optional_floats(records, "sound_speed_theory", |r| r.metrics.sound_speed_theory),
        optional_floats(records, "dt_omega_max", |r| r.metrics.dt_omega_max),
        optional_floats(records, "mode_damping_ratio", |r| r.metrics.mode_damping_ratio),
        optional_floats(records, "stability_limit", |r| r.metrics.stability_limit),
    ];
    if records.iter().any(|r| r.spec.lattice().is_some()) {
        columns.extend(lattice_columns(records));
    }
    let anisotropic = |l: &crate::spec::LatticeSpec| {
        l.rotated || l.k_x != l.k_y || matches!(l.diagonals, Diagonals::Rising | Diagonals::Falling)
    };
    if records.iter().any(|r| r.spec.lattice().is_some_and(anisotropic)) {
        columns.extend(directional_columns(records));
    }
    if records.iter().any(|r| r.spec.chain().is_some_and(|c| c.relax.is_some())) {
        let m = |name: &str, get| metric(records, name, get);
        columns.extend([
            optional_floats(records, "wall_displacement", |r| {
                r.spec.chain().and_then(|c| c.relax).map(|_| r.spec.chain_wall_extension())
            }),
            m("equilibrium_spacing", |m| m.chain.equilibrium_spacing),
            m("equilibrium_spacing_theory", |m| m.chain.equilibrium_spacing_theory),
            m("spacing_spread", |m| m.chain.spacing_spread),
            m("wall_force", |m| m.chain.wall_force),
            m("wall_force_theory", |m| m.chain.wall_force_theory),
            m("secant_stiffness", |m| m.chain.secant_stiffness),
            m("secant_stiffness_theory", |m| m.chain.secant_stiffness_theory),
            m("tangent_stiffness", |m| m.chain.tangent_stiffness),
            m("tangent_stiffness_theory", |m| m.chain.tangent_stiffness_theory),
        ]);
    }
    if records.iter().any(|r| r.spec.wave().is_some()) {
        for criterion in crate::measure::ARRIVAL_CRITERIA {
            columns.push(optional_floats(records, &format!("sound_speed_{criterion}"), |r| {
                r.metrics.sound_speed(criterion)
            }));
        }
    }
    let paths: BTreeSet<&String> = records.iter().flat_map(|r| r.spec.varied.keys()).collect();
    // A grid path named like a resolved column (`supports`) is already there.
    let resolved: BTreeSet<String> = columns.iter().map(|c| c.name().to_string()).collect();
    for path in paths.into_iter().filter(|p| !resolved.contains(p.as_str())) {
        let values: Vec<Option<&Value>> = records.iter().map(|r| r.spec.varied.get(path)).collect();
        let column = if values.iter().flatten().all(|v| v.is_number()) {
            Column::new(
                path.as_str().into(),
                values.iter().map(|v| v.and_then(Value::as_f64)).collect::<Vec<Option<f64>>>(),
            )
        } else {
            let text = |v: &Value| v.as_str().map(str::to_string).unwrap_or_else(|| v.to_string());
            Column::new(path.as_str().into(), values.iter().map(|v| v.map(text)).collect::<Vec<Option<String>>>())
        };
        columns.push(column);
    }
    DataFrame::new_infer_height(columns)
}

/// The columns of lattice scenes (absent from campaigns without lattices): the resolved
/// lattice, then each modulus from MD, from the static solution and from the continuum.
fn lattice_columns(records: &[RunRecord]) -> Vec<Column> {
    let lattice = |get: fn(&crate::spec::LatticeSpec) -> f64| move |r: &RunRecord| r.spec.lattice().map(get);
    let sizes = |get: fn(&crate::spec::LatticeSpec) -> usize| {
        records.iter().map(|r| r.spec.lattice().map(|l| get(l) as u64)).collect::<Vec<Option<u64>>>()
    };
    let words = |get: fn(&crate::spec::LatticeSpec) -> &'static str| {
        records.iter().map(|r| r.spec.lattice().map(get)).collect::<Vec<Option<&str>>>()
    };
    let m = |name: &str, get| metric(records, name, get);
    vec![
        Column::new("nx".into(), sizes(|l| l.nx)),
        Column::new("ny".into(), sizes(|l| l.ny)),
        optional_floats(records, "k_diag", lattice(|l| l.k_diag)),
        Column::new("diagonals".into(), words(|l| l.diagonals.name())),
        optional_floats(records, "k_x", lattice(|l| l.k_x)),
        optional_floats(records, "k_y", lattice(|l| l.k_y)),
        optional_floats(records, "cut_fraction", lattice(|l| l.cut_fraction)),
        optional_floats(records, "stiffness_spread", lattice(|l| l.stiffness_spread)),
        Column::new("seed".into(), records.iter().map(|r| r.spec.lattice().map(|l| l.seed)).collect::<Vec<_>>()),
        m("bond_fraction_kept", |m| m.lattice.bond_fraction_kept),
        optional_floats(records, "depth", lattice(|l| l.depth)),
        Column::new("supports".into(), words(|l| l.supports.name())),
        Column::new(
            "load_case".into(),
            words(|l| if l.rotated { crate::spec::LoadCase::TensileX.name() } else { l.load_case.name() }),
        ),
        Column::new("load_control".into(), words(|l| l.control.name())),
        optional_floats(records, "drive_strain", |r| {
            r.spec.lattice().filter(|l| l.control == crate::spec::Control::Velocity).map(|l| l.drive_strain)
        }),
        optional_floats(records, "load_per_node", |r| r.spec.lattice().and_then(|l| l.force_per_node())),
        m("youngs_modulus", |m| m.lattice.youngs_modulus),
        m("youngs_modulus_fem", |m| m.lattice.youngs_modulus_fem),
        m("youngs_modulus_theory", |m| m.lattice.youngs_modulus_theory),
        m("poisson_ratio", |m| m.lattice.poisson_ratio),
        m("poisson_ratio_fem", |m| m.lattice.poisson_ratio_fem),
        m("poisson_ratio_theory", |m| m.lattice.poisson_ratio_theory),
        m("poisson_ratio_coursework", |m| m.lattice.poisson_ratio_coursework),
        m("shear_modulus", |m| m.lattice.shear_modulus),
        m("shear_modulus_fem", |m| m.lattice.shear_modulus_fem),
        m("shear_modulus_theory", |m| m.lattice.shear_modulus_theory),
        m("youngs_modulus_tangent", |m| m.lattice.youngs_modulus_tangent),
        m("youngs_modulus_tangent_fem", |m| m.lattice.youngs_modulus_tangent_fem),
        m("poisson_ratio_tangent", |m| m.lattice.poisson_ratio_tangent),
        m("poisson_ratio_tangent_fem", |m| m.lattice.poisson_ratio_tangent_fem),
        m("shear_modulus_tangent", |m| m.lattice.shear_modulus_tangent),
        m("shear_modulus_tangent_fem", |m| m.lattice.shear_modulus_tangent_fem),
        m("static_nonlinearity", |m| m.lattice.static_nonlinearity),
        m("homogeneity", |m| m.lattice.homogeneity),
        m("dissipation_time", |m| m.dissipation_time),
        Column::new(
            "dissipation_criterion".into(),
            records.iter().map(|r| r.metrics.dissipation_criterion.clone()).collect::<Vec<Option<String>>>(),
        ),
        Column::new(
            "relax_steps".into(),
            records.iter().map(|r| r.spec.lattice().map(|_| r.steps)).collect::<Vec<Option<u64>>>(),
        ),
    ]
}

/// Moduli by direction for anisotropic lattices: a run loaded up (`tensile`) measures E_y and
/// ν_yx, one loaded along x (`tensile-x`, simulated turned by 90°) E_x and ν_xy; each beside
/// its static value.
fn directional_columns(records: &[RunRecord]) -> Vec<Column> {
    let along = |x: bool, get: fn(&crate::runner::Metrics) -> Option<f64>| {
        move |r: &RunRecord| r.spec.lattice().filter(|l| l.rotated == x).and_then(|_| get(&r.metrics))
    };
    vec![
        optional_floats(records, "youngs_modulus_x", along(true, |m| m.lattice.youngs_modulus)),
        optional_floats(records, "youngs_modulus_x_fem", along(true, |m| m.lattice.youngs_modulus_fem)),
        optional_floats(records, "youngs_modulus_y", along(false, |m| m.lattice.youngs_modulus)),
        optional_floats(records, "youngs_modulus_y_fem", along(false, |m| m.lattice.youngs_modulus_fem)),
        optional_floats(records, "poisson_ratio_xy", along(true, |m| m.lattice.poisson_ratio)),
        optional_floats(records, "poisson_ratio_xy_fem", along(true, |m| m.lattice.poisson_ratio_fem)),
        optional_floats(records, "poisson_ratio_yx", along(false, |m| m.lattice.poisson_ratio)),
        optional_floats(records, "poisson_ratio_yx_fem", along(false, |m| m.lattice.poisson_ratio_fem)),
    ]
}

/// The campaign summary: one row per fitted scaling law (`summary.csv`).
pub fn summary_frame(fits: &[ScalingFit]) -> PolarsResult<DataFrame> {
    DataFrame::new_infer_height(vec![
        Column::new("scene".into(), fits.iter().map(|f| f.scene.clone()).collect::<Vec<String>>()),
        Column::new("group".into(), fits.iter().map(|f| f.group.clone()).collect::<Vec<String>>()),
        Column::new("law".into(), fits.iter().map(|f| f.law).collect::<Vec<&str>>()),
        Column::new("quantity".into(), fits.iter().map(|f| f.quantity).collect::<Vec<&str>>()),
        Column::new("against".into(), fits.iter().map(|f| f.against).collect::<Vec<&str>>()),
        Column::new("exponent".into(), fits.iter().map(|f| f.fit.exponent).collect::<Vec<f64>>()),
        Column::new("r_squared".into(), fits.iter().map(|f| f.fit.r_squared).collect::<Vec<f64>>()),
        Column::new("points".into(), fits.iter().map(|f| f.points.len() as u64).collect::<Vec<u64>>()),
        Column::new("x_min".into(), fits.iter().map(|f| f.points[0].0).collect::<Vec<f64>>()),
        Column::new("x_max".into(), fits.iter().map(|f| f.points[f.points.len() - 1].0).collect::<Vec<f64>>()),
    ])
}

/// Writes `results.csv` and `results.parquet` for `frame`, each atomically.
pub fn write_tables(layout: &Layout, frame: &mut DataFrame) -> anyhow::Result<()> {
    let mut csv = Vec::new();
    CsvWriter::new(&mut csv).include_header(true).finish(frame)?;
    write_atomically(&layout.file("results.csv"), &csv)?;
    let mut parquet = Vec::new();
    ParquetWriter::new(&mut parquet).finish(frame)?;
    write_atomically(&layout.file("results.parquet"), &parquet)
}

/// Before a partial table of `rows` runs is written: a larger `results.csv` and
/// `results.parquet` are moved aside as `results.previous.csv` and `results.previous.parquet`
/// (over an older pair). Returns the row count of the table aside, moved now or by an earlier
/// partial report, if there is one.
pub fn keep_larger_table_aside(layout: &Layout, rows: usize) -> anyhow::Result<Option<usize>> {
    let count = |name: &str| {
        let file = std::fs::File::open(layout.file(name)).ok()?;
        ParquetReader::new(file).num_rows().ok()
    };
    if count("results.parquet").is_some_and(|previous| previous > rows) {
        for (name, aside) in [("results.csv", "results.previous.csv"), ("results.parquet", "results.previous.parquet")]
        {
            let (from, to) = (layout.file(name), layout.file(aside));
            if from.is_file() {
                std::fs::rename(&from, &to)
                    .with_context(|| format!("cannot move '{}' aside to '{}'", from.display(), to.display()))?;
            }
        }
    }
    Ok(count("results.previous.parquet"))
}

/// Writes `summary.csv` (the fitted scaling laws), atomically; nothing when there are none.
pub fn write_summary(layout: &Layout, fits: &[ScalingFit]) -> anyhow::Result<()> {
    if fits.is_empty() {
        return Ok(());
    }
    let mut csv = Vec::new();
    CsvWriter::new(&mut csv).include_header(true).finish(&mut summary_frame(fits)?)?;
    write_atomically(&layout.file("summary.csv"), &csv)
}
