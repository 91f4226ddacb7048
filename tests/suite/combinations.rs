//! The cross product of every axis a loaded lattice has, at small N: lattice type (square with
//! and without diagonals, triangular, honeycomb, kagome) × load case (tensile, tensile-x,
//! shear) × supports (coursework, clamped-bottom, periodic-x) × relaxation (damped with a fixed
//! γ, critical background damping, FIRE, FIRE in the stiffness's metric, CG, the static solve)
//! × law (linear, Hertz) × tangent step (on, off) × movie (on, off): 2 160 cells. Each cell is either refused at plan time with
//! a message that names a field, or runs, and then:
//!
//! - the static answer (`*_fem`) agrees to 1e-9 with an independent one written here: a dense
//!   stiffness matrix assembled from the run's own bond list, supports and loads (not from
//!   `fem.rs`), Newton–Raphson on it, and the moduli from the loads' own sum;
//! - a mechanism is one here too, and a network called floppy has a singular stiffness here;
//! - an `ok` run has every column it promises (MD moduli unless static, the bound, the tangent
//!   columns), its MD moduli within `relax.tolerance` of that static answer, and its bound at
//!   most the tolerance; an MD tangent within the tolerance of the secant over the same step;
//! - a movie has frames.
//!
//! A new axis joins the product here, so its combinations are tested the day it lands.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use mdsolids::plan::{self, Estimates};
use mdsolids::runner::RunRecord;
use mdsolids::sim::RunStatus;
use mdsolids::spec::{Budget, LoadCase, RunSpec};
use mdsolids::study::Metrics;
use rayon::prelude::*;

use crate::dense::Reference;

/// The relaxation tolerance of every MD cell. The static answers agree to 1e-9: Newton–Raphson
/// to 1e-12 of the load on both sides, a stiffness condition number ≤ ~1e3 at this size.
const TOLERANCE: f64 = 1e-5;
const STATIC_AGREEMENT: f64 = 1e-9;
const STEP: f64 = 1e-3;
const LOAD: f64 = 1e-3;

const TYPES: [&str; 5] = ["square", "square-no-diagonals", "triangular", "honeycomb", "kagome"];
const CASES: [&str; 3] = ["tensile", "tensile-x", "shear"];
const SUPPORTS: [&str; 3] = ["coursework", "clamped-bottom", "periodic-x"];
const METHODS: [&str; 6] = ["damped", "critical", "fire", "fire-stiffness", "cg", "static"];
const LAWS: [&str; 2] = ["linear", "hertz"];

/// One cell of the product.
#[derive(Clone, Copy, Debug)]
struct Cell {
    lattice: &'static str,
    case: &'static str,
    supports: &'static str,
    method: &'static str,
    law: &'static str,
    tangent: bool,
    movie: bool,
}

fn cells() -> Vec<Cell> {
    let mut cells = Vec::new();
    for lattice in TYPES {
        for case in CASES {
            for supports in SUPPORTS {
                for method in METHODS {
                    for law in LAWS {
                        for tangent in [false, true] {
                            for movie in [false, true] {
                                cells.push(Cell { lattice, case, supports, method, law, tangent, movie });
                            }
                        }
                    }
                }
            }
        }
    }
    cells
}

/// The campaign of one cell: a 4 × 5 block (k = m = a = d = 1, 1e-3 N per top-row node). The
/// fixed γ_g = 0.1 lies between the blocks' critical values (2√k_min: 2e-3 on a Hertz kagome
/// block, 0.27 on a linear square one), so the damped cells relax both over- and underdamped;
/// at 0.5 the slowest cell (kagome, Hertz, a tangent step) took 0.8 s, at 0.1 0.17 s.
fn campaign(c: &Cell) -> String {
    let lattice = match c.lattice {
        "square-no-diagonals" => "{nx: 4, ny: 5, type: square, diagonals: none}".to_string(),
        other => format!("{{nx: 4, ny: 5, type: {other}}}"),
    };
    let (method, damping) = match c.method {
        "damped" => ("damped", "\n    damping: {restitution: 0.5, background: 0.1}"),
        "critical" => ("damped", "\n    damping: {background: critical}"),
        "fire-stiffness" => ("fire, preconditioner: stiffness", ""),
        other => (other, ""),
    };
    let tolerance = if c.method == "static" { String::new() } else { format!(", tolerance: {TOLERANCE:e}") };
    let tangent = if c.tangent { format!(", tangent_step: {STEP:e}") } else { String::new() };
    let movie = if c.movie { "\n    movie: {frames: 4, width: 120, height: 80}" } else { "" };
    format!(
        "version: 1\nname: cell\nscenes:\n  - name: c\n    kind: lattice\n    lattice: {lattice}\n    supports: {}\n    \
         load: {{case: {}, per_node: {LOAD:e}}}\n    material: {{law: {}}}{damping}\n    relax: {{method: {method}, \
         max_tc: 20000{tolerance}{tangent}}}{movie}\n",
        c.supports, c.case, c.law
    )
}

/// What the fields of a refusal may be: the axes' own.
const FIELDS: [&str; 9] = [
    "supports",
    "load.case",
    "relax.method",
    "relax.tangent_step",
    "movie",
    "damping",
    "relax.tolerance",
    "relax.preconditioner",
    "lattice.",
];

#[test]
fn every_combination_is_refused_with_its_field_or_runs_to_the_independent_static_answer() {
    let cells = cells();
    assert_eq!(cells.len(), 2160);
    // A pool of its own: on the global one its seconds of cells would queue every other test's
    // parallel work behind them (a plan in `hostile::` then passed its 10 s hang guard).
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    // One set of estimates for all cells, as a campaign's runs share theirs: each integrator's
    // stability limit at each damping ratio is measured once (per cell, twice, it was half of
    // the test's time), each network's modes once per cell.
    let estimates = Estimates::default();
    let references = References::default();
    let mut failures: Vec<String> = pool.install(|| {
        cells
            .par_iter()
            .filter_map(|c| check(c, &estimates, &references).err().map(|e| format!("{c:?}: {e}")))
            .collect()
    });
    failures.sort_by_key(|f| f.contains("movie without frames"));
    let shown: Vec<&String> = failures.iter().take(400).collect();
    assert!(failures.is_empty(), "{} of {} cells fail:\n{shown:#?}", failures.len(), cells.len());
}

/// The dense answers, one per lattice, load case, supports and law: the relaxation, tangent-step
/// and movie axes leave the static problem as it is, so the 2 160 cells need 90 of them, not one
/// each (half the test's time, unoptimised: docs/performance.md, "Build and test times"). Each
/// is made from the spec of the first cell that asks; a cell whose network, supports or loads
/// differed would disagree with it and fail.
type References = Mutex<HashMap<(&'static str, &'static str, &'static str, &'static str), Arc<Option<Reference>>>>;

fn dense_answer(c: &Cell, spec: &RunSpec, references: &References) -> Arc<Option<Reference>> {
    let key = (c.lattice, c.case, c.supports, c.law);
    if let Some(known) = references.lock().unwrap().get(&key) {
        return known.clone();
    }
    let made = Arc::new(Reference::of(spec, STEP));
    references.lock().unwrap().entry(key).or_insert(made).clone()
}

fn check(c: &Cell, estimates: &Estimates, references: &References) -> Result<(), String> {
    let planned = mdsolids::spec::parse("cell.yaml", &campaign(c))
        .and_then(|campaign| plan::plan_sharing("cell.yaml", campaign, estimates));
    let spec = match planned {
        Err(refusal) => {
            let text = refusal.to_string();
            return FIELDS
                .iter()
                .any(|f| text.contains(f))
                .then_some(())
                .ok_or(format!("refused naming no field: {text}"));
        }
        Ok(campaign) => campaign.runs.into_iter().next().ok_or("no run")?,
    };
    let (status, message, metrics) = outcome(c, &spec, estimates)?;
    let known = dense_answer(c, &spec, references);
    let reference = known.as_ref().as_ref();
    match status {
        RunStatus::Mechanism => {
            reference.is_none().then_some(()).ok_or(format!("mechanism here, not in the dense solve: {message}"))
        }
        RunStatus::NoEquilibrium if message.contains("floppy") => {
            let dense = reference.ok_or("floppy, and a mechanism in the dense solve")?;
            (dense.zero_pivots > 0 || c.law == "hertz")
                .then_some(())
                .ok_or(format!("called floppy, dense K regular: {message}"))?;
            dense.agrees_statically(&spec, &metrics, STATIC_AGREEMENT)
        }
        RunStatus::Ok => {
            let dense = reference.ok_or(format!("ok, but a mechanism in the dense solve ({message})"))?;
            dense.agrees_statically(&spec, &metrics, STATIC_AGREEMENT)?;
            promised(c, &spec, &metrics, dense)
        }
        other => Err(format!("status {other:?}: {message}")),
    }
}

/// The run's status, message and metrics: through the runner's record, or, for a movie, through
/// `study::run`, whose outcome holds the frames; both with the plan's `estimates`.
fn outcome(c: &Cell, spec: &RunSpec, estimates: &Estimates) -> Result<(RunStatus, String, Metrics), String> {
    if !c.movie {
        let RunRecord { status, message, metrics, .. } =
            mdsolids::runner::execute_within(spec, &Budget::default(), estimates);
        return Ok((status, message, metrics));
    }
    match mdsolids::study::run(spec, Instant::now() + Duration::from_secs(60), estimates.shared()) {
        Err(mdsolids::study::Stopped::Mechanism { .. }) => {
            Ok((RunStatus::Mechanism, String::new(), Metrics::default()))
        }
        Err(stopped) => Err(format!("stopped: {stopped:?}")),
        Ok(run) if run.outcome.frames.is_empty() && run.outcome.trace.status == RunStatus::Ok => {
            Err("a movie without frames".into())
        }
        Ok(run) => Ok((run.outcome.trace.status, run.outcome.trace.message.clone(), run.metrics)),
    }
}

/// The columns an `ok` run promises, and how close its MD values lie to the dense answer.
fn promised(c: &Cell, spec: &RunSpec, m: &Metrics, dense: &Reference) -> Result<(), String> {
    let l = &m.lattice;
    let shear = spec.lattice().unwrap().load_case == LoadCase::Shear;
    let (md, md_tangent) =
        if shear { (l.shear_modulus, l.shear_modulus_tangent) } else { (l.youngs_modulus, l.youngs_modulus_tangent) };
    let fem_tangent = if shear { l.shear_modulus_tangent_fem } else { l.youngs_modulus_tangent_fem };
    if c.tangent && fem_tangent.is_none() {
        return Err("no static tangent modulus".into());
    }
    if c.method == "static" {
        return (md.is_none() && md_tangent.is_none()).then_some(()).ok_or("MD columns filled by a static run".into());
    }
    let md = md.ok_or("no MD modulus")?;
    let bound = l.relax_error_bound.ok_or("no relax_error_bound")?;
    if bound > TOLERANCE * (1.0 + 1e-12) {
        return Err(format!("relax_error_bound {bound:e} > tolerance"));
    }
    let error = (md / dense.modulus - 1.0).abs();
    if error > TOLERANCE {
        return Err(format!("MD modulus {md} off the dense {} by {error:e}", dense.modulus));
    }
    if !c.tangent {
        return Ok(());
    }
    let tangent = md_tangent.ok_or("no MD tangent modulus")?;
    let secant = dense.secant.ok_or("no dense secant")?;
    // Each relaxed state is held to half the increment's allowed error, so the tangent (the
    // secant over the step) is within the tolerance of the exact secant.
    let error = (tangent / secant - 1.0).abs();
    (error <= TOLERANCE).then_some(()).ok_or(format!("MD tangent {tangent} off the dense secant {secant} by {error:e}"))
}

// Findings that combine several axes of one campaign: each claim must be computed from the runs
// that share the axes it speaks of (supports, network, load case, method), not from all of them.

/// The cells of the report's table row that starts with `prefix` (the row's text up to its
/// first cells), trimmed, without the empty cells outside the outer bars.
fn table_row(report: &str, prefix: &str) -> Vec<String> {
    let row = report.lines().find(|l| l.starts_with(prefix)).unwrap_or_else(|| panic!("no row {prefix:?}"));
    row.trim_matches('|').split('|').map(|c| c.trim().to_string()).collect()
}

/// A small linear lattice scene (k = 1e6 N/m, m = 0.5 kg, a = 0.1 m, d = 0.01 m, 1 N per
/// top-row node) named `name`, with `lattice` and `relax` as YAML flow maps and `grid` as the
/// grid's lines.
fn lattice_campaign(name: &str, lattice: &str, relax: &str, grid: &str) -> String {
    format!(
        "version: 1\nname: {name}\ndefaults:\n  material: {{mass: 0.5, k: 1.0e6}}\n  geometry: {{spacing: 0.1, \
         depth: 0.01}}\nscenes:\n  - name: l\n    kind: lattice\n    lattice: {lattice}\n    load: {{per_node: 1.0}}\n    \
         relax: {relax}\n    grid:\n{grid}"
    )
}

/// The static E of the tensile (`rotated` false) or tensile-x run on `supports` among `records`.
fn static_youngs(records: &[RunRecord], supports: &str, rotated: bool) -> f64 {
    records
        .iter()
        .find(|r| {
            r.spec.lattice().is_some_and(|l| {
                l.supports.name() == supports && l.rotated == rotated && l.load_case == LoadCase::Tensile
            })
        })
        .and_then(|r| r.metrics.lattice.youngs_modulus_fem)
        .unwrap_or_else(|| panic!("no static E on {supports}, turned {rotated}"))
}

#[test]
fn isotropy_pairs_e_x_and_e_y_of_the_same_supports() {
    // A triangular block pulled along y and x and sheared, on two supports (static answers,
    // 0.1 s): the shear runs had written "no E_y" over E_y, and the clamped block's E_x had
    // replaced the free block's. Each row's E_x/E_y must be that of its own supports' two runs,
    // recomputed here; the table writes 4 decimals, so within 5e-5 (rounding). The two supports'
    // ratios differ by far more (1.189 against 1.186 at this size), so a mix-up shows.
    let grid = "      load.case: [tensile, shear, tensile-x]\n      supports: [coursework, clamped-bottom]\n";
    let yaml = lattice_campaign("iso", "{type: triangular, size: 6}", "{method: static}", grid);
    let records = crate::common::execute_all(&yaml);
    let report = crate::common::report_of("iso", &yaml);
    let mut ratios = Vec::new();
    for supports in ["coursework", "clamped-bottom"] {
        let row = table_row(&report, &format!("| triangular | 6 | {supports} |"));
        let (e_y, e_x) = (static_youngs(&records, supports, false), static_youngs(&records, supports, true));
        let stated: f64 = row[5].parse().unwrap_or_else(|_| panic!("no E_x/E_y in {row:?}"));
        assert!((stated - e_x / e_y).abs() < 5e-5, "{supports}: {stated} against {}", e_x / e_y);
        // E_y and E_x to the 4 significant digits the table writes.
        for (cell, e) in [(&row[3], e_y), (&row[4], e_x)] {
            let cell: f64 = cell.parse().unwrap_or_else(|_| panic!("{supports}: no modulus in {row:?}"));
            assert!((cell / e - 1.0).abs() < 5e-4, "{supports}: {cell} against {e}");
        }
        ratios.push(stated);
    }
    assert!((ratios[0] - ratios[1]).abs() > 1e-3, "the supports' ratios coincide: {ratios:?}");
    let short = crate::common::line_with(&report, "[Lattice types: isotropy](#");
    let said = crate::common::number_after(short, "triangular E_x/E_y = ");
    assert!((said - ratios[0]).abs() < 5e-4 && short.contains("(coursework supports)"), "{short}");
}

/// The random networks' table row of the runs among `records` with `diagonals` under `case`,
/// recomputed: its rigid seeds ("3/4") and the modulus mean over its relaxed seeds.
fn cut_row_from_records(records: &[RunRecord], diagonals: &str, case: LoadCase) -> (String, Option<f64>) {
    let mine: Vec<&RunRecord> = records
        .iter()
        .filter(|r| r.spec.lattice().is_some_and(|l| l.diagonals.name() == diagonals && l.load_case == case))
        .collect();
    let rigid = mine.iter().filter(|r| r.status != RunStatus::Mechanism).count();
    let moduli: Vec<f64> = mine
        .iter()
        .filter(|r| r.status == RunStatus::Ok)
        .filter_map(|r| r.metrics.lattice.youngs_modulus.or(r.metrics.lattice.shear_modulus))
        .collect();
    let mean = (!moduli.is_empty()).then(|| moduli.iter().sum::<f64>() / moduli.len() as f64);
    (format!("{rigid}/{}", mine.len()), mean)
}

#[test]
fn random_networks_with_and_without_diagonals_are_rows_of_their_own() {
    // Cut square networks (6 × 6, 5 % cut, four seeds, CG, 0.1 s a campaign) with both diagonals,
    // then with and without them: the table had averaged both lattices' seeds in one row. With
    // one network its row's mean is its own; with two, each network has its row, whose rigid
    // seeds and mean are recomputed here from its runs alone, and the row with diagonals keeps
    // the one network's mean (whose table has no network column). Means within 5e-4 relative
    // (the table's 4 significant digits).
    let grid = |diagonals: &str| {
        format!(
            "      lattice.diagonals: [{diagonals}]\n      lattice.cut_fraction: [0.05]\n      load.case: [tensile, \
             shear]\n      seed: [1, 2, 3, 4]\n"
        )
    };
    let relax = "{method: cg, tolerance: 1.0e-6}";
    let campaign = |diagonals: &str| lattice_campaign("rnd", "{size: 6, k_diag_ratio: 0.5}", relax, &grid(diagonals));
    let (one, two) = (campaign("both"), campaign("both, none"));
    let records = crate::common::execute_all(&two);
    let (report_one, report_two) = (crate::common::report_of("rnd", &one), crate::common::report_of("rnd", &two));
    // The mean is the row's last but one cell.
    let mean_of = |row: &[String]| row[row.len() - 2].parse::<f64>().ok();
    let close = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => (a / b - 1.0).abs() < 5e-4,
        (a, b) => a.is_none() && b.is_none(),
    };
    for (load, case) in
        [("tensile: E", LoadCase::Tensile), ("shear: apparent G (coursework supports)", LoadCase::Shear)]
    {
        // One network: no network column (the scene's own network), its cut fraction second.
        let alone = table_row(&report_one, &format!("| {load} | 0.05 |"));
        for (diagonals, words) in [("both", "both diagonals"), ("none", "no diagonals")] {
            let row = table_row(&report_two, &format!("| {load} | {words} | 0.05 |"));
            let (rigid, mean) = cut_row_from_records(&records, diagonals, case);
            assert_eq!(row[3], rigid, "{row:?}");
            assert!(close(mean_of(&row), mean), "{row:?} against {mean:?}");
            if diagonals == "both" {
                assert!(close(mean_of(&row), mean_of(&alone)), "{row:?} against {alone:?}");
            }
        }
    }
    // The mix would differ: one no-diagonal network in tension is rigid here, and softer.
    let (_, without) = cut_row_from_records(&records, "none", LoadCase::Tensile);
    let (_, with) = cut_row_from_records(&records, "both", LoadCase::Tensile);
    assert!(without.unwrap() < 0.9 * with.unwrap(), "{without:?} {with:?}");
}

#[test]
fn the_diagonals_paragraph_counts_only_sheared_mechanisms() {
    // Square networks (6 × 6, CG) with and without diagonals, uncut and cut at 0.3 over two
    // seeds, pulled and sheared: the paragraph had counted every mechanism without diagonals as
    // a shear run (the cut networks pulled apart too). Its count must be the sheared ones among
    // the runs without diagonals, recomputed here; exact (counts).
    let grid = "      lattice.diagonals: [both, none]\n      lattice.cut_fraction: [0.0, 0.3]\n      load.case: \
                [tensile, shear]\n      seed: [1, 2]\n";
    let yaml = lattice_campaign("dg", "{size: 6, k_diag_ratio: 0.5}", "{method: cg, tolerance: 1.0e-6}", grid);
    let records = crate::common::execute_all(&yaml);
    let without = |r: &&RunRecord| r.spec.lattice().is_some_and(|l| l.diagonals.name() == "none");
    let sheared = |r: &&RunRecord| r.spec.lattice().is_some_and(|l| l.load_case == LoadCase::Shear);
    let floppy = |r: &&RunRecord| r.status == RunStatus::Mechanism;
    let shear_runs = records.iter().filter(without).filter(sheared).count();
    let shear_mechanisms = records.iter().filter(without).filter(sheared).filter(floppy).count();
    let all_mechanisms = records.iter().filter(without).filter(floppy).count();
    // The old count differs here, so the test tells them apart.
    assert!(all_mechanisms > shear_mechanisms, "{all_mechanisms} {shear_mechanisms}");
    let report = crate::common::report_of("dg", &yaml);
    let paragraph = crate::common::line_with(&report, "**With and without diagonals.**");
    let said = format!("no shear stiffness ({shear_mechanisms} of its {shear_runs} shear runs end as mechanism)");
    assert!(paragraph.contains(&said), "{said}: {paragraph}");
    // E without diagonals: the uncut block's own, to the 4 significant digits written.
    let uncut = records
        .iter()
        .filter(without)
        .find(|r| r.spec.lattice().is_some_and(|l| l.cut_fraction == 0.0 && l.load_case == LoadCase::Tensile))
        .and_then(|r| r.metrics.lattice.youngs_modulus)
        .unwrap();
    let stated = crate::common::number_after(paragraph, "supports), E = ");
    assert!((stated / uncut - 1.0).abs() < 5e-4, "{stated} against {uncut}");
}

/// Two packing scenes of 16 discs over two seeds, one relaxed by FIRE within `fire_budget`
/// (a YAML map's entries after the method), one by CG.
fn two_minimisers(fire_budget: &str) -> String {
    format!(
        "version: 1\nname: mn\ndefaults:\n  material: {{mass: 1.0, k: 1.0, law: linear}}\n  packing: {{n: 16, \
         fraction: 0.88}}\ngrid:\n  seed: [1, 2]\nscenes:\n  - name: fire\n    kind: packing\n    relax: {{method: \
         fire{fire_budget}}}\n  - name: cg\n    kind: packing\n    relax: {{method: cg}}\n"
    )
}

#[test]
fn the_time_step_paragraph_names_every_minimiser_and_which_runs_did_not_relax() {
    // A FIRE scene whose budget (2 t_c) no run meets beside a CG scene that relaxes: the
    // paragraph had named CG alone, from the relaxed runs. Both methods are named whether FIRE's
    // runs relax or not; the unrelaxed ones are counted (recomputed here, exact) only when there
    // are some.
    for (budget, relaxed) in [(", max_tc: 2", false), ("", true)] {
        let yaml = two_minimisers(budget);
        let records = crate::common::execute_all(&yaml);
        let failed = records.iter().filter(|r| r.spec.scene == "fire" && r.status != RunStatus::Ok).count();
        assert_eq!(failed == 0, relaxed, "FIRE's runs: {failed} unrelaxed with budget {budget:?}");
        assert!(records.iter().filter(|r| r.spec.scene == "cg").all(|r| r.status == RunStatus::Ok));
        let report = crate::common::report_of("mn", &yaml);
        let paragraph = crate::common::line_with(&report, "**The time step.**");
        let named = "The packings of this campaign are relaxed by a minimiser (FIRE or conjugate gradients)";
        assert!(paragraph.contains(named), "{paragraph}");
        let count = format!("all {failed} runs by FIRE ended unrelaxed (status no_equilibrium)");
        assert_eq!(paragraph.contains(&count), !relaxed, "{count}: {paragraph}");
        assert_eq!(paragraph.contains("unrelaxed"), !relaxed, "{paragraph}");
    }
}
