//! The analytical curves drawn over the MD data, and the measurements between them: the pair's
//! overlap δ(t) against the damped oscillator's, the chain's motion against its normal-mode
//! sum, the damped power-law contact's restitution and duration against v0 beside their
//! independent references, a lattice's relaxation under background damping against its slowest
//! envelope, and a lattice strip's dispersion relation ω(q), measured by a
//! space–time Fourier transform of a probed column, against the branches of its springs. The
//! findings (`findings/curves.rs`) state these numbers through the same functions.

use super::figure::{Figure, FigureKind, Part, background_damping_only, background_gamma, groups, representative};
use crate::draw::chart::{Chart, Mark, Scale, Series, line_chart};
use crate::measure::{ModePeak, branch_stiffness, curve_deviation, decay_rate, free_line_modes};
use crate::model::LawSpec;
use crate::runner::RunRecord;
use crate::spec::{Diagonals, KindSpec, Supports};
use crate::theory;

/// The curves' part of `scene`: figures only.
pub fn part(records: &[RunRecord], scene: &str) -> anyhow::Result<Part> {
    let groups = groups(records, scene);
    let shown: Vec<&RunRecord> = groups.iter().map(|(_, members)| representative(members)).collect();
    let mut figures = Vec::new();
    figures.extend(overlap_figure(scene, &shown)?);
    figures.extend(normal_mode_figure(scene, &shown)?);
    figures.extend(restitution_figures(scene, &shown)?);
    figures.extend(dispersion_figure(scene, &shown)?);
    figures.extend(envelope_figure(scene, &shown)?);
    Ok(Part { figures, rows: () })
}

/// At most this many markers of an MD curve: the analytical line is drawn through all of it.
const MARKERS: usize = 80;

/// Every `n`-th point of `points`, at most [`MARKERS`] of them.
fn thinned(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let every = points.len().div_ceil(MARKERS).max(1);
    points.iter().step_by(every).copied().collect()
}

/// A chart with linear axes.
fn chart(title: String, x_label: &str, y_label: &str, scale: Scale) -> Chart {
    Chart { title, x_label: x_label.into(), y_label: y_label.into(), scale }
}

/// A pair of linear springs whose trace holds both particles: its overlap has a closed form.
fn has_overlap(r: &RunRecord) -> bool {
    matches!(r.spec.scene_kind, KindSpec::Pair(_))
        && r.spec.law == LawSpec::Linear
        && r.spec.gamma_background == 0.0
        && r.trace.displacement_x.first().is_some_and(|row| row.len() == 2)
}

/// The initial gap (m) of a contact pair; 0 for a bonded one.
fn gap(r: &RunRecord) -> f64 {
    match r.spec.scene_kind {
        KindSpec::Pair(pair) => pair.gap.unwrap_or(0.0),
        _ => 0.0,
    }
}

/// The MD overlap δ(t) = x_e − |x_2 − x_1| (m, compression positive) of a pair at every sample.
pub fn pair_overlap(r: &RunRecord) -> Vec<(f64, f64)> {
    let t = &r.trace;
    t.time.iter().zip(&t.displacement_x).map(|(&time, u)| (time, -gap(r) - (u[1] - u[0]))).collect()
}

/// The analytical overlap at `t` (s): (v0/ω_d) e^(−γt'/m) sin(ω_d t') from the contact's start
/// t' = 0 (a contact pair's gap/v0 in), while the spring acts (a contact spring for one t_c).
pub fn exact_overlap(r: &RunRecord, t: f64) -> Option<f64> {
    let s = &r.spec;
    let since = t - gap(r) / s.v0;
    let duration = if s.contact { theory::linear_contact_duration(s.k, s.mass, s.gamma).ok()? } else { f64::INFINITY };
    (since >= 0.0 && since <= duration).then(|| theory::linear_pair_overlap(s.k, s.mass, s.gamma, s.v0, since).ok())?
}

/// The largest |δ_MD − δ_exact| over the largest |δ_exact| of a linear pair.
pub fn overlap_deviation(r: &RunRecord) -> Option<f64> {
    has_overlap(r).then(|| curve_deviation(&pair_overlap(r), |t| exact_overlap(r, t)))?
}

/// The overlap of the first undamped and the first damped linear pair of a scene against δ(t).
fn overlap_figure(scene: &str, shown: &[&RunRecord]) -> anyhow::Result<Option<Figure>> {
    let chosen: Vec<&RunRecord> = [false, true]
        .iter()
        .filter_map(|&damped| shown.iter().copied().find(|r| has_overlap(r) && (r.spec.gamma > 0.0) == damped))
        .collect();
    if chosen.is_empty() {
        return Ok(None);
    }
    let mut series = Vec::new();
    for r in &chosen {
        let label =
            format!("γ = {} N s/m, dt = t_c/{:.0}", crate::report::words::short(r.spec.gamma), r.spec.dt_per_tc());
        let exact = r.trace.time.iter().filter_map(|&t| exact_overlap(r, t).map(|d| (t, d))).collect();
        series.push(Series { label: format!("MD, {label}"), points: thinned(&pair_overlap(r)), mark: Mark::Markers });
        series.push(Series {
            label: format!("(v0/ω_d) e^(−γt/m) sin(ω_d t), {label}"),
            points: exact,
            mark: Mark::Line,
        });
    }
    Ok(Some(Figure {
        scene: scene.into(),
        kind: FigureKind::Overlap,
        file: format!("plots/{scene}-overlap.svg"),
        caption: format!(
            "The pair's overlap δ = x_e − |x_2 − x_1| against time, {scene}: MD (markers) over the damped oscillator \
             of the reduced mass m/2, δ(t) = (v0/ω_d) e^(−γt/m) sin(ω_d t) with ω_d = √(2k/m − (γ/m)²) (lines)."
        ),
        image: line_chart(
            &chart(format!("{scene}: overlap δ(t)"), "time t (s)", "overlap δ (m)", Scale::Linear),
            &series,
        )?,
    }))
}

/// A hit chain of linear springs with a normal-mode error: the run the figure draws.
fn has_modes(r: &RunRecord) -> bool {
    r.spec.chain().is_some_and(|c| c.relax.is_none() && c.wave.is_none())
        && r.spec.law == LawSpec::Linear
        && r.metrics.chain.chain_mode_error.is_some()
        && !r.trace.displacement_x.is_empty()
}

/// The kicked particle's and its right neighbour's displacement of the first chain with normal
/// modes, MD over the exact normal-mode sum.
fn normal_mode_figure(scene: &str, shown: &[&RunRecord]) -> anyhow::Result<Option<Figure>> {
    let Some(r) = shown.iter().copied().find(|r| has_modes(r)) else { return Ok(None) };
    let Some(chain) = r.spec.chain() else { return Ok(None) };
    let v0: Vec<f64> = (1..=chain.n).map(|p| if p == chain.node { r.spec.v0 } else { 0.0 }).collect();
    let modes = theory::ChainModes::new(r.spec.k, r.spec.mass, &v0);
    let exact: Vec<Vec<f64>> = r.trace.time.iter().map(|&t| modes.at(t).0).collect();
    let mut series = Vec::new();
    for p in [chain.node, chain.node + 1].into_iter().filter(|&p| p <= chain.n) {
        let md: Vec<(f64, f64)> = r.trace.time.iter().zip(&r.trace.displacement_x).map(|(&t, u)| (t, u[p])).collect();
        let line = r.trace.time.iter().zip(&exact).map(|(&t, u)| (t, u[p - 1])).collect();
        series.push(Series { label: format!("MD, particle {p}"), points: thinned(&md), mark: Mark::Markers });
        series.push(Series { label: format!("normal-mode sum, particle {p}"), points: line, mark: Mark::Line });
    }
    Ok(Some(Figure {
        scene: scene.into(),
        kind: FigureKind::NormalModes,
        file: format!("plots/{scene}-normal-modes.svg"),
        caption: format!(
            "The kicked particle {} and its neighbour against time, {scene}{}: MD (markers) over the exact \
             normal-mode sum u_j(t) = Σ B_n sin(ω_n t) sin(njπ/(N+1)) (lines).",
            chain.node,
            Some(r.spec.varied_in_words(|_| true))
                .filter(|w| !w.is_empty())
                .map(|w| format!(" ({w})"))
                .unwrap_or_default()
        ),
        image: line_chart(
            &chart(format!("{scene}: normal modes"), "time t (s)", "displacement u (m)", Scale::Linear),
            &series,
        )?,
    }))
}

/// A power-law contact pair, without background damping: its restitution has the independent
/// reference [`restitution_reference`].
pub fn is_power_contact(r: &RunRecord) -> bool {
    matches!(r.spec.scene_kind, KindSpec::Pair(_))
        && r.spec.contact
        && r.spec.law != LawSpec::Linear
        && r.spec.gamma_background == 0.0
}

/// The restitution of a damped power-law contact by its own integration
/// (`theory::power_law_restitution`).
pub fn restitution_reference(r: &RunRecord) -> Option<f64> {
    let s = &r.spec;
    theory::power_law_restitution(s.k, s.law.beta(), s.mass, s.gamma, s.v0)
}

/// `count` values from `low` to `high`, evenly spaced on a logarithmic axis.
fn log_spaced(low: f64, high: f64, count: usize) -> Vec<f64> {
    (0..count).map(|i| low * (high / low).powf(i as f64 / (count - 1) as f64)).collect()
}

/// A power-law contact's restitution (damped runs) and contact duration (undamped runs)
/// against v0, MD over their references, when the scene sweeps v0.
fn restitution_figures(scene: &str, shown: &[&RunRecord]) -> anyhow::Result<Vec<Figure>> {
    let runs: Vec<&RunRecord> = shown.iter().copied().filter(|r| is_power_contact(r)).collect();
    let (low, high) = runs.iter().fold((f64::INFINITY, 0.0f64), |(l, h), r| (l.min(r.spec.v0), h.max(r.spec.v0)));
    if high <= low {
        return Ok(Vec::new());
    }
    let mut gammas: Vec<f64> = runs.iter().map(|r| r.spec.gamma).collect();
    gammas.sort_by(f64::total_cmp);
    gammas.dedup();
    let (mut restitution, mut duration) = (Vec::new(), Vec::new());
    for gamma in gammas {
        let mine: Vec<&RunRecord> = runs.iter().copied().filter(|r| r.spec.gamma == gamma).collect();
        let curves = v0_curves(&mine, log_spaced(low, high, 40));
        if gamma > 0.0 { restitution.extend(curves) } else { duration.extend(curves) }
    }
    [(FigureKind::RestitutionV0, restitution), (FigureKind::DurationV0, duration)]
        .into_iter()
        .filter(|(_, series)| !series.is_empty())
        .map(|(kind, series)| v0_figure(scene, kind, &series))
        .collect()
}

/// The MD markers and the reference line against v0 of the power-law contacts `mine`, which
/// share one γ: restitution over the own integration when damped, else the contact duration
/// over the exact one, the line at the `speeds` given.
fn v0_curves(mine: &[&RunRecord], speeds: Vec<f64>) -> [Series; 2] {
    let s = &mine[0].spec;
    let (gamma, beta) = (s.gamma, s.law.beta());
    let label = format!("γ = {} N s/m", crate::report::words::short(gamma));
    let pick = |r: &RunRecord| if gamma > 0.0 { r.metrics.pair.restitution } else { r.metrics.pair.contact_duration };
    let reference = |v: f64| match gamma > 0.0 {
        true => theory::power_law_restitution(s.k, beta, s.mass, gamma, v),
        false => Some(theory::power_law_contact_duration(s.k, beta, s.mass, v)),
    };
    let name = if gamma > 0.0 { "own integration" } else { "exact 2 (δ_max/v0) B(1/(β+1), ½)/(β+1)" };
    [
        Series {
            label: format!("MD, {label}"),
            points: mine.iter().filter_map(|r| pick(r).map(|y| (r.spec.v0, y))).collect(),
            mark: Mark::Markers,
        },
        Series {
            label: format!("{name}, {label}"),
            points: speeds.into_iter().filter_map(|v| reference(v).map(|y| (v, y))).collect(),
            mark: Mark::Line,
        },
    ]
}

/// The restitution or contact-duration figure against v0 of `scene`.
fn v0_figure(scene: &str, kind: FigureKind, series: &[Series]) -> anyhow::Result<Figure> {
    let (slug, what, y_label, scale, caption) = match kind {
        FigureKind::RestitutionV0 => (
            "restitution",
            "restitution",
            "restitution r",
            Scale::LogX,
            "Restitution of the damped power-law contact against the impact speed v0: MD (markers) over \
             (m/2) δ̈ = −C δ^β − γ δ̇ integrated on its own (lines). A fixed dashpot damps slow impacts more.",
        ),
        _ => (
            "duration",
            "contact duration",
            "t_c (s)",
            Scale::LogLog,
            "Contact duration of the undamped power-law contact against v0: MD (markers) over the exact duration \
             2 (δ_max/v0) B(1/(β+1), ½)/(β+1), ∝ v0^(−1/5) for Hertz (line).",
        ),
    };
    Ok(Figure {
        scene: scene.into(),
        kind,
        file: format!("plots/{scene}-{slug}-v0.svg"),
        caption: format!("{caption} Scene {scene}."),
        image: line_chart(&chart(format!("{scene}: {what} against v0"), "v0 (m/s)", y_label, scale), series)?,
    })
}

/// A lattice strip's dispersion relation along its probed column, measured and in theory.
pub struct Dispersion {
    /// A sideways step: the transverse branch (else the longitudinal one).
    pub sideways: bool,
    /// The measured modes of the column.
    pub peaks: Vec<ModePeak>,
    /// The branch's stiffness k_eff (N/m) from the springs (`theory::square_branch_stiffnesses`).
    pub k_eff: f64,
    /// k_eff fitted to the measured peaks (N/m).
    pub k_fitted: Option<f64>,
    /// The spectrum's resolution 2π/T (rad/s) over the run's length T.
    pub resolution: f64,
    /// The largest |ω_MD − ω(q)| (rad/s) over the modes.
    pub worst: f64,
}

/// The dispersion of a square strip of linear springs periodic in x with a free bottom
/// (`periodic-x-free`), pushed by a step force on its top row, along its probed column: the
/// motion is uniform in x, so the column moves as a free chain of the branch's k_eff, whose
/// modes [`free_line_modes`] measures (velocities along the force). `None` for other runs.
pub fn dispersion(r: &RunRecord) -> Option<Dispersion> {
    let l = r.spec.lattice()?;
    let impulse = l.impulse.filter(|i| i.top_row_force.is_some())?;
    let (k_rising, k_falling) = match l.diagonals {
        Diagonals::Both => (l.k_diag, l.k_diag),
        Diagonals::None => (0.0, 0.0),
        _ => return None,
    };
    if !l.lattice_type.is_square() || r.spec.law != LawSpec::Linear || l.supports != Supports::PeriodicXFree {
        return None;
    }
    let column =
        r.trace.probes.iter().find(|p| p.name.starts_with("column") && crate::runner::is_asked_for(&r.spec, p))?;
    let sideways = impulse.is_sideways();
    let rows = if sideways { &column.velocity_x } else { &column.velocity_y };
    let peaks = free_line_modes(&r.trace.time, rows, r.spec.spacing);
    let [transverse, longitudinal] = theory::square_branch_stiffnesses(l.k_y, k_rising, k_falling);
    let k_eff = if sideways { transverse } else { longitudinal };
    let branch = |q: f64| theory::branch_frequency(k_eff, r.spec.mass, q, r.spec.spacing);
    let worst = peaks.iter().map(|p| (p.omega - branch(p.q)).abs()).fold(0.0, f64::max);
    let length = r.trace.time.last()? - r.trace.time.first()?;
    (!peaks.is_empty()).then(|| Dispersion {
        sideways,
        k_fitted: branch_stiffness(&peaks, r.spec.mass, r.spec.spacing),
        peaks,
        k_eff,
        resolution: 2.0 * std::f64::consts::PI / length,
        worst,
    })
}

/// The measured ω(q) of every strip of `scene` over its branch's 2√(k_eff/m)|sin(qa/2)|.
fn dispersion_figure(scene: &str, shown: &[&RunRecord]) -> anyhow::Result<Option<Figure>> {
    let measured: Vec<(&RunRecord, Dispersion)> = shown.iter().filter_map(|r| Some((*r, dispersion(r)?))).collect();
    if measured.is_empty() {
        return Ok(None);
    }
    let mut series = Vec::new();
    for (r, d) in &measured {
        let label = format!(
            "{}, diagonals {}",
            if d.sideways { "transverse" } else { "longitudinal" },
            r.spec.lattice().map_or("", |l| l.diagonals.name())
        );
        let top = std::f64::consts::PI / r.spec.spacing;
        let curve = (0..=60)
            .map(|i| top * i as f64 / 60.0)
            .map(|q| (q, theory::branch_frequency(d.k_eff, r.spec.mass, q, r.spec.spacing)));
        series.push(Series {
            label: format!("MD, {label}"),
            points: d.peaks.iter().map(|p| (p.q, p.omega)).collect(),
            mark: Mark::Markers,
        });
        series.push(Series {
            label: format!("2√(k_eff/m)|sin(qa/2)|, k_eff = {} N/m", crate::report::words::short(d.k_eff)),
            points: curve.collect(),
            mark: Mark::Line,
        });
    }
    Ok(Some(Figure {
        scene: scene.into(),
        kind: FigureKind::Dispersion,
        file: format!("plots/{scene}-dispersion.svg"),
        caption: format!(
            "Dispersion relation ω(q) of the plane waves along y, {scene}: the peak frequency of each standing mode \
             q = nπ/(N a) of the probed column's velocity (a space–time Fourier transform, markers) over the branches \
             of the springs, ω = 2√(k_eff/m)|sin(qa/2)| with k_eff = k + k_d (longitudinal) and k_d (transverse; 0 \
             without diagonals) (lines)."
        ),
        image: line_chart(
            &chart(format!("{scene}: dispersion ω(q)"), "wavenumber q (rad/m)", "ω (rad/s)", Scale::Linear),
            &series,
        )?,
    }))
}

/// A loaded lattice's relaxation under background damping alone: E_kin/E_pot against time, and
/// its late decay rate measured and predicted.
pub struct Envelope {
    /// (t, E_kin/E_pot) at every sample with E_pot > 0.
    pub ratio: Vec<(f64, f64)>,
    /// The decay rate (1/s) of the ratio over the second half of its decay (`measure::decay_rate`).
    pub measured: f64,
    /// γ_g/m − Re √((γ_g/m)² − 4k_min/m) (1/s) (`theory::background_decay_rate`).
    pub predicted: f64,
}

/// The relaxation envelope of a loaded lattice relaxed by background damping alone whose
/// softest stiffness k_min is known (E_pot settles at the static answer's, so E_kin/E_pot falls
/// as E_kin); `None` for other runs.
pub fn envelope(r: &RunRecord) -> Option<Envelope> {
    let lattice = r.spec.lattice().is_some() && r.spec.relax().is_some() && background_damping_only(r);
    let k_min = r.metrics.lattice.stiffness_min.filter(|&k| lattice && k > 0.0)?;
    let t = &r.trace;
    let ratio: Vec<(f64, f64)> = (0..t.time.len())
        .filter(|&s| t.potential[s] > 0.0)
        .map(|s| (t.time[s], t.kinetic[s] / t.potential[s]))
        .collect();
    Some(Envelope {
        measured: decay_rate(&ratio)?,
        predicted: theory::background_decay_rate(background_gamma(r), r.spec.mass, k_min),
        ratio,
    })
}

/// At most this many relaxations in the envelope figure.
const MOST_ENVELOPES: usize = 6;

/// E_kin/E_pot of the lattices of `scene` relaxed by background damping alone (those stopped
/// by the energy criterion, where any are), each with its predicted envelope C e^(−rate t)
/// through the highest of its late crests.
fn envelope_figure(scene: &str, shown: &[&RunRecord]) -> anyhow::Result<Option<Figure>> {
    let all: Vec<(&RunRecord, Envelope)> = shown.iter().filter_map(|r| Some((*r, envelope(r)?))).collect();
    let by_energy = |r: &RunRecord| r.spec.relax().is_some_and(|x| x.residual_force.is_none());
    let energy_only = all.iter().any(|(r, _)| by_energy(r));
    let drawn: Vec<&(&RunRecord, Envelope)> =
        all.iter().filter(|(r, _)| !energy_only || by_energy(r)).take(MOST_ENVELOPES).collect();
    if drawn.is_empty() {
        return Ok(None);
    }
    let mut series = Vec::new();
    for (r, e) in drawn {
        let (Some(&(first, _)), Some(&(last, _))) = (e.ratio.first(), e.ratio.last()) else { continue };
        let middle = 0.5 * (first + last);
        let height = e
            .ratio
            .iter()
            .filter(|p| p.0 >= middle)
            .map(|&(t, y)| y.ln() + e.predicted * t)
            .fold(f64::NEG_INFINITY, f64::max);
        let label = format!("γ_g = {} N s/m", crate::report::words::short(background_gamma(r)));
        let line =
            (0..=30).map(|i| first + (last - first) * i as f64 / 30.0).map(|t| (t, (height - e.predicted * t).exp()));
        series.push(Series { label: format!("MD, {label}"), points: e.ratio.clone(), mark: Mark::Line });
        series.push(Series {
            label: format!("e^(−{} t/s), {label}", crate::report::words::short(e.predicted)),
            points: line.collect(),
            mark: Mark::Line,
        });
    }
    Ok(Some(Figure {
        scene: scene.into(),
        kind: FigureKind::Envelope,
        file: format!("plots/{scene}-envelope.svg"),
        caption: format!(
            "Relaxation under background damping alone, {scene}: E_kin/E_pot of MD against time with the predicted \
             late envelope C e^(−rate t), rate = γ_g/m − Re √((γ_g/m)² − 4k_min/m) (the energy's γ_g/m below \
             γ_crit = 2√(k_min m), the slowest mode's above), through the highest late crest."
        ),
        image: line_chart(
            &chart(format!("{scene}: relaxation envelopes"), "time t (s)", "E_kin / E_pot", Scale::LogY),
            &series,
        )?,
    }))
}
