//! The scenes as the report shows them: every topic (`kinds.rs`, `curves.rs`, `precision.rs`,
//! `waves.rs`, `probes.rs`, `solids.rs`, `stability_map.rs`, `exponents.rs`) asked once per scene
//! for its part, the figures it draws and the rows of its tables. The one list of the topics, in the
//! order a scene shows their figures; a new topic is one line in [`scene_part`] and one field of
//! [`SceneTables`].

use serde::Serialize;

use super::curves;
use super::exponents::{self, ExponentRow};
use super::figure::{Figure, Part};
use super::figures::dissipation_figure;
use super::kinds::{self, KindRows};
use super::precision::{self, PrecisionRow};
use super::probes;
use super::solids::{self, EnsembleRow};
use super::stability_map::{self, StabilityRows};
use super::waves::{self, WaveRow};
use crate::runner::RunRecord;
use crate::spec::{Campaign, SceneKind};
use crate::summary::ScalingFit;

/// Every scene's tables, and every figure: the scenes' in campaign order, each tagged with its
/// scene, then the one across scenes.
pub struct Scenes {
    /// The drawn figures.
    pub figures: Vec<Figure>,
    /// One per scene of the campaign, in its order.
    pub scenes: Vec<Scene>,
}

/// One scene's name, kind and tables (its figures are in [`Scenes::figures`]).
pub struct Scene {
    /// As the campaign names it.
    pub name: String,
    /// Its kind.
    pub kind: SceneKind,
    /// Its tables.
    pub tables: SceneTables,
}

/// The rows of every table of a scene, each topic's under the names the template reads.
#[derive(Serialize)]
pub struct SceneTables {
    /// The scene's own kind's (`kinds.rs`).
    #[serde(flatten)]
    pub kind: KindRows,
    /// Work against precision (`precision.rs`).
    pub precision_rows: Vec<PrecisionRow>,
    /// The runs and limits of a stability scene (`stability_map.rs`).
    #[serde(flatten)]
    pub stability: StabilityRows,
    /// Timed waves (`waves.rs`).
    pub wave_rows: Vec<WaveRow>,
    /// Fitted scaling laws (`exponents.rs`).
    pub exponent_rows: Vec<ExponentRow>,
    /// Ensembles of random lattices (`solids.rs`).
    pub ensemble_rows: Vec<EnsembleRow>,
}

/// Asks every topic for its part of every scene of `campaign`, once, and draws the figure
/// across scenes.
pub fn ask_topics(campaign: &Campaign, records: &[RunRecord], fits: &[ScalingFit]) -> anyhow::Result<Scenes> {
    let mut figures = Vec::new();
    let mut scenes = Vec::new();
    for (name, kind) in &campaign.scenes {
        let part = scene_part(records, fits, name, *kind, campaign.target_error)?;
        figures.extend(part.figures);
        scenes.push(Scene { name: name.clone(), kind: *kind, tables: part.rows });
    }
    figures.extend(dissipation_figure(records)?);
    Ok(Scenes { figures, scenes })
}

/// Every topic's part of `scene`: their figures in the order the scene shows them, and their
/// tables for the accuracy `target_error`.
fn scene_part(
    records: &[RunRecord],
    fits: &[ScalingFit],
    scene: &str,
    kind: SceneKind,
    target_error: f64,
) -> anyhow::Result<Part<SceneTables>> {
    let kind = kinds::part(records, scene, kind)?;
    let curves = curves::part(records, scene)?;
    let precision = precision::part(records, scene, target_error)?;
    let waves = waves::part(records, fits, scene)?;
    let probes = probes::part(records, scene)?;
    let solids = solids::part(records, fits, scene)?;
    let stability = stability_map::part(records, scene)?;
    let exponents = exponents::part(fits, scene);
    let figures = [
        kind.figures,
        curves.figures,
        precision.figures,
        waves.figures,
        probes.figures,
        solids.figures,
        stability.figures,
        exponents.figures,
    ]
    .into_iter()
    .flatten()
    .collect();
    let tables = SceneTables {
        kind: kind.rows,
        precision_rows: precision.rows,
        stability: stability.rows,
        wave_rows: waves.rows,
        exponent_rows: exponents.rows,
        ensemble_rows: solids.rows,
    };
    Ok(Part { figures, rows: tables })
}
