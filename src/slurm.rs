//! Slurm job arrays: task I of an N-task array runs `mdsolids run --shard I/N` into the shared
//! store, and a report job that depends on the array with `afterany` (it starts when every
//! task has ended, failed or not) merges whatever is stored.

use anyhow::Context;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::output::{Layout, write_atomically};

/// What the scripts run and how Slurm should schedule it. Paths are absolute: the jobs may
/// start on any node, in any directory.
#[derive(Clone, Debug)]
pub struct ArrayJob {
    /// The `mdsolids` binary.
    pub exe: PathBuf,
    /// The reports directory (on a file system every node sees).
    pub reports: PathBuf,
    /// The campaign file.
    pub campaign_file: PathBuf,
    /// The campaign's name (job names, and the directory under `reports`).
    pub campaign: String,
    /// Array tasks, one shard each.
    pub tasks: usize,
    /// `--partition`, if given.
    pub partition: Option<String>,
    /// `--time` limit per job, if given (Slurm's formats, e.g. `30`, `2:00:00`, `1-0`).
    pub time: Option<String>,
    /// CPUs per array task; also the task's `--jobs`.
    pub cpus_per_task: usize,
}

/// The scripts written for one campaign, under `<reports>/<campaign>/slurm/`.
#[derive(Clone, Debug)]
pub struct Scripts {
    /// The job array.
    pub array: PathBuf,
    /// The report job.
    pub report: PathBuf,
    /// Submits the array, then the report job with `--dependency=afterany:<array>`.
    pub submit: PathBuf,
}

/// Job ids returned by `sbatch`.
#[derive(Clone, Debug)]
pub struct Submitted {
    /// The array job.
    pub array: String,
    /// The report job.
    pub report: String,
}

/// Writes `array.sh`, `report.sh` and `submit.sh` into `<reports>/<campaign>/slurm/`, where
/// the jobs' logs go too.
pub fn write_scripts(job: &ArrayJob) -> anyhow::Result<Scripts> {
    anyhow::ensure!(job.tasks >= 1, "--tasks must be ≥ 1");
    anyhow::ensure!(job.cpus_per_task >= 1, "--cpus-per-task must be ≥ 1");
    // `#SBATCH --output=<path>` takes no shell quoting.
    anyhow::ensure!(
        !job.reports.to_string_lossy().contains(char::is_whitespace),
        "the reports directory '{}' contains white space, which #SBATCH --output cannot hold",
        job.reports.display()
    );
    // Each becomes an `#SBATCH` line: a line break in one would add a line of shell to the script.
    if let Some(partition) = &job.partition {
        partition_option(partition).map_err(anyhow::Error::msg)?;
    }
    if let Some(time) = &job.time {
        time_option(time).map_err(anyhow::Error::msg)?;
    }
    let dir = Layout::new(&job.reports, &job.campaign).file("slurm");
    let scripts = Scripts { array: dir.join("array.sh"), report: dir.join("report.sh"), submit: dir.join("submit.sh") };
    write_atomically(&scripts.array, array_script(job, &dir).as_bytes())?;
    write_atomically(&scripts.report, report_script(job, &dir).as_bytes())?;
    write_atomically(&scripts.submit, submit_script(job, &scripts).as_bytes())?;
    Ok(scripts)
}

/// `--partition`: one partition name or several separated by commas, each 1 to 64 ASCII
/// letters, digits, `-`, `_` and `.`.
pub fn partition_option(text: &str) -> Result<String, String> {
    let name =
        |p: &str| (1..=64).contains(&p.len()) && p.chars().all(|c| c.is_ascii_alphanumeric() || "-_.".contains(c));
    if text.split(',').all(name) {
        Ok(text.to_string())
    } else {
        Err(format!(
            "{text:?}: a Slurm partition is 1 to 64 letters, digits, '-', '_' and '.' (several separated by commas)"
        ))
    }
}

/// `--time`: one of Slurm's time formats, `M`, `M:S`, `H:M:S`, `D-H`, `D-H:M`, `D-H:M:S`, or
/// `UNLIMITED`/`INFINITE`; at most 32 characters.
pub fn time_option(text: &str) -> Result<String, String> {
    let clock = |t: &str| {
        let parts: Vec<&str> = t.split(':').collect();
        parts.len() <= 3 && parts.iter().all(|p| !p.is_empty() && p.chars().all(|c| c.is_ascii_digit()))
    };
    let valid = text.len() <= 32
        && (["UNLIMITED", "INFINITE"].contains(&text)
            || match text.split_once('-') {
                Some((days, rest)) => !days.is_empty() && days.chars().all(|c| c.is_ascii_digit()) && clock(rest),
                None => clock(text),
            });
    if valid {
        Ok(text.to_string())
    } else {
        Err(format!(
            "{text:?}: a Slurm time limit is minutes, M:S, H:M:S, D-H, D-H:M or D-H:M:S (digits only), or UNLIMITED"
        ))
    }
}

/// Submits the array, then the report job depending on it with `afterany`.
pub fn submit(scripts: &Scripts) -> anyhow::Result<Submitted> {
    let array = sbatch(&[], &scripts.array)?;
    let report = sbatch(&[format!("--dependency=afterany:{array}")], &scripts.report)?;
    Ok(Submitted { array, report })
}

/// `sbatch --parsable [options] script`, returning the job id.
fn sbatch(options: &[String], script: &Path) -> anyhow::Result<String> {
    let out = Command::new("sbatch")
        .arg("--parsable")
        .args(options)
        .arg(script)
        .output()
        .context("cannot run sbatch (is this a Slurm submit host?); the scripts are written, see submit.sh")?;
    anyhow::ensure!(
        out.status.success(),
        "sbatch {} failed ({}): {}",
        script.display(),
        out.status,
        String::from_utf8_lossy(&out.stderr).trim()
    );
    // `--parsable` prints `id` or `id;cluster`.
    let stdout = String::from_utf8_lossy(&out.stdout);
    let id = stdout.trim().split(';').next().unwrap_or_default().to_string();
    anyhow::ensure!(!id.is_empty(), "sbatch {} printed no job id", script.display());
    Ok(id)
}

/// The `#SBATCH` lines both jobs share.
fn common_options(job: &ArrayJob) -> String {
    let mut lines = format!("#SBATCH --cpus-per-task={}\n", job.cpus_per_task);
    if let Some(partition) = &job.partition {
        lines += &format!("#SBATCH --partition={partition}\n");
    }
    if let Some(time) = &job.time {
        lines += &format!("#SBATCH --time={time}\n");
    }
    lines
}

fn array_script(job: &ArrayJob, dir: &Path) -> String {
    format!(
        "#!/bin/bash\n\
         # Written by `mdsolids slurm`: task I of this array runs share I of {tasks} of campaign '{name}'\n\
         # and stores its runs under the reports directory. Runs already stored are skipped, so a\n\
         # resubmission only runs what is missing. report.sh merges the store afterwards.\n\
         #SBATCH --job-name=mdsolids-{name}\n\
         #SBATCH --array=0-{last}\n\
         {common}\
         #SBATCH --output={log}\n\
         exec {exe} --reports {reports} run {campaign} --shard \"$SLURM_ARRAY_TASK_ID/{tasks}\" --jobs {jobs}\n",
        tasks = job.tasks,
        name = job.campaign,
        last = job.tasks - 1,
        common = common_options(job),
        log = dir.join("array-%A_%a.log").display(),
        exe = shell_quote(&job.exe),
        reports = shell_quote(&job.reports),
        campaign = shell_quote(&job.campaign_file),
        jobs = job.cpus_per_task,
    )
}

fn report_script(job: &ArrayJob, dir: &Path) -> String {
    format!(
        "#!/bin/bash\n\
         # Written by `mdsolids slurm`: merges the stored runs of campaign '{name}' into its tables and\n\
         # report. Submitted with --dependency=afterany on the array, so it also runs when a task\n\
         # failed; runs without a stored result are listed in this job's log.\n\
         #SBATCH --job-name=mdsolids-{name}-report\n\
         {common}\
         #SBATCH --output={log}\n\
         exec {exe} --reports {reports} report {campaign}\n",
        name = job.campaign,
        common = common_options(job),
        log = dir.join("report-%j.log").display(),
        exe = shell_quote(&job.exe),
        reports = shell_quote(&job.reports),
        campaign = shell_quote(&job.campaign_file),
    )
}

fn submit_script(job: &ArrayJob, scripts: &Scripts) -> String {
    format!(
        "#!/bin/bash\n\
         # Written by `mdsolids slurm`: submits the {tasks}-task array of campaign '{name}', then its\n\
         # report job, which waits for every task to end (afterany: a failed task does not block it).\n\
         set -euo pipefail\n\
         array=$(sbatch --parsable {array})\n\
         array=${{array%%;*}}\n\
         report=$(sbatch --parsable --dependency=afterany:\"$array\" {report})\n\
         report=${{report%%;*}}\n\
         echo \"array job $array ({tasks} tasks), report job $report\"\n",
        tasks = job.tasks,
        name = job.campaign,
        array = shell_quote(&scripts.array),
        report = shell_quote(&scripts.report),
    )
}

/// `path` as one shell word: in single quotes, each `'` written as `'\''`.
pub fn shell_quote(path: &Path) -> String {
    format!("'{}'", path.to_string_lossy().replace('\'', r"'\''"))
}
