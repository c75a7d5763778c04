//! Reading the reference data files of `tests/data/` (JSON written by peers' scripts).

use ccdsim::Vector;
use serde_json::Value;

/// The number `v`; panics when it is not one.
pub fn num(v: &Value) -> f64 {
    v.as_f64().expect("a number")
}

/// The array of `N` numbers `v` as a vector; panics when it is not one.
pub fn vec_of<const N: usize>(v: &Value) -> Vector<N> {
    let a = v.as_array().expect("an array");
    assert_eq!(a.len(), N, "an array of {N} numbers");
    Vector(std::array::from_fn(|k| num(&a[k])))
}
