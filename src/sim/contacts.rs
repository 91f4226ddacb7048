//! The force field of a packing: discs in a periodic box whose contacts are found as they
//! move. A list of the pairs within r_i + r_j + skin (`model::contacts_within`, cell lists) is
//! kept while no disc has moved half a skin since it was made: until then no pair outside it
//! can overlap. The few discs that have ("escaped") are searched for alone at every step
//! (`ContactSearch::missed`), and the list is made again once they are more than one in
//! [`ESCAPED_SHARE`]: so the rebuilds follow the share of discs that moved, which does not
//! grow with N, not the fastest disc among more and more (lists over the bench's 500 steps at
//! 10⁴, 10⁵ and 10⁶ discs: 118, 134 and 159 at the first escape; 74, 75 and 75 now). Every
//! pair's force is the one spring force, `Spring::force_on_i` with rest length r_i + r_j,
//! which a contact spring exerts only while the discs overlap (δ < 0).

use super::field::{ForceField, add_background_damping};
use crate::model::{ContactSearch, Contacts, Dashpot, ForceLaw, NearPairs, PeriodicBox, Spring, contacts_within};

/// The discs' geometry a packing's field needs: radii (m), the periodic box and the stiffness
/// constant of every contact (k, N/m, or C, N/m^β).
#[derive(Clone, Debug, PartialEq)]
pub struct Packing {
    /// Radius of each disc (m).
    pub radius: Vec<f64>,
    /// The periodic box.
    pub periodic: PeriodicBox,
    /// Stiffness constant of every contact.
    pub k: f64,
    /// Skin (m): the list keeps pairs up to r_i + r_j + skin apart.
    pub skin: f64,
}

impl Packing {
    /// Σ π r² / A: the share of the box's area the discs cover.
    pub fn area_fraction(&self) -> f64 {
        self.radius.iter().map(|r| std::f64::consts::PI * r * r).sum::<f64>() / self.periodic.area()
    }

    /// The pairs of discs that overlap (δ < 0) at positions `(x, y)`.
    pub fn overlapping(&self, x: &[f64], y: &[f64]) -> Contacts {
        let near = contacts_within(x, y, &self.radius, &self.periodic, 0.0);
        let mut touching = Contacts::default();
        for b in 0..near.len() {
            let (dx, dy) = near.separation(b, x, y);
            if (dx * dx + dy * dy).sqrt() < near.rest[b] {
                touching.push(near.i[b], near.j[b], near.rest[b], (near.shift_x[b], near.shift_y[b]));
            }
        }
        touching
    }
}

/// The list is made again when more than one disc in `ESCAPED_SHARE` has moved half a skin
/// since it was made. Chosen by the packing bench (500 steps, one run each): 1 in 16, 64 and
/// 256 gave 27.1, 29.4 and 27.7 M particle-steps/s at 10⁴ discs, 18.5, 20.6 and 21.0 at 10⁶.
const ESCAPED_SHARE: usize = 64;

/// Discs tested at once for having escaped ([`ContactNetwork::find_escaped`]). Blocks of 16,
/// 64 and 256 ran the packing bench alike (10⁴ discs, 500 steps: 30.1, 29.2–30.1 and 29.8–30.0
/// M particle-steps/s, against 27.9 testing disc by disc with a jump each).
const ESCAPE_BLOCK: usize = 64;

/// A packing's contacts under one spring law `L`, dashpot `D` (contact springs: `CONTACT` is
/// true for every packing the spec builds), with background damping.
#[derive(Clone, Debug)]
pub struct ContactNetwork<L, D, const CONTACT: bool> {
    spring: Spring<L, D, CONTACT>,
    packing: Packing,
    /// The pairs within reach when the list was made ...
    near: NearPairs,
    /// ... by this search (its memory kept for the next) ...
    search: ContactSearch,
    /// ... at these positions (m).
    made_at: (Vec<f64>, Vec<f64>),
    /// The discs now more than half a skin from where the list was made, in increasing order,
    /// and their touching pairs the list does not hold.
    escaped: (Vec<usize>, Contacts),
    /// Lists made so far.
    builds: u64,
    background_gamma: f64,
}

impl<L: ForceLaw, D: Dashpot, const CONTACT: bool> ContactNetwork<L, D, CONTACT> {
    /// The field of `packing` under `spring`, with background damping `background_gamma`
    /// (N s/m); its list is made at the first evaluation.
    pub fn new(spring: Spring<L, D, CONTACT>, packing: Packing, background_gamma: f64) -> Self {
        ContactNetwork {
            spring,
            packing,
            near: NearPairs::default(),
            search: ContactSearch::default(),
            made_at: (Vec::new(), Vec::new()),
            escaped: (Vec::new(), Contacts::default()),
            builds: 0,
            background_gamma,
        }
    }

    /// Lists made so far (one at the first evaluation, then one each time more than one disc
    /// in `ESCAPED_SHARE` has moved half a skin; in a box under three cells, any disc).
    pub fn builds(&self) -> u64 {
        self.builds
    }

    /// The discs more than half a skin from where the list was made, into `escaped.0`: the
    /// list holds every touching pair of two other discs (two discs closing in on each other
    /// cover at most a skin).
    fn find_escaped(&mut self, x: &[f64], y: &[f64]) {
        let (x0, y0) = &self.made_at;
        let limit = 0.25 * self.packing.skin * self.packing.skin;
        let escaped = &mut self.escaped.0;
        escaped.clear();
        let n = x.len();
        let (x, y, x0, y0) = (&x[..n], &y[..n], &x0[..n], &y0[..n]);
        let moved = |p: usize| (x[p] - x0[p]).powi(2) + (y[p] - y0[p]).powi(2) > limit;
        // Escapes are rare: each block of discs is tested without a jump (a loop the compiler
        // vectorises), and only a block with an escape is looked through.
        for start in (0..n).step_by(ESCAPE_BLOCK) {
            let block = start..(start + ESCAPE_BLOCK).min(n);
            if block.clone().fold(false, |any, p| any | moved(p)) {
                escaped.extend(block.filter(|&p| moved(p)));
            }
        }
    }

    /// Brings the list up to date at `(x, y)`: the escaped discs' missed pairs found, or the
    /// list made again (at the first evaluation, when more than one disc in `ESCAPED_SHARE`
    /// escaped, or when escaped discs have no cells to be looked for in).
    fn refresh(&mut self, x: &[f64], y: &[f64]) {
        if self.made_at.0.len() == x.len() {
            self.find_escaped(x, y);
            let (p, (escaped, extra)) = (&self.packing, &mut self.escaped);
            let made = (self.made_at.0.as_slice(), self.made_at.1.as_slice());
            if escaped.len() * ESCAPED_SHARE <= x.len()
                && self.search.missed(escaped, (x, y), made, &p.radius, &p.periodic, p.skin, extra)
            {
                return;
            }
        }
        let p = &self.packing;
        self.search.within(x, y, &p.radius, &p.periodic, p.skin, &mut self.near);
        self.made_at.0.clear();
        self.made_at.0.extend_from_slice(x);
        self.made_at.1.clear();
        self.made_at.1.extend_from_slice(y);
        self.escaped.0.clear();
        self.escaped.1.clear();
        self.builds += 1;
    }
}

impl<L: ForceLaw, D: Dashpot, const CONTACT: bool> ForceField for ContactNetwork<L, D, CONTACT> {
    // A damped contact's force jumps where it closes (γ δ̇): a packing's thousands of contacts
    // switch within most steps, so the step is not split there (as in LAMMPS's granular
    // styles); the jump costs an O(dt) error per contact (restitution off by ~1e-2 at t_c/50).

    fn uses_velocity(&self) -> bool {
        D::ACTIVE || self.background_gamma > 0.0
    }

    fn add_forces(&mut self, x: &[f64], y: &[f64], vx: &[f64], vy: &[f64], fx: &mut [f64], fy: &mut [f64]) -> f64 {
        self.refresh(x, y);
        let (near, radius, k) = (&self.near, &self.packing.radius, self.packing.k);
        // The force on i of the pair (i, j) at separation (dx, dy), rest length `rest`: the list's
        // pairs and the escaped discs' alike.
        let pair_force = |i: usize, j: usize, rest: f64, (dx, dy): (f64, f64)| {
            let (dvx, dvy) = if D::ACTIVE { (vx[i] - vx[j], vy[i] - vy[j]) } else { (0.0, 0.0) };
            self.spring.force_on_i(k, rest, dx, dy, dvx, dvy)
        };
        let mut power = 0.0;
        // The list is grouped by the second disc j of each pair (i < j), so j's memory is read
        // and written in increasing order and its force summed in a register: the leading
        // edge of the loop's memory traffic is one stream the processor prefetches. The first
        // discs i lie at most a row of cells behind (but for pairs across the box's top and
        // bottom edge), read a few rows ago and still in cache. Grouped by i, the other disc
        // was a row ahead and its scattered first reads waited on main memory (10⁶ discs:
        // 19.3 against 22.8 M particle-steps/s, docs/performance.md). j's force collects the
        // pairs in which it is second before those in which it is first, as the sums did when
        // grouped by i, but each group in another order: the last bits differ.
        for (j, rows) in near.start.windows(2).enumerate() {
            let (mut fx_j, mut fy_j) = (fx[j], fy[j]);
            for b in rows[0] as usize..rows[1] as usize {
                let i = near.first[b] as usize;
                let (shift_x, shift_y) = near.shifts[near.image[b] as usize];
                let f = pair_force(i, j, radius[i] + radius[j], (x[i] - x[j] + shift_x, y[i] - y[j] + shift_y));
                fx[i] += f.fx;
                fy[i] += f.fy;
                fx_j -= f.fx;
                fy_j -= f.fy;
                power += f.dissipation;
            }
            (fx[j], fy[j]) = (fx_j, fy_j);
        }
        let extra = &self.escaped.1;
        for b in 0..extra.len() {
            let (i, j) = (extra.i[b], extra.j[b]);
            let f = pair_force(i, j, extra.rest[b], extra.separation(b, x, y));
            fx[i] += f.fx;
            fy[i] += f.fy;
            fx[j] -= f.fx;
            fy[j] -= f.fy;
            power += f.dissipation;
        }
        if self.background_gamma > 0.0 {
            power += add_background_damping(self.background_gamma, vx, vy, fx, fy);
        }
        power
    }

    /// Σ e(δ) over the overlapping pairs, from a search of its own (the list may be stale).
    fn potential_energy(&self, x: &[f64], y: &[f64]) -> f64 {
        let touching = self.packing.overlapping(x, y);
        (0..touching.len())
            .map(|b| {
                let (dx, dy) = touching.separation(b, x, y);
                self.spring.energy(self.packing.k, touching.rest[b], dx, dy)
            })
            .sum()
    }

    fn bond_energy(&self, k: f64, rest: f64, dx: f64, dy: f64) -> f64 {
        self.spring.energy(k, rest, dx, dy)
    }

    /// None: contacts come and go, so there is no bond whose collapse the samples could check
    /// (two discs may turn about each other), and no switch is predicted (see above).
    fn for_each_bond(&self, _visit: &mut dyn FnMut(usize, usize, f64, f64, f64)) {}
}
