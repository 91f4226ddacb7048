//! Build script: fingerprints the source that computes a run's stored result, so that every
//! record can name the build that made it (`RunRecord::build`) and a rebuilt binary with other
//! physics never serves old numbers as its own (docs/guarantees.md, "Stale results and corrupt records").

use std::path::{Path, PathBuf};

/// Everything a run's record depends on: the spec and its resolution, the scene kinds (`study`), the physics
/// core, the measurements and their references, the plan that sets dt, the runner's
/// `execute`, the record it fills and the series it keeps.
/// Not the table, the reports, the command line or the store's bookkeeping: they only read records.
const RESULT_SOURCES: [&str; 12] = [
    "src/spec",
    "src/study",
    "src/model",
    "src/sim",
    "src/measure",
    "src/theory",
    "src/fem.rs",
    "src/fem",
    "src/plan",
    "src/runner/execute.rs",
    "src/runner/record.rs",
    "src/runner/series.rs",
];

fn main() {
    let mut files = Vec::new();
    for source in RESULT_SOURCES {
        println!("cargo:rerun-if-changed={source}");
        collect(Path::new(source), &mut files);
    }
    files.sort();
    // FNV-1a (64 bits) over each file's path and bytes, in sorted order: a change, a new file or
    // a renamed one gives another fingerprint. Line endings are left out (a CRLF checkout of the
    // same source is the same build).
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for file in &files {
        let bytes = std::fs::read(file).unwrap_or_else(|e| panic!("cannot read {}: {e}", file.display()));
        let path = file.to_string_lossy().replace('\\', "/");
        for &byte in path.as_bytes().iter().chain([0u8].iter()).chain(bytes.iter().filter(|&&b| b != b'\r')) {
            hash = (hash ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    println!("cargo:rustc-env=MDSOLIDS_SOURCE_FINGERPRINT={hash:016x}");
}

/// The `.rs` files at `path`: the file itself, or every one under the directory.
fn collect(path: &Path, files: &mut Vec<PathBuf>) {
    if path.is_dir() {
        let entries = std::fs::read_dir(path).unwrap_or_else(|e| panic!("cannot list {}: {e}", path.display()));
        for entry in entries {
            collect(&entry.expect("a readable directory entry").path(), files);
        }
    } else if path.extension().is_some_and(|e| e == "rs") {
        files.push(path.to_path_buf());
    }
}
