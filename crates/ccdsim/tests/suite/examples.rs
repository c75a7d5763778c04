//! The game examples the README and docs/game-api.md run (`cargo run --release -p ccdsim
//! --example …`): each plays to its end without an error, and the run file it records
//! passes `verify`. The examples are compiled here, as modules of this test binary, rather than
//! as binaries of their own: `scripts/test` builds test targets only, and each example alone
//! would compile the simulation's generic code once more (about 25 s each on two cores).

#[path = "../../examples/air_hockey.rs"]
#[allow(dead_code)]
mod air_hockey;
#[path = "../../examples/calibrate_thesis.rs"]
#[allow(dead_code)]
mod calibrate_thesis;
#[path = "../../examples/galton.rs"]
#[allow(dead_code)]
mod galton;
#[path = "../../examples/pinball.rs"]
#[allow(dead_code)]
mod pinball;

use ccdsim::record::RunReader;
use ccdsim::verify::Verifier;

/// An example's game: plays it, recording to the run file given.
type Play = fn(Option<&str>) -> Result<(), Box<dyn std::error::Error>>;

/// Plays an example with `play`, recording it, and checks the run file whole with `verify`;
/// returns its event count.
fn plays_and_verifies(name: &str, play: Play) -> usize {
    let dir = tempfile::Builder::new()
        .prefix(&format!("ccdsim-example-{name}-"))
        .tempdir()
        .unwrap();
    let path = dir.path().join(format!("{name}.ccd"));
    play(Some(path.to_str().unwrap())).unwrap_or_else(|e| panic!("{name}: {e}"));
    let bytes = std::fs::read(&path).unwrap();
    let mut r = RunReader::<_, 2>::new(&bytes[..], name.into()).unwrap();
    let scene = r.scene().clone();
    let (records, end) = r.read_events().unwrap();
    let mut v = Verifier::new(&scene);
    for c in &records {
        v.check(c)
            .unwrap_or_else(|e| panic!("{name} fails verify: {e}"));
    }
    v.finish(end.expect("a finished run"))
        .unwrap_or_else(|e| panic!("{name} fails verify: {e}"));
    records.len()
}

#[test]
fn air_hockey_plays_and_its_run_verifies() {
    assert!(plays_and_verifies("air_hockey", air_hockey::play) > 100);
}

#[test]
fn the_galton_board_plays_and_its_run_verifies() {
    assert!(plays_and_verifies("galton", galton::play) > 1000);
}

#[test]
fn pinball_plays_and_its_run_verifies() {
    // The cabinet is open at its drain and its bumpers are closed polygons: the ball is in
    // none of them, and no table encloses it (a scene refused as "outside the table" from
    // 9bf964a until table_edges).
    assert!(plays_and_verifies("pinball", pinball::play) > 50);
}

#[test]
fn the_thesis_calibration_counts_collisions_of_a_small_scene() {
    use ccdsim::generate::{thesis, ThesisConfig};
    let scene = thesis::<2>(&ThesisConfig {
        n: 16,
        seed: 1,
        ..ThesisConfig::default()
    })
    .unwrap();
    let (body, wall) = calibrate_thesis::count(&scene);
    assert!(
        body > 0 && wall > 0,
        "{body} body and {wall} wall collisions"
    );
}
