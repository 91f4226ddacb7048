//! Readers' defects of pairs claims, each with a campaign where the claim flips (2026-12-07, twenty-first session).

use std::collections::HashMap;
use std::f64::consts::PI;

use crate::common::{line_with, mdsolids_ok, number_after, scratch};

/// One row of results.csv: column name to cell.
type Row = HashMap<String, String>;

/// The report.md and the rows of results.csv of the campaign `yaml` named `name`, run by the
/// binary in a scratch folder.
fn run(name: &str, yaml: &str) -> (String, Vec<Row>) {
    let dir = scratch();
    let file = dir.path().join(format!("{name}.yaml"));
    std::fs::write(&file, yaml).unwrap();
    mdsolids_ok(dir.path(), &["run", file.to_str().unwrap()]);
    let read = |file: &str| std::fs::read_to_string(dir.path().join(name).join(file)).unwrap();
    let csv = read("results.csv");
    let mut lines = csv.lines();
    // A pair campaign's cells hold no comma (its one quoted cell, the message, is empty).
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines.map(|line| header.iter().cloned().zip(line.split(',').map(String::from)).collect()).collect();
    (read("report.md"), rows)
}

/// A cell as a number (NaN where empty).
fn value(row: &Row, column: &str) -> f64 {
    row[column].parse().unwrap_or(f64::NAN)
}

/// The summary line of an item, by its title.
fn summary<'a>(report: &'a str, title: &str) -> &'a str {
    line_with(report, &format!("| [{title}]("))
}

/// The printed numbers read back: 2 significant digits ({:.1e}) are good to 5 % of a value.
const TWO_DIGITS: f64 = 5e-2;

/// Item 2's tolerance of t_c and r at t_c/50 for a second-order scheme (one_d::PAIR_TOLERANCE).
const PAIR_TOLERANCE: f64 = 2e-3;

/// Two particles of m = 2 kg on a contact spring of k = 8 N/m (not unit) hit at 0.5 m/s, by
/// position Verlet at t_c/50, for each restitution target of `targets`.
fn linear_pairs(targets: &str) -> String {
    format!(
        "version: 1\nname: lp\nscenes:\n  - name: pair\n    kind: pair\n    material: {{mass: 2.0, k: 8.0, contact: \
         true}}\n    v0: 0.5\n    time: {{integrator: position-verlet, dt_per_tc: 50}}\n    grid:\n      \
         damping.restitution: {targets}\n"
    )
}

/// The dashpot of restitution r for two masses m on k: the reduced mass m/2 has critical
/// damping 2√(k m/2) = √(2km), and r = exp(−π ζ/√(1 − ζ²)) gives ζ = −ln r/√(π² + ln² r).
fn gamma_for(r: f64, k: f64, m: f64) -> f64 {
    -r.ln() / (PI * PI + r.ln().powi(2)).sqrt() * (2.0 * k * m).sqrt()
}

/// The reduced-mass oscillator's t_c = π/ω_d with ω_d = √(2k/m − (γ/m)²) (s), and its
/// restitution exp(−π ζ/√(1 − ζ²)), ζ = γ/√(2km).
fn linear_theory(k: f64, m: f64, gamma: f64) -> (f64, f64) {
    let zeta = gamma / (2.0 * k * m).sqrt();
    (PI / (2.0 * k / m - (gamma / m).powi(2)).sqrt(), (-PI * zeta / (1.0 - zeta * zeta).sqrt()).exp())
}

#[test]
fn every_damping_target_of_the_pair_counts_in_its_verdict_and_the_discussion_agrees() {
    // r = 0.1 (ζ = 0.59) makes position Verlet miss t_c by +2.1e-3 and r by −4.1e-3 at t_c/50
    // (second order: 5.3e-4 at t_c/100), outside the item's 2e-3; r = 0.5 stays at 1.3e-3. The
    // item had told one target only, so its ✓ hid the run; now each target has its sentence, the
    // summary's worst is every run's, recomputed here from the two-body theory, and the verdict
    // flips with the r = 0.1 run. The Discussion's "keeps t_c to" must quote the same number.
    for (targets, within) in [("[1.0, 0.5, 0.1]", false), ("[1.0, 0.5]", true)] {
        let (report, rows) = run("lp", &linear_pairs(targets));
        let (mut worst_t, mut worst_r) = (0.0f64, 0.0f64);
        for row in &rows {
            let (k, m, target) = (8.0, 2.0, value(row, "damping.restitution"));
            let gamma = if target < 1.0 { gamma_for(target, k, m) } else { 0.0 };
            // The campaign's γ is the formula's: the same in the last digits.
            assert!((value(row, "gamma") - gamma).abs() <= 1e-9 * gamma.max(1.0), "{row:?}");
            let (t_c, r) = linear_theory(k, m, gamma);
            worst_t = worst_t.max((value(row, "contact_duration") / t_c - 1.0).abs());
            worst_r = worst_r.max((value(row, "restitution") / r - 1.0).abs());
            if gamma > 0.0 {
                // Each damped target has its sentence, its π/ω printed to 4 digits (5e-4 read back).
                let told = report.lines().filter(|l| l.starts_with("- Linear contact, γ = ")).any(|line| {
                    let restitution = &line[line.find("), r = ").unwrap()..];
                    (number_after(line, "s against ") / t_c - 1.0).abs() < 1e-3
                        && (number_after(restitution, " against ") / r - 1.0).abs() < 1e-3
                });
                assert!(told, "no sentence of r = {target}: {report}");
            }
        }
        assert_eq!(worst_t.max(worst_r) <= PAIR_TOLERANCE, within, "{worst_t} {worst_r}");
        let line = summary(&report, "Two particles: contact duration and restitution");
        assert!((number_after(line, "t_c within ") / worst_t - 1.0).abs() < TWO_DIGITS, "{line} {worst_t}");
        assert!((number_after(line, "r within ") / worst_r - 1.0).abs() < TWO_DIGITS, "{line} {worst_r}");
        assert_eq!(line.contains('✓'), within, "{line}");
        let discussion = line_with(&report, "On two particles it keeps t_c to ");
        assert_eq!(number_after(discussion, "keeps t_c to "), number_after(line, "t_c within "), "{discussion}");
    }
}

/// ∫₀¹ dx/√(1 − x^(β+1)), so that a power-law contact lasts 2 (δ_max/v) times it: with
/// x = 1 − u² the end's 1/√ singularity becomes 2u/√(1 − (1 − u²)^(β+1)) → 2/√(β+1) at u = 0,
/// smooth, and Simpson's rule on 2000 intervals is good to far below 1e-8.
fn duration_integral(beta: f64) -> f64 {
    let n = 2000;
    let f = |u: f64| {
        if u == 0.0 { 2.0 / (beta + 1.0).sqrt() } else { 2.0 * u / (1.0 - (1.0 - u * u).powf(beta + 1.0)).sqrt() }
    };
    let h = 1.0 / n as f64;
    let inner: f64 = (1..n).map(|i| f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 }).sum();
    (f(0.0) + inner + f(1.0)) * h / 3.0
}

/// The largest overlap of two masses m hit at v on s = C δ^β: (m/2) v²/2 = C δ^(β+1)/(β+1).
fn max_overlap(c: f64, beta: f64, m: f64, v: f64) -> f64 {
    ((beta + 1.0) * (m / 2.0) * v * v / (2.0 * c)).powf(1.0 / (beta + 1.0))
}

/// A bonded Hertz pair (β = 3/2, C = 1, m = 1) given 0.2 m/s at t_c/`dt_per_tc`, and a β = 2
/// contact (C = 3, m = 0.5) hit at 0.1 m/s at t_c/50, both undamped.
fn power_pairs(dt_per_tc: u32) -> String {
    format!(
        "version: 1\nname: pw\nscenes:\n  - name: bonded\n    kind: pair\n    material: {{law: hertz, contact: \
         false}}\n    v0: 0.2\n    time: {{dt_per_tc: {dt_per_tc}}}\n  - name: beta2\n    kind: pair\n    \
         material: {{law: power, beta: 2.0, contact: true, k: 3.0, mass: 0.5}}\n    v0: 0.1\n"
    )
}

#[test]
fn every_power_law_of_the_pairs_is_summarised_and_judged() {
    // Item 4 told and judged only the first exponent's pair, so a campaign's Hertz pair (β = 3/2)
    // beside a β = 2 one was dropped from its summary and verdict. Now each law has its own worst
    // error of t_c against 2 (δ_max/v) ∫₀¹ dx/√(1 − x^(β+1)), integrated here. The flip: the
    // bonded Hertz pair at t_c/5 misses its t_c by 2.5e-2 (Verlet's (ω dt)² error, 100 times
    // t_c/50's 2.1e-4), outside 2e-3, and the item's ✓ turns ✗ although β = 2 stays within.
    for (dt_per_tc, within) in [(50, true), (5, false)] {
        let (report, rows) = run("pw", &power_pairs(dt_per_tc));
        let line = summary(&report, "Hertz springs in 1D");
        for (scene, label, beta) in [("bonded", "Hertz t_c within ", 1.5), ("beta2", "β = 2: t_c within ", 2.0)] {
            let row = rows.iter().find(|r| r["scene"] == scene).unwrap();
            let (c, m, v) = (value(row, "k"), value(row, "mass"), value(row, "v0"));
            let t_c = 2.0 * max_overlap(c, beta, m, v) / v * duration_integral(beta);
            let error = (value(row, "contact_duration") / t_c - 1.0).abs();
            assert!((number_after(line, label) / error - 1.0).abs() < TWO_DIGITS, "{line}: {scene} {error}");
            assert_eq!(error <= PAIR_TOLERANCE, within || scene == "beta2", "{scene} {error}");
        }
        assert_eq!(line.contains('✓'), within, "{line}");
    }
}

/// The restitution of (m/2) δ̈ = −C δ^β − γ δ̇ from δ = 0, δ̇ = v to δ = 0 again, integrated
/// here by RK4 in steps of t_end/10⁵ (t_end about twice the half period) (the crossing's velocity interpolated linearly: its
/// error γ dt/(m/2) ≈ 1e-5 of v). A bonded symmetric law swings the same half period.
fn own_restitution(c: f64, beta: f64, m: f64, gamma: f64, v: f64, t_end: f64) -> f64 {
    let accel = |d: f64, w: f64| (-c * d.abs().powf(beta) * d.signum() - gamma * w) / (m / 2.0);
    let dt = t_end / 1e5;
    let (mut d, mut w) = (0.0f64, v);
    // At most 10 t_end, 20 half periods: a pair that never returns fails here.
    for _ in 0..1_000_000 {
        let (k1d, k1w) = (w, accel(d, w));
        let (k2d, k2w) = (w + k1w * dt / 2.0, accel(d + k1d * dt / 2.0, w + k1w * dt / 2.0));
        let (k3d, k3w) = (w + k2w * dt / 2.0, accel(d + k2d * dt / 2.0, w + k2w * dt / 2.0));
        let (k4d, k4w) = (w + k3w * dt, accel(d + k3d * dt, w + k3w * dt));
        let next =
            (d + dt / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d), w + dt / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w));
        if next.0 < 0.0 && d > 0.0 {
            let s = d / (d - next.0);
            return -(w + s * (next.1 - w)) / v;
        }
        (d, w) = next;
    }
    panic!("the pair did not come back to δ = 0 within 10 t_end")
}

#[test]
fn a_bonded_hertz_pair_given_a_restitution_target_is_told_whether_its_calibration_holds() {
    // A bonded Hertz pair's γ for a target r is the linear formula at the tangent stiffness
    // k_t = βCδ_max^(β−1): r = 0.5 gives 0.322 (the contact, softer for most of its course, lasts
    // 3.9 s against the linear 2.7 s, so the dashpot acts longer), r = 0.98 gives 0.971 (miss
    // 0.009). The report had said neither (only the appendix table showed 0.3219). Now each
    // target has its sentence: its own integration read back to its 4 digits (1e-3 here), the
    // MD within the item's 5e-3 of it, and the claim flips at the 0.02 the report allows a miss.
    let yaml = "version: 1\nname: hb\nscenes:\n  - name: bonded\n    kind: pair\n    material: {law: hertz, contact: \
                false}\n    v0: 0.2\n    grid:\n      damping.restitution: [0.5, 0.98]\n";
    let (report, rows) = run("hb", yaml);
    for (target, holds) in [(0.5, false), (0.98, true)] {
        let row = rows.iter().find(|r| value(r, "damping.restitution") == target).unwrap();
        let (c, beta, m, v, gamma) = (1.0, 1.5, value(row, "mass"), value(row, "v0"), value(row, "gamma"));
        // The campaign's γ: the linear formula at the tangent stiffness of the largest overlap.
        let k_t = beta * c * max_overlap(c, beta, m, v).powf(beta - 1.0);
        assert!((gamma / gamma_for(target, k_t, m) - 1.0).abs() < 1e-9, "{gamma}");
        let own = own_restitution(c, beta, m, gamma, v, 2.0 * value(row, "contact_duration"));
        let md = value(row, "restitution");
        assert!((md / own - 1.0).abs() < 5e-3, "MD {md} against {own}");
        let line = line_with(&report, &format!("bonded asked for r = {target:.4}"));
        assert!((number_after(line, "and gets ") / md - 1.0).abs() < 1e-3, "{line}");
        assert_eq!((own - target).abs() <= 0.02, holds, "{own}");
        assert_eq!(line.contains("the linear calibration of γ holds"), holds, "{line}");
        if !holds {
            assert!((number_after(line, "own integration: ") / own - 1.0).abs() < 1e-3, "{line} {own}");
        }
    }
}
