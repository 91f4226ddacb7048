//! Unit tests of `src/plan/stability.rs`, moved out of the library (one test binary).

use mdsolids::plan::stability::{
    Estimates, RUN_GROWTH, TEST_PARTICLE, TestEquation, TestField, estimate, gear_spectral_radius, modes, network_key,
    node_bound, test_problem,
};
use mdsolids::sim::{Gear, IntegratorKind, Sampling, State, StepProbe, simulate_with};
use mdsolids::spec::{LANCZOS_BONDS, RunSpec};
use mdsolids::study::build_scene;

/// Runs of one network share its modes: a grid over dt, integrators and run lengths has one
/// key (one ω_max estimate, issue 14); a different stiffness or damping has another.
#[test]
fn runs_of_one_network_share_one_estimate() {
    let campaign = mdsolids::spec::parse(
        "k.yaml",
        "version: 1\nname: k\nscenes:\n  - name: l\n    kind: lattice\n    lattice: {size: 4}\n    \
         load: {case: tensile}\n    grid:\n      time.dt_per_tc: [20, 50]\n      time.integrator: [velocity-verlet, rk4]\n      \
         relax.max_tc: [10, 20]\n      material.k: [1.0, 2.0]\n      damping.restitution: [1.0, 0.5]\n",
    )
    .unwrap();
    let keys: std::collections::HashSet<String> = campaign.runs.iter().map(network_key).collect();
    assert_eq!((campaign.runs.len(), keys.len()), (32, 4));
}

/// Planning computes one estimate per network: a grid of pairs over v0 and mass has one per
/// mass with linear springs (v0 moves no spring), and one per run with Hertz contacts,
/// linearised at each collision's largest overlap. A shared estimate is the run's own.
#[test]
fn planning_estimates_each_network_once() {
    // Bonded pairs hit at up to 4 m/s overlap by up to 4.9 x_e, which the plan refuses unless
    // allowed; the estimates do not depend on that.
    let grid = "    time: {allow_unstable: true}\n    grid:\n      v0: [0.5, 1.0, 2.0, 4.0]\n      material.mass: [1.0, 2.0, 3.0]\n";
    for (law, networks) in [("", 3), ("    material: {law: hertz, contact: true}\n", 12)] {
        let yaml = format!("version: 1\nname: k\nscenes:\n  - name: p\n    kind: pair\n{law}{grid}");
        let plan = mdsolids::plan::parse("k.yaml", &yaml).unwrap();
        let estimated = plan.estimates.networks();
        assert_eq!((plan.campaign.runs.len(), estimated), (12, networks), "{law}");
        for spec in &plan.campaign.runs {
            assert_eq!(plan.estimates.stability(spec), estimate(spec), "{}", spec.varied_label(|_| true));
        }
    }
}

/// The scenes of a one-scene campaign whose scene section (after `kind:`) is `body`.
fn runs_of(body: &str) -> Vec<RunSpec> {
    mdsolids::spec::parse("b.yaml", &format!("version: 1\nname: b\nscenes:\n  - name: s\n{body}")).unwrap().runs
}

/// The node bound is an upper bound on every kind of network (the Lanczos estimate, a Ritz
/// value, is a lower bound, so "≥" is the test) and tight where the top mode is staggered:
/// for the chain and the square lattice with both or no diagonal families the finite
/// network's ω_max lies below the infinite one's by (π/2(N+1))²/2 relative, ≤ 0.3 % at N = 20;
/// 1.5 % allows that. One diagonal family: √(6/5.24) − 1 = 7 % high in the infinite lattice
/// (7.4 % at 20 × 20; 8 % allowed). ζ and ν_max of the
/// bound within 10 % and above the Lanczos estimate's (ν_max) where it is an upper bound too.
#[test]
fn the_node_bound_holds_and_is_tight_on_staggered_modes() {
    let cases = [
        ("    kind: chain\n    n: 30\n    node: 3\n    v0: 0.1\n    damping: {restitution: 0.5}\n", 0.015),
        (
            "    kind: lattice\n    lattice: {size: 20, diagonals: both}\n    load: {case: tensile}\n    damping: {restitution: 0.5, background: 0.2}\n",
            0.015,
        ),
        ("    kind: lattice\n    lattice: {size: 20, diagonals: none}\n    load: {case: shear}\n", 0.015),
        (
            "    kind: lattice\n    lattice: {size: 20, diagonals: rising, k_diag_ratio: 0.5}\n    load: {case: tensile}\n",
            0.08,
        ),
        (
            "    kind: lattice\n    lattice: {size: 20, cut_fraction: 0.2}\n    load: {case: tensile}\n    seed: 3\n",
            0.05,
        ),
        (
            "    kind: lattice\n    lattice: {size: 12}\n    material: {law: hertz}\n    load: {case: tensile}\n    damping: {restitution: 0.5}\n",
            0.05,
        ),
    ];
    for (body, tolerance) in cases {
        let spec = &runs_of(body)[0];
        let (scene, extension) = (build_scene(spec), mdsolids::spec::reference_extension(spec));
        let (power, bound) = (modes(&scene, extension), node_bound(&scene, extension));
        let ratio = bound.omega_max / power.omega_max;
        assert!((1.0..=1.0 + tolerance).contains(&ratio), "{body}: bound/power = {ratio}");
        assert!(bound.damping_rate >= power.damping_rate * (1.0 - 1e-9), "{body}: ν_max {bound:?} {power:?}");
        if power.damping_ratio > 0.0 {
            let zeta = bound.damping_ratio / power.damping_ratio;
            assert!((0.9..=1.1).contains(&zeta), "{body}: ζ bound/power = {zeta}");
        }
    }
}

/// A network beyond [`LANCZOS_BONDS`] gets the bound, which on a square lattice with
/// both diagonal families (k = 1 N/m, k_d = 0.5 N/m, m = 1 kg) is √(4(k + k_d)/m) = √6 rad/s
/// to round-off; the Lanczos method on this 251 × 251 network would give its finite ω_max,
/// ~2e-5 lower, in hundreds of passes.
#[test]
fn a_network_beyond_the_power_method_gets_the_staggered_bound() {
    let spec =
        &runs_of("    kind: lattice\n    lattice: {size: 251, k_diag_ratio: 0.5}\n    load: {case: tensile}\n")[0];
    assert!(spec.bonds() > LANCZOS_BONDS);
    let omega_max = estimate(spec).omega_max;
    assert!((omega_max - 6f64.sqrt()).abs() < 1e-12, "{omega_max}");
}

#[test]
fn undamped_limits_match_the_known_values() {
    // Exact limits of the test equation: Verlet and symplectic Euler |1 − h²/2| ≤ 1 → 2;
    // RK4 on the imaginary axis 2√2; the bisection resolves 1e-4, the trial growth ~1e-5.
    for (kind, exact) in [
        (IntegratorKind::VelocityVerlet, 2.0),
        (IntegratorKind::PositionVerlet, 2.0),
        (IntegratorKind::SymplecticEuler, 2.0),
        (IntegratorKind::Rk4, 2.0 * 2f64.sqrt()),
    ] {
        let limit = Estimates::default().stability_limit(kind, 0.0, 1000);
        assert!((limit - exact).abs() < 1e-3 * exact, "{}: {limit} against {exact}", kind.name());
    }
}

#[test]
fn gear_amplification_matrix_is_the_textbook_scheme() {
    // Independent answer: predictor P (Pascal's triangle), then r += c Δ with
    // Δ = (h²/2) a − r₂ᵖ and a = −x − 2ζ ẋ at the prediction: G = (I + c gᵀ) P with
    // gᵀ = (−h²/2, −ζh, −1, 0, 0, 0), c = (c₀, 251/360, 1, 11/18, 1/6, 1/60) and
    // c₀ = 3/20 undamped, 3/16 with a dashpot. Tolerance 1e-13: round-off of a few
    // operations on entries up to 10.
    for (zeta, c0) in [(0.0, 3.0 / 20.0), (0.1, 3.0 / 16.0)] {
        let h = 0.37;
        let (state, field) = test_problem(TestEquation::Oscillator { zeta });
        let coded = match field {
            TestField::Damped(mut f) => Gear::amplification_matrix(&state, &mut f, TEST_PARTICLE, h),
            TestField::Undamped(mut f) => Gear::amplification_matrix(&state, &mut f, TEST_PARTICLE, h),
        };
        let pascal = |i: usize, j: usize| {
            if j >= i { (1..=i).fold(1.0, |b, m| b * (j + 1 - m) as f64 / m as f64) } else { 0.0 }
        };
        let c = [c0, 251.0 / 360.0, 1.0, 11.0 / 18.0, 1.0 / 6.0, 1.0 / 60.0];
        let g = [-h * h / 2.0, -zeta * h, -1.0, 0.0, 0.0, 0.0];
        for (i, row) in coded.iter().enumerate() {
            for (j, &entry) in row.iter().enumerate() {
                let gp: f64 = (0..6).map(|k| g[k] * pascal(k, j)).sum();
                let expected = pascal(i, j) + c[i] * gp;
                assert!((entry - expected).abs() < 1e-13, "ζ {zeta}: G[{i}][{j}] = {entry} against {expected}");
            }
        }
    }
}

#[test]
fn gear_limit_bounds_the_growth_over_the_run() {
    // The limit is where ρ^steps reaches RUN_GROWTH: just below it the growth over the
    // run is at most 2, just above (by 1 %) more; it falls as runs get longer, because ρ
    // exceeds 1 (~1e-4 per step at ω dt = 0.45, where the old 4000-step trial put the
    // limit at 0.4919 and a chain of 78 000 steps blew up at step 38 805).
    let estimates = Estimates::default();
    let short = estimates.stability_limit(IntegratorKind::Gear, 0.0, 1000);
    let long = estimates.stability_limit(IntegratorKind::Gear, 0.0, 78_181);
    assert!(long < short && long < 0.45, "limits {short} (1000 steps) and {long} (78 181 steps)");
    let test = TestEquation::Oscillator { zeta: 0.0 };
    let steps = 131_072.0; // 78 181 rounded up to a power of two
    assert!(gear_spectral_radius(test, long).powf(steps) <= RUN_GROWTH);
    assert!(gear_spectral_radius(test, 1.01 * long).powf(steps) > RUN_GROWTH);
}

/// ω_max from the Lanczos method against closed forms, to 1e-9 relative (the method stops at
/// a residual of 1e-10 θ; the power method it replaced came within ~0.15 % and stopped after
/// 1000 passes on networks like these). A chain of N unit masses and springs k = 1 N/m between
/// two walls: ω² = 4 sin²(jπ/2(N+1)), j = 1 … N. A free N × N square lattice without diagonals
/// separates into free chains along x and along y: ω² = 4 sin²(jπ/2N), j < N.
#[test]
fn lanczos_finds_omega_max_of_chains_and_square_lattices_to_1e_9() {
    let walls = |n: f64| 2.0 * (n * std::f64::consts::PI / (2.0 * (n + 1.0))).sin();
    let free = |n: f64| 2.0 * ((n - 1.0) * std::f64::consts::PI / (2.0 * n)).sin();
    let cases = [
        ("    kind: chain\n    n: 2\n    v0: 0.1\n", walls(2.0)),
        ("    kind: chain\n    n: 40\n    v0: 0.1\n", walls(40.0)),
        ("    kind: chain\n    n: 400\n    v0: 0.1\n", walls(400.0)),
        (
            "    kind: lattice\n    lattice: {size: 40, diagonals: none}\n    supports: free\n    impulse: {velocity: [0.0, -0.01]}\n",
            free(40.0),
        ),
    ];
    for (body, expected) in cases {
        let spec = &runs_of(body)[0];
        let (scene, extension) = (build_scene(spec), mdsolids::spec::reference_extension(spec));
        let omega_max = modes(&scene, extension).omega_max;
        let relative = omega_max / expected - 1.0;
        assert!(relative.abs() < 1e-9, "{body}: ω_max {omega_max}, closed form {expected}, relative {relative:e}");
    }
}

/// A probe that has seen enough ends its run after that step (a stability trial once its
/// amplitude has escaped); without one the run takes every step it was given, and a pair of
/// probes ends it only once both have seen enough.
#[test]
fn a_probe_that_has_seen_enough_ends_the_run() {
    /// Counts the states it is shown (the start, then one per step) and has seen enough after
    /// `enough` of them.
    struct Count {
        seen: u64,
        enough: u64,
    }
    impl StepProbe for Count {
        fn observe(&mut self, _state: &State) {
            self.seen += 1;
        }
        fn seen_enough(&self) -> bool {
            self.seen >= self.enough
        }
    }
    fn steps_run(mut probe: impl StepProbe) -> u64 {
        let (mut state, field) = test_problem(TestEquation::Oscillator { zeta: 0.0 });
        let TestField::Undamped(mut field) = field else { panic!("the undamped test problem has no dashpot") };
        let sampling = Sampling::new(0.1, 1000);
        simulate_with(IntegratorKind::VelocityVerlet, &mut state, &mut field, &sampling, &mut probe);
        state.steps
    }
    let count = |enough| Some(Count { seen: 0, enough });
    assert_eq!(steps_run(count(11)), 10, "the start and ten steps make eleven states seen");
    assert_eq!(steps_run(None::<Count>), 1000);
    assert_eq!(steps_run((count(11), count(51))), 50, "the pair runs until the later one has seen enough");
    assert_eq!(steps_run((count(11), None::<Count>)), 1000, "a pair with a probe that never has");
}
