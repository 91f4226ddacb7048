//! Unit tests of `src/spec/flat.rs`, moved out of the library (one test binary).

use mdsolids::spec::RunSpec;
use serde_json::Value;

/// A resolved spec of each kind in `yaml`'s scenes.
fn specs() -> Vec<RunSpec> {
    let yaml = "version: 1\nname: t\nscenes:\n\
        \x20 - {name: p, kind: pair, v0: 1.0, material: {contact: true}}\n\
        \x20 - {name: c, kind: chain, v0: 1.0, n: 5, wave: {}}\n\
        \x20 - {name: l, kind: lattice, lattice: {size: 3}}\n";
    mdsolids::spec::parse("t.yaml", yaml).unwrap().runs
}

#[test]
fn every_kind_reads_back_as_written() {
    for spec in specs() {
        let json = serde_json::to_value(&spec).unwrap();
        for key in ["kind", "gap", "n", "node", "wall_distance", "relax", "lattice", "wave"] {
            assert!(json.get(key).is_some(), "{} has no `{key}` key: {json}", spec.scene);
        }
        assert_eq!(serde_json::from_value::<RunSpec>(json).unwrap(), spec);
    }
}

#[test]
fn a_field_of_another_kind_is_refused() {
    let [pair, chain, lattice] = specs().try_into().unwrap();
    let mut json = serde_json::to_value(&pair).unwrap();
    json["n"] = 3.into();
    let error = serde_json::from_value::<RunSpec>(json).unwrap_err().to_string();
    assert!(error.contains("a pair run has no `n`"), "{error}");
    let mut json = serde_json::to_value(&chain).unwrap();
    json["wall_distance"] = Value::Null;
    let error = serde_json::from_value::<RunSpec>(json).unwrap_err().to_string();
    assert!(error.contains("a chain run needs `wall_distance`"), "{error}");
    let mut json = serde_json::to_value(&lattice).unwrap();
    json["gap"] = 0.1.into();
    let error = serde_json::from_value::<RunSpec>(json).unwrap_err().to_string();
    assert!(error.contains("a lattice run has no `gap`"), "{error}");
}

/// `output.series` is stored with the run (a record says which series it kept) but is no part
/// of its id: the same run keeps one id whichever series its files keep, and a run keeping the
/// default series is written as before the field existed.
#[test]
fn output_series_is_stored_but_not_part_of_the_run_id() {
    let yaml =
        |output: &str| format!("version: 1\nname: t\nscenes:\n  - {{name: c, kind: chain, v0: 1.0, n: 5{output}}}\n");
    let default = mdsolids::spec::parse("t.yaml", &yaml("")).unwrap().runs.remove(0);
    let full = mdsolids::spec::parse("t.yaml", &yaml(", output: {series: full}")).unwrap().runs.remove(0);
    assert_eq!(full.series, mdsolids::spec::SeriesKept::Full);
    assert_eq!(full.run_id(), default.run_id());
    let json = serde_json::to_value(&full).unwrap();
    assert_eq!(json["series"], "full");
    assert_eq!(serde_json::from_value::<RunSpec>(json).unwrap(), full);
    assert!(serde_json::to_value(&default).unwrap().get("series").is_none());
}
