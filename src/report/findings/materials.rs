//! The coursework's questions on the solid the network makes: homogeneity of the deformation,
//! Hertz moduli against the load, anisotropic and random networks, and MD against the static
//! truss (FEM) answer.

use crate::report::figure::FigureKind;
use crate::report::words::{self, number};
use std::collections::BTreeMap;

use super::block::Block;
use super::discussion::symbol;
use super::finding::{
    Answer, Evidence, Table, Verdict, cell, exponents, noise, percent, rel, relative, shear_name, sig,
};
use super::finding::{EXPONENT_TOLERANCE, predicted_exponent};
use crate::measure::{power_law_poisson_ratio, youngs_modulus_along};
use crate::model::LawSpec;
use crate::runner::RunRecord;
use crate::spec::{Diagonals, LoadCase};
use crate::summary::LOAD;

/// Homogeneity by block size (N_x, N_y).
type BySize = BTreeMap<(usize, usize), f64>;

/// A set-up whose homogeneity is compared over sizes: load case, supports and diagonals (names).
type Setup = (&'static str, &'static str, &'static str);

/// After relaxation: are the left and right edges straight lines?
pub(super) fn homogeneity(e: &Evidence) -> Option<Answer> {
    let regular = |r: &RunRecord| {
        r.spec.law == LawSpec::Linear
            && r.spec.lattice().is_some_and(|l| l.impulse.is_none() && !l.is_random() && l.k_x == l.k_y && !l.rotated)
    };
    let measured = e.ok(|r| regular(r) && r.metrics.lattice.homogeneity.is_some());
    let undefined =
        e.ok(|r| regular(r) && r.metrics.lattice.homogeneity.is_none() && r.metrics.lattice.youngs_modulus.is_some());
    // Without a loaded regular lattice (a packing campaign) there is nothing to say.
    let by_size = homogeneity_by_setup(&measured).filter(|b| !b.is_empty() || !undefined.is_empty())?;
    let mut sentences = vec![
        "Homogeneity is the largest distance of a left- or right-edge node's horizontal displacement from the \
         straight line fitted through that edge, divided by the edges' mean horizontal displacement: 0 when the \
         edges stay straight lines, as a homogeneous strain requires."
            .to_string(),
    ];
    let mut rows = Vec::new();
    // The diagonals are named only where the campaign measures more than one kind.
    let mixed = by_size.keys().any(|k| k.2 != by_size.keys().next().map_or(k.2, |f| f.2));
    for ((case, supports, diagonals), sizes) in &by_size {
        let diagonals = if mixed { format!(", {diagonals} diagonals") } else { String::new() };
        sentences.extend(homogeneity_sentence(case, &format!("{supports} supports{diagonals}"), sizes));
        let cell = format!("{supports}{diagonals}");
        rows.extend(
            sizes.iter().map(|((nx, ny), h)| vec![case.to_string(), cell.clone(), format!("{nx} × {ny}"), sig(*h)]),
        );
    }
    if !undefined.is_empty() {
        sentences.push(format!(
            "In {} tensile runs the edges do not move sideways at all (without diagonals ν = 0; a periodic strip \
             cannot contract): homogeneity is not defined there, and the tables leave it empty.",
            undefined.len()
        ));
    }
    sentences.extend(top_row_sentence(
        &e.ok(|r| regular(r) && r.spec.lattice().is_some_and(|l| l.load_case == LoadCase::Tensile)),
    ));
    // The edge profiles of the scenes measured here, as the figures draw them.
    let mut scenes: Vec<&str> = measured.iter().chain(&undefined).map(|r| r.spec.scene.as_str()).collect();
    scenes.dedup();
    let figures: Vec<_> = scenes
        .iter()
        .flat_map(|scene| [e.figure(scene, FigureKind::Edges), e.figure(scene, FigureKind::TopRow)])
        .flatten()
        .take(3)
        .collect();
    Some(Answer {
        title: "Homogeneity of the deformation",
        question: "After each relaxation, check that the left and right nodes are aligned on a line; discuss.",
        short: homogeneity_short(&by_size),
        sentences,
        reference: "A homogeneous strain keeps the edges straight (0); an observation of how far each set-up departs \
                    from it."
            .into(),
        see_also: None,
        verdict: Verdict::Observed,
        figures,
        table: Some(Table { header: ["load", "supports", "lattice", "homogeneity"].map(String::from).to_vec(), rows }),
    })
}

/// Per set-up (load case, supports, diagonals): homogeneity by lattice size, the first run of
/// each size.
fn homogeneity_by_setup(measured: &[&RunRecord]) -> Option<BTreeMap<Setup, BySize>> {
    let mut by_size: BTreeMap<Setup, BySize> = BTreeMap::new();
    for r in measured {
        let l = r.spec.lattice()?;
        let value = r.metrics.lattice.homogeneity?;
        let setup = (l.load_case.name(), l.supports.name(), l.diagonals.name());
        by_size.entry(setup).or_default().entry((l.nx, l.ny)).or_insert(value);
    }
    Some(by_size)
}

/// The summary's homogeneity: the largest lattice of the coursework's set-up (tension on its
/// supports), or of the first set-up when the campaign lacks it.
fn homogeneity_short(by_size: &BTreeMap<Setup, BySize>) -> String {
    by_size
        .iter()
        .find(|((case, supports, _), _)| *case == "tensile" && *supports == "coursework")
        .or_else(|| by_size.iter().next())
        .and_then(|((case, supports, _), sizes)| {
            sizes.iter().next_back().map(|((nx, ny), h)| format!("{case}, {supports}, {nx} × {ny}: {}", sig(*h)))
        })
        .unwrap_or_default()
}

/// How flat the loaded top row of the largest tensile lattice rises, without and with
/// diagonals: its spread (max − min) against its mean lift.
fn top_row_sentence(tensile: &[&RunRecord]) -> Option<String> {
    let size = |r: &RunRecord| r.spec.lattice().map_or((0, 0), |l| (l.nx, l.ny));
    let largest = tensile
        .iter()
        .filter(|r| r.metrics.lattice.edge_displacements.is_some())
        .map(|r| size(r))
        .max_by_key(|(nx, ny)| nx * ny)?;
    let mut parts = Vec::new();
    for r in tensile.iter().filter(|r| size(r) == largest) {
        let (Some(l), Some(edges)) = (r.spec.lattice(), r.metrics.lattice.edge_displacements.as_ref()) else {
            continue;
        };
        let top = &edges.top_y;
        let mean = top.iter().sum::<f64>() / top.len() as f64;
        let spread =
            top.iter().fold(f64::NEG_INFINITY, |m, &u| m.max(u)) - top.iter().fold(f64::INFINITY, |m, &u| m.min(u));
        let diagonals = match l.diagonals {
            Diagonals::None => "without diagonals".to_string(),
            Diagonals::Both => "with diagonals".to_string(),
            one => format!("with {} diagonals", one.name()),
        };
        // A spread below 1e-9 of the lift is round-off: the row is flat.
        let relative = spread / mean.abs();
        let shape = if relative < 1e-9 {
            "uniformly".to_string()
        } else {
            format!("varying by {} % along it", sig(100.0 * relative))
        };
        parts.push(format!("{diagonals} on {} supports by {} µm, {shape}", l.supports.name(), sig(mean / 1e-6)));
    }
    let (nx, ny) = largest;
    (!parts.is_empty()).then(|| {
        format!("On {nx} × {ny} the loaded top row rises {} (figure: the top row's profile).", parts.join("; "))
    })
}

/// A homogeneity below this is a straight edge: the relaxation stops with the slowest mode's
/// displacement error at about 1e-4 … 1e-3 of the deformation (the moduli's tolerance), and
/// an edge departs from its line by as much.
const STRAIGHT: f64 = super::two_d::STATIC_TOLERANCE;

/// How far one set-up's edges (`supports` in words, with its diagonals where they differ)
/// depart from straight lines, smallest against largest lattice, with the trend in words.
fn homogeneity_sentence(case: &str, supports: &str, sizes: &BySize) -> Option<String> {
    let (small, large) = (sizes.iter().next()?, sizes.iter().next_back()?);
    let trend = if sizes.values().all(|&h| h < STRAIGHT) {
        ": straight lines at every size, to within the relaxation's precision".to_string()
    } else if sizes.len() < 2 {
        String::new()
    } else if *large.1 < 0.8 * small.1 {
        ", shrinking as the block grows: the disturbance stays in a boundary layer of a few rows near the \
         point loads and the supports"
            .to_string()
    } else if *large.1 > 1.25 * small.1 {
        ", growing with the block: the supports bend it as a whole".to_string()
    } else {
        format!(
            ", {} times the smallest's on a block {} times as wide: a disturbance in proportion to the block, not a \
             boundary layer of fixed thickness",
            sig(large.1 / small.1),
            number(large.0.0 as f64 / small.0.0 as f64)
        )
    };
    let at = |((nx, ny), h): (&(usize, usize), &f64)| format!("{} on {nx} × {ny}", sig(*h));
    let measured = if sizes.len() < 2 { at(small) } else { format!("{} and {}", at(small), at(large)) };
    Some(format!("{case}, {supports}: {measured}{trend}."))
}

/// Non-linear 2D: moduli of power-law lattices (Hertz, β = 3/2) against the load, each fitted
/// exponent held against its own β's (β − 1)/β, and their Poisson ratio.
pub(super) fn hertz_moduli(e: &Evidence) -> Option<Answer> {
    let fits: Vec<_> = e
        .fits
        .iter()
        .filter(|f| f.law != "linear" && f.against == "load_per_node" && !f.quantity.ends_with("tangent"))
        .collect();
    let first = fits.first()?;
    let runs = e.ok(|r| r.spec.law != LawSpec::Linear && r.spec.lattice().is_some_and(|l| l.impulse.is_none()));
    let mut sentences = vec![power_law_words(&runs)];
    let mut checks = Vec::new();
    for f in &fits {
        let predicted = predicted_exponent(f)?;
        let group = runs.iter().find(|r| r.spec.scene == f.scene && load_group(r) == f.group);
        sentences.push(format!(
            "{} of scene {}{}: from {} to {} Pa over loads of {} to {} N per node, ∝ F^{:.3} ({}; predicted \
             {predicted:.3}).",
            symbol(f.quantity),
            f.scene,
            group.map_or_else(String::new, |r| load_group_words(r)),
            sig(f.points.first().map_or(0.0, |p| p.1)),
            sig(f.points.last().map_or(0.0, |p| p.1)),
            sig(f.points.first().map_or(0.0, |p| p.0)),
            sig(f.points.last().map_or(0.0, |p| p.0)),
            f.fit.exponent,
            crate::report::words::fit_quality(&f.fit, 4)
        ));
        checks.push((f.fit.exponent - predicted).abs() <= EXPONENT_TOLERANCE);
    }
    sentences.extend(tangent_over_secant(&runs));
    sentences.extend(power_law_poisson(e, &runs));
    // One figure per scene draws all of its moduli against the load.
    let mut scenes: Vec<&str> = fits.iter().map(|f| f.scene.as_str()).collect();
    scenes.dedup();
    let load_figures = scenes.iter().map(|scene| e.figure(scene, FigureKind::AgainstLoad));
    Some(Answer {
        // Hertz only where every spring is β = 3/2: other powers are the same question.
        title: if exponents(runs.iter().copied()) == [1.5] {
            "Hertz lattices: moduli against the load"
        } else {
            "Power-law lattices: moduli against the load"
        },
        question: "Non-linear 2D: set the load to different values and analyse the moduli of the different \
                   equilibria.",
        short: format!(
            "{} ∝ F^{:.3} (predicted {:.3})",
            symbol(first.quantity),
            first.fit.exponent,
            predicted_exponent(first)?
        ),
        sentences,
        reference: format!(
            "The power law F^((β − 1)/β) of springs s = C δ^β (Hertz: F^(1/3)); fitted exponents within \
             {EXPONENT_TOLERANCE}."
        ),
        see_also: None,
        verdict: Verdict::of(checks),
        figures: load_figures.into_iter().flatten().take(2).collect(),
        table: None,
    })
}

/// Why a power-law lattice's moduli grow with the load, with this campaign's exponents.
fn power_law_words(runs: &[&RunRecord]) -> String {
    let betas = exponents(runs.iter().copied());
    let each = |f: &dyn Fn(f64) -> String| words::listed(&betas.iter().map(|&b| f(b)).collect::<Vec<_>>(), "and");
    format!(
        "A spring s = C δ^β with β > 1 (Hertz: 3/2) stiffens as it is stretched: under a load F its bonds stretch by \
         δ ∝ F^(1/β), so the secant and tangent moduli, ∝ C δ^(β − 1), grow as F^((β − 1)/β), the tangent β × the \
         secant; here β = {}: F^{}.",
        each(&|b| number(b)),
        each(&|b| format!("{:.3}", (b - 1.0) / b)),
    )
}

/// Tangent over secant Young's modulus of each run, by exponent: β for springs s ∝ δ^β.
fn tangent_over_secant(runs: &[&RunRecord]) -> Option<String> {
    let groups: Vec<String> = exponents(runs.iter().copied())
        .into_iter()
        .filter_map(|beta| {
            let ratios: Vec<String> = runs
                .iter()
                .filter(|r| r.spec.law.beta() == beta)
                .filter_map(|r| Some(r.metrics.lattice.youngs_modulus_tangent? / r.metrics.lattice.youngs_modulus?))
                .map(|x| format!("{x:.3}"))
                .collect();
            (!ratios.is_empty()).then(|| format!("{} (β = {})", ratios.join(", "), number(beta)))
        })
        .collect();
    (!groups.is_empty()).then(|| format!("Tangent over secant Young's modulus: {}.", groups.join("; ")))
}

/// The group of runs that differ from `r` only in the load: its scene's other grid values, as
/// the scaling fits label them (`ScalingFit::group`).
fn load_group(r: &RunRecord) -> String {
    r.spec.varied_label(|path| !LOAD.contains(&path))
}

/// `r`'s load group in words, where its scene varies more than the load: its other grid values
/// and, pulled, the direction (a tensile-x run is the block turned by 90°, pulled along x).
fn load_group_words(r: &RunRecord) -> String {
    let others = r.spec.varied_in_words(|path| !LOAD.contains(&path));
    let along = r.spec.lattice().filter(|l| l.load_case == LoadCase::Tensile).map(|l| l.rotated);
    match (others.is_empty(), along) {
        (true, _) => String::new(),
        (false, Some(rotated)) => format!(", {others} (pulled along {})", if rotated { "x" } else { "y" }),
        (false, None) => format!(", {others}"),
    }
}

/// ν of each loaded power-law scene over its loads, one load group at a time (a pull along y
/// and one along x are different ν, not a change with the load), against the continuum of its
/// springs and the linear springs' ν on the same block.
fn power_law_poisson(e: &Evidence, runs: &[&RunRecord]) -> Vec<String> {
    let mut groups: Vec<((&str, String), Vec<&RunRecord>)> = Vec::new();
    let tensile = runs.iter().copied().filter(|r| r.spec.lattice().is_some_and(|l| l.load_case == LoadCase::Tensile));
    for r in tensile.filter(|r| r.metrics.lattice.poisson_ratio.is_some()) {
        let key = (r.spec.scene.as_str(), load_group(r));
        match groups.iter_mut().find(|(k, _)| *k == key) {
            Some((_, own)) => own.push(r),
            None => groups.push((key, vec![r])),
        }
    }
    let load = |r: &RunRecord| r.spec.lattice().map_or(0.0, |l| l.load_per_node);
    groups
        .into_iter()
        .filter_map(|(_, mut own)| {
            own.sort_by(|a, b| load(a).total_cmp(&load(b)));
            Some(format!("{}{}", load_independence(&own)?, continuum_poisson(e, own[0]).unwrap_or_default()))
        })
        .collect()
}

/// The block's strain ε = σ/E of a force-controlled square lattice run, σ = N_x F/(d L_x) with
/// L_x = (N_x − 1) a (the coursework's E).
fn strain_of(r: &RunRecord) -> Option<f64> {
    let l = r.spec.lattice().filter(|l| l.lattice_type.is_square() && l.nx > 1)?;
    let stress = l.nx as f64 * l.force_per_node()? / (l.depth * (l.nx - 1) as f64 * r.spec.spacing);
    Some(stress / r.metrics.lattice.youngs_modulus?)
}

/// ν of one scene over its loads (sorted by load). Springs of one exponent β scale every force
/// by λ^β when the displacements scale by λ, so ν does not depend on the load but through the
/// block's change of shape, whose share is of the order of the strain.
fn load_independence(own: &[&RunRecord]) -> Option<String> {
    let nu: Vec<f64> = own.iter().filter_map(|r| r.metrics.lattice.poisson_ratio).collect();
    let (low, high) = crate::measure::extremes(&nu);
    let strain = own.iter().filter_map(|r| strain_of(r)).fold(0.0, f64::max);
    let (first, last) = (own.first()?, own.last()?);
    let change = if high - low <= strain {
        format!(
            "a change of {} within the largest strain, {} (the block's change of shape): springs of one exponent \
             scale every force by λ^β when the displacements scale by λ, so ν does not depend on the load",
            sig(high - low),
            sig(strain)
        )
    } else {
        format!("a change of {}, more than the largest strain ({}) explains", sig(high - low), sig(strain))
    };
    Some(format!(
        "ν of scene {}{}: {} at {} N and {} at {} N per node, {change}.",
        first.spec.scene,
        load_group_words(first),
        cell(first.metrics.lattice.poisson_ratio),
        sig(first.spec.lattice()?.load_per_node),
        cell(last.metrics.lattice.poisson_ratio),
        sig(last.spec.lattice()?.load_per_node),
    ))
}

/// The continuum's ν of a power-law run's springs against the linear springs' of the same
/// k_d/k, and MD's against a linear run on the same block where the campaign has one.
fn continuum_poisson(e: &Evidence, r: &RunRecord) -> Option<String> {
    let l = r.spec.lattice()?;
    let continuum = r.metrics.lattice.poisson_ratio_theory?;
    let ratio = l.k_diag / l.k_x;
    let linear = power_law_poisson_ratio(ratio, 1.0);
    let mut words = format!(
        " The continuum of these springs has ν = {} (ν/(1 − ν) = (r 2^((1 − β)/2))^(1/β), r = k_d/k = {}), {} the \
         linear springs' {} (a larger β raises ν for r < 1/√2, lowers it above)",
        cell(Some(continuum)),
        sig(ratio),
        side(continuum, linear),
        cell(Some(linear)),
    );
    let same_block = |x: &RunRecord| {
        super::finding::regular(x).is_some_and(|xl| {
            xl.load_case == LoadCase::Tensile
                && (xl.lattice_type, xl.nx, xl.ny, xl.supports, xl.diagonals)
                    == (l.lattice_type, l.nx, l.ny, l.supports, l.diagonals)
                && (xl.k_diag / xl.k_x - ratio).abs() < 1e-9
        })
    };
    if let (Some(md), Some(lin)) = (r.metrics.lattice.poisson_ratio, e.ok(same_block).first()) {
        let lin_nu = lin.metrics.lattice.poisson_ratio?;
        let agrees =
            if side(md, lin_nu) == side(continuum, linear) { "as in the continuum" } else { "unlike the continuum" };
        words += &format!(
            "; on this {} × {} block MD gives {} against the linear springs' {} (scene {}): {}, {agrees}",
            l.nx,
            l.ny,
            cell(Some(md)),
            cell(Some(lin_nu)),
            lin.spec.scene,
            side(md, lin_nu),
        );
    }
    Some(words + ".")
}

/// Where `a` lies against `b`, in words.
fn side(a: f64, b: f64) -> &'static str {
    if (a - b).abs() <= 1e-12 * b.abs() {
        "equal to"
    } else if a > b {
        "above"
    } else {
        "below"
    }
}

/// Anisotropic networks: moduli in both directions.
pub(super) fn anisotropic(e: &Evidence) -> Option<Answer> {
    let runs = anisotropy_runs(e);
    let mut groups: BTreeMap<String, Vec<&RunRecord>> = BTreeMap::new();
    for r in &runs {
        groups.entry(network_words(r)).or_default().push(r);
    }
    let (rows, mut sentences) = anisotropic_rows(&groups);
    if rows.is_empty() {
        return None;
    }
    let worst = runs
        .iter()
        .filter_map(|r| {
            let m = &r.metrics.lattice;
            relative(m.youngs_modulus.or(m.shear_modulus), m.youngs_modulus_fem.or(m.shear_modulus_fem))
        })
        .map(f64::abs)
        .fold(0.0, f64::max);
    sentences.insert(
        0,
        "Anisotropic networks must be measured in every direction: tensile loads along y and, with the loading \
         turned by 90° (tensile-x), along x, and shear."
            .to_string(),
    );
    sentences.push(format!(
        "MD agrees with the static answer of each anisotropic network to {} at worst.",
        rel(worst).trim_start_matches('+')
    ));
    Some(Answer {
        title: "Anisotropic networks",
        question: "(a) Make the packing anisotropic (cut one diagonal family, or stiffer vertical springs) and \
                   measure the moduli in all directions.",
        short: format!("E_x ≠ E_y measured; MD = static within {}", rel(worst).trim_start_matches('+')),
        sentences,
        reference: "The static truss answer of each network (tolerance 2e-3); the continuum's E_y/E_x from its \
                    constants C11 = k_x + k_d, C22 = k_y + k_d, C12 = C66 = k_d (both families; one family of \
                    k_r: k_r/2 each, with C16 = C26 = k_r/2); a finite block keeps a share ∝ 1/N above it."
            .into(),
        see_also: None,
        verdict: Verdict::of([worst <= 2e-3]),
        figures: Vec::new(),
        table: Some(Table {
            header: [
                "network",
                "E_y (Pa)",
                "E_x (Pa)",
                "ν (load y)",
                "ν (load x)",
                &format!("{} (Pa)", shear_name(&runs)),
            ]
            .map(String::from)
            .to_vec(),
            rows,
        }),
    })
}

/// The runs of the scenes that measure anisotropy: those with an anisotropic network (k_y ≠ k_x
/// or one diagonal family) or a load turned to x, with every other regular run of those scenes,
/// so the isotropic network a scene holds as its reference keeps its E_y and G beside its E_x.
fn anisotropy_runs<'a>(e: &Evidence<'a>) -> Vec<&'a RunRecord> {
    let anisotropic = |r: &RunRecord| {
        r.spec.lattice().is_some_and(|l| {
            l.impulse.is_none()
                && (l.k_x != l.k_y || !matches!(l.diagonals, Diagonals::Both | Diagonals::None) || l.rotated)
        })
    };
    let scenes: Vec<&str> = e.ok(anisotropic).iter().map(|r| r.spec.scene.as_str()).collect();
    // Loaded runs only: a kicked anisotropic lattice has no moduli to measure in any direction.
    e.ok(|r| {
        scenes.contains(&r.spec.scene.as_str())
            && r.spec.lattice().is_some_and(|l| !l.is_random() && l.impulse.is_none())
    })
}

/// An anisotropic network in words, from its lattice whatever the grid varies: its diagonal
/// families and its vertical springs' stiffness over the horizontal ones', in the campaign's
/// frame (a run loaded along x simulates the lattice turned by 90°: k_x and k_y, and the
/// rising and falling families, swapped back here).
fn network_words(r: &RunRecord) -> String {
    let Some(l) = r.spec.lattice() else { return String::new() };
    let (diagonals, ratio) = match (l.rotated, l.diagonals) {
        (false, d) => (d, l.k_y / l.k_x),
        (true, Diagonals::Rising) => (Diagonals::Falling, l.k_x / l.k_y),
        (true, Diagonals::Falling) => (Diagonals::Rising, l.k_x / l.k_y),
        (true, d) => (d, l.k_x / l.k_y),
    };
    format!("{} diagonals, k_y/k = {ratio}", diagonals.name())
}

/// One row per anisotropic network (E_y, E_x, ν both ways, G) and a sentence each on how its
/// directions differ.
fn anisotropic_rows(groups: &BTreeMap<String, Vec<&RunRecord>>) -> (Vec<Vec<String>>, Vec<String>) {
    let modulus = |rs: &[&RunRecord], case: LoadCase, rotated: bool, pick: fn(&RunRecord) -> Option<f64>| {
        rs.iter()
            .find(|r| r.spec.lattice().is_some_and(|l| l.load_case == case && l.rotated == rotated))
            .and_then(|r| pick(r))
    };
    let (mut rows, mut sentences, mut free_shear_said) = (Vec::new(), Vec::new(), false);
    for (key, rs) in groups {
        let e_y = modulus(rs, LoadCase::Tensile, false, |r| r.metrics.lattice.youngs_modulus);
        let e_x = modulus(rs, LoadCase::Tensile, true, |r| r.metrics.lattice.youngs_modulus);
        let nu_y = modulus(rs, LoadCase::Tensile, false, |r| r.metrics.lattice.poisson_ratio);
        let nu_x = modulus(rs, LoadCase::Tensile, true, |r| r.metrics.lattice.poisson_ratio);
        let continuum = modulus(rs, LoadCase::Tensile, false, |r| r.metrics.lattice.youngs_modulus_theory)
            .zip(modulus(rs, LoadCase::Tensile, true, |r| r.metrics.lattice.youngs_modulus_theory))
            .map(|(y, x)| y / x);
        if let (Some(y), Some(x)) = (e_y, e_x) {
            sentences.push(format!(
                "{key}: E_y/E_x = {} against the continuum's {} ({}), ν = {} loaded along y and {} along x{}.",
                sig(y / x),
                continuum.map_or_else(|| "–".into(), sig),
                continuum.map_or_else(|| "–".into(), |c| percent((y / x - c) / c)),
                noise(nu_y, 1.0),
                noise(nu_x, 1.0),
                direction_words(rs, y / x)
            ));
        }
        // Said once: every one-family network shears freely for the same reason.
        if let Some(free) = rs.iter().find_map(|r| free_shear_sentence(r)).filter(|_| !free_shear_said) {
            sentences.push(free);
            free_shear_said = true;
        }
        rows.push(vec![
            key.clone(),
            cell(e_y),
            cell(e_x),
            noise(nu_y, 1.0),
            noise(nu_x, 1.0),
            cell(modulus(rs, LoadCase::Shear, false, |r| r.metrics.lattice.shear_modulus)),
        ]);
    }
    (rows, sentences)
}

/// Directions closer than this in E (relative) are the same.
const SAME_E: f64 = 1e-3;

/// Whether the network of `rs` is isotropic, from its continuum's E in every direction (the
/// extremes over θ in steps of 0.5°, from x towards y), and where its measured `e_ratio`
/// E_y/E_x alone would mislead: one diagonal family with k_y = k_x has E_y = E_x, yet is
/// three times softer along its missing diagonal (k_r = k/2).
fn direction_words(rs: &[&RunRecord], e_ratio: f64) -> String {
    let along_y = rs.iter().find_map(|r| r.spec.lattice().filter(|l| !l.rotated));
    let Some(l) = along_y else { return String::new() };
    let (rising, falling) = l.diagonal_stiffness();
    // (E, angle in degrees) every 0.5°; none without diagonals (no stiffness off the axes).
    let along: Option<Vec<(f64, f64)>> = (0..360)
        .map(|i| 0.5 * f64::from(i))
        .map(|degrees| {
            youngs_modulus_along(l.k_x, l.k_y, rising, falling, l.depth, degrees.to_radians()).map(|e| (e, degrees))
        })
        .collect();
    let by_e = |a: &&(f64, f64), b: &&(f64, f64)| a.0.total_cmp(&b.0);
    let Some(along) = along else { return String::new() };
    let (Some(&(e_low, low)), Some(&(e_high, high))) = (along.iter().min_by(by_e), along.iter().max_by(by_e)) else {
        return String::new();
    };
    // Springs s = C δ^β (β ≠ 1) have no stiffness at rest and a load-dependent one under load:
    // their network has no continuum E to quote, only the linear springs' of the same constants.
    let (whose, caveat) = if rs.iter().all(|r| r.spec.law.is_linear()) {
        ("the continuum's E", "")
    } else {
        ("the continuum E of linear springs of the same k", "; a power-law network has none independent of the load")
    };
    if e_high / e_low - 1.0 <= SAME_E {
        format!(": isotropic ({whose} = {} Pa in every direction{caveat})", cell(Some(e_low)))
    } else if (e_ratio - 1.0).abs() <= SAME_E {
        format!(": E_y = E_x, yet anisotropic: {whose} falls to {} Pa at {low:.0}° from x{caveat}", cell(Some(e_low)))
    } else {
        format!(
            ": the directions differ ({whose} from {} Pa at {low:.0}° to {} Pa at {high:.0}° from x{caveat})",
            cell(Some(e_low)),
            cell(Some(e_high))
        )
    }
}

/// A block with one diagonal family pulled along y: whether it shears freely, read from its
/// relaxed sides. With u_x = γ y and the strain ε = ΔL_y/L_y, a diagonal along (1, ±1)/√2 is
/// strained by (ε_xx + ε_yy ± γ)/2 = (ε ± γ)/2 (ε_xx = 0 when ν = 0): a shear γ = ∓ε leaves it
/// at its rest length, carrying nothing, so E_y is the vertical springs' k_y/d alone and ν = 0;
/// N_x columns of vertical springs carry the load, but the stress divides it over the block's
/// width L_x = (N_x − 1) a, so the measured E_y is N_x/(N_x − 1) times k_y/d, exactly.
fn free_shear_sentence(r: &RunRecord) -> Option<String> {
    let l = r.spec.lattice().filter(|l| l.nx >= 2 && l.ny >= 2)?;
    let sign = match l.diagonals {
        Diagonals::Rising => 1.0,
        Diagonals::Falling => -1.0,
        _ => return None,
    };
    if l.load_case != LoadCase::Tensile || l.rotated {
        return None;
    }
    let edges = r.metrics.lattice.edge_displacements.as_ref()?;
    let height = (l.ny - 1) as f64 * r.spec.spacing;
    let strain = edges.top_y.iter().sum::<f64>() / edges.top_y.len() as f64 / height;
    let lean = (edges.left_x.last()? - edges.left_x.first()?) / height;
    let diagonal = (strain + sign * lean) / 2.0;
    // A diagonal strain below 1e-3 of ε is the relaxation's leftover (its tolerance 2e-3).
    let carried = if diagonal.abs() < 1e-3 * strain.abs() {
        "keep their length and carry nothing".to_string()
    } else {
        format!("are strained by {} of ε and carry part of the load", sig(diagonal / strain))
    };
    let (measured, theory) = (r.metrics.lattice.youngs_modulus?, r.metrics.lattice.youngs_modulus_theory?);
    let columns = l.nx as f64;
    Some(format!(
        "With {} diagonals alone the pulled block shears freely: with the strain ε = {} its sides lean by \
         Δu_x/L_y = {}, so the diagonals, strained by (ε {} γ)/2 = {}, {carried}; E_y = {} Pa is the vertical \
         springs' k_y/d = {} Pa times {} (N_x/(N_x − 1) = {} for {} columns loaded over the width (N_x − 1) a, as \
         without diagonals), and ν = {}.",
        l.diagonals.name(),
        sig(strain),
        sig(lean),
        if sign > 0.0 { "+" } else { "−" },
        sig(diagonal),
        sig(measured),
        sig(theory),
        sig(measured / theory),
        sig(columns / (columns - 1.0)),
        l.nx,
        noise(r.metrics.lattice.poisson_ratio, 1.0)
    ))
}

/// Every relaxed lattice's |MD − static|/static of its modulus, with its run, and their median.
fn md_against_static<'a>(e: &Evidence<'a>) -> Option<(Vec<(f64, &'a RunRecord)>, f64)> {
    let pairs: Vec<(f64, &RunRecord)> = e
        .ok(|r| r.spec.lattice().is_some())
        .into_iter()
        .filter_map(|r| {
            let m = &r.metrics.lattice;
            let md = m.youngs_modulus.or(m.shear_modulus);
            let fem = m.youngs_modulus_fem.or(m.shear_modulus_fem);
            relative(md, fem).map(|x| (x.abs(), r))
        })
        .collect();
    let median = crate::measure::median(pairs.iter().map(|p| p.0).collect())?;
    Some((pairs, median))
}

/// What the two comparisons compare: the static truss is the same network, so MD against it
/// tests the relaxation alone; the finite-element comparison, a discretised body against its
/// continuum, is the network's static E against the continuum's, which converges as the block
/// grows (fitted |E_static − E|/E ∝ N^−p over the block's sizes).
fn continuum_convergence(block: &Block) -> Option<String> {
    let points: Vec<(f64, f64)> = block
        .tensile
        .iter()
        .filter_map(|r| {
            let m = &r.metrics.lattice;
            Some((r.spec.lattice()?.nx as f64, relative(m.youngs_modulus_fem, m.youngs_modulus_theory)?.abs()))
        })
        .collect();
    let fit = crate::measure::power_law_fit(&points)?;
    let (first, last) = (points.first()?, points.last()?);
    Some(format!(
        "The finite-element kind of comparison, a discretised body against the continuum it stands for, is the \
         continuum column: the network's static E departs from the continuum's by {} on {:.0} × {:.0} and {} on \
         {:.0} × {:.0}, ∝ N^{}, converging as a refined mesh does.",
        percent(first.1),
        first.0,
        first.0,
        percent(last.1),
        last.0,
        last.0,
        crate::report::words::exponent(fit.exponent, 2)
    ))
}

/// The abstract's sentence on MD against the static answer of the same network.
pub(super) fn fem_headline(e: &Evidence) -> Option<String> {
    let (pairs, median) = md_against_static(e)?;
    Some(format!(
        "Relaxed MD reaches the exact static answer of the same spring network (the truss a finite-element \
         model of bars would build) to {} at the median over {} lattices.",
        sig(median),
        pairs.len()
    ))
}

/// The diagonal bars' E_bar A = k_d a√2 of a square lattice with diagonals, in words: one E_bar A
/// for every bar would give k_d/k = 1/√2, not the network's ratio.
fn diagonal_bar_words(r: &RunRecord) -> String {
    match r.spec.lattice() {
        Some(l) if l.k_diag > 0.0 && l.lattice_type.is_square() => format!(
            ", and a diagonal bar of length a√2 with k_d = {} N/m needs E_bar A = k_d a√2 = {} N (one E_bar A for \
             every bar would give k_d/k = 1/√2)",
            sig(l.k_diag),
            sig(l.k_diag * r.spec.spacing * std::f64::consts::SQRT_2)
        ),
        _ => String::new(),
    }
}

/// MD against the static truss (FEM) answer, and how k_FEM relates to k_MD.
pub(super) fn md_and_fem(e: &Evidence) -> Option<Answer> {
    let (pairs, median) = md_against_static(e)?;
    let (worst, worst_run) = pairs.iter().copied().max_by(|a, b| a.0.total_cmp(&b.0))?;
    let s = &worst_run.spec;
    let mut sentences = vec![
        format!(
            "Each spring with its masses is a truss bar: k = E_bar A/L over its length L. With k = {} N/m and a = {} m \
             a bar of E_bar A = k a = {} N gives the same network{}, so k_FEM = k_MD and σ_FEM = (k_FEM/k_MD) σ_MD = \
             σ_MD; the static solver here is that truss model, solved exactly (sparse Cholesky, then Newton for \
             large rotations and non-linear springs).",
            sig(s.k),
            sig(s.spacing),
            sig(s.k * s.spacing),
            diagonal_bar_words(worst_run)
        ),
        format!(
            "Over {} relaxed lattice runs MD and the static answer differ by {} at the median and {} at worst \
             ({}): the difference is the relaxation's leftover motion, not the method.",
            pairs.len(),
            sig(median),
            sig(worst),
            worst_run.spec.scene
        ),
    ];
    sentences.extend(Block::of(e).and_then(|b| continuum_convergence(&b)));
    Some(Answer {
        title: "MD against the static truss (FEM) answer",
        question: "Compare MD with FEM for the same systems, and explain how k_FEM and k_MD are computed.",
        short: format!("median |MD − static| = {}", sig(median)),
        sentences,
        reference: "The exact static answer of the same network; the median within 1e-3.".into(),
        see_also: None,
        verdict: Verdict::of([median <= 1e-3]),
        figures: Vec::new(),
        table: None,
    })
}
