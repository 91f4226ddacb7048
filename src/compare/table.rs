//! The tables of a report directory read back (`results.parquet`, `summary.csv`), columns as
//! numbers (any numeric type, as f64) or text, and one side of the comparison.

use anyhow::Context as _;
use polars::prelude::{Column, CsvReadOptions, DataFrame, DataType, ParquetReader, PolarsResult, SerReader};
use std::path::{Path, PathBuf};

use crate::output::read_regular;
use crate::table::TABLE_MOST_BYTES;

/// One column of a table read back: numbers (any numeric type, as f64) or text.
#[derive(Clone, Debug)]
pub(super) enum Values {
    Numbers(Vec<Option<f64>>),
    Text(Vec<Option<String>>),
}

impl Values {
    pub(super) fn read(column: &Column) -> PolarsResult<Values> {
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
    pub(super) fn key(&self, row: usize) -> Option<String> {
        match self {
            Values::Numbers(v) => v[row].map(|x| x.to_string()),
            Values::Text(v) => v[row].clone(),
        }
    }

    pub(super) fn number(&self, row: usize) -> Option<f64> {
        match self {
            Values::Numbers(v) => v[row],
            Values::Text(_) => None,
        }
    }

    pub(super) fn is_null(&self, row: usize) -> bool {
        match self {
            Values::Numbers(v) => v[row].is_none(),
            Values::Text(v) => v[row].is_none(),
        }
    }

    /// The cells where `keep` holds, null elsewhere.
    pub(super) fn masked(&self, keep: impl Fn(usize) -> bool) -> Values {
        match self {
            Values::Numbers(v) => Values::Numbers(v.iter().enumerate().map(|(r, x)| x.filter(|_| keep(r))).collect()),
            Values::Text(v) => Values::Text(v.iter().enumerate().map(|(r, x)| x.clone().filter(|_| keep(r))).collect()),
        }
    }

    /// The cells at `rows`, in that order.
    pub(super) fn gather(&self, rows: impl Iterator<Item = usize>) -> Values {
        match self {
            Values::Numbers(v) => Values::Numbers(rows.map(|r| v[r]).collect()),
            Values::Text(v) => Values::Text(rows.map(|r| v[r].clone()).collect()),
        }
    }
}

/// A results or summary table read back from disk.
pub(super) struct Table {
    pub(super) path: PathBuf,
    pub(super) columns: Vec<(String, Values)>,
    pub(super) height: usize,
}

impl Table {
    /// Reads a `.csv` or a Parquet file.
    pub(super) fn read(path: &Path) -> anyhow::Result<Table> {
        let cannot = || format!("cannot read the table '{}'", path.display());
        let bytes = std::io::Cursor::new(read_regular(path, TABLE_MOST_BYTES, "a table").with_context(cannot)?);
        let frame = if path.extension().is_some_and(|e| e == "csv") {
            CsvReadOptions::default().with_has_header(true).into_reader_with_file_handle(bytes).finish()
        } else {
            ParquetReader::new(bytes).finish()
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

    pub(super) fn column(&self, name: &str) -> Option<&Values> {
        self.columns.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }

    /// A column the comparison cannot do without.
    pub(super) fn require(&self, name: &str) -> anyhow::Result<&Values> {
        self.column(name).with_context(|| format!("'{}' has no column `{name}`", self.path.display()))
    }

    pub(super) fn names(&self) -> impl Iterator<Item = &str> {
        self.columns.iter().map(|(n, _)| n.as_str())
    }

    pub(super) fn frame(&self) -> PolarsResult<DataFrame> {
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
pub(super) struct Side {
    pub(super) name: String,
    pub(super) dir: PathBuf,
    pub(super) results: Table,
    pub(super) summary: Option<Table>,
}

impl Side {
    pub(super) fn open(dir: &Path) -> anyhow::Result<Side> {
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

    pub(super) fn summary_path(&self) -> PathBuf {
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
