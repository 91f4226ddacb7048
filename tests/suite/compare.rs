//! `mdsolids compare`, through the binary: two small campaigns, one with linear springs and one
//! with power-law springs, are run and compared; then the refusals of directories that are not
//! campaign reports.

use polars::prelude::{CsvReadOptions, DataFrame, ParquetReader, SerReader};
use std::path::Path;

use crate::common::{line_with, mdsolids, mdsolids_ok, text};

/// Linear springs: a collision over two time steps and a wave chain over two impact speeds.
const LINEAR: &str = "version: 1
name: linear
defaults:
  material: {mass: 1.0, k: 1.0}
scenes:
  - name: pair
    kind: pair
    material: {contact: true}
    v0: 1.0
    grid:
      time.dt_per_tc: [20, 50]
  - name: wave
    kind: chain
    n: 30
    node: first
    wave: {}
    time: {duration_tc: 60}
    grid:
      v0: [0.01, 0.1]
";

/// The same scenes with power-law springs; the pair also varies β, which the linear campaign
/// does not, so each linear pair run meets two of these.
const POWER: &str = "version: 1
name: power
defaults:
  material: {mass: 1.0, k: 1.0, law: power}
scenes:
  - name: pair
    kind: pair
    material: {contact: true}
    v0: 1.0
    grid:
      time.dt_per_tc: [20, 50]
      material.beta: [1.5, 2.0]
  - name: wave
    kind: chain
    n: 30
    node: first
    wave: {}
    material: {contact: true}
    time: {duration_tc: 60}
    grid:
      v0: [0.01, 0.1]
";

/// Runs the binary and returns its standard output, failing the test with its error otherwise.
fn succeed(reports: &Path, args: &[&str]) -> String {
    text(&mdsolids_ok(reports, args).stdout)
}

/// Runs the binary, expects it to refuse, and returns its error message.
fn refuse(reports: &Path, args: &[&str]) -> String {
    let out = mdsolids(reports, args);
    assert!(!out.status.success(), "{args:?} was accepted");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
    stderr
}

fn read(path: &Path) -> DataFrame {
    ParquetReader::new(std::fs::File::open(path).unwrap()).finish().unwrap()
}

fn floats(frame: &DataFrame, name: &str) -> Vec<Option<f64>> {
    frame.column(name).unwrap().f64().unwrap().iter().collect()
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 { values[n / 2] } else { 0.5 * (values[n / 2 - 1] + values[n / 2]) }
}

/// The numbers of a sentence, in order (words that read as numbers once stripped of punctuation).
fn numbers(sentence: &str) -> Vec<f64> {
    sentence.split_whitespace().filter_map(|w| w.trim_matches(|c| ",.:;()".contains(c)).parse().ok()).collect()
}

fn texts(frame: &DataFrame, name: &str) -> Vec<String> {
    frame.column(name).unwrap().str().unwrap().iter().map(|s| s.unwrap().to_string()).collect()
}

/// Runs both campaigns under `reports`.
fn run_campaigns(reports: &Path) {
    for (name, yaml) in [("linear.yaml", LINEAR), ("power.yaml", POWER)] {
        let file = reports.join(name);
        std::fs::write(&file, yaml).unwrap();
        succeed(reports, &["run", file.to_str().unwrap()]);
    }
}

#[test]
fn linear_against_power_law() {
    let dir = crate::common::scratch();
    let reports = dir.path();
    run_campaigns(reports);
    let (a, b) = (reports.join("linear"), reports.join("power"));
    let stdout = succeed(reports, &["compare", a.to_str().unwrap(), b.to_str().unwrap()]);
    let out = reports.join("compare-linear-vs-power");
    assert!(stdout.contains("6 joined rows") && stdout.contains(out.to_str().unwrap()), "{stdout}");

    // pair: 2 linear runs × 2 values of β on the power side (β is no key); wave: joined on v0.
    let joined = read(&out.join("compare.parquet"));
    assert_eq!(joined.height(), 6);
    let scenes = texts(&joined, "scene");
    assert_eq!(scenes.iter().filter(|s| *s == "pair").count(), 4);
    assert_eq!(scenes.iter().filter(|s| *s == "wave").count(), 2);
    assert!(texts(&joined, "status_a").iter().chain(&texts(&joined, "status_b")).all(|s| s == "ok"));
    let run_a = texts(&joined, "run_id_a");
    assert!(run_a[..4].iter().all(|id| run_a[..4].iter().filter(|other| *other == id).count() == 2));
    assert_eq!(floats(&joined, "v0_a")[4..], floats(&joined, "v0_b")[4..], "wave rows meet at equal v0");

    // The values are the runs' own: A's come from A's table row by row. Exact equality: they
    // are copied, not computed, and Parquet stores f64 bit for bit.
    let results_a = read(&a.join("results.parquet"));
    let ids = texts(&results_a, "run_id");
    let durations = floats(&results_a, "contact_duration");
    let duration_a = floats(&joined, "contact_duration_a");
    for (row, id) in run_a.iter().enumerate() {
        let source = ids.iter().position(|i| i == id).unwrap();
        assert_eq!(duration_a[row].map(f64::to_bits), durations[source].map(f64::to_bits), "{id}");
    }

    // The ratio is B/A. Exact equality: it is the same IEEE division of the same stored values.
    let duration_b = floats(&joined, "contact_duration_b");
    let ratio = floats(&joined, "contact_duration_ratio");
    let theory_ratio = floats(&joined, "contact_duration_theory_ratio");
    for row in 0..4 {
        let (da, db) = (duration_a[row].unwrap(), duration_b[row].unwrap());
        assert_eq!(ratio[row], Some(db / da), "row {row}");
        // The measured ratio follows the analytical one. Tolerance 3e-3: it bounds the sum of the
        // two sides' errors against their analytical durations at t_c/20 (measured: 1.0e-3
        // linear, 1.2e-3 and 1.5e-3 for β = 1.5 and 2; second order, so 4× that at t_c/10),
        // which bounds the ratio's error whatever their signs; at t_c/50 it is 6× looser still.
        let expected = theory_ratio[row].unwrap();
        assert!((ratio[row].unwrap() / expected - 1.0).abs() < 3e-3, "row {row}: {ratio:?} against {expected}");
    }
    assert!(ratio[4..].iter().all(Option::is_none), "wave chains have no contact duration");

    let csv = std::fs::read_to_string(out.join("compare.csv")).unwrap();
    assert_eq!(csv.lines().count(), 7, "a header and the six rows");
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    let figure = "plots/pair-contact_duration-vs-time.dt_per_tc.svg";
    assert!(out.join(figure).is_file() && report.contains(figure), "{figure} missing or not linked");
    assert!(report.contains("Varied in B only: `material.beta`"), "{report}");
    assert!(report.contains("| wave |") && report.contains("| linear | power |"), "exponent table: {report}");
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("<table>") && html.contains(figure));
    opens_with_what_differs(&report, &joined);
    assert!(report.contains(&format!("]({figure})")), "the pair's contact duration is shown, not only linked");

    other_comparisons(reports, &a, &b);
}

/// A campaign against itself: nothing differs, and the report says so. Without B's summary the
/// exponent section says which file is missing; --out moves it all.
fn other_comparisons(reports: &Path, a: &Path, b: &Path) {
    let same = reports.join("same");
    succeed(reports, &["compare", a.to_str().unwrap(), a.to_str().unwrap(), "--out", same.to_str().unwrap()]);
    let report = std::fs::read_to_string(same.join("report.md")).unwrap();
    assert!(report.contains("No measured quantity differs beyond its noise"), "{report}");
    assert!(report.contains("No input differs between the two campaigns"), "{report}");

    std::fs::remove_file(b.join("summary.csv")).unwrap();
    let elsewhere = reports.join("elsewhere");
    succeed(reports, &["compare", a.to_str().unwrap(), b.to_str().unwrap(), "--out", elsewhere.to_str().unwrap()]);
    let report = std::fs::read_to_string(elsewhere.join("report.md")).unwrap();
    let missing = b.join("summary.csv");
    assert!(report.contains(&format!("`{}` does not exist", missing.display())), "{report}");
}

/// The report opens with what differs (issue 16, item 8): the pair's contact duration in a
/// sentence with A, B and B/A as the joined table has them (medians over the pair's rows, each
/// run once, and of their ratios, with the smallest and largest ratio), before the appendix;
/// the mass, equal on both sides, and the timings only in the appendix.
fn opens_with_what_differs(report: &str, joined: &DataFrame) {
    let (main, appendix) = report.split_at(report.find("## Appendix").expect("an appendix"));
    let scenes = texts(joined, "scene");
    let pair: Vec<usize> = (0..joined.height()).filter(|&r| scenes[r] == "pair").collect();
    let once = |side: &str| {
        let (ids, values) =
            (texts(joined, &format!("run_id_{side}")), floats(joined, &format!("contact_duration_{side}")));
        let mut seen = std::collections::BTreeMap::new();
        for &r in &pair {
            seen.entry(ids[r].clone()).or_insert(values[r].unwrap());
        }
        seen.into_values().collect::<Vec<f64>>()
    };
    let ratios: Vec<f64> = pair.iter().map(|&r| floats(joined, "contact_duration_ratio")[r].unwrap()).collect();
    let lo = ratios.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = ratios.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let expected = [median(once("a")), median(once("b")), median(ratios.clone()), pair.len() as f64, lo, hi];
    let sentence = main.lines().find(|l| l.starts_with("- In pair, contact_duration (s) is ")).expect(main);
    let stated = numbers(sentence);
    assert_eq!(stated.len(), expected.len(), "{sentence}");
    for (stated, expected) in stated.iter().zip(expected) {
        // Four significant digits: within 5e-4 relative.
        assert!((stated / expected - 1.0).abs() <= 5e-4, "{sentence}: {stated} against {expected}");
    }
    assert_eq!(floats(joined, "mass_a"), floats(joined, "mass_b"), "the mass is an input equal on both sides");
    assert!(!main.contains("`mass`") && appendix.contains("| `mass` |"), "{main}");
    assert!(!main.contains("`wall_s`") && appendix.contains("| `wall_s` |"), "{main}");
    assert!(main.contains("predicted 0.2000 = (β−1)/(β+1)) in B"), "the wave's exponent against its law: {main}");
}

#[test]
fn refuses_what_is_not_a_report() {
    let dir = crate::common::scratch();
    let reports = dir.path();
    let missing = reports.join("missing");
    let empty = reports.join("empty");
    std::fs::create_dir(&empty).unwrap();
    let (missing, empty_name) = (missing.to_str().unwrap(), empty.to_str().unwrap());

    let error = refuse(reports, &["compare", missing, empty_name]);
    assert!(error.contains(&format!("report directory '{missing}' does not exist")), "{error}");
    let error = refuse(reports, &["compare", empty_name, empty_name]);
    assert!(error.contains(&format!("'{}' is missing", empty.join("results.parquet").display())), "{error}");
    std::fs::write(empty.join("results.parquet"), b"not parquet").unwrap();
    let error = refuse(reports, &["compare", empty_name, empty_name]);
    assert!(error.contains(&format!("cannot read the table '{}'", empty.join("results.parquet").display())), "{error}");
    assert!(!reports.join("compare-empty-vs-empty").exists(), "nothing is written for a refused comparison");
}

/// `--out` may not be a campaign's folder (issue 14, item 13): it would overwrite its report.
#[test]
fn refuses_to_write_into_a_campaign_folder() {
    let dir = crate::common::scratch();
    let reports = dir.path();
    run_campaigns(reports);
    let (a, b) = (reports.join("linear"), reports.join("power"));
    let report = std::fs::read(a.join("report.md")).unwrap();
    let error = refuse(reports, &["compare", a.to_str().unwrap(), b.to_str().unwrap(), "--out", a.to_str().unwrap()]);
    assert!(error.contains("is the report folder of campaign file") && error.contains("linear.yaml"), "{error}");
    assert_eq!(std::fs::read(a.join("report.md")).unwrap(), report, "A's report is untouched");
    assert!(!a.join("compare.csv").exists());
}

/// A damped contact pair whose dashpot is set for r = 0.5 by the linear two-body formula, with
/// the force law `law`.
fn damped_pair(name: &str, law: &str) -> String {
    format!(
        "version: 1\nname: {name}\nscenes:\n  - name: pair\n    kind: pair\n    \
         material: {{mass: 1.0, k: 1.0, law: {law}, contact: true}}\n    damping: {{restitution: 0.5}}\n    v0: 1.0\n"
    )
}

/// Runs the campaigns `campaign(name, law)` makes for A = (`a`, linear springs) and B = (`b`,
/// Hertz springs) under `reports` and compares A with B: the command's output and the
/// comparison's report.md.
fn linear_against_hertz(
    reports: &Path,
    (a, b): (&str, &str),
    campaign: impl Fn(&str, &str) -> String,
) -> (String, String) {
    compare_two(reports, [(a, "linear"), (b, "hertz")], campaign)
}

/// Runs the campaigns `campaign(name, value)` makes for A and B, each a (name, value), under
/// `reports` and compares A with B: the command's output and the comparison's report.md.
fn compare_two(
    reports: &Path,
    [(a, value_a), (b, value_b)]: [(&str, &str); 2],
    campaign: impl Fn(&str, &str) -> String,
) -> (String, String) {
    for (name, value) in [(a, value_a), (b, value_b)] {
        let file = reports.join(format!("{name}.yaml"));
        std::fs::write(&file, campaign(name, value)).unwrap();
        succeed(reports, &["run", file.to_str().unwrap()]);
    }
    let (dir_a, dir_b) = (reports.join(a), reports.join(b));
    let stdout = succeed(reports, &["compare", dir_a.to_str().unwrap(), dir_b.to_str().unwrap()]);
    let report = std::fs::read_to_string(reports.join(format!("compare-{a}-vs-{b}")).join("report.md")).unwrap();
    (stdout, report)
}

/// The page opens with what differs physically (issue 33): each physical quantity's medians on
/// both sides in a sentence, before the diagnostics; and a restitution that misses the target
/// its dashpot was set for is said, side by side. The claim flips between the sides: the linear
/// pair meets r = 0.5 (to 1.3e-3 at the default step, well inside the 1 % the sentence allows), the Hertz
/// pair, whose γ comes from the same linear formula, does not (r ≈ 0.3 measured in the Hertz twin).
#[test]
fn the_physics_comes_first_and_a_missed_restitution_is_said() {
    let dir = crate::common::scratch();
    let reports = dir.path();
    let (_, report) = linear_against_hertz(reports, ("lin", "hertz"), damped_pair);
    let (a, b) = (reports.join("lin"), reports.join("hertz"));
    let physics = report.find("## What differs physically").expect("a physics section");
    assert!(physics < report.find("## What differs\n").expect("the diagnostics"), "{report}");
    assert!(!report.contains("(dimensionless)"), "{report}");
    let r = |dir: &Path| floats(&read(&dir.join("results.parquet")), "restitution")[0].unwrap();
    let (r_a, r_b) = (r(&a), r(&b));
    assert!((r_a / 0.5 - 1.0).abs() < 5e-3 && (r_b / 0.5 - 1.0).abs() > 0.01, "A {r_a}, B {r_b}");
    let line = report.lines().find(|l| l.starts_with("- The restitution r, in pair: ")).expect(&report);
    let stated = numbers(line);
    // Four significant digits: within 5e-4 relative.
    for (stated, expected) in stated.iter().zip([r_a, r_b, r_b / r_a]) {
        assert!((stated / expected - 1.0).abs() <= 5e-4, "{line}: {stated} against {expected}");
    }
    let missed = report.lines().find(|l| l.contains("In B, pair's restitution r = ")).expect(&report);
    assert!((numbers(missed)[0] / r_b - 1.0).abs() <= 5e-4 && missed.contains("0.5"), "{missed}");
    assert!(!report.contains("In A, pair's restitution"), "the linear pair meets its target: {report}");
}

#[test]
fn a_static_solves_time_is_a_cost_not_a_difference() {
    // `solve_s` (the static answer's share of `wall_s`) is a timing like `wall_s` and
    // `loop_s`: two lattice campaigns had it among the "measured quantities that differ".
    let dir = crate::common::scratch();
    let reports = dir.path();
    let tensile = |name: &str, law: &str| {
        format!(
            "version: 1\nname: {name}\nscenes:\n  - name: tens\n    kind: lattice\n    material: {{law: {law}}}\n    \
             lattice: {{size: 4, k_diag_ratio: 0.5}}\n    load: {{case: tensile, per_node: 0.001}}\n    relax: {{method: fire}}\n"
        )
    };
    let (_, report) = linear_against_hertz(reports, ("lin", "hz"), tensile);
    let differ = report.split("### Measured quantities that differ beyond noise").nth(1).unwrap();
    let differ = differ.split("### Inputs that differ").next().unwrap();
    assert!(differ.contains("`youngs_modulus`"), "the moduli differ: {differ}");
    assert!(!differ.contains("`solve_s`"), "{differ}");
}

/// A small packing campaign of contact law `law` over two fractions and two seeds.
fn packings(name: &str, law: &str) -> String {
    format!(
        "version: 1\nname: {name}\nscenes:\n  - name: pk\n    kind: packing\n    packing: {{n: 16}}\n    \
         material: {{law: {law}}}\n    grid:\n      packing.fraction: [0.86, 0.9]\n      seed: [1, 2]\n"
    )
}

/// Two packing campaigns that both vary the seed join seed with seed: each side's 4 runs meet
/// their one twin (4 rows, not 8 of every seed against every other, different random states);
/// and a packing's 2D moduli and pressure are written in N/m, not the lattices' Pa.
#[test]
fn packings_are_joined_seed_by_seed_and_their_moduli_are_per_length() {
    let dir = crate::common::scratch();
    let reports = dir.path();
    let (stdout, report) = linear_against_hertz(reports, ("lin", "hz"), packings);
    assert!(stdout.contains("4 joined rows"), "{stdout}");
    let out = reports.join("compare-lin-vs-hz");
    let joined = read(&out.join("compare.parquet"));
    assert_eq!(floats(&joined, "seed_a"), floats(&joined, "seed_b"));
    // The quantities that differ beyond the seeds' spread are in the table with their unit:
    // the pressure always (Hertz's is several times lower), the moduli where the seeds allow.
    let differ = section(&report, "### Measured quantities that differ beyond noise");
    assert!(differ.contains("| `pressure` |"), "{differ}");
    for quantity in ["shear_modulus_2d", "bulk_modulus_2d", "pressure"] {
        if let Some(line) = differ.lines().find(|l| l.contains(&format!("| `{quantity}` |"))) {
            assert!(line.contains("| N/m |"), "{line}");
        }
    }
}

/// Packings of two sizes, N = 16 and 32, over four fractions and three seeds.
fn packings_of_two_sizes(name: &str, law: &str) -> String {
    format!(
        "version: 1\nname: {name}\nscenes:\n  - name: pk\n    kind: packing\n    packing: {{n: 16}}\n    \
         material: {{law: {law}}}\n    grid:\n      packing.n: [16, 32]\n      packing.fraction: [0.86, 0.88, 0.9, 0.92]\n      \
         seed: [1, 2, 3]\n"
    )
}

/// A packing's scalings are judged at its scene's largest N only, as the report's item Jamming
/// judges them: at N = 16 the finite size bends them far beyond the 0.15 allowed (z − 4 ∝
/// Δφ^0.75 and G ∝ Δφ^−0.77 measured, against ½ and ½), so `compare` had called them misses of
/// the spring laws. `summary.csv` now says each fit's particles; the N = 16 fits are counted as
/// not judged, and no N = 16 group is named among the misses.
#[test]
fn packing_scalings_are_judged_at_the_largest_size_only() {
    let dir = crate::common::scratch();
    let reports = dir.path();
    let (_, report) = linear_against_hertz(reports, ("lin", "hz"), packings_of_two_sizes);
    // summary.csv: its group label (`n=16`) and its `particles` column agree, row by row.
    let summary = std::fs::read_to_string(reports.join("lin").join("summary.csv")).unwrap();
    let header: Vec<&str> = summary.lines().next().unwrap().split(',').collect();
    let at = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let mut small = 0;
    for row in summary.lines().skip(1).map(|l| l.split(',').collect::<Vec<&str>>()) {
        assert_eq!(row[at("group")].trim_start_matches("n="), row[at("particles")], "{row:?}");
        small += usize::from(row[at("particles")] == "16");
    }
    assert!(small > 0, "{summary}");
    let verdict = line_with(&report, "fitted exponents");
    assert!(verdict.contains(&format!("at a scene's smaller N ({} fits) are not judged", 2 * small)), "{verdict}");
    assert!(!verdict.contains("(n=16)"), "{verdict}");
}

/// A contact chain of 30 hit at its first particle at two speeds: a fit through two points.
fn chain_hit_twice(name: &str, law: &str) -> String {
    format!(
        "version: 1\nname: {name}\nscenes:\n  - name: wave\n    kind: chain\n    n: 30\n    node: first\n    \
         material: {{law: {law}, contact: true}}\n    wave: {{}}\n    grid:\n      v0: [0.01, 0.1]\n"
    )
}

/// The appendix's exponent table gives no R² for a fit through two points (R² = 1 by
/// construction: it had shown 1.000000), but the point count; three speeds give an R² again.
#[test]
fn a_fit_through_two_points_shows_no_r_squared_in_the_comparison() {
    let dir = crate::common::scratch();
    let reports = dir.path();
    let (_, report) = linear_against_hertz(reports, ("two-a", "two-b"), chain_hit_twice);
    let row = report.lines().find(|l| l.starts_with("| wave |  | sound_speed |")).unwrap_or_else(|| panic!("{report}"));
    assert!(row.ends_with("| – (2 points) | – (2 points) |"), "{row}");
    let three = |name: &str, law: &str| chain_hit_twice(name, law).replace("[0.01, 0.1]", "[0.01, 0.03, 0.1]");
    let (_, report) = linear_against_hertz(reports, ("three-a", "three-b"), three);
    let row = report.lines().find(|l| l.starts_with("| wave |  | sound_speed |")).unwrap_or_else(|| panic!("{report}"));
    assert!(!row.contains("points"), "{row}");
}

/// A contact pair of force law `law` over two impact speeds and two restitution targets: r = 1
/// (undamped) and r = 0.5 (γ from the linear two-body formula).
fn two_target_pairs(name: &str, law: &str) -> String {
    format!(
        "version: 1\nname: {name}\nscenes:\n  - name: pair\n    kind: pair\n    \
         material: {{mass: 1.0, k: 1.0, law: {law}, contact: true}}\n    grid:\n      v0: [0.1, 1.0]\n      \
         damping.restitution: [1.0, 0.5]\n"
    )
}

/// A restitution is judged against the target its runs were set for, one target at a time: a
/// median over the undamped runs (r = 1) and the damped ones (r ≈ 0.5) is 0.75, which would be
/// said to miss 0.5 on both sides. The claim flips: the linear pair meets 0.5 at its damped runs
/// and is not said to miss anything; the Hertz pair misses 0.5 with its damped r, and only there.
#[test]
fn a_restitution_is_judged_against_its_own_target() {
    let dir = crate::common::scratch();
    let reports = dir.path();
    let (_, report) = linear_against_hertz(reports, ("lin", "hertz"), two_target_pairs);
    let (a, b) = (reports.join("lin"), reports.join("hertz"));
    // Each side's restitution at target `goal`: the median of its runs set for it.
    let at = |dir: &Path, goal: f64| {
        let results = read(&dir.join("results.parquet"));
        let (targets, r) = (floats(&results, "damping.restitution"), floats(&results, "restitution"));
        median(targets.iter().zip(r).filter(|(t, _)| **t == Some(goal)).map(|(_, r)| r.unwrap()).collect())
    };
    let (damped_a, damped_b) = (at(&a, 0.5), at(&b, 0.5));
    // The premise, as in the single-target test: the linear pair meets 0.5 to 1.3e-3 at the
    // default step (5e-3 allows for it), the Hertz pair misses it by more than the 1 % allowed.
    assert!((damped_a / 0.5 - 1.0).abs() < 5e-3 && (damped_b / 0.5 - 1.0).abs() > 0.01, "{damped_a}, {damped_b}");
    assert!(!report.contains("In A, pair's restitution"), "the linear pair meets both its targets: {report}");
    let missed: Vec<&str> = report.lines().filter(|l| l.contains("In B, pair's restitution r = ")).collect();
    assert_eq!(missed.len(), 1, "only the damped Hertz runs miss their target: {report}");
    // Four significant digits: within 5e-4 relative, for B's damped r and the target 0.5.
    let stated = numbers(missed[0]);
    assert!((stated[0] / damped_b - 1.0).abs() <= 5e-4 && (stated[1] / 0.5 - 1.0).abs() <= 5e-4, "{}", missed[0]);
    // Side by side, target by target: four significant digits again (5e-4 relative); the
    // undamped runs bounce back whole, r = 1 on both sides (within 1.1e-6 measured, so 1.000 as
    // written, to the same 5e-4).
    let line = report.lines().find(|l| l.starts_with("- The restitution r, in pair at the target ")).expect(&report);
    let damped = line.split("; ").find(|s| s.contains("at the target 0.5000:")).expect(line);
    for (stated, expected) in numbers(damped).iter().zip([0.5, damped_a, damped_b, damped_b / damped_a]) {
        assert!((stated / expected - 1.0).abs() <= 5e-4, "{damped}: {stated} against {expected}");
    }
    let undamped = line.split("; ").find(|s| s.contains("at the target 1.000:")).expect(line);
    assert!(numbers(undamped)[1..3].iter().all(|r| (r - 1.0).abs() <= 5e-4), "{undamped}");
}

/// Contact pairs over restitution and spring law, stepped at t_c/50 (A) or t_c/10 (B).
fn law_grid(name: &str, side: &str) -> String {
    let step = if side == "linear" { 50 } else { 10 };
    format!(
        "version: 1\nname: {name}\nscenes:\n  - name: pair\n    kind: pair\n    material: {{mass: 1.0, k: 1.0, contact: true}}\n    \
         v0: 1.0\n    time: {{dt_per_tc: {step}}}\n    grid:\n      damping.restitution: [1.0, 0.5]\n      \
         material.law: [linear, hertz]\n"
    )
}

/// A grid over the spring law keeps each law's restitution apart (one median over a linear
/// r = 0.4994 and a Hertz 0.3219 had read 0.41 'missing' 0.5 for both), and says why each
/// misses: a Hertz contact does not follow the linear formula γ came from; a linear one at
/// t_c/10 does, and misses by the step's error (3 % there, beyond the 1 % allowed; 1.3e-3 at
/// t_c/50, within it).
#[test]
fn a_restitution_is_judged_per_spring_law_and_says_why_it_misses() {
    let dir = crate::common::scratch();
    let (_, report) = linear_against_hertz(dir.path(), ("fine", "coarse"), law_grid);
    let missed = |side: &str, law: &str| {
        report.lines().find(|l| l.starts_with(&format!("- In {side}, pair (material.law = {law})'s restitution")))
    };
    assert!(missed("A", "linear").is_none(), "{report}");
    assert!(missed("A", "hertz").expect(&report).contains("which this contact does not follow"));
    assert!(missed("B", "linear").expect(&report).contains("the integration's error at its time step"));
}

/// The text of `report` under `heading`, up to the next heading (empty where there is none).
fn section<'a>(report: &'a str, heading: &str) -> &'a str {
    let Some(start) = report.find(heading).map(|i| i + heading.len()) else { return "" };
    let rest = &report[start..];
    rest.find("\n#").map_or(rest, |end| &rest[..end])
}

/// A chain of 11 without contacts, whose `error` is measured against its normal modes where
/// its springs are linear and against energy conservation where they are not.
fn free_chain(name: &str, law: &str) -> String {
    format!(
        "version: 1\nname: {name}\nscenes:\n  - name: modes\n    kind: chain\n    n: 11\n    \
         material: {{mass: 1.0, k: 1.0, law: {law}, contact: false}}\n    v0: 0.1\n"
    )
}

/// An error is compared only where both sides measured it against the same reference: the
/// linear chain's `error` is against its normal modes, the Hertz chain's against energy, and the
/// two had been set side by side as "differing beyond noise". The claim flips: the row's two
/// errors differ by far more than the 1e-6 a deviation may (premise asserted), yet the report
/// says they are not compared, and why, and compare.csv has no ratio for them.
#[test]
fn an_error_is_compared_only_against_the_same_reference() {
    let dir = crate::common::scratch();
    let (_, report) = linear_against_hertz(dir.path(), ("lin", "hz"), free_chain);
    let joined = read(&dir.path().join("compare-lin-vs-hz").join("compare.parquet"));
    assert_eq!(texts(&joined, "error_measure_a"), ["normal_modes"]);
    assert_eq!(texts(&joined, "error_measure_b"), ["energy"]);
    let (a, b) = (floats(&joined, "error_a")[0].unwrap(), floats(&joined, "error_b")[0].unwrap());
    assert!((a - b).abs() > 1e-6, "the premise: the two errors are far apart ({a}, {b})");
    assert_eq!(floats(&joined, "error_ratio"), [None], "no ratio of errors against different references");
    let differ = section(&report, "### Measured quantities that differ beyond noise");
    assert!(!differ.contains("| modes | `error` |"), "{report}");
    let line = report.lines().find(|l| l.starts_with("Not compared, measured differently")).expect(&report);
    assert!(line.contains("modes: error (normal_modes in A, energy in B)"), "{line}");
}

/// Both campaigns' static solves stop at Newton's tolerance, 1e-12 of the load: their residuals
/// (6e-16 and 4e-13) are round-off, and the report had called them "equal within noise" with a
/// ratio of several hundred. The claim flips: they are said to be both at round-off, with no
/// ratio, and not in the list of what is equal within noise.
#[test]
fn residuals_below_their_floor_are_both_at_round_off() {
    let dir = crate::common::scratch();
    let tensile = |name: &str, law: &str| {
        format!(
            "version: 1\nname: {name}\nscenes:\n  - name: tens\n    kind: lattice\n    material: {{law: {law}}}\n    \
             lattice: {{size: 4, k_diag_ratio: 0.5}}\n    load: {{case: tensile, per_node: 0.001}}\n    relax: {{method: fire}}\n"
        )
    };
    let (_, report) = linear_against_hertz(dir.path(), ("lin", "hz"), tensile);
    let joined = read(&dir.path().join("compare-lin-vs-hz").join("compare.parquet"));
    let (a, b) = (floats(&joined, "static_residual_a")[0].unwrap(), floats(&joined, "static_residual_b")[0].unwrap());
    // The premise: both at or below the solver's tolerance 1e-12, and far from equal.
    assert!(a <= 1e-12 && b <= 1e-12 && (b / a - 1.0).abs() > 0.5, "{a}, {b}");
    assert_eq!(floats(&joined, "static_residual_ratio"), [None], "no ratio of two round-off residues");
    let equal = report.lines().find(|l| l.starts_with("Equal within noise")).unwrap_or_default();
    assert!(!equal.contains("static_residual"), "{equal}");
    let line = report.lines().find(|l| l.starts_with("Both at round-off")).expect(&report);
    assert!(line.contains("tens: static_residual (A "), "{line}");
}

/// Packings of contact law `law` over an unjammed fraction and a jammed one, three seeds each.
fn seeded_packings(name: &str, law: &str) -> String {
    format!(
        "version: 1\nname: {name}\nscenes:\n  - name: pk\n    kind: packing\n    packing: {{n: 16}}\n    \
         material: {{law: {law}}}\n    grid:\n      packing.fraction: [0.8, 0.9]\n      seed: [1, 2, 3]\n"
    )
}

/// The mean of `values` and the variance of that mean.
fn mean_and_variance(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    (mean, values.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0) / n)
}

/// Packings are compared seed against seed only where both are jammed, and their own φ_J within
/// the spread between the seeds. Before, `own_jamming_fraction` "differed beyond noise" at a
/// noise of 1e-6 though a packing's φ_J is found to 5e-5 and the seeds scatter it by percents,
/// the unjammed packings' pressures (below the floor) were divided, and the inputs' last bits
/// (dt·ω_max of a linear and a Hertz law) made them "differ". Each claim flips here.
#[test]
fn packings_compare_jammed_states_within_the_seeds_spread() {
    let dir = crate::common::scratch();
    let (_, report) = linear_against_hertz(dir.path(), ("lin", "hz"), seeded_packings);
    let joined = read(&dir.path().join("compare-lin-vs-hz").join("compare.parquet"));
    let (state_a, state_b) = (texts(&joined, "packing_state_a"), texts(&joined, "packing_state_b"));
    assert!(
        texts(&joined, "law_a").iter().all(|l| l == "linear") && texts(&joined, "law_b").iter().all(|l| l == "power")
    );
    assert_eq!(floats(&joined, "seed"), floats(&joined, "seed_a"), "the seed the rows were joined on");
    let pressure = floats(&joined, "pressure_ratio");
    for r in 0..joined.height() {
        let jammed = state_a[r] == "jammed" && state_b[r] == "jammed";
        assert_eq!(pressure[r].is_some(), jammed, "row {r}: {} against {}", state_a[r], state_b[r]);
    }
    assert!(state_a.iter().zip(&state_b).any(|(a, b)| a == "unjammed" && b == "unjammed"), "the premise");
    assert!(report.contains("Packings not compared: pk: "), "{report}");

    // φ_J: the rows differ by more than 1e-6 (premise), but the seed means lie within two
    // standard errors of their difference (recomputed here from the table).
    let rows: Vec<usize> = (0..joined.height()).filter(|&r| pressure[r].is_some()).collect();
    let phi = |side: &str| -> Vec<f64> {
        rows.iter().map(|&r| floats(&joined, &format!("own_jamming_fraction_{side}"))[r].unwrap()).collect()
    };
    let ((mean_a, var_a), (mean_b, var_b)) = (mean_and_variance(&phi("a")), mean_and_variance(&phi("b")));
    assert!(phi("a").iter().zip(phi("b")).any(|(a, b)| (b / a - 1.0).abs() > 1e-6), "the premise");
    assert!((mean_b - mean_a).abs() < 2.0 * (var_a + var_b).sqrt(), "{mean_a} against {mean_b}");
    let differ = section(&report, "### Measured quantities that differ beyond noise");
    assert!(!differ.contains("`own_jamming_fraction`"), "{differ}");
    assert!(differ.contains("| pk | `pressure` |"), "the pressure does differ: {differ}");

    // dt·ω_max: equal to the last bits, so equal.
    let (da, db) = (floats(&joined, "dt_omega_max_a"), floats(&joined, "dt_omega_max_b"));
    assert!(da.iter().zip(&db).any(|(a, b)| a != b), "the premise: the last bits differ");
    assert!(da.iter().zip(&db).all(|(a, b)| (b.unwrap() / a.unwrap() - 1.0).abs() < 1e-12));
    let inputs = section(&report, "### Inputs that differ");
    assert!(inputs.contains("| `beta` |") && !inputs.contains("`dt_omega_max`"), "{inputs}");
    pressures_are_held_to_the_jamming_theory(dir.path(), &report);
}

/// Each side's p ∝ Δφ^x near jamming (its `summary.csv`), recomputed from its results table over
/// its jammed packings with Δφ = φ − own φ_J, beside the theory's β (O'Hern et al. 2003): 1
/// linear, 1.5 Hertz; said to disagree exactly where it misses by more than the item Jamming's
/// 0.15. Stated to 4 decimals: within 5e-5.
fn pressures_are_held_to_the_jamming_theory(reports: &Path, report: &str) {
    let slope = |side: &str| {
        let results = read(&reports.join(side).join("results.parquet"));
        let states = texts(&results, "packing_state");
        let (phi, own, p) = (
            floats(&results, "packing_fraction"),
            floats(&results, "own_jamming_fraction"),
            floats(&results, "pressure"),
        );
        let points: Vec<(f64, f64)> = (0..results.height())
            .filter(|&r| states[r] == "jammed")
            .map(|r| (phi[r].unwrap() - own[r].unwrap(), p[r].unwrap()))
            .collect();
        // Every Δφ above the fit's floor, 5 × 5e-5 φ_J ≈ 2.1e-4: all of them are fitted.
        assert!(points.len() >= 2 && points.iter().all(|d| d.0 > 3e-4), "the premise: {points:?}");
        crate::common::log_slope(&points)
    };
    let (a, b) = (slope("lin"), slope("hz"));
    let line =
        report.lines().find(|l| l.starts_with("- pk: pressure ∝ fraction_excess^p")).expect("the pressure's line");
    let stated = numbers(line);
    assert!((stated[0] - a).abs() < 5e-5 && (stated[2] - b).abs() < 5e-5, "{line}: independent {a}, {b}");
    assert!(line.contains("(linear, predicted 1.0000) in A") && line.contains("(β = 1.5, predicted 1.5000 = β) in B"));
    let verdict = report.lines().find(|l| l.contains("fitted exponents agree")).unwrap();
    for (side, x, theory) in [("A", a, 1.0), ("B", b, 1.5)] {
        let named = verdict.contains(&format!("pk pressure in {side}"));
        assert_eq!(named, (x - theory).abs() > 0.15, "{verdict}: {side} {x}");
    }
    assert!(verdict.contains("within 0.15"), "{verdict}");
}

/// Packings of 32 discs of contact law `law` at three fractions across jamming, six seeds each:
/// at the lowest only some seeds jam.
fn straddling_packings(name: &str, law: &str) -> String {
    format!(
        "version: 1\nname: {name}\nscenes:\n  - name: pk\n    kind: packing\n    packing: {{n: 32}}\n    \
         material: {{law: {law}}}\n    grid:\n      packing.fraction: [0.835, 0.845, 0.86]\n      seed: [1, 2, 3, 4, 5, 6]\n"
    )
}

/// A group of seeds is judged only where every seed jammed on both sides: where some did not,
/// the jammed ones are those whose own φ_J lies below the fraction, a share selected on each
/// side by its own law. Recomputed from compare.parquet: `own_jamming_fraction` is said to
/// differ exactly where a complete group's seed means part by more than 2 standard errors of
/// their difference. The claim flips here: a group where only some seeds jammed parts by more
/// than that (premise), and it had made φ_J "differ beyond noise".
#[test]
fn groups_of_packings_where_some_seeds_did_not_jam_are_not_judged() {
    let dir = crate::common::scratch();
    let (_, report) = linear_against_hertz(dir.path(), ("lin", "hz"), straddling_packings);
    let joined = read(&dir.path().join("compare-lin-vs-hz").join("compare.parquet"));
    let (state_a, state_b) = (texts(&joined, "packing_state_a"), texts(&joined, "packing_state_b"));
    let fraction = floats(&joined, "packing.fraction");
    let (own_a, own_b) = (floats(&joined, "own_jamming_fraction_a"), floats(&joined, "own_jamming_fraction_b"));
    // Per fraction: whether every seed jammed on both sides, and whether the jammed seeds'
    // means part by more than 2 standard errors of their difference.
    let parts = |phi: f64| -> (bool, bool) {
        let rows: Vec<usize> = (0..joined.height()).filter(|&r| fraction[r] == Some(phi)).collect();
        let jammed: Vec<usize> =
            rows.iter().copied().filter(|&r| state_a[r] == "jammed" && state_b[r] == "jammed").collect();
        let side =
            |own: &[Option<f64>]| mean_and_variance(&jammed.iter().map(|&r| own[r].unwrap()).collect::<Vec<_>>());
        let parted = jammed.len() >= 2 && {
            let ((ma, va), (mb, vb)) = (side(&own_a), side(&own_b));
            (mb - ma).abs() > 2.0 * (va + vb).sqrt()
        };
        (jammed.len() == rows.len(), parted)
    };
    let groups: Vec<(bool, bool)> = [0.835, 0.845, 0.86].map(parts).to_vec();
    assert!(groups.iter().any(|&(complete, parted)| !complete && parted), "the premise: {groups:?}");
    let differs = groups.iter().any(|&(complete, parted)| complete && parted);
    let differ = section(&report, "### Measured quantities that differ beyond noise");
    assert_eq!(differ.contains("| pk | `own_jamming_fraction` |"), differs, "{groups:?}: {differ}");
}

/// Linear packings of 64 discs at φ = 0.835, four seeds, contact spring `k`: only some seeds jam.
fn partly_jammed(name: &str, k: &str) -> String {
    format!(
        "version: 1\nname: {name}\nscenes:\n  - name: pk\n    kind: packing\n    packing: {{n: 64, fraction: 0.835}}\n    \
         material: {{law: linear, k: {k}}}\n    grid:\n      seed: [1, 2, 3, 4]\n"
    )
}

/// A quantity measured only in groups of seeds where some packings did not jam is judged
/// nowhere, so it neither differs nor agrees: it is said to be not judged. The pressure of
/// springs twice as stiff is twice as high (B/A = 2 at every jammed seed, the premise), and it
/// had been listed as "Equal within noise" with the two campaigns said to "agree in all".
#[test]
fn a_quantity_judged_in_no_group_is_said_not_judged_not_equal() {
    let dir = crate::common::scratch();
    let (_, report) = compare_two(dir.path(), [("soft", "1.0"), ("stiff", "2.0")], partly_jammed);
    let joined = read(&dir.path().join("compare-soft-vs-stiff").join("compare.parquet"));
    let states = [texts(&joined, "packing_state_a"), texts(&joined, "packing_state_b")];
    assert!(states.iter().all(|s| s.iter().any(|x| x == "jammed") && s.iter().any(|x| x != "jammed")), "the premise");
    let ratios: Vec<f64> = floats(&joined, "pressure_ratio").into_iter().flatten().collect();
    assert!(!ratios.is_empty() && ratios.iter().all(|r| (r - 2.0).abs() < 1e-6), "the premise: {ratios:?}");
    let not_judged = report.lines().find(|l| l.starts_with("Not judged, measured only where")).expect("{report}");
    assert!(not_judged.contains("pk: pressure (B/A = 2.0000)"), "{not_judged}");
    assert!(!report.lines().any(|l| l.starts_with("Equal within noise") && l.contains("pk: pressure ")), "{report}");
    assert!(report.contains("No measured quantity is judged to differ or to agree there"), "{report}");
}

/// Packings of both laws on one scene's grid, contact spring `k`.
fn both_laws(name: &str, k: &str) -> String {
    format!(
        "version: 1\nname: {name}\nscenes:\n  - name: pk\n    kind: packing\n    packing: {{n: 32}}\n    \
         material: {{k: {k}}}\n    grid:\n      material.law: [linear, hertz]\n      packing.fraction: [0.86, 0.9]\n      \
         seed: [1, 2]\n"
    )
}

/// A grid over the law inside one scene gives each group its own law, and `summary.csv` its
/// β: its fits are held to that law's exponents near jamming, p ∝ Δφ^β with β = 1 and 3/2
/// (O'Hern et al. 2003). Before, the scene's two β left every fit without a prediction
/// ("predicted –").
#[test]
fn a_grid_over_the_law_holds_each_group_to_its_own_exponents() {
    let dir = crate::common::scratch();
    let (_, report) = compare_two(dir.path(), [("one", "1.0"), ("two", "2.0")], both_laws);
    for (law, predicted) in [("linear", "(linear, predicted 1.0000)"), ("hertz", "(β = 1.5, predicted 1.5000 = β)")] {
        let line = report
            .lines()
            .find(|l| l.starts_with(&format!("- pk (law={law}): pressure ∝ fraction_excess^p")))
            .unwrap_or_else(|| panic!("{law}: {report}"));
        assert!(line.contains(predicted), "{line}");
    }
}

/// Two chains whose grids run over the spring law, the non-linear springs' β = `beta`: a wave
/// chain over two impact speeds (`material.law: [linear, power]`) and a chain between walls
/// over two wall distances (`[linear, hertz]`: `hertz` takes the campaign's β too).
fn law_gridded_chains(name: &str, beta: &str) -> String {
    format!(
        "version: 1\nname: {name}\ndefaults:\n  material: {{mass: 1.0, k: 1.0, beta: {beta}}}\nscenes:\n  \
         - name: wave\n    kind: chain\n    n: 30\n    node: first\n    wave: {{}}\n    material: {{contact: true}}\n    \
         time: {{duration_tc: 60}}\n    grid:\n      material.law: [linear, power]\n      v0: [0.01, 0.1]\n  \
         - name: walls\n    kind: chain\n    n: 9\n    damping: {{restitution: 0.5}}\n    \
         time: {{integrator: velocity-verlet}}\n    relax: {{residual_force: 1.0e-9, tangent_step: 0.001}}\n    \
         grid:\n      material.law: [linear, hertz]\n      wall_distance: [9.5, 9.9]\n"
    )
}

/// The exponent springs s ∝ δ^β predict for `scene` of [`law_gridded_chains`], written out
/// here rather than asked of the library: the wave's speed ∝ v0^((β−1)/(β+1)) (Nesterenko),
/// the walled chain's stiffness ∝ |ΔW|^(β−1); 0 for linear springs.
fn chain_exponent(scene: &str, beta: f64) -> f64 {
    if scene == "wave" { (beta - 1.0) / (beta + 1.0) } else { beta - 1.0 }
}

/// Each fit of `summary.csv` in `dir` states the β of its group's runs (results.parquet's
/// `beta` of the scene's runs of its law): 1 for linear springs, the campaign's `beta` else.
fn summary_states_each_groups_beta(dir: &Path, beta: f64) {
    let summary = CsvReadOptions::default()
        .try_into_reader_with_file_path(Some(dir.join("summary.csv")))
        .unwrap()
        .finish()
        .unwrap();
    let results = read(&dir.join("results.parquet"));
    let (run_scenes, run_laws, run_betas) =
        (texts(&results, "scene"), texts(&results, "material.law"), floats(&results, "beta"));
    let (scenes, groups, betas) = (texts(&summary, "scene"), texts(&summary, "group"), floats(&summary, "beta"));
    assert_eq!(summary.height(), 6, "two laws of each of three fits");
    for ((scene, group), fitted) in scenes.iter().zip(&groups).zip(betas) {
        let law = group.strip_prefix("law=").expect(group);
        let runs: Vec<Option<f64>> = (0..results.height())
            .filter(|&r| run_scenes[r] == *scene && run_laws[r] == law)
            .map(|r| run_betas[r])
            .collect();
        assert!(runs.len() == 2 && runs.iter().all(|b| *b == fitted), "{scene} {group}: {fitted:?} against {runs:?}");
        assert_eq!(fitted, Some(if law == "linear" { 1.0 } else { beta }), "{scene} {group}");
    }
}

/// The discussion's table of `dir`'s report.md holds every fit against its own group's
/// exponent ([`chain_exponent`] of 1 or the campaign's `beta`), and the item is within.
fn discussion_holds_each_group_to_its_own_beta(dir: &Path, beta: f64) {
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    let name = if beta == 1.5 { "Hertz" } else { "power-law" };
    let item = section(&report, &format!(". Linear against {name} springs\n"));
    let rows: Vec<Vec<&str>> = item
        .lines()
        .filter(|l| l.starts_with("| wave |") || l.starts_with("| walls |"))
        .map(|l| l.split(" | ").map(|c| c.trim_matches(|c| c == '|' || c == ' ')).collect())
        .collect();
    assert_eq!(rows.len(), 6, "{item}");
    for row in rows {
        let row_beta = if row[1] == "linear" { 1.0 } else { beta };
        let expected = format!("{:.3}", chain_exponent(row[0], row_beta));
        assert_eq!((row[3], row[4]), (expected.as_str(), expected.as_str()), "{row:?}");
    }
    assert!(item.contains("**Verdict: ✓ within.**"), "{item}");
}

/// A grid over the spring law holds each group's fit to its own β, which `summary.csv` states
/// (`beta`): compare predicts the `law=power` wave's v0^((β−1)/(β+1)) and the `law=hertz`
/// walls' |ΔW|^(β−1) from each side's β, 2 and 3/2, and each report's discussion holds them to
/// the same. Before, compare read β off the label: none for `law=power` ("predicted –"), 3/2
/// for `law=hertz` whatever β the campaign set (A's exponent 1 "off by 0.5000"); and the
/// discussion took every fit's β from its scene's first run, linear springs, and judged both
/// non-linear groups against 0 ("✗ outside").
#[test]
fn a_grid_over_the_law_holds_each_fit_to_its_own_groups_beta() {
    let dir = crate::common::scratch();
    let sides = [("steep", "2.0"), ("hertzian", "1.5")];
    let (_, report) = compare_two(dir.path(), sides, law_gridded_chains);
    let betas = sides.map(|(_, beta)| beta.parse::<f64>().unwrap());
    for ((name, _), beta) in sides.into_iter().zip(betas) {
        summary_states_each_groups_beta(&dir.path().join(name), beta);
        discussion_holds_each_group_to_its_own_beta(&dir.path().join(name), beta);
    }
    for (scene, quantity, law) in [
        ("wave", "sound_speed ∝ v0^p", "power"),
        ("walls", "secant_stiffness ∝ wall_displacement^p", "hertz"),
        ("walls", "tangent_stiffness ∝ wall_displacement^p", "hertz"),
    ] {
        let line =
            report.lines().find(|l| l.starts_with(&format!("- {scene} (law={law}): {quantity}"))).expect(&report);
        let (a, b) = line.split_once(" in A and ").expect(line);
        for (words, beta) in [a, b].into_iter().zip(betas) {
            let predicted = format!("predicted {:.4} = ", chain_exponent(scene, beta));
            assert!(words.contains(&predicted), "{line}: {predicted}");
        }
    }
    assert!(
        report.contains("- All 12 fitted exponents agree with the exponents their spring laws predict"),
        "{report}"
    );
    an_older_summary_guesses_no_beta(dir.path());
}

/// A `summary.csv` of an older mdsolids, without `beta` (A's here, the column cut out): a fit's
/// β is its label's `beta=`, 1 for linear springs, else the one β of its scene's runs; a scene
/// gridded over the law has two, so A's Hertz walls are predicted by none ("predicted –")
/// rather than guessed from `law=hertz` (a power law takes the campaign's β), while its linear
/// group keeps 0; B's keep their own.
fn an_older_summary_guesses_no_beta(reports: &Path) {
    let (a, b) = (reports.join("steep"), reports.join("hertzian"));
    let summary = a.join("summary.csv");
    let text = std::fs::read_to_string(&summary).unwrap();
    assert!(text.starts_with("scene,group,law,beta,"), "{text}");
    let without_beta: String = text
        .lines()
        .map(|line| {
            let mut cells: Vec<&str> = line.split(',').collect();
            cells.remove(3);
            cells.join(",") + "\n"
        })
        .collect();
    std::fs::write(&summary, without_beta).unwrap();
    let out = reports.join("older");
    succeed(reports, &["compare", a.to_str().unwrap(), b.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    let line = report.lines().find(|l| l.starts_with("- walls (law=hertz): secant_stiffness")).expect(&report);
    assert!(line.contains("(power, predicted –) in A") && line.contains("predicted 0.5000 = β−1) in B"), "{line}");
    let linear = report.lines().find(|l| l.starts_with("- walls (law=linear): secant_stiffness")).expect(&report);
    assert!(linear.split_once(" in A").expect(linear).0.contains("predicted 0.0000"), "{linear}");
}

/// `--out` never overwrites or deletes what the user made: a folder holding other files, the
/// folder that holds the campaigns and a folder inside a campaign's report folder are refused,
/// naming the flag; a comparison's own folder may be written again, and only the files it wrote
/// there are replaced or removed. Before, the user's report.md was overwritten and their
/// plots/keep.svg deleted without a word.
#[test]
fn out_never_overwrites_what_the_user_made() {
    let dir = crate::common::scratch();
    let reports = dir.path();
    run_campaigns(reports);
    let (a, b) = (reports.join("linear"), reports.join("power"));
    let compare = |out: &Path| -> Vec<String> {
        ["compare", a.to_str().unwrap(), b.to_str().unwrap(), "--out", out.to_str().unwrap()].map(String::from).to_vec()
    };
    fn args(v: &[String]) -> Vec<&str> {
        v.iter().map(String::as_str).collect()
    }
    let mine = reports.join("mine");
    std::fs::create_dir_all(mine.join("plots")).unwrap();
    std::fs::write(mine.join("report.md"), "my notes").unwrap();
    std::fs::write(mine.join("plots/keep.svg"), "<svg/>").unwrap();
    for out in [mine.clone(), reports.to_path_buf(), a.join("sub")] {
        let error = refuse(reports, &args(&compare(&out)));
        assert!(error.contains(&format!("--out '{}'", out.display())), "{error}");
        assert!(error.contains("a new folder, an empty one, or the folder of an earlier comparison"), "{error}");
    }
    assert_eq!(std::fs::read_to_string(mine.join("report.md")).unwrap(), "my notes");
    assert!(mine.join("plots/keep.svg").is_file() && !a.join("sub").exists());

    let own = reports.join("own");
    succeed(reports, &args(&compare(&own)));
    std::fs::write(own.join("plots/stale.svg"), "<svg/>").unwrap();
    let marker = own.join(".mdsolids-compare");
    let listed = std::fs::read_to_string(&marker).unwrap();
    std::fs::write(&marker, format!("{listed}plots/old.svg\n")).unwrap();
    std::fs::write(own.join("plots/old.svg"), "<svg/>").unwrap();
    succeed(reports, &args(&compare(&own)));
    assert!(own.join("report.md").is_file() && own.join("plots/stale.svg").is_file(), "not its own: kept");
    assert!(!own.join("plots/old.svg").exists(), "its own figure, no longer drawn: removed");
}
