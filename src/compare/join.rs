//! How the rows of A meet the rows of B: per scene, on the grid parameters both campaigns vary
//! there; the joined table of both sides' values and their ratios B/A, and one scene's rows of it.

use std::collections::BTreeSet;
use std::ops::Range;
use std::path::PathBuf;

use super::quantity::{floor, measure_column};
use super::table::{Table, Values};
use crate::sim::RunStatus;

/// How the rows of one scene met.
pub(super) struct SceneJoin {
    pub(super) scene: String,
    /// The grid parameters both campaigns vary in this scene: the join keys besides the scene.
    pub(super) keys: Vec<String>,
    /// Parameters only A varies in this scene (one run of B may meet several of A), and only B.
    pub(super) only_a: Vec<String>,
    pub(super) only_b: Vec<String>,
    pub(super) rows_a: usize,
    pub(super) rows_b: usize,
    /// This scene's entries of [`Join::pairs`].
    pub(super) pairs: Range<usize>,
}

/// Which rows of A met which rows of B.
pub(super) struct Join {
    /// (row of A, row of B), scene by scene in A's order.
    pub(super) pairs: Vec<(usize, usize)>,
    pub(super) scenes: Vec<SceneJoin>,
    pub(super) only_a: Vec<String>,
    pub(super) only_b: Vec<String>,
}

/// Grid parameters nested in a scene have a dotted column (`time.dt_per_tc`).
pub(super) fn is_dotted(name: &str) -> bool {
    name.contains('.')
}

/// The top-level fields of a scene a grid may vary (`RawScene` in `spec/raw.rs`). Their columns
/// have no dot, and `v0`, `n`, `supports` and `seed` share theirs with the resolved value every run has,
/// so that such a field is varied shows only as more than one value within a scene.
const TOP_LEVEL_PARAMETERS: [&str; 7] = ["v0", "gap", "n", "node", "wall_distance", "supports", "seed"];

/// A column that may hold a grid parameter.
fn may_be_parameter(name: &str) -> bool {
    is_dotted(name) || TOP_LEVEL_PARAMETERS.contains(&name)
}

/// The distinct values of `column` at `rows`, in order of first appearance.
fn distinct(column: &Values, rows: impl Iterator<Item = usize>) -> Vec<String> {
    let mut seen = Vec::new();
    for value in rows.filter_map(|row| column.key(row)) {
        if !seen.contains(&value) {
            seen.push(value);
        }
    }
    seen
}

/// True when `table` varies parameter `name` at `rows` (one scene): a dotted column has a value
/// there (null only where the scene's grid does not name it), a top-level one takes two values.
fn varies(table: &Table, rows: &[usize], name: &str) -> bool {
    match table.column(name) {
        Some(column) if is_dotted(name) => rows.iter().any(|&r| !column.is_null(r)),
        Some(column) => distinct(column, rows.iter().copied()).len() > 1,
        None => false,
    }
}

/// Joins the rows of A and B scene by scene. The keys are decided per scene: a parameter is a
/// key where both campaigns vary it in that scene, so a parameter only one campaign varies there
/// leaves one row of the other side meeting several. Equal cells match, nulls included (a grid
/// may list `null`).
pub(super) fn join(a: &Table, b: &Table) -> anyhow::Result<Join> {
    let (scene_a, scene_b) = (a.require("scene")?, b.require("scene")?);
    let (scenes_a, scenes_b) = (distinct(scene_a, 0..a.height), distinct(scene_b, 0..b.height));
    let common: Vec<&str> = a.names().filter(|n| may_be_parameter(n) && b.column(n).is_some()).collect();
    let mut pairs = Vec::new();
    let mut scenes = Vec::new();
    for scene in scenes_a.iter().filter(|s| scenes_b.contains(s)) {
        let rows = |table: &Table, column: &Values| -> Vec<usize> {
            (0..table.height).filter(|&r| column.key(r).as_ref() == Some(scene)).collect()
        };
        let (rows_a, rows_b) = (rows(a, scene_a), rows(b, scene_b));
        let keys: Vec<&str> =
            common.iter().copied().filter(|&n| varies(a, &rows_a, n) && varies(b, &rows_b, n)).collect();
        let columns: Vec<(&Values, &Values)> =
            keys.iter().map(|&n| Ok((a.require(n)?, b.require(n)?))).collect::<anyhow::Result<_>>()?;
        let start = pairs.len();
        for &i in &rows_a {
            for &j in &rows_b {
                if columns.iter().all(|(ka, kb)| ka.key(i) == kb.key(j)) {
                    pairs.push((i, j));
                }
            }
        }
        let only = |table: &Table, rows: &[usize]| -> Vec<String> {
            let names = table.names().filter(|n| may_be_parameter(n) && !keys.contains(n));
            names.filter(|n| varies(table, rows, n)).map(str::to_string).collect()
        };
        scenes.push(SceneJoin {
            scene: scene.clone(),
            only_a: only(a, &rows_a),
            only_b: only(b, &rows_b),
            keys: keys.iter().map(|n| n.to_string()).collect(),
            rows_a: rows_a.len(),
            rows_b: rows_b.len(),
            pairs: start..pairs.len(),
        });
    }
    let only = |own: &[String], other: &[String]| own.iter().filter(|s| !other.contains(s)).cloned().collect();
    Ok(Join { pairs, only_a: only(&scenes_a, &scenes_b), only_b: only(&scenes_b, &scenes_a), scenes })
}

/// The text columns besides the scene, the run's identity and status, and the top-level grid
/// parameters (`supports`): what a run is (`law`, `packing_state`, `error_measure`, ...).
fn is_description(name: &str, values: &Values) -> bool {
    matches!(values, Values::Text(_))
        && !is_dotted(name)
        && !["scene", "status", "run_id"].contains(&name)
        && !TOP_LEVEL_PARAMETERS.contains(&name)
}

/// Builds the joined table: `scene`; every dotted grid parameter, holding the value both sides
/// share where it is a key and otherwise the value of the one side that varies it; each
/// top-level parameter that is a key of some scene (`seed`) under its own name, holding the value
/// both sides share in the scenes it is a key of; `status_a`, `status_b`, `run_id_a`,
/// `run_id_b`; each side's text columns (`law_a`, `packing_state_b`, `error_measure_a`, and the
/// top-level parameters that are text, `supports`); then for every numeric column both tables
/// have (the metrics, with the wall times and the resolved inputs such as `t_c` and `dt`, which
/// differ between campaigns of different laws, and `v0`, `n`) its two values and their ratio
/// ([`SceneRows::ratio`]).
pub(super) fn joined_table(a: &Table, b: &Table, join: &Join) -> anyhow::Result<Joined> {
    let rows_a = || join.pairs.iter().map(|p| p.0);
    let rows_b = || join.pairs.iter().map(|p| p.1);
    let mut columns = vec![("scene".to_string(), a.require("scene")?.gather(rows_a()))];
    columns.extend(grid_columns(a, b, join));
    for name in ["status", "run_id"] {
        columns.push((format!("{name}_a"), a.require(name)?.gather(rows_a())));
        columns.push((format!("{name}_b"), b.require(name)?.gather(rows_b())));
    }
    let is_metric = |name: &str| {
        !is_dotted(name)
            && matches!((a.column(name), b.column(name)), (Some(Values::Numbers(_)), Some(Values::Numbers(_))))
    };
    let texts = a
        .columns
        .iter()
        .chain(&b.columns)
        .filter(|(n, v)| is_description(n, v) || (TOP_LEVEL_PARAMETERS.contains(&n.as_str()) && !is_metric(n)));
    let mut described: Vec<&str> = Vec::new();
    for (name, _) in texts {
        if described.contains(&name.as_str()) {
            continue;
        }
        described.push(name);
        let none = || Values::Text(vec![None; join.pairs.len()]);
        columns.push((format!("{name}_a"), a.column(name).map_or_else(none, |v| v.gather(rows_a()))));
        columns.push((format!("{name}_b"), b.column(name).map_or_else(none, |v| v.gather(rows_b()))));
    }
    let metrics: Vec<String> = a.names().filter(|n| is_metric(n)).map(str::to_string).collect();
    for name in &metrics {
        columns.push((format!("{name}_a"), a.require(name)?.gather(rows_a())));
        columns.push((format!("{name}_b"), b.require(name)?.gather(rows_b())));
    }
    let mut table = Table { path: PathBuf::from("compare.parquet"), columns, height: join.pairs.len() };
    with_ratios(&mut table, &metrics);
    Ok(Joined { table, metrics })
}

/// The grid parameters of the joined table: every dotted one, holding the value both sides
/// share where it is a key and otherwise the value of the one side that varies it; then each
/// top-level one that is a key of some scene (`seed`, `v0`), under its own name, holding the
/// value both sides share in the scenes it is a key of (null elsewhere), as the join met them.
fn grid_columns(a: &Table, b: &Table, join: &Join) -> Vec<(String, Values)> {
    let rows_a = || join.pairs.iter().map(|p| p.0);
    let rows_b = || join.pairs.iter().map(|p| p.1);
    let mut columns = Vec::new();
    for (name, va) in a.columns.iter().filter(|(n, _)| is_dotted(n)) {
        let merged = match (va, b.column(name)) {
            (Values::Numbers(va), Some(Values::Numbers(vb))) => {
                Values::Numbers(join.pairs.iter().map(|&(i, j)| va[i].or(vb[j])).collect())
            }
            (va, Some(vb)) => Values::Text(join.pairs.iter().map(|&(i, j)| va.key(i).or(vb.key(j))).collect()),
            (va, None) => va.gather(rows_a()),
        };
        columns.push((name.clone(), merged));
    }
    for (name, vb) in b.columns.iter().filter(|(n, _)| is_dotted(n) && a.column(n).is_none()) {
        columns.push((name.clone(), vb.gather(rows_b())));
    }
    for name in TOP_LEVEL_PARAMETERS {
        let keyed: Vec<&SceneJoin> = join.scenes.iter().filter(|s| s.keys.iter().any(|k| k == name)).collect();
        if let Some(va) = a.column(name).filter(|_| !keyed.is_empty()) {
            let shared = va.gather(rows_a()).masked(|row| keyed.iter().any(|s| s.pairs.contains(&row)));
            columns.push((name.to_string(), shared));
        }
    }
    columns
}

/// Puts each metric's ratio column `<metric>_ratio` after its `<metric>_b`.
fn with_ratios(table: &mut Table, metrics: &[String]) {
    let all = SceneRows { table, rows: (0..table.height).collect(), keys: Vec::new() };
    let mut ratios: Vec<(String, Values)> = metrics
        .iter()
        .map(|name| (name.clone(), Values::Numbers(all.rows.iter().map(|&r| all.ratio(name, r)).collect())))
        .collect();
    let columns = std::mem::take(&mut table.columns);
    for (name, values) in columns {
        let ratio = name.strip_suffix("_b").and_then(|m| ratios.iter().position(|(n, _)| n == m));
        table.columns.push((name, values));
        if let Some(i) = ratio {
            let (metric, values) = ratios.swap_remove(i);
            table.columns.push((format!("{metric}_ratio"), values));
        }
    }
}

/// The joined table, with the names of its metric columns.
pub(super) struct Joined {
    pub(super) table: Table,
    /// Metrics: each has `<metric>_a`, `<metric>_b` and `<metric>_ratio` in the table.
    pub(super) metrics: Vec<String>,
}

impl Joined {
    /// The rows of `scene` in the joined table.
    pub(super) fn scene_rows(&self, scene: &SceneJoin) -> SceneRows<'_> {
        SceneRows { table: &self.table, rows: scene.pairs.clone().collect(), keys: scene.keys.clone() }
    }
}

/// The joined rows of one scene, with the questions its report section asks of them.
pub(super) struct SceneRows<'a> {
    table: &'a Table,
    /// The scene's rows of the joined table.
    pub(super) rows: Vec<usize>,
    /// The scene's join keys besides the scene.
    keys: Vec<String>,
}

/// The one state of a packing whose pressure, contacts, energy and moduli are the packing's:
/// an unjammed one holds what its relaxation left below the pressure floor, and one not relaxed
/// is no state at all.
const JAMMED: &str = "jammed";

impl SceneRows<'_> {
    /// A column of the joined table.
    pub(super) fn column(&self, name: &str) -> Option<&Values> {
        self.table.column(name)
    }

    /// Row `r`'s grid values (its dotted columns that hold one) as "name = value", but those
    /// whose name starts with `except`.
    pub(super) fn grid_values(&self, r: usize, except: &str) -> Vec<String> {
        let names = self.table.names().filter(|n| is_dotted(n) && !n.starts_with(except));
        names.filter_map(|name| Some(format!("{name} = {}", self.cell(name, r)?))).collect()
    }

    /// Cell `r` of column `name`, as text.
    pub(super) fn cell(&self, name: &str, r: usize) -> Option<String> {
        self.column(name).and_then(|c| c.key(r))
    }

    /// Row `r` ended `ok` on `side` (`a` or `b`).
    pub(super) fn ok(&self, side: &str, r: usize) -> bool {
        self.cell(&format!("status_{side}"), r).is_some_and(|s| s == RunStatus::Ok.as_str())
    }

    /// `rows` with each run of `side` once: one run of a side may meet several of the other,
    /// and counts once (by its run id).
    pub(super) fn once(&self, side: &str, rows: &[usize]) -> Vec<usize> {
        let mut seen = BTreeSet::new();
        rows.iter().copied().filter(|&r| seen.insert(self.cell(&format!("run_id_{side}"), r))).collect()
    }

    /// Row `r` compares like with like: both runs ended `ok` and, for packings, both jammed
    /// ([`JAMMED`]): a jammed packing against an unjammed one is not the same kind of state.
    pub(super) fn comparable(&self, r: usize) -> bool {
        let jammed = |side: &str| self.cell(&format!("packing_state_{side}"), r).is_none_or(|s| s == JAMMED);
        self.ok("a", r) && self.ok("b", r) && jammed("a") && jammed("b")
    }

    /// How A and B measured metric `name` in row `r` where they measured it differently (the
    /// `error` against normal modes in one, against energy in the other): no ratio there.
    pub(super) fn unlike(&self, name: &str, r: usize) -> Option<(String, String)> {
        let column = measure_column(name)?;
        let (a, b) = (self.cell(&format!("{column}_a"), r), self.cell(&format!("{column}_b"), r));
        (a != b).then(|| (a.unwrap_or_else(|| "none".into()), b.unwrap_or_else(|| "none".into())))
    }

    /// Metric `name` of `side` in row `r`, 0 where it is at or below its floor ([`floor`]): a
    /// value there is round-off or what a relaxation left, not a number to divide.
    pub(super) fn value(&self, name: &str, side: &str, r: usize) -> Option<f64> {
        let x = self.metric(name, side).number(r)?;
        Some(if self.at_floor(name, side, r) { 0.0 } else { x })
    }

    /// Metric `name` of `side` in row `r` is at or below its floor: the run's own
    /// (`<name>_floor`, a packing's `pressure_floor`) or the quantity's ([`floor`]).
    pub(super) fn at_floor(&self, name: &str, side: &str, r: usize) -> bool {
        let own = self.column(&format!("{name}_floor_{side}")).and_then(|c| c.number(r));
        let floor = own.or_else(|| floor(name));
        self.metric(name, side).number(r).zip(floor).is_some_and(|(x, floor)| x.abs() <= floor)
    }

    /// B/A of metric `name` in row `r`: where the row compares like with like
    /// ([`SceneRows::comparable`]), both sides measured it alike ([`SceneRows::unlike`]), both
    /// values exist and A's is not 0 (nor at its floor).
    pub(super) fn ratio(&self, name: &str, r: usize) -> Option<f64> {
        if !self.comparable(r) || self.unlike(name, r).is_some() {
            return None;
        }
        match (self.value(name, "a", r), self.value(name, "b", r)) {
            (Some(a), Some(b)) if a != 0.0 => Some(b / a).filter(|r| r.is_finite()),
            _ => None,
        }
    }

    /// Every seed of row `r`'s group (the rows that differ from it only by their seed) compares
    /// like with like ([`SceneRows::comparable`]), or the scene has no packings. Where some
    /// packings of a group did not jam, those that did are a selected share, not a sample of
    /// the seeds: a packing quenched at φ jams only where its own φ_J lies below φ, so their
    /// φ_J, pressure and moduli are biased by the cut, on each side by its own (the item
    /// "Jamming" leaves such fractions out for the same reason).
    pub(super) fn every_seed_comparable(&self, r: usize) -> bool {
        let key = self.replicate_key(r);
        self.column("packing_state_a").is_none()
            || self.rows.iter().filter(|&&o| self.replicate_key(o) == key).all(|&o| self.comparable(o))
    }

    /// The scene varies the seed on both sides: each row's runs are one sample of many.
    pub(super) fn seeded(&self) -> bool {
        self.keys.iter().any(|k| k == "seed")
    }

    /// Row `r`'s values of the join keys besides the seed: the rows that share them differ only
    /// by their random start.
    pub(super) fn replicate_key(&self, r: usize) -> Vec<Option<String>> {
        self.keys.iter().filter(|k| *k != "seed").map(|k| self.cell(k, r)).collect()
    }

    /// The column `<name>_<suffix>` of a metric (`suffix`: `a`, `b` or `ratio`).
    pub(super) fn metric(&self, name: &str, suffix: &str) -> &Values {
        self.column(&format!("{name}_{suffix}")).expect("every metric has its columns")
    }
}
