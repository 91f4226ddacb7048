//! The serialised form of a [`RunSpec`]: one flat object whose keys are the results table's
//! column names, the kind's own fields beside the others (`null` where the kind has none).
//! Run ids hash it and stored records hold it, so it never changes shape.

use serde::{Deserialize, Deserializer, Serialize, Serializer};
use serde_json::Value;
use std::collections::BTreeMap;

use super::kind::KindColumns;
use super::raw::{SceneKind, SeriesKept};
use super::run_spec::{MovieSpec, RunSpec};
use crate::model::LawSpec;
use crate::sim::IntegratorKind;

/// [`RunSpec`] as stored: its fields in their order, the kind as a tag with the fields of
/// every kind beside it ([`KindColumns`]). Every key here but `series` is part of every run id.
#[derive(Serialize, Deserialize)]
struct FlatRunSpec {
    campaign: String,
    scene: String,
    kind: SceneKind,
    varied: BTreeMap<String, Value>,
    mass: f64,
    spacing: f64,
    k: f64,
    #[serde(flatten)]
    law: LawSpec,
    contact: bool,
    gamma: f64,
    restitution_target: Option<f64>,
    gamma_background: f64,
    integrator: IntegratorKind,
    t_c: f64,
    dt: f64,
    dt_omega_max: Option<f64>,
    reference_refinement: Option<u32>,
    allow_unstable: bool,
    duration: f64,
    steps: u64,
    samples: u64,
    v0: f64,
    #[serde(flatten)]
    kind_columns: KindColumns,
    #[serde(default)]
    movie: Option<MovieSpec>,
    /// Left out when `default`: the specs of runs that keep the default series, their ids
    /// among them, are what they were before the field existed.
    #[serde(default, skip_serializing_if = "SeriesKept::is_default")]
    series: SeriesKept,
}

impl From<RunSpec> for FlatRunSpec {
    fn from(spec: RunSpec) -> FlatRunSpec {
        FlatRunSpec {
            kind: spec.kind(),
            campaign: spec.campaign,
            scene: spec.scene,
            varied: spec.varied,
            mass: spec.mass,
            spacing: spec.spacing,
            k: spec.k,
            law: spec.law,
            contact: spec.contact,
            gamma: spec.gamma,
            restitution_target: spec.restitution_target,
            gamma_background: spec.gamma_background,
            integrator: spec.integrator,
            t_c: spec.t_c,
            dt: spec.dt,
            dt_omega_max: spec.dt_omega_max,
            reference_refinement: spec.reference_refinement,
            allow_unstable: spec.allow_unstable,
            duration: spec.duration,
            steps: spec.steps,
            samples: spec.samples,
            v0: spec.v0,
            kind_columns: spec.scene_kind.into(),
            movie: spec.movie,
            series: spec.series,
        }
    }
}

impl TryFrom<FlatRunSpec> for RunSpec {
    type Error = String;

    fn try_from(flat: FlatRunSpec) -> Result<RunSpec, String> {
        Ok(RunSpec {
            campaign: flat.campaign,
            scene: flat.scene,
            scene_kind: flat.kind_columns.into_kind(flat.kind)?,
            varied: flat.varied,
            mass: flat.mass,
            spacing: flat.spacing,
            k: flat.k,
            law: flat.law,
            contact: flat.contact,
            gamma: flat.gamma,
            restitution_target: flat.restitution_target,
            gamma_background: flat.gamma_background,
            integrator: flat.integrator,
            t_c: flat.t_c,
            dt: flat.dt,
            dt_omega_max: flat.dt_omega_max,
            reference_refinement: flat.reference_refinement,
            allow_unstable: flat.allow_unstable,
            duration: flat.duration,
            steps: flat.steps,
            samples: flat.samples,
            v0: flat.v0,
            movie: flat.movie,
            series: flat.series,
        })
    }
}

impl Serialize for RunSpec {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        FlatRunSpec::from(self.clone()).serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for RunSpec {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<RunSpec, D::Error> {
        RunSpec::try_from(FlatRunSpec::deserialize(deserializer)?).map_err(serde::de::Error::custom)
    }
}
