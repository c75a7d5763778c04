//! Two misses pooltool's users reported, played in ccdsim:
//!
//! - pooltool issue #217: a ball shot at 45° into a corner meets two cushion segments a hair
//!   apart; pooltool dropped one of the two events and the ball left the table. Played here
//!   into every corner, from several distances, at several speeds, a little either side of
//!   45°: no ball leaves the table.
//! - pooltool issue #154: in an 8-ball break with the rack's apex at (0.5, 0.75) and the cue
//!   ball at (0.5, 0.25) (fractions of the table), struck with `V0 = 3.262213`,
//!   `phi = 81.83468`, a ball went through another. On 100 seeded racks ccdsim either plays
//!   the break to the end with no overlap, or stops where two touching balls press together
//!   (a lasting contact the model does not have yet, docs/model.md), and says so: never a
//!   pass-through, never an endless run.
//!
//! Between consecutive events every ball is sampled at 16 times and at both ends (positions
//! from the shot's own motion laws), and every pair checked for overlap beyond 10⁻¹² R.

use ccdsim::billiards::{rack_at, BallParams, Game, PocketTableSpecs, Shot, ShotError, Table};
use ccdsim::motion::CueStrike;
use ccdsim::Vector;

/// Plays `shot` to the end, checking between events that no two balls on the table overlap
/// by more than 10⁻¹² R and that every ball stays within the cushions' outer edge.
fn play_and_check(mut shot: Shot, what: &str) -> Shot {
    let r = shot.params().radius();
    let (w, l) = (shot.table().width, shot.table().length);
    let reach = PocketTableSpecs::default().cushion_width;
    let mut steps = 0;
    loop {
        let t0 = shot.time();
        let Some(next) = shot.next_event() else { break };
        let n = shot.balls().len();
        for k in 0..=16 {
            let t = t0 + (next.time - t0) * f64::from(k) / 16.0;
            let at: Vec<Option<Vector<2>>> = (0..n)
                .map(|i| (shot.balls()[i].pocket.is_none()).then(|| shot.ball_at(i, t).pos))
                .collect();
            for i in 0..n {
                let Some(p) = at[i] else { continue };
                assert!(
                    p[0] > -reach && p[0] < w + reach && p[1] > -reach && p[1] < l + reach,
                    "{what}: ball {i} left the table at t = {t}: {p:?}"
                );
                for (j, q) in at.iter().enumerate().skip(i + 1) {
                    let Some(q) = *q else { continue };
                    let d = (p - q).norm();
                    assert!(
                        d >= 2.0 * r * (1.0 - 1e-12),
                        "{what}: balls {i} and {j} overlap by {} R at t = {t}",
                        (2.0 * r - d) / r
                    );
                }
            }
        }
        shot.step();
        steps += 1;
        assert!(
            steps < 100_000,
            "{what}: no end; the last events: {:?}",
            &shot.events()[shot.events().len() - 12..]
        );
    }
    assert!(shot.is_still(), "{what}");
    shot
}

#[test]
fn issue_217_a_ball_shot_into_a_corner_never_leaves_the_table() {
    let table = Table::pool(&PocketTableSpecs::default());
    let params = BallParams::default();
    let (w, l) = (table.width, table.length);
    let mut pocketed = 0;
    let mut shots = 0;
    // From a point on each corner's diagonal, towards the corner.
    for (corner, toward) in [
        (Vector([0.0, 0.0]), 225.0),
        (Vector([w, 0.0]), 315.0),
        (Vector([0.0, l]), 135.0),
        (Vector([w, l]), 45.0),
    ] {
        let inward = Vector([
            if corner[0] == 0.0 { 1.0 } else { -1.0 },
            if corner[1] == 0.0 { 1.0 } else { -1.0 },
        ]);
        for distance in [0.15, 0.3, 0.45] {
            for speed in [0.5, 1.5, 3.0, 6.0] {
                for off in [-2.0, -0.5, 0.0, 0.5, 2.0] {
                    let start = corner + inward * distance;
                    let mut shot = Shot::new(table.clone(), params, &[start]).unwrap();
                    shot.strike(0, &CueStrike::new(speed, toward + off))
                        .unwrap();
                    let what = format!("corner {corner:?}, {distance} m, {speed} m/s, {off}°");
                    let shot = play_and_check(shot, &what);
                    pocketed += usize::from(shot.balls()[0].pocket.is_some());
                    shots += 1;
                }
            }
        }
    }
    // Straight at the pocket, most drop; the rest bounce off the jaws and stay on the table.
    assert!(pocketed > shots / 2, "{pocketed} of {shots}");
}

#[test]
fn issue_154_the_break_ends_cleanly_or_stops_where_balls_press_together() {
    let table = Table::pool(&PocketTableSpecs::default());
    let params = BallParams::default();
    let (mut ended, mut pressed) = (0, 0);
    for seed in 0..100 {
        let balls = rack_at(
            Game::EightBall,
            &table,
            params.radius(),
            seed,
            [0.5, 0.75],
            [0.5, 0.25],
        );
        let positions: Vec<Vector<2>> = balls.iter().map(|(_, p)| *p).collect();
        let mut shot = Shot::new(table.clone(), params, &positions).unwrap();
        shot.strike(0, &CueStrike::new(3.262213, 81.83468)).unwrap();
        let fresh = shot.clone();
        match shot.run(100_000) {
            Ok(_) => {
                play_and_check(fresh, &format!("rack seed {seed}"));
                ended += 1;
            }
            Err(ShotError::Pressed(a, b, t)) => {
                // Touching when they met, and nothing overlapped before.
                let d = (shot.ball_at(a, t).pos - shot.ball_at(b, t).pos).norm();
                assert!(
                    (d - 2.0 * params.radius()).abs() < 1e-12,
                    "seed {seed}: {d}"
                );
                pressed += 1;
            }
            Err(e) => panic!("rack seed {seed}: {e}"),
        }
    }
    assert_eq!(ended + pressed, 100);
    assert!(ended > 0, "{ended} breaks ended, {pressed} pressed");
}
