//! Reports: SVG figures, then `report.md` rendered by tera from `templates/report.md.tera`,
//! and `index.html`: the same Markdown turned into HTML (pulldown-cmark) inside the page shell
//! `templates/index.html.tera`, so the report's text exists once. The templates are compiled
//! in, so the binary works from any directory. Only sections of the campaign's scenes show.

mod context;
mod figures;
mod movie;
pub mod plots;
mod solids;
mod studies;

pub use self::movie::{speed_color, write_movie, write_movie_panels};

use anyhow::Context as _;

use crate::output::{Layout, write_atomically};
use crate::runner::RunRecord;
use crate::spec::Campaign;

const MARKDOWN_TEMPLATE: &str = include_str!("../../templates/report.md.tera");
const HTML_TEMPLATE: &str = include_str!("../../templates/index.html.tera");

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

/// Draws the figures and writes `report.md` and `index.html` for `records`, one per run of
/// the campaign.
pub fn render(campaign: &Campaign, layout: &Layout, records: &[RunRecord]) -> anyhow::Result<()> {
    render_with_left_out(campaign, layout, records, &LeftOut::default())
}

/// [`render`] for `records` that lack the campaign's runs `left_out`: the report says so.
pub fn render_with_left_out(
    campaign: &Campaign,
    layout: &Layout,
    records: &[RunRecord],
    left_out: &LeftOut,
) -> anyhow::Result<()> {
    let figures = figures::draw_all(campaign, records)?;
    for figure in &figures {
        write_atomically(&layout.file(&figure.file), figure.svg.as_bytes())?;
    }
    for record in records {
        if let Some(csv) = studies::probe_table(record) {
            write_atomically(&layout.file(&format!("probes/{}.csv", record.run_id)), csv.as_bytes())?;
        }
    }
    // Side-by-side movies exist only when their runs were simulated together (see the runner).
    let side_by_side: Vec<String> = campaign
        .scenes
        .iter()
        .map(|(scene, _)| scene.clone())
        .filter(|scene| layout.side_by_side_movie(scene).is_file())
        .collect();
    let context = context::build(campaign, records, left_out, &figures, &side_by_side);
    let context = tera::Context::from_serialize(&context).context("cannot build the report context")?;
    write_pages(&layout.root, ("report.md", MARKDOWN_TEMPLATE), context)
}

/// Renders the Markdown template `(name, text)` with `context` into `<dir>/report.md`, and the
/// same Markdown as HTML (pulldown-cmark) inside the page shell into `<dir>/index.html`, so
/// the text exists once.
pub(crate) fn write_pages(
    dir: &std::path::Path,
    markdown: (&str, &str),
    mut context: tera::Context,
) -> anyhow::Result<()> {
    let (name, text) = markdown;
    let mut tera = tera::Tera::new();
    tera.add_raw_template(name, text).with_context(|| format!("templates/{name}.tera does not parse"))?;
    tera.add_raw_template("index.html", HTML_TEMPLATE).context("templates/index.html.tera does not parse")?;
    let markdown = tera.render(name, &context).with_context(|| format!("cannot render templates/{name}.tera"))?;
    write_atomically(&dir.join("report.md"), markdown.as_bytes())?;
    let mut body = String::new();
    pulldown_cmark::html::push_html(
        &mut body,
        pulldown_cmark::Parser::new_ext(&markdown, pulldown_cmark::Options::ENABLE_TABLES),
    );
    context.insert("body", &body);
    let html = tera.render("index.html", &context).context("cannot render templates/index.html.tera")?;
    write_atomically(&dir.join("index.html"), html.as_bytes())
}

/// A number with 6 significant digits, plain where that reads well, scientific otherwise.
fn number(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let magnitude = x.abs().log10().floor();
    if (-3.0..5.0).contains(&magnitude) {
        let decimals = (5.0 - magnitude) as usize;
        let text = format!("{x:.decimals$}");
        if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.').to_string() } else { text }
    } else {
        format!("{x:.5e}")
    }
}

fn optional(x: Option<f64>) -> String {
    x.map(number).unwrap_or_else(|| "–".into())
}

fn error(x: Option<f64>) -> String {
    x.map(|e| format!("{e:+.2e}")).unwrap_or_else(|| "–".into())
}
