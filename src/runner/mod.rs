//! The job runner: the campaign's runs in parallel (rayon), each stored as soon as it ends,
//! cached by content hash, with a progress bar; a failing run becomes a record, not a crash.

pub use self::execute::{execute, execute_within};
pub use self::record::{BUILD, Metrics, Movie, RunRecord};
pub use self::shard::{Shard, shard_campaign, shard_of_each_run};

mod execute;
mod record;
mod shard;

use anyhow::Context;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::output::{Layout, write_atomically};
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
    /// A valid record made by this build.
    Current(RunRecord),
}

/// Reads and checks the stored record of `spec` (`runs/<run_id>.json`).
pub fn read_stored(layout: &Layout, spec: &RunSpec) -> Stored {
    let text = match std::fs::read_to_string(layout.run_file(&spec.run_id())) {
        Ok(text) => text,
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => return Stored::Missing,
        Err(error) => return Stored::Corrupt(format!("cannot be read: {error}")),
    };
    let record = match serde_json::from_str::<RunRecord>(&text) {
        Ok(record) => record,
        Err(error) => return Stored::Corrupt(format!("is not a run record: {error}")),
    };
    match record.check(spec) {
        Err(why) => Stored::Corrupt(why),
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

/// Runs every run of `campaign` that has no valid stored record of this build, on `jobs`
/// threads (all cores when `None`), storing each record as soon as it is finished.
pub fn run_campaign(campaign: &Campaign, layout: &Layout, jobs: Option<usize>) -> anyhow::Result<CampaignRun> {
    run_campaign_with(campaign, layout, jobs, OtherBuilds::Simulate)
}

/// [`run_campaign`], with records of another build simulated again or reused as `other_builds`
/// says.
pub fn run_campaign_with(
    campaign: &Campaign,
    layout: &Layout,
    jobs: Option<usize>,
    other_builds: OtherBuilds,
) -> anyhow::Result<CampaignRun> {
    let (mut corrupt, mut other_build) = (Vec::new(), Vec::new());
    // A run stopped by its budget is tried again: its outcome depends on the machine and the
    // budget, not only on its spec.
    let stored: Vec<Option<RunRecord>> = campaign
        .runs
        .iter()
        .map(|spec| {
            let record = match read_stored(layout, spec) {
                Stored::Current(record) => record,
                Stored::OtherBuild(record) if record.status != "budget" => {
                    other_build.push((record.run_id.clone(), record.build.clone()));
                    match other_builds {
                        OtherBuilds::Reuse => record,
                        OtherBuilds::Simulate => return None,
                    }
                }
                Stored::Corrupt(why) => {
                    corrupt.push((spec.run_id(), why));
                    return None;
                }
                Stored::OtherBuild(_) | Stored::Missing => return None,
            };
            (record.status != "budget").then_some(record)
        })
        .collect();
    let todo: Vec<&RunSpec> = campaign.runs.iter().zip(&stored).filter(|(_, r)| r.is_none()).map(|(s, _)| s).collect();
    let progress = progress_bar(todo.len() as u64);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.unwrap_or(0))
        .build()
        .context("cannot start the thread pool")?;
    // Longest first, in a first-in-first-out queue: the long lattice runs start at once and the
    // short ones fill the gaps, instead of a late long run keeping one core busy alone.
    let mut order: Vec<usize> = (0..todo.len()).collect();
    order.sort_by(|&a, &b| todo[b].estimated_seconds().total_cmp(&todo[a].estimated_seconds()));
    let finished: Vec<Mutex<Option<(RunRecord, bool)>>> = todo.iter().map(|_| Mutex::new(None)).collect();
    // Movies of scenes that show their runs side by side, kept until all runs have ended.
    let panels: Vec<Mutex<Option<Movie>>> = todo.iter().map(|_| Mutex::new(None)).collect();
    // The first failure to store a result (disk full, permissions) stops the campaign: runs
    // not yet started are skipped, the ones running finish, everything stored stays.
    let failure: Mutex<Option<anyhow::Error>> = Mutex::new(None);
    let stopping = AtomicBool::new(false);
    pool.scope_fifo(|scope| {
        for &index in &order {
            let (spec, slot, panel, progress) = (todo[index], &finished[index], &panels[index], &progress);
            let (failure, stopping) = (&failure, &stopping);
            scope.spawn_fifo(move |_| {
                if !stopping.load(Ordering::Relaxed) {
                    match run_and_store(campaign, layout, spec, panel) {
                        Ok(done) => *slot.lock().expect("a slot is written once") = Some(done),
                        Err(error) => {
                            stopping.store(true, Ordering::Relaxed);
                            failure.lock().expect("failures are only pushed").get_or_insert(error);
                        }
                    }
                }
                progress.inc(1);
            });
        }
    });
    progress.finish_and_clear();
    if let Some(error) = failure.into_inner().expect("failures are only pushed") {
        let kept = finished.iter().filter(|slot| slot.lock().is_ok_and(|s| s.is_some())).count();
        return Err(error.context(format!(
            "campaign '{}' stopped: a result could not be stored; {kept} runs finished now and every result stored \
             before are kept in {}",
            campaign.name,
            layout.root.join("runs").display()
        )));
    }
    write_side_by_side(campaign, layout, &todo, panels)?;
    let fresh: Vec<(RunRecord, bool)> = finished
        .into_iter()
        .map(|slot| slot.into_inner().expect("a slot is written once").expect("every queued run ends"))
        .collect();
    let simulated = fresh.iter().filter(|(_, simulated)| *simulated).count();
    let mut fresh = fresh.into_iter();
    let records: Vec<RunRecord> = stored
        .into_iter()
        .map(|r| r.unwrap_or_else(|| fresh.next().expect("one fresh record per missing run").0))
        .collect();
    Ok(CampaignRun { cached: records.len() - simulated, records, simulated, corrupt, other_build })
}

/// Runs `spec` and stores its record (and movie), holding the run's lock file so that another
/// `mdsolids` process on the same store (a second `run`, another shard) never runs it at the
/// same time: whoever comes second waits, then finds the record stored and takes it. The lock
/// is an OS file lock, released when the process ends however it ends (even by SIGKILL), so a
/// killed run leaves nothing that blocks a rerun. Returns the record and whether it was
/// simulated here.
fn run_and_store(
    campaign: &Campaign,
    layout: &Layout,
    spec: &RunSpec,
    panel: &Mutex<Option<Movie>>,
) -> anyhow::Result<(RunRecord, bool)> {
    let run_id = spec.run_id();
    let lock_path = layout.run_lock_file(&run_id);
    if let Some(dir) = lock_path.parent() {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create directory '{}'", dir.display()))?;
    }
    let lock = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&lock_path)
        .with_context(|| format!("cannot open the lock file '{}'", lock_path.display()))?;
    lock.lock().with_context(|| format!("cannot lock '{}'", lock_path.display()))?;
    if let Some(record) = stored_record(layout, spec).filter(|record| record.status != "budget") {
        return Ok((record, false));
    }
    let mut record = execute_within(spec, &campaign.budget);
    if let Some(movie) = record.movie.take() {
        crate::report::write_movie(&layout.movie_file(&record.run_id), &movie)?;
        if movie.spec.side_by_side {
            *panel.lock().expect("a panel is written once") = Some(movie);
        }
    }
    let json = serde_json::to_vec(&record).context("cannot serialise a run record")?;
    write_atomically(&layout.run_file(&record.run_id), &json)?;
    Ok((record, true))
}

/// Writes one movie per scene that asks for its runs side by side, from the movies of the runs
/// simulated now (in campaign order); a scene with a stored run has no frames for it and is
/// left as it is.
fn write_side_by_side(
    campaign: &Campaign,
    layout: &Layout,
    todo: &[&RunSpec],
    panels: Vec<Mutex<Option<Movie>>>,
) -> anyhow::Result<()> {
    let movies: Vec<Option<Movie>> =
        panels.into_iter().map(|m| m.into_inner().expect("a panel is written once")).collect();
    for (scene, _) in &campaign.scenes {
        let wanted = campaign.runs.iter().filter(|r| r.scene == *scene && r.movie.is_some_and(|m| m.side_by_side));
        let fresh: Vec<&Movie> = todo
            .iter()
            .zip(&movies)
            .filter(|(spec, _)| spec.scene == *scene)
            .filter_map(|(_, movie)| movie.as_ref())
            .collect();
        if fresh.len() >= 2 && fresh.len() == wanted.count() {
            crate::report::write_movie_panels(&layout.side_by_side_movie(scene), &fresh)?;
        }
    }
    Ok(())
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
