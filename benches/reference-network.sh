# Sourced by the benches: the network of ../shared/bench/in.minimize (N x N square lattice with
# both diagonals, k = 1, k_d = 0.5, a = 1, m = 1, clamped bottom row, F = 1e-3 up on every
# top-row node) as a one-scene mdsolids campaign, so every bench measures the same network.
#
# reference_campaign NAME SCENE N RELAX: prints the campaign `NAME` whose scene `SCENE` is the
# N x N network relaxed by RELAX (a YAML mapping, e.g. "{method: static}").
reference_campaign() {
  cat <<YAML
version: 1
name: $1
budget: {seconds_per_run: 3600, memory_per_run_mb: 20000}
scenes:
  - name: $2
    kind: lattice
    material: {mass: 1.0, k: 1.0}
    geometry: {spacing: 1.0, depth: 1.0}
    time: {integrator: velocity-verlet, dt_per_tc: 50}
    supports: clamped-bottom
    lattice: {size: $3, k_diag_ratio: 0.5, diagonals: both}
    load: {case: tensile, per_node: 1.0e-3}
    relax: $4
YAML
}
