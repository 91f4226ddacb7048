//! Unit tests of `src/compare/quantity.rs`, moved out of the library (one test binary).

use mdsolids::compare::quantity::{Class, class, unit};

#[test]
fn classes_and_units() {
    assert_eq!(class("wall_s"), Class::Cost);
    assert_eq!(class("mass"), Class::Setup);
    assert_eq!(class("contact_duration_theory"), Class::Setup);
    assert_eq!(class("contact_duration_error"), Class::Deviation);
    assert_eq!(class("homogeneity"), Class::Deviation);
    assert_eq!(class("sound_speed_first_maximum"), Class::Result);
    assert_eq!(unit("contact_duration_error"), Some("1"));
    assert_eq!(unit("sound_speed_first_maximum"), Some("m/s"));
    assert_eq!(unit("youngs_modulus_tangent_fem"), Some("Pa"));
    assert_eq!(unit("spacing_spread"), Some("m"));
    assert_eq!(unit("dt_per_tc"), Some("1"));
    assert_eq!(unit("k_diag"), Some("N/m^β"));
    assert_eq!(unit("poisson_ratio"), Some("1"));
}

/// Guards issue 31, item 12: `compare` labelled `stiffness_min` (N/m) and
/// `extension_sensitivity` (m/N) "(dimensionless)", because every column its unit list missed
/// fell to "1". Every numeric column of the shipped campaigns' results tables (their pinned
/// headers, grid paths included) must now have its unit listed, and an unknown name has none.
#[test]
fn every_result_column_has_its_own_unit() {
    assert_eq!(unit("stiffness_min"), Some("N/m"));
    assert_eq!(unit("extension_sensitivity"), Some("m/N"));
    assert_eq!(unit("damping.background"), Some("N s/m"));
    assert_eq!(unit("load.per_node"), Some("N"));
    assert_eq!(unit("gamma_background_critical"), Some("N s/m"));
    assert_eq!(unit("no_such_column"), None);
    // Columns of words, not numbers: compare never asks their unit.
    let words = [
        "run_id",
        "scene",
        "kind",
        "status",
        "message",
        "build",
        "other_build",
        "law",
        "contact",
        "integrator",
        "error_measure",
        "arrival_criterion",
        "supports",
        "load_case",
        "load_control",
        "diagonals",
        "dissipation_criterion",
        "relax_method",
        "lattice_type",
        "impulse.force",
        "impulse.velocity",
        "lattice.diagonals",
        "lattice.type",
        "load.case",
        "material.law",
        "time.integrator",
    ];
    let snapshots = crate::common::repo().join("tests/snapshots/results");
    let mut unlisted = std::collections::BTreeSet::new();
    for entry in std::fs::read_dir(&snapshots).unwrap() {
        let text = std::fs::read_to_string(entry.unwrap().path()).unwrap();
        let header = text.lines().next().unwrap_or_default();
        unlisted.extend(header.split(',').filter(|c| !words.contains(c) && unit(c).is_none()).map(String::from));
    }
    assert!(unlisted.is_empty(), "columns without a unit: {unlisted:?}");
}
