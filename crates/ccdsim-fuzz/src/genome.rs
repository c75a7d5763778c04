//! Adversarial fuzz cases, drawn with proptest so that a failing case shrinks.
//!
//! proptest draws a [`Genome`], plain small numbers, and [`Genome::build`] turns it into a
//! [`Case`] deterministically. Shrinking works on the genome (fewer bodies, walls and edits,
//! simpler choices: choice 0 is always the plainest), so a failing case shrinks to a small
//! scene that still fails.
//!
//! The distributions are meant to hit what random floats never do:
//! * coordinates on a lattice of integers, halves, quarters or `L/m` (a box side over a small
//!   integer, which is where the `cells` grid puts its faces: `lo + k·L/dims`), lattice
//!   points, and now and then a float off the lattice;
//! * bodies exactly touching each other (placed at `r_i + r_j` along an axis) or a wall
//!   (clamped to `r` from it), mirror images of another body (symmetric starts, simultaneous
//!   events), zero and axis-aligned velocities, equal speeds;
//! * every feature the scene format has and their combinations: gravity (along an axis or
//!   oblique), restitution, the TC model, resting contacts, growth, a thermostat, periodic
//!   boxes, sheared periodic boxes (Lees–Edwards), segment and plane walls, walls cut into collinear pieces, shelves and slopes (so
//!   bodies rest, slide and roll over segment ends), 3D rods, sensors, moving walls,
//!   kinematic bodies, per-body restitution, mass and collision groups, arrivals (bodies
//!   entering at lattice points, several at one instant, some onto bodies); and edits between
//!   steps (velocities, teleports, bodies added and removed, filters, wall velocities, every
//!   velocity rescaled at once), driven
//!   event by event or frame by frame as a game loop does.

use crate::case::{Case, EditOp, Schedule};
use ccdsim::generate::box_walls;
use ccdsim::{Arrival, BodySpec, MovingWall, Scene, Sensor, Settings, Vector, Wall};
use proptest::prelude::*;

/// Velocity components, m/s: zero first (the plainest), then small dyadic values of both signs.
const SPEEDS: [f64; 12] = [
    0.0, 1.0, -1.0, 0.5, -0.5, 2.0, -2.0, 0.25, -0.25, 3.0, -3.0, 1.5,
];
/// Radii, in units of the lattice step.
const RADII: [f64; 6] = [0.5, 0.25, 0.125, 0.375, 0.75, 1.0];
/// Collision filters: group, mask.
const FILTERS: [(u32, u32); 4] = [(2, !1), (4, !2), (0, 0), (8, 8)];

/// One body's choices.
#[derive(Clone, Debug)]
pub struct BodyGene {
    /// Lattice indices of the position.
    pub pos: [u16; 3],
    /// Indices into [`SPEEDS`].
    pub vel: [u8; 3],
    /// Index into [`RADII`].
    pub radius: u8,
    /// 0–3: on the lattice; 4: touching the previous body; 5: the mirror image of the previous
    /// body; 6: a float off the lattice; 7: at rest.
    pub placement: u8,
    /// Velocity along one axis only (the axis `vel[2] % D`).
    pub axis_aligned: bool,
    /// 0–7: plain; 8: kinematic; 9: own restitution; 10: a collision filter; 11: heavy;
    /// 12: spinning; 13: its own inertia factor and tangential restitution (rough).
    pub extra: u8,
}

/// One edit's choices.
#[derive(Clone, Debug)]
pub struct EditGene {
    kind: u8,
    body: u8,
    vel: [u8; 3],
    pos: [u16; 3],
    radius: u8,
    filter: u8,
}

/// The raw choices a case is built from.
#[derive(Clone, Debug)]
pub struct Genome {
    dim3: bool,
    /// 0: 1 m; 1: 1/2; 2: 1/4; 3: side/m for m in 2..=9.
    unit: u8,
    /// Box sides, in whole metres beyond 3.
    sides: [u8; 3],
    /// 0: segments (2D) or planes (3D); 1: planes; 2: periodic; 3: sides cut into collinear
    /// pieces; 4: no walls at all (an open world); 5: periodic and sheared (Lees–Edwards).
    boundary: u8,
    /// 0: none; 1: −9.81 along the last axis; 2: −1; 3: oblique; 4: along the first axis;
    /// 5: −4 along the last axis.
    gravity: u8,
    restitution: u8,
    tc: u8,
    rest_speed: u8,
    growth: u8,
    thermostat: u8,
    start: u8,
    /// 0: smooth; 1–3: rough bodies, tangential restitution 0.5, 1 or −0.5 (not with
    /// resting contacts).
    rough: u8,
    bodies: Vec<BodyGene>,
    /// Interior walls: end points on the lattice.
    walls: Vec<([u16; 3], [u16; 3])>,
    sensors: Vec<([u16; 3], u8)>,
    moving_walls: Vec<u8>,
    /// Arrivals: lattice point, velocity choices, time slot (quarter seconds after the start,
    /// so several share one instant).
    arrivals: Vec<([u16; 3], [u8; 3], u8)>,
    schedule: u8,
    every: u8,
    edits: Vec<EditGene>,
    max_events: u16,
    duration: u8,
}

fn body_gene() -> impl Strategy<Value = BodyGene> {
    (
        any::<[u16; 3]>(),
        [0u8..12, 0u8..12, 0u8..12],
        0u8..6,
        0u8..8,
        any::<bool>(),
        0u8..14,
    )
        .prop_map(
            |(pos, vel, radius, placement, axis_aligned, extra)| BodyGene {
                pos,
                vel,
                radius,
                placement,
                axis_aligned,
                extra,
            },
        )
}

fn edit_gene() -> impl Strategy<Value = EditGene> {
    (
        0u8..7,
        any::<u8>(),
        [0u8..12, 0u8..12, 0u8..12],
        any::<[u16; 3]>(),
        0u8..6,
        0u8..4,
    )
        .prop_map(|(kind, body, vel, pos, radius, filter)| EditGene {
            kind,
            body,
            vel,
            pos,
            radius,
            filter,
        })
}

/// The strategy of genomes: up to `max_bodies` bodies.
pub fn genome(max_bodies: usize) -> impl Strategy<Value = Genome> {
    let world = (
        any::<bool>(),
        0u8..4,
        [0u8..10, 0u8..10, 0u8..10],
        0u8..6,
        prop_oneof![3 => Just(0u8), 5 => 1u8..6],
        prop_oneof![3 => Just(0u8), 1 => 1u8..4],
        0u8..3,
        0u8..3,
        prop_oneof![4 => Just(0u8), 1 => 1u8..3],
        prop_oneof![6 => Just(0u8), 1 => Just(1u8)],
        0u8..4,
        prop_oneof![2 => Just(0u8), 1 => 1u8..4],
    );
    let contents = (
        prop::collection::vec(body_gene(), 0..=max_bodies),
        prop::collection::vec((any::<[u16; 3]>(), any::<[u16; 3]>()), 0..4),
        prop::collection::vec((any::<[u16; 3]>(), 0u8..4), 0..3),
        // Moving walls exclude growth: most cases go without, so growth is drawn often.
        prop_oneof![3 => Just(Vec::new()), 1 => prop::collection::vec(0u8..4, 1..3)],
        prop_oneof![
            3 => Just(Vec::new()),
            1 => prop::collection::vec(
                (any::<[u16; 3]>(), [0u8..12, 0u8..12, 0u8..12], 0u8..6),
                1..6
            )
        ],
        0u8..4,
        1u8..8,
        prop::collection::vec(edit_gene(), 0..8),
        30u16..400,
        0u8..4,
    );
    (world, contents).prop_map(
        |(
            (
                dim3,
                unit,
                sides,
                boundary,
                gravity,
                restitution,
                tc,
                rest_speed,
                growth,
                thermostat,
                start,
                rough,
            ),
            (
                bodies,
                walls,
                sensors,
                moving_walls,
                arrivals,
                schedule,
                every,
                edits,
                max_events,
                duration,
            ),
        )| Genome {
            dim3,
            unit,
            sides,
            boundary,
            gravity,
            restitution,
            tc,
            rest_speed,
            growth,
            thermostat,
            start,
            rough,
            bodies,
            walls,
            sensors,
            moving_walls,
            arrivals,
            schedule,
            every,
            edits,
            max_events,
            duration,
        },
    )
}

/// The strategy of cases: genomes of up to `max_bodies` bodies, built.
pub fn case(max_bodies: usize) -> impl Strategy<Value = Case> {
    genome(max_bodies).prop_map(|g| g.build())
}

impl Genome {
    /// The case these choices describe.
    #[must_use]
    pub fn build(&self) -> Case {
        if self.dim3 {
            Builder::<3>::new(self).build()
        } else {
            Builder::<2>::new(self).build()
        }
    }
}

/// Turns a genome into a scene of dimension `D`.
struct Builder<'a, const D: usize> {
    g: &'a Genome,
    /// Box sides, m.
    side: Vector<D>,
    /// Lattice step per axis, m.
    step: Vector<D>,
    periodic: bool,
    walled: bool,
}

impl<'a, const D: usize> Builder<'a, D> {
    fn new(g: &'a Genome) -> Self {
        let side = Vector::<D>(std::array::from_fn(|d| 3.0 + f64::from(g.sides[d] % 10)));
        let divisor = 2.0 + f64::from(g.sides[2] % 8);
        let step = Vector::<D>(std::array::from_fn(|d| match g.unit {
            0 => 1.0,
            1 => 0.5,
            2 => 0.25,
            _ => side[d] / divisor,
        }));
        let periodic = g.boundary == 2 || g.boundary == 5;
        Builder {
            g,
            side,
            step,
            periodic,
            walled: !periodic && g.boundary != 4,
        }
    }

    /// The lattice point with indices `k`, folded into the box.
    fn lattice(&self, k: &[u16; 3]) -> Vector<D> {
        Vector(std::array::from_fn(|d| {
            let n = (self.side[d] / self.step[d]).round().max(1.0) as u16;
            f64::from(k[d] % (n + 1)) * self.step[d]
        }))
    }

    fn velocity(&self, choice: &[u8; 3], axis_aligned: bool) -> Vector<D> {
        let mut v = Vector(std::array::from_fn(|d| SPEEDS[choice[d] as usize % 12]));
        if axis_aligned {
            let keep = choice[2] as usize % D;
            for d in 0..D {
                if d != keep {
                    v[d] = 0.0;
                }
            }
        }
        v
    }

    fn settings(&self) -> Settings {
        let g = self.g;
        let mut s = Settings {
            restitution: [1.0, 0.5, 0.9, 0.0][g.restitution as usize % 4],
            ..Settings::default()
        };
        if self.walled || g.boundary == 4 {
            let mut acc = [0.0; 3];
            match g.gravity {
                1 => acc[D - 1] = -9.81,
                2 => acc[D - 1] = -1.0,
                3 => {
                    acc[0] = 1.0;
                    acc[D - 1] = -2.0;
                }
                4 => acc[0] = -9.81,
                5 => acc[D - 1] = -4.0,
                _ => {}
            }
            if g.gravity != 0 {
                s.gravity = ccdsim::Gravity::new(&acc[..D]);
                s.rest_speed = [None, Some(0.1), Some(1.0)][g.rest_speed as usize % 3];
            }
        }
        s.tc = [None, Some(1e-3), Some(0.05)][g.tc as usize % 3];
        if s.rest_speed.is_none() {
            s.tangential_restitution =
                [None, Some(0.5), Some(1.0), Some(-0.5)][g.rough as usize % 4];
        }
        if g.growth != 0 && g.moving_walls.is_empty() {
            s.growth = Some(ccdsim::Growth {
                rate: [0.0, 0.05, 0.5][g.growth as usize % 3],
            });
        }
        if g.boundary == 5 && s.growth.is_none() {
            s.shear_rate = Some([0.5, -2.0, 0.25][g.sides[1] as usize % 3]);
        }
        if g.thermostat != 0 && self.periodic {
            s.thermostat = Some(ccdsim::thermostat::Thermostat {
                temperature: 1.0,
                rate: 0.5,
                seed: u64::from(g.sides[0]),
            });
        }
        s
    }

    fn boundary(&self) -> Vec<Wall<D>> {
        match self.g.boundary {
            0 if D == 2 => box_walls(self.side),
            0 | 1 => plane_box(self.side),
            3 => cut_box(self.side, 1 + usize::from(self.g.sides[1] % 3)),
            _ => Vec::new(),
        }
    }

    fn build(&self) -> Case {
        let g = self.g;
        let mut scene = Scene::<D> {
            settings: self.settings(),
            start_time: [0.0, 1.0, 0.5, -2.0][g.start as usize % 4],
            walls: self.boundary(),
            periodic: self.periodic.then_some(self.side),
            ..Scene::default()
        };
        // Interior walls: shelves, slopes and (3D) rods between lattice points; walls the
        // validator refuses (degenerate) are dropped.
        if !self.periodic {
            for (a, b) in &g.walls {
                scene.walls.push(Wall::Segment {
                    a: self.lattice(a),
                    b: self.lattice(b),
                });
                if scene.validate().is_err() {
                    scene.walls.pop();
                }
            }
            if self.walled && scene.settings.growth.is_none() {
                for &m in &g.moving_walls {
                    scene.moving_walls.push(self.moving_wall(m));
                    if scene.validate().is_err() {
                        scene.moving_walls.pop();
                    }
                }
            }
        }
        let mut placed: Vec<BodySpec<D>> = Vec::new();
        for (k, b) in g.bodies.iter().enumerate() {
            let Some(spec) = self.body(b, k, &placed) else {
                continue;
            };
            scene.bodies.push(spec.clone());
            if scene.validate().is_err() {
                scene.bodies.pop();
            } else {
                placed.push(spec);
            }
        }
        let r_max = scene.bodies.iter().fold(0.25f64, |m, b| m.max(b.radius));
        for (c, r) in &g.sensors {
            scene.sensors.push(Sensor {
                center: self.lattice(c),
                radius: r_max * f64::from(1 + r % 4) * 0.5,
            });
            if scene.validate().is_err() {
                scene.sensors.pop();
            }
        }
        // Arrivals at lattice points, as large as the smallest body; those the validator
        // refuses (crossing a wall, outside the box) are dropped, those landing on a body are
        // kept (the run stops there, alike for every finder).
        let r_min = scene.bodies.iter().fold(r_max, |m, b| m.min(b.radius));
        for (pos, vel, slot) in &g.arrivals {
            scene.arrivals.push(Arrival {
                time: scene.start_time + 0.25 * f64::from(*slot),
                body: BodySpec::new(self.lattice(pos), self.velocity(vel, false), r_min),
            });
            if scene.validate().is_err() {
                scene.arrivals.pop();
            }
        }
        let schedule = match g.schedule {
            0 | 1 => Schedule::Events {
                every: u32::from(g.every),
            },
            s => Schedule::Frames {
                dt: [0.25, 0.1][s as usize % 2],
            },
        };
        let edits = g.edits.iter().map(|e| self.edit(e)).collect();
        Case::new(
            &scene,
            schedule,
            edits,
            u64::from(g.max_events),
            [2.0, 5.0, 1.0, 10.0][g.duration as usize % 4],
        )
    }

    /// Body `k` of the genome, placed as its gene says; `None` when it cannot be placed.
    fn body(&self, b: &BodyGene, k: usize, placed: &[BodySpec<D>]) -> Option<BodySpec<D>> {
        let unit = self.step.0.iter().fold(f64::INFINITY, |m, &s| m.min(s));
        let radius = RADII[b.radius as usize % RADII.len()] * unit.min(1.0);
        let mut pos = self.lattice(&b.pos);
        let mut vel = self.velocity(&b.vel, b.axis_aligned);
        match (b.placement, placed.last()) {
            (4, Some(prev)) => {
                // Exactly touching the previous body along an axis.
                let axis = b.vel[1] as usize % D;
                pos = prev.pos;
                pos[axis] += prev.radius + radius;
            }
            (5, Some(prev)) => {
                // The previous body's mirror image across the box's middle, moving mirrored.
                pos = prev.pos;
                pos[0] = self.side[0] - pos[0];
                vel = prev.vel;
                vel[0] = -vel[0];
            }
            (6, _) => {
                // Off the lattice: a float that no face holds.
                for d in 0..D {
                    pos[d] += self.step[d] * (0.1 + 0.037 * (k + d) as f64);
                }
            }
            (7, _) => vel = Vector::ZERO,
            _ => {}
        }
        if self.periodic {
            for d in 0..D {
                pos[d] = pos[d].rem_euclid(self.side[d]);
            }
        } else if self.walled {
            // Clamped into the box: a body pushed to a side touches it exactly.
            for d in 0..D {
                pos[d] = pos[d].clamp(radius, self.side[d] - radius);
            }
        }
        let mut spec = BodySpec::new(pos, vel, radius);
        match b.extra {
            8 => spec.kinematic = true,
            9 => spec.restitution = Some(0.5),
            10 => {
                let (group, mask) = FILTERS[b.vel[0] as usize % FILTERS.len()];
                (spec.group, spec.mask) = (Some(group), Some(mask));
            }
            11 => spec.mass = Some(8.0),
            // Rough bodies do not rest on walls.
            12 if self.settings().rest_speed.is_none() => {
                let w = std::array::from_fn(|d| SPEEDS[b.vel[(d + 1) % 3] as usize % 12]);
                spec.spin = Some(ccdsim::Spin::of::<D>(Vector(w)));
            }
            13 if self.settings().rest_speed.is_none() => {
                spec.inertia = Some(0.25);
                spec.tangential_restitution = Some(0.0);
            }
            _ => {}
        }
        Some(spec)
    }

    fn moving_wall(&self, m: u8) -> MovingWall<D> {
        let h = self.side[D - 1] * [0.75, 0.5, 0.25, 1.0][m as usize % 4];
        let speed = [0.5, -0.5, 1.0, 0.0][m as usize % 4];
        if D == 2 {
            // A paddle: a horizontal segment across part of the box, moving up or down.
            let mut a = Vector::<D>::ZERO;
            let mut b = Vector::<D>::ZERO;
            a[0] = self.side[0] * 0.25;
            b[0] = self.side[0] * 0.75;
            a[1] = h;
            b[1] = h;
            let mut velocity = Vector::<D>::ZERO;
            velocity[if m % 2 == 0 { 1 } else { 0 }] = speed;
            MovingWall {
                wall: Wall::Segment { a, b },
                velocity,
            }
        } else {
            // A piston: a plane facing down from the top, moving along the last axis.
            let mut point = Vector::<D>::ZERO;
            point[D - 1] = self.side[D - 1];
            let mut normal = Vector::<D>::ZERO;
            normal[D - 1] = -1.0;
            let mut velocity = Vector::<D>::ZERO;
            velocity[D - 1] = -speed.abs();
            MovingWall {
                wall: Wall::Plane { point, normal },
                velocity,
            }
        }
    }

    fn edit(&self, e: &EditGene) -> EditOp {
        let body = usize::from(e.body);
        match e.kind {
            0 => EditOp::Velocity {
                body,
                vel: self.velocity(&e.vel, e.filter % 2 == 0).0.to_vec(),
            },
            1 => EditOp::Position {
                body,
                pos: self.lattice(&e.pos).0.to_vec(),
            },
            2 => EditOp::Add {
                pos: self.lattice(&e.pos).0.to_vec(),
                vel: self.velocity(&e.vel, false).0.to_vec(),
                radius: RADII[e.radius as usize % RADII.len()]
                    * self.step.0.iter().fold(1.0f64, |m, &s| m.min(s)),
                kinematic: e.filter == 3,
            },
            3 => EditOp::Remove { body },
            4 => {
                let (group, mask) = FILTERS[e.filter as usize % FILTERS.len()];
                EditOp::Filter { body, group, mask }
            }
            // Halving, doubling, stopping everything, and a factor with no short binary form.
            6 => EditOp::Rescale {
                factor: [0.5, 2.0, 0.0, 1.0 / 3.0][e.filter as usize % 4],
            },
            _ => EditOp::WallVelocity {
                wall: body,
                vel: self.velocity(&e.vel, true).0.to_vec(),
            },
        }
    }
}

/// The box `[0, side]` bounded by one-sided planes facing in.
fn plane_box<const D: usize>(side: Vector<D>) -> Vec<Wall<D>> {
    let mut walls = Vec::new();
    for d in 0..D {
        for (at, sign) in [(0.0, 1.0), (side[d], -1.0)] {
            let mut point = Vector::<D>::ZERO;
            point[d] = at;
            let mut normal = Vector::<D>::ZERO;
            normal[d] = sign;
            walls.push(Wall::Plane { point, normal });
        }
    }
    walls
}

/// A 2D box of segments, each side cut into `pieces` collinear segments (3D: planes).
fn cut_box<const D: usize>(side: Vector<D>, pieces: usize) -> Vec<Wall<D>> {
    if D != 2 {
        return plane_box(side);
    }
    let corners = [
        [0.0, 0.0],
        [side[0], 0.0],
        [side[0], side[1]],
        [0.0, side[1]],
    ];
    let mut walls = Vec::new();
    for c in 0..4 {
        let (p, q) = (corners[c], corners[(c + 1) % 4]);
        for k in 0..pieces {
            let at = |s: f64| {
                let mut v = Vector::<D>::ZERO;
                v[0] = p[0] + (q[0] - p[0]) * s;
                v[1] = p[1] + (q[1] - p[1]) * s;
                v
            };
            walls.push(Wall::Segment {
                a: at(k as f64 / pieces as f64),
                b: at((k + 1) as f64 / pieces as f64),
            });
        }
    }
    walls
}
