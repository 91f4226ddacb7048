//! The report's sentences are claims computed from the data: each test builds small campaigns
//! on both sides of a claim and sees the sentence flip with the data.

use crate::common::{execute_all, report_of};

/// The first number in `text` after `marker` (the report writes 4 to 6 significant digits).
fn number_after(text: &str, marker: &str) -> f64 {
    let rest = &text[text.find(marker).unwrap_or_else(|| panic!("no {marker:?} in {text}")) + marker.len()..];
    let end = rest.find(|c: char| !(c.is_ascii_digit() || ".e-+".contains(c))).unwrap_or(rest.len());
    // A sentence's full stop is not a decimal point.
    rest[..end].trim_end_matches('.').parse().unwrap_or_else(|_| panic!("no number after {marker:?}: {rest}"))
}

/// The report line that contains `marker`.
fn line_with<'a>(report: &'a str, marker: &str) -> &'a str {
    report.lines().find(|l| l.contains(marker)).unwrap_or_else(|| panic!("no line with {marker:?}"))
}

/// A 4 × 4 loaded lattice, m = k = 1, with `damping` (a YAML flow map) and a `grid` line.
fn loaded_lattice(damping: &str, grid: &str) -> String {
    format!(
        "version: 1\nname: bg\nscenes:\n  - name: bg\n    kind: lattice\n    lattice: {{size: 4, k_diag_ratio: 0.5}}\n    \
         load: {{case: tensile, per_node: 0.01}}\n    damping: {damping}\n    relax: {{max_tc: 20000}}\n    grid:\n      {grid}\n"
    )
}

/// The lattice of [`loaded_lattice`] swept over background damping `gammas` (N s/m).
fn background_sweep(gammas: &str) -> String {
    loaded_lattice("{}", &format!("damping.background: {gammas}"))
}

#[test]
fn background_damping_is_judged_against_its_critical_value() {
    // γ_crit = 2√(k_min m) as the program computes it for `background: critical`.
    let critical = execute_all(&loaded_lattice("{background: critical}", "seed: [1]"))[0]
        .metrics
        .lattice
        .gamma_background_critical
        .unwrap();
    let g = |x: f64| format!("{}", x * critical);
    // Across γ_crit: the fastest run is the one nearest it, and the least damped follows the
    // underdamped envelope ln(1/θ) m/γ_g within 5 % (the load ramp and the window of checks
    // shift the measured time by a few t_c).
    let across = report_of("bg", &background_sweep(&format!("[{}, {}, {}, {}]", g(0.25), g(0.8), g(3.0), g(8.0))));
    let critical_line = line_with(&across, "critical background damping is γ_crit");
    assert!((number_after(critical_line, "γ_crit = 2√(k_min m) = ") / critical - 1.0).abs() < 1e-3, "{critical_line}");
    assert!(critical_line.contains("= 0.80 γ_crit."), "{critical_line}");
    let envelope = line_with(&across, "Below γ_crit");
    let (predicted, measured) = (number_after(envelope, "m/γ_g = "), number_after(envelope, "measured "));
    assert!((measured / predicted - 1.0).abs() < 0.05, "{envelope}");
    assert!(line_with(&across, "above γ_crit").contains("more damping relaxes slower"));
    // All above γ_crit: no underdamped sentence, and the least damped run is the fastest.
    let above = report_of("bg", &background_sweep(&format!("[{}, {}, {}]", g(2.0), g(4.0), g(8.0))));
    assert!(!above.contains("Below γ_crit"));
    assert!(line_with(&above, "critical background damping is γ_crit").contains("= 2.00 γ_crit."));
    assert!(!above.contains("overdamped and creeps"), "the old, unconditional claim");
}

/// A linear chain of `n` hit at one end, timed at the far end.
fn wave_chain(n: usize) -> String {
    format!(
        "version: 1\nname: ch\nscenes:\n  - name: wave\n    kind: chain\n    n: {n}\n    v0: 0.01\n    wave: {{}}\n"
    )
}

#[test]
fn the_arrival_criteria_are_ordered_by_their_measured_speeds() {
    // Short chains see the displacement threshold after the speed threshold, long ones before
    // it (each threshold is relative to its own source peak): the words follow the numbers.
    for (n, order) in [(10, "after"), (50, "before")] {
        let report = report_of("ch", &wave_chain(n));
        let first = line_with(&report, "by the speed threshold (the receiver's speed");
        let by_speed = number_after(first, "m away, at ");
        let criteria = line_with(&report, "Other criteria give");
        let by_displacement = number_after(criteria, "Other criteria give ");
        assert!(criteria.contains(&format!("by the displacement threshold (arrives {order} the speed threshold)")));
        assert_eq!(by_displacement > by_speed, order == "before", "{first}\n{criteria}");
        assert!(!criteria.contains("lags"), "the old, unconditional claim");
    }
}

#[test]
fn the_lattice_time_step_states_the_formula_that_gives_its_number() {
    // m = 0.785 kg, k = 2e9 N/m: t_c from the formulas here, not from the program; with
    // r = 0.5 the dashpot γ = |ln r| √(2km)/√(π² + ln² r) slows the pair.
    let (m, k) = (0.785f64, 2.0e9f64);
    let undamped = std::f64::consts::PI * (m / (2.0 * k)).sqrt();
    let ln_r = 0.5f64.ln();
    let gamma = ln_r.abs() * (2.0 * k * m).sqrt() / (std::f64::consts::PI.powi(2) + ln_r * ln_r).sqrt();
    let damped = std::f64::consts::PI / (2.0 * k / m - (gamma / m).powi(2)).sqrt();
    for damping in ["{background: 10000.0}", "{restitution: 0.5, background: 10000.0}"] {
        let yaml = format!(
            "version: 1\nname: dt\nscenes:\n  - name: block\n    kind: lattice\n    material: {{mass: {m}, k: {k}}}\n    \
             lattice: {{size: 4}}\n    damping: {damping}\n    load: {{case: tensile, per_node: 1000.0}}\n    \
             relax: {{max_tc: 20000}}\n"
        );
        let report = report_of("dt", &yaml);
        let line = line_with(&report, "gives the pair's t_c");
        if !damping.contains("restitution") {
            assert!((number_after(line, "t_c = π√(m/(2k)) = ") / undamped - 1.0).abs() < 1e-3, "{line}");
        } else {
            assert!((number_after(line, "t_c = π/√(2k/m − (γ/m)²) = ") / damped - 1.0).abs() < 1e-3, "{line}");
            assert!((number_after(line, "(π√(m/(2k)) = ") / undamped - 1.0).abs() < 1e-3, "{line}");
        }
    }
}

/// A 10 × 10 tensile block cut at `cuts` over six seeds, relaxed by FIRE.
fn random_block(cuts: &str) -> String {
    format!(
        "version: 1\nname: rnd\nscenes:\n  - name: random\n    kind: lattice\n    lattice: {{size: 10, k_diag_ratio: 0.5}}\n    \
         load: {{case: tensile, per_node: 0.001}}\n    relax: {{method: fire}}\n    grid:\n      lattice.cut_fraction: {cuts}\n      \
         seed: [1, 2, 3, 4, 5, 6]\n"
    )
}

#[test]
fn random_networks_average_the_rigid_seeds_and_say_where_rigidity_held() {
    // Lightly cut, every seed is rigid and keeps well over half its bonds; cut to 0.6 and
    // beyond, none is rigid: the sentence names what the runs show, not the theory's margin.
    let light = report_of("rnd", &random_block("[0.2]"));
    let sentence = line_with(&light, "Effective-medium theory for central-force networks");
    assert!(number_after(sentence, "the sparsest rigid one keeps ") > 0.5, "{sentence}");
    assert!(line_with(&light, "| tensile | 0.20 |").contains("| 6/6 |"));
    let heavy = report_of("rnd", &random_block("[0.6, 0.7]"));
    let sentence = line_with(&heavy, "Effective-medium theory for central-force networks");
    assert!(sentence.contains("No cut network stayed rigid here."), "{sentence}");
    assert!(!sentence.contains("a little beyond it"), "the old, unconditional claim");
    // A mechanism has no kept fraction and no modulus: its row says so instead of averaging 0.
    let row = line_with(&heavy, "| tensile | 0.60 |");
    assert_eq!(row, "| tensile | 0.60 | 0/6 | – | – | – |");
}

/// A free 20 × 20 lattice kicked down at its upper-right node with speed `v0` (m/s, c = 1 m/s
/// without diagonals), its bottom row probed.
fn kicked_block(v0: f64) -> String {
    format!(
        "version: 1\nname: kick\nscenes:\n  - name: kick\n    kind: lattice\n    lattice: {{size: 20}}\n    supports: free\n    \
         impulse: {{node: top-right, velocity: [0.0, -{v0}]}}\n    wave: {{}}\n    probes: {{rows: [bottom]}}\n    \
         time: {{integrator: velocity-verlet}}\n    grid:\n      lattice.diagonals: [none, both]\n"
    )
}

#[test]
fn the_kicked_column_keeps_its_front_only_while_the_strain_is_small() {
    // Without diagonals the kicked column is a chain of its own: at a strain of 1e-3 its front
    // reaches the bottom row in that column alone (share ≥ 99.9 %: the linear lattice has no
    // coupling between columns); at 0.1 the column's rotations pass a share sideways. With
    // diagonals the front spreads (share < 50 %).
    let share = |report: &str, which: &str| {
        let line = line_with(report, which);
        number_after(line, "s), ")
    };
    let small = report_of("kick", &kicked_block(0.001));
    let without = share(&small, "Without diagonals the kicked column");
    assert!(without >= 99.9, "{without}");
    assert!(share(&small, "With diagonals every node") < 50.0);
    assert!(line_with(&small, "Without diagonals the kicked column").contains("v0/c = 0.001000"));
    let large = report_of("kick", &kicked_block(0.1));
    let without = share(&large, "Without diagonals the kicked column");
    assert!(without < 99.0, "{without}");
}

/// Loaded blocks of side `size` (m = k = 1, clamped bottom) brought to rest by critical damping,
/// FIRE and CG, each stopped by the displacement bound at 1e-4.
fn relaxation_race(size: usize) -> String {
    format!(
        "version: 1\nname: race\ndefaults:\n  lattice: {{size: {size}, k_diag_ratio: 0.5}}\n  supports: clamped-bottom\n  \
         load: {{case: tensile, per_node: 0.01}}\n  relax: {{tolerance: 1.0e-4, max_tc: 20000}}\nscenes:\n  \
         - name: critical\n    kind: lattice\n    damping: {{background: critical}}\n  \
         - name: minimisers\n    kind: lattice\n    grid:\n      relax.method: [fire, cg]\n"
    )
}

#[test]
fn the_relaxation_winner_is_the_method_with_the_fewest_force_evaluations() {
    // On a 3 × 3 block CG needs the fewest evaluations, on a 32 × 32 one FIRE (measured: 18
    // against 71 and 375 against 360): the summary names the winner the runs' step counts give,
    // and the factor over the most expensive method is the ratio of their counts.
    for (size, winner) in [(3, "CG"), (32, "FIRE")] {
        let records = execute_all(&relaxation_race(size));
        let fewest = records.iter().min_by_key(|r| r.steps).unwrap();
        let most = records.iter().max_by_key(|r| r.steps).unwrap();
        let name = |r: &mdsolids::runner::RunRecord| match r.spec.relax().unwrap() {
            relax if relax.critical_background => "critical damping".to_string(),
            relax => relax.method.name().to_uppercase(),
        };
        assert_eq!(name(fewest), winner, "the runs themselves: {size} × {size}");
        let report = report_of("race", &relaxation_race(size));
        let summary = line_with(&report, "](#1-relaxation-time-to-a-modulus)");
        let said = format!("{winner} first at {size} × {size}: ");
        assert!(summary.contains(&said), "{summary}");
        let factor = number_after(summary, &said);
        // 4 significant digits in the text.
        assert!((factor / (most.steps as f64 / fewest.steps as f64) - 1.0).abs() < 1e-3, "{summary}");
        assert!(summary.contains(&format!("than {}", name(most))), "{summary}");
        let paragraph = line_with(&report, "**Which method to use.**");
        assert!(paragraph.contains(&format!("{winner} wins on the largest block")), "{paragraph}");
    }
}

#[test]
fn each_lattice_type_is_set_against_its_continuum_or_said_to_have_no_modulus() {
    // A triangular block carries the tensile load (E and ν against λ = μ = √3k/(4d)); a
    // honeycomb one is a mechanism (z = 3 < 4) and has neither.
    let yaml = "version: 1\nname: lt\nscenes:\n  - name: types\n    kind: lattice\n    damping: {restitution: 0.5}\n    \
                lattice: {nx: 6, ny: 5}\n    load: {per_node: 0.01}\n    relax: {max_tc: 2000}\n    grid:\n      \
                lattice.type: [triangular, honeycomb]\n";
    let records = execute_all(yaml);
    let triangular = &records[0].metrics.lattice;
    let report = report_of("lt", yaml);
    let paragraph = line_with(&report, "**The networks against their continuum.**");
    let (e, e_continuum) =
        (number_after(paragraph, "triangular (z = 6): E = "), number_after(paragraph, " Pa against "));
    // 4 significant digits in the text.
    assert!((e / triangular.youngs_modulus.unwrap() - 1.0).abs() < 1e-3, "{paragraph}");
    assert!((e_continuum / triangular.youngs_modulus_theory.unwrap() - 1.0).abs() < 1e-3, "{paragraph}");
    assert!(
        (e_continuum / (2.0 / 3f64.sqrt()) - 1.0).abs() < 1e-3,
        "E = 2k/(√3 d) of the triangular continuum: {paragraph}"
    );
    assert!(paragraph.contains("honeycomb (z = 3): no E (mechanism"), "{paragraph}");
    assert!(!paragraph.contains("honeycomb (z = 3): E ="), "{paragraph}");
}
