//! The tests of single functions, moved out of the library so that it is not compiled twice
//! (docs/performance.md, "Build and test times"): one module per source file, named after its path
//! (`src/spec/grid.rs` → `spec_grid`, `src/report/findings/mod.rs` → `report_findings`).

mod alloc;
mod compare_quantity;
mod draw_chart;
mod draw_movie;
mod fem;
mod measure;
mod measure_dispersion;
mod measure_moduli;
mod measure_wave;
mod model_lattice;
mod model_law;
mod model_planar;
mod output;
mod owner;
mod plan;
mod plan_stability;
mod report;
mod report_findings;
mod report_kinds;
mod report_markdown;
mod report_page;
mod report_words;
mod runner;
mod runner_record;
mod runner_shard;
mod slurm;
mod spec_finite;
mod spec_flat;
mod spec_grid;
mod spec_run_spec;
mod study;
mod summary;
mod theory_chain;
mod theory_collision;
mod theory_special;
mod theory_two_body;
