//! A power law fitted through two points meets both: R² = 1 by construction, whatever the data.
//! The report had printed "R² = 1.0000" for such fits; it now says "through 2 points" wherever
//! it writes an R² (the items' sentences, the exponent tables, the figures' labels), and the R²
//! itself from three points on.
//!
//! Three sentences of the 2D items that had not been computed from the campaign (2026-12-07):
//! the shear item named a clamped bottom that no run stood on, the mechanism note blamed missing
//! diagonals for any mechanism, and the E and ν item's ✗ against the continuum had no test.

use mdsolids::runner::RunRecord;
use mdsolids::sim::RunStatus;
use mdsolids::spec::Supports;

use crate::common::{execute_all, line_with, mdsolids_ok, number_after, scratch};

/// Amplitude sweeps over `points` (2 or 3) values: chains of 9 between walls moved in, linear and
/// Hertz (item 8, figure against |ΔW|); a 6 × 6 Hertz block pulled (item 20, figure against the
/// load); a free 8 × 8 Hertz lattice kicked at its corner (item 21, figure of V against v0).
/// Beside the linear chain, the Hertz fits fill the table of linear against Hertz springs.
fn amplitude_sweeps(points: usize) -> String {
    let pick = |values: [&str; 3]| values[..points].join(", ");
    let walls = pick(["9.9", "9.99", "9.5"]);
    let chain = |law: &str| {
        format!(
            "  - name: walls-{law}\n    kind: chain\n    n: 9\n    material: {{law: {law}}}\n    damping: {{restitution: 0.5}}\n    \
             time: {{integrator: velocity-verlet}}\n    relax: {{residual_force: 1.0e-9}}\n    grid:\n      wall_distance: [{walls}]\n"
        )
    };
    format!(
        "version: 1\nname: fits\nscenes:\n{}{}  - name: power\n    kind: lattice\n    material: {{law: hertz}}\n    \
         lattice: {{size: 6, k_diag_ratio: 0.5}}\n    load: {{case: tensile}}\n    relax: {{method: fire}}\n    grid:\n      \
         load.per_node: [{}]\n  - name: kick\n    kind: lattice\n    material: {{law: hertz}}\n    lattice: {{size: 8}}\n    \
         supports: free\n    impulse: {{node: top-right, velocity: [0.0, -0.001]}}\n    wave: {{}}\n    grid:\n      \
         impulse.velocity: [{}]\n",
        chain("linear"),
        chain("hertz"),
        pick(["0.0001", "0.01", "0.001"]),
        pick(["[0.0, -0.0001]", "[0.0, -0.01]", "[0.0, -0.001]"])
    )
}

/// The report of `yaml` (campaign `fits`) and the text of all its SVG figures, where the fits'
/// labels are.
fn report_and_figures(yaml: &str) -> (String, String) {
    let dir = scratch();
    let file = dir.path().join("fits.yaml");
    std::fs::write(&file, yaml).unwrap();
    mdsolids_ok(dir.path(), &["run", file.to_str().unwrap()]);
    let out = dir.path().join("fits");
    let mut figures = String::new();
    for entry in std::fs::read_dir(out.join("plots")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "svg") {
            figures += &std::fs::read_to_string(path).unwrap();
        }
    }
    (std::fs::read_to_string(out.join("report.md")).unwrap(), figures)
}

/// R² of the least-squares line through (ln x, ln y): the squared correlation of the logs,
/// computed here from the records, independently of the program's fit.
fn log_log_r_squared(points: &[(f64, f64)]) -> f64 {
    let logs: Vec<(f64, f64)> = points.iter().map(|(x, y)| (x.ln(), y.ln())).collect();
    let n = logs.len() as f64;
    let (mx, my) = (logs.iter().map(|p| p.0).sum::<f64>() / n, logs.iter().map(|p| p.1).sum::<f64>() / n);
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (x, y) in &logs {
        (sxy, sxx, syy) = (sxy + (x - mx) * (y - my), sxx + (x - mx).powi(2), syy + (y - my).powi(2));
    }
    sxy * sxy / (sxx * syy)
}

/// The (x, y) the report fits for `scene`, from its records: |ΔW| and the secant stiffness of a
/// chain between walls, the load per node and E of a pulled block, the kick and V of a kicked one.
fn swept(records: &[RunRecord], scene: &str) -> Vec<(f64, f64)> {
    let point = |r: &RunRecord| match r.spec.lattice() {
        Some(l) => match l.impulse {
            Some(kick) => (kick.vy.abs(), r.metrics.recommended_sound_speed().unwrap()),
            None => (l.load_per_node, r.metrics.lattice.youngs_modulus.unwrap()),
        },
        None => (r.spec.chain_wall_extension().abs(), r.metrics.chain.secant_stiffness.unwrap()),
    };
    records.iter().filter(|r| r.spec.scene == scene).map(point).collect()
}

/// The sentences that state a fit's R², each found by its marker, with the scene it fits.
const SENTENCES: [(&str, &str); 3] = [
    ("walls-hertz's secant stiffness ∝", "walls-hertz"),
    ("E of scene power: from", "power"),
    ("its front speeds up from", "kick"),
];

#[test]
fn a_fit_through_two_points_states_no_r_squared() {
    // Two points: every sentence, table cell and label says so, and no R² is written anywhere.
    let (report, figures) = report_and_figures(&amplitude_sweeps(2));
    for (marker, _) in SENTENCES {
        let line = line_with(&report, marker);
        assert!(line.contains("(through 2 points") && !line.contains("R²"), "{line}");
    }
    assert!(!report.contains("R² ="), "{report}");
    // Item 25's table (R² last) and the appendix's exponent tables (R², then the run count).
    let kick = report.lines().find(|l| l.starts_with("| kick | Hertz | c against the kick v0 |")).unwrap();
    assert!(kick.ends_with("| – (2 points) |"), "{kick}");
    let appendix = line_with(&report, "| all | power | youngs_modulus | load_per_node |");
    assert!(appendix.contains("| – (2 points) | 2 |"), "{appendix}");
    // The labels of the fitted lines: walls (2 laws), E and its tangent, V against v0.
    assert!(!figures.contains("R²") && figures.matches("(through 2 points)").count() >= 4, "{figures}");
    assert!(figures.contains("fit v0^0.200 (through 2 points)"), "{figures}");

    // Three points: R² is a measure of the fit, stated to 4 decimals in the sentences (half a
    // unit of the last, 5e-5, of the R² computed here) and 6 in the appendix's table.
    let yaml = amplitude_sweeps(3);
    let (report, figures) = report_and_figures(&yaml);
    let records = execute_all(&yaml);
    for (marker, scene) in SENTENCES {
        let line = line_with(&report, marker);
        let r_squared = log_log_r_squared(&swept(&records, scene));
        assert!((number_after(line, "(R² = ") - r_squared).abs() <= 5e-5, "{r_squared}: {line}");
        assert!(!line.contains("points"), "{line}");
    }
    // | all | power | youngs_modulus | load_per_node | p | R² | runs | range |: R² the sixth.
    let appendix = line_with(&report, "| all | power | youngs_modulus | load_per_node |");
    let cell: f64 = appendix.split(" | ").nth(5).unwrap().parse().unwrap_or_else(|_| panic!("{appendix}"));
    assert!((cell - log_log_r_squared(&swept(&records, "power"))).abs() <= 5e-7, "{appendix}");
    assert!(!report.contains("2 points)") && !report.contains("through 2"), "{report}");
    assert!(!figures.contains("(through ") && figures.contains("(R² = "), "{figures}");
}

/// A 4 × 4 block in reduced units (m = 1 kg, k = 1 N/m, k_d/k = 0.5, a = d = 1 m), damped to rest
/// under 1e-3 N per top-row node (a strain of ~1e-3: linear), loaded by `case`; `grid` its lines.
fn block(case: &str, grid: &str) -> String {
    format!(
        "version: 1\nname: fits\nscenes:\n  - name: blk\n    kind: lattice\n    damping: {{restitution: 0.5, background: 0.5}}\n    \
         lattice: {{size: 4, k_diag_ratio: 0.5}}\n    load: {{case: {case}, per_node: 0.001}}\n    grid:\n{grid}"
    )
}

/// The number the report writes just before `marker` in `line` (`0.2798 Pa on 4 × 4 …`).
fn number_before(line: &str, marker: &str) -> f64 {
    let head = &line[..line.find(marker).unwrap_or_else(|| panic!("no {marker:?} in {line}"))];
    let word = head.rsplit([' ', '(']).next().unwrap();
    word.parse().unwrap_or_else(|_| panic!("no number before {marker:?}: {line}"))
}

#[test]
fn the_shear_item_names_a_clamped_bottom_only_where_the_campaign_shears_on_one() {
    // The periodic strip and the coursework supports only: the item had said "and a clamped
    // bottom bends the block" all the same. With a clamped-bottom run it is named, with its
    // apparent G (4 significant digits: within 5e-4 of the record's) and its share of k_d/d
    // (two decimals: within 0.005).
    let marker = "Only the periodic strip";
    let (report, _) = report_and_figures(&block("shear", "      supports: [periodic-x, coursework]\n"));
    let line = line_with(&report, marker);
    assert!(!line.contains("clamped") && line.contains("4 × 4 coursework supports (0.56 of k_d/d: "), "{line}");
    let yaml = block("shear", "      supports: [periodic-x, coursework, clamped-bottom]\n");
    let (report, _) = report_and_figures(&yaml);
    let line = line_with(&report, marker);
    let clamped = execute_all(&yaml)
        .into_iter()
        .find(|r| r.spec.lattice().is_some_and(|l| l.supports == Supports::ClampedBottom))
        .unwrap();
    let (g, theory) =
        (clamped.metrics.lattice.shear_modulus.unwrap(), clamped.metrics.lattice.shear_modulus_theory.unwrap());
    let stated = number_before(line, " Pa on 4 × 4 clamped-bottom supports (");
    assert!((stated / g - 1.0).abs() <= 5e-4, "{g}: {line}");
    let share = number_before(line, " of k_d/d: the clamped bottom bends the block)");
    assert!((share - g / theory).abs() <= 0.005, "{}: {line}", g / theory);
}

#[test]
fn a_mechanism_is_put_down_to_missing_diagonals_only_where_it_has_none() {
    // Sheared 4 × 4 blocks on the coursework's supports: k_d = 0 has no shear stiffness
    // (C44 = k_d); k_d/k = 1e-15 has diagonals, yet its K u = f has no solution the static solver
    // accepts (the premise, from the records). The note had blamed missing diagonals for both.
    let grid = |ratios: &str| format!("      lattice.k_diag_ratio: [{ratios}]\n");
    let records = execute_all(&block("shear", &grid("1.0e-15")));
    assert!(records.iter().all(|r| r.status == RunStatus::Mechanism), "the premise: a mechanism with diagonals");
    let cases = [
        (
            "0.0, 0.5",
            "1 run ended as mechanism: the load meets a zero-stiffness motion (a lattice without diagonals has no shear stiffness), and",
        ),
        ("1.0e-15, 0.5", "1 run ended as mechanism: the load meets a zero-stiffness motion, and no modulus exists."),
        (
            "0.0, 1.0e-15, 0.5",
            "2 runs ended as mechanism: the load meets a zero-stiffness motion (1 of them sheared without diagonals, which have no shear stiffness), and",
        ),
    ];
    for (ratios, sentence) in cases {
        let (report, _) = report_and_figures(&block("shear", &grid(ratios)));
        let line = line_with(&report, "ended as mechanism");
        assert!(line.contains(sentence), "k_d/k = {ratios}: {line}");
    }
}

/// |v∞ − continuum| over v∞'s uncertainty of the modulus `pick` (E or ν) over `records`, one
/// block per size by rising size: v∞ = (N₂ v₂ − N₁ v₁)/(N₂ − N₁) of v(N) = v∞ + b/N from the two
/// largest, the uncertainty its change from the next smaller pair.
fn continuum_distance(records: &[RunRecord], pick: fn(&RunRecord) -> [f64; 2]) -> f64 {
    let points: Vec<(f64, [f64; 2])> = records.iter().map(|r| (r.spec.lattice().unwrap().nx as f64, pick(r))).collect();
    let at = |i: usize, j: usize| {
        let ((n1, v1), (n2, v2)) = (points[i], points[j]);
        (n2 * v2[0] - n1 * v1[0]) / (n2 - n1)
    };
    let n = points.len();
    let value = at(n - 2, n - 1);
    (value - points[n - 1].1[1]).abs() / (value - at(n - 3, n - 2)).abs()
}

#[test]
fn the_extrapolated_moduli_fail_the_continuum_where_they_lie_beyond_three_uncertainties() {
    // Squares 2, 3, 4 and 3, 4, 5 on the coursework's supports. The first pair's v∞ and the
    // second's differ by the next order of the finite-size share (≈ 1/N²), and for 3, 4, 5 the
    // two estimates of ν∞ agree by chance to 2e-4 while both lie 0.004 above 1/3: ν∞ is ~20 of
    // its uncertainties from the continuum (the premise, from the records), past the tolerance of
    // 3, and the item says so with its ✗; for 2, 3, 4 both lie within 3 (✓). The report's
    // uncertainty also has a floor, MD − static (1e-5), which the premise leaves out: the
    // distances are compared to 2 %.
    let young =
        |r: &RunRecord| [r.metrics.lattice.youngs_modulus, r.metrics.lattice.youngs_modulus_theory].map(Option::unwrap);
    let poisson =
        |r: &RunRecord| [r.metrics.lattice.poisson_ratio, r.metrics.lattice.poisson_ratio_theory].map(Option::unwrap);
    for (sizes, held) in [("2, 3, 4", true), ("3, 4, 5", false)] {
        let yaml = block("tensile", &format!("      lattice.size: [{sizes}]\n"));
        let records = execute_all(&yaml);
        let (e, nu) = (continuum_distance(&records, young), continuum_distance(&records, poisson));
        assert_eq!(e <= 3.0 && nu <= 3.0, held, "the premise, {sizes}: E {e}, ν {nu}");
        let (report, _) = report_and_figures(&yaml);
        let summary = line_with(&report, "[Young's modulus and Poisson's ratio]");
        let verdict = if held { "| ✓\u{a0}within |" } else { "| ✗\u{a0}outside |" };
        assert!(summary.contains(verdict), "{sizes}: {summary}");
        let sentence = line_with(&report, "Richardson's v∞");
        let said = sentence.contains("of their uncertainties from them, more than 3, so the blocks do not converge");
        assert_eq!(said, !held, "{sizes}: {sentence}");
        if !held {
            assert!((number_after(sentence, "E lies ") / e - 1.0).abs() < 0.02, "E {e}: {sentence}");
            let after = &sentence[sentence.find("E lies ").unwrap()..];
            assert!((number_after(after, " and ν ") / nu - 1.0).abs() < 0.02, "ν {nu}: {sentence}");
        }
    }
}
