//! From world coordinates to pixels: top-down for 2D, an orthographic view for 3D.

use ccdsim::{Aabb, Vector};

/// Pixels left free around the run's bounds.
const MARGIN: f64 = 8.0;

/// A fixed view of a run: 2D runs are seen from above (x right, y up); 3D runs through an
/// orthographic camera turned by `yaw` about the world's y axis, then tilted by `pitch`
/// about the camera's x axis (yaw = pitch = 0 is the 2D view of the x–y plane).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Pixels per metre.
    pub scale: f64,
    centre: [f64; 3],
    rot: [[f64; 3]; 3],
    mid: [f64; 2],
}

impl Camera {
    /// The camera that fits `bounds` into an image `width` wide and `height` high (or as
    /// high as the bounds' aspect asks when `height` is `None`, between 16 and 8192 pixels).
    #[must_use]
    pub fn fit<const D: usize>(
        bounds: &Aabb<D>,
        width: u32,
        height: Option<u32>,
        yaw_deg: f64,
        pitch_deg: f64,
    ) -> Self {
        let rot = if D == 3 {
            rotation(yaw_deg, pitch_deg)
        } else {
            IDENTITY
        };
        let c = bounds.center();
        let mut centre = [0.0; 3];
        for k in 0..D.min(3) {
            centre[k] = c[k];
        }
        let mut cam = Camera {
            width,
            height: height.unwrap_or(1),
            scale: 1.0,
            centre,
            rot,
            mid: [0.0; 2],
        };
        // Extent of the bounds' projected corners.
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for corner in 0..(1usize << D) {
            let mut p = Vector::<D>::ZERO;
            for k in 0..D {
                p[k] = if corner >> k & 1 == 1 {
                    bounds.max[k]
                } else {
                    bounds.min[k]
                };
            }
            let q = cam.view(p);
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        let span = [(hi[0] - lo[0]).max(1e-12), (hi[1] - lo[1]).max(1e-12)];
        let w = f64::from(width.max(16));
        let h = match height {
            Some(h) => f64::from(h.max(16)),
            None => ((w - 2.0 * MARGIN) * span[1] / span[0] + 2.0 * MARGIN)
                .clamp(16.0, 8192.0)
                .round(),
        };
        cam.width = w as u32;
        cam.height = h as u32;
        cam.scale = ((w - 2.0 * MARGIN) / span[0]).min((h - 2.0 * MARGIN) / span[1]);
        cam.mid = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
        cam
    }

    /// Camera coordinates of `p` (metres, relative to the bounds' centre): right, up, and
    /// towards the viewer.
    fn view<const D: usize>(&self, p: Vector<D>) -> [f64; 3] {
        let mut d = [0.0; 3];
        for k in 0..D.min(3) {
            d[k] = p[k] - self.centre[k];
        }
        let r = &self.rot;
        [
            r[0][0] * d[0] + r[0][1] * d[1] + r[0][2] * d[2],
            r[1][0] * d[0] + r[1][1] * d[1] + r[1][2] * d[2],
            r[2][0] * d[0] + r[2][1] * d[1] + r[2][2] * d[2],
        ]
    }

    /// Pixel coordinates of `p` (x right, y down) and its depth (larger is nearer the viewer).
    #[must_use]
    pub fn project<const D: usize>(&self, p: Vector<D>) -> (f32, f32, f64) {
        let q = self.view(p);
        let x = f64::from(self.width) / 2.0 + self.scale * (q[0] - self.mid[0]);
        let y = f64::from(self.height) / 2.0 - self.scale * (q[1] - self.mid[1]);
        (x as f32, y as f32, q[2])
    }
}

const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// `Rx(pitch) · Ry(yaw)`.
fn rotation(yaw_deg: f64, pitch_deg: f64) -> [[f64; 3]; 3] {
    let (sy, cy) = yaw_deg.to_radians().sin_cos();
    let (sp, cp) = pitch_deg.to_radians().sin_cos();
    let ry = [[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]];
    let rx = [[1.0, 0.0, 0.0], [0.0, cp, -sp], [0.0, sp, cp]];
    let mut m = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = (0..3).map(|k| rx[i][k] * ry[k][j]).sum();
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_d_fits_the_bounds_with_y_up() {
        let b = Aabb {
            min: Vector([0.0, 0.0]),
            max: Vector([2.0, 1.0]),
        };
        let cam = Camera::fit(&b, 216, None, 0.0, 0.0);
        assert_eq!(cam.width, 216);
        assert_eq!(cam.height, 116);
        assert!((cam.scale - 100.0).abs() < 1e-9);
        let (x, y, _) = cam.project(Vector([0.0, 0.0]));
        assert!(
            (x - 8.0).abs() < 1e-4 && (y - 108.0).abs() < 1e-4,
            "{x} {y}"
        );
        let (x, y, _) = cam.project(Vector([2.0, 1.0]));
        assert!(
            (x - 208.0).abs() < 1e-4 && (y - 8.0).abs() < 1e-4,
            "{x} {y}"
        );
    }

    #[test]
    fn three_d_at_zero_angles_is_the_x_y_view() {
        let b = Aabb {
            min: Vector([0.0, 0.0, 0.0]),
            max: Vector([1.0, 1.0, 1.0]),
        };
        let cam = Camera::fit(&b, 116, Some(116), 0.0, 0.0);
        let (x, y, z) = cam.project(Vector([1.0, 1.0, 1.0]));
        assert!((x - 108.0).abs() < 1e-4 && (y - 8.0).abs() < 1e-4);
        assert!((z - 0.5).abs() < 1e-12);
    }
}
