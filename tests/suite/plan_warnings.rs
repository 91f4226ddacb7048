//! What the plan refuses or warns of in a collision beyond the stability limit's dt · ω_max:
//! particles that pass through each other (a step longer than the contact, a kick harder than
//! the spring can stop) and contacts resolved by a few steps. Each threshold is computed here
//! from closed forms (t_c = π/√(2k/m), the energy balance ½ μ v0² = C δ^(β+1)/(β+1)), not by
//! the plan's code, and the verdict is asked just either side of it.

use mdsolids::plan::{self, collision_warning};
use mdsolids::sim::RunStatus;
use std::f64::consts::PI;

use crate::common::{execute_all, repo, runs};

/// A contact pair of m = 1 kg, k = 1 N/m, x_e = 1 m (the defaults) meeting at `v0`, with
/// `time` a YAML flow map.
fn contact_pair(v0: f64, time: &str) -> String {
    format!(
        "version: 1\nname: pw\nscenes:\n  - name: pair\n    kind: pair\n    material: {{contact: true}}\n    v0: {v0}\n    \
         time: {time}\n"
    )
}

/// A chain of 11 hit at its centre at `v0`, Hertz springs (C = 1 N/m^1.5), `contact` or bonded.
fn hertz_chain(v0: f64, contact: bool, time: &str) -> String {
    format!(
        "version: 1\nname: pw\nscenes:\n  - name: chain\n    kind: chain\n    n: 11\n    node: centre\n    v0: {v0}\n    \
         material: {{law: hertz, contact: {contact}}}\n    time: {time}\n"
    )
}

/// The plan's refusal of `yaml`, or `None` when it plans.
fn refusal(yaml: &str) -> Option<String> {
    plan::parse("pw.yaml", yaml).err().map(|e| e.to_string())
}

fn assert_names(error: &str, needed: &[&str]) {
    for part in needed {
        assert!(error.contains(part), "{part} missing from: {error}");
    }
}

/// The contact's own limit: a soft pair (v0 = 0.01 m/s, overlap 0.007 x_e) at position Verlet
/// is refused where ω dt = π dt/t_c passes Verlet's 2, dt_per_tc = π/2. Tolerance 1 %: the
/// limit is measured by bisection to 1e-4 (1.99988, not 2), far inside 1 %.
#[test]
fn a_contact_pair_is_refused_beyond_its_own_omega_limit() {
    let limit_per_tc = PI / 2.0;
    let error = refusal(&contact_pair(0.01, &format!("{{dt_per_tc: {}}}", 0.99 * limit_per_tc))).expect("refused");
    assert_names(&error, &["pw.yaml", "scenes[0] (pair)", "time.dt_per_tc", "stability limit", "allow_unstable"]);
    assert_eq!(refusal(&contact_pair(0.01, &format!("{{dt_per_tc: {}}}", 1.01 * limit_per_tc))), None);
}

/// The student's pair: v0 = 1 m/s at dt_per_tc = 2 has ω dt = π/2, inside Verlet's limit, yet
/// its first step of free flight, v0 dt = 1.11 m, is longer than x_e. The overlap δ = v0/ω =
/// x_e/√2 met one step v0 dt deep reaches √(δ² + (v0 dt)²), which is x_e at v0 dt = x_e/√2 =
/// v0 t_c/π: dt_per_tc = π. Tolerance 1e-3 either side: both sides are closed forms, equal to
/// rounding (1e-15). Allowed to run, the student's run collapses; the run just inside runs.
#[test]
fn a_contact_pair_is_refused_where_one_step_carries_it_through_its_rest_length() {
    let (m, k, rest, v0) = (1.0f64, 1.0f64, 1.0f64, 1.0f64);
    let omega = (2.0 * k / m).sqrt();
    let (t_c, overlap) = (PI / omega, v0 / omega);
    let per_tc = t_c / ((rest * rest - overlap * overlap).sqrt() / v0);
    assert!((per_tc - PI).abs() < 1e-12, "{per_tc}");
    let error = refusal(&contact_pair(v0, "{dt_per_tc: 2}")).expect("the student's step is refused");
    assert_names(
        &error,
        &["pw.yaml", "time.dt_per_tc", "pass through each other", "dt_per_tc > 3.1416", "allow_unstable"],
    );
    assert!(refusal(&contact_pair(v0, &format!("{{dt_per_tc: {}}}", per_tc * (1.0 - 1e-3)))).is_some());
    let inside = contact_pair(v0, &format!("{{dt_per_tc: {}}}", per_tc * (1.0 + 1e-3)));
    assert_eq!(refusal(&inside), None);
    assert_eq!(execute_all(&inside)[0].status, RunStatus::Ok);
    let allowed = &execute_all(&contact_pair(v0, "{dt_per_tc: 2, allow_unstable: true}"))[0];
    assert!(allowed.status == RunStatus::Unstable && allowed.message.contains("collapsed"), "{}", allowed.message);
}

/// The student's Hertz contact chain hit at v0 = 1 m/s (dt·ω_max = 0.11) collapsed at its wall:
/// all of the kick's energy ½ m v0² in one contact compresses it by δ with C δ^2.5/2.5 = ½ m v0²,
/// which reaches x_e at v0 = √(2 C x_e^2.5/(2.5 m)) = √0.8. Tolerance 1e-3 in v0: at dt = t_c/2000
/// one step's free flight (~1e-3 m) adds (1e-3)^2.5/2.5 ~ 1e-8 J to the balance's 0.4 J.
#[test]
fn a_compression_only_chain_is_refused_where_its_kick_could_carry_a_particle_through_the_wall() {
    let (m, c, rest, beta) = (1.0f64, 1.0f64, 1.0f64, 1.5f64);
    let largest = (2.0 * c * rest.powf(beta + 1.0) / ((beta + 1.0) * m)).sqrt();
    let fine = "{dt_per_tc: 2000, duration_tc: 1}";
    let error = refusal(&hertz_chain(largest * (1.0 + 1e-3), true, fine)).expect("refused");
    assert_names(&error, &["scenes[0] (chain).v0", "pass through each other", "v0 < 8.9443e-1", "allow_unstable"]);
    assert_eq!(refusal(&hertz_chain(largest * (1.0 - 1e-3), true, fine)), None);
    assert!(refusal(&hertz_chain(1.0, true, "{}")).is_some(), "the student's chain");
    let allowed = &execute_all(&hertz_chain(1.0, true, "{allow_unstable: true}"))[0];
    assert!(allowed.status == RunStatus::Unstable && allowed.message.contains("collapsed"), "{}", allowed.message);
}

/// A bonded chain sends part of the kick into tension: no refusal, but a warning once the kicked
/// particle's two-body overlap (μ = m/2) reaches x_e, at v0 = √(2 C x_e^2.5/(2.5 m/2)) = √1.6.
/// And a collision whose free flight per step passes half the two-body overlap v0/ω (linear:
/// π/dt_per_tc > 1/2, dt_per_tc < 2π) is warned of as resolved by a few steps. Tolerance 1e-3,
/// closed forms on both sides.
#[test]
fn a_bonded_chain_and_a_coarse_contact_are_warned_of() {
    let largest = (2.0 * 1.0 / (2.5 * 0.5f64)).sqrt();
    let fine = "{dt_per_tc: 2000, duration_tc: 1}";
    let warned = |yaml: &str| collision_warning(&runs(yaml)[0]);
    let above = warned(&hertz_chain(largest * (1.0 + 1e-3), false, fine)).expect("warned");
    assert!(above.contains("pass through its neighbour"), "{above}");
    assert_eq!(warned(&hertz_chain(largest * (1.0 - 1e-3), false, fine)), None);
    let per_tc = 2.0 * PI;
    let coarse = warned(&contact_pair(0.01, &format!("{{dt_per_tc: {}}}", per_tc * (1.0 - 1e-3)))).expect("warned");
    assert!(coarse.contains("resolved by a few steps") && coarse.contains("dt_per_tc > 6.28"), "{coarse}");
    assert_eq!(warned(&contact_pair(0.01, &format!("{{dt_per_tc: {}}}", per_tc * (1.0 + 1e-3)))), None);
    // `mdsolids plan` prints it, naming the run.
    let dir = crate::common::scratch();
    let file = dir.path().join("pw.yaml");
    std::fs::write(&file, contact_pair(0.01, &format!("{{dt_per_tc: {}}}", per_tc * (1.0 - 1e-3)))).unwrap();
    let out = crate::common::text(&crate::common::mdsolids_ok(dir.path(), &["plan", file.to_str().unwrap()]).stdout);
    let line = out.lines().find(|l| l.starts_with("warning: pair-")).unwrap_or_else(|| panic!("{out}"));
    assert!(line.contains("resolved by a few steps"), "{line}");
}

/// Every shipped campaign plans, and only `stability.yaml`, which drives particles through each
/// other on purpose, has a collision warning.
#[test]
fn the_shipped_campaigns_plan_and_only_the_stability_study_is_warned_of() {
    for entry in std::fs::read_dir(repo().join("campaigns")).unwrap() {
        let path = entry.unwrap().path();
        let plan = plan::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let warned: Vec<String> = plan.campaign.runs.iter().filter_map(collision_warning).collect();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        assert!(warned.is_empty() || name == "stability.yaml", "{name}: {warned:?}");
    }
}
