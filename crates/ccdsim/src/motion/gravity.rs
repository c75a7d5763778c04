//! The gravity setting: a uniform acceleration of every dynamic body. Its contacts are in
//! [`crate::contact::gravity`].

use crate::geom::Vector;
use serde::{Deserialize, Serialize};

/// The gravity setting of a scene (`settings.gravity` in a scene file): the acceleration
/// every body undergoes, metres per second squared, with as many components as the scene
/// has dimensions.
///
/// ```json
/// "settings": { "gravity": [0.0, -9.81] }
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gravity {
    components: [f64; 3],
    len: usize,
}

impl Gravity {
    /// Gravity with the given components (2 or 3); `None` for any other count.
    #[must_use]
    pub fn new(components: &[f64]) -> Option<Self> {
        if !(2..=3).contains(&components.len()) {
            return None;
        }
        let mut c = [0.0; 3];
        c[..components.len()].copy_from_slice(components);
        Some(Gravity {
            components: c,
            len: components.len(),
        })
    }

    /// The components as written.
    #[must_use]
    pub fn components(&self) -> &[f64] {
        &self.components[..self.len]
    }

    /// The acceleration as a vector of a `D`-dimensional world; `None` when the setting has
    /// another number of components.
    #[must_use]
    pub fn vector<const D: usize>(&self) -> Option<Vector<D>> {
        Vector::from_slice(self.components())
    }
}

impl Serialize for Gravity {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.components().serialize(s)
    }
}

impl<'de> Deserialize<'de> for Gravity {
    fn deserialize<De: serde::Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        let v = Vec::<f64>::deserialize(d)?;
        Gravity::new(&v).ok_or_else(|| {
            serde::de::Error::custom(format!(
                "gravity has {} components; it needs one per dimension (2 or 3)",
                v.len()
            ))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gravity_setting_reads_two_or_three_components() {
        let g: Gravity = serde_json::from_str("[0, -9.81]").unwrap();
        assert_eq!(g.vector::<2>(), Some(Vector([0.0, -9.81])));
        assert_eq!(g.vector::<3>(), None);
        assert_eq!(serde_json::to_string(&g).unwrap(), "[0.0,-9.81]");
        let err = serde_json::from_str::<Gravity>("[1]").unwrap_err();
        assert!(err.to_string().contains("1 components"), "{err}");
    }
}
