//! Campaign files: YAML → validated campaign → one [`RunSpec`] per grid point.
//! The only module that knows YAML. Everything is checked before any run starts, and every
//! error names the file, the field path, the value and what is allowed.

pub use self::raw::{Control, Diagonals, LawName, LoadCase, SceneKind, Supports};
pub use self::run_spec::{
    Budget, ImpulseSpec, LatticeSpec, MovieSpec, ProbeLine, RESULT_FORMAT, RelaxSpec, RunSpec, WaveSpec, reference_extension,
};

mod grid;
mod raw;
mod resolve;
mod run_spec;

use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;

use self::grid::{get_path, grid_points, merge, set_path};
use self::raw::{Grid, RawCampaign, RawScene};

/// Why a campaign file was refused.
#[derive(Debug, thiserror::Error)]
pub enum SpecError {
    /// The file could not be read.
    #[error("cannot read campaign file {file}: {source}")]
    Read {
        /// The file.
        file: String,
        /// The I/O error.
        #[source]
        source: std::io::Error,
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

/// The accuracy the work–precision report aims at unless the campaign says `target_error`.
pub const DEFAULT_TARGET_ERROR: f64 = 1e-3;

/// Reads, validates and expands the campaign file at `path`.
pub fn load(path: &Path) -> Result<Campaign, SpecError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| SpecError::Read { file: file.clone(), source })?;
    parse(&file, &text)
}

/// Validates and expands campaign text; `file` names it in errors.
pub fn parse(file: &str, text: &str) -> Result<Campaign, SpecError> {
    let invalid = |detail: String| SpecError::Invalid { file: file.to_string(), detail };
    let raw: RawCampaign = serde_saphyr::from_str(text).map_err(|e| invalid(describe_yaml_error(text, &e)))?;
    if raw.version != 1 {
        return Err(invalid(format!("version = {}: only version 1 exists", raw.version)));
    }
    if raw.name.is_empty() || !raw.name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_') {
        return Err(invalid(format!(
            "name = {:?}: use letters, digits, '-' and '_' (it names reports/<name>/)",
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
    let defaults = to_value(&raw.defaults);
    let mut runs = Vec::new();
    let mut scenes: Vec<(String, SceneKind)> = Vec::new();
    for (index, scene) in raw.scenes.iter().enumerate() {
        let expanded = expand_scene(&raw, &defaults, index, scene).map_err(invalid)?;
        let first = &expanded[0];
        if scenes.iter().any(|(name, _)| *name == first.scene) {
            return Err(invalid(format!("scenes[{index}].name = {:?}: scene names must be unique", first.scene)));
        }
        scenes.push((first.scene.clone(), first.kind));
        runs.extend(expanded);
    }
    let target_error = raw.target_error.unwrap_or(DEFAULT_TARGET_ERROR);
    if !(target_error > 0.0 && target_error < 1.0) {
        return Err(invalid(format!("target_error = {target_error}: must be in (0, 1) (a relative error)")));
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
            return Err(format!("budget.seconds_per_run = {seconds}: must be a finite number of seconds > 0"));
        }
        budget.seconds_per_run = seconds;
    }
    if let Some(megabytes) = raw.memory_per_run_mb {
        if !(megabytes.is_finite() && megabytes > 0.0) {
            return Err(format!("budget.memory_per_run_mb = {megabytes}: must be a finite number of MB > 0"));
        }
        budget.memory_per_run = megabytes * 1e6;
    }
    Ok(budget)
}

fn to_value(scene: &RawScene) -> Value {
    serde_json::to_value(scene).expect("raw scenes always serialise")
}

/// Names the field path of a YAML error (serde-saphyr gives line and column, serde_path_to_error
/// the path), followed by saphyr's message with its source snippet.
fn describe_yaml_error(text: &str, error: &serde_saphyr::Error) -> String {
    let path = serde_saphyr::from_str::<Value>(text)
        .ok()
        .and_then(|value| serde_path_to_error::deserialize::<_, RawCampaign>(value).err())
        .map(|e| (e.path().to_string(), e.inner().to_string()));
    match path {
        Some((path, message)) => format!("{path}: {message}\n{error}"),
        None => error.to_string(),
    }
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

/// All runs of one scene: defaults merged under it, then every point of the campaign grid
/// combined with the scene's own grid.
fn expand_scene(raw: &RawCampaign, defaults: &Value, index: usize, scene: &RawScene) -> Result<Vec<RunSpec>, String> {
    let mut base = defaults.clone();
    let own = to_value(scene);
    merge(&mut base, &own);
    base.as_object_mut().expect("a scene is a map").remove("grid");
    let mut grid: Grid = raw.grid.clone();
    let mut grid_keys: BTreeMap<String, &'static str> = raw.grid.keys().map(|k| (k.clone(), "campaign")).collect();
    for (path, values) in scene.grid.iter().flatten() {
        grid.insert(path.clone(), values.clone());
        grid_keys.insert(path.clone(), "scene");
    }
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
            let varied = point.into_iter().collect();
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
        for value in values {
            let mut probe = base.clone();
            set_path(&mut probe, path, value.clone());
            if let Err(e) = serde_json::from_value::<RawScene>(probe) {
                return Err(format!(
                    "{} = {value}: {e} (grid keys are dotted field paths such as time.dt_per_tc)",
                    origins.locate(path)
                ));
            }
        }
    }
    Ok(())
}
