//! One sampled instant of a run.

use crate::geom::Vector;
use crate::sim::Simulation;
use crate::wall::walls_bounds;

/// The simulation cell a frame lives in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cell<const D: usize> {
    /// A periodic box `[0, L)` per axis, metres.
    Periodic(Vector<D>),
    /// The box bounding the walls' points (`lo`, `hi`), metres; not periodic.
    Walls {
        /// Lowest corner.
        lo: Vector<D>,
        /// Highest corner.
        hi: Vector<D>,
    },
    /// No periodic box and no wall with a finite extent.
    Open,
}

impl<const D: usize> Cell<D> {
    /// Origin (lowest corner) and edge lengths of the cell, if it has any.
    #[must_use]
    pub fn origin_and_size(&self) -> Option<(Vector<D>, Vector<D>)> {
        match *self {
            Cell::Periodic(size) => Some((Vector([0.0; D]), size)),
            Cell::Walls { lo, hi } => Some((lo, hi - lo)),
            Cell::Open => None,
        }
    }
}

/// The bodies at one instant: what a trajectory file stores per frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame<const D: usize> {
    /// Simulated time, seconds.
    pub time: f64,
    /// The cell (periodic box, walls' bounding box, or none).
    pub cell: Cell<D>,
    /// Body ids (the scene's, stable across the run).
    pub ids: Vec<u64>,
    /// Positions, metres; inside `[0, L)` in a periodic box.
    pub positions: Vec<Vector<D>>,
    /// Periodic images: `positions[i] + images[i] · L` is body `i`'s unwrapped position (all
    /// zeros without a periodic box), plus `images[i][1] · strain` along x in a sheared box.
    pub images: Vec<[i64; D]>,
    /// In a sheared box (see [`crate::contact::lees_edwards`]), how far along x the layer
    /// above has slid since `t = 0`, `γ̇ L_y t`, metres: a body `k_y` layers up has slid
    /// `k_y` times that with it. 0 otherwise.
    pub strain: f64,
    /// Velocities, metres per second.
    pub velocities: Vec<Vector<D>>,
    /// Radii, metres.
    pub radii: Vec<f64>,
    /// Masses, kilograms.
    pub masses: Vec<f64>,
    /// Angular velocities, radians per second (about the third axis in 2D), when the run
    /// keeps spins (rough bodies, see [`crate::motion::spin`]); `None` otherwise.
    pub spins: Option<Vec<Vector<3>>>,
}

impl<const D: usize> Frame<D> {
    /// The state of `sim` at its current time: its bodies in slot order, vacant slots left
    /// out (after `remove_body` the frame has fewer bodies; `ids` tell them apart).
    #[must_use]
    pub fn of(sim: &Simulation<D>) -> Self {
        let world = sim.world();
        let slots: Vec<usize> = (0..world.len()).filter(|&i| !world.is_vacant(i)).collect();
        let each = |f: &dyn Fn(usize) -> Vector<D>| slots.iter().map(|&i| f(i)).collect();
        let cell = match world.periodic() {
            Some(size) => Cell::Periodic(size),
            None => match walls_bounds(world.walls()) {
                Some((lo, hi)) => Cell::Walls { lo, hi },
                None => Cell::Open,
            },
        };
        Frame {
            time: sim.time(),
            cell,
            ids: slots.iter().map(|&i| world.id(i)).collect(),
            positions: each(&|i| sim.position(i)),
            images: slots.iter().map(|&i| sim.image(i)).collect(),
            strain: world
                .shear()
                .map_or(0.0, |bx| bx.unwrapped_shift(1, sim.time())),
            // At the frame's time: under gravity the stored velocities hold only at each
            // body's reference time.
            velocities: each(&|i| world.velocity_at(i, sim.time())),
            radii: slots
                .iter()
                .map(|&i| world.radius_at(i, sim.time()))
                .collect(),
            masses: slots.iter().map(|&i| world.mass(i)).collect(),
            spins: world
                .is_rotational()
                .then(|| slots.iter().map(|&i| world.spin(i)).collect()),
        }
    }

    /// Number of bodies.
    #[must_use]
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// True for a frame without bodies.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Unwrapped positions (`position + image · L`, and in a sheared box the strain of the
    /// layers crossed, [`Frame::strain`]), metres: the paths the bodies travelled, for
    /// displacements over many box lengths.
    #[must_use]
    pub fn unwrapped_positions(&self) -> Vec<Vector<D>> {
        let Cell::Periodic(size) = self.cell else {
            return self.positions.clone();
        };
        self.positions
            .iter()
            .zip(&self.images)
            .map(|(p, k)| {
                let mut u = *p;
                for d in 0..D {
                    u[d] += k[d] as f64 * size[d];
                }
                if self.strain != 0.0 {
                    u[0] += k[1] as f64 * self.strain;
                }
                u
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::Gravity;
    use crate::scene::{BodySpec, Scene};

    #[test]
    fn frames_between_events_fall_and_grow() {
        // Two balls far apart in an open world: no event, so every frame is between events.
        let mut scene = Scene::<2> {
            bodies: vec![
                BodySpec::new(Vector([0.0, 0.0]), Vector([1.0, 2.0]), 0.5),
                BodySpec::new(Vector([10.0, 0.0]), Vector([0.0, 0.0]), 0.5),
            ],
            ..Scene::default()
        };
        scene.settings.gravity = Gravity::new(&[0.0, -4.0]);
        // With growing radii too: positions on the parabolas, radii grown (0.5·1.3 at 1.5 s).
        for (growth, radius) in [(None, 0.5), (Some(0.2), 0.65)] {
            scene.settings.growth = growth.map(|rate| crate::motion::Growth { rate });
            let mut sim = Simulation::new(&scene, "all-pairs").unwrap();
            assert!(sim.advance(1.5).is_empty());
            let f = Frame::of(&sim);
            assert_eq!(f.time, 1.5);
            // x = p + v·t + ½·g·t², v(t) = v + g·t.
            let want_p = [[1.5, 3.0 - 4.5], [10.0, -4.5]];
            let want_v = [[1.0, 2.0 - 6.0], [0.0, -6.0]];
            for i in 0..2 {
                for d in 0..2 {
                    assert!((f.positions[i][d] - want_p[i][d]).abs() < 1e-12, "{f:?}");
                    assert!((f.velocities[i][d] - want_v[i][d]).abs() < 1e-12, "{f:?}");
                }
                assert!((f.radii[i] - radius).abs() < 1e-15, "{f:?}");
            }
        }
    }
}
