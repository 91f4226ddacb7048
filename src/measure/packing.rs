//! A packing at rest, measured: its contacts' forces, the 2D virial pressure, rattlers and
//! coordination, and the affine parts of its moduli. Pure functions of the positions.

use crate::model::{Contacts, LawSpec};
use crate::sim::Packing;

/// The overlapping pairs of a packing with what the moduli need of each: length l = |r_ij| (m),
/// unit vector n̂ = r_ij/l, the spring's tension s(δ) (N, negative in compression) and tangent
/// ds/dδ (N/m) at its overlap δ = l − (r_i + r_j) < 0.
#[derive(Clone, Debug, Default)]
pub struct ContactForces {
    /// The pairs.
    pub pairs: Contacts,
    /// l (m).
    pub length: Vec<f64>,
    /// n̂ (x, y).
    pub normal: Vec<(f64, f64)>,
    /// s(δ) (N).
    pub tension: Vec<f64>,
    /// ds/dδ (N/m).
    pub tangent: Vec<f64>,
    /// e(δ) (J).
    pub energy: Vec<f64>,
}

impl ContactForces {
    /// The contacts of `packing` at positions `(x, y)` under `law`.
    pub fn of(packing: &Packing, law: LawSpec, x: &[f64], y: &[f64]) -> ContactForces {
        let pairs = packing.overlapping(x, y);
        let mut forces = ContactForces::default();
        for b in 0..pairs.len() {
            let (dx, dy) = pairs.separation(b, x, y);
            let length = (dx * dx + dy * dy).sqrt();
            let delta = length - pairs.rest[b];
            forces.length.push(length);
            forces.normal.push((dx / length, dy / length));
            forces.tension.push(law.elastic_force(packing.k, delta));
            forces.tangent.push(law.tangent_stiffness(packing.k, delta));
            forces.energy.push(law.energy(packing.k, delta));
        }
        forces.pairs = pairs;
        forces
    }

    /// The 2D virial pressure p = Σ f_c l_c / (2A) (N/m) over the contacts, f_c = −s(δ) the
    /// repulsion, in a box of area `area` (m²): p = −dU/dA.
    pub fn pressure(&self, area: f64) -> f64 {
        -self.tension.iter().zip(&self.length).map(|(s, l)| s * l).sum::<f64>() / (2.0 * area)
    }

    /// Σ e(δ) (J).
    pub fn total_energy(&self) -> f64 {
        self.energy.iter().sum()
    }

    /// Which of `discs` discs are rattlers: removed, repeatedly, while they have fewer than 3
    /// contacts with the discs not yet removed (d + 1 in 2D: fewer cannot hold a disc in
    /// balance under compressive forces).
    pub fn rattlers(&self, discs: usize) -> Vec<bool> {
        let mut neighbours = vec![Vec::new(); discs];
        for (&i, &j) in self.pairs.i.iter().zip(&self.pairs.j) {
            neighbours[i].push(j);
            neighbours[j].push(i);
        }
        let mut count: Vec<usize> = neighbours.iter().map(Vec::len).collect();
        let mut rattler: Vec<bool> = count.iter().map(|&c| c < 3).collect();
        // Each removal lowers its neighbours' counts once: linear in the contacts.
        let mut removed: Vec<usize> = (0..discs).filter(|&p| rattler[p]).collect();
        while let Some(p) = removed.pop() {
            for &q in &neighbours[p] {
                if !rattler[q] {
                    count[q] -= 1;
                    if count[q] < 3 {
                        rattler[q] = true;
                        removed.push(q);
                    }
                }
            }
        }
        rattler
    }

    /// The contacts between discs that are not `rattler`s (the backbone's).
    pub fn backbone(&self, rattler: &[bool]) -> Vec<usize> {
        (0..self.pairs.len()).filter(|&c| !rattler[self.pairs.i[c]] && !rattler[self.pairs.j[c]]).collect()
    }

    /// The affine part of d²U/dε² (J) under the homogeneous deformation r → (I + εE) r of the
    /// `contacts` (strain gradient E row-major, [Exx, Exy, Eyx, Eyy]), and the mixed
    /// derivatives Ξ = ∂²U/∂u∂ε (N, two per disc, x then y) that the non-affine relaxation
    /// takes off (d²U/dε² = affine − Ξᵀ H⁻¹ Ξ). Per contact, with e = E n̂:
    /// dl/dε = l n̂·e, d²l/dε² = l (|e|² − (n̂·e)²), so the affine part is
    /// Σ k_t (dl/dε)² + s d²l/dε² (the second term the pre-stress), and Ξ_i = −Ξ_j =
    /// k_t (dl/dε) n̂ + s (e − (n̂·e) n̂).
    pub fn affine(&self, contacts: &[usize], strain: [f64; 4], discs: usize) -> (f64, Vec<f64>) {
        let mut second = 0.0;
        let mut mixed = vec![0.0; 2 * discs];
        for &c in contacts {
            let (nx, ny) = self.normal[c];
            let (ex, ey) = (strain[0] * nx + strain[1] * ny, strain[2] * nx + strain[3] * ny);
            let along = nx * ex + ny * ey;
            let (l, s, k_t) = (self.length[c], self.tension[c], self.tangent[c]);
            let stretch = l * along;
            second += k_t * stretch * stretch + s * l * (ex * ex + ey * ey - along * along);
            let (xi_x, xi_y) = (k_t * stretch * nx + s * (ex - along * nx), k_t * stretch * ny + s * (ey - along * ny));
            let (i, j) = (self.pairs.i[c], self.pairs.j[c]);
            mixed[2 * i] += xi_x;
            mixed[2 * i + 1] += xi_y;
            mixed[2 * j] -= xi_x;
            mixed[2 * j + 1] -= xi_y;
        }
        (second, mixed)
    }
}

/// A contact as a movie draws it: from disc i to the image of disc j it touches (m), and its
/// repulsion |s(δ)| (N).
pub type ContactLine = ((f64, f64), (f64, f64), f64);

/// A frame of a packing as a movie draws it: every disc wrapped into the box [0, L)², each
/// contact as a segment from disc i to the image of disc j it touches, with its repulsion
/// |s(δ)| (N), and each disc's load Σ|s| over its contacts (N).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DiscFrame {
    /// The box side L (m): a compressed packing's frames each have their own.
    pub side: f64,
    /// x of each disc in the box (m).
    pub x: Vec<f64>,
    /// y of each disc in the box (m).
    pub y: Vec<f64>,
    /// Contacts: the segment's ends (x_i, y_i), (x_i − dx, y_i − dy) (m) and its force (N).
    pub contacts: Vec<ContactLine>,
    /// Σ|s| over each disc's contacts (N).
    pub load: Vec<f64>,
}

impl DiscFrame {
    /// The frame of `packing` at positions `(x, y)` under `law`.
    pub fn of(packing: &Packing, law: LawSpec, x: &[f64], y: &[f64]) -> DiscFrame {
        let forces = ContactForces::of(packing, law, x, y);
        let (inside_x, inside_y) = x.iter().zip(y).map(|(&x, &y)| packing.periodic.inside(x, y)).unzip();
        let mut frame = DiscFrame {
            side: packing.periodic.side,
            x: inside_x,
            y: inside_y,
            contacts: Vec::with_capacity(forces.pairs.len()),
            load: vec![0.0; x.len()],
        };
        for b in 0..forces.pairs.len() {
            let (i, j) = (forces.pairs.i[b], forces.pairs.j[b]);
            let (dx, dy) = forces.pairs.separation(b, x, y);
            let force = forces.tension[b].abs();
            let from = (frame.x[i], frame.y[i]);
            frame.contacts.push((from, (from.0 - dx, from.1 - dy), force));
            frame.load[i] += force;
            frame.load[j] += force;
        }
        frame
    }
}

/// A packing's movie frames as discs: their radii (m) and each frame in its box.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Discs {
    /// Radius of each disc (m).
    pub radius: Vec<f64>,
    /// The frames, as the movie's.
    pub frames: Vec<DiscFrame>,
}
