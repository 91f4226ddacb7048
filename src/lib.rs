//! mdsolids: molecular-dynamics studies of solids made of masses and springs.
//!
//! Data flows one way:
//!
//! ```text
//! campaign YAML ──spec::load──▶ Campaign { runs: [RunSpec] }                 (spec)
//! Campaign ──plan::load──▶ Plan { campaign (dt final, stability checked), estimates }  (plan)
//! RunSpec ──study::build_scene──▶ Scene { particles, bonds, law, damping }    (study, model)
//! Scene ──Scene::run──▶ Outcome { Trace, crossings, final state }             (sim: pure)
//! Outcome ──study::run, measure::*──▶ Metrics, beside theory::* references    (study, measure, theory)
//! runner: rayon over RunSpecs, content-hash cache, one stored RunRecord per run
//!         (`--shard I/N`: one cost-balanced share; `slurm`: one share per array task)
//! [RunRecord] ──table──▶ results.csv / results.parquet (Polars)
//! [RunRecord] ──report──▶ plots/*.svg, report.md, index.html (plotters, tera)
//! two report directories ──compare──▶ compare.csv / .parquet, report.md, index.html, plots/
//! ```
//!
//! The physics core (`model`, `sim`, `theory`, `measure`, `study`) does no I/O.
//!
//! To add a force law: implement [`model::ForceLaw`] (force and energy, with a doctest), add a
//! variant to [`model::LawSpec`] with its arm in `LawSpec::dispatch` and its name, and read it in
//! `spec/resolve.rs`; the bond loop, static solver, integrators and measurements need no
//! change. To add a measurement: a pure function in `measure`, a field in
//! its kind's group of [`study::Metrics`] (`study/<kind>.rs`, set by that kind's `measure`), and
//! its result column in that kind's `columns` (same file).

#![warn(missing_docs)]
// These docs are for those who extend mdsolids: read them with `cargo doc --no-deps
// --document-private-items`, where links to private items resolve.
#![allow(rustdoc::private_intra_doc_links)]

pub mod alloc;
pub mod bench;
pub mod cli;
pub mod compare;
pub mod draw;
pub mod fem;
pub mod measure;
pub mod model;
pub mod output;
pub mod owner;
pub mod plan;
pub mod report;
pub mod runner;
pub mod sim;
pub mod slurm;
pub mod spec;
pub mod study;
pub mod summary;
pub mod table;
pub mod theory;
