//! Reports: figures (SVG, or PNG where heavy), then `report.md` rendered by tera from `templates/report.md.tera`,
//! and `index.html`: the same Markdown turned into HTML (pulldown-cmark) inside the page shell
//! `templates/index.html.tera`, so the report's text exists once. The templates are compiled
//! in, so the binary works from any directory. Only sections of the campaign's scenes show.

mod context;
mod curves;
mod edges;

pub use self::context::LeftOut;
mod exponents;
mod figure;
mod figures;
pub mod findings;
pub mod images;
mod jamming;
pub mod kinds;
pub mod markdown;
pub mod page;
mod precision;
mod probes;
mod scene;
mod solids;
mod stability_map;
mod units;
mod waves;
pub mod words;

use anyhow::Context as _;
use std::collections::BTreeSet;
use std::path::Path;

use crate::output::{Layout, write_atomically};
use crate::runner::RunRecord;
use crate::spec::Campaign;
use crate::summary::{ScalingFit, scaling_fits};

const MARKDOWN_TEMPLATE: &str = include_str!("../../templates/report.md.tera");
const HTML_TEMPLATE: &str = include_str!("../../templates/index.html.tera");

/// Draws the figures and writes `report.md` and `index.html` for `records`, one per run of
/// the campaign.
pub fn render(campaign: &Campaign, layout: &Layout, records: &[RunRecord]) -> anyhow::Result<()> {
    render_with_left_out(campaign, layout, records, &scaling_fits(records), &LeftOut::default())
}

/// [`render`] for `records` that lack the campaign's runs `left_out`: the report says so.
/// `fits` are the scaling laws fitted over `records` (`summary::scaling_fits`), the ones the
/// campaign's `summary.csv` holds.
pub fn render_with_left_out(
    campaign: &Campaign,
    layout: &Layout,
    records: &[RunRecord],
    fits: &[ScalingFit],
    left_out: &LeftOut,
) -> anyhow::Result<()> {
    let mut scenes = scene::ask_topics(campaign, records, fits)?;
    for figure in &mut scenes.figures {
        figure.file = figure.image.file_name(&figure.file);
        write_atomically(&layout.file(&figure.file), figure.image.bytes())?;
    }
    // Only a side-by-side movie drawn from exactly the scene's current runs is shown.
    let side_by_side: Vec<String> = campaign
        .scenes
        .iter()
        .map(|(scene, _)| scene.clone())
        .filter(|scene| crate::runner::side_by_side_is_current(campaign, layout, scene))
        .collect();
    // What an earlier report of this folder drew and this one did not (a scene renamed or
    // removed, a campaign that took the folder over) goes.
    let drawn: BTreeSet<String> = scenes.figures.iter().map(|f| f.file.clone()).collect();
    remove_stale(&layout.root, "plots", ".svg", &drawn)?;
    remove_stale(&layout.root, "plots", ".png", &drawn)?;
    let movies: BTreeSet<String> = side_by_side
        .iter()
        .map(|scene| crate::output::side_by_side_name(scene))
        .chain(records.iter().filter(|r| r.has_own_movie()).map(|r| crate::output::movie_name(&r.run_id)))
        .collect();
    remove_stale(&layout.root, "plots", ".gif", &movies)?;
    // Movies of earlier versions sat in the cache folder.
    remove_stale(&layout.root, "runs", ".gif", &BTreeSet::new())?;
    // Probe tables are stored with their runs: those of every run of the campaign stay (also
    // of a run another process is storing now, which `records` may not hold yet).
    let probes: BTreeSet<String> = campaign
        .runs
        .iter()
        .filter(|spec| spec.lattice().is_some_and(|l| !l.probes.is_empty()))
        .map(|spec| crate::output::probe_table_name(&spec.run_id()))
        .collect();
    remove_stale(&layout.root, "probes", ".parquet", &probes)?;
    // Probe tables of earlier versions were CSV.
    remove_stale(&layout.root, "probes", ".csv", &BTreeSet::new())?;
    remember_written(&layout.root, "plots", drawn.iter().chain(&movies))?;
    remember_written(&layout.root, "probes", probes.iter())?;
    let mut context = context::build(campaign, records, fits, left_out, scenes, &side_by_side);
    context.look_for_pointed_pages(&layout.root);
    let context = tera::Context::from_serialize(&context).context("cannot build the report context")?;
    write_pages(&layout.root, ("report.md", MARKDOWN_TEMPLATE), context)
}

/// Removes the files `<root>/<dir>/*<suffix>` not in `keep` (paths relative to `root`) that this
/// program wrote there: those its last report listed in `<dir>/.written` ([`remember_written`]),
/// or, in a folder of an earlier version without that list, those named as it names its
/// outputs (ASCII letters, digits, `-`, `_` and `.`, not starting with a dot: temporary files
/// of a writer at work are hidden and never touched). A file of the user's own in the folder,
/// and sub-folders, stay.
pub(crate) fn remove_stale(root: &Path, dir: &str, suffix: &str, keep: &BTreeSet<String>) -> anyhow::Result<()> {
    let entries = match std::fs::read_dir(root.join(dir)) {
        Ok(entries) => entries,
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(error) => return Err(error).with_context(|| format!("cannot list '{}'", root.join(dir).display())),
    };
    let written = std::fs::read_to_string(root.join(dir).join(WRITTEN)).ok();
    let listed: Option<BTreeSet<&str>> = written.as_deref().map(|w| w.lines().collect());
    for entry in entries {
        let entry = entry.with_context(|| format!("cannot list '{}'", root.join(dir).display()))?;
        let Some(name) = entry.file_name().to_str().map(str::to_string) else { continue };
        let ours = match &listed {
            Some(listed) => listed.contains(name.as_str()),
            None => !name.starts_with('.') && name.chars().all(|c| c.is_ascii_alphanumeric() || "-_.".contains(c)),
        };
        let stale = ours && name.ends_with(suffix) && !keep.contains(&format!("{dir}/{name}"));
        if stale && entry.file_type().is_ok_and(|t| t.is_file()) {
            std::fs::remove_file(entry.path())
                .with_context(|| format!("cannot remove the stale '{}'", entry.path().display()))?;
        }
    }
    Ok(())
}

/// The list of the files a report wrote or kept in one of its folders, `<dir>/.written`.
const WRITTEN: &str = ".written";

/// Lists in `<root>/<dir>/.written` the files of `kept` (paths relative to `root`) that lie in
/// `dir`, so that the next report removes only what this program wrote ([`remove_stale`]).
fn remember_written<'a>(root: &Path, dir: &str, kept: impl Iterator<Item = &'a String>) -> anyhow::Result<()> {
    if !root.join(dir).is_dir() {
        return Ok(());
    }
    let prefix = format!("{dir}/");
    let names: BTreeSet<&str> = kept.filter_map(|path| path.strip_prefix(&prefix)).collect();
    let text: String = names.iter().map(|name| format!("{name}\n")).collect();
    write_atomically(&root.join(dir).join(WRITTEN), text.as_bytes())
}

/// Renders the Markdown template `(name, text)` with `context` into `<dir>/report.md`, and the
/// same Markdown as HTML (pulldown-cmark) inside the page shell into `<dir>/index.html`, so
/// the text exists once; where the Markdown marks an appendix (`page::APPENDIX_MARKER`), what
/// follows it goes to `<dir>/appendix.html` instead, linked from `index.html`. The images are
/// read back for their sizes, and each movie gets its filmstrip for print (`images.rs`).
pub fn write_pages(dir: &std::path::Path, markdown: (&str, &str), mut context: tera::Context) -> anyhow::Result<()> {
    let (name, text) = markdown;
    // Two instances: every value is escaped for its target, Markdown (`markdown::tera`) or HTML.
    let mut tera = markdown::tera();
    tera.add_raw_template(name, text).with_context(|| format!("templates/{name}.tera does not parse"))?;
    let markdown = tera.render(name, &context).with_context(|| format!("cannot render templates/{name}.tera"))?;
    let mut tera = tera::Tera::new();
    tera.add_raw_template("index.html", HTML_TEMPLATE).context("templates/index.html.tera does not parse")?;
    write_atomically(&dir.join("report.md"), page::with_contents(&markdown).as_bytes())?;
    let sources = page::image_sources(&markdown);
    let shown = images::shown(dir, sources.iter().map(String::as_str))?;
    let (main, appendix) = page::split_appendix(&page::to_html(&markdown, &shown));
    context.insert("body", &main);
    let html = tera.render("index.html", &context).context("cannot render templates/index.html.tera")?;
    write_atomically(&dir.join(page::MAIN_PAGE), html.as_bytes())?;
    let appendix_file = dir.join(page::APPENDIX_PAGE);
    let Some(appendix) = appendix else {
        // An earlier report of this folder may have had an appendix.
        return match std::fs::remove_file(&appendix_file) {
            Err(error) if error.kind() != std::io::ErrorKind::NotFound => {
                Err(error).with_context(|| format!("cannot remove the stale '{}'", appendix_file.display()))
            }
            _ => Ok(()),
        };
    };
    let title = context.get("title").and_then(|t| t.as_str()).unwrap_or_default().to_string();
    context.insert("title", &format!("{title}: appendix"));
    context.insert("body", &appendix);
    let html = tera.render("index.html", &context).context("cannot render templates/index.html.tera")?;
    write_atomically(&appendix_file, html.as_bytes())
}
