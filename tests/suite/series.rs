//! A run's series as Parquet tables (issue 32, part 3): `series/<run_id>.parquet` and
//! `series/<run_id>.particles.parquet` beside `probes/<run_id>.parquet`, what they keep by
//! default and with `output.series: full`, what the store does when a campaign switches between
//! the two, the budget of a full run, and the Python snippets of docs/data.md run against a
//! campaign's folder.

use polars::prelude::{DataFrame, DataType, ParquetReader, SerReader};
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::{mdsolids_ok, text};

fn table(path: &Path) -> DataFrame {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    ParquetReader::new(file).finish().unwrap()
}

/// Column names and types of `frame`.
fn columns(frame: &DataFrame) -> Vec<(String, DataType)> {
    frame.columns().iter().map(|c| (c.name().to_string(), c.dtype().clone())).collect()
}

/// A chain, an impulse lattice probing its bottom row and a loaded lattice: the three kinds of
/// particle tables (every particle, the kicked column, none), `SERIES` in the defaults.
const CAMPAIGN: &str = "version: 1\nname: kept\ndefaults:SERIES\nscenes:\n  - name: chain\n    kind: chain\n    \
    n: 5\n    v0: 0.1\n    time: {duration_tc: 4, samples: 30}\n  - name: kick\n    kind: lattice\n    \
    lattice: {nx: 5, ny: 4}\n    supports: free\n    impulse: {velocity: [0.0, -0.1]}\n    probes: {rows: [bottom]}\n    \
    time: {duration_tc: 4, samples: 20}\n  - name: loaded\n    kind: lattice\n    lattice: {size: 3}\n    \
    damping: {restitution: 0.5, background: 1.0}\n    load: {per_node: 0.01}\n    relax: {max_tc: 400}\n";

/// The run ids of `folder`'s results, in table order, by scene.
fn run_ids(folder: &Path) -> Vec<(String, String)> {
    let results = table(&folder.join("results.parquet"));
    let words = |name: &str| -> Vec<String> {
        results.column(name).unwrap().str().unwrap().iter().map(|s| s.unwrap().to_string()).collect()
    };
    words("scene").into_iter().zip(words("run_id")).collect()
}

/// `results.parquet` without the columns that change from run to run (times, build).
fn results_without_times(folder: &Path) -> DataFrame {
    table(&folder.join("results.parquet")).drop_many(["wall_s", "loop_s", "solve_s", "build"])
}

fn particles_of(folder: &Path, run_id: &str) -> PathBuf {
    folder.join("series").join(format!("{run_id}.particles.parquet"))
}

/// Guards issue 32, part 3: a chain's velocities and y displacements were dropped and a run's
/// series were kept in a format only mdsolids read. By default the particle table holds a
/// chain's every particle (x and y displacements, y velocities: a chain's y columns are zero)
/// and an impulse lattice's kicked column (its displacement along the kick); with
/// `output.series: full` every particle's four series at every sample, in double precision.
/// Switching keeps the run ids and the results, simulates the runs again once for the tables
/// asked for (`plan` says so), and switching back leaves no full table behind.
#[test]
fn full_series_keep_every_particle_and_switching_simulates_the_runs_again() {
    let dir = crate::common::scratch();
    let (file, reports) = (dir.path().join("kept.yaml"), dir.path().join("reports"));
    let (file_arg, folder) = (file.to_str().unwrap(), reports.join("kept"));
    let write = |series: &str| std::fs::write(&file, CAMPAIGN.replace("SERIES", series)).unwrap();
    write(" {}");
    mdsolids_ok(&reports, &["run", file_arg]);
    let ids = run_ids(&folder);
    let [(_, chain), (_, kick), (_, loaded)] = ids.clone().try_into().unwrap();
    let default_results = results_without_times(&folder);
    let kept = table(&particles_of(&folder, &chain));
    let f32 = |name: &str| (name.to_string(), DataType::Float32);
    let head = [("time".to_string(), DataType::Float64), ("particle".to_string(), DataType::UInt32)];
    let expected = [head.to_vec(), vec![f32("displacement_x"), f32("displacement_y"), f32("velocity_y")]].concat();
    assert_eq!(columns(&kept), expected);
    let samples = table(&folder.join("series").join(format!("{chain}.parquet"))).height();
    assert_eq!(kept.height(), 7 * samples, "every particle of the chain, walls included");
    let kicked = table(&particles_of(&folder, &kick));
    assert_eq!(columns(&kicked), [head.to_vec(), vec![f32("displacement_y")]].concat());
    let nodes: Vec<u32> = kicked.column("particle").unwrap().u32().unwrap().into_no_null_iter().collect();
    assert_eq!(nodes[0], 4, "the kicked column (the right one), bottom node first");
    assert!(!particles_of(&folder, &loaded).exists(), "a loaded lattice keeps no particle's series");

    write("\n  output: {series: full}");
    let plan = text(&mdsolids_ok(&reports, &["plan", file_arg]).stdout);
    assert!(plan.contains("`run` simulates 3: 3 whose stored series are not the ones output.series asks"), "{plan}");
    let run = mdsolids_ok(&reports, &["run", file_arg]);
    assert!(text(&run.stdout).contains("(3 simulated, 0 cached"), "{}", text(&run.stdout));
    assert!(text(&run.stderr).contains("3 stored runs kept other series than output.series asks"));
    assert_eq!(run_ids(&folder), ids, "the same runs, under the same ids");
    assert!(results_without_times(&folder).equals_missing(&default_results), "the same results");
    let f64 = |name: &str| (name.to_string(), DataType::Float64);
    let motions = ["displacement_x", "displacement_y", "velocity_x", "velocity_y"].map(f64).to_vec();
    for (run_id, particles) in [(&chain, 7), (&kick, 20), (&loaded, 9)] {
        let full = table(&particles_of(&folder, run_id));
        assert_eq!(columns(&full), [head.to_vec(), motions.clone()].concat(), "{run_id}");
        let samples = table(&folder.join("series").join(format!("{run_id}.parquet"))).height();
        assert_eq!(full.height(), particles * samples, "{run_id}: every particle at every sample");
    }
    // The report drawn at the end of `run` is the one `report` draws from the store.
    let drawn = std::fs::read(folder.join("report.md")).unwrap();
    mdsolids_ok(&reports, &["report", file_arg]);
    assert_eq!(std::fs::read(folder.join("report.md")).unwrap(), drawn);
    let again = mdsolids_ok(&reports, &["run", file_arg]);
    assert!(text(&again.stdout).contains("(0 simulated, 3 cached"), "{}", text(&again.stdout));

    write(" {}");
    let back = mdsolids_ok(&reports, &["run", file_arg]);
    assert!(text(&back.stdout).contains("(3 simulated, 0 cached"), "{}", text(&back.stdout));
    assert_eq!(columns(&table(&particles_of(&folder, &chain))), expected);
    assert!(!particles_of(&folder, &loaded).exists(), "the full table is removed with the record naming it");
}

/// A full series beyond the run's memory budget: the run is not started, and the message says
/// that the full series are what the budget cannot hold (`plan` warns before anything runs).
#[test]
fn a_full_series_beyond_the_memory_budget_is_refused_saying_so() {
    let yaml = |output: &str| {
        format!(
            "version: 1\nname: big\nbudget: {{memory_per_run_mb: 400}}\nscenes:\n  - name: c\n    kind: chain\n    \
             n: 1000\n    v0: 0.1\n    time: {{duration_tc: 50, samples: 3000}}\n{output}"
        )
    };
    let runs = |output: &str| mdsolids::plan::parse("big.yaml", &yaml(output)).unwrap().campaign;
    let default = runs("");
    assert_eq!(default.budget.refuses(&default.runs[0]), None);
    let full = runs("    output: {series: full}\n");
    let why = full.budget.refuses(&full.runs[0]).expect("beyond the budget");
    assert!(why.contains("output.series: full") && why.contains("budget.memory_per_run_mb"), "{why}");
    let record = mdsolids::runner::execute_within(&full.runs[0], &full.budget, &Default::default());
    assert_eq!(record.status, mdsolids::sim::RunStatus::Budget);
    assert!(record.message.contains("output.series: full"), "{}", record.message);
}

/// The Python interpreter the docs' snippets run with: `MDSOLIDS_PYTHON` (`.ci/run` sets up
/// one with pandas, polars and pyarrow), else `python3`.
fn python() -> String {
    std::env::var("MDSOLIDS_PYTHON").unwrap_or_else(|_| "python3".into())
}

/// The ```python blocks of `markdown`, in order.
fn python_blocks(markdown: &str) -> Vec<String> {
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in markdown.lines() {
        match (&mut current, line.trim_start()) {
            (None, "```python") => current = Some(String::new()),
            (Some(_), "```") => blocks.extend(current.take()),
            (Some(block), _) => block.push_str(&format!("{line}\n")),
            (None, _) => {}
        }
    }
    blocks
}

/// A small campaign named like the coursework, with the scenes the snippets read.
const DOCS_CAMPAIGN: &str = "version: 1\nname: coursework\nscenes:\n  - name: chain\n    kind: chain\n    n: 11\n    \
    v0: 0.1\n    time: {duration_tc: 4, samples: 40}\n  - name: lattice-impulse\n    kind: lattice\n    \
    lattice: {size: 6, k_diag_ratio: 0.5}\n    supports: free\n    impulse: {node: top-right, velocity: [0.0, -0.1]}\n    \
    wave: {}\n    probes: {rows: [centre, bottom], columns: [centre]}\n    time: {duration_tc: 6, samples: 40}\n";

/// Guards the docs: every ```python block of docs/data.md runs, as written, against a campaign
/// folder `reports/coursework/` (pandas, polars and pyarrow; taken from the page, so the page
/// and this test cannot drift apart). Where those modules are missing it fails under CI
/// (`CI` set, as `.ci/run` does) and says it skips elsewhere.
#[test]
fn the_python_snippets_of_the_data_page_run() {
    let check = Command::new(python()).args(["-c", "import pandas, polars, pyarrow"]).output();
    if !check.as_ref().is_ok_and(|out| out.status.success()) {
        let why = match &check {
            Ok(out) => text(&out.stderr),
            Err(error) => format!("cannot start {}: {error}", python()),
        };
        assert!(std::env::var_os("CI").is_none(), "pandas, polars and pyarrow are needed (pip install): {why}");
        eprintln!("SKIPPED the_python_snippets_of_the_data_page_run: pandas, polars and pyarrow are not there: {why}");
        return;
    }
    let dir = crate::common::scratch();
    std::fs::write(dir.path().join("coursework.yaml"), DOCS_CAMPAIGN).unwrap();
    let campaign = dir.path().join("coursework.yaml");
    mdsolids_ok(&dir.path().join("reports"), &["run", campaign.to_str().unwrap()]);
    let page = std::fs::read_to_string(crate::common::repo().join("docs/data.md")).unwrap();
    let blocks = python_blocks(&page);
    assert!(blocks.len() >= 2, "docs/data.md has {} python blocks", blocks.len());
    for (index, block) in blocks.iter().enumerate() {
        let out = Command::new(python()).args(["-c", block]).current_dir(dir.path()).output().unwrap();
        assert!(out.status.success(), "block {} of docs/data.md:\n{block}\n{}", index + 1, text(&out.stderr));
    }
}
