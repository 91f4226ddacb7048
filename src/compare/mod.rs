//! `mdsolids compare A B`: two campaigns' results side by side. The rows of the two results
//! tables are joined per scene on the grid parameters both campaigns vary there; every numeric
//! column the tables share gets its two values and their ratio B/A; the fitted exponents of the
//! two `summary.csv` files are set against each other and against their spring laws; and a
//! report (`report.md`, `index.html`, `plots/*.svg`, `*.png` where heavy) opens with what
//! differs beyond noise, in sentences with their numbers, and keeps the full tables for its
//! appendix. Everything is read back from the report directories, so
//! campaigns run by different versions of mdsolids can be compared as long as their tables are.

pub mod exponents;
mod join;
mod out;
mod overview;
mod plots;
pub mod quantity;
mod restitution;
mod section;
mod stats;
mod table;
mod words;

use anyhow::Context as _;
use polars::prelude::{CsvWriter, ParquetWriter, SerWriter};
use serde::Serialize;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use self::exponents::{Exponents, exponents};
use self::join::{join, joined_table};
use self::overview::{Overview, overview};
use self::section::{SceneSection, scene_section};
use self::table::Side;
use crate::output::write_atomically;

const MARKDOWN_TEMPLATE: &str = include_str!("../../templates/compare.md.tera");

/// What `compare` wrote.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// The output directory.
    pub out: PathBuf,
    /// Rows of the joined table.
    pub rows: usize,
    /// Overlaid figures written under `plots/`.
    pub plots: usize,
    /// Rows of the exponent table (fits of either side).
    pub exponents: usize,
}

/// Compares the report directories `a` and `b` and writes `compare.csv`, `compare.parquet`,
/// `report.md`, `index.html` and `plots/*.svg` (`*.png` where heavy) into `out`, by default
/// `<reports>/compare-<name of a>-vs-<name of b>`.
pub fn compare(a: &Path, b: &Path, out: Option<&Path>, reports: &Path) -> anyhow::Result<Comparison> {
    let (a, b) = (Side::open(a)?, Side::open(b)?);
    let dir = out.map_or_else(|| reports.join(format!("compare-{}-vs-{}", a.name, b.name)), Path::to_path_buf);
    let out = self::out::claim(&dir, out.is_some())?;
    let join = join(&a.results, &b.results)?;
    let joined = joined_table(&a.results, &b.results, &join)?;
    let mut frame = joined.table.frame().context("cannot build the joined table")?;
    let mut csv = Vec::new();
    CsvWriter::new(&mut csv).include_header(true).finish(&mut frame)?;
    let mut parquet = Vec::new();
    ParquetWriter::new(&mut parquet).finish(&mut frame)?;
    let mut written = BTreeSet::new();
    for (file, bytes) in [("compare.csv", &csv), ("compare.parquet", &parquet)] {
        write_atomically(&dir.join(file), bytes)?;
        written.insert(file.to_string());
    }
    let mut scenes = Vec::new();
    for scene in &join.scenes {
        let section = scene_section(&a, &b, &joined, scene)?;
        for plot in section.plots.iter().flat_map(|group| &group.plots) {
            write_atomically(&dir.join(&plot.file), plot.image.bytes())?;
            written.insert(plot.file.clone());
        }
        scenes.push(section);
    }
    let plots = written.iter().filter(|f| f.starts_with("plots/")).count();
    let exponents = exponents(&a, &b)?;
    let fits = exponents.rows.len();
    let context = ReportContext {
        title: format!("{} against {}", a.name, b.name),
        version: env!("CARGO_PKG_VERSION"),
        a: SideInfo::of(&a),
        b: SideInfo::of(&b),
        rows: joined.table.height,
        only_a: join.only_a,
        only_b: join.only_b,
        overview: overview(&scenes),
        scenes,
        exponents,
    };
    render(&dir, &context)?;
    // The appendix has a page of its own only where the report has one.
    let pages = ["report.md", "index.html", "appendix.html"];
    written.extend(pages.iter().filter(|page| dir.join(page).is_file()).map(|page| page.to_string()));
    out.finish(&written)?;
    Ok(Comparison { out: dir, rows: joined.table.height, plots, exponents: fits })
}

/// Writes `report.md` and `index.html` (the same Markdown as HTML inside the page shell).
fn render(out: &Path, context: &ReportContext) -> anyhow::Result<()> {
    let context = tera::Context::from_serialize(context).context("cannot build the comparison context")?;
    crate::report::write_pages(out, ("compare.md", MARKDOWN_TEMPLATE), context)
}

/// Everything `templates/compare.md.tera` shows.
#[derive(Serialize)]
struct ReportContext {
    title: String,
    version: &'static str,
    a: SideInfo,
    b: SideInfo,
    rows: usize,
    only_a: Vec<String>,
    only_b: Vec<String>,
    overview: Overview,
    scenes: Vec<SceneSection>,
    exponents: Exponents,
}

#[derive(Serialize)]
struct SideInfo {
    name: String,
    dir: String,
    runs: usize,
}

impl SideInfo {
    fn of(side: &Side) -> SideInfo {
        SideInfo { name: side.name.clone(), dir: side.dir.display().to_string(), runs: side.results.height }
    }
}
