//! The coefficient of restitution of each collision, as the simulation chooses it (see
//! [`crate::World::pair_restitution`]): a body's own or the scene's, the mean of the two for
//! a pair, and 1 under the TC model when either body collided less than `tc` before.
//!
//! The replay keeps the bodies' last collision times itself, from the records, and compares
//! them with the same `f64` operations as the simulation, so it chooses the same coefficient
//! bit for bit.

use crate::scene::Scene;

/// Each body's restitution and, under the TC model, its last collision time.
#[derive(Clone, Debug)]
pub(super) struct Restitutions {
    /// `settings.restitution`.
    scene: f64,
    /// Per body, its own restitution or the scene's; empty while no body has its own.
    own: Vec<f64>,
    /// `settings.tc`, seconds, if the scene sets it.
    tc: Option<f64>,
    /// Per body, when it last collided (`−∞`: not yet); empty without `tc`.
    last: Vec<f64>,
}

impl Restitutions {
    /// The rules of `scene` at its start: no body has collided yet.
    pub(super) fn new<const D: usize>(scene: &Scene<D>) -> Self {
        let e = scene.settings.restitution;
        let own = if scene.bodies.iter().any(|b| b.restitution.is_some()) {
            scene
                .bodies
                .iter()
                .map(|b| b.restitution.unwrap_or(e))
                .collect()
        } else {
            Vec::new()
        };
        Restitutions {
            scene: e,
            own,
            tc: scene.settings.tc,
            last: match scene.settings.tc {
                Some(_) => vec![f64::NEG_INFINITY; scene.bodies.len()],
                None => Vec::new(),
            },
        }
    }

    /// True under the TC model when body `i` collided less than `tc` before `t`.
    fn within_tc(&self, i: usize, t: f64) -> bool {
        self.tc
            .is_some_and(|tc| t - self.last.get(i).copied().unwrap_or(f64::NEG_INFINITY) < tc)
    }

    /// Body `i`'s own restitution, or the scene's.
    fn of(&self, i: usize) -> f64 {
        self.own.get(i).copied().unwrap_or(self.scene)
    }

    /// The restitution of a collision of bodies `i` and `j` at `t`.
    pub(super) fn pair(&self, i: usize, j: usize, t: f64) -> f64 {
        if self.within_tc(i, t) || self.within_tc(j, t) {
            1.0
        } else if self.own.is_empty() {
            self.scene
        } else {
            0.5 * (self.of(i) + self.of(j))
        }
    }

    /// The restitution of a collision of body `i` with a wall at `t`.
    pub(super) fn wall(&self, i: usize, t: f64) -> f64 {
        if self.within_tc(i, t) {
            1.0
        } else {
            self.of(i)
        }
    }

    /// Body `i` collided at `t` (with a body or a wall).
    pub(super) fn note(&mut self, i: usize, t: f64) {
        if let Some(last) = self.last.get_mut(i) {
            *last = t;
        }
    }

    /// A body with restitution `restitution` (`None`: the scene's) was added in slot `i`; it
    /// has not collided yet.
    pub(super) fn add(&mut self, i: usize, restitution: Option<f64>) {
        if restitution.is_some() || !self.own.is_empty() {
            let n = self.own.len().max(i + 1);
            self.own.resize(n, self.scene);
            self.own[i] = restitution.unwrap_or(self.scene);
        }
        if self.tc.is_some() {
            let n = self.last.len().max(i + 1);
            self.last.resize(n, f64::NEG_INFINITY);
            self.last[i] = f64::NEG_INFINITY;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Vector;
    use crate::scene::BodySpec;

    fn scene(own: [Option<f64>; 2], tc: Option<f64>) -> Scene<2> {
        let mut s = Scene::<2> {
            bodies: vec![
                BodySpec::new(Vector([0.0, 0.0]), Vector::ZERO, 0.5),
                BodySpec::new(Vector([2.0, 0.0]), Vector::ZERO, 0.5),
            ],
            ..Scene::default()
        };
        s.settings.restitution = 0.8;
        s.settings.tc = tc;
        for (b, e) in s.bodies.iter_mut().zip(own) {
            b.restitution = e;
        }
        s
    }

    #[test]
    fn pairs_take_the_mean_and_walls_the_body_own() {
        let r = Restitutions::new(&scene([Some(0.5), None], None));
        assert_eq!(r.pair(0, 1, 0.0), 0.5 * (0.5 + 0.8));
        assert_eq!(r.wall(0, 0.0), 0.5);
        assert_eq!(r.wall(1, 0.0), 0.8);
        let r = Restitutions::new(&scene([None, None], None));
        assert_eq!((r.pair(0, 1, 0.0), r.wall(1, 0.0)), (0.8, 0.8));
    }

    #[test]
    fn the_tc_model_makes_collisions_soon_after_another_elastic() {
        let mut r = Restitutions::new(&scene([Some(0.5), None], Some(0.1)));
        assert_eq!(r.pair(0, 1, 1.0), 0.65);
        r.note(1, 1.0);
        assert_eq!(r.pair(0, 1, 1.05), 1.0);
        assert_eq!(r.wall(0, 1.05), 0.5);
        assert_eq!(r.wall(1, 1.05), 1.0);
        assert_eq!(r.wall(1, 1.1), 0.8);
        // An added body has not collided, and has its own restitution.
        r.add(3, Some(0.25));
        assert_eq!(r.wall(3, 1.05), 0.25);
        assert_eq!(r.wall(2, 1.05), 0.8);
    }
}
