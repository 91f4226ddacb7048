//! The fill-reducing elimination order of a network's stiffness: geometric nested dissection.
//! The degrees of freedom are split at the median of their longer extent; the ones of the lower
//! half bonded to the upper half are the separator, numbered after both halves, each half
//! ordered the same way. On an n × n grid a separator is one line of ~2n dofs, and the factor
//! holds O(N log N) entries for N dofs. Against faer's minimum degree order (AMD) on the 500²
//! lattice of benches/static-vs-pardiso.sh (one run each, 2026-12-04, shared machine): a 6 %
//! larger factor (6.32·10⁷ entries against 5.95·10⁷), but its analysis 0.28 s against 0.46 s and
//! its factorisation 1.10 s against 1.29 s (the separators give faer larger, denser
//! supernodes). Pure.

/// Parts this small are numbered as they come: their fill is bounded by their size.
const LEAF: usize = 64;

/// The order of the `positions.len()` degrees of freedom whose stiffness pattern is the lower
/// triangle `col_ptr`, `row_idx` and whose nodes lie at `positions` (x, y): `forward[new]` is the
/// dof eliminated `new`-th, `inverse[dof]` its place.
pub(super) fn nested_dissection(
    col_ptr: &[usize],
    row_idx: &[usize],
    positions: &[(f64, f64)],
) -> (Vec<usize>, Vec<usize>) {
    let size = positions.len();
    let graph = Graph::of(col_ptr, row_idx, size);
    let mut part: Vec<usize> = (0..size).collect();
    let mut dissection =
        Dissection { graph, positions, stamp: vec![0; size], stamps: 0, order: Vec::with_capacity(size) };
    dissection.dissect(&mut part);
    let forward = dissection.order;
    let mut inverse = vec![0; size];
    forward.iter().enumerate().for_each(|(new, &dof)| inverse[dof] = new);
    (forward, inverse)
}

/// Both triangles of the pattern as neighbour lists (u32: half the memory at 10⁶ nodes).
struct Graph {
    start: Vec<usize>,
    neighbours: Vec<u32>,
}

impl Graph {
    fn of(col_ptr: &[usize], row_idx: &[usize], size: usize) -> Graph {
        let mut degree = vec![0usize; size + 1];
        for column in 0..size {
            for &row in row_idx[col_ptr[column]..col_ptr[column + 1]].iter().filter(|&&row| row != column) {
                degree[row + 1] += 1;
                degree[column + 1] += 1;
            }
        }
        for dof in 0..size {
            degree[dof + 1] += degree[dof];
        }
        let mut fill = degree.clone();
        let mut neighbours = vec![0u32; degree[size]];
        for column in 0..size {
            for &row in row_idx[col_ptr[column]..col_ptr[column + 1]].iter().filter(|&&row| row != column) {
                neighbours[fill[row]] = column as u32;
                fill[row] += 1;
                neighbours[fill[column]] = row as u32;
                fill[column] += 1;
            }
        }
        Graph { start: degree, neighbours }
    }

    fn of_dof(&self, dof: usize) -> &[u32] {
        &self.neighbours[self.start[dof]..self.start[dof + 1]]
    }
}

/// The state of one dissection: which part a dof was last put in (`stamp`), and the order so far.
struct Dissection<'a> {
    graph: Graph,
    positions: &'a [(f64, f64)],
    stamp: Vec<u32>,
    stamps: u32,
    order: Vec<usize>,
}

impl Dissection<'_> {
    /// Numbers `part`: its lower half, its upper half, then the separator between them.
    fn dissect(&mut self, part: &mut [usize]) {
        if part.len() <= LEAF {
            self.order.extend_from_slice(part);
            return;
        }
        let positions = self.positions;
        let extent = |axis: fn(&(f64, f64)) -> f64| {
            let values = part.iter().map(|&d| axis(&positions[d]));
            values.clone().fold(f64::NEG_INFINITY, f64::max) - values.fold(f64::INFINITY, f64::min)
        };
        let along_x = extent(|p| p.0) >= extent(|p| p.1);
        let key = |d: usize| {
            let (x, y) = positions[d];
            if along_x { (x, y, d) } else { (y, x, d) }
        };
        let middle = part.len() / 2;
        part.select_nth_unstable_by(middle, |&a, &b| {
            let (a, b) = (key(a), key(b));
            a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)).then(a.2.cmp(&b.2))
        });
        self.stamps += 1;
        part[middle..].iter().for_each(|&d| self.stamp[d] = self.stamps);
        let (lower, upper) = part.split_at_mut(middle);
        // The lower half's dofs bonded to the upper half go to its end: the separator.
        let mut interior = 0;
        for at in 0..lower.len() {
            let dof = lower[at];
            if !self.graph.of_dof(dof).iter().any(|&n| self.stamp[n as usize] == self.stamps) {
                lower.swap(interior, at);
                interior += 1;
            }
        }
        let (inside, separator) = lower.split_at_mut(interior);
        self.dissect(inside);
        self.dissect(upper);
        self.order.extend_from_slice(separator);
    }
}
