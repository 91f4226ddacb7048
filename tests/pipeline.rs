//! The campaign pipeline end to end, through the binary: files written, reruns served from the
//! store, reports re-rendered without simulating, and bad input refused before anything runs.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn mdsolids(reports: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mdsolids"))
        .arg("--reports")
        .arg(reports)
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn modified(path: &Path) -> std::time::SystemTime {
    std::fs::metadata(path).and_then(|m| m.modified()).expect("file exists")
}

fn run_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir.join("runs")).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    files
}

#[test]
fn small_campaign_end_to_end() {
    let reports = tempfile::tempdir().unwrap();
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
    for column in [
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
    ] {
        assert!(header.contains(&column), "results.csv lacks column {column}: {header:?}");
    }
    assert_eq!(csv.lines().count(), 6, "one header and one row per run");
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(report.contains("Scene `pair` (pair)") && report.contains("Scene `chain` (chain)"));
    assert!(report.contains("not clamped"), "the report states the contact force is not clamped");

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

#[test]
fn plan_lists_runs_and_simulates_nothing() {
    let reports = tempfile::tempdir().unwrap();
    let out = mdsolids(reports.path(), &["plan", "campaigns/coursework.yaml"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("pair-contact-") && stdout.contains("dt_per_tc=500"), "{stdout}");
    assert!(stdout.contains("208 runs") && stdout.contains("dt·ω_max"), "{stdout}");
    assert!(!reports.path().join("coursework").exists(), "plan wrote output");
}

/// Writes `yaml` to a file named `name` and returns the error `plan` prints for it.
fn refusal(name: &str, yaml: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
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
        error.contains("key.yaml: grid.\"damping.restitutio\"") && error.contains("unknown field `restitutio`"),
        "{error}"
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
    let campaign = mdsolids::stability::parse_campaign("awkward.yaml", yaml).unwrap();
    let reports = tempfile::tempdir().unwrap();
    let layout = mdsolids::output::Layout::new(reports.path(), &campaign.name);
    let first = mdsolids::runner::run_campaign(&campaign, &layout, Some(1)).unwrap();
    assert_eq!(first.simulated, 2);
    let again = mdsolids::runner::run_campaign(&campaign, &layout, Some(1)).unwrap();
    assert_eq!((again.simulated, again.cached), (0, 2));
}

/// Two campaign files named alike (issue 14, item 13): the second is refused with both files
/// named and nothing of the first's changed; `--force` hands the folder over, and the figures of
/// the first's scenes, which the second does not have, are removed. Before `campaign.json` the
/// second silently overwrote the first's tables and report and kept its figures.
#[test]
fn two_campaigns_with_one_name_do_not_share_a_folder() {
    let work = tempfile::tempdir().unwrap();
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

    let out = mdsolids(&reports, &["run", second, "--force"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(dir.join("plots/beta-energy-0.svg").is_file());
    assert!(!alpha.exists(), "the first campaign's figure is stale and removed");
    // The folder is the second's now; the first's runs are still stored, and `report` of the
    // first is refused too.
    for command in ["run", "report"] {
        let out = mdsolids(&reports, &[command, first]);
        assert!(!out.status.success() && text(&out.stderr).contains("second.yaml"), "{command}: {}", text(&out.stderr));
    }
}
