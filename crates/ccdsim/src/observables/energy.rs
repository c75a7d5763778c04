//! The relative energy drift of a run: one definition for every tool that prints one
//! (`ccdsim run`, `ccdsim verify`, the Python bindings).

/// The energies of a run at its start and end, and the energy put in from outside.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EnergyBalance {
    /// Kinetic energy at the start, joules.
    pub kinetic_start: f64,
    /// Kinetic energy at the end, joules.
    pub kinetic_end: f64,
    /// Potential energy in the gravity field at the start, joules (`−Σ m g·x`; 0 without
    /// gravity).
    pub potential_start: f64,
    /// Potential energy at the end, joules.
    pub potential_end: f64,
    /// Energy put in from outside the collisions, joules: the work of moving walls and the
    /// energy a program's edits added (negative when they took some out).
    pub work: f64,
    /// Rotational kinetic energy at the start, joules (0 unless bodies spin, see
    /// [`crate::motion::spin`]).
    pub rotational_start: f64,
    /// Rotational kinetic energy at the end, joules.
    pub rotational_end: f64,
}

impl EnergyBalance {
    /// The relative energy drift: what the collisions changed of the total energy,
    ///
    /// `((K_end + U_end) − (K_start + U_start) − work) / max(K_start, K_end)`,
    ///
    /// the change of kinetic (translational plus rotational) plus potential energy not
    /// accounted for by outside work, relative to the larger kinetic energy (the potential energy's zero is arbitrary, so it
    /// cannot be the scale). Elastic collisions keep it at rounding level (about 1e-15 per
    /// collision); inelastic ones make it negative: without gravity, moving walls or edits it
    /// is `(K_end − K_start) / K_start`, the fraction of kinetic energy lost. 0 when there is
    /// no kinetic energy at either end.
    #[must_use]
    pub fn relative_drift(&self) -> f64 {
        let (start, end) = (
            self.kinetic_start + self.rotational_start,
            self.kinetic_end + self.rotational_end,
        );
        let scale = start.max(end);
        if scale.is_nan() || scale <= 0.0 {
            return 0.0;
        }
        let change = (end + self.potential_end) - (start + self.potential_start) - self.work;
        change / scale
    }
}

#[cfg(test)]
mod tests {
    use super::EnergyBalance;

    #[test]
    fn inelastic_loss_without_gravity_is_the_fraction_lost() {
        let b = EnergyBalance {
            kinetic_start: 8.0,
            kinetic_end: 2.0,
            ..EnergyBalance::default()
        };
        assert_eq!(b.relative_drift(), -0.75);
    }

    #[test]
    fn falling_converts_potential_energy_without_drift() {
        // A ball falls 5 m: 49.05 J of potential energy become kinetic energy.
        let b = EnergyBalance {
            kinetic_start: 0.0,
            kinetic_end: 49.05,
            potential_start: 0.0,
            potential_end: -49.05,
            ..EnergyBalance::default()
        };
        assert_eq!(b.relative_drift(), 0.0);
    }

    #[test]
    fn outside_work_is_not_drift() {
        let b = EnergyBalance {
            kinetic_start: 1.0,
            kinetic_end: 3.0,
            work: 2.0,
            ..EnergyBalance::default()
        };
        assert_eq!(b.relative_drift(), 0.0);
        let lost = EnergyBalance { work: 1.0, ..b };
        assert_eq!(lost.relative_drift(), 1.0 / 3.0);
    }

    #[test]
    fn no_kinetic_energy_no_drift() {
        assert_eq!(EnergyBalance::default().relative_drift(), 0.0);
    }
}
