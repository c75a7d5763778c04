//! Colours shared by the renderer and (mirrored in `assets/raster.js`) the page.

/// An 8-bit RGB colour.
pub type Rgb = [u8; 3];

/// Background of every frame.
pub const BACKGROUND: Rgb = [17, 20, 24];
/// Walls.
pub const WALL: Rgb = [200, 200, 200];
/// Leaf (swept body) boxes of the finder.
pub const LEAF_BOX: Rgb = [120, 230, 140];
/// Fill of a body that collides in the current frame.
pub const FLASH_FILL: Rgb = [255, 255, 255];
/// Ring around a body that collides in the current frame.
pub const FLASH_RING: Rgb = [255, 210, 40];
/// Outline of a sensor region with no body in it.
pub const SENSOR: Rgb = [70, 150, 170];
/// Outline of a sensor region that holds a body.
pub const SENSOR_HELD: Rgb = [80, 240, 255];
/// Progress bar at the foot of a frame.
pub const PROGRESS: Rgb = [90, 140, 220];
/// Number of distinct body colours; bodies are drawn in batches of one colour.
pub const BUCKETS: usize = 64;

/// How bodies are coloured.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ColourBy {
    /// A hue per body id, stable over the run.
    #[default]
    Id,
    /// Speed, from dark blue (at rest) to yellow and red (the run's top speed).
    Speed,
}

impl std::str::FromStr for ColourBy {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "id" => Ok(ColourBy::Id),
            "speed" => Ok(ColourBy::Speed),
            _ => Err(format!("unknown colouring `{s}` (known: id, speed)")),
        }
    }
}

/// Colour bucket of the body with user id `id`: its golden-ratio hue, quantised.
#[must_use]
pub fn id_bucket(id: u64) -> usize {
    let hue = (id as f64 * 0.618_033_988_749_895).fract();
    ((hue * BUCKETS as f64) as usize).min(BUCKETS - 1)
}

/// Colour bucket of a speed, given the run's top speed (m/s).
#[must_use]
pub fn speed_bucket(speed: f64, max_speed: f64) -> usize {
    let s = if max_speed > 0.0 {
        (speed / max_speed).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((s * (BUCKETS - 1) as f64).round() as usize).min(BUCKETS - 1)
}

/// The colour of an id bucket: a hue at fixed saturation and value.
#[must_use]
pub fn id_colour(bucket: usize) -> Rgb {
    hsv(bucket as f64 / BUCKETS as f64, 0.65, 0.95)
}

/// The colour of a speed bucket: a blue–cyan–yellow–red ramp.
#[must_use]
pub fn speed_colour(bucket: usize) -> Rgb {
    const STOPS: [[f64; 3]; 4] = [
        [40.0, 60.0, 160.0],
        [40.0, 200.0, 220.0],
        [250.0, 230.0, 60.0],
        [240.0, 60.0, 40.0],
    ];
    let s = bucket as f64 / (BUCKETS - 1) as f64 * 3.0;
    let k = (s.floor() as usize).min(2);
    let f = s - k as f64;
    let mut out = [0u8; 3];
    for c in 0..3 {
        out[c] = (STOPS[k][c] + (STOPS[k + 1][c] - STOPS[k][c]) * f).round() as u8;
    }
    out
}

/// Colour of the finder's inner boxes at tree depth `depth` (thesis Figure 5.3 colours the
/// BVH's levels apart): a hue that turns with depth.
#[must_use]
pub fn depth_colour(depth: u32) -> Rgb {
    hsv((f64::from(depth) * 0.13 + 0.55).fract(), 0.8, 1.0)
}

fn hsv(h: f64, s: f64, v: f64) -> Rgb {
    let i = (h * 6.0).floor();
    let f = h * 6.0 - i;
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - f * s), v * (1.0 - (1.0 - f) * s));
    let (r, g, b) = match (i as i64).rem_euclid(6) {
        0 => (v, t, p),
        1 => (q, v, p),
        2 => (p, v, t),
        3 => (p, q, v),
        4 => (t, p, v),
        _ => (v, p, q),
    };
    [
        (r * 255.0).round() as u8,
        (g * 255.0).round() as u8,
        (b * 255.0).round() as u8,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buckets_stay_in_range() {
        for id in [0, 1, 15, u64::MAX] {
            assert!(id_bucket(id) < BUCKETS);
        }
        assert_eq!(speed_bucket(0.0, 10.0), 0);
        assert_eq!(speed_bucket(10.0, 10.0), BUCKETS - 1);
        assert_eq!(speed_bucket(99.0, 10.0), BUCKETS - 1);
        assert_eq!(speed_bucket(1.0, 0.0), 0);
    }

    #[test]
    fn ramps_are_their_stops_at_the_ends() {
        assert_eq!(speed_colour(0), [40, 60, 160]);
        assert_eq!(speed_colour(BUCKETS - 1), [240, 60, 40]);
        assert_eq!(hsv(0.0, 1.0, 1.0), [255, 0, 0]);
    }
}
