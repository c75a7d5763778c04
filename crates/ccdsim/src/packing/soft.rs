//! Soft spheres at rest: the harmonic overlap energy of a packing and its minimisation by FIRE.
//!
//! Two bodies whose centres are closer than their contact distance `σ = r_i + r_j` store the
//! energy `½ (1 − d/σ)²` (dimensionless, one unit of stiffness), a body closer to a wall than
//! its radius `½ (1 − c/r)²`. A packing of such bodies is *jammed* when its energy minimum is
//! above zero: overlaps cannot all be relaxed away (O'Hern, Silbert, Liu & Nagel, "Jamming
//! at zero temperature and zero applied stress", Phys. Rev. E 68, 011306, 2003). The minimum
//! is found by the Fast Inertial Relaxation Engine (Bitzek, Koskinen, Gähler, Moseler &
//! Gumbsch, Phys. Rev. Lett. 97, 170201, 2006): damped dynamics whose velocity is turned
//! towards the force while the power stays positive, and stopped when it turns negative.

use crate::contact::periodic::min_image;
use crate::geom::Vector;
use crate::packing::contacts::close_pairs;
use crate::wall::{wall_clearance_and_normal, Wall};

/// The outcome of [`minimize`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Minimum {
    /// Energy per body at the end.
    pub energy_per_body: f64,
    /// Mean relative overlap `1 − d/σ` of the overlapping pairs and wall contacts (0 when
    /// none overlap).
    pub mean_overlap: f64,
    /// Largest relative overlap.
    pub max_overlap: f64,
    /// FIRE steps taken.
    pub steps: u64,
    /// Whether the residual forces fell below the tolerance (or no overlap was left); `false`
    /// when the step limit came first.
    pub converged: bool,
    /// Relative overlaps at or below this are rounding (of coordinates, relative to a contact
    /// distance), not compression.
    pub rounding: f64,
}

impl Minimum {
    /// Jammed: overlaps beyond rounding remain at a minimum of the energy.
    pub fn jammed(&self) -> bool {
        self.energy_per_body > 0.0 && self.mean_overlap > self.rounding
    }
}

/// How [`minimize`] stops.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Tolerance {
    /// Converged when no body's net force exceeds this fraction of the mean contact force.
    /// (A root-mean-square criterion takes half the steps but lets minima on the way stop
    /// while they still slide towards unjamming.)
    pub relative_force: f64,
    /// Give up after this many steps.
    pub max_steps: u64,
}

/// Soft bodies with fixed radii in a periodic box or between walls, their positions free.
pub(crate) struct SoftPacking<'a, const D: usize> {
    /// Centres, moved by [`minimize`].
    pub positions: Vec<Vector<D>>,
    base: Vec<f64>,
    radii: Vec<f64>,
    walls: &'a [Wall<D>],
    periodic: Option<Vector<D>>,
    /// Pairs within `reach` when the list was built, with `1/σ`, that are close directly,
    /// and where the bodies were then.
    list: Vec<(u32, u32, f64)>,
    /// Pairs close through a periodic image, with `1/σ` and the image's shift (added to
    /// `x_j − x_i`; it stays right while no body moves half the skin). Kept apart so that the
    /// many direct pairs are small to stream through at every step.
    list_across: Vec<(u32, u32, f64, Vector<D>)>,
    listed_at: Vec<Vector<D>>,
    skin: f64,
}

impl<'a, const D: usize> SoftPacking<'a, D> {
    /// Bodies at `positions` with `radii`. A periodic box must be wider than twice the
    /// largest contact distance and the skin, so that a pair overlaps through one image only.
    pub fn new(
        positions: Vec<Vector<D>>,
        radii: Vec<f64>,
        walls: &'a [Wall<D>],
        periodic: Option<Vector<D>>,
    ) -> Self {
        let r_min = radii.iter().copied().fold(f64::INFINITY, f64::min);
        let mut soft = SoftPacking {
            positions,
            base: radii.clone(),
            radii,
            walls,
            periodic,
            list: Vec::new(),
            list_across: Vec::new(),
            listed_at: Vec::new(),
            // Wide enough that bodies of a packing near jamming seldom outrun it.
            skin: 0.1 * r_min,
        };
        soft.relist();
        soft
    }

    /// The radii.
    pub fn radii(&self) -> &[f64] {
        &self.radii
    }

    /// Every radius set to `scale` times its value at [`SoftPacking::new`] (the pair list
    /// widens with them).
    pub fn set_scale(&mut self, scale: f64) {
        for (r, b) in self.radii.iter_mut().zip(&self.base) {
            *r = b * scale;
        }
        self.relist();
    }

    fn relist(&mut self) {
        let r_max = self.radii.iter().copied().fold(0.0f64, f64::max);
        let reach = 2.0 * r_max + self.skin;
        self.list.clear();
        self.list_across.clear();
        if self.positions.len() >= 2 {
            let radii = &self.radii;
            let skin = self.skin;
            let positions = &self.positions;
            let pairs = close_pairs(positions, self.periodic, reach, |i, j, d| {
                d.norm() <= radii[i] + radii[j] + skin
            });
            for (i, j) in pairs {
                let raw = positions[j] - positions[i];
                let shift = match self.periodic {
                    Some(size) => min_image(raw, &size) - raw,
                    None => Vector::default(),
                };
                let inv_sigma = 1.0 / (radii[i] + radii[j]);
                if shift == Vector::default() {
                    self.list.push((i as u32, j as u32, inv_sigma));
                } else {
                    self.list_across
                        .push((i as u32, j as u32, inv_sigma, shift));
                }
            }
        }
        self.listed_at.clone_from(&self.positions);
    }

    /// Relists when some body has moved half the skin since the last list: until then every
    /// pair that can overlap is on it. `bound` is an upper bound of every body's displacement
    /// since the list (the sum of the largest step of each step): the bodies are only looked
    /// at once it passes half the skin, and it then becomes their largest displacement.
    fn relist_if_stale(&mut self, bound: &mut f64) {
        let half = 0.5 * self.skin;
        if *bound <= half {
            return;
        }
        let moved_sq = self
            .positions
            .iter()
            .zip(&self.listed_at)
            .map(|(p, q)| (*p - *q).norm_sq())
            .fold(0.0, f64::max);
        if moved_sq > half * half {
            self.relist();
            *bound = 0.0;
        } else {
            *bound = moved_sq.sqrt();
        }
    }

    /// The net force on every body into `forces`; returns the energy, the sum and largest of
    /// the relative overlaps, the number of overlapping contacts and the sum of their force
    /// magnitudes.
    fn forces(&self, forces: &mut [Vector<D>]) -> Overlaps {
        forces.fill(Vector::default());
        let mut o = Overlaps::default();
        let direct = self
            .list
            .iter()
            .map(|&(i, j, s)| (i, j, s, Vector::default()));
        for (i, j, inv_sigma, shift) in direct.chain(self.list_across.iter().copied()) {
            let (i, j) = (i as usize, j as usize);
            let d = self.positions[j] - self.positions[i] + shift;
            let dist_sq = d.norm_sq();
            if dist_sq * (inv_sigma * inv_sigma) >= 1.0 {
                continue;
            }
            let dist = dist_sq.sqrt();
            let overlap = 1.0 - dist * inv_sigma;
            let push = d * (overlap * inv_sigma / dist);
            forces[i] -= push;
            forces[j] += push;
            o.add(overlap, overlap * inv_sigma);
        }
        for (i, &p) in self.positions.iter().enumerate() {
            let r = self.radii[i];
            for wall in self.walls {
                let (clearance, normal) = wall_clearance_and_normal(wall, p);
                if clearance >= r {
                    continue;
                }
                let overlap = 1.0 - clearance / r;
                forces[i] += normal * (overlap / r);
                o.add(overlap, overlap / r);
            }
        }
        o
    }

    /// Minimises the energy from the current positions with FIRE, stopping at `tolerance`.
    pub fn minimize(&mut self, tolerance: &Tolerance) -> Minimum {
        const DELAY: u32 = 5;
        const GROW: f64 = 1.1;
        const SHRINK: f64 = 0.5;
        const ALPHA_START: f64 = 0.1;
        const ALPHA_DECAY: f64 = 0.99;
        let n = self.positions.len();
        let sigma_min = 2.0 * self.radii.iter().copied().fold(f64::INFINITY, f64::min);
        // Unit mass and stiffness 1/σ²: the fastest vibration has a period of a few σ.
        let dt_max = 0.5 * sigma_min;
        let dt_min = 1e-3 * sigma_min;
        let mut dt = 0.1 * sigma_min;
        let mut alpha = ALPHA_START;
        let mut positive = 0u32;
        let mut velocities = vec![Vector::<D>::default(); n];
        let mut forces = vec![Vector::<D>::default(); n];
        let mut steps = 0u64;
        // Forces below this are rounding: coordinates of magnitude `extent` carry errors of
        // `ε · extent`, each a force error of that over σ².
        let extent = match self.periodic {
            Some(size) => size.0.iter().copied().fold(0.0, f64::max),
            None => self
                .positions
                .iter()
                .flat_map(|p| p.0)
                .fold(0.0, |m: f64, x| m.max(x.abs())),
        };
        let floor = 64.0 * f64::EPSILON * extent / (sigma_min * sigma_min);
        // How far any body may have moved since the pair list was made.
        let mut moved = f64::INFINITY;
        loop {
            self.relist_if_stale(&mut moved);
            let o = self.forces(&mut forces);
            // One pass for every sum the step needs: the largest force (convergence), the
            // power `F·v`, and `|F|²` and `|v|²` (FIRE's mixing).
            let (mut max_force_sq, mut power, mut f_sq, mut v_sq) = (0.0f64, 0.0, 0.0, 0.0);
            for (f, v) in forces.iter().zip(&velocities) {
                let ff = f.norm_sq();
                max_force_sq = max_force_sq.max(ff);
                f_sq += ff;
                power += f.dot(*v);
                v_sq += v.norm_sq();
            }
            let mean_force = if o.count > 0 {
                o.force_sum / o.count as f64
            } else {
                0.0
            };
            let limit = (tolerance.relative_force * mean_force).max(floor);
            let done = o.count == 0 || max_force_sq <= limit * limit;
            if done || steps >= tolerance.max_steps {
                let per_body = if n > 0 { o.energy / n as f64 } else { 0.0 };
                return Minimum {
                    energy_per_body: per_body,
                    mean_overlap: if o.count > 0 {
                        o.overlap_sum / o.count as f64
                    } else {
                        0.0
                    },
                    max_overlap: o.overlap_max,
                    steps,
                    converged: done,
                    rounding: 1e3 * f64::EPSILON * extent / sigma_min,
                };
            }
            steps += 1;
            if power > 0.0 {
                positive += 1;
                if positive > DELAY {
                    dt = (dt * GROW).min(dt_max);
                    alpha *= ALPHA_DECAY;
                }
            } else {
                // Uphill: step back half a step, stop, and start again more carefully.
                positive = 0;
                for (p, v) in self.positions.iter_mut().zip(&velocities) {
                    *p -= *v * (0.5 * dt);
                }
                moved += 0.5 * dt * v_sq.sqrt();
                velocities.fill(Vector::default());
                (power, v_sq) = (0.0, 0.0);
                dt = (dt * SHRINK).max(dt_min);
                alpha = ALPHA_START;
            }
            // The kick `v + F dt` has the norm `|v|² + 2 dt F·v + dt² |F|²`; the velocity is
            // then turned towards the force (FIRE's mixing) and the bodies move, in one pass.
            let kicked_sq = (v_sq + dt * (2.0 * power + dt * f_sq)).max(0.0);
            let turn = if f_sq > 0.0 {
                alpha * (kicked_sq / f_sq).sqrt()
            } else {
                0.0
            };
            let keep = if f_sq > 0.0 { 1.0 - alpha } else { 1.0 };
            let mut step_sq = 0.0f64;
            for ((p, v), f) in self.positions.iter_mut().zip(&mut velocities).zip(&forces) {
                let kicked = *v + *f * dt;
                *v = kicked * keep + *f * turn;
                step_sq = step_sq.max(v.norm_sq());
                *p += *v * dt;
            }
            moved += dt * step_sq.sqrt();
        }
    }

    /// The current overlaps, without moving anything.
    pub fn overlaps(&self) -> (f64, f64) {
        let mut forces = vec![Vector::<D>::default(); self.positions.len()];
        let o = self.forces(&mut forces);
        (
            if o.count > 0 {
                o.overlap_sum / o.count as f64
            } else {
                0.0
            },
            o.overlap_max,
        )
    }
}

#[derive(Default)]
struct Overlaps {
    energy: f64,
    overlap_sum: f64,
    overlap_max: f64,
    force_sum: f64,
    count: usize,
}

impl Overlaps {
    fn add(&mut self, overlap: f64, force: f64) {
        self.energy += 0.5 * overlap * overlap;
        self.overlap_sum += overlap;
        self.overlap_max = self.overlap_max.max(overlap);
        self.force_sum += force;
        self.count += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TIGHT: Tolerance = Tolerance {
        relative_force: 1e-9,
        max_steps: 100_000,
    };

    #[test]
    fn two_overlapping_discs_in_open_space_move_apart() {
        let mut soft = SoftPacking::<2>::new(
            vec![Vector([0.0, 0.0]), Vector([1.5, 0.0])],
            vec![1.0, 1.0],
            &[],
            None,
        );
        let m = soft.minimize(&TIGHT);
        assert!(m.converged && !m.jammed(), "{m:?}");
        let d = (soft.positions[1] - soft.positions[0]).norm();
        assert!(d >= 2.0, "{d}");
    }

    #[test]
    fn a_square_lattice_squeezed_in_its_box_stays_jammed() {
        // Nine unit discs on a 3 × 3 lattice of spacing 1.95 in a periodic box: each overlaps
        // its four neighbours by 0.05 / 2 of a contact distance, and by symmetry the forces
        // are already balanced.
        let p: Vec<Vector<2>> = (0..9)
            .map(|k| Vector([1.95 * (k % 3) as f64, 1.95 * (k / 3) as f64]))
            .collect();
        let mut soft = SoftPacking::<2>::new(p, vec![1.0; 9], &[], Some(Vector([5.85; 2])));
        let m = soft.minimize(&TIGHT);
        assert!(m.jammed() && m.converged, "{m:?}");
        assert!((m.mean_overlap - 0.025).abs() < 1e-12, "{m:?}");
        assert_eq!(m.steps, 0);
    }

    #[test]
    fn a_disc_pressed_into_a_corner_is_pushed_out_of_both_walls() {
        let walls = [
            Wall::Segment {
                a: Vector([0.0, 0.0]),
                b: Vector([10.0, 0.0]),
            },
            Wall::Plane {
                point: Vector([0.0, 0.0]),
                normal: Vector([1.0, 0.0]),
            },
        ];
        let mut soft = SoftPacking::<2>::new(vec![Vector([0.5, 0.7])], vec![1.0], &walls, None);
        let m = soft.minimize(&TIGHT);
        assert!(m.converged && !m.jammed(), "{m:?}");
        let p = soft.positions[0];
        assert!(p[0] >= 1.0 && p[1] >= 1.0, "{p:?}");
    }
}
