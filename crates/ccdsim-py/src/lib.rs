//! The extension module `ccdsim._ccdsim`: a thin binding of the library's `Simulation`, scene
//! generators and run-file reader. The Python package `ccdsim` (python/ccdsim) wraps it with
//! NumPy structured arrays, type hints and docs; see there for the API.

#![forbid(unsafe_code)]

mod billiards;
mod observables;
mod packing;
mod simulation;

use ccdsim::generate::{gas, rack, thesis, GasConfig, Lattice, RackConfig, ThesisConfig};
use ccdsim::record::{open_run, AnyRunReader, RunReader, RunRecord};
use ccdsim::Collision;
use numpy::{PyArray1, PyArray3, PyArrayMethods};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A hard-disc (2D) or hard-sphere (3D) gas as a scene-file JSON string; see `ccdsim gen gas`.
#[pyfunction]
#[pyo3(signature = (n=1000, packing=0.2, dim=2, radius_min=0.5, radius_max=0.5, speed_min=0.0, speed_max=1.0, seed=1, periodic=false, lattice=false, temperature=None))]
#[allow(clippy::too_many_arguments)]
fn gas_json(
    n: usize,
    packing: f64,
    dim: usize,
    radius_min: f64,
    radius_max: f64,
    speed_min: f64,
    speed_max: f64,
    seed: u64,
    periodic: bool,
    lattice: bool,
    temperature: Option<f64>,
) -> PyResult<String> {
    let cfg = GasConfig {
        n,
        packing,
        radius_min,
        radius_max,
        speed_min,
        speed_max,
        seed,
        periodic,
        lattice: lattice.then_some(Lattice::Densest),
        temperature,
    };
    let json = match dim {
        2 => gas::<2>(&cfg).map(|s| s.to_json()),
        3 => gas::<3>(&cfg).map(|s| s.to_json()),
        d => {
            return Err(PyValueError::new_err(format!(
                "dim must be 2 or 3, not {d}"
            )))
        }
    };
    json.map_err(|e| PyValueError::new_err(e.to_string()))
}

/// The thesis's §5.2 benchmark scene as a scene-file JSON string; see `ccdsim gen thesis`.
#[pyfunction]
#[pyo3(signature = (n=256, seed=1, dim=2))]
fn thesis_json(n: usize, seed: u64, dim: usize) -> PyResult<String> {
    let cfg = ThesisConfig {
        n,
        seed,
        ..ThesisConfig::default()
    };
    let json = match dim {
        2 => thesis::<2>(&cfg).map(|s| s.to_json()),
        3 => thesis::<3>(&cfg).map(|s| s.to_json()),
        d => {
            return Err(PyValueError::new_err(format!(
                "dim must be 2 or 3, not {d}"
            )))
        }
    };
    json.map_err(|e| PyValueError::new_err(e.to_string()))
}

/// A 15-ball billiard rack with the cue ball shot into it, as a scene-file JSON string.
#[pyfunction]
#[pyo3(signature = (speed=None, offset=None))]
fn rack_json(speed: Option<f64>, offset: Option<f64>) -> String {
    let d = RackConfig::default();
    rack(&RackConfig {
        speed: speed.unwrap_or(d.speed),
        offset: offset.unwrap_or(d.offset),
        ..d
    })
    .to_json()
}

/// Reads a run file: a dict with the header scene (`scene`, JSON text), the events as arrays
/// (`t`, `kind` 0 body 1 wall, `a`, `b`, `pos` and `vel` of shape (k, 2, D)), the end time
/// (`end`, or None) and the tail (`complete`).
#[pyfunction]
fn read_run<'py>(py: Python<'py>, path: &str) -> PyResult<Bound<'py, PyDict>> {
    let reader = open_run(std::path::Path::new(path)).map_err(|e| match e {
        ccdsim::record::RecordError::Io { .. } => PyOSError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    })?;
    match reader {
        AnyRunReader::D2(r) => run_dict(py, r),
        AnyRunReader::D3(r) => run_dict(py, r),
    }
}

fn run_dict<'py, R: std::io::Read, const D: usize>(
    py: Python<'py>,
    mut r: RunReader<R, D>,
) -> PyResult<Bound<'py, PyDict>> {
    let mut events: Vec<Collision<D>> = Vec::new();
    let mut end = None;
    while let Some(rec) = r
        .next_record()
        .map_err(|e| PyValueError::new_err(e.to_string()))?
    {
        match rec {
            RunRecord::Event(c) => events.push(c),
            RunRecord::End(t) => end = Some(t),
        }
    }
    let out = events_dict(py, &events)?;
    out.set_item("scene", r.scene().to_json())?;
    out.set_item("end", end)?;
    out.set_item("complete", r.tail() == ccdsim::record::Tail::Complete)?;
    Ok(out)
}

/// Events as a dict of arrays (see `read_run`).
pub(crate) fn events_dict<'py, const D: usize>(
    py: Python<'py>,
    events: &[Collision<D>],
) -> PyResult<Bound<'py, PyDict>> {
    let k = events.len();
    let out = PyDict::new(py);
    let t: Vec<f64> = events.iter().map(|c| c.event.time).collect();
    let kind: Vec<u8> = events.iter().map(|c| c.event.kind as u8).collect();
    let a: Vec<u32> = events.iter().map(|c| c.event.a).collect();
    let b: Vec<u32> = events.iter().map(|c| c.event.b).collect();
    let flat = |f: fn(&Collision<D>) -> [ccdsim::Vector<D>; 2]| -> Vec<f64> {
        events
            .iter()
            .flat_map(|c| f(c).into_iter().flat_map(|v| v.0))
            .collect()
    };
    let pos = PyArray1::from_vec(py, flat(|c| c.pos)).reshape([k, 2, D])?;
    let vel = PyArray1::from_vec(py, flat(|c| c.vel)).reshape([k, 2, D])?;
    let _: &Bound<'py, PyArray3<f64>> = &pos;
    out.set_item("t", PyArray1::from_vec(py, t))?;
    out.set_item("kind", PyArray1::from_vec(py, kind))?;
    out.set_item("a", PyArray1::from_vec(py, a))?;
    out.set_item("b", PyArray1::from_vec(py, b))?;
    out.set_item("pos", pos)?;
    out.set_item("vel", vel)?;
    let flags =
        |f: fn(&Collision<D>) -> [bool; 2]| -> Vec<bool> { events.iter().flat_map(f).collect() };
    out.set_item(
        "rests",
        PyArray1::from_vec(py, flags(|c| c.rests)).reshape([k, 2])?,
    )?;
    out.set_item(
        "pivots",
        PyArray1::from_vec(py, flags(|c| c.pivots)).reshape([k, 2])?,
    )?;
    Ok(out)
}

/// The extension module.
#[pymodule]
fn _ccdsim(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<simulation::PySimulation>()?;
    m.add_function(wrap_pyfunction!(gas_json, m)?)?;
    m.add_function(wrap_pyfunction!(thesis_json, m)?)?;
    m.add_function(wrap_pyfunction!(rack_json, m)?)?;
    m.add_function(wrap_pyfunction!(read_run, m)?)?;
    m.add_function(wrap_pyfunction!(packing::pack_json, m)?)?;
    m.add_function(wrap_pyfunction!(billiards::pool_shot, m)?)?;
    m.add_function(wrap_pyfunction!(billiards::pool_rack, m)?)?;
    observables::register(m)?;
    m.add("FINDER_NAMES", ccdsim::FINDER_NAMES.to_vec())?;
    Ok(())
}
