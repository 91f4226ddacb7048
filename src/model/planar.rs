//! The lattice types beside the square one: triangular, honeycomb and kagome networks of
//! central springs with nearest-neighbour distance a, as explicit bond lists, and the layout
//! every type shares (node positions; the bottom and top rows, the left and right columns the
//! supports, loads and measurements name; the block's width and height).
//!
//! Nodes are numbered row by row from the bottom, left to right. Mean coordination in the
//! bulk (Maxwell's count against 2d = 4 in two dimensions): triangular z = 6 (rigid),
//! kagome z = 4 (isostatic), honeycomb z = 3 (floppy).

use serde::{Deserialize, Serialize};

use super::bonds::Bonds;

/// Which network a lattice is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LatticeType {
    /// nx × ny nodes on a square grid, with its diagonal families (`SquareLattice`).
    #[default]
    Square,
    /// Rows of nx nodes a apart, every other row shifted by a/2, rows a√3/2 apart: six
    /// neighbours.
    Triangular,
    /// Zigzag rows of nx nodes (a√3/2 apart along x, alternately a/2 up), joined to the next
    /// row by vertical bonds at every other node: three neighbours.
    Honeycomb,
    /// Corner-sharing triangles: full rows of nx nodes a apart alternate with sparse rows of
    /// nodes 2a apart, rows a√3/2 apart: four neighbours.
    Kagome,
}

impl LatticeType {
    /// Every type, in the order docs/campaigns.md lists them (`lattice.type`).
    pub const ALL: [LatticeType; 4] =
        [LatticeType::Square, LatticeType::Triangular, LatticeType::Honeycomb, LatticeType::Kagome];

    /// The name used in files and tables.
    pub fn name(self) -> &'static str {
        match self {
            LatticeType::Square => "square",
            LatticeType::Triangular => "triangular",
            LatticeType::Honeycomb => "honeycomb",
            LatticeType::Kagome => "kagome",
        }
    }

    /// True for the default square lattice (stored fields skip it, so run ids stay).
    pub fn is_square(&self) -> bool {
        *self == LatticeType::Square
    }

    /// Bulk coordination number z (bonds per node of the infinite lattice; the square
    /// lattice's with both diagonals).
    pub fn coordination(self) -> f64 {
        match self {
            LatticeType::Square => 8.0,
            LatticeType::Triangular => 6.0,
            LatticeType::Honeycomb => 3.0,
            LatticeType::Kagome => 4.0,
        }
    }

    /// Area per node of the infinite lattice with nearest-neighbour distance a (m²): a² square,
    /// √3a²/2 triangular, 3√3a²/4 honeycomb, 2√3a²/3 kagome (cell 2a × a√3 of three nodes).
    pub fn area_per_node(self, a: f64) -> f64 {
        let s3 = 3.0_f64.sqrt();
        a * a
            * match self {
                LatticeType::Square => 1.0,
                LatticeType::Triangular => s3 / 2.0,
                LatticeType::Honeycomb => 3.0 * s3 / 4.0,
                LatticeType::Kagome => 2.0 * s3 / 3.0,
            }
    }
}

/// The nodes the supports, loads and measurements name, and the block's size.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Edges {
    /// Bottom row, left to right (supported).
    pub bottom: Vec<usize>,
    /// Top row, left to right (loaded).
    pub top: Vec<usize>,
    /// Left column, bottom to top.
    pub left: Vec<usize>,
    /// Right column, bottom to top.
    pub right: Vec<usize>,
    /// Width L_x carrying the load (m): between the side columns, or the period of a
    /// periodic lattice.
    pub width: f64,
    /// Height L_y between the bottom and the top row (m).
    pub height: f64,
}

/// Node positions at rest and the edges of a lattice.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Layout {
    /// x of every node (m).
    pub x: Vec<f64>,
    /// y of every node (m).
    pub y: Vec<f64>,
    /// Rows and columns by name.
    pub edges: Edges,
}

impl Layout {
    /// The nx × ny square grid of spacing a: node (ix, iy) at (ix a, iy a), index iy·nx + ix;
    /// L_x = (nx − 1) a, or nx a when `periodic_x`.
    pub fn square(nx: usize, ny: usize, a: f64, periodic_x: bool) -> Layout {
        let rows: Vec<Vec<usize>> = (0..ny).map(|iy| (iy * nx..(iy + 1) * nx).collect()).collect();
        let columns = if periodic_x { nx } else { nx - 1 };
        let (x, y) = (0..nx * ny).map(|n| ((n % nx) as f64 * a, (n / nx) as f64 * a)).unzip();
        Layout { x, y, edges: edges_of(&rows, columns as f64 * a, (ny - 1) as f64 * a) }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// True without nodes.
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// The same block turned by +90° (x → y, y → −x, moved back to x ≥ 0): pulled from its
    /// new top row, the former right column, it is the original pulled along x. The old
    /// left column is the new bottom row, the old top row the new left column.
    pub fn turned(self) -> Layout {
        let top = self.y.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let Edges { bottom, top: top_row, left, right, width, height } = self.edges;
        Layout {
            x: self.y.iter().map(|y| top - y).collect(),
            y: self.x,
            edges: Edges { bottom: left, top: right, left: top_row, right: bottom, width: height, height: width },
        }
    }
}

/// The edges of rows of nodes listed bottom to top, each left to right.
fn edges_of(rows: &[Vec<usize>], width: f64, height: f64) -> Edges {
    Edges {
        bottom: rows[0].clone(),
        top: rows[rows.len() - 1].clone(),
        left: rows.iter().map(|r| r[0]).collect(),
        right: rows.iter().map(|r| r[r.len() - 1]).collect(),
        width,
        height,
    }
}

/// A triangular, honeycomb or kagome lattice of nx × ny rows and nodes (see [`LatticeType`]),
/// central springs k of rest length a between nearest neighbours.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarLattice {
    /// The network (`Square` here is the plain grid without diagonals; the square lattice
    /// of the scenes, with its families, is [`super::SquareLattice`]).
    pub kind: LatticeType,
    /// Nodes per (full) row.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
    /// Nearest-neighbour distance a = rest length of every spring (m).
    pub spacing: f64,
    /// Stiffness constant of every spring.
    pub k: f64,
    /// Bonds wrap across the left and right sides (period [`PlanarLattice::period`]).
    pub periodic_x: bool,
}

/// One row of a lattice: the x of its nodes in units of the row's pitch, and its y.
struct Row {
    /// Column index (in units of `pitch`) of each node, increasing.
    columns: Vec<usize>,
    /// y of the row's base (m).
    y: f64,
}

impl PlanarLattice {
    /// Why nx, ny cannot make this lattice, if they cannot: the field (`nx` or `ny`) and the
    /// rule, in words.
    pub fn size_problem(
        kind: LatticeType,
        nx: usize,
        ny: usize,
        periodic_x: bool,
    ) -> Option<(&'static str, &'static str)> {
        match kind {
            LatticeType::Honeycomb if periodic_x && nx % 2 == 1 => {
                Some(("nx", "must be even for a periodic honeycomb (its zigzag rows repeat every two nodes)"))
            }
            LatticeType::Kagome if ny.is_multiple_of(2) => {
                Some(("ny", "must be odd for a kagome lattice (its top and bottom rows are then full rows)"))
            }
            LatticeType::Kagome if nx < 3 || (periodic_x && nx % 2 == 1) => Some((
                "nx",
                "must be ≥ 3, and even when periodic, for a kagome lattice (its sparse rows repeat every 2a)",
            )),
            _ => None,
        }
    }

    /// Period along x (m) of a periodic lattice: nx a (triangular, kagome), nx a√3/2
    /// (honeycomb).
    pub fn period(&self) -> f64 {
        self.nx as f64 * self.pitch()
    }

    /// Distance along x between neighbouring columns of a full row (m).
    fn pitch(&self) -> f64 {
        match self.kind {
            LatticeType::Honeycomb => self.spacing * 3.0_f64.sqrt() / 2.0,
            _ => self.spacing,
        }
    }

    /// Rows from the bottom, their nodes' columns and y.
    fn rows(&self) -> Vec<Row> {
        let (nx, a) = (self.nx, self.spacing);
        let full = || (0..nx).collect::<Vec<_>>();
        (0..self.ny)
            .map(|iy| match self.kind {
                LatticeType::Honeycomb => Row { columns: full(), y: iy as f64 * 1.5 * a },
                LatticeType::Square => Row { columns: full(), y: iy as f64 * a },
                LatticeType::Kagome if iy % 2 == 1 => {
                    // Sparse nodes sit at half columns 2j + ½ (+1 every other sparse row), over
                    // the bond between full columns c and c + 1 with c = 2j (+1); column c here.
                    let offset = usize::from(iy % 4 == 3);
                    let last = if self.periodic_x { nx - 1 } else { nx - 2 };
                    Row { columns: (offset..=last).step_by(2).collect(), y: iy as f64 * a * 3.0_f64.sqrt() / 2.0 }
                }
                _ => Row { columns: full(), y: iy as f64 * a * 3.0_f64.sqrt() / 2.0 },
            })
            .collect()
    }

    /// Node positions and edges. Triangular: node (ix, iy) at ((ix + (iy mod 2)/2) a,
    /// iy a√3/2). Honeycomb: (ix a√3/2, 3a iy/2 + a/2 where ix + iy is even). Kagome: full
    /// rows at (ix a, iy a√3/2), sparse ones at ((c + ½) a, iy a√3/2). The side columns are
    /// the first and last node of every row (of every full row for kagome); L_x = (nx − 1)
    /// times the pitch, or the period; L_y = (ny − 1) times the row distance.
    pub fn layout(&self) -> Layout {
        let (a, pitch) = (self.spacing, self.pitch());
        let mut layout = Layout::default();
        let mut rows = Vec::new();
        for (iy, row) in self.rows().iter().enumerate() {
            let mut nodes = Vec::new();
            for &c in &row.columns {
                nodes.push(layout.x.len());
                let (x, y) = match self.kind {
                    LatticeType::Triangular => ((c as f64 + 0.5 * (iy % 2) as f64) * a, row.y),
                    LatticeType::Honeycomb => (c as f64 * pitch, row.y + if (c + iy) % 2 == 0 { 0.5 * a } else { 0.0 }),
                    LatticeType::Kagome if iy % 2 == 1 => ((c as f64 + 0.5) * a, row.y),
                    _ => (c as f64 * a, row.y),
                };
                layout.x.push(x);
                layout.y.push(y);
            }
            if self.kind != LatticeType::Kagome || iy % 2 == 0 {
                rows.push(nodes);
            } else {
                // Sparse kagome rows are neither side column nor edge row (ny is odd).
                rows.push(Vec::new());
            }
        }
        let full: Vec<Vec<usize>> = rows.into_iter().filter(|r| !r.is_empty()).collect();
        let width = if self.periodic_x { self.period() } else { (self.nx - 1) as f64 * pitch };
        let height = self.rows().last().map_or(0.0, |r| r.y);
        layout.edges = edges_of(&full, width, height);
        layout
    }

    /// Every spring, row by row: along the row, then up to the next row; bonds across a
    /// periodic side carry the shift ∓ period (x_i − x_j + shift is their separation).
    pub fn bonds(&self) -> Bonds {
        let grid = NodeGrid::of(self);
        let mut bonds = Bonds::default();
        for (iy, row) in grid.rows.iter().enumerate() {
            for (at, &column) in row.columns.iter().enumerate() {
                for (j, shift) in self.bonds_up_and_along(&grid, iy, column).into_iter().flatten() {
                    bonds.push_shifted(grid.starts[iy] + at, j, self.spacing, self.k, shift);
                }
            }
        }
        bonds
    }

    /// The nodes the node in `column` of row `iy` is bonded to further along its row or in the
    /// next, in the order the bond list keeps them (each with its shift, see [`NodeGrid::node`]);
    /// `None` where the lattice has no such node.
    fn bonds_up_and_along(&self, grid: &NodeGrid, iy: usize, column: usize) -> [Option<(usize, f64)>; 4] {
        let c = column as isize;
        let up = iy + 1 < grid.rows.len();
        // Row iy + 1 only where there is one.
        let above = |c: isize| if up { grid.node(iy + 1, c) } else { None };
        match self.kind {
            LatticeType::Triangular => {
                // Row iy + 1 is shifted by +a/2 (iy even) or −a/2 (iy odd).
                let other = if iy.is_multiple_of(2) { c - 1 } else { c + 1 };
                [grid.node(iy, c + 1), above(c), above(other), None]
            }
            LatticeType::Honeycomb => {
                let vertical = if (column + iy).is_multiple_of(2) { above(c) } else { None };
                [grid.node(iy, c + 1), vertical, None, None]
            }
            // A sparse node closes a triangle below and one above.
            LatticeType::Kagome if iy % 2 == 1 => {
                [grid.node(iy - 1, c), grid.node(iy - 1, c + 1), grid.node(iy + 1, c), grid.node(iy + 1, c + 1)]
            }
            LatticeType::Kagome => [grid.node(iy, c + 1), None, None, None],
            LatticeType::Square => [grid.node(iy, c + 1), above(c), None, None],
        }
    }
}

/// A lattice's rows with the index of each row's first node, to find the node at a column.
struct NodeGrid {
    /// Rows from the bottom ([`PlanarLattice::rows`]).
    rows: Vec<Row>,
    /// Index of the first node of each row.
    starts: Vec<usize>,
    /// Nodes per full row.
    count: isize,
    /// The period along x where bonds wrap across the sides, else `None`.
    period: Option<f64>,
}

impl NodeGrid {
    fn of(lattice: &PlanarLattice) -> NodeGrid {
        let rows = lattice.rows();
        let starts: Vec<usize> = rows
            .iter()
            .scan(0, |start, r| {
                let here = *start;
                *start += r.columns.len();
                Some(here)
            })
            .collect();
        NodeGrid { rows, starts, count: lattice.nx as isize, period: lattice.periodic_x.then(|| lattice.period()) }
    }

    /// Node of column `c` (possibly one period off) in row `iy`, and the shift of a bond to it.
    fn node(&self, iy: usize, c: isize) -> Option<(usize, f64)> {
        let (wrapped, shift) = match (c, self.period) {
            (c, _) if (0..self.count).contains(&c) => (c, 0.0),
            (_, None) => return None,
            (c, Some(period)) if c < 0 => (c + self.count, period),
            (c, Some(period)) => (c - self.count, -period),
        };
        let at = self.rows[iy].columns.binary_search(&(wrapped as usize)).ok()?;
        Some((self.starts[iy] + at, shift))
    }
}
