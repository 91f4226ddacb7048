//! `mdsolids compare A B`: two campaigns' results side by side. The rows of the two results
//! tables are joined per scene on the grid parameters both campaigns vary there; every numeric
//! column the tables share gets its two values and their ratio B/A; the fitted exponents of the
//! two `summary.csv` files are set against each other; and a report (`report.md`, `index.html`,
//! `plots/*.svg`) shows it all. Everything is read back from the report directories, so
//! campaigns run by different versions of mdsolids can be compared as long as their tables are.

use anyhow::Context as _;
use polars::prelude::{
    Column, CsvReadOptions, CsvWriter, DataFrame, DataType, ParquetReader, ParquetWriter, PolarsResult, SerReader,
    SerWriter,
};
use serde::Serialize;
use std::collections::BTreeSet;
use std::ops::Range;
use std::path::{Path, PathBuf};

use crate::draw::chart::{Chart, Scale, Series, line_chart};
use crate::output::write_atomically;
use crate::sim::RunStatus;

const MARKDOWN_TEMPLATE: &str = include_str!("../templates/compare.md.tera");

/// The columns a `summary.csv` row is identified by. `law` is not among them: comparing a linear
/// campaign with its Hertz twin means comparing fits of different laws.
const SUMMARY_KEYS: [&str; 3] = ["scene", "group", "quantity"];

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
/// `report.md`, `index.html` and `plots/*.svg` into `out`, by default
/// `<reports>/compare-<name of a>-vs-<name of b>`.
pub fn compare(a: &Path, b: &Path, out: Option<&Path>, reports: &Path) -> anyhow::Result<Comparison> {
    let (a, b) = (Side::open(a)?, Side::open(b)?);
    let out = out.map_or_else(|| reports.join(format!("compare-{}-vs-{}", a.name, b.name)), Path::to_path_buf);
    if let Some(owner) = crate::owner::campaign_of(&out) {
        anyhow::bail!(
            "'{}' is the report folder of {owner}: a comparison would overwrite its report; choose another --out",
            out.display()
        );
    }
    let join = join(&a.results, &b.results)?;
    let joined = joined_table(&a.results, &b.results, &join)?;
    let mut frame = joined.table.frame().context("cannot build the joined table")?;
    let mut csv = Vec::new();
    CsvWriter::new(&mut csv).include_header(true).finish(&mut frame)?;
    write_atomically(&out.join("compare.csv"), &csv)?;
    let mut parquet = Vec::new();
    ParquetWriter::new(&mut parquet).finish(&mut frame)?;
    write_atomically(&out.join("compare.parquet"), &parquet)?;

    let mut scenes = Vec::new();
    let mut plots = BTreeSet::new();
    for scene in &join.scenes {
        let section = scene_section(&a, &b, &joined, scene)?;
        for group in &section.plots {
            for plot in &group.plots {
                write_atomically(&out.join(&plot.file), plot.svg.as_bytes())?;
                plots.insert(plot.file.clone());
            }
        }
        scenes.push(section);
    }
    // Figures of an earlier comparison into this folder that this one did not draw.
    crate::report::remove_stale(&out, "plots", ".svg", &plots)?;
    let plots = plots.len();
    let (exponent_rows, missing_summaries) = exponents(&a, &b)?;
    let exponents = exponent_rows.len();
    let context = ReportContext {
        title: format!("{} against {}", a.name, b.name),
        version: env!("CARGO_PKG_VERSION"),
        a: SideInfo::of(&a),
        b: SideInfo::of(&b),
        rows: joined.table.height,
        only_a: join.only_a,
        only_b: join.only_b,
        scenes,
        exponent_rows,
        missing_summaries,
    };
    render(&out, &context)?;
    Ok(Comparison { out, rows: joined.table.height, plots, exponents })
}

/// Writes `report.md` and `index.html` (the same Markdown as HTML inside the page shell).
fn render(out: &Path, context: &ReportContext) -> anyhow::Result<()> {
    let context = tera::Context::from_serialize(context).context("cannot build the comparison context")?;
    crate::report::write_pages(out, ("compare.md", MARKDOWN_TEMPLATE), context)
}

/// One column of a table read back: numbers (any numeric type, as f64) or text.
#[derive(Clone, Debug)]
enum Values {
    Numbers(Vec<Option<f64>>),
    Text(Vec<Option<String>>),
}

impl Values {
    fn read(column: &Column) -> PolarsResult<Values> {
        if column.dtype().is_primitive_numeric() {
            let numbers = column.cast(&DataType::Float64)?;
            Ok(Values::Numbers(numbers.f64()?.iter().collect()))
        } else {
            let text = column.cast(&DataType::String)?;
            Ok(Values::Text(text.str()?.iter().map(|s| s.map(str::to_string)).collect()))
        }
    }

    /// Cell `row` as the text rows are matched on. A number is written in its shortest exact
    /// form, so two numeric cells match exactly when they hold the same f64.
    fn key(&self, row: usize) -> Option<String> {
        match self {
            Values::Numbers(v) => v[row].map(|x| x.to_string()),
            Values::Text(v) => v[row].clone(),
        }
    }

    fn number(&self, row: usize) -> Option<f64> {
        match self {
            Values::Numbers(v) => v[row],
            Values::Text(_) => None,
        }
    }

    fn is_null(&self, row: usize) -> bool {
        match self {
            Values::Numbers(v) => v[row].is_none(),
            Values::Text(v) => v[row].is_none(),
        }
    }

    /// The cells at `rows`, in that order.
    fn gather(&self, rows: impl Iterator<Item = usize>) -> Values {
        match self {
            Values::Numbers(v) => Values::Numbers(rows.map(|r| v[r]).collect()),
            Values::Text(v) => Values::Text(rows.map(|r| v[r].clone()).collect()),
        }
    }
}

/// A results or summary table read back from disk.
struct Table {
    path: PathBuf,
    columns: Vec<(String, Values)>,
    height: usize,
}

impl Table {
    /// Reads a `.csv` or a Parquet file.
    fn read(path: &Path) -> anyhow::Result<Table> {
        let cannot = || format!("cannot read the table '{}'", path.display());
        let file = std::fs::File::open(path).with_context(cannot)?;
        let frame = if path.extension().is_some_and(|e| e == "csv") {
            CsvReadOptions::default().with_has_header(true).into_reader_with_file_handle(file).finish()
        } else {
            ParquetReader::new(file).finish()
        }
        .with_context(cannot)?;
        let columns = frame
            .columns()
            .iter()
            .map(|c| Ok((c.name().to_string(), Values::read(c)?)))
            .collect::<PolarsResult<_>>()
            .with_context(cannot)?;
        Ok(Table { path: path.to_path_buf(), columns, height: frame.height() })
    }

    fn column(&self, name: &str) -> Option<&Values> {
        self.columns.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }

    /// A column the comparison cannot do without.
    fn require(&self, name: &str) -> anyhow::Result<&Values> {
        self.column(name).with_context(|| format!("'{}' has no column `{name}`", self.path.display()))
    }

    fn names(&self) -> impl Iterator<Item = &str> {
        self.columns.iter().map(|(n, _)| n.as_str())
    }

    fn frame(&self) -> PolarsResult<DataFrame> {
        DataFrame::new_infer_height(
            self.columns
                .iter()
                .map(|(name, values)| match values {
                    Values::Numbers(v) => Column::new(name.as_str().into(), v),
                    Values::Text(v) => Column::new(name.as_str().into(), v),
                })
                .collect(),
        )
    }
}

/// One side of the comparison: a campaign's report directory and its tables.
struct Side {
    name: String,
    dir: PathBuf,
    results: Table,
    summary: Option<Table>,
}

impl Side {
    fn open(dir: &Path) -> anyhow::Result<Side> {
        anyhow::ensure!(dir.is_dir(), "report directory '{}' does not exist or is not a directory", dir.display());
        let results = dir.join("results.parquet");
        anyhow::ensure!(
            results.is_file(),
            "'{}' holds no results table: '{}' is missing (`mdsolids run CAMPAIGN` writes it)",
            dir.display(),
            results.display()
        );
        let results = Table::read(&results)?;
        for column in ["run_id", "scene", "status"] {
            results.require(column)?;
        }
        let summary = dir.join("summary.csv");
        let summary = if summary.is_file() { Some(Table::read(&summary)?) } else { None };
        Ok(Side { name: campaign_name(dir)?, dir: dir.to_path_buf(), results, summary })
    }

    fn summary_path(&self) -> PathBuf {
        self.dir.join("summary.csv")
    }
}

/// The last component of `dir` (made absolute first when it has none, as `.` has not).
fn campaign_name(dir: &Path) -> anyhow::Result<String> {
    let absolute;
    let named = if dir.file_name().is_some() {
        dir
    } else {
        absolute = std::fs::canonicalize(dir).with_context(|| format!("cannot resolve '{}'", dir.display()))?;
        &absolute
    };
    named
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .with_context(|| format!("'{}' has no name to call its campaign by", dir.display()))
}

/// How the rows of one scene met.
struct SceneJoin {
    scene: String,
    /// The grid parameters both campaigns vary in this scene: the join keys besides the scene.
    keys: Vec<String>,
    /// Parameters only A varies in this scene (one run of B may meet several of A), and only B.
    only_a: Vec<String>,
    only_b: Vec<String>,
    rows_a: usize,
    rows_b: usize,
    /// This scene's entries of [`Join::pairs`].
    pairs: Range<usize>,
}

/// Which rows of A met which rows of B.
struct Join {
    /// (row of A, row of B), scene by scene in A's order.
    pairs: Vec<(usize, usize)>,
    scenes: Vec<SceneJoin>,
    only_a: Vec<String>,
    only_b: Vec<String>,
}

/// Grid parameters nested in a scene have a dotted column (`time.dt_per_tc`).
fn is_dotted(name: &str) -> bool {
    name.contains('.')
}

/// The top-level fields of a scene a grid may vary (`RawScene` in `spec/raw.rs`). Their columns
/// have no dot, and `v0`, `n` and `supports` share theirs with the resolved value every run has,
/// so that such a field is varied shows only as more than one value within a scene.
const TOP_LEVEL_PARAMETERS: [&str; 6] = ["v0", "gap", "n", "node", "wall_distance", "supports"];

/// A column that may hold a grid parameter.
fn may_be_parameter(name: &str) -> bool {
    is_dotted(name) || TOP_LEVEL_PARAMETERS.contains(&name)
}

/// The distinct values of `column` at `rows`, in order of first appearance.
fn distinct(column: &Values, rows: impl Iterator<Item = usize>) -> Vec<String> {
    let mut seen = Vec::new();
    for value in rows.filter_map(|row| column.key(row)) {
        if !seen.contains(&value) {
            seen.push(value);
        }
    }
    seen
}

/// True when `table` varies parameter `name` at `rows` (one scene): a dotted column has a value
/// there (null only where the scene's grid does not name it), a top-level one takes two values.
fn varies(table: &Table, rows: &[usize], name: &str) -> bool {
    match table.column(name) {
        Some(column) if is_dotted(name) => rows.iter().any(|&r| !column.is_null(r)),
        Some(column) => distinct(column, rows.iter().copied()).len() > 1,
        None => false,
    }
}

/// Joins the rows of A and B scene by scene. The keys are decided per scene: a parameter is a
/// key where both campaigns vary it in that scene, so a parameter only one campaign varies there
/// leaves one row of the other side meeting several. Equal cells match, nulls included (a grid
/// may list `null`).
fn join(a: &Table, b: &Table) -> anyhow::Result<Join> {
    let (scene_a, scene_b) = (a.require("scene")?, b.require("scene")?);
    let (scenes_a, scenes_b) = (distinct(scene_a, 0..a.height), distinct(scene_b, 0..b.height));
    let common: Vec<&str> = a.names().filter(|n| may_be_parameter(n) && b.column(n).is_some()).collect();
    let mut pairs = Vec::new();
    let mut scenes = Vec::new();
    for scene in scenes_a.iter().filter(|s| scenes_b.contains(s)) {
        let rows = |table: &Table, column: &Values| -> Vec<usize> {
            (0..table.height).filter(|&r| column.key(r).as_ref() == Some(scene)).collect()
        };
        let (rows_a, rows_b) = (rows(a, scene_a), rows(b, scene_b));
        let keys: Vec<&str> =
            common.iter().copied().filter(|&n| varies(a, &rows_a, n) && varies(b, &rows_b, n)).collect();
        let columns: Vec<(&Values, &Values)> =
            keys.iter().map(|&n| Ok((a.require(n)?, b.require(n)?))).collect::<anyhow::Result<_>>()?;
        let start = pairs.len();
        for &i in &rows_a {
            for &j in &rows_b {
                if columns.iter().all(|(ka, kb)| ka.key(i) == kb.key(j)) {
                    pairs.push((i, j));
                }
            }
        }
        let only = |table: &Table, rows: &[usize]| -> Vec<String> {
            let names = table.names().filter(|n| may_be_parameter(n) && !keys.contains(n));
            names.filter(|n| varies(table, rows, n)).map(str::to_string).collect()
        };
        scenes.push(SceneJoin {
            scene: scene.clone(),
            only_a: only(a, &rows_a),
            only_b: only(b, &rows_b),
            keys: keys.iter().map(|n| n.to_string()).collect(),
            rows_a: rows_a.len(),
            rows_b: rows_b.len(),
            pairs: start..pairs.len(),
        });
    }
    let only = |own: &[String], other: &[String]| own.iter().filter(|s| !other.contains(s)).cloned().collect();
    Ok(Join { pairs, only_a: only(&scenes_a, &scenes_b), only_b: only(&scenes_b, &scenes_a), scenes })
}

/// The joined table, with the names of its metric columns.
struct Joined {
    table: Table,
    /// Metrics: each has `<metric>_a`, `<metric>_b` and `<metric>_ratio` in the table.
    metrics: Vec<String>,
}

/// B/A where both runs ended `ok`, both values exist and A is not zero.
fn ratio(ok: bool, a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) if ok && a != 0.0 => Some(b / a).filter(|r| r.is_finite()),
        _ => None,
    }
}

/// Builds the joined table: `scene`; every dotted grid parameter, holding the value both sides
/// share where it is a key and otherwise the value of the one side that varies it; `status_a`,
/// `status_b`, `run_id_a`, `run_id_b`; the text top-level parameters (`supports`) of each side;
/// then for every numeric column both tables have (the metrics, with the wall times and the
/// resolved inputs such as `t_c` and `dt`, which differ between campaigns of different laws, and
/// `v0`, `n`) its two values and their ratio.
fn joined_table(a: &Table, b: &Table, join: &Join) -> anyhow::Result<Joined> {
    let rows_a = || join.pairs.iter().map(|p| p.0);
    let rows_b = || join.pairs.iter().map(|p| p.1);
    let mut columns = vec![("scene".to_string(), a.require("scene")?.gather(rows_a()))];
    for (name, va) in a.columns.iter().filter(|(n, _)| is_dotted(n)) {
        let merged = match (va, b.column(name)) {
            (Values::Numbers(va), Some(Values::Numbers(vb))) => {
                Values::Numbers(join.pairs.iter().map(|&(i, j)| va[i].or(vb[j])).collect())
            }
            (va, Some(vb)) => Values::Text(join.pairs.iter().map(|&(i, j)| va.key(i).or(vb.key(j))).collect()),
            (va, None) => va.gather(rows_a()),
        };
        columns.push((name.clone(), merged));
    }
    for (name, vb) in b.columns.iter().filter(|(n, _)| is_dotted(n) && a.column(n).is_none()) {
        columns.push((name.clone(), vb.gather(rows_b())));
    }
    for name in ["status", "run_id"] {
        columns.push((format!("{name}_a"), a.require(name)?.gather(rows_a())));
        columns.push((format!("{name}_b"), b.require(name)?.gather(rows_b())));
    }
    let is_metric = |name: &str| {
        !is_dotted(name)
            && matches!((a.column(name), b.column(name)), (Some(Values::Numbers(_)), Some(Values::Numbers(_))))
    };
    for name in TOP_LEVEL_PARAMETERS.into_iter().filter(|n| !is_metric(n)) {
        if let Some(va) = a.column(name) {
            columns.push((format!("{name}_a"), va.gather(rows_a())));
        }
        if let Some(vb) = b.column(name) {
            columns.push((format!("{name}_b"), vb.gather(rows_b())));
        }
    }
    let ok: Vec<bool> = join
        .pairs
        .iter()
        .map(|&(i, j)| {
            let ok =
                |t: &Table, r| t.column("status").and_then(|s| s.key(r)).is_some_and(|s| s == RunStatus::Ok.as_str());
            ok(a, i) && ok(b, j)
        })
        .collect();
    let mut metrics = Vec::new();
    for (name, va) in a.columns.iter().filter(|(n, _)| is_metric(n)) {
        let vb = b.require(name)?;
        let value_a = va.gather(rows_a());
        let value_b = vb.gather(rows_b());
        let ratios = (0..join.pairs.len()).map(|r| ratio(ok[r], value_a.number(r), value_b.number(r))).collect();
        columns.push((format!("{name}_a"), value_a));
        columns.push((format!("{name}_b"), value_b));
        columns.push((format!("{name}_ratio"), Values::Numbers(ratios)));
        metrics.push(name.clone());
    }
    let table = Table { path: PathBuf::from("compare.parquet"), columns, height: join.pairs.len() };
    Ok(Joined { table, metrics })
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
    scenes: Vec<SceneSection>,
    exponent_rows: Vec<ExponentRow>,
    /// The `summary.csv` files that do not exist (then no exponent is compared).
    missing_summaries: Vec<String>,
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

#[derive(Serialize)]
struct SceneSection {
    name: String,
    keys: Vec<String>,
    only_a: Vec<String>,
    only_b: Vec<String>,
    rows: usize,
    rows_a: usize,
    rows_b: usize,
    ok: usize,
    /// Joined rows that are not `ok` on both sides, by (status A, status B).
    statuses: Vec<StatusCount>,
    metrics: Vec<MetricRow>,
    plots: Vec<PlotGroup>,
}

#[derive(Serialize)]
struct StatusCount {
    a: String,
    b: String,
    rows: usize,
}

#[derive(Serialize)]
struct MetricRow {
    metric: String,
    a: String,
    b: String,
    ratio: String,
    range: String,
    ratios: usize,
}

/// The figures of one scene against one parameter.
#[derive(Serialize)]
struct PlotGroup {
    parameter: String,
    plots: Vec<PlotLink>,
}

#[derive(Serialize)]
struct PlotLink {
    metric: String,
    file: String,
    #[serde(skip)]
    svg: String,
}

/// A value in the comparison tables: the same form at every magnitude, so that A and B line
/// up digit by digit.
fn value(x: Option<f64>) -> String {
    x.map_or_else(|| "–".into(), |x| format!("{x:.4e}"))
}

/// A ratio, an exponent or an R²: fixed decimals for the values of order one they mostly are.
fn fixed(x: Option<f64>) -> String {
    match x {
        Some(x) if x == 0.0 || (1e-3..1e4).contains(&x.abs()) => format!("{x:.4}"),
        Some(x) => format!("{x:.3e}"),
        None => "–".into(),
    }
}

fn median(mut values: Vec<f64>) -> Option<f64> {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(values[n / 2]),
        _ => Some(0.5 * (values[n / 2 - 1] + values[n / 2])),
    }
}

/// The report section of one scene: the statuses of rows not `ok` on both sides, the metrics
/// table (medians over the rows `ok` on both sides, each run counted once) and the overlaid
/// figures (each side's `ok` runs).
fn scene_section(a: &Side, b: &Side, joined: &Joined, scene: &SceneJoin) -> anyhow::Result<SceneSection> {
    let table = &joined.table;
    let rows: Vec<usize> = scene.pairs.clone().collect();
    let cell = |name: &str, r: usize| table.column(name).and_then(|c| c.key(r));
    let ok = |side: &str, r: usize| cell(&format!("status_{side}"), r).is_some_and(|s| s == RunStatus::Ok.as_str());
    let both: Vec<usize> = rows.iter().copied().filter(|&r| ok("a", r) && ok("b", r)).collect();
    let mut statuses: Vec<StatusCount> = Vec::new();
    for &r in rows.iter().filter(|&&r| !(ok("a", r) && ok("b", r))) {
        let (sa, sb) = (cell("status_a", r).unwrap_or_default(), cell("status_b", r).unwrap_or_default());
        match statuses.iter_mut().find(|c| c.a == sa && c.b == sb) {
            Some(count) => count.rows += 1,
            None => statuses.push(StatusCount { a: sa, b: sb, rows: 1 }),
        }
    }
    // One run of a side may meet several of the other: count it once (by its run id).
    let once = |side: &str, rows: &[usize]| -> Vec<usize> {
        let mut seen = BTreeSet::new();
        rows.iter().copied().filter(|&r| seen.insert(cell(&format!("run_id_{side}"), r))).collect()
    };
    let metric =
        |name: &str, suffix: &str| table.column(&format!("{name}_{suffix}")).expect("every metric has its columns");
    let mut metrics = Vec::new();
    for name in &joined.metrics {
        let with_ratio: Vec<usize> =
            both.iter().copied().filter(|&r| metric(name, "ratio").number(r).is_some()).collect();
        // A and B over the rows behind the ratios, so that the three agree; where there is no
        // ratio (a value of zero or missing on one side), over every row ok on both sides.
        let basis = if with_ratio.is_empty() { &both } else { &with_ratio };
        let values = |side: &str| -> Vec<f64> {
            once(side, basis).into_iter().filter_map(|r| metric(name, side).number(r)).collect()
        };
        let (va, vb) = (values("a"), values("b"));
        if va.is_empty() && vb.is_empty() {
            continue;
        }
        let ratios: Vec<f64> = with_ratio.iter().filter_map(|&r| metric(name, "ratio").number(r)).collect();
        let (lo, hi) = ratios.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)));
        metrics.push(MetricRow {
            metric: name.clone(),
            a: value(median(va)),
            b: value(median(vb)),
            range: if ratios.len() > 1 {
                format!("{} … {}", fixed(Some(lo)), fixed(Some(hi)))
            } else {
                String::new()
            },
            ratios: ratios.len(),
            ratio: fixed(median(ratios)),
        });
    }
    let mut plots = Vec::new();
    for parameter in &scene.keys {
        // A top-level key is a metric column too; being a key, its two sides agree.
        let column = if is_dotted(parameter) { parameter.clone() } else { format!("{parameter}_a") };
        let Some(Values::Numbers(x)) = table.column(&column) else { continue };
        if rows.iter().filter_map(|&r| x[r]).map(f64::to_bits).collect::<BTreeSet<_>>().len() < 2 {
            continue;
        }
        let mut group = PlotGroup { parameter: parameter.clone(), plots: Vec::new() };
        for row in &metrics {
            let points = |side: &str| -> Vec<(f64, f64)> {
                let own: Vec<usize> = rows.iter().copied().filter(|&r| ok(side, r)).collect();
                let mut points: Vec<(f64, f64)> = once(side, &own)
                    .into_iter()
                    .filter_map(|r| Some((x[r]?, metric(&row.metric, side).number(r)?)))
                    .collect();
                points.sort_by(|p, q| p.0.total_cmp(&q.0));
                points
            };
            let (pa, pb) = (points("a"), points("b"));
            let all: Vec<(f64, f64)> = pa.iter().chain(&pb).copied().collect();
            let count_distinct =
                |get: fn(&(f64, f64)) -> f64| all.iter().map(|p| get(p).to_bits()).collect::<BTreeSet<_>>().len();
            // One x or one y value in all, or the parameter itself (`dt_per_tc` against
            // `time.dt_per_tc`): the table above says all there is.
            if count_distinct(|p| p.0) < 2 || count_distinct(|p| p.1) < 2 || all.iter().all(|p| p.0 == p.1) {
                continue;
            }
            let chart = Chart {
                title: format!("{}: {} against {parameter}", scene.scene, row.metric),
                x_label: parameter.clone(),
                y_label: row.metric.clone(),
                scale: scale(&all),
            };
            let series = [series(format!("A: {}", a.name), pa), series(format!("B: {}", b.name), pb)];
            let svg = line_chart(&chart, &series)
                .with_context(|| format!("cannot draw {} against {parameter} for scene {}", row.metric, scene.scene))?;
            let file =
                format!("plots/{}-{}-vs-{}.svg", file_part(&scene.scene), file_part(&row.metric), file_part(parameter));
            group.plots.push(PlotLink { metric: row.metric.clone(), file, svg });
        }
        if !group.plots.is_empty() {
            plots.push(group);
        }
    }
    Ok(SceneSection {
        name: scene.scene.clone(),
        keys: scene.keys.clone(),
        only_a: scene.only_a.clone(),
        only_b: scene.only_b.clone(),
        rows: rows.len(),
        rows_a: scene.rows_a,
        rows_b: scene.rows_b,
        ok: both.len(),
        statuses,
        metrics,
        plots,
    })
}

/// A side's points as one series: a line through one run per parameter value, markers where
/// other grid values put several runs at one value.
fn series(label: String, points: Vec<(f64, f64)>) -> Series {
    let markers = points.windows(2).any(|w| w[0].0 == w[1].0);
    Series { label, points, markers }
}

/// Logarithmic along each axis whose values are positive and span more than a decade.
fn scale(points: &[(f64, f64)]) -> Scale {
    let spans_decades = |get: fn(&(f64, f64)) -> f64| {
        let (lo, hi) =
            points.iter().map(get).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
        lo > 0.0 && hi > 10.0 * lo
    };
    match (spans_decades(|p| p.0), spans_decades(|p| p.1)) {
        (true, true) => Scale::LogLog,
        (true, false) => Scale::LogX,
        (false, true) => Scale::LogY,
        (false, false) => Scale::Linear,
    }
}

/// A name made safe for a file name.
fn file_part(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || "-_.".contains(c) { c } else { '_' }).collect()
}

#[derive(Serialize)]
struct ExponentRow {
    scene: String,
    group: String,
    quantity: String,
    law_a: String,
    law_b: String,
    exponent_a: String,
    exponent_b: String,
    difference: String,
    r_squared_a: String,
    r_squared_b: String,
}

/// The exponent table: every fit of either `summary.csv`, matched on [`SUMMARY_KEYS`] (a fit
/// without a partner shows – on the other side), or the missing `summary.csv` files (the
/// template names them; paths are data, escaped there).
fn exponents(a: &Side, b: &Side) -> anyhow::Result<(Vec<ExponentRow>, Vec<String>)> {
    let (Some(sa), Some(sb)) = (&a.summary, &b.summary) else {
        let missing = [a, b]
            .iter()
            .filter(|side| side.summary.is_none())
            .map(|side| side.summary_path().display().to_string())
            .collect();
        return Ok((Vec::new(), missing));
    };
    let keys: Vec<(&Values, &Values)> =
        SUMMARY_KEYS.iter().filter_map(|&k| Some((sa.column(k)?, sb.column(k)?))).collect();
    let (exponent_a, exponent_b) = (sa.require("exponent")?, sb.require("exponent")?);
    let (r_squared_a, r_squared_b) = (sa.require("r_squared")?, sb.require("r_squared")?);
    let number = |column: &Values, row: Option<usize>| row.and_then(|r| column.number(r));
    let text = |table: &Table, name: &str, row: Option<usize>| row.and_then(|r| table.column(name)?.key(r));
    let row = |i: Option<usize>, j: Option<usize>| {
        let shared = |name: &str| text(sa, name, i).or_else(|| text(sb, name, j)).unwrap_or_else(|| "–".into());
        let (ea, eb) = (number(exponent_a, i), number(exponent_b, j));
        ExponentRow {
            scene: shared("scene"),
            group: shared("group"),
            quantity: shared("quantity"),
            law_a: text(sa, "law", i).unwrap_or_else(|| "–".into()),
            law_b: text(sb, "law", j).unwrap_or_else(|| "–".into()),
            exponent_a: fixed(ea),
            exponent_b: fixed(eb),
            difference: fixed(ea.zip(eb).map(|(ea, eb)| eb - ea)),
            r_squared_a: fixed(number(r_squared_a, i)),
            r_squared_b: fixed(number(r_squared_b, j)),
        }
    };
    let mut rows = Vec::new();
    let mut matched = vec![false; sb.height];
    for i in 0..sa.height {
        let partners: Vec<usize> =
            (0..sb.height).filter(|&j| keys.iter().all(|(ka, kb)| ka.key(i) == kb.key(j))).collect();
        if partners.is_empty() {
            rows.push(row(Some(i), None));
        }
        for j in partners {
            matched[j] = true;
            rows.push(row(Some(i), Some(j)));
        }
    }
    for j in (0..sb.height).filter(|&j| !matched[j]) {
        rows.push(row(None, Some(j)));
    }
    Ok((rows, Vec::new()))
}
