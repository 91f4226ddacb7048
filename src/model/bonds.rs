//! Connectivity of an irregular network: which particle pairs are joined by a spring, with rest
//! length and stiffness, as a structure of arrays in particle order.

/// Bond list: bond `b` joins particles `i[b]` and `j[b]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bonds {
    /// First particle of each bond.
    pub i: Vec<usize>,
    /// Second particle of each bond.
    pub j: Vec<usize>,
    /// Rest length x_e (m): δ = |x_i − x_j| − x_e.
    pub rest: Vec<f64>,
    /// Stiffness constant of each bond: k (N/m) for linear, C (N/m^β) for power-law springs.
    pub stiffness: Vec<f64>,
    /// x offset (m) added to x_i − x_j: the period for a bond that wraps around a periodic
    /// side, 0 otherwise.
    pub shift_x: Vec<f64>,
}

impl Bonds {
    /// Number of bonds.
    pub fn len(&self) -> usize {
        self.i.len()
    }

    /// True when there are no bonds.
    pub fn is_empty(&self) -> bool {
        self.i.is_empty()
    }

    /// Appends a bond between `i` and `j`.
    pub fn push(&mut self, i: usize, j: usize, rest: f64, stiffness: f64) {
        self.push_shifted(i, j, rest, stiffness, 0.0);
    }

    /// Appends a bond between `i` and the image of `j` shifted by `shift_x` (m) along x.
    pub fn push_shifted(&mut self, i: usize, j: usize, rest: f64, stiffness: f64, shift_x: f64) {
        self.i.push(i);
        self.j.push(j);
        self.rest.push(rest);
        self.stiffness.push(stiffness);
        self.shift_x.push(shift_x);
    }

    /// Copies bond `b` of `self` onto the end of `to`.
    pub fn copy_to(&self, b: usize, to: &mut Bonds) {
        to.push_shifted(self.i[b], self.j[b], self.rest[b], self.stiffness[b], self.shift_x[b]);
    }

    /// Calls `visit(i, j, rest, k, shift_x)` for every bond, in list order.
    pub fn for_each(&self, mut visit: impl FnMut(usize, usize, f64, f64, f64)) {
        for b in 0..self.len() {
            visit(self.i[b], self.j[b], self.rest[b], self.stiffness[b], self.shift_x[b]);
        }
    }

    /// Largest particle index used, plus one (0 without bonds).
    pub fn particles_needed(&self) -> usize {
        self.i.iter().chain(&self.j).map(|&p| p + 1).max().unwrap_or(0)
    }

    /// The bonds left after removing each with probability `cut_fraction`, the kept ones'
    /// stiffness times 1 + w·U with U uniform in [−1, 1] (w = `stiffness_spread`); the
    /// random numbers are a hash of the bond's key `key(b)` (its index, or the index of the
    /// same bond in another listing of the network) and `seed`, one stream for the cut and
    /// another for the spread (reproducible on every machine, and a spread does not change
    /// which bonds are cut). Bonds for which `uncut(i, j)` holds are never cut.
    pub fn randomised(
        &self,
        cut_fraction: f64,
        stiffness_spread: f64,
        seed: u64,
        key: impl Fn(usize) -> u64,
        uncut: impl Fn(usize, usize) -> bool,
    ) -> Bonds {
        let mut kept = Bonds::default();
        for b in 0..self.len() {
            if uncut(self.i[b], self.j[b]) || uniform(seed, key(b)) >= cut_fraction {
                self.copy_to(b, &mut kept);
                if stiffness_spread > 0.0 {
                    let u = 2.0 * uniform(!seed, key(b)) - 1.0;
                    *kept.stiffness.last_mut().expect("just pushed") *= 1.0 + stiffness_spread * u;
                }
            }
        }
        kept
    }

    /// Reorders the bonds by (smaller index, larger index), so the force loop reads and writes
    /// particle memory in nearly increasing order.
    pub fn sorted(&self) -> Bonds {
        let mut order: Vec<usize> = (0..self.len()).collect();
        order.sort_by_key(|&b| (self.i[b].min(self.j[b]), self.i[b].max(self.j[b])));
        let mut sorted = Bonds::default();
        for b in order {
            self.copy_to(b, &mut sorted);
        }
        sorted
    }
}

/// A uniform number in [0, 1) from `(seed, index)` by the splitmix64 finaliser: the one
/// source of randomness of the networks and packings (reproducible on every machine).
pub(crate) fn uniform(seed: u64, index: u64) -> f64 {
    let mut z = seed.wrapping_add(index.wrapping_mul(0x9e37_79b9_7f4a_7c15));
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}
