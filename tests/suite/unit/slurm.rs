//! Unit tests of `src/slurm.rs`, moved out of the library (one test binary).

use mdsolids::slurm::{ArrayJob, partition_option, shell_quote, time_option, write_scripts};
use std::path::Path;

fn job(reports: &Path) -> ArrayJob {
    ArrayJob {
        exe: "/opt/md solids/bin/mdsolids".into(),
        reports: reports.to_path_buf(),
        campaign_file: "/home/u/it's.yaml".into(),
        campaign: "smoke".into(),
        tasks: 4,
        partition: Some("short".into()),
        time: None,
        cpus_per_task: 2,
    }
}

#[test]
fn the_scripts_run_one_shard_per_task_and_report_after_any_end() {
    let reports = crate::common::scratch();
    let scripts = write_scripts(&job(reports.path())).unwrap();
    let array = std::fs::read_to_string(&scripts.array).unwrap();
    for line in ["#SBATCH --array=0-3\n", "#SBATCH --partition=short\n", "#SBATCH --cpus-per-task=2\n"] {
        assert!(array.contains(line), "{line} missing from\n{array}");
    }
    assert!(!array.contains("--time"), "no --time unless asked for");
    assert!(array.contains("exec '/opt/md solids/bin/mdsolids' --reports '"), "{array}");
    assert!(array.contains(r#"run '/home/u/it'\''s.yaml' --shard "$SLURM_ARRAY_TASK_ID/4" --jobs 2"#), "{array}");
    let report = std::fs::read_to_string(&scripts.report).unwrap();
    assert!(report.contains(" report '/home/u/it'\\''s.yaml'\n"), "{report}");
    assert!(!report.contains("--array"), "{report}");
    let submit = std::fs::read_to_string(&scripts.submit).unwrap();
    assert!(submit.contains("--dependency=afterany:\"$array\""), "{submit}");
}

#[test]
fn a_reports_directory_with_spaces_is_refused() {
    let error = write_scripts(&job(Path::new("/shared/my reports"))).unwrap_err();
    assert!(error.to_string().contains("white space"), "{error}");
}

#[test]
fn a_partition_or_time_that_is_not_one_is_refused_before_writing() {
    for (partition, time) in [(Some("short\nrm -rf ~"), None), (None, Some("30\nrm -rf ~")), (None, Some("1-"))] {
        let reports = crate::common::scratch();
        let job = ArrayJob { partition: partition.map(Into::into), time: time.map(Into::into), ..job(reports.path()) };
        let error = write_scripts(&job).unwrap_err().to_string();
        assert!(error.contains("a Slurm"), "{error}");
        assert!(std::fs::read_dir(reports.path()).unwrap().next().is_none(), "nothing is written");
    }
    for good in ["short", "a,b.c", "gpu_x-1"] {
        assert_eq!(partition_option(good).as_deref(), Ok(good));
    }
    for good in ["30", "30:00", "2:00:00", "1-0", "1-12:30", "1-0:0:0", "UNLIMITED"] {
        assert_eq!(time_option(good).as_deref(), Ok(good));
    }
    for bad in ["", "a b", "a,,b", "x;y", "a\rb"] {
        assert!(partition_option(bad).is_err(), "{bad:?}");
    }
    for bad in ["", "1:2:3:4", "-1", "1-", "1h", "30 ", "1:", "1-2-3"] {
        assert!(time_option(bad).is_err(), "{bad:?}");
    }
}

#[test]
fn shell_quoting_survives_quotes() {
    assert_eq!(shell_quote(Path::new("/a b/c'd")), r"'/a b/c'\''d'");
}
