//! A reader's defect of the kicked-lattice waves (2026-12-07): a node kicked sideways was held
//! against c_T alone, though its first arrival at the bottom row is the P wave met obliquely.

use polars::prelude::*;

use crate::common::{line_with, mdsolids_ok, number_after, numbers, scratch};

/// Node mass m (kg), spring k (N/m), k_d/k and spacing a (m) of the campaign below: not 1, so
/// that a slipped m, k or a shows.
const M: f64 = 2.0;
const K: f64 = 8.0;
const K_DIAG_RATIO: f64 = 0.5;
const A: f64 = 0.5;

/// Two free 16 × 16 lattices with both diagonals, kicked at the top centre at 1e-3 m/s: first
/// sideways (the scene a report quoted first, had it a single reference), then down, undamped
/// and with bond dashpots (r = 0.5).
fn campaign() -> String {
    let scene = |name: &str, velocity: &str, grid: &str| {
        format!(
            "  - name: {name}\n    kind: lattice\n    material: {{mass: {M}, k: {K}}}\n    geometry: {{spacing: {A}}}\n    \
             lattice: {{size: 16, k_diag_ratio: {K_DIAG_RATIO}}}\n    supports: free\n    \
             impulse: {{node: top-centre, velocity: {velocity}}}\n    wave: {{}}\n    \
             time: {{integrator: velocity-verlet}}\n{grid}"
        )
    };
    format!(
        "version: 1\nname: kicks\nscenes:\n{}{}",
        scene("side", "[0.001, 0.0]", ""),
        scene("down", "[0.0, -0.001]", "    grid:\n      damping.restitution: [1.0, 0.5]\n")
    )
}

/// The report and results table of [`campaign`].
fn run() -> (String, DataFrame) {
    let dir = scratch();
    let file = dir.path().join("kicks.yaml");
    std::fs::write(&file, campaign()).unwrap();
    mdsolids_ok(dir.path(), &["run", file.to_str().unwrap()]);
    let folder = dir.path().join("kicks");
    let frame =
        CsvReadOptions::default().try_into_reader_with_file_path(Some(folder.join("results.csv"))).unwrap().finish();
    (std::fs::read_to_string(folder.join("report.md")).unwrap(), frame.unwrap())
}

/// The cells of the appendix's `at`-th wave row of the scene `scene`.
fn wave_row<'a>(report: &'a str, scene: &str, at: usize) -> Vec<&'a str> {
    let rows: Vec<&str> = report.lines().filter(|l| l.starts_with(&format!("| `{scene}-"))).collect();
    rows[at].trim_matches('|').split('|').map(str::trim).collect()
}

#[test]
fn a_node_kicked_sideways_is_held_between_c_t_and_c_l_and_a_kick_down_against_c_l() {
    // The references recomputed from the spring constants per unit depth: C22 = k + k_d,
    // C66 = k_d (both diagonals), c = a√(C/m).
    let (c_l, c_t) = (A * ((K + K_DIAG_RATIO * K) / M).sqrt(), A * (K_DIAG_RATIO * K / M).sqrt());
    let (report, frame) = run();
    let scenes: Vec<String> =
        frame.column("scene").unwrap().str().unwrap().iter().map(|s| s.unwrap_or_default().to_string()).collect();
    let (theory, speed) = (numbers(&frame, "sound_speed_theory"), numbers(&frame, "sound_speed_speed_threshold"));
    let restitution = numbers(&frame, "damping.restitution");
    let at = |scene: &str, r: Option<f64>| {
        (0..scenes.len()).find(|&i| scenes[i] == scene && (r.is_none() || restitution[i] == r)).unwrap()
    };
    let (side, down, damped) = (at("side", None), at("down", Some(1.0)), at("down", Some(0.5)));
    // The sideways kick: no single reference (it was c_T, and its front ran +50 % on it); the
    // front lies between c_T and c_L, sooner than any S wave.
    assert_eq!(theory[side], None, "a sideways kick has no one reference speed");
    let v = speed[side].unwrap();
    assert!(c_t < v && v < c_l, "sideways front {v} m/s outside c_T = {c_t} … c_L = {c_l}");
    let row = wave_row(&report, "side", 0);
    let reference = row[row.len() - 2];
    assert!(reference.contains("(c_T) …") && reference.ends_with("(c_L)"), "{row:?}");
    assert!((number_after(reference, "") / c_t - 1.0).abs() < 1e-5, "{reference} against c_T = {c_t}");
    assert!((number_after(reference, "… ") / c_l - 1.0).abs() < 1e-5, "{reference} against c_L = {c_l}");
    let sideways = line_with(&report, "Kicked sideways (side)");
    assert!(sideways.contains("unjudged") && sideways.contains("so it is P"), "{sideways}");
    for (marker, value) in [("between c_T = ", c_t), ("and c_L = ", c_l), ("(L/c_T = ", 15.0 * A / c_t)] {
        assert!((number_after(sideways, marker) / value - 1.0).abs() < 1e-3, "{marker}{value}: {sideways}");
    }
    assert!((number_after(sideways, "bottom row at ") / v - 1.0).abs() < 1e-3, "{sideways}");
    // The kick down keeps its reference c_L and is the one quoted with it, though the sideways
    // scene comes first (quoted before, it read "against c_L = … = 0.7071 m/s").
    assert!((theory[down].unwrap() / c_l - 1.0).abs() < 1e-12, "down: {:?} against {c_l}", theory[down]);
    let row = wave_row(&report, "down", 0);
    assert!((number_after(row[row.len() - 2], "") / c_l - 1.0).abs() < 1e-5, "{row:?}");
    let quoted = line_with(&report, "With diagonals every node is tied");
    assert!((number_after(quoted, "c_L = a√((k + k_d)/m) = ") / c_l - 1.0).abs() < 1e-3, "{quoted}");
    assert!((number_after(quoted, "bottom row at ") / speed[down].unwrap() - 1.0).abs() < 1e-3, "{quoted}");
    // The damped kick is said to be left out, and to arrive sooner only because it does.
    let left_out = line_with(&report, "The damped kicks are left out");
    let damped_speed = speed[damped].unwrap();
    assert!((number_after(left_out, "left out (") / damped_speed - 1.0).abs() < 1e-3, "{left_out}");
    assert_eq!(left_out.contains("arrive sooner"), damped_speed > speed[down].unwrap(), "{left_out}");
}

/// Chains of 21 springs s = δ^β (β = 3/2 and 2), hit at one end at three speeds, and, with
/// `lattice`, a Hertz lattice kicked at the same speeds.
fn solitary_campaign(lattice: bool) -> String {
    let chains = "  - name: hit\n    kind: chain\n    n: 21\n    node: first\n    material: {law: power, contact: true}\n    \
                  wave: {}\n    grid:\n      material.beta: [1.5, 2.0]\n      v0: [0.001, 0.01, 0.1]\n";
    let kicked = "  - name: kick\n    kind: lattice\n    material: {law: hertz}\n    lattice: {size: 8}\n    supports: free\n    \
                  impulse: {node: top-right, velocity: [0.0, -0.001]}\n    wave: {}\n    grid:\n      \
                  impulse.velocity: [[0.0, -0.0001], [0.0, -0.001], [0.0, -0.01]]\n";
    format!("version: 1\nname: solitary\nscenes:\n{chains}{}", if lattice { kicked } else { "" })
}

#[test]
fn a_power_law_chains_solitary_wave_is_answered_in_the_1d_item() {
    // A student's campaign of Hertz chains hit at several speeds got no item that answered it:
    // the speeds and their v0^(1/5) stood only in the abstract. The item "Hertz springs in 1D"
    // now holds each exponent's chain to Nesterenko's (β − 1)/(β + 1), computed here, within
    // the report's 0.05; where a kicked Hertz lattice's item tells the chain's wave beside its
    // own front, the 1D item leaves it to that one (the flip).
    let report = crate::common::report_of("solitary", &solitary_campaign(false));
    let line = line_with(&report, "[Hertz springs in 1D]");
    assert!(line.contains("| ✓\u{a0}within |"), "{line}");
    for beta in [1.5f64, 2.0] {
        let predicted = (beta - 1.0) / (beta + 1.0);
        let told = format!("(β − 1)/(β + 1) = {predicted:.3} for β = {beta}, within 0.05");
        let sentence = line_with(&report, &told);
        assert!(sentence.contains("a solitary wave") && sentence.contains("over 3 runs"), "{sentence}");
        assert!((number_after(sentence, "V ∝ v0^") - predicted).abs() <= 0.05, "{sentence}");
    }
    // The kick item tells the first chain (β = 3/2) beside its lattice; the 1D item the other.
    let report = crate::common::report_of("solitary", &solitary_campaign(true));
    assert!(report.contains("The Hertz chain's solitary wave (hit) speeds up"), "{report}");
    let told: Vec<&str> = report.lines().filter(|l| l.contains("chain carries a solitary wave")).collect();
    assert!(told.len() == 1 && told[0].contains("= 0.333 for β = 2, within 0.05"), "{told:?}");
}

#[test]
fn a_pre_compressed_power_law_chain_is_not_held_to_the_solitary_wave() {
    // Walls pushed in (61 springs over 55 m: δ₀ ≈ 0.098) give the Hertz chain a linear sound
    // speed √(s′(δ₀)/m) ≈ 0.686 m/s that hardly depends on v0 (exponent ~0.006): it carries no
    // Nesterenko wave, and the item had said it did, ✗ against 0.200. It is now not told as
    // one, and the summary fits no speed against v0 for it; the same chain between walls at
    // the rest spacing is (the test above).
    let yaml = "version: 1\nname: pre\nscenes:\n  - name: pre\n    kind: chain\n    n: 60\n    wall_distance: 55.0\n    \
                material: {law: hertz}\n    wave: {}\n    grid:\n      v0: [0.001, 0.01, 0.1]\n";
    let report = crate::common::report_of("pre", yaml);
    assert!(!report.contains("solitary wave, "), "{report}");
    assert!(!report.contains("[Hertz springs in 1D]"), "{report}");
    // Nor does the abstract claim its speed grows with the kick (it said v0^0.006, ✗ 0.200).
    assert!(!report.contains("the kick v0^"), "{report}");
}
