//! Unit tests of `src/runner/record.rs` and `src/runner/series.rs` (the Parquet tables a record's
//! series are stored in), moved out of the library (one test binary).

use mdsolids::runner::series::{
    particle_table, read_particle_table, read_probe_table, read_series_table, series_table,
};
use mdsolids::sim::{STORED_SAMPLES, Trace};
use mdsolids::spec::RunSpec;

/// A chain of 2 moving particles (4 with the walls) and a kicked 4 × 3 lattice probing its bottom
/// row, each keeping its default series, and the same chain keeping its full series.
fn specs() -> (RunSpec, RunSpec, RunSpec) {
    let yaml = "version: 1\nname: t\nscenes:\n\
        \x20 - {name: c, kind: chain, v0: 1.0, n: 2}\n\
        \x20 - {name: l, kind: lattice, lattice: {nx: 4, ny: 3}, supports: free, \
        impulse: {velocity: [0.0, -0.1]}, probes: {rows: [bottom]}}\n\
        \x20 - {name: f, kind: chain, v0: 1.0, n: 2, output: {series: full}}\n";
    let [chain, lattice, full] = crate::common::runs(yaml).try_into().unwrap();
    (chain, lattice, full)
}

/// Three samples of energies and of four particles' series: 1/3 and 1e300 are no
/// single-precision numbers, the rest are.
fn chain_trace() -> Trace {
    let rows = |scale: f64| (0..3).map(|s| (0..4).map(|i| scale * (s * 4 + i) as f64).collect()).collect();
    Trace {
        time: vec![0.0, 0.1, 0.2],
        kinetic: vec![1.0, 0.5, 0.25],
        potential: vec![0.0, 1.0 / 3.0, 0.75],
        dissipated: vec![0.0; 3],
        work: vec![0.0, 0.0, 1e300],
        displacement_x: rows(0.5),
        displacement_y: rows(0.0),
        velocity_y: rows(1.0 / 3.0),
        ..Trace::default()
    }
}

/// What a record's JSON gives the reader: no samples.
fn bare() -> Trace {
    Trace::default()
}

/// The series and particle tables give back every number they were given, bit for bit (single
/// precision where every value of a column is a single-precision number, double where not),
/// and a series not kept (here the x velocities) as none; cut short, lengthened or not Parquet,
/// they are refused.
#[test]
fn series_tables_read_back_exactly_and_refuse_damage() {
    let (chain, _, _) = specs();
    let original = chain_trace();
    let series = series_table(&original, &chain).unwrap();
    let particles = particle_table(&original, &chain).unwrap().expect("a chain keeps its particles");
    let mut read = bare();
    read_series_table(&series, &chain, &mut read).unwrap();
    read_particle_table(&particles, &chain, &mut read).unwrap();
    assert_eq!(read, original);
    for damaged in [series[..series.len() - 1].to_vec(), [series.clone(), vec![0]].concat(), b"not parquet".to_vec()] {
        assert!(read_series_table(&damaged, &chain, &mut bare()).is_err());
    }
    // A particle table read against other sample times (another run's series table).
    let mut other = bare();
    read_series_table(&series, &chain, &mut other).unwrap();
    other.time[1] = 0.15;
    let error = read_particle_table(&particles, &chain, &mut other).unwrap_err();
    assert!(error.contains("row 1 is not particle 0 at sample 1"), "{error}");
}

/// Python users read the tables as they are: the columns by name, in the types they hold.
#[test]
fn the_tables_have_named_columns_of_plain_types() {
    use polars::prelude::{DataType, ParquetReader, SerReader};
    let (chain, _, _) = specs();
    let particles = particle_table(&chain_trace(), &chain).unwrap().unwrap();
    let frame = ParquetReader::new(std::io::Cursor::new(particles)).finish().unwrap();
    let columns: Vec<(String, DataType)> =
        frame.columns().iter().map(|c| (c.name().to_string(), c.dtype().clone())).collect();
    let expected = [
        ("time", DataType::Float64),
        ("particle", DataType::UInt32),
        ("displacement_x", DataType::Float32),
        ("displacement_y", DataType::Float32),
        ("velocity_y", DataType::Float64),
    ];
    assert_eq!(columns, expected.map(|(name, dtype)| (name.to_string(), dtype)));
    // Particle by particle, each particle's samples in time order.
    let particle: Vec<u32> = frame.column("particle").unwrap().u32().unwrap().into_no_null_iter().collect();
    assert_eq!(particle, [0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3]);
}

/// An impulse lattice keeps of its kicked column the displacement along the kick in the
/// particle table (the column's nodes), and its probed row in the probe table.
#[test]
fn a_kicked_column_and_probed_lines_read_back() {
    let (_, lattice, _) = specs();
    let record = crate::common::execute(&lattice);
    let t = &record.trace;
    assert_eq!(t.probes.iter().map(|p| p.name.as_str()).collect::<Vec<_>>(), ["column 3", "row 0"]);
    assert!(t.displacement_x.is_empty() && t.probes[0].displacement_x.is_empty());
    assert!(!t.probes[0].displacement_y.is_empty() && !t.probes[1].velocity_x.is_empty());
    let series = series_table(t, &lattice).unwrap();
    let particles = particle_table(t, &lattice).unwrap().expect("the kicked column");
    let probes = mdsolids::runner::series::probe_table(t, &lattice).unwrap().expect("the bottom row");
    let mut read = Trace { probes: t.probes.iter().map(shape).collect(), ..Trace::default() };
    read_series_table(&series, &lattice, &mut read).unwrap();
    read_particle_table(&particles, &lattice, &mut read).unwrap();
    read_probe_table(&probes, &lattice, &mut read).unwrap();
    assert_eq!(read.probes, t.probes);
    assert_eq!(read.time, t.time);
}

/// A line's name and nodes without its samples, as a record's JSON holds it.
fn shape(p: &mdsolids::sim::ProbeTrace) -> mdsolids::sim::ProbeTrace {
    mdsolids::sim::ProbeTrace { name: p.name.clone(), nodes: p.nodes.clone(), ..Default::default() }
}

/// A table whose footer declares more rows than its run can hold (here a default record's
/// bound of `STORED_SAMPLES`) is refused before it is decoded, not read into memory; the same
/// rows are read for a run that keeps every sample and asked for that many.
#[test]
fn a_table_declaring_more_rows_than_its_run_holds_is_refused_before_decoding() {
    let (chain, _, full) = specs();
    let samples = STORED_SAMPLES + 1;
    let long = Trace {
        time: (0..samples).map(|s| s as f64).collect(),
        kinetic: vec![0.0; samples],
        potential: vec![0.0; samples],
        dissipated: vec![0.0; samples],
        work: vec![0.0; samples],
        ..Trace::default()
    };
    let bytes = series_table(&long, &chain).unwrap();
    let error = read_series_table(&bytes, &chain, &mut bare()).unwrap_err();
    assert!(error.contains("declares 10001 rows") && error.contains("not decoded"), "{error}");
    let full = RunSpec { samples: samples as u64, ..full };
    read_series_table(&bytes, &full, &mut bare()).unwrap();
}
