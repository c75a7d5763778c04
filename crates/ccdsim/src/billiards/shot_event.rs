//! What happens at an event of a shot, and the order events at the same time come in.

use std::cmp::Ordering;

use super::table::Table;
use crate::motion::ClothState;

/// What happens at an event. Balls, cushions, jaws and pockets are indices into the shot's
/// balls and the table's lists.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShotEventKind {
    /// A ball's motion state ends and the next begins.
    Transition {
        /// The ball.
        ball: usize,
        /// The state that ends.
        from: ClothState,
        /// The state that begins.
        to: ClothState,
    },
    /// Two balls meet (`a < b`).
    Balls {
        /// The lower-numbered ball.
        a: usize,
        /// The higher-numbered ball.
        b: usize,
    },
    /// A ball meets a straight cushion.
    Cushion {
        /// The ball.
        ball: usize,
        /// The cushion.
        cushion: usize,
    },
    /// A ball meets a jaw.
    Jaw {
        /// The ball.
        ball: usize,
        /// The jaw.
        jaw: usize,
    },
    /// A ball drops into a pocket.
    Pocket {
        /// The ball.
        ball: usize,
        /// The pocket.
        pocket: usize,
    },
}

impl ShotEventKind {
    /// pooltool's rank for events at the same time: lower first.
    pub(crate) fn rank(&self) -> (u8, usize, usize) {
        match *self {
            ShotEventKind::Transition { ball, .. } => (0, ball, 0),
            ShotEventKind::Balls { a, b } => (1, a, b),
            ShotEventKind::Cushion { ball, cushion } => (2, ball, cushion),
            ShotEventKind::Jaw { ball, jaw } => (3, ball, jaw),
            ShotEventKind::Pocket { ball, pocket } => (4, ball, pocket),
        }
    }
}

impl ShotEventKind {
    /// The event's type and agents as pooltool names them: "ball_ball", "ball_linear_cushion",
    /// "ball_circular_cushion", "ball_pocket", or a transition such as "sliding_rolling";
    /// agents by `ball_names` and the table's ids.
    #[must_use]
    pub fn names(&self, table: &Table, ball_names: &[String]) -> (String, Vec<String>) {
        let ball = |i: usize| ball_names[i].clone();
        match *self {
            ShotEventKind::Transition { ball: i, from, to } => {
                (format!("{}_{}", from.name(), to.name()), vec![ball(i)])
            }
            ShotEventKind::Balls { a, b } => ("ball_ball".into(), vec![ball(a), ball(b)]),
            ShotEventKind::Cushion { ball: i, cushion } => (
                "ball_linear_cushion".into(),
                vec![ball(i), table.cushions[cushion].id.clone()],
            ),
            ShotEventKind::Jaw { ball: i, jaw } => (
                "ball_circular_cushion".into(),
                vec![ball(i), table.jaws[jaw].id.clone()],
            ),
            ShotEventKind::Pocket { ball: i, pocket } => (
                "ball_pocket".into(),
                vec![ball(i), table.pockets[pocket].id.clone()],
            ),
        }
    }
}

/// An event of a shot: what happens and when (seconds from the strike).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShotEvent {
    /// Time, seconds.
    pub time: f64,
    /// What happens.
    pub kind: ShotEventKind,
}

/// Whether `a` comes before `b`: earlier, or at the same time and ranked lower.
pub(crate) fn earlier(a: &ShotEvent, b: &ShotEvent) -> bool {
    match a.time.total_cmp(&b.time) {
        Ordering::Less => true,
        Ordering::Greater => false,
        Ordering::Equal => a.kind.rank() < b.kind.rank(),
    }
}

/// The earlier of two events, if any ([`earlier`]).
pub(crate) fn first(a: Option<ShotEvent>, b: Option<ShotEvent>) -> Option<ShotEvent> {
    match (a, b) {
        (Some(x), Some(y)) => Some(if earlier(&y, &x) { y } else { x }),
        (x, None) => x,
        (None, y) => y,
    }
}
