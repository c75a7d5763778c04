//! Vectors and axis-aligned boxes over a const-generic dimension `D` (2 or 3), `f64` throughout.

use serde::de::{Error as DeError, SeqAccess, Visitor};
use serde::ser::SerializeTuple;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;
use std::ops::{Add, AddAssign, Index, IndexMut, Mul, Neg, Sub, SubAssign};

/// A point or displacement in `D`-dimensional space (metres, metres per second, …).
#[derive(Clone, Copy, PartialEq, Debug)]
pub struct Vector<const D: usize>(pub [f64; D]);

impl<const D: usize> Default for Vector<D> {
    fn default() -> Self {
        Self::ZERO
    }
}

impl<const D: usize> Vector<D> {
    /// The zero vector.
    pub const ZERO: Self = Vector([0.0; D]);

    /// Builds a vector from a slice; `None` when the slice length is not `D`.
    #[must_use]
    pub fn from_slice(s: &[f64]) -> Option<Self> {
        <[f64; D]>::try_from(s).ok().map(Vector)
    }

    /// Inner product.
    #[must_use]
    #[inline]
    pub fn dot(self, o: Self) -> f64 {
        let mut s = 0.0;
        for k in 0..D {
            s += self.0[k] * o.0[k];
        }
        s
    }

    /// Squared Euclidean length.
    #[must_use]
    #[inline]
    pub fn norm_sq(self) -> f64 {
        self.dot(self)
    }

    /// Euclidean length.
    #[must_use]
    #[inline]
    pub fn norm(self) -> f64 {
        self.norm_sq().sqrt()
    }

    /// True when every component is finite (no NaN, no infinity).
    #[must_use]
    pub fn is_finite(self) -> bool {
        self.0.iter().all(|x| x.is_finite())
    }

    /// Component-wise minimum.
    #[must_use]
    #[inline]
    pub fn min(self, o: Self) -> Self {
        let mut r = self;
        for k in 0..D {
            r.0[k] = self.0[k].min(o.0[k]);
        }
        r
    }

    /// Component-wise maximum.
    #[must_use]
    #[inline]
    pub fn max(self, o: Self) -> Self {
        let mut r = self;
        for k in 0..D {
            r.0[k] = self.0[k].max(o.0[k]);
        }
        r
    }

    /// A vector with every component equal to `x`.
    #[must_use]
    pub fn splat(x: f64) -> Self {
        Vector([x; D])
    }

    /// The components as a slice.
    #[must_use]
    pub fn as_slice(&self) -> &[f64] {
        &self.0
    }
}

impl Vector<3> {
    /// Cross product `self × o`.
    #[must_use]
    #[inline]
    pub fn cross(self, o: Self) -> Self {
        Vector([
            self[1] * o[2] - self[2] * o[1],
            self[2] * o[0] - self[0] * o[2],
            self[0] * o[1] - self[1] * o[0],
        ])
    }
}

impl<const D: usize> Add for Vector<D> {
    type Output = Self;
    #[inline]
    fn add(mut self, o: Self) -> Self {
        for k in 0..D {
            self.0[k] += o.0[k];
        }
        self
    }
}
impl<const D: usize> AddAssign for Vector<D> {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl<const D: usize> Sub for Vector<D> {
    type Output = Self;
    #[inline]
    fn sub(mut self, o: Self) -> Self {
        for k in 0..D {
            self.0[k] -= o.0[k];
        }
        self
    }
}
impl<const D: usize> SubAssign for Vector<D> {
    #[inline]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}
impl<const D: usize> Mul<f64> for Vector<D> {
    type Output = Self;
    #[inline]
    fn mul(mut self, s: f64) -> Self {
        for k in 0..D {
            self.0[k] *= s;
        }
        self
    }
}
impl<const D: usize> Neg for Vector<D> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        self * -1.0
    }
}
impl<const D: usize> Index<usize> for Vector<D> {
    type Output = f64;
    #[inline]
    fn index(&self, k: usize) -> &f64 {
        &self.0[k]
    }
}
impl<const D: usize> IndexMut<usize> for Vector<D> {
    #[inline]
    fn index_mut(&mut self, k: usize) -> &mut f64 {
        &mut self.0[k]
    }
}

impl<const D: usize> Serialize for Vector<D> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut t = s.serialize_tuple(D)?;
        for x in &self.0 {
            t.serialize_element(x)?;
        }
        t.end()
    }
}

impl<'de, const D: usize> Deserialize<'de> for Vector<D> {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        struct V<const D: usize>;
        impl<'de, const D: usize> Visitor<'de> for V<D> {
            type Value = Vector<D>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                write!(f, "an array of {D} numbers")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vector<D>, A::Error> {
                let mut out = [0.0; D];
                for (k, slot) in out.iter_mut().enumerate() {
                    *slot = seq
                        .next_element()?
                        .ok_or_else(|| A::Error::invalid_length(k, &self))?;
                }
                if seq.next_element::<serde::de::IgnoredAny>()?.is_some() {
                    return Err(A::Error::invalid_length(D + 1, &self));
                }
                Ok(Vector(out))
            }
        }
        d.deserialize_seq(V::<D>)
    }
}

/// An axis-aligned box `[min, max]`; empty when any `min > max`.
#[derive(Clone, Copy, PartialEq, Debug)]
pub struct Aabb<const D: usize> {
    /// Lower corner.
    pub min: Vector<D>,
    /// Upper corner.
    pub max: Vector<D>,
}

impl<const D: usize> Aabb<D> {
    /// The empty box: the identity of [`Aabb::union`].
    pub const EMPTY: Self = Aabb {
        min: Vector([f64::INFINITY; D]),
        max: Vector([f64::NEG_INFINITY; D]),
    };

    /// The box of a ball of radius `r` centred at `c`.
    #[must_use]
    #[inline]
    pub fn of_ball(c: Vector<D>, r: f64) -> Self {
        let e = Vector::splat(r);
        Aabb {
            min: c - e,
            max: c + e,
        }
    }

    /// The smallest box holding both.
    #[must_use]
    #[inline]
    pub fn union(self, o: Self) -> Self {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// True when the closed boxes share at least one point.
    #[must_use]
    #[inline]
    pub fn overlaps(&self, o: &Self) -> bool {
        (0..D).all(|k| self.min[k] <= o.max[k] && o.min[k] <= self.max[k])
    }

    /// True when `o` lies inside this box (closed).
    #[must_use]
    pub fn contains(&self, o: &Self) -> bool {
        (0..D).all(|k| self.min[k] <= o.min[k] && o.max[k] <= self.max[k])
    }

    /// Centre of the box.
    #[must_use]
    pub fn center(&self) -> Vector<D> {
        (self.min + self.max) * 0.5
    }
}

/// Volume of a ball of radius `r` in `D` dimensions (area of a disc for `D = 2`).
#[must_use]
pub fn ball_volume<const D: usize>(r: f64) -> f64 {
    match D {
        1 => 2.0 * r,
        2 => std::f64::consts::PI * r * r,
        3 => 4.0 / 3.0 * std::f64::consts::PI * r * r * r,
        _ => {
            // Unit-ball volume recurrence V_n = 2π/n · V_{n-2}.
            let mut v = [1.0, 2.0];
            let mut n = 1;
            while n < D {
                n += 1;
                let next = 2.0 * std::f64::consts::PI / n as f64 * v[(n - 2) % 2];
                v[n % 2] = next;
            }
            v[D % 2] * r.powi(D as i32)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vector_arithmetic() {
        let a = Vector([1.0, 2.0]);
        let b = Vector([3.0, -1.0]);
        assert_eq!(a + b, Vector([4.0, 1.0]));
        assert_eq!(a - b, Vector([-2.0, 3.0]));
        assert_eq!(a.dot(b), 1.0);
        assert_eq!((a * 2.0).norm_sq(), 20.0);
    }

    #[test]
    fn vector_serde_checks_length() {
        let v: Vector<3> = serde_json::from_str("[1,2,3]").unwrap();
        assert_eq!(v, Vector([1.0, 2.0, 3.0]));
        assert!(serde_json::from_str::<Vector<3>>("[1,2]").is_err());
        assert!(serde_json::from_str::<Vector<2>>("[1,2,3]").is_err());
        assert_eq!(
            serde_json::to_string(&Vector([0.5, 1.0])).unwrap(),
            "[0.5,1.0]"
        );
    }

    #[test]
    fn boxes() {
        let a = Aabb::of_ball(Vector([0.0, 0.0]), 1.0);
        let b = Aabb::of_ball(Vector([2.0, 0.0]), 1.0);
        let c = Aabb::of_ball(Vector([2.1, 0.0]), 1.0);
        assert!(a.overlaps(&b));
        assert!(!a.overlaps(&c));
        assert!(a.union(c).contains(&b));
        assert!(Aabb::EMPTY.union(a) == a);
    }

    #[test]
    fn ball_volumes() {
        assert!((ball_volume::<2>(2.0) - 4.0 * std::f64::consts::PI).abs() < 1e-12);
        assert!((ball_volume::<3>(1.0) - 4.0 / 3.0 * std::f64::consts::PI).abs() < 1e-12);
        assert!((ball_volume::<4>(1.0) - std::f64::consts::PI.powi(2) / 2.0).abs() < 1e-12);
    }
}
