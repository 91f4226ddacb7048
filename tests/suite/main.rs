//! The integration tests, one module per area, in one test binary: each binary links the whole
//! dependency tree (polars, tera, faer, ...) again, so one binary builds in a fraction of the
//! time of one per file. A module name filters one area (`cargo test --release --test suite
//! faults::`); the pinned snapshots: `cargo test --release --test suite pinned`. `unit::` holds
//! the tests of single functions, moved out of the library so that it is not compiled twice
//! (once more as its own test binary); one file's: `cargo test --release --test suite unit::fem`.

mod chain_front;
mod claims;
mod cluster;
mod combinations;
mod common;
mod compare;
mod dense;
mod dissipation;
mod docs;
mod fast_paths;
mod faults;
mod floppy_drive;
mod hostile;
mod integrators;
mod lattice;
mod lattice_types;
mod movies;
mod nonlinear;
mod orders;
mod packing;
mod physics;
mod pipeline;
mod plan_warnings;
mod relax;
mod report_fits;
mod review_block;
mod review_jamming;
mod review_pairs;
mod review_waves;
mod series;
mod shear_nonlinearity;
mod shipped;
mod steps;
mod unit;
mod waves;
