//! The opening of a comparison: what differs between the two campaigns, in sentences with
//! their numbers, computed from the scenes' statistics at render time; the measured quantities
//! that differ beyond their noise and the inputs that differ, in compact tables (equal inputs
//! and costs left out); and the few figures where the two campaigns part most.

use serde::Serialize;

use super::quantity::{Class, NOISE, ROUND_OFF, unit};
use super::restitution::Targets;
use super::section::SceneSection;
use super::stats::{SEED_ERRORS, Stats};
use super::words::{count, counted, fixed, short, value};
use crate::measure::sorted_distinct;

/// At most this many sentences name a differing quantity, and at most this many figures show
/// one; the table and the appendix hold the rest.
const HEADLINES: usize = 6;

/// At most this many entries in a sentence that lists quantities; the appendix has them all.
const LISTED: usize = 12;

/// The opening of the report.
#[derive(Serialize)]
pub(super) struct Overview {
    /// What differs physically: moduli, sound speed, dissipation, contact; first on the page.
    physics: Vec<String>,
    /// How much differs, in one sentence.
    lead: String,
    /// The quantities where the campaigns part most, one sentence each.
    headlines: Vec<String>,
    /// What agrees, what one side alone measures, which inputs differ.
    rest: Vec<String>,
    differ: Vec<DifferRow>,
    inputs: Vec<InputRow>,
    figures: Vec<Figure>,
    /// The noise floor, as the method paragraph states it.
    noise: String,
    /// How many standard errors of the seeds' spread two sides may differ by.
    seed_errors: String,
    /// The relative difference below which two inputs are equal.
    round_off: String,
}

/// A measured quantity of one scene whose two sides differ beyond its noise.
#[derive(Serialize)]
struct DifferRow {
    scene: String,
    quantity: String,
    unit: &'static str,
    a: String,
    b: String,
    ratio: String,
    range: String,
    noise: String,
}

/// An input that differs, over the scenes where it does.
#[derive(Serialize)]
struct InputRow {
    quantity: String,
    unit: &'static str,
    scenes: String,
    a: String,
    b: String,
    ratio: String,
}

/// A figure shown in the opening.
#[derive(Serialize)]
struct Figure {
    file: String,
    caption: String,
}

type Entry<'a> = (&'a SceneSection, &'a Stats);

/// A sentence's opening words, the entries it lists and what it says after each.
type Listed<'a> = (String, Vec<Entry<'a>>, &'a dyn Fn(&Stats) -> String);

/// How far B parts from A: |ln B/A|, 0 without a ratio.
fn parting(stats: &Stats) -> f64 {
    stats.ratio.filter(|r| *r > 0.0).map_or(0.0, |r| r.ln().abs())
}

fn measured(stats: &Stats) -> bool {
    matches!(stats.class, Class::Result | Class::Deviation)
}

fn on_both_sides(stats: &Stats) -> bool {
    stats.a.is_some() && stats.b.is_some()
}

/// Measured on both sides, alike, in some row, judged there, and not found to differ.
fn agrees(stats: &Stats) -> bool {
    measured(stats) && on_both_sides(stats) && stats.compared > 0 && !stats.differs && !stats.unjudged
}

/// Measured on both sides, alike, in some row, but judged in none ([`Stats::unjudged`]).
fn unjudged(stats: &Stats) -> bool {
    measured(stats) && on_both_sides(stats) && stats.compared > 0 && stats.unjudged
}

/// A result that may headline: measured by MD with a ratio, with medians that mean something
/// (not of values of both signs), and no repeat of another: a `_fem` twin (the static answer of
/// the same network) and `sound_speed_<criterion>` (the sound speed by each arrival criterion)
/// would repeat the MD value and the recommended criterion's `sound_speed`.
fn headline(stats: &Stats) -> bool {
    let repeat = stats.metric.ends_with("_fem") || stats.metric.starts_with("sound_speed_");
    stats.class == Class::Result && stats.ratio.is_some() && !stats.signed && !repeat
}

/// At most [`HEADLINES`] of `ranked` (best first): the best of each scene first, then the
/// next best whatever their scene; in the order of `ranked`.
fn spread<T>(ranked: Vec<T>, scene: impl Fn(&T) -> &str) -> Vec<T> {
    let mut chosen: Vec<usize> = Vec::new();
    for i in 0..ranked.len() {
        if chosen.len() < HEADLINES && !chosen.iter().any(|&j| scene(&ranked[j]) == scene(&ranked[i])) {
            chosen.push(i);
        }
    }
    for i in 0..ranked.len() {
        if chosen.len() < HEADLINES && !chosen.contains(&i) {
            chosen.push(i);
        }
    }
    chosen.sort_unstable();
    ranked.into_iter().enumerate().filter(|(i, _)| chosen.contains(i)).map(|(_, x)| x).collect()
}

/// The opening of the report of `scenes`.
pub(super) fn overview(scenes: &[SceneSection]) -> Overview {
    let all: Vec<Entry> = scenes.iter().flat_map(|s| s.stats.iter().map(move |st| (s, st))).collect();
    let mut differ: Vec<Entry> = all.iter().copied().filter(|(_, st)| measured(st) && st.differs).collect();
    // The results that may headline first, then twins, errors and spreads; each by how far they part.
    differ.sort_by(|x, y| (headline(y.1), parting(y.1)).partial_cmp(&(headline(x.1), parting(x.1))).expect("finite"));
    let top = spread(differ.iter().copied().filter(|(_, st)| headline(st)).collect(), |(scene, _)| &scene.name);
    Overview {
        physics: physics(&all),
        lead: lead(scenes, &all, &differ),
        headlines: top.iter().map(|(scene, st)| sentence(&scene.name, st)).collect(),
        rest: rest(scenes, &all),
        differ: differ.iter().map(|(scene, st)| differ_row(&scene.name, st)).collect(),
        inputs: input_rows(&all),
        figures: figures(&differ),
        noise: format!("{NOISE:.0e}"),
        seed_errors: format!("{SEED_ERRORS}"),
        round_off: format!("{ROUND_OFF:.0e}"),
    }
}

/// How many measured quantities differ, agree and have one side only, in how many scenes.
fn lead(scenes: &[SceneSection], all: &[Entry], differ: &[Entry]) -> String {
    let names: Vec<&str> = scenes.iter().map(|s| s.name.as_str()).collect();
    let equal = all.iter().filter(|(_, st)| agrees(st)).count();
    let one_side = all.iter().filter(|(_, st)| measured(st) && !on_both_sides(st)).count();
    let unlike = all.iter().filter(|(_, st)| measured(st) && on_both_sides(st) && st.compared == 0).count();
    let unlike = match unlike {
        0 => String::new(),
        n => format!(" ({} differently on the two sides, not compared)", count(n, "is measured", "are measured")),
    } + &match all.iter().filter(|(_, st)| unjudged(st)).count() {
        0 => String::new(),
        n => format!(
            "; {} only where some seeds' packings did not jam, not judged",
            count(n, "is measured", "are measured")
        ),
    };
    let differing: Vec<&str> = sorted_distinct(differ.iter().map(|(s, _)| s.name.as_str()));
    let shared = format!("The two campaigns share {} ({})", counted(names.len(), "scene"), names.join(", "));
    if differ.is_empty() && equal == 0 {
        return format!(
            "{shared}. No measured quantity is judged to differ or to agree there ({one_side} are measured on one side only{unlike})."
        );
    }
    if differ.is_empty() {
        return format!(
            "{shared}. No measured quantity differs beyond its noise there: the two campaigns agree in all {equal} \
             quantities measured alike on both sides ({one_side} are measured on one side only{unlike})."
        );
    }
    format!(
        "{shared}. Over the rows compared, {} beyond {} noise in {} of them, {} within it and {} on \
         one side only{unlike}.",
        count(differ.len(), "measured quantity differs", "measured quantities differ"),
        if differ.len() == 1 { "its" } else { "their" },
        differing.len(),
        count(equal, "agrees", "agree"),
        count(one_side, "is measured", "are measured")
    )
}

/// A quantity with its unit in words, or alone when its unit is not known.
fn with_unit(metric: &str) -> String {
    match unit(metric) {
        Some("1") => metric.to_string(),
        Some(unit) => format!("{metric} ({unit})"),
        None => metric.to_string(),
    }
}

/// A quantity's unit in a table cell: "–" when it is not known.
fn unit_cell(metric: &str) -> &'static str {
    unit(metric).unwrap_or("–")
}

/// One differing quantity in a sentence with its numbers.
fn sentence(scene: &str, st: &Stats) -> String {
    let spread = match st.range {
        Some((lo, hi)) => format!(" (median of {} rows, from {} to {})", st.ratios, short(lo), short(hi)),
        None => String::new(),
    };
    let number = |x: Option<f64>| x.map_or_else(|| "–".into(), short);
    format!(
        "In {scene}, {} is {} in A and {} in B: B/A = {}{spread}.",
        with_unit(&st.metric),
        number(st.a),
        number(st.b),
        number(st.ratio)
    )
}

fn differ_row(scene: &str, st: &Stats) -> DifferRow {
    DifferRow {
        scene: scene.to_string(),
        quantity: st.metric.clone(),
        unit: unit_cell(&st.metric),
        a: value(st.a),
        b: value(st.b),
        ratio: fixed(st.ratio),
        range: st.range.map_or_else(String::new, |(lo, hi)| format!("{} … {}", fixed(Some(lo)), fixed(Some(hi)))),
        noise: match st.class {
            Class::Deviation => format!("{NOISE:.0e} abs."),
            _ if st.seeded => format!("{:.1e} (seeds)", st.noise),
            _ => format!("{:.1e}", st.noise),
        },
    }
}

/// Entries as `scene: quantity` (with `extra`), at most [`LISTED`] of them.
fn listing(entries: &[Entry], extra: impl Fn(&Stats) -> String) -> String {
    let mut words: Vec<String> =
        entries.iter().take(LISTED).map(|(scene, st)| format!("{}: {}{}", scene.name, st.metric, extra(st))).collect();
    if entries.len() > LISTED {
        words.push(format!("and {} more (appendix)", entries.len() - LISTED));
    }
    words.join(", ")
}

/// The quantities measured only in groups of seeds where some packings did not jam
/// ([`Stats::unjudged`]), in the words of [`rest`].
const NOT_JUDGED: &str = "Not judged, measured only where some seeds of the packings did not jam (those that did are the \
             share whose own φ_J lies below the fraction: a selected sample, not the seeds')";

/// What agrees within noise, what is at round-off on both sides, what is measured differently
/// or by one side alone, which rows are not compared, and which inputs differ or not.
fn rest(scenes: &[SceneSection], all: &[Entry]) -> Vec<String> {
    let pick =
        |keep: &dyn Fn(&Stats) -> bool| -> Vec<Entry> { all.iter().copied().filter(|(_, st)| keep(st)).collect() };
    let both = |st: &Stats| format!(" (A {}, B {})", short(st.a.unwrap_or(f64::NAN)), short(st.b.unwrap_or(f64::NAN)));
    let ratio = |st: &Stats| st.ratio.map_or_else(String::new, |r| format!(" (B/A = {})", fixed(Some(r))));
    let groups: [Listed; 8] = [
        (
            "Equal within noise".into(),
            pick(&|st| agrees(st) && !st.at_floor && st.class == Class::Result && !st.seeded),
            &ratio,
        ),
        (
            format!(
                "The same within the spread between seeds (the seed means of A and B, rows of equal other grid \
                 values, less than {SEED_ERRORS} standard errors of their difference apart; B/A the rows' median, \
                 noise relative to A's mean)"
            ),
            pick(&|st| agrees(st) && !st.at_floor && st.class == Class::Result && st.seeded),
            &|st| format!(" (B/A = {}, noise {:.1e})", fixed(st.ratio), st.noise),
        ),
        (
            format!(
                "Errors and spreads within {NOISE:.0e} of each other (absolute: ideally 0, they are compared by \
                 their difference, not their ratio)"
            ),
            pick(&|st| agrees(st) && !st.at_floor && st.class == Class::Deviation),
            &both,
        ),
        (
            "Both at round-off, at or below their floor on both sides (a static solve's residual below Newton's \
             tolerance 1e-12 of the load, a value below the run's own floor column such as pressure_floor): zero on both, no \
             ratio to take"
                .into(),
            pick(&|st| agrees(st) && st.at_floor),
            &both,
        ),
        (
            "Not compared, measured differently on the two sides (an error against one reference says nothing \
             about an error against another)"
                .into(),
            pick(&|st| measured(st) && st.unlike.is_some()),
            &|st| st.unlike.as_ref().map_or_else(String::new, |(a, b)| format!(" ({a} in A, {b} in B)")),
        ),
        (
            NOT_JUDGED.into(),
            pick(&unjudged),
            &ratio,
        ),
        ("Measured in A only (nothing to compare)".into(), pick(&|st| measured(st) && st.b.is_none()), &|_| String::new()),
        ("Measured in B only (nothing to compare)".into(), pick(&|st| measured(st) && st.a.is_none()), &|_| String::new()),
    ];
    let mut rest: Vec<String> = groups
        .iter()
        .filter(|(_, entries, _)| !entries.is_empty())
        .map(|(words, entries, extra)| format!("{words}: {}.", listing(entries, extra)))
        .collect();
    rest.extend(states_sentence(scenes));
    rest.push(inputs_sentence(all));
    rest
}

/// The rows of runs `ok` on both sides that are not compared because their packings are not
/// both jammed, scene by scene; `None` where there are none.
fn states_sentence(scenes: &[SceneSection]) -> Option<String> {
    let ok = |status: &str| status.starts_with("ok, ");
    let parts: Vec<String> = scenes
        .iter()
        .flat_map(|scene| scene.statuses.iter().map(move |c| (scene, c)))
        .filter(|(_, c)| ok(&c.a) && ok(&c.b))
        .map(|(scene, c)| {
            format!("{}: {} {} in A and {} in B", scene.name, counted(c.rows, "row"), &c.a[4..], &c.b[4..])
        })
        .collect();
    (!parts.is_empty()).then(|| {
        format!(
            "Packings not compared: {}. A packing's pressure, contacts, energy and moduli are its own only where \
             it jammed (pressure above the run's pressure_floor, carried by a rigid backbone): below the floor \
             they are zero, what the relaxation left, and a jammed packing against an unjammed one is not the same \
             kind of state.",
            parts.join("; ")
        )
    })
}

/// The metrics of `entries`, each once, in order of first appearance.
fn distinct(entries: &[Entry]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for (_, st) in entries {
        if !names.contains(&st.metric) {
            names.push(st.metric.clone());
        }
    }
    names
}

/// The set-up values (inputs and what follows from them) that differ in a scene: two values of
/// one row that are not the same number.
fn differing_inputs<'a>(all: &[Entry<'a>]) -> Vec<Entry<'a>> {
    all.iter().copied().filter(|(_, st)| st.class == Class::Setup && st.differs).collect()
}

/// Which inputs differ, and which are equal on both sides and left out with the costs.
fn inputs_sentence(all: &[Entry]) -> String {
    let differ = distinct(&differing_inputs(all));
    let setup: Vec<Entry> =
        all.iter().copied().filter(|(_, st)| st.class == Class::Setup && !st.differs && on_both_sides(st)).collect();
    let equal: Vec<String> = distinct(&setup).into_iter().filter(|n| !differ.contains(n)).collect();
    let differ = if differ.is_empty() {
        "No input differs between the two campaigns".to_string()
    } else {
        format!("The inputs that differ, and what follows from them before a run: {} (table)", differ.join(", "))
    };
    format!(
        "{differ}. Equal on both sides wherever both have a value, and left out of these tables: {}; so are the costs \
         wall_s, loop_s, steps and relax_steps, timings rather than results. The appendix has them all.",
        if equal.is_empty() { "none".to_string() } else { equal.join(", ") }
    )
}

/// `values` as their smallest and largest, written by `write`; one value where they agree.
fn span(values: &[f64], write: fn(Option<f64>) -> String) -> String {
    let (lo, hi) = crate::measure::extremes(values);
    match values.len() {
        0 => "–".to_string(),
        _ if lo == hi => write(Some(lo)),
        _ => format!("{} … {}", write(Some(lo)), write(Some(hi))),
    }
}

/// The inputs that differ, one row each over the scenes where they do: A's and B's medians and
/// the ratios, from the smallest to the largest over those scenes.
fn input_rows(all: &[Entry]) -> Vec<InputRow> {
    let differ = differing_inputs(all);
    distinct(&differ)
        .into_iter()
        .map(|name| {
            let mine: Vec<&Stats> = differ.iter().filter(|(_, st)| st.metric == name).map(|(_, st)| *st).collect();
            let values = |get: fn(&Stats) -> Vec<f64>| -> Vec<f64> { mine.iter().flat_map(|st| get(st)).collect() };
            let scenes: Vec<&str> =
                differ.iter().filter(|(_, st)| st.metric == name).map(|(scene, _)| scene.name.as_str()).collect();
            InputRow {
                unit: unit_cell(&name),
                scenes: scenes.join(", "),
                a: span(&values(|st| st.a.into_iter().collect()), value),
                b: span(&values(|st| st.b.into_iter().collect()), value),
                ratio: span(
                    &values(|st| st.range.map_or_else(|| st.ratio.into_iter().collect(), |(l, h)| vec![l, h])),
                    fixed,
                ),
                quantity: name,
            }
        })
        .collect()
}

/// The figures of the quantities that part most, spread over the scenes ([`spread`]).
fn figures(differ: &[Entry]) -> Vec<Figure> {
    let drawn: Vec<(Entry, &str, &str)> = differ
        .iter()
        .filter(|(_, st)| headline(st))
        .filter_map(|&(scene, st)| {
            let group = scene.plots.iter().find(|g| g.plots.iter().any(|p| p.metric() == st.metric))?;
            let plot = group.plots.iter().find(|p| p.metric() == st.metric)?;
            Some(((scene, st), group.parameter(), plot.file.as_str()))
        })
        .collect();
    spread(drawn, |((scene, _), _, _)| &scene.name)
        .into_iter()
        .map(|((scene, st), parameter, file)| {
            let caption = format!(
                "{}: {} against {parameter}, every ok run of A and of B; B/A = {} (median).",
                scene.name,
                with_unit(&st.metric),
                st.ratio.map_or_else(|| "–".into(), short)
            );
            Figure { file: file.to_string(), caption }
        })
        .collect()
}

/// The physical quantities a reader compares first, with their names in words.
const PHYSICS: [(&str, &str); 7] = [
    ("youngs_modulus", "Young's modulus E"),
    ("poisson_ratio", "Poisson's ratio ν"),
    ("shear_modulus", "The shear modulus G"),
    ("sound_speed", "The sound speed"),
    ("dissipation_time", "The dissipation time"),
    ("contact_duration", "The contact time t_c"),
    ("restitution", "The restitution r"),
];

/// A restitution further than this from its target (relative) misses it: a linear pair meets its
/// target to ~1e-4 at t_c/50, so 1 % is no integration error but a contact the target's formula
/// (γ from the linear two-body solution) does not describe.
const RESTITUTION_MISS: f64 = 0.01;

/// What differs physically, quantity by quantity, scene by scene (medians over the rows ok on
/// both sides; the restitution's target by target), and each side's restitution that misses
/// its target.
fn physics(all: &[Entry]) -> Vec<String> {
    let mut said = Vec::new();
    for (metric, words) in PHYSICS {
        let scenes: Vec<String> = all
            .iter()
            .filter(|(_, st)| st.metric == metric && on_both_sides(st))
            .flat_map(|&(scene, st)| match metric {
                "restitution" => by_target(scene, st),
                _ => vec![side_by_side(&scene.name, st)],
            })
            .collect();
        if !scenes.is_empty() {
            said.push(format!("{words}, in {}.", scenes.join("; ")));
        }
    }
    let measured = all.iter().filter(|(_, st)| st.metric == "restitution");
    said.extend(measured.flat_map(|(scene, _)| missed_restitution(scene)));
    said
}

/// The medians of `st` on both sides and their ratio, after `label` (a scene, or a scene at
/// its target).
fn side_by_side(label: &str, st: &Stats) -> String {
    let unit = unit(&st.metric).filter(|u| *u != "1").map_or(String::new(), |u| format!(" {u}"));
    let verdict = match (st.differs, st.unjudged) {
        (true, _) => "differs beyond its noise",
        (false, true) => "not judged: only some seeds of its packings jammed",
        (false, false) => "the same within its noise",
    };
    format!(
        "{label}: {}{unit} in A, {}{unit} in B, B/A = {} ({verdict})",
        short(st.a.unwrap_or(f64::NAN)),
        short(st.b.unwrap_or(f64::NAN)),
        st.ratio.map_or_else(|| "–".into(), short)
    )
}

/// A scene's restitution side by side: over all its rows (`st`) where they share one target on
/// each side, otherwise target by target, since a median over runs set for different targets
/// (r = 1 undamped with r = 0.5 damped) is the restitution of neither.
fn by_target(scene: &SceneSection, st: &Stats) -> Vec<String> {
    let groups = &scene.restitution.both;
    if groups.len() <= 1 {
        return vec![side_by_side(&scene.name, st)];
    }
    let shared = groups.iter().filter(|g| on_both_sides(&g.stats));
    shared
        .map(|g| side_by_side(&format!("{} {}", place(&scene.name, &g.grid), at_target(g.target)), &g.stats))
        .collect()
}

/// The targets of a group of rows in words: one where both sides' read the same.
fn at_target((a, b): Targets) -> String {
    let write = |t: Option<f64>| t.map_or_else(|| "none".to_string(), short);
    match (write(a), write(b)) {
        _ if a.is_none() && b.is_none() => "with no target".to_string(),
        (a, b) if a == b => format!("at the target {a}"),
        (a, b) => format!("at the targets {a} in A and {b} in B"),
    }
}

/// Each side's restitution in `scene` that misses the target its runs were set for by more
/// than [`RESTITUTION_MISS`], target by target: a median over runs set for different targets
/// would be said to miss them all. Rows with no target (an overdamped mode) are not judged.
fn missed_restitution(scene: &SceneSection) -> Vec<String> {
    let by = &scene.restitution;
    let a = by.a.iter().map(|g| ("A", g, g.stats.a, g.target.0, g.linear.0));
    let b = by.b.iter().map(|g| ("B", g, g.stats.b, g.target.1, g.linear.1));
    a.chain(b)
        .filter_map(|(side, g, r, goal, linear)| {
            let (r, goal) = (r?, goal?);
            let scene = place(&scene.name, &g.grid);
            ((r / goal - 1.0).abs() > RESTITUTION_MISS).then(|| missed_sentence(side, &scene, r, goal, linear))
        })
        .collect()
}

/// A scene with the grid values of a group of its rows: "pair (material.law = hertz)".
fn place(scene: &str, grid: &[String]) -> String {
    if grid.is_empty() { scene.to_string() } else { format!("{scene} ({})", grid.join(", ")) }
}

/// One side's restitution `r` that misses its target `goal`, in words, with why: a non-linear
/// contact does not follow the formula γ came from; a linear one does, so its miss is the
/// integration's at the run's time step.
fn missed_sentence(side: &str, scene: &str, r: f64, goal: f64, linear: bool) -> String {
    let why = if linear {
        "its linear springs follow the two-body formula its damping γ comes from, so the miss is the integration's \
         error at its time step"
    } else {
        "its damping γ comes from the linear two-body formula, which this contact does not follow"
    };
    format!(
        "In {side}, {scene}'s restitution r = {} misses the target it was set for, {} ({}): {why}.",
        short(r),
        short(goal),
        crate::report::words::percent(r / goal - 1.0)
    )
}
