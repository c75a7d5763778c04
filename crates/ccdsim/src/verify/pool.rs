//! Checking a recorded pool shot ([`crate::billiards::run_file`]) against the laws of the
//! cloth, the collision models and the table, independently of the shot's event search.
//!
//! Between two records every ball follows the motion state of its last record: its centre
//! moves on a parabola with the state's constant acceleration ([`crate::motion::cloth`]). For
//! every stretch between records [`PoolVerifier`] finds, in closed form (the ends of the
//! stretch and the roots of the derivative of the squared distance, a cubic split at its own
//! turning points and bisected), how close each pair of balls, each ball and jaw, and each ball
//! and pocket centre came, and how close each ball came to each straight cushion while the
//! foot of its perpendicular lay on the cushion: a missed collision shows as an overlap beyond
//! `1e-9` of the contact distance, a missed pocket as a centre inside a pocket's circle. No
//! ball's state may end before the next record unless that record is its state change.
//!
//! At each record it checks that the ball (balls) it names touch what the record says at its
//! time and approach it; that recorded positions follow from the motion; the state change's
//! time and next state (pooltool's rules, [`crate::motion::ClothParams::transition`]); the
//! strike's launch ([`crate::motion::CueStrike::launch`]); the ball–ball model (momentum kept;
//! frictionless: tangential velocities and every spin kept; the outcome the model and the
//! parting of pressed balls give, [`crate::billiards::ball_impact::part_pressed`]); that a ball leaves a cushion or jaw
//! moving away from it, with the velocity and spin Han's model gives
//! ([`crate::billiards::cushion_impact`]); that a pocketed ball rests at its pocket's centre;
//! and that the total energy (translational and rotational) never grows on the cloth or in a
//! collision of two balls, but for what parting pressed balls adds (reported). (It may at a cushion: Han's model as pooltool applies it drops the
//! ball's vertical velocity change and can add a few per cent of energy.)

use super::Violation;
use crate::billiards::ball_impact::{
    exchange, frictional, part_pressed, rest_if_rounding, rounding_floor,
};
use crate::billiards::cushion_impact::bounce_as_played;
use crate::billiards::{
    BallAfter, BallBallModel, BallParams, PoolRecord, PoolScene, ShotEventKind, Table,
};
use crate::geom::Vector;
use crate::motion::{ClothBall, ClothState, CueStrike};

/// Allowed overlap, relative to the contact distance (as for every run, see
/// [`super::OVERLAP_TOLERANCE`]).
const OVERLAP: f64 = super::OVERLAP_TOLERANCE;
/// Allowed relative difference between a recorded quantity and the one the laws give.
const CLOSE: f64 = 1e-9;

/// Totals of a verified pool shot.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PoolReport {
    /// Events checked (the strike and the end record not counted).
    pub events: u64,
    /// Meetings of two balls.
    pub ball_ball: u64,
    /// Bounces off straight cushions and jaws.
    pub cushion: u64,
    /// Balls pocketed.
    pub pocketed: u64,
    /// Motion state changes.
    pub transitions: u64,
    /// Largest overlap seen, relative to the contact distance, at records or in between.
    pub max_overlap: f64,
    /// Total kinetic energy (translational and rotational) just after the strike, joules.
    pub energy_start: f64,
    /// Total kinetic energy at the end, joules.
    pub energy_end: f64,
    /// Whether every ball rests or is pocketed at the end.
    pub still: bool,
    /// Collisions of balls pressed together (or a ball pressed against a cushion), parted at
    /// the speed the contact time asks for ([`crate::billiards::ball_impact::part_pressed`],
    /// [`crate::billiards::cushion_impact::part_from_cushion`]).
    pub pressings: u64,
    /// The kinetic energy those partings added, joules.
    pub pressing_energy: f64,
}

#[derive(Clone, Copy, Debug)]
struct Stored {
    ball: ClothBall,
    state: ClothState,
    time: f64,
    pocketed: bool,
}

/// Replays a pool shot's records in order and checks each (see the module docs).
pub struct PoolVerifier {
    table: Table,
    params: BallParams,
    cue: usize,
    strike: CueStrike,
    balls: Vec<Stored>,
    time: f64,
    index: u64,
    struck: bool,
    /// Speeds below this are rounding of the strike's (10⁻⁶ of the struck ball's speed), m/s.
    speed_floor: f64,
    energy: f64,
    /// Energy the record being checked added by parting pressed balls, joules.
    pressed_now: f64,
    report: PoolReport,
}

impl PoolVerifier {
    /// A verifier for a shot of `scene`, before its strike.
    ///
    /// # Errors
    /// The scene does not set up (the message says why).
    pub fn new(scene: &PoolScene) -> Result<PoolVerifier, String> {
        let shot = scene.shot().map_err(|e| e.to_string())?;
        let names = scene.names();
        let s = &scene.pool.shot;
        let cue = names
            .iter()
            .position(|n| *n == s.ball)
            .ok_or("no struck ball")?;
        let balls = scene
            .pool
            .balls
            .iter()
            .map(|b| Stored {
                ball: ClothBall {
                    pos: Vector(b.pos),
                    vel: Vector::ZERO,
                    spin: Vector::ZERO,
                },
                state: ClothState::Stationary,
                time: 0.0,
                pocketed: false,
            })
            .collect();
        Ok(PoolVerifier {
            table: shot.table().clone(),
            params: *shot.params(),
            cue,
            strike: CueStrike {
                speed: s.speed,
                phi: s.phi,
                theta: s.theta,
                a: s.a,
                b: s.b,
            },
            balls,
            time: 0.0,
            index: 0,
            struck: false,
            speed_floor: 0.0,
            energy: 0.0,
            pressed_now: 0.0,
            report: PoolReport::default(),
        })
    }

    fn fail(&self, time: f64, what: String) -> Violation {
        Violation {
            index: self.index,
            time,
            what,
        }
    }

    /// Checks the next record.
    ///
    /// # Errors
    /// The first rule the record (or the stretch before it) breaks.
    pub fn check(&mut self, rec: &PoolRecord) -> Result<(), Violation> {
        let t = rec.time();
        if t < self.time {
            return Err(self.fail(t, format!("time goes back from {}", self.time)));
        }
        match *rec {
            PoolRecord::Strike { ball, after, .. } => self.check_strike(t, ball, &after)?,
            PoolRecord::End(_) => {
                self.check_stretch(t, None)?;
                return Ok(());
            }
            PoolRecord::Event {
                event,
                after,
                after_b,
            } => {
                if !self.struck {
                    return Err(self.fail(t, "an event before the strike".into()));
                }
                self.check_stretch(t, Some(&event.kind))?;
                self.check_event(t, &event.kind, &after, after_b.as_ref())?;
                self.report.events += 1;
            }
        }
        self.time = t;
        let e = self.energy_at(t);
        // Han's cushion model as pooltool applies it can add energy (it drops the vertical
        // velocity change and may stop the contact point's slip); its outcome is checked
        // against the model instead.
        let bounced = matches!(
            rec,
            PoolRecord::Event { event, .. }
                if matches!(event.kind, ShotEventKind::Cushion { .. } | ShotEventKind::Jaw { .. })
        );
        let allowed = self.energy + std::mem::take(&mut self.pressed_now);
        if !bounced && e > allowed * (1.0 + CLOSE) + 1e-15 && self.struck && self.index > 0 {
            return Err(self.fail(
                t,
                format!("the balls' energy grew from {} J to {e} J", self.energy),
            ));
        }
        self.energy = e;
        if matches!(rec, PoolRecord::Strike { .. }) {
            self.report.energy_start = e;
        }
        self.index += 1;
        Ok(())
    }

    /// The totals, once every record is checked; `end` is the time the shot stopped at.
    ///
    /// # Errors
    /// A ball still due an event before `end`.
    pub fn finish(mut self, end: f64) -> Result<PoolReport, Violation> {
        if end > self.time {
            self.check_stretch(end, None)?;
        }
        self.report.energy_end = self.energy_at(end.max(self.time));
        self.report.still = self
            .balls
            .iter()
            .all(|b| b.pocketed || b.state == ClothState::Stationary);
        Ok(self.report)
    }

    fn check_strike(&mut self, t: f64, ball: usize, after: &BallAfter) -> Result<(), Violation> {
        if self.struck || self.index != 0 || t != 0.0 {
            return Err(self.fail(t, "the strike is not the first record, at t = 0".into()));
        }
        if ball != self.cue {
            return Err(self.fail(t, format!("the cue strikes ball {ball}, not {}", self.cue)));
        }
        let p = &self.params;
        let (vel, spin) = self
            .strike
            .launch(p.mass, p.radius(), p.cue_mass, p.throttle_english)
            .ok_or_else(|| self.fail(t, "the cue misses".into()))?;
        let b = &self.balls[ball];
        if after.ball.pos != b.ball.pos
            || !close2(after.ball.vel, vel)
            || !close3(after.ball.spin, spin)
            || after.state != ClothState::Sliding
        {
            return Err(self.fail(
                t,
                format!(
                    "the struck ball leaves as {:?}, the strike gives v {vel:?}, ω {spin:?}, sliding",
                    after
                ),
            ));
        }
        self.set(ball, after, t);
        self.struck = true;
        self.speed_floor = 1e-6 * after.ball.vel.norm();
        Ok(())
    }

    /// Ball `i` at `t`, from its last record.
    fn at(&self, i: usize, t: f64) -> ClothBall {
        let b = &self.balls[i];
        if b.pocketed {
            return b.ball;
        }
        self.params.cloth.evolve(&b.ball, b.state, t - b.time)
    }

    fn set(&mut self, i: usize, after: &BallAfter, t: f64) {
        self.balls[i].ball = after.ball;
        self.balls[i].state = after.state;
        self.balls[i].time = t;
    }

    fn energy_at(&self, t: f64) -> f64 {
        let p = &self.params;
        let inertia = 0.4 * p.mass * p.radius() * p.radius();
        (0..self.balls.len())
            .filter(|&i| !self.balls[i].pocketed)
            .map(|i| {
                let b = self.at(i, t);
                0.5 * p.mass * b.vel.norm_sq() + 0.5 * inertia * b.spin.norm_sq()
            })
            .sum()
    }

    /// The stretch from the last record to `t`: no state change due, no overlap, no pocket
    /// entered, except what the record `kind` at `t` is.
    fn check_stretch(&mut self, t: f64, kind: Option<&ShotEventKind>) -> Result<(), Violation> {
        let r = self.params.radius();
        let t0 = self.time;
        let span = t - t0;
        let n = self.balls.len();
        // Each moving ball's parabola from t0.
        let mut paths = Vec::with_capacity(n);
        for i in 0..n {
            let b = self.balls[i];
            if b.pocketed {
                paths.push(None);
                continue;
            }
            if let Some((dt, _)) = self.params.cloth.transition(&b.ball, b.state) {
                let due = b.time + dt;
                let this =
                    matches!(kind, Some(ShotEventKind::Transition { ball, .. }) if *ball == i);
                if due < t && !this {
                    return Err(self.fail(
                        t,
                        format!(
                            "ball {i}'s {:?} state ended at {due} with no record",
                            b.state
                        ),
                    ));
                }
            }
            let now = self.at(i, t0);
            let acc = self.params.cloth.acceleration(&b.ball, b.state);
            paths.push(Some((now.pos, now.vel, acc)));
        }
        let overlap = |gap: f64, sigma: f64| (sigma - gap) / sigma;
        // How far a relative motion can take a pair in the stretch (with room for rounding):
        // pairs further apart than that and their contact distance need no closer look.
        let reach = |v: Vector<2>, a: Vector<2>| {
            (v.norm() * span + 0.5 * a.norm() * span * span) * (1.0 + 1e-9)
        };
        let far = |gap: f64, reach: f64, sigma: f64| gap - reach > sigma * (1.0 + 1e-9);
        for i in 0..n {
            let Some((p, v, a)) = paths[i] else { continue };
            let own = reach(v, a);
            for (j, q) in paths.iter().enumerate().skip(i + 1) {
                let Some((pj, vj, aj)) = *q else { continue };
                if far((pj - p).norm(), reach(vj - v, aj - a), 2.0 * r) {
                    continue;
                }
                let d = least_distance(pj - p, vj - v, aj - a, span);
                let o = overlap(d, 2.0 * r);
                note(&mut self.report, self.index, o, t, || {
                    format!("balls {i} and {j} overlap")
                })?;
            }
            for (k, jaw) in self.table.jaws.iter().enumerate() {
                if far((p - jaw.center).norm(), own, r + jaw.radius) {
                    continue;
                }
                let d = least_distance(p - jaw.center, v, a, span);
                let o = overlap(d, r + jaw.radius);
                note(&mut self.report, self.index, o, t, || {
                    format!("ball {i} passes into jaw {k}")
                })?;
            }
            for (k, c) in self.table.cushions.iter().enumerate() {
                if far((p - c.p1).dot(c.normal()).abs(), own, r) {
                    continue;
                }
                let d = least_distance_to_segment(p, v, a, span, c.p1, c.p2);
                let o = overlap(d, r);
                note(&mut self.report, self.index, o, t, || {
                    format!("ball {i} passes into cushion {k}")
                })?;
            }
            let dropping = match kind {
                Some(ShotEventKind::Pocket { ball, .. }) => *ball == i,
                _ => false,
            };
            for (k, pocket) in self.table.pockets.iter().enumerate() {
                if far((p - pocket.center).norm(), own, pocket.radius) {
                    continue;
                }
                let d = least_distance(p - pocket.center, v, a, span);
                if !dropping && d < pocket.radius * (1.0 - OVERLAP) {
                    return Err(self.fail(
                        t,
                        format!("ball {i} entered pocket {k} with no record (centre {d} m from its centre)"),
                    ));
                }
            }
        }
        Ok(())
    }

    fn check_event(
        &mut self,
        t: f64,
        kind: &ShotEventKind,
        after: &BallAfter,
        after_b: Option<&BallAfter>,
    ) -> Result<(), Violation> {
        let r = self.params.radius();
        let single = |s: &Self, i: usize| -> Result<ClothBall, Violation> {
            if s.balls[i].pocketed {
                return Err(s.fail(t, format!("ball {i} is in a pocket")));
            }
            let b = s.at(i, t);
            if !close2(after.ball.pos, b.pos) {
                return Err(s.fail(
                    t,
                    format!(
                        "ball {i} recorded at {:?}, its motion puts it at {:?}",
                        after.ball.pos, b.pos
                    ),
                ));
            }
            Ok(b)
        };
        match *kind {
            ShotEventKind::Transition { ball, from, to } => {
                let b = single(self, ball)?;
                let s = self.balls[ball];
                if s.state != from {
                    return Err(self.fail(t, format!("ball {ball} is {:?}, not {from:?}", s.state)));
                }
                let (dt, next) = self
                    .params
                    .cloth
                    .transition(&s.ball, s.state)
                    .ok_or_else(|| self.fail(t, format!("ball {ball}'s state does not end")))?;
                if !close(s.time + dt, t, 1.0) || next != to || after.state != to {
                    return Err(self.fail(
                        t,
                        format!(
                            "ball {ball}'s {from:?} state ends at {} into {next:?}, recorded at {t} into {to:?}",
                            s.time + dt
                        ),
                    ));
                }
                let settled = crate::motion::cloth::settle(b, to);
                if !close2(after.ball.vel, settled.vel) || !close3(after.ball.spin, settled.spin) {
                    return Err(self.fail(
                        t,
                        format!("ball {ball} changes its motion at a state change"),
                    ));
                }
                self.set(ball, after, t);
                self.report.transitions += 1;
            }
            ShotEventKind::Balls { a, b } => {
                let after_b = after_b.ok_or_else(|| self.fail(t, "no second ball".into()))?;
                let (ba, bb) = (self.at(a, t), self.at(b, t));
                if self.balls[a].pocketed || self.balls[b].pocketed {
                    return Err(self.fail(t, format!("ball {a} or {b} is in a pocket")));
                }
                let d = bb.pos - ba.pos;
                if !close(d.norm(), 2.0 * r, 2.0 * r) {
                    return Err(self.fail(
                        t,
                        format!(
                            "balls {a} and {b} meet {} m apart, not {}",
                            d.norm(),
                            2.0 * r
                        ),
                    ));
                }
                if !close2(after.ball.pos, ba.pos) || !close2(after_b.ball.pos, bb.pos) {
                    return Err(self.fail(t, format!("balls {a} and {b} recorded elsewhere")));
                }
                let n = d * (1.0 / d.norm());
                let approach = (bb.vel - ba.vel).dot(n);
                let scale = ba.vel.norm()
                    + bb.vel.norm()
                    + after.ball.vel.norm()
                    + after_b.ball.vel.norm()
                    + self.speed_floor;
                // Not approaching (to rounding): pressed together, where a shot stops.
                if approach > CLOSE * scale {
                    return Err(self.fail(
                        t,
                        format!("balls {a} and {b} meet moving apart at {approach} m/s"),
                    ));
                }
                let (na, nb) = (after.ball, after_b.ball);
                let momentum = (na.vel + nb.vel) - (ba.vel + bb.vel);
                // (Up to the rounding-level speeds a collision sets to rest.)
                if momentum.norm() > CLOSE * scale + 2.0 * rounding_floor(0.0) {
                    return Err(self.fail(t, format!("balls {a} and {b}: momentum changes")));
                }
                // The model's outcome, then the push that parts balls pressed together.
                let p = &self.params;
                let (mut ea, mut eb) = match p.ball_ball {
                    BallBallModel::FrictionlessElastic => exchange(&ba, &bb),
                    BallBallModel::FrictionalInelastic {
                        restitution,
                        friction,
                    } => frictional(&ba, &bb, r, restitution, &friction),
                };
                rest_if_rounding(&mut ea, r);
                rest_if_rounding(&mut eb, r);
                let added =
                    part_pressed(&mut ea, &mut eb, &p.cloth, p.contact_time).map(|e| p.mass * e);
                let tang = |v: Vector<2>| v - n * v.dot(n);
                let kept = match p.ball_ball {
                    // Frictionless: tangential velocities and spins kept, whatever the push.
                    BallBallModel::FrictionlessElastic => {
                        let rest = CLOSE * scale + 2.0 * rounding_floor(0.0);
                        (tang(na.vel) - tang(ba.vel)).norm() <= rest
                            && (tang(nb.vel) - tang(bb.vel)).norm() <= rest
                            && close3(na.spin, ba.spin)
                            && close3(nb.spin, bb.spin)
                    }
                    BallBallModel::FrictionalInelastic { .. } => true,
                };
                let out = (nb.vel - na.vel).dot(n);
                let expected = (eb.vel - ea.vel).dot(n);
                if !kept
                    || (out - expected).abs() > CLOSE * scale
                    || !close2(na.vel, ea.vel)
                    || !close2(nb.vel, eb.vel)
                    || !close3(na.spin, ea.spin)
                    || !close3(nb.spin, eb.spin)
                {
                    return Err(self.fail(
                        t,
                        format!(
                            "balls {a} and {b} part at {out} m/s with v {:?}, {:?}; the model gives {expected} m/s, v {:?}, {:?}",
                            na.vel, nb.vel, ea.vel, eb.vel
                        ),
                    ));
                }
                if let Some(added) = added {
                    self.report.pressings += 1;
                    self.report.pressing_energy += added;
                    self.pressed_now += added;
                }
                if after.state != ClothState::Sliding || after_b.state != ClothState::Sliding {
                    return Err(self.fail(t, "balls leave a collision sliding".into()));
                }
                self.set(a, after, t);
                self.set(b, after_b, t);
                self.report.ball_ball += 1;
            }
            ShotEventKind::Cushion { ball, cushion } => {
                let b = single(self, ball)?;
                let c = &self.table.cushions[cushion];
                let nrm = c.normal();
                let dist = (b.pos - c.p1).dot(nrm);
                let along = c.p2 - c.p1;
                let s = (b.pos - c.p1).dot(along) / along.norm_sq();
                if !close(dist.abs(), r, r) || !(-CLOSE..=1.0 + CLOSE).contains(&s) {
                    return Err(self.fail(
                        t,
                        format!("ball {ball} is {} m from cushion {cushion}'s line (foot at {s}), not touching it", dist.abs()),
                    ));
                }
                let toward = nrm * (-dist.signum());
                self.bounce(t, ball, &b, toward, c.height, after)?;
            }
            ShotEventKind::Jaw { ball, jaw } => {
                let b = single(self, ball)?;
                let j = &self.table.jaws[jaw];
                let d = j.center - b.pos;
                if !close(d.norm(), r + j.radius, r) {
                    return Err(self.fail(
                        t,
                        format!(
                            "ball {ball} is {} m from jaw {jaw}'s centre, not touching it",
                            d.norm()
                        ),
                    ));
                }
                let height = j.height;
                self.bounce(t, ball, &b, d * (1.0 / d.norm()), height, after)?;
            }
            ShotEventKind::Pocket { ball, pocket } => {
                if self.balls[ball].pocketed {
                    return Err(self.fail(t, format!("ball {ball} is pocketed twice")));
                }
                let b = self.at(ball, t);
                let k = &self.table.pockets[pocket];
                let d = (b.pos - k.center).norm();
                if !close(d, k.radius, k.radius) {
                    return Err(self.fail(
                        t,
                        format!("ball {ball} drops into pocket {pocket} {d} m from its centre, not at its edge"),
                    ));
                }
                if after.ball.pos != k.center
                    || after.ball.vel != Vector::ZERO
                    || after.ball.spin != Vector::ZERO
                    || after.state != ClothState::Stationary
                {
                    return Err(self.fail(
                        t,
                        format!("pocketed ball {ball} does not rest at the pocket's centre"),
                    ));
                }
                self.set(ball, after, t);
                self.balls[ball].pocketed = true;
                self.report.pocketed += 1;
            }
        }
        Ok(())
    }

    /// Ball `i`, `b` just before it meets a cushion or jaw in direction `toward` (a unit
    /// vector from its centre to the contact) whose nose is `height` above the cloth, leaves
    /// as `after`: it was approaching, it leaves moving away, sliding, as Han's model says.
    fn bounce(
        &mut self,
        t: f64,
        i: usize,
        b: &ClothBall,
        toward: Vector<2>,
        height: f64,
        after: &BallAfter,
    ) -> Result<(), Violation> {
        let (han, added) = bounce_as_played(b, toward, height, &self.params);
        if !close2(after.ball.vel, han.vel) || !close3(after.ball.spin, han.spin) {
            return Err(self.fail(
                t,
                format!(
                    "ball {i} leaves the cushion with v {:?}, ω {:?}; Han's model gives v {:?}, ω {:?}",
                    after.ball.vel, after.ball.spin, han.vel, han.spin
                ),
            ));
        }
        let scale = b.vel.norm() + after.ball.vel.norm() + self.speed_floor;
        if b.vel.dot(toward) < -CLOSE * scale {
            return Err(self.fail(t, format!("ball {i} meets a cushion moving away from it")));
        }
        if after.ball.vel.dot(toward) > CLOSE * scale || after.state != ClothState::Sliding {
            return Err(self.fail(
                t,
                format!(
                    "ball {i} does not leave the cushion (velocity {:?})",
                    after.ball.vel
                ),
            ));
        }
        if let Some(added) = added {
            self.report.pressings += 1;
            self.report.pressing_energy += added;
        }
        self.set(i, after, t);
        self.report.cushion += 1;
        Ok(())
    }
}

/// Keeps the largest overlap `o`; one beyond the tolerance is a violation, `what` happened.
fn note(
    report: &mut PoolReport,
    index: u64,
    o: f64,
    time: f64,
    what: impl Fn() -> String,
) -> Result<(), Violation> {
    report.max_overlap = report.max_overlap.max(o);
    if o > OVERLAP {
        return Err(Violation {
            index,
            time,
            what: format!("{} by {o:e} of the contact distance", what()),
        });
    }
    Ok(())
}

fn close(x: f64, y: f64, scale: f64) -> bool {
    (x - y).abs() <= CLOSE * (scale.abs() + x.abs().max(y.abs()) * 1e-3)
}

fn close2(x: Vector<2>, y: Vector<2>) -> bool {
    (x - y).norm() <= CLOSE * (1e-3 + x.norm().max(y.norm()))
}

fn close3(x: Vector<3>, y: Vector<3>) -> bool {
    (x - y).norm() <= CLOSE * (1e-3 + x.norm().max(y.norm()))
}

/// The value at `x` of the polynomial with coefficients `c` (constant first).
fn poly(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &k| acc * x + k)
}

/// The real roots of `c0 + c1 x + c2 x²` in `[lo, hi]`.
fn quadratic_roots(c0: f64, c1: f64, c2: f64, lo: f64, hi: f64) -> Vec<f64> {
    let mut out = Vec::new();
    if c2 == 0.0 {
        if c1 != 0.0 {
            out.push(-c0 / c1);
        }
    } else {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc >= 0.0 {
            let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
            if q != 0.0 {
                out.push(q / c2);
                out.push(c0 / q);
            } else {
                out.push(0.0);
            }
        }
    }
    out.retain(|x| x.is_finite() && (lo..=hi).contains(x));
    out
}

/// The roots in `[0, span]` of the cubic `c` (constant first): the interval split where the
/// cubic turns, each piece with a sign change bisected to adjacent floats.
fn cubic_roots(c: [f64; 4], span: f64) -> Vec<f64> {
    let mut cuts = vec![0.0];
    cuts.extend(quadratic_roots(c[1], 2.0 * c[2], 3.0 * c[3], 0.0, span));
    cuts.push(span);
    cuts.sort_by(f64::total_cmp);
    let mut out = Vec::new();
    for w in cuts.windows(2) {
        let (mut lo, mut hi) = (w[0], w[1]);
        let (flo, fhi) = (poly(&c, lo), poly(&c, hi));
        if flo == 0.0 {
            out.push(lo);
            continue;
        }
        if flo.signum() == fhi.signum() {
            continue;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if poly(&c, mid).signum() == flo.signum() {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        out.push(lo);
        out.push(hi);
    }
    out
}

/// The least length over `τ ∈ [0, span]` of `q(τ) = p + v·τ + ½·a·τ²`, metres.
fn least_distance(p: Vector<2>, v: Vector<2>, a: Vector<2>, span: f64) -> f64 {
    let at = |tau: f64| (p + v * tau + a * (0.5 * tau * tau)).norm();
    // d/dτ |q|²/2 = q·q′, a cubic.
    let c = [
        p.dot(v),
        v.norm_sq() + p.dot(a),
        1.5 * v.dot(a),
        0.5 * a.norm_sq(),
    ];
    let mut best = at(0.0).min(at(span));
    for tau in cubic_roots(c, span) {
        best = best.min(at(tau));
    }
    best
}

/// The least distance over `τ ∈ [0, span]` from `p + v·τ + ½·a·τ²` to the line through `p1`
/// and `p2`, at times when the foot of the perpendicular lies on the segment (infinite if it
/// never does).
fn least_distance_to_segment(
    p: Vector<2>,
    v: Vector<2>,
    a: Vector<2>,
    span: f64,
    p1: Vector<2>,
    p2: Vector<2>,
) -> f64 {
    let along = p2 - p1;
    let len2 = along.norm_sq();
    let n = Vector([-along[1], along[0]]) * (1.0 / len2.sqrt());
    let d = [(p - p1).dot(n), v.dot(n), 0.5 * a.dot(n)];
    let s = [
        (p - p1).dot(along) / len2,
        v.dot(along) / len2,
        0.5 * a.dot(along) / len2,
    ];
    let mut times = vec![0.0, span];
    if d[2] != 0.0 {
        let vertex = -d[1] / (2.0 * d[2]);
        if (0.0..=span).contains(&vertex) {
            times.push(vertex);
        }
    }
    times.extend(quadratic_roots(d[0], d[1], d[2], 0.0, span));
    let ends: Vec<f64> = [0.0, 1.0]
        .iter()
        .flat_map(|&k| quadratic_roots(s[0] - k, s[1], s[2], 0.0, span))
        .collect();
    let mut best = f64::INFINITY;
    for &tau in times.iter().chain(&ends) {
        let on = poly(&s, tau);
        let at_end = ends.contains(&tau);
        if at_end || (0.0..=1.0).contains(&on) {
            best = best.min(poly(&d, tau).abs());
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn least_distance_finds_the_closest_approach_inside_a_stretch() {
        // Passing the origin at distance 0.5 at τ = 2, decelerating.
        let p = Vector([-2.0, 0.5]);
        let v = Vector([1.0, 0.0]);
        let d = least_distance(p, v, Vector::ZERO, 5.0);
        assert!((d - 0.5).abs() < 1e-12, "{d}");
        assert!((least_distance(p, v, Vector::ZERO, 1.0) - (1.25f64).sqrt()).abs() < 1e-12);
        // Stopping short: v = 1 − 0.25 τ stops at τ = 4 having gone 2.
        let d = least_distance(Vector([-3.0, 0.0]), v, Vector([-0.25, 0.0]), 4.0);
        assert!((d - 1.0).abs() < 1e-12, "{d}");
    }

    #[test]
    fn the_distance_to_a_segment_counts_only_where_its_foot_is_on_it() {
        let (p1, p2) = (Vector([0.0, 0.0]), Vector([1.0, 0.0]));
        // Passing over the segment's middle, 0.2 above it at the lowest.
        let p = Vector([0.5, 1.0]);
        let d = least_distance_to_segment(p, Vector([0.0, -0.8]), Vector([0.0, 0.4]), 4.0, p1, p2);
        assert!((d - 0.2).abs() < 1e-12, "{d}");
        // Passing beyond its end: never over it.
        let d = least_distance_to_segment(
            Vector([2.0, 1.0]),
            Vector([0.0, -1.0]),
            Vector::ZERO,
            3.0,
            p1,
            p2,
        );
        assert!(d.is_infinite());
    }
}
