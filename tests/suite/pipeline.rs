//! The campaign pipeline end to end, through the binary: files written, reruns served from the
//! store, reports re-rendered without simulating, and bad input refused before anything runs.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::common::{mdsolids, text};
use crate::shipped;

fn modified(path: &Path) -> std::time::SystemTime {
    std::fs::metadata(path).and_then(|m| m.modified()).expect("file exists")
}

/// The run records (`runs/*.json`) of the campaign folder `dir`, sorted.
fn run_files(dir: &Path) -> Vec<PathBuf> {
    let entries = std::fs::read_dir(dir.join("runs")).unwrap().map(|e| e.unwrap().path());
    let mut files: Vec<PathBuf> = entries.filter(|f| f.extension().is_some_and(|e| e == "json")).collect();
    files.sort();
    files
}

/// Columns `results.csv` of the smoke campaign (a pair and a chain) must have: the common ones,
/// the kinds' own, and the grid paths the campaign varies.
const SMOKE_COLUMNS: &[&str] = &[
    "run_id",
    "scene",
    "kind",
    "status",
    "message",
    "wall_s",
    "steps",
    "mass",
    "spacing",
    "k",
    "law",
    "beta",
    "contact",
    "gamma",
    "gamma_background",
    "integrator",
    "dt",
    "t_c",
    "n",
    "v0",
    "contact_duration",
    "contact_duration_theory",
    "restitution",
    "restitution_theory",
    "energy_error",
    "time.dt_per_tc",
    "damping.restitution",
];

#[test]
fn small_campaign_end_to_end() {
    let reports = crate::common::scratch();
    let out = mdsolids(reports.path(), &["run", "campaigns/smoke.yaml"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("5 runs (5 simulated, 0 cached, 0 not ok)"), "{}", text(&out.stdout));

    let dir = reports.path().join("smoke");
    for file in [
        "results.csv",
        "results.parquet",
        "report.md",
        "index.html",
        "plots/pair-convergence.svg",
        "plots/chain-displacements.svg",
    ] {
        assert!(dir.join(file).is_file(), "missing {file}");
    }
    let csv = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    for column in SMOKE_COLUMNS {
        assert!(header.contains(column), "results.csv lacks column {column}: {header:?}");
    }
    assert_eq!(csv.lines().count(), 6, "one header and one row per run");
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(report.contains("Scene `pair` (pair)") && report.contains("Scene `chain` (chain)"));
    assert!(report.contains("not clamped"), "the report states the contact force is not clamped");
    pages_are_whole(&dir, &report);

    // A rerun of the unchanged campaign simulates nothing and leaves the stored runs alone.
    let stored: Vec<_> = run_files(&dir).iter().map(|f| modified(f)).collect();
    let again = mdsolids(reports.path(), &["run", "campaigns/smoke.yaml"]);
    assert!(text(&again.stdout).contains("(0 simulated, 5 cached, 0 not ok)"), "{}", text(&again.stdout));
    assert_eq!(stored, run_files(&dir).iter().map(|f| modified(f)).collect::<Vec<_>>());

    // `report` re-renders from the store without simulating.
    std::fs::remove_file(dir.join("report.md")).unwrap();
    std::fs::remove_dir_all(dir.join("plots")).unwrap();
    let report = mdsolids(reports.path(), &["report", "campaigns/smoke.yaml"]);
    assert!(report.status.success(), "{}", text(&report.stderr));
    assert!(text(&report.stdout).contains("re-rendered from 5 stored runs"));
    assert!(dir.join("report.md").is_file() && dir.join("plots/chain-energy-0.svg").is_file());
    assert_eq!(stored, run_files(&dir).iter().map(|f| modified(f)).collect::<Vec<_>>());
}

/// The report's pages in `dir` (of the Markdown `report`): the appendix on its own page where
/// the report has answers, every image with its width and height (nothing moves as they load),
/// and no table without rows.
fn pages_are_whole(dir: &Path, report: &str) {
    assert!(report.contains("## Summary"), "the smoke campaign answers coursework items");
    let main = std::fs::read_to_string(dir.join("index.html")).unwrap();
    let appendix = std::fs::read_to_string(dir.join("appendix.html")).unwrap();
    assert!(
        main.contains("<h2 id=\"summary\">") && !main.contains("id=\"appendix-methods-and-every-scene-in-detail\"")
    );
    assert!(
        appendix.contains("id=\"appendix-methods-and-every-scene-in-detail\"") && !appendix.contains("id=\"summary\"")
    );
    for page in [&main, &appendix] {
        let images: Vec<&str> = page.split("<img ").skip(1).map(|rest| &rest[..rest.find('>').unwrap()]).collect();
        assert!(!images.is_empty());
        for image in images {
            assert!(image.contains(" width=\"") && image.contains(" height=\""), "an image without its size: {image}");
        }
        for table in page.split("<table>").skip(1) {
            assert!(table[..table.find("</table>").unwrap()].contains("<td"), "a table without rows: {table}");
        }
    }
}

/// A reader that stops after one line (`mdsolids plan … | head -1`) ends the command quietly,
/// by SIGPIPE as `ls | head` does: no panic, no backtrace (it printed "failed printing to
/// stdout: Broken pipe" and a stack before). The list is ~250 lines, far more than the pipe's
/// first read, so the write after the reader has gone is sure to happen.
#[test]
fn a_reader_that_stops_early_ends_plan_quietly() {
    use std::io::{BufRead, BufReader};
    use std::os::unix::process::ExitStatusExt;
    let reports = crate::common::scratch();
    let mut child = std::process::Command::new(crate::common::MDSOLIDS)
        .args(["--reports", reports.path().to_str().unwrap(), "plan", "campaigns/coursework.yaml"])
        .current_dir(crate::common::repo())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap()).read_line(&mut first).unwrap();
    assert!(first.starts_with("run_id"), "{first}");
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked") && !stderr.contains("Broken pipe"), "{stderr}");
    assert!(out.status.success() || out.status.signal() == Some(libc::SIGPIPE), "{:?}: {stderr}", out.status);
}

#[test]
fn plan_lists_runs_and_simulates_nothing() {
    let reports = crate::common::scratch();
    let out = mdsolids(reports.path(), &["plan", "campaigns/coursework.yaml"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("pair-contact-") && stdout.contains("dt_per_tc=500"), "{stdout}");
    assert!(stdout.contains("312 runs") && stdout.contains("dt·ω_max"), "{stdout}");
    assert!(!reports.path().join("coursework").exists(), "plan wrote output");
}

/// Writes `yaml` to a file named `name` and returns the error `plan` prints for it.
fn refusal(name: &str, yaml: &str) -> String {
    let dir = crate::common::scratch();
    let file = dir.path().join(name);
    std::fs::write(&file, yaml).unwrap();
    let out = mdsolids(dir.path(), &["plan", file.to_str().unwrap()]);
    assert!(!out.status.success(), "{name} was accepted");
    text(&out.stderr)
}

const SCENE: &str = "version: 1\nname: bad\nscenes:\n  - name: p\n    kind: pair\n    v0: 1.0\n";

#[test]
fn malformed_yaml_names_file_and_line() {
    let error = refusal("malformed.yaml", &format!("{SCENE}    damping: {{restitution: 0.5\n"));
    assert!(error.contains("malformed.yaml") && error.contains("line 7"), "{error}");
}

#[test]
fn unknown_key_names_path_and_allowed_keys() {
    let error = refusal("unknown.yaml", &format!("{SCENE}    damping: {{gama: 0.3}}\n"));
    assert!(error.contains("unknown.yaml: scenes[0].damping.gama"), "{error}");
    assert!(error.contains("expected one of `restitution`, `gamma`, `background`"), "{error}");
    // The source snippet names the file too, not the reader's placeholder.
    assert!(error.contains("unknown.yaml:7:") && !error.contains("<input>"), "{error}");
}

#[test]
fn out_of_range_value_names_path_value_and_range() {
    let error = refusal("range.yaml", &format!("{SCENE}    damping: {{restitution: 1.5}}\n"));
    assert!(error.contains("range.yaml: scenes[0].damping.restitution = 1.5: must be in (0, 1]"), "{error}");
    let error = refusal("grid.yaml", &format!("{SCENE}grid:\n  damping.restitution: [0.5, 1.5]\n"));
    assert!(
        error.contains("grid.yaml: grid.\"damping.restitution\" (in scenes[0]) = 1.5: must be in (0, 1]"),
        "{error}"
    );
    let error = refusal("key.yaml", &format!("{SCENE}grid:\n  damping.restitutio: [0.5]\n"));
    assert!(
        error.contains("key.yaml: grid.\"damping.restitutio\" (in scenes[0]): unknown field `restitutio`"),
        "an unknown grid key is the path's fault, so no value is shown: {error}"
    );
}

#[test]
fn overdamped_and_misplaced_fields_are_refused() {
    let error = refusal("over.yaml", &format!("{SCENE}    damping: {{gamma: 2.0}}\n"));
    assert!(error.contains("overdamped"), "{error}");
    let error = refusal("misplaced.yaml", &format!("{SCENE}    n: 11\n"));
    assert!(error.contains("scenes[0].n") && error.contains("only for chain scenes"), "{error}");
}

#[test]
fn stored_runs_with_awkward_numbers_are_found_again() {
    // A steel-like lattice and a Hertz pair: t_c, dt and γ come out as numbers whose shortest
    // decimal form needs all 17 digits. Every stored spec must read back bit for bit, or the
    // cache misses and a rerun simulates again (it did, for 54 of 134 coursework runs, before
    // serde_json's exact float parsing was switched on).
    let yaml = "version: 1\nname: awkward\nscenes:\n  - name: l\n    kind: lattice\n    \
                material: {mass: 0.785, k: 2.0e9}\n    geometry: {spacing: 0.1, depth: 0.01}\n    lattice: {size: 3}\n    \
                damping: {restitution: 0.3}\n  - name: h\n    kind: pair\n    v0: 0.37\n    \
                material: {contact: true, law: hertz, mass: 0.785, k: 3.3e7}\n";
    let planned = mdsolids::plan::parse("awkward.yaml", yaml).unwrap();
    let campaign = &planned.campaign;
    let reports = crate::common::scratch();
    let layout = mdsolids::output::Layout::new(reports.path(), &campaign.name);
    let first = mdsolids::runner::run_campaign(&planned, &layout, Some(1)).unwrap();
    assert_eq!(first.simulated, 2);
    let again = mdsolids::runner::run_campaign(&planned, &layout, Some(1)).unwrap();
    assert_eq!((again.simulated, again.cached), (0, 2));
}

/// Two campaign files named alike (issue 14, item 13): the second is refused with both files
/// named and nothing of the first's changed; `--force` hands the folder over, and the figures of
/// the first's scenes, which the second does not have, are removed. Before `campaign.json` the
/// second silently overwrote the first's tables and report and kept its figures.
#[test]
fn two_campaigns_with_one_name_do_not_share_a_folder() {
    let work = crate::common::scratch();
    let scene =
        |name: &str| format!("version: 1\nname: same\nscenes:\n  - name: {name}\n    kind: pair\n    v0: 1.0\n");
    let (first, second) = (work.path().join("first.yaml"), work.path().join("second.yaml"));
    std::fs::write(&first, scene("alpha")).unwrap();
    std::fs::write(&second, scene("beta")).unwrap();
    let (first, second) = (first.to_str().unwrap(), second.to_str().unwrap());
    let reports = work.path().join("reports");
    let dir = reports.join("same");
    let out = mdsolids(&reports, &["run", first]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let alpha = dir.join("plots/alpha-energy-0.svg");
    assert!(alpha.is_file());
    let results = std::fs::read(dir.join("results.csv")).unwrap();
    let owner = std::fs::read_to_string(dir.join("campaign.json")).unwrap();
    assert!(owner.contains(&std::fs::canonicalize(first).unwrap().display().to_string()), "{owner}");

    for command in [&["run", second][..], &["run", second, "--shard", "0/2"], &["slurm", second, "--tasks", "1"]] {
        let out = mdsolids(&reports, command);
        let error = text(&out.stderr);
        assert!(!out.status.success(), "{command:?} was accepted");
        for part in ["first.yaml", "second.yaml", "--force", "name:"] {
            assert!(error.contains(part), "{command:?}: {part} missing from {error}");
        }
    }
    assert_eq!(std::fs::read(dir.join("results.csv")).unwrap(), results, "the first's table is untouched");

    // The same file again, by another path, is the same campaign.
    let out = mdsolids(&reports, &["report", &format!("{}/./first.yaml", work.path().display())]);
    assert!(out.status.success(), "{}", text(&out.stderr));

    // A figure of the user's own in the plots folder, named as this program names its own:
    // not written by any report, so never removed (it had been, as stale).
    let own = dir.join("plots/my-figure.svg");
    std::fs::write(&own, "<svg/>").unwrap();
    let out = mdsolids(&reports, &["run", second, "--force"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(dir.join("plots/beta-energy-0.svg").is_file());
    assert!(!alpha.exists(), "the first campaign's figure is stale and removed");
    assert!(own.is_file(), "the user's own figure was removed");
    // The folder is the second's now; the first's runs are still stored, and `report` of the
    // first is refused too.
    for command in ["run", "report"] {
        let out = mdsolids(&reports, &[command, first]);
        assert!(!out.status.success() && text(&out.stderr).contains("second.yaml"), "{command}: {}", text(&out.stderr));
    }
}

/// A pair sweep and a probed lattice kick: small, and every kind of stored series.
const STORE_CAMPAIGN: &str = "version: 1\nname: store\nscenes:\n  - name: kick\n    kind: lattice\n    \
    lattice: {size: 6}\n    impulse: {node: top-right, velocity: [0.0, -0.1]}\n    time: {duration_tc: 5, samples: 10}\n    \
    probes: {rows: [bottom]}\n  - name: pair\n    kind: pair\n    v0: 1.0\n    grid:\n      time.dt_per_tc: [20, 50, 100, 200]\n";

/// Runs [`STORE_CAMPAIGN`] into a fresh reports directory: (that directory, the campaign file,
/// the campaign file).
fn stored_campaign() -> (tempfile::TempDir, PathBuf) {
    let dir = crate::common::scratch();
    let file = dir.path().join("store.yaml");
    std::fs::write(&file, STORE_CAMPAIGN).unwrap();
    let out = mdsolids(&dir.path().join("reports"), &["run", file.to_str().unwrap()]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    (dir, file)
}

/// The stored record of the first run of `scene`, as JSON.
fn record_of(runs: &Path, scene: &str) -> (PathBuf, serde_json::Value) {
    let path = run_files(runs.parent().unwrap())
        .into_iter()
        .find(|f| f.file_name().unwrap().to_string_lossy().starts_with(&format!("{scene}-")))
        .unwrap();
    let json = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    (path, json)
}

#[test]
fn records_of_another_build_are_simulated_again_or_reused_loudly() {
    let (dir, file) = stored_campaign();
    let (file, reports) = (file.to_str().unwrap(), dir.path().join("reports"));
    let runs = reports.join("store/runs");
    let (path, mut record) = record_of(&runs, "pair");
    let run_id = record["run_id"].as_str().unwrap().to_string();
    assert!(record["build"].as_str().is_some_and(|b| b.starts_with(concat!(env!("CARGO_PKG_VERSION"), "+"))));
    let age = |record: &mut serde_json::Value| {
        record["build"] = "0.0.1+0123456789abcdef".into();
        std::fs::write(&path, record.to_string()).unwrap();
    };
    age(&mut record);

    // `plan` says it would be simulated again and why; `report` keeps it, marked.
    let plan = text(&mdsolids(&reports, &["plan", file]).stdout);
    let line = plan.lines().find(|l| l.starts_with(&run_id)).unwrap();
    assert!(line.contains(" stale "), "{line}");
    assert!(plan.contains("1 made by another build"), "{plan}");
    let report = mdsolids(&reports, &["report", file]);
    assert!(report.status.success(), "{}", text(&report.stderr));
    assert!(text(&report.stderr).contains("made by another build than this one"), "{}", text(&report.stderr));
    let csv = std::fs::read_to_string(reports.join("store/results.csv")).unwrap();
    let row = csv.lines().find(|l| l.starts_with(&run_id)).unwrap();
    assert!(row.contains(",0.0.1+0123456789abcdef,true,"), "{row}");
    let column = csv.lines().next().unwrap().split(',').position(|c| c == "other_build").unwrap();
    let marks: Vec<&str> = csv.lines().skip(1).map(|l| l.split(',').nth(column).unwrap()).collect();
    assert_eq!(marks.iter().filter(|&&m| m == "false").count(), 4, "the other runs are of this build: {csv}");
    let markdown = std::fs::read_to_string(reports.join("store/report.md")).unwrap();
    assert!(markdown.contains("**1 of these runs were made by another build**"), "{markdown}");
    assert!(markdown.contains(&format!("| `{run_id}` | `0.0.1+0123456789abcdef` |")), "{markdown}");

    // `run --reuse-other-builds` takes it, saying so for that run; plain `run` simulates it.
    let reuse = mdsolids(&reports, &["run", file, "--reuse-other-builds"]);
    assert!(text(&reuse.stdout).contains("(0 simulated, 5 cached"), "{}", text(&reuse.stdout));
    let warning = format!("warning: reusing {run_id}, made by build 0.0.1+0123456789abcdef, not by this build");
    assert!(text(&reuse.stderr).contains(&warning), "{}", text(&reuse.stderr));
    let again = mdsolids(&reports, &["run", file]);
    assert!(text(&again.stdout).contains("(1 simulated, 4 cached"), "{}", text(&again.stdout));
    assert!(text(&again.stderr).contains("simulated again"), "{}", text(&again.stderr));
    let (_, rewritten) = record_of(&runs, "pair");
    assert_ne!(rewritten["build"], "0.0.1+0123456789abcdef");
}

#[test]
fn corrupt_records_are_reported_left_out_and_simulated_again() {
    let (dir, file) = stored_campaign();
    let (file, reports) = (file.to_str().unwrap(), dir.path().join("reports"));
    let runs = reports.join("store/runs");
    let complete = std::fs::read_to_string(reports.join("store/results.csv")).unwrap();
    // A record whose run_id climbs out of the reports folder (it named probes/<run_id>.csv),
    // one whose series file is another run's (as a kill between writing the two could leave
    // it), one holding a number beyond f64 and one that is not JSON.
    let (kick, mut record) = record_of(&runs, "kick");
    record["run_id"] = "../../../escaped".into();
    std::fs::write(&kick, record.to_string()).unwrap();
    let pairs: Vec<PathBuf> =
        run_files(&reports.join("store")).into_iter().filter(|f| f.to_string_lossy().contains("/pair-")).collect();
    let series =
        |record: &Path| reports.join("store/series").join(record.with_extension("parquet").file_name().unwrap());
    std::fs::copy(series(&pairs[3]), series(&pairs[0])).unwrap();
    let not_its_own = "its series table (";
    let huge = std::fs::read_to_string(&pairs[1]).unwrap().replacen("\"wall_s\":", "\"wall_s\":1e999,\"x\":", 1);
    std::fs::write(&pairs[1], huge).unwrap();
    std::fs::write(&pairs[2], "{\"run_id\": ").unwrap();

    let plan = text(&mdsolids(&reports, &["plan", file]).stdout);
    assert_eq!(plan.lines().filter(|l| l.split_whitespace().nth(9) == Some("corrupt")).count(), 4, "{plan}");
    assert!(plan.contains("`run` simulates 4: 4 with a corrupt record"), "{plan}");

    let report = mdsolids(&reports, &["report", file]);
    let stderr = text(&report.stderr);
    assert!(report.status.success(), "{stderr}");
    assert!(!dir.path().join("escaped.csv").exists() && !reports.join("escaped.csv").exists());
    for why in [
        "its run_id \"../../../escaped\" is not its file name",
        not_its_own,
        "is not a run record: number out of range",
        "is not a run record: EOF while parsing",
    ] {
        assert!(stderr.contains(why), "{why} not in {stderr}");
    }
    assert!(!stderr.contains("no stored result"), "corrupt is not missing: {stderr}");
    assert!(stderr.contains("PARTIAL results") && stderr.contains("kept as results.previous.csv"), "{stderr}");
    // The complete table is kept aside, the partial one says what it lacks.
    assert_eq!(std::fs::read_to_string(reports.join("store/results.previous.csv")).unwrap(), complete);
    assert_eq!(std::fs::read_to_string(reports.join("store/results.csv")).unwrap().lines().count(), 2);
    let markdown = std::fs::read_to_string(reports.join("store/report.md")).unwrap();
    assert!(markdown.contains("**Partial report: 1 of the campaign's 5 runs"), "{markdown}");
    assert_eq!(markdown.matches("| corrupt record: ").count(), 4, "{markdown}");

    let run = mdsolids(&reports, &["run", file]);
    assert!(text(&run.stdout).contains("(4 simulated, 1 cached"), "{}", text(&run.stdout));
    assert_eq!(text(&run.stderr).matches(" is corrupt (").count(), 4, "{}", text(&run.stderr));
    let report = mdsolids(&reports, &["report", file]);
    assert!(
        text(&report.stdout).contains("from 5 stored runs (0 without results, 0 corrupt"),
        "{}",
        text(&report.stdout)
    );
    assert!(!text(&report.stderr).contains("PARTIAL"), "{}", text(&report.stderr));
}

// ---------------------------------------------------------------------------------------------
// Pinned outputs. `MDSOLIDS_UPDATE_SNAPSHOTS=1 cargo test --release --test suite pinned`
// writes the snapshots anew; do that only for a change that is meant to change results or the
// report, and say so in the commit.

/// Columns that change from run to run (wall times, the static solve's `solve_s` among them) or
/// from build to build (the build stamp).
const UNPINNED_COLUMNS: [&str; 4] = ["build", "wall_s", "loop_s", "solve_s"];

fn updating_snapshots() -> bool {
    std::env::var_os("MDSOLIDS_UPDATE_SNAPSHOTS").is_some()
}

fn snapshot_dir() -> PathBuf {
    crate::common::repo().join("tests/snapshots")
}

/// The fields of a CSV text, rows of cells (RFC 4180 quoting, as polars writes it).
fn csv_cells(text: &str) -> Vec<Vec<String>> {
    let (mut rows, mut row, mut cell, mut quoted) = (Vec::new(), Vec::new(), String::new(), false);
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                cell.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => row.push(std::mem::take(&mut cell)),
            ('\n', false) => {
                row.push(std::mem::take(&mut cell));
                rows.push(std::mem::take(&mut row));
            }
            _ => cell.push(c),
        }
    }
    if !cell.is_empty() || !row.is_empty() {
        row.push(cell);
        rows.push(row);
    }
    rows
}

/// The table without its unpinned columns, as CSV text.
fn pinned_table(csv: &str) -> String {
    let rows = csv_cells(csv);
    let keep: Vec<bool> = rows[0].iter().map(|name| !UNPINNED_COLUMNS.contains(&name.as_str())).collect();
    let quote = |cell: &String| {
        if cell.contains([',', '"', '\n']) { format!("\"{}\"", cell.replace('"', "\"\"")) } else { cell.clone() }
    };
    rows.iter()
        .map(|row| {
            row.iter().zip(&keep).filter(|(_, keep)| **keep).map(|(cell, _)| quote(cell)).collect::<Vec<_>>().join(",")
        })
        .map(|line| line + "\n")
        .collect()
}

/// Cells equal as text, or as numbers to 1e-12 relative: a refactor may reorder a sum and move
/// the last digits of a result (a few ulps, ~1e-15); anything it really changes moves far more.
fn same_cell(pinned: &str, now: &str) -> bool {
    match (pinned.parse::<f64>(), now.parse::<f64>()) {
        (Ok(a), Ok(b)) if a.is_finite() && b.is_finite() => (a - b).abs() <= 1e-12 * a.abs().max(b.abs()),
        _ => pinned == now,
    }
}

/// Where the rows of `now` differ from the snapshot's rows of the same runs (matched by
/// `run_id`), as lines saying run, column and both values. A column `now` lacks (a grid path or
/// a kind's column none of a share's runs has) must be empty in the snapshot for these runs,
/// and `now` may have no column the snapshot lacks. With `whole`, the columns and the runs must
/// be the snapshot's, all of them.
fn table_differences(pinned: &str, now: &str, whole: bool) -> Vec<String> {
    let (pinned, now) = (csv_cells(pinned), csv_cells(now));
    let (header, columns) = (&pinned[0], &now[0]);
    let mut differences: Vec<String> =
        columns.iter().filter(|c| !header.contains(c)).map(|c| format!("column {c} is not in the snapshot")).collect();
    if whole && (header != columns || pinned.len() != now.len()) {
        differences.push(format!(
            "columns or rows differ: {} rows of {header:?} pinned, {} rows of {columns:?} now",
            pinned.len(),
            now.len()
        ));
    }
    let by_run: BTreeMap<&str, &Vec<String>> = pinned[1..].iter().map(|row| (row[0].as_str(), row)).collect();
    for row in &now[1..] {
        let Some(pinned_row) = by_run.get(row[0].as_str()) else {
            differences.push(format!("run {} is not in the snapshot", row[0]));
            continue;
        };
        for (column, name) in header.iter().enumerate() {
            let cell = columns.iter().position(|c| c == name).map_or("", |at| row[at].as_str());
            if !same_cell(&pinned_row[column], cell) {
                differences
                    .push(format!("run {} column {name}: pinned {:?}, now {cell:?}", row[0], pinned_row[column]));
            }
        }
    }
    differences
}

/// How much of a shipped campaign a pinned test runs.
#[derive(Clone, Copy, PartialEq)]
enum Scope {
    /// Every run (`shipped::whole`).
    Whole,
    /// Per scene, the cheapest runs that take every value of every grid axis once
    /// (`shipped::covering_share`): the rows of those runs are compared with the snapshot.
    Share,
}

/// `results.csv` of the shipped campaign `campaign`, timing and build columns aside, against
/// its snapshot in tests/snapshots/results/ (which holds every run): a refactor must leave
/// every result as it was. `scope` is how much of the campaign the test runs;
/// `MDSOLIDS_PINNED=whole` runs every campaign whole, and `MDSOLIDS_UPDATE_SNAPSHOTS=1` runs it
/// whole and writes its snapshot (docs/guarantees.md, "Pinned outputs").
fn pinned_results(campaign: &str, scope: Scope) {
    let whole = scope == Scope::Whole
        || updating_snapshots()
        || std::env::var_os("MDSOLIDS_PINNED").is_some_and(|v| v == "whole");
    let folder = if whole { shipped::whole(campaign) } else { shipped::covering_share(campaign) };
    let now = pinned_table(&std::fs::read_to_string(folder.join("results.csv")).unwrap());
    let snapshot = snapshot_dir().join("results").join(format!("{campaign}.csv"));
    if updating_snapshots() {
        std::fs::create_dir_all(snapshot.parent().unwrap()).unwrap();
        std::fs::write(&snapshot, &now).unwrap();
        return;
    }
    let pinned =
        std::fs::read_to_string(&snapshot).expect("the snapshot exists (MDSOLIDS_UPDATE_SNAPSHOTS=1 writes it)");
    let differences = table_differences(&pinned, &now, whole);
    assert!(
        differences.is_empty(),
        "{campaign}: results changed, {} cells differ in the {} of {} runs run:\n  {}",
        differences.len(),
        now.lines().count() - 1,
        pinned.lines().count() - 1,
        differences[..differences.len().min(20)].join("\n  ")
    );
}

/// One test per pinned campaign, `pinned_results_of_<campaign>`, so that the campaigns run
/// side by side and fail one by one.
macro_rules! pinned_campaigns {
    ($($test:ident: $campaign:literal, $scope:ident;)*) => {
        $(
            #[test]
            fn $test() {
                pinned_results($campaign, Scope::$scope);
            }
        )*
    };
}

// The shipped campaigns whose results are pinned: whole where that is cheap (smoke, shards) or
// another test runs it anyway (lattice-types, whose report the lattice-types tests read), a
// covering share of the others (docs/performance.md, "The slowest tests").
pinned_campaigns! {
    pinned_results_of_smoke: "smoke", Whole;
    pinned_results_of_shards: "shards", Whole;
    pinned_results_of_lattice_types: "lattice-types", Whole;
    pinned_results_of_coursework: "coursework", Share;
    pinned_results_of_coursework_hertz: "coursework-hertz", Share;
    pinned_results_of_stability: "stability", Share;
    pinned_results_of_dt_study: "dt-study", Share;
}

/// report.md rendered from a frozen set of records (tests/snapshots/report/runs, made once by
/// `mdsolids run tests/snapshots/report.yaml`) is pinned: any change of the templates, the
/// report's context or the tables shows here. The records are stamped with this build first,
/// so they are rendered as current results, and the build stamp in the text is masked.
#[test]
fn pinned_report_of_frozen_records() {
    let reports = crate::common::scratch();
    let runs = reports.path().join("report-snapshot").join("runs");
    std::fs::create_dir_all(&runs).unwrap();
    for entry in std::fs::read_dir(snapshot_dir().join("report").join("runs")).unwrap() {
        let path = entry.unwrap().path();
        let mut record: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        record["build"] = serde_json::Value::from(mdsolids::runner::BUILD);
        std::fs::write(runs.join(path.file_name().unwrap()), serde_json::to_string(&record).unwrap()).unwrap();
    }
    let out = mdsolids(reports.path(), &["report", "tests/snapshots/report.yaml"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let now = std::fs::read_to_string(reports.path().join("report-snapshot").join("report.md"))
        .unwrap()
        .replace(mdsolids::runner::BUILD, "<build>");
    let snapshot = snapshot_dir().join("report").join("report.md");
    if updating_snapshots() {
        std::fs::write(&snapshot, &now).unwrap();
        return;
    }
    let pinned = std::fs::read_to_string(&snapshot).unwrap();
    if pinned != now {
        let line = pinned
            .lines()
            .zip(now.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(pinned.lines().count().min(now.lines().count()));
        panic!(
            "report.md changed at line {}:\n  pinned: {:?}\n  now:    {:?}",
            line + 1,
            pinned.lines().nth(line),
            now.lines().nth(line)
        );
    }
}

/// Four significant digits, as the report's sentences write a plain number (an independent
/// copy of the rule, so a change of the report's format shows here).
fn four_digits(x: f64) -> String {
    let decimals = (3.0 - x.abs().log10().floor()).max(0.0) as usize;
    format!("{x:.decimals$}")
}

/// The report's sentences are computed from the results, not written into the template: the
/// same campaign with another mass and stiffness states the new t_c and dt, read back from
/// its own results.csv, and the verdicts follow.
#[test]
fn report_sentences_follow_the_results() {
    let mut stated = Vec::new();
    for (mass, k) in [(1.0f64, 1.0f64), (2.0, 9.0)] {
        let dir = crate::common::scratch();
        let file = dir.path().join("follow.yaml");
        let yaml = format!(
            "version: 1\nname: follow\ndefaults:\n  material: {{mass: {mass}, k: {k}}}\nscenes:\n  - name: pair\n    \
             kind: pair\n    v0: 1.0\n    grid:\n      damping.restitution: [1.0, 0.5]\n      time.dt_per_tc: [10, 50, 200]\n"
        );
        std::fs::write(&file, yaml).unwrap();
        let out = mdsolids(dir.path(), &["run", file.to_str().unwrap()]);
        assert!(out.status.success(), "{}", text(&out.stderr));
        let report = std::fs::read_to_string(dir.path().join("follow").join("report.md")).unwrap();
        let csv = std::fs::read_to_string(dir.path().join("follow").join("results.csv")).unwrap();
        let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
        let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
        let row: Vec<&str> = csv.lines().nth(1).unwrap().split(',').collect();
        let t_c: f64 = row[column("t_c")].parse().unwrap();
        assert!((t_c - std::f64::consts::PI * (mass / (2.0 * k)).sqrt()).abs() < 1e-12 * t_c);
        for sentence in [
            format!("t_c = π/ω = {} s undamped", four_digits(t_c)),
            format!("dt = t_c/50 = {} s", four_digits(t_c / 50.0)),
        ] {
            assert!(report.contains(&sentence), "report.md of m = {mass}, k = {k} lacks {sentence:?}");
        }
        assert!(report.contains("| 3 | [The time step](#3-the-time-step) |"), "the summary links each item");
        stated.push(four_digits(t_c));
    }
    assert_ne!(stated[0], stated[1], "the two campaigns state different numbers");
}

/// The summary line of the time step (item 3, after the force function and the pair) judges the order of the pair's time-step error only where the
/// campaign sweeps dt: one dt gives an observation ("no dt sweep", •), not ✗ with no order; a
/// sweep gives the order and ✓. A scene shows only the tables it has rows for: a chain between
/// walls no normal-mode table, an impulse lattice no moduli table.
#[test]
fn the_time_step_is_judged_only_over_a_sweep_and_empty_tables_are_left_out() {
    let mut lines = Vec::new();
    for sweep in ["[50]", "[10, 50, 200]"] {
        let dir = crate::common::scratch();
        let file = dir.path().join("sweep.yaml");
        let yaml = format!(
            "version: 1\nname: sweep\nscenes:\n  - name: pair\n    kind: pair\n    v0: 1.0\n    grid:\n      \
             time.dt_per_tc: {sweep}\n  - name: walls\n    kind: chain\n    n: 5\n    damping: {{restitution: 0.5}}\n    \
             relax: {{residual_force: 1.0e-6}}\n    wall_distance: 5.5\n  - name: kick\n    kind: lattice\n    \
             lattice: {{size: 6}}\n    supports: free\n    impulse: {{node: top-right, velocity: [0.0, -0.1]}}\n"
        );
        std::fs::write(&file, yaml).unwrap();
        let out = mdsolids(dir.path(), &["run", file.to_str().unwrap()]);
        assert!(out.status.success(), "{}", text(&out.stderr));
        let report = std::fs::read_to_string(dir.path().join("sweep").join("report.md")).unwrap();
        let line = report.lines().find(|l| l.starts_with("| 3 | [The time step]")).unwrap().to_string();
        for header in ["| run | grid values | N | excited |", "| run | grid values | size | springs |"] {
            assert!(!report.contains(header), "a table without rows: {header}");
        }
        lines.push(line);
    }
    assert!(lines[0].contains("no dt sweep") && lines[0].contains('•') && !lines[0].contains('✗'), "{}", lines[0]);
    assert!(lines[1].contains("error ∝ dt^2.0") && lines[1].contains('✓'), "{}", lines[1]);
}
