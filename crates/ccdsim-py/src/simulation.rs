//! `ccdsim._ccdsim.Simulation`: one `ccdsim::Simulation` of either dimension.

use ccdsim::observables::PressureTensor;
use ccdsim::trajectory::{Cell, Frame, SampleTimes, TrajectoryFormat, TrajectoryWriter};
use ccdsim::{AnyScene, Collision, Simulation, Vector};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyIndexError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A simulation of either dimension.
enum AnySim {
    D2(Simulation<2>),
    D3(Simulation<3>),
}

/// Runs `$body` with `$s` bound to the simulation, whatever its dimension (`D` the dimension).
macro_rules! with_sim {
    ($self:expr, $s:ident, $body:expr) => {
        match &mut *$self.sim.lock().unwrap_or_else(|e| e.into_inner()) {
            AnySim::D2($s) => {
                #[allow(dead_code)]
                const D: usize = 2;
                $body
            }
            AnySim::D3($s) => {
                #[allow(dead_code)]
                const D: usize = 3;
                $body
            }
        }
    };
}

/// The exact event-driven simulation of a scene (see the Python class `ccdsim.Simulation`).
#[pyclass(name = "Simulation", module = "ccdsim._ccdsim")]
pub struct PySimulation {
    // A mutex makes the class shareable between Python threads (PyO3 asks for `Sync`); the
    // GIL already serialises the calls, so it is never contended.
    sim: std::sync::Mutex<AnySim>,
}

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// `n` numbers as the vector of dimension `D`.
fn vector<const D: usize>(v: &[f64]) -> PyResult<Vector<D>> {
    let a: [f64; D] = v.try_into().map_err(|_| {
        value_error(format!(
            "a vector of {D} numbers is needed, not {}",
            v.len()
        ))
    })?;
    Ok(Vector(a))
}

/// An N×D array of vectors.
fn matrix<'py, const D: usize>(
    py: Python<'py>,
    rows: impl Iterator<Item = Vector<D>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = rows.flat_map(|v| v.0).collect();
    let n = flat.len() / D;
    PyArray1::from_vec(py, flat).reshape([n, D])
}

impl PySimulation {
    fn check_index(&mut self, i: usize) -> PyResult<()> {
        let n = with_sim!(self, s, s.world().len());
        if i >= n {
            return Err(PyIndexError::new_err(format!(
                "body {i} does not exist ({n} bodies)"
            )));
        }
        Ok(())
    }
}

#[pymethods]
impl PySimulation {
    /// A simulation of the scene `scene_json` (the scene-file format) with finder `finder`.
    #[new]
    #[pyo3(signature = (scene_json, finder="cells"))]
    fn new(scene_json: &str, finder: &str) -> PyResult<Self> {
        let scene = AnyScene::from_json(scene_json).map_err(value_error)?;
        let sim = match scene {
            AnyScene::D2(s) => AnySim::D2(Simulation::new(&s, finder).map_err(value_error)?),
            AnyScene::D3(s) => AnySim::D3(Simulation::new(&s, finder).map_err(value_error)?),
        };
        Ok(PySimulation {
            sim: std::sync::Mutex::new(sim),
        })
    }

    /// 2 or 3.
    #[getter]
    fn dim(&mut self) -> usize {
        with_sim!(self, _s, D)
    }

    /// Number of body slots (bodies and vacant slots, see `present`).
    fn __len__(&mut self) -> usize {
        with_sim!(self, s, s.world().len())
    }

    /// The finder's name.
    #[getter]
    fn finder(&mut self) -> &'static str {
        with_sim!(self, s, s.finder_name())
    }

    /// Current simulated time, seconds.
    #[getter]
    fn time(&mut self) -> f64 {
        with_sim!(self, s, s.time())
    }

    /// Positions at the current time (inside the box in periodic worlds), N×D, metres.
    #[getter]
    fn positions<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        with_sim!(self, s, {
            let n = s.world().len();
            matrix::<D>(py, (0..n).map(|i| s.position(i)))
        })
    }

    /// Velocities now, N×D, metres per second (under gravity, the stored velocities plus
    /// the fall since each body's last change).
    #[getter]
    fn velocities<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        with_sim!(self, s, {
            let (w, t) = (s.world(), s.time());
            matrix::<D>(py, (0..w.len()).map(|i| w.velocity_at(i, t)))
        })
    }

    /// Angular velocities now, N×3, radians per second (a disc's about the third axis; zeros
    /// in a run that keeps no spins). Only collisions of rough bodies change them.
    #[getter]
    fn spins<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        with_sim!(self, s, {
            let w = s.world();
            matrix::<3>(py, (0..w.len()).map(|i| w.spin(i)))
        })
    }

    /// Rotational kinetic energy now, joules (0 in a run that keeps no spins).
    fn rotational_energy(&mut self) -> f64 {
        with_sim!(self, s, s.world().rotational_energy())
    }

    /// Periodic images, N×D integers: `positions + images · L` are the unwrapped positions
    /// (zeros without a periodic box).
    #[getter]
    fn images<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        with_sim!(self, s, {
            let n = s.world().len();
            let flat: Vec<i64> = (0..n).flat_map(|i| s.image(i)).collect();
            PyArray1::from_vec(py, flat).reshape([n, D])
        })
    }

    /// Unwrapped positions (the paths travelled, never folded into the box), N×D, metres.
    #[getter]
    fn unwrapped_positions<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        with_sim!(self, s, {
            let n = s.world().len();
            matrix::<D>(py, (0..n).map(|i| s.unwrapped_position(i)))
        })
    }

    /// The simulation cell: `(kind, origin, size)` with kind "periodic", "walls" (the walls'
    /// bounding box) or "open" (origin and size None).
    #[allow(clippy::type_complexity)]
    fn cell(&mut self) -> (&'static str, Option<Vec<f64>>, Option<Vec<f64>>) {
        with_sim!(self, s, {
            let cell = Frame::of(s).cell;
            let kind = match cell {
                Cell::Periodic(_) => "periodic",
                Cell::Walls { .. } => "walls",
                Cell::Open => "open",
            };
            match cell.origin_and_size() {
                Some((o, l)) => (kind, Some(o.0.to_vec()), Some(l.0.to_vec())),
                None => (kind, None, None),
            }
        })
    }

    /// Runs to `until`, writing a frame every `every` seconds from now (now included) to
    /// `path` (.xyz/.extxyz: extended XYZ; .gsd: GSD); the number of frames. Runs without the
    /// GIL. This advances the simulation: afterwards its time is the last frame's (or where
    /// the run halted), as after `run_until`.
    fn write_trajectory(
        &mut self,
        py: Python<'_>,
        path: std::path::PathBuf,
        every: f64,
        until: f64,
    ) -> PyResult<u64> {
        let format = TrajectoryFormat::from_path(&path).map_err(value_error)?;
        with_sim!(self, s, {
            let times = SampleTimes::new(s.time(), every, until).map_err(value_error)?;
            py.detach(|| -> PyResult<u64> {
                let io = |e: std::io::Error| {
                    pyo3::exceptions::PyOSError::new_err(format!("{}: {e}", path.display()))
                };
                let mut w = TrajectoryWriter::create_for(&path, format, s.world().is_rotational())
                    .map_err(io)?;
                let mut frames = 0;
                for t in times {
                    s.run_until(t);
                    if s.time() < t {
                        break; // halted: no frame claims a time the run did not reach
                    }
                    w.write(&Frame::of(s)).map_err(io)?;
                    frames += 1;
                }
                s.run_until(until);
                w.finish().map_err(io)?;
                Ok(frames)
            })
        })
    }

    /// Runs to time `t` and returns the pressure tensor (D×D) over that stretch, from the
    /// collision virial and the time-integrated kinetic tensor. Runs without the GIL.
    fn run_until_pressure_tensor<'py>(
        &mut self,
        py: Python<'py>,
        t: f64,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        if t.is_nan() {
            return Err(value_error("t is NaN"));
        }
        with_sim!(self, s, {
            let mut p = PressureTensor::new(s).map_err(value_error)?;
            let tensor = py.detach(|| {
                s.run_until_with(t, |c| p.observe(c));
                p.tensor(s.time())
            });
            let flat: Vec<f64> = tensor.iter().flatten().copied().collect();
            PyArray1::from_vec(py, flat).reshape([D, D])
        })
    }

    /// Radii now, metres (they grow in a scene with `settings.growth`).
    #[getter]
    fn radii<'py>(&mut self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        with_sim!(self, s, {
            let r = (0..s.world().len()).map(|i| s.radius(i)).collect();
            PyArray1::from_vec(py, r)
        })
    }

    /// Multiplies every velocity by `factor` from now on (O(n): every body's next events are
    /// computed anew).
    fn rescale_velocities(&mut self, factor: f64) -> PyResult<()> {
        with_sim!(self, s, s.rescale_velocities(factor).map_err(value_error))
    }

    /// Stops the growth of the radii now: they keep their current values.
    fn stop_growth(&mut self) -> PyResult<()> {
        with_sim!(self, s, s.stop_growth().map_err(value_error))
    }

    /// Masses, kilograms.
    #[getter]
    fn masses<'py>(&mut self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        with_sim!(
            self,
            s,
            PyArray1::from_vec(py, s.world().masses().collect())
        )
    }

    /// Why the run stopped while events remained (see docs/numerics.md), or None.
    #[getter]
    fn halt(&mut self) -> Option<String> {
        with_sim!(self, s, s.halt().map(|h| h.to_string()))
    }

    /// Resolves the next event; its arrays (see `read_run`) hold one event, or none when no
    /// event will ever happen.
    fn step<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        with_sim!(self, s, {
            let c: Vec<Collision<D>> = s.step_event().into_iter().collect();
            crate::events_dict(py, &c)
        })
    }

    /// Resolves every event up to time `t` and moves the clock there; the number of events.
    /// Runs without the GIL.
    fn run_until(&mut self, py: Python<'_>, t: f64) -> PyResult<u64> {
        if t.is_nan() {
            return Err(value_error("t is NaN"));
        }
        Ok(with_sim!(self, s, py.detach(|| s.run_until(t))))
    }

    /// Resolves up to `n` events (fewer when none is left); the number resolved. Runs without
    /// the GIL.
    fn run_events(&mut self, py: Python<'_>, n: u64) -> u64 {
        with_sim!(self, s, py.detach(|| s.run_events(n)))
    }

    /// Advances the clock by `dt` seconds (one frame) and returns the frame's events as
    /// arrays (see `read_run`).
    fn advance<'py>(&mut self, py: Python<'py>, dt: f64) -> PyResult<Bound<'py, PyDict>> {
        if dt.is_nan() || dt < 0.0 {
            return Err(value_error(format!("dt must be ≥ 0, not {dt}")));
        }
        with_sim!(self, s, {
            let events = s.advance(dt);
            crate::events_dict(py, &events)
        })
    }

    /// Gives body `i` a new velocity from the current time on.
    fn set_velocity(&mut self, i: usize, v: Vec<f64>) -> PyResult<()> {
        self.check_index(i)?;
        with_sim!(self, s, {
            let v = vector::<D>(&v)?;
            s.set_velocity(i, v).map_err(value_error)
        })
    }

    /// Gives moving wall `k` (the scene's `moving_walls[k]`) the velocity `v` from the
    /// current time on; it stays where it is now.
    fn set_wall_velocity(&mut self, k: usize, v: Vec<f64>) -> PyResult<()> {
        with_sim!(self, s, {
            let v = vector::<D>(&v)?;
            s.set_wall_velocity(k, v).map_err(value_error)
        })
    }

    /// Moving wall `k`'s displacement from where the scene put it, now (a list of floats).
    fn wall_offset(&self, k: usize) -> PyResult<Vec<f64>> {
        with_sim!(self, s, {
            let w = s.world();
            if k >= w.moving_wall_count() {
                return Err(value_error(format!(
                    "moving wall {k} does not exist ({} moving walls)",
                    w.moving_wall_count()
                )));
            }
            Ok(w.wall_motion(k).offset_at(s.time()).0.to_vec())
        })
    }

    /// Moves body `i` to `p` at the current time, keeping its velocity; refused (ValueError)
    /// where it would overlap a body or a wall.
    fn set_position(&mut self, i: usize, p: Vec<f64>) -> PyResult<()> {
        self.check_index(i)?;
        with_sim!(self, s, {
            let p = vector::<D>(&p)?;
            s.set_position(i, p).map_err(value_error)
        })
    }

    /// Gives body `i` the collision group and mask bit sets `group` and `mask` from now on
    /// (two bodies collide only when each one's group meets the other's mask); refused
    /// (ValueError) when it would make overlapping bodies collide.
    #[pyo3(signature = (i, group, mask = u32::MAX))]
    fn set_collision_filter(&mut self, i: usize, group: u32, mask: u32) -> PyResult<()> {
        self.check_index(i)?;
        let filter = ccdsim::CollisionFilter { group, mask };
        with_sim!(
            self,
            s,
            s.set_collision_filter(i, filter).map_err(value_error)
        )
    }

    /// Adds a body at the current time and returns its slot index (see
    /// `ccdsim::Simulation::add_body`); ValueError when it is refused.
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (pos, vel, radius, mass=None, restitution=None, kinematic=false, group=None, mask=None, id=None))]
    fn add_body(
        &mut self,
        pos: Vec<f64>,
        vel: Vec<f64>,
        radius: f64,
        mass: Option<f64>,
        restitution: Option<f64>,
        kinematic: bool,
        group: Option<u32>,
        mask: Option<u32>,
        id: Option<u64>,
    ) -> PyResult<usize> {
        with_sim!(self, s, {
            let spec = ccdsim::BodySpec {
                id,
                mass,
                restitution,
                kinematic,
                group,
                mask,
                ..ccdsim::BodySpec::new(vector::<D>(&pos)?, vector::<D>(&vel)?, radius)
            };
            s.add_body(spec).map_err(value_error)
        })
    }

    /// Removes body `i` now; its slot becomes vacant (ValueError for a vacant slot).
    fn remove_body(&mut self, i: usize) -> PyResult<()> {
        self.check_index(i)?;
        with_sim!(self, s, s.remove_body(i).map_err(value_error))
    }

    /// Which slots hold a body (false: vacant, see `remove_body`), N booleans.
    #[getter]
    fn present<'py>(&mut self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        with_sim!(self, s, {
            let w = s.world();
            PyArray1::from_vec(py, (0..w.len()).map(|i| !w.is_vacant(i)).collect())
        })
    }

    /// The user id of each slot (2**64 − 1 for a vacant slot), N integers.
    #[getter]
    fn ids<'py>(&mut self, py: Python<'py>) -> Bound<'py, PyArray1<u64>> {
        with_sim!(self, s, PyArray1::from_vec(py, s.world().ids().to_vec()))
    }

    /// The sensor events since the last call, in time order, as arrays `t`, `body`, `sensor`
    /// and `enter` (true for an enter, false for a leave).
    fn take_sensor_events<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let events = with_sim!(self, s, s.take_sensor_events());
        let out = PyDict::new(py);
        let t: Vec<f64> = events.iter().map(|e| e.time).collect();
        let body: Vec<u32> = events.iter().map(|e| e.body as u32).collect();
        let sensor: Vec<u32> = events.iter().map(|e| e.sensor as u32).collect();
        let enter: Vec<bool> = events
            .iter()
            .map(|e| e.change == ccdsim::SensorChange::Enter)
            .collect();
        out.set_item("t", PyArray1::from_vec(py, t))?;
        out.set_item("body", PyArray1::from_vec(py, body))?;
        out.set_item("sensor", PyArray1::from_vec(py, sensor))?;
        out.set_item("enter", PyArray1::from_vec(py, enter))?;
        Ok(out)
    }

    /// Counters of the run: events, body and wall collisions, largest overlap, kinetic energy
    /// at the start, the collision virial.
    fn stats<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let st = with_sim!(self, s, *s.stats());
        let d = PyDict::new(py);
        d.set_item("events", st.events)?;
        d.set_item("body_collisions", st.body_collisions)?;
        d.set_item("wall_collisions", st.wall_collisions)?;
        d.set_item("max_overlap", st.max_overlap)?;
        d.set_item("kinetic_energy_start", st.kinetic_energy_start)?;
        d.set_item("virial", st.virial)?;
        d.set_item("resets", st.resets)?;
        d.set_item("arrivals", st.arrivals)?;
        d.set_item("arrival_energy", st.arrival_energy)?;
        Ok(d)
    }

    /// Kinetic energy now, joules.
    fn kinetic_energy(&mut self) -> f64 {
        with_sim!(self, s, s.world().kinetic_energy_at(s.time()))
    }

    /// Potential energy in the gravity field now, joules (−Σ m g·x; 0 without gravity).
    fn potential_energy(&mut self) -> f64 {
        with_sim!(self, s, s.world().potential_energy_at(s.time()))
    }

    /// Temperature, rotational temperature (None unless the run keeps spins), collision
    /// rate, volume, pressure and compressibility factor over the run so far (None where the
    /// world has no volume).
    fn observables<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let o = with_sim!(self, s, s.observables());
        let d = PyDict::new(py);
        d.set_item("temperature", o.temperature)?;
        d.set_item("rotational_temperature", o.rotational_temperature)?;
        d.set_item("collision_rate", o.collision_rate)?;
        d.set_item("volume", o.volume)?;
        d.set_item("pressure", o.pressure)?;
        d.set_item("compressibility", o.compressibility)?;
        Ok(d)
    }
}
