//! Scene files: bodies, walls and settings; JSON parsing and validation with typed errors.
//!
//! A scene is what a run starts from. [`AnyScene::from_json`] parses a file of either
//! dimension; [`Scene::validate`] checks everything the simulator relies on.

pub mod arrival;

use crate::collision_filter::CollisionFilter;
use crate::contact::lees_edwards::ShearedBox;
use crate::geom::{ball_volume, Vector};
use crate::histogram::Histogram;
use crate::motion::Gravity;
use crate::motion::Growth;
use crate::motion::MovingWall;
use crate::resolution::{resolution_error, resolves, ulp, RESOLUTION_LIMIT};
use crate::sensor::{sensor_fits_box, Sensor};
use crate::thermostat::Thermostat;
use crate::wall::{inside_even_odd, table_edges};
pub use crate::wall::{wall_clearance, Wall};
use arrival::Arrival;
use serde::{Deserialize, Serialize};
use std::fmt;

/// One body as written in a scene: a circle (2D) or sphere (3D).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec<const D: usize> {
    /// Optional user id, unique within the scene; defaults to the body's index.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<u64>,
    /// Centre position at the scene's start time, metres.
    pub pos: Vector<D>,
    /// Velocity, metres per second.
    pub vel: Vector<D>,
    /// Radius, metres; strictly positive.
    pub radius: f64,
    /// Mass, kilograms; strictly positive. Defaults to unit density (the ball's area or volume).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    /// This body's coefficient of restitution in `[0, 1]`; defaults to
    /// `settings.restitution`. A pair collides with the mean of its two bodies' values, a
    /// body and a wall with the body's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restitution: Option<f64>,
    /// A kinematic body: infinite mass, moved only by its velocity (which a program sets, say
    /// every frame), never by collisions or gravity. It collides with ordinary (dynamic)
    /// bodies, not with walls or other kinematic bodies.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub kinematic: bool,
    /// The collision groups this body belongs to, a bit set; defaults to group 1 (bit 0).
    /// See [`crate::collision_filter`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<u32>,
    /// The collision groups this body collides with, a bit set; defaults to all. Two bodies
    /// collide only when each one's `group` meets the other's `mask`; walls always collide.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mask: Option<u32>,
    /// Angular velocity at the start, radians per second: one number in 2D (about the axis
    /// out of the plane), three components in 3D; defaults to zero. Only collisions of rough
    /// bodies change it ([`Settings::tangential_restitution`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spin: Option<crate::motion::Spin>,
    /// Moment-of-inertia factor `q` in `(0, 1]`: the body's moment of inertia is `q·m·r²`;
    /// defaults to a uniform body's (1/2 for a disc, 2/5 for a sphere).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia: Option<f64>,
    /// This body's tangential restitution `β` in `[−1, 1]`; defaults to
    /// `settings.tangential_restitution`. A pair collides with the mean of its two bodies'
    /// values, a body and a wall with the body's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangential_restitution: Option<f64>,
}

impl<const D: usize> BodySpec<D> {
    /// A body with unit-density mass and no explicit id.
    #[must_use]
    pub fn new(pos: Vector<D>, vel: Vector<D>, radius: f64) -> Self {
        BodySpec {
            id: None,
            pos,
            vel,
            radius,
            mass: None,
            restitution: None,
            kinematic: false,
            group: None,
            mask: None,
            spin: None,
            inertia: None,
            tangential_restitution: None,
        }
    }

    /// True when the body sets a spin, an inertia factor or a tangential restitution.
    #[must_use]
    pub fn is_rotational(&self) -> bool {
        self.spin.is_some() || self.inertia.is_some() || self.tangential_restitution.is_some()
    }

    /// This body's collision filter (its `group` and `mask`, defaults filled in).
    #[must_use]
    pub fn filter(&self) -> CollisionFilter {
        CollisionFilter::of(self.group, self.mask)
    }

    /// Checks this body's own fields as body `i` of a scene: finite position and velocity, a
    /// positive radius and mass (none for a kinematic body), a restitution in `[0, 1]`.
    /// Errors name `bodies[i]`.
    pub fn check_fields(&self, i: usize) -> Result<(), SceneError> {
        let f = |name: &str| format!("bodies[{i}].{name}");
        if !self.pos.is_finite() {
            return Err(SceneError::NonFinite(f("pos")));
        }
        if !self.vel.is_finite() {
            return Err(SceneError::NonFinite(f("vel")));
        }
        if !self.radius.is_finite() {
            return Err(SceneError::NonFinite(f("radius")));
        }
        if self.radius <= 0.0 {
            return Err(SceneError::NonPositive(f("radius")));
        }
        check_magnitudes(|| f("pos"), &self.pos.0)?;
        check_magnitudes(|| f("vel"), &self.vel.0)?;
        check_size(|| f("radius"), self.radius)?;
        if let Some(e) = self.restitution {
            if !e.is_finite() {
                return Err(SceneError::NonFinite(f("restitution")));
            }
            if !(0.0..=1.0).contains(&e) {
                return Err(SceneError::Field {
                    path: f("restitution"),
                    message: format!("{e} is outside [0, 1]"),
                });
            }
        }
        if let Some(beta) = self.tangential_restitution {
            check_tangential_restitution(&f("tangential_restitution"), beta)?;
        }
        if let Some(q) = self.inertia {
            if !q.is_finite() {
                return Err(SceneError::NonFinite(f("inertia")));
            }
            if !(q > 0.0 && q <= 1.0) {
                return Err(SceneError::Field {
                    path: f("inertia"),
                    message: format!(
                        "{q} is outside (0, 1]: the moment of inertia q·m·r² of a body of \
                         radius r is at most m·r²"
                    ),
                });
            }
        }
        if let Some(spin) = self.spin {
            if !spin.fits::<D>() {
                return Err(SceneError::Field {
                    path: f("spin"),
                    message: if D == 2 {
                        "a disc's spin is one number (about the axis out of the plane)".into()
                    } else {
                        "a sphere's spin is an array of three numbers".into()
                    },
                });
            }
            if !spin.vector().is_finite() {
                return Err(SceneError::NonFinite(f("spin")));
            }
            check_magnitudes(|| f("spin"), &spin.vector().0)?;
        }
        if self.kinematic {
            let refuse = |why: &str| {
                Err(SceneError::Unsupported {
                    field: f("kinematic"),
                    why: why.into(),
                })
            };
            if self.mass.is_some() {
                return refuse("a kinematic body has infinite mass: drop its `mass`");
            }
            return Ok(());
        }
        let m = self.effective_mass();
        if !m.is_finite() {
            return Err(SceneError::NonFinite(f("mass")));
        }
        if m <= 0.0 {
            return Err(SceneError::NonPositive(f("mass")));
        }
        check_size(|| f("mass"), m)?;
        Ok(())
    }

    /// True when the body sets a collision group or mask.
    #[must_use]
    pub fn is_filtered(&self) -> bool {
        self.group.is_some() || self.mask.is_some()
    }

    /// The mass to simulate with: infinite for a kinematic body, else the given one, or unit
    /// density.
    #[must_use]
    pub fn effective_mass(&self) -> f64 {
        if self.kinematic {
            return f64::INFINITY;
        }
        self.mass.unwrap_or_else(|| ball_volume::<D>(self.radius))
    }
}

/// Global settings of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Settings {
    /// Coefficient of restitution in `[0, 1]` for every collision; 1 is elastic.
    #[serde(default = "one")]
    pub restitution: f64,
    /// The Andersen thermostat (random velocity resets at a temperature), if any; see
    /// [`crate::thermostat`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thermostat: Option<Thermostat>,
    /// Growing radii (Lubachevsky–Stillinger compression), if any; see [`crate::contact::growth`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub growth: Option<Growth>,
    /// Uniform gravity, if any: the acceleration of every body, metres per second squared,
    /// one component per dimension; see [`crate::contact::gravity`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gravity: Option<Gravity>,
    /// The TC model of inelastic collapse (Luding & McNamara), seconds: a collision of a
    /// body that already collided less than `tc` before is elastic, whatever the
    /// restitution. Keeps inelastic bodies from collapsing into infinitely many collisions
    /// in finite time (a ball bouncing on a floor under gravity, a dense granular gas).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tc: Option<f64>,
    /// Resting contacts under gravity, metres per second: a body that leaves a collision with
    /// a static plane it is pressed on by gravity at a normal speed of at most `rest_speed`
    /// comes to rest on it and slides along it (see [`crate::contact::resting`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rest_speed: Option<f64>,
    /// Tangential restitution `β` in `[−1, 1]` of every collision (rough spheres): a
    /// collision turns the tangential velocity of the contact points `g_t` into `−β·g_t`,
    /// trading translational for rotational energy; −1 is smooth (spins never change), 1
    /// perfectly rough. Setting it, or any body's `spin`, `inertia` or
    /// `tangential_restitution`, makes the world keep each body's angular velocity.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangential_restitution: Option<f64>,
    /// Lees–Edwards shear rate `γ̇ = ∂v_x/∂y`, 1/s, of a periodic scene: the copies of the
    /// box stacked along y slide past each other along x at `γ̇ L_y` (see
    /// [`crate::contact::lees_edwards`]). Velocities stay lab-frame ones: bodies start with the
    /// velocities the scene gives them (add the flow `γ̇ (y − L_y/2)` to start in it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_rate: Option<f64>,
}

fn one() -> f64 {
    1.0
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            restitution: 1.0,
            thermostat: None,
            growth: None,
            gravity: None,
            tc: None,
            rest_speed: None,
            tangential_restitution: None,
            shear_rate: None,
        }
    }
}

/// The rotational fields of a scene's bodies, defaults filled in ([`Scene::body_rotations`]).
#[derive(Clone, Debug, PartialEq)]
pub struct BodyRotations {
    /// Each body's angular velocity at the start, radians per second (a disc's about the
    /// third axis).
    pub spins: Vec<Vector<3>>,
    /// Each body's moment-of-inertia factor `q`.
    pub inertia: Vec<f64>,
    /// Each body's tangential restitution `β`.
    pub tangential: Vec<f64>,
    /// The inertia factor of a body that sets none: a uniform disc's or sphere's.
    pub default_inertia: f64,
    /// The tangential restitution of a body that sets none: the scene's, or −1 (smooth).
    pub default_tangential: f64,
}

/// A complete scene in `D` dimensions.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene<const D: usize> {
    /// Global settings.
    #[serde(default)]
    pub settings: Settings,
    /// Simulated time at which the bodies' positions hold, seconds.
    #[serde(default)]
    pub start_time: f64,
    /// The bodies; a body's index in this list is its identity in events.
    pub bodies: Vec<BodySpec<D>>,
    /// The static walls; a wall's index in this list names it in events.
    #[serde(default)]
    pub walls: Vec<Wall<D>>,
    /// Periodic boundaries: the sides `[L₁, …, L_D]` of the box `[0, L₁) × … × [0, L_D)` whose
    /// opposite faces are identified (see [`crate::contact::periodic`]). A periodic scene has no walls,
    /// every body starts inside the box, and every side exceeds twice the largest contact
    /// distance (`4 · r_max`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub periodic: Option<Vector<D>>,
    /// Sensor regions: balls fixed in space that report bodies entering and leaving them,
    /// and never touch them (see [`crate::sensor`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sensors: Vec<Sensor<D>>,
    /// Walls that translate (a paddle, a piston; see [`crate::world::time_of_impact`]): moving wall `k`
    /// is wall `walls.len() + k` in events. Not in periodic scenes, nor with growing radii.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub moving_walls: Vec<MovingWall<D>>,
    /// Bodies that enter while the scene runs, each at its time (see [`crate::scene::arrival`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub arrivals: Vec<Arrival<D>>,
    /// Bins that count where the bodies are at the end of a run (see
    /// [`crate::histogram`]); they change nothing in the run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub histogram: Option<Histogram>,
}

impl<const D: usize> Default for Scene<D> {
    fn default() -> Self {
        Scene {
            settings: Settings::default(),
            start_time: 0.0,
            bodies: Vec::new(),
            walls: Vec::new(),
            periodic: None,
            sensors: Vec::new(),
            moving_walls: Vec::new(),
            arrivals: Vec::new(),
            histogram: None,
        }
    }
}

/// Why a scene was refused. Every message names the field or the body.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    /// The text is not JSON.
    #[error("malformed JSON at line {line}, column {column}: {message}")]
    Json {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What the parser said.
        message: String,
    },
    /// A field is missing, of the wrong type or unknown.
    #[error("field `{path}`: {message}")]
    Field {
        /// Path to the field, e.g. `bodies[3].radius`.
        path: String,
        /// What is wrong with it.
        message: String,
    },
    /// `dim` is missing or not 2 or 3, or the scene does not have the dimension asked for.
    #[error("field `dim`: {0}")]
    Dimension(String),
    /// A number is NaN or infinite.
    #[error("field `{0}`: not a finite number")]
    NonFinite(String),
    /// A radius or mass is zero or negative.
    #[error("field `{0}`: must be greater than zero")]
    NonPositive(String),
    /// The restitution is outside `[0, 1]`.
    #[error("field `settings.restitution`: {0} is outside [0, 1]")]
    Restitution(f64),
    /// Two bodies share an id.
    #[error("bodies {first} and {second}: duplicate id {id}")]
    DuplicateId {
        /// The id.
        id: u64,
        /// Index of its first holder.
        first: usize,
        /// Index of its second holder.
        second: usize,
    },
    /// Two bodies overlap at the start.
    #[error("{a} and {b} overlap by {depth:e} m")]
    Overlap {
        /// First body.
        a: BodyName,
        /// Second body.
        b: BodyName,
        /// Overlap depth, metres.
        depth: f64,
    },
    /// A wall has zero length or a zero normal.
    #[error("field `walls[{wall}]`: degenerate wall ({why})")]
    DegenerateWall {
        /// Wall index.
        wall: usize,
        /// What is degenerate.
        why: &'static str,
    },
    /// A body overlaps a wall, or is behind a plane.
    #[error("{body} crosses wall {wall}")]
    CrossesWall {
        /// The body.
        body: BodyName,
        /// Wall index.
        wall: usize,
    },
    /// The walls form a closed table (a closed polygon of segments around every other
    /// segment, in a scene without planes) and a body is outside it, or inside one of the
    /// polygons within it (by the even–odd rule).
    #[error("{body} is outside the table formed by the walls")]
    OutsideTable {
        /// The body.
        body: BodyName,
    },
    /// The periodic box is invalid, or a body or wall does not fit a periodic scene.
    #[error("field `{field}`: {why}")]
    Periodic {
        /// The offending field, e.g. `periodic` or `bodies[3].pos`.
        field: String,
        /// What is wrong.
        why: String,
    },
    /// `f64` cannot resolve a body's contacts: its start time or coordinates are so large
    /// that their rounding is a sizeable part of its radius (see [`crate::resolution`]).
    #[error("{body}: {why}")]
    Resolution {
        /// The body.
        body: BodyName,
        /// What is too coarse, with the numbers and a remedy.
        why: String,
    },
    /// A setting cannot be combined with the rest of the scene.
    #[error("field `{field}`: {why}")]
    Unsupported {
        /// The offending field, e.g. `settings.gravity`.
        field: String,
        /// Why, and what to do instead.
        why: String,
    },
    /// Reading the file failed.
    #[error("{0}")]
    Io(String),
}

/// A body named by index and id, for messages: `body 3 (id 7)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BodyName {
    /// Index in the scene's body list.
    pub index: usize,
    /// The body's id.
    pub id: u64,
}

impl fmt::Display for BodyName {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        if self.index as u64 == self.id {
            write!(f, "body {}", self.index)
        } else {
            write!(f, "body {} (id {})", self.index, self.id)
        }
    }
}

impl<const D: usize> Scene<D> {
    /// The id of body `i`: its explicit id or its index.
    #[must_use]
    pub fn id_of(&self, i: usize) -> u64 {
        self.bodies[i].id.unwrap_or(i as u64)
    }

    fn name(&self, i: usize) -> BodyName {
        BodyName {
            index: i,
            id: self.id_of(i),
        }
    }

    /// Serialises the scene as JSON with its `dim` field.
    #[must_use]
    pub fn to_json(&self) -> String {
        serde_json::to_string(&SceneOut {
            dim: D,
            scene: self,
        })
        .expect("scenes always serialise")
    }

    /// Serialises the scene as indented JSON with its `dim` field.
    #[must_use]
    pub fn to_json_pretty(&self) -> String {
        serde_json::to_string_pretty(&SceneOut {
            dim: D,
            scene: self,
        })
        .expect("scenes always serialise")
    }

    /// Parses a scene of dimension `D` from JSON text (with a `dim` field equal to `D`).
    pub fn from_json(text: &str) -> Result<Self, SceneError> {
        let dim = read_dim(text)?;
        if dim != D {
            return Err(SceneError::Dimension(format!(
                "the scene is {dim}D, {D}D was expected"
            )));
        }
        let scene = parse_typed::<D>(text)?;
        scene.validate()?;
        Ok(scene)
    }

    /// Checks every rule a run relies on: finite numbers, positive radii and masses,
    /// restitution in `[0, 1]`, unique ids, non-degenerate walls, no body overlapping another
    /// body or a wall, (2D) every body inside the closed table the walls form, if any, and for
    /// periodic scenes: no walls, sides finite and above `4 · r_max`, bodies and sensors'
    /// centres inside the box, every sensor's `2 · (R + r_max)` below every side, overlaps
    /// measured between nearest images.
    pub fn validate(&self) -> Result<(), SceneError> {
        let r = self.settings.restitution;
        if !r.is_finite() {
            return Err(SceneError::NonFinite("settings.restitution".into()));
        }
        if !(0.0..=1.0).contains(&r) {
            return Err(SceneError::Restitution(r));
        }
        if let Some(th) = &self.settings.thermostat {
            for (value, field) in [
                (th.temperature, "settings.thermostat.temperature"),
                (th.rate, "settings.thermostat.rate"),
            ] {
                if !value.is_finite() {
                    return Err(SceneError::NonFinite(field.into()));
                }
                if value <= 0.0 {
                    return Err(SceneError::NonPositive(field.into()));
                }
                check_magnitudes(|| field.into(), &[value])?;
            }
        }
        if let Some(g) = &self.settings.growth {
            if !g.rate.is_finite() {
                return Err(SceneError::NonFinite("settings.growth.rate".into()));
            }
            if g.rate <= 0.0 {
                return Err(SceneError::NonPositive("settings.growth.rate".into()));
            }
            check_magnitudes(|| "settings.growth.rate".into(), &[g.rate])?;
        }
        self.validate_gravity()?;
        self.validate_shear()?;
        if let Some(tc) = self.settings.tc {
            if !tc.is_finite() {
                return Err(SceneError::NonFinite("settings.tc".into()));
            }
            if tc <= 0.0 {
                return Err(SceneError::NonPositive("settings.tc".into()));
            }
        }
        self.validate_rest_speed()?;
        if let Some(beta) = self.settings.tangential_restitution {
            check_tangential_restitution("settings.tangential_restitution", beta)?;
        }
        if self.is_rotational() && self.settings.rest_speed.is_some() {
            return Err(SceneError::Unsupported {
                field: "settings.rest_speed".into(),
                why: "bodies resting on walls do not spin: leave rest_speed out of a scene \
                      of rough bodies (tangential_restitution, spin, inertia)"
                    .into(),
            });
        }
        if !self.start_time.is_finite() {
            return Err(SceneError::NonFinite("start_time".into()));
        }
        check_magnitudes(|| "start_time".into(), &[self.start_time])?;
        for (w, wall) in self.walls.iter().enumerate() {
            validate_wall(w, wall)?;
        }
        for (i, b) in self.bodies.iter().enumerate() {
            b.check_fields(i)?;
        }
        self.validate_moving_walls()?;
        self.validate_resolution()?;
        if let Some((first, second)) = self.first_duplicate_id() {
            return Err(SceneError::DuplicateId {
                id: self.id_of(second),
                first,
                second,
            });
        }
        if let Some(size) = self.periodic {
            self.validate_periodic(size)?;
        }
        self.validate_sensors()?;
        if let Some((a, b, depth)) =
            first_overlap(&self.bodies, self.periodic, self.shear(), self.start_time)
        {
            return Err(SceneError::Overlap {
                a: self.name(a),
                b: self.name(b),
                depth,
            });
        }
        for (i, b) in self.bodies.iter().enumerate() {
            for (w, wall) in self.walls.iter().enumerate() {
                if wall_clearance(wall, b.pos) < b.radius {
                    return Err(SceneError::CrossesWall {
                        body: self.name(i),
                        wall: w,
                    });
                }
            }
        }
        if D == 2 {
            let loops = table_edges(&self.walls);
            if !loops.is_empty() {
                for (i, b) in self.bodies.iter().enumerate() {
                    if !inside_even_odd(&loops, b.pos[0], b.pos[1]) {
                        return Err(SceneError::OutsideTable { body: self.name(i) });
                    }
                }
            }
        }
        self.validate_arrivals()?;
        if let Some(h) = &self.histogram {
            h.check(D).map_err(|message| SceneError::Field {
                path: "histogram".into(),
                message,
            })?;
        }
        Ok(())
    }

    /// `arrivals[]`: each a valid body, entering at a finite time not before `start_time`,
    /// without rotational fields, where no wall stands (bodies are checked when it enters).
    fn validate_arrivals(&self) -> Result<(), SceneError> {
        let loops = if D == 2 {
            table_edges(&self.walls)
        } else {
            Vec::new()
        };
        for (k, a) in self.arrivals.iter().enumerate() {
            let field = |what: &str| format!("arrivals[{k}].{what}");
            if !a.time.is_finite() {
                return Err(SceneError::NonFinite(field("time")));
            }
            check_magnitudes(|| field("time"), &[a.time])?;
            let bad = |message: String| {
                Err(SceneError::Field {
                    path: format!("arrivals[{k}]"),
                    message,
                })
            };
            if a.time < self.start_time {
                return bad(format!(
                    "enters at {} s, before the scene's start_time {} s",
                    a.time, self.start_time
                ));
            }
            a.body.check_fields(k).map_err(|e| SceneError::Field {
                path: format!("arrivals[{k}].body"),
                message: e.to_string(),
            })?;
            if a.body.is_rotational() {
                return bad(
                    "an arriving body starts without spin and with the scene's inertia factor \
                     and tangential restitution: leave its spin, inertia and \
                     tangential_restitution out"
                        .into(),
                );
            }
            if let Some(w) = (0..self.walls.len())
                .find(|&w| wall_clearance(&self.walls[w], a.body.pos) < a.body.radius)
            {
                return bad(format!("the body would cross wall {w}"));
            }
            if D == 2 && !loops.is_empty() && !inside_even_odd(&loops, a.body.pos[0], a.body.pos[1])
            {
                return bad("the body would lie outside the table the walls enclose".into());
            }
            if let Some(size) = self.periodic {
                if (0..D).any(|d| !(0.0..size[d]).contains(&a.body.pos[d])) {
                    return bad("the body would lie outside the periodic box".into());
                }
            }
        }
        Ok(())
    }
}

impl<const D: usize> Scene<D> {
    /// Every body's collision filter by index (see [`crate::collision_filter`]), or an empty
    /// list when no body sets one (every pair collides).
    #[must_use]
    pub fn filters(&self) -> Vec<CollisionFilter> {
        if self.bodies.iter().any(BodySpec::is_filtered) {
            self.bodies.iter().map(BodySpec::filter).collect()
        } else {
            Vec::new()
        }
    }

    /// The acceleration of `settings.gravity` as a vector of this dimension, if the scene has
    /// gravity with the right number of components (see [`Scene::validate`]).
    #[must_use]
    pub fn gravity(&self) -> Option<Vector<D>> {
        self.settings.gravity.and_then(|g| g.vector::<D>())
    }

    /// The sheared periodic box of a scene with `settings.shear_rate` and a periodic box.
    #[must_use]
    pub fn shear(&self) -> Option<ShearedBox<D>> {
        let rate = self.settings.shear_rate?;
        self.periodic.map(|size| ShearedBox { size, rate })
    }

    /// `settings.shear_rate`: finite, on a periodic scene without growing radii or sensors.
    fn validate_shear(&self) -> Result<(), SceneError> {
        let Some(rate) = self.settings.shear_rate else {
            return Ok(());
        };
        let field = "settings.shear_rate";
        if !rate.is_finite() {
            return Err(SceneError::NonFinite(field.into()));
        }
        check_magnitudes(|| field.into(), &[rate])?;
        let unsupported = |why: &str| {
            Err(SceneError::Unsupported {
                field: field.into(),
                why: why.into(),
            })
        };
        if self.periodic.is_none() {
            return unsupported(
                "shear (Lees–Edwards boundaries) needs a periodic box: set `periodic`",
            );
        }
        if self.settings.growth.is_some() {
            return unsupported(
                "a sheared box cannot be combined with growing radii (`settings.growth`)",
            );
        }
        if !self.sensors.is_empty() {
            return unsupported("a sheared box cannot be combined with sensors");
        }
        Ok(())
    }

    /// `settings.gravity`: one finite component per dimension, and no periodic box, which it
    /// cannot be combined with.
    fn validate_gravity(&self) -> Result<(), SceneError> {
        let Some(g) = self.settings.gravity else {
            return Ok(());
        };
        let field = || "settings.gravity".to_string();
        let Some(v) = g.vector::<D>() else {
            return Err(SceneError::Field {
                path: field(),
                message: format!("has {} components, the scene is {D}D", g.components().len()),
            });
        };
        if !v.is_finite() {
            return Err(SceneError::NonFinite(field()));
        }
        check_magnitudes(field, &v.0)?;
        let unsupported = |why: &str| {
            Err(SceneError::Unsupported {
                field: field(),
                why: why.into(),
            })
        };
        if self.periodic.is_some() {
            return unsupported(
                "gravity in a periodic box is not supported (bodies would fall for ever); \
                 use walls",
            );
        }
        Ok(())
    }

    /// True when the world keeps each body's angular velocity: the scene sets
    /// `settings.tangential_restitution` or a body sets its `spin`, `inertia` or
    /// `tangential_restitution` (see [`crate::motion::spin`]).
    #[must_use]
    pub fn is_rotational(&self) -> bool {
        self.settings.tangential_restitution.is_some()
            || self.bodies.iter().any(BodySpec::is_rotational)
    }

    /// The bodies' spins, inertia factors and tangential restitutions with the defaults filled
    /// in, and the defaults a body added later takes; `None` unless the scene is rotational
    /// ([`Scene::is_rotational`]). The one reading of these fields for the world and `verify`.
    #[must_use]
    pub fn body_rotations(&self) -> Option<BodyRotations> {
        if !self.is_rotational() {
            return None;
        }
        let default_tangential = self.settings.tangential_restitution.unwrap_or(-1.0);
        let default_inertia = crate::motion::spin::default_inertia::<D>();
        Some(BodyRotations {
            spins: self
                .bodies
                .iter()
                .map(|b| b.spin.map_or(Vector::ZERO, |s| s.vector()))
                .collect(),
            inertia: self
                .bodies
                .iter()
                .map(|b| b.inertia.unwrap_or(default_inertia))
                .collect(),
            tangential: self
                .bodies
                .iter()
                .map(|b| b.tangential_restitution.unwrap_or(default_tangential))
                .collect(),
            default_inertia,
            default_tangential,
        })
    }

    /// `settings.rest_speed`: positive and finite, under gravity, with fixed radii.
    fn validate_rest_speed(&self) -> Result<(), SceneError> {
        let Some(speed) = self.settings.rest_speed else {
            return Ok(());
        };
        let field = || "settings.rest_speed".to_string();
        if !speed.is_finite() {
            return Err(SceneError::NonFinite(field()));
        }
        if speed <= 0.0 {
            return Err(SceneError::NonPositive(field()));
        }
        check_magnitudes(field, &[speed])?;
        if self.settings.gravity.is_none() {
            return Err(SceneError::Unsupported {
                field: field(),
                why: "bodies rest on walls only under gravity; set settings.gravity".into(),
            });
        }
        if self.settings.growth.is_some() {
            // A resting body whose radius grows would have to move its centre off the wall
            // at Γ·r while it slides, which the resting motion (a parabola along the wall)
            // does not model: refused rather than approximated.
            return Err(SceneError::Unsupported {
                field: field(),
                why: "bodies cannot rest on walls while their radii grow (settings.growth); \
                      leave rest_speed out and let them bounce"
                    .into(),
            });
        }
        Ok(())
    }

    /// Moving walls: finite, non-degenerate, a finite velocity; not in periodic scenes; no
    /// body crossing one at the start.
    fn validate_moving_walls(&self) -> Result<(), SceneError> {
        let first = self.walls.len();
        for (k, m) in self.moving_walls.iter().enumerate() {
            let field = format!("moving_walls[{k}]");
            let unsupported = |why: &str| {
                Err(SceneError::Unsupported {
                    field: field.clone(),
                    why: why.into(),
                })
            };
            if self.periodic.is_some() {
                return unsupported("a periodic scene has no walls, moving or not");
            }
            validate_wall(first + k, &m.wall).map_err(|e| match e {
                SceneError::NonFinite(_) => SceneError::NonFinite(field.clone()),
                SceneError::DegenerateWall { why, .. } => SceneError::Field {
                    path: field.clone(),
                    message: format!("degenerate wall ({why})"),
                },
                SceneError::Field { message, .. } => SceneError::Field {
                    path: field.clone(),
                    message,
                },
                other => other,
            })?;
            if !m.velocity.is_finite() {
                return Err(SceneError::NonFinite(format!("{field}.velocity")));
            }
            check_magnitudes(|| format!("{field}.velocity"), &m.velocity.0)?;
            for (i, b) in self.bodies.iter().enumerate() {
                if wall_clearance(&m.wall, b.pos) < b.radius {
                    return Err(SceneError::CrossesWall {
                        body: self.name(i),
                        wall: first + k,
                    });
                }
            }
        }
        Ok(())
    }

    /// Sensors: finite centres, finite positive radii; in a periodic box, centres inside the
    /// box and every sensor small enough that a body overlaps at most one of its images
    /// ([`sensor_fits_box`]).
    fn validate_sensors(&self) -> Result<(), SceneError> {
        let r_max = self.bodies.iter().map(|b| b.radius).fold(0.0, f64::max);
        for (k, s) in self.sensors.iter().enumerate() {
            let f = |field: &str| format!("sensors[{k}].{field}");
            if !s.center.is_finite() {
                return Err(SceneError::NonFinite(f("center")));
            }
            if !s.radius.is_finite() {
                return Err(SceneError::NonFinite(f("radius")));
            }
            if s.radius <= 0.0 {
                return Err(SceneError::NonPositive(f("radius")));
            }
            check_magnitudes(|| f("center"), &s.center.0)?;
            check_magnitudes(|| f("radius"), &[s.radius])?;
            let Some(size) = self.periodic else { continue };
            if (0..D).any(|d| !(0.0..size[d]).contains(&s.center[d])) {
                return Err(SceneError::Periodic {
                    field: f("center"),
                    why: format!(
                        "{:?} is outside the periodic box [0, L) (give the image inside it)",
                        s.center.0
                    ),
                });
            }
            if let Err(why) = sensor_fits_box(s.radius, r_max, "the largest body radius", &size) {
                return Err(SceneError::Periodic {
                    field: f("radius"),
                    why,
                });
            }
        }
        Ok(())
    }

    /// Every body resolved at the start time (see [`crate::resolution`]).
    fn validate_resolution(&self) -> Result<(), SceneError> {
        let t = self.start_time;
        for (i, b) in self.bodies.iter().enumerate() {
            if resolves(t, b.pos, b.vel, b.radius) {
                continue;
            }
            let limit = RESOLUTION_LIMIT * b.radius;
            let why = if resolves(0.0, b.pos, b.vel, b.radius) {
                format!(
                    "at start_time {t:e} s the clock resolves only {:.2e} s, so its position \
                     at speed {:.2e} m/s is uncertain by more than {limit:.2e} m ({RESOLUTION_LIMIT:e} \
                     of its radius): give start_time a value near 0",
                    ulp(t),
                    b.vel.norm()
                )
            } else {
                format!(
                    "its coordinates ({:.2e} m) are resolved only to {:.2e} m, more than {limit:.2e} m \
                     ({RESOLUTION_LIMIT:e} of its radius): move the origin closer or change \
                     the unit of length",
                    b.pos.0.iter().fold(0.0f64, |m, c| m.max(c.abs())),
                    resolution_error(0.0, b.pos, Vector::ZERO)
                )
            };
            return Err(SceneError::Resolution {
                body: self.name(i),
                why,
            });
        }
        Ok(())
    }

    /// The first body (in index order) whose id an earlier body already has, with that
    /// earlier body: `(first, second)`. Sorting keeps this at 16 bytes per body, so that
    /// validating a million bodies stays cheap in memory.
    fn first_duplicate_id(&self) -> Option<(usize, usize)> {
        if self.bodies.iter().all(|b| b.id.is_none()) {
            return None; // ids are the indices
        }
        let mut ids: Vec<(u64, u32)> = (0..self.bodies.len())
            .map(|i| (self.id_of(i), i as u32))
            .collect();
        ids.sort_unstable();
        // In each run of equal ids, the two earliest holders come first.
        ids.chunk_by(|a, b| a.0 == b.0)
            .filter(|run| run.len() > 1)
            .map(|run| (run[0].1 as usize, run[1].1 as usize))
            .min_by_key(|&(_, second)| second)
    }

    fn validate_periodic(&self, size: Vector<D>) -> Result<(), SceneError> {
        let bad = |field: String, why: String| Err(SceneError::Periodic { field, why });
        if !size.is_finite() || (0..D).any(|d| size[d] <= 0.0) {
            return bad(
                "periodic".into(),
                "sides must be finite and positive".into(),
            );
        }
        check_magnitudes(|| "periodic".into(), &size.0)?;
        if !self.walls.is_empty() {
            return bad("walls".into(), "a periodic scene has no walls".into());
        }
        let r_max = self.bodies.iter().map(|b| b.radius).fold(0.0, f64::max);
        if let Some(d) = (0..D).find(|&d| size[d] <= 4.0 * r_max) {
            return bad(
                "periodic".into(),
                format!(
                    "side {} must exceed twice the largest contact distance, {}",
                    size[d],
                    4.0 * r_max
                ),
            );
        }
        for (i, b) in self.bodies.iter().enumerate() {
            if (0..D).any(|d| !(0.0..size[d]).contains(&b.pos[d])) {
                return bad(
                    format!("bodies[{i}].pos"),
                    format!("{} is outside the periodic box [0, L)", self.name(i)),
                );
            }
        }
        Ok(())
    }
}

#[derive(Serialize)]
struct SceneOut<'a, const D: usize> {
    dim: usize,
    #[serde(flatten)]
    scene: &'a Scene<D>,
}

/// A scene of either dimension, as read from a file.
#[derive(Clone, Debug, PartialEq)]
pub enum AnyScene {
    /// Circles in the plane.
    D2(Scene<2>),
    /// Spheres in space.
    D3(Scene<3>),
}

impl AnyScene {
    /// Parses and validates a scene; its `dim` field (2 or 3) picks the dimension.
    pub fn from_json(text: &str) -> Result<Self, SceneError> {
        let out = match read_dim(text)? {
            2 => AnyScene::D2(parse_typed(text)?),
            3 => AnyScene::D3(parse_typed(text)?),
            d => return Err(SceneError::Dimension(format!("{d} is not 2 or 3"))),
        };
        match &out {
            AnyScene::D2(s) => s.validate()?,
            AnyScene::D3(s) => s.validate()?,
        }
        Ok(out)
    }

    /// Reads, parses and validates a scene file.
    pub fn from_file(path: &std::path::Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| SceneError::Io(format!("cannot read: {e}")))?;
        Self::from_json(&text)
    }

    /// The dimension, 2 or 3.
    #[must_use]
    pub fn dim(&self) -> usize {
        match self {
            AnyScene::D2(_) => 2,
            AnyScene::D3(_) => 3,
        }
    }

    /// Serialises as JSON with the `dim` field.
    #[must_use]
    pub fn to_json(&self) -> String {
        match self {
            AnyScene::D2(s) => s.to_json(),
            AnyScene::D3(s) => s.to_json(),
        }
    }
}

impl From<Scene<2>> for AnyScene {
    fn from(s: Scene<2>) -> Self {
        AnyScene::D2(s)
    }
}
impl From<Scene<3>> for AnyScene {
    fn from(s: Scene<3>) -> Self {
        AnyScene::D3(s)
    }
}

/// First pass: only the syntax and the `dim` field; every other value is skipped unread, so
/// that range errors are reported with their field's path by the second pass.
fn read_dim(text: &str) -> Result<usize, SceneError> {
    #[derive(Deserialize)]
    struct DimOnly {
        dim: Option<serde_json::Value>,
    }
    let probe: DimOnly = serde_json::from_str(text).map_err(|e| match e.classify() {
        serde_json::error::Category::Data => SceneError::Field {
            path: ".".into(),
            message: "a scene is a JSON object".into(),
        },
        _ => SceneError::Json {
            line: e.line(),
            column: e.column(),
            message: strip_position(&e.to_string()),
        },
    })?;
    let dim = probe
        .dim
        .ok_or_else(|| SceneError::Dimension("missing (2 or 3)".into()))?;
    match dim.as_u64() {
        Some(d) => Ok(d as usize),
        None => Err(SceneError::Dimension(format!("{dim} is not 2 or 3"))),
    }
}

/// The file form of a scene: the scene's fields plus `dim`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile<const D: usize> {
    #[allow(dead_code)]
    dim: usize,
    #[serde(default)]
    settings: Settings,
    #[serde(default)]
    start_time: f64,
    bodies: Vec<BodySpec<D>>,
    #[serde(default)]
    walls: Vec<Wall<D>>,
    #[serde(default)]
    periodic: Option<Vector<D>>,
    #[serde(default)]
    sensors: Vec<Sensor<D>>,
    #[serde(default)]
    moving_walls: Vec<MovingWall<D>>,
    #[serde(default)]
    arrivals: Vec<Arrival<D>>,
    #[serde(default)]
    histogram: Option<Histogram>,
}

fn parse_typed<const D: usize>(text: &str) -> Result<Scene<D>, SceneError> {
    let mut de = serde_json::Deserializer::from_str(text);
    let f: SceneFile<D> =
        serde_path_to_error::deserialize(&mut de).map_err(|e| SceneError::Field {
            path: e.path().to_string(),
            message: e.into_inner().to_string(),
        })?;
    Ok(Scene {
        settings: f.settings,
        start_time: f.start_time,
        bodies: f.bodies,
        walls: f.walls,
        periodic: f.periodic,
        sensors: f.sensors,
        moving_walls: f.moving_walls,
        arrivals: f.arrivals,
        histogram: f.histogram,
    })
}

fn strip_position(msg: &str) -> String {
    match msg.rfind(" at line ") {
        Some(k) => msg[..k].to_string(),
        None => msg.to_string(),
    }
}

/// The largest magnitude of a scene's numbers: every coordinate (bodies, wall points, sensor
/// centres), velocity component, radius, mass, periodic side, gravity component and rate is at
/// most `1e100` in absolute value, and `start_time` too. Why so far below `f64::MAX` (1.8e308):
/// the simulation multiplies several of them, and the products must stay finite. A squared
/// distance of two points is `D·(2e100)² ≈ 1e201`; a kinetic energy `m·v²`, `1e300`; the
/// potential energy `m·g·x`, `1e300`; the gravity quartic's coefficients (`g²`, `g·Δv`,
/// `Δp·g`), `1e200`. With `1e150` squares would stay finite but not these products; with
/// `1e308` nothing does (a segment end at `−1e308` gave an infinite length and the run the
/// time NaN). No physical scene in any unit comes near.
pub const MAX_MAGNITUDE: f64 = 1e100;

/// The smallest radius and mass: `1e-100`, so that their squares and products stay normal
/// floats (contact distances squared, `1e-200`) instead of underflowing to zero.
pub const MIN_SIZE: f64 = 1e-100;

/// A tangential restitution, finite and in `[−1, 1]`, at the field `path`.
fn check_tangential_restitution(path: &str, beta: f64) -> Result<(), SceneError> {
    if !beta.is_finite() {
        return Err(SceneError::NonFinite(path.into()));
    }
    if !(-1.0..=1.0).contains(&beta) {
        return Err(SceneError::Field {
            path: path.into(),
            message: format!("{beta} is outside [-1, 1]"),
        });
    }
    Ok(())
}

/// Refuses any of `values` beyond [`MAX_MAGNITUDE`], naming `field`.
fn check_magnitudes(field: impl FnOnce() -> String, values: &[f64]) -> Result<(), SceneError> {
    match values.iter().find(|x| x.abs() > MAX_MAGNITUDE) {
        Some(x) => Err(SceneError::Field {
            path: field(),
            message: format!(
                "{x:e} is beyond ±{MAX_MAGNITUDE:e}, the largest magnitude f64 can simulate \
                 (squares and products of a scene's numbers must stay finite)"
            ),
        }),
        None => Ok(()),
    }
}

/// Refuses a radius or mass `x` outside `[MIN_SIZE, MAX_MAGNITUDE]`, naming `field`.
fn check_size(field: impl Fn() -> String, x: f64) -> Result<(), SceneError> {
    check_magnitudes(&field, &[x])?;
    if x < MIN_SIZE {
        return Err(SceneError::Field {
            path: field(),
            message: format!(
                "{x:e} is below {MIN_SIZE:e}, the smallest f64 can simulate (its square must \
                 not underflow)"
            ),
        });
    }
    Ok(())
}

fn validate_wall<const D: usize>(w: usize, wall: &Wall<D>) -> Result<(), SceneError> {
    match wall {
        Wall::Segment { a, b } => {
            if !a.is_finite() || !b.is_finite() {
                return Err(SceneError::NonFinite(format!("walls[{w}]")));
            }
            check_magnitudes(|| format!("walls[{w}].a"), &a.0)?;
            check_magnitudes(|| format!("walls[{w}].b"), &b.0)?;
            if (*b - *a).norm_sq() == 0.0 {
                return Err(SceneError::DegenerateWall {
                    wall: w,
                    why: "its end points coincide",
                });
            }
        }
        Wall::Plane { point, normal } => {
            if !point.is_finite() || !normal.is_finite() {
                return Err(SceneError::NonFinite(format!("walls[{w}]")));
            }
            check_magnitudes(|| format!("walls[{w}].point"), &point.0)?;
            check_magnitudes(|| format!("walls[{w}].normal"), &normal.0)?;
            if normal.norm_sq() == 0.0 {
                return Err(SceneError::DegenerateWall {
                    wall: w,
                    why: "its normal is zero",
                });
            }
        }
    }
    Ok(())
}

/// The first overlapping pair `(i, j)`, `i < j`, in lexicographic order, with its depth,
/// among pairs that collide (see [`crate::collision_filter`]); in a periodic box of sides
/// `period`, distances are between nearest images, and in a sheared one (`shear`) between
/// the nearest images at time `time` (see [`crate::contact::lees_edwards`]).
fn first_overlap<const D: usize>(
    bodies: &[BodySpec<D>],
    period: Option<Vector<D>>,
    shear: Option<ShearedBox<D>>,
    time: f64,
) -> Option<(usize, usize, f64)> {
    let max_r = bodies.iter().map(|b| b.radius).fold(0.0, f64::max);
    if bodies.len() < 2 || max_r <= 0.0 {
        return None;
    }
    // Cells at least 2·r_max wide; in a periodic box they tile it and keys wrap around.
    let cells: [i64; D] = match period {
        Some(p) => std::array::from_fn(|d| ((p[d] / (2.0 * max_r)).floor() as i64).max(1)),
        None => [1; D],
    };
    let width: [f64; D] = match period {
        Some(p) => std::array::from_fn(|d| p[d] / cells[d] as f64),
        None => [2.0 * max_r; D],
    };
    let key = |p: Vector<D>| {
        let mut k = [0i64; D];
        for d in 0..D {
            k[d] = (p[d] / width[d]).floor() as i64;
            if period.is_some() {
                k[d] = k[d].rem_euclid(cells[d]);
            }
        }
        k
    };
    // Bodies sorted by cell: a cell's bodies are a run found by binary search. (A sorted
    // array takes a fraction of a hash map's memory, which matters for a million bodies.)
    let mut grid: Vec<([i64; D], u32)> = bodies
        .iter()
        .enumerate()
        .map(|(i, b)| (key(b.pos), i as u32))
        .collect();
    grid.sort_unstable();
    let cell = |k: &[i64; D]| {
        let from = grid.partition_point(|e| e.0 < *k);
        let to = from + grid[from..].partition_point(|e| e.0 == *k);
        grid[from..to].iter().map(|e| e.1)
    };
    let mut neighbours: Vec<[i64; D]> = Vec::with_capacity(27);
    for (i, bi) in bodies.iter().enumerate() {
        let k = key(bi.pos);
        neighbours.clear();
        for code in 0..3usize.pow(D as u32) {
            let mut nk = k;
            let mut c = code;
            let mut across = false;
            for (d, slot) in nk.iter_mut().enumerate() {
                *slot += (c % 3) as i64 - 1;
                across |= d == 1 && !(0..cells[1]).contains(slot);
                if period.is_some() {
                    *slot = slot.rem_euclid(cells[d]);
                }
                c /= 3;
            }
            // In a sheared box the row across a y face slides: its whole row is added below.
            if !(across && shear.is_some()) {
                neighbours.push(nk);
            }
        }
        if shear.is_some() && (k[1] == 0 || k[1] == cells[1] - 1) {
            let opposite = if k[1] == 0 { cells[1] - 1 } else { 0 };
            for x in 0..cells[0] {
                for dz in if D == 3 { -1..=1 } else { 0..=0 } {
                    let mut nk = k;
                    nk[0] = x;
                    nk[1] = opposite;
                    if D == 3 {
                        nk[D - 1] = (k[D - 1] + dz).rem_euclid(cells[D - 1]);
                    }
                    neighbours.push(nk);
                }
            }
        }
        neighbours.sort_unstable();
        neighbours.dedup();
        let mut best: Option<(usize, f64)> = None;
        for nk in &neighbours {
            for j in cell(nk) {
                let j = j as usize;
                if j <= i {
                    continue;
                }
                let bj = &bodies[j];
                if !bi.filter().collides(&bj.filter()) {
                    // Bodies that pass through each other may overlap.
                    continue;
                }
                let sum = bi.radius + bj.radius;
                let dp = bi.pos - bj.pos;
                let d = match (period, shear) {
                    (_, Some(bx)) => bx.nearest_image(dp, time).0.norm(),
                    (Some(p), None) => crate::contact::periodic::min_image(dp, &p).norm(),
                    (None, None) => dp.norm(),
                };
                if d < sum && best.is_none_or(|(bj0, _)| j < bj0) {
                    best = Some((j, sum - d));
                }
            }
        }
        if let Some((j, depth)) = best {
            return Some((i, j, depth));
        }
    }
    None
}

/// The acceleration of a body sliding on each static wall of `scene`, by wall index
/// ([`crate::contact::resting::slide_acceleration`]; `None` where no body rests), when bodies rest on walls there
/// (`settings.rest_speed` and gravity); empty otherwise.
#[must_use]
pub fn slides<const D: usize>(scene: &Scene<D>) -> Vec<Option<Vector<D>>> {
    match (scene.settings.rest_speed, scene.gravity()) {
        (Some(_), Some(g)) => scene
            .walls
            .iter()
            .map(|w| crate::contact::resting::slide_acceleration(&g, w))
            .collect(),
        _ => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> Vec<Wall<2>> {
        let c = [[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0]];
        (0..4)
            .map(|k| Wall::Segment {
                a: Vector(c[k]),
                b: Vector(c[(k + 1) % 4]),
            })
            .collect()
    }

    fn scene(bodies: Vec<BodySpec<2>>) -> Scene<2> {
        Scene {
            bodies,
            walls: table(),
            ..Scene::default()
        }
    }

    #[test]
    fn good_scene_round_trips() {
        let s = scene(vec![
            BodySpec::new(Vector([1.0, 1.0]), Vector([1.0, 0.0]), 0.5),
            BodySpec {
                id: Some(9),
                mass: Some(2.0),
                ..BodySpec::new(Vector([3.0, 1.0]), Vector([0.0, 0.0]), 0.5)
            },
        ]);
        s.validate().unwrap();
        let back = AnyScene::from_json(&s.to_json()).unwrap();
        assert_eq!(back, AnyScene::D2(s));
    }

    #[test]
    fn rejects_each_class() {
        let ok = || BodySpec::new(Vector([1.0, 1.0]), Vector([0.0, 0.0]), 0.5);
        let mut b = ok();
        b.radius = -1.0;
        assert_eq!(
            scene(vec![b]).validate(),
            Err(SceneError::NonPositive("bodies[0].radius".into()))
        );
        let mut b = ok();
        b.vel = Vector([f64::NAN, 0.0]);
        assert_eq!(
            scene(vec![b]).validate(),
            Err(SceneError::NonFinite("bodies[0].vel".into()))
        );
        let b2 = BodySpec::new(Vector([1.5, 1.0]), Vector([0.0, 0.0]), 0.5);
        assert!(matches!(
            scene(vec![ok(), b2]).validate(),
            Err(SceneError::Overlap { .. })
        ));
        let b3 = BodySpec::new(Vector([0.2, 1.0]), Vector([0.0, 0.0]), 0.5);
        assert!(matches!(
            scene(vec![b3]).validate(),
            Err(SceneError::CrossesWall { wall: 3, .. })
        ));
        let b4 = BodySpec::new(Vector([9.0, 1.0]), Vector([0.0, 0.0]), 0.5);
        assert!(matches!(
            scene(vec![b4]).validate(),
            Err(SceneError::OutsideTable { .. })
        ));
        let mut s = scene(vec![ok()]);
        s.walls.push(Wall::Segment {
            a: Vector([1.0, 1.0]),
            b: Vector([1.0, 1.0]),
        });
        assert!(matches!(
            s.validate(),
            Err(SceneError::DegenerateWall { wall: 4, .. })
        ));
        let mut a = ok();
        a.id = Some(1);
        let mut c = BodySpec::new(Vector([3.0, 1.0]), Vector([0.0, 0.0]), 0.5);
        c.id = Some(1);
        assert!(matches!(
            scene(vec![a, c]).validate(),
            Err(SceneError::DuplicateId { id: 1, .. })
        ));
    }

    #[test]
    fn touching_bodies_are_allowed() {
        let a = BodySpec::new(Vector([1.0, 1.0]), Vector([0.0, 0.0]), 0.5);
        let b = BodySpec::new(Vector([2.0, 1.0]), Vector([0.0, 0.0]), 0.5);
        scene(vec![a, b]).validate().unwrap();
    }

    #[test]
    fn parse_errors_name_the_place() {
        let e = AnyScene::from_json("{\"dim\": 2,\n \"bodies\": [}").unwrap_err();
        assert!(matches!(e, SceneError::Json { line: 2, .. }), "{e}");
        let e = AnyScene::from_json(r#"{"dim": 2, "bodies": [{"pos": [0,0], "vel": [0,0]}]}"#)
            .unwrap_err();
        assert!(
            e.to_string()
                .starts_with("field `bodies[0]`: missing field `radius`"),
            "{e}"
        );
        let e = AnyScene::from_json(
            r#"{"dim": 2, "bodies": [{"pos": [0,0], "vel": [0,0], "radius": 1e999}]}"#,
        )
        .unwrap_err();
        assert!(e.to_string().starts_with("field `bodies[0].radius`"), "{e}");
        let e = AnyScene::from_json(
            r#"{"dim": 3, "bodies": [{"pos": [0,0], "vel": [0,0,0], "radius": 1}]}"#,
        )
        .unwrap_err();
        assert!(e.to_string().starts_with("field `bodies[0].pos`"), "{e}");
        let e = AnyScene::from_json(r#"{"dim": 4, "bodies": []}"#).unwrap_err();
        assert!(matches!(e, SceneError::Dimension(_)));
        let e = Scene::<3>::from_json(r#"{"dim": 2, "bodies": []}"#).unwrap_err();
        assert!(matches!(e, SceneError::Dimension(_)));
    }

    #[test]
    fn the_first_duplicate_id_is_named() {
        let with_ids = |ids: &[u64]| Scene::<2> {
            bodies: ids
                .iter()
                .enumerate()
                .map(|(k, &id)| BodySpec {
                    id: Some(id),
                    ..BodySpec::new(Vector([2.0 * k as f64, 0.0]), Vector([0.0, 0.0]), 0.5)
                })
                .collect(),
            ..Scene::default()
        };
        let dup = |ids: &[u64]| match with_ids(ids).validate() {
            Err(SceneError::DuplicateId { id, first, second }) => Some((id, first, second)),
            _ => None,
        };
        assert_eq!(dup(&[5, 7, 5, 7, 5]), Some((5, 0, 2)));
        assert_eq!(dup(&[7, 5, 5, 7]), Some((5, 1, 2)));
        assert_eq!(dup(&[1, 2, 3]), None);
    }

    #[test]
    fn periodic_scenes() {
        let body = |p: [f64; 2]| BodySpec::new(Vector(p), Vector([1.0, 0.0]), 0.5);
        let mut s = Scene::<2> {
            bodies: vec![body([0.2, 1.0]), body([4.5, 1.0])],
            periodic: Some(Vector([5.0, 3.0])),
            ..Scene::default()
        };
        // 0.2 and 4.5 are 0.7 apart across the face x = 0: they overlap.
        assert!(matches!(s.validate(), Err(SceneError::Overlap { .. })));
        s.bodies[1].pos = Vector([3.5, 1.0]);
        s.validate().unwrap();
        let back = AnyScene::from_json(&s.to_json()).unwrap();
        assert_eq!(back, AnyScene::D2(s.clone()));
        assert!(s.to_json().contains("\"periodic\":[5.0,3.0]"));
        let mut t = s.clone();
        t.walls = table();
        let e = t.validate().unwrap_err();
        assert_eq!(
            e.to_string(),
            "field `walls`: a periodic scene has no walls"
        );
        let mut t = s.clone();
        t.bodies[0].pos = Vector([5.0, 1.0]);
        let e = t.validate().unwrap_err();
        assert!(e.to_string().starts_with("field `bodies[0].pos`"), "{e}");
        let mut t = s.clone();
        t.periodic = Some(Vector([5.0, 2.0]));
        let e = t.validate().unwrap_err();
        assert!(e.to_string().starts_with("field `periodic`: side 2"), "{e}");
        t.periodic = Some(Vector([5.0, f64::NAN]));
        assert!(t.validate().is_err());
        assert!(Scene::<2> {
            periodic: None,
            ..s.clone()
        }
        .to_json()
        .find("periodic")
        .is_none());
    }

    #[test]
    fn planes_are_one_sided() {
        let wall = Wall::Plane {
            point: Vector([0.0, 0.0, 0.0]),
            normal: Vector([0.0, 0.0, 2.0]),
        };
        assert_eq!(wall_clearance(&wall, Vector([5.0, 1.0, 3.0])), 3.0);
        assert_eq!(wall_clearance(&wall, Vector([5.0, 1.0, -3.0])), -3.0);
    }
}
