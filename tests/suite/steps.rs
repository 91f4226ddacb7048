//! The time step on a kicked lattice: the item fits the energy error's order over runs that
//! differ in dt alone, one fit per integrator (and per other setting the scene sweeps), each
//! judged against its own integrator's order; and the upper-right kick quotes the front speed of
//! the scene's most accurate run.

use crate::common::{line_with, number_after, report_of};

/// A free 6 × 6 lattice kicked at its upper-right node, undamped, with `law` springs and a
/// `grid`; `integrator` set at the scene unless the grid sweeps it.
fn kicked(name: &str, law: &str, integrator: &str, grid: &str) -> String {
    format!(
        "version: 1\nname: {name}\nscenes:\n  - name: kick\n    kind: lattice\n    material: {{law: {law}}}\n    \
         lattice: {{size: 6}}\n    supports: free\n    impulse: {{node: top-right, velocity: [0.0, -0.01]}}\n    \
         wave: {{}}\n    time: {{{integrator}}}\n    grid:\n{grid}"
    )
}

/// Symplectic Euler (energy error of order 1) and Forest–Ruth (order 4), each at t_c/10, t_c/20
/// and t_c/40.
fn two_integrators() -> String {
    kicked(
        "mix",
        "linear",
        "",
        "      time.integrator: [symplectic-euler, forest-ruth]\n      time.dt_per_tc: [10, 20, 40]\n",
    )
}

/// The energy error of a row of the item's table (`| sweep | t_c/dt | dt·ω_max | energy error |`).
fn energy_error_of(row: &str) -> f64 {
    row.split('|').nth(4).and_then(|c| c.trim().parse().ok()).unwrap_or_else(|| panic!("no energy error in {row}"))
}

#[test]
fn each_integrator_of_a_lattice_dt_sweep_is_fitted_and_judged_against_its_own_order() {
    let report = report_of("mix", &two_integrators());
    // One fit over both integrators read dt^2.55 from symplectic Euler's 0.1008 at t_c/10 to
    // Forest–Ruth's 1.8e-6 at t_c/40, and judged it against velocity Verlet, which never ran.
    for (integrator, order, tolerance) in [("symplectic-euler", 1.0, 0.1), ("forest-ruth", 4.0, 0.2)] {
        let sentence = line_with(&report, &format!("with {integrator} (energy error of order {order})"));
        // Three steps from t_c/10, where dt·ω_max ≈ 0.52 and the next order's term shows by
        // (ω dt)/2 for the first-order scheme, (ω dt)²/… for Forest–Ruth: their fits read 1.03
        // and 4.07; 0.1 and 0.2 leave room without admitting the neighbouring order.
        let fitted = number_after(sentence, "falls as dt^");
        assert!((fitted - order).abs() < tolerance, "{integrator}: order {fitted}\n{sentence}");
        // Its end points are its own rows of the table, printed from the same numbers (4 digits).
        let tail = &sentence[sentence.find("falls as dt^").unwrap()..];
        for (marker, step) in [(" (", 10), ("at the largest step, ", 40)] {
            let row = line_with(&report, &format!("| {integrator} | {step} | "));
            let said = number_after(tail, marker);
            assert!((said / energy_error_of(row) - 1.0).abs() < 1e-3, "{row}\n{sentence}");
        }
    }
    let reference = line_with(&report, "**Reference:** Symplectic Euler's first order and Forest–Ruth's fourth order");
    assert!(!reference.contains("Verlet"), "{reference}");
    assert!(reference.contains("**Verdict: ✓ within.**"), "{reference}");
}

#[test]
fn the_upper_right_kick_quotes_the_front_of_the_smallest_step_at_the_highest_order() {
    let report = report_of("mix", &two_integrators());
    // The first run, symplectic Euler at t_c/10, times the front at 1.576 m/s; Forest–Ruth at
    // t_c/40 at 1.646 m/s (4 % apart, beyond the 1e-3 of two printings of one number).
    let sentence = line_with(&report, "reaches the bottom row at ");
    assert!(sentence.contains("m/s (dt = t_c/40, forest-ruth: the smallest step at the highest order"), "{sentence}");
    let row = line_with(&report, "| dt = t_c/40, forest-ruth | node ");
    let speed_threshold: f64 = row.split('|').nth(6).and_then(|c| c.trim().parse().ok()).expect(row);
    let quoted = number_after(sentence, "reaches the bottom row at ");
    assert!((quoted / speed_threshold - 1.0).abs() < 1e-3, "{row}\n{sentence}");
}

#[test]
fn runs_that_differ_in_the_kick_alone_are_no_time_step_sweep() {
    // Three kicks of a Hertz lattice, all at t_c/50 of their own t_c: the step differs with the
    // kick, but so does everything else; the item once read "from dt = t_c/50 to t_c/50: dt^0.00".
    let speeds = "      impulse.velocity: [[0.0, -0.0001], [0.0, -0.001], [0.0, -0.01]]\n";
    let kicks = report_of("hz", &kicked("hz", "hertz", "integrator: velocity-verlet", speeds));
    assert!(!kicks.contains("The time step on a lattice"), "a sweep over dt claimed from kicks");
    // Two kicks, each over three steps: two sweeps, each over dt alone. One fit over all six
    // read dt^1.65 and an arrival moving by +5.8e-1, the faster kick's earlier front (a Hertz
    // front speeds up as v0^0.2: 10^0.2 = 1.6); within one kick Verlet's phase error at
    // dt·ω_max ≈ 0.52 moves it by about (ω dt)²/24 ≈ 1 %, so 5 % tells the two apart.
    let grid = "      impulse.velocity: [[0.0, -0.001], [0.0, -0.01]]\n      time.dt_per_tc: [10, 20, 40]\n";
    let report = report_of("hz2", &kicked("hz2", "hertz", "integrator: velocity-verlet", grid));
    for kick in ["kick \\[0,-0.001\\] m/s", "kick \\[0,-0.01\\] m/s"] {
        let sentence = line_with(&report, &format!("with {kick}, velocity-verlet (energy error of order 2)"));
        assert!(sentence.contains("from dt = t_c/10 to t_c/40"), "{sentence}");
        assert!(number_after(sentence, "moves by ").abs() < 0.05, "{sentence}");
        // Velocity Verlet's second order, fitted over three steps from t_c/10 (1.92 here).
        assert!((number_after(sentence, "falls as dt^") - 2.0).abs() < 0.2, "{sentence}");
    }
}
