//! The three scenes, built once as ccdsim scenes; the Rapier world is built from the same
//! bodies and walls.

use crate::{
    BALL_RADIUS, BOX_SIZE, BULLETS, BULLET_SPEED, GRAVITY, MAX_SPEED, N_BALLS, PLACEMENT_GAP, SEED,
};
use ccdsim::generate::{box_walls, pegs, PegsConfig};
use ccdsim::gravity::Gravity;
use ccdsim::{BodySpec, Scene, Vector, Wall};

/// A scene and the geometry the metrics need.
pub struct Setup {
    /// Short name for the table.
    pub name: &'static str,
    /// One line on what it is.
    pub description: String,
    /// The scene, as ccdsim runs it (Rapier is built from its bodies and walls).
    pub scene: Scene<2>,
    /// The walled box `[0, w] × [0, h]`.
    pub box_size: [f64; 2],
    /// The first `bullets` bodies are the scene's bullets.
    pub bullets: usize,
    /// Walls inside the box (the pegs), as segments.
    pub pegs: Vec<([f64; 2], [f64; 2])>,
}

impl Setup {
    /// Gravity vector of the scene.
    pub fn gravity(&self) -> [f64; 2] {
        let g = self.scene.gravity().unwrap_or(Vector([0.0, 0.0]));
        [g[0], g[1]]
    }

    /// Body radii.
    pub fn radii(&self) -> Vec<f64> {
        self.scene.bodies.iter().map(|b| b.radius).collect()
    }
}

/// splitmix64: a small, fixed, dependency-free generator (same scene on every platform).
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Rounds to the nearest `f32`, so that both engines start from exactly the same numbers
/// (Rapier's `rapier2d` works in `f32`).
fn f32_exact(x: f64) -> f64 {
    f64::from(x as f32)
}

/// `N_BALLS` balls at random non-overlapping positions in the box, speeds uniform in
/// `[0, MAX_SPEED]` in uniform directions; the first `bullets` of them at `BULLET_SPEED`.
fn gas_scene(name: &'static str, bullets: usize) -> Setup {
    let mut rng = Rng(SEED);
    let r = BALL_RADIUS;
    let mut pos: Vec<[f64; 2]> = Vec::with_capacity(N_BALLS);
    while pos.len() < N_BALLS {
        let p = [
            f32_exact(rng.uniform(r + PLACEMENT_GAP, BOX_SIZE - r - PLACEMENT_GAP)),
            f32_exact(rng.uniform(r + PLACEMENT_GAP, BOX_SIZE - r - PLACEMENT_GAP)),
        ];
        let clear = pos.iter().all(|q| {
            let (dx, dy) = (p[0] - q[0], p[1] - q[1]);
            (dx * dx + dy * dy).sqrt() > 2.0 * r + PLACEMENT_GAP
        });
        if clear {
            pos.push(p);
        }
    }
    let bodies = pos
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let speed = if i < bullets {
                BULLET_SPEED
            } else {
                rng.uniform(0.0, MAX_SPEED)
            };
            let angle = rng.uniform(0.0, std::f64::consts::TAU);
            let v = [
                f32_exact(speed * angle.cos()),
                f32_exact(speed * angle.sin()),
            ];
            BodySpec::new(Vector(*p), Vector(v), r)
        })
        .collect();
    let mut scene = Scene {
        bodies,
        walls: box_walls(Vector([BOX_SIZE, BOX_SIZE])),
        ..Scene::default()
    };
    scene.settings.restitution = 1.0;
    scene.settings.gravity = Gravity::new(&[0.0, -GRAVITY]);
    scene.validate().expect("the generated gas scene is valid");
    let description = if bullets == 0 {
        format!(
            "{N_BALLS} balls r = {r} m in a {BOX_SIZE} m × {BOX_SIZE} m box, speeds ≤ {MAX_SPEED} m/s"
        )
    } else {
        format!("as (a), but {bullets} of the balls are bullets at {BULLET_SPEED} m/s")
    };
    Setup {
        name,
        description,
        scene,
        box_size: [BOX_SIZE, BOX_SIZE],
        bullets,
        pegs: Vec::new(),
    }
}

/// ccdsim's peg board (`pegs(&PegsConfig::default())`), initial state rounded to `f32`.
fn peg_scene() -> Setup {
    let mut scene = pegs(&PegsConfig::default()).expect("the default peg board");
    for b in &mut scene.bodies {
        b.pos = Vector([f32_exact(b.pos[0]), f32_exact(b.pos[1])]);
        b.vel = Vector([f32_exact(b.vel[0]), f32_exact(b.vel[1])]);
    }
    scene.validate().expect("the rounded peg board is valid");
    let segments: Vec<([f64; 2], [f64; 2])> = scene
        .walls
        .iter()
        .map(|w| match w {
            Wall::Segment { a, b } => ([a[0], a[1]], [b[0], b[1]]),
            Wall::Plane { .. } => unreachable!("a 2D scene has segment walls"),
        })
        .collect();
    // `pegs` puts the four sides of the box `[0, w] × [0, h]` first (`box_walls`).
    let (w, h) = (segments[1].0[0], segments[2].0[1]);
    assert_eq!(segments[2].0, [w, h], "the first four walls are the box");
    let n = scene.bodies.len();
    let r = scene.bodies[0].radius;
    Setup {
        name: "(c) peg board",
        description: format!(
            "ccdsim's `pegs(&PegsConfig::default())`: {n} balls r = {r} m, {} segment pegs, a {w} m × {h} m box",
            segments.len() - 4
        ),
        scene,
        box_size: [w, h],
        bullets: 0,
        pegs: segments[4..].to_vec(),
    }
}

/// The scenes of the comparison, in table order.
pub fn all() -> Vec<Setup> {
    vec![
        gas_scene("(a) gas", 0),
        gas_scene("(b) gas + bullets", BULLETS),
        peg_scene(),
    ]
}
