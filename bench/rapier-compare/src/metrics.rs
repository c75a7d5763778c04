//! Measurements over a frame's positions and velocities. Both engines go through these same
//! functions, so their figures are computed alike.

use crate::scenes::Setup;

/// A snapshot of every body at a frame end, in `f64` (Rapier's `f32` state converted).
#[derive(Clone, Debug, Default)]
pub struct State {
    /// Centre positions, metres.
    pub pos: Vec<[f64; 2]>,
    /// Velocities, metres per second.
    pub vel: Vec<[f64; 2]>,
}

/// The largest penetrations in one snapshot, relative to the ball radius.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Penetration {
    /// Largest `(r_i + r_j − |x_i − x_j|) / r` over pairs of balls (`r` the smaller radius);
    /// 0 when no pair overlaps.
    pub pair: f64,
    /// Largest `(r − distance to the wall) / r` over balls whose centre is inside the box,
    /// against the box's sides and the pegs (segments); 0 when no ball touches a wall.
    pub wall: f64,
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// Distance from `p` to the segment `[a, b]`.
fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let ab = sub(b, a);
    let t = (dot(sub(p, a), ab) / dot(ab, ab)).clamp(0.0, 1.0);
    let foot = [a[0] + t * ab[0], a[1] + t * ab[1]];
    let d = sub(p, foot);
    dot(d, d).sqrt()
}

/// True when the centre `p` lies outside the walled box (a ball that tunnelled out).
pub fn outside_box(setup: &Setup, p: [f64; 2]) -> bool {
    let [w, h] = setup.box_size;
    !(p[0] >= 0.0 && p[0] <= w && p[1] >= 0.0 && p[1] <= h)
}

/// The largest ball–ball and ball–wall penetrations of a snapshot. Balls outside the box are
/// left out of the wall figure (they are counted as tunnelled instead).
pub fn penetration(setup: &Setup, radii: &[f64], pos: &[[f64; 2]]) -> Penetration {
    let mut out = Penetration::default();
    for i in 0..pos.len() {
        for j in i + 1..pos.len() {
            let d = sub(pos[i], pos[j]);
            let gap = dot(d, d).sqrt() - (radii[i] + radii[j]);
            out.pair = out.pair.max(-gap / radii[i].min(radii[j]));
        }
    }
    let [w, h] = setup.box_size;
    for (&p, &r) in pos.iter().zip(radii) {
        if outside_box(setup, p) {
            continue;
        }
        let side = p[0].min(w - p[0]).min(p[1]).min(h - p[1]);
        out.wall = out.wall.max((r - side) / r);
        for &(a, b) in &setup.pegs {
            out.wall = out.wall.max((r - segment_distance(p, a, b)) / r);
        }
    }
    out
}

/// Kinetic plus potential energy, joules: `Σ ½ m |v|² − m g·x` (zero potential at the
/// origin, the box's bottom-left corner).
pub fn mechanical_energy(masses: &[f64], gravity: [f64; 2], state: &State) -> f64 {
    masses
        .iter()
        .zip(&state.pos)
        .zip(&state.vel)
        .map(|((&m, &x), &v)| 0.5 * m * dot(v, v) - m * dot(gravity, x))
        .sum()
}

/// The median and the 99th percentile of a sample (nearest rank).
pub fn median_p99(sample: &[f64]) -> (f64, f64) {
    if sample.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    let mut s = sample.to_vec();
    s.sort_by(f64::total_cmp);
    let rank = |q: f64| s[((q * s.len() as f64).ceil() as usize).clamp(1, s.len()) - 1];
    (rank(0.5), rank(0.99))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_distance_covers_interior_and_ends() {
        let (a, b) = ([0.0, 0.0], [2.0, 0.0]);
        assert_eq!(segment_distance([1.0, 3.0], a, b), 3.0);
        assert_eq!(segment_distance([-3.0, 4.0], a, b), 5.0);
        assert_eq!(segment_distance([5.0, -4.0], a, b), 5.0);
    }

    #[test]
    fn penetration_of_pairs_box_sides_and_pegs() {
        let setup = Setup {
            name: "test",
            description: String::new(),
            scene: ccdsim::Scene::default(),
            box_size: [4.0, 4.0],
            bullets: 0,
            pegs: vec![([2.0, 2.0], [3.0, 2.0])],
        };
        let radii = [0.1; 4];
        // Pair overlapping by 0.05 (half a radius); a ball 0.02 into the floor; one 0.08
        // into the peg; one outside the box, which the wall figure leaves out.
        let pos = [[1.0, 1.0], [1.15, 1.0], [3.0, 0.08], [2.5, 2.02]];
        let p = penetration(&setup, &radii, &pos);
        assert!((p.pair - 0.5).abs() < 1e-12, "{p:?}");
        assert!((p.wall - 0.8).abs() < 1e-12, "{p:?}");
        let outside = [[1.0, 1.0], [5.0, 2.0]];
        assert_eq!(penetration(&setup, &radii[..2], &outside).wall, 0.0);
        assert!(outside_box(&setup, outside[1]) && !outside_box(&setup, outside[0]));
    }

    #[test]
    fn percentiles_by_nearest_rank() {
        let s: Vec<f64> = (1..=100).map(f64::from).collect();
        assert_eq!(median_p99(&s), (50.0, 99.0));
        assert_eq!(median_p99(&[3.0]), (3.0, 3.0));
    }
}
