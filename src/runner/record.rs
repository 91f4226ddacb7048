//! The stored result of one run: its spec, outcome, measurements and sampled series.

use serde::{Deserialize, Serialize};

use crate::draw::Movie;
use crate::sim::{ProbeTrace, RunStatus, STORED_NUMBERS, Trace};
use crate::spec::RunSpec;
pub use crate::study::Metrics;

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
    /// Sampled series (what the report draws: [`keep_what_is_stored`]).
    pub trace: Trace,
    /// The file its sampled series are stored in (`runs/<run_id>.series`, [`encode_series`]),
    /// by length and content hash: set when the record is stored. `None` in a record of an
    /// earlier build, which holds its series in the JSON itself.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub series: Option<SeriesFile>,
    /// The file the series of its probed lines are stored in, when the run asks for probes
    /// (`probes/<run_id>.parquet`, [`probe_table`]), by length and content hash.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub probe_table: Option<SeriesFile>,
    /// The movie's frames, when the run asked for one: written by the runner as
    /// `runs/<run_id>.gif`, never stored in the record.
    #[serde(skip)]
    pub movie: Option<Movie>,
}

/// What a record's message says (followed by why) when its run's movie could not be drawn:
/// the run is recorded, and its movie is not tried again.
pub const NO_MOVIE: &str = "its movie could not be drawn";

impl RunRecord {
    /// Whether the run has a movie beside its record (`runs/<run_id>.gif`): it asked for one,
    /// ran to an end (not panicked, not stopped by its budget, not a mechanism) and its movie
    /// could be drawn ([`NO_MOVIE`]).
    pub fn has_movie(&self) -> bool {
        self.spec.movie.is_some()
            && !matches!(self.status, RunStatus::Panicked | RunStatus::Budget | RunStatus::Mechanism)
            && !self.message.contains(NO_MOVIE)
    }

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
/// line one row per sample with one entry per node (or none: a series not kept), nodes inside
/// the lattice; sample times in order.
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
    let rows = |name: &str, series: &[Vec<f64>], width: usize| -> Result<(), String> {
        if !(series.len() == samples || series.is_empty()) {
            return Err(format!("{name} has {} rows for {samples} sample times", series.len()));
        }
        match series.iter().position(|row| row.len() != width) {
            Some(s) => Err(format!("{name}[{s}] has {} entries, not {width}", series[s].len())),
            None => Ok(()),
        }
    };
    rows("trace.displacement_x", &trace.displacement_x, particles)?;
    rows("trace.displacement_y", &trace.displacement_y, particles)?;
    rows("trace.velocity_x", &trace.velocity_x, particles)?;
    rows("trace.velocity_y", &trace.velocity_y, particles)?;
    for (p, probe) in trace.probes.iter().enumerate() {
        if let Some(node) = probe.nodes.iter().find(|&&node| node >= particles) {
            return Err(format!("trace.probes[{p}] names node {node} of a run of {particles} particles"));
        }
        let width = probe.nodes.len();
        rows(&format!("trace.probes[{p}].displacement_x"), &probe.displacement_x, width)?;
        rows(&format!("trace.probes[{p}].displacement_y"), &probe.displacement_y, width)?;
        rows(&format!("trace.probes[{p}].velocity_x"), &probe.velocity_x, width)?;
        rows(&format!("trace.probes[{p}].velocity_y"), &probe.velocity_y, width)?;
    }
    Ok(())
}

/// Which file holds a record's series: its length and blake3 hash, checked on reading, so a
/// record and a series file that do not belong together (a kill between writing the two, a
/// file replaced or cut short) are found out and the run counts as corrupt.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SeriesFile {
    /// Length (bytes).
    pub bytes: u64,
    /// blake3 of the bytes, hex.
    pub blake3: String,
}

impl SeriesFile {
    /// The length and hash of `bytes`.
    pub fn of(bytes: &[u8]) -> SeriesFile {
        SeriesFile { bytes: bytes.len() as u64, blake3: blake3::hash(bytes).to_hex().to_string() }
    }
}

/// A record as stored: the files [`RunRecord::to_stored`] makes.
pub struct StoredFiles {
    /// `runs/<run_id>.json`: the record, whose trace holds the shapes (probe names and nodes)
    /// and scalars but no samples.
    pub json: Vec<u8>,
    /// `runs/<run_id>.series` ([`encode_series`]).
    pub series: Vec<u8>,
    /// `probes/<run_id>.parquet` ([`probe_table`]), when the run asks for probes.
    pub probe_table: Option<Vec<u8>>,
}

impl RunRecord {
    /// The record as stored, naming its series file and probe table by [`SeriesFile`]. They
    /// are written before the JSON, so a record is never stored before its series (see
    /// `runner::run_and_store`).
    pub fn to_stored(&mut self) -> anyhow::Result<StoredFiles> {
        let series = encode_series(&self.trace, |probe| is_asked_for(&self.spec, probe));
        let probe_table = probe_table(self)?;
        self.series = Some(SeriesFile::of(&series));
        self.probe_table = probe_table.as_deref().map(SeriesFile::of);
        let t = &self.trace;
        let bare = RunRecord {
            run_id: self.run_id.clone(),
            build: self.build.clone(),
            spec: self.spec.clone(),
            status: self.status,
            message: self.message.clone(),
            wall_s: self.wall_s,
            steps: self.steps,
            metrics: self.metrics.clone(),
            trace: Trace {
                probes: t
                    .probes
                    .iter()
                    .map(|p| ProbeTrace { name: p.name.clone(), nodes: p.nodes.clone(), ..ProbeTrace::default() })
                    .collect(),
                steps: t.steps,
                loop_s: t.loop_s,
                status: t.status,
                message: t.message.clone(),
                relaxed_at: t.relaxed_at,
                relaxed_by: t.relaxed_by.clone(),
                ..Trace::default()
            },
            series: self.series.clone(),
            probe_table: self.probe_table.clone(),
            movie: None,
        };
        Ok(StoredFiles { json: serde_json::to_vec(&bare)?, series, probe_table })
    }

    /// Fills the trace of a record read from the store from the bytes of its series file and
    /// probe table (`read` gets them by path), each checked against the record's
    /// [`SeriesFile`]; why not, if they do not belong together or do not decode. A record of
    /// an earlier build, which names neither, holds its series itself.
    pub fn read_series(&mut self, read: impl Fn(StoredFile) -> std::io::Result<Vec<u8>>) -> Result<(), String> {
        for (which, named) in [(StoredFile::Series, &self.series), (StoredFile::ProbeTable, &self.probe_table)] {
            let Some(named) = named.clone() else { continue };
            let what = match which {
                StoredFile::Series => "series file",
                StoredFile::ProbeTable => "probe table",
            };
            let bytes = read(which).map_err(|error| format!("its {what} cannot be read: {error}"))?;
            let found = SeriesFile::of(&bytes);
            if found != named {
                return Err(format!(
                    "its {what} ({} bytes, blake3 {}…) is not the one it names ({} bytes, blake3 {}…)",
                    found.bytes,
                    &found.blake3[..12],
                    named.bytes,
                    named.blake3.chars().take(12).collect::<String>()
                ));
            }
            match which {
                StoredFile::Series => decode_series(&bytes, &mut self.trace),
                StoredFile::ProbeTable => read_probe_table(&bytes, &self.spec, &mut self.trace),
            }
            .map_err(|why| format!("its {what} {why}"))?;
        }
        Ok(())
    }
}

/// The files beside a record's JSON that hold its series.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StoredFile {
    /// `runs/<run_id>.series`.
    Series,
    /// `probes/<run_id>.parquet`.
    ProbeTable,
}

/// True when `probe` is a line the run's campaign asked for (`probes:`), not only the kicked
/// column an impulse lattice records for its space–time figure.
pub fn is_asked_for(spec: &RunSpec, probe: &ProbeTrace) -> bool {
    spec.lattice().is_some_and(|l| l.probes.iter().any(|line| line.name() == probe.name))
}

/// The probed lines a run asked for as a Parquet table, one row per sample and node: `time`,
/// `probe`, `node`, `index` along the line, `displacement_x`, `displacement_y`, `velocity_x`,
/// `velocity_y` (single precision, as the record keeps them); `None` when it asked for none.
/// The store of those series (the series file leaves them out) and the table users read.
pub fn probe_table(record: &RunRecord) -> anyhow::Result<Option<Vec<u8>>> {
    use polars::prelude::{Column, DataFrame, ParquetWriter};
    let probes: Vec<&ProbeTrace> = record.trace.probes.iter().filter(|p| is_asked_for(&record.spec, p)).collect();
    if probes.is_empty() {
        return Ok(None);
    }
    let (mut time, mut probe, mut node, mut index) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut values: [Vec<f32>; 4] = Default::default();
    for (s, &t) in record.trace.time.iter().enumerate() {
        for line in &probes {
            for (i, &n) in line.nodes.iter().enumerate() {
                time.push(t);
                probe.push(line.name.as_str());
                node.push(n as u32);
                index.push(i as u32);
                let series = [&line.displacement_x, &line.displacement_y, &line.velocity_x, &line.velocity_y];
                for (column, series) in values.iter_mut().zip(series) {
                    column.push(series[s][i] as f32);
                }
            }
        }
    }
    let mut columns =
        vec![Column::new("time".into(), time), Column::new("probe".into(), probe), Column::new("node".into(), node)];
    columns.push(Column::new("index".into(), index));
    for (name, values) in PROBE_VALUES.iter().zip(values) {
        columns.push(Column::new((*name).into(), values));
    }
    let mut parquet = Vec::new();
    ParquetWriter::new(&mut parquet).finish(&mut DataFrame::new_infer_height(columns)?)?;
    Ok(Some(parquet))
}

/// The value columns of a probe table, in the order of a [`ProbeTrace`]'s series.
const PROBE_VALUES: [&str; 4] = ["displacement_x", "displacement_y", "velocity_x", "velocity_y"];

/// Reads the series of the lines `spec` asked for from its [`probe_table`] into `trace`
/// (whose sample times and lines come from the record and its series file); why not, if the
/// table is not one, or holds other lines, nodes or samples.
fn read_probe_table(bytes: &[u8], spec: &RunSpec, trace: &mut Trace) -> Result<(), String> {
    use polars::prelude::{ParquetReader, SerReader};
    let frame = ParquetReader::new(std::io::Cursor::new(bytes)).finish().map_err(|e| format!("cannot be read: {e}"))?;
    let column = |name: &str| frame.column(name).map_err(|e| format!("has no column {name}: {e}"));
    let names = column("probe")?.str().map_err(|e| e.to_string())?.clone();
    let nodes = column("node")?.u32().map_err(|e| e.to_string())?.clone();
    let values: Vec<Vec<f32>> = PROBE_VALUES
        .iter()
        .map(|name| Ok(column(name)?.f32().map_err(|e| e.to_string())?.into_no_null_iter().collect()))
        .collect::<Result<_, String>>()?;
    let samples = trace.time.len();
    let asked: Vec<usize> = (0..trace.probes.len()).filter(|&p| is_asked_for(spec, &trace.probes[p])).collect();
    let rows_per_sample: usize = asked.iter().map(|&p| trace.probes[p].nodes.len()).sum();
    if frame.height() != samples * rows_per_sample || values.iter().any(|v| v.len() != frame.height()) {
        return Err(format!("has {} rows, not {samples} samples × {rows_per_sample} probed nodes", frame.height()));
    }
    let mut row = 0;
    for &p in &asked {
        let probe = &mut trace.probes[p];
        let width = probe.nodes.len();
        for series in
            [&mut probe.displacement_x, &mut probe.displacement_y, &mut probe.velocity_x, &mut probe.velocity_y]
        {
            *series = vec![vec![0.0; width]; samples];
        }
    }
    for s in 0..samples {
        for &p in &asked {
            let probe = &mut trace.probes[p];
            for i in 0..probe.nodes.len() {
                if names.get(row) != Some(probe.name.as_str()) || nodes.get(row) != Some(probe.nodes[i] as u32) {
                    return Err(format!("row {row} is not node {} of {} at sample {s}", probe.nodes[i], probe.name));
                }
                let series = [
                    &mut probe.displacement_x,
                    &mut probe.displacement_y,
                    &mut probe.velocity_x,
                    &mut probe.velocity_y,
                ];
                for (series, column) in series.into_iter().zip(&values) {
                    series[s][i] = f64::from(column[row]);
                }
                row += 1;
            }
        }
    }
    if values.iter().flatten().any(|v| !v.is_finite()) {
        return Err("holds a number that is not finite".into());
    }
    Ok(())
}

/// What a record keeps of a run's trace once it is measured: what the report draws and
/// `report` draws again, nothing more. The sample times in full; the energies, a chain's x
/// displacements (its waterfall and space–time figures) and every series of the probed lines
/// a campaign asked for (figures and `probes/<run_id>.parquet`) in single precision (7
/// digits: figures show 3 or 4) wherever they fit its range; of an impulse lattice's kicked
/// column, when not asked for, only the displacement along the impulse (the space–time figure).
/// Not kept: the y displacements and velocities of a chain's particles and the kicked column's
/// other series, which nothing draws. Done to the record in memory, so a report rendered at the end
/// of `run` and one by `report` from the store draw the same numbers.
pub fn keep_what_is_stored(trace: &mut Trace, spec: &RunSpec) {
    (trace.displacement_y, trace.velocity_x, trace.velocity_y) = Default::default();
    // The kicked column's displacement along the impulse: x under a sideways step (a transverse
    // wave, whose u_y is round-off), else y.
    let sideways = spec.lattice().and_then(|l| l.impulse).is_some_and(|i| i.is_sideways());
    for probe in trace.probes.iter_mut().filter(|p| !is_asked_for(spec, p)) {
        let across = if sideways { &mut probe.displacement_y } else { &mut probe.displacement_x };
        (*across, probe.velocity_x, probe.velocity_y) = Default::default();
    }
    for series in [&mut trace.kinetic, &mut trace.potential, &mut trace.dissipated, &mut trace.work] {
        to_single(series);
    }
    let matrices = trace
        .probes
        .iter_mut()
        .flat_map(|p| [&mut p.displacement_x, &mut p.displacement_y, &mut p.velocity_x, &mut p.velocity_y]);
    for matrix in std::iter::once(&mut trace.displacement_x).chain(matrices) {
        if matrix.iter().flatten().all(|v| v.abs() <= f32::MAX as f64) {
            matrix.iter_mut().for_each(|row| to_single(row));
        }
    }
}

/// Rounds `series` to single precision when all of it fits (|v| ≤ f32::MAX; values below its
/// smallest number become 0 or lose digits, 1e-38 of anything a figure shows).
fn to_single(series: &mut [f64]) {
    if series.iter().all(|v| v.abs() <= f32::MAX as f64) {
        series.iter_mut().for_each(|v| *v = *v as f32 as f64);
    }
}

/// Opens every series file, before anything is decoded; the version after it.
pub const SERIES_MAGIC: &[u8] = b"mdsolids-series 1\n";

/// zstd level of the series files: 9 is within 2 % of the smallest (19) on the coursework's
/// series at a fraction of its time.
const SERIES_LEVEL: i32 = 9;

/// The most bytes a series file may decode to: a bounded trace ([`STORED_NUMBERS`], plus the
/// sample times and energies of at most `sim::STORED_SAMPLES` samples) in double precision,
/// with room for the headers. A file that decodes to more is refused, not read into memory.
pub const SERIES_MOST_BYTES: u64 = 16 * STORED_NUMBERS as u64 + (1 << 20);

/// The series of `trace` as bytes: zstd over [`SERIES_MAGIC`] and each series in a fixed
/// order (time, kinetic, potential, dissipated and work energy, the per-particle x and y
/// displacements and velocities, then those four of each probed line, in the trace's order of
/// lines), each as its value width (4 where every value is a single-precision number, else 8),
/// its rows and columns (u64, little-endian; a plain series has one row) and its values
/// little-endian, byte planes one after another (the sign and exponent bytes of neighbouring
/// samples are alike, which is what zstd finds: a third smaller than the values as they are).
pub fn encode_series(trace: &Trace, in_table: impl Fn(&ProbeTrace) -> bool) -> Vec<u8> {
    let mut raw = SERIES_MAGIC.to_vec();
    for_each_series(trace, in_table, |values, rows, columns| {
        let single = values.iter().all(|&v| v as f32 as f64 == v);
        let bytes: Vec<u8> = if single {
            values.iter().flat_map(|&v| (v as f32).to_le_bytes()).collect()
        } else {
            values.iter().flat_map(|&v| v.to_le_bytes()).collect()
        };
        let width = if single { 4 } else { 8 };
        raw.push(width as u8);
        raw.extend((rows as u64).to_le_bytes());
        raw.extend((columns as u64).to_le_bytes());
        raw.extend((0..width).flat_map(|plane| bytes.iter().skip(plane).step_by(width).copied()));
    });
    zstd::bulk::compress(&raw, SERIES_LEVEL).expect("zstd compresses any bytes in memory")
}

/// Calls `visit(values, rows, columns)` for each series of `trace` in the stored order; the
/// lines `in_table` (stored in the probe table) as no rows.
fn for_each_series(trace: &Trace, in_table: impl Fn(&ProbeTrace) -> bool, mut visit: impl FnMut(&[f64], usize, usize)) {
    for series in [&trace.time, &trace.kinetic, &trace.potential, &trace.dissipated, &trace.work] {
        visit(series, 1, series.len());
    }
    // Rows of one width (`check_trace` holds every record to it).
    let mut matrix = |rows: &Vec<Vec<f64>>| {
        let flat: Vec<f64> = rows.iter().flatten().copied().collect();
        visit(&flat, rows.len(), rows.first().map_or(0, Vec::len))
    };
    for rows in [&trace.displacement_x, &trace.displacement_y, &trace.velocity_x, &trace.velocity_y] {
        matrix(rows);
    }
    let none = Vec::new();
    for p in &trace.probes {
        for rows in [&p.displacement_x, &p.displacement_y, &p.velocity_x, &p.velocity_y] {
            matrix(if in_table(p) { &none } else { rows });
        }
    }
}

/// Reads the series of [`encode_series`] into `trace`, whose probed lines (names and nodes)
/// come from the record; why not, if the bytes are not such a file or end early or late.
pub fn decode_series(bytes: &[u8], trace: &mut Trace) -> Result<(), String> {
    use std::io::Read;
    let mut raw = Vec::new();
    let decoder = zstd::stream::read::Decoder::new(bytes).map_err(|e| format!("cannot be decoded: {e}"))?;
    decoder.take(SERIES_MOST_BYTES + 1).read_to_end(&mut raw).map_err(|e| format!("cannot be decoded: {e}"))?;
    if raw.len() as u64 > SERIES_MOST_BYTES {
        return Err(format!("decodes to more than {SERIES_MOST_BYTES} bytes, more than any record holds"));
    }
    let mut rest = raw.strip_prefix(SERIES_MAGIC).ok_or("is not a series file of this version")?;
    let rest = &mut rest;
    trace.time = next_series(rest, "time")?.0;
    trace.kinetic = next_series(rest, "kinetic")?.0;
    trace.potential = next_series(rest, "potential")?.0;
    trace.dissipated = next_series(rest, "dissipated")?.0;
    trace.work = next_series(rest, "work")?.0;
    trace.displacement_x = next_matrix(rest, "displacement_x")?;
    trace.displacement_y = next_matrix(rest, "displacement_y")?;
    trace.velocity_x = next_matrix(rest, "velocity_x")?;
    trace.velocity_y = next_matrix(rest, "velocity_y")?;
    for (p, probe) in trace.probes.iter_mut().enumerate() {
        probe.displacement_x = next_matrix(rest, &format!("probes[{p}].displacement_x"))?;
        probe.displacement_y = next_matrix(rest, &format!("probes[{p}].displacement_y"))?;
        probe.velocity_x = next_matrix(rest, &format!("probes[{p}].velocity_x"))?;
        probe.velocity_y = next_matrix(rest, &format!("probes[{p}].velocity_y"))?;
    }
    if !rest.is_empty() {
        return Err(format!("has {} bytes after its last series", rest.len()));
    }
    Ok(())
}

/// The series `name` at the start of `rest` (moved past it): its values, rows and columns.
fn next_series(rest: &mut &[u8], name: &str) -> Result<(Vec<f64>, usize, usize), String> {
    let short = || format!("ends before the end of {name}");
    let (&width, after) = rest.split_first().ok_or_else(short)?;
    let number = |at: Option<&[u8]>| at.map(|b| u64::from_le_bytes(b.try_into().expect("eight bytes")));
    let (rows, columns) = (number(after.get(..8)).ok_or_else(short)?, number(after.get(8..16)).ok_or_else(short)?);
    if width != 4 && width != 8 {
        return Err(format!("gives {name} values of {width} bytes (4 or 8)"));
    }
    let count = rows.checked_mul(columns).filter(|&n| n <= SERIES_MOST_BYTES).ok_or_else(short)? as usize;
    let width = usize::from(width);
    let planes = after.get(16..16 + count * width).ok_or_else(short)?;
    let byte = |plane: usize, i: usize| planes[plane * count + i];
    let values: Vec<f64> = (0..count)
        .map(|i| match width {
            4 => f32::from_le_bytes(std::array::from_fn(|plane| byte(plane, i))) as f64,
            _ => f64::from_le_bytes(std::array::from_fn(|plane| byte(plane, i))),
        })
        .collect();
    if values.iter().any(|v| !v.is_finite()) {
        return Err(format!("holds a number that is not finite in {name}"));
    }
    *rest = &after[16 + count * width..];
    Ok((values, rows as usize, columns as usize))
}

/// [`next_series`] as rows: none, or `rows` of `columns` values.
fn next_matrix(rest: &mut &[u8], name: &str) -> Result<Vec<Vec<f64>>, String> {
    let (values, rows, columns) = next_series(rest, name)?;
    match columns {
        0 if rows > 0 => Err(format!("gives {name} {rows} rows of no values")),
        0 => Ok(Vec::new()),
        _ => Ok(values.chunks(columns).map(<[f64]>::to_vec).collect()),
    }
}
