//! The angular velocities of a world of rough bodies, with each body's inertia factor and
//! tangential restitution (see [`crate::motion::spin`]). A world whose scene sets none of
//! these keeps none of it: smooth bodies pay nothing for rotation.

use crate::geom::Vector;
use crate::scene::{BodySpec, Scene};

/// Per-slot rotational state, present in a world whose scene is rotational
/// ([`Scene::is_rotational`]).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Rotation {
    /// Angular velocity of each slot, radians per second (zero for vacant slots).
    pub(crate) spins: Vec<Vector<3>>,
    /// Moment-of-inertia factor `q` of each slot (`I = q·m·r²`).
    pub(crate) inertia: Vec<f64>,
    /// Tangential restitution `β` of each slot.
    pub(crate) tangential: Vec<f64>,
    /// The scene's tangential restitution: the default of added bodies (−1, smooth, when the
    /// scene sets none).
    pub(crate) default_tangential: f64,
    /// The default inertia factor of the world's dimension.
    pub(crate) default_inertia: f64,
}

impl Rotation {
    /// The rotational state of `scene`'s bodies at its start, or `None` for a scene of smooth
    /// bodies that sets no spin.
    pub(crate) fn of<const D: usize>(scene: &Scene<D>) -> Option<Self> {
        let r = scene.body_rotations()?;
        Some(Rotation {
            spins: r.spins,
            inertia: r.inertia,
            tangential: r.tangential,
            default_tangential: r.default_tangential,
            default_inertia: r.default_inertia,
        })
    }

    /// Appends a vacant slot: no spin, the defaults.
    pub(crate) fn push_vacant(&mut self) {
        self.spins.push(Vector::ZERO);
        self.inertia.push(self.default_inertia);
        self.tangential.push(self.default_tangential);
    }

    /// Fills slot `i` with a body added by a program: it starts without spin, with the
    /// defaults (a spec that sets rotational fields is refused before it gets here, because
    /// run files do not record them).
    pub(crate) fn occupy<const D: usize>(&mut self, i: usize, spec: &BodySpec<D>) {
        debug_assert!(!spec.is_rotational());
        self.spins[i] = Vector::ZERO;
        self.inertia[i] = self.default_inertia;
        self.tangential[i] = self.default_tangential;
    }
}
