//! The stored result of one run: its spec, outcome, measurements and sampled series.

use serde::{Deserialize, Serialize};

use super::series;
use crate::draw::Movie;
use crate::sim::{ProbeTrace, RunStatus, Trace};
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
    /// Sampled series: what the report draws ([`series::keep_by_default`]).
    pub trace: Trace,
    /// The table its sample times and energies are stored in (`series/<run_id>.parquet`,
    /// [`series::series_table`]), by length and content hash: set when the record is stored.
    /// `None` in a record of an earlier build, which holds its series in the JSON itself.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub series: Option<SeriesFile>,
    /// The table its per-particle series are stored in, when it keeps any
    /// (`series/<run_id>.particles.parquet`, [`series::particle_table`]), by length and hash.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub particle_table: Option<SeriesFile>,
    /// The table the series of its probed lines are stored in, when the run asks for probes
    /// (`probes/<run_id>.parquet`, [`series::probe_table`]), by length and content hash.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub probe_table: Option<SeriesFile>,
    /// With `output.series: full`, the series its tables keep beyond what the report draws
    /// (every particle at every sample, in double precision, [`series::kept`]): written by the
    /// runner beside the record, never held in it.
    #[serde(skip)]
    pub full_series: Option<Trace>,
    /// The movie's frames, when the run asked for one: written by the runner as
    /// `runs/<run_id>.gif`, never stored in the record.
    #[serde(skip)]
    pub movie: Option<Movie>,
    /// A packing's discs where its run stopped (`packings/<run_id>.parquet`,
    /// [`series::packing_table`]): written by the runner beside the record, never held in it.
    #[serde(skip)]
    pub final_state: Option<Vec<u8>>,
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

    /// Whether the run has a movie of its own (`plots/<run_id>.gif`): it has a movie
    /// ([`RunRecord::has_movie`]) and is not shown side by side with its scene's other runs,
    /// where it is a panel of the scene's movie instead.
    pub fn has_own_movie(&self) -> bool {
        self.has_movie() && self.spec.movie.is_some_and(|m| !m.side_by_side)
    }

    /// Checks a record read from the store as the record of `spec` (whose id names its file):
    /// its own `run_id` is that id and the id of its own spec, its spec is `spec` (but perhaps
    /// for `output.series`, which the id leaves out: `runner::Stored::OtherSeries`), and its
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
        if (RunSpec { series: spec.series, ..self.spec.clone() }) != *spec {
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
    /// `series/<run_id>.parquet` ([`series::series_table`]).
    pub series: Vec<u8>,
    /// `series/<run_id>.particles.parquet` ([`series::particle_table`]), when it keeps any
    /// particle's series.
    pub particle_table: Option<Vec<u8>>,
    /// `probes/<run_id>.parquet` ([`series::probe_table`]), when the run asks for probes.
    pub probe_table: Option<Vec<u8>>,
}

/// Drops the null fields of the record's `metrics`: an unset metric (an `Option`) reads back as
/// `None` without its key, and a lattice run's record loses about a quarter of its ~4.5 kB, to
/// under one 4 KiB block on disk (the coursework folder: ~660 KiB less over its 319 runs). The
/// spec keeps its nulls: a grid value may be null (`relax.residual_force: [null, 1e-6]`), and
/// the stored spec must equal the planned one.
fn without_null_metrics(record: &mut serde_json::Value) {
    if let Some(serde_json::Value::Object(metrics)) = record.get_mut("metrics") {
        metrics.retain(|_, metric| !metric.is_null());
    }
}

impl RunRecord {
    /// The record as stored, naming its tables by [`SeriesFile`] (taking its full series, if
    /// it kept them). They are written before the JSON, so a record is never stored before
    /// its series (see `runner::run_and_store`).
    pub fn to_stored(&mut self) -> anyhow::Result<StoredFiles> {
        let full = self.full_series.take();
        let kept = full.as_ref().unwrap_or(&self.trace);
        let series = series::series_table(kept, &self.spec)?;
        let particle_table = series::particle_table(kept, &self.spec)?;
        let probe_table = series::probe_table(kept, &self.spec)?;
        self.series = Some(SeriesFile::of(&series));
        self.particle_table = particle_table.as_deref().map(SeriesFile::of);
        self.probe_table = probe_table.as_deref().map(SeriesFile::of);
        let mut record = serde_json::to_value(self.without_samples())?;
        without_null_metrics(&mut record);
        let json = serde_json::to_vec(&record)?;
        Ok(StoredFiles { json, series, particle_table, probe_table })
    }

    /// The record as its JSON holds it: its trace's shapes (probe names and nodes) and scalars,
    /// no samples.
    fn without_samples(&self) -> RunRecord {
        let t = &self.trace;
        RunRecord {
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
            particle_table: self.particle_table.clone(),
            probe_table: self.probe_table.clone(),
            full_series: None,
            movie: None,
            final_state: None,
        }
    }

    /// Fills the trace of a record read from the store from the bytes of its tables (`read`
    /// gets them by which and the most bytes to read), each checked against the record's
    /// [`SeriesFile`], then keeps of them what the report draws; why not, if they do not
    /// belong together or do not decode. A record of an earlier build, which names none,
    /// holds its series itself.
    pub fn read_series(&mut self, read: impl Fn(StoredFile, u64) -> std::io::Result<Vec<u8>>) -> Result<(), String> {
        let named = [
            (StoredFile::Series, &self.series),
            (StoredFile::ParticleTable, &self.particle_table),
            (StoredFile::ProbeTable, &self.probe_table),
        ];
        if named.iter().all(|(_, file)| file.is_none()) {
            return Ok(());
        }
        let mut kept = std::mem::take(&mut self.trace);
        for (which, file) in named {
            let Some(file) = file else { continue };
            let bytes = read(which, file.bytes.min(series::most_bytes(&self.spec)))
                .map_err(|error| format!("its {which} cannot be read: {error}"))?;
            let found = SeriesFile::of(&bytes);
            if found != *file {
                return Err(format!(
                    "its {which} ({} bytes, blake3 {}…) is not the one it names ({} bytes, blake3 {}…)",
                    found.bytes,
                    &found.blake3[..12],
                    file.bytes,
                    file.blake3.chars().take(12).collect::<String>()
                ));
            }
            match which {
                StoredFile::Series => series::read_series_table(&bytes, &self.spec, &mut kept),
                StoredFile::ParticleTable => series::read_particle_table(&bytes, &self.spec, &mut kept),
                StoredFile::ProbeTable => series::read_probe_table(&bytes, &self.spec, &mut kept),
            }
            .map_err(|why| format!("its {which} {why}"))?;
        }
        series::keep_by_default(&mut kept, &self.spec);
        self.trace = kept;
        Ok(())
    }
}

/// The tables beside a record's JSON that hold its series.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StoredFile {
    /// `series/<run_id>.parquet`.
    Series,
    /// `series/<run_id>.particles.parquet`.
    ParticleTable,
    /// `probes/<run_id>.parquet`.
    ProbeTable,
}

impl std::fmt::Display for StoredFile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            StoredFile::Series => "series table",
            StoredFile::ParticleTable => "particle table",
            StoredFile::ProbeTable => "probe table",
        })
    }
}
