//! Racks: where the balls stand before the break, as pooltool 0.3.3 racks them
//! (`layouts.py`): the apex ball on the foot spot at 77 % of the table's length, the others
//! packed behind it on a triangular grid of pitch `2·R·(1 + gap)`, each then moved by up to
//! `R·gap` in a random direction so that no two touch, and the cue ball behind the head
//! string.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::table::Table;
use crate::geom::Vector;

/// A game, for its rack.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Game {
    /// Nine-ball: the 1 to 9 in a diamond, the 1 at the apex and the 9 in the middle.
    NineBall,
    /// Eight-ball: the 1 to 15 in a triangle, the 8 in the middle of the third row, a stripe
    /// and a solid in the back corners.
    EightBall,
}

/// Pooltool's spacing factor: balls stand `2·R·gap` apart on the grid.
pub const RACK_GAP: f64 = 1e-3;

/// The balls of `game`'s rack on `table` for balls of radius `radius` (metres): names
/// ("cue", "1", …) and positions, the cue ball first. `seed` draws the small random offsets
/// that keep the racked balls apart.
#[must_use]
pub fn rack(game: Game, table: &Table, radius: f64, seed: u64) -> Vec<(String, Vector<2>)> {
    let cue = match game {
        Game::NineBall => [0.85, 0.23],
        Game::EightBall => [0.6, 0.23],
    };
    rack_at(game, table, radius, seed, [0.5, 0.77], cue)
}

/// [`rack`] with the apex ball at `apex` and the cue ball at `cue`, each given as fractions of
/// the table's width and length (pooltool's convention: `[0.5, 0.77]` and, for nine-ball,
/// `[0.85, 0.23]`).
#[must_use]
pub fn rack_at(
    game: Game,
    table: &Table,
    radius: f64,
    seed: u64,
    apex: [f64; 2],
    cue: [f64; 2],
) -> Vec<(String, Vector<2>)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let pitch = radius * (1.0 + RACK_GAP);
    let apex = Vector([apex[0] * table.width, apex[1] * table.length]);
    let cue = Vector([cue[0] * table.width, cue[1] * table.length]);
    let h = 3f64.sqrt();
    // Grid steps in units of the pitch: along a row (2, 0), to the next row (±1, √3).
    let at = |row: f64, across: f64| apex + Vector([across * pitch, row * h * pitch]);
    let spots: Vec<(&str, Vector<2>)> = match game {
        Game::NineBall => vec![
            ("1", at(0.0, 0.0)),
            ("2", at(1.0, -1.0)),
            ("3", at(1.0, 1.0)),
            ("4", at(2.0, 2.0)),
            ("9", at(2.0, 0.0)),
            ("5", at(2.0, -2.0)),
            ("6", at(3.0, -1.0)),
            ("7", at(3.0, 1.0)),
            ("8", at(4.0, 0.0)),
        ],
        Game::EightBall => vec![
            ("1", at(0.0, 0.0)),
            ("9", at(1.0, -1.0)),
            ("2", at(1.0, 1.0)),
            ("10", at(2.0, 2.0)),
            ("8", at(2.0, 0.0)),
            ("3", at(2.0, -2.0)),
            ("11", at(3.0, -3.0)),
            ("4", at(3.0, -1.0)),
            ("12", at(3.0, 1.0)),
            ("5", at(3.0, 3.0)),
            ("13", at(4.0, 4.0)),
            ("6", at(4.0, 2.0)),
            ("14", at(4.0, 0.0)),
            ("15", at(4.0, -2.0)),
            ("7", at(4.0, -4.0)),
        ],
    };
    let mut balls = vec![("cue".to_owned(), wiggle(cue, radius, &mut rng))];
    balls.extend(
        spots
            .into_iter()
            .map(|(name, p)| (name.to_owned(), wiggle(p, radius, &mut rng))),
    );
    balls
}

fn wiggle(p: Vector<2>, radius: f64, rng: &mut ChaCha8Rng) -> Vector<2> {
    let angle = std::f64::consts::TAU * rng.random::<f64>();
    let r = radius * RACK_GAP * rng.random::<f64>();
    p + Vector([r * angle.cos(), r * angle.sin()])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::billiards::table::PocketTableSpecs;

    #[test]
    fn racked_balls_are_close_but_never_touch_and_lie_on_the_table() {
        let t = Table::pool(&PocketTableSpecs::default());
        let r = 0.028575;
        for game in [Game::NineBall, Game::EightBall] {
            for seed in 0..20 {
                let balls = rack(game, &t, r, seed);
                assert_eq!(balls.len(), if game == Game::NineBall { 10 } else { 16 });
                for (i, (_, p)) in balls.iter().enumerate() {
                    assert!(t.holds(*p, r));
                    let nearest = balls
                        .iter()
                        .enumerate()
                        .filter(|&(j, _)| j != i)
                        .map(|(_, (_, q))| (*p - *q).norm())
                        .fold(f64::INFINITY, f64::min);
                    assert!(nearest > 2.0 * r, "{game:?} seed {seed}: {nearest}");
                    if i > 0 {
                        assert!(nearest < 2.0 * r * (1.0 + 3.0 * RACK_GAP));
                    }
                }
            }
        }
    }
}
