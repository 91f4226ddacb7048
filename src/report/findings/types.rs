//! Lattice types (`lattice.type`) side by side: each type's moduli against its static twin and
//! continuum with Maxwell's count, isotropy in x and y, rigidity percolation of diluted
//! networks, and the longitudinal and transverse waves of every type.

use std::collections::BTreeMap;

use super::discussion::Paragraph;
use super::finding::{Answer, Evidence, Table, Verdict, cell, extremes, noise, rel, relative, sig};
use crate::measure::lattice_constants;
use crate::model::LatticeType;
use crate::report::figure::FigureKind;
use crate::report::words;
use crate::runner::RunRecord;
use crate::sim::RunStatus;
use crate::spec::{Control, LatticeSpec, LoadCase, Supports};
use crate::study::lattice::LatticeMetrics;
use crate::theory::{background_decay_rate, critical_damping};

/// True for a lattice run of another type than square (a campaign that names types).
fn other_type(r: &RunRecord) -> bool {
    r.spec.lattice().is_some_and(|l| !l.lattice_type.is_square())
}

/// The type of a lattice run (square for other kinds: never asked).
fn kind(r: &RunRecord) -> LatticeType {
    r.spec.lattice().map(|l| l.lattice_type).unwrap_or_default()
}

/// Maxwell's count in words: z against 2d = 4.
fn maxwell(kind: LatticeType) -> &'static str {
    match kind.coordination().total_cmp(&4.0) {
        std::cmp::Ordering::Greater => "above twice the dimension, 4: rigid by counting",
        std::cmp::Ordering::Equal => "equal to twice the dimension, 4: isostatic, marginal",
        std::cmp::Ordering::Less => "below twice the dimension, 4: floppy by counting",
    }
}

/// What a periodic strip and a free block measure, and why the honeycomb has no E.
const STRIP_AND_BLOCK: &str = "A periodic strip cannot contract sideways, so in tension it measures the constrained \
     modulus λ + 2μ (exact for the triangular strip; the kagome's and honeycomb's approach it as O(1/N_y) of their top \
     and bottom rows); a free block measures E = 4μ(λ + μ)/(λ + 2μ)/d to O(1/N) of its edges. The honeycomb's μ = 0 \
     (its three bonds at 120° turn freely), so it has no E, only its bulk modulus λ = k/(2√3 d).";

/// Loaded lattices of every type (no random ones, no isotropy study): status and moduli
/// beside the static twin and the continuum, and what Maxwell's count predicts.
pub(super) fn moduli(e: &Evidence) -> Option<Answer> {
    let scenes: Vec<&str> = e.all(other_type).iter().map(|r| r.spec.scene.as_str()).collect();
    let runs = e.all(|r| {
        r.spec.lattice().is_some_and(|l| l.impulse.is_none() && !l.is_random() && !r.spec.static_only())
            && scenes.contains(&r.spec.scene.as_str())
    });
    if runs.is_empty() {
        return None;
    }
    let mut rows = Vec::new();
    let mut sentences = Vec::new();
    for kind in LatticeType::ALL {
        let mine: Vec<&RunRecord> = runs.iter().copied().filter(|r| self::kind(r) == kind).collect();
        if mine.is_empty() {
            continue;
        }
        let moduli = TypeModuli::of(kind, &mine)?;
        rows.extend(moduli.rows);
        sentences.push(moduli.sentence);
    }
    let departures: Vec<(&RunRecord, Departure)> = runs.iter().filter_map(|r| Some((*r, Departure::of(r)?))).collect();
    let (agreement, short) = agreement_sentences(&departures);
    sentences.extend(agreement);
    sentences.push(STRIP_AND_BLOCK.into());
    Some(Answer {
        title: "Lattice types: rigidity and moduli",
        question: "Which networks are rigid, and do their moduli follow the continuum of their bonds?",
        short,
        sentences,
        reference: "The static answer of the same network within 5e-3 (E and G relative, ν absolute) where MD \
                    counted its run relaxed; the continuum λ = μ = √3k/(4d) (triangular), √3k/(8d) (kagome), \
                    λ = k/(2√3 d), μ = 0 (honeycomb); Maxwell's count z against twice the dimension, 4."
            .into(),
        see_also: None,
        verdict: Verdict::of(departures.iter().map(|(_, d)| !d.parts())),
        figures: Vec::new(),
        table: Some(Table {
            header: [
                "type",
                "z",
                "load",
                "status",
                "MD (Pa)",
                "static (Pa)",
                "MD ν",
                "static ν",
                "continuum (Pa)",
                "static/continuum − 1",
            ]
            .map(String::from)
            .to_vec(),
            rows,
        }),
    })
}

/// MD and its static answer may differ by this much (E and G relative, ν absolute) in a run
/// MD counted relaxed: the square lattice's bound.
const MD_STATIC_TOLERANCE: f64 = 5e-3;

/// How far a loaded run's MD lies from the static answer of the same network: |E − E_fem|/E_fem
/// or |G − G_fem|/G_fem, and |ν − ν_fem| (absolute: ν is 0 on a periodic strip). Both are
/// needed: the error bound MD stops by covers the extension along the load, which sets E, not
/// the sideways contraction that sets ν, so a soft sideways mode can leave ν alone far off.
struct Departure {
    modulus: Option<f64>,
    poisson: Option<f64>,
}

impl Departure {
    /// `None` where MD measured nothing (a mechanism, a run that never relaxed).
    fn of(r: &RunRecord) -> Option<Departure> {
        let m = &r.metrics.lattice;
        let modulus = relative(m.youngs_modulus, m.youngs_modulus_fem)
            .or_else(|| relative(m.shear_modulus, m.shear_modulus_fem))
            .map(f64::abs);
        let poisson = m.poisson_ratio.zip(m.poisson_ratio_fem).map(|(a, b)| (a - b).abs());
        (modulus.is_some() || poisson.is_some()).then_some(Departure { modulus, poisson })
    }

    fn parts(&self) -> bool {
        [self.modulus, self.poisson].iter().flatten().any(|x| *x > MD_STATIC_TOLERANCE)
    }
}

/// The largest of `values`, 0 when there are none.
fn worst(values: impl Iterator<Item = Option<f64>>) -> f64 {
    values.flatten().fold(0.0, f64::max)
}

/// How MD and the static answer agree over the runs MD counted relaxed, and a sentence on
/// each run where they part; with the summary's short answer.
fn agreement_sentences(departures: &[(&RunRecord, Departure)]) -> (Vec<String>, String) {
    let (parted, agreed): (Vec<_>, Vec<_>) = departures.iter().partition(|(_, d)| d.parts());
    let (modulus, poisson) =
        (worst(agreed.iter().map(|(_, d)| d.modulus)), worst(agreed.iter().map(|(_, d)| d.poisson)));
    let within = format!("{} in E and G (relative) and {} in ν (absolute)", sig(modulus), sig(poisson));
    if parted.is_empty() {
        let sentence = format!(
            "Where a network carried its load and MD counted it relaxed, MD and the static answer of the same \
             network agree to {within} at worst."
        );
        return (vec![sentence], format!("MD against static within {}", sig(modulus.max(poisson))));
    }
    let mut sentences = vec![format!(
        "MD and the static answer of the same network part beyond {MD_STATIC_TOLERANCE:e} in {} of the {} runs \
         MD counted relaxed{}.",
        parted.len(),
        departures.len(),
        if agreed.is_empty() {
            String::new()
        } else {
            format!("; the other {} agree to {within} at worst", agreed.len())
        }
    )];
    sentences.extend(parted.iter().map(|(r, d)| parting_sentence(r, d)));
    let short = format!("MD and static part in {} of {} runs", parted.len(), departures.len());
    (sentences, short)
}

/// A loaded run in words: "kagome, tensile-x on coursework".
/// A loaded run in words, with what else sets it apart in its grid: "kagome, tensile-x on
/// coursework, γ_g = 200 N s/m".
fn set_up(r: &RunRecord) -> String {
    let Some(l) = r.spec.lattice() else { return String::new() };
    let said = format!("{}, {} on {}", l.lattice_type.name(), l.load_name(), l.supports.name());
    match varied_beside(r, MODULI_COLUMNS) {
        beside if beside.is_empty() => said,
        beside => format!("{said}, {beside}"),
    }
}

/// The grid paths the moduli table has columns for (type, load, supports).
const MODULI_COLUMNS: &[&str] = &["lattice.type", "load.case", "supports"];

/// A run's grid values other than the paths `shown` (said in columns of their own), in words:
/// what sets apart rows that would otherwise read alike.
fn varied_beside(r: &RunRecord, shown: &[&str]) -> String {
    r.spec.varied_in_words(|path| !shown.contains(&path))
}

/// Where one run's MD parts from its static answer, and when MD stopped against how slowly its
/// softest mode settles.
fn parting_sentence(r: &RunRecord, d: &Departure) -> String {
    let (parted, within) = quantities(r, d);
    let said: Vec<String> = parted.into_iter().chain(within).collect();
    format!("{}: {}; {}.", words::capitalised(&set_up(r)), said.join(", "), stopping_words(r))
}

/// A run's measured quantities in words: those where MD parts from the static answer
/// ("ν = 0.1798 by MD against 0.3333 static") and those where it does not ("E within 1.3e-4").
fn quantities(r: &RunRecord, d: &Departure) -> (Vec<String>, Vec<String>) {
    let m = &r.metrics.lattice;
    let modulus = match m.youngs_modulus {
        Some(_) => ("E", " Pa", m.youngs_modulus, m.youngs_modulus_fem, d.modulus),
        None => ("G", " Pa", m.shear_modulus, m.shear_modulus_fem, d.modulus),
    };
    let poisson = ("ν", "", m.poisson_ratio, m.poisson_ratio_fem, d.poisson);
    let (mut parted, mut within) = (Vec::new(), Vec::new());
    for (name, unit, md, fem, off) in [poisson, modulus] {
        match off {
            Some(off) if off > MD_STATIC_TOLERANCE => {
                parted.push(format!("{name} = {}{unit} by MD against {}{unit} static", cell(md), cell(fem)))
            }
            Some(off) => within.push(format!("{name} within {}", sig(off))),
            None => {}
        }
    }
    (parted, within)
}

/// When MD counted a run relaxed and stopped, and the time constant of its softest mode under
/// the background damping alone (m ẍ = −k_min x − γ_g ẋ: the bond dashpots barely stretch in
/// a soft mode): where that time is longer than the run, MD stopped before its rest.
fn stopping_words(r: &RunRecord) -> String {
    let stopped = r.steps as f64 * r.spec.dt;
    let counted = format!(
        "MD counted it relaxed ({}) from {} s and stopped at {} s",
        r.metrics.dissipation_criterion.as_deref().unwrap_or("its criterion"),
        cell(r.metrics.dissipation_time),
        sig(stopped)
    );
    let (m, gamma) = (r.spec.mass, r.spec.gamma_background);
    let Some(k_min) = r.metrics.lattice.stiffness_min.filter(|k| *k > 0.0 && gamma > 0.0) else { return counted };
    // The amplitude falls at half the kinetic energy's rate.
    let settles = 2.0 / background_decay_rate(gamma, m, k_min);
    let mode = format!(
        "its softest mode (k_min = {} N/m, γ_g = {} N s/m = {} × its critical 2√(k_min m)) settles with a time \
         constant of {} s",
        sig(k_min),
        sig(gamma),
        sig(gamma / critical_damping(k_min, m)),
        sig(settles)
    );
    if settles > stopped {
        format!("{counted}, but {mode}: MD stopped on its way to rest, and the static answer is that rest")
    } else {
        format!("{counted}; {mode}")
    }
}

/// One lattice type's loaded runs in [`moduli`]: its table rows and its sentence on what it
/// carried.
struct TypeModuli {
    rows: Vec<Vec<String>>,
    sentence: String,
}

impl TypeModuli {
    fn of(kind: LatticeType, mine: &[&RunRecord]) -> Option<TypeModuli> {
        let mut rows = Vec::new();
        let mut carried = Vec::new();
        let mut mechanisms = Vec::new();
        for r in mine {
            let l = r.spec.lattice()?;
            let m = &r.metrics.lattice;
            // A velocity drive (the top row held where it stops) can meet stiffness that the same
            // load under force control does not (a kagome block pulled), so it is named apart.
            let driven = if l.control == Control::Velocity { " driven" } else { "" };
            let what = format!("{}{driven} on {}", l.load_name(), l.supports.name());
            // Each set-up once, however many runs (methods, seeds) it had.
            let said = if r.status == RunStatus::Mechanism { &mut mechanisms } else { &mut carried };
            if !said.contains(&what) {
                said.push(what.clone());
            }
            let (md, fem, theory) = match l.load_case {
                LoadCase::Shear => (m.shear_modulus, m.shear_modulus_fem, m.shear_modulus_theory),
                _ => (m.youngs_modulus, m.youngs_modulus_fem, m.youngs_modulus_theory),
            };
            let beside = varied_beside(r, MODULI_COLUMNS);
            rows.push(vec![
                if beside.is_empty() { kind.name().into() } else { format!("{}, {beside}", kind.name()) },
                format!("{}", kind.coordination()),
                what,
                r.status.as_str().into(),
                cell(md),
                cell(fem),
                noise(m.poisson_ratio, 1.0),
                noise(m.poisson_ratio_fem, 1.0),
                cell(theory),
                words::error(relative(fem, theory)),
            ]);
        }
        let sentence = format!(
            "{}: z = {}, {}. It carried {}; {}.",
            kind.name(),
            kind.coordination(),
            maxwell(kind),
            if carried.is_empty() { "no load".to_string() } else { carried.join(", ") },
            if mechanisms.is_empty() {
                "it was never a mechanism".to_string()
            } else {
                format!(
                    "the static solver's rigidity test found a mechanism (before MD) under {}",
                    mechanisms.join(", ")
                )
            }
        );
        Some(TypeModuli { rows, sentence })
    }
}

/// The isotropy study: the static E and ν of blocks pulled along y and along x, by size and
/// supports, against the continuum (a free block, on coursework supports); the square lattice's
/// in-plane anisotropy from its constants.
pub(super) fn isotropy(e: &Evidence) -> Option<Answer> {
    let runs = e.all(|r| r.spec.lattice().is_some_and(|l| l.rotated && l.supports == Supports::Coursework));
    let scene = runs.iter().find(|r| other_type(r))?.spec.scene.clone();
    let runs =
        e.all(|r| r.spec.scene == scene && r.spec.lattice().is_some_and(|l| !l.is_random() && l.impulse.is_none()));
    let by_size = isotropy_by_size(&runs)?;
    let first = runs.first()?;
    let (k, depth) = (first.spec.k, first.spec.lattice()?.depth);
    let triangular_e = 2.0 * k / (3.0_f64.sqrt() * depth);
    let mut rows = Vec::new();
    // Per type, its largest block on coursework supports (free to contract sideways) pulled both
    // ways: the continuum's.
    let mut last_ratio = BTreeMap::new();
    // The triangular block's E_x/E_y on coursework supports at every size, N rising.
    let mut triangular_sizes = Vec::new();
    for ((name, n, supports, network), v) in &by_size {
        let ratio = v[2].zip(v[0]).map(|(x, y)| x / y);
        if let Some(ratio) = ratio.filter(|_| *supports == Supports::Coursework.name()) {
            last_ratio.insert(*name, (*n, ratio, v));
            if *name == "triangular" {
                triangular_sizes.push((*n, ratio));
            }
        }
        rows.push(vec![
            if network.is_empty() { name.to_string() } else { format!("{name}, {network}") },
            n.to_string(),
            supports.to_string(),
            cell(v[0]),
            cell(v[2]),
            ratio.map(|x| format!("{x:.4}")).unwrap_or_else(|| "–".into()),
            cell(v[1]),
            cell(v[3]),
        ]);
    }
    let triangular =
        last_ratio.get("triangular").map(|&(_, _, v)| triangular_isotropy(&triangular_sizes, v, triangular_e));
    let checks: Vec<bool> = triangular.iter().map(|(_, isotropic)| *isotropic).collect();
    let mut sentences: Vec<String> = triangular.into_iter().map(|(sentence, _)| sentence).collect();
    sentences.extend(square_isotropy_sentence(&runs, last_ratio.get("square").map(|&(n, r, _)| (n, r))));
    sentences.extend(isotropy_md_sentence(&runs));
    Some(Answer {
        title: "Lattice types: isotropy",
        question: "Do E and ν measured along x and along y agree (triangular), and how does the square lattice differ?",
        short: last_ratio.get("triangular").map_or("–".into(), |&(n, r, _)| {
            format!("triangular E_x/E_y = {} at N = {n} (coursework supports)", sig(r))
        }),
        sentences,
        reference: "Isotropy: E_x/E_y = 1 within 5 % at the largest block on coursework supports (free to \
                    contract sideways; edges O(1/N)); E = 2k/(√3 d), ν = 1/3."
            .into(),
        see_also: None,
        verdict: if checks.is_empty() { Verdict::Observed } else { Verdict::of(checks) },
        figures: Vec::new(),
        table: Some(Table { header: ISOTROPY_HEADER.map(String::from).to_vec(), rows }),
    })
}

/// The isotropy table's columns: every modulus in it is the static answer's (the block at rest),
/// which MD of the same block need not have reached.
const ISOTROPY_HEADER: [&str; 8] =
    ["type", "N", "supports", "static E_y (Pa)", "static E_x (Pa)", "E_x/E_y", "static ν_yx", "static ν_xy"];

/// The largest triangular block's E_x/E_y on coursework supports (`v`: E_y, ν_yx, E_x, ν_xy of
/// the static answer; `sizes`: (N, E_x/E_y) by rising N, the largest last) against the continuum
/// E = 2k/(√3 d) (`continuum`, Pa), and whether it is isotropic within 5 %.
fn triangular_isotropy(sizes: &[(usize, f64)], v: &[Option<f64>; 4], continuum: f64) -> (String, bool) {
    let (ey, ex) = (v[0].unwrap_or(f64::NAN), v[2].unwrap_or(f64::NAN));
    let &(n, ratio) = sizes.last().unwrap_or(&(0, f64::NAN));
    let isotropic = (ratio - 1.0).abs() < 0.05;
    let sentence = format!(
        "The triangular block on coursework supports (free to contract sideways) {} isotropic within 5 %: at N = \
         {n} the static answer's E_x/E_y = {}, against the continuum E = 2k/(√3 d) = {} Pa ({} along y, {} along \
         x) with ν = 1/3 ({}, {}); {}.",
        if isotropic { "is" } else { "is not" },
        sig(ratio),
        sig(continuum),
        rel(ey / continuum - 1.0),
        rel(ex / continuum - 1.0),
        cell(v[1]),
        cell(v[3]),
        size_trend(sizes),
    );
    (sentence, isotropic)
}

/// How the triangular block's E_x/E_y − 1 goes with N (`sizes` by rising N): only sizes that
/// ran can say it falls, as an edge effect's O(1/N) would.
fn size_trend(sizes: &[(usize, f64)]) -> String {
    const EDGES: &str = "the zigzag sides stiffen a pull along x more than the straight rows one along y";
    let [_, _, ..] = sizes else {
        let n = sizes.first().map_or(0, |s| s.0);
        return format!(
            "an edge effect would be O(1/N) ({EDGES}), but only N = {n} ran, so how the difference goes with N is \
             not measured here"
        );
    };
    let listed: Vec<String> = sizes.iter().map(|(n, r)| format!("{} at N = {n}", sig(r - 1.0))).collect();
    let falls = sizes.windows(2).all(|w| (w[1].1 - 1.0).abs() < (w[0].1 - 1.0).abs());
    if falls {
        format!(
            "the difference falls as N grows, as the edges' O(1/N) does ({EDGES}): E_x/E_y − 1 = {}",
            words::listed(&listed, "and")
        )
    } else {
        format!("the difference does not fall steadily with N: E_x/E_y − 1 = {}", words::listed(&listed, "and"))
    }
}

/// Where MD ran on the isotropy study's blocks: the table is the static answer, and which of
/// those blocks' MD parts from it.
fn isotropy_md_sentence(runs: &[&RunRecord]) -> Option<String> {
    let md: Vec<(&RunRecord, Departure)> = runs.iter().filter_map(|r| Some((*r, Departure::of(r)?))).collect();
    if md.is_empty() {
        return None;
    }
    let parted: Vec<String> = md
        .iter()
        .filter(|(_, d)| d.parts())
        .map(|(r, d)| format!("{} ({})", set_up(r), quantities(r, d).0.join(", ")))
        .collect();
    Some(if parted.is_empty() {
        format!(
            "The table is the static answer of each block; MD of the same blocks agrees with it within \
             {MD_STATIC_TOLERANCE:e} (the item on rigidity and moduli)."
        )
    } else {
        format!(
            "The table is the static answer of each block, the block at rest; MD of the same blocks parts from it \
             on {}: the item on rigidity and moduli says why.",
            words::listed(&parted, "and")
        )
    })
}

/// (type, N, supports, the network's other grid values in words) → (E_y, ν_yx, E_x, ν_xy) from
/// the static answer.
type IsotropyBySize = BTreeMap<(&'static str, usize, &'static str, String), [Option<f64>; 4]>;

/// Per type, N, supports and network: E_y, ν_yx of the static answer of the block pulled along y
/// (`tensile`) and E_x, ν_xy of it pulled along x (`tensile-x`, turned). Only those two runs
/// measure them: a shear run, or a second run of the same block, erases nothing.
fn isotropy_by_size(runs: &[&RunRecord]) -> Option<IsotropyBySize> {
    let mut by_size = IsotropyBySize::new();
    for r in runs {
        let l = r.spec.lattice()?;
        if l.load_case != LoadCase::Tensile {
            continue;
        }
        let m = &r.metrics.lattice;
        let key = (
            l.lattice_type.name(),
            l.upright().nx,
            l.supports.name(),
            varied_beside(r, &["load.case", "lattice.type", "lattice.size", "lattice.nx", "supports"]),
        );
        let entry = by_size.entry(key).or_default();
        let at = if l.rotated { 2 } else { 0 };
        entry[at] = entry[at].or(m.youngs_modulus_fem);
        entry[at + 1] = entry[at + 1].or(m.poisson_ratio_fem);
    }
    Some(by_size)
}

/// The square lattice's isotropy along its axes (`largest`: its largest N with E_x/E_y there)
/// against its anisotropy between them.
fn square_isotropy_sentence(runs: &[&RunRecord], largest: Option<(usize, f64)>) -> Option<String> {
    let square = runs.iter().find(|r| kind(r).is_square()).and_then(|r| r.spec.lattice())?;
    Some(format!(
        "The square lattice's E_x and E_y are equal by its four-fold symmetry (E_x/E_y = {} at N = {}); its \
         anisotropy lies between the axes: with k_d/k = {} its Zener ratio 2C66/(C11 − C12) = 2k_d/k = {} and \
         E(45°)/E(0°) = {} from its compliance, isotropic only at k_d = k/2 (measured at three k_d/k in the \
         item on direction).",
        largest.map_or("–".into(), |(_, r)| sig(r)),
        largest.map_or(0, |(n, _)| n),
        sig(square.k_diag / square.k_x),
        sig(2.0 * square.k_diag / square.k_x),
        cell(square_diagonal_stiffening(square)),
    ))
}

/// E(45°)/E(0°) of a solid with the square symmetry of its elastic constants, from E, ν and G
/// along its axes: 1/E(θ) = S11(c⁴ + s⁴) + (2 S12 + S66) c² s² with S11 = 1/E, S12 = −ν/E,
/// S66 = 1/G, so at θ = 45° E(45°)/E = 1/((1 − ν)/2 + E/(4G)). 1 for an isotropic solid
/// (G = E/(2(1 + ν))).
fn diagonal_stiffening(youngs: f64, poisson: f64, shear: f64) -> f64 {
    1.0 / ((1.0 - poisson) / 2.0 + youngs / (4.0 * shear))
}

/// [`diagonal_stiffening`] of a square lattice's continuum: C per unit depth C11 = k + k_d,
/// C12 = C66 = k_d (both diagonals), so E = C11 − C12²/C11, ν = C12/C11, G = C66 (all per unit
/// depth: the depth cancels); `None` for another type.
pub(super) fn square_diagonal_stiffening(l: &LatticeSpec) -> Option<f64> {
    if !l.lattice_type.is_square() {
        return None;
    }
    let (kr, kf) = l.diagonal_stiffness();
    let c = lattice_constants(l.k_x, l.k_y, kr, kf);
    Some(diagonal_stiffening(c.c11 - c.c12 * c.c12 / c.c11, c.c12 / c.c11, c.c66))
}

/// The measured direction dependence: E(0°) and ν of a free block pulled along y and G of a
/// periodic strip in shear (its exact C66/d), all from the static answer of the same network,
/// give E(45°) by the square symmetry of the elastic constants ([`diagonal_stiffening`]); the
/// triangular network (isotropic: E(45°) = E) beside square ones at several k_d/k.
pub(super) fn directions(e: &Evidence) -> Option<Answer> {
    let networks = direction_networks(e)?;
    let Directions { rows, checks, square, triangular } = direction_numbers(&networks);
    if rows.is_empty() {
        return None;
    }
    Some(Answer {
        title: "Lattice types: direction",
        question: "How does the stiffness depend on direction: the triangular network beside the square one?",
        short: match square.iter().map(|(_, said)| said.as_str()).next_back() {
            Some(last) => format!("square E(45°)/E(0°) up to {last}; triangular isotropic"),
            None => "triangular isotropic".into(),
        },
        sentences: direction_sentences(&square, triangular),
        reference: format!(
            "The continuum's E(45°)/E(0°) from the lattice constants (1 for the triangular network), within {:.0} % \
             (the free block's E and ν carry its edges' O(1/N), about 2 % at N = 33).",
            DIRECTION_TOLERANCE * 100.0
        ),
        see_also: None,
        verdict: Verdict::of(checks),
        figures: Vec::new(),
        table: Some(Table {
            header: ["type", "k_d/k", "N", "E(0°) (Pa)", "ν", "G (Pa)", "E(45°)/E(0°)", "continuum"]
                .map(String::from)
                .to_vec(),
            rows,
        }),
    })
}

/// The networks of the direction study, each with E and ν of its free block pulled along y
/// and G of its periodic strip in shear, all from the static answer.
fn direction_networks<'a>(e: &Evidence<'a>) -> Option<Vec<Network<'a>>> {
    let fixed = |r: &RunRecord| {
        r.spec.static_only() && r.spec.lattice().is_some_and(|l| !l.is_random() && !l.rotated && l.impulse.is_none())
    };
    let mut networks: Vec<Network> = Vec::new();
    for r in e.ok(fixed) {
        let l = r.spec.lattice()?;
        let key = (r.spec.scene.clone(), l.lattice_type, l.k_diag / l.k_x, l.nx);
        let at = match networks.iter().position(|n| n.key == key) {
            Some(at) => at,
            None => {
                networks.push(Network { key, lattice: l, youngs: None, poisson: None, shear: None });
                networks.len() - 1
            }
        };
        let m = &r.metrics.lattice;
        let network = &mut networks[at];
        match (l.supports, l.load_case) {
            (Supports::Coursework, LoadCase::Tensile) => {
                (network.youngs, network.poisson) = (m.youngs_modulus_fem, m.poisson_ratio_fem)
            }
            (Supports::PeriodicX, LoadCase::Shear) => network.shear = m.shear_modulus_fem,
            _ => {}
        }
    }
    Some(networks)
}

/// The direction study's numbers: a table row and a check per complete network, the square
/// lattices' E(45°)/E(0°) in words by k_d/k, and the triangular network's.
struct Directions {
    rows: Vec<Vec<String>>,
    checks: Vec<bool>,
    square: Vec<(f64, String)>,
    triangular: Option<(LatticeType, usize, String)>,
}

/// E(45°)/E(0°) of every network with all three moduli, against its continuum value.
fn direction_numbers(networks: &[Network]) -> Directions {
    let mut found = Directions { rows: Vec::new(), checks: Vec::new(), square: Vec::new(), triangular: None };
    for Network { key: (_, kind, ratio, n), lattice, youngs, poisson, shear } in networks {
        let (Some(youngs), Some(poisson), Some(shear)) = (*youngs, *poisson, *shear) else { continue };
        let stiffening = diagonal_stiffening(youngs, poisson, shear);
        let continuum = if kind.is_square() { square_diagonal_stiffening(lattice) } else { Some(1.0) };
        if let Some(continuum) = continuum {
            found.checks.push((stiffening / continuum - 1.0).abs() <= DIRECTION_TOLERANCE);
        }
        let said = format!("{} (continuum {})", sig(stiffening), cell(continuum));
        if kind.is_square() {
            found.square.push((*ratio, said));
        } else {
            found.triangular = Some((*kind, *n, said));
        }
        found.rows.push(vec![
            kind.name().into(),
            if kind.is_square() { sig(*ratio) } else { "–".into() },
            n.to_string(),
            sig(youngs),
            sig(poisson),
            sig(shear),
            sig(stiffening),
            cell(continuum),
        ]);
    }
    found
}

/// How E(45°) is found, and what the triangular and square networks show.
fn direction_sentences(square: &[(f64, String)], triangular: Option<(LatticeType, usize, String)>) -> Vec<String> {
    let mut sentences = vec![
        "E(45°) follows from three measured moduli of the same network by the square symmetry of its elastic \
         constants, 1/E(45°) = (1 − ν)/(2E) + 1/(4G): E and ν of the free block pulled along y, G of the \
         periodic strip in shear (exactly C66/d, no edges); all from the static answer."
            .to_string(),
    ];
    if let Some((kind, n, said)) = triangular {
        sentences.push(format!(
            "The {} network ({n} × {n}): E(45°)/E(0°) = {said}: isotropic, as its six-fold symmetry requires.",
            kind.name()
        ));
    }
    if !square.is_empty() {
        let listed: Vec<String> =
            square.iter().map(|(ratio, said)| format!("{said} at k_d/k = {}", sig(*ratio))).collect();
        sentences.push(format!(
            "The square lattice depends on direction: E(45°)/E(0°) = {}. Above k_d = k/2 it is stiffer along its \
             diagonals than along its rows, below it softer, and only at k_d = k/2 (Zener ratio 2k_d/k = 1) \
             isotropic.",
            listed.join(", ")
        ));
    }
    sentences
}

/// One network of the direction study, (scene, type, k_d/k, N), with E and ν of its free block
/// and G of its periodic strip.
struct Network<'a> {
    key: (String, LatticeType, f64, usize),
    lattice: &'a LatticeSpec,
    youngs: Option<f64>,
    poisson: Option<f64>,
    shear: Option<f64>,
}

/// The measured E(45°)/E(0°) must lie within this fraction of the continuum's.
const DIRECTION_TOLERANCE: f64 = 0.05;

/// One diluted network: its cut fraction, whether it carried the load, its linear static E (Pa).
type Diluted = (f64, bool, Option<f64>);

/// The mean of the seeds' thresholds `p`, their standard deviation and the mean's standard
/// error.
fn over_seeds(p: &[f64]) -> (f64, f64, f64) {
    let mean = p.iter().sum::<f64>() / p.len() as f64;
    let sd = (p.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (p.len().max(2) - 1) as f64).sqrt();
    (mean, sd, sd / (p.len() as f64).sqrt())
}

/// The rigidity threshold of diluted networks of each type and size: per seed, between the
/// largest cut fraction still rigid and the smallest that is a mechanism (the cut sets of one
/// seed are nested: a bond is cut when its own uniform number is below the fraction).
pub(super) fn percolation(e: &Evidence) -> Option<Answer> {
    let runs = percolation_runs(e);
    if !runs.iter().any(|r| other_type(r) && r.spec.lattice().is_some_and(|l| l.cut_fraction > 0.0)) {
        return None;
    }
    let mut diluted_scenes: Vec<&str> = runs
        .iter()
        .filter(|r| r.spec.lattice().is_some_and(|l| l.cut_fraction > 0.0))
        .map(|r| r.spec.scene.as_str())
        .collect();
    diluted_scenes.dedup();
    let (thresholds, brackets, stiffness) = dilution(&runs)?;
    if thresholds.is_empty() {
        return Some(no_threshold(e, &runs, &diluted_scenes));
    }
    let (rows, mut sentences) = threshold_rows(&thresholds);
    sentences.extend(largest_triangular_sentence(&thresholds, &brackets));
    sentences.extend(unstable_sentence(&runs));
    sentences.extend(effective_medium_sentence(&stiffness));
    sentences.push(THRESHOLD_METHOD.into());
    Some(Answer {
        title: "Lattice types: rigidity percolation",
        question: "Where does a randomly diluted network lose its rigidity, against effective-medium theory?",
        short: thresholds
            .iter()
            .map(|(network, p)| {
                format!("{}: p_c = {:.3}", network.words(&thresholds), p.iter().sum::<f64>() / p.len() as f64)
            })
            .collect::<Vec<_>>()
            .join(", "),
        sentences,
        reference: "Effective-medium theory: p_c = 2d/z (2/3 triangular, 1/2 square with both diagonals); \
                    Jacobs and Thorpe (1995): 0.660 for the triangular network; an observation."
            .into(),
        see_also: None,
        verdict: Verdict::Observed,
        figures: diluted_scenes.iter().filter_map(|scene| e.figure(scene, FigureKind::Dilution)).collect(),
        table: Some(Table {
            header: ["type", "N", "seeds", "p_c (± s.e.)", "spread", "EMT", "literature"].map(String::from).to_vec(),
            rows,
        }),
    })
}

/// The item when no seed's threshold could be located: what a threshold needs, and what the
/// diluted runs were.
fn no_threshold(e: &Evidence, runs: &[&RunRecord], scenes: &[&str]) -> Answer {
    let diluted: Vec<&&RunRecord> =
        runs.iter().filter(|r| r.spec.lattice().is_some_and(|l| l.cut_fraction > 0.0)).collect();
    let floppy = diluted.iter().filter(|r| r.status == RunStatus::Mechanism).count();
    Answer {
        title: "Lattice types: rigidity percolation",
        question: "Where does a randomly diluted network lose its rigidity, against effective-medium theory?",
        short: "no threshold located".into(),
        sentences: vec![format!(
            "No threshold is located: a seed's lies between its largest cut fraction still rigid and its smallest \
             that is a mechanism, which takes at least three cut fractions of one network and seed with both \
             kinds among them. Here {} diluted runs, {floppy} of them a mechanism.",
            diluted.len()
        )],
        reference: "Effective-medium theory: p_c = 2d/z; an observation.".into(),
        see_also: None,
        verdict: Verdict::Observed,
        figures: scenes.iter().filter_map(|scene| e.figure(scene, FigureKind::Dilution)).collect(),
        table: None,
    }
}

/// The tensile runs of the dilution study that say whether their network is rigid.
fn percolation_runs<'a>(e: &Evidence<'a>) -> Vec<&'a RunRecord> {
    e.all(|r| {
        r.spec.lattice().is_some_and(|l| l.stiffness_spread == 0.0 && l.load_case == LoadCase::Tensile)
            && (matches!(r.status, RunStatus::Mechanism | RunStatus::Ok | RunStatus::NoEquilibrium)
                // Rigid by the linear test, but so close to a mechanism that the linear answer's
                // displacements leave small strains behind (relax.method: static sets them).
                || r.status == RunStatus::Unstable && r.metrics.lattice.youngs_modulus_linear.is_some())
    })
}

/// A diluted network up to its seed and cut fraction: what its threshold depends on. Its
/// coordination z (in thousandths) sets effective-medium theory's p_c = 2d/z.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct DilutedNetwork<'a> {
    name: &'a str,
    n: usize,
    ny: usize,
    diagonals: &'static str,
    supports: &'static str,
    z_thousandths: u64,
}

impl DilutedNetwork<'_> {
    /// Effective-medium theory's threshold p_c = 2d/z, d = 2.
    fn effective_medium(&self) -> f64 {
        4000.0 / self.z_thousandths as f64
    }

    /// Its type, with its height, diagonals and supports where another network of that type
    /// and N in `thresholds` differs in them.
    fn type_words(&self, thresholds: &Thresholds) -> String {
        match thresholds.keys().filter(|k| k.name == self.name && k.n == self.n).count() {
            1 => self.name.to_string(),
            _ => format!("{} ({} rows, diagonals {}, {} supports)", self.name, self.ny, self.diagonals, self.supports),
        }
    }

    /// The network in words: [`DilutedNetwork::type_words`] and N.
    fn words(&self, thresholds: &Thresholds) -> String {
        format!("{} N = {}", self.type_words(thresholds), self.n)
    }
}

/// Per network, the rigidity thresholds p_c of its seeds.
type Thresholds<'a> = BTreeMap<DilutedNetwork<'a>, Vec<f64>>;

/// Per network, the widest gap between a seed's last rigid and first floppy cut fraction: how
/// finely the campaign's grid locates each threshold.
type Brackets<'a> = BTreeMap<DilutedNetwork<'a>, f64>;

/// Per (type, cut fraction in thousandths), the seeds' E/E(p = 1), mechanisms counted as 0.
type StiffnessByCut<'a> = BTreeMap<(&'a str, u64), Vec<f64>>;

/// One diluted network family: the network, the seed and the bits of k_x, k_y and k_d. Runs of
/// one family differ only in their cut fraction and in what does not change the network (load,
/// control, relaxation), so each cut fraction is one network.
type Family<'a> = (DilutedNetwork<'a>, u64, [u64; 3]);

/// The diluted networks of each family, one point per cut fraction in increasing order: a cut
/// that several runs share (two controls, two relaxation methods of one network) counts once,
/// rigid only if every run of it is, so a seed is not counted twice.
fn families<'a>(runs: &[&'a RunRecord]) -> Option<BTreeMap<Family<'a>, Vec<Diluted>>> {
    let mut series: BTreeMap<Family, Vec<Diluted>> = BTreeMap::new();
    for r in runs {
        let l = r.spec.lattice()?;
        if l.rotated || l.impulse.is_some() {
            continue;
        }
        let network = DilutedNetwork {
            name: l.lattice_type.name(),
            n: l.nx,
            ny: l.ny,
            diagonals: l.diagonals.name(),
            supports: l.supports.name(),
            z_thousandths: (1000.0 * l.coordination()).round() as u64,
        };
        let points = series.entry((network, l.seed, [l.k_x, l.k_y, l.k_diag].map(f64::to_bits))).or_default();
        let rigid = r.status != RunStatus::Mechanism;
        match points.iter_mut().find(|p| p.0 == l.cut_fraction) {
            Some(point) => point.1 &= rigid,
            None => points.push((l.cut_fraction, rigid, r.metrics.lattice.youngs_modulus_linear)),
        }
    }
    series.retain(|_, points| points.len() > 2 && points.iter().any(|p| p.0 > 0.0));
    series.values_mut().for_each(|points| points.sort_by(|a, b| a.0.total_cmp(&b.0)));
    Some(series)
}

/// The thresholds per network, how finely the grid brackets them, and the stiffness by cut.
type Dilution<'a> = (Thresholds<'a>, Brackets<'a>, StiffnessByCut<'a>);

/// The thresholds (per seed midway between the largest cut still rigid and the smallest that
/// is a mechanism: the cut sets of a seed are nested) and the stiffness by cut. Families that
/// differ only in their stiffness constants share a seed's threshold, which is counted once.
fn dilution<'a>(runs: &[&'a RunRecord]) -> Option<Dilution<'a>> {
    let mut per_seed: BTreeMap<(DilutedNetwork, u64), (f64, f64)> = BTreeMap::new();
    let mut stiffness = StiffnessByCut::new();
    for (&(network, seed, _), points) in &families(runs)? {
        let full = points.iter().find(|p| p.0 == 0.0).and_then(|p| p.2);
        let last_rigid = points.iter().filter(|p| p.1).map(|p| p.0).fold(f64::NEG_INFINITY, f64::max);
        let first_floppy = points.iter().filter(|p| !p.1).map(|p| p.0).fold(f64::INFINITY, f64::min);
        if last_rigid.is_finite() && first_floppy.is_finite() {
            let threshold = (1.0 - 0.5 * (last_rigid + first_floppy), first_floppy - last_rigid);
            per_seed.insert((network, seed), threshold);
        }
        if let Some(full) = full {
            for p in points.iter().filter(|p| p.0 > 0.0) {
                let ratio = if p.1 { p.2.map_or(0.0, |e| e / full) } else { 0.0 };
                stiffness.entry((network.name, (p.0 * 1000.0).round() as u64)).or_default().push(ratio);
            }
        }
    }
    let (mut thresholds, mut brackets) = (Thresholds::new(), Brackets::new());
    for ((network, _), (p_c, bracket)) in per_seed {
        thresholds.entry(network).or_default().push(p_c);
        let widest = brackets.entry(network).or_insert(bracket);
        *widest = widest.max(bracket);
    }
    Some((thresholds, brackets, stiffness))
}

/// A table row and a sentence per network: the seeds' mean threshold against theory.
fn threshold_rows(thresholds: &Thresholds) -> (Vec<Vec<String>>, Vec<String>) {
    let mut rows = Vec::new();
    let mut sentences = Vec::new();
    for (network, p) in thresholds {
        let (mean, sd, error) = over_seeds(p);
        let emt = network.effective_medium();
        let literature = (network.name == "triangular").then_some(0.660);
        let words = network.words(thresholds);
        // One seed has no scatter to give an error: its threshold alone.
        let (value, spread, over) = match p.len() {
            1 => (format!("{mean:.3}"), "–".to_string(), format!("{mean:.3} (one seed: no standard error)")),
            n => (
                format!("{mean:.3} ± {error:.3}"),
                format!("{sd:.3}"),
                format!("{mean:.3} ± {error:.3} over {n} seeds (standard error; seed-to-seed spread {sd:.3})"),
            ),
        };
        rows.push(vec![
            network.type_words(thresholds),
            network.n.to_string(),
            p.len().to_string(),
            value,
            spread,
            format!("{emt:.3}"),
            literature.map_or("–".into(), |x| format!("{x:.3}")),
        ]);
        sentences.push(format!(
            "{words}: the rigidity threshold is p_c = {over}, against effective-medium theory's {emt:.3}{}.",
            literature
                .map_or(String::new(), |x| format!(" and Jacobs and Thorpe's {x:.3} (central forces, large networks)"))
        ));
    }
    (rows, sentences)
}

/// The largest triangular network's threshold against Jacobs and Thorpe's bulk value, in
/// standard errors over the seeds (or the seeds' agreement, where they all found one value)
/// and beside the grid step `brackets` that located it.
fn largest_triangular_sentence(thresholds: &Thresholds, brackets: &Brackets) -> Option<String> {
    let (network, p) = thresholds.iter().rev().find(|(network, _)| network.name == "triangular")?;
    let n = network.n;
    let (mean, _, error) = over_seeds(p);
    let (off, emt_off) = (mean - 0.660, mean - 2.0 / 3.0);
    let side = |x: f64| if x < 0.0 { "below" } else { "above" };
    let scatter = match p.len() {
        1 => "one seed".to_string(),
        _ if error == 0.0 => format!("every one of {} seeds found it", p.len()),
        _ => format!("{:.1} standard errors over the seeds", off.abs() / error),
    };
    Some(format!(
        "At the largest size, N = {n}, the triangular threshold {mean:.3} lies {:.3} {} Jacobs and Thorpe's \
         bulk 0.660 ({scatter}, on a grid that brackets each seed's threshold within {:.3} in cut fraction: a \
         finite network between rigid edge bands need not share the bulk's value) and {:.3} {} \
         effective-medium theory's 2/3, which counts constraints on average.",
        off.abs(),
        side(off),
        brackets[network],
        emt_off.abs(),
        side(emt_off),
    ))
}

/// The networks rigid by the linear test but too near a mechanism for its answer.
fn unstable_sentence(runs: &[&RunRecord]) -> Option<String> {
    let unstable: Vec<f64> = runs
        .iter()
        .filter(|r| r.status == RunStatus::Unstable)
        .filter_map(|r| r.spec.lattice().map(|l| 1.0 - l.cut_fraction))
        .collect();
    let (low, high) = (unstable.iter().copied().reduce(f64::min)?, unstable.iter().copied().reduce(f64::max)?);
    Some(format!(
        "{} networks at p = {low:.3} … {high:.3} are rigid by the static solver's linear test but so near a \
         mechanism that the linear answer's large displacements fail the energy check (status unstable): \
         they count as rigid here, with their linear E.",
        unstable.len()
    ))
}

/// The triangular networks' E against the effective-medium line.
fn effective_medium_sentence(stiffness: &StiffnessByCut) -> Option<String> {
    let emt_rows: Vec<String> = stiffness
        .iter()
        .filter(|((name, _), _)| *name == "triangular")
        .map(|((_, cut), ratios)| {
            let p = 1.0 - *cut as f64 / 1000.0;
            let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
            // Cut fractions on a grid of 0.005: three decimals where the third is not 0.
            let p_text = if cut % 10 == 0 { format!("{p:.2}") } else { format!("{p:.3}") };
            format!("p = {p_text}: E/E(1) = {} (EMT {})", sig(mean), sig(((p - 2.0 / 3.0) / (1.0 / 3.0)).max(0.0)))
        })
        .collect();
    (!emt_rows.is_empty()).then(|| {
        format!(
            "E of the triangular networks (linear static answer, mechanisms counted as 0, averaged over seeds and \
             sizes) against the effective-medium line E(p)/E(1) = (p − 2/3)/(1 − 2/3): {}.",
            emt_rows.join("; ")
        )
    })
}

/// How the threshold is located, in words.
const THRESHOLD_METHOD: &str = "The threshold is located by the static solver's rigidity test: a network is floppy when the load \
         drives a zero-stiffness motion (status mechanism); p = 1 − cut_fraction is the probability an interior \
         bond is kept. The loaded and the supported rows sit in rigid bands that are never cut (the bonds that \
         touch them and those along the rows next to them): without the second row's bonds a triangular top \
         row is a chain of triangles hinged at its loaded nodes, and one of them folds the likelier the wider \
         the network. Per seed the threshold lies midway between the largest cut fraction still rigid and the \
         smallest that is a mechanism (the cut sets of a seed are nested), to half the grid's step there; the \
         thresholds scatter by seed, less as N grows.";

/// True for an impulse lattice stepped or kicked mostly sideways: its wave is transverse.
fn transverse(r: &RunRecord) -> bool {
    r.spec.lattice().and_then(|l| l.impulse).is_some_and(|i| i.is_sideways())
}

/// An impulse in words: "1000 N step" (per top-row node) or "0.1 m/s kick".
fn impulse_in_words(r: &RunRecord) -> String {
    let Some(impulse) = r.spec.lattice().and_then(|l| l.impulse) else { return String::new() };
    let [x, y] = impulse.direction();
    let size = x.hypot(y);
    let size = if size.fract() == 0.0 && size < 1e6 { format!("{size}") } else { sig(size) };
    if impulse.top_row_force.is_some() { format!("{size} N step") } else { format!("{size} m/s kick") }
}

/// The lowest and highest of `values` in words, "a … b" (one number when they agree to
/// four digits).
fn span(values: &[f64]) -> String {
    let (low, high) = extremes(values);
    if sig(low) == sig(high) { sig(low) } else { format!("{} … {}", sig(low), sig(high)) }
}

/// One impulse lattice's wave: its type, polarisation, impulse and speed over its reference.
struct Wave<'a> {
    record: &'a RunRecord,
    kind: LatticeType,
    transverse: bool,
    impulse: String,
    /// What sets the network apart beyond its type: its other grid values and its damping
    /// ("no diagonals, r = 0.5"); empty for an undamped lattice where only the type varies.
    network: String,
    /// Bond dashpots or background damping: the reference is the undamped lattice's speed, so
    /// its front is shown, not judged.
    damped: bool,
    /// Measured speed over the reference; `None` when no front arrived or there is no reference.
    ratio: Option<f64>,
    /// No criterion saw a front reach the bottom row.
    no_front: bool,
}

impl Wave<'_> {
    /// The type and what sets the network apart: "square, no diagonals, r = 0.5".
    fn label(&self) -> String {
        if self.network.is_empty() {
            self.kind.name().into()
        } else {
            format!("{}, {}", self.kind.name(), self.network)
        }
    }
}

/// A run's damping in words ("r = 0.5", "γ_g = 300 N s/m"); empty when undamped.
fn damping_in_words(r: &RunRecord) -> String {
    let s = &r.spec;
    let mut said = Vec::new();
    if s.gamma > 0.0 {
        said.push(s.restitution_target.map_or_else(|| format!("γ = {} N s/m", sig(s.gamma)), |x| format!("r = {x}")));
    }
    if s.gamma_background > 0.0 {
        said.push(format!("γ_g = {} N s/m", sig(s.gamma_background)));
    }
    said.join(", ")
}

/// The wave of every type, longitudinal (a force step down on the top row) and transverse (a
/// force step sideways on a periodic strip): the measured speed against the speed of that
/// lattice's plane wave along y (`measure::plane_wave_speeds`; c² = C A/m on the square one).
pub(super) fn waves(e: &Evidence) -> Option<Answer> {
    let runs = e.ok(|r| r.spec.lattice().is_some_and(|l| l.impulse.is_some()) && r.spec.wave().is_some());
    if !runs.iter().any(|r| other_type(r)) {
        return None;
    }
    let (rows, waves) = wave_rows(&runs)?;
    let criterion = runs.first().and_then(|r| r.metrics.arrival_criterion.clone()).unwrap_or_default();
    let longitudinal = ratios(&waves, |w| !w.transverse && judged(w));
    let rigid = ratios(&waves, |w| w.transverse && judged(w));
    let mut sentences = longitudinal_sentences(&waves, &criterion);
    sentences.extend(no_front_sentence(&waves));
    sentences.extend(transverse_sentence(&waves, &rigid));
    sentences.extend(kagome_sentence(&waves));
    sentences.extend(honeycomb_sentence(&waves));
    sentences.extend(damped_sentence(&waves));
    let short = if ratios(&waves, |w| w.transverse).is_empty() {
        format!("v/c_L = {}", span(&longitudinal))
    } else {
        format!("v/c_L = {}; v/c_T = {}", span(&longitudinal), span(&rigid))
    };
    let damped = if waves.iter().any(|w| w.damped) { " Damped lattices are shown, not judged." } else { "" };
    Some(Answer {
        title: "Lattice types: waves",
        question: "Does a wave on every type arrive at that lattice's longitudinal and transverse speeds?",
        short,
        sentences,
        reference: format!(
            "The plane-wave speed along y of each type (c_L; c_T of the square and triangular lattices; the \
             kagome's a√(k/(2m)), shown, not judged), within 20 % (the arrival criteria's spread on the square \
             lattice).{damped}"
        ),
        see_also: None,
        verdict: Verdict::of(ratios(&waves, judged).iter().map(|x| (x - 1.0).abs() < 0.2)),
        figures: e.movies(|r| other_type(r) && r.spec.movie.is_some()),
        table: Some(Table {
            header: [
                "type",
                "wave",
                "supports",
                "impulse",
                "distance (m)",
                "arrival (s)",
                "speed (m/s)",
                "reference (m/s)",
                "ratio",
            ]
            .map(String::from)
            .to_vec(),
            rows,
        }),
    })
}

/// The measured speeds over their references of the waves `pick` selects.
fn ratios(waves: &[Wave], pick: impl Fn(&Wave) -> bool) -> Vec<f64> {
    waves.iter().filter(|w| pick(w)).filter_map(|w| w.ratio).collect()
}

/// Whether a wave's speed is judged: not on a damped lattice (its reference is the undamped
/// speed), and the kagome's transverse arrival is read apart, its strip being a mechanism in
/// shear.
fn judged(w: &Wave) -> bool {
    !w.damped && (!w.transverse || w.kind != LatticeType::Kagome)
}

/// A table row and a [`Wave`] per timed impulse run.
fn wave_rows<'a>(runs: &[&'a RunRecord]) -> Option<(Vec<Vec<String>>, Vec<Wave<'a>>)> {
    let mut rows = Vec::new();
    let mut waves = Vec::new();
    // The network's grid values beyond its type, its impulse (a column of its own) and its
    // damping (said from the spec, grid value or not).
    let network = |path: &str| path != "lattice.type" && !path.starts_with("impulse.") && !path.starts_with("damping.");
    for r in runs {
        let (m, l) = (&r.metrics, r.spec.lattice()?);
        let measured = m.recommended_sound_speed();
        let said: Vec<String> =
            [r.spec.varied_in_words(network), damping_in_words(r)].into_iter().filter(|s| !s.is_empty()).collect();
        let wave = Wave {
            record: r,
            kind: kind(r),
            transverse: transverse(r),
            impulse: impulse_in_words(r),
            network: said.join(", "),
            damped: r.spec.gamma > 0.0 || r.spec.gamma_background > 0.0,
            ratio: measured.zip(m.sound_speed_theory).map(|(a, b)| a / b),
            no_front: m.arrival_times.is_empty(),
        };
        rows.push(vec![
            wave.label(),
            if wave.transverse { "transverse" } else { "longitudinal" }.into(),
            l.supports.name().into(),
            wave.impulse.clone(),
            cell(m.wave_distance),
            cell(m.arrival_time()),
            cell(measured),
            cell(m.sound_speed_theory),
            wave.ratio.map(|x| format!("{x:.3}")).unwrap_or_else(|| "–".into()),
        ]);
        waves.push(wave);
    }
    Some((rows, waves))
}

/// Each name once, in the order first met.
fn distinct(names: impl IntoIterator<Item = String>) -> Vec<String> {
    let mut seen: Vec<String> = Vec::new();
    for name in names {
        if !seen.contains(&name) {
            seen.push(name);
        }
    }
    seen
}

/// The undamped longitudinal waves' speeds against each type's c_L, said of the impulses that
/// sent them and the types a front crossed, and over two networks or more whether their ratios
/// are alike.
fn longitudinal_sentences(waves: &[Wave], criterion: &str) -> Vec<String> {
    let sent: Vec<&Wave> = waves.iter().filter(|w| !w.transverse).collect();
    let down: Vec<&Wave> = sent.iter().copied().filter(|w| judged(w) && w.ratio.is_some()).collect();
    if down.is_empty() {
        return Vec::new();
    }
    let crossed = distinct(down.iter().map(|w| w.kind.name().to_string()));
    let all_types = distinct(sent.iter().map(|w| w.kind.name().to_string()));
    let across = match crossed.as_slice() {
        [one] => format!("the {one} lattice"),
        _ if crossed.len() == all_types.len() => "every type".into(),
        _ => format!("the {} lattices", words::listed(&crossed, "and")),
    };
    let undamped = if sent.iter().any(|w| w.damped) { " on the undamped lattices" } else { "" };
    let kicks = sent.iter().any(|w| w.impulse.ends_with(" kick"));
    let mut sentences = vec![format!(
        "{} sends a {}longitudinal wave down {across}; timed at the bottom row by the {criterion} criterion, its \
         speed{undamped} is {} of that lattice's c_L = √((λ + 2μ) A/m) (A the area per node): a√((k + k_d)/m) \
         square, a√(9k/(8m)) triangular, a√(3k/(4m)) kagome, a√(3k/(8m)) honeycomb.",
        words::capitalised(&sources(&sent)),
        if kicks { "" } else { "plane " },
        span(&ratios(waves, |w| !w.transverse && judged(w)))
    )];
    sentences.extend(alike_sentence(&down));
    sentences
}

/// The impulses that sent the longitudinal waves `sent`, each kind once before its sizes: "a
/// force step down on the top row (1000 N)"; only a step on the whole top row makes a plane
/// front, a kicked node sends a circular one.
fn sources(sent: &[&Wave]) -> String {
    let of_kind = |ending: &str| {
        // "1000 N step" → "1000 N".
        let mut sizes: Vec<String> =
            sent.iter().filter_map(|w| w.impulse.strip_suffix(ending).map(String::from)).collect();
        sizes.sort_unstable();
        sizes.dedup();
        sizes
    };
    let (steps, kicks) = (of_kind(" step"), of_kind(" kick"));
    let mut said = Vec::new();
    if !steps.is_empty() {
        said.push(format!("a force step down on the top row ({})", words::listed(&steps, "or")));
    }
    if !kicks.is_empty() {
        said.push(format!("a kick of one node ({})", words::listed(&kicks, "or")));
    }
    words::listed(&said, "or")
}

/// The longitudinal ratios of two networks or more (`down`, undamped, timed): alike within
/// [`ALIKE`], the criterion sets the offset; further apart, not it alone.
fn alike_sentence(down: &[&Wave]) -> Option<String> {
    let networks = distinct(down.iter().map(|w| w.label()));
    if networks.len() < 2 {
        return None;
    }
    let by_ratio = |a: &&&Wave, b: &&&Wave| a.ratio.unwrap_or(0.0).total_cmp(&b.ratio.unwrap_or(0.0));
    let (low, high) = (down.iter().min_by(by_ratio)?, down.iter().max_by(by_ratio)?);
    let (low_ratio, high_ratio) = (low.ratio?, high.ratio?);
    let apart = high_ratio / low_ratio - 1.0;
    Some(if apart <= ALIKE {
        format!(
            "Over the {} networks the ratios lie within {:.1} % of one another: the criterion, not the network, \
             sets the offset, for a discrete lattice's front is dispersed over a few rows and a threshold catches \
             its leading edge.",
            networks.len(),
            100.0 * apart
        )
    } else {
        format!(
            "Over the {} networks the ratios lie {:.1} % apart, from {} ({}) to {} ({}): one criterion timed them \
             all, so it alone does not set the offset.",
            networks.len(),
            100.0 * apart,
            sig(low_ratio),
            low.label(),
            sig(high_ratio),
            high.label()
        )
    })
}

/// Ratios of the networks' longitudinal speeds to their c_L this close (largest over smallest
/// − 1) are alike: the criterion's offset, not the network's.
const ALIKE: f64 = 0.05;

/// The longitudinal waves whose front no criterion saw reach the bottom row.
fn no_front_sentence(waves: &[Wave]) -> Option<String> {
    let quiet: Vec<String> = waves
        .iter()
        .filter(|w| !w.transverse && w.no_front)
        .map(|w| format!("the {} lattice under a {}", w.label(), w.impulse))
        .collect();
    if quiet.is_empty() {
        return None;
    }
    let (it, has) = if quiet.len() == 1 { ("it", "has") } else { ("they", "have") };
    Some(format!(
        "No criterion saw a longitudinal front reach the bottom row of {}: {it} {has} no speed here, and the \
         ratios above and the verdict leave {} out.",
        words::listed(&quiet, "or"),
        if quiet.len() == 1 { "it" } else { "them" }
    ))
}

/// The damped lattices' fronts against the undamped lattice's speed, beside the same network
/// undamped where it ran.
fn damped_sentence(waves: &[Wave]) -> Option<String> {
    let damped: Vec<(&Wave, f64, Option<f64>)> = waves
        .iter()
        .filter(|w| w.damped)
        .filter_map(|w| Some((w, w.ratio?, undamped_twin(waves, w).and_then(|u| u.ratio))))
        .collect();
    if damped.is_empty() {
        return None;
    }
    let listed: Vec<String> = damped
        .iter()
        .map(|(w, ratio, twin)| {
            let twin = twin.map_or_else(String::new, |x| format!(" against {} undamped", sig(x)));
            let reference = if w.transverse { "its c_T" } else { "its c_L" };
            format!("{} ({}), {} of {reference}{twin}", w.label(), w.impulse, sig(*ratio))
        })
        .collect();
    let earlier = damped.iter().all(|(_, ratio, twin)| twin.is_some_and(|x| *ratio > x));
    Some(format!(
        "A damped lattice's front is held against the undamped lattice's speed, and shown, not judged: {}{}.",
        listed.join("; "),
        if earlier { ". Each arrived earlier than on the same network undamped" } else { "" }
    ))
}

/// The wave of the same network, impulse and material as `w`, undamped.
fn undamped_twin<'a, 'b>(waves: &'b [Wave<'a>], w: &Wave) -> Option<&'b Wave<'a>> {
    let (s, l) = (&w.record.spec, w.record.spec.lattice());
    waves.iter().find(|u| {
        let t = &u.record.spec;
        !u.damped && t.lattice() == l && (t.k, t.mass, t.spacing, t.law) == (s.k, s.mass, s.spacing, s.law)
    })
}

/// The transverse waves of the rigid types against their c_T.
fn transverse_sentence(waves: &[Wave], rigid: &[f64]) -> Option<String> {
    if rigid.is_empty() {
        return None;
    }
    let mut steps: Vec<&str> =
        waves.iter().filter(|w| w.transverse && judged(w) && w.ratio.is_some()).map(|w| w.impulse.as_str()).collect();
    steps.sort_unstable();
    steps.dedup();
    let sizes = if steps.len() > 1 { format!(", alike under a {}", steps.join(" and a ")) } else { String::new() };
    Some(format!(
        "A force step sideways on the top row of a periodic strip (no side edges to shed longitudinal waves, a \
         free bottom row) sends a plane transverse wave: by the same criterion its speed is {} of c_T = \
         √(μ A/m), a√(k_d/m) square, a√(3k/(8m)) triangular{sizes}. On the strip every row moves as one, so \
         both are the same chain of rows, each timed against its own c_T.",
        span(rigid)
    ))
}

/// The kagome's sideways wave: a mechanism's branch, and what its fronts show.
fn kagome_sentence(waves: &[Wave]) -> Option<String> {
    let kagome: Vec<&Wave> = waves.iter().filter(|w| w.transverse && w.kind == LatticeType::Kagome).collect();
    if kagome.is_empty() {
        return None;
    }
    let quiet: Vec<&str> = kagome.iter().filter(|w| w.no_front).map(|w| w.impulse.as_str()).collect();
    let arrived: Vec<String> = kagome
        .iter()
        .filter_map(|w| {
            w.ratio.map(|x| format!("under a {} at {} of it ({} of c_T)", w.impulse, sig(x), sig(x * 2.0_f64.sqrt())))
        })
        .collect();
    let mut sentence = "The kagome's acoustic Bloch branch along y that moves sideways has the slope a√(k/(2m)) = \
                        √2 c_T, not the affine c_T = a√(k/(4m)) (its triangles twist at no cost, z = 2d, and the \
                        twist joins the shear at the order of the strain), and its other sideways branch is flat \
                        at zero: its strip shears as a mechanism, and that branch takes the step."
        .to_string();
    if !quiet.is_empty() {
        sentence += &format!(
            " Under a {} no front reached the bottom row by any criterion: the top row runs away, and the \
             receivers never reach the threshold its growing speed sets.",
            quiet.join(" or a ")
        );
    }
    if !arrived.is_empty() {
        sentence += &format!(
            " A front arrived {}; with linear springs only the geometry can make the arrival depend on the \
             step's size, so that front rides on the turned bonds of a large step, and the verdict leaves \
             it out.",
            arrived.join(", ")
        );
    }
    Some(sentence)
}

/// The honeycomb's strip, which carries no transverse front.
fn honeycomb_sentence(waves: &[Wave]) -> Option<String> {
    let honeycomb: Vec<&str> = waves
        .iter()
        .filter(|w| w.transverse && w.kind == LatticeType::Honeycomb && w.no_front)
        .map(|w| w.impulse.as_str())
        .collect();
    if honeycomb.is_empty() {
        return None;
    }
    Some(format!(
        "The honeycomb's strip carried no transverse front under a {}: its sideways branch along y is flat at \
         zero (μ = 0), and a sideways step turns its bonds and sends nothing down.",
        honeycomb.join(" or a ")
    ))
}

/// The discussion of a lattice-types campaign: each type's E, ν, G and longitudinal wave speed
/// against its continuum, from its largest loaded block of each kind (E and ν of a free block in
/// tension on coursework supports, G of a periodic strip in shear) and its waves.
pub(super) fn against_continuum(e: &Evidence) -> Option<Paragraph> {
    if !e.records.iter().any(|r| other_type(r)) {
        return None;
    }
    let waves = e.ok(|r| r.spec.lattice().is_some_and(|l| l.impulse.is_some()) && r.spec.wave().is_some());
    let (_, waves) = wave_rows(&waves)?;
    let types: Vec<String> = LatticeType::ALL
        .into_iter()
        .filter(|&t| e.records.iter().any(|r| r.spec.lattice().is_some() && kind(r) == t))
        .filter_map(|t| type_against_continuum(e, t, &waves))
        .collect();
    if types.is_empty() {
        return None;
    }
    Some(Paragraph {
        title: "The networks against their continuum",
        text: format!(
            "Each network from its largest block, measured against the continuum of its bonds (the static \
             answer where no MD ran or MD parts from it): {}. The continuum is the network's long-wavelength limit, which a finite \
             block approaches as its edges and supports matter less.",
            types.join("; ")
        ),
    })
}

/// One type's sentence of [`against_continuum`]; `None` where the campaign loaded no block of
/// it (only diluted ones, say) and sent no wave through it.
fn type_against_continuum(e: &Evidence, t: LatticeType, waves: &[Wave]) -> Option<String> {
    let tension = loaded_runs(e, t, LoadCase::Tensile, Supports::Coursework);
    let shear = loaded_runs(e, t, LoadCase::Shear, Supports::PeriodicX);
    let mut said: Vec<String> = [
        against("E", " Pa", &tension, |l| (l.youngs_modulus, l.youngs_modulus_fem), |l| l.youngs_modulus_theory),
        against("ν", "", &tension, |l| (l.poisson_ratio, l.poisson_ratio_fem), |l| l.poisson_ratio_theory),
        against("G", " Pa", &shear, |l| (l.shear_modulus, l.shear_modulus_fem), |l| l.shear_modulus_theory),
    ]
    .into_iter()
    .flatten()
    .collect();
    said.extend(longitudinal_by_network(waves, t));
    let z = distinct(
        e.records
            .iter()
            .filter(|r| kind(r) == t)
            .filter_map(|r| r.spec.lattice())
            .map(|l| l.coordination().to_string()),
    );
    (!said.is_empty()).then(|| format!("{} (z = {}): {}", t.name(), words::listed(&z, "or"), said.join(", ")))
}

/// The undamped longitudinal waves of type `t` against c_L, each network apart ("1.196 × c_L (no
/// diagonals) and 1.054 × c_L (both diagonals)"): networks of one type have c_L of their own.
fn longitudinal_by_network(waves: &[Wave], t: LatticeType) -> Option<String> {
    let mine = |w: &Wave| w.kind == t && !w.transverse && judged(w);
    let networks = distinct(waves.iter().filter(|w| mine(w) && w.ratio.is_some()).map(|w| w.network.clone()));
    let listed: Vec<String> = networks
        .iter()
        .map(|network| {
            let of_it = span(&ratios(waves, |w| mine(w) && w.network == *network));
            if network.is_empty() { format!("{of_it} × c_L") } else { format!("{of_it} × c_L ({network})") }
        })
        .collect();
    (!listed.is_empty()).then(|| format!("its longitudinal wave at {}", words::listed(&listed, "and")))
}

/// A modulus `name` (in `unit`) of the largest of `runs` that has one, against its continuum;
/// where none has, why not (the largest run's status). `measured` gives (MD, static): MD where
/// it ran and agrees with the static answer, the static answer where MD stopped short of it.
fn against(
    name: &str,
    unit: &str,
    runs: &[&RunRecord],
    measured: fn(&LatticeMetrics) -> (Option<f64>, Option<f64>),
    theory: fn(&LatticeMetrics) -> Option<f64>,
) -> Option<String> {
    let largest = |pick: &dyn Fn(&RunRecord) -> bool| {
        runs.iter().copied().filter(|r| pick(r)).max_by_key(|r| r.spec.lattice().map_or(0, |l| l.nx * l.ny))
    };
    let value = |r: &RunRecord| {
        let (md, fem) = measured(&r.metrics.lattice);
        let parts = Departure::of(r).is_some_and(|d| d.parts());
        if parts || md.is_none() { (fem, "static") } else { (md, "MD") }
    };
    let Some(r) = largest(&|r| value(r).0.is_some()) else {
        return largest(&|_| true).map(|r| format!("no {name} ({}, {})", r.status.as_str(), block_in_words(r, None)));
    };
    let ((x, how), reference) = (value(r), theory(&r.metrics.lattice));
    let off = relative(x, reference).map_or_else(|| "no reference".into(), super::finding::percent);
    Some(format!(
        "{name} = {}{unit} against {}{unit} ({off}, {})",
        cell(x),
        cell(reference),
        block_in_words(r, Some(how))
    ))
}

/// The loaded blocks of type `t` under `case` on `supports` (not diluted, not turned).
fn loaded_runs<'a>(e: &Evidence<'a>, t: LatticeType, case: LoadCase, supports: Supports) -> Vec<&'a RunRecord> {
    e.all(|r| {
        kind(r) == t
            && r.spec.lattice().is_some_and(|l| {
                l.load_case == case && l.supports == supports && l.impulse.is_none() && !l.is_random() && !l.rotated
            })
    })
}

/// "free block 33 × 33" or "periodic strip 12 × 11", and whether MD or the static answer
/// (`how`, where said; else MD unless the run is static only).
fn block_in_words(r: &RunRecord, how: Option<&str>) -> String {
    let Some(l) = r.spec.lattice() else { return String::new() };
    let what = if l.supports == Supports::PeriodicX { "periodic strip" } else { "block" };
    let how = how.unwrap_or(if r.spec.static_only() { "static" } else { "MD" });
    format!("{how}, {what} {} × {}", l.nx, l.ny)
}
