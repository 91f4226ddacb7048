#!/usr/bin/env bash
# CI: a real single-node Slurm cluster (Debian packages, started by ../shared/slurm/slurm-local.sh)
# runs a campaign as a 4-task job array plus its afterany report job (`mdsolids slurm --submit`);
# the merged results table must equal the same campaign run locally, row for row, apart from
# the measured-time columns wall_s and loop_s.
#
# Skipped (exit 0, "SKIP" message) where Slurm cannot be installed: not root, no apt-get, no
# recipe beside the clone, or the packages do not install. Once installed, a cluster that does
# not start or a table that differs fails the step. The daemons are always stopped on exit.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)
campaign=campaigns/shards.yaml
tasks=4
recipe=$repo/../shared/slurm/slurm-local.sh

skip() {
  echo "SKIP slurm test: $* (the sharding itself is still tested by tests/suite/cluster.rs)"
  exit 0
}
[ "$(id -u)" = 0 ] || skip "needs root to install and start Slurm"
[ -f "$recipe" ] || skip "no Slurm recipe at $recipe (../shared must be beside the clone)"
if ! command -v sbatch >/dev/null || ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  command -v apt-get >/dev/null || skip "no apt-get to install slurm-wlm and munge"
  started=$(date +%s)
  { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends slurm-wlm munge; } \
    >/tmp/slurm-test-apt.log 2>&1 || { tail -n 20 /tmp/slurm-test-apt.log; skip "apt-get could not install slurm-wlm munge"; }
  echo "slurm-wlm and munge installed in $(($(date +%s) - started)) s"
fi

# shellcheck source=/dev/null
source "$recipe"
work=$(mktemp -d)
trap 'slurm_local_stop || true; rm -rf "$work"' EXIT
slurm_local_start || { echo "FAIL: the local Slurm cluster did not start" >&2; exit 1; }

cargo build --release -q
bin=${CARGO_TARGET_DIR:-$repo/target}/release/mdsolids
"$bin" --reports "$work/local" run "$campaign"

submitted=$(date +%s.%N)
out=$("$bin" --reports "$work/slurm" slurm "$campaign" --tasks "$tasks" --time 10 --submit)
echo "$out"
# "submitted: array job <id>, report job <id> (afterany)"
ids=$(echo "$out" | sed -n 's/^submitted: array job \([0-9]*\), report job \([0-9]*\) .*/\1 \2/p')
[ -n "$ids" ] || { echo "FAIL: no job ids in the output of mdsolids slurm" >&2; exit 1; }
# shellcheck disable=SC2086  # two ids, split on purpose
slurm_local_wait 300 $ids || { echo "FAIL: the array or the report job did not finish" >&2; exit 1; }
finished=$(date +%s.%N)

logs=$work/slurm/shards/slurm
for log in "$logs"/*.log; do echo "--- ${log##*/}"; cat "$log"; done
grep -q "(0 without results, 0 corrupt, 0 of another build)" "$logs"/report-*.log || { echo "FAIL: the report job did not merge every run" >&2; exit 1; }

# Compare the tables without the timing columns (found by name in the header).
timing=$(head -n 1 "$work/local/shards/results.csv" | tr , '\n' | grep -nx 'wall_s\|loop_s' | cut -d: -f1 | paste -sd,)
without_timing() { cut --complement -d, -f "$timing" "$1"; }
if ! diff <(without_timing "$work/local/shards/results.csv") <(without_timing "$work/slurm/shards/results.csv"); then
  echo "FAIL: the Slurm results table differs from the local one" >&2
  exit 1
fi
rows=$(($(wc -l <"$work/local/shards/results.csv") - 1))
echo "slurm test: $rows runs over a $tasks-task array + afterany report job give the local results table" \
  "row for row; submit -> report done in $(awk -v a="$submitted" -v b="$finished" 'BEGIN { printf "%.1f", b - a }') s"
