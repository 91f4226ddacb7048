//! Helpers shared by the integration tests.

use mdsolids::plan::{self, Estimates};
use mdsolids::runner::{RunRecord, execute_within};
use mdsolids::spec::{Budget, RunSpec};
use polars::prelude::{DataFrame, DataType};

/// The estimates this process's tests plan and run with (each network's modes, each
/// integrator's stability limits, the static solve's symbolic analyses), as the runs of one
/// campaign share their plan's: a test that plans an inline campaign and then runs it
/// estimates each network's modes once, not again in the runner, and tests of one network
/// share them (the cache is keyed by the network, `plan::network_key`). The suite spent ~4 of
/// its ~93 CPU-s in the Lanczos estimate of ω_max, half of it estimating again what the plan
/// had (2026-12-06). A test of the estimates themselves makes its own.
pub fn estimates() -> &'static Estimates {
    static SHARED: std::sync::OnceLock<Estimates> = std::sync::OnceLock::new();
    SHARED.get_or_init(Estimates::default)
}

/// The runs of an inline campaign (YAML text), planned with [`estimates`]; panics with the
/// spec error if it is invalid.
pub fn runs(yaml: &str) -> Vec<RunSpec> {
    let campaign = mdsolids::spec::parse("inline.yaml", yaml).unwrap_or_else(|e| panic!("{e}"));
    plan::plan_sharing("inline.yaml", campaign, estimates()).unwrap_or_else(|e| panic!("{e}")).runs
}

/// Runs `spec` as the program does, its stability read from [`estimates`].
pub fn execute(spec: &RunSpec) -> RunRecord {
    execute_within(spec, &Budget::default(), estimates())
}

/// Executes every run of an inline campaign.
pub fn execute_all(yaml: &str) -> Vec<RunRecord> {
    runs(yaml).iter().map(execute).collect()
}

/// Relative error (measured − reference)/reference.
pub fn relative(measured: Option<f64>, reference: Option<f64>) -> f64 {
    let (m, r) = (measured.expect("measured value"), reference.expect("reference value"));
    (m - r) / r
}

/// A pair campaign: `material` and `damping` are YAML flow maps, `sweep` the dt_per_tc values.
pub fn pair_campaign(material: &str, damping: &str, integrator: &str, sweep: &[f64]) -> String {
    format!(
        "version: 1\nname: t\nscenes:\n  - name: p\n    kind: pair\n    v0: 1.0\n    material: {material}\n    damping: {damping}\n    time: {{integrator: {integrator}}}\n    grid:\n      time.dt_per_tc: {sweep:?}\n"
    )
}

/// Asserts that every number in the results table of `records` is finite (nulls allowed).
pub fn assert_table_finite(records: &[RunRecord]) {
    let frame = mdsolids::table::results_frame(records).unwrap();
    for column in frame.columns() {
        if let Ok(values) = column.f64() {
            assert!(values.iter().flatten().all(f64::is_finite), "non-finite value in {}", column.name());
        }
    }
}

/// The `report.md` the binary renders for an inline campaign named `name` (run in a temporary
/// reports folder); panics with the binary's error output if the run fails.
pub fn report_of(name: &str, yaml: &str) -> String {
    let dir = scratch();
    let file = dir.path().join(format!("{name}.yaml"));
    std::fs::write(&file, yaml).unwrap();
    mdsolids_ok(dir.path(), &["run", file.to_str().unwrap()]);
    std::fs::read_to_string(dir.path().join(name).join("report.md")).unwrap()
}

/// Where the tests' scratch folders go: `/dev/shm` (memory) where the machine has it, else the
/// system's temporary folder. The suite makes and removes ~10 000 short-lived files; on this
/// project's ext4 disk their inode allocation and write-back cost ~1.5 s of its ~50 s on two
/// cores (48.3 and 48.6 s against 50.0 and 49.7 s, alternating). What the tests check does not
/// depend on the file system: renames are atomic on both, and no test can check durability.
pub fn scratch_root() -> &'static std::path::Path {
    static ROOT: std::sync::OnceLock<std::path::PathBuf> = std::sync::OnceLock::new();
    ROOT.get_or_init(|| {
        let memory = std::path::Path::new("/dev/shm");
        let usable = tempfile::Builder::new().prefix("mdsolids-probe-").tempdir_in(memory).is_ok();
        if usable { memory.to_path_buf() } else { std::env::temp_dir() }
    })
}

/// A fresh scratch folder under [`scratch_root`], removed when dropped.
pub fn scratch() -> tempfile::TempDir {
    tempfile::Builder::new().prefix("mdsolids-test-").tempdir_in(scratch_root()).expect("a scratch folder")
}

/// The program under test: `../src/main.rs` built as this package's binary (tests/Cargo.toml).
pub const MDSOLIDS: &str = env!("CARGO_BIN_EXE_mdsolids-tested");

/// The repository's top folder, with the campaigns, docs and snapshots the tests read (this
/// package, tests/Cargo.toml, sits one below it).
pub fn repo() -> &'static std::path::Path {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("tests/ sits in the repository")
}

/// Runs the binary with `--reports reports` and `args` from the repository's top folder.
pub fn mdsolids(reports: &std::path::Path, args: &[&str]) -> std::process::Output {
    std::process::Command::new(MDSOLIDS)
        .arg("--reports")
        .arg(reports)
        .args(args)
        .current_dir(repo())
        .output()
        .expect("the binary runs")
}

/// [`mdsolids`], asserting that it succeeded, with its error output if not.
pub fn mdsolids_ok(reports: &std::path::Path, args: &[&str]) -> std::process::Output {
    let out = mdsolids(reports, args);
    assert!(out.status.success(), "mdsolids {args:?}: {}", text(&out.stderr));
    out
}

/// A command's output as text.
pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// The first number in `text` after `marker` (the report writes 4 to 6 significant digits).
pub fn number_after(text: &str, marker: &str) -> f64 {
    let rest = &text[text.find(marker).unwrap_or_else(|| panic!("no {marker:?} in {text}")) + marker.len()..];
    // The report writes a minus sign (−), not a hyphen, before a negative number.
    let (sign, rest) = rest.strip_prefix('−').map_or((1.0, rest), |magnitude| (-1.0, magnitude));
    let end = rest.find(|c: char| !(c.is_ascii_digit() || ".e-+".contains(c))).unwrap_or(rest.len());
    // A sentence's full stop is not a decimal point.
    let magnitude: f64 =
        rest[..end].trim_end_matches('.').parse().unwrap_or_else(|_| panic!("no number after {marker:?}: {rest}"));
    sign * magnitude
}

/// The report line that contains `marker`.
pub fn line_with<'a>(report: &'a str, marker: &str) -> &'a str {
    report.lines().find(|l| l.contains(marker)).unwrap_or_else(|| panic!("no line with {marker:?}"))
}

/// The coursework's steel block (10 × 10, k_d/k = 0.5) cut at 0.3 and pulled along x at 1 kN
/// per node, with springs of `law`, over `seeds`: seed 3's load buckles its network, seed 1's
/// does not (`lattice::a_network_its_load_buckles_settles_by_md_and_statically_in_one_softer_state`).
pub fn cut_steel_block(law: &str, seeds: &str) -> String {
    format!(
        "version: 1\nname: rnd\nscenes:\n  - name: random\n    kind: lattice\n    material: {{mass: 0.785, k: 2.0e9, law: {law}}}\n    \
         geometry: {{spacing: 0.1, depth: 0.01}}\n    damping: {{restitution: 0.5, background: 1000.0}}\n    \
         time: {{integrator: velocity-verlet}}\n    lattice: {{size: 10, k_diag_ratio: 0.5, cut_fraction: 0.3}}\n    \
         load: {{case: tensile-x, per_node: 1000.0}}\n    relax: {{residual_force: 1.0e-6, max_tc: 20000}}\n    \
         grid:\n      seed: {seeds}\n"
    )
}

/// The least-squares slope of ln y against ln x over `points`.
pub fn log_slope(points: &[(f64, f64)]) -> f64 {
    let logs: Vec<(f64, f64)> = points.iter().map(|(x, y)| (x.ln(), y.ln())).collect();
    let n = logs.len() as f64;
    let (sx, sy) = logs.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
    let (sxx, sxy) = logs.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x * x, b + x * y));
    (n * sxy - sx * sy) / (n * sxx - sx * sx)
}

/// The value and uncertainty the report writes after `marker`, as `(a ± b)eP` or `a ± b`.
pub fn value_after(text: &str, marker: &str) -> (f64, f64) {
    let rest = &text[text.find(marker).unwrap_or_else(|| panic!("no {marker:?} in {text}")) + marker.len()..];
    let (inner, power) = match rest.strip_prefix('(') {
        Some(open) => {
            let (inner, tail) = open.split_once(")e").unwrap_or_else(|| panic!("no power after {marker:?}: {rest}"));
            let digits: String = tail.chars().take_while(|c| c.is_ascii_digit() || *c == '-').collect();
            (inner, digits.parse::<i32>().unwrap())
        }
        None => (rest, 0),
    };
    let (value, uncertainty) = inner.split_once(" ± ").unwrap_or_else(|| panic!("no ± after {marker:?}: {rest}"));
    let uncertainty: String = uncertainty.chars().take_while(|c| c.is_ascii_digit() || *c == '.').collect();
    let scale = 10f64.powi(power);
    (value.parse::<f64>().unwrap() * scale, uncertainty.parse::<f64>().unwrap() * scale)
}

/// Column `name` of `frame` as numbers.
pub fn numbers(frame: &DataFrame, name: &str) -> Vec<Option<f64>> {
    frame.column(name).unwrap().cast(&DataType::Float64).unwrap().f64().unwrap().iter().collect()
}
