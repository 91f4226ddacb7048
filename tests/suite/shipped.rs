//! The shipped campaigns (`campaigns/*.yaml`) as the tests use them, each simulated at most
//! once per test process, into one store that every test of the process shares
//! (`mdsolids-shipped/shipped-<pid>/` under `common::scratch_root`): a test that needs a shipped campaign's results or report asks
//! [`whole`] for its folder instead of running the campaign itself, so the pinned results and
//! the tests of the report's sentences read one run (docs/architecture.md, "Tests").
//!
//! [`covering_share`] is the cheaper fixture of a pinned test: per scene, only as many runs as
//! it takes for every value of every grid axis to be run once, each by the cheapest run that
//! has it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

use mdsolids::output::Layout;
use mdsolids::spec::RunSpec;

use crate::common::mdsolids_ok;

/// The store this process's tests share, under the scratch root (`common::scratch_root`); made
/// empty by its first caller. Folders that processes no longer running left behind (~20 MB
/// each, the last suite's among them) are removed then.
fn store() -> &'static Path {
    static STORE: OnceLock<PathBuf> = OnceLock::new();
    STORE.get_or_init(|| {
        let root = crate::common::scratch_root().join("mdsolids-shipped");
        let own = root.join(format!("shipped-{}", std::process::id()));
        for entry in std::fs::read_dir(&root).into_iter().flatten().flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            let left = name.strip_prefix("shipped-").is_some_and(|pid| !Path::new("/proc").join(pid).exists());
            if left || entry.path() == own {
                // Another test process may be removing the same leftover: whoever wins, it goes.
                let _ = std::fs::remove_dir_all(entry.path());
            }
        }
        std::fs::create_dir_all(&own).unwrap();
        own
    })
}

/// Runs `make` once per `key` in this process; a second caller waits for the first and gets
/// the same folder.
fn once(key: String, make: impl FnOnce() -> PathBuf) -> PathBuf {
    static MADE: Mutex<BTreeMap<String, Arc<OnceLock<PathBuf>>>> = Mutex::new(BTreeMap::new());
    let cell = MADE.lock().unwrap().entry(key).or_default().clone();
    cell.get_or_init(make).clone()
}

/// The folder (`<store>/<campaign>/`) of the whole shipped campaign `campaigns/<name>.yaml`,
/// run by `mdsolids run` the first time a test asks for it. Read it, do not change it: other
/// tests read it too.
pub fn whole(name: &str) -> PathBuf {
    once(format!("whole {name}"), || {
        let reports = store().join("whole");
        mdsolids_ok(&reports, &["run", &format!("campaigns/{name}.yaml")]);
        reports.join(name)
    })
}

/// The folder of a share of the shipped campaign `campaigns/<name>.yaml`: the runs
/// [`covering_runs`] picks, simulated in this process by the runner (`run_campaign`, which
/// stores them as `mdsolids run` does), then `mdsolids report` writes the tables and the report
/// from them (the campaign's other runs listed as missing).
pub fn covering_share(name: &str) -> PathBuf {
    once(format!("share {name}"), || {
        let file = format!("campaigns/{name}.yaml");
        let mut plan = mdsolids::plan::load(&crate::common::repo().join(&file)).unwrap();
        plan.campaign.runs = covering_runs(&plan.campaign.runs);
        let reports = store().join("share");
        mdsolids::runner::run_campaign(&plan, &Layout::new(&reports, name), None).unwrap();
        mdsolids_ok(&reports, &["report", &file]);
        reports.join(name)
    })
}

/// The runs of a covering share, in campaign order: scene by scene, the runs in the order of
/// the plan's cost estimate (`RunSpec::estimated_seconds`), each kept if it has a value of a
/// grid axis that no run kept before had; a scene without a grid keeps its one run. Every
/// code path a grid value selects (an integrator, a law, a support, a lattice type, a size
/// that splits rows over threads) is still run; only its combinations with the other axes'
/// values are thinned out.
fn covering_runs(runs: &[RunSpec]) -> Vec<RunSpec> {
    let mut order: Vec<usize> = (0..runs.len()).collect();
    order.sort_by(|&a, &b| runs[a].estimated_seconds().total_cmp(&runs[b].estimated_seconds()));
    let (mut seen, mut kept) = (BTreeSet::new(), BTreeSet::new());
    for index in order {
        let spec = &runs[index];
        let values: Vec<(String, String, String)> = match spec.varied.is_empty() {
            true => vec![(spec.scene.clone(), String::new(), String::new())],
            false => {
                spec.varied.iter().map(|(path, value)| (spec.scene.clone(), path.clone(), value.to_string())).collect()
            }
        };
        let mut new = false;
        for value in values {
            new |= seen.insert(value);
        }
        if new {
            kept.insert(index);
        }
    }
    kept.into_iter().map(|index| runs[index].clone()).collect()
}
