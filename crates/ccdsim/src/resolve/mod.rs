//! Collision response: impulses along the contact normal, with masses and restitution.

mod rough;

use crate::contact::narrow::wall_normal;
use crate::contact::periodic::min_image;
use crate::geom::Vector;
use crate::wall::Wall;
use crate::world::World;

/// Resolves a body–body collision at time `t`: both bodies are moved to `t` and receive
/// equal and opposite impulses along the line of centres (walls are not involved). In a
/// periodic world the line of centres is that of the nearest images.
///
/// Returns the overlap depth at contact relative to the sum of radii (0 when not overlapping).
pub fn resolve_body_body<const D: usize>(world: &mut World<D>, i: usize, j: usize, t: f64) -> f64 {
    resolve_body_body_contact(world, i, j, t).overlap
}

/// What [`resolve_body_body_contact`] found at the contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact<const D: usize> {
    /// Overlap depth at contact relative to the sum of radii (0 when not overlapping).
    pub overlap: f64,
    /// `x_j − x_i` at the contact, metres (nearest images in a periodic world).
    pub separation: Vector<D>,
}

/// [`resolve_body_body`], also returning the separation of the centres at the contact, so
/// that a caller accumulating the collision virial does not take the minimum image again.
#[inline(always)]
pub fn resolve_body_body_contact<const D: usize>(
    world: &mut World<D>,
    i: usize,
    j: usize,
    t: f64,
) -> Contact<D> {
    if world.has_resting() {
        resolve_resting_pair(world, i, j, t)
    } else if world.is_rotational() {
        resolve_free_pair::<D, true>(world, i, j, t)
    } else {
        resolve_free_pair::<D, false>(world, i, j, t)
    }
}

/// [`resolve_body_body_contact`] where no body rests on a wall: the impulse along the line
/// of centres, and with `ROUGH` (a world that keeps spins) the tangential impulse of rough
/// bodies. Out of line and without calls out (see [`World::free_position_at`]), as it
/// always was: its values stay in registers, and smooth worlds' copy has no rough path.
#[inline(never)]
fn resolve_free_pair<const D: usize, const ROUGH: bool>(
    world: &mut World<D>,
    i: usize,
    j: usize,
    t: f64,
) -> Contact<D> {
    let (a, b) = (world.motion(i), world.motion(j));
    let (pi, pj, vi, vj) = match world.gravity() {
        None => (a.at(t), b.at(t), a.vel, b.vel),
        Some(_) => (
            world.free_position_at(i, t),
            world.free_position_at(j, t),
            world.free_velocity_at(i, t),
            world.free_velocity_at(j, t),
        ),
    };
    let (share_i, share_j) = mass_shares(world, i, j);
    // `vj_seen`: the velocity of the image of `j` that `i` meets, which in a sheared box
    // moves a layer's speed faster or slower than `j` (see `crate::contact::lees_edwards`).
    let (d, vj_seen) = match world.periodic() {
        Some(size) => match world.shear() {
            None => (min_image(pj - pi, &size), vj),
            Some(bx) => {
                let (d, layer) = bx.nearest_image(pj - pi, t);
                (d, bx.image_velocity(vj, layer))
            }
        },
        None => (pj - pi, vj),
    };
    let dist = d.norm();
    let sigma = world.radius_at(i, t) + world.radius_at(j, t);
    let (mut vi2, mut vj2) = (vi, vj);
    let e = world.pair_restitution(i, j, t);
    let mut collided = false;
    if let Some(law) = world.growth() {
        // Growing radii: reverse the speed at which the surfaces approach (see
        // `crate::contact::growth`): u' = (1 + e)·σ̇ − e·u along the line of centres.
        if dist > 0.0 {
            let n = d * (1.0 / dist);
            let grow = law.speed(world.radius(i) + world.radius(j));
            let vn = (vj - vi).dot(n);
            if vn < grow {
                let k = (1.0 + e) * (vn - grow);
                vi2 = vi + n * (k * share_i);
                vj2 = vj - n * (k * share_j);
                collided = true;
            }
        }
    } else if dist > 0.0 {
        let n = d * (1.0 / dist);
        let vn = (vj_seen - vi).dot(n);
        if vn < 0.0 {
            // Velocity changes J/mi and J/mj with J = −(1+e)·vn·mi·mj/(mi+mj), written as mass
            // fractions so that equal masses exchange normal velocities exactly (m/2m = 0.5).
            let k = (1.0 + e) * vn;
            vi2 = vi + n * (k * share_i);
            vj2 = vj - n * (k * share_j);
            collided = true;
        }
    }
    if ROUGH && collided {
        let n = d * (1.0 / dist);
        if let Some(kick) = rough::pair_kick(world, (i, vi), (j, vj_seen), n, t) {
            vi2 += kick.dv[0];
            vj2 += kick.dv[1];
            world.set_spin(i, kick.spins[0]);
            world.set_spin(j, kick.spins[1]);
        }
    }
    world.set_state(i, pi, vi2, t);
    world.set_state(j, pj, vj2, t);
    world.note_pair_collision(i, j, t);
    Contact {
        overlap: ((sigma - dist) / sigma).max(0.0),
        separation: d,
    }
}

/// Each body's share of a collision's velocity change: `m_j/(m_i + m_j)` and
/// `m_i/(m_i + m_j)`, or, against a kinematic body (infinite mass), all of it for the other
/// (∞/∞ is no number).
#[inline(always)]
fn mass_shares<const D: usize>(world: &World<D>, i: usize, j: usize) -> (f64, f64) {
    let (mi, mj) = (world.mass(i), world.mass(j));
    let shares = (mj / (mi + mj), mi / (mi + mj));
    if !world.has_kinematic() {
        return shares;
    }
    match (mi == f64::INFINITY, mj == f64::INFINITY) {
        (false, false) => shares,
        (false, true) => (1.0, 0.0),
        (true, false) => (0.0, 1.0),
        (true, true) => (0.0, 0.0),
    }
}

/// [`resolve_body_body_contact`] where bodies rest on walls (see [`crate::contact::resting`]; such
/// worlds have gravity, fixed radii and no periodic box). A resting body stays on its plane
/// when the collision pressed it into it ([`pressed_impulse`]), or left its
/// velocity as it was (the pair was already parting).
#[inline(never)]
fn resolve_resting_pair<const D: usize>(
    world: &mut World<D>,
    i: usize,
    j: usize,
    t: f64,
) -> Contact<D> {
    let (pi, pj) = (world.position_at(i, t), world.position_at(j, t));
    let (vi, vj) = (world.velocity_at(i, t), world.velocity_at(j, t));
    let d = pj - pi;
    let dist = d.norm();
    let sigma = world.radius(i) + world.radius(j);
    let e = world.pair_restitution(i, j, t);
    let (mut vi2, mut vj2) = (vi, vj);
    let mut held = (false, false);
    let n = d * (1.0 / dist);
    let vn = if dist > 0.0 { (vj - vi).dot(n) } else { 0.0 };
    if let Some((v2, by)) = pressed_impulse(world, (i, vi), (j, vj), n, vn, e) {
        ((vi2, vj2), held) = (v2, by);
    } else if vn < 0.0 {
        // The free collision, as in `resolve_body_body_contact` (no growth under gravity).
        let (share_i, share_j) = mass_shares(world, i, j);
        let k = (1.0 + e) * vn;
        vi2 = vi + n * (k * share_i);
        vj2 = vj - n * (k * share_j);
    }
    let supports = (world.support(i), world.support(j));
    world.set_state(i, pi, vi2, t);
    world.set_state(j, pj, vj2, t);
    if let (Some(w), true) = (supports.0, held.0 || vi2 == vi) {
        world.rest_on(i, w);
    }
    if let (Some(w), true) = (supports.1, held.1 || vj2 == vj) {
        world.rest_on(j, w);
    }
    world.note_pair_collision(i, j, t);
    Contact {
        overlap: ((sigma - dist) / sigma).max(0.0),
        separation: d,
    }
}

/// Resolves a collision of body `i` with wall `w` at time `t`: the body is moved to `t` and
/// the normal component of its velocity relative to the wall reflected (scaled by the
/// restitution); the wall, static or moving (`w ≥ walls().len()`, see
/// [`crate::world::time_of_impact`]), has infinite mass and keeps its velocity. Under growing radii
/// the speed reflected is that of the body's surface relative to the wall, `(v − w)·n − Γ·r`
/// (see [`crate::contact::growth`]).
///
/// Under `settings.rest_speed` a body that leaves a static wall gravity presses it on at a
/// normal speed of at most that speed comes to rest on it instead, its normal velocity
/// removed ([`World::support`] is then `w`; see [`crate::contact::resting`]). A body meeting the
/// segment it slides on has reached its end: see [`resolve_slide_end`].
///
/// Returns the overlap depth at contact relative to the radius (0 when not overlapping).
pub fn resolve_body_wall<const D: usize>(world: &mut World<D>, i: usize, w: usize, t: f64) -> f64 {
    let p = world.position_at(i, t);
    let v = world.velocity_at(i, t);
    let wall = world.wall_at(w, t);
    let r = world.radius_at(i, t);
    // Growing radii: the surface moves towards the wall at the growth speed too (see
    // `crate::contact::growth`).
    let grow = world.growth().map_or(0.0, |law| law.speed(world.radius(i)));
    let mut v2 = v;
    let mut rests = false;
    if let Some(n) = wall_normal(&wall, p) {
        // A static wall's velocity is zero, and `v − 0` is `v` bit for bit.
        let vn = (v - world.wall_velocity(w)).dot(n) - grow;
        if vn < 0.0 {
            v2 = v - n * ((1.0 + world.wall_restitution(i, t)) * vn);
            if world.is_rotational() {
                if let Some((dv, spin)) =
                    rough::wall_kick(world, (i, v), world.wall_velocity(w), n, t)
                {
                    v2 += dv;
                    world.set_spin(i, spin);
                }
            }
        }
        if let (Some(rest_speed), Some(_), Some(g)) =
            (world.rest_speed(), world.slide_of(w), world.gravity())
        {
            if crate::contact::resting::comes_to_rest(v2.dot(n), rest_speed)
                && crate::contact::resting::held_at(&wall, &g, p)
            {
                v2 = crate::contact::resting::along_support(&v2, &wall);
                rests = true;
            }
        }
    }
    let clearance = crate::wall::wall_clearance(&wall, p);
    world.set_state(i, p, v2, t);
    if rests {
        world.rest_on(i, w);
    }
    world.note_collision(i, t);
    ((r - clearance) / r).max(0.0)
}

/// What became of a body that slid to the end of its segment ([`resolve_slide_end`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlideEnd {
    /// It rests on this segment, which goes straight on.
    GoesOn(usize),
    /// It flies clear of the edge, falling.
    FliesClear,
    /// It turns about the end point ([`crate::motion::pivot`]); `laws_changed` when parking it gave
    /// the world its first collision filter (re-initialise a finder then).
    Pivots {
        /// See [`World::start_pivot`](crate::World::pivot).
        laws_changed: bool,
    },
}

/// Resolves the arrival of body `i`, sliding on segment `w`, at the segment's end at time `t`
/// (see [`crate::contact::ledge`]): it rests on the segment that goes straight on from there, if
/// there is one, its velocity projected onto it; otherwise it flies off if it is fast enough
/// to clear the edge, its state as it was, falling under gravity from now on; otherwise it
/// turns about the end point ([`crate::motion::pivot`], 2D), parked for the finders (see
/// [`World::pivot`]).
pub fn resolve_slide_end<const D: usize>(
    world: &mut World<D>,
    i: usize,
    w: usize,
    t: f64,
) -> SlideEnd {
    let p = world.position_at(i, t);
    let v = world.velocity_at(i, t);
    let Wall::Segment { a, b } = world.walls()[w] else {
        unreachable!("bodies slide to the ends of segments only");
    };
    let end = crate::contact::ledge::end_reached(a, b, p);
    if let Some(next) = crate::contact::ledge::continuation(world.walls(), world.slides(), w, end) {
        let v2 = crate::contact::resting::along_support(&v, &world.walls()[next]);
        world.set_state(i, p, v2, t);
        world.rest_on(i, next);
        return SlideEnd::GoesOn(next);
    }
    let g = world.gravity().expect("bodies slide under gravity");
    let m = crate::motion::Motion {
        pos: p,
        vel: v,
        time: t,
    };
    let pivot = (D == 2 && !crate::contact::ledge::flies_clear(&m, end, &g))
        .then(|| {
            use crate::motion::pivot::to_2d;
            crate::motion::pivot::Pivot::new(
                to_2d(end),
                world.radius(i),
                to_2d(g),
                to_2d(p),
                to_2d(v),
                t,
            )
        })
        .flatten();
    match pivot {
        Some(pivot) => SlideEnd::Pivots {
            laws_changed: world.start_pivot(i, pivot, w, (p, v)),
        },
        None => {
            world.set_state(i, p, v, t);
            world.depart(i, w);
            SlideEnd::FliesClear
        }
    }
}

/// Applies the exit of body `i` through face `face` (see [`crate::contact::periodic`]) of the periodic
/// box at time `t`: the body is moved to `t` and then by one period back into the box along
/// the face's axis. Its velocity is unchanged, but in a sheared box, where a body leaving
/// through a y face also moves along x and changes its x velocity ([`ShearedBox::exit`]).
/// Returns the whole periods to add to the body's x image count (0 but in a sheared box).
///
/// [`ShearedBox::exit`]: crate::contact::lees_edwards::ShearedBox::exit
pub fn resolve_exit<const D: usize>(world: &mut World<D>, i: usize, face: usize, t: f64) -> i64 {
    if let Some(bx) = world.shear() {
        let (p, v, x_periods) = bx.exit(world.position_at(i, t), world.velocity(i), face, t);
        world.set_state(i, p, v, t);
        return x_periods;
    }
    let size = world
        .periodic()
        .expect("box exits happen in periodic worlds only");
    let mut p = world.position_at(i, t);
    let axis = face / 2;
    if face % 2 == 1 {
        p[axis] -= size[axis];
    } else {
        p[axis] += size[axis];
    }
    let v = world.velocity(i);
    world.set_state(i, p, v, t);
    0
}

/// The velocities after a collision of bodies `i` and `j` (velocities `vi`, `vj` at the
/// contact, `n` the unit vector from `i` to `j`, `vn = (vj − vi)·n < 0`, restitution `e`)
/// when it presses one of them, or both, into the wall it rests on: such a body is held by
/// its wall, which takes the normal part of its push, so it moves along the wall only
/// (its velocity changes along `P n`, `P` the projection onto the wall). The pair's
/// impulse `J = −(1 + e) vn / (w_i (P_i n)·n + w_j (P_j n)·n)` (`w` the inverse masses, 0
/// for a kinematic body; `P = 1` for a body not held) reverses their normal speed times
/// `e` as a free collision does. Returns the two velocities and which body its wall
/// held; `None` when no body is pressed into its wall (or the pair parts), for the free
/// collision.
#[must_use]
#[inline(never)]
#[allow(clippy::type_complexity)]
pub fn pressed_impulse<const D: usize>(
    world: &World<D>,
    (i, vi): (usize, Vector<D>),
    (j, vj): (usize, Vector<D>),
    n: Vector<D>,
    vn: f64,
    e: f64,
) -> Option<((Vector<D>, Vector<D>), (bool, bool))> {
    if vn >= 0.0 {
        return None;
    }
    // The direction the pair's impulse moves body `k` (pushed along `push`) and the wall
    // that holds it, if one does.
    let g = world.gravity().unwrap_or(Vector::ZERO);
    let held = |k: usize, push: Vector<D>| match world.support(k).map(|w| world.walls()[w]) {
        Some(wall) if push.dot(crate::contact::resting::support_normal(&wall, &g)) < 0.0 => (
            crate::contact::resting::along_support(&push, &wall),
            Some(wall),
        ),
        _ => (push, None),
    };
    let (ui, hi) = held(i, Vector::ZERO - n);
    let (uj, hj) = held(j, n);
    if hi.is_none() && hj.is_none() {
        return None;
    }
    let inverse = |k: usize| 1.0 / world.mass(k);
    let (wi, wj) = (inverse(i), inverse(j));
    let denominator = wi * ui.dot(Vector::ZERO - n) + wj * uj.dot(n);
    if denominator <= 0.0 {
        // Pressed straight into its wall by a kinematic body: no motion takes the push.
        return None;
    }
    let impulse = -(1.0 + e) * vn / denominator;
    let along = |v: Vector<D>, u: Vector<D>, w: f64, wall: Option<Wall<D>>| {
        let v2 = v + u * (impulse * w);
        // On its wall to the last bit where the wall is axis-aligned.
        wall.map_or(v2, |wall| {
            crate::contact::resting::along_support(&v2, &wall)
        })
    };
    Some((
        (along(vi, ui, wi, hi), along(vj, uj, wj, hj)),
        (hi.is_some(), hj.is_some()),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::periodic::min_image;
    use crate::scene::{BodySpec, Scene};

    fn body(x: f64, vx: f64) -> BodySpec<2> {
        BodySpec {
            id: None,
            pos: Vector([x, 5.0]),
            vel: Vector([vx, 0.0]),
            radius: 0.5,
            mass: None,
            restitution: None,
            kinematic: false,
            group: None,
            mask: None,
            inertia: None,
            spin: None,
            tangential_restitution: None,
        }
    }

    #[test]
    fn contact_separation_is_the_nearest_image_and_its_negation_the_virial_lever() {
        // Two discs touching across the periodic face x = 0 ≡ 10.
        let mut scene = Scene::<2> {
            bodies: vec![body(0.5, -1.0), body(9.5, 1.0)],
            ..Scene::default()
        };
        scene.periodic = Some(Vector([10.0, 10.0]));
        let mut world = World::from_scene(&scene).unwrap();
        let size = world.periodic().unwrap();
        let contact = resolve_body_body_contact(&mut world, 0, 1, 0.0);
        assert_eq!(contact.separation.0, [-1.0, 0.0]);
        assert_eq!(contact.overlap, 0.0);
        let r = min_image(world.position(0) - world.position(1), &size);
        assert_eq!(r, -contact.separation);
        // Equal masses exchange their normal velocities.
        assert_eq!(world.velocity(0).0, [1.0, 0.0]);
        assert_eq!(world.velocity(1).0, [-1.0, 0.0]);
    }
}
