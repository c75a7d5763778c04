//! Recorded runs where bodies rest on 2D segments, go on along a shelf drawn in pieces, fly
//! off a segment's end (see `ccdsim::contact::ledge`) or, too slow for that, roll over it, turning
//! about its end point (see `ccdsim::motion::pivot`), with the simulation's own states at frames and
//! between each slide-off or roll-over and the event after it, to check playback against.
//! Scenes with segments bodies rest on are written in format version 13
//! (`ccdsim::record::VERSION_PIVOTS`), whether or not a body turns in them.

use super::resting::{checkpoint, recorded_motion, Checkpoint};
use ccdsim::record::{RunReader, RunWriter};
use ccdsim::Gravity;
use ccdsim::Motion;
use ccdsim::{BodySpec, Collision, EventKind, Scene, Settings, Simulation, Vector, Wall};
use std::path::Path;

/// Radius of the shelf ball, metres.
pub const RADIUS: f64 = 0.2;

/// The height of the shelf's top, metres.
pub const SHELF_Y: f64 = 1.0;

/// Where the shelf ends on the right, metres.
pub const SHELF_END: f64 = 2.0;

/// The floor (static wall 0) and the shelf's two pieces (walls 1 and 2).
pub const FLOOR: usize = 0;
pub const SHELF_LEFT: usize = 1;
pub const SHELF_RIGHT: usize = 2;

/// The ball on the shelf, under `g = (0, −10)` with restitution 0.5 and `rest_speed` 1 m/s:
/// a floor plane `y = 0` and a level shelf at `y = 1` from `x = 0` to 2, drawn in two
/// pieces that meet at `x = 1`. The ball is put a hair above the shelf at `x = 0.5`, moving
/// right at 2 m/s: it rests on the left piece at once, goes on along the right one at
/// `x = 1`, flies off its end at `x = 2` (`2² > r g = 2`), falls onto the floor and bounces
/// there until it rests on it.
#[must_use]
pub fn shelf_scene() -> Scene<2> {
    shelf_scene_at(2.0)
}

/// [`shelf_scene`] with the ball moving right at 1 m/s: too slow to fly off the shelf's end
/// (`1² < r g = 2`), it rolls over it, turning about the end point `(2, 1)` until the point
/// stops pushing it (`cos θ = 5/6` from the top), and falls from there onto the floor.
#[must_use]
pub fn roll_scene() -> Scene<2> {
    shelf_scene_at(1.0)
}

/// The end point of the shelf, which [`roll_scene`]'s ball turns about.
pub const SHELF_CORNER: Vector<2> = Vector([SHELF_END, SHELF_Y]);

fn shelf_scene_at(speed: f64) -> Scene<2> {
    let segment = |a: [f64; 2], b: [f64; 2]| Wall::Segment {
        a: Vector(a),
        b: Vector(b),
    };
    Scene {
        settings: Settings {
            restitution: 0.5,
            gravity: Gravity::new(&[0.0, -10.0]),
            rest_speed: Some(1.0),
            ..Settings::default()
        },
        bodies: vec![BodySpec::new(
            Vector([0.5, SHELF_Y + RADIUS + 1e-6]),
            Vector([speed, 0.0]),
            RADIUS,
        )],
        walls: vec![
            Wall::Plane {
                point: Vector([0.0, 0.0]),
                normal: Vector([0.0, 1.0]),
            },
            segment([0.0, SHELF_Y], [1.0, SHELF_Y]),
            segment([1.0, SHELF_Y], [SHELF_END, SHELF_Y]),
        ],
        ..Scene::default()
    }
}

/// `examples/shelves.json` at the repository's root: seven balls on shelves (one in two
/// pieces) and ramps.
#[must_use]
pub fn shelves_example() -> Scene<2> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/shelves.json");
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// What one event did to its body `a`, as the simulation's supports before and after it say.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ledge {
    /// A wall record of a body with the segment it slid on, not resting nor turning: it flies
    /// off.
    SlideOff,
    /// A wall record flagged "turns" (`pivots[0]`): the body rolls over the end of the
    /// segment it slid on, turning about its end point.
    RollsOver,
    /// A wall record flagged "rests" of a body that slid on another segment: it goes on.
    GoesOn,
}

/// A recorded run and what the simulation had along the way.
pub struct LedgeRun {
    pub scene: Scene<2>,
    /// Every event, in order.
    pub events: Vec<Collision<2>>,
    /// Per event, whether it was a slide-off or a going on (`None`: anything else).
    pub ledges: Vec<Option<Ledge>>,
    /// Every body's stored state and support after each event (`after[k]`: after the first
    /// `k` events; `after[0]` the start).
    pub after: Vec<Vec<(Motion<2>, Option<usize>)>>,
    /// The end of the run, seconds.
    pub end: f64,
    /// The simulation at every frame and at times between each slide-off or roll-over and the
    /// event after it, in time order.
    pub checkpoints: Vec<Checkpoint>,
}

impl LedgeRun {
    /// The events that are slide-offs, by index.
    pub fn slide_offs(&self) -> Vec<usize> {
        self.indices(Ledge::SlideOff)
    }

    /// The events after which a body turns about a segment's end point, by index.
    pub fn roll_overs(&self) -> Vec<usize> {
        self.indices(Ledge::RollsOver)
    }

    /// The events where a body goes on along the next segment, by index.
    pub fn goes_on(&self) -> Vec<usize> {
        self.indices(Ledge::GoesOn)
    }

    fn indices(&self, what: Ledge) -> Vec<usize> {
        (0..self.ledges.len())
            .filter(|&k| self.ledges[k] == Some(what))
            .collect()
    }

    /// The time of event `k`, or the run's end past the last one.
    pub fn time_of(&self, k: usize) -> f64 {
        self.events.get(k).map_or(self.end, |c| c.event.time)
    }
}

fn bodies(sim: &Simulation<2>) -> Vec<(Motion<2>, Option<usize>)> {
    let w = sim.world();
    (0..w.len())
        .map(|i| (recorded_motion(w, i), w.support(i)))
        .collect()
}

/// Runs `scene` until `until` with the all-pairs finder and records it to `path` (its format
/// version checked to be 13: the scene has segments bodies rest on), taking checkpoints every
/// `frame` seconds and at three times between each slide-off or roll-over and the next event
/// (a hundredth, half and 99 hundredths of the way). The run must not halt.
pub fn record_ledge_run(scene: &Scene<2>, until: f64, frame: f64, path: &Path) -> LedgeRun {
    // First the events, classified from the supports before and after each: a second run
    // stops at checkpoints placed from their times.
    let mut sim = Simulation::new(scene, "all-pairs").unwrap();
    let (mut events, mut ledges, mut after) = (Vec::new(), Vec::new(), vec![bodies(&sim)]);
    while let Some(c) = sim.step_event_until(until) {
        let a = c.event.a as usize;
        let (was, now) = (after.last().unwrap()[a].1, sim.world().support(a));
        let on_segment = |w: usize| matches!(scene.walls[w], Wall::Segment { .. });
        ledges.push(match (c.event.kind, was) {
            (EventKind::Wall, _) if c.pivots[0] => {
                assert!(sim.world().pivot(a).is_some(), "{c:?}");
                Some(Ledge::RollsOver)
            }
            (EventKind::Wall, Some(w)) if w == c.event.b as usize && !c.rests[0] => {
                assert_eq!(now, None, "{c:?}");
                Some(Ledge::SlideOff)
            }
            (EventKind::Wall, Some(w))
                if w != c.event.b as usize && c.rests[0] && on_segment(w) =>
            {
                Some(Ledge::GoesOn)
            }
            _ => None,
        });
        events.push(c);
        after.push(bodies(&sim));
    }
    assert!(sim.halt().is_none(), "{:?}", sim.halt());
    let time_of = |k: usize| events.get(k).map_or(until, |c: &Collision<2>| c.event.time);
    let mut times: Vec<f64> = (0..)
        .map(|f| f as f64 * frame)
        .take_while(|&t| t <= until)
        .collect();
    let off_or_over = |k: &usize| matches!(ledges[*k], Some(Ledge::SlideOff | Ledge::RollsOver));
    for k in (0..events.len()).filter(off_or_over) {
        let (from, to) = (time_of(k), time_of(k + 1));
        times.extend(
            [0.01, 0.5, 0.99]
                .map(|f| from + f * (to - from))
                .into_iter()
                .filter(|&t| t > from && t < to),
        );
    }
    // Between events only: at an event's own time the state after it is the one shown.
    times.retain(|&t| events.iter().all(|c| c.event.time != t));
    times.sort_by(f64::total_cmp);
    times.dedup();

    let mut sim = Simulation::new(scene, "all-pairs").unwrap();
    let mut w = RunWriter::create(path, scene).unwrap();
    let mut recorded = Vec::new();
    let mut checkpoints = Vec::new();
    for &t in &times {
        sim.run_until_with(t, |c| {
            w.write_event(c).unwrap();
            recorded.push(*c);
        });
        checkpoints.push(checkpoint(&sim, recorded.len() as u64));
    }
    sim.run_until_with(until, |c| {
        w.write_event(c).unwrap();
        recorded.push(*c);
    });
    w.finish(until).unwrap();
    assert!(
        recorded == events,
        "stopping at the checkpoints changed the run"
    );
    let file = std::fs::File::open(path).unwrap();
    let reader = RunReader::<_, 2>::new(file, path.display().to_string()).unwrap();
    assert_eq!(reader.version(), ccdsim::record::VERSION_PIVOTS);
    LedgeRun {
        scene: scene.clone(),
        events,
        ledges,
        after,
        end: until,
        checkpoints,
    }
}
