//! Scale-out without Slurm: a campaign run as four shards into one store and merged by
//! `report` gives the results table of the same campaign run in one go, row for row; reruns
//! skip stored runs; `report` lists what is missing; `slurm` writes the array and report jobs.

use std::path::Path;
use std::process::Command;

use crate::common::{mdsolids_ok, text};

/// The rows of `results.csv` without the measured-time columns (`wall_s`, `loop_s`, and
/// `solve_s` where a loaded lattice ran), which no
/// two runs share. The columns compared are the header's own, so a new column is compared too.
fn results_without_timing(dir: &Path) -> Vec<Vec<String>> {
    let csv = std::fs::read_to_string(dir.join("results.csv")).expect("results.csv");
    let mut reader = csv.lines().map(|line| line.split(',').map(str::to_string).collect::<Vec<_>>());
    let header = reader.next().expect("a header");
    let timing: Vec<usize> = header
        .iter()
        .enumerate()
        .filter(|(_, name)| ["wall_s", "loop_s", "solve_s"].contains(&name.as_str()))
        .map(|(i, _)| i)
        .collect();
    assert!((2..=3).contains(&timing.len()), "{header:?}");
    std::iter::once(header)
        .chain(reader)
        .map(|row| row.into_iter().enumerate().filter(|(i, _)| !timing.contains(i)).map(|(_, v)| v).collect())
        .collect()
}

#[test]
fn four_shards_and_a_report_give_the_table_of_one_run() {
    let (whole, sharded) = (crate::common::scratch(), crate::common::scratch());
    mdsolids_ok(whole.path(), &["run", "campaigns/smoke.yaml"]);

    let mut ran = 0;
    for index in 0..4 {
        let shard = format!("{index}/4");
        let out = text(&mdsolids_ok(sharded.path(), &["run", "campaigns/smoke.yaml", "--shard", &shard]).stdout);
        let runs: usize = out.split(" of 5 runs").next().and_then(|s| s.rsplit(' ').next()).unwrap().parse().unwrap();
        ran += runs;
        assert!(!sharded.path().join("smoke/results.csv").exists(), "a shard writes no table: {out}");
    }
    assert_eq!(ran, 5, "the shards cover the campaign once");
    // A second pass of a shard finds its runs stored.
    let again = text(&mdsolids_ok(sharded.path(), &["run", "campaigns/smoke.yaml", "--shard", "0/4"]).stdout);
    assert!(again.contains("0 simulated"), "{again}");

    let report = mdsolids_ok(sharded.path(), &["report", "campaigns/smoke.yaml"]);
    assert!(
        text(&report.stdout).contains("from 5 stored runs (0 without results, 0 corrupt"),
        "{}",
        text(&report.stdout)
    );
    assert!(text(&report.stderr).is_empty(), "{}", text(&report.stderr));
    let (a, b) =
        (results_without_timing(&whole.path().join("smoke")), results_without_timing(&sharded.path().join("smoke")));
    assert_eq!(a.len(), 6);
    assert_eq!(a, b);
}

#[test]
fn report_merges_what_is_stored_and_lists_what_is_missing() {
    let reports = crate::common::scratch();
    mdsolids_ok(reports.path(), &["run", "campaigns/smoke.yaml", "--shard", "0/4"]);
    let stored = std::fs::read_dir(reports.path().join("smoke/runs"))
        .unwrap()
        .filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().ends_with(".json"))
        .count();
    assert!((1..5).contains(&stored), "{stored}");
    let out = mdsolids_ok(reports.path(), &["report", "campaigns/smoke.yaml"]);
    let warning = text(&out.stderr);
    assert!(warning.contains(&format!("warning: {} of 5 runs have no stored result", 5 - stored)), "{warning}");
    let table = std::fs::read_to_string(reports.path().join("smoke/results.csv")).unwrap();
    assert_eq!(table.lines().count(), 1 + stored);
    let page = std::fs::read_to_string(reports.path().join("smoke/report.md")).unwrap();
    assert!(page.contains(&format!("Left out: {} without a stored result", 5 - stored)), "{page}");
}

#[test]
fn bad_shards_are_refused() {
    for bad in ["4/4", "1/0", "two/4"] {
        let out = Command::new(crate::common::MDSOLIDS)
            .args(["run", "campaigns/smoke.yaml", "--shard", bad])
            .current_dir(crate::common::repo())
            .output()
            .unwrap();
        assert!(!out.status.success());
        assert!(text(&out.stderr).contains("expected I/N with 0 ≤ I < N"), "{}", text(&out.stderr));
    }
}

#[test]
fn slurm_writes_an_array_and_an_afterany_report_job() {
    let reports = crate::common::scratch();
    let out =
        text(&mdsolids_ok(reports.path(), &["slurm", "campaigns/smoke.yaml", "--tasks", "4", "--time", "10"]).stdout);
    assert!(out.contains("submit with: bash "), "{out}");
    let dir = reports.path().join("smoke/slurm");
    let array = std::fs::read_to_string(dir.join("array.sh")).unwrap();
    for part in ["#SBATCH --array=0-3\n", "#SBATCH --time=10\n", "--shard \"$SLURM_ARRAY_TASK_ID/4\"", "smoke.yaml'"] {
        assert!(array.contains(part), "{part} missing from\n{array}");
    }
    assert!(array.contains(&format!("--output={}", dir.display())), "logs beside the scripts:\n{array}");
    let report = std::fs::read_to_string(dir.join("report.sh")).unwrap();
    assert!(report.contains(" report '") && !report.contains("--shard"), "{report}");
    let submit = std::fs::read_to_string(dir.join("submit.sh")).unwrap();
    assert!(submit.contains("--dependency=afterany:"), "{submit}");

    let too_many = Command::new(crate::common::MDSOLIDS)
        .arg("--reports")
        .arg(reports.path())
        .args(["slurm", "campaigns/smoke.yaml", "--tasks", "6"])
        .current_dir(crate::common::repo())
        .output()
        .unwrap();
    assert!(text(&too_many.stderr).contains("--tasks 6: must be between 1 and the campaign's 5 runs"));

    // A line break in --partition or --time once added a line of shell to array.sh.
    std::fs::remove_dir_all(&dir).unwrap();
    for option in ["--partition", "--time"] {
        let out = Command::new(crate::common::MDSOLIDS)
            .arg("--reports")
            .arg(reports.path())
            .args(["slurm", "campaigns/smoke.yaml", option, "10\ntouch /tmp/injected"])
            .current_dir(crate::common::repo())
            .output()
            .unwrap();
        assert!(!out.status.success(), "{option} with a line break was accepted");
        assert!(text(&out.stderr).contains("a Slurm"), "{}", text(&out.stderr));
        assert!(!dir.exists(), "no script is written");
    }
}
