//! Readers' defects of jamming claims, each with a campaign where the claim flips (2026-12-07, twenty-first session).

use polars::prelude::*;

use crate::common::{line_with, number_after, numbers, scratch, value_after};
use crate::packing::run_jam;

/// One packing scene: its name, its `packing` fields and its `relax` fields (YAML flow maps'
/// insides), its fractions and seeds (YAML lists); linear contacts.
#[derive(Clone, Copy)]
struct Scene<'a> {
    name: &'a str,
    packing: &'a str,
    relax: &'a str,
    fractions: &'a str,
    seeds: &'a str,
}

/// Runs the scenes as a campaign named `jam` under `dir`: its results table and its report.
fn run(dir: &std::path::Path, scenes: &[Scene]) -> (DataFrame, String) {
    let mut yaml = "version: 1\nname: jam\nscenes:\n".to_string();
    for s in scenes {
        yaml += &format!(
            "  - name: {}\n    kind: packing\n    packing: {{{}}}\n    material: {{law: linear}}\n    relax: {{{}}}\n    \
             grid:\n      packing.fraction: {}\n      seed: {}\n",
            s.name, s.packing, s.relax, s.fractions, s.seeds
        );
    }
    let (frame, folder) = run_jam(dir, &yaml);
    (frame, std::fs::read_to_string(folder.join("report.md")).unwrap())
}

/// Column `name` of `frame` as text.
fn texts(frame: &DataFrame, name: &str) -> Vec<Option<String>> {
    frame.column(name).unwrap().str().unwrap().iter().map(|s| s.map(String::from)).collect()
}

/// A jammed row of the results table: seed, Δφ = φ − own φ_J, z (rattlers removed), and
/// N′ = N (1 − rattler fraction), its discs that are not rattlers.
struct Jammed {
    seed: f64,
    excess: f64,
    z: f64,
    backbone: f64,
}

/// The jammed rows of `frame`, of `n` discs each.
fn jammed_rows(frame: &DataFrame, n: f64) -> Vec<Jammed> {
    let states = texts(frame, "packing_state");
    let [phi, own, z, rattlers, seed] =
        ["packing_fraction", "own_jamming_fraction", "backbone_coordination", "rattler_fraction", "seed"]
            .map(|c| numbers(frame, c));
    (0..frame.height())
        .filter(|&i| states[i].as_deref() == Some("jammed"))
        .map(|i| Jammed {
            seed: seed[i].unwrap(),
            excess: phi[i].unwrap() - own[i].unwrap(),
            z: z[i].unwrap(),
            backbone: (n * (1.0 - rattlers[i].unwrap())).round(),
        })
        .collect()
}

/// The mean over seeds of each seed's mean own φ_J over the jammed packings of `scene`.
fn scene_onset(frame: &DataFrame, scene: &str) -> f64 {
    let own = numbers(frame, "own_jamming_fraction");
    let (states, scenes, seed) = (texts(frame, "packing_state"), texts(frame, "scene"), numbers(frame, "seed"));
    let of_scene: Vec<usize> = (0..frame.height())
        .filter(|&i| states[i].as_deref() == Some("jammed") && scenes[i].as_deref() == Some(scene))
        .collect();
    let mut seeds: Vec<f64> = of_scene.iter().filter_map(|&i| seed[i]).collect();
    seeds.sort_by(f64::total_cmp);
    seeds.dedup();
    let seed_mean = |s: f64| {
        let of: Vec<f64> = of_scene.iter().filter(|&&i| seed[i] == Some(s)).filter_map(|&i| own[i]).collect();
        of.iter().sum::<f64>() / of.len() as f64
    };
    seeds.iter().map(|&s| seed_mean(s)).sum::<f64>() / seeds.len() as f64
}

/// The verdict word (within, outside or observed) of the item's summary line: its last cell
/// (the symbol before it is followed by a no-break space).
fn summary_verdict(report: &str) -> &str {
    let line = line_with(report, "[Jamming](#");
    let cell = line.trim_end_matches(" |").rsplit('|').next().unwrap();
    ["within", "outside", "observed"].into_iter().find(|v| cell.ends_with(v)).expect(line)
}

#[test]
fn packings_relaxed_by_another_minimiser_are_left_out_whatever_the_scene_order() {
    // 64 linear discs at φ = 0.845 … 0.9, seeds 1 to 3, relaxed by FIRE in one scene and by CG in
    // the other: the same random starts, but other states (cg.yaml: 1.1–1.5 diameters apart).
    // φ_J is FIRE's (the default) in either scene order, the CG packings are named as relaxed by
    // another minimiser, not as repeats; CG alone gives CG's φ_J. φ_J is printed to its standard
    // error's second digit: within a tenth of that error of the seeds' mean recomputed here,
    // and the two minimisers' means are farther apart than that.
    let dir = scratch();
    let fire =
        Scene { name: "fire", packing: "n: 64", relax: "", fractions: "[0.845, 0.85, 0.86, 0.9]", seeds: "[1, 2, 3]" };
    let cg = Scene { name: "cg", relax: "method: cg", ..fire };
    let stated = |report: &str| {
        let line = line_with(report, "N = 64: φ_J = ");
        (number_after(line, "N = 64: φ_J = "), number_after(line, " ± ") / 10.0)
    };
    let (frame, first) = run(dir.path(), &[cg, fire]);
    let (by_fire, by_cg) = (scene_onset(&frame, "fire"), scene_onset(&frame, "cg"));
    let (phi_j, digit) = stated(&first);
    assert!(
        (phi_j - by_fire).abs() <= digit && (phi_j - by_cg).abs() > digit,
        "{phi_j}: FIRE's {by_fire}, CG's {by_cg}"
    );
    let left_out = line_with(&first, "Left out of φ_J and the scalings");
    assert!(left_out.contains("12 packings relaxed by cg (the kept ones' fire)"), "{left_out}");
    assert!(!left_out.contains("repeating"), "{left_out}");
    let other = number_after(left_out, "their φ_J = ");
    assert!((other - by_cg).abs() <= number_after(left_out, " ± ") / 10.0, "{left_out}: CG's {by_cg}");
    // The other order: the same headline.
    let (_, second) = run(dir.path(), &[fire, cg]);
    assert_eq!(line_with(&first, "[Jamming](#"), line_with(&second, "[Jamming](#"));
    // CG alone: its own φ_J, nothing left out.
    let (_, alone) = run(dir.path(), &[cg]);
    let (phi_j, digit) = stated(&alone);
    assert!((phi_j - by_cg).abs() <= digit, "{phi_j} against CG's {by_cg}");
    assert!(!alone.contains("Left out of φ_J"), "{alone}");
}

/// The verdict cell of the item's table row of `quantity`.
fn table_verdict<'a>(report: &'a str, quantity: &str) -> &'a str {
    let row = line_with(report, &format!("| {quantity} |"));
    row.split('|').map(str::trim).rfind(|c| !c.is_empty()).unwrap()
}

#[test]
fn slowly_compressed_packings_alone_are_said_to_be_another_protocol() {
    // 16 linear discs compressed slowly from φ = 0.8 to 0.86 and 0.9, seeds 1 and 2: they jam
    // and results.csv has an own φ_J for each, but φ_J and the scalings are O'Hern et al.'s
    // quenches. The item says they jammed and were compressed (before: "no quench jammed",
    // "k of the k packings jammed, and none of them is a quench ... with its own φ_J").
    let dir = scratch();
    let slow = Scene {
        name: "slow",
        packing: "n: 16, compress_from: 0.8, compress_steps: 2",
        relax: "",
        fractions: "[0.86, 0.9]",
        seeds: "[1, 2]",
    };
    let (frame, report) = run(dir.path(), &[slow]);
    let jammed = jammed_rows(&frame, 16.0).len();
    assert!(jammed > 0, "the case needs compressed packings that jam");
    let own = numbers(&frame, "own_jamming_fraction").iter().flatten().count();
    assert_eq!(own, jammed, "an own φ_J for each jammed packing");
    let line = line_with(&report, "No φ_J could be found");
    let said =
        format!("No φ_J could be found: {jammed} packings jammed, all made by slow compression, which this item");
    assert!(line.contains(&said) && !line.contains("quench of the mixture"), "{line}");
    assert!(line_with(&report, "[Jamming](#").contains("no φ_J: only slowly compressed packings jammed"));
    // Beside quenches far below jamming: those are said not to have jammed, up to φ = 0.75.
    let below = Scene { name: "quench", packing: "n: 16", relax: "", fractions: "[0.7, 0.75]", seeds: "[1, 2]" };
    let (_, report) = run(dir.path(), &[slow, below]);
    let line = line_with(&report, "No φ_J could be found");
    assert!(line.contains("; none of the 4 packings quenched (relaxed up to φ = "), "{line}");
    assert_eq!(number_after(line, "relaxed up to φ = "), 0.75, "{line}");
    // Beside quenches that jam: φ_J is theirs.
    let (_, report) = run(dir.path(), &[slow, Scene { fractions: "[0.86, 0.9]", ..below }]);
    assert!(report.contains("N = 16: φ_J = ") && !report.contains("No φ_J could be found"), "{report}");
    // Quenches alone, none jammed: how many and how far, without the clause about quenches
    // with their own φ_J, which only repeated that none jammed.
    let (_, report) = run(dir.path(), &[below]);
    let line = line_with(&report, "No jammed state was found");
    assert!(line.starts_with("No jammed state was found: 0 of the 4 packings (relaxed up to φ = "), "{line}");
    assert!(!line.contains("none of them is a quench"), "{line}");
}

#[test]
fn nothing_held_against_a_reference_is_observed() {
    // One packing of 16 discs of diameter ratio 1.2 at φ = 0.88: its φ_J is another mixture's
    // than O'Hern et al.'s (not held against 0.842), and one packing has no z_J and no scaling
    // to fit: nothing is judged, and the verdict is an observation (before: "✓ within"). The
    // same packing of their 1:1.4 mixture has its φ_J judged: the verdict is that row's.
    let dir = scratch();
    let one = Scene { name: "one", packing: "n: 16, radius_ratio: 1.2", relax: "", fractions: "[0.88]", seeds: "[1]" };
    let (frame, report) = run(dir.path(), &[one]);
    assert_eq!(jammed_rows(&frame, 16.0).len(), 1, "the case needs the packing jammed");
    assert!(report.contains("N = 16: φ_J = ") && !report.contains("| φ_J |"), "{report}");
    assert_eq!(summary_verdict(&report), "observed");
    assert!(line_with(&report, "**Verdict:").ends_with("observed.**"), "{report}");
    let (_, report) = run(dir.path(), &[Scene { packing: "n: 16", ..one }]);
    assert_eq!(summary_verdict(&report), table_verdict(&report, "φ_J"));
}

/// Each seed's jammed packing nearest its own φ_J (smallest Δφ > 0) among `rows`.
fn nearest(rows: &[Jammed]) -> Vec<&Jammed> {
    let mut seeds: Vec<f64> = rows.iter().map(|r| r.seed).collect();
    seeds.sort_by(f64::total_cmp);
    seeds.dedup();
    let of_seed =
        |s: f64| rows.iter().filter(|r| r.seed == s && r.excess > 0.0).min_by(|a, b| a.excess.total_cmp(&b.excess));
    seeds.into_iter().filter_map(of_seed).collect()
}

#[test]
fn z_at_jamming_is_judged_on_the_packings_nearest_it_not_on_an_extrapolation() {
    // 64 linear discs at φ = 0.84 … 0.9, seeds 1 to 4. Every jammed packing has at least its
    // isostatic count 2N′ − 1 of contacts (z ≥ 4 − 2/N′, N′ its discs that are not rattlers),
    // counted here from results.csv. z = z_J + c √Δφ is an extrapolation, stated against the
    // least bound 4 − 2/N′ and not judged; z of each seed's packing nearest its own φ_J is
    // judged against 4 within 0.25 where their mean Δφ ≤ 0.005. Numbers are printed to 4
    // significant digits or to their standard error's second digit: 1e-3 absolute, or a tenth
    // of the printed error.
    let dir = scratch();
    let near = Scene {
        name: "near",
        packing: "n: 64",
        relax: "",
        fractions: "[0.84, 0.845, 0.85, 0.86, 0.88, 0.9]",
        seeds: "[1, 2, 3, 4]",
    };
    let (frame, report) = run(dir.path(), &[near]);
    let rows: Vec<Jammed> = jammed_rows(&frame, 64.0).into_iter().filter(|r| r.excess > 0.0).collect();
    let line = line_with(&report, "z at jamming (mean contacts per disc");
    assert!(rows.iter().all(|r| r.z * r.backbone / 2.0 >= 2.0 * r.backbone - 1.5), "fewer than 2N′ − 1 contacts");
    let fewest = rows.iter().map(|r| r.backbone).fold(f64::INFINITY, f64::min);
    let bound = 4.0 - 2.0 / fewest;
    assert!((number_after(line, "4 − 2/N′ = ") - bound).abs() <= 1e-3, "{line}: {bound}");
    assert!(line.contains(&format!("N′ ≥ {fewest}")), "{line}");
    // z_J by least squares of z on √Δφ.
    let n = rows.len() as f64;
    let (sx, sy) = rows.iter().fold((0.0, 0.0), |(a, b), r| (a + r.excess.sqrt(), b + r.z));
    let (sxx, sxy) = rows.iter().fold((0.0, 0.0), |(a, b), r| (a + r.excess, b + r.excess.sqrt() * r.z));
    let z_j = (sy - (n * sxy - sx * sy) / (n * sxx - sx * sx) * sx) / n;
    assert!((number_after(line, "z_J = ") - z_j).abs() <= 1e-3, "{line}: {z_j}");
    let side = if z_j < bound { "standard errors below 4 − 2/N′" } else { "at or above 4 − 2/N′" };
    assert!(line.contains(side) && line.contains("not judged."), "{line}");
    // Each seed's nearest packing: its mean z over the seeds, their mean Δφ.
    let closest = nearest(&rows);
    let count = closest.len() as f64;
    let mean = closest.iter().map(|r| r.z).sum::<f64>() / count;
    let distance = closest.iter().map(|r| r.excess).sum::<f64>() / count;
    let error = (closest.iter().map(|r| (r.z - mean).powi(2)).sum::<f64>() / (count - 1.0) / count).sqrt();
    let stated = number_after(line, "has z = ");
    assert!((stated - mean).abs() <= (error / 10.0).max(1e-3), "{line}: {mean} ± {error}");
    assert!(distance <= 0.005, "the case needs the nearest packings within 0.005 of their φ_J: {distance}");
    let within = (mean - 4.0).abs() <= 0.25;
    assert!(line.contains(if within { ": within 0.25 of the isostatic 4" } else { ": outside 0.25" }), "{line}");
    assert_eq!(table_verdict(&report, "z nearest φ_J"), if within { "within" } else { "outside" });
    // Far above jamming the nearest packings tell nothing of z there: not judged (before: the
    // extrapolation in √Δφ, "within").
    let (frame, report) = run(dir.path(), &[Scene { fractions: "[0.9, 0.92]", ..near }]);
    let rows: Vec<Jammed> = jammed_rows(&frame, 64.0).into_iter().filter(|r| r.excess > 0.0).collect();
    let closest = nearest(&rows);
    let distance = closest.iter().map(|r| r.excess).sum::<f64>() / closest.len() as f64;
    assert!(distance > 0.005, "{distance}");
    let line = line_with(&report, "z at jamming (mean contacts per disc");
    assert!(line.contains("too far from φ_J to judge z there") && !line.contains("within"), "{line}");
    assert_eq!(table_verdict(&report, "z nearest φ_J"), "not judged");
}

/// The own φ_J of each seed's jammed packing quenched at `fraction` (seed, own φ_J).
fn own_at(frame: &DataFrame, fraction: f64) -> Vec<(f64, f64)> {
    let states = texts(frame, "packing_state");
    let [quench, own, seed] = ["packing.fraction", "own_jamming_fraction", "seed"].map(|c| numbers(frame, c));
    (0..frame.height())
        .filter(|&i| quench[i] == Some(fraction) && states[i].as_deref() == Some("jammed"))
        .map(|i| (seed[i].unwrap(), own[i].unwrap()))
        .collect()
}

#[test]
fn phi_j_says_its_error_is_the_seeds_scatter_at_its_quench_fractions_alone() {
    // 64 linear discs, seeds 1 to 8, quenched at φ = 0.84 and 0.92: every packing jams at both,
    // and each seed's own φ_J rises from the one to the other by about 0.01, far beyond the
    // seeds' standard error of φ_J (≈ 0.001). The item had stated φ_J ± that error alone, so
    // the same seeds quenched at 0.84 only and at 0.92 only gave two φ_J many of their errors
    // apart, each "within". Now φ_J's sentence, the summary and the table row say at which
    // fractions its error is the seeds' scatter, and the sentence how the own φ_J moves between
    // them per seed (to its error's second digit: a tenth of it), which the summary and the row
    // repeat where the seeds resolve it (a paired t-test at 5 %, 7 degrees of freedom: 2.365).
    let dir = scratch();
    let both = Scene {
        name: "quench",
        packing: "n: 64",
        relax: "",
        fractions: "[0.84, 0.92]",
        seeds: "[1, 2, 3, 4, 5, 6, 7, 8]",
    };
    let (frame, report) = run(dir.path(), &[both]);
    let (low, high) = (own_at(&frame, 0.84), own_at(&frame, 0.92));
    assert!(low.len() == 8 && high.len() == 8, "the case: every packing jammed at both fractions");
    let differences: Vec<f64> = high.iter().map(|&(s, phi)| phi - low.iter().find(|o| o.0 == s).unwrap().1).collect();
    let mean = differences.iter().sum::<f64>() / 8.0;
    let error = (differences.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / 7.0 / 8.0).sqrt();
    let line = line_with(&report, "N = 64: φ_J = ");
    assert!(line.contains("mean ± standard error over 8 seeds: their scatter at φ = 0.84 … 0.92 alone;"), "{line}");
    let resolved = mean.abs() / error > 2.365;
    let (stated, stated_error) = value_after(line, if resolved { "the own φ_J rises by +" } else { "moves by " });
    assert!(
        (stated - mean).abs() <= error / 10.0 && (stated_error / error - 1.0).abs() < 0.05,
        "{line}: {mean} ± {error}"
    );
    let leaves_out = line.contains("a dependence on the preparation that this standard error leaves out");
    assert_eq!(leaves_out, resolved, "{line}: {mean} ± {error}");
    let summary = line_with(&report, "[Jamming](#");
    let row = line_with(&report, "| φ_J |");
    for words in [summary, row] {
        assert!(words.contains("± the seeds' scatter quenched at φ = 0.84 … 0.92 alone"), "{words}");
        assert_eq!(words.contains("; it depends on the preparation: the own φ_J rises by +"), resolved, "{words}");
    }
    // The same seeds quenched at one fraction each: φ_J moves by the difference per seed (each
    // printed to its error's second digit), and each says the preparation is not measured.
    let single = |fractions: &str| {
        let (_, report) = run(dir.path(), &[Scene { fractions, ..both }]);
        let line = line_with(&report, "N = 64: φ_J = ").to_string();
        assert!(line.contains("how it moves with the quench fraction is not measured here"), "{line}");
        let summary = line_with(&report, "[Jamming](#").to_string();
        assert!(summary.contains("alone) against 0.842") && !summary.contains("preparation"), "{summary}");
        (number_after(&line, "φ_J = "), number_after(&line, " ± "))
    };
    let ((at_low, low_error), (at_high, high_error)) = (single("[0.84]"), single("[0.92]"));
    let apart = at_high - at_low;
    assert!((apart - mean).abs() <= (low_error + high_error) / 10.0 + 1e-5, "{at_low}, {at_high}: {mean}");
    assert!(apart > 2.0 * low_error.hypot(high_error), "the case: {at_low} ± {low_error}, {at_high} ± {high_error}");
}

/// The two-sided sign test of `a` against `b`: twice the chance that a fair coin tossed a + b
/// times gives max(a, b) heads or more, at most 1.
fn sign_test(a: usize, b: usize) -> f64 {
    let n = a + b;
    let choose = |k: usize| (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64);
    let tail: f64 = (a.max(b)..=n).map(choose).sum::<f64>() / 2f64.powi(n as i32);
    (2.0 * tail).min(1.0)
}

#[test]
fn a_fall_of_the_unstable_share_is_tested_one_sample_per_seed() {
    // 32 and 64 discs, linear and Hertz, quenched at φ = 0.845 … 0.94, seeds 1 to 3: 108 jammed
    // packings, 19 of 73 with G < 0 at Δφ N² < 10² and 2 of 35 from 10² to 10³, which Fisher's
    // exact test over the packings finds below p = 0.05, and the item had called "a finite-size
    // effect". But the packings of a seed share its random start at every fraction, N and law:
    // one sample per seed, the seeds' own shares from the lowest range to the highest, and the
    // sign test of their falls against their rises can never go below 0.05 with three seeds
    // (2/2³ = 0.25 at best). These states are FIRE's, which move with the forces' last bits: a
    // change to the force loop may need the case re-found (checked below).
    let dir = scratch();
    let yaml = "version: 1\nname: jam\ngrid:\n  packing.n: [32, 64]\n  packing.fraction: [0.845, 0.85, 0.855, 0.86, \
                0.87, 0.88, 0.9, 0.92, 0.94]\n  seed: [1, 2, 3]\nscenes:\n  - name: linear\n    kind: packing\n    \
                packing: {n: 64}\n    material: {law: linear}\n  - name: hertz\n    kind: packing\n    packing: {n: 64}\n    \
                material: {law: hertz}\n";
    let (frame, folder) = run_jam(dir.path(), yaml);
    let report = std::fs::read_to_string(folder.join("report.md")).unwrap();
    let line = line_with(&report, "Unstable to shear: ");
    assert!(line.contains("Here the share falls") && number_after(line, "against the highest: p = ") < 0.05, "{line}");
    // Each seed's share of G < 0 in the lowest range of Δφ N² and in the highest, from the table.
    let states = texts(&frame, "packing_state");
    let [phi, own, g, discs, seed] =
        ["packing_fraction", "own_jamming_fraction", "shear_modulus_2d", "discs", "seed"].map(|c| numbers(&frame, c));
    let with_g: Vec<usize> =
        (0..frame.height()).filter(|&i| states[i].as_deref() == Some("jammed") && g[i].is_some()).collect();
    let range = |i: usize| {
        let scaled = (phi[i].unwrap() - own[i].unwrap()).max(0.0) * discs[i].unwrap().powi(2);
        usize::from(scaled >= 1e2) + usize::from(scaled >= 1e3)
    };
    let (lowest, highest) =
        (with_g.iter().map(|&i| range(i)).min().unwrap(), with_g.iter().map(|&i| range(i)).max().unwrap());
    let share = |s: f64, k: usize| {
        let of: Vec<usize> = with_g.iter().copied().filter(|&i| seed[i] == Some(s) && range(i) == k).collect();
        (!of.is_empty()).then(|| of.iter().filter(|&&i| g[i].unwrap() < 0.0).count() as f64 / of.len() as f64)
    };
    let changes: Vec<f64> =
        [1.0, 2.0, 3.0].iter().filter_map(|&s| Some(share(s, highest)? - share(s, lowest)?)).collect();
    let falls = changes.iter().filter(|c| **c < 0.0).count();
    let rises = changes.iter().filter(|c| **c > 0.0).count();
    let counted = format!(
        "falls from the lowest range to the highest in {falls} of the {} seeds with packings in both, rises in {rises} \
         and stays in {}",
        changes.len(),
        changes.len() - falls - rises
    );
    assert!(line.contains(&counted), "{line}: {counted}");
    let p = sign_test(falls, rises);
    assert!((number_after(line, "the sign test gives p = ") / p - 1.0).abs() < 1e-3, "{line}: {p}");
    assert!(p >= 0.05 && line.contains("these seeds cannot tell a finite-size effect"), "{line}");
    assert!(!line.contains("a finite-size effect, of that kind"), "{line}");
    // Both laws pooled, and Δφ N² is p N² for the linear ones alone.
    assert!(line.contains("∝ p N² for linear contacts alone") && line.contains("linear and Hertz packings are pooled"));
}
