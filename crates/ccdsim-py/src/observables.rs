//! `ccdsim._ccdsim` observables over frames given as NumPy arrays: g(r), MSD, VACF.

use ccdsim::observables::{mean_square_displacement, velocity_autocorrelation, PairCorrelation};
use ccdsim::trajectory::{Cell, Frame};
use ccdsim::Vector;
use numpy::{PyArray1, PyReadonlyArray3};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// Frames × bodies of `D`-vectors from an F×N×D array.
fn frames<const D: usize>(a: &PyReadonlyArray3<'_, f64>) -> PyResult<Vec<Vec<Vector<D>>>> {
    let a = a.as_array();
    let (f, n, d) = a.dim();
    if d != D {
        return Err(value_error(format!("expected {D} coordinates, not {d}")));
    }
    Ok((0..f)
        .map(|k| {
            (0..n)
                .map(|i| {
                    let mut v = Vector([0.0; D]);
                    for c in 0..D {
                        v[c] = a[[k, i, c]];
                    }
                    v
                })
                .collect()
        })
        .collect())
}

fn dim_of(a: &PyReadonlyArray3<'_, f64>) -> PyResult<usize> {
    match a.as_array().dim().2 {
        d @ (2 | 3) => Ok(d),
        d => Err(value_error(format!(
            "frames must be F x N x 2 or F x N x 3, not F x N x {d}"
        ))),
    }
}

#[pyfunction]
#[pyo3(signature = (positions, origin, size, periodic, r_max, bins))]
#[allow(clippy::type_complexity)]
fn rdf<'py>(
    py: Python<'py>,
    positions: PyReadonlyArray3<'py, f64>,
    origin: Vec<f64>,
    size: Vec<f64>,
    periodic: bool,
    r_max: f64,
    bins: usize,
) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>, u64)> {
    fn run<const D: usize>(
        frames: Vec<Vec<Vector<D>>>,
        origin: &[f64],
        size: &[f64],
        periodic: bool,
        r_max: f64,
        bins: usize,
    ) -> PyResult<(Vec<f64>, Vec<f64>, u64)> {
        let vec = |v: &[f64], what: &str| -> PyResult<Vector<D>> {
            let a: [f64; D] = v
                .try_into()
                .map_err(|_| value_error(format!("{what} needs {D} numbers, not {}", v.len())))?;
            Ok(Vector(a))
        };
        let (o, l) = (vec(origin, "origin")?, vec(size, "box")?);
        if (0..D).any(|d| !(l[d].is_finite() && l[d] > 0.0)) {
            return Err(value_error("box sides must be positive"));
        }
        let cell = if periodic {
            Cell::Periodic(l)
        } else {
            Cell::Walls { lo: o, hi: o + l }
        };
        let mut g = PairCorrelation::<D>::new(r_max, bins).map_err(value_error)?;
        for positions in frames {
            let n = positions.len();
            let positions = if periodic {
                positions
                    .into_iter()
                    .map(|p| ccdsim::contact::periodic::wrap_point(p - o, &l))
                    .collect()
            } else {
                positions
            };
            let frame = Frame {
                time: 0.0,
                cell,
                ids: Vec::new(),
                positions,
                images: Vec::new(),
                strain: 0.0,
                velocities: Vec::new(),
                radii: vec![0.0; n],
                masses: Vec::new(),
                spins: None,
            };
            g.add(&frame).map_err(value_error)?;
        }
        Ok((g.bin_centres(), g.values(), g.pair_counts().iter().sum()))
    }
    let (r, g, pairs) = match dim_of(&positions)? {
        2 => {
            let f = frames::<2>(&positions)?;
            py.detach(|| run::<2>(f, &origin, &size, periodic, r_max, bins))?
        }
        _ => {
            let f = frames::<3>(&positions)?;
            py.detach(|| run::<3>(f, &origin, &size, periodic, r_max, bins))?
        }
    };
    Ok((PyArray1::from_vec(py, r), PyArray1::from_vec(py, g), pairs))
}

#[pyfunction]
fn msd<'py>(
    py: Python<'py>,
    positions: PyReadonlyArray3<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let out = match dim_of(&positions)? {
        2 => {
            let f = frames::<2>(&positions)?;
            py.detach(|| mean_square_displacement(&f))
        }
        _ => {
            let f = frames::<3>(&positions)?;
            py.detach(|| mean_square_displacement(&f))
        }
    };
    Ok(PyArray1::from_vec(py, out.map_err(value_error)?))
}

#[pyfunction]
fn vacf<'py>(
    py: Python<'py>,
    velocities: PyReadonlyArray3<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let out = match dim_of(&velocities)? {
        2 => {
            let f = frames::<2>(&velocities)?;
            py.detach(|| velocity_autocorrelation(&f))
        }
        _ => {
            let f = frames::<3>(&velocities)?;
            py.detach(|| velocity_autocorrelation(&f))
        }
    };
    Ok(PyArray1::from_vec(py, out.map_err(value_error)?))
}

/// Adds the functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(rdf, m)?)?;
    m.add_function(wrap_pyfunction!(msd, m)?)?;
    m.add_function(wrap_pyfunction!(vacf, m)?)?;
    Ok(())
}
