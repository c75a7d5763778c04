//! Edits a program makes to a running simulation, as the records a steered run file keeps
//! ([`EventKind::Edit`], see [`crate::Simulation::record_edits`]).
//!
//! A record names its body in `a` and what the edit was in `b`:
//!
//! | `b` | edit | first slot | second slot |
//! |---|---|---|---|
//! | 0 | new position or velocity | position at `t`, velocity from then on | zero |
//! | 1 | a body added | its position and velocity | position: radius, mass (∞: kinematic); velocity: filter, restitution |
//! | 2 | the added body's id (follows `b` = 1) | zero | position: the id |
//! | 3 | a body removed | where it stopped, zero velocity | zero |
//! | 4 | new collision group and mask | position at `t`, velocity | velocity: filter |
//! | 5 | a moving wall's new velocity (`a` names the moving wall) | its displacement from the scene's geometry at `t`, its velocity from then on | zero |
//!
//! A filter is written as the `f64` whose bits are `group << 32 | mask`, an id as the `f64`
//! whose bits are the id, a body's own restitution as itself and "the scene's" as NaN: every
//! value comes back bit for bit. A run file with records of `b` ≠ 0 is format version 9, and
//! one with records of `b` = 5 (moving walls, see [`crate::world::time_of_impact`]) version 10.

use crate::collision_filter::CollisionFilter;
use crate::event::{Collision, Event, EventKind};
use crate::geom::Vector;

pub(crate) const MOTION: u32 = 0;
pub(crate) const ADD: u32 = 1;
pub(crate) const ADD_ID: u32 = 2;
pub(crate) const REMOVE: u32 = 3;
pub(crate) const FILTER: u32 = 4;
pub(crate) const WALL_MOTION: u32 = 5;
/// How many edit codes there are (`b` is below it).
pub const EDIT_CODES: u32 = 6;
/// How many edit codes a run file of version 9 may hold (no moving walls).
pub const EDIT_CODES_SLOTS: u32 = 5;

/// What a program did to a body, as recorded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Edit<const D: usize> {
    /// Body `body` was moved or given a new velocity: from `time` on it is at `pos` moving at
    /// `vel`.
    Motion {
        /// The body.
        body: usize,
        /// Its position at the edit, metres.
        pos: Vector<D>,
        /// Its velocity from then on, m/s.
        vel: Vector<D>,
    },
    /// A body was added in slot `body`.
    Add {
        /// Its slot.
        body: usize,
        /// Its user id.
        id: u64,
        /// Its position, metres.
        pos: Vector<D>,
        /// Its velocity, m/s.
        vel: Vector<D>,
        /// Its radius, metres.
        radius: f64,
        /// Its mass, kilograms; infinite for a kinematic body.
        mass: f64,
        /// Its collision group and mask.
        filter: CollisionFilter,
        /// Its own restitution, if it has one.
        restitution: Option<f64>,
    },
    /// The body of slot `body` was removed where it was, `pos`; the slot is vacant.
    Remove {
        /// The slot.
        body: usize,
        /// Where the body stopped, metres.
        pos: Vector<D>,
    },
    /// Body `body` got a new collision group and mask; its state was stored anew.
    Filter {
        /// The body.
        body: usize,
        /// Its position at the edit, metres.
        pos: Vector<D>,
        /// Its velocity then, m/s.
        vel: Vector<D>,
        /// The new filter.
        filter: CollisionFilter,
    },
    /// Moving wall `wall` (see [`crate::world::time_of_impact`]) got a new velocity: from `time` on it
    /// is displaced by `offset` from the scene's geometry and translates at `vel`.
    WallMotion {
        /// The moving wall's index among the moving walls.
        wall: usize,
        /// Its displacement at the edit, metres.
        offset: Vector<D>,
        /// Its velocity from then on, m/s.
        vel: Vector<D>,
    },
}

fn filter_bits(f: CollisionFilter) -> f64 {
    f64::from_bits(u64::from(f.group) << 32 | u64::from(f.mask))
}

fn filter_of(x: f64) -> CollisionFilter {
    let b = x.to_bits();
    CollisionFilter {
        group: (b >> 32) as u32,
        mask: b as u32,
    }
}

/// A vector whose first components are `xs` and the rest zero.
fn packed<const D: usize>(xs: &[f64]) -> Vector<D> {
    let mut v = Vector::ZERO;
    for (k, &x) in xs.iter().enumerate().take(D) {
        v[k] = x;
    }
    v
}

fn record<const D: usize>(
    t: f64,
    body: usize,
    code: u32,
    slots: [[Vector<D>; 2]; 2],
) -> Collision<D> {
    Collision {
        event: Event {
            time: t,
            kind: EventKind::Edit,
            a: body as u32,
            b: code,
        },
        pos: [slots[0][0], slots[1][0]],
        vel: [slots[0][1], slots[1][1]],
        rests: [false; 2],
        pivots: [false; 2],
    }
}

impl<const D: usize> Edit<D> {
    /// What the edit names in its records' `a`: the body edited, or for
    /// [`Edit::WallMotion`] the moving wall.
    #[must_use]
    pub fn subject(&self) -> usize {
        match *self {
            Edit::Motion { body, .. }
            | Edit::Add { body, .. }
            | Edit::Remove { body, .. }
            | Edit::Filter { body, .. } => body,
            Edit::WallMotion { wall, .. } => wall,
        }
    }

    /// True when record `c` gives a moving wall a new velocity (its `a` names no body).
    #[must_use]
    pub fn moves_a_wall(c: &Collision<D>) -> bool {
        c.event.kind == EventKind::Edit && c.event.b == WALL_MOTION
    }

    /// The records of this edit made at time `t`, seconds: two for an added body, one
    /// otherwise.
    #[must_use]
    pub fn records(&self, t: f64) -> Vec<Collision<D>> {
        let z = Vector::ZERO;
        match *self {
            Edit::Motion { body, pos, vel } => vec![record(t, body, MOTION, [[pos, vel], [z, z]])],
            Edit::Add {
                body,
                id,
                pos,
                vel,
                radius,
                mass,
                filter,
                restitution,
            } => vec![
                record(
                    t,
                    body,
                    ADD,
                    [
                        [pos, vel],
                        [
                            packed(&[radius, mass]),
                            packed(&[filter_bits(filter), restitution.unwrap_or(f64::NAN)]),
                        ],
                    ],
                ),
                record(
                    t,
                    body,
                    ADD_ID,
                    [[z, z], [packed(&[f64::from_bits(id)]), z]],
                ),
            ],
            Edit::Remove { body, pos } => vec![record(t, body, REMOVE, [[pos, z], [z, z]])],
            Edit::Filter {
                body,
                pos,
                vel,
                filter,
            } => vec![record(
                t,
                body,
                FILTER,
                [[pos, vel], [z, packed(&[filter_bits(filter)])]],
            )],
            Edit::WallMotion { wall, offset, vel } => {
                vec![record(t, wall, WALL_MOTION, [[offset, vel], [z, z]])]
            }
        }
    }

    /// True when record `c` is an edit of a kind this build knows.
    #[must_use]
    pub fn is_known(c: &Collision<D>) -> bool {
        c.event.kind == EventKind::Edit && c.event.b < EDIT_CODES
    }

    /// True when record `c` starts an added body's pair of records (its id follows).
    #[must_use]
    pub fn starts_add(c: &Collision<D>) -> bool {
        c.event.kind == EventKind::Edit && c.event.b == ADD
    }

    /// The edit of record `c` (with `next`, the record after it, for an added body), or why
    /// it is not one.
    pub fn decode(c: &Collision<D>, next: Option<&Collision<D>>) -> Result<Self, String> {
        if c.event.kind != EventKind::Edit {
            return Err("not an edit record".into());
        }
        let body = c.event.a as usize;
        let (pos, vel) = (c.pos[0], c.vel[0]);
        match c.event.b {
            MOTION => Ok(Edit::Motion { body, pos, vel }),
            ADD => {
                let next = next.ok_or("an added body's record without its id record")?;
                if next.event.kind != EventKind::Edit
                    || next.event.b != ADD_ID
                    || next.event.a != c.event.a
                    || next.event.time.to_bits() != c.event.time.to_bits()
                {
                    return Err(format!(
                        "an added body's record (body {body}) is not followed by its id record"
                    ));
                }
                let e = c.vel[1][1];
                Ok(Edit::Add {
                    body,
                    id: next.pos[1][0].to_bits(),
                    pos,
                    vel,
                    radius: c.pos[1][0],
                    mass: c.pos[1][1],
                    filter: filter_of(c.vel[1][0]),
                    restitution: (!e.is_nan()).then_some(e),
                })
            }
            ADD_ID => Err(format!("an id record (body {body}) without its added body")),
            REMOVE => Ok(Edit::Remove { body, pos }),
            FILTER => Ok(Edit::Filter {
                body,
                pos,
                vel,
                filter: filter_of(c.vel[1][0]),
            }),
            WALL_MOTION => Ok(Edit::WallMotion {
                wall: body,
                offset: pos,
                vel,
            }),
            code => Err(format!("unknown edit code {code}")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trip<const D: usize>(e: Edit<D>) {
        let rs = e.records(1.25);
        let back = Edit::decode(&rs[0], rs.get(1)).unwrap();
        assert_eq!(format!("{back:?}"), format!("{e:?}"));
        assert!(rs
            .iter()
            .all(|r| r.event.time == 1.25 && r.event.a as usize == e.subject()));
    }

    #[test]
    fn every_edit_comes_back_bit_for_bit() {
        let (p, v) = (Vector([1.5, -2.0]), Vector([0.1, 3.0]));
        round_trip(Edit::<2>::Motion {
            body: 3,
            pos: p,
            vel: v,
        });
        round_trip(Edit::<2>::Remove { body: 7, pos: p });
        round_trip(Edit::<2>::WallMotion {
            wall: 2,
            offset: p,
            vel: v,
        });
        round_trip(Edit::<2>::Filter {
            body: 1,
            pos: p,
            vel: v,
            filter: CollisionFilter {
                group: 0x8000_0001,
                mask: 0xFFFF_FFFE,
            },
        });
        for (mass, restitution) in [(2.5, Some(0.25)), (f64::INFINITY, None)] {
            round_trip(Edit::<2>::Add {
                body: 9,
                id: u64::MAX - 3,
                pos: p,
                vel: v,
                radius: 0.5,
                mass,
                filter: CollisionFilter::DEFAULT,
                restitution,
            });
        }
        round_trip(Edit::<3>::Add {
            body: 2,
            id: 42,
            pos: Vector([1.0, 2.0, 3.0]),
            vel: Vector([0.0, 0.0, -1.0]),
            radius: 0.1,
            mass: 1.0,
            filter: CollisionFilter::NONE,
            restitution: Some(1.0),
        });
    }

    #[test]
    fn an_add_without_its_id_is_refused() {
        let e = Edit::<2>::Add {
            body: 0,
            id: 5,
            pos: Vector::ZERO,
            vel: Vector::ZERO,
            radius: 1.0,
            mass: 1.0,
            filter: CollisionFilter::DEFAULT,
            restitution: None,
        };
        let rs = e.records(0.0);
        assert!(Edit::decode(&rs[0], None).is_err());
        assert!(Edit::decode(&rs[1], None).is_err());
        let other = Edit::<2>::Motion {
            body: 0,
            pos: Vector::ZERO,
            vel: Vector::ZERO,
        }
        .records(0.0);
        assert!(Edit::decode(&rs[0], Some(&other[0])).is_err());
    }
}
