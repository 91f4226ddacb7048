//! The results table: one row per run, as a Polars frame, written as CSV and Parquet.
//! Column names are a contract other tools read (docs/results.md, "The results table").

use anyhow::Context as _;
use polars::prelude::*;
use serde_json::Value;
use std::collections::BTreeSet;

use crate::output::{Layout, read_regular, write_atomically};
use crate::runner::RunRecord;
use crate::study::{self, RunRow, Slot, Values};
use crate::summary::ScalingFit;

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

/// The columns the kinds declare at `slot` (`study::result_columns`), over `runs`; a
/// non-finite number becomes null, as in [`floats`].
fn kind_columns(runs: &[RunRow], slot: Slot) -> Vec<Column> {
    let column = |(name, values): (&str, Values)| match values {
        Values::Numbers(numbers) => {
            Column::new(name.into(), numbers.into_iter().map(|v| v.filter(|v| v.is_finite())).collect::<Vec<_>>())
        }
        Values::Counts(counts) => Column::new(name.into(), counts),
        Values::Words(words) => Column::new(name.into(), words),
    };
    study::result_columns(slot, runs).into_iter().map(column).collect()
}

/// The results frame of `records`: identity, status and timing, the resolved physics, the
/// measurements with their analytical twins and relative errors, and one column per grid
/// path (numeric where every value is a number, text otherwise). The kinds' columns sit at
/// their slots among the common ones.
pub fn results_frame(records: &[RunRecord]) -> PolarsResult<DataFrame> {
    let runs: Vec<RunRow> = records.iter().map(|r| (&r.spec, &r.metrics, r.steps)).collect();
    let mut columns = run_columns(records);
    columns.extend(kind_columns(&runs, Slot::Size));
    columns.push(floats(records, "v0", |r| r.spec.v0));
    columns.extend(kind_columns(&runs, Slot::Measured));
    columns.push(optional_floats(records, "energy_error", |r| r.metrics.energy_error));
    columns.extend(kind_columns(&runs, Slot::Error));
    columns.extend(measurement_columns(records));
    columns.extend(kind_columns(&runs, Slot::Tail));
    if records.iter().any(|r| r.spec.wave().is_some()) {
        for criterion in crate::measure::ARRIVAL_CRITERIA {
            columns.push(optional_floats(records, &format!("sound_speed_{criterion}"), |r| {
                r.metrics.sound_speed(criterion)
            }));
        }
    }
    let grid = grid_columns(records, &columns);
    columns.extend(grid);
    DataFrame::new_infer_height(columns)
}

/// A run's identity, status and timing, and the resolved physics every kind has.
fn run_columns(records: &[RunRecord]) -> Vec<Column> {
    vec![
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
        optional_floats(records, "solve_s", |r| r.metrics.solve_s),
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
    ]
}

/// The measurements every kind may have: the error against a reference, the wave's arrival
/// and speed, and the stability estimates.
fn measurement_columns(records: &[RunRecord]) -> Vec<Column> {
    vec![
        optional_floats(records, "error", |r| r.metrics.error),
        Column::new(
            "error_measure".into(),
            records.iter().map(|r| r.metrics.error_measure.clone()).collect::<Vec<Option<String>>>(),
        ),
        optional_floats(records, "omega_max", |r| r.metrics.omega_max),
        optional_floats(records, "arrival_time", |r| r.metrics.arrival_time()),
        optional_floats(records, "sound_speed", |r| r.metrics.recommended_sound_speed()),
        Column::new(
            "arrival_criterion".into(),
            records.iter().map(|r| r.metrics.arrival_criterion.clone()).collect::<Vec<Option<String>>>(),
        ),
        optional_floats(records, "arrival_time_tc_estimate", |r| r.metrics.arrival_time_tc_estimate),
        optional_floats(records, "sound_speed_theory", |r| r.metrics.sound_speed_theory),
        optional_floats(records, "dt_omega_max", |r| r.metrics.dt_omega_max),
        optional_floats(records, "mode_damping_ratio", |r| r.metrics.mode_damping_ratio),
        optional_floats(records, "stability_limit", |r| r.metrics.stability_limit),
    ]
}

/// One column per grid path the runs vary, in name order: numeric where every value is a
/// number, text otherwise. A path named like one of the `resolved` columns (`supports`) is
/// already there.
fn grid_columns(records: &[RunRecord], resolved: &[Column]) -> Vec<Column> {
    let paths: BTreeSet<&String> = records.iter().flat_map(|r| r.spec.varied.keys()).collect();
    let resolved: BTreeSet<&str> = resolved.iter().map(|c| c.name().as_str()).collect();
    let column = |path: &String| {
        let values: Vec<Option<&Value>> = records.iter().map(|r| r.spec.varied.get(path)).collect();
        if values.iter().flatten().all(|v| v.is_number()) {
            Column::new(
                path.as_str().into(),
                values.iter().map(|v| v.and_then(Value::as_f64)).collect::<Vec<Option<f64>>>(),
            )
        } else {
            let text = |v: &Value| v.as_str().map(str::to_string).unwrap_or_else(|| v.to_string());
            Column::new(path.as_str().into(), values.iter().map(|v| v.map(text)).collect::<Vec<Option<String>>>())
        }
    };
    paths.into_iter().filter(|p| !resolved.contains(p.as_str())).map(column).collect()
}

/// The most bytes a results table is read back up to (`report` before it writes a partial one,
/// `compare`): 2.6 kB a row for the most runs a campaign may have (100 000; a coursework row
/// takes 690 bytes as CSV).
pub const TABLE_MOST_BYTES: u64 = 256 << 20;

/// The campaign summary: one row per fitted scaling law (`summary.csv`).
pub fn summary_frame(fits: &[ScalingFit]) -> PolarsResult<DataFrame> {
    DataFrame::new_infer_height(vec![
        Column::new("scene".into(), fits.iter().map(|f| f.scene.clone()).collect::<Vec<String>>()),
        Column::new("group".into(), fits.iter().map(|f| f.group.clone()).collect::<Vec<String>>()),
        Column::new("law".into(), fits.iter().map(|f| f.law).collect::<Vec<&str>>()),
        Column::new("beta".into(), fits.iter().map(|f| f.beta).collect::<Vec<f64>>()),
        Column::new("quantity".into(), fits.iter().map(|f| f.quantity).collect::<Vec<&str>>()),
        Column::new("against".into(), fits.iter().map(|f| f.against).collect::<Vec<&str>>()),
        Column::new("exponent".into(), fits.iter().map(|f| f.fit.exponent).collect::<Vec<f64>>()),
        Column::new("r_squared".into(), fits.iter().map(|f| f.fit.r_squared).collect::<Vec<f64>>()),
        // The points the line went through (the positive, finite ones), as the report counts them.
        Column::new("points".into(), fits.iter().map(|f| f.fit.points as u64).collect::<Vec<u64>>()),
        Column::new("x_min".into(), fits.iter().map(|f| f.points[0].0).collect::<Vec<f64>>()),
        Column::new("x_max".into(), fits.iter().map(|f| f.points[f.points.len() - 1].0).collect::<Vec<f64>>()),
        Column::new("particles".into(), fits.iter().map(|f| f.particles as u64).collect::<Vec<u64>>()),
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
        let bytes = read_regular(&layout.file(name), TABLE_MOST_BYTES, "a results table").ok()?;
        ParquetReader::new(std::io::Cursor::new(bytes)).num_rows().ok()
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
