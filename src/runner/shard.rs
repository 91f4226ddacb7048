//! Shares of a campaign for separate processes (`mdsolids run --shard I/N`, Slurm array tasks):
//! deterministic, balanced by the plan's cost estimate, and independent of what is stored, so
//! every task of an array and every rerun agrees on who runs what.

use std::collections::BTreeMap;

use crate::spec::{Campaign, MAX_RUNS, RunSpec};

/// Share `index` of `count` (0 ≤ index < count, 0-based like `SLURM_ARRAY_TASK_ID` of an
/// array `--array=0-(count-1)`), written `index/count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which share, from 0.
    pub index: usize,
    /// How many shares.
    pub count: usize,
}

impl std::str::FromStr for Shard {
    type Err = String;

    fn from_str(text: &str) -> Result<Shard, String> {
        let invalid =
            || format!("'{text}': expected I/N with 0 ≤ I < N, e.g. 0/4 (I is 0-based like SLURM_ARRAY_TASK_ID)");
        let (index, count) = text.split_once('/').ok_or_else(invalid)?;
        let index: usize = index.trim().parse().map_err(|_| invalid())?;
        let count: usize = count.trim().parse().map_err(|_| invalid())?;
        if index >= count {
            return Err(invalid());
        }
        // More shares than a campaign can have runs would only be empty; refused before the
        // per-share bookkeeping is allocated.
        if count as u64 > MAX_RUNS {
            return Err(format!(
                "'{text}': N = {count} shares; at most {MAX_RUNS} (a campaign has at most {MAX_RUNS} runs)"
            ));
        }
        Ok(Shard { index, count })
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// The campaign reduced to the runs of `shard`, in campaign order.
pub fn shard_campaign(campaign: &Campaign, shard: Shard) -> Campaign {
    let owners = shard_of_each_run(&campaign.runs, shard.count);
    let runs = campaign.runs.iter().zip(&owners).filter(|(_, owner)| **owner == shard.index).map(|(r, _)| r.clone());
    Campaign { runs: runs.collect(), ..campaign.clone() }
}

/// The shard (0..count) of each run. The runs of a scene shown side by side stay together:
/// that movie is drawn from the frames of all of them in one process (see the runner).
pub fn shard_of_each_run(runs: &[RunSpec], count: usize) -> Vec<usize> {
    let mut units: Vec<Vec<usize>> = Vec::new();
    let mut side_by_side: BTreeMap<&str, usize> = BTreeMap::new();
    for (index, run) in runs.iter().enumerate() {
        if run.movie.is_some_and(|m| m.side_by_side) {
            let unit = *side_by_side.entry(run.scene.as_str()).or_insert_with(|| {
                units.push(Vec::new());
                units.len() - 1
            });
            units[unit].push(index);
        } else {
            units.push(vec![index]);
        }
    }
    let weighted: Vec<(f64, String)> = units
        .iter()
        .map(|members| {
            let cost = members.iter().map(|&i| runs[i].estimated_seconds()).sum();
            let key = members.iter().map(|&i| runs[i].run_id()).min().expect("a unit has a run");
            (cost, key)
        })
        .collect();
    let unit_shards = balance(&weighted, count);
    let mut owners = vec![0; runs.len()];
    for (members, shard) in units.iter().zip(unit_shards) {
        for &index in members {
            owners[index] = shard;
        }
    }
    owners
}

/// Longest processing time first: items `(cost, key)` by cost, largest first (ties by key),
/// each to the shard with the least cost so far (ties to the lowest index). The order depends
/// only on costs and keys, never on input order or on the store; the largest shard exceeds
/// the mean by at most one item's cost.
pub fn balance(items: &[(f64, String)], count: usize) -> Vec<usize> {
    assert!(count >= 1, "at least one shard");
    let mut order: Vec<usize> = (0..items.len()).collect();
    order.sort_by(|&a, &b| items[b].0.total_cmp(&items[a].0).then_with(|| items[a].1.cmp(&items[b].1)));
    // Shares past the number of items stay empty: while fewer than all items are placed, one of
    // the first `items` shares is still empty (load 0, the lowest such index wins the tie), so
    // with costs ≥ 0 leaving the others out changes nothing and keeps the work O(items²).
    let mut loads = vec![0.0_f64; count.min(items.len()).max(1)];
    let count = loads.len();
    let mut shards = vec![0; items.len()];
    for item in order {
        let lightest = (0..count).min_by(|&a, &b| loads[a].total_cmp(&loads[b]).then(a.cmp(&b))).expect("count ≥ 1");
        loads[lightest] += items[item].0;
        shards[item] = lightest;
    }
    shards
}
