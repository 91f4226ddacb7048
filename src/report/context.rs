//! The data the templates see: pre-formatted numbers, one section per scene.

use serde::Serialize;

use super::figure::{Figure, FigureRef, movie_refs};
use super::findings::{AppendixWords, Evidence, Finding, Paragraph, appendix_words, discussion, findings, overview};
use super::kinds::{KindsPresent, physics_words, time_step_words};
use super::scene::{Scene, SceneTables, Scenes};
use super::words::number;
use crate::runner::{BUILD, RunRecord};
use crate::sim::RunStatus;
use crate::spec::Campaign;
use crate::summary::ScalingFit;

/// Runs of the campaign that are not in a report, and why (`mdsolids report` of a store that
/// lacks some).
#[derive(Clone, Debug, Default)]
pub struct LeftOut {
    /// Runs without a stored record.
    pub missing: Vec<String>,
    /// Runs whose stored record is corrupt, with why.
    pub corrupt: Vec<(String, String)>,
    /// The row count of the previous, larger results table, when it was kept aside as
    /// `results.previous.csv` and `.parquet`.
    pub previous_table: Option<usize>,
}

/// Everything the report templates show.
#[derive(Serialize)]
pub struct ReportContext {
    name: String,
    title: String,
    description: String,
    /// Which scenes use which masses, springs and spacings, from their specs.
    units: Option<String>,
    /// This build (version + source fingerprint).
    build: &'static str,
    runs: usize,
    /// Runs of the campaign.
    campaign_runs: usize,
    ok: usize,
    failed: usize,
    /// Runs of the campaign without a stored record (a shard not run yet, or a task that died).
    missing: usize,
    /// Runs whose stored record is corrupt.
    corrupt: usize,
    /// The runs left out (corrupt ones first, then at most [`LISTED_MISSING`] missing ones).
    left_out: Vec<LeftOutRow>,
    /// Row count of the previous, larger table kept aside (0: none kept).
    previous_table: usize,
    /// Runs in the report made by another build.
    other_build: Vec<LeftOutRow>,
    wall_s: String,
    /// Which kinds of scene the campaign has (`has_pair`, `has_chain`, `has_lattice`).
    #[serde(flatten)]
    kinds: KindsPresent,
    has_wave: bool,
    target_error: String,
    /// The abstract: the answers in sentences, each computed from the results.
    overview: Vec<String>,
    /// The coursework's items this campaign answers, in the coursework's order.
    findings: Vec<Finding>,
    /// The discussion's paragraphs.
    discussion: Vec<Paragraph>,
    /// Which methods the scenes' tables need explained (once, not per scene).
    explains: Explains,
    /// The appendix's sentences that state this campaign's numbers.
    appendix: AppendixWords,
    scenes: Vec<SceneSection>,
    failures: Vec<FailureRow>,
}

/// The methods whose explanation the report needs: those of the tables some scene shows.
#[derive(Serialize)]
struct Explains {
    walls: bool,
    waves: bool,
    ensembles: bool,
    exponents: bool,
    precision: bool,
    stability: bool,
    /// Some run is allowed beyond its stability limit (`time.allow_unstable: true`).
    allows_unstable: bool,
}

impl Explains {
    fn of(scenes: &[SceneSection], records: &[RunRecord]) -> Explains {
        let any = |has: fn(&SceneTables) -> bool| scenes.iter().any(|s| has(&s.tables));
        Explains {
            walls: any(|t| t.kind.has_walls()),
            waves: any(|t| !t.wave_rows.is_empty()),
            ensembles: any(|t| !t.ensemble_rows.is_empty()),
            exponents: any(|t| !t.exponent_rows.is_empty()),
            precision: any(|t| !t.precision_rows.is_empty()),
            stability: any(|t| !t.stability.stability_rows.is_empty()),
            allows_unstable: records.iter().any(|r| r.spec.allow_unstable),
        }
    }
}

/// One scene's section: its physics, figures, tables and movies.
#[derive(Serialize)]
struct SceneSection {
    name: String,
    kind: &'static str,
    physics: String,
    /// The two-body contact time t_c the scene's dt is set from, with its formula.
    contact_time: String,
    /// The step its runs took ([`time_step_words`]).
    time_step: String,
    figures: Vec<FigureRef>,
    /// Every topic's rows, under the names the template reads.
    #[serde(flatten)]
    tables: SceneTables,
    movies: Vec<FigureRef>,
}

/// A run and a reason: why it is left out, or the build that made it.
#[derive(Serialize)]
struct LeftOutRow {
    run_id: String,
    why: String,
}

/// Missing runs listed by name in a report (a cluster job may lack thousands).
const LISTED_MISSING: usize = 50;

#[derive(Serialize)]
struct FailureRow {
    run_id: String,
    status: RunStatus,
    message: String,
}

/// Builds the context from the campaign, its records, their scaling fits and its `scenes` as
/// every topic gave them (`scene::ask_topics`), figures drawn and written.
pub fn build(
    campaign: &Campaign,
    records: &[RunRecord],
    fits: &[ScalingFit],
    left_out: &LeftOut,
    scenes: Scenes,
    side_by_side: &[String],
) -> ReportContext {
    let ok = records.iter().filter(|r| r.status == RunStatus::Ok).count();
    let Scenes { figures, scenes } = scenes;
    let evidence = Evidence::new(records, fits, &figures, side_by_side);
    let scenes: Vec<SceneSection> =
        scenes.into_iter().filter_map(|scene| section(scene, records, &figures, side_by_side)).collect();
    ReportContext {
        name: campaign.name.clone(),
        title: campaign.title.clone(),
        description: campaign.description.clone(),
        units: super::units::units_sentence(records),
        build: BUILD,
        runs: records.len(),
        campaign_runs: campaign.runs.len(),
        ok,
        failed: records.len() - ok,
        missing: left_out.missing.len(),
        corrupt: left_out.corrupt.len(),
        left_out: left_out_rows(left_out),
        previous_table: left_out.previous_table.unwrap_or(0),
        other_build: records
            .iter()
            .filter(|r| r.build != BUILD)
            .map(|r| LeftOutRow { run_id: r.run_id.clone(), why: r.build.clone() })
            .collect(),
        wall_s: number(records.iter().map(|r| r.wall_s).sum()),
        kinds: KindsPresent::of(campaign),
        target_error: format!("{:e}", campaign.target_error),
        has_wave: records.iter().any(|r| r.spec.wave().is_some()),
        overview: overview(&evidence),
        findings: findings(&evidence),
        discussion: discussion(&evidence),
        explains: Explains::of(&scenes, records),
        appendix: appendix_words(&evidence),
        scenes,
        failures: records
            .iter()
            .filter(|r| r.status != RunStatus::Ok)
            .map(|r| FailureRow { run_id: r.run_id.clone(), status: r.status, message: r.message.clone() })
            .collect(),
    }
}

/// The runs left out: the corrupt ones with why, then at most [`LISTED_MISSING`] missing ones
/// and how many more.
fn left_out_rows(left_out: &LeftOut) -> Vec<LeftOutRow> {
    let row = |run_id: &String, why: String| LeftOutRow { run_id: run_id.clone(), why };
    let mut rows: Vec<LeftOutRow> =
        left_out.corrupt.iter().map(|(run_id, why)| row(run_id, format!("corrupt record: {why}"))).collect();
    rows.extend(left_out.missing.iter().take(LISTED_MISSING).map(|run_id| row(run_id, "no stored result".into())));
    if left_out.missing.len() > LISTED_MISSING {
        let more = left_out.missing.len() - LISTED_MISSING;
        rows.push(LeftOutRow { run_id: format!("… and {more} more"), why: "no stored result".into() });
    }
    rows
}

/// The section of `scene`, with its `figures` among all of them; `None` when it has no records.
fn section(scene: Scene, records: &[RunRecord], figures: &[Figure], side_by_side: &[String]) -> Option<SceneSection> {
    let mine: Vec<&RunRecord> = records.iter().filter(|r| r.spec.scene == scene.name).collect();
    let s = &mine.first()?.spec;
    Some(SceneSection {
        kind: scene.kind.name(),
        physics: physics_words(s),
        contact_time: super::kinds::contact_time_words(s),
        time_step: time_step_words(&mine),
        figures: figures.iter().filter(|f| f.scene == scene.name).map(Figure::reference).collect(),
        movies: movie_refs(&scene.name, &mine, side_by_side),
        tables: scene.tables,
        name: scene.name,
    })
}

impl ReportContext {
    /// Marks each finding's pointer to another campaign's report whose page is there, relative to
    /// this report's folder `root`: only those are linked (the others say how to make them).
    pub fn look_for_pointed_pages(&mut self, root: &std::path::Path) {
        for see_also in self.findings.iter_mut().filter_map(|f| f.see_also.as_mut()) {
            see_also.written = root.join(see_also.page).is_file();
        }
    }
}
