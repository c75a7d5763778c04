//! The growth setting and law: radii growing linearly in time. Its contacts are in
//! [`crate::contact::growth`].

use serde::{Deserialize, Serialize};

/// The growth setting of a scene (`settings.growth` in a scene file).
///
/// ```json
/// "settings": { "growth": { "rate": 0.01 } }
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Growth {
    /// `Γ`, per second: every radius grows by `Γ` times its scene value each second.
    pub rate: f64,
}

/// A growth law in force: radii at time `t` are the stored radii times [`GrowthLaw::scale`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GrowthLaw {
    /// `Γ`, per second.
    pub rate: f64,
    /// `t₀`, seconds: when radii equal the stored ones.
    pub origin: f64,
}

impl GrowthLaw {
    /// `1 + Γ·(t − t₀)`: the factor radii have at time `t`.
    #[must_use]
    #[inline]
    pub fn scale(&self, t: f64) -> f64 {
        1.0 + self.rate * (t - self.origin)
    }

    /// Radius at time `t`, metres, of a body whose stored radius is `r`.
    #[must_use]
    #[inline]
    pub fn radius_at(&self, r: f64, t: f64) -> f64 {
        r * self.scale(t)
    }

    /// Growth speed of a body whose stored radius is `r`, metres per second.
    #[must_use]
    #[inline]
    pub fn speed(&self, r: f64) -> f64 {
        r * self.rate
    }

    /// The first time `t ≥ from` at which a stored radius `r` has grown to `target` metres
    /// (`from` when it already has; `+∞` when it never will).
    #[must_use]
    pub fn time_to_reach(&self, r: f64, target: f64, from: f64) -> f64 {
        if self.radius_at(r, from) >= target {
            return from;
        }
        if self.rate <= 0.0 {
            return f64::INFINITY;
        }
        (self.origin + (target / r - 1.0) / self.rate).max(from)
    }
}
