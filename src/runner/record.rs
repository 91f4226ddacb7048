//! The stored result of one run: its spec, outcome, measurements and sampled series.

use serde::{Deserialize, Serialize};

use crate::draw::Movie;
use crate::sim::{RunStatus, Trace};
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
