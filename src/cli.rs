//! Command line: `run`, `plan`, `report` and `slurm` on a campaign file.
// The doc comments of the commands are their `--help` text, where <name> is a placeholder,
// not an HTML tag.
#![allow(rustdoc::invalid_html_tags)]

use anyhow::Context;
use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};

use crate::bench::{BenchConfig, BenchResult, Workload, run_once};
use crate::model::{LatticeType, PlanarLattice};
use crate::output::{Layout, escape_for_terminal};
use crate::plan::{Plan, Stability};
use crate::runner::{
    BUILD, CampaignRun, INTERRUPTED, Interrupted, OtherBuilds, RunRecord, Shard, Stored, read_stored, read_stored_as,
    run_campaign_with, shard_campaign, shard_of_each_run, stored_count, write_missing_movies,
};
use crate::sim::RunStatus;
use crate::spec::Campaign;
use crate::{report, table};

/// Molecular-dynamics studies of mass-spring solids: campaign YAML in, tables and reports out.
#[derive(Debug, Parser)]
// `bin_name`: usage and help say `mdsolids` whatever the executable is called (the test suite
// starts it as `mdsolids-tested`, tests/Cargo.toml).
#[command(name = "mdsolids", bin_name = "mdsolids", version, about)]
pub struct Cli {
    /// Directory that holds one output directory per campaign.
    #[arg(long, global = true, default_value = "reports")]
    pub reports: PathBuf,
    /// Longest wait (s) for a lock another mdsolids process holds (a run it simulates, the
    /// reports it writes) before giving up [default: the campaign's budget.seconds_per_run].
    #[arg(long, global = true, value_name = "SECONDS", value_parser = parse_seconds)]
    pub lock_wait: Option<f64>,
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run every run of the campaign that has no stored result, then write tables and reports.
    Run {
        /// Campaign file (YAML).
        campaign: PathBuf,
        /// Parallel jobs, 1 to 1024 (default: all cores).
        #[arg(short, long, value_parser = thread_count)]
        jobs: Option<usize>,
        /// Run only share I of N (0 ≤ I < N) of the runs, balanced by the plan's cost estimate,
        /// and store them without writing tables or reports (`report` merges the shares).
        #[arg(long, value_name = "I/N")]
        shard: Option<Shard>,
        /// Write into reports/<name>/ even when another campaign file owns it (it becomes this
        /// file's; see campaign.json there).
        #[arg(long)]
        force: bool,
        /// Take stored results made by another build (another version, or other physics source)
        /// as they are, with one warning per run, instead of simulating them again.
        #[arg(long)]
        reuse_other_builds: bool,
    },
    /// List the expanded runs with dt, t_c, cost and cache state; runs nothing.
    Plan {
        /// Campaign file (YAML).
        campaign: PathBuf,
        /// List only the runs of share I of N (as `run --shard I/N` would run them).
        #[arg(long, value_name = "I/N")]
        shard: Option<Shard>,
    },
    /// Re-render tables and reports from the stored results without simulating (except the runs
    /// a missing movie needs: frames are not stored); runs without a stored result are listed
    /// and left out.
    Report {
        /// Campaign file (YAML).
        campaign: PathBuf,
        /// Write into reports/<name>/ even when another campaign file owns it.
        #[arg(long)]
        force: bool,
    },
    /// Write a Slurm job array (task I runs `run --shard I/N`) and a report job that runs after
    /// every task has ended (afterany) into <reports>/<campaign>/slurm/; --reports must be on
    /// a file system all nodes share.
    Slurm {
        /// Campaign file (YAML).
        campaign: PathBuf,
        /// Array tasks (shares of the campaign).
        #[arg(long, default_value_t = 4)]
        tasks: usize,
        /// Slurm partition or comma-separated partitions (default: the cluster's default partition).
        #[arg(long, value_parser = crate::slurm::partition_option)]
        partition: Option<String>,
        /// Time limit of each job, in Slurm's format (e.g. 30, 2:00:00, 1-0).
        #[arg(long, value_parser = crate::slurm::time_option)]
        time: Option<String>,
        /// CPUs per array task (also its --jobs), 1 to 1024.
        #[arg(long, default_value_t = 1, value_parser = thread_count)]
        cpus_per_task: usize,
        /// Submit with sbatch and print the job ids (otherwise print how to submit).
        #[arg(long)]
        submit: bool,
        /// Write into reports/<name>/ even when another campaign file owns it.
        #[arg(long)]
        force: bool,
    },
    /// Time the reference workloads (docs/performance.md) on an N × N lattice with diagonals:
    /// `kernel` (undamped, free, velocity Verlet) and `relax` (a damped, loaded, clamped
    /// coursework lattice with its relaxation checks); prints particle-steps/s, bond-updates/s
    /// and energy drift.
    Bench {
        /// Workloads to time, comma-separated (`kernel,relax`): their repetitions alternate,
        /// so their ratio comes from one run.
        #[arg(long, value_enum, value_delimiter = ',', default_value = "kernel")]
        workload: Vec<Workload>,
        /// Lattice side N (N² particles).
        #[arg(long, default_value_t = 316)]
        n: usize,
        /// Steps to time.
        #[arg(long, default_value_t = 1000)]
        steps: u64,
        /// Threads, 1 to 1024 (default: all cores).
        #[arg(long, value_parser = thread_count)]
        threads: Option<usize>,
        /// Remove this fraction of the bonds at random (runs the generic bond-list loop).
        #[arg(long, default_value_t = 0.0)]
        dilute: f64,
        /// Run the full lattice through the generic bond-list loop instead of the stencil.
        #[arg(long)]
        bond_list: bool,
        /// Lattice types to time, comma-separated (`square,triangular,honeycomb,kagome`; the
        /// others always through the bond list): each with every workload, repetitions
        /// alternating.
        #[arg(long, value_parser = lattice_type, value_delimiter = ',', default_value = "square")]
        lattice: Vec<LatticeType>,
        /// Timed repetitions; the median is reported.
        #[arg(long, default_value_t = 3)]
        repeat: usize,
        /// Print one JSON line instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Set two campaigns' reports side by side: the joined results with ratios B/A, the fitted
    /// exponents of both, and A and B overlaid in one figure per scene, parameter and quantity.
    Compare {
        /// Report directory of campaign A (e.g. reports/coursework).
        a: PathBuf,
        /// Report directory of campaign B (e.g. reports/coursework-hertz).
        b: PathBuf,
        /// Output directory [default: <reports>/compare-<A>-vs-<B>].
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

/// Parses the command line and does what it says.
pub fn run() -> anyhow::Result<()> {
    let cli = Cli::parse();
    match &cli.command {
        Command::Run { campaign, jobs, shard, force, reuse_other_builds } => {
            let options = RunOptions {
                jobs: *jobs,
                force: *force,
                lock_wait: cli.lock_wait,
                other_builds: if *reuse_other_builds { OtherBuilds::Reuse } else { OtherBuilds::Simulate },
            };
            match shard {
                Some(shard) => run_shard_command(&cli.reports, campaign, *shard, &options),
                None => run_command(&cli.reports, campaign, &options),
            }
        }
        Command::Plan { campaign, shard } => plan_command(&cli.reports, campaign, *shard),
        Command::Report { campaign, force } => report_command(&cli.reports, campaign, *force, cli.lock_wait),
        Command::Slurm { campaign, tasks, partition, time, cpus_per_task, submit, force } => {
            let request = SlurmRequest {
                tasks: *tasks,
                partition: partition.clone(),
                time: time.clone(),
                cpus_per_task: *cpus_per_task,
                submit: *submit,
                force: *force,
            };
            slurm_command(&cli.reports, campaign, &request)
        }
        Command::Bench { workload, n, steps, threads, dilute, bond_list, lattice, repeat, json } => {
            let configs: Vec<_> = lattice
                .iter()
                .flat_map(|&lattice| {
                    workload.iter().map(move |&workload| BenchConfig {
                        workload,
                        n: *n,
                        steps: *steps,
                        dilute: *dilute,
                        bond_list: *bond_list,
                        lattice,
                    })
                })
                .collect();
            bench_command(&configs, *threads, *repeat, *json)
        }
        Command::Compare { a, b, out } => compare_command(&cli.reports, a, b, out.as_deref()),
    }
}

fn open(reports: &Path, file: &Path) -> anyhow::Result<(Plan, Layout)> {
    let plan = crate::plan::load(file)?;
    let layout = Layout::new(reports, &plan.campaign.name);
    Ok((plan, layout))
}

/// [`open`] for a command that writes into the campaign's folder: claims the folder for `file`
/// first, refusing one another campaign file of the same name owns unless `force`.
fn open_to_write(reports: &Path, file: &Path, force: bool) -> anyhow::Result<(Plan, Layout)> {
    let (plan, layout) = open(reports, file)?;
    crate::owner::claim(&layout, file, force)?;
    Ok((plan, layout))
}

/// Most threads `-j`, `--threads` and `--cpus-per-task` accept: four times the cores of a large
/// node; starting 100 000 threads took minutes.
const MAX_THREADS: usize = 1024;

/// A thread count in 1..=[`MAX_THREADS`].
fn thread_count(text: &str) -> Result<usize, String> {
    match text.trim().parse::<usize>() {
        Ok(n) if (1..=MAX_THREADS).contains(&n) => Ok(n),
        _ => Err(format!("'{text}': give a number of threads from 1 to {MAX_THREADS} (leave it out for all cores)")),
    }
}

/// A number of seconds: finite and not negative.
fn parse_seconds(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(seconds) if seconds.is_finite() && seconds >= 0.0 => Ok(seconds),
        _ => Err(format!("'{text}': expected a number of seconds ≥ 0")),
    }
}

/// `--lock-wait`, or the campaign's time budget per run: no run holds its lock longer than
/// that unless its process is suspended or stuck.
fn lock_patience(campaign: &Campaign, lock_wait: Option<f64>) -> std::time::Duration {
    lock_wait.map_or_else(|| campaign.budget.time_per_run(), crate::spec::seconds_up_to_1e9)
}

/// Takes the campaign's publish lock (tables, figures, report), so that a `report` and a
/// `run` never write them at the same time; whoever publishes later read the store later.
fn lock_publishing(campaign: &Campaign, layout: &Layout, lock_wait: Option<f64>) -> anyhow::Result<std::fs::File> {
    let path = layout.publish_lock_file();
    let lock = crate::output::open_lock_file(&path)?;
    let what = format!("the reports of campaign '{}'", campaign.name);
    crate::output::wait_for_lock(&lock, &path, &what, lock_patience(campaign, lock_wait))?;
    Ok(lock)
}

/// Runs `campaign` into the store after sweeping the temporaries killed processes left. On
/// Ctrl-C (or SIGTERM) the runs in progress finish and are stored and no more start; a second
/// one ends the process at once; either way it ends (exit code 130) with how many runs are
/// stored and the command that continues.
fn run_stored(plan: &Plan, layout: &Layout, options: &RunOptions) -> anyhow::Result<CampaignRun> {
    let campaign = &plan.campaign;
    crate::output::sweep_temporaries(layout);
    let rerun = format!("rerun `mdsolids {}` to continue", std::env::args().skip(1).collect::<Vec<_>>().join(" "));
    let mut signals = signal_hook::iterator::Signals::new([signal_hook::consts::SIGINT, signal_hook::consts::SIGTERM])
        .context("cannot handle Ctrl-C")?;
    let (owned, hint) = ((campaign.clone(), layout.clone()), rerun.clone());
    std::thread::spawn(move || {
        for (count, _) in signals.forever().enumerate() {
            if count == 0 {
                INTERRUPTED.store(true, std::sync::atomic::Ordering::Relaxed);
                eprintln!("interrupted: the runs in progress finish and are stored, no more start (again: stop now)");
            } else {
                let (campaign, layout) = &owned;
                let stopped = Interrupted { stored: stored_count(campaign, layout), total: campaign.runs.len() };
                eprintln!("{stopped}; {hint}");
                std::process::exit(130);
            }
        }
    });
    let lock_wait = lock_patience(campaign, options.lock_wait);
    match run_campaign_with(plan, layout, options.jobs, lock_wait, options.other_builds) {
        Err(error) if error.is::<Interrupted>() => {
            eprintln!("{error}; {rerun}");
            std::process::exit(130)
        }
        done => done,
    }
}

/// What `run` was asked for besides the campaign.
struct RunOptions {
    /// Threads (`-j`).
    jobs: Option<usize>,
    /// Write into a folder another campaign file owns (`--force`).
    force: bool,
    /// Longest wait for a lock another process holds (`--lock-wait`, s).
    lock_wait: Option<f64>,
    /// What to do with records of another build (`--reuse-other-builds`).
    other_builds: OtherBuilds,
}

fn run_command(reports: &Path, file: &Path, options: &RunOptions) -> anyhow::Result<()> {
    let started = std::time::Instant::now();
    let (plan, layout) = open_to_write(reports, file, options.force)?;
    let campaign = &plan.campaign;
    collision_warnings(campaign).for_each(|line| eprintln!("{line}"));
    let done = run_stored(&plan, &layout, options)?;
    warn_about_store(&layout, &done, options.other_builds);
    let failed = done.records.iter().filter(|r| r.status != RunStatus::Ok).count();
    let _publishing = lock_publishing(campaign, &layout, options.lock_wait)?;
    publish(campaign, &layout, &done.records, &report::LeftOut::default())?;
    println!(
        "{}: {} runs ({} simulated, {} cached, {} not ok) in {:.2} s -> {}",
        campaign.name,
        done.records.len(),
        done.simulated,
        done.cached,
        failed,
        started.elapsed().as_secs_f64(),
        layout.root.display()
    );
    Ok(())
}

/// Runs one share of the campaign into the store. Tables and reports are left to `report`:
/// the other shares may still be running, and several shards writing them at once would race.
fn run_shard_command(reports: &Path, file: &Path, shard: Shard, options: &RunOptions) -> anyhow::Result<()> {
    let started = std::time::Instant::now();
    let (mut plan, layout) = open_to_write(reports, file, options.force)?;
    let total = plan.campaign.runs.len();
    plan.campaign = shard_campaign(&plan.campaign, shard);
    collision_warnings(&plan.campaign).for_each(|line| eprintln!("{line}"));
    let done = run_stored(&plan, &layout, options)?;
    warn_about_store(&layout, &done, options.other_builds);
    let failed = done.records.iter().filter(|r| r.status != RunStatus::Ok).count();
    println!(
        "{} shard {shard}: {} of {} runs ({} simulated, {} cached, {} not ok) in {:.2} s -> {}; \
         `mdsolids report` merges the shards",
        plan.campaign.name,
        done.records.len(),
        total,
        done.simulated,
        done.cached,
        failed,
        started.elapsed().as_secs_f64(),
        layout.file("runs").display()
    );
    Ok(())
}

/// Says on stderr what `run` found in the store besides valid records of this build: each
/// corrupt record (simulated again), each record of another build it reused, or how many it
/// simulated again.
fn warn_about_store(layout: &Layout, done: &CampaignRun, other_builds: OtherBuilds) {
    for (run_id, why) in &done.corrupt {
        eprintln!(
            "warning: {} is corrupt ({}); simulated again",
            layout.run_file(run_id).display(),
            escape_for_terminal(why)
        );
    }
    match other_builds {
        OtherBuilds::Reuse => {
            for (run_id, build) in &done.other_build {
                eprintln!(
                    "warning: reusing {run_id}, made by build {}, not by this build {BUILD}",
                    escape_for_terminal(build)
                );
            }
        }
        OtherBuilds::Simulate if !done.other_build.is_empty() => eprintln!(
            "note: {} stored runs were made by another build than this one ({BUILD}) and were simulated again \
             (--reuse-other-builds takes them as they are): {}",
            done.other_build.len(),
            listed(done.other_build.iter().map(|(run_id, _)| run_id.as_str()))
        ),
        OtherBuilds::Simulate => {}
    }
    if !done.other_series.is_empty() {
        eprintln!(
            "note: {} stored runs kept other series than output.series asks for and were simulated again for \
             their tables (their results are the same): {}",
            done.other_series.len(),
            listed(done.other_series.iter().map(String::as_str))
        );
    }
}

/// At most 20 of `ids`, comma-separated, with how many more there are.
fn listed<'a>(ids: impl ExactSizeIterator<Item = &'a str>) -> String {
    const LISTED: usize = 20;
    let more = ids.len().saturating_sub(LISTED);
    let shown: Vec<&str> = ids.take(LISTED).collect();
    format!("{}{}", shown.join(", "), if more > 0 { format!(" and {more} more") } else { String::new() })
}

/// Writing tables, figures and the report of a campaign of a few dozen runs (measured ~0.07 s).
const REPORT_SECONDS: f64 = 0.1;

fn plan_command(reports: &Path, file: &Path, shard: Option<Shard>) -> anyhow::Result<()> {
    let (mut plan, layout) = open(reports, file)?;
    if let Some(shard) = shard {
        plan.campaign = shard_campaign(&plan.campaign, shard);
    }
    let tally = print_plan_rows(&plan, &layout);
    print_plan_summary(&plan.campaign, &layout, &tally);
    print_budget_warnings(&plan.campaign);
    collision_warnings(&plan.campaign).for_each(|line| println!("{line}"));
    Ok(())
}

/// The collisions the plan lets run but warns of ([`crate::plan::collision_warning`]), one line
/// each: a collision that may pass through its neighbour by an estimate only, a contact resolved
/// by a few steps. `plan` prints them with its table, `run` before it starts, with its notices.
fn collision_warnings(campaign: &Campaign) -> impl Iterator<Item = String> + '_ {
    campaign
        .runs
        .iter()
        .filter_map(|spec| crate::plan::collision_warning(spec).map(|why| format!("warning: {}: {why}", spec.run_id())))
}

/// What `plan` found in the store, run by run.
struct PlanTally {
    /// How many runs are in each stored state (yes, missing, corrupt, stale, series, budget).
    states: std::collections::BTreeMap<&'static str, usize>,
    /// Runs whose record is corrupt, with why.
    corrupt: Vec<(String, String)>,
    /// Estimated seconds of simulation of the runs `run` would simulate, on one core.
    simulation_s: f64,
}

/// Prints the plan's table, one row per run, and returns what it found in the store.
fn print_plan_rows(plan: &Plan, layout: &Layout) -> PlanTally {
    let campaign = &plan.campaign;
    println!(
        "{:<28} {:<8} {:<16} {:>11} {:>11} {:>8} {:>10} {:>8} {:>7} {:>7}  varied",
        "run_id", "kind", "integrator", "dt (s)", "t_c (s)", "t_c/dt", "steps", "dt·ω_max", "limit", "stored"
    );
    let mut tally = PlanTally { states: Default::default(), corrupt: Vec::new(), simulation_s: 0.0 };
    for spec in &campaign.runs {
        let run_id = spec.run_id();
        // What `run` would do with the run's stored record: take it (`yes`), or simulate the
        // run because the record is missing, corrupt, of another build, kept other series than
        // `output.series` asks for or stopped by its budget.
        let state = match read_stored_as(layout, spec, &run_id) {
            Stored::Current(record) | Stored::OtherBuild(record) | Stored::OtherSeries(record)
                if record.status == RunStatus::Budget =>
            {
                "budget"
            }
            Stored::Current(_) => "yes",
            Stored::OtherBuild(_) => "stale",
            Stored::OtherSeries(_) => "series",
            Stored::Corrupt(why) => {
                tally.corrupt.push((run_id.clone(), why));
                "corrupt"
            }
            Stored::Missing => "missing",
        };
        *tally.states.entry(state).or_default() += 1;
        if state != "yes" {
            tally.simulation_s += spec.estimated_seconds();
        }
        // A run the memory budget refuses is not estimated (a large lattice's estimate takes long).
        let stability =
            campaign.budget.refuses(spec).is_none().then(|| plan.estimates.stepped_stability(spec)).flatten();
        let shown =
            |value: fn(&Stability) -> f64| stability.as_ref().map_or("-".into(), |s| format!("{:.4}", value(s)));
        println!(
            "{:<28} {:<8} {:<16} {:>11.4e} {:>11.4e} {:>8.1} {:>10} {:>8} {:>7} {:>7}  {}",
            run_id,
            spec.kind().name(),
            spec.integrator.name(),
            spec.dt,
            spec.t_c,
            spec.dt_per_tc(),
            spec.steps,
            shown(|s| s.dt_omega_max),
            shown(|s| s.limit),
            state,
            spec.varied_label(|_| true)
        );
    }
    tally
}

/// Prints the corrupt records, what `run` would simulate and the estimated cost.
fn print_plan_summary(campaign: &Campaign, layout: &Layout, tally: &PlanTally) {
    let states = &tally.states;
    for (run_id, why) in &tally.corrupt {
        println!(
            "corrupt: {} ({}); `run` simulates it again",
            layout.run_file(run_id).display(),
            escape_for_terminal(why)
        );
    }
    let to_simulate: Vec<String> = [
        ("missing", "without a stored result"),
        ("corrupt", "with a corrupt record"),
        ("stale", "made by another build (--reuse-other-builds keeps them)"),
        ("series", "whose stored series are not the ones output.series asks for (default or full)"),
        ("budget", "stopped by their budget"),
    ]
    .iter()
    .filter_map(|(state, what)| states.get(state).map(|count| format!("{count} {what}")))
    .collect();
    println!(
        "stored: {} runs of this build ({BUILD}); `run` simulates {}{}",
        states.get("yes").copied().unwrap_or(0),
        campaign.runs.len() - states.get("yes").copied().unwrap_or(0),
        if to_simulate.is_empty() { String::new() } else { format!(": {}", to_simulate.join(", ")) }
    );
    let threads = rayon::current_num_threads();
    println!(
        "{} runs; estimated {:.3} s of simulation on one core, about {:.3} s with tables and report on {threads} cores \
         (release build)",
        campaign.runs.len(),
        tally.simulation_s,
        tally.simulation_s / threads as f64 + REPORT_SECONDS
    );
}

/// Warns of every run beyond the campaign's budget per run, before anything runs.
fn print_budget_warnings(campaign: &Campaign) {
    let over: Vec<(String, String)> =
        campaign.runs.iter().filter_map(|spec| campaign.budget.warning(spec).map(|why| (spec.run_id(), why))).collect();
    for (run_id, why) in &over {
        println!("warning: {run_id}: {why}; if it runs that long, it ends with status = budget");
    }
    if !over.is_empty() {
        println!(
            "warning: {} of {} runs exceed the budget per run ({:.0} s, {:.0} MB; campaign field budget:)",
            over.len(),
            campaign.runs.len(),
            campaign.budget.seconds_per_run,
            campaign.budget.memory_per_run / 1e6
        );
    }
}

fn report_command(reports: &Path, file: &Path, force: bool, lock_wait: Option<f64>) -> anyhow::Result<()> {
    let (plan, layout) = open(reports, file)?;
    let campaign = &plan.campaign;
    // Locked before the store is read: a report publishes what is stored when it starts, so it
    // can never overwrite the tables of a `run` that stored more.
    let _publishing = lock_publishing(campaign, &layout, lock_wait)?;
    crate::output::sweep_temporaries(&layout);
    let (records, mut left_out) = stored_for_report(campaign, &layout);
    // A shard that has not run yet, or an array task that died (time limit, node failure):
    // rerunning `run` (or its shard) fills these in, and simulates corrupt records again.
    for (run_id, why) in &left_out.corrupt {
        eprintln!(
            "warning: {} is corrupt ({}); left out of the report",
            layout.run_file(run_id).display(),
            escape_for_terminal(why)
        );
    }
    if records.is_empty() {
        anyhow::bail!(
            "no valid stored results for campaign '{}' under {}: run `mdsolids run {}` first",
            campaign.name,
            layout.root.display(),
            file.display()
        );
    }
    crate::owner::claim(&layout, file, force)?;
    write_missing_movies(&plan, &layout, &records, Default::default())?;
    if records.len() < campaign.runs.len() {
        left_out.previous_table = table::keep_larger_table_aside(&layout, records.len())?;
    }
    publish(campaign, &layout, &records, &left_out)?;
    warn_about_partial_report(campaign, &records, &left_out);
    let other = records.iter().filter(|r| r.build != BUILD).count();
    println!(
        "{}: report re-rendered from {} stored runs ({} without results, {} corrupt, {other} of another build) -> {}",
        campaign.name,
        records.len(),
        left_out.missing.len(),
        left_out.corrupt.len(),
        layout.root.display()
    );
    Ok(())
}

/// The stored records of `campaign` (current or of another build), and the runs left out:
/// those without a record and those whose record is corrupt.
fn stored_for_report(campaign: &Campaign, layout: &Layout) -> (Vec<RunRecord>, report::LeftOut) {
    let (mut records, mut left_out) = (Vec::new(), report::LeftOut::default());
    for spec in &campaign.runs {
        match read_stored(layout, spec) {
            Stored::Current(record) | Stored::OtherBuild(record) | Stored::OtherSeries(record) => records.push(record),
            Stored::Corrupt(why) => left_out.corrupt.push((spec.run_id(), why)),
            Stored::Missing => left_out.missing.push(spec.run_id()),
        }
    }
    (records, left_out)
}

/// Warns on stderr of what a re-rendered report lacks: runs without a result, a partial
/// table (and the larger one kept aside), runs made by another build.
fn warn_about_partial_report(campaign: &Campaign, records: &[RunRecord], left_out: &report::LeftOut) {
    let missing = &left_out.missing;
    if !missing.is_empty() {
        eprintln!(
            "warning: {} of {} runs have no stored result and are not in the report: {}",
            missing.len(),
            campaign.runs.len(),
            listed(missing.iter().map(String::as_str))
        );
    }
    if records.len() < campaign.runs.len() {
        eprintln!(
            "warning: PARTIAL results: results.csv, results.parquet and report.md hold {} of the campaign's {} runs{}",
            records.len(),
            campaign.runs.len(),
            match left_out.previous_table {
                Some(rows) =>
                    format!("; the previous table ({rows} runs) is kept as results.previous.csv and .parquet"),
                None => String::new(),
            }
        );
    }
    let other: Vec<&str> = records.iter().filter(|r| r.build != BUILD).map(|r| r.run_id.as_str()).collect();
    if !other.is_empty() {
        eprintln!(
            "warning: {} runs in the report were made by another build than this one ({BUILD}); marked in the table \
             (other_build) and the report; `mdsolids run` simulates them again: {}",
            other.len(),
            listed(other.iter().copied())
        );
    }
}

/// What `mdsolids slurm` was asked for.
struct SlurmRequest {
    tasks: usize,
    partition: Option<String>,
    time: Option<String>,
    cpus_per_task: usize,
    submit: bool,
    force: bool,
}

fn slurm_command(reports: &Path, file: &Path, request: &SlurmRequest) -> anyhow::Result<()> {
    let (plan, layout) = open(reports, file)?;
    let campaign = &plan.campaign;
    anyhow::ensure!(
        (1..=campaign.runs.len()).contains(&request.tasks),
        "--tasks {}: must be between 1 and the campaign's {} runs",
        request.tasks,
        campaign.runs.len()
    );
    crate::owner::claim(&layout, file, request.force)?;
    let job = crate::slurm::ArrayJob {
        exe: std::env::current_exe().context("cannot locate the mdsolids binary")?,
        reports: std::path::absolute(reports)
            .with_context(|| format!("cannot make '{}' absolute", reports.display()))?,
        campaign_file: std::fs::canonicalize(file).with_context(|| format!("cannot resolve '{}'", file.display()))?,
        campaign: campaign.name.clone(),
        tasks: request.tasks,
        partition: request.partition.clone(),
        time: request.time.clone(),
        cpus_per_task: request.cpus_per_task,
    };
    let scripts = crate::slurm::write_scripts(&job)?;
    let mut loads = vec![0.0; request.tasks];
    for (spec, shard) in campaign.runs.iter().zip(shard_of_each_run(&campaign.runs, request.tasks)) {
        loads[shard] += spec.estimated_seconds();
    }
    println!(
        "{}: {} runs in {} array tasks, estimated at most {:.3} s of simulation per task on one core \
         (release build); scripts in {}",
        campaign.name,
        campaign.runs.len(),
        request.tasks,
        loads.iter().copied().fold(0.0, f64::max),
        scripts.submit.parent().unwrap_or(Path::new(".")).display()
    );
    if request.submit {
        let submitted = crate::slurm::submit(&scripts)?;
        println!("submitted: array job {}, report job {} (afterany)", submitted.array, submitted.report);
    } else {
        println!("submit with: bash {}", scripts.submit.display());
    }
    Ok(())
}

fn publish(
    campaign: &Campaign,
    layout: &Layout,
    records: &[crate::runner::RunRecord],
    left_out: &report::LeftOut,
) -> anyhow::Result<()> {
    let mut frame = table::results_frame(records).context("cannot build the results table")?;
    table::write_tables(layout, &mut frame)?;
    let fits = crate::summary::scaling_fits(records);
    let packings = crate::summary::jamming::fits(records);
    table::write_summary(layout, &[fits.as_slice(), &packings].concat())?;
    report::render_with_left_out(campaign, layout, records, &fits, left_out)
}

/// A lattice type by its name (`--lattice`).
fn lattice_type(name: &str) -> Result<LatticeType, String> {
    LatticeType::ALL.into_iter().find(|t| t.name() == name).ok_or_else(|| {
        let names: Vec<&str> = LatticeType::ALL.iter().map(|t| t.name()).collect();
        format!("`{name}`: one of {}", names.join(", "))
    })
}

fn bench_command(configs: &[BenchConfig], threads: Option<usize>, repeat: usize, json: bool) -> anyhow::Result<()> {
    anyhow::ensure!(!configs.is_empty(), "--workload: name at least one");
    let config = &configs[0];
    anyhow::ensure!(config.steps >= 1 && repeat >= 1, "--steps and --repeat must be ≥ 1");
    anyhow::ensure!(repeat <= 100, "--repeat {repeat}: at most 100 timed repetitions");
    anyhow::ensure!((0.0..1.0).contains(&config.dilute), "--dilute {}: must be in [0, 1)", config.dilute);
    for config in configs {
        if config.workload == Workload::Packing {
            // The most discs a packing campaign may hold.
            anyhow::ensure!(
                (2..=10_000_000).contains(&config.n),
                "--n {}: the packing's discs must be in 2..=10000000",
                config.n
            );
            continue;
        }
        // The largest lattice a campaign may hold (2000 × 2000): a larger N aborted on allocation.
        anyhow::ensure!((2..=2000).contains(&config.n), "--n {}: the lattice side must be in 2..=2000", config.n);
        let rows = config.rows();
        if let Some((_, rule)) = PlanarLattice::size_problem(config.lattice, config.n, rows, false) {
            anyhow::bail!("--n {} --lattice {}: {rule}", config.n, config.lattice.name());
        }
    }
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads.unwrap_or(0)).build()?;
    // Repetitions alternate between the workloads, so a machine's drift touches all alike.
    let mut results: Vec<Vec<BenchResult>> = vec![Vec::new(); configs.len()];
    for _ in 0..repeat {
        for (config, runs) in configs.iter().zip(&mut results) {
            runs.push(pool.install(|| run_once(config)));
        }
    }
    let medians: Vec<BenchResult> = results
        .into_iter()
        .map(|mut runs| {
            runs.sort_by(|a, b| a.particle_steps_per_s.total_cmp(&b.particle_steps_per_s));
            runs.swap_remove(runs.len() / 2)
        })
        .collect();
    for median in &medians {
        print_bench(median, repeat, json)?;
    }
    if !json && let [first, .., last] = &medians[..] {
        let ratio = last.particle_steps_per_s / first.particle_steps_per_s;
        let name = |r: &BenchResult| format!("{} {}", r.lattice.name(), r.workload.name());
        println!("{}/{} particle-steps/s: {ratio:.3}", name(last), name(first));
    }
    Ok(())
}

/// Prints one workload's median as text or one JSON line.
fn print_bench(median: &BenchResult, repeat: usize, json: bool) -> anyhow::Result<()> {
    if json {
        println!("{}", serde_json::to_string(median)?);
    } else {
        println!(
            "{} {}: N = {} ({} particles, {} bonds, {} path), {} steps on {} thread(s), median of {repeat}:\n  \
             {:.1} million particle-steps/s, {:.1} million bond-updates/s, {:.3} s, energy drift {:+.2e}",
            median.lattice.name(),
            median.workload.name(),
            median.n,
            median.particles,
            median.bonds,
            median.path,
            median.steps,
            median.threads,
            median.particle_steps_per_s / 1e6,
            median.bond_updates_per_s / 1e6,
            median.wall_s,
            median.energy_drift
        );
    }
    Ok(())
}

fn compare_command(reports: &Path, a: &Path, b: &Path, out: Option<&Path>) -> anyhow::Result<()> {
    let done = crate::compare::compare(a, b, out, reports)?;
    println!(
        "{} against {}: {} joined rows, {} figures, {} fitted exponents -> {}",
        a.display(),
        b.display(),
        done.rows,
        done.plots,
        done.exponents,
        done.out.display()
    );
    Ok(())
}
