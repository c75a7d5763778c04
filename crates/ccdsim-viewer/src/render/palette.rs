//! A fixed 256-colour palette for GIF frames: a 6×7×6 colour cube plus greys.
//!
//! A fixed palette keeps frames consistent (no colour flicker between frames), makes encoding
//! a table lookup instead of per-frame quantisation, and keeps the flat regions of a
//! simulation frame highly compressible.

const R: usize = 6;
const G: usize = 7;
const B: usize = 6;

/// The palette as the GIF encoder wants it: 256 RGB triples.
#[must_use]
pub fn palette() -> Vec<u8> {
    let mut p = Vec::with_capacity(256 * 3);
    for r in 0..R {
        for g in 0..G {
            for b in 0..B {
                p.extend_from_slice(&[level(r, R), level(g, G), level(b, B)]);
            }
        }
    }
    for k in 0..(256 - R * G * B) {
        let v = (k * 255 / (255 - R * G * B)) as u8;
        p.extend_from_slice(&[v, v, v]);
    }
    p
}

fn level(k: usize, n: usize) -> u8 {
    (k * 255 / (n - 1)) as u8
}

fn nearest(x: u8, n: usize) -> usize {
    (usize::from(x) * (n - 1) + 127) / 255
}

/// Palette index of an opaque RGB colour: its nearest point of the cube.
#[must_use]
pub fn index_of(rgb: [u8; 3]) -> u8 {
    (nearest(rgb[0], R) * G * B + nearest(rgb[1], G) * B + nearest(rgb[2], B)) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_colours_map_to_themselves() {
        let p = palette();
        assert_eq!(p.len(), 768);
        for i in 0..R * G * B {
            let c = [p[3 * i], p[3 * i + 1], p[3 * i + 2]];
            assert_eq!(index_of(c) as usize, i);
        }
        assert_eq!(index_of([0, 0, 0]), 0);
    }
}
