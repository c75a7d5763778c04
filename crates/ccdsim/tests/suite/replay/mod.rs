//! Run-file helpers shared by the integration tests that record runs and verify them.
// Each test crate uses only some of these.
#![allow(dead_code)]

use ccdsim::record::RunReader;
use ccdsim::verify::{Verifier, VerifyReport};
use ccdsim::{Collision, Scene};

/// A run file's scene, events and end time.
pub fn records<const D: usize>(bytes: &[u8]) -> (Scene<D>, Vec<Collision<D>>, f64) {
    let mut r = RunReader::<_, D>::new(bytes, "run".into()).unwrap();
    let (events, end) = r.read_events().unwrap();
    (r.scene().clone(), events, end.expect("an end record"))
}

/// `verify`'s verdict on `events` of `scene` ending at `end`, in grid mode or checking every
/// pair (`all_pairs`).
pub fn replay<const D: usize>(
    scene: &Scene<D>,
    events: &[Collision<D>],
    end: f64,
    all_pairs: bool,
) -> Result<VerifyReport, String> {
    let mut v = if all_pairs {
        Verifier::all_pairs(scene)
    } else {
        Verifier::new(scene)
    };
    for c in events {
        v.check(c).map_err(|e| e.to_string())?;
    }
    v.finish(end).map_err(|e| e.to_string())
}
