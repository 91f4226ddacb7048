//! `src/runner/mod.rs`: a run's movie beside its record.

use mdsolids::output::Layout;
use mdsolids::runner::{NO_MOVIE, write_run_movie};
use mdsolids::sim::RunStatus;

/// Issue 31, item 6: a movie that cannot be drawn is recorded on its run, whose status stays,
/// and the campaign goes on (`Ok`); before, the runner returned the error, which stopped the
/// whole campaign, naming no run. No campaign reaches this since minimisers draw two frames,
/// so a movie with no frames stands in for whatever else may fail while drawing.
#[test]
fn a_movie_that_cannot_be_drawn_is_recorded_on_its_run() {
    let yaml = "version: 1\nname: film\nscenes:\n  - name: chain\n    kind: chain\n    n: 4\n    v0: 0.1\n    \
                movie: {frames: 3, width: 200, height: 120}\n";
    let planned = mdsolids::plan::parse("film.yaml", yaml).unwrap();
    let mut record = crate::common::execute(&planned.campaign.runs[0]);
    let mut movie = record.movie.take().unwrap();
    movie.frames.clear();
    let reports = crate::common::scratch();
    let layout = Layout::new(reports.path(), "film");
    std::fs::create_dir_all(layout.movie_file(&record.run_id).parent().unwrap()).unwrap();
    assert!(record.has_movie());
    write_run_movie(&layout, &mut record, &movie, 3600.0).expect("a movie's own failure is no error of the campaign");
    assert_eq!(record.status, RunStatus::Ok);
    assert!(record.message.contains(NO_MOVIE) && record.message.contains("at least one frame"), "{}", record.message);
    assert!(!record.has_movie(), "not drawn again by the next run or report");
    assert!(!layout.movie_file(&record.run_id).exists());
}
