//! The 2D block's answers, computed once for the summary, the abstract and the items: E and ν
//! of the loaded block extrapolated to an infinite block with their uncertainty, G of the
//! periodic strip, and the block's sound speed in m/s, measured by a wave run of the same
//! material and derived from the measured moduli and density.

use std::collections::BTreeMap;

use super::finding::{Evidence, lattice_size, percent, plus_minus, regular, relative, sig};
use crate::runner::RunRecord;
use crate::spec::{Control, Diagonals, LoadCase, Supports};

/// The material of a lattice run, as bits so that it can key a map: mass (kg), k (N/m),
/// k_d (N/m), spacing a (m), depth d (m).
type Material = [u64; 5];

/// The material of `r`, if it is a lattice.
fn material(r: &RunRecord) -> Option<Material> {
    let l = r.spec.lattice()?;
    Some([r.spec.mass, r.spec.k, l.k_diag, r.spec.spacing, l.depth].map(f64::to_bits))
}

/// A set-up whose tensile blocks are extrapolated together: on other supports than the
/// coursework's, the material, and the block's shape.
type Setup = (bool, Material, (usize, usize));

/// A block's shape N_x : N_y in lowest terms. The finite-size share b/N of a modulus depends on
/// the shape (a 20 × 6 block has the boundary layer of a 6-row block under its loads), so
/// v(N) = v∞ + b/N holds, with one b, only over blocks of one shape.
fn shape(nx: usize, ny: usize) -> (usize, usize) {
    let gcd = (1..=nx.min(ny)).rev().find(|&g| nx.is_multiple_of(g) && ny.is_multiple_of(g)).unwrap_or(1);
    (nx / gcd, ny / gcd)
}

/// The extrapolated E and ν agree with the continuum when each lies within this many of its own
/// uncertainties of the continuum's value: the uncertainty estimates the neglected next order of
/// the finite-size share, not a standard deviation, so a few of it are allowed, not tens.
pub(super) const CONTINUUM_UNCERTAINTIES: f64 = 3.0;

/// A modulus measured on blocks of several sizes N, extrapolated to N → ∞.
pub(super) struct Extrapolated {
    /// The extrapolated value.
    pub(super) value: f64,
    /// Its uncertainty: the change of the extrapolation when the smallest block is left out
    /// (three or more sizes), or the whole finite-size correction (two sizes); with one size
    /// the relaxation's MD − static difference alone, which says nothing of the finite-size
    /// share, so it is not written as ± ([`Extrapolated::words`]).
    pub(super) uncertainty: f64,
    /// The block sizes it comes from.
    sizes: usize,
    /// The measured value on the largest block.
    pub(super) largest: f64,
    /// The continuum value the network discretises.
    pub(super) continuum: Option<f64>,
}

/// Richardson's extrapolation of a finite-size effect ∝ 1/N from blocks of N₁ < N₂ nodes a
/// side: v(N) = v∞ + b/N gives v∞ = (N₂ v₂ − N₁ v₁)/(N₂ − N₁). A boundary layer of fixed
/// thickness (the point loads, the single pinned corner) changes a modulus by a share ∝ 1/N.
fn richardson((n1, v1): (f64, f64), (n2, v2): (f64, f64)) -> f64 {
    (n2 * v2 - n1 * v1) / (n2 - n1)
}

impl Extrapolated {
    /// The extrapolation of `pick` over `runs`, one per size, by rising size; `fem` the same
    /// quantity's static answer, whose difference from MD bounds the uncertainty from below.
    fn of(
        runs: &[&RunRecord],
        pick: fn(&RunRecord) -> Option<f64>,
        fem: fn(&RunRecord) -> Option<f64>,
        theory: fn(&RunRecord) -> Option<f64>,
    ) -> Option<Extrapolated> {
        let series: Vec<(f64, f64)> =
            runs.iter().filter_map(|r| Some((r.spec.lattice()?.nx as f64, pick(r)?))).collect();
        let last = *runs.last()?;
        let largest = series.last()?.1;
        let relaxation = relative(pick(last), fem(last)).map_or(0.0, |x| (x * largest).abs());
        let n = series.len();
        let (value, finite_size) = match n {
            1 => (largest, 0.0),
            2 => {
                let value = richardson(series[0], series[1]);
                (value, (value - largest).abs())
            }
            _ => {
                let value = richardson(series[n - 2], series[n - 1]);
                (value, (value - richardson(series[n - 3], series[n - 2])).abs())
            }
        };
        Some(Extrapolated {
            value,
            uncertainty: finite_size.max(relaxation),
            largest,
            continuum: theory(last),
            sizes: n,
        })
    }

    /// The value with its uncertainty where two sizes or more give one; one block's value alone
    /// (its ± would be MD against its static answer, read as the distance to the continuum).
    pub(super) fn words(&self) -> String {
        if self.sizes < 2 { sig(self.value) } else { plus_minus(self.value, self.uncertainty) }
    }

    /// How far one block's value lies from the continuum's, relative (`+9.029 %`).
    fn continuum_offset(&self) -> String {
        self.continuum.map_or_else(|| "–".into(), |c| percent((self.value - c) / c))
    }

    /// |v∞ − continuum| in units of the uncertainty (infinite when the uncertainty is 0 and the
    /// values differ), if the continuum is known.
    fn distance(&self) -> Option<f64> {
        let off = (self.value - self.continuum?).abs();
        Some(if off == 0.0 { 0.0 } else { off / self.uncertainty })
    }
}

/// The largest force-loaded, regular, linear block with both diagonals sheared on `supports` whose
/// G MD measured, among the runs `keep` selects.
pub(super) fn largest_sheared<'a>(
    e: &Evidence<'a>,
    supports: Supports,
    keep: impl Fn(&RunRecord) -> bool,
) -> Option<&'a RunRecord> {
    e.ok(|r| {
        regular(r).is_some_and(|l| {
            (l.load_case, l.supports, l.control, l.diagonals)
                == (LoadCase::Shear, supports, Control::Force, Diagonals::Both)
        }) && r.metrics.lattice.shear_modulus.is_some()
            && keep(r)
    })
    .into_iter()
    .max_by_key(|r| r.spec.lattice().map_or(0, |l| l.nx))
}

/// The block's E and ν from the tensile runs of one set-up (supports and material), G from its
/// periodic strip and its coursework supports, and its sound speed.
pub(super) struct Block<'a> {
    /// The tensile runs extrapolated, one per size, by rising size, all of one shape.
    pub(super) tensile: Vec<&'a RunRecord>,
    /// The tensile blocks of the same supports and material but other shapes, left out of the
    /// extrapolation.
    left_out: Vec<&'a RunRecord>,
    pub(super) youngs: Extrapolated,
    pub(super) poisson: Extrapolated,
    /// The periodic strip (the largest one), whose G MD and the static answer both measure.
    pub(super) shear: Option<&'a RunRecord>,
    /// The largest block sheared on the coursework's supports, whose apparent G they bend below
    /// k_d/d (0.40 of it on 40 × 40).
    supported_shear: Option<&'a RunRecord>,
    /// The wave run of the same material that timed its front over the longest distance.
    pub(super) wave: Option<&'a RunRecord>,
}

impl<'a> Block<'a> {
    /// The block of `e`: the force-loaded, linear, regular lattices with both diagonals, on the
    /// coursework's supports where the campaign has them (their moduli converge to the
    /// continuum's: a clamped bottom stiffens a block of any size), else on the set-up with the
    /// most sizes. A periodic strip cannot contract, so it gives G but not E and ν.
    pub(super) fn of(e: &Evidence<'a>) -> Option<Block<'a>> {
        let loaded = |case: LoadCase| {
            e.ok(move |r| {
                regular(r).is_some_and(|l| {
                    l.load_case == case && l.control == Control::Force && l.diagonals == Diagonals::Both
                })
            })
        };
        let mut setups: BTreeMap<Setup, BTreeMap<usize, &RunRecord>> = BTreeMap::new();
        for r in loaded(LoadCase::Tensile) {
            let Some(l) = r.spec.lattice().filter(|l| l.supports != Supports::PeriodicX) else { continue };
            let key = (l.supports != Supports::Coursework, material(r)?, shape(l.nx, l.ny));
            setups.entry(key).or_default().entry(l.nx).or_insert(r);
        }
        // The coursework's supports first, then the shape with the most sizes, squares on a tie.
        let (&(other, chosen, family), _) = setups
            .iter()
            .min_by_key(|((other, _, family), sizes)| (*other, usize::MAX - sizes.len(), *family != (1, 1)))?;
        let left_out: Vec<&RunRecord> = setups
            .iter()
            .filter(|((o, m, f), _)| (*o, *m) == (other, chosen) && *f != family)
            .flat_map(|(_, sizes)| sizes.values().copied())
            .collect();
        let tensile: Vec<&RunRecord> = setups.remove(&(other, chosen, family))?.into_values().collect();
        let youngs = Extrapolated::of(
            &tensile,
            |r| r.metrics.lattice.youngs_modulus,
            |r| r.metrics.lattice.youngs_modulus_fem,
            |r| r.metrics.lattice.youngs_modulus_theory,
        )?;
        let poisson = Extrapolated::of(
            &tensile,
            |r| r.metrics.lattice.poisson_ratio,
            |r| r.metrics.lattice.poisson_ratio_fem,
            |r| r.metrics.lattice.poisson_ratio_theory,
        )?;
        let same_medium = |r: &RunRecord| material(r).is_some_and(|m| m == chosen);
        let shear = largest_sheared(e, Supports::PeriodicX, |r| {
            same_medium(r) && r.metrics.lattice.shear_modulus_fem.is_some()
        });
        let supported_shear = largest_sheared(e, Supports::Coursework, same_medium);
        let wave = e
            .ok(|r| {
                r.spec.law.is_linear()
                    && r.spec.lattice().is_some_and(|l| l.impulse.is_some() && l.diagonals == Diagonals::Both)
                    && r.metrics.recommended_sound_speed().is_some()
                    && r.metrics.sound_speed_theory.is_some()
            })
            .into_iter()
            .filter(|r| same_medium(r))
            .max_by(|a, b| a.metrics.wave_distance.unwrap_or(0.0).total_cmp(&b.metrics.wave_distance.unwrap_or(0.0)));
        Some(Block { tensile, left_out, youngs, poisson, shear, supported_shear, wave })
    }

    /// The run that fixes the block's material (its largest tensile block).
    pub(super) fn first(&self) -> &'a RunRecord {
        self.tensile[self.tensile.len() - 1]
    }

    /// The block's density ρ = m/(a² d) (kg/m³): one node's mass over its cell's volume.
    pub(super) fn density(&self) -> f64 {
        let s = &self.first().spec;
        s.mass / (s.spacing * s.spacing * s.lattice().map_or(f64::NAN, |l| l.depth))
    }

    /// The longitudinal sound speed (m/s) of a sheet with the extrapolated E and ν and the
    /// block's density, c = √(E/(ρ(1 − ν²))) (plane stress), with its uncertainty from theirs:
    /// δc/c = ½ δE/E + ν δν/(1 − ν²).
    pub(super) fn sound_from_moduli(&self) -> (f64, f64) {
        let (e, nu) = (&self.youngs, &self.poisson);
        let c = (e.value / (self.density() * (1.0 - nu.value * nu.value))).sqrt();
        let share = 0.5 * e.uncertainty / e.value + nu.value * nu.uncertainty / (1.0 - nu.value * nu.value);
        (c, c * share)
    }

    /// [`Block::sound_from_moduli`] in words, with its unit: with its uncertainty where two sizes
    /// or more give E and ν one, else one block's value (its finite-size share included).
    fn sound_words(&self) -> String {
        let (c, spread) = self.sound_from_moduli();
        if self.tensile.len() < 2 {
            format!("{} m/s (one block's E and ν)", sig(c))
        } else {
            format!("{} m/s", plus_minus(c, spread))
        }
    }

    /// The sizes extrapolated from, in words (`6 × 6 and 20 × 20`, `5 × 5 … 40 × 40`).
    fn family(&self) -> String {
        let size = super::finding::lattice_size;
        match self.tensile.as_slice() {
            [first, _, _, ..] => format!("{} … {}", size(first), size(self.first())),
            all => crate::report::words::listed(&all.iter().map(|r| size(r)).collect::<Vec<_>>(), "and"),
        }
    }

    /// The blocks of other shapes left out, in words, where the campaign has them.
    fn left_out(&self) -> String {
        if self.left_out.is_empty() {
            return String::new();
        }
        let others: Vec<String> = self.left_out.iter().map(|r| super::finding::lattice_size(r)).collect();
        let (nx, ny) = self.first().spec.lattice().map_or((0, 0), |l| shape(l.nx, l.ny));
        format!(
            " (blocks of shape N_x : N_y = {nx} : {ny} only; {} left out: another shape has another finite-size \
             share)",
            crate::report::words::listed(&others, "and")
        )
    }

    /// How the values were found: extrapolated over two sizes or more, else measured on one
    /// block, whose finite-size share is then not estimated.
    fn basis(&self) -> String {
        if self.tensile.len() < 2 {
            format!(
                "measured on {} alone (one size: its finite-size share, ∝ 1/N, is not estimated; E {} and ν {} from \
                 the continuum){}",
                self.family(),
                self.youngs.continuum_offset(),
                self.poisson.continuum_offset(),
                self.left_out()
            )
        } else {
            format!(
                "extrapolated to an infinite block (the finite-size share falls as 1/N) from {}{}",
                self.family(),
                self.left_out()
            )
        }
    }

    /// The summary's line of E and ν: the extrapolated values with their uncertainty, or one
    /// block's values with their distance from the continuum, which its finite size keeps.
    pub(super) fn youngs_short(&self) -> String {
        let basis = if self.tensile.len() < 2 {
            format!(
                "one size: {}, {} and {} from the continuum, its finite-size share not separated",
                self.family(),
                self.youngs.continuum_offset(),
                self.poisson.continuum_offset()
            )
        } else {
            format!("N → ∞ from {}", self.family())
        };
        format!(
            "E = {} Pa, ν = {} ({}, {basis}); continuum {} Pa, {}",
            self.youngs.words(),
            self.poisson.words(),
            self.supports(),
            self.youngs.continuum.map_or_else(|| "–".into(), sig),
            self.poisson.continuum.map_or_else(|| "–".into(), sig),
        )
    }

    /// The supports of the extrapolated set-up, in words.
    fn supports(&self) -> String {
        format!("{} supports", self.first().spec.lattice().map_or("", |l| l.supports.name()))
    }

    /// The summary's line of G, on each boundary condition the campaign shears the block on: on
    /// the periodic strip MD's, with its difference from the static answer of the same network
    /// (the relaxation's residual: a bias, not a scatter, so not written as ±); on the
    /// coursework's supports the apparent G as a share of k_d/d.
    pub(super) fn shear_short(&self) -> Option<String> {
        let strip = self.shear.and_then(|r| {
            let m = &r.metrics.lattice;
            let (md, exact) = (m.shear_modulus?, m.shear_modulus_fem?);
            Some(format!(
                "G = {} Pa on the periodic strip (MD, {} on the static answer) against k_d/d = {} Pa",
                crate::report::words::number(md),
                super::finding::rel((md - exact) / exact),
                sig(m.shear_modulus_theory?)
            ))
        });
        let supported = self.supported_shear.and_then(|r| {
            let (g, theory) = (r.metrics.lattice.shear_modulus?, r.metrics.lattice.shear_modulus_theory?);
            let words =
                format!("{} Pa ({:.2} of k_d/d) on {} coursework supports", sig(g), g / theory, lattice_size(r));
            Some((words, theory))
        });
        match (strip, supported) {
            (Some(strip), Some((supported, _))) => Some(format!("{strip}, and {supported}")),
            (Some(strip), None) => Some(strip),
            (None, Some((supported, theory))) => Some(format!("G = {supported}, k_d/d = {} Pa", sig(theory))),
            (None, None) => None,
        }
    }

    /// The summary's line of the sound speed in m/s: measured if a wave crossed the block,
    /// else from the moduli.
    pub(super) fn sound_short(&self) -> String {
        let derived = format!("√(E/(ρ(1 − ν²))) = {}", self.sound_words());
        match self.wave.and_then(|w| Some((w.metrics.recommended_sound_speed()?, w.metrics.sound_speed_theory?))) {
            Some((v, c_l)) => format!(
                "V = {} m/s in the block, {} on c_L = {} m/s; {derived}",
                sig(v),
                percent((v - c_l) / c_l),
                sig(c_l)
            ),
            None => format!("{derived} in the block (no wave crossed it)"),
        }
    }

    /// The abstract's sentence on the block's moduli.
    pub(super) fn moduli_sentence(&self) -> String {
        let s = &self.first().spec;
        let shear = self.shear_short().map_or_else(String::new, |g| format!("; {g}"));
        // One block's values are the largest block's: not said twice.
        let largest = (self.tensile.len() >= 2).then(|| {
            format!(
                " ({} Pa and {} on {})",
                sig(self.youngs.largest),
                sig(self.poisson.largest),
                super::finding::lattice_size(self.first())
            )
        });
        format!(
            "The 2D block (m = {} kg per node, k = {} N/m, k_d/k = {}, a = {} m, d = {} m: ρ = {} kg/m³) has \
             E = {} Pa and ν = {}, {} on the {}{}, against the continuum's {} Pa and {}{}{shear}.",
            sig(s.mass),
            sig(s.k),
            sig(s.lattice().map_or(f64::NAN, |l| l.k_diag) / s.k),
            sig(s.spacing),
            sig(s.lattice().map_or(f64::NAN, |l| l.depth)),
            sig(self.density()),
            self.youngs.words(),
            self.poisson.words(),
            self.basis(),
            self.supports(),
            largest.unwrap_or_default(),
            self.youngs.continuum.map_or_else(|| "–".into(), sig),
            self.poisson.continuum.map_or_else(|| "–".into(), sig),
            self.disagreement().unwrap_or_default(),
        )
    }

    /// Whether the extrapolated E and ν each lie within [`CONTINUUM_UNCERTAINTIES`] of their
    /// own uncertainties of the continuum's: only with two sizes or more (one size leaves its
    /// finite-size share unestimated), where the continuum is known, and on the coursework's
    /// supports (a clamped bottom stiffens a block of any size: it converges elsewhere).
    pub(super) fn continuum_check(&self) -> Option<bool> {
        let distances = [self.youngs.distance()?, self.poisson.distance()?];
        let coursework = self.tensile[0].spec.lattice()?.supports == Supports::Coursework;
        (self.tensile.len() >= 2 && coursework).then(|| distances.iter().all(|&x| x <= CONTINUUM_UNCERTAINTIES))
    }

    /// How far the extrapolated E and ν lie from the continuum, in their own uncertainties, when
    /// more than [`CONTINUUM_UNCERTAINTIES`]: the finite-size share is then not what is left.
    fn disagreement(&self) -> Option<String> {
        if self.continuum_check()? {
            return None;
        }
        let (e, nu) = (self.youngs.distance()?, self.poisson.distance()?);
        Some(format!(
            ": E lies {} and ν {} of their uncertainties from them, more than {CONTINUUM_UNCERTAINTIES}, so the \
             blocks do not converge to the continuum as 1/N",
            sig(e),
            sig(nu)
        ))
    }

    /// The abstract's sentence on the block's sound speed.
    pub(super) fn sound_sentence(&self) -> String {
        let derived = format!("its measured E, ν and density give c = √(E/(ρ(1 − ν²))) = {}", self.sound_words());
        let measured = self.wave.and_then(|w| {
            Some((w, w.metrics.recommended_sound_speed()?, w.metrics.sound_speed_theory?, w.metrics.wave_distance?))
        });
        match measured {
            Some((w, v, c_l, distance)) => format!(
                "Sound crosses the block at {} m/s (the front timed over {} m by the {} speed threshold), {} on \
                 c_L = a√((k + k_d)/m) = {} m/s, and {derived}: the threshold {}.",
                sig(v),
                sig(distance),
                super::finding::threshold_percent(w),
                percent((v - c_l) / c_l),
                sig(c_l),
                if v > c_l {
                    "catches the dispersive precursor ahead of the front"
                } else {
                    "waits for the front's rise, which the dispersion broadens behind x = c_L t"
                }
            ),
            None => format!("No wave crossed the block here; {derived}."),
        }
    }
}

/// The coursework's estimate t_s = N_s t_c of run `w`'s arrival time, with N_s the particles
/// along the wave's path as the coursework counts them (the springs crossed, one fewer, are
/// the `arrival_time_tc_estimate` column): (N_s, V = L/(N_s t_c), V counting the springs), m/s.
pub(super) fn coursework_estimate(w: &RunRecord) -> Option<(f64, f64, f64)> {
    let (distance, t_s) = (w.metrics.wave_distance?, w.metrics.arrival_time_tc_estimate?);
    let springs = (t_s / w.spec.t_c).round();
    Some((springs + 1.0, distance / ((springs + 1.0) * w.spec.t_c), distance / t_s))
}

/// The coursework's estimate t_s = N_s t_c for the block's wave `w`, against its measured speed.
pub(super) fn estimate_words(w: &RunRecord) -> Option<String> {
    let v = w.metrics.recommended_sound_speed()?;
    let (particles, by_particles, by_springs) = coursework_estimate(w)?;
    Some(format!(
        "The coursework's estimate t_s = N_s t_c (N_s = {particles} particles down the block, t_c = {} s) gives \
         V = {} m/s, {:.2} × slower than measured ({} m/s counting the {} springs instead).",
        sig(w.spec.t_c),
        sig(by_particles),
        v / by_particles,
        sig(by_springs),
        particles - 1.0
    ))
}

impl Block<'_> {
    /// Item 10's sentence on the extrapolation: how the moduli converge and to what.
    pub(super) fn extrapolation_sentence(&self) -> Option<String> {
        (self.tensile.len() >= 2).then(|| {
            format!(
                "A finite block departs from the continuum by a share ∝ 1/N (to first order): its N columns carry the \
             load over a width of only (N − 1) a (without diagonals E = N/(N − 1) k/d exactly), and the loads and \
             supports disturb a boundary layer; Richardson's v∞ = (N₂ v₂ − N₁ v₁)/(N₂ − N₁) over \
             the two largest of {}{} on the {} gives E = {} Pa and ν = {} (the uncertainty: the change when the next \
             smaller pair of blocks is used, or the whole correction with two sizes), against the continuum's {} Pa \
             and {}{}.",
                self.family(),
                self.left_out(),
                self.supports(),
                self.youngs.words(),
                self.poisson.words(),
                self.youngs.continuum.map_or_else(|| "–".into(), sig),
                self.poisson.continuum.map_or_else(|| "–".into(), sig),
                self.disagreement().unwrap_or_default(),
            )
        })
    }
}
