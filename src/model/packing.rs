//! Connectivity of a packing: discs in a periodic box whose contacts come and go. What touches
//! what is found here, by cell lists (never by all pairs); the force of a contact is the one
//! spring force (`Spring::force_on_i`, rest length r_i + r_j, acting in compression only), and
//! neither knows how time is integrated (`crate::sim`).

use super::bonds::uniform;

/// A periodic square box of side L (m), sheared by `tilt` (m): the image of a point one period
/// up sits at (x + tilt, y + L) (Lees–Edwards), so that a shear strain γ is tilt = γ L.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeriodicBox {
    /// Side L (m).
    pub side: f64,
    /// x offset (m) of the image one period up; 0 for the unsheared box.
    pub tilt: f64,
}

impl PeriodicBox {
    /// The unsheared box of side `side` (m).
    pub fn square(side: f64) -> PeriodicBox {
        PeriodicBox { side, tilt: 0.0 }
    }

    /// Its area L² (m²): shearing keeps it.
    pub fn area(&self) -> f64 {
        self.side * self.side
    }

    /// The lattice vector a (L, 0) + b (tilt, L) that, added to the separation `(dx, dy)` (m),
    /// gives its nearest image (exactly so for |tilt| ≤ L/2 and separations below L/2).
    pub fn nearest_image(&self, dx: f64, dy: f64) -> (f64, f64) {
        let b = (dy / self.side).round();
        let a = ((dx - b * self.tilt) / self.side).round();
        (-a * self.side - b * self.tilt, -b * self.side)
    }

    /// The image of point (x, y) (m) inside the box: s (L, 0) + t (tilt, L) with its fractions
    /// s, t in [0, 1) ([`PeriodicBox::fractional`]).
    pub fn inside(&self, x: f64, y: f64) -> (f64, f64) {
        let (s, t) = self.fractional(x, y);
        (s * self.side + t * self.tilt, t * self.side)
    }

    /// The point's coordinates along the box's two edges, as fractions in [0, 1).
    fn fractional(&self, x: f64, y: f64) -> (f64, f64) {
        let t = y / self.side;
        let s = (x - self.tilt * t) / self.side;
        (s - s.floor(), t - t.floor())
    }
}

/// Pairs of discs: pair `b` joins `i[b] < j[b]` through the image of `j` whose separation is
/// x_i − x_j + (shift_x, shift_y); its rest length is r_i + r_j, so that δ < 0 is an overlap.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Contacts {
    /// First disc of each pair (the smaller index).
    pub i: Vec<usize>,
    /// Second disc.
    pub j: Vec<usize>,
    /// r_i + r_j (m).
    pub rest: Vec<f64>,
    /// x of the image's lattice vector (m).
    pub shift_x: Vec<f64>,
    /// y of the image's lattice vector (m).
    pub shift_y: Vec<f64>,
}

impl Contacts {
    /// Number of pairs.
    pub fn len(&self) -> usize {
        self.i.len()
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.i.is_empty()
    }

    /// Forgets the pairs, keeping the memory.
    pub fn clear(&mut self) {
        self.i.clear();
        self.j.clear();
        self.rest.clear();
        self.shift_x.clear();
        self.shift_y.clear();
    }

    /// Room for `additional` more pairs.
    fn reserve(&mut self, additional: usize) {
        self.i.reserve(additional);
        self.j.reserve(additional);
        self.rest.reserve(additional);
        self.shift_x.reserve(additional);
        self.shift_y.reserve(additional);
    }

    /// Appends the pair (i, j) through the image (shift_x, shift_y) (m), rest length `rest` (m).
    #[inline]
    pub fn push(&mut self, i: usize, j: usize, rest: f64, (shift_x, shift_y): (f64, f64)) {
        self.i.push(i);
        self.j.push(j);
        self.rest.push(rest);
        self.shift_x.push(shift_x);
        self.shift_y.push(shift_y);
    }

    /// The separation (m) of pair `b` at positions `(x, y)`.
    #[inline(always)]
    pub fn separation(&self, b: usize, x: &[f64], y: &[f64]) -> (f64, f64) {
        let (i, j) = (self.i[b], self.j[b]);
        (x[i] - x[j] + self.shift_x[b], y[i] - y[j] + self.shift_y[b])
    }
}

/// The pairs within reach as the force loop reads them, grouped by their second disc
/// (compressed rows): disc j's pairs are `start[j]..start[j + 1]`, each with its first disc
/// `first[b]` (< j) and its image's lattice vector `shifts[image[b]]` (m); the rest length is
/// r_i + r_j from the radii. Eight bytes a pair instead of [`Contacts`]' forty, read in order
/// once a step: at 10⁶ discs the list is ~20 MB instead of ~100, and the force loop and the
/// search wait less on main memory. Grouped by the second disc, not the first, so that the
/// force loop's other disc of a pair is behind it in memory, not ahead (`sim::contacts`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NearPairs {
    /// Where each disc's pairs start (one more entry than discs).
    pub start: Vec<u32>,
    /// First disc of each pair.
    pub first: Vec<u32>,
    /// Index of each pair's image in `shifts`.
    pub image: Vec<u32>,
    /// The distinct lattice vectors (m) of the list's images, (0, 0) first.
    pub shifts: Vec<(f64, f64)>,
}

impl NearPairs {
    /// Number of pairs.
    pub fn len(&self) -> usize {
        self.first.len()
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.first.is_empty()
    }

    /// The same pairs in the same order as [`Contacts`], with their rest lengths r_i + r_j
    /// from `radius` (m): for the measurements, which look at pairs one by one.
    pub fn to_contacts(&self, radius: &[f64]) -> Contacts {
        let mut pairs = Contacts::default();
        pairs.reserve(self.len());
        for (j, rows) in self.start.windows(2).enumerate() {
            for b in rows[0] as usize..rows[1] as usize {
                let i = self.first[b] as usize;
                pairs.push(i, j, radius[i] + radius[j], self.shifts[self.image[b] as usize]);
            }
        }
        pairs
    }
}

/// A disc's number as the lists store it: 32 bits (a packing of 2³² discs would need
/// hundreds of GB, far beyond the memory budget the spec checks first).
fn narrow(index: usize) -> u32 {
    u32::try_from(index).expect("a packing has fewer than 2³² discs and pairs")
}

/// The pairs in the order the search finds them: first and second disc and the image's index
/// in `shifts`, which `index` finds by the vector's bits (so that ±0 stay apart and every
/// separation keeps its last bit).
#[derive(Clone, Debug, Default)]
struct Found {
    first: Vec<u32>,
    other: Vec<u32>,
    image: Vec<u32>,
    shifts: Vec<(f64, f64)>,
    index: std::collections::HashMap<(u64, u64), u32>,
}

impl Found {
    /// Forgets the pairs, keeping the memory; image 0 is (0, 0).
    fn clear(&mut self) {
        self.first.clear();
        self.other.clear();
        self.image.clear();
        self.shifts.clear();
        self.index.clear();
        self.push_shift((0.0, 0.0));
    }

    /// Room for `additional` more pairs.
    fn reserve(&mut self, additional: usize) {
        self.first.reserve(additional);
        self.other.reserve(additional);
        self.image.reserve(additional);
    }

    /// The index of image `shift` (m), added if new.
    fn push_shift(&mut self, shift: (f64, f64)) -> u32 {
        let next = narrow(self.shifts.len());
        let index = *self.index.entry((shift.0.to_bits(), shift.1.to_bits())).or_insert(next);
        if index == next {
            self.shifts.push(shift);
        }
        index
    }

    /// Appends the pair (i, j) through the image of index `image`.
    #[inline(always)]
    fn push(&mut self, i: usize, j: usize, image: u32) {
        self.first.push(narrow(i));
        self.other.push(narrow(j));
        self.image.push(image);
    }

    /// Appends the pair (i, j) through image 0 when `keep`. Written without a branch on
    /// `keep`: the pair is stored, then dropped again when not kept, because whether a pair
    /// is within reach is a coin toss the processor cannot predict (~15 ns per wrong guess).
    #[inline(always)]
    fn push_if(&mut self, i: usize, j: usize, keep: bool) {
        let kept = self.first.len() + usize::from(keep);
        self.push(i, j, 0);
        self.first.truncate(kept);
        self.other.truncate(kept);
        self.image.truncate(kept);
    }

    /// Appends the pair (i, j) through the image (shift_x, shift_y) (m).
    fn push_shifted(&mut self, i: usize, j: usize, shift: (f64, f64)) {
        let image = self.push_shift(shift);
        self.push(i, j, image);
    }
}

/// Every pair of discs (i < j, each image of j separately) whose centres are closer than
/// r_i + r_j + `skin` (m), at positions `(x, y)` in `periodic`, ordered by j (by
/// [`ContactSearch::within`], in memory of its own).
pub fn contacts_within(x: &[f64], y: &[f64], radius: &[f64], periodic: &PeriodicBox, skin: f64) -> Contacts {
    let mut near = NearPairs::default();
    ContactSearch::default().within(x, y, radius, periodic, skin, &mut near);
    near.to_contacts(radius)
}

/// The memory a contact search works in, kept from one search to the next: a packing's list is
/// made again every few steps, and lists of 10⁶ discs made in fresh memory spent more time in
/// the kernel's page faults than in the search.
#[derive(Clone, Debug, Default)]
pub struct ContactSearch {
    /// Each disc's cell.
    home: Vec<usize>,
    /// Where each cell's discs start in `members`, kept after the search for
    /// [`ContactSearch::missed`].
    start: Vec<usize>,
    /// The discs, cell after cell (at the positions of the last search).
    members: Vec<usize>,
    /// The next free place of each cell in `members`, then each disc's pairs in the list.
    next: Vec<usize>,
    /// Cells a side at the last search; 0 when it compared every pair (a box under three cells).
    cells: usize,
    /// The escaped discs of [`ContactSearch::missed`] by the cell they are in now: (cell, disc).
    escaped_cells: Vec<(usize, usize)>,
    /// The pairs in the order the search finds them.
    found: Found,
}

impl ContactSearch {
    /// Puts into `near` every pair of discs (i < j, each image of j separately) whose centres
    /// are closer than r_i + r_j + `skin` (m), at positions `(x, y)` in `periodic`, ordered by
    /// j. Cell lists: the box is cut into c × c cells at least one reach 2 r_max + skin wide
    /// (across its sheared edges), and each cell is compared with itself and four neighbours,
    /// so the work is linear in the discs. A box under three cells wide (a few discs) compares
    /// every pair with its images.
    pub fn within(
        &mut self,
        x: &[f64],
        y: &[f64],
        radius: &[f64],
        periodic: &PeriodicBox,
        skin: f64,
        near: &mut NearPairs,
    ) {
        let reach = 2.0 * radius.iter().fold(0.0f64, |m, r| m.max(*r)) + skin;
        // A cell's width across its slanted edge is (L/c)/√(1 + (tilt/L)²).
        let slant = (1.0 + (periodic.tilt / periodic.side).powi(2)).sqrt();
        let cells = (periodic.side / (reach * slant)).floor();
        self.found.clear();
        self.cells = if cells >= 3.0 { cells as usize } else { 0 };
        if self.cells > 0 {
            self.cell_list(x, y, radius, periodic, skin, self.cells);
        } else {
            every_image(x, y, radius, periodic, skin, reach, &mut self.found);
        }
        ordered_by_second(&self.found, x.len(), &mut self.next, near);
    }

    /// The touching pairs (centres closer than r_i + r_j) at positions `(x, y)` that involve a
    /// disc of `escaped` (in increasing order) and are not in the list the last search made at
    /// `(made_x, made_y)` with `skin`, into `extra`; false, and nothing found, when there are
    /// escaped discs and that search had no cells to look for them in.
    ///
    /// Sound when every other disc is within skin/2 of where the list was made: such a disc j
    /// touching an escaped e at x_e was within r_e + r_j + skin/2 of x_e when the list was made,
    /// so in the nine cells around x_e's (cells are 2 r_max + skin wide). A pair is in the list
    /// exactly when [`reach_of`] says so at the made positions, so each touching pair is
    /// counted once: by the list or here. Two escaped discs are found by the cells they are
    /// in now.
    #[allow(clippy::too_many_arguments)] // both positions and the disc's geometry
    pub fn missed(
        &mut self,
        escaped: &[usize],
        (x, y): (&[f64], &[f64]),
        (made_x, made_y): (&[f64], &[f64]),
        radius: &[f64],
        periodic: &PeriodicBox,
        skin: f64,
        extra: &mut Contacts,
    ) -> bool {
        extra.clear();
        if self.cells == 0 {
            return escaped.is_empty();
        }
        let listed = |i: usize, j: usize| reach_of(i, j, made_x, made_y, radius, periodic, skin).0;
        let mut add = |p: usize, q: usize| {
            let (i, j) = (p.min(q), p.max(q));
            if let (true, shift) = reach_of(i, j, x, y, radius, periodic, 0.0)
                && !listed(i, j)
            {
                extra.push(i, j, radius[i] + radius[j], shift.unwrap_or((0.0, 0.0)));
            }
        };
        let now = &mut self.escaped_cells;
        now.clear();
        now.extend(escaped.iter().map(|&e| (cell_of(periodic, self.cells, x[e], y[e]), e)));
        now.sort_unstable();
        for &(home, e) in now.iter() {
            for cell in around(self.cells, home) {
                let from = now.partition_point(|&(c, _)| c < cell);
                for &(_, other) in now[from..].iter().take_while(|&&(c, _)| c == cell) {
                    if other > e {
                        add(e, other);
                    }
                }
                for &j in &self.members[self.start[cell]..self.start[cell + 1]] {
                    if escaped.binary_search(&j).is_err() {
                        add(e, j);
                    }
                }
            }
        }
        true
    }

    /// Sorts the discs by cell (a counting sort): `members[start[c]..start[c + 1]]` are cell
    /// c's, of `cells` × `cells`.
    fn sort_into_cells(&mut self, x: &[f64], y: &[f64], periodic: &PeriodicBox, cells: usize) {
        self.home.clear();
        self.home.extend((0..x.len()).map(|p| cell_of(periodic, cells, x[p], y[p])));
        self.start.clear();
        self.start.resize(cells * cells + 1, 0);
        for &c in &self.home {
            self.start[c + 1] += 1;
        }
        for c in 0..cells * cells {
            self.start[c + 1] += self.start[c];
        }
        self.members.resize(x.len(), 0);
        self.next.clear();
        self.next.extend_from_slice(&self.start);
        for (p, &c) in self.home.iter().enumerate() {
            self.members[self.next[c]] = p;
            self.next[c] += 1;
        }
    }

    /// The cell-list search over `cells` × `cells` cells (≥ 3 a side, so that the nine around
    /// a cell are distinct and the nearest image is the only one in reach), into `found`.
    fn cell_list(&mut self, x: &[f64], y: &[f64], radius: &[f64], periodic: &PeriodicBox, skin: f64, cells: usize) {
        self.sort_into_cells(x, y, periodic, cells);
        let (start, members, found) = (&self.start, &self.members, &mut self.found);
        // A dense packing has ~3 pairs per disc within a reach: room for 4 saves the regrowths.
        found.reserve(4 * x.len());
        // Each pair of neighbouring cells once: the cell itself and the half of its eight
        // neighbours to the right and above, across the box's edges (wrapped without `%`: an
        // integer division costs more than a cell's few pairs).
        let wrap = |k: usize| if k == cells { 0 } else { k };
        for row in 0..cells {
            let up = wrap(row + 1) * cells;
            for column in 0..cells {
                let own = &members[start[row * cells + column]..start[row * cells + column + 1]];
                for (a, &p) in own.iter().enumerate() {
                    for &q in &own[a + 1..] {
                        consider(p, q, x, y, radius, periodic, skin, found);
                    }
                }
                let (left, right) = (if column == 0 { cells - 1 } else { column - 1 }, wrap(column + 1));
                for other in [row * cells + right, up + left, up + column, up + right] {
                    for &p in own {
                        for &q in &members[start[other]..start[other + 1]] {
                            consider(p, q, x, y, radius, periodic, skin, found);
                        }
                    }
                }
            }
        }
    }
}

/// The nine cells around `cell` (itself included) of `cells` × `cells`, across the box's edges.
fn around(cells: usize, cell: usize) -> impl Iterator<Item = usize> {
    let (row, column) = (cell / cells, cell % cells);
    let step = move |k: usize, d: usize| (k + cells + d - 1) % cells;
    (0..3).flat_map(move |dr| (0..3).map(move |dc| step(row, dr) * cells + step(column, dc)))
}

/// The cell, of `cells` × `cells` in `periodic`, that holds the point (x, y) (m).
fn cell_of(periodic: &PeriodicBox, cells: usize, x: f64, y: f64) -> usize {
    let (s, t) = periodic.fractional(x, y);
    let column = ((s * cells as f64) as usize).min(cells - 1);
    let row = ((t * cells as f64) as usize).min(cells - 1);
    row * cells + column
}

/// Adds the pair (p, q) when its nearest image is within r_p + r_q + `skin` ([`reach_of`]).
#[allow(clippy::too_many_arguments)] // the structure of arrays, one slice per component
#[inline(always)]
fn consider(
    p: usize,
    q: usize,
    x: &[f64],
    y: &[f64],
    radius: &[f64],
    periodic: &PeriodicBox,
    skin: f64,
    found: &mut Found,
) {
    let (i, j) = (p.min(q), p.max(q));
    match reach_of(i, j, x, y, radius, periodic, skin) {
        (keep, None) => found.push_if(i, j, keep),
        (true, Some(shift)) => found.push_shifted(i, j, shift),
        (false, Some(_)) => {}
    }
}

/// Whether the nearest image of disc j is within r_i + r_j + `skin` of disc i (i < j), and
/// through which lattice vector: `None` for (0, 0) found without rounding. A separation
/// under 0.49 L along both axes is its own nearest image (`PeriodicBox::nearest_image` rounds
/// both fractions to 0), so the divisions and roundings are left to the pairs near half a box
/// apart: those across its edges, or with a disc that has left the box (positions are not
/// wrapped back).
#[inline(always)]
fn reach_of(
    i: usize,
    j: usize,
    x: &[f64],
    y: &[f64],
    radius: &[f64],
    periodic: &PeriodicBox,
    skin: f64,
) -> (bool, Option<(f64, f64)>) {
    let (dx, dy) = (x[i] - x[j], y[i] - y[j]);
    let inside = 0.49 * periodic.side;
    let reach = radius[i] + radius[j] + skin;
    if dx.abs() < inside && dy.abs() < inside {
        (dx * dx + dy * dy < reach * reach, None)
    } else {
        let shift = periodic.nearest_image(dx, dy);
        let (sx, sy) = (dx + shift.0, dy + shift.1);
        (sx * sx + sy * sy < reach * reach, Some(shift))
    }
}

/// The search of a box under three cells wide: every pair with every image in reach (a disc
/// may touch two images of another), into `found`. Only a few discs fit such a box (its side
/// is below three reaches), so the pairs are few.
fn every_image(x: &[f64], y: &[f64], radius: &[f64], periodic: &PeriodicBox, skin: f64, reach: f64, found: &mut Found) {
    let images = (reach / periodic.side).ceil() as i64 + 1;
    for i in 0..x.len() {
        for j in i + 1..x.len() {
            let (dx, dy) = (x[i] - x[j], y[i] - y[j]);
            let nearest = periodic.nearest_image(dx, dy);
            let rest = radius[i] + radius[j];
            for b in -images..=images {
                for a in -images..=images {
                    let (a, b) = (a as f64, b as f64);
                    let shift = (nearest.0 + a * periodic.side + b * periodic.tilt, nearest.1 + b * periodic.side);
                    let (sx, sy) = (dx + shift.0, dy + shift.1);
                    if sx * sx + sy * sy < (rest + skin) * (rest + skin) {
                        found.push_shifted(i, j, shift);
                    }
                }
            }
        }
    }
}

/// `found`'s pairs into `sorted`, grouped by their second disc (a counting sort, stable, with
/// `place` its counts), so that the force loop reads and writes the second disc's memory in
/// increasing order.
fn ordered_by_second(found: &Found, discs: usize, place: &mut Vec<usize>, sorted: &mut NearPairs) {
    place.clear();
    place.resize(discs + 1, 0);
    for &j in &found.other {
        place[j as usize + 1] += 1;
    }
    for p in 0..discs {
        place[p + 1] += place[p];
    }
    sorted.start.clear();
    sorted.start.extend(place.iter().map(|&b| narrow(b)));
    sorted.first.resize(found.first.len(), 0);
    sorted.image.resize(found.image.len(), 0);
    for b in 0..found.other.len() {
        let at = &mut place[found.other[b] as usize];
        sorted.first[*at] = found.first[b];
        sorted.image[*at] = found.image[b];
        *at += 1;
    }
    sorted.shifts.clone_from(&found.shifts);
}

/// The periodic square box in which ⌈n/2⌉ discs of radius `small` (m) and ⌊n/2⌋ of `ratio`
/// times that cover the area fraction `fraction`: L = √(π (n_s r_s² + n_l r_l²) / φ).
pub fn bidisperse_box(n: usize, small: f64, ratio: f64, fraction: f64) -> PeriodicBox {
    let (n_small, n_large) = (n.div_ceil(2) as f64, (n / 2) as f64);
    let discs_area = std::f64::consts::PI * small * small * (n_small + n_large * ratio * ratio);
    PeriodicBox::square((discs_area / fraction).sqrt())
}

/// `n` discs, the first ⌈n/2⌉ of radius `small` (m) and the rest `ratio` times larger, at
/// uniformly random positions (from `seed`) in the periodic square box whose area their discs
/// cover to the fraction `fraction`: (box, x, y, radius). The discs are numbered along rows of
/// the box (cells one large diameter wide), so that neighbours in space are near in memory.
pub fn random_bidisperse(
    n: usize,
    small: f64,
    ratio: f64,
    fraction: f64,
    seed: u64,
) -> (PeriodicBox, Vec<f64>, Vec<f64>, Vec<f64>) {
    let radius: Vec<f64> = (0..n).map(|k| if k < n.div_ceil(2) { small } else { small * ratio }).collect();
    let periodic = bidisperse_box(n, small, ratio, fraction);
    let side = periodic.side;
    let place = |k: usize| (uniform(seed, 2 * k as u64) * side, uniform(seed, 2 * k as u64 + 1) * side);
    let cell = 2.0 * small * ratio;
    let columns = (side / cell).ceil().max(1.0) as usize;
    let mut order: Vec<(usize, usize)> = (0..n)
        .map(|k| {
            let (x, y) = place(k);
            (((y / cell) as usize) * columns + (x / cell) as usize, k)
        })
        .collect();
    order.sort_unstable();
    let (x, y): (Vec<f64>, Vec<f64>) = order.iter().map(|&(_, k)| place(k)).unzip();
    let radius = order.iter().map(|&(_, k)| radius[k]).collect();
    (periodic, x, y, radius)
}
