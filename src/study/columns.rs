//! The result columns a kind declares beside its metrics group: where they stand in the
//! results table, when they are shown, and their value in one run. The table (`crate::table`)
//! turns them into columns; a kind's columns are named by its own file, not by the table.

use crate::spec::RunSpec;

/// Where a kind's columns stand among the table's own.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slot {
    /// After `duration`: the scene's size.
    Size,
    /// After `v0`: what the kind measures against its exact answer.
    Measured,
    /// After `energy_error`: the kind's own error.
    Error,
    /// After the stability columns, before the wave's: the kind's resolved parameters and
    /// measurements.
    Tail,
}

/// One run as a kind's columns read it: its spec, its kind's metrics group `G`, and what every
/// relaxing run has (when and by which criterion it came to rest, the steps it took).
pub struct Row<'a, G> {
    /// The run's spec.
    pub spec: &'a RunSpec,
    /// The kind's metrics group of the run.
    pub group: &'a G,
    /// Time (s) from which the relaxation criterion held.
    pub dissipation_time: Option<f64>,
    /// The relaxation criterion, in words.
    pub dissipation_criterion: Option<&'a str>,
    /// Steps the run took.
    pub steps: u64,
}

/// A column and its value in a run: a number (non-finite ones become null in the table), a
/// count or a word; `None` where the run has no such value.
pub enum Column<G> {
    /// Numbers.
    Number(&'static str, fn(&Row<G>) -> Option<f64>),
    /// Counts.
    Count(&'static str, fn(&Row<G>) -> Option<u64>),
    /// Words.
    Word(&'static str, fn(&Row<G>) -> Option<String>),
}

/// Columns a kind declares at one slot, shown when any run passes `shown` (always when `None`).
pub struct Block<G: 'static> {
    /// Where they stand.
    pub slot: Slot,
    /// Which runs call for them.
    pub shown: Option<fn(&RunSpec) -> bool>,
    /// The columns, in order.
    pub columns: Vec<Column<G>>,
}

/// A column's values over the runs, in run order.
pub enum Values {
    /// Numbers.
    Numbers(Vec<Option<f64>>),
    /// Counts.
    Counts(Vec<Option<u64>>),
    /// Words.
    Words(Vec<Option<String>>),
}

impl<G> Column<G> {
    /// The column's name.
    pub fn name(&self) -> &'static str {
        match self {
            Column::Number(name, _) | Column::Count(name, _) | Column::Word(name, _) => name,
        }
    }

    /// Its values in `rows`.
    pub fn values(&self, rows: &[Row<G>]) -> Values {
        match self {
            Column::Number(_, get) => Values::Numbers(rows.iter().map(get).collect()),
            Column::Count(_, get) => Values::Counts(rows.iter().map(get).collect()),
            Column::Word(_, get) => Values::Words(rows.iter().map(get).collect()),
        }
    }
}
