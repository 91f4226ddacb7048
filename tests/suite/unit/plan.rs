//! Unit tests of `src/plan/mod.rs`, moved out of the library (one test binary).

/// A pair whose dt `time.dt_omega_max` sets, under `budget` (YAML, or empty).
fn campaign(budget: &str) -> String {
    format!(
        "version: 1\nname: t\n{budget}scenes:\n  - name: p\n    kind: pair\n    v0: 1.0\n    \
         time: {{dt_omega_max: 0.1}}\n"
    )
}

/// The spec layer leaves dt to the plan where `dt_omega_max` sets it; the plan decides it
/// once: dt = 0.1 / ω_max with ω_max = √(2k/m) = √2 rad/s for the unit pair.
#[test]
fn the_plan_decides_dt_where_dt_omega_max_sets_it() {
    let unplanned = mdsolids::spec::parse("t.yaml", &campaign("")).unwrap().runs.remove(0);
    assert!(!unplanned.is_planned() && unplanned.steps == 0);
    let spec = mdsolids::plan::parse("t.yaml", &campaign("")).unwrap().campaign.runs.remove(0);
    assert!(spec.is_planned());
    assert!((spec.dt - 0.1 / 2f64.sqrt()).abs() < 1e-9 * spec.dt, "dt = {}", spec.dt);
    assert_eq!(spec.steps, (spec.duration / spec.dt).ceil() as u64);
}

/// A run its memory budget refuses is never estimated: it keeps the nominal dt = t_c / 50,
/// and with it the run id its records have always had.
#[test]
fn a_run_the_budget_refuses_gets_the_nominal_dt() {
    let plan = mdsolids::plan::parse("t.yaml", &campaign("budget: {memory_per_run_mb: 0.000001}\n")).unwrap();
    let spec = &plan.campaign.runs[0];
    assert!(plan.campaign.budget.refuses(spec).is_some());
    assert_eq!(spec.dt, spec.t_c / mdsolids::spec::DEFAULT_DT_PER_TC);
    assert_eq!(spec.steps, (spec.duration / spec.dt).ceil() as u64);
}
