//! A run's sampled series as the Parquet tables beside its record, which a Python user opens
//! as they are (docs/data.md): `series/<run_id>.parquet` (the sample times and energies),
//! `series/<run_id>.particles.parquet` (per-particle displacements and velocities, one row per
//! particle and sample) and `probes/<run_id>.parquet` (the lines of nodes the campaign
//! probed); what a record keeps of its run's trace (`output.series`); and the tables read
//! back, checked against the run they belong to.
//!
//! Every table is zstd-compressed Parquet written by polars, whose writer encodes floats as
//! PLAIN (or RLE_DICTIONARY where few values repeat) and cannot be asked for
//! BYTE_STREAM_SPLIT; polars reads that encoding but has no writer for it.

use polars::prelude::{
    Column, DataFrame, DataType, KeyValueMetadata, ParallelStrategy, ParquetCompression, ParquetReader, ParquetWriter,
    SerReader, StatisticsOptions,
};

use crate::model::Particles;
use crate::sim::{ProbeTrace, STORED_SAMPLES, Trace, stored_samples};
use crate::spec::{KindSpec, RunSpec, SeriesKept};

/// The energy columns of a series table, in the order of a [`Trace`]'s series: kinetic,
/// potential, dissipated energy and the loads' work so far (J).
pub const ENERGIES: [&str; 4] = ["kinetic", "potential", "dissipated", "work"];

/// The value columns of a particle or probe table, in the order of a [`ProbeTrace`]'s series:
/// displacements from the start (m) and velocities (m/s) along x and y.
pub const MOTIONS: [&str; 4] = ["displacement_x", "displacement_y", "velocity_x", "velocity_y"];

/// Bytes a table may declare per row before it is decoded: the widest row (the particle
/// table's time, particle and four doubles, 44 bytes; a probe table's name) with room to spare.
const BYTES_PER_ROW: u64 = 64;

/// True when `probe` is a line the run's campaign asked for (`probes:`), not only the kicked
/// column an impulse lattice records for its space–time figure.
pub fn is_asked_for(spec: &RunSpec, probe: &ProbeTrace) -> bool {
    spec.lattice().is_some_and(|l| l.probes.iter().any(|line| line.name() == probe.name))
}

/// A run's measured trace split into what its record holds and what its files keep beyond
/// that: by default both are what the report draws ([`keep_by_default`]), and the second is
/// `None`; with `output.series: full` the files keep every sample of every series in double
/// precision (the second), and the record what a default run's would hold.
pub fn kept(mut trace: Trace, spec: &RunSpec) -> (Trace, Option<Trace>) {
    if spec.series == SeriesKept::Default {
        keep_by_default(&mut trace, spec);
        return (trace, None);
    }
    for probe in trace.probes.iter_mut().filter(|p| !is_asked_for(spec, p)) {
        keep_kicked_column(probe, spec);
    }
    // A lattice's record holds none of its particles' rows: they are not copied for it.
    let lattice = spec.lattice().is_some();
    let particles = lattice.then(|| take_particles(&mut trace));
    let mut drawn = trace.clone();
    if let Some([ux, uy, vx, vy]) = particles {
        (trace.displacement_x, trace.displacement_y, trace.velocity_x, trace.velocity_y) = (ux, uy, vx, vy);
    }
    keep_by_default(&mut drawn, spec);
    (drawn, Some(trace))
}

/// The four per-particle series of `trace`, taken out of it.
fn take_particles(trace: &mut Trace) -> [Vec<Vec<f64>>; 4] {
    [&mut trace.displacement_x, &mut trace.displacement_y, &mut trace.velocity_x, &mut trace.velocity_y]
        .map(std::mem::take)
}

/// What a record keeps of a run's samples by default: what the report draws and `report`
/// draws again, and a chain's (or pair's) other per-particle series, which cost little. The
/// sample times in full; the energies, every particle's displacements and velocities of a
/// chain or pair (its waterfall and space–time figures; along y they are zero) and every
/// series of the probed lines a campaign asked for in single precision (7 digits: figures show
/// 3 or 4) wherever they fit its range; of an impulse lattice's kicked column, when not asked
/// for, only the displacement along the impulse (the space–time figure). A lattice's particles
/// are kept only in its probed lines. Thinned within `sim::stored_samples`. Done to the record
/// in memory, so a report rendered at the end of `run` and one by `report` from the store draw
/// the same numbers; doing it twice changes nothing.
pub fn keep_by_default(trace: &mut Trace, spec: &RunSpec) {
    if spec.lattice().is_some() {
        take_particles(trace);
    }
    trace.velocity_x = Vec::new();
    for probe in trace.probes.iter_mut().filter(|p| !is_asked_for(spec, p)) {
        keep_kicked_column(probe, spec);
    }
    trace.thin(stored_samples(trace.numbers_per_sample()));
    for series in [&mut trace.kinetic, &mut trace.potential, &mut trace.dissipated, &mut trace.work] {
        to_single(series);
    }
    let probes = trace
        .probes
        .iter_mut()
        .flat_map(|p| [&mut p.displacement_x, &mut p.displacement_y, &mut p.velocity_x, &mut p.velocity_y]);
    let particles =
        [&mut trace.displacement_x, &mut trace.displacement_y, &mut trace.velocity_x, &mut trace.velocity_y];
    for matrix in particles.into_iter().chain(probes) {
        if matrix.iter().flatten().all(|v| v.abs() <= f32::MAX as f64) {
            matrix.iter_mut().for_each(|row| to_single(row));
        }
    }
}

/// Of an impulse lattice's kicked column (a line the campaign did not ask for), only the
/// displacement along the impulse, in single precision where it fits: u_x under a sideways
/// step (a transverse wave, whose u_y is round-off), else u_y.
fn keep_kicked_column(probe: &mut ProbeTrace, spec: &RunSpec) {
    let sideways = spec.lattice().and_then(|l| l.impulse).is_some_and(|i| i.is_sideways());
    let across = if sideways { &mut probe.displacement_y } else { &mut probe.displacement_x };
    (*across, probe.velocity_x, probe.velocity_y) = Default::default();
    let along = if sideways { &mut probe.displacement_x } else { &mut probe.displacement_y };
    if along.iter().flatten().all(|v| v.abs() <= f32::MAX as f64) {
        along.iter_mut().for_each(|row| to_single(row));
    }
}

/// Rounds `series` to single precision when all of it fits (|v| ≤ f32::MAX; values below its
/// smallest number become 0 or lose digits, 1e-38 of anything a figure shows).
fn to_single(series: &mut [f64]) {
    if series.iter().all(|v| v.abs() <= f32::MAX as f64) {
        series.iter_mut().for_each(|v| *v = *v as f32 as f64);
    }
}

/// `series/<run_id>.parquet` of `spec`'s run: one row per kept sample, `time` (s, double
/// precision) and the [`ENERGIES`] (J).
pub fn series_table(trace: &Trace, spec: &RunSpec) -> anyhow::Result<Vec<u8>> {
    let mut columns = vec![Column::new("time".into(), trace.time.clone())];
    for (name, series) in ENERGIES.iter().zip([&trace.kinetic, &trace.potential, &trace.dissipated, &trace.work]) {
        columns.push(values_column(name, series.clone(), spec));
    }
    parquet(columns)
}

/// Reads a [`series_table`] of `spec`'s run into `trace`: its sample times (in order) and
/// energies; why not, if it is not one.
pub fn read_series_table(bytes: &[u8], spec: &RunSpec, trace: &mut Trace) -> Result<(), String> {
    let frame = open(bytes, most_samples(spec))?;
    trace.time = numbers(&frame, "time")?;
    if trace.time.windows(2).any(|pair| pair[1] < pair[0]) {
        return Err("gives sample times out of order".into());
    }
    let [kinetic, potential, dissipated, work] = ENERGIES.map(|name| numbers(&frame, name));
    (trace.kinetic, trace.potential, trace.dissipated, trace.work) = (kinetic?, potential?, dissipated?, work?);
    Ok(())
}

/// `series/<run_id>.particles.parquet`: the per-particle series `trace` keeps, one row per
/// particle and sample, particle by particle (each particle's samples in time order): `time`
/// (s), `particle` (its index) and of the [`MOTIONS`] those kept; `None` when none are. The
/// particles are every particle when the trace holds their rows (a chain, a pair recording
/// them, any run with `output.series: full`), else the nodes of an impulse lattice's kicked
/// column (the particle rows are then node numbers).
pub fn particle_table(trace: &Trace, spec: &RunSpec) -> anyhow::Result<Option<Vec<u8>>> {
    let Some((nodes, series)) = particle_rows(trace, spec) else { return Ok(None) };
    let samples = trace.time.len();
    let time: Vec<f64> = nodes.iter().flat_map(|_| trace.time.iter().copied()).collect();
    let particle: Vec<u32> = nodes.iter().flat_map(|&n| std::iter::repeat_n(n as u32, samples)).collect();
    let mut columns = vec![Column::new("time".into(), time), Column::new("particle".into(), particle)];
    for (name, rows) in MOTIONS.iter().zip(series).filter(|(_, rows)| !rows.is_empty()) {
        let values = (0..nodes.len()).flat_map(|i| rows.iter().map(move |row| row[i])).collect();
        columns.push(values_column(name, values, spec));
    }
    parquet(columns).map(Some)
}

/// The four series of [`MOTIONS`], each one row per sample (or empty when not kept).
type Motions<'a> = [&'a Vec<Vec<f64>>; 4];

/// The particles whose series `trace` keeps ([`particle_table`]) and those four series; `None`
/// when it keeps none.
fn particle_rows<'a>(trace: &'a Trace, spec: &RunSpec) -> Option<(Vec<usize>, Motions<'a>)> {
    let own = [&trace.displacement_x, &trace.displacement_y, &trace.velocity_x, &trace.velocity_y];
    if let Some(rows) = own.iter().find(|rows| !rows.is_empty()) {
        return Some(((0..rows[0].len()).collect(), own));
    }
    let kicked = trace.probes.iter().find(|p| !is_asked_for(spec, p))?;
    let series = [&kicked.displacement_x, &kicked.displacement_y, &kicked.velocity_x, &kicked.velocity_y];
    series.iter().any(|rows| !rows.is_empty()).then(|| (kicked.nodes.clone(), series))
}

/// Reads a [`particle_table`] of `spec`'s run into `trace`, whose sample times come from its
/// series table and probed lines (names and nodes) from its record: every particle's rows, or
/// an impulse lattice's kicked column (with `output.series: full` taken from every particle's
/// rows); why not, if the table holds other particles, samples or times.
pub fn read_particle_table(bytes: &[u8], spec: &RunSpec, trace: &mut Trace) -> Result<(), String> {
    let every_particle = spec.series == SeriesKept::Full || spec.lattice().is_none();
    let kicked = trace.probes.iter().position(|p| !is_asked_for(spec, p));
    let nodes: Vec<usize> = match kicked {
        _ if every_particle => (0..spec.particles()).collect(),
        Some(p) => trace.probes[p].nodes.clone(),
        None => return Err("is stored for a run that keeps no particle's series".into()),
    };
    let samples = trace.time.len();
    let frame = open(bytes, most_samples(spec).saturating_mul(nodes.len() as u64))?;
    if frame.height() != nodes.len() * samples {
        return Err(format!("has {} rows, not {} particles × {samples} samples", frame.height(), nodes.len()));
    }
    let (time, particle) = (numbers(&frame, "time")?, indices(&frame, "particle")?);
    for (row, (&t, &n)) in time.iter().zip(&particle).enumerate() {
        let (i, s) = (row / samples.max(1), row % samples.max(1));
        if n != nodes[i] as u32 || t.to_bits() != trace.time[s].to_bits() {
            return Err(format!("row {row} is not particle {} at sample {s} (t = {} s)", nodes[i], trace.time[s]));
        }
    }
    let mut kept = [Vec::new(), Vec::new(), Vec::new(), Vec::new()];
    for (name, rows) in MOTIONS.iter().zip(&mut kept).filter(|(name, _)| frame.column(name).is_ok()) {
        let values = numbers(&frame, name)?;
        *rows = (0..samples).map(|s| (0..nodes.len()).map(|i| values[i * samples + s]).collect()).collect();
    }
    if kept.iter().all(Vec::is_empty) {
        return Err(format!("has none of the columns {}", MOTIONS.join(", ")));
    }
    let [ux, uy, vx, vy] = kept;
    match kicked {
        Some(p) if !every_particle => {
            let probe = &mut trace.probes[p];
            (probe.displacement_x, probe.displacement_y, probe.velocity_x, probe.velocity_y) = (ux, uy, vx, vy);
        }
        _ => {
            (trace.displacement_x, trace.displacement_y, trace.velocity_x, trace.velocity_y) = (ux, uy, vx, vy);
            rebuild_kicked_column(trace, spec);
        }
    }
    Ok(())
}

/// With every particle's rows read back, an impulse lattice's kicked column as the run kept
/// it ([`kept`]): picked out of them, then only the displacement along the impulse.
fn rebuild_kicked_column(trace: &mut Trace, spec: &RunSpec) {
    let Some(p) = trace.probes.iter().position(|p| !is_asked_for(spec, p)) else { return };
    let (name, nodes) = (trace.probes[p].name.clone(), trace.probes[p].nodes.clone());
    let mut probe = ProbeTrace::from_trace(name, nodes, trace);
    keep_kicked_column(&mut probe, spec);
    trace.probes[p] = probe;
}

/// The probed lines a run asked for as a Parquet table, one row per sample and node: `time`,
/// `probe`, `node`, `index` along the line and the [`MOTIONS`] (single precision as the record
/// keeps them by default, double with `output.series: full`); `None` when it asked for none.
/// The store of those series (the other tables leave them out) and the table users read.
pub fn probe_table(trace: &Trace, spec: &RunSpec) -> anyhow::Result<Option<Vec<u8>>> {
    let probes: Vec<&ProbeTrace> = trace.probes.iter().filter(|p| is_asked_for(spec, p)).collect();
    if probes.is_empty() {
        return Ok(None);
    }
    let (mut time, mut probe, mut node, mut index) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut values: [Vec<f64>; 4] = Default::default();
    for (s, &t) in trace.time.iter().enumerate() {
        for line in &probes {
            for (i, &n) in line.nodes.iter().enumerate() {
                time.push(t);
                probe.push(line.name.as_str());
                node.push(n as u32);
                index.push(i as u32);
                let series = [&line.displacement_x, &line.displacement_y, &line.velocity_x, &line.velocity_y];
                for (column, series) in values.iter_mut().zip(series) {
                    column.push(series[s][i]);
                }
            }
        }
    }
    let mut columns =
        vec![Column::new("time".into(), time), Column::new("probe".into(), probe), Column::new("node".into(), node)];
    columns.push(Column::new("index".into(), index));
    for (name, values) in MOTIONS.iter().zip(values) {
        columns.push(values_column(name, values, spec));
    }
    parquet(columns).map(Some)
}

/// Reads the series of the lines `spec` asked for from its [`probe_table`] into `trace`
/// (whose sample times and lines come from the record and its series table); why not, if the
/// table is not one, or holds other lines, nodes or samples.
pub fn read_probe_table(bytes: &[u8], spec: &RunSpec, trace: &mut Trace) -> Result<(), String> {
    let samples = trace.time.len();
    let asked: Vec<usize> = (0..trace.probes.len()).filter(|&p| is_asked_for(spec, &trace.probes[p])).collect();
    let rows_per_sample: usize = asked.iter().map(|&p| trace.probes[p].nodes.len()).sum();
    let frame = open(bytes, most_samples(spec).saturating_mul(rows_per_sample as u64))?;
    if frame.height() != samples * rows_per_sample {
        return Err(format!("has {} rows, not {samples} samples × {rows_per_sample} probed nodes", frame.height()));
    }
    let names =
        frame.column("probe").and_then(|c| c.str().cloned()).map_err(|e| format!("has no column probe: {e}"))?;
    let nodes = indices(&frame, "node")?;
    let values = MOTIONS.map(|name| numbers(&frame, name));
    let [ux, uy, vx, vy] = values;
    let values = [ux?, uy?, vx?, vy?];
    for &p in &asked {
        let probe = &mut trace.probes[p];
        let width = probe.nodes.len();
        for series in
            [&mut probe.displacement_x, &mut probe.displacement_y, &mut probe.velocity_x, &mut probe.velocity_y]
        {
            *series = vec![vec![0.0; width]; samples];
        }
    }
    let mut row = 0;
    for s in 0..samples {
        for &p in &asked {
            let probe = &mut trace.probes[p];
            for i in 0..probe.nodes.len() {
                if names.get(row) != Some(probe.name.as_str()) || nodes[row] != probe.nodes[i] as u32 {
                    return Err(format!("row {row} is not node {} of {} at sample {s}", probe.nodes[i], probe.name));
                }
                let series = [
                    &mut probe.displacement_x,
                    &mut probe.displacement_y,
                    &mut probe.velocity_x,
                    &mut probe.velocity_y,
                ];
                for (series, column) in series.into_iter().zip(&values) {
                    series[s][i] = column[row];
                }
                row += 1;
            }
        }
    }
    Ok(())
}

/// The most bytes a table of `spec`'s run may hold on disk: the store's bound by default; with
/// `output.series: full` also room for every particle at every sample.
pub fn most_bytes(spec: &RunSpec) -> u64 {
    let rows = most_samples(spec).saturating_mul(spec.particles() as u64);
    super::STORED_FILE_MOST_BYTES.max(rows.saturating_mul(BYTES_PER_ROW).saturating_add(1 << 20))
}

/// The most samples a table of `spec`'s run holds: the bound of a thinned trace by default;
/// with `output.series: full` every sample the run takes (one every ⌊steps / samples⌋ steps,
/// fewer than 2 · samples, with the first and the last).
fn most_samples(spec: &RunSpec) -> u64 {
    match spec.series {
        SeriesKept::Default => STORED_SAMPLES as u64,
        SeriesKept::Full => spec.samples.saturating_mul(2).saturating_add(3),
    }
}

/// A column of `values` of `spec`'s run: single precision where its series are kept by default
/// and every value is a single-precision number ([`keep_by_default`]), else double (every
/// column of a run with `output.series: full`).
fn values_column(name: &str, values: Vec<f64>, spec: &RunSpec) -> Column {
    if spec.series == SeriesKept::Default && values.iter().all(|&v| v as f32 as f64 == v) {
        Column::new(name.into(), values.into_iter().map(|v| v as f32).collect::<Vec<f32>>())
    } else {
        Column::new(name.into(), values)
    }
}

/// `packings/<run_id>.parquet` of a packing run: its discs where the run stopped, one row per
/// disc, `x`, `y` and `radius` (m, double precision), from which every number of its row
/// can be computed again (with `box_side` of the results table); `None` for other kinds.
pub fn packing_table(spec: &RunSpec, particles: &Particles) -> anyhow::Result<Option<Vec<u8>>> {
    let KindSpec::Packing(run) = &spec.scene_kind else { return Ok(None) };
    let (packing, _) = crate::study::packing::discs(spec, run);
    let columns = vec![
        Column::new("x".into(), particles.x.clone()),
        Column::new("y".into(), particles.y.clone()),
        Column::new("radius".into(), packing.radius),
    ];
    parquet(columns).map(Some)
}

/// `columns` as a Parquet file: zstd at polars' level (3: level 19 made the coursework's folder
/// 0.3 % smaller and a full chain of 1000 particles over 3000 samples 3.5 × slower to store,
/// 19 s against 5.3 s), no statistics (one row group of a few pages: nothing to skip by them) and no embedded Arrow schema (readers take the types from the Parquet schema:
/// `float`, `double`, `uint32`, `string`), a few hundred bytes less in every file. Written on
/// the calling thread: polars' own pool, waited for from a worker of the campaign's pool, let
/// that worker take up other runs meanwhile, nested until its stack overflowed.
fn parquet(columns: Vec<Column>) -> anyhow::Result<Vec<u8>> {
    let mut frame = DataFrame::new_infer_height(columns)?;
    let mut bytes = Vec::new();
    ParquetWriter::new(&mut bytes)
        .set_parallel(false)
        .with_compression(ParquetCompression::Zstd(None))
        .with_statistics(StatisticsOptions::empty())
        .with_key_value_metadata(Some(KeyValueMetadata::Static(Vec::new())))
        .finish(&mut frame)?;
    Ok(bytes)
}

/// The table in `bytes`, refused before it is decoded when its footer declares more than
/// `most_rows` rows (or more bytes than such rows hold): a small file that would decode to
/// more than its run can hold is not read into memory. Read on the calling thread, as
/// [`parquet`] writes.
fn open(bytes: &[u8], most_rows: u64) -> Result<DataFrame, String> {
    let mut reader = ParquetReader::new(std::io::Cursor::new(bytes)).read_parallel(ParallelStrategy::None);
    let metadata = reader.get_metadata().map_err(|e| format!("is not a Parquet table: {e}"))?;
    let grouped: u64 = metadata.row_groups.iter().map(|g| g.num_rows() as u64).sum();
    let rows = grouped.max(metadata.num_rows as u64);
    let declared: u64 = metadata.row_groups.iter().map(|g| g.total_byte_size() as u64).sum();
    if rows > most_rows || declared > most_rows.saturating_mul(BYTES_PER_ROW).saturating_add(1 << 20) {
        return Err(format!(
            "declares {rows} rows of {declared} bytes, more than its run can hold ({most_rows} rows); not decoded"
        ));
    }
    reader.finish().map_err(|e| format!("cannot be decoded: {e}"))
}

/// Column `name` of `frame` as numbers (stored as single or double precision), each finite.
fn numbers(frame: &DataFrame, name: &str) -> Result<Vec<f64>, String> {
    let column = frame.column(name).map_err(|_| format!("has no column {name}"))?;
    if column.null_count() > 0 {
        return Err(format!("has a missing value in {name}"));
    }
    let values: Vec<f64> = match column.dtype() {
        DataType::Float32 => column.f32().map_err(|e| e.to_string())?.into_no_null_iter().map(f64::from).collect(),
        DataType::Float64 => column.f64().map_err(|e| e.to_string())?.into_no_null_iter().collect(),
        other => return Err(format!("gives {name} as {other}, not as numbers")),
    };
    match values.iter().find(|v| !v.is_finite()) {
        Some(v) => Err(format!("holds a number that is not finite in {name}: {v}")),
        None => Ok(values),
    }
}

/// Column `name` of `frame` as particle or node numbers (unsigned 32-bit integers, none missing).
fn indices(frame: &DataFrame, name: &str) -> Result<Vec<u32>, String> {
    let column = frame.column(name).map_err(|_| format!("has no column {name}"))?;
    let values = column.u32().map_err(|e| format!("gives {name} as {}, not as u32: {e}", column.dtype()))?;
    if values.null_count() > 0 {
        return Err(format!("has a missing value in {name}"));
    }
    Ok(values.into_no_null_iter().collect())
}
