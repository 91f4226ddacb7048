//! The exponent table: every scaling law fitted over a scene's runs (`summary::ScalingFit`),
//! one row per group, as the report writes it.

use serde::Serialize;

use super::figure::Part;
use super::words::{fit_quality_cell, number};
use crate::summary::ScalingFit;

/// A fitted y ∝ x^p of one group.
#[derive(Serialize)]
pub struct ExponentRow {
    group: String,
    law: &'static str,
    quantity: &'static str,
    against: &'static str,
    exponent: String,
    r_squared: String,
    points: usize,
    range: String,
}

/// The exponent part of `scene`: a table only (`solids.rs` and `waves.rs` draw the fits).
pub fn part(fits: &[ScalingFit], scene: &str) -> Part<Vec<ExponentRow>> {
    Part { figures: Vec::new(), rows: exponent_rows(fits, scene) }
}

/// The exponent rows of `scene`: every scaling law fitted over its runs.
fn exponent_rows(fits: &[ScalingFit], scene: &str) -> Vec<ExponentRow> {
    fits.iter()
        .filter(|f| f.scene == scene)
        .map(|f| ExponentRow {
            group: if f.group.is_empty() { "all".into() } else { f.group.clone() },
            law: f.law,
            quantity: f.quantity,
            against: f.against,
            exponent: format!("{:.4}", f.fit.exponent),
            r_squared: fit_quality_cell(&f.fit, 6),
            points: f.points.len(),
            range: format!("{} … {}", number(f.points[0].0), number(f.points[f.points.len() - 1].0)),
        })
        .collect()
}
