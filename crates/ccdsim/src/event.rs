//! Events and their total order: (time, kind, lower id, higher id).

use crate::geom::Vector;
use std::cmp::Ordering;

/// What an event is between: two bodies, or a body and a wall; or a thermostat reset.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug)]
pub enum EventKind {
    /// Two bodies touch. Orders before a wall event at the same time.
    Body = 0,
    /// A body touches a wall.
    Wall = 1,
    /// The Andersen thermostat gives body `a` a new velocity (`b` is 0); never predicted by a
    /// finder, see [`crate::thermostat`]. Orders after collisions at the same time.
    Reset = 2,
    /// A program moved body `a` or gave it a new velocity (`b` is 0):
    /// [`Simulation::set_velocity`](crate::Simulation::set_velocity) or
    /// [`Simulation::set_position`](crate::Simulation::set_position), recorded in run files
    /// so that a steered run can be replayed (see
    /// [`Simulation::record_edits`](crate::Simulation::record_edits)). Never predicted by a
    /// finder.
    Edit = 3,
}

/// A collision at absolute simulated time `time` (seconds).
///
/// For [`EventKind::Body`], `a < b` are body indices (their positions in the scene's body
/// list). For [`EventKind::Wall`], `a` is the body index and `b` the wall index.
#[derive(Clone, Copy, Debug)]
pub struct Event {
    /// Absolute time of contact, seconds; never NaN.
    pub time: f64,
    /// Body–body or body–wall.
    pub kind: EventKind,
    /// Lower body index (body events) or the body (wall events).
    pub a: u32,
    /// Higher body index (body events) or the wall index (wall events).
    pub b: u32,
}

impl Event {
    /// A body–body event; orders the indices so that `a < b`.
    #[must_use]
    #[inline]
    pub fn body(time: f64, i: usize, j: usize) -> Self {
        debug_assert!(i != j && !time.is_nan());
        let (a, b) = if i < j { (i, j) } else { (j, i) };
        Event {
            time,
            kind: EventKind::Body,
            a: a as u32,
            b: b as u32,
        }
    }

    /// A body–wall event between body `i` and wall `w`.
    #[must_use]
    #[inline]
    pub fn wall(time: f64, i: usize, w: usize) -> Self {
        debug_assert!(!time.is_nan());
        Event {
            time,
            kind: EventKind::Wall,
            a: i as u32,
            b: w as u32,
        }
    }

    /// The thermostat's velocity reset of body `i` at `time`.
    #[must_use]
    pub fn reset(time: f64, i: usize) -> Self {
        Event {
            time,
            kind: EventKind::Reset,
            a: i as u32,
            b: 0,
        }
    }

    /// A program's edit of body `i`'s state at `time` (see [`EventKind::Edit`]).
    #[must_use]
    pub fn edit(time: f64, i: usize) -> Self {
        Event {
            time,
            kind: EventKind::Edit,
            a: i as u32,
            b: 0,
        }
    }

    /// The earlier of two optional events under the total order.
    #[must_use]
    #[inline]
    pub fn earliest(x: Option<Event>, y: Option<Event>) -> Option<Event> {
        match (x, y) {
            (Some(p), Some(q)) => Some(if q < p { q } else { p }),
            (p, None) => p,
            (None, q) => q,
        }
    }
}

impl Ord for Event {
    #[inline]
    fn cmp(&self, o: &Self) -> Ordering {
        self.time
            .total_cmp(&o.time)
            .then(self.kind.cmp(&o.kind))
            .then(self.a.cmp(&o.a))
            .then(self.b.cmp(&o.b))
    }
}
impl PartialOrd for Event {
    #[inline]
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
/// Equality is bit-for-bit on the time (via the total order), so `==` is the exactness test.
impl PartialEq for Event {
    #[inline]
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Event {}

/// A resolved collision: the event and the involved bodies' states right after it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Collision<const D: usize> {
    /// The event that was resolved.
    pub event: Event,
    /// Positions at `event.time` of body `event.a` and (body events) body `event.b`.
    pub pos: [Vector<D>; 2],
    /// Velocities after the collision, in the same order.
    pub vel: [Vector<D>; 2],
    /// For each body of the event (`event.a`, then `event.b` for body events), true when it
    /// rests on a wall after it (see [`crate::contact::resting`]): for a wall event on that wall,
    /// for a body event on the wall it rested on before (the collision left its velocity as
    /// it was). Edits and resets lift every body they change off its wall.
    pub rests: [bool; 2],
    /// For each body of the event, as `rests`, true when it turns about a segment's end
    /// point after it (see [`crate::motion::pivot`]): for a wall event, about an end point of that
    /// segment; its `pos` and `vel` are then the state its turn starts from.
    pub pivots: [bool; 2],
}

impl<const D: usize> Collision<D> {
    /// Number of bodies involved: 2 for body events, 1 for wall events.
    #[must_use]
    pub fn body_count(&self) -> usize {
        match self.event.kind {
            EventKind::Body => 2,
            EventKind::Wall | EventKind::Reset | EventKind::Edit => 1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_is_time_kind_ids() {
        let e1 = Event::body(1.0, 3, 2);
        assert_eq!((e1.a, e1.b), (2, 3));
        assert!(Event::body(1.0, 0, 5) < Event::wall(1.0, 0, 0));
        assert!(Event::body(1.0, 0, 5) < Event::body(1.0, 1, 2));
        assert!(Event::body(1.0, 1, 2) < Event::body(1.0, 1, 3));
        assert!(Event::wall(0.5, 9, 9) < Event::body(1.0, 0, 1));
        // -0.0 and 0.0 differ bit for bit, so they are ordered, not equal.
        assert!(Event::body(-0.0, 0, 1) < Event::body(0.0, 0, 1));
        assert_eq!(Event::earliest(Some(e1), None), Some(e1));
        assert_eq!(
            Event::earliest(Some(e1), Some(Event::wall(0.1, 0, 0)))
                .unwrap()
                .kind,
            EventKind::Wall
        );
    }
}
