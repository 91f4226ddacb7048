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
