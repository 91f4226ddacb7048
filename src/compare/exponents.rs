//! The exponent table of a comparison: every fit of either side's `summary.csv`, matched on
//! scene, group and quantity, with the difference of the exponents.

use serde::Serialize;

use super::table::{Side, Table, Values};
use super::words::fixed;

/// The columns a `summary.csv` row is identified by. `law` is not among them: comparing a linear
/// campaign with its Hertz twin means comparing fits of different laws.
const SUMMARY_KEYS: [&str; 3] = ["scene", "group", "quantity"];

#[derive(Serialize)]
pub(super) struct ExponentRow {
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
pub(super) fn exponents(a: &Side, b: &Side) -> anyhow::Result<(Vec<ExponentRow>, Vec<String>)> {
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
