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
fn balance(items: &[(f64, String)], count: usize) -> Vec<usize> {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn items(costs: &[f64]) -> Vec<(f64, String)> {
        costs.iter().enumerate().map(|(i, &c)| (c, format!("run-{i:03}"))).collect()
    }

    fn loads(items: &[(f64, String)], shards: &[usize], count: usize) -> Vec<f64> {
        let mut loads = vec![0.0; count];
        for (item, &shard) in items.iter().zip(shards) {
            loads[shard] += item.0;
        }
        loads
    }

    /// Costs spread over four decades, like a campaign of pairs, chains and lattices.
    fn campaign_like_costs() -> Vec<f64> {
        (0..97).map(|i: u32| 1e-4 * 10f64.powf(f64::from((i * 37) % 97) / 24.0)).collect()
    }

    #[test]
    fn every_item_goes_to_exactly_one_shard_in_range() {
        let items = items(&campaign_like_costs());
        for count in [1, 2, 3, 4, 8, 100, 200] {
            let shards = balance(&items, count);
            assert_eq!(shards.len(), items.len());
            assert!(shards.iter().all(|&s| s < count), "{count} shards: {shards:?}");
        }
    }

    #[test]
    fn the_largest_shard_exceeds_the_mean_by_at_most_one_item() {
        let items = items(&campaign_like_costs());
        let largest_item = items.iter().map(|i| i.0).fold(0.0, f64::max);
        let total: f64 = items.iter().map(|i| i.0).sum();
        for count in [2, 3, 4, 7, 16] {
            let loads = loads(&items, &balance(&items, count), count);
            let largest = loads.iter().copied().fold(0.0, f64::max);
            assert!(largest <= total / count as f64 + largest_item + 1e-12, "{count} shards: {loads:?}");
        }
        // Equal costs split evenly.
        let equal = self::items(&[1.0; 12]);
        assert_eq!(loads(&equal, &balance(&equal, 4), 4), vec![3.0; 4]);
    }

    #[test]
    fn the_assignment_ignores_input_order() {
        let items = items(&campaign_like_costs());
        let shards = balance(&items, 4);
        let mut reversed = items.clone();
        reversed.reverse();
        let mut again = balance(&reversed, 4);
        again.reverse();
        assert_eq!(shards, again);
        assert_eq!(shards, balance(&items, 4), "the same input gives the same shares");
    }

    #[test]
    fn a_side_by_side_scene_stays_in_one_shard_and_the_shards_cover_the_campaign() {
        let yaml = "version: 1\nname: t\nscenes:\n  - name: kick\n    kind: lattice\n    lattice: {size: 5}\n    \
                    supports: free\n    impulse: {velocity: [0.0, -0.01]}\n    \
                    movie: {frames: 5, width: 300, height: 200, side_by_side: true}\n    \
                    grid:\n      lattice.diagonals: [none, both]\n  \
                    - name: p\n    kind: pair\n    v0: 1.0\n    grid:\n      time.dt_per_tc: [10, 20, 30, 40, 50, 60]\n";
        let campaign = crate::plan::parse("t.yaml", yaml).unwrap().campaign;
        let owners = shard_of_each_run(&campaign.runs, 4);
        let kick: Vec<usize> =
            campaign.runs.iter().zip(&owners).filter(|(r, _)| r.scene == "kick").map(|(_, &s)| s).collect();
        assert_eq!(kick.len(), 2);
        assert_eq!(kick[0], kick[1], "the side-by-side runs share a shard");
        let shares: Vec<Campaign> = (0..4).map(|index| shard_campaign(&campaign, Shard { index, count: 4 })).collect();
        let mut ids: Vec<String> = shares.iter().flat_map(|c| c.runs.iter().map(RunSpec::run_id)).collect();
        ids.sort();
        let mut all: Vec<String> = campaign.runs.iter().map(RunSpec::run_id).collect();
        all.sort();
        assert_eq!(ids, all, "every run in exactly one share");
        assert!(shares.iter().all(|c| !c.runs.is_empty()));
    }

    #[test]
    fn shard_arguments_are_validated() {
        assert_eq!("2/4".parse::<Shard>(), Ok(Shard { index: 2, count: 4 }));
        assert_eq!("0/1".parse::<Shard>().map(|s| s.to_string()), Ok("0/1".to_string()));
        for bad in ["4/4", "1/0", "3", "-1/4", "a/b", "1/4/2", ""] {
            let error = bad.parse::<Shard>().expect_err(bad);
            assert!(error.contains("0 ≤ I < N"), "{bad}: {error}");
        }
        // One past the limit, and the 800 GB of per-share loads that once aborted the process.
        assert!("0/100000".parse::<Shard>().is_ok());
        for huge in ["0/100001", "0/100000000000"] {
            let error = huge.parse::<Shard>().expect_err(huge);
            assert!(error.contains("at most 100000"), "{huge}: {error}");
        }
    }
}
