//! Unit tests of `src/runner/shard.rs`, moved out of the library (one test binary).

use mdsolids::runner::shard::{Shard, balance, shard_campaign, shard_of_each_run};
use mdsolids::spec::{Campaign, RunSpec};

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
    let campaign = mdsolids::plan::parse("t.yaml", yaml).unwrap().campaign;
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
