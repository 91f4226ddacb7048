//! Unit tests of `src/runner/record.rs`, moved out of the library (one test binary).

use mdsolids::runner::record::{SERIES_MAGIC, SERIES_MOST_BYTES, decode_series, encode_series};
use mdsolids::sim::{ProbeTrace, Trace};

/// A trace with energies, per-particle rows and two probed lines (one not stored here).
fn trace() -> Trace {
    let rows = |scale: f64| (0..3).map(|s| (0..4).map(|i| scale * (s * 4 + i) as f64).collect()).collect();
    let line = |name: &str| ProbeTrace {
        name: name.into(),
        nodes: vec![0, 1, 2, 3],
        displacement_x: rows(1e-3),
        displacement_y: rows(-2e-3),
        velocity_x: rows(0.5),
        velocity_y: rows(1e300),
    };
    Trace {
        time: vec![0.0, 0.1, 0.2],
        kinetic: vec![1.0, 0.5, 0.25],
        potential: vec![0.0, 0.5, 0.75],
        dissipated: vec![0.0; 3],
        work: vec![0.0; 3],
        displacement_x: rows(1.0 / 3.0),
        probes: vec![line("row 0"), line("column 1")],
        ..Trace::default()
    }
}

/// The series file gives back every number it was given, bit for bit, in single precision
/// where they are single-precision numbers and in double where not (1/3, 1e300), and the
/// lines kept in the probe table as no rows; cut short, lengthened or garbled, it is refused.
#[test]
fn series_files_read_back_exactly_and_refuse_damage() {
    let mut original = trace();
    original.kinetic = vec![1.0f32 as f64, 0.1f32 as f64, 3e-39];
    let bytes = encode_series(&original, |p| p.name == "column 1");
    let mut read = Trace { probes: original.probes.clone(), ..Trace::default() };
    decode_series(&bytes, &mut read).unwrap();
    let mut expected = original.clone();
    expected.probes[1] = ProbeTrace { name: "column 1".into(), nodes: vec![0, 1, 2, 3], ..ProbeTrace::default() };
    assert_eq!(read, expected);
    let mut raw = zstd::bulk::decompress(&bytes, 1 << 20).unwrap();
    for damaged in [raw[..raw.len() - 1].to_vec(), [raw.clone(), vec![0]].concat(), b"x".to_vec()] {
        let bytes = zstd::bulk::compress(&damaged, 1).unwrap();
        assert!(decode_series(&bytes, &mut read).is_err());
    }
    raw[SERIES_MAGIC.len()] = 5;
    let error = decode_series(&zstd::bulk::compress(&raw, 1).unwrap(), &mut read).unwrap_err();
    assert!(error.contains("5 bytes"), "{error}");
    assert!(decode_series(b"not zstd", &mut read).is_err());
}

/// A file that decodes to more than any record holds is refused after reading that much,
/// not read whole into memory.
#[test]
fn a_series_file_that_decodes_beyond_any_record_is_refused() {
    let bomb = zstd::bulk::compress(&vec![0u8; SERIES_MOST_BYTES as usize + 10], 3).unwrap();
    let error = decode_series(&bomb, &mut Trace::default()).unwrap_err();
    assert!(error.contains("more than any record"), "{error}");
}
