//! The events of bodies turning about segment ends, which the finders do not see.
//!
//! A pivoting body ([`World::pivot`]) is parked for the finders: at rest, colliding with
//! nothing. Its own events are found here, by the functions of [`crate::contact::pivot_contact`] and
//! [`crate::contact::pivot_end`], against every body and every wall: the first contact with each
//! other body is kept per pair and recomputed when either changes (O(pivots) a change), the
//! first wall contact and the end of the turn when the pivot or a moving wall changes. The
//! simulation takes the earlier of the finder's event and the first of these, under the
//! events' total order, so the run is the same whatever the finder.

use crate::contact::pivot_contact::{first_contact_points, toi_pivot_wall, Parabola};
use crate::contact::pivot_end::{pivot_end, PivotEnd};
use crate::event::Event;
use crate::geom::Vector;
use crate::motion::pivot::Pivot;
use crate::wall::Wall;
use crate::world::{to_2d, wall_2d, World};

/// One pivoting body's next events.
#[derive(Clone, Debug)]
struct Entry {
    body: usize,
    /// The body's change count when its turn started: the entry is stale once it moves.
    changes: u64,
    /// The segment whose end point it turns about.
    segment: usize,
    /// When the turn ends by itself, and how.
    end: Option<PivotEnd>,
    /// Its first contact with each other body, by body index.
    pairs: Vec<Option<f64>>,
    /// Its first contact with a wall, as an event.
    wall: Option<Event>,
}

/// The next events of every pivoting body.
#[derive(Clone, Debug, Default)]
pub(crate) struct PivotEvents {
    entries: Vec<Entry>,
}

/// The motion of body `j` of `world` as the contact search takes it.
enum Motion2 {
    Falling(Parabola),
    Turning(Pivot),
}

impl Motion2 {
    fn of<const D: usize>(world: &World<D>, j: usize) -> Self {
        if let Some((p, _)) = world.pivot(j) {
            return Motion2::Turning(*p);
        }
        let m = world.motion(j);
        Motion2::Falling(Parabola {
            pos: to_2d(m.pos),
            vel: to_2d(m.vel),
            acc: to_2d(world.acceleration(j)),
            time: m.time,
        })
    }
}

impl PivotEvents {
    /// True when no body pivots (as far as the entries know).
    pub(crate) fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Brings the entries in line with `world`'s pivoting bodies (new turns get every event
    /// computed; ended ones are dropped), then recomputes the pairs of every other entry with
    /// `changed` bodies.
    pub(crate) fn bodies_changed<const D: usize>(&mut self, world: &World<D>, changed: &[usize]) {
        self.entries
            .retain(|e| world.pivot(e.body).is_some() && world.change_count(e.body) == e.changes);
        for i in world.pivoting() {
            if !self.entries.iter().any(|e| e.body == i) {
                self.entries.push(Self::entry(world, i));
            }
        }
        for entry in &mut self.entries {
            entry.pairs.resize(world.len(), None);
            for &j in changed {
                if j != entry.body {
                    entry.pairs[j] = pair_time(world, entry.body, entry.end, j);
                }
            }
        }
    }

    /// Every entry computed anew (after a change of every body, or of a moving wall).
    pub(crate) fn reset<const D: usize>(&mut self, world: &World<D>) {
        self.entries.clear();
        self.bodies_changed(world, &[]);
    }

    /// How body `i`'s turn ends by itself, and the event that is: a wall event naming the
    /// segment it turned about (release, swing back) or the one it lands on.
    pub(crate) fn end_of(&self, i: usize) -> Option<(PivotEnd, Event)> {
        let e = self.entries.iter().find(|e| e.body == i)?;
        Self::end_event(e)
    }

    fn end_event(e: &Entry) -> Option<(PivotEnd, Event)> {
        let end = e.end?;
        let event = match end {
            PivotEnd::Release { time } | PivotEnd::Back { time } => {
                Event::wall(time, e.body, e.segment)
            }
            PivotEnd::Land { time, wall } => Event::wall(time, e.body, wall),
        };
        Some((end, event))
    }

    /// The first event of any pivoting body, under the events' order.
    pub(crate) fn next(&self) -> Option<Event> {
        let mut best: Option<Event> = None;
        for e in &self.entries {
            best = Event::earliest(best, Self::end_event(e).map(|(_, x)| x));
            best = Event::earliest(best, e.wall);
            for (j, t) in e.pairs.iter().enumerate() {
                if let Some(t) = *t {
                    best = Event::earliest(best, Some(Event::body(t, e.body, j)));
                }
            }
        }
        best
    }

    /// All of one new pivot's events.
    fn entry<const D: usize>(world: &World<D>, i: usize) -> Entry {
        let (pivot, w) = world.pivot(i).expect("a pivoting body");
        let walls: Vec<Wall<2>> = world.walls().iter().map(wall_2d).collect();
        let end = pivot_end(pivot, &walls, w);
        let hi = end.map_or(f64::INFINITY, |e| e.time());
        // Searches start from the later of the two motions' reference times, whenever they
        // are made: the same bits however the events before came.
        let lo = pivot.start_time();
        let r = world.radius(i);
        let statics = walls.iter().enumerate().filter_map(|(k, wall)| {
            toi_pivot_wall(pivot, r, wall, Vector::ZERO, lo, lo, hi).map(|t| Event::wall(t, i, k))
        });
        let moving = (0..world.moving_wall_count()).filter_map(|k| {
            let idx = walls.len() + k;
            let from = lo.max(world.wall_motion(k).time);
            let wall = wall_2d(&world.wall_at(idx, from));
            let vel = to_2d(world.wall_velocity(idx));
            toi_pivot_wall(pivot, r, &wall, vel, from, from, hi).map(|t| Event::wall(t, i, idx))
        });
        let wall = statics.chain(moving).min();
        let pairs = (0..world.len())
            .map(|j| {
                if j == i {
                    None
                } else {
                    pair_time(world, i, end, j)
                }
            })
            .collect();
        Entry {
            body: i,
            changes: world.change_count(i),
            segment: w,
            end,
            pairs,
            wall,
        }
    }
}

/// How pivoting body `i`'s turn ends by itself ([`pivot_end`] over `world`'s static walls).
pub(crate) fn turn_end<const D: usize>(world: &World<D>, i: usize) -> Option<PivotEnd> {
    let (pivot, w) = world.pivot(i)?;
    let walls: Vec<Wall<2>> = world.walls().iter().map(wall_2d).collect();
    pivot_end(pivot, &walls, w)
}

/// The first contact of pivoting body `i` (its turn ending as `end` says) with body `j`, from
/// now on: `None` for a vacant slot, a pair whose filters pass through each other, or no
/// contact before the turn ends.
fn pair_time<const D: usize>(
    world: &World<D>,
    i: usize,
    end: Option<PivotEnd>,
    j: usize,
) -> Option<f64> {
    if world.is_vacant(j) || !world.filter(i).collides(&world.filter(j)) {
        return None;
    }
    let (pivot, _) = world.pivot(i)?;
    let mut hi = end.map_or(f64::INFINITY, |e| e.time());
    let lo = pivot.start_time().max(world.time(j));
    let reach = world.radius(i) + world.radius(j);
    match Motion2::of(world, j) {
        Motion2::Falling(p) => first_contact_points(pivot, &p, reach, lo, hi),
        Motion2::Turning(q) => {
            // The other turn's end bounds the search too: past it, that body moves on anew.
            if let Some(e) = turn_end(world, j) {
                hi = hi.min(e.time());
            }
            first_contact_points(pivot, &q, reach, lo, hi)
        }
    }
}
