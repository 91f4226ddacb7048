//! The job runner: the campaign's runs in parallel (rayon), each stored as soon as it ends,
//! cached by content hash, with a progress bar; a failing run becomes a record, not a crash.

pub use self::execute::{execute, execute_within};
pub use self::record::{BUILD, Metrics, NO_MOVIE, RunRecord, StoredFile};
pub use self::series::is_asked_for;
pub use self::shard::{Shard, shard_campaign, shard_of_each_run};

mod execute;
pub mod record;
pub mod series;
pub mod shard;

use anyhow::Context;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use crate::draw::Movie;
use crate::output::{Layout, open_lock_file, read_regular, try_lock, wait_for_lock, write_atomically};
use crate::plan::Plan;
use crate::sim::RunStatus;
use crate::spec::{Campaign, RunSpec};

/// What `run_campaign` did.
#[derive(Debug)]
pub struct CampaignRun {
    /// One record per run of the campaign, in campaign order.
    pub records: Vec<RunRecord>,
    /// Runs simulated now.
    pub simulated: usize,
    /// Runs taken from the store (with [`OtherBuilds::Reuse`], those of another build too).
    pub cached: usize,
    /// Runs whose stored record was corrupt, with why: simulated again.
    pub corrupt: Vec<(String, String)>,
    /// Runs whose stored record was made by another build, with that build: simulated again,
    /// or taken as they are with [`OtherBuilds::Reuse`].
    pub other_build: Vec<(String, String)>,
    /// Runs whose stored record kept other series than `output.series` asks now (default or
    /// full): simulated again for the tables asked for.
    pub other_series: Vec<String>,
}

/// Set when the user interrupts the process (Ctrl-C or SIGTERM, see `cli`): runs not started
/// yet are skipped, the ones running finish and are stored, and `run_campaign` returns
/// [`Interrupted`].
pub static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// `run_campaign` stopped early because the process was interrupted.
#[derive(Debug)]
pub struct Interrupted {
    /// Runs of the campaign with a stored result.
    pub stored: usize,
    /// Runs of the campaign.
    pub total: usize,
}

impl std::fmt::Display for Interrupted {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "interrupted: {} of {} runs stored", self.stored, self.total)
    }
}

impl std::error::Error for Interrupted {}

/// How many runs of `campaign` have a stored record (counted by file, not read).
pub fn stored_count(campaign: &Campaign, layout: &Layout) -> usize {
    campaign.runs.iter().filter(|spec| layout.run_file(&spec.run_id()).is_file()).count()
}

/// What `run` does with a valid record made by another build (another version, or other
/// source that computes results): its numbers may predate a fix.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OtherBuilds {
    /// Simulate the run again with this build (the default).
    Simulate,
    /// Take the record as it is (`run --reuse-other-builds`; the caller says so per run).
    Reuse,
}

/// What the store holds for one run of a campaign.
#[derive(Debug)]
pub enum Stored {
    /// No record.
    Missing,
    /// A file that is not a valid record of this run, and why (unreadable, not a record, another
    /// run's id or spec, series of the wrong length).
    Corrupt(String),
    /// A valid record made by another build ([`RunRecord::build`] is not [`BUILD`]).
    OtherBuild(RunRecord),
    /// A valid record that kept other series than the campaign's `output.series` asks now
    /// (`default` or `full`): the same run, whose tables are not the ones asked for. `run`
    /// simulates it again; `report` draws from it (what the report draws is the same).
    OtherSeries(RunRecord),
    /// A valid record made by this build.
    Current(RunRecord),
}

/// The most bytes a file of the store (a record, its series tables, a movie's list of runs) is
/// read up to: room for the largest record of earlier builds, which held their series in the
/// JSON (`sim::STORED_NUMBERS`, 2 million numbers of up to 25 characters: ~50 MB), and for the
/// tables of a thinned trace (2 million numbers, at most 8 bytes each). A larger file (a record
/// of a build before records were bounded) counts as corrupt: simulated again. The tables of a
/// run with `output.series: full` may hold more (`series::most_bytes`).
pub const STORED_FILE_MOST_BYTES: u64 = 64 << 20;

/// Reads and checks the stored record of `spec` (`runs/<run_id>.json`) and its series
/// (`series/<run_id>.parquet` and the other tables it names, which must be those files).
pub fn read_stored(layout: &Layout, spec: &RunSpec) -> Stored {
    read_stored_as(layout, spec, &spec.run_id())
}

/// [`read_stored`] for a caller that holds the run's id already (`run_id` = `spec.run_id()`):
/// the id hashes the whole spec, half of `plan`'s time on a 100 000-run campaign when it was
/// computed twice per run.
pub fn read_stored_as(layout: &Layout, spec: &RunSpec, run_id: &str) -> Stored {
    let text = match read_regular(&layout.run_file(run_id), STORED_FILE_MOST_BYTES, "a stored file") {
        Ok(text) => text,
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => return Stored::Missing,
        Err(error) => return Stored::Corrupt(format!("cannot be read: {error}")),
    };
    let mut record = match serde_json::from_slice::<RunRecord>(&text) {
        Ok(record) => record,
        Err(error) => return Stored::Corrupt(format!("is not a run record: {error}")),
    };
    let read = record.read_series(|file, most| {
        let path = match file {
            StoredFile::Series => layout.series_table_file(run_id),
            StoredFile::ParticleTable => layout.particle_table_file(run_id),
            StoredFile::ProbeTable => layout.probe_table_file(run_id),
        };
        read_regular(&path, most, "a stored file")
    });
    if let Err(why) = read {
        return Stored::Corrupt(why);
    }
    match record.check(spec) {
        Err(why) => Stored::Corrupt(why),
        Ok(()) if record.spec.series != spec.series => Stored::OtherSeries(record),
        Ok(()) if record.build == BUILD => Stored::Current(record),
        Ok(()) => Stored::OtherBuild(record),
    }
}

/// The stored record of `spec`, if there is a valid one made by this build.
pub fn stored_record(layout: &Layout, spec: &RunSpec) -> Option<RunRecord> {
    match read_stored(layout, spec) {
        Stored::Current(record) => Some(record),
        _ => None,
    }
}

/// Runs every run of the planned campaign that has no valid stored record of this build, on
/// `jobs` threads (all cores when `None`), storing each record as soon as it is finished;
/// records of another build are simulated again, and a run locked by another process is
/// waited for at most the campaign's time budget per run (see [`run_campaign_with`]).
pub fn run_campaign(plan: &Plan, layout: &Layout, jobs: Option<usize>) -> anyhow::Result<CampaignRun> {
    run_campaign_with(plan, layout, jobs, plan.campaign.budget.time_per_run(), OtherBuilds::Simulate)
}

/// [`run_campaign`], with records of another build simulated again or reused as `other_builds`
/// says, and waiting at most `lock_wait` for each run another process holds (its lock file):
/// those runs are left until every other run is done, then waited for, saying so on stderr;
/// after `lock_wait` the campaign stops with an error naming the run and lock file.
pub fn run_campaign_with(
    plan: &Plan,
    layout: &Layout,
    jobs: Option<usize>,
    lock_wait: Duration,
    other_builds: OtherBuilds,
) -> anyhow::Result<CampaignRun> {
    let campaign = &plan.campaign;
    let (stored, notes) = read_store(campaign, layout, other_builds);
    let todo: Vec<&RunSpec> = campaign.runs.iter().zip(&stored).filter(|(_, r)| r.is_none()).map(|(s, _)| s).collect();
    let (mut frames, mut simulated, mut fresh) = (BTreeMap::new(), 0, Vec::new());
    for (spec, ran) in todo.iter().zip(simulate_missing(plan, layout, &todo, jobs, lock_wait)?) {
        if let Some(movie) = ran.panel {
            frames.insert(spec.run_id(), movie);
        }
        simulated += usize::from(ran.simulated);
        fresh.push(ran.record);
    }
    let mut fresh = fresh.into_iter();
    let records: Vec<RunRecord> = stored
        .into_iter()
        .map(|r| r.unwrap_or_else(|| fresh.next().expect("one fresh record per missing run")))
        .collect();
    write_missing_movies(plan, layout, &records, frames)?;
    let StoreNotes { corrupt, other_build, other_series } = notes;
    Ok(CampaignRun { cached: records.len() - simulated, records, simulated, corrupt, other_build, other_series })
}

/// Each run's usable stored record (`None`: to simulate), with what was noted of the others.
/// A run stopped by its budget is tried again: its outcome depends on the machine and the
/// budget, not only on its spec.
fn read_store(campaign: &Campaign, layout: &Layout, other_builds: OtherBuilds) -> (Vec<Option<RunRecord>>, StoreNotes) {
    let mut notes = StoreNotes::default();
    let stored = campaign
        .runs
        .iter()
        .map(|spec| {
            let record = match read_stored(layout, spec) {
                Stored::Current(record) => record,
                Stored::OtherBuild(record) if record.status != RunStatus::Budget => {
                    notes.other_build.push((record.run_id.clone(), record.build.clone()));
                    match other_builds {
                        OtherBuilds::Reuse => record,
                        OtherBuilds::Simulate => return None,
                    }
                }
                Stored::OtherSeries(record) => {
                    notes.other_series.push(record.run_id);
                    return None;
                }
                Stored::Corrupt(why) => {
                    notes.corrupt.push((spec.run_id(), why));
                    return None;
                }
                Stored::OtherBuild(_) | Stored::Missing => return None,
            };
            (record.status != RunStatus::Budget).then_some(record)
        })
        .collect();
    (stored, notes)
}

/// What [`read_store`] noted of the records it does not take, by run id: why a record was
/// corrupt, which build made a record of another build, which records kept other series.
#[derive(Default)]
struct StoreNotes {
    corrupt: Vec<(String, String)>,
    other_build: Vec<(String, String)>,
    other_series: Vec<String>,
}

/// One run of [`simulate_missing`]: its record, whether it was simulated here (not found
/// stored by another process meanwhile), and its movie frames if its scene shows its runs side
/// by side.
struct Ran {
    record: RunRecord,
    simulated: bool,
    panel: Option<Movie>,
}

/// Simulates and stores the runs `todo` on `jobs` threads, longest first. The first failure
/// to store a result stops the campaign with an error; an interruption with [`Interrupted`].
fn simulate_missing(
    plan: &Plan,
    layout: &Layout,
    todo: &[&RunSpec],
    jobs: Option<usize>,
    lock_wait: Duration,
) -> anyhow::Result<Vec<Ran>> {
    let campaign = &plan.campaign;
    let progress = progress_bar(todo.len() as u64);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.unwrap_or(0))
        .build()
        .context("cannot start the thread pool")?;
    // Longest first, in a first-in-first-out queue: the long lattice runs start at once and the
    // short ones fill the gaps, instead of a late long run keeping one core busy alone.
    let mut order: Vec<usize> = (0..todo.len()).collect();
    order.sort_by(|&a, &b| todo[b].estimated_seconds().total_cmp(&todo[a].estimated_seconds()));
    let slots = Slots::new(todo.len());
    // First every run whose lock is free; the runs another process holds are put aside and
    // waited for once all others are done, so a suspended process holds back nothing else.
    for patience in [None, Some(lock_wait)] {
        let queue =
            if patience.is_none() { order.clone() } else { std::mem::take(&mut *slots.busy.lock().expect("pushed")) };
        pool.scope_fifo(|scope| {
            for &index in &queue {
                let (spec, slots, progress) = (todo[index], &slots, &progress);
                scope.spawn_fifo(move |_| {
                    if !slots.stopping.load(Ordering::Relaxed) && !INTERRUPTED.load(Ordering::Relaxed) {
                        match run_and_store(plan, layout, spec, &slots.panels[index], patience) {
                            Ok(Some(done)) => {
                                *slots.finished[index].lock().expect("a slot is written once") = Some(done)
                            }
                            Ok(None) => return slots.busy.lock().expect("busy runs are only pushed").push(index),
                            Err(error) => {
                                slots.stopping.store(true, Ordering::Relaxed);
                                slots.failure.lock().expect("failures are only pushed").get_or_insert(error);
                            }
                        }
                    }
                    progress.inc(1);
                });
            }
        });
    }
    progress.finish_and_clear();
    slots.into_runs(campaign, layout)
}

/// Where the parallel runs of [`simulate_missing`] leave what they did, one slot per run.
struct Slots {
    /// Each run's record, with whether it was simulated here.
    finished: Vec<Mutex<Option<(RunRecord, bool)>>>,
    /// Movies of scenes that show their runs side by side, kept until all runs have ended.
    panels: Vec<Mutex<Option<Movie>>>,
    /// The first failure to store a result (disk full, permissions): it stops the campaign;
    /// runs not yet started are skipped, the ones running finish, everything stored stays.
    failure: Mutex<Option<anyhow::Error>>,
    stopping: AtomicBool,
    /// Runs whose lock another process holds, waited for last.
    busy: Mutex<Vec<usize>>,
}

impl Slots {
    fn new(runs: usize) -> Slots {
        Slots {
            finished: (0..runs).map(|_| Mutex::new(None)).collect(),
            panels: (0..runs).map(|_| Mutex::new(None)).collect(),
            failure: Mutex::new(None),
            stopping: AtomicBool::new(false),
            busy: Mutex::new(Vec::new()),
        }
    }

    /// Every run's outcome, or the failure that stopped the campaign, or [`Interrupted`] when
    /// some runs never started.
    fn into_runs(self, campaign: &Campaign, layout: &Layout) -> anyhow::Result<Vec<Ran>> {
        if let Some(error) = self.failure.into_inner().expect("failures are only pushed") {
            let kept = self.finished.iter().filter(|slot| slot.lock().is_ok_and(|s| s.is_some())).count();
            return Err(error.context(format!(
                "campaign '{}' stopped; {kept} runs finished now and every result stored before are kept in {}",
                campaign.name,
                layout.root.join("runs").display()
            )));
        }
        if self.finished.iter().any(|slot| slot.lock().is_ok_and(|s| s.is_none())) {
            return Err(Interrupted { stored: stored_count(campaign, layout), total: campaign.runs.len() }.into());
        }
        Ok(self
            .finished
            .into_iter()
            .zip(self.panels)
            .map(|(slot, panel)| {
                let (record, simulated) =
                    slot.into_inner().expect("a slot is written once").expect("every queued run ends");
                Ran { record, simulated, panel: panel.into_inner().expect("a panel is written once") }
            })
            .collect())
    }
}

/// Runs `spec` and stores its record (and movie), holding the run's lock file so that another
/// `mdsolids` process on the same store (a second `run`, another shard) never runs it at the
/// same time: whoever comes second waits (at most `patience`; with `None` it returns `None` at
/// once), then finds the record stored and takes it. The lock is an OS file lock, released
/// when the process ends however it ends (even by SIGKILL), so a killed run leaves nothing that
/// blocks a rerun. Returns the record and whether it was simulated here.
fn run_and_store(
    plan: &Plan,
    layout: &Layout,
    spec: &RunSpec,
    panel: &Mutex<Option<Movie>>,
    patience: Option<Duration>,
) -> anyhow::Result<Option<(RunRecord, bool)>> {
    let run_id = spec.run_id();
    let lock_path = layout.run_lock_file(&run_id);
    let lock = open_lock_file(&lock_path)?;
    match patience {
        None if !try_lock(&lock, &lock_path)? => return Ok(None),
        None => {}
        Some(patience) => wait_for_lock(&lock, &lock_path, &format!("run {run_id}"), patience)?,
    }
    if let Some(record) = stored_record(layout, spec).filter(|record| record.status != RunStatus::Budget) {
        return Ok(Some((record, false)));
    }
    let campaign = &plan.campaign;
    let mut record = execute_within(spec, &campaign.budget, &plan.estimates);
    if let Some(movie) = record.movie.take() {
        // A run shown side by side is a panel of its scene's movie, drawn once all have ended;
        // its own movie would repeat that panel (and weigh as much), so none is written.
        if movie.spec.side_by_side {
            *panel.lock().expect("a panel is written once") = Some(movie);
        } else {
            write_run_movie(layout, &mut record, &movie, campaign.budget.seconds_per_run)?;
        }
    }
    // The tables first: a kill between them and the record leaves files and no record (the
    // run is missing), or a record naming earlier files by their hash (corrupt): either way
    // the run is simulated again, never read with series not its own.
    let stored = record.to_stored().context("cannot serialise a run record")?;
    if let Some(table) = &stored.probe_table {
        write_atomically(&layout.probe_table_file(&record.run_id), table)?;
    }
    let particles = layout.particle_table_file(&record.run_id);
    match &stored.particle_table {
        Some(table) => write_atomically(&particles, table)?,
        // An earlier record's (say with `output.series: full`) would be left behind, unnamed.
        None if std::fs::symlink_metadata(&particles).is_ok() => {
            std::fs::remove_file(&particles).with_context(|| format!("cannot remove '{}'", particles.display()))?
        }
        None => {}
    }
    write_atomically(&layout.series_table_file(&record.run_id), &stored.series)?;
    if let Some(table) = record.final_state.take() {
        write_atomically(&layout.packing_file(&record.run_id), &table)?;
    }
    write_atomically(&layout.run_file(&record.run_id), &stored.json)?;
    Ok(Some((record, true)))
}

/// Draws the movie of `record`'s run and writes it beside the record. A movie that cannot be
/// drawn never stops the campaign: the run is recorded with why, as any failing run is. Past
/// the run's deadline (`seconds_per_run`) it becomes `status = budget` (a run already stopped
/// by its budget keeps its own reason); otherwise its status stays and its message says that
/// [`NO_MOVIE`] and why, so that no later `run` or `report` simulates it again for the movie.
/// Only a file that cannot be written (a full disk) is an error, as for the record itself.
pub fn write_run_movie(
    layout: &Layout,
    record: &mut RunRecord,
    movie: &Movie,
    seconds_per_run: f64,
) -> anyhow::Result<()> {
    let error = match crate::draw::encode_movie_panels(&[movie], movie.deadline) {
        Ok(bytes) => return write_atomically(&layout.movie_file(&record.run_id), &bytes),
        Err(error) => error,
    };
    if !error.is::<crate::draw::PastDeadline>() {
        let why = format!("{NO_MOVIE}: {error:#}");
        record.message = if record.message.is_empty() { why } else { format!("{}; {why}", record.message) };
    } else if record.status != RunStatus::Budget {
        record.status = RunStatus::Budget;
        record.message = format!(
            "passed its time budget of {seconds_per_run} s per run (budget.seconds_per_run) while encoding its movie of \
             {} frames of {} × {} pixels; the measurements are kept, the movie is not written",
            movie.frames.len(),
            movie.spec.width,
            movie.spec.height
        );
    }
    Ok(())
}

/// Writes the movies of `records` that are missing: each run's GIF, and for each scene that
/// shows its runs side by side, that movie unless it exists for exactly the scene's current
/// runs (the ids listed in `plots/<scene>-side-by-side.runs`). Frames are not stored (they would
/// make the records many times heavier), so the frames not in `frames` (the movies of the runs
/// simulated now) come from simulating the run again: runs are deterministic, so the frames
/// are the same, and scenes with movies are small. A side-by-side movie whose runs are not all
/// stored yet (or left no frames) is removed rather than shown stale. A movie that cannot be
/// drawn is said on stderr and left out ([`write_movie_or_say`]).
pub fn write_missing_movies(
    plan: &Plan,
    layout: &Layout,
    records: &[RunRecord],
    mut frames: BTreeMap<String, Movie>,
) -> anyhow::Result<()> {
    let campaign = &plan.campaign;
    let mut movie_of = |spec: &RunSpec| {
        frames.remove(&spec.run_id()).or_else(|| execute_within(spec, &campaign.budget, &plan.estimates).movie)
    };
    let mut redrawn: BTreeMap<String, Movie> = BTreeMap::new();
    let own_missing = |r: &&RunRecord| r.has_own_movie() && !layout.movie_file(&r.run_id).is_file();
    for record in records.iter().filter(own_missing) {
        if let Some(movie) = movie_of(&record.spec) {
            write_movie_or_say(&layout.movie_file(&record.run_id), &[&movie])?;
            redrawn.insert(record.run_id.clone(), movie);
        }
    }
    for (scene, _) in &campaign.scenes {
        let ids = side_by_side_ids(campaign, scene);
        if ids.is_empty() || side_by_side_is_current(campaign, layout, scene) {
            continue;
        }
        let (movie_path, runs_path) = (layout.side_by_side_movie(scene), layout.side_by_side_runs(scene));
        // The list goes first and comes back last: a movie is never listed with another's runs.
        for stale in [&runs_path, &movie_path] {
            if stale.exists() {
                std::fs::remove_file(stale).with_context(|| format!("cannot remove '{}'", stale.display()))?;
            }
        }
        let stored: Vec<&RunRecord> = ids.iter().filter_map(|id| records.iter().find(|r| r.run_id == *id)).collect();
        if stored.len() < ids.len() || !stored.iter().all(|r| r.has_movie()) {
            continue;
        }
        let movies: Option<Vec<Movie>> =
            stored.iter().map(|r| redrawn.remove(&r.run_id).or_else(|| movie_of(&r.spec))).collect();
        if let Some(movies) = movies
            && write_movie_or_say(&movie_path, &movies.iter().collect::<Vec<_>>())?
        {
            write_atomically(&runs_path, (ids.join("\n") + "\n").as_bytes())?;
        }
    }
    Ok(())
}

/// Writes `panels` as one movie at `path` and returns true; a movie that cannot be drawn (the
/// movie's own error: past its run's deadline, positions not finite) is said on stderr and left
/// out (false), for it never stops a campaign. A file that cannot be written is an error.
fn write_movie_or_say(path: &std::path::Path, panels: &[&Movie]) -> anyhow::Result<bool> {
    match crate::draw::encode_movie_panels(panels, None) {
        Ok(bytes) => write_atomically(path, &bytes).map(|()| true),
        Err(error) => {
            eprintln!("warning: the movie '{}' is not drawn: {error:#}", path.display());
            Ok(false)
        }
    }
}

/// The runs of `scene` shown side by side, in campaign order.
fn side_by_side_ids(campaign: &Campaign, scene: &str) -> Vec<String> {
    let shown = campaign.runs.iter().filter(|r| r.scene == scene && r.movie.is_some_and(|m| m.side_by_side));
    shown.map(RunSpec::run_id).collect()
}

/// Whether the side-by-side movie of `scene` exists and was drawn from exactly the scene's runs.
pub fn side_by_side_is_current(campaign: &Campaign, layout: &Layout, scene: &str) -> bool {
    let ids = side_by_side_ids(campaign, scene);
    let listed = read_regular(&layout.side_by_side_runs(scene), STORED_FILE_MOST_BYTES, "a stored file")
        .map(|bytes| String::from_utf8_lossy(&bytes).into_owned())
        .unwrap_or_default();
    !ids.is_empty() && listed == ids.join("\n") + "\n" && layout.side_by_side_movie(scene).is_file()
}

/// One bar for the whole campaign (count, elapsed, ETA); hidden when stderr is not a terminal.
fn progress_bar(total: u64) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    if !std::io::stderr().is_terminal() {
        bar.set_draw_target(ProgressDrawTarget::hidden());
    }
    if let Ok(style) = ProgressStyle::with_template("{bar:40} {pos}/{len} runs  {elapsed} elapsed, ETA {eta}") {
        bar.set_style(style);
    }
    bar
}
