//! Waves in chains against independent answers: the front speed of a linear chain, a√(k/m),
//! and the v0^(1/5) speed of the solitary wave in a Hertz chain without pre-load.

mod common;

use common::execute_all;
use mdsolids::measure::power_law_fit;
use mdsolids::runner::RunRecord;

/// A chain of 200 hit at its first particle, the wave timed at the last, over `v0s`.
fn chain(material: &str, duration_tc: f64, v0s: &[f64]) -> Vec<RunRecord> {
    execute_all(&format!(
        "version: 1\nname: t\nscenes:\n  - name: w\n    kind: chain\n    n: 200\n    node: first\n    \
         material: {material}\n    wave: {{}}\n    time: {{duration_tc: {duration_tc}}}\n    grid:\n      v0: {v0s:?}\n"
    ))
}

fn speeds(records: &[RunRecord]) -> Vec<(f64, f64)> {
    records
        .iter()
        .map(|r| {
            assert_eq!(r.status, "ok", "{}", r.message);
            (r.spec.v0, r.metrics.sound_speed(r.metrics.arrival_criterion.as_deref().unwrap()).unwrap())
        })
        .collect()
}

#[test]
fn linear_chain_front_travels_at_the_sound_speed_whatever_v0() {
    let records = chain("{mass: 2.0, k: 8.0}", 100.0, &[0.01, 0.1, 1.0]);
    let theory = (8.0f64 / 2.0).sqrt(); // a√(k/m), a = 1 m
    let speeds = speeds(&records);
    for &(v0, speed) in &speeds {
        // Issue bound 5 %: the threshold front of the discrete chain arrives within a few
        // particles of L/c (measured +0.74 %, the Airy precursor of the front).
        assert!((speed / theory - 1.0).abs() < 0.05, "v0 = {v0}: V = {speed}, a√(k/m) = {theory}");
        assert_eq!(records[0].metrics.sound_speed_theory, Some(theory));
    }
    // Linear: the motion scales with v0 and the criteria are relative, so the speed is the same
    // (issue bound 1 %; measured to 1e-9, round-off).
    for &(_, speed) in &speeds[1..] {
        assert!((speed / speeds[0].1 - 1.0).abs() < 0.01, "{speeds:?}");
    }
}

#[test]
fn hertz_chain_solitary_wave_speed_grows_as_v0_to_the_one_fifth() {
    // Compression-only β = 3/2 contacts at zero pre-load, v0 over two decades. Issue bound:
    // exponent within 0.02 of 1/5 (measured 0.2000: the chain is scale-free and dt follows t_c(v0)).
    let records = chain("{mass: 1.0, k: 1.0, law: hertz, contact: true}", 250.0, &[0.001, 0.01, 0.1]);
    let fit = power_law_fit(&speeds(&records)).unwrap();
    assert!((fit.exponent - 0.2).abs() < 0.02, "exponent {}", fit.exponent);
    assert!(fit.r_squared > 0.999, "R² {}", fit.r_squared);
    assert_eq!(records[0].metrics.sound_speed_theory, None, "no linear sound speed without pre-load");
}

#[test]
fn every_criterion_is_reported_and_the_estimate_is_n_t_c() {
    let r = &chain("{mass: 1.0, k: 1.0}", 100.0, &[0.1])[0];
    let m = &r.metrics;
    for criterion in mdsolids::measure::ARRIVAL_CRITERIA {
        assert!(m.arrival_times.contains_key(criterion), "{criterion} missing");
    }
    // 199 springs between the first and the last particle: t_s = 199 t_c.
    assert!((m.arrival_time_tc_estimate.unwrap() - 199.0 * r.spec.t_c).abs() < 1e-9);
    assert_eq!(m.wave_distance, Some(199.0));
}

/// A free N × N lattice whose top-right node is kicked downwards, timed to the bottom row.
fn lattice(size: usize, diagonals: &str) -> RunRecord {
    execute_all(&format!(
        "version: 1\nname: t\nscenes:\n  - name: l\n    kind: lattice\n    material: {{mass: 1.0, k: 1.0}}\n    \
         lattice: {{size: {size}, diagonals: {diagonals}, k_diag_ratio: 0.5}}\n    supports: free\n    \
         impulse: {{node: top-right, velocity: [0.0, -0.1]}}\n    wave: {{}}\n    time: {{integrator: velocity-verlet}}\n"
    ))
    .remove(0)
}

#[test]
fn lattice_impulse_reaches_the_bottom_row_at_the_longitudinal_speed() {
    let r = lattice(40, "both");
    assert_eq!(r.status, "ok", "{}", r.message);
    let c_l = (1.5f64).sqrt(); // a√((k + k_d)/m)
    assert_eq!(r.metrics.sound_speed_theory, Some(c_l));
    let speed = r.metrics.sound_speed("speed_threshold").unwrap();
    // 5 %: 39 springs are short for a dispersive front (measured +0.6 % with diagonals; the
    // plain chain of columns without them, +11 %, is the same Airy precursor as a 40-particle
    // chain, ~39^(1/3) particles ahead).
    assert!((speed / c_l - 1.0).abs() < 0.05, "V = {speed}, c_L = {c_l}");
    assert_eq!(r.metrics.wave_distance, Some(39.0));
    assert!(r.metrics.youngs_modulus.is_none() && r.metrics.youngs_modulus_fem.is_none(), "no moduli for a kick");
}

#[test]
fn an_impulse_lattice_is_not_loaded() {
    let yaml = "version: 1\nname: t\nscenes:\n  - name: l\n    kind: lattice\n    lattice: {size: 5}\n    \
                impulse: {velocity: [0.0, -0.01]}\n    load: {case: tensile}\n";
    let error = mdsolids::stability::parse_campaign("kick.yaml", yaml).unwrap_err().to_string();
    assert!(error.contains("kick.yaml") && error.contains("scenes[0].load") && error.contains("impulse"), "{error}");
}

#[test]
fn a_force_step_on_the_top_row_sends_a_plane_wave_at_c_l() {
    let r = execute_all(
        "version: 1\nname: t\nscenes:\n  - name: s\n    kind: lattice\n    material: {mass: 1.0, k: 1.0}\n    \
         lattice: {size: 40, k_diag_ratio: 0.5}\n    supports: free\n    impulse: {node: top-centre, force: [0.0, -0.001]}\n    \
         wave: {}\n    time: {integrator: velocity-verlet}\n",
    )
    .remove(0);
    assert_eq!(r.status, "ok", "{}", r.message);
    let c_l = (1.5f64).sqrt();
    let speed = r.metrics.sound_speed("speed_threshold").unwrap();
    // 6 %: a step is not a sharp pulse at its source (the top row accelerates over about a t_c),
    // so the relative threshold is met a spring or two early over 39 (measured +4.6 %).
    assert!((speed / c_l - 1.0).abs() < 0.06, "V = {speed}, c_L = {c_l}");
    // The loads' work is booked: the energy balance closes (measured 1.7e-7).
    assert!(r.metrics.energy_error.unwrap() < 1e-5);
}
