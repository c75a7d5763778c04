//! A shot played out event by event: balls sliding, rolling and spinning on the cloth,
//! meeting each other, the cushions and the jaws, and dropping into pockets, until every ball
//! rests or is pocketed.
//!
//! The events and their order are those of Leckie & Greenspan's event-based simulator as
//! pooltool 0.3.3 runs it: a ball's state change, two balls meeting (frictionless elastic, or
//! frictional as an option: [`super::ball_impact`], [`BallParams::ball_ball`]), a ball meeting a straight cushion or a jaw (Han 2005,
//! [`super::cushion_impact`]) or dropping into a pocket. After a collision both balls (or the
//! one) are sliding, as pooltool sets them. Nothing is moved apart after a collision: the
//! contact times are certified roots ([`super::contact_time`]), and a pair still touching
//! meets again only if it turns to approach. Balls their decelerations press together part at
//! the speed a contact's duration asks for ([`super::ball_impact::part_pressed`]).
//!
//! Each ball's state is stored as of its last event; the next event of every pair, of every
//! ball against the table and of every ball's state is a pure function of the stored states,
//! kept until one of its balls has an event. [`Shot::next_event_naive`] computes it all afresh
//! and is the oracle every finder ([`PoolFinder`]: an event calendar, a grid, hierarchies of
//! swept boxes) must equal bit for bit. Ties in time go to the state change, then two balls, a
//! cushion, a jaw, a pocket (pooltool's order), then to the lowest index.

use thiserror::Error;

use super::ball_impact::{exchange, frictional, part_pressed, rest_if_rounding};
use super::calendar::Calendar;
use super::contact_time::{self, Flight};
use super::cushion_impact::bounce_as_played;
use super::params::{BallBallModel, BallParams};
use super::search::{parts_of, BroadPhase, PoolFinder, TablePart};
use super::shot_event::{first, ShotEvent, ShotEventKind};
use super::table::Table;
use crate::geom::{Aabb, Vector};
use crate::motion::cloth::settle;
use crate::motion::{ClothBall, ClothState, CueStrike};

/// One ball: its state as of `time`, or the pocket it dropped into.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TableBall {
    /// Position, velocity and angular velocity at `time`.
    pub ball: ClothBall,
    /// Motion state from `time` on.
    pub state: ClothState,
    /// Time of the ball's last event, seconds.
    pub time: f64,
    /// The pocket (an index into [`Table::pockets`]) it dropped into, if it did; it then rests
    /// at the pocket's centre.
    pub pocket: Option<usize>,
}

/// Why a shot cannot be set up or played on.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ShotError {
    /// A ball does not lie on the playing surface clear of the cushions and pockets.
    #[error("ball {0} at ({1}, {2}) is not on the table (clear of the cushions and pockets)")]
    OffTable(usize, f64, f64),
    /// Two balls overlap.
    #[error("balls {0} and {1} overlap")]
    Overlap(usize, usize),
    /// A ball index out of range, or a pocketed ball.
    #[error("there is no ball {0} on the table")]
    NoSuchBall(usize),
    /// The cue's tip would miss the ball (`a² + b² > 1` after throttling) or the strike is not
    /// finite.
    #[error(
        "the cue would miss the ball (tip offset beyond its radius) or the strike is not finite"
    )]
    Miss,
    /// The shot went on for more events than allowed (balls trapped in an endless sequence of
    /// ever smaller bounces, or a limit set too low).
    #[error("the shot did not end within {0} events")]
    TooManyEvents(usize),
    /// Two touching balls meet twice at one instant with nothing to part them: pressed
    /// together where [`super::ball_impact::part_pressed`] gives them no parting speed
    /// (docs/model.md, "Balls pressed together").
    #[error(
        "balls {0} and {1} press together at t = {2} s (touching, meeting again at once, \
         nothing to part them)"
    )]
    Pressed(usize, usize, f64),
}

impl ShotError {
    /// The message with the balls called by `names` (indexed as the shot's balls) instead of
    /// by number.
    #[must_use]
    pub fn describe(&self, names: &[String]) -> String {
        let name = |i: usize| {
            names
                .get(i)
                .map_or_else(|| i.to_string(), |n| format!("{n:?}"))
        };
        match *self {
            ShotError::OffTable(i, x, y) => format!(
                "ball {} at ({x}, {y}) is not on the table (clear of the cushions and pockets)",
                name(i)
            ),
            ShotError::Overlap(i, j) => format!("balls {} and {} overlap", name(i), name(j)),
            ShotError::NoSuchBall(i) => format!("there is no ball {} on the table", name(i)),
            ShotError::Pressed(a, b, t) => format!(
                "balls {} and {} press together at t = {t} s (touching, meeting again at once, \
                 nothing to part them)",
                name(a),
                name(b)
            ),
            ShotError::Miss | ShotError::TooManyEvents(_) => self.to_string(),
        }
    }
}

/// A shot on a table: the balls, the events so far and the predictions of the next ones.
#[derive(Clone, Debug)]
pub struct Shot {
    table: Table,
    params: BallParams,
    balls: Vec<TableBall>,
    time: f64,
    /// Each ball's flight in its current state (end: its state change).
    flights: Vec<Flight>,
    /// Each ball's state change, if its state ends.
    transitions: Vec<Option<ShotEvent>>,
    /// The next meeting of balls `i < j`, at `i·n + j`.
    pairs: Vec<Option<f64>>,
    /// Each ball's next cushion, jaw or pocket.
    rails: Vec<Option<ShotEvent>>,
    events: Vec<ShotEvent>,
    /// The first meeting of two balls that were not approaching.
    pressed: Option<(usize, usize, f64)>,
    /// Each ball's last meeting with a higher-numbered ball: that ball and the time.
    last_meeting: Vec<Option<(usize, f64)>>,
    /// Collisions parted by [`part_pressed`] or [`part_from_cushion`], and the energy that
    /// added (J).
    pressings: usize,
    pressing_energy: f64,
    /// How [`Shot::step`] finds the next event.
    finder: PoolFinder,
    /// The finder's broad phase, over `boxes`.
    broad: BroadPhase,
    /// Each ball's swept box over its flight ([`Aabb::EMPTY`] once pocketed).
    boxes: Vec<Aabb<2>>,
    /// The `sedgewick` finder's calendar of predictions.
    calendar: Calendar,
    /// The table's parts, in the broad phases' numbering.
    parts: Vec<TablePart>,
    /// Scratch: the balls and parts a ball's contacts are looked for among.
    near_balls: Vec<usize>,
    near_parts: Vec<usize>,
}

impl Shot {
    /// Balls at rest at `positions` (metres) on `table`, at time 0.
    ///
    /// # Errors
    /// A ball off the playing surface or in a pocket ([`ShotError::OffTable`]), or two balls
    /// overlapping ([`ShotError::Overlap`]; touching is allowed).
    pub fn new(
        table: Table,
        params: BallParams,
        positions: &[Vector<2>],
    ) -> Result<Shot, ShotError> {
        let r = params.radius();
        for (i, &p) in positions.iter().enumerate() {
            if !p.is_finite() || !table.holds(p, r) {
                return Err(ShotError::OffTable(i, p[0], p[1]));
            }
            for (j, &q) in positions.iter().enumerate().take(i) {
                if (p - q).norm() < 2.0 * r {
                    return Err(ShotError::Overlap(j, i));
                }
            }
        }
        let balls: Vec<TableBall> = positions
            .iter()
            .map(|&pos| TableBall {
                ball: ClothBall {
                    pos,
                    vel: Vector::ZERO,
                    spin: Vector::ZERO,
                },
                state: ClothState::Stationary,
                time: 0.0,
                pocket: None,
            })
            .collect();
        let n = balls.len();
        let finder = PoolFinder::default();
        let broad = BroadPhase::new(finder, &table, n, r);
        let parts = parts_of(&table).0;
        let mut shot = Shot {
            table,
            params,
            balls,
            time: 0.0,
            flights: Vec::new(),
            transitions: vec![None; n],
            pairs: vec![None; n * n],
            rails: vec![None; n],
            events: Vec::new(),
            pressed: None,
            last_meeting: vec![None; n],
            pressings: 0,
            pressing_energy: 0.0,
            finder,
            broad,
            boxes: vec![Aabb::EMPTY; n],
            calendar: Calendar::new(n),
            parts,
            near_balls: Vec::new(),
            near_parts: Vec::new(),
        };
        shot.flights = (0..n).map(|i| shot.flight_of(i)).collect();
        for i in 0..n {
            shot.predict(i);
        }
        Ok(shot)
    }

    /// Makes [`Shot::step`] find each event with `finder` from now on (the default is
    /// [`PoolFinder::Cells`]). Every finder gives the same events, bit for bit.
    pub fn set_finder(&mut self, finder: PoolFinder) {
        let n = self.balls.len();
        self.finder = finder;
        self.broad = BroadPhase::new(finder, &self.table, n, self.params.radius());
        self.calendar = Calendar::new(n);
        for i in 0..n {
            self.predict(i);
        }
    }

    /// How [`Shot::step`] finds each event.
    #[must_use]
    pub fn finder(&self) -> PoolFinder {
        self.finder
    }

    /// Strikes ball `ball` with the cue now: it leaves sliding with the strike's velocity and
    /// angular velocity ([`CueStrike::launch`] with the shot's ball and cue parameters).
    ///
    /// # Errors
    /// [`ShotError::NoSuchBall`] for a ball that is not on the table, [`ShotError::Miss`] when
    /// the tip would miss it.
    pub fn strike(&mut self, ball: usize, strike: &CueStrike) -> Result<(), ShotError> {
        if self.balls.get(ball).is_none_or(|b| b.pocket.is_some()) {
            return Err(ShotError::NoSuchBall(ball));
        }
        let p = &self.params;
        let (vel, spin) = strike
            .launch(p.mass, p.radius(), p.cue_mass, p.throttle_english)
            .filter(|(v, w)| v.is_finite() && w.is_finite())
            .ok_or(ShotError::Miss)?;
        let now = self.time;
        let b = self.ball_at(ball, now);
        self.set(
            ball,
            ClothBall {
                pos: b.pos,
                vel,
                spin,
            },
            ClothState::Sliding,
        );
        Ok(())
    }

    /// The table.
    #[must_use]
    pub fn table(&self) -> &Table {
        &self.table
    }

    /// The ball parameters.
    #[must_use]
    pub fn params(&self) -> &BallParams {
        &self.params
    }

    /// The balls as of their last events.
    #[must_use]
    pub fn balls(&self) -> &[TableBall] {
        &self.balls
    }

    /// The time of the last event (or strike), seconds.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Every event so far, in order.
    #[must_use]
    pub fn events(&self) -> &[ShotEvent] {
        &self.events
    }

    /// Ball `i` at time `t` (seconds, not before its last event and not past its next state
    /// change): position, velocity and angular velocity.
    #[must_use]
    pub fn ball_at(&self, i: usize, t: f64) -> ClothBall {
        let b = &self.balls[i];
        if b.pocket.is_some() {
            return b.ball;
        }
        self.params.cloth.evolve(&b.ball, b.state, t - b.time)
    }

    /// The first two balls that met twice at the same time with nothing to part them, and
    /// when: touching balls pressed together where
    /// [`super::ball_impact::part_pressed`] found no parting speed to give them (not seen in
    /// any shot so far). They would meet at that instant for ever; [`Shot::run`] stops there.
    #[must_use]
    pub fn pressed(&self) -> Option<(usize, usize, f64)> {
        self.pressed
    }

    /// Collisions so far whose balls (or ball and cushion) parted too slowly to stay apart
    /// for a contact's duration and were parted faster (pressed together:
    /// [`super::ball_impact::part_pressed`], [`super::cushion_impact::part_from_cushion`]), and
    /// the kinetic energy that added, joules.
    #[must_use]
    pub fn pressings(&self) -> (usize, f64) {
        (self.pressings, self.pressing_energy)
    }

    /// Whether every ball rests or is pocketed.
    #[must_use]
    pub fn is_still(&self) -> bool {
        self.balls
            .iter()
            .all(|b| b.pocket.is_some() || b.state == ClothState::Stationary)
    }

    /// The next event, from the kept predictions.
    #[must_use]
    pub fn next_event(&self) -> Option<ShotEvent> {
        let n = self.balls.len();
        let mut best = None;
        for i in 0..n {
            best = first(best, self.transitions[i]);
            best = first(best, self.rails[i]);
            for j in i + 1..n {
                best = first(
                    best,
                    self.pairs[i * n + j].map(|time| ShotEvent {
                        time,
                        kind: ShotEventKind::Balls { a: i, b: j },
                    }),
                );
            }
        }
        best
    }

    /// The next event, every prediction computed afresh from the stored states: the oracle
    /// [`Shot::next_event`] must equal bit for bit.
    #[must_use]
    pub fn next_event_naive(&self) -> Option<ShotEvent> {
        let n = self.balls.len();
        let flights: Vec<Flight> = (0..n).map(|i| self.flight_of(i)).collect();
        let r = self.params.radius();
        let mut best = None;
        for i in 0..n {
            if self.balls[i].pocket.is_some() {
                continue;
            }
            best = first(best, self.transition_of(i));
            best = first(best, self.rail_of(i, &flights[i]));
            for j in i + 1..n {
                if self.balls[j].pocket.is_some() {
                    continue;
                }
                let hit = contact_time::ball_ball(&flights[i], &flights[j], r);
                best = first(
                    best,
                    hit.map(|time| ShotEvent {
                        time,
                        kind: ShotEventKind::Balls { a: i, b: j },
                    }),
                );
            }
        }
        best
    }

    /// Makes [`Shot::step`] find each event with the oracle, [`Shot::next_event_naive`] (every
    /// prediction computed afresh: O(n²) quartics an event; [`PoolFinder::AllPairs`]), or
    /// back to the default finder. The events are the same, bit for bit; the oracle is for
    /// checking that.
    pub fn search_afresh(&mut self, afresh: bool) {
        self.set_finder(if afresh {
            PoolFinder::AllPairs
        } else {
            PoolFinder::default()
        });
    }

    /// Plays the next event and returns it; `None` once every ball rests or is pocketed.
    pub fn step(&mut self) -> Option<ShotEvent> {
        let event = match self.finder {
            PoolFinder::AllPairs => self.next_event_naive()?,
            PoolFinder::Sedgewick => self.calendar.first()?,
            PoolFinder::Cells | PoolFinder::Bvh => self.next_event()?,
        };
        let t = event.time;
        self.time = t;
        match event.kind {
            ShotEventKind::Transition { ball, to, .. } => {
                let b = settle(self.ball_at(ball, t), to);
                self.set(ball, b, to);
            }
            ShotEventKind::Balls { a, b } => {
                let (ba, bb) = (self.ball_at(a, t), self.ball_at(b, t));
                let (mut na, mut nb) = match self.params.ball_ball {
                    BallBallModel::FrictionlessElastic => exchange(&ba, &bb),
                    BallBallModel::FrictionalInelastic {
                        restitution,
                        friction,
                    } => frictional(&ba, &bb, self.params.radius(), restitution, &friction),
                };
                rest_if_rounding(&mut na, self.params.radius());
                rest_if_rounding(&mut nb, self.params.radius());
                let p = &self.params;
                if let Some(added) = part_pressed(&mut na, &mut nb, &p.cloth, p.contact_time) {
                    self.pressing_energy += p.mass * added;
                    self.pressings += 1;
                }
                // Meeting again with no time in between and nothing to part them (the
                // intervals of a Zeno sequence fall below the resolution of t): pressed
                // together beyond what the contact time resolves.
                let again = self.last_meeting[a] == Some((b, t));
                let parting = (nb.vel - na.vel).dot(nb.pos - na.pos);
                if again && parting <= 0.0 {
                    self.pressed.get_or_insert((a, b, t));
                }
                self.last_meeting[a] = Some((b, t));
                self.set(a, na, ClothState::Sliding);
                self.set(b, nb, ClothState::Sliding);
            }
            ShotEventKind::Cushion { ball, cushion } => {
                let c = &self.table.cushions[cushion];
                let n = c.normal();
                let side = (self.ball_at(ball, t).pos - c.p1).dot(n);
                let toward = if side >= 0.0 { -n } else { n };
                self.bounce_off(ball, toward, c.height);
            }
            ShotEventKind::Jaw { ball, jaw } => {
                let j = &self.table.jaws[jaw];
                let d = j.center - self.ball_at(ball, t).pos;
                self.bounce_off(ball, d * (1.0 / d.norm()), j.height);
            }
            ShotEventKind::Pocket { ball, pocket } => {
                let centre = self.table.pockets[pocket].center;
                self.balls[ball].pocket = Some(pocket);
                self.set(
                    ball,
                    ClothBall {
                        pos: centre,
                        vel: Vector::ZERO,
                        spin: Vector::ZERO,
                    },
                    ClothState::Stationary,
                );
            }
        }
        self.events.push(event);
        Some(event)
    }

    /// Plays events until every ball rests or is pocketed, at most `max_events` of them;
    /// returns how many it played.
    ///
    /// # Errors
    /// [`ShotError::TooManyEvents`] when balls are still moving after `max_events` events;
    /// [`ShotError::Pressed`] as soon as two balls meet without approaching (see
    /// [`Shot::pressed`]).
    pub fn run(&mut self, max_events: usize) -> Result<usize, ShotError> {
        self.run_with(max_events, |_, _| {})
    }

    /// [`Shot::run`], calling `after` with the shot and each event as soon as it is played
    /// (to record it: the balls' states are the event's outcome then).
    ///
    /// # Errors
    /// As [`Shot::run`].
    pub fn run_with(
        &mut self,
        max_events: usize,
        mut after: impl FnMut(&Shot, &ShotEvent),
    ) -> Result<usize, ShotError> {
        for played in 0..max_events {
            if let Some((a, b, t)) = self.pressed {
                return Err(ShotError::Pressed(a, b, t));
            }
            match self.step() {
                Some(event) => after(self, &event),
                None => return Ok(played),
            }
        }
        if self.next_event().is_some() {
            return Err(ShotError::TooManyEvents(max_events));
        }
        Ok(max_events)
    }

    /// Ball `i` bounces now off a cushion nose at `height` (m) in the direction `toward` (a
    /// unit vector from its centre to the contact; Han 2005), parted from it if pressed
    /// against it ([`bounce_as_played`]), and slides on.
    fn bounce_off(&mut self, i: usize, toward: Vector<2>, height: f64) {
        let (b, added) =
            bounce_as_played(&self.ball_at(i, self.time), toward, height, &self.params);
        if let Some(added) = added {
            self.pressing_energy += added;
            self.pressings += 1;
        }
        self.set(i, b, ClothState::Sliding);
    }

    /// Gives ball `i` a new state at the current time and renews every prediction it is in.
    fn set(&mut self, i: usize, ball: ClothBall, state: ClothState) {
        let b = &mut self.balls[i];
        b.ball = ball;
        b.state = state;
        b.time = self.time;
        self.flights[i] = self.flight_of(i);
        self.predict(i);
    }

    /// Renews ball `i`'s state change, its next table event and its meetings with every other
    /// ball, from its flight and theirs: among the balls and table parts its finder's broad
    /// phase puts near it (the others cannot be met: their predictions are none).
    fn predict(&mut self, i: usize) {
        let n = self.balls.len();
        let r = self.params.radius();
        self.transitions[i] = self.transition_of(i);
        self.boxes[i] = if self.balls[i].pocket.is_some() {
            Aabb::EMPTY
        } else {
            self.flights[i].swept_box(r)
        };
        self.broad.place(i, &self.boxes);
        let mut near = std::mem::take(&mut self.near_balls);
        let mut parts = std::mem::take(&mut self.near_parts);
        let everything = self
            .broad
            .near(i, &self.boxes, &mut near, &mut parts)
            .is_none();
        let meeting = |shot: &Shot, j: usize| {
            let (a, b) = (i.min(j), i.max(j));
            let off = shot.balls[a].pocket.is_some() || shot.balls[b].pocket.is_some();
            if off {
                None
            } else {
                contact_time::ball_ball(&shot.flights[a], &shot.flights[b], r)
            }
        };
        if everything {
            for j in (0..n).filter(|&j| j != i) {
                self.pairs[i.min(j) * n + i.max(j)] = meeting(self, j);
            }
            self.rails[i] = self.rail_of(i, &self.flights[i]);
        } else {
            for j in (0..n).filter(|&j| j != i) {
                self.pairs[i.min(j) * n + i.max(j)] = None;
            }
            for &j in &near {
                self.pairs[i.min(j) * n + i.max(j)] = meeting(self, j);
            }
            let f = self.flights[i];
            self.rails[i] = parts.iter().fold(None, |best, &k| {
                first(best, self.part_event(i, &f, self.parts[k]))
            });
        }
        self.near_balls = near;
        self.near_parts = parts;
        if self.finder == PoolFinder::Sedgewick {
            self.calendar.renew(i);
            if let Some(e) = self.transitions[i] {
                self.calendar.add(e, i, None);
            }
            if let Some(e) = self.rails[i] {
                self.calendar.add(e, i, None);
            }
            for j in (0..n).filter(|&j| j != i) {
                let (a, b) = (i.min(j), i.max(j));
                if let Some(time) = self.pairs[a * n + b] {
                    let kind = ShotEventKind::Balls { a, b };
                    self.calendar.add(ShotEvent { time, kind }, a, Some(b));
                }
            }
        }
    }

    fn flight_of(&self, i: usize) -> Flight {
        let b = &self.balls[i];
        let end = self.transition_of(i).map_or(f64::INFINITY, |e| e.time);
        Flight::new(&self.params.cloth, &b.ball, b.state, b.time, end)
    }

    fn transition_of(&self, i: usize) -> Option<ShotEvent> {
        let b = &self.balls[i];
        if b.pocket.is_some() {
            return None;
        }
        let (span, to) = self.params.cloth.transition(&b.ball, b.state)?;
        Some(ShotEvent {
            time: b.time + span,
            kind: ShotEventKind::Transition {
                ball: i,
                from: b.state,
                to,
            },
        })
    }

    fn rail_of(&self, i: usize, f: &Flight) -> Option<ShotEvent> {
        self.parts
            .iter()
            .fold(None, |best, &part| first(best, self.part_event(i, f, part)))
    }

    /// When ball `i` on flight `f` meets `part` of the table, if it does.
    fn part_event(&self, i: usize, f: &Flight, part: TablePart) -> Option<ShotEvent> {
        if self.balls[i].pocket.is_some() || !f.moves() {
            return None;
        }
        let r = self.params.radius();
        let t = &self.table;
        let (time, kind) = match part {
            TablePart::Cushion(k) => (
                contact_time::cushion(f, &t.cushions[k], r)?,
                ShotEventKind::Cushion {
                    ball: i,
                    cushion: k,
                },
            ),
            TablePart::Jaw(k) => (
                contact_time::jaw(f, &t.jaws[k], r)?,
                ShotEventKind::Jaw { ball: i, jaw: k },
            ),
            TablePart::Pocket(k) => (
                contact_time::pocket(f, &t.pockets[k])?,
                ShotEventKind::Pocket { ball: i, pocket: k },
            ),
        };
        Some(ShotEvent { time, kind })
    }
}
