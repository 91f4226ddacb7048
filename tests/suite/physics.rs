//! Physics against independent answers: force laws, the two-body collision, the chain's
//! normal modes and the conservation laws. Each tolerance says why it is what it is.

use crate::common::{execute_all, pair_campaign, relative};
use mdsolids::measure::convergence_order;
use mdsolids::model::{Axes, BondDashpot, Bonds, ForceLaw, LawSpec, Linear, NoDashpot, Particles, PowerLaw, Spring};
use mdsolids::runner::RunRecord;
use mdsolids::sim::{BondNetwork, ForceField, IntegratorKind, Network, Sampling, Scene};

/// Separations to test: stretched and compressed, oblique, in 2D.
const SEPARATIONS: [(f64, f64); 4] = [(1.07, 0.02), (0.93, -0.05), (-0.6, 0.71), (0.3, -0.96)];

fn check_law<L: ForceLaw, const CONTACT: bool>(law: L) {
    let spring = Spring::<L, NoDashpot, CONTACT>::new(law, NoDashpot);
    let (k, rest) = (2.5, 1.0);
    for (dx, dy) in SEPARATIONS {
        let f = spring.force_on_i(k, rest, dx, dy, 0.0, 0.0);
        // f_i = −∂E/∂x_i by a central difference; h = 1e-6 gives truncation ~h² ≈ 1e-12 and
        // round-off ~1e-16/h ≈ 1e-10, so 1e-7 (absolute, forces are O(0.1–1) N) is safe.
        let h = 1e-6;
        let de_dx = (spring.energy(k, rest, dx + h, dy) - spring.energy(k, rest, dx - h, dy)) / (2.0 * h);
        let de_dy = (spring.energy(k, rest, dx, dy + h) - spring.energy(k, rest, dx, dy - h)) / (2.0 * h);
        assert!((f.fx + de_dx).abs() < 1e-7, "fx = {} but −dE/dx = {}", f.fx, -de_dx);
        assert!((f.fy + de_dy).abs() < 1e-7, "fy = {} but −dE/dy = {}", f.fy, -de_dy);
        let stretched = (dx * dx + dy * dy).sqrt() > rest;
        if CONTACT && stretched {
            assert_eq!((f.fx, f.fy), (0.0, 0.0), "a contact spring in tension pulls");
        }
    }
}

#[test]
fn force_is_minus_energy_gradient_for_every_law() {
    check_law::<_, false>(Linear);
    check_law::<_, true>(Linear);
    check_law::<_, false>(PowerLaw { beta: 1.5 });
    check_law::<_, true>(PowerLaw { beta: 1.5 });
    check_law::<_, false>(PowerLaw { beta: 2.2 });
}

#[test]
fn newtons_third_law_in_the_force_loop() {
    let mut bonds = Bonds::default();
    bonds.push(0, 1, 1.0, 3.0);
    let spring = Spring::<PowerLaw, BondDashpot, false>::new(PowerLaw { beta: 1.5 }, BondDashpot { gamma: 0.4 });
    let mut field = BondNetwork::new(spring, &bonds, 2, 0.0);
    let (x, y, vx, vy) = ([0.1, 1.0], [0.2, -0.3], [0.5, -0.1], [0.0, 0.3]);
    let (mut fx, mut fy) = ([0.0; 2], [0.0; 2]);
    field.add_forces(&x, &y, &vx, &vy, &mut fx, &mut fy);
    // Each pair force is computed once and applied with opposite signs: exactly equal.
    assert_eq!(fx[0], -fx[1]);
    assert_eq!(fy[0], -fy[1]);
    assert!(fx[0] != 0.0 && fy[0] != 0.0);
}

fn by_dt(records: &[RunRecord], error: impl Fn(&RunRecord) -> f64) -> Vec<(f64, f64)> {
    records.iter().map(|r| (r.spec.dt, error(r))).collect()
}

fn duration_error(r: &RunRecord) -> f64 {
    relative(r.metrics.pair.contact_duration, r.metrics.pair.contact_duration_theory)
}

fn restitution_error(r: &RunRecord) -> f64 {
    relative(r.metrics.pair.restitution, r.metrics.pair.restitution_theory)
}

/// The sweep used for orders: t_c/20 … t_c/160, with the contact start at gap/v0 = 0.05 s,
/// which no dt of the sweep divides, so the contact end is not aligned with a step.
const SWEEP: [f64; 4] = [20.0, 40.0, 80.0, 160.0];

#[test]
fn undamped_contact_collision_matches_theory_at_second_order() {
    for integrator in ["position-verlet", "velocity-verlet"] {
        let records = execute_all(&pair_campaign("{contact: true}", "{restitution: 1.0}", integrator, &[50.0]));
        let r = &records[0];
        // Issue bound: 0.5 % at t_c/50 (measured 1.6e-4 for t_c and 3e-9 for r).
        assert!(duration_error(r).abs() < 5e-3, "{integrator}: t_c error {}", duration_error(r));
        assert!(restitution_error(r).abs() < 5e-3, "{integrator}: r error {}", restitution_error(r));
        let sweep = execute_all(&pair_campaign("{contact: true}", "{restitution: 1.0}", integrator, &SWEEP));
        let order = convergence_order(&by_dt(&sweep, duration_error)).unwrap();
        // Verlet is second order; 1.8–2.2 allows for the interpolation of the crossings.
        assert!((1.8..=2.2).contains(&order), "{integrator}: t_c order {order}");
    }
}

#[test]
fn hertz_contact_duration_matches_the_exact_integral() {
    let records =
        execute_all(&pair_campaign("{contact: true, law: hertz}", "{restitution: 1.0}", "velocity-verlet", &SWEEP));
    let at_80 = records.iter().find(|r| (r.spec.dt_per_tc() - 80.0).abs() < 1e-9).unwrap();
    // Measured 8e-5 at t_c/80; the bound 3e-4 leaves room and still fails a wrong formula
    // (the tangent-stiffness estimate π/ω is off by several per cent).
    assert!(duration_error(at_80).abs() < 3e-4, "Hertz t_c error {}", duration_error(at_80));
    let order = convergence_order(&by_dt(&records, duration_error)).unwrap();
    assert!((1.8..=2.2).contains(&order), "Hertz t_c order {order}");
}

#[test]
fn damped_bonded_pair_converges_at_second_order() {
    for integrator in ["position-verlet", "velocity-verlet"] {
        let at_50 = &execute_all(&pair_campaign("{contact: false}", "{restitution: 0.5}", integrator, &[50.0]))[0];
        // Measured −1.27e-3 at t_c/50 with the predicted dashpot velocity; an explicit
        // half-step dashpot gives ~1.5e-2, so 2e-3 separates the two.
        assert!(restitution_error(at_50).abs() < 2e-3, "{integrator}: r error {}", restitution_error(at_50));
        assert!(duration_error(at_50).abs() < 5e-4, "{integrator}: t_c error {}", duration_error(at_50));
        let sweep = execute_all(&pair_campaign("{contact: false}", "{restitution: 0.5}", integrator, &SWEEP));
        let order = convergence_order(&by_dt(&sweep, restitution_error)).unwrap();
        assert!((1.8..=2.2).contains(&order), "{integrator}: r order {order}");
    }
}

fn energy_error(r: &RunRecord) -> f64 {
    r.metrics.energy_error.expect("energy error")
}

/// A named error of a pair run.
type PairError = (&'static str, fn(&RunRecord) -> f64);

/// The errors a damped pair is judged by: contact duration, restitution, energy balance.
const PAIR_ERRORS: [PairError; 3] = [("t_c", duration_error), ("r", restitution_error), ("energy", energy_error)];

/// The contact pair (`contact`) or the bonded pair of restitution `restitution`, over `sweep`
/// (dt_per_tc).
fn pair_sweep(contact: bool, restitution: f64, integrator: &str, sweep: &[f64]) -> Vec<RunRecord> {
    let material = format!("{{contact: {contact}}}");
    execute_all(&pair_campaign(&material, &format!("{{restitution: {restitution}}}"), integrator, sweep))
}

#[test]
fn damped_contact_collision_converges_at_each_schemes_order() {
    // The dashpot force γ δ̇ jumps where the contact closes and opens; the step is split there,
    // so each scheme keeps its own order for t_c and r against π/ω and exp(−γ t_c/m). Before
    // the split the orders of r were 0.8–1.0 (Verlet), 0.5–1.8 (RK4), 0.9–1.6 (Gear), measured
    // over t_c/20 … t_c/400. Now, over t_c/20 … t_c/160: Verlet 1.98, 2.00 and 1.97 (t_c, r,
    // energy), RK4 4.08, 3.94, 3.83, symplectic Euler 1.05, 1.06, 0.95; the bounds are the
    // issue's (order ≥ 1.9 for the second-order schemes), ± 0.3 about 4 for RK4 (as on the
    // chain) and ± 0.2 about 1 for symplectic Euler. Gear: t_c and r at least 4.5, as on the
    // chain (5.43 and 4.78 measured; the bonded pair 5.42 and 4.83), energy 2 ± 0.2: Gear
    // books the dissipated energy by the trapezoidal rule, second order for the bonded pair too
    // (2.00).
    let cases: [(&str, [(f64, f64); 3]); 5] = [
        ("position-verlet", [(1.9, 2.2), (1.9, 2.2), (1.9, 2.2)]),
        ("velocity-verlet", [(1.9, 2.2), (1.9, 2.2), (1.9, 2.2)]),
        ("rk4", [(3.7, 4.3), (3.7, 4.3), (3.7, 4.3)]),
        ("gear", [(4.5, 7.0), (4.5, 7.0), (1.8, 2.2)]),
        ("symplectic-euler", [(0.8, 1.2), (0.8, 1.2), (0.8, 1.2)]),
    ];
    for (integrator, bounds) in cases {
        let sweep = pair_sweep(true, 0.5, integrator, &SWEEP);
        for ((name, error), (low, high)) in PAIR_ERRORS.into_iter().zip(bounds) {
            let order = convergence_order(&by_dt(&sweep, error)).unwrap();
            assert!((low..=high).contains(&order), "{integrator}: {name} order {order}, expected {low}–{high}");
        }
    }
}

#[test]
fn damped_contact_error_at_t_c_over_50_is_within_twice_the_bonded_pairs() {
    // Once the switch is located, the contact pair is the bonded pair's half period plus
    // exact free flight: measured ratios (contact/bonded) 0.97–1.04 for t_c and r and 0.75–1.01
    // for the energy, in every scheme (before: r +1.2e-2 against −1.3e-3 for Verlet, ×10).
    for integrator in ["position-verlet", "velocity-verlet", "rk4", "gear", "symplectic-euler"] {
        let contact = &pair_sweep(true, 0.5, integrator, &[50.0])[0];
        let bonded = &pair_sweep(false, 0.5, integrator, &[50.0])[0];
        for (name, error) in PAIR_ERRORS {
            let (c, b) = (error(contact).abs(), error(bonded).abs());
            assert!(c <= 2.0 * b, "{integrator}: {name} error {c:e} at t_c/50, bonded {b:e}");
        }
    }
}

#[test]
fn undamped_contact_is_untouched_by_the_switch_location() {
    // An undamped contact switches without a jump (s(0) = 0), so its steps are never split:
    // t_c and r at t_c/50 are bit for bit those of the code before the switch location.
    for (integrator, duration, restitution) in [
        ("position-verlet", 2.221075867555446, 0.9999999974106094),
        ("velocity-verlet", 2.2210758675554456, 0.9999999974106095),
        ("rk4", 2.221439008240734, 1.000123666209521),
        ("gear", 2.2214388804138387, 1.0000531097311662),
        ("symplectic-euler", 2.221075867555446, 0.9995793378859396),
    ] {
        let r = &pair_sweep(true, 1.0, integrator, &[50.0])[0];
        assert_eq!(r.metrics.pair.contact_duration, Some(duration), "{integrator}: t_c");
        assert_eq!(r.metrics.pair.restitution, Some(restitution), "{integrator}: r");
    }
}

const CHAIN: &str = "version: 1\nname: t\nscenes:\n  - name: c\n    kind: chain\n    n: 11\n    v0: 0.1\n    time: {dt_per_tc: 50, duration_tc: DURATION, samples: 200}\n";

#[test]
fn chain_follows_its_normal_modes() {
    let records = execute_all(&CHAIN.replace("DURATION", "5"));
    let error = records[0].metrics.chain.chain_mode_error.expect("linear undamped chain has modes");
    // Issue bound: 0.5 % of the largest amplitude at t_c/50 over the first 5 t_c; Verlet's
    // phase error grows like (ω dt)²/24 · ω t, about 0.2 % here (measured 0.11 %).
    assert!(error < 5e-3, "mode error {error}");
    assert!(error > 1e-5, "a mode error of {error} is too small to be real: is the comparison wired?");
}

#[test]
fn undamped_chain_conserves_energy_without_drift() {
    let record = &execute_all(&CHAIN.replace("DURATION", "200"))[0];
    let t = &record.trace;
    let total: Vec<f64> = (0..t.time.len()).map(|s| t.kinetic[s] + t.potential[s]).collect();
    let deviation =
        |range: std::ops::Range<usize>| range.map(|s| (total[s] - total[0]).abs() / total[0]).fold(0.0, f64::max);
    let half = total.len() / 2;
    let (first, second) = (deviation(0..half), deviation(half..total.len()));
    // Verlet conserves a shadow energy: the error oscillates with amplitude ~(ω_max dt)²/8
    // ≈ 1e-3 and does not grow; a drifting scheme would make the second half clearly worse.
    assert!(first < 2e-3 && second < 2e-3, "energy errors {first}, {second}");
    assert!(second < 1.5 * first, "energy drifts: {first} then {second}");
}

#[test]
fn free_pair_conserves_momentum_with_damping() {
    for integrator in [IntegratorKind::PositionVerlet, IntegratorKind::VelocityVerlet] {
        let mut particles = Particles::default();
        particles.push(0.0, 0.0, 1.0, Axes::FREE);
        particles.push(1.1, 0.3, 2.5, Axes::FREE);
        particles.vx = vec![0.7, -0.2];
        particles.vy = vec![0.1, 0.05];
        let (px0, py0) = particles.momentum();
        let mut bonds = Bonds::default();
        bonds.push(0, 1, 1.0, 1.0);
        let sampling = Sampling { every: 100, ..Sampling::new(0.01, 5000) };
        let scene = Scene::new(particles, Network::Bonds(bonds), LawSpec::Power { beta: 1.5 }, sampling)
            .damping(0.3, 0.0)
            .integrator(integrator);
        let (px, py) = scene.run().state.particles.momentum();
        // Pair forces cancel exactly; only round-off remains. Störmer's position form adds
        // ε|x| to every position each step and divides by dt for the velocity: after 5000 steps
        // with |x| ≈ 10 m and dt = 0.01 s that is ~1e-12 kg m/s (measured 1.7e-12); 1e-10 still
        // fails any real force imbalance (one unmatched force of 1e-3 N gives 0.05 kg m/s).
        assert!((px - px0).abs() < 1e-10 && (py - py0).abs() < 1e-10, "{integrator:?}: ({px}, {py}) vs ({px0}, {py0})");
    }
}

/// What the contact clock sees, as the report's appendix states it: every step's end, and for
/// a damped contact also each switch, where the time loop splits the step at the Taylor
/// polynomial's root (δ ≈ 0); every crossing is placed by linear interpolation between two of
/// these states.
#[derive(Default)]
struct Seen {
    /// (time, δ, at a switch) of every state shown.
    states: Vec<(f64, f64, bool)>,
}

impl Seen {
    fn delta(state: &mdsolids::sim::State) -> f64 {
        let p = &state.particles;
        (p.x[1] - p.x[0]).hypot(p.y[1] - p.y[0]) - 1.0
    }
}

impl mdsolids::sim::StepProbe for Seen {
    fn observe(&mut self, state: &mdsolids::sim::State) {
        self.states.push((state.time, Self::delta(state), false));
    }
    fn observe_switch(&mut self, state: &mdsolids::sim::State) {
        self.states.push((state.time, Self::delta(state), true));
    }
}

/// The crossings of a contact pair closing at 1 m/s from a gap of 0.05 m (k = m = 1, dt =
/// 0.03 s: the contact closes inside the second step) with `dashpot`, and the states seen.
fn clocked_contact<D: mdsolids::model::Dashpot>(dashpot: D) -> (Vec<mdsolids::sim::Crossing>, Seen) {
    let mut particles = Particles::default();
    particles.push(0.0, 0.0, 1.0, Axes::FREE);
    particles.push(1.05, 0.0, 1.0, Axes::FREE);
    particles.vx = vec![0.5, -0.5];
    let mut bonds = Bonds::default();
    bonds.push(0, 1, 1.0, 1.0);
    let mut field = BondNetwork::new(Spring::<Linear, D, true>::new(Linear, dashpot), &bonds, 2, 0.0);
    let mut state = mdsolids::sim::State::new(particles);
    let mut probes = (mdsolids::sim::ContactClock::new(0, 1, 1.0), Seen::default());
    mdsolids::sim::simulate_with(
        IntegratorKind::VelocityVerlet,
        &mut state,
        &mut field,
        &Sampling::new(0.03, 150),
        &mut probes,
    );
    (probes.0.crossings, probes.1)
}

#[test]
fn the_contact_clock_interpolates_between_step_ends_and_at_damped_switches() {
    let dt = 0.03;
    // Damped: each crossing is a switch the step was split at, δ ≈ 0 there.
    let (crossings, seen) = clocked_contact(BondDashpot { gamma: 0.3 });
    assert_eq!(crossings.len(), 2, "{crossings:?}");
    for c in &crossings {
        let at = seen.states.iter().find(|s| s.2 && (s.0 - c.time).abs() < 1e-9 * dt);
        assert!(at.is_some_and(|s| s.1.abs() < 1e-9), "{c:?} at no switch: {:?}", seen.states);
    }
    // Free flight closes the contact at t = 0.05 s exactly (straight paths meet).
    assert!((crossings[0].time - 0.05).abs() < 1e-12, "{:?}", crossings[0]);
    // Undamped: whole steps, no switch shown; the crossings fall inside steps, interpolated.
    let (crossings, seen) = clocked_contact(NoDashpot);
    assert!(seen.states.iter().all(|s| !s.2), "an undamped contact's step was split");
    assert_eq!(crossings.len(), 2, "{crossings:?}");
    for c in &crossings {
        let steps = c.time / dt;
        assert!((steps - steps.round()).abs() > 1e-6, "{c:?} on a step's end");
    }
}
