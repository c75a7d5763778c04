//! `ccdsim._ccdsim.pack_json`: compression to a jammed packing (see `ccdsim pack`).

use ccdsim::packing::{
    compress, dilute_start, finish_isostatic, CompressConfig, CompressStop, IsostaticConfig,
    Packed, SizeMix,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// Compresses a dilute random gas into a jammed packing and returns, as JSON: the summary
/// (`packing_fraction`, `reduced_pressure`, `stop`, `events`, `time`, `mean_contacts`,
/// `contact_tolerance`, `held_contacts`, `isostatic_contacts`, `rigid`, and with `isostatic`
/// the `finish`), `contacts` (body pairs), `wall_contacts` (body, wall), `rattlers` and
/// `scene` (the packing as a scene). `until_pressure` defaults to 10¹², or 10⁴ before an
/// isostatic finish. Runs without the GIL.
#[pyfunction]
#[pyo3(signature = (dim=3, n=1000, bidisperse=None, polydisperse=None, rate=0.01, periodic=true, until_pressure=None, start_packing=None, seed=1, finder="cells", max_events=None, isostatic=false, overlap=1e-6))]
#[allow(clippy::too_many_arguments)]
pub fn pack_json(
    py: Python<'_>,
    dim: usize,
    n: usize,
    bidisperse: Option<f64>,
    polydisperse: Option<f64>,
    rate: f64,
    periodic: bool,
    until_pressure: Option<f64>,
    start_packing: Option<f64>,
    seed: u64,
    finder: &str,
    max_events: Option<u64>,
    isostatic: bool,
    overlap: f64,
) -> PyResult<String> {
    let mix = match (bidisperse, polydisperse) {
        (Some(_), Some(_)) => {
            return Err(PyValueError::new_err(
                "give bidisperse or polydisperse, not both",
            ))
        }
        (Some(r), None) => SizeMix::Bidisperse(r),
        (None, Some(w)) => SizeMix::Polydisperse(w),
        (None, None) => SizeMix::Monodisperse,
    };
    let until_pressure = until_pressure.unwrap_or(if isostatic { 1e4 } else { 1e12 });
    let finish = isostatic.then_some(IsostaticConfig {
        overlap,
        ..IsostaticConfig::default()
    });
    let config = CompressConfig {
        rate,
        until_pressure,
        max_events,
        ..CompressConfig::default()
    };
    let start = start_packing.unwrap_or(if dim == 2 { 0.3 } else { 0.2 });
    let finder = finder.to_string();
    let run = move || -> Result<String, String> {
        match dim {
            2 => pack::<2>(n, start, mix, periodic, seed, &finder, &config, finish),
            3 => pack::<3>(n, start, mix, periodic, seed, &finder, &config, finish),
            d => Err(format!("dim must be 2 or 3, not {d}")),
        }
    };
    py.detach(run).map_err(PyValueError::new_err)
}

#[allow(clippy::too_many_arguments)]
fn pack<const D: usize>(
    n: usize,
    start: f64,
    mix: SizeMix,
    periodic: bool,
    seed: u64,
    finder: &str,
    config: &CompressConfig,
    finish: Option<IsostaticConfig>,
) -> Result<String, String> {
    if n == 0 {
        return Err("a packing needs at least one body".into());
    }
    let scene = dilute_start::<D>(n, start, mix, periodic, seed).map_err(|e| e.to_string())?;
    let mut packed = compress(&scene, finder, config, |_| {}).map_err(|e| e.to_string())?;
    if let Some(finish) = finish {
        packed = finish_isostatic(&packed, &finish, |_| {}).map_err(|e| e.to_string())?;
    }
    Ok(summary(&packed).to_string())
}

fn summary<const D: usize>(p: &Packed<D>) -> serde_json::Value {
    let stop = match p.stop {
        CompressStop::Pressure => "pressure".to_string(),
        CompressStop::MaxEvents => "max_events".to_string(),
        CompressStop::NoEvents => "no_events".to_string(),
        CompressStop::Halt(h) => format!("halt: {h}"),
    };
    let scene: serde_json::Value =
        serde_json::from_str(&p.scene.to_json()).expect("scenes serialise to JSON");
    serde_json::json!({
        "packing_fraction": p.packing_fraction,
        "reduced_pressure": p.reduced_pressure,
        "stop": stop,
        "events": p.events,
        "time": p.time,
        "mean_contacts": p.contacts.mean_contacts,
        "contact_tolerance": p.contact_tolerance,
        "held_contacts": p.contacts.held_contacts,
        "isostatic_contacts": p.contacts.isostatic_contacts,
        "rigid": p.contacts.is_rigid(),
        "finish": p.finish.map(|f| serde_json::json!({
            "minimizations": f.minimizations,
            "steps": f.steps,
            "mean_overlap": f.mean_overlap,
            "max_overlap": f.max_overlap,
            "radius_scale": f.radius_scale,
        })),
        "contacts": p.contacts.pairs,
        "wall_contacts": p.contacts.walls,
        "rattlers": p.contacts.rattlers,
        "scene": scene,
    })
}
