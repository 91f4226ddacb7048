//! The results table: one row per run, as a Polars frame, written as CSV and Parquet.
//! Column names are a contract other tools read (README, "Results table").

use polars::prelude::*;
use serde_json::Value;
use std::collections::BTreeSet;

use crate::output::{Layout, write_atomically};
use crate::runner::RunRecord;

/// Relative error (measured − reference)/reference, when both exist.
pub fn relative_error(measured: Option<f64>, reference: Option<f64>) -> Option<f64> {
    match (measured, reference) {
        (Some(m), Some(r)) if r != 0.0 => Some((m - r) / r),
        _ => None,
    }
}

/// A column of numbers; a non-finite value (a blown-up run's measurement) becomes null, so no
/// NaN or infinity ever reaches a table.
fn floats(records: &[RunRecord], name: &str, get: impl Fn(&RunRecord) -> f64) -> Column {
    optional_floats(records, name, |r| Some(get(r)))
}

fn optional_floats(records: &[RunRecord], name: &str, get: impl Fn(&RunRecord) -> Option<f64>) -> Column {
    Column::new(name.into(), records.iter().map(|r| get(r).filter(|v| v.is_finite())).collect::<Vec<Option<f64>>>())
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
        strings(records, "kind", |r| r.spec.kind.name().into()),
        strings(records, "status", |r| r.status.clone()),
        strings(records, "message", |r| r.message.clone()),
        floats(records, "wall_s", |r| r.wall_s),
        floats(records, "loop_s", |r| r.trace.loop_s),
        Column::new("steps".into(), records.iter().map(|r| r.steps).collect::<Vec<u64>>()),
        floats(records, "mass", |r| r.spec.mass),
        floats(records, "spacing", |r| r.spec.spacing),
        floats(records, "k", |r| r.spec.k),
        strings(records, "law", |r| r.spec.law.name().into()),
        floats(records, "beta", |r| r.spec.beta),
        Column::new("contact".into(), records.iter().map(|r| r.spec.contact).collect::<Vec<bool>>()),
        floats(records, "gamma", |r| r.spec.gamma),
        floats(records, "gamma_background", |r| r.spec.gamma_background),
        strings(records, "integrator", |r| r.spec.integrator.name().into()),
        floats(records, "dt", |r| r.spec.dt),
        floats(records, "dt_per_tc", |r| r.spec.dt_per_tc()),
        floats(records, "t_c", |r| r.spec.t_c),
        floats(records, "duration", |r| r.spec.duration),
        Column::new("n".into(), records.iter().map(|r| r.spec.n.map(|n| n as u64)).collect::<Vec<Option<u64>>>()),
        floats(records, "v0", |r| r.spec.v0),
        optional_floats(records, "contact_duration", |r| r.metrics.contact_duration),
        optional_floats(records, "contact_duration_theory", |r| r.metrics.contact_duration_theory),
        optional_floats(records, "contact_duration_error", |r| {
            relative_error(r.metrics.contact_duration, r.metrics.contact_duration_theory)
        }),
        optional_floats(records, "restitution", |r| r.metrics.restitution),
        optional_floats(records, "restitution_theory", |r| r.metrics.restitution_theory),
        optional_floats(records, "restitution_error", |r| {
            relative_error(r.metrics.restitution, r.metrics.restitution_theory)
        }),
        optional_floats(records, "energy_error", |r| r.metrics.energy_error),
        optional_floats(records, "chain_mode_error", |r| r.metrics.chain_mode_error),
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
    if records.iter().any(|r| r.spec.lattice.is_some()) {
        columns.extend(lattice_columns(records));
    }
    if records.iter().any(|r| r.spec.wave.is_some()) {
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
    let lattice = |get: fn(&crate::spec::LatticeSpec) -> f64| move |r: &RunRecord| r.spec.lattice.as_ref().map(get);
    let sizes = |get: fn(&crate::spec::LatticeSpec) -> usize| {
        records.iter().map(|r| r.spec.lattice.as_ref().map(|l| get(l) as u64)).collect::<Vec<Option<u64>>>()
    };
    let words = |get: fn(&crate::spec::LatticeSpec) -> &'static str| {
        records.iter().map(|r| r.spec.lattice.as_ref().map(get)).collect::<Vec<Option<&str>>>()
    };
    let m = |name: &str, get: fn(&crate::runner::Metrics) -> Option<f64>| {
        optional_floats(records, name, move |r| get(&r.metrics))
    };
    vec![
        Column::new("nx".into(), sizes(|l| l.nx)),
        Column::new("ny".into(), sizes(|l| l.ny)),
        optional_floats(records, "k_diag", lattice(|l| l.k_diag)),
        optional_floats(records, "depth", lattice(|l| l.depth)),
        Column::new("supports".into(), words(|l| l.supports.name())),
        Column::new("load_case".into(), words(|l| l.load_case.name())),
        Column::new("load_control".into(), words(|l| l.control.name())),
        optional_floats(records, "drive_strain", |r| {
            r.spec.lattice.as_ref().filter(|l| l.control == crate::spec::Control::Velocity).map(|l| l.drive_strain)
        }),
        optional_floats(records, "load_per_node", lattice(|l| l.load_per_node)),
        m("youngs_modulus", |m| m.youngs_modulus),
        m("youngs_modulus_fem", |m| m.youngs_modulus_fem),
        m("youngs_modulus_theory", |m| m.youngs_modulus_theory),
        m("poisson_ratio", |m| m.poisson_ratio),
        m("poisson_ratio_fem", |m| m.poisson_ratio_fem),
        m("poisson_ratio_theory", |m| m.poisson_ratio_theory),
        m("poisson_ratio_coursework", |m| m.poisson_ratio_coursework),
        m("shear_modulus", |m| m.shear_modulus),
        m("shear_modulus_fem", |m| m.shear_modulus_fem),
        m("shear_modulus_theory", |m| m.shear_modulus_theory),
        m("static_nonlinearity", |m| m.static_nonlinearity),
        m("homogeneity", |m| m.homogeneity),
        m("dissipation_time", |m| m.dissipation_time),
        Column::new(
            "dissipation_criterion".into(),
            records.iter().map(|r| r.metrics.dissipation_criterion.clone()).collect::<Vec<Option<String>>>(),
        ),
        Column::new(
            "relax_steps".into(),
            records.iter().map(|r| r.spec.lattice.as_ref().map(|_| r.steps)).collect::<Vec<Option<u64>>>(),
        ),
    ]
}

/// How the sound speed of one group of chain-wave runs (a scene's runs that differ only in
/// v0) scales with v0: V_s ∝ v0^p.
#[derive(Clone, Debug, PartialEq)]
pub struct SpeedFit {
    /// Scene.
    pub scene: String,
    /// The group's other grid values.
    pub group: String,
    /// Elastic law of the group.
    pub law: &'static str,
    /// (v0, V_s) of its ok runs, by the recommended criterion.
    pub points: Vec<(f64, f64)>,
    /// The fit.
    pub fit: crate::measure::PowerLawFit,
}

/// The V_s-against-v0 fits of every chain-wave scene with at least two values of v0.
pub fn speed_fits(records: &[RunRecord]) -> Vec<SpeedFit> {
    /// A group's first run, its label and its (v0, V_s) points.
    type Group<'a> = (&'a RunRecord, String, Vec<(f64, f64)>);
    let mut groups: Vec<Group> = Vec::new();
    for r in records.iter().filter(|r| r.status == "ok") {
        let Some(speed) = r.metrics.arrival_criterion.as_deref().and_then(|c| r.metrics.sound_speed(c)) else {
            continue;
        };
        let group = r.spec.varied_label(|path| path != "v0");
        match groups.iter_mut().find(|(first, label, _)| first.spec.scene == r.spec.scene && *label == group) {
            Some((_, _, points)) => points.push((r.spec.v0, speed)),
            None => groups.push((r, group, vec![(r.spec.v0, speed)])),
        }
    }
    groups
        .into_iter()
        .filter_map(|(first, group, mut points)| {
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let fit = crate::measure::power_law_fit(&points)?;
            Some(SpeedFit { scene: first.spec.scene.clone(), group, law: first.spec.law.name(), points, fit })
        })
        .collect()
}

/// The campaign summary: one row per fitted scaling law (`summary.csv`).
pub fn summary_frame(fits: &[SpeedFit]) -> PolarsResult<DataFrame> {
    DataFrame::new_infer_height(vec![
        Column::new("scene".into(), fits.iter().map(|f| f.scene.clone()).collect::<Vec<String>>()),
        Column::new("group".into(), fits.iter().map(|f| f.group.clone()).collect::<Vec<String>>()),
        Column::new("law".into(), fits.iter().map(|f| f.law).collect::<Vec<&str>>()),
        Column::new("quantity".into(), fits.iter().map(|_| "sound_speed against v0").collect::<Vec<&str>>()),
        Column::new("exponent".into(), fits.iter().map(|f| f.fit.exponent).collect::<Vec<f64>>()),
        Column::new("r_squared".into(), fits.iter().map(|f| f.fit.r_squared).collect::<Vec<f64>>()),
        Column::new("points".into(), fits.iter().map(|f| f.points.len() as u64).collect::<Vec<u64>>()),
        Column::new("v0_min".into(), fits.iter().map(|f| f.points[0].0).collect::<Vec<f64>>()),
        Column::new("v0_max".into(), fits.iter().map(|f| f.points[f.points.len() - 1].0).collect::<Vec<f64>>()),
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

/// Writes `summary.csv` (the fitted scaling laws), atomically; nothing when there are none.
pub fn write_summary(layout: &Layout, fits: &[SpeedFit]) -> anyhow::Result<()> {
    if fits.is_empty() {
        return Ok(());
    }
    let mut csv = Vec::new();
    CsvWriter::new(&mut csv).include_header(true).finish(&mut summary_frame(fits)?)?;
    write_atomically(&layout.file("summary.csv"), &csv)
}
