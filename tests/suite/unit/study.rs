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
    // 60 keys before the packing's 17.
    assert_eq!(object.len(), 77, "{object:?}");
    for (key, number) in [("energy_error", 1e-3), ("contact_duration", 0.5), ("wall_force", -2.0), ("pressure", 0.01)] {
        assert_eq!(object[key].as_f64(), Some(number), "{key}");
    }
    assert_eq!(object["youngs_modulus"].as_f64(), Some(2e11));
    assert_eq!(serde_json::from_value::<Metrics>(value).unwrap(), metrics);
    let sparse: Metrics = serde_json::from_str(r#"{"energy_error": 1, "homogeneity": 0.25}"#).unwrap();
    assert_eq!((sparse.energy_error, sparse.lattice.homogeneity), (Some(1.0), Some(0.25)));
}

/// N × 1 gives back the chain: the chain scene is the 2D code's (n + 2) × 1 lattice with its
/// particles held on the x axis. Let them move along y as well (only the walls held) and the
/// run is the same to the last bit, with y ≡ 0: every spring lies along x, so n̂ = (±1, 0) and
/// the force function gives no y force, exactly, in a 2D code with vectors. Exact comparison:
/// the same operations on the same numbers must give the same bits.
#[test]
fn the_chain_is_the_n_by_1_lattice_of_the_2d_code() {
    let yaml = "version: 1\nname: c\nscenes:\n  - name: c\n    kind: chain\n    n: 11\n    node: 6\n    v0: 0.01\n";
    let spec = &mdsolids::spec::parse("c.yaml", yaml).unwrap().runs[0];
    let held_on_x = mdsolids::study::build_scene(spec);
    let mdsolids::sim::Network::Lattice(lattice) = &held_on_x.network else { panic!("a chain is a lattice") };
    assert_eq!((lattice.nx, lattice.ny), (13, 1), "11 particles and two walls in one row");
    let mut in_2d = held_on_x.clone();
    let walls = in_2d.particles.held_x.clone();
    assert_eq!(walls, vec![0, 12], "only the walls are held along x");
    in_2d.particles.held_y = walls;
    let (one_d, two_d) = (held_on_x.run().trace, in_2d.run().trace);
    assert!(!two_d.displacement_x.is_empty() && two_d.displacement_x.len() == one_d.displacement_x.len());
    assert_eq!(two_d.displacement_x, one_d.displacement_x, "x(t) of the row and of the chain");
    assert!(two_d.displacement_y.iter().flatten().all(|&y| y == 0.0), "the row stays on its line");
    assert!(one_d.kinetic.iter().zip(&two_d.kinetic).all(|(a, b)| a == b));
}
