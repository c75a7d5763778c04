//! The two engines behind one small interface: step one frame, read the state.

use crate::metrics::State;
use crate::scenes::Setup;
use crate::{CCDSIM_FINDER, DT, WALL_THICKNESS};
use ccdsim::Simulation;
use rapier2d::prelude::*;

/// An engine running one scene frame by frame.
pub trait Engine {
    /// Advances one frame of `DT` seconds.
    fn step(&mut self);
    /// Writes every body's position and velocity at the current frame end into `out`.
    fn state(&self, out: &mut State);
    /// Body masses, kilograms, as the engine simulates them.
    fn masses(&self) -> Vec<f64>;
    /// Anything worth a note about the run so far (collision counts, halts).
    fn notes(&self) -> String;
}

/// ccdsim, exact and event-driven: `Simulation::advance(DT)` per frame.
pub struct Ccdsim {
    sim: Simulation<2>,
    collisions: usize,
}

impl Ccdsim {
    /// The scene, as it is.
    pub fn new(setup: &Setup) -> Self {
        let sim = Simulation::new(&setup.scene, CCDSIM_FINDER).expect("ccdsim accepts the scene");
        Ccdsim { sim, collisions: 0 }
    }

    /// ccdsim's own kinetic plus potential energy now, to check the shared function.
    pub fn own_energy(&self) -> f64 {
        let t = self.sim.time();
        self.sim.world().kinetic_energy_at(t) + self.sim.world().potential_energy_at(t)
    }
}

impl Engine for Ccdsim {
    fn step(&mut self) {
        self.collisions += self.sim.advance(DT).len();
    }

    fn state(&self, out: &mut State) {
        let t = self.sim.time();
        let n = self.sim.world().len();
        out.pos.clear();
        out.vel.clear();
        for i in 0..n {
            let p = self.sim.position(i);
            let v = self.sim.world().velocity_at(i, t);
            out.pos.push([p[0], p[1]]);
            out.vel.push([v[0], v[1]]);
        }
    }

    fn masses(&self) -> Vec<f64> {
        self.sim.world().masses().collect()
    }

    fn notes(&self) -> String {
        let mut s = format!(
            "{} collisions; largest overlap at a contact {:.1e} of r_i + r_j",
            self.collisions,
            self.sim.stats().max_overlap
        );
        if let Some(halt) = self.sim.halt() {
            s.push_str(&format!("; HALTED: {halt}"));
        }
        s
    }
}

/// Which balls Rapier gives full CCD (`ccd_enabled(true)`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CcdOn {
    /// Every ball: the comparison's set-up.
    AllBalls,
    /// Only the scene's bullets. Rapier documents that a CCD body ("bullet") sweeps against
    /// every other body except other bullets, so with CCD on every ball no ball–ball pair is
    /// swept; this variant lets the bullets sweep against the slow balls.
    BulletsOnly,
}

/// Rapier: `PhysicsPipeline::step` per frame, default integration parameters but `dt`,
/// CCD on the balls, restitution 1 (combine rule `Max`), friction 0.
pub struct Rapier {
    gravity: Vector,
    params: IntegrationParameters,
    pipeline: PhysicsPipeline,
    islands: IslandManager,
    broad_phase: BroadPhaseBvh,
    narrow_phase: NarrowPhase,
    bodies: RigidBodySet,
    colliders: ColliderSet,
    impulse_joints: ImpulseJointSet,
    multibody_joints: MultibodyJointSet,
    soft_bodies: SoftBodySet,
    ccd: CCDSolver,
    balls: Vec<RigidBodyHandle>,
}

fn vec2(p: [f64; 2]) -> Vector {
    Vector::new(p[0] as Real, p[1] as Real)
}

/// Restitution 1, friction 0, for every collider of the comparison.
fn elastic(builder: ColliderBuilder) -> ColliderBuilder {
    builder
        .restitution(1.0)
        .restitution_combine_rule(CoefficientCombineRule::Max)
        .friction(0.0)
}

impl Rapier {
    /// The scene's balls as dynamic bodies with CCD, the box as four thick cuboids whose inner
    /// faces are the box's sides, the pegs as segment colliders.
    pub fn new(setup: &Setup, ccd_on: CcdOn) -> Self {
        let params = IntegrationParameters {
            dt: DT as Real,
            ..IntegrationParameters::default()
        };
        let mut bodies = RigidBodySet::new();
        let mut colliders = ColliderSet::new();
        let balls = setup
            .scene
            .bodies
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let ccd = ccd_on == CcdOn::AllBalls || i < setup.bullets;
                let handle = bodies.insert(
                    RigidBodyBuilder::dynamic()
                        .translation(vec2([b.pos[0], b.pos[1]]))
                        .linvel(vec2([b.vel[0], b.vel[1]]))
                        .ccd_enabled(ccd),
                );
                // Density 1: mass π r², ccdsim's unit-density mass.
                let ball = elastic(ColliderBuilder::ball(b.radius as Real)).density(1.0);
                colliders.insert_with_parent(ball, handle, &mut bodies);
                handle
            })
            .collect();
        let [w, h] = setup.box_size;
        let t = WALL_THICKNESS;
        let sides = [
            ([w / 2.0, -t / 2.0], [w / 2.0 + t, t / 2.0]),
            ([w / 2.0, h + t / 2.0], [w / 2.0 + t, t / 2.0]),
            ([-t / 2.0, h / 2.0], [t / 2.0, h / 2.0 + t]),
            ([w + t / 2.0, h / 2.0], [t / 2.0, h / 2.0 + t]),
        ];
        for (centre, half) in sides {
            let cuboid = ColliderBuilder::cuboid(half[0] as Real, half[1] as Real);
            colliders.insert(elastic(cuboid).translation(vec2(centre)));
        }
        for &(a, b) in &setup.pegs {
            colliders.insert(elastic(ColliderBuilder::segment(vec2(a), vec2(b))));
        }
        let g = setup.gravity();
        Rapier {
            gravity: vec2(g),
            params,
            pipeline: PhysicsPipeline::new(),
            islands: IslandManager::new(),
            broad_phase: BroadPhaseBvh::new(),
            narrow_phase: NarrowPhase::new(),
            bodies,
            colliders,
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            soft_bodies: SoftBodySet::new(),
            ccd: CCDSolver::new(),
            balls,
        }
    }
}

impl Engine for Rapier {
    fn step(&mut self) {
        self.pipeline.step(
            self.gravity,
            &self.params,
            &mut self.islands,
            &mut self.broad_phase,
            &mut self.narrow_phase,
            &mut self.bodies,
            &mut self.colliders,
            &mut self.impulse_joints,
            &mut self.multibody_joints,
            &mut self.soft_bodies,
            &mut self.ccd,
            &(),
            &(),
        );
    }

    fn state(&self, out: &mut State) {
        out.pos.clear();
        out.vel.clear();
        for &h in &self.balls {
            let b = &self.bodies[h];
            let (p, v) = (b.translation(), b.linvel());
            out.pos.push([f64::from(p.x), f64::from(p.y)]);
            out.vel.push([f64::from(v.x), f64::from(v.y)]);
        }
    }

    fn masses(&self) -> Vec<f64> {
        self.balls
            .iter()
            .map(|&h| f64::from(self.bodies[h].mass()))
            .collect()
    }

    fn notes(&self) -> String {
        let sleeping = self
            .balls
            .iter()
            .filter(|&&h| self.bodies[h].is_sleeping())
            .count();
        format!("{sleeping} balls asleep at the end")
    }
}
