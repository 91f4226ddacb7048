#!/usr/bin/env bash
# The static solve against a sparse direct solver, back to back on one machine
# (docs/performance.md, "The static solve against PARDISO"): the network of
# ../shared/bench/in.minimize (N x N square lattice with both diagonals, k = 1, k_d = 0.5, a = 1,
# clamped bottom row, F = 1e-3 up on every top-row node). First its linear stiffness matrix,
# assembled vectorised in numpy (the 16 entries of each bond's k n n^T blocks, held dofs
# dropped, scipy summing duplicates), factored and solved by MKL PARDISO through pypardiso
# (mtype 2: real symmetric positive definite, upper triangle, one thread), the factor + solve
# timed alone (wall and CPU time); then mdsolids' whole command on the same network
# (`relax.method: static`, -j 1), its wall and CPU time (user + system) from /usr/bin/time.
# Prints one JSON line per tool and the ratio. The E's differ by the geometric non-linearity
# mdsolids solves for and PARDISO's linear answer does not: the printed |E/E_pardiso - 1|
# is to be read beside mdsolids' own static_nonlinearity (its largest difference between its
# non-linear and linear answers, E's or ν's).
# Usage: cargo build --release && bash benches/static-vs-pardiso.sh [N]   (N = 250 by default)
# numpy, scipy and pypardiso (with MKL) come from PyPI into target/pardiso-venv, made once.
set -euo pipefail
N=${1:-250}
root=$(cd "$(dirname "$0")/.." && pwd)
. "$root/benches/reference-network.sh"
mdsolids=$root/target/release/mdsolids
[ -x "$mdsolids" ] || { echo "build first: cargo build --release" >&2; exit 1; }
venv=$root/target/pardiso-venv
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c "import pypardiso" 2>/dev/null; then
  python3 -m venv "$venv" && "$venv/bin/pip" install -q numpy scipy pypardiso
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

MKL_NUM_THREADS=1 OMP_NUM_THREADS=1 "$venv/bin/python" - "$N" >"$work/pardiso.json" <<'PY'
import json, resource, sys, time
import numpy as np
import scipy.sparse as sp
import pypardiso

n = int(sys.argv[1])
k, k_diagonal, force = 1.0, 0.5, 1e-3
start = time.perf_counter()
node = np.arange(n * n).reshape(n, n)          # node[j, i]: row j (y), column i (x)
# Bonds as (i, j, n_x, n_y, k): along x, along y, both diagonals.
pairs = [
    (node[:, :-1], node[:, 1:], 1.0, 0.0, k),
    (node[:-1, :], node[1:, :], 0.0, 1.0, k),
    (node[:-1, :-1], node[1:, 1:], 2 ** -0.5, 2 ** -0.5, k_diagonal),
    (node[:-1, 1:], node[1:, :-1], -(2 ** -0.5), 2 ** -0.5, k_diagonal),
]
rows, cols, vals = [], [], []
for a, b, nx, ny, stiffness in pairs:
    a, b = a.ravel(), b.ravel()
    block = stiffness * np.array([[nx * nx, nx * ny], [ny * nx, ny * ny]])
    for (p, q) in [(0, 0), (0, 1), (1, 0), (1, 1)]:
        for (u, v, sign) in [(a, a, 1.0), (b, b, 1.0), (a, b, -1.0), (b, a, -1.0)]:
            rows.append(2 * u + p)
            cols.append(2 * v + q)
            vals.append(np.full(u.size, sign * block[p, q]))
rows, cols, vals = np.concatenate(rows), np.concatenate(cols), np.concatenate(vals)
free = np.ones(2 * n * n, dtype=bool)
free[: 2 * n] = False                                   # the bottom row (j = 0) clamped
index = np.cumsum(free) - 1
keep = free[rows] & free[cols]
size = int(free.sum())
stiffness = sp.csr_matrix((vals[keep], (index[rows[keep]], index[cols[keep]])), shape=(size, size))
upper = sp.triu(stiffness, format="csr")
upper.sort_indices()
load = np.zeros(size)
load[index[2 * node[-1, :] + 1]] = force
assembled = time.perf_counter() - start

solver = pypardiso.PyPardisoSolver(mtype=2)     # one thread: MKL_NUM_THREADS=1 above
start, cpu = time.perf_counter(), time.process_time()
solver.factorize(upper)
u = solver.solve(upper, load)
solved, solved_cpu = time.perf_counter() - start, time.process_time() - cpu
stretch = u[index[2 * node[-1, :] + 1]].mean()
print(json.dumps({"tool": "PARDISO", "n": n, "dofs": size, "assemble_s": round(assembled, 3),
                  "factor_solve_s": round(solved, 3), "factor_solve_cpu_s": round(solved_cpu, 3), "E_linear": n * force / stretch,
                  "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024}))
PY

reference_campaign static-vs-pardiso static "$N" "{method: static}" >"$work/static.yaml"
/usr/bin/time -f "%e %U %S %M" -o "$work/time" "$mdsolids" --reports "$work/reports" run -j 1 "$work/static.yaml" >/dev/null
python3 - "$work/reports/static-vs-pardiso/results.csv" "$work/time" "$work/pardiso.json" "$N" <<'PY'
import csv, json, sys
row = next(csv.DictReader(open(sys.argv[1])))
wall, user, system, peak_kb = open(sys.argv[2]).read().split()
pardiso = json.loads(open(sys.argv[3]).read())
print(json.dumps(pardiso))
e, nonlinearity = float(row["youngs_modulus_fem"]), float(row["static_nonlinearity"])
mdsolids = {"tool": "mdsolids", "n": int(sys.argv[4]), "status": row["status"], "wall_s": float(wall),
            "cpu_s": round(float(user) + float(system), 2),
            "solve_s": float(row["solve_s"]), "E": e, "static_residual": float(row["static_residual"] or "nan"),
            "peak_mb": int(peak_kb) // 1024, "E_over_pardiso_minus_1": abs(e / pardiso["E_linear"] - 1),
            "static_nonlinearity": nonlinearity}
print(json.dumps(mdsolids))
print(f'mdsolids whole command / PARDISO factor + solve: {mdsolids["wall_s"] / pardiso["factor_solve_s"]:.2f} wall, '
      f'{mdsolids["cpu_s"] / pardiso["factor_solve_cpu_s"]:.2f} CPU time (the fairer one on a shared machine)')
PY
