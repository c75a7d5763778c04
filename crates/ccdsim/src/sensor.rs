//! Sensors: regions that report exactly when bodies start and stop overlapping them, and
//! never touch them.
//!
//! A sensor is a ball (a disc in 2D) fixed in space. Body `i` of radius `r` overlaps sensor
//! `k` (centre `c`, radius `R`) while its centre is within `R + r` of `c`. Between events a
//! body's path is a line or, under gravity, a parabola, so the overlap starts and ends at
//! roots of a quadratic or a quartic: [`crate::contact::accelerated_contact::first_contact_accelerating`] and
//! [`crate::contact::accelerated_contact::first_exit_accelerating`] give them with the same guarantees as the collisions' (no
//! root skipped; each narrowed to adjacent floats), and with growing radii under gravity their
//! growing forms (the same module's `_growing` functions).
//! A body that starts inside a sensor, or is
//! put there by an edit, enters it at that instant.
//!
//! In a periodic box of sides `L` a sensor is seen through its images: a body overlaps it
//! while its centre is within `R + r` of `c + k·L` for some integer vector `k`. Scenes keep
//! the centre in the box and `2·(R + r) < L` on every axis, `r` the largest body radius
//! ([`sensor_fits_box`]; [`crate::Simulation::add_body`] checks bodies added later), so that
//! a body overlaps at most one image at a time. A box exit moves a body by a period without
//! moving it in space: what it overlaps is kept, and a body crossing a face inside a sensor
//! that straddles it neither leaves nor enters there. With growing radii
//! ([`crate::contact::growth`]) the contact distance `R + r(t)` is linear in time and the overlap
//! starts and ends at roots of a quadratic, as for a pair of growing balls. Both are the
//! functions of [`crate::contact::sensor_crossing`], which also follows a body from image to image
//! should growth make it overlap two at once.
//!
//! Sensors change no motion, so they are not seen by the finders: the simulation keeps, per
//! body, its next sensor event in a priority queue, computed when the body's motion changes
//! (O(sensors) per change) or when it crosses a sensor, and reports the events in time order
//! as its clock passes them ([`crate::sim::SensorTracker`]). They are the same whatever the finder, since the motions are.

use crate::geom::Vector;
use serde::{Deserialize, Serialize};

/// A sensor region as written in a scene (`sensors[]`): a ball fixed in space.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sensor<const D: usize> {
    /// Centre, metres.
    pub center: Vector<D>,
    /// Radius, metres; strictly positive.
    pub radius: f64,
}

/// Refuses a sensor of radius `sensor_radius` (metres) in a periodic box of sides `size`
/// alongside bodies of radius up to `body_radius` (metres; `body` names it in the error),
/// unless `2·(R + r) < L` on every axis: then a body overlaps at most one image of the sensor
/// at a time, and the sensor's images do not overlap one another, so the sensor is one ball
/// seen through the box. The error says why, naming the side.
pub fn sensor_fits_box<const D: usize>(
    sensor_radius: f64,
    body_radius: f64,
    body: &str,
    size: &Vector<D>,
) -> Result<(), String> {
    let reach = sensor_radius + body_radius;
    match (0..D).find(|&d| 2.0 * reach >= size[d]) {
        None => Ok(()),
        Some(d) => Err(format!(
            "the sensor's radius {sensor_radius} plus {body} {body_radius} must be less than \
             half the periodic box's side {} (axis {d}), or a body could overlap two images \
             of the sensor at once",
            size[d]
        )),
    }
}

/// Whether a body started or stopped overlapping a sensor.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SensorChange {
    /// The body started to overlap the sensor.
    Enter,
    /// The body stopped overlapping the sensor.
    Leave,
}

/// A body entering or leaving a sensor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorEvent {
    /// When, seconds.
    pub time: f64,
    /// The body's index.
    pub body: usize,
    /// The sensor's index in the scene's `sensors`.
    pub sensor: usize,
    /// Entered or left.
    pub change: SensorChange,
}
