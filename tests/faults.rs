//! Faults: a campaign killed (SIGKILL) at random moments and rerun ends with the table of an
//! uninterrupted run; two processes on one store do every run once; a result that cannot be
//! written stops the campaign with a clear error and keeps what was stored; runs beyond their
//! budget end with `status = budget`.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// 24 chain runs of a few tens of ms each: long enough to be killed in the middle.
const CAMPAIGN: &str = "version: 1\nname: faults\ndefaults:\n  material: {mass: 1.0, k: 1.0}\nscenes:\n  \
    - name: chain\n    kind: chain\n    v0: 0.1\n    time: {duration_tc: 400, samples: 50}\n    grid:\n      \
    n: [40, 60, 80, 100, 120, 140]\n      damping.restitution: [1.0, 0.9, 0.7, 0.5]\n";
const RUNS: usize = 24;

fn mdsolids(reports: &Path, args: &[&str]) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_mdsolids"));
    command.arg("--reports").arg(reports).args(args).stdout(Stdio::piped()).stderr(Stdio::piped());
    command
}

/// Writes the campaign file into `dir` and returns its path.
fn campaign_file(dir: &Path, text: &str) -> PathBuf {
    let path = dir.join("faults.yaml");
    std::fs::write(&path, text).unwrap();
    path
}

/// `results.csv` without the columns that time the runs (they differ from run to run).
fn table(reports: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(reports.join("faults/results.csv")).unwrap();
    let rows: Vec<Vec<String>> = text.lines().map(|l| l.split(',').map(str::to_string).collect()).collect();
    let keep: Vec<bool> = rows[0].iter().map(|name| name != "wall_s" && name != "loop_s").collect();
    rows.iter().map(|row| row.iter().zip(&keep).filter(|(_, k)| **k).map(|(v, _)| v.clone()).collect()).collect()
}

/// The stored run records: file names, each parsed once.
fn stored(reports: &Path) -> Vec<String> {
    let dir = reports.join("faults/runs");
    let Ok(entries) = std::fs::read_dir(&dir) else { return Vec::new() };
    let mut names: Vec<String> = entries
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|name| name.ends_with(".json") && !name.starts_with('.'))
        .collect();
    for name in &names {
        let text = std::fs::read_to_string(dir.join(name)).unwrap();
        let record: mdsolids::runner::RunRecord = serde_json::from_str(&text).expect("a stored record is whole");
        assert_eq!(format!("{}.json", record.run_id), *name);
    }
    names.sort();
    names
}

/// Waits (polling every 2 ms, at most 60 s) until `count` records are stored under
/// `reports`; returns the time waited.
fn wait_for_records(reports: &Path, count: usize) -> Duration {
    let started = Instant::now();
    while count_records(reports) < count {
        assert!(started.elapsed() < Duration::from_secs(60), "{count} records never appeared");
        std::thread::sleep(Duration::from_millis(2));
    }
    started.elapsed()
}

/// The number of stored records, without reading them (they may be being written).
fn count_records(reports: &Path) -> usize {
    std::fs::read_dir(reports.join("faults/runs")).map_or(0, |entries| {
        entries
            .filter(|e| {
                let name = e.as_ref().unwrap().file_name().to_string_lossy().to_string();
                name.ends_with(".json") && !name.starts_with('.')
            })
            .count()
    })
}

/// "(N simulated, M cached" from a run's summary line.
fn simulated(output: &std::process::Output) -> usize {
    let text = String::from_utf8_lossy(&output.stdout).to_string() + &String::from_utf8_lossy(&output.stderr);
    let at = text.find(" simulated").unwrap_or_else(|| panic!("no summary in {text}"));
    text[..at].rsplit('(').next().unwrap().trim().parse().unwrap()
}

/// A small linear congruential generator: reproducible kill times from a printed seed.
struct Lcg(u64);
impl Lcg {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn a_campaign_killed_at_random_moments_reruns_to_the_uninterrupted_table() {
    let dir = tempfile::tempdir().unwrap();
    let file = campaign_file(dir.path(), CAMPAIGN);
    let reference = dir.path().join("reference");
    let out = mdsolids(&reference, &["run", file.to_str().unwrap(), "-j", "2"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let expected = table(&reference);
    let expected_runs = stored(&reference);
    assert_eq!(expected_runs.len(), RUNS);
    let seed = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap().as_nanos() as u64;
    println!("kill times from seed {seed}");
    let mut rng = Lcg(seed);
    let (trials, mut in_the_middle) = (20, 0);
    for trial in 0..trials {
        let reports = dir.path().join(format!("trial-{trial}"));
        // One to three kills in a row.
        for _ in 0..1 + trial % 3 {
            let mut child = mdsolids(&reports, &["run", file.to_str().unwrap(), "-j", "2"]).spawn().unwrap();
            // A random moment while it works: once a random number of further runs is stored
            // (at least one, never all), plus up to 5 ms.
            let held = stored(&reports).len();
            if held + 1 < RUNS {
                let target = held + 1 + (rng.uniform() * (RUNS - 1 - held) as f64) as usize;
                wait_for_records(&reports, target);
            }
            std::thread::sleep(Duration::from_secs_f64(0.005 * rng.uniform()));
            child.kill().unwrap(); // SIGKILL
            child.wait().unwrap();
            let count = stored(&reports).len();
            in_the_middle += usize::from(count > 0 && count < RUNS);
        }
        let out = mdsolids(&reports, &["run", file.to_str().unwrap(), "-j", "2"]).output().unwrap();
        assert!(out.status.success(), "trial {trial}: {}", String::from_utf8_lossy(&out.stderr));
        assert_eq!(stored(&reports), expected_runs, "trial {trial}: every run stored exactly once");
        assert_eq!(table(&reports), expected, "trial {trial}: the table of an uninterrupted run");
    }
    println!("{trials} trials, {in_the_middle} kills with some but not all runs stored");
    // Not vacuous: most kills must land while the campaign runs.
    assert!(in_the_middle >= 15, "only {in_the_middle} kills landed in the middle of a campaign");
}

#[test]
fn two_processes_on_one_store_run_every_run_once() {
    let dir = tempfile::tempdir().unwrap();
    let file = campaign_file(dir.path(), CAMPAIGN);
    let reports = dir.path().join("shared");
    let run = || mdsolids(&reports, &["run", file.to_str().unwrap(), "-j", "2"]).spawn().unwrap();
    let (a, b) = (run(), run());
    let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
    assert!(a.status.success() && b.status.success(), "{}", String::from_utf8_lossy(&b.stderr));
    // The run locks: each run simulated by exactly one of the two processes.
    assert_eq!(simulated(&a) + simulated(&b), RUNS);
    assert_eq!(stored(&reports).len(), RUNS);
    let reference = dir.path().join("reference");
    assert!(mdsolids(&reference, &["run", file.to_str().unwrap()]).output().unwrap().status.success());
    assert_eq!(table(&reports), table(&reference));
}

#[test]
fn a_result_that_cannot_be_written_stops_the_campaign_and_keeps_the_stored_ones() {
    let dir = tempfile::tempdir().unwrap();
    let reports = dir.path().join("reports");
    // First half of the grid, stored.
    let first = CAMPAIGN.replace("n: [40, 60, 80, 100, 120, 140]", "n: [40, 60, 80]");
    let file = campaign_file(dir.path(), &first);
    assert!(mdsolids(&reports, &["run", file.to_str().unwrap()]).output().unwrap().status.success());
    let before: Vec<(String, Vec<u8>)> = stored(&reports)
        .into_iter()
        .map(|name| {
            let bytes = std::fs::read(reports.join("faults/runs").join(&name)).unwrap();
            (name, bytes)
        })
        .collect();
    // The whole grid, with a directory where one new record must go: its rename fails (as a
    // full disk or a read-only folder would fail it; a directory fails even for root).
    let file = campaign_file(dir.path(), CAMPAIGN);
    let campaign = mdsolids::stability::parse_campaign("faults.yaml", CAMPAIGN).unwrap();
    let blocked = campaign.runs.iter().map(|r| r.run_id()).find(|id| !before.iter().any(|(n, _)| n.starts_with(id)));
    let blocked = reports.join("faults/runs").join(format!("{}.json", blocked.unwrap()));
    std::fs::create_dir_all(blocked.join("in-the-way")).unwrap();
    let out = mdsolids(&reports, &["run", file.to_str().unwrap(), "-j", "1"]).output().unwrap();
    assert!(!out.status.success());
    let error = String::from_utf8_lossy(&out.stderr);
    assert!(
        error.contains("stopped") && error.contains("cannot move") && error.contains(blocked.to_str().unwrap()),
        "{error}"
    );
    for (name, bytes) in &before {
        assert_eq!(&std::fs::read(reports.join("faults/runs").join(name)).unwrap(), bytes, "{name} intact");
    }
    // No partial file left behind.
    let leftovers = std::fs::read_dir(reports.join("faults/runs"))
        .unwrap()
        .filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().ends_with(".tmp"))
        .count();
    assert_eq!(leftovers, 0);
}

#[test]
fn runs_beyond_their_budget_end_with_status_budget_and_plan_warns() {
    use mdsolids::runner::execute_within;
    use mdsolids::spec::Budget;
    let runs = common::runs(
        "version: 1\nname: b\nscenes:\n  - name: long\n    kind: chain\n    n: 2000\n    v0: 0.1\n    \
         time: {duration_tc: 100000}\n",
    );
    // Memory: 2000 particles × 400 samples × 4 numbers ≈ 26 MB recorded; a 1 MB budget refuses it
    // before it starts.
    let tight = Budget { seconds_per_run: 3600.0, memory_per_run: 1e6 };
    let r = execute_within(&runs[0], &tight);
    assert_eq!(r.status, "budget");
    assert!(r.message.contains("budget.memory_per_run_mb") && r.steps == 0, "{}", r.message);
    // Time: ~1e10 particle-steps would take minutes; a 0.2 s budget stops it (the bound below
    // is a hang guard, not a speed test).
    let started = Instant::now();
    let r = execute_within(&runs[0], &Budget { seconds_per_run: 0.2, memory_per_run: 4e9 });
    assert_eq!(r.status, "budget", "{}", r.message);
    assert!(r.message.contains("time budget") && r.steps > 0 && r.steps < runs[0].steps, "{}", r.message);
    assert!(started.elapsed() < Duration::from_secs(30));
    // The plan warns before anything runs.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("b.yaml");
    std::fs::write(
        &file,
        "version: 1\nname: b\nbudget: {seconds_per_run: 0.5}\nscenes:\n  - name: long\n    kind: chain\n    \
         n: 2000\n    v0: 0.1\n    time: {duration_tc: 100000}\n",
    )
    .unwrap();
    let out = mdsolids(dir.path(), &["plan", file.to_str().unwrap()]).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("warning") && text.contains("budget.seconds_per_run"), "{text}");
    // A budget must be a positive number.
    let error = mdsolids::stability::parse_campaign(
        "b.yaml",
        "version: 1\nname: b\nbudget: {seconds_per_run: 0}\nscenes:\n  - name: p\n    kind: pair\n    v0: 1.0\n",
    )
    .unwrap_err()
    .to_string();
    assert!(error.contains("b.yaml") && error.contains("budget.seconds_per_run"), "{error}");
}
