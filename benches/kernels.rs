//! Criterion benchmarks of the reference workload's kernels (docs/performance.md): the force
//! loop and one velocity-Verlet step, at N = 100, 316 and 1000, on one thread; then both
//! workloads of `mdsolids bench` side by side, `kernel` and `relax` (damped, loaded, clamped,
//! checked), through the whole time loop. Throughput is in particles, so criterion's "elem/s"
//! is particle-steps per second.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::{Duration, Instant};

use mdsolids::bench::{BenchConfig, Workload, reference_lattice, reference_scene};
use mdsolids::model::{LatticeType, Linear, NoDashpot, Spring};
use mdsolids::sim::{ForceField, Integrator, LatticeNetwork, State, VelocityVerlet};

/// The program's own allocator (`src/alloc.rs`), so the arrays lie as they do in `mdsolids`.
#[global_allocator]
static ALLOCATOR: mdsolids::alloc::Coloured = mdsolids::alloc::Coloured;

const SIZES: [usize; 3] = [100, 316, 1000];
const SPRING: Spring<Linear, NoDashpot, false> = Spring::new(Linear, NoDashpot);

fn one_thread() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("a one-thread pool")
}

/// Wall time of `iterations` calls of `work`, all inside `pool` (entering a pool costs a
/// thread hand-off, which would swamp the 0.1 ms kernels of N = 100).
fn timed_on(pool: &rayon::ThreadPool, iterations: u64, mut work: impl FnMut() + Send) -> Duration {
    pool.install(|| {
        let started = Instant::now();
        for _ in 0..iterations {
            work();
        }
        started.elapsed()
    })
}

/// The reference lattice, strained a little so every bond carries a force.
fn strained_state(n: usize) -> State {
    let config = BenchConfig {
        workload: Workload::Kernel,
        n,
        steps: 0,
        dilute: 0.0,
        bond_list: false,
        lattice: LatticeType::Square,
    };
    let mut particles = reference_scene(&config).particles;
    for (i, x) in particles.x.iter_mut().enumerate() {
        *x *= 1.0 + 1e-3 * ((i % 7) as f64);
    }
    State::new(particles)
}

fn force_loop(c: &mut Criterion) {
    let pool = one_thread();
    let mut group = c.benchmark_group("force_loop");
    group.sample_size(10);
    for n in SIZES {
        group.throughput(Throughput::Elements((n * n) as u64));
        let mut state = strained_state(n);
        let mut field = LatticeNetwork::new(SPRING, reference_lattice(n), 0.0);
        group.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter_custom(|iterations| {
                timed_on(&pool, iterations, || {
                    state.fx.fill(0.0);
                    state.fy.fill(0.0);
                    let p = &state.particles;
                    black_box(field.add_forces(&p.x, &p.y, &p.vx, &p.vy, &mut state.fx, &mut state.fy));
                })
            })
        });
    }
    group.finish();
}

fn integrator_step(c: &mut Criterion) {
    let pool = one_thread();
    let mut group = c.benchmark_group("velocity_verlet_step");
    group.sample_size(10);
    for n in SIZES {
        group.throughput(Throughput::Elements((n * n) as u64));
        let mut state = strained_state(n);
        let mut field = LatticeNetwork::new(SPRING, reference_lattice(n), 0.0);
        let mut integrator = VelocityVerlet::default();
        integrator.start(&mut state, &mut field, 0.01);
        group.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter_custom(|iterations| timed_on(&pool, iterations, || integrator.step(&mut state, &mut field, 0.01)))
        });
    }
    group.finish();
}

/// Steps per timed run of a workload: two relaxation checks (one per 50 steps) among them.
const WORKLOAD_STEPS: u64 = 100;

/// Both `mdsolids bench` workloads at N = 100 and 316, each timed by its own loop clock
/// (`Trace::loop_s`), which leaves out building the scene and its first and last samples.
fn workloads(c: &mut Criterion) {
    let pool = one_thread();
    let mut group = c.benchmark_group("workload");
    group.sample_size(10);
    for n in [100, 316] {
        group.throughput(Throughput::Elements((n * n) as u64 * WORKLOAD_STEPS));
        for workload in [Workload::Kernel, Workload::Relax] {
            let config = BenchConfig {
                workload,
                n,
                steps: WORKLOAD_STEPS,
                dilute: 0.0,
                bond_list: false,
                lattice: LatticeType::Square,
            };
            group.bench_function(BenchmarkId::new(workload.name(), n), |b| {
                b.iter_custom(|iterations| {
                    (0..iterations)
                        .map(|_| {
                            let scene = reference_scene(&config);
                            Duration::from_secs_f64(pool.install(|| scene.run()).trace.loop_s)
                        })
                        .sum()
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, force_loop, integrator_step, workloads);
criterion_main!(benches);
