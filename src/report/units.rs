//! The units the campaign's scenes work in, read from their specs: which scenes use the
//! reduced units m = k = a = 1 and which a physical material, so the report's opening states
//! each scene's scale as its runs had it (a description may say it in words; this is the data).

use super::words::short as number;
use crate::model::LawSpec;
use crate::runner::RunRecord;

/// A material in words: m, the spring, a and a lattice's ρ = m/(a² d); [`REDUCED`] alone for
/// reduced units.
type Key = (String, String, String, Option<String>);

/// One material and the scenes that use it, in the campaign's order.
struct Material {
    key: Key,
    scenes: Vec<String>,
}

/// The one clause of every scene in reduced units, whatever its law or dimension.
const REDUCED: &str = "reduced units (m = 1 kg, a spring constant of 1, a = 1 m)";

/// A run's material ([`Key`]); every run in reduced units has the same.
fn material_of(r: &RunRecord) -> Key {
    let s = &r.spec;
    if s.mass == 1.0 && s.k == 1.0 && s.spacing == 1.0 {
        return (REDUCED.into(), String::new(), String::new(), None);
    }
    let spring = match s.law {
        LawSpec::Linear => format!("k = {} N/m", number(s.k)),
        LawSpec::Power { beta } => format!("C = {} N/m^{}", number(s.k), super::words::number(beta)),
    };
    let density =
        s.lattice().map(|l| format!("ρ = m/(a² d) = {} kg/m³", number(s.mass / (s.spacing * s.spacing * l.depth))));
    (format!("m = {} kg", number(s.mass)), spring, format!("a = {} m", number(s.spacing)), density)
}

/// The campaign's materials, each with the scenes that use it (a scene whose grid varies its
/// mass or springs is listed under each of its materials), reduced units named as such.
pub(super) fn units_sentence(records: &[RunRecord]) -> Option<String> {
    let mut materials: Vec<Material> = Vec::new();
    for r in records {
        let key = material_of(r);
        let index = match materials.iter().position(|m| m.key == key) {
            Some(index) => index,
            None => {
                materials.push(Material { key, scenes: Vec::new() });
                materials.len() - 1
            }
        };
        if !materials[index].scenes.contains(&r.spec.scene) {
            materials[index].scenes.push(r.spec.scene.clone());
        }
    }
    if materials.is_empty() {
        return None;
    }
    let clauses: Vec<String> = materials
        .iter()
        .map(|m| {
            let (mass, spring, spacing, density) = &m.key;
            let words = [Some(mass.clone()), Some(spring.clone()), Some(spacing.clone()), density.clone()];
            let words: Vec<String> = words.into_iter().flatten().filter(|w| !w.is_empty()).collect();
            format!("{} in {}", words.join(", "), m.scenes.join(", "))
        })
        .collect();
    Some(format!("The scenes' scales, from their specs: {}.", clauses.join("; ")))
}
