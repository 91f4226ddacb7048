//! Lattice types (`lattice.type`): the triangular lattice against its static twin and its
//! continuum (λ = μ = √3k/(4d)), in x and in y; the honeycomb and kagome networks as the
//! static solver sees them (Maxwell: z = 3 floppy, z = 4 marginal); the rigidity of diluted
//! triangular networks on both sides of Maxwell's count; waves on every type.

use crate::common::{execute_all, line_with, number_after, report_of, runs};
use crate::shipped;
use mdsolids::runner::RunRecord;
use mdsolids::sim::RunStatus;

/// k = 1e6 N/m, 1 N per node (strains ~1e-6: geometric non-linearity far below the
/// tolerances), m = 0.5 kg, a = 0.1 m, d = 0.01 m.
fn campaign(lattice: &str, extra: &str, grid: &str) -> String {
    format!(
        "version: 1\nname: t\ndefaults:\n  material: {{mass: 0.5, k: 1.0e6}}\n  damping: {{restitution: 0.5}}\n  geometry: {{spacing: 0.1, depth: 0.01}}\nscenes:\n  - name: l\n    kind: lattice\n    lattice: {lattice}\n{extra}    grid:\n{grid}"
    )
}

const K: f64 = 1.0e6;
const DEPTH: f64 = 0.01;

fn relative(a: Option<f64>, b: Option<f64>) -> f64 {
    let (a, b) = (a.expect("measured"), b.expect("reference"));
    (a - b).abs() / b.abs()
}

fn label(r: &RunRecord) -> String {
    format!("{} {:?}", r.run_id, r.spec.varied)
}

/// The static answers of a campaign whose MD stops after 1 t_c (`relax.max_tc: 1`): the
/// static solve comes first and is complete; the short MD run only marks `no_equilibrium`.
fn static_answers(yaml: &str) -> Vec<RunRecord> {
    runs(yaml).iter().map(crate::common::execute).collect()
}

#[test]
fn triangular_md_relaxes_to_its_static_twin() {
    // The square lattice's bound (0.5 %); measured at most 7e-5 for E and G, 3e-5 for ν.
    let yaml = campaign(
        "{type: triangular, nx: 7, ny: 7}",
        "    load: {per_node: 1.0}\n",
        "      supports: [coursework, clamped-bottom]\n      load.case: [tensile, shear, tensile-x]\n",
    );
    let records = execute_all(&yaml);
    assert_eq!(records.len(), 6);
    for r in &records {
        assert_eq!(r.status, RunStatus::Ok, "{}: {}", label(r), r.message);
        let m = &r.metrics.lattice;
        if m.youngs_modulus_fem.is_some() {
            assert!(relative(m.youngs_modulus, m.youngs_modulus_fem) < 5e-3, "E {}", label(r));
            assert!(relative(m.poisson_ratio, m.poisson_ratio_fem) < 5e-3, "ν {}", label(r));
        } else {
            assert!(relative(m.shear_modulus, m.shear_modulus_fem) < 5e-3, "G {}", label(r));
        }
    }
}

#[test]
fn triangular_periodic_strip_has_the_lame_constants_at_every_size() {
    // A uniform strain is the static answer of the periodic strip (every node is a centre of
    // inversion of its bonds), so it measures λ + 2μ = 3√3k/(4d) in tension (ν = 0: it cannot
    // contract) and μ = √3k/(4d) in shear at every size. Tolerances: 1e-5 in tension (the
    // non-linear answer moves by about the strain, 1e-6; measured 2.9e-6), 1e-9 in shear
    // (measured 2e-10), ν 0 to 1e-9 (round-off), the theory columns to 1e-15.
    let yaml = campaign(
        "{type: triangular}",
        "    supports: periodic-x\n    relax: {max_tc: 1}\n    load: {per_node: 1.0}\n",
        "      lattice.size: [4, 9, 16]\n      load.case: [tensile, shear]\n",
    );
    let (constrained, mu) = (3.0 * 3.0_f64.sqrt() * K / (4.0 * DEPTH), 3.0_f64.sqrt() * K / (4.0 * DEPTH));
    for r in static_answers(&yaml) {
        let m = &r.metrics.lattice;
        assert!(relative(m.shear_modulus_theory, Some(mu)) < 1e-15, "{}", label(&r));
        if m.youngs_modulus_fem.is_some() {
            assert!(relative(m.youngs_modulus_fem, Some(constrained)) < 1e-5, "E {}", label(&r));
            assert!(relative(m.youngs_modulus_theory, Some(constrained)) < 1e-15, "{}", label(&r));
            assert!(m.poisson_ratio_fem.unwrap().abs() < 1e-9, "ν {}", label(&r));
        } else {
            assert!(relative(m.shear_modulus_fem, Some(mu)) < 1e-9, "G {}", label(&r));
        }
    }
}

/// E_fem and ν_fem of a free triangular block (coursework supports) loaded along y
/// (`tensile`) and along x (`tensile-x`), by size.
fn triangular_block(sizes: &str) -> Vec<(usize, bool, f64, f64)> {
    let yaml = campaign(
        "{type: triangular}",
        "    relax: {max_tc: 1}\n    load: {per_node: 1.0}\n",
        &format!("      lattice.size: [{sizes}]\n      load.case: [tensile, tensile-x]\n"),
    );
    static_answers(&yaml)
        .iter()
        .map(|r| {
            let l = r.spec.lattice().unwrap();
            let m = &r.metrics.lattice;
            (l.nx, l.rotated, m.youngs_modulus_fem.unwrap(), m.poisson_ratio_fem.unwrap())
        })
        .collect()
}

#[test]
fn triangular_block_approaches_the_isotropic_continuum_in_x_and_y() {
    // E = 2k/(√3 d), ν = 1/3 in every direction. A block's edges stiffen it by O(1/N) (its
    // zigzag sides more than its straight top and bottom): each error must shrink as N
    // doubles, and at N = 33 lie within 5 % for E (measured 1.1 % along y, 3.5 % along x) and
    // 3 % for ν (measured 2.0 %, 1.0 %); E_x/E_y → 1 (measured 1.109, 1.050, 1.024).
    let (youngs, nu) = (2.0 * K / (3.0_f64.sqrt() * DEPTH), 1.0 / 3.0);
    let block = triangular_block("9, 17, 33");
    for along_x in [false, true] {
        let runs: Vec<_> = block.iter().filter(|b| b.1 == along_x).collect();
        let errors: Vec<f64> = runs.iter().map(|b| (b.2 / youngs - 1.0).abs()).collect();
        assert!(errors.windows(2).all(|w| w[1] < w[0]) && errors[2] < 0.05, "E along x {along_x}: {errors:?}");
        let errors: Vec<f64> = runs.iter().map(|b| (b.3 / nu - 1.0).abs()).collect();
        assert!(errors.windows(2).all(|w| w[1] < w[0]) && errors[2] < 0.03, "ν along x {along_x}: {errors:?}");
    }
    let ratio = |n: usize| {
        let e = |x: bool| block.iter().find(|b| b.0 == n && b.1 == x).unwrap().2;
        e(true) / e(false) - 1.0
    };
    assert!(
        ratio(17) < ratio(9) && ratio(33) < ratio(17) && ratio(33).abs() < 0.04,
        "E_x/E_y − 1 at 33: {}",
        ratio(33)
    );
}

#[test]
fn honeycomb_and_kagome_carry_only_what_maxwell_allows() {
    // Central forces: the honeycomb (z = 3 < 4) has no shear stiffness, the kagome (z = 4)
    // is marginal, floppy at its free edges. Both free blocks, on either support, are
    // mechanisms in tension and shear; so is a periodic strip in shear. A periodic strip in
    // tension is rigid: it measures λ + 2μ, the kagome's 3√3k/(8d) and the honeycomb's
    // k/(2√3 d) (its μ = 0), to O(1/ny) of the top and bottom rows: within 10 % (honeycomb,
    // measured 6.7 %) and 1 % (kagome, 0.8 %) at ny = 9, closer at ny = 17.
    let yaml = campaign(
        "{nx: 8}",
        "    load: {per_node: 1.0}\n    relax: {max_tc: 1}\n",
        "      lattice.type: [honeycomb, kagome]\n      lattice.ny: [9, 17]\n      supports: [coursework, clamped-bottom, periodic-x]\n      load.case: [tensile, shear]\n",
    );
    let s3 = 3.0_f64.sqrt();
    for r in static_answers(&yaml) {
        let l = r.spec.lattice().unwrap();
        let rigid =
            l.supports == mdsolids::spec::Supports::PeriodicX && l.load_case == mdsolids::spec::LoadCase::Tensile;
        if !rigid {
            assert_eq!(r.status, RunStatus::Mechanism, "{}: {}", label(&r), r.message);
            continue;
        }
        let honeycomb = l.lattice_type == mdsolids::model::LatticeType::Honeycomb;
        let constrained = if honeycomb { K / (2.0 * s3 * DEPTH) } else { 3.0 * s3 * K / (8.0 * DEPTH) };
        let m = &r.metrics.lattice;
        assert!(relative(m.youngs_modulus_theory, Some(constrained)) < 1e-15, "{}", label(&r));
        let tolerance = match (honeycomb, l.ny) {
            (true, 9) => 0.10,
            (true, _) => 0.05,
            (false, 9) => 0.01,
            (false, _) => 0.005,
        };
        assert!(relative(m.youngs_modulus_fem, Some(constrained)) < tolerance, "E {}", label(&r));
    }
}

#[test]
fn diluted_triangular_network_is_floppy_below_maxwells_count() {
    // Keeping a fraction p of the bonds leaves a mean coordination 6p; below 2/3 (z < 4)
    // there are fewer constraints than degrees of freedom and the loaded network must be a
    // mechanism, whatever the seed (Maxwell's count is a bound, not an estimate). Near p = 1
    // the network is rigid. 21 × 21, four seeds each.
    let yaml = campaign(
        "{type: triangular, size: 21}",
        "    load: {per_node: 1.0}\n    relax: {max_tc: 1}\n",
        "      lattice.cut_fraction: [0.03, 0.5]\n      seed: [1, 2, 3, 4]\n",
    );
    for r in static_answers(&yaml) {
        let cut = r.spec.lattice().unwrap().cut_fraction;
        if cut > 1.0 / 3.0 {
            assert_eq!(r.status, RunStatus::Mechanism, "{}", label(&r));
        } else {
            assert_ne!(r.status, RunStatus::Mechanism, "{}: {}", label(&r), r.message);
            let p = r.metrics.lattice.bond_fraction_kept.unwrap();
            assert!(p > 0.9, "{}: kept {p}", label(&r));
            assert!(r.metrics.lattice.youngs_modulus_linear.unwrap() > 0.0);
        }
    }
}

#[test]
fn wave_from_the_top_row_arrives_near_each_lattice_longitudinal_speed() {
    // A force step down on the whole top row of a free 21 × 21 block: a plane longitudinal
    // wave, timed at the bottom row from the top-centre node. Theory c_L: square a√((k + k_d)/m),
    // triangular a√(9k/(8m)), kagome a√(3k/(4m)), honeycomb a√(3k/(8m)). The kinetic-energy
    // criterion's speed distance/t within 20 % of c_L on every type (measured 0.87 … 0.98 of
    // the arrival time; the front of a discrete lattice is dispersed over a few rows).
    let yaml = campaign(
        "{nx: 21, ny: 21}",
        "    supports: free\n    impulse: {node: top-centre, force: [0.0, -0.001]}\n    wave: {}\n    time: {integrator: velocity-verlet}\n",
        "      lattice.type: [square, triangular, honeycomb, kagome]\n",
    );
    let (a, m) = (0.1, 0.5);
    for r in execute_all(&yaml) {
        let l = r.spec.lattice().unwrap();
        let c_l = a * match l.lattice_type.name() {
            "square" => (1.5 * K / m).sqrt(),
            "triangular" => (9.0 * K / (8.0 * m)).sqrt(),
            "kagome" => (3.0 * K / (4.0 * m)).sqrt(),
            _ => (3.0 * K / (8.0 * m)).sqrt(),
        };
        let metrics = &r.metrics;
        assert!(relative(metrics.sound_speed_theory, Some(c_l)) < 1e-12, "{}", label(&r));
        let speed = metrics.wave_distance.unwrap() / metrics.arrival_times["kinetic_energy"];
        assert!((speed / c_l - 1.0).abs() < 0.2, "{}: {speed} against {c_l}", label(&r));
    }
}

#[test]
fn a_sideways_step_on_a_periodic_strip_sends_a_transverse_wave_at_each_lattice_speed() {
    // A force step along x on the whole top row of a periodic strip 8 nodes wide with a free
    // bottom (`periodic-x-free`: no side edges to shed longitudinal waves), timed at the bottom
    // row; no damping. Theory along y (the slopes of the Bloch branches, unit::measure_moduli):
    // square c_T = a√(k_d/m), triangular c_T = a√(3k/(8m)). The speed threshold catches the
    // leading edge of a front that spreads as it goes, so its offset falls with the distance:
    // measured 5.9 % at 41 rows and 2.6 % at 161 on both. Required: within 3.5 % at 161 rows,
    // and closer there than at 41. The honeycomb (μ = 0) has no transverse speed and carries
    // no front: no criterion fires.
    let yaml = campaign(
        "{nx: 8}",
        "    supports: periodic-x-free\n    damping: {restitution: 1.0}\n    impulse: {node: top-centre, force: [0.001, 0.0]}\n    wave: {}\n    time: {integrator: velocity-verlet}\n",
        "      lattice.type: [square, triangular, honeycomb, kagome]\n      lattice.ny: [41, 161]\n",
    );
    let (a, m) = (0.1, 0.5);
    let mut offsets: std::collections::BTreeMap<String, Vec<(usize, f64)>> = Default::default();
    for r in execute_all(&yaml) {
        let l = r.spec.lattice().unwrap();
        let metrics = &r.metrics;
        let c = match l.lattice_type.name() {
            "square" => a * (0.5 * K / m).sqrt(),
            "triangular" => a * (3.0 * K / (8.0 * m)).sqrt(),
            "kagome" => {
                // Its reference is the Bloch slope a√(k/(2m)); what arrives depends on how the
                // zero branch takes the step (the report reads it), so no speed is required.
                assert!(relative(metrics.sound_speed_theory, Some(a * (K / (2.0 * m)).sqrt())) < 1e-12);
                continue;
            }
            _ => {
                assert!(metrics.sound_speed_theory.is_none(), "{}", label(&r));
                assert!(metrics.arrival_times.is_empty(), "{}: {:?}", label(&r), metrics.arrival_times);
                continue;
            }
        };
        assert!(relative(metrics.sound_speed_theory, Some(c)) < 1e-12, "{}", label(&r));
        let speed = metrics.wave_distance.unwrap() / metrics.arrival_times["speed_threshold"];
        offsets.entry(l.lattice_type.name().into()).or_default().push((l.ny, (speed / c - 1.0).abs()));
    }
    assert_eq!(offsets.len(), 2, "{offsets:?}");
    for (kind, by_rows) in &offsets {
        let offset = |rows: usize| by_rows.iter().find(|(n, _)| *n == rows).unwrap().1;
        let (near, far) = (offset(41), offset(161));
        assert!(far < 0.035 && far < near, "{kind}: offset {near} at 41 rows, {far} at 161");
    }
}

#[test]
fn the_lattice_types_report_states_the_count_and_what_was_observed() {
    // The shipped campaign (408 runs, ~2.5 s) rendered, run once for this and the pinned results.
    let report = std::fs::read_to_string(shipped::whole("lattice-types").join("report.md")).unwrap();
    for title in ["rigidity and moduli", "isotropy", "rigidity percolation", "waves"] {
        assert!(report.contains(&format!(". Lattice types: {title}\n")), "no section {title}");
    }
    for line in [
        "honeycomb: z = 3, below twice the dimension, 4: floppy by counting. It carried tensile on periodic-x; the static solver's \
         rigidity test found a mechanism (before MD) under tensile on coursework, shear on coursework, shear on \
         periodic-x.",
        "kagome: z = 4, equal to twice the dimension, 4: isostatic, marginal. It carried tensile on periodic-x;",
        "triangular: z = 6, above twice the dimension, 4: rigid by counting. It carried tensile on coursework, tensile on \
         periodic-x, shear on coursework, shear on periodic-x; it was never a mechanism.",
        "sends a plane transverse wave: by the same criterion its speed is 1.039 of c_T",
        "The kagome's acoustic Bloch branch along y that moves sideways has the slope a√(k/(2m)) = √2 c_T",
        "The honeycomb's strip carried no transverse front under a 1 N step or a 1000 N step",
        // The four types' ratios to c_L (1.065 … 1.099) are alike within 5 %: the criterion's offset.
        "Over the 4 networks the ratios lie within 3.2 % of one another: the criterion, not the network",
        // No MD run stopped short of the static answer.
        "Where a network carried its load and MD counted it relaxed, MD and the static answer of the same network \
         agree to",
    ] {
        assert!(report.contains(line), "missing: {line}");
    }
    // A sideways step sends a transverse wave: its space–time picture draws u_x (u_y is round-off).
    assert!(
        report.contains(
            "Displacement along x of every node of the kicked column (0: bottom) against time, types-shear-wave"
        ),
        "the transverse wave's space–time figure draws u_x"
    );
    // Direction: E(45°)/E(0°) from the measured E, ν and G, against the continuum within 5 %:
    // 1.6 for the square lattice at k_d = k, 0.625 at k_d = k/4, 1 for the triangular network.
    assert!(report.contains(". Lattice types: direction\n"), "no section on direction");
    let ratio = |prefix: &str| -> f64 {
        let row = report.lines().find(|l| l.starts_with(prefix)).unwrap_or_else(|| panic!("no row {prefix}"));
        row.split('|').nth(7).unwrap().trim().parse().unwrap()
    };
    for (prefix, continuum) in
        [("| square | 1.000 | 33 |", 1.6), ("| square | 0.2500 | 33 |", 0.625), ("| triangular | – | 33 |", 1.0)]
    {
        let measured = ratio(prefix);
        assert!((measured / continuum - 1.0).abs() < 0.05, "{prefix} E(45°)/E(0°) = {measured} against {continuum}");
    }
    // E(p) of both diluted types with its seeds' error bars and the effective-medium line at
    // that type's 2d/z, shown in the percolation item.
    for (scene, threshold) in [("types-percolation", "0.667"), ("square-percolation", "0.500")] {
        // SVG, or PNG where the SVG would pass 30 kB.
        let figure = format!("](plots/{scene}-dilution.");
        let at = report.find(&figure).unwrap_or_else(|| panic!("no E(p) figure of {scene}"));
        assert!(at < report.find("## Discussion").unwrap(), "the E(p) figure of {scene} is in its item");
        assert!(report.contains(&format!("zero at p = 2d/z = {threshold}")), "{scene}: EMT at {threshold}");
    }
    // The triangular thresholds from 32 nodes up within 0.645 … 0.675 of Jacobs and Thorpe's
    // 0.660 (measured 0.656 and 0.654 at 32 and 64, grid steps of 0.005 there; with a top row
    // hinged at its loaded nodes they rose with the size instead, to 0.71 at 128), and the
    // seeds' spread at 64 nodes below that at 16 (measured 0.011 and 0.020).
    let row = |n: usize| report.lines().find(|l| l.starts_with(&format!("| triangular | {n} | 6 | "))).expect("a row");
    let column = |n: usize, at: usize| -> f64 {
        row(n).split('|').nth(at).unwrap().split('±').next().unwrap().trim().parse().unwrap()
    };
    for n in [32, 64] {
        assert!((0.645..0.675).contains(&column(n, 4)), "{}", row(n));
    }
    assert!(column(64, 5) < column(16, 5), "{} against {}", row(64), row(16));
}

#[test]
fn hertz_springs_work_on_every_rigid_type() {
    // Power-law springs C|δ|^1.5 (no stiffness at rest) through the same bond list and static
    // solver: relaxed MD against the Newton–Raphson static answer within 5e-3 (the linear
    // lattices' bound), triangular free block and kagome periodic strip, in tension.
    let yaml = campaign(
        "{nx: 8, ny: 7}",
        "    material: {mass: 0.5, k: 1.0e6, law: hertz}\n    damping: {restitution: 0.5, background: 300.0}\n    load: {per_node: 1.0}\n",
        "      lattice.type: [triangular, kagome]\n      supports: [clamped-bottom, periodic-x]\n",
    );
    let records = execute_all(&yaml);
    for r in &records {
        let l = r.spec.lattice().unwrap();
        if l.lattice_type == mdsolids::model::LatticeType::Kagome && l.supports != mdsolids::spec::Supports::PeriodicX {
            assert_eq!(r.status, RunStatus::Mechanism, "{}", label(r));
            continue;
        }
        assert_eq!(r.status, RunStatus::Ok, "{}: {}", label(r), r.message);
        let m = &r.metrics.lattice;
        assert!(relative(m.youngs_modulus, m.youngs_modulus_fem) < 5e-3, "E {}", label(r));
    }
}

#[test]
fn md_stopped_before_its_softest_mode_settles_is_said_to_part_from_the_static_answer() {
    // A kagome block 12 × 11 pulled along x on coursework supports: its softest mode, k_min =
    // 0.95 N/m, sways the free sides, which set ν and not E. Under γ_g = 200 N s/m (145 × that
    // mode's critical damping) it creeps with a time constant of ~210 s, and E_kin/E_pot counts
    // the run relaxed at ~7 s with ν = 0.23 against the static 0.333 (E within 1.2e-4, its
    // error bound's quantity). Under critical background damping the same block comes to rest,
    // ν within 1.5e-4. The item's bound is 5e-3 (E and G relative, ν absolute): the first run
    // must be named as parting (by more than 0.05 in ν, and stopped before its time constant),
    // the second among those that agree; the item had said "relaxed MD and the static answer
    // agree to 1.2e-4" of both and left tensile-x out of what the kagome carried.
    let yaml = campaign(
        "{type: kagome, nx: 12, ny: 11}",
        "    load: {per_node: 1.0, case: tensile-x}\n",
        "      damping.background: [200.0, critical]\n",
    );
    let report = report_of("t", &yaml);
    assert!(report.contains("It carried tensile-x on coursework;"), "{report}");
    let count = line_with(&report, "MD and the static answer of the same network part beyond 5e-3");
    assert!(count.contains("in 1 of the 2 runs MD counted relaxed; the other 1 agree to"), "{count}");
    let parting = line_with(&report, "- Kagome, tensile-x on coursework, γ_g = 200 N s/m: ν = ");
    let (md, fem) = (number_after(parting, ": ν = "), number_after(parting, "by MD against "));
    assert!((md - fem).abs() > 0.05 && (fem - 1.0 / 3.0).abs() < 1e-3, "{parting}");
    let (stopped, settles) = (number_after(parting, "stopped at "), number_after(parting, "time constant of "));
    assert!(settles > 10.0 * stopped && parting.contains("MD stopped on its way to rest"), "{parting}");
    assert!(!report.contains("γ_g = critical: ν ="), "the critically damped run parts too");
    // `critical` is a word, not a number of N s/m.
    assert!(!report.contains("critical N s/m"), "a unit after a word");
    let summary = line_with(&report, "Lattice types: rigidity and moduli](");
    assert!(summary.contains("| ✗"), "{summary}");
    // The isotropy table is the static answer and says so; the MD that parts from it is named.
    assert!(report.contains("| static E_y (Pa) | static E_x (Pa) | E_x/E_y | static ν_yx | static ν_xy |"));
    let isotropy = line_with(&report, "The table is the static answer of each block");
    assert!(isotropy.contains("parts from it on kagome, tensile-x on coursework, γ_g = 200 N s/m (ν = "), "{isotropy}");
}

/// The isotropy item's sentence on the triangular block, from a static campaign pulling it along
/// y and x at `sizes`, and its table.
fn isotropy_report(sizes: &str) -> String {
    let yaml = campaign(
        "{type: triangular}",
        "    relax: {max_tc: 1}\n    load: {per_node: 1.0}\n",
        &format!("      lattice.size: [{sizes}]\n      load.case: [tensile, tensile-x]\n"),
    );
    report_of("t", &yaml)
}

#[test]
fn isotropy_says_how_the_difference_goes_with_n_only_from_sizes_that_ran() {
    // One size cannot show E_x/E_y − 1 falling as N grows (the item had said "halves as N
    // doubles" of N = 12 alone); two can, and the sentence lists each size's E_x/E_y − 1 as the
    // table has it (its 4 decimals against the sentence's 4 digits: within 1e-4). Measured
    // 0.1088 at N = 9 and 0.0505 at 17.
    let one = isotropy_report("9");
    let sentence = line_with(&one, "The triangular block on coursework supports");
    assert!(sentence.contains("only N = 9 ran, so how the difference goes with N is not measured here"), "{sentence}");
    let two = isotropy_report("9, 17");
    let sentence = line_with(&two, "The triangular block on coursework supports");
    assert!(sentence.contains("the difference falls as N grows"), "{sentence}");
    // "E_x/E_y − 1 = 0.1088 at N = 9 and 0.05047 at N = 17."
    let listed = sentence.split_once("E_x/E_y − 1 = ").unwrap().1.trim_end_matches('.');
    for (item, n) in listed.split(" and ").zip([9, 17]) {
        let row = line_with(&two, &format!("| triangular | {n} | coursework |"));
        let ratio: f64 = row.split('|').nth(6).unwrap().trim().parse().unwrap();
        let said: f64 = item.strip_suffix(&format!(" at N = {n}")).unwrap().parse().unwrap();
        assert!((said - (ratio - 1.0)).abs() < 1e-4, "N = {n}: {said} against the table's {ratio}: {sentence}");
    }
}

/// The ratio column of the waves table's row that starts with `label`.
fn wave_ratio(report: &str, label: &str) -> Option<f64> {
    let row = line_with(report, &format!("| {label} | longitudinal |"));
    row.split('|').nth(9).unwrap().trim().parse().ok()
}

#[test]
fn kicked_waves_keep_damped_lattices_and_a_missing_front_apart() {
    // The square lattice kicked at a corner with and without diagonals, undamped and at r = 0.5,
    // beside the triangular, kagome and honeycomb ones (the campaign of the review). Undamped
    // the ratios to c_L run 0.866 (honeycomb) … 1.196 (square, no diagonals); damped fronts
    // arrive earlier, 1.407 and 1.183 of the undamped c_L; no criterion sees the kagome's front.
    // The item had pooled them ("1.054 … 1.407"), called the ratios alike, printed four rows
    // "square", not said that the kagome's never came, and the Discussion had "square (z = 8)"
    // of a lattice without diagonals. Numbers from the table's 3 decimals: within 1e-3.
    let yaml = "version: 1\nname: w\nscenes:\n  - name: square\n    kind: lattice\n    lattice: {size: 20}\n    \
                supports: free\n    impulse: {node: top-right, velocity: [0.0, -0.001]}\n    wave: {}\n    \
                time: {integrator: velocity-verlet}\n    grid:\n      lattice.diagonals: [none, both]\n      \
                damping.restitution: [1.0, 0.5]\n  - name: types\n    kind: lattice\n    lattice: {nx: 15, ny: 15}\n    \
                supports: free\n    impulse: {node: top-right, velocity: [0.0, -0.001]}\n    wave: {}\n    \
                time: {integrator: velocity-verlet}\n    grid:\n      lattice.type: [triangular, kagome, honeycomb]\n";
    let report = report_of("w", yaml);
    let undamped: Vec<f64> = ["square, no diagonals", "square, both diagonals", "triangular", "honeycomb"]
        .iter()
        .map(|label| wave_ratio(&report, label).unwrap())
        .collect();
    let (low, high) = undamped.iter().fold((f64::MAX, f64::MIN), |(l, h), x| (l.min(*x), h.max(*x)));
    let first = line_with(&report, "A kick of one node");
    assert!(first.contains("down the square, triangular and honeycomb lattices"), "{first}");
    assert!((number_after(first, "on the undamped lattices is ") - low).abs() < 1e-3, "{first}");
    assert!((number_after(first, " … ") - high).abs() < 1e-3, "{first}");
    let apart = line_with(&report, "Over the 4 networks the ratios lie ");
    assert!((number_after(apart, "ratios lie ") - 100.0 * (high / low - 1.0)).abs() < 0.2, "{apart}");
    assert!(apart.contains("% apart") && apart.contains("it alone does not set the offset"), "{apart}");
    assert!(wave_ratio(&report, "kagome").is_none());
    assert!(report.contains("No criterion saw a longitudinal front reach the bottom row of the kagome lattice"));
    let damped = line_with(&report, "A damped lattice's front is held against the undamped lattice's speed");
    for diagonals in ["no diagonals", "both diagonals"] {
        let (hot, cold) = (
            wave_ratio(&report, &format!("square, {diagonals}, r = 0.5")).unwrap(),
            wave_ratio(&report, &format!("square, {diagonals}")).unwrap(),
        );
        let said = format!("square, {diagonals}, r = 0.5 (0.001000 m/s kick), ");
        assert!((number_after(damped, &said) - hot).abs() < 1e-3 && hot > cold, "{damped}");
    }
    let summary = line_with(&report, "Lattice types: waves](");
    assert!(summary.contains("| ✓"), "damped runs are not judged: {summary}");
    let discussion = line_with(&report, "**The networks against their continuum.**");
    assert!(discussion.contains("square (z = 4 or 8): its longitudinal wave at 1.196 × c_L (no diagonals) and"));
}

#[test]
fn a_diluted_network_run_twice_counts_as_one_seed() {
    // Two loads on the same diluted networks (two runs of each network, seed and cut): each
    // seed's threshold counts once. Grouped by type, N and seed alone, the two runs of each cut
    // had made every seed two, so the table showed 4 seeds for 2 and a standard error √2 too small.
    let yaml = "version: 1\nname: twice\nscenes:\n  - name: twice\n    kind: lattice\n    lattice: {type: triangular, size: 12}\n    \
                relax: {method: static}\n    grid:\n      load.per_node: [1.0, 2.0]\n      \
                lattice.cut_fraction: [0.0, 0.2, 0.3, 0.35, 0.4, 0.5]\n      seed: [1, 2]\n";
    let report = report_of("twice", yaml);
    let row = report.lines().find(|l| l.starts_with("| triangular | 12 | ")).unwrap_or_else(|| panic!("{report}"));
    assert_eq!(row.split('|').nth(3).unwrap().trim(), "2", "seeds: {row}");
    // Nor do two runs of one cut count as two cut fractions: two cuts run twice each locate no
    // threshold (it takes three).
    let two_cuts = yaml.replace("[0.0, 0.2, 0.3, 0.35, 0.4, 0.5]", "[0.0, 0.5]");
    let report = report_of("twice", &two_cuts);
    assert!(
        line_with(&report, "Lattice types: rigidity percolation](#").contains("| no threshold located |"),
        "{report}"
    );
}

#[test]
fn diluted_networks_that_differ_in_supports_are_not_pooled_as_seeds() {
    // One seed of a square lattice with both diagonals on two supports: two networks of one
    // seed each, each against its own effective-medium 2d/z (z = 8: 0.500). Pooled by type and
    // N they had been "over 2 seeds" from one seed run.
    let yaml = "version: 1\nname: pool\ndefaults:\n  material: {k: 1.0e7}\nscenes:\n  - name: sq\n    kind: lattice\n    \
                lattice: {type: square, size: 10}\n    relax: {method: static}\n    grid:\n      supports: [coursework, clamped-bottom]\n      \
                lattice.cut_fraction: [0.0, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5]\n      seed: [1]\n  - name: tri\n    kind: lattice\n    \
                lattice: {type: triangular, size: 10}\n    relax: {method: static}\n    grid:\n      \
                lattice.cut_fraction: [0.0, 0.2, 0.3, 0.4, 0.5]\n";
    // (The item asks for a type other than square among the diluted ones.)
    let report = report_of("pool", yaml);
    for supports in ["coursework", "clamped-bottom"] {
        let row = format!("| square (10 rows, diagonals both, {supports} supports) | 10 | 1 | ");
        let line = report.lines().find(|l| l.starts_with(&row)).unwrap_or_else(|| panic!("no row {row}: {report}"));
        assert!(line.ends_with("| – | 0.500 | – |"), "{line}");
    }
    assert!(line_with(&report, "diagonals both, coursework supports) N = 10: the rigidity").contains("(one seed: no"));
}
