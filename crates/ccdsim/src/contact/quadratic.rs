//! The real roots of a quadratic in time, `c + b·t + a·t²`, where it falls or rises through a
//! level: the cancellation-free forms that the parabolas of gravity share (a ball against a
//! segment's line, [`super::falling_segment`]; a falling body against a cell's face, the
//! `cells` finder).

/// The roots of `h(t) = k`, `h(t) = c + b·t + a·t²`, at which `h` falls through `k`
/// (`falling`) or rises through it: at most one each for a proper parabola, taken in the
/// cancellation-free forms; tangent touches (a zero discriminant) are no crossing.
pub(crate) fn crossing(c: f64, b: f64, a: f64, k: f64, falling: bool) -> Option<f64> {
    let c = c - k;
    if a == 0.0 {
        return ((b < 0.0) == falling && b != 0.0).then(|| -c / b);
    }
    roots(c, b, a).map(|(falls, rises)| if falling { falls } else { rises })
}

/// The roots of `c + b·t + a·t² = 0` (`a ≠ 0`) as `(falling, rising)`, in the
/// cancellation-free forms: the falling root is `(−b − s)/2a` and the rising one `(−b + s)/2a`
/// with `s = √(b² − 4ac)`, whatever the sign of `a`. `None` unless the discriminant is
/// positive (a tangent touch is no crossing).
fn roots(c: f64, b: f64, a: f64) -> Option<(f64, f64)> {
    let disc = b * b - 4.0 * a * c;
    if disc.is_nan() || disc <= 0.0 {
        return None;
    }
    let s = disc.sqrt();
    let q = -0.5 * (b + if b >= 0.0 { s } else { -s });
    Some(if b >= 0.0 {
        (q / a, c / q)
    } else {
        (c / q, q / a)
    })
}

/// The two roots of `c + b·t + a·t² = 0` (`a ≠ 0`) as `(falling, rising)`: where the
/// quadratic falls through zero and where it rises through it, in the cancellation-free
/// forms; `None` when it does not cross zero, or when rounding left the two roots equal or in
/// the wrong order (`falling < rising` when `a > 0`, the reverse when `a < 0`): a graze.
#[must_use]
pub(crate) fn face_roots(c: f64, b: f64, a: f64) -> Option<(f64, f64)> {
    roots(c, b, a).filter(|&(falls, rises)| {
        if a > 0.0 {
            falls < rises
        } else {
            rises < falls
        }
    })
}
