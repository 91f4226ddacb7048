//! Faults: a campaign killed (SIGKILL) at random moments and rerun ends with the report folder
//! of an uninterrupted run, movies included; two processes on one store do every run once; a
//! run locked by another process is waited for last, saying so, and given up after a stated
//! time; a report racing a run never publishes less than is stored; Ctrl-C says how many runs
//! are stored; a result that cannot be written (also a movie on a full disk) stops the campaign
//! with an error naming the file and leaves no partial file; runs beyond their budget end with
//! `status = budget`.

use crate::common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use mdsolids::sim::RunStatus;

/// 24 chain runs of a few tens of ms each (long enough to be killed in the middle), and two
/// small chains with movies, also shown side by side.
const CAMPAIGN: &str = "version: 1\nname: faults\ndefaults:\n  material: {mass: 1.0, k: 1.0}\nscenes:\n  \
    - name: chain\n    kind: chain\n    v0: 0.1\n    time: {duration_tc: 400, samples: 50}\n    grid:\n      \
    n: [40, 60, 80, 100, 120, 140]\n      damping.restitution: [1.0, 0.9, 0.7, 0.5]\n  \
    - name: film\n    kind: chain\n    n: 6\n    v0: 0.1\n    time: {duration_tc: 10, samples: 20}\n    \
    movie: {frames: 4, width: 200, height: 100, side_by_side: true}\n    grid:\n      node: [first, last]\n";
const RUNS: usize = 26;

fn mdsolids(reports: &Path, args: &[&str]) -> Command {
    let mut command = Command::new(crate::common::MDSOLIDS);
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
    let keep: Vec<bool> =
        rows[0].iter().map(|name| !["wall_s", "loop_s", "solve_s"].contains(&name.as_str())).collect();
    rows.iter().map(|row| row.iter().zip(&keep).filter(|(_, k)| **k).map(|(v, _)| v.clone()).collect()).collect()
}

/// Every file of the campaign's folder (path relative to it) with what must be the same after
/// an interrupted campaign is rerun as after an uninterrupted one: its bytes, but for the run
/// times, which differ from run to run: `wall_s`, `loop_s` and `solve_s` are taken out of the records and
/// tables, and every decimal number is masked in the report's text (`report.md`, `index.html`:
/// its words, tables, figure and movie links stay). Movies, figures, lock files, everything
/// else: byte for byte.
fn folder(reports: &Path) -> BTreeMap<String, Vec<u8>> {
    let root = reports.join("faults");
    let (mut files, mut dirs) = (BTreeMap::new(), vec![root.clone()]);
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                dirs.push(path);
                continue;
            }
            let name = path.strip_prefix(&root).unwrap().to_string_lossy().to_string();
            let bytes = std::fs::read(&path).unwrap();
            let normalised = if name.starts_with("runs/") && name.ends_with(".json") {
                let mut record: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
                without_times(&mut record);
                serde_json::to_vec(&record).unwrap()
            } else if name == "results.csv" {
                format!("{:?}", table(reports)).into_bytes()
            } else if name == "results.parquet" {
                use polars::prelude::{CsvWriter, ParquetReader, SerReader, SerWriter};
                let frame = ParquetReader::new(std::fs::File::open(&path).unwrap()).finish().unwrap();
                let (mut csv, mut frame) = (Vec::new(), frame.drop_many(["wall_s", "loop_s", "solve_s"]));
                CsvWriter::new(&mut csv).finish(&mut frame).unwrap();
                csv
            } else if name.ends_with(".md") || name.ends_with(".html") {
                masked_decimals(&String::from_utf8(bytes).unwrap()).into_bytes()
            } else {
                bytes
            };
            files.insert(name, normalised);
        }
    }
    files
}

/// Removes the timing fields `wall_s`, `loop_s` and `solve_s` wherever they are.
fn without_times(value: &mut serde_json::Value) {
    match value {
        serde_json::Value::Object(map) => {
            map.remove("wall_s");
            map.remove("loop_s");
            map.remove("solve_s");
            map.values_mut().for_each(without_times);
        }
        serde_json::Value::Array(items) => items.iter_mut().for_each(without_times),
        _ => {}
    }
}

/// `text` with every decimal number (digits with a point, and an exponent if it has one)
/// replaced by `#`: the same time prints as `0.000981` or `9.81e-4` by its size.
fn masked_decimals(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let (mut out, mut i) = (String::new(), 0);
    while i < chars.len() {
        let start = i;
        while i < chars.len() && (chars[i].is_ascii_digit() || (chars[i] == '.' && i > start)) {
            i += 1;
        }
        let number: String = chars[start..i].iter().collect();
        let number = number.trim_end_matches('.');
        i = start + number.len();
        if number.contains('.') {
            out.push('#');
            // The exponent, if one follows: e, an optional sign, digits.
            let mut j = i + 1;
            if chars.get(i) == Some(&'e') {
                j += usize::from(matches!(chars.get(j), Some('+' | '-')));
                if chars.get(j).is_some_and(char::is_ascii_digit) {
                    i = j;
                    while chars.get(i).is_some_and(char::is_ascii_digit) {
                        i += 1;
                    }
                }
            }
        } else if number.is_empty() {
            out.push(chars[i]);
            i += 1;
        } else {
            out.push_str(number);
        }
    }
    out
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
    let dir = crate::common::scratch();
    let file = campaign_file(dir.path(), CAMPAIGN);
    let reference = dir.path().join("reference");
    let out = mdsolids(&reference, &["run", file.to_str().unwrap(), "-j", "2"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let expected = table(&reference);
    let masked = masked_decimals("t = 0.000981 s, 9.81e-4 s, +6.42e-4, 1e-3, run a1b2, 3.");
    assert_eq!(masked, "t = # s, # s, +#, 1e-3, run a1b2, 3.");
    let expected_folder = folder(&reference);
    assert!(expected_folder.contains_key("plots/film-side-by-side.gif"), "the campaign has a side-by-side movie");
    let expected_runs = stored(&reference);
    assert_eq!(expected_runs.len(), RUNS);
    let seed = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap().as_nanos() as u64;
    println!("kill times from seed {seed}");
    let mut rng = Lcg(seed);
    let (trials, mut in_the_middle) = (12, 0);
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
        let got = folder(&reports);
        let names = |f: &BTreeMap<String, Vec<u8>>| f.keys().cloned().collect::<Vec<_>>();
        assert_eq!(names(&got), names(&expected_folder), "trial {trial}: the same files");
        for (name, bytes) in &expected_folder {
            let first_difference = || {
                let (a, b) = (String::from_utf8_lossy(&got[name]), String::from_utf8_lossy(bytes));
                a.lines().zip(b.lines()).find(|(x, y)| x != y).map(|(x, y)| format!("{x}\n  instead of\n{y}"))
            };
            assert!(got[name] == *bytes, "trial {trial}: {name} differs: {:?}", first_difference());
        }
    }
    println!("{trials} trials, {in_the_middle} kills with some but not all runs stored");
    // Not vacuous: most kills must land while the campaign runs.
    assert!(in_the_middle >= 15, "only {in_the_middle} kills landed in the middle of a campaign");
}

#[test]
fn two_processes_on_one_store_run_every_run_once() {
    let dir = crate::common::scratch();
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
    let dir = crate::common::scratch();
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
    let campaign = mdsolids::plan::parse("faults.yaml", CAMPAIGN).unwrap().campaign;
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
    let r = execute_within(&runs[0], &tight, &Default::default());
    assert_eq!(r.status, RunStatus::Budget);
    assert!(r.message.contains("budget.memory_per_run_mb") && r.steps == 0, "{}", r.message);
    // Time: ~1e10 particle-steps would take minutes; a 0.2 s budget stops it (the bound below
    // is a hang guard, not a speed test).
    let started = Instant::now();
    let r = execute_within(&runs[0], &Budget { seconds_per_run: 0.2, memory_per_run: 4e9 }, &Default::default());
    assert_eq!(r.status, RunStatus::Budget, "{}", r.message);
    assert!(r.message.contains("time budget") && r.steps > 0 && r.steps < runs[0].steps, "{}", r.message);
    assert!(started.elapsed() < Duration::from_secs(30));
    // The plan warns before anything runs.
    let dir = crate::common::scratch();
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
    // A budget below 10 s is written to the millisecond (0.5 s had read "0 s").
    assert!(text.contains("beyond the budget of 0.500 s per run"), "{text}");
    // A budget must be a positive number.
    let error = mdsolids::plan::parse(
        "b.yaml",
        "version: 1\nname: b\nbudget: {seconds_per_run: 0}\nscenes:\n  - name: p\n    kind: pair\n    v0: 1.0\n",
    )
    .unwrap_err()
    .to_string();
    assert!(error.contains("b.yaml") && error.contains("budget.seconds_per_run"), "{error}");
}

/// Waits for `child` at most `limit`; kills it and fails if it is still running then.
fn wait_at_most(mut child: std::process::Child, limit: Duration, what: &str) -> std::process::Output {
    let started = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if started.elapsed() > limit {
            child.kill().unwrap();
            panic!("{what}: still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

#[test]
fn a_run_locked_by_another_process_is_left_for_last_and_given_up_after_the_stated_time() {
    // Another process (here: this test) holds the lock of the longest run, as a suspended
    // `mdsolids run` would. With one thread, the longest run comes first.
    let dir = crate::common::scratch();
    let file = campaign_file(dir.path(), CAMPAIGN);
    let reports = dir.path().join("reports");
    let campaign = mdsolids::plan::parse("faults.yaml", CAMPAIGN).unwrap().campaign;
    let layout = mdsolids::output::Layout::new(&reports, &campaign.name);
    let longest = campaign.runs.iter().max_by(|a, b| a.estimated_seconds().total_cmp(&b.estimated_seconds())).unwrap();
    let lock_path = layout.run_lock_file(&longest.run_id());
    let lock = mdsolids::output::open_lock_file(&lock_path).unwrap();
    lock.lock().unwrap();
    let child = mdsolids(&reports, &["--lock-wait", "1", "run", file.to_str().unwrap(), "-j", "1"]).spawn().unwrap();
    let out = wait_at_most(child, Duration::from_secs(60), "a run waiting on a held lock");
    let error = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{error}");
    // Every other run is stored; the wait is announced and given up, naming the run and file.
    assert_eq!(stored(&reports).len(), RUNS - 1, "{error}");
    let (id, path) = (longest.run_id(), lock_path.display().to_string());
    assert!(error.contains(&format!("waiting for run {id}")) && error.contains(&path), "{error}");
    assert!(error.contains(&format!("gave up waiting for run {id} after 1 s")), "{error}");
}

#[test]
fn a_report_racing_a_run_never_publishes_less_than_is_stored() {
    // Half the runs are stored (one shard) when `report` starts; while it waits for the
    // publish lock (held here, as by a `run` publishing) the other half is stored. It must
    // publish every run: it reads the store once it holds the lock.
    let dir = crate::common::scratch();
    let file = campaign_file(dir.path(), CAMPAIGN);
    let reports = dir.path().join("reports");
    let shard = |i: &str| mdsolids(&reports, &["run", file.to_str().unwrap(), "--shard", i]).output().unwrap();
    assert!(shard("0/2").status.success());
    let layout = mdsolids::output::Layout::new(&reports, "faults");
    let publishing = mdsolids::output::open_lock_file(&layout.publish_lock_file()).unwrap();
    publishing.lock().unwrap();
    let report = mdsolids(&reports, &["report", file.to_str().unwrap()]).spawn().unwrap();
    std::thread::sleep(Duration::from_millis(300));
    assert!(shard("1/2").status.success());
    drop(publishing);
    let out = wait_at_most(report, Duration::from_secs(60), "report");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(table(&reports).len(), RUNS + 1, "every stored run is in the published table");
    let reference = dir.path().join("reference");
    assert!(mdsolids(&reference, &["run", file.to_str().unwrap()]).output().unwrap().status.success());
    assert_eq!(table(&reports), table(&reference));
}

#[test]
fn ctrl_c_ends_with_how_many_runs_are_stored_and_how_to_continue() {
    let dir = crate::common::scratch();
    let file = campaign_file(dir.path(), CAMPAIGN);
    let reports = dir.path().join("reports");
    let child = mdsolids(&reports, &["run", file.to_str().unwrap(), "-j", "1"]).spawn().unwrap();
    wait_for_records(&reports, 2);
    // SAFETY: kill(2) on the pid of our own child, which has not been waited for.
    assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) }, 0);
    let out = wait_at_most(child, Duration::from_secs(60), "an interrupted run");
    let error = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{error}");
    let count = stored(&reports).len();
    assert!((2..RUNS).contains(&count), "{count} runs stored");
    let last = error.lines().last().unwrap_or_default();
    let rerun = format!("rerun `mdsolids --reports {} run {} -j 1` to continue", reports.display(), file.display());
    assert_eq!(last, format!("interrupted: {count} of {RUNS} runs stored; {rerun}"));
}

#[test]
fn a_full_disk_while_a_movie_is_encoded_names_the_file_and_leaves_no_partial_file() {
    // A file-size limit (ulimit -f, SIGXFSZ ignored) fails writes beyond it with EFBIG as a
    // full disk fails them with ENOSPC: 20 blocks (10 KB in dash, 20 KB in bash) is more than
    // the run's record and less than the movie (20 large frames, over 30 KB even with each later
    // frame stored as the box that changed).
    let dir = crate::common::scratch();
    let movie = CAMPAIGN
        .split("  - name: film")
        .nth(1)
        .unwrap()
        .replace("frames: 4, width: 200, height: 100", "frames: 20, width: 900, height: 450");
    let text = format!("{}  - name: film{movie}", CAMPAIGN.split("  - name: chain").next().unwrap());
    let file = campaign_file(dir.path(), &text);
    let reports = dir.path().join("reports");
    let script = format!(
        "trap '' XFSZ; ulimit -f 20; exec {} --reports {} run {} -j 1",
        crate::common::MDSOLIDS,
        reports.display(),
        file.display()
    );
    let out = Command::new("sh").args(["-c", &script]).output().unwrap();
    let error = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{error}");
    let plots = reports.join("faults/plots");
    // The film's runs are shown side by side: their one movie is the file written.
    let named = error.contains(&format!("cannot write '{}/film-side-by-side.gif'", plots.display()));
    assert!(named, "the error names the movie: {error}");
    let left: Vec<String> = std::fs::read_dir(&plots)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .filter(|name| name.ends_with(".tmp") || name.ends_with(".gif"))
        .collect();
    assert!(left.is_empty(), "partial files left: {left:?}");
}

/// Peak resident memory (bytes) of `mdsolids run <file>` from start to end, by the kernel's
/// account of the process (wait4's ru_maxrss, kB on Linux). A child spawned from this test
/// process would start from its memory (exec keeps the spawning process's high-water mark in
/// the child's ru_maxrss), and this process runs the rest of the suite's tests at the same
/// time: so a small shell starts the run in the background and exits, and this process, as
/// child subreaper, inherits the orphaned run and waits for it itself.
fn peak_memory_of_run(reports: &Path, file: &Path) -> f64 {
    // SAFETY: a plain integer option; it only makes this process the reaper of orphaned descendants.
    assert_eq!(unsafe { libc::prctl(libc::PR_SET_CHILD_SUBREAPER, 1) }, 0);
    let shell = Command::new("sh")
        .args(["-c", "\"$0\" --reports \"$1\" run \"$2\" >/dev/null 2>&1 & echo $!", crate::common::MDSOLIDS])
        .arg(reports)
        .arg(file)
        .output()
        .unwrap();
    assert!(shell.status.success(), "{}", String::from_utf8_lossy(&shell.stderr));
    let pid: libc::pid_t = String::from_utf8_lossy(&shell.stdout).trim().parse().unwrap();
    let mut status = 0;
    // SAFETY: `usage` is a plain C struct the call fills in; `pid` is our own unwaited child
    // since its shell exited.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    assert_eq!(unsafe { libc::wait4(pid, &mut status, 0, &mut usage) }, pid);
    assert!(libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0, "{} failed", file.display());
    usage.ru_maxrss as f64 * 1024.0
}

/// The memory estimate of a run covers its whole process: the ω_max estimate, the static
/// solve, the time loop, storing the record and writing the report (issue 14: a loaded
/// 300 × 300 lattice estimated at ~45 MB peaked at ~600 MB; 2e6 samples at 660 MB with a 167 MB
/// record and 73 MB of figures). For each kind of run, the peak resident memory of
/// `mdsolids run` less that of the smallest campaign (the program itself, ~50 MB) must lie
/// below the estimate, and the whole process's peak above estimate / 4: the estimate adds the stages up although their
/// transient parts do not overlap, and counts 50 bytes per stored number of JSON where ~22 are
/// written, so it sits about 1.2-2.5 × above the peak; 4 leaves room for the allocator.
#[test]
fn the_memory_estimate_covers_the_peak_of_every_kind_of_run() {
    // The loaded lattices peak in their static solve; their MD stops after 2 t_c unrelaxed
    // (`no_equilibrium`, a recorded result): 20 t_c peaked the same (95 MB) in 0.75 s more.
    // The chains run 30 t_c over their 1 500 samples: 100 t_c peaked 10 % higher, 0.4 s later.
    let loaded = |diagonals: &str| {
        format!(
            "  - name: s\n    kind: lattice\n    material: {{mass: 0.785, k: 2.0e9}}\n    geometry: {{spacing: 0.1, \
             depth: 0.01}}\n    damping: {{restitution: 0.5, background: 12000.0}}\n    lattice: {{size: 150, \
             k_diag_ratio: 0.5, diagonals: {diagonals}}}\n    load: {{case: tensile, per_node: 1000.0}}\n    relax: \
             {{max_tc: 2}}\n"
        )
    };
    let cases = [
        ("the program alone", "  - name: s\n    kind: pair\n    v0: 1.0\n".to_string()),
        ("loaded lattice with diagonals (static solve)", loaded("both")),
        ("loaded square lattice (static solve)", loaded("none")),
        ("pair with 2·10^6 samples", "  - name: s\n    kind: pair\n    v0: 1.0\n    time: {duration_tc: 80000, samples: 2000000}\n".into()),
        ("chain recording displacements", "  - name: s\n    kind: chain\n    n: 1000\n    v0: 0.1\n    time: {duration_tc: 30, samples: 1500}\n".into()),
        (
            "chain keeping every particle's series (output.series: full)",
            "  - name: s\n    kind: chain\n    n: 1000\n    v0: 0.1\n    time: {duration_tc: 30, samples: 1500}\n    \
             output: {series: full}\n"
                .into(),
        ),
        (
            "kicked lattice with probes and a movie",
            "  - name: s\n    kind: lattice\n    lattice: {size: 70, k_diag_ratio: 0.5}\n    supports: free\n    \
             impulse: {velocity: [0.0, -0.01]}\n    probes: {rows: [bottom, centre]}\n    movie: {frames: 10, width: \
             300, height: 300, bond_strain: true}\n    time: {integrator: velocity-verlet, duration_tc: 20, samples: 2000}\n"
                .into(),
        ),
    ];
    let dir = crate::common::scratch();
    let mut program = 0.0;
    for (index, (what, scene)) in cases.iter().enumerate() {
        let yaml = format!("version: 1\nname: m{index}\nscenes:\n{scene}");
        // The spec as read (its dt from t_c): planning it would estimate the 150 × 150
        // lattices' ω_max here as well as in the process measured (~0.4 s each).
        let estimate = mdsolids::spec::parse("m.yaml", &yaml).unwrap().runs[0].estimated_memory_bytes();
        let file = dir.path().join(format!("m{index}.yaml"));
        std::fs::write(&file, &yaml).unwrap();
        let peak = peak_memory_of_run(dir.path(), &file);
        println!("{what}: peak {:.0} MB, estimate {:.0} MB", peak / 1e6, estimate / 1e6);
        if index == 0 {
            program = peak;
            continue;
        }
        let run = peak - program;
        assert!(run <= estimate, "{what}: the run used {:.0} MB, estimated {:.0} MB", run / 1e6, estimate / 1e6);
        // Against the whole process's peak, which varies by tens of MB with how the threads'
        // allocator arenas fill: the square lattice's process peaked at 108 MB alone and at
        // 80 MB inside the full test suite on 2 loaded cores (29 MB above the program's own).
        assert!(
            estimate <= 4.0 * peak,
            "{what}: estimated {:.0} MB, the process peaked at {:.0} MB",
            estimate / 1e6,
            peak / 1e6
        );
    }
}

/// A record stores a bounded trace however many samples the run took (issue 14: 10^7 samples
/// made an 890 MB record): thinned evenly to at most `STORED_SAMPLES`, the first and the last
/// sample kept, measured from every sample before.
#[test]
fn a_long_sampled_run_stores_a_bounded_record() {
    let runs = common::runs(
        "version: 1\nname: r\nscenes:\n  - name: p\n    kind: pair\n    v0: 1.0\n    \
         time: {duration_tc: 10000, samples: 200000}\n",
    );
    let record = crate::common::execute(&runs[0]);
    let time = &record.trace.time;
    assert!(time.len() <= mdsolids::sim::STORED_SAMPLES && time.len() > 1000, "{} samples", time.len());
    let end = runs[0].steps as f64 * runs[0].dt;
    assert!(time[0] == 0.0 && (time[time.len() - 1] - end).abs() < 1e-9 * end, "first and last kept");
    assert!(record.metrics.pair.contact_duration.is_some(), "measured from every sample");
    // 5 numbers per sample of ~20 characters of JSON: about 1 MB (200 001 samples: ~22 MB).
    let json = serde_json::to_vec(&record).unwrap();
    assert!(json.len() < 2_000_000, "{} bytes", json.len());
}

/// Every stage of a run is within its deadline (issue 14: a static solve ran 135 s under a
/// 60 s budget and the message said "stopped after 1.163 s"): a 150 × 150 loaded lattice, whose
/// ω_max estimate alone takes longer than a 0.05 s budget, stops before its static solve and
/// says so, with the time it took.
#[test]
fn the_static_solve_is_within_the_time_budget() {
    use mdsolids::runner::execute_within;
    use mdsolids::spec::Budget;
    // Read, not planned: the plan would estimate the ω_max that the run must be stopped in.
    let runs = mdsolids::spec::parse(
        "s.yaml",
        "version: 1\nname: s\nscenes:\n  - name: s\n    kind: lattice\n    material: {mass: 0.785, k: 2.0e9}\n    \
         geometry: {spacing: 0.1, depth: 0.01}\n    damping: {restitution: 0.5, background: 12000.0}\n    \
         lattice: {size: 150, k_diag_ratio: 0.5}\n    load: {case: tensile, per_node: 1000.0}\n",
    )
    .unwrap()
    .runs;
    let r = execute_within(&runs[0], &Budget { seconds_per_run: 0.05, memory_per_run: 4e9 }, &Default::default());
    assert_eq!(r.status, RunStatus::Budget, "{}", r.message);
    assert!(
        r.message.contains("static solve") && r.message.contains("budget.seconds_per_run") && r.steps == 0,
        "{}",
        r.message
    );
    assert!(r.metrics.lattice.youngs_modulus_fem.is_none(), "the static solve was not finished");
}

/// `plan` and the campaign check estimate no ω_max for a run the memory budget refuses
/// (issue 14: `plan` of one 2000 × 2000 lattice took 168 s and 1.7 GB for a run that could not
/// start): 4 million nodes under a 100 MB budget are checked at once (the bound is generous:
/// a hang guard; the estimate alone would take minutes).
#[test]
fn runs_the_memory_budget_refuses_are_not_estimated() {
    let started = Instant::now();
    let campaign = mdsolids::plan::parse(
        "big.yaml",
        "version: 1\nname: big\nbudget: {memory_per_run_mb: 100}\nscenes:\n  - name: l\n    kind: lattice\n    \
         lattice: {size: 2000, k_diag_ratio: 0.5}\n    load: {case: tensile, per_node: 1.0}\n    grid:\n      \
         time.dt_per_tc: [20, 50]\n",
    )
    .unwrap()
    .campaign;
    assert!(campaign.runs.iter().all(|spec| campaign.budget.refuses(spec).is_some()));
    assert!(started.elapsed() < Duration::from_secs(10), "{:?}", started.elapsed());
}
