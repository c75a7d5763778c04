//! The billiard break: a 15-ball triangle rack and a cue ball shot into it.

use super::box_walls;
use crate::geom::Vector;
use crate::scene::{BodySpec, Scene};

/// Parameters of [`rack`]; defaults are a 9-foot pool table and regulation balls.
#[derive(Clone, Debug, PartialEq)]
pub struct RackConfig {
    /// Table length and width (playing surface), metres.
    pub table: [f64; 2],
    /// Ball radius, metres.
    pub radius: f64,
    /// Ball mass, kilograms.
    pub mass: f64,
    /// Cue ball speed, metres per second.
    pub speed: f64,
    /// Sideways offset of the cue ball's aim at the apex ball, metres (0 = full hit).
    pub offset: f64,
    /// Gap between neighbouring rack balls, relative to the diameter, so that rounding never
    /// makes them overlap.
    pub gap: f64,
}

impl Default for RackConfig {
    fn default() -> Self {
        RackConfig {
            table: [2.54, 1.27],
            radius: 0.028575,
            mass: 0.17,
            speed: 10.0,
            offset: 0.002,
            gap: 1e-9,
        }
    }
}

/// The break: 15 balls racked in a triangle on the foot spot (ids 1–15), the cue ball (id 0)
/// on the head string moving towards the apex, four cushions.
#[must_use]
pub fn rack(cfg: &RackConfig) -> Scene<2> {
    let [len, wid] = cfg.table;
    let d = 2.0 * cfg.radius * (1.0 + cfg.gap);
    let row_dx = d * 3f64.sqrt() / 2.0;
    let foot = Vector([0.75 * len, 0.5 * wid]);
    let head = Vector([0.25 * len, 0.5 * wid + cfg.offset]);
    let ball = |p, v, id| BodySpec {
        id: Some(id),
        mass: Some(cfg.mass),
        ..BodySpec::new(p, v, cfg.radius)
    };
    let mut bodies = vec![ball(head, Vector([cfg.speed, 0.0]), 0)];
    let mut id = 1;
    for row in 0..5 {
        for k in 0..=row {
            let p = Vector([
                foot[0] + row as f64 * row_dx,
                foot[1] + (k as f64 - row as f64 / 2.0) * d,
            ]);
            bodies.push(ball(p, Vector([0.0, 0.0]), id));
            id += 1;
        }
    }
    Scene {
        bodies,
        walls: box_walls(Vector([len, wid])),
        ..Scene::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rack_is_valid() {
        let s = rack(&RackConfig::default());
        assert_eq!(s.bodies.len(), 16);
        s.validate().unwrap();
    }
}
