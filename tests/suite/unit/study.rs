//! Unit tests of `src/study/mod.rs`, moved out of the library (one test binary).

use mdsolids::study::Metrics;

/// The kinds' groups are flattened: a record's metrics keep one flat object of the
/// fields' names, and read back the same.
#[test]
fn metrics_serialise_flat() {
    let mut metrics = Metrics { energy_error: Some(1e-3), ..Metrics::default() };
    metrics.pair.contact_duration = Some(0.5);
    metrics.chain.wall_force = Some(-2.0);
    metrics.lattice.youngs_modulus = Some(2e11);
    metrics.packing.pressure = Some(0.01);
    let value = serde_json::to_value(&metrics).unwrap();
    let object = value.as_object().unwrap();
    // 53 keys before the packing's 13.
    assert_eq!(object.len(), 66, "{object:?}");
    for (key, number) in [("energy_error", 1e-3), ("contact_duration", 0.5), ("wall_force", -2.0), ("pressure", 0.01)] {
        assert_eq!(object[key].as_f64(), Some(number), "{key}");
    }
    assert_eq!(object["youngs_modulus"].as_f64(), Some(2e11));
    assert_eq!(serde_json::from_value::<Metrics>(value).unwrap(), metrics);
    let sparse: Metrics = serde_json::from_str(r#"{"energy_error": 1, "homogeneity": 0.25}"#).unwrap();
    assert_eq!((sparse.energy_error, sparse.lattice.homogeneity), (Some(1.0), Some(0.25)));
}
