//! Campaign files: YAML → validated campaign → one [`RunSpec`] per grid point.
//! The only module that knows YAML. Everything is checked before any run starts, and every
//! error names the file, the field path, the value and what is allowed.

// The kind tag's enum and every kind's own types (`PairRun`, `ChainRun`, `LatticeSpec`, ...),
// which `kind` re-exports: a new kind adds none here.
pub use self::fields::{campaign_fields, scene_fields};
pub use self::issue::Num;
pub use self::kind::*;
pub use self::name::MAX_NAME_LEN;
pub use self::raw::{Control, Diagonals, Grid, LoadCase, SceneKind, SeriesKept, Supports};
pub use self::run_spec::{
    Budget, LANCZOS_BONDS, MovieSpec, RESIDUAL_OVER_ROUND_OFF, RESULT_FORMAT, RunSpec, force_resolution,
    reference_extension, round_off_words, seconds_up_to_1e9,
};
pub use self::shared::{Deformation, RelaxSpec, WaveSpec};

pub use self::resolve::DEFAULT_DT_PER_TC;

mod fields;
pub mod finite;
mod flat;
pub mod grid;
mod issue;
mod kind;
mod name;
mod raw;
mod resolve;
mod run_spec;
mod shared;

use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;

use crate::output::read_at_most;

use self::grid::{canonical, get_path, grid_points, merge, point_count, set_path};
use self::name::is_safe_name;
use self::raw::{RawCampaign, RawScene};

/// Why a campaign file was refused.
#[derive(Debug, thiserror::Error)]
pub enum SpecError {
    /// The file could not be read.
    #[error("cannot read campaign file {file}: {reason}")]
    Read {
        /// The file.
        file: String,
        /// The I/O error. Part of the message, not a `source`: `{:#}` would print it twice.
        reason: std::io::Error,
    },
    /// The file was read but is not a valid campaign.
    #[error("{file}: {detail}")]
    Invalid {
        /// The file.
        file: String,
        /// Field path, value and what is allowed.
        detail: String,
    },
}

/// A validated campaign with its runs expanded.
#[derive(Clone, Debug)]
pub struct Campaign {
    /// Campaign name (output directory name).
    pub name: String,
    /// Title for the report.
    pub title: String,
    /// Description for the report.
    pub description: String,
    /// Scene names and kinds in file order.
    pub scenes: Vec<(String, SceneKind)>,
    /// All runs: scene by scene, then grid points in order.
    pub runs: Vec<RunSpec>,
    /// Relative error the report recommends a time step for.
    pub target_error: f64,
    /// What one run may use.
    pub budget: Budget,
}

/// Most runs one campaign may expand to. A grid is a cartesian product, so a few long lists
/// multiply quickly (10 axes of 100 values: 1e20 runs); the count is checked before the product
/// is expanded. Every run is resolved and its stability estimated before anything runs, and
/// stores a result file: 100 000 runs is over a hundred times the largest shipped campaign (688)
/// and `plan` of 100 000 pair runs takes ~35 s and ~230 MB (release build, 2 cores).
pub const MAX_RUNS: u64 = 100_000;

/// The accuracy the work–precision report aims at unless the campaign says `target_error`.
pub const DEFAULT_TARGET_ERROR: f64 = 1e-3;

/// Largest campaign file read, in bytes: a hundred times the largest shipped campaign (10.5 kB),
/// and room for serde-saphyr's 250 000 values. The file is read only up to one byte past it, so
/// `/dev/zero` or a runaway generator is refused at once instead of filling the memory.
pub const MAX_CAMPAIGN_BYTES: u64 = 1 << 20;

/// Reads, validates and expands the campaign file at `path`.
pub fn load(path: &Path) -> Result<Campaign, SpecError> {
    let file = path.display().to_string();
    let text = read_bounded(path).map_err(|reason| SpecError::Read { file: file.clone(), reason })?;
    parse(&file, &text)
}

/// The text of `path`, refused past [`MAX_CAMPAIGN_BYTES`] or when it is not UTF-8. Not only
/// regular files: a campaign named on the command line may be a pipe (`run <(generate)`).
fn read_bounded(path: &Path) -> std::io::Result<String> {
    let bytes = read_at_most(std::fs::File::open(path)?, MAX_CAMPAIGN_BYTES, "a campaign file")?;
    String::from_utf8(bytes).map_err(|_| std::io::Error::new(std::io::ErrorKind::InvalidData, "not UTF-8 text"))
}

/// Validates and expands campaign text; `file` names it in errors.
pub fn parse(file: &str, text: &str) -> Result<Campaign, SpecError> {
    let invalid = |detail: String| SpecError::Invalid { file: file.to_string(), detail };
    let raw = read_raw(file, text).map_err(invalid)?;
    if let Some(issue) = name::read_as_boolean(text, &raw) {
        return Err(invalid(issue));
    }
    if let Some((path, value)) = finite::first_non_finite(text) {
        return Err(invalid(format!("{path} = {value}: must be a finite number (not NaN or an infinity)")));
    }
    if raw.version != 1 {
        return Err(invalid(format!("version = {}: only version 1 exists", raw.version)));
    }
    if !is_safe_name(&raw.name) {
        return Err(invalid(format!(
            "name = {:?}: use 1 to {MAX_NAME_LEN} letters, digits, '-' and '_' (it names reports/<name>/)",
            raw.name
        )));
    }
    if raw.scenes.is_empty() {
        return Err(invalid("scenes: the list is empty; give at least one scene".into()));
    }
    for (field, present) in [
        ("name", raw.defaults.name.is_some()),
        ("kind", raw.defaults.kind.is_some()),
        ("grid", raw.defaults.grid.is_some()),
    ] {
        if present {
            return Err(invalid(format!("defaults.{field}: not allowed in defaults; set it in each scene")));
        }
    }
    let grids: Vec<Grid> = raw.scenes.iter().map(|scene| scene_grid(&raw.grid, scene)).collect();
    check_run_count(&raw, &grids).map_err(invalid)?;
    let defaults = to_value(&raw.defaults);
    let mut runs = Vec::new();
    let mut scenes: Vec<(String, SceneKind)> = Vec::new();
    for (index, (scene, grid)) in raw.scenes.iter().zip(grids).enumerate() {
        let expanded = expand_scene(&raw, &defaults, index, scene, grid).map_err(invalid)?;
        let first = &expanded[0];
        if scenes.iter().any(|(name, _)| *name == first.scene) {
            return Err(invalid(format!("scenes[{index}].name = {:?}: scene names must be unique", first.scene)));
        }
        scenes.push((first.scene.clone(), first.kind()));
        runs.extend(expanded);
    }
    let target_error = raw.target_error.unwrap_or(DEFAULT_TARGET_ERROR);
    if !(target_error > 0.0 && target_error < 1.0) {
        return Err(invalid(format!("target_error = {}: must be in (0, 1) (a relative error)", Num(target_error))));
    }
    let budget = resolve_budget(raw.budget.as_ref()).map_err(invalid)?;
    Ok(Campaign {
        target_error,
        budget,
        name: raw.name.clone(),
        title: raw.title.clone().unwrap_or_else(|| raw.name.clone()),
        description: raw.description.clone().unwrap_or_default(),
        scenes,
        runs,
    })
}

/// The campaign's `budget:` over the defaults of [`Budget`].
fn resolve_budget(raw: Option<&raw::RawBudget>) -> Result<Budget, String> {
    let mut budget = Budget::default();
    let Some(raw) = raw else { return Ok(budget) };
    if let Some(seconds) = raw.seconds_per_run {
        if !(seconds.is_finite() && seconds > 0.0) {
            return Err(format!("budget.seconds_per_run = {}: must be a finite number of seconds > 0", Num(seconds)));
        }
        budget.seconds_per_run = seconds;
    }
    if let Some(megabytes) = raw.memory_per_run_mb {
        if !(megabytes.is_finite() && megabytes > 0.0) {
            return Err(format!("budget.memory_per_run_mb = {}: must be a finite number of MB > 0", Num(megabytes)));
        }
        budget.memory_per_run = megabytes * 1e6;
    }
    Ok(budget)
}

fn to_value(scene: &RawScene) -> Value {
    serde_json::to_value(scene).expect("raw scenes always serialise")
}

/// The campaign as written, or why not; `file` names it in the error's source snippet.
/// serde_path_to_error wraps serde-saphyr's own reader, so the field path named is the one
/// saphyr failed at.
fn read_raw(file: &str, text: &str) -> Result<RawCampaign, String> {
    let mut path = None;
    serde_saphyr::with_deserializer_from_str(text, |deserializer| {
        serde_path_to_error::deserialize(deserializer).map_err(|error| {
            path = Some(error.path().to_string());
            error.into_inner()
        })
    })
    .map_err(|error| describe_yaml_error(text, path, &error).replace(SNIPPET_SOURCE, &format!(" --> {file}:")))
}

/// How saphyr names the text in its snippets (` --> <input>:7:16`): it cannot be told the
/// file's name through the reader serde_path_to_error needs, so the name is put in afterwards.
const SNIPPET_SOURCE: &str = " --> <input>:";

/// Names the field path of a YAML error, followed by saphyr's message with its source snippet.
fn describe_yaml_error(text: &str, path: Option<String>, error: &serde_saphyr::Error) -> String {
    let shown = error.to_string();
    if shown.contains("budget breached") || shown.contains("recursion limit") {
        return format!(
            "the YAML exceeds the reader's limits (nesting depth 64, 250 000 values, 50 000 aliases; anchors and \
             aliases may not expand further)\n{shown}"
        );
    }
    if shown.contains("unexpected end of input") {
        return format!("the file holds no campaign; give version, name and scenes\n{shown}");
    }
    // "." is the whole document: not a field worth naming.
    let Some(path) = path.filter(|path| path != ".") else { return shown };
    // serde's wording through a JSON value says more (`invalid type: string "fast", expected
    // f64`, where saphyr says "invalid floating point"), but a value reads an unquoted `y` or
    // `123` as a boolean or a number where saphyr gives a string field its text: it is used
    // only when it fails at the same field, else `name: y` would head every later error.
    let worded = serde_saphyr::from_str::<Value>(text)
        .ok()
        .and_then(|value| serde_path_to_error::deserialize::<_, RawCampaign>(value).err())
        .filter(|e| e.path().to_string() == path)
        .map_or_else(|| error.without_snippet().to_string(), |e| e.inner().to_string());
    format!("{path}: {worded}\n{shown}")
}

/// Where the value of a field path of scene `index` came from, for error messages.
struct Origins<'a> {
    index: usize,
    scene: Value,
    defaults: &'a Value,
    grid_keys: BTreeMap<String, &'static str>,
}

impl Origins<'_> {
    fn locate(&self, path: &str) -> String {
        match self.grid_keys.get(path) {
            Some(&"scene") => format!("scenes[{}].grid.\"{path}\"", self.index),
            Some(_) => format!("grid.\"{path}\" (in scenes[{}])", self.index),
            None if get_path(&self.scene, path).is_none() && get_path(self.defaults, path).is_some() => {
                format!("defaults.{path} (in scenes[{}])", self.index)
            }
            None => format!("scenes[{}].{path}", self.index),
        }
    }
}

/// The grid of one scene: the campaign's grid with the scene's own on top (a scene's list for
/// a path replaces the campaign's).
fn scene_grid(campaign: &Grid, scene: &RawScene) -> Grid {
    let mut grid = campaign.clone();
    grid.extend(scene.grid.iter().flatten().map(|(path, values)| (path.clone(), values.clone())));
    grid
}

/// Refuses a campaign of more than [`MAX_RUNS`] runs, counted from the list lengths alone.
fn check_run_count(raw: &RawCampaign, grids: &[Grid]) -> Result<(), String> {
    let mut total: u64 = 0;
    for (index, grid) in grids.iter().enumerate() {
        let count = point_count(grid).filter(|&count| count <= MAX_RUNS);
        match count.and_then(|count| total.checked_add(count)) {
            Some(sum) => total = sum,
            None => {
                let field = if raw.scenes[index].grid.is_some() {
                    format!("scenes[{index}].grid")
                } else {
                    format!("grid (in scenes[{index}])")
                };
                return Err(format!(
                    "{field}: {} runs ({}); at most {MAX_RUNS} runs per campaign: shorten the lists or split the campaign",
                    describe_count(grid),
                    describe_axes(grid)
                ));
            }
        }
        if total > MAX_RUNS {
            let counts: Vec<String> = grids[..=index]
                .iter()
                .enumerate()
                .map(|(i, g)| format!("scenes[{i}]: {}", describe_count(g)))
                .collect();
            return Err(format!(
                "grid: the scenes expand to {total} runs ({}); at most {MAX_RUNS} runs per campaign: shorten the \
                 lists or split the campaign",
                counts.join(", ")
            ));
        }
    }
    Ok(())
}

/// The number of points of `grid`, also when it does not fit in 64 bits (then approximately).
fn describe_count(grid: &Grid) -> String {
    match point_count(grid) {
        Some(count) => count.to_string(),
        None => format!("about {:.1e}", grid.values().map(|values| values.len() as f64).product::<f64>()),
    }
}

/// `time.dt_per_tc: 4 values × v0: 3 values`, the first few axes of `grid`.
fn describe_axes(grid: &Grid) -> String {
    const SHOWN: usize = 6;
    let mut axes: Vec<String> =
        grid.iter().take(SHOWN).map(|(path, values)| format!("{path}: {} values", values.len())).collect();
    if grid.len() > SHOWN {
        axes.push(format!("{} more axes", grid.len() - SHOWN));
    }
    axes.join(" × ")
}

/// All runs of one scene: defaults merged under it, then every point of its `grid` (the
/// campaign grid combined with the scene's own).
fn expand_scene(
    raw: &RawCampaign,
    defaults: &Value,
    index: usize,
    scene: &RawScene,
    grid: Grid,
) -> Result<Vec<RunSpec>, String> {
    let mut base = defaults.clone();
    let own = to_value(scene);
    merge(&mut base, &own);
    base.as_object_mut().expect("a scene is a map").remove("grid");
    let mut grid_keys: BTreeMap<String, &'static str> = raw.grid.keys().map(|k| (k.clone(), "campaign")).collect();
    grid_keys.extend(scene.grid.iter().flatten().map(|(path, _)| (path.clone(), "scene")));
    let origins = Origins { index, scene: own, defaults, grid_keys };
    check_grid_paths(&base, &grid, &origins)?;
    grid_points(&grid)
        .into_iter()
        .map(|point| {
            let mut merged = base.clone();
            for (path, value) in &point {
                set_path(&mut merged, path, value.clone());
            }
            let resolved: RawScene = serde_json::from_value(merged).map_err(|e| format!("scenes[{index}]: {e}"))?;
            let varied = point.into_iter().map(|(path, value)| (path, canonical(&value))).collect();
            resolve::resolve(&raw.name, &resolved, varied)
                .map_err(|issue| format!("{} = {}: {}", origins.locate(&issue.path), issue.value, issue.allowed))
        })
        .collect()
}

/// Every grid path must name a field of a scene, every value must have that field's type.
fn check_grid_paths(base: &Value, grid: &Grid, origins: &Origins) -> Result<(), String> {
    for (path, values) in grid {
        if values.is_empty() {
            return Err(format!("{}: the list of values is empty", origins.locate(path)));
        }
        if matches!(path.as_str(), "name" | "kind" | "grid") {
            return Err(format!("{}: the scene's {path} cannot be varied", origins.locate(path)));
        }
        if path == "output" || path.starts_with("output.") {
            return Err(format!(
                "{}: output.series cannot be varied: it says which series a run's files keep, not which run it is \
                 (a run has one id either way); set it in the scene or in defaults",
                origins.locate(path)
            ));
        }
        // Two equal values (`[50, 50]`, `[50, 50.0]`, `[0.0, -0.0]`) would give two rows of one
        // run: one id, simulated and stored once.
        let forms: Vec<Value> = values.iter().map(canonical).collect();
        if let Some((second, first)) =
            forms.iter().enumerate().find_map(|(j, form)| forms[..j].iter().position(|f| f == form).map(|i| (j, i)))
        {
            let scene = origins.scene.get("name").and_then(Value::as_str).unwrap_or("?");
            return Err(format!(
                "{} (scene {scene}): values {} and {} (positions {} and {}) are the same number, so the grid would \
                 give scene {scene} the same run twice; list each value once",
                origins.locate(path),
                values[first],
                values[second],
                first + 1,
                second + 1
            ));
        }
        for value in values {
            let mut probe = base.clone();
            set_path(&mut probe, path, value.clone());
            if let Err(e) = serde_json::from_value::<RawScene>(probe) {
                // An unknown field is the path's fault, not the value's: the value is not shown.
                let shown =
                    if e.to_string().starts_with("unknown field") { String::new() } else { format!(" = {value}") };
                return Err(format!(
                    "{}{shown}: {e} (grid keys are dotted field paths such as time.dt_per_tc)",
                    origins.locate(path)
                ));
            }
        }
    }
    Ok(())
}
