//! A reviewer's defect of the chain's sound speed (item "The speed of sound"): the 1 % speed
//! threshold was judged against the continuum speed a√(k/m), which it leads by 3.8 % at
//! mid-chain and 0.7 % beside the far wall, so the verdict depended on where the receiver sat.
//! The discrete chain is dispersive; the reference is now its exact threshold arrival
//! (`sound_speed_exact`), timed by the same criterion on its normal-mode motion.

use std::f64::consts::PI;

use crate::common::{execute_all, line_with, number_after, report_of};

/// Node mass m (kg), spring k (N/m) and spacing a (m) of the chains below: not 1, so that a
/// slipped m, k or a shows. √(k/m) = 2 rad/s, a√(k/m) = 1 m/s.
const M: f64 = 2.0;
const K: f64 = 8.0;
const A: f64 = 0.5;
/// Particles of the chain, the source's speed v0 (m/s) and the threshold θ of the arrival.
const N: usize = 200;
const V0: f64 = 0.1;
const THETA: f64 = 0.01;

/// A chain of [`N`] between fixed walls hit at particle 1, timed at particle `receiver` over
/// 100 t_c (the front crosses the whole chain) by `integrator` at dt = t_c/`dt_per_tc`.
fn chain(receiver: usize, integrator: &str, dt_per_tc: u32) -> String {
    format!(
        "version: 1\nname: front\nscenes:\n  - name: wave\n    kind: chain\n    material: {{mass: {M}, k: {K}}}\n    \
         geometry: {{spacing: {A}}}\n    n: {N}\n    node: first\n    v0: {V0}\n    wave: {{receiver: {receiver}}}\n    \
         time: {{integrator: {integrator}, dt_per_tc: {dt_per_tc}, duration_tc: 100, samples: 50}}\n"
    )
}

/// J_n(x) by the trapezoidal rule on Bessel's integral (1/2π) ∫₀^{2π} cos(nτ − x sin τ) dτ:
/// the integrand is periodic and smooth, so `POINTS` nodes are exact but for the aliased
/// J_{POINTS ± n}(x), below 1e-100 for n ≤ 202 and x ≤ 400 (order − argument > 400).
fn bessel_j(n: usize, x: f64) -> f64 {
    const POINTS: usize = 1024;
    let step = 2.0 * PI / POINTS as f64;
    (0..POINTS).map(|i| (n as f64 * i as f64 * step - x * (i as f64 * step).sin()).cos()).sum::<f64>() / POINTS as f64
}

/// Velocity (m/s) of particle `j` of a chain with a fixed wall at site 0, particle 1 hit with
/// [`V0`] at t = 0, before anything comes back from the far wall. On the infinite chain a
/// particle 0 hit with v0 gives u̇_j(t) = v0 J_{2j}(2ω₀t), ω₀ = √(k/m) (J_{2j}(0) = δ_j0, and
/// 4J″_n = J_{n−2} − 2J_n + J_{n+2} is the chain's equation); the wall at 0 is the image of
/// the hit at site −1 with the opposite sign: u̇_j = v0 (J_{2(j−1)} − J_{2(j+1)})(2ω₀t). The far
/// wall's images enter as J of order ≥ 2(2(N + 1) − j − 1): ≥ 602 at 2ω₀t < 200 for the
/// receiver (t < 50 s), ≥ 800 at 2ω₀t ≤ 400 for the source (t ≤ 100 s); below 1e-40.
fn semi_infinite_velocity(j: usize, t: f64) -> f64 {
    let x = 2.0 * (K / M).sqrt() * t;
    V0 * (bessel_j(2 * (j - 1), x) - bessel_j(2 * (j + 1), x))
}

/// The first time (s) particle `j`'s speed reaches θ v0: scanned in steps of 0.05 s until it
/// does, then bisected to 1e-12 s. The source's peak speed is v0, at t = 0 (checked).
fn threshold_crossing(j: usize) -> f64 {
    let peak = (0..2000).map(|i| semi_infinite_velocity(1, 0.05 * i as f64).abs()).fold(0.0, f64::max);
    assert!((peak / V0 - 1.0).abs() < 1e-12, "the source's peak is v0: {peak}");
    let reached = |t: f64| semi_infinite_velocity(j, t).abs() >= THETA * V0;
    let mut high = (1..).map(|i| 0.05 * i as f64).find(|&t| reached(t)).unwrap();
    let mut low = high - 0.05;
    while high - low > 1e-12 {
        let mid = 0.5 * (low + high);
        if reached(mid) { high = mid } else { low = mid }
    }
    high
}

#[test]
fn the_exact_discrete_front_is_the_bessel_front_of_the_chain() {
    // The program's exact threshold arrival (normal modes at the run's record times, crossings
    // interpolated linearly between them, dt = t_c/50 = 0.022 s) against the continuous crossing
    // of the Bessel solution: the chord of the convex rise is early by about Δ² |v̈|/(8 |v̇|), 6e-5 s
    // at a growth rate |v̈/v̇| ~ 1/s near θ, 1e-6 of the 48 s arrival (measured −8.6e-7); the
    // bound 1e-5 leaves a factor 10.
    let receiver = 100;
    let record = &execute_all(&chain(receiver, "position-verlet", 50))[0];
    let (exact, distance) = (record.metrics.chain.sound_speed_exact.unwrap(), record.metrics.wave_distance.unwrap());
    assert!((distance / (99.0 * A) - 1.0).abs() < 1e-12, "{distance}");
    let bessel = threshold_crossing(receiver);
    let program = distance / exact;
    assert!((program / bessel - 1.0).abs() < 1e-5, "{program} s against {bessel} s");
    // The dispersive front: the threshold arrives 3.8 % before x = a√(k/m) t (A√(K/M) = 1 m/s).
    let lead = distance / bessel / (A * (K / M).sqrt()) - 1.0;
    assert!((0.035..0.042).contains(&lead), "{lead}");
}

#[test]
fn a_mid_chain_receiver_is_judged_against_the_exact_discrete_front() {
    // Held against a√(k/m) within the former 2 % it read ✗ (its lead is 3.8 %); against the
    // exact discrete chain it is ✓, within the item's stated tolerance, at Verlet's t_c/50.
    let report = report_of("front", &chain(N / 2, "position-verlet", 50));
    let summary = line_with(&report, "[The speed of sound]");
    let (error, lead) =
        (number_after(summary, "by the speed threshold, "), number_after(summary, "of the exact discrete chain's, "));
    assert!((0.035..0.042).contains(&lead), "{summary}");
    let reference = line_with(&report, "**Reference:** The exact discrete chain's front speed");
    let tolerance = number_after(reference, "tolerance ");
    assert!(lead > 0.02 && error.abs() < tolerance, "{summary}\n{reference}");
    assert!(reference.contains("**Verdict: ✓ within.**"), "{reference}");
    let sentence = line_with(&report, "A chain of 200 hit at one end");
    assert!(sentence.contains("the front reaches particle 100, 49.50 m away"), "{sentence}");
    assert!(sentence.contains("it runs ahead of x = a√(k/m) t because the chain is dispersive"), "{sentence}");
}

#[test]
fn a_time_step_that_misses_the_exact_front_is_outside() {
    // Symplectic Euler at dt = t_c/5: its velocity lags half a step (0.11 s) and its phase error
    // grows as (ω dt)²/24, so its front misses the exact discrete chain's by 3e-3 (Verlet's by
    // 8e-4 at the same step), beyond the tolerance: the item must say ✗.
    let report = report_of("front", &chain(N / 2, "symplectic-euler", 5));
    let summary = line_with(&report, "[The speed of sound]");
    let error = number_after(summary, "by the speed threshold, ");
    let reference = line_with(&report, "**Reference:** The exact discrete chain's front speed");
    assert!(error.abs() > number_after(reference, "tolerance "), "{summary}\n{reference}");
    assert!(reference.contains("**Verdict: ✗ outside"), "{reference}");
}

#[test]
fn the_item_judges_the_run_nearest_its_tolerances_time_step() {
    // The same mid-chain front by symplectic Euler at t_c/5 (outside, above) and by position
    // Verlet at t_c/50 (inside) in one campaign, the coarse run first: the reviewer's campaign
    // had its first chain judged, at t_c/10, against a tolerance derived at t_c/50. The item
    // now judges the run nearest t_c/50 by Verlet, whatever the order.
    let coarse = chain(N / 2, "symplectic-euler", 5);
    let fine = chain(N / 2, "position-verlet", 50);
    let scene = |yaml: &str, name: &str| yaml.split_once("scenes:\n").unwrap().1.replacen("name: wave", name, 1);
    let yaml =
        format!("version: 1\nname: front\nscenes:\n{}{}", scene(&coarse, "name: coarse"), scene(&fine, "name: fine"));
    let report = report_of("front", &yaml);
    let reference = line_with(&report, "**Reference:** The exact discrete chain's front speed");
    assert!(reference.contains("**Verdict: ✓ within.**"), "{reference}");
    let summary = line_with(&report, "[The speed of sound]");
    assert!(
        number_after(summary, "by the speed threshold, ").abs() < number_after(reference, "tolerance "),
        "{summary}"
    );
}
