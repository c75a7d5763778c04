//! The isostatic finish: from a compressed packing to the nearest jammed one.
//!
//! Lubachevsky–Stillinger compression reaches a high pressure before the contact network is
//! rigid: the growth itself holds the packing up, and once it stops the pressure falls by
//! orders of magnitude. [`finish_isostatic`] takes the compressed packing to its jamming point
//! the way O'Hern, Silbert, Liu & Nagel (Phys. Rev. E 68, 011306, 2003) find the jamming
//! point of soft spheres: the bodies are made soft ([`super::soft`]), all radii are scaled by
//! a common factor `s`, and the energy is minimised; the packing is jammed at `s` when
//! overlaps remain at the minimum. A first factor above 1 jams it; then each step shrinks
//! the radii by most of the mean overlap (which is proportional to the distance from the
//! jamming point), or bisects when a step overshoots, until the mean overlap of the jammed
//! minimum is below the target. Only minima whose forces balanced within the steps allowed,
//! and whose mean overlap is not far below the target ([`MARGINAL`]), count as jammed: one
//! that ran out of steps may still be unjamming, and one with next to no overlap sits on
//! the jamming point, where contacts carrying no force cannot be told from gaps. The contacts of that minimum carry balanced forces, so after
//! removing rattlers they hold the packing rigid: the contact count is isostatic, `2D` per
//! body less `O(1/N)`.
//!
//! The packing returned is hard again: its radii are those of the last jammed minimum less
//! its largest overlap, so no pair overlaps, and its contacts are the pairs that overlapped,
//! whose gaps are now within twice that overlap of their contact distance.

use crate::contact::periodic::wrap_point;
use crate::geom::Vector;
use crate::packing::contacts::contact_network;
use crate::packing::soft::{Minimum, SoftPacking, Tolerance};
use crate::packing::{packing_fraction, CompressError, Packed};
use crate::scene::Scene;
use crate::sim::Simulation;

/// Steps towards the jamming point [`finish_isostatic`] takes before it gives up (a search
/// takes 5 to 10).
const MAX_ROUNDS: usize = 200;

/// Times [`finish_isostatic`] looks again below a jammed minimum whose bracket has closed
/// with its overlap still above the target, before it settles for that minimum.
const MAX_RELOOKS: usize = 3;

/// Jammed minima whose mean overlap is below this fraction of the target count as not
/// jammed (see [`finish_isostatic`]).
const MARGINAL: f64 = 1e-2;

/// The fraction of the jammed minimum's mean overlap below which a bracket counts as closed
/// (see [`bracket_closed`]).
const BRACKET_RESOLUTION: f64 = 1e-2;

/// How [`finish_isostatic`] runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IsostaticConfig {
    /// Stop when the mean relative overlap of the jammed minimum is at most this: the
    /// returned packing's touching pairs have gaps of about this fraction of their contact
    /// distance (a hard-sphere packing at reduced pressure `Z` has gaps of about `D / Z`).
    pub overlap: f64,
    /// FIRE steps allowed per minimisation.
    pub max_steps: u64,
}

impl Default for IsostaticConfig {
    fn default() -> Self {
        IsostaticConfig {
            overlap: 1e-6,
            max_steps: 200_000,
        }
    }
}

/// A jammed minimum on the way: its radius factor, how it went and where the bodies are.
struct Jammed<const D: usize> {
    scale: f64,
    minimum: Minimum,
    positions: Vec<Vector<D>>,
    /// Minimised to the strict tolerance.
    strict: bool,
}

impl<const D: usize> Jammed<D> {
    fn new(scale: f64, minimum: Minimum, positions: &[Vector<D>]) -> Self {
        Jammed {
            scale,
            minimum,
            positions: positions.to_vec(),
            strict: false,
        }
    }
}

/// What [`finish_isostatic`] did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IsostaticFinish {
    /// Energy minimisations run.
    pub minimizations: usize,
    /// FIRE steps over all of them.
    pub steps: u64,
    /// Mean relative overlap of the last jammed minimum.
    pub mean_overlap: f64,
    /// Largest relative overlap of the last jammed minimum (the radii were reduced by it).
    pub max_overlap: f64,
    /// Factor between the returned radii and the compressed packing's.
    pub radius_scale: f64,
}

/// Takes a compressed packing to its jamming point (see the module docs), calling
/// `on_jammed` with the mean relative overlap of each jammed minimum on the way (they fall
/// towards `config.overlap`); the result's `finish` says what it took and its `contacts` are
/// the last jammed minimum's.
pub fn finish_isostatic<const D: usize>(
    packed: &Packed<D>,
    config: &IsostaticConfig,
    mut on_jammed: impl FnMut(f64),
) -> Result<Packed<D>, CompressError> {
    if !(config.overlap.is_finite() && config.overlap > 0.0 && config.overlap < 1e-2) {
        return Err(CompressError::Config(
            "the target overlap must be a number in (0, 0.01)".into(),
        ));
    }
    let scene = &packed.scene;
    let r_max = scene.bodies.iter().map(|b| b.radius).fold(0.0, f64::max);
    if let Some(size) = scene.periodic {
        // The soft packing's pairs overlap through one image only.
        if size.0.iter().any(|&l| l <= 2.0 * (2.0 * r_max) * 1.1) {
            return Err(CompressError::Config(
                "the periodic box must be wider than 4.4 of the largest radii".into(),
            ));
        }
    }
    let wrapped: Vec<Vector<D>> = scene
        .bodies
        .iter()
        .map(|b| match scene.periodic {
            Some(size) => wrap_point(b.pos, &size),
            None => b.pos,
        })
        .collect();
    // The soft packing holds the bodies in the order of a grid of cells one diameter wide,
    // so that neighbours sit near each other in memory.
    let order = spatial_order(&wrapped, 2.0 * r_max);
    let positions: Vec<Vector<D>> = order.iter().map(|&i| wrapped[i]).collect();
    let radii: Vec<f64> = order.iter().map(|&i| scene.bodies[i].radius).collect();
    // Steps on the way only need to tell jammed from not and to locate the jamming point;
    // the last minimum balances its forces a hundred times more closely. (Looser steps on the
    // way misjudge which sizes jam: the minimum found last then slides towards unjamming.)
    let loose = Tolerance {
        relative_force: 1e-4,
        max_steps: config.max_steps,
    };
    let strict = Tolerance {
        relative_force: 1e-6,
        ..loose
    };
    let mut soft = SoftPacking::new(positions, radii, &scene.walls, scene.periodic);
    let mut minimizations = 0usize;
    let mut steps = 0u64;
    let mut minimize_at =
        |soft: &mut SoftPacking<D>, from: &[Vector<D>], s: f64, tolerance: &Tolerance| {
            soft.positions.copy_from_slice(from);
            soft.set_scale(s);
            let m = soft.minimize(tolerance);
            minimizations += 1;
            steps += m.steps;
            m
        };
    // Over-compress until the minimum keeps overlaps.
    let start = soft.positions.clone();
    let mut s_lo = 1.0f64;
    let mut grow = 4e-3;
    let mut hi = loop {
        let s = 1.0 + grow;
        let m = minimize_at(&mut soft, &start, s, &loose);
        if m.jammed() && m.converged {
            break Jammed::new(s, m, &soft.positions);
        }
        // Unjammed, or so near the jamming point that the minimisation ran out of steps
        // (the closer, the slower): compress further, where the minimum is found fast.
        if m.converged {
            s_lo = s;
        }
        grow *= 4.0;
        if grow > 0.3 {
            return Err(far_from_jammed());
        }
    };
    on_jammed(hi.minimum.mean_overlap);
    // The jammed minimum before `hi`, for the secant and the warm start.
    let mut before: Option<Jammed<D>> = None;
    let mut guess = hi.positions.clone();
    let mut rounds = 0usize;
    let mut relooks = 0usize;
    loop {
        rounds += 1;
        if rounds > MAX_ROUNDS {
            return Err(CompressError::Config(format!(
                "the jamming point was not found in {MAX_ROUNDS} steps"
            )));
        }
        let close = hi.minimum.mean_overlap <= config.overlap;
        let mut unresolved = bracket_closed(&hi, s_lo);
        if unresolved && !close && !hi.strict && relooks < MAX_RELOOKS {
            // The bracket closed on a jammed minimum whose overlap is still far above the
            // target: the size below it was judged unjammed from other positions (a soft
            // packing's minimum depends on where the minimisation starts, and a jammed branch
            // can end abruptly), so look below it again from this minimum's positions.
            relooks += 1;
            s_lo = 1.0;
            before = None;
            unresolved = false;
        }
        if (close || unresolved) && hi.strict {
            break;
        }
        let (s, tolerance) = if close || unresolved {
            (hi.scale, &strict)
        } else {
            // The mean overlap falls linearly to zero at the jamming point, found by the
            // secant through the last two jammed minima.
            let ov = hi.minimum.mean_overlap;
            let jamming = match &before {
                Some(b) if b.minimum.mean_overlap > ov => {
                    hi.scale - ov * (b.scale - hi.scale) / (b.minimum.mean_overlap - ov)
                }
                _ => hi.scale * (1.0 - 1.5 * ov),
            };
            // A tenth of the way, or just past the target when that is nearer: the last
            // minima, near the jamming point, are the slow ones. (A thirtieth of the way
            // starts the next minimisation too far from its minimum: at N = 3000 one ran
            // out of 2 × 10⁵ steps.)
            let fraction = (0.7 * config.overlap / ov).max(0.1);
            let mut s = jamming + fraction * (hi.scale - jamming);
            if !(s > s_lo && s < hi.scale) {
                s = 0.5 * (s_lo + hi.scale);
            }
            (s, &loose)
        };
        // Start from the positions the last two minima extrapolate to.
        guess.copy_from_slice(&hi.positions);
        if let Some(b) = &before {
            let k = (s - hi.scale) / (hi.scale - b.scale);
            for ((g, h), p) in guess.iter_mut().zip(&hi.positions).zip(&b.positions) {
                *g = *h + (*h - *p) * k;
            }
        }
        let m = minimize_at(&mut soft, &guess, s, tolerance);
        let strict_now = std::ptr::eq(tolerance, &strict);
        if counts_as_jammed(&m, strict_now, s, &hi, config.overlap) {
            let next = Jammed {
                strict: strict_now,
                ..Jammed::new(s, m, &soft.positions)
            };
            if s < hi.scale {
                before = Some(std::mem::replace(&mut hi, next));
            } else {
                hi = next;
            }
            on_jammed(hi.minimum.mean_overlap);
        } else if s < hi.scale {
            s_lo = s;
        } else {
            // The loose minimum was not jammed after all: go back to the one before, or, if
            // it was the first, compress further, with the strict tolerance.
            s_lo = s;
            hi = match before.take() {
                Some(b) => b,
                None => {
                    let mut grow = 4.0 * (s - 1.0);
                    loop {
                        if grow > 0.3 {
                            return Err(far_from_jammed());
                        }
                        let s = 1.0 + grow;
                        let m = minimize_at(&mut soft, &start, s, &strict);
                        if m.jammed() {
                            break Jammed {
                                strict: true,
                                ..Jammed::new(s, m, &soft.positions)
                            };
                        }
                        s_lo = s;
                        grow *= 4.0;
                    }
                }
            };
        }
    }
    let s_hi = hi.scale;
    let at_hi = hi.positions;
    // The last jammed minimum, its contacts, and its radii less the largest overlap, in the
    // scene's order.
    soft.positions.copy_from_slice(&at_hi);
    soft.set_scale(s_hi);
    let (mean_overlap, max_overlap) = soft.overlaps();
    let mut positions = vec![Vector::default(); order.len()];
    let mut radii = vec![0.0; order.len()];
    for (k, &i) in order.iter().enumerate() {
        positions[i] = match scene.periodic {
            Some(size) => wrap_point(soft.positions[k], &size),
            None => soft.positions[k],
        };
        radii[i] = soft.radii()[k];
    }
    let contacts = contact_network(&positions, &radii, &scene.walls, scene.periodic, 0.0);
    let shrink = (1.0 - max_overlap) * (1.0 - 1e-13);
    let mut bodies = scene.bodies.clone();
    for (b, (&p, &r)) in bodies.iter_mut().zip(positions.iter().zip(&radii)) {
        b.pos = p;
        b.radius = r * shrink;
    }
    let finished = Scene {
        bodies,
        ..scene.clone()
    };
    let sim = Simulation::new(&finished, "all-pairs")?;
    let fraction = packing_fraction(sim.world(), sim.time()).unwrap_or(0.0);
    Ok(Packed {
        scene: finished,
        packing_fraction: fraction,
        reduced_pressure: packed.reduced_pressure,
        events: packed.events,
        time: packed.time,
        stop: packed.stop,
        contacts,
        contact_tolerance: 2.0 * max_overlap,
        finish: Some(IsostaticFinish {
            minimizations,
            steps,
            mean_overlap,
            max_overlap,
            radius_scale: s_hi * shrink,
        }),
    })
}

/// Whether the minimum `m` found at radius factor `s` (with the strict tolerance or not) counts
/// as jammed, `hi` being the jammed minimum the search holds. Not when:
/// * no overlap beyond rounding is left ([`Minimum::jammed`]);
/// * a loose minimisation ran out of steps before its forces balanced: it may still be
///   unjamming (near the jamming point minima are slow to find);
/// * at `hi`'s size or larger, its overlaps mostly relaxed away: the loose minimum `hi` was
///   sliding towards unjamming;
/// * its mean overlap is below [`MARGINAL`] of the `target`: it sits so near the jamming point
///   that contacts carrying next to no force cannot be told from gaps.
fn counts_as_jammed<const D: usize>(
    m: &Minimum,
    strict: bool,
    s: f64,
    hi: &Jammed<D>,
    target: f64,
) -> bool {
    let settled = m.converged || strict;
    let sliding = s >= hi.scale && m.mean_overlap < 0.5 * hi.minimum.mean_overlap;
    let marginal = m.mean_overlap < MARGINAL * target;
    m.jammed() && settled && !sliding && !marginal
}

/// Whether the bracket between the size judged unjammed, `s_lo`, and the jammed minimum `hi`
/// is too narrow to search: sizes within it can lower `hi`'s mean overlap by at most
/// [`BRACKET_RESOLUTION`] of itself (overlaps fall at most as fast as the radius factor, in
/// relative terms: at fixed positions `δ = 1 − d/(sσ)` moves by `ds/s`), or it has shrunk to
/// rounding. Bisecting further would spend rounds of minimisations that find the same minimum
/// (they take no steps), up to [`MAX_ROUNDS`].
fn bracket_closed<const D: usize>(hi: &Jammed<D>, s_lo: f64) -> bool {
    let width = hi.scale - s_lo;
    width <= 4.0 * f64::EPSILON * hi.scale
        || width <= BRACKET_RESOLUTION * hi.minimum.mean_overlap * hi.scale
}

fn far_from_jammed() -> CompressError {
    CompressError::Config(
        "the packing does not jam when its radii grow by 30 %: it is far from jammed".into(),
    )
}

/// Body indices sorted by the cell of side `cell` that holds each position (cells in the
/// order of their coordinates, last axis slowest).
fn spatial_order<const D: usize>(positions: &[Vector<D>], cell: f64) -> Vec<usize> {
    let key = |p: &Vector<D>| -> [i64; D] {
        std::array::from_fn(|d| (p[D - 1 - d] / cell).floor() as i64)
    };
    let mut order: Vec<usize> = (0..positions.len()).collect();
    if cell > 0.0 {
        order.sort_by_key(|&i| key(&positions[i]));
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;

    fn minimum(mean_overlap: f64, converged: bool) -> Minimum {
        Minimum {
            energy_per_body: mean_overlap * mean_overlap,
            mean_overlap,
            max_overlap: 4.0 * mean_overlap,
            steps: 1000,
            converged,
            rounding: 1e-12,
        }
    }

    #[test]
    fn a_bracket_closes_when_bisecting_it_cannot_lower_the_overlap_by_a_hundredth() {
        // The case an N = 10⁴ search once bisected forty times, every minimisation taking no
        // step: a size judged unjammed (its minimisation ran out of steps) just below a jammed
        // minimum whose overlap was still 7 × 10⁻⁶.
        let hi = Jammed::<3>::new(1.0014121, minimum(6.8e-6, true), &[]);
        assert!(bracket_closed(&hi, hi.scale - 5e-8));
        assert!(!bracket_closed(&hi, hi.scale - 1e-6));
        assert!(!bracket_closed(&hi, 1.0014042));
        // Near the target the bracket narrows with the overlap; rounding closes it at last.
        let tiny = Jammed::<3>::new(1.0014, minimum(1e-15, true), &[]);
        assert!(!bracket_closed(&tiny, tiny.scale - 1e-14));
        assert!(bracket_closed(
            &tiny,
            tiny.scale * (1.0 - 2.0 * f64::EPSILON)
        ));
    }

    #[test]
    fn only_settled_minima_clear_of_the_jamming_point_count_as_jammed() {
        let hi = Jammed::<3>::new(1.002, minimum(1e-4, true), &[]);
        let target = 1e-6;
        // Below `hi`, settled, overlap above the target: jammed.
        assert!(counts_as_jammed(
            &minimum(2e-5, true),
            false,
            1.0015,
            &hi,
            target
        ));
        // A loose minimisation that ran out of steps may still be unjamming; a strict one
        // that did so is taken as it is.
        assert!(!counts_as_jammed(
            &minimum(2e-5, false),
            false,
            1.0015,
            &hi,
            target
        ));
        assert!(counts_as_jammed(
            &minimum(2e-5, false),
            true,
            1.0015,
            &hi,
            target
        ));
        // Overlaps far below the target (the case a 3D N = 3000 search once ended on, with
        // 1.3 × 10⁻¹¹ and too few contacts to hold the packing): not jammed.
        assert!(!counts_as_jammed(
            &minimum(1.3e-11, true),
            true,
            1.0015,
            &hi,
            target
        ));
        assert!(counts_as_jammed(
            &minimum(1.1e-8, true),
            true,
            1.0015,
            &hi,
            target
        ));
        // At `hi`'s size, overlaps that relax to less than half of `hi`'s: sliding.
        assert!(!counts_as_jammed(
            &minimum(4e-5, true),
            true,
            1.002,
            &hi,
            target
        ));
        assert!(counts_as_jammed(
            &minimum(6e-5, true),
            true,
            1.002,
            &hi,
            target
        ));
        // Nothing left beyond rounding.
        assert!(!counts_as_jammed(
            &minimum(1e-13, true),
            true,
            1.0015,
            &hi,
            1e-12
        ));
    }
}
