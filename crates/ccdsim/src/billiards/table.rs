//! A pool table seen from above: straight cushions, the round jaws at the pockets' mouths, and
//! the pockets.
//!
//! The playing surface is the rectangle `[0, width] × [0, length]` (metres). Its edge is made
//! of straight cushion segments ([`LinearCushion`]): the four rails, cut short at the pockets,
//! and at each pocket the two angled faces that lead into it. Where a rail turns into a
//! pocket's face the cushion's nose is rounded ([`Jaw`]). A ball whose centre enters a
//! pocket's circle ([`Pocket`]) drops. [`Table::pool`] builds the standard six-pocket table
//! from [`PocketTableSpecs`], with the names, dimensions and construction of pooltool 0.3.3's
//! default table (`objects/table/layout.py`; diagram in Kiefl, "pooltool-alg", 2020).

use crate::geom::{Aabb, Vector};

/// A straight cushion: the segment from `p1` to `p2` (metres) at height `height` above the
/// cloth. A ball meets it when its centre is one radius from the segment, on either side.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearCushion {
    /// pooltool's name for it ("1" … "18").
    pub id: String,
    /// One end, metres.
    pub p1: Vector<2>,
    /// The other end, metres.
    pub p2: Vector<2>,
    /// Height of the cushion's nose above the cloth, metres.
    pub height: f64,
}

impl LinearCushion {
    /// The unit normal of the segment's line (`p2 − p1` turned a quarter counter-clockwise).
    #[must_use]
    pub fn normal(&self) -> Vector<2> {
        let d = self.p2 - self.p1;
        Vector([-d[1], d[0]]) * (1.0 / d.norm())
    }

    /// The segment's bounding box, metres.
    #[must_use]
    pub fn bounds(&self) -> Aabb<2> {
        Aabb {
            min: self.p1.min(self.p2),
            max: self.p1.max(self.p2),
        }
    }
}

/// A rounded cushion nose at a pocket's mouth: a circle of `radius` around `center`
/// (metres). A ball meets it when its centre is `radius + R` from `center`.
#[derive(Clone, Debug, PartialEq)]
pub struct Jaw {
    /// pooltool's name for it ("1t" … "17t").
    pub id: String,
    /// Centre, metres.
    pub center: Vector<2>,
    /// Radius, metres.
    pub radius: f64,
    /// Height of the cushion's nose above the cloth, metres.
    pub height: f64,
}

impl Jaw {
    /// The circle's bounding box, metres.
    #[must_use]
    pub fn bounds(&self) -> Aabb<2> {
        Aabb::of_ball(self.center, self.radius)
    }
}

/// A pocket: a ball drops when its centre comes within `radius` of `center` (metres).
#[derive(Clone, Debug, PartialEq)]
pub struct Pocket {
    /// pooltool's name for it: `l`/`r` (left, right) and `b`/`c`/`t` (bottom, centre, top).
    pub id: String,
    /// Centre, metres.
    pub center: Vector<2>,
    /// Radius, metres.
    pub radius: f64,
}

impl Pocket {
    /// The circle's bounding box, metres.
    #[must_use]
    pub fn bounds(&self) -> Aabb<2> {
        Aabb::of_ball(self.center, self.radius)
    }
}

/// A table: its playing surface and everything a ball can meet at its edge.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// Width of the playing surface (along `x`), metres.
    pub width: f64,
    /// Length of the playing surface (along `y`), metres.
    pub length: f64,
    /// Straight cushion segments.
    pub cushions: Vec<LinearCushion>,
    /// Rounded cushion noses.
    pub jaws: Vec<Jaw>,
    /// Pockets.
    pub pockets: Vec<Pocket>,
}

/// The dimensions of a six-pocket table (pooltool 0.3.3's `PocketTableSpecs`; metres and
/// degrees). The default is the table pooltool plays on by default (`Table.default()`, its
/// "seven_foot_showood"): a 7-foot table, 78 × 39 inch playing surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PocketTableSpecs {
    /// Length of the playing surface, metres (1.9812).
    pub length: f64,
    /// Width of the playing surface, metres (half the length).
    pub width: f64,
    /// How far the cushions reach back from the playing surface, metres (2 inches).
    pub cushion_width: f64,
    /// Height of the cushions' noses above the cloth, metres (0.64 of a 57.15 mm ball).
    pub cushion_height: f64,
    /// Width of a corner pocket's mouth, metres (0.118).
    pub corner_pocket_width: f64,
    /// How far a corner pocket's faces open beyond 45°, degrees (5.3).
    pub corner_pocket_angle: f64,
    /// How far a corner pocket's centre lies beyond the corner, metres (0.0417).
    pub corner_pocket_depth: f64,
    /// Radius of a corner pocket, metres (0.062).
    pub corner_pocket_radius: f64,
    /// Radius of a corner pocket's jaws, metres (0.02095).
    pub corner_jaw_radius: f64,
    /// Width of a side pocket's mouth, metres (0.137).
    pub side_pocket_width: f64,
    /// How far a side pocket's faces open from square, degrees (7.14).
    pub side_pocket_angle: f64,
    /// How far a side pocket's centre lies beyond the rail, metres (0.0685).
    pub side_pocket_depth: f64,
    /// Radius of a side pocket, metres (0.0645).
    pub side_pocket_radius: f64,
    /// Radius of a side pocket's jaws, metres (0.00795).
    pub side_jaw_radius: f64,
}

impl Default for PocketTableSpecs {
    fn default() -> Self {
        PocketTableSpecs {
            length: 1.9812,
            width: 1.9812 / 2.0,
            cushion_width: 2.0 * 2.54 / 100.0,
            cushion_height: 0.64 * 2.0 * 0.028575,
            corner_pocket_width: 0.118,
            corner_pocket_angle: 5.3,
            corner_pocket_depth: 0.0417,
            corner_pocket_radius: 0.124 / 2.0,
            corner_jaw_radius: 0.0419 / 2.0,
            side_pocket_width: 0.137,
            side_pocket_angle: 7.14,
            side_pocket_depth: 0.0685,
            side_pocket_radius: 0.129 / 2.0,
            side_jaw_radius: 0.0159 / 2.0,
        }
    }
}

/// The table's four mirror images of a point drawn near the bottom-left corner.
#[derive(Clone, Copy)]
enum Mirror {
    None,
    /// `x → width − x`.
    X,
    /// `y → length − y`.
    Y,
    /// Both.
    XY,
}

impl Table {
    /// The standard six-pocket table of `specs`, built as pooltool builds its default table:
    /// the bottom-left corner pocket and the left side pocket are drawn once (rails, angled
    /// faces, jaws, pocket) and mirrored to the other corners and the right side, with
    /// pooltool's names for every part.
    #[must_use]
    pub fn pool(specs: &PocketTableSpecs) -> Table {
        let s = specs;
        let (w, l, cw, h) = (s.width, s.length, s.cushion_width, s.cushion_height);
        let corner_angle = (s.corner_pocket_angle + 45.0).to_radians();
        let side_angle = s.side_pocket_angle.to_radians();
        let (rc, rs) = (s.corner_jaw_radius, s.side_jaw_radius);
        // How far back from the mouth a jaw's tangent point lies along the rail.
        let dc = rc / ((std::f64::consts::FRAC_PI_2 + corner_angle) / 2.0).tan();
        let ds = rs / ((std::f64::consts::FRAC_PI_2 + side_angle) / 2.0).tan();
        // Where a corner pocket's mouth meets a rail, measured from the corner.
        let mouth = s.corner_pocket_width * std::f64::consts::FRAC_PI_4.cos();
        let (sin_c, cos_c, tan_c) = (corner_angle.sin(), corner_angle.cos(), corner_angle.tan());
        let (sin_s, cos_s) = (side_angle.sin(), side_angle.cos());

        let at = |m: Mirror, x: f64, y: f64| -> Vector<2> {
            match m {
                Mirror::None => Vector([x, y]),
                Mirror::X => Vector([w - x, y]),
                Mirror::Y => Vector([x, l - y]),
                Mirror::XY => Vector([w - x, l - y]),
            }
        };
        let mut cushions = Vec::new();
        let mut jaws = Vec::new();
        let mut segment = |id: &str, m: Mirror, a: (f64, f64), b: (f64, f64)| {
            cushions.push(LinearCushion {
                id: id.to_owned(),
                p1: at(m, a.0, a.1),
                p2: at(m, b.0, b.1),
                height: h,
            });
        };
        // The long rails, between a corner pocket and a side pocket.
        for (id, m) in [
            ("3", Mirror::None),
            ("6", Mirror::Y),
            ("15", Mirror::X),
            ("12", Mirror::XY),
        ] {
            segment(
                id,
                m,
                (0.0, mouth + dc),
                (0.0, (l - s.side_pocket_width) / 2.0 - ds),
            );
        }
        // The short rails, from corner pocket to corner pocket.
        for (id, m) in [("18", Mirror::None), ("9", Mirror::Y)] {
            segment(id, m, (mouth + dc, 0.0), (w - mouth - dc, 0.0));
        }
        // A side pocket's two faces, below and above its mouth.
        let side_low = (l - s.side_pocket_width) / 2.0;
        let side_high = (l + s.side_pocket_width) / 2.0;
        for (below, above, m) in [("4", "5", Mirror::None), ("14", "13", Mirror::X)] {
            segment(
                below,
                m,
                (-cw, side_low + cw * sin_s),
                (-ds * cos_s, side_low + ds * sin_s),
            );
            segment(
                above,
                m,
                (-cw, side_high - cw * sin_s),
                (-ds * cos_s, side_high - ds * sin_s),
            );
        }
        // A corner pocket's two faces: off the short rail and off the long rail.
        for (short, long, m) in [
            ("1", "2", Mirror::None),
            ("8", "7", Mirror::Y),
            ("17", "16", Mirror::X),
            ("10", "11", Mirror::XY),
        ] {
            segment(
                short,
                m,
                (mouth - cw * tan_c, -cw),
                (mouth - dc * sin_c, -dc * cos_c),
            );
            segment(
                long,
                m,
                (-cw, mouth - cw * tan_c),
                (-dc * cos_c, mouth - dc * sin_c),
            );
        }
        let mut jaw = |id: &str, m: Mirror, x: f64, y: f64, radius: f64| {
            jaws.push(Jaw {
                id: id.to_owned(),
                center: at(m, x, y),
                radius,
                height: h,
            });
        };
        for (short, long, m) in [
            ("1t", "2t", Mirror::None),
            ("8t", "7t", Mirror::Y),
            ("17t", "16t", Mirror::X),
            ("10t", "11t", Mirror::XY),
        ] {
            jaw(short, m, mouth + dc, -rc, rc);
            jaw(long, m, -rc, mouth + dc, rc);
        }
        for (below, above, m) in [("4t", "5t", Mirror::None), ("14t", "13t", Mirror::X)] {
            jaw(below, m, -rs, l / 2.0 - s.side_pocket_width / 2.0 - ds, rs);
            jaw(above, m, -rs, l / 2.0 + s.side_pocket_width / 2.0 + ds, rs);
        }
        let corner = s.corner_pocket_depth / std::f64::consts::SQRT_2;
        let side = s.side_pocket_depth;
        let pocket = |id: &str, m: Mirror, x: f64, y: f64, radius: f64| Pocket {
            id: id.to_owned(),
            center: at(m, x, y),
            radius,
        };
        let pockets = vec![
            pocket("lb", Mirror::None, -corner, -corner, s.corner_pocket_radius),
            pocket("lc", Mirror::None, -side, l / 2.0, s.side_pocket_radius),
            pocket("lt", Mirror::Y, -corner, -corner, s.corner_pocket_radius),
            pocket("rb", Mirror::X, -corner, -corner, s.corner_pocket_radius),
            pocket("rc", Mirror::X, -side, l / 2.0, s.side_pocket_radius),
            pocket("rt", Mirror::XY, -corner, -corner, s.corner_pocket_radius),
        ];
        Table {
            width: w,
            length: l,
            cushions,
            jaws,
            pockets,
        }
    }

    /// Whether a ball of radius `radius` centred at `p` lies on the playing surface, clear of
    /// every cushion and outside every pocket (touching allowed).
    #[must_use]
    pub fn holds(&self, p: Vector<2>, radius: f64) -> bool {
        let inside = p[0] >= radius
            && p[0] <= self.width - radius
            && p[1] >= radius
            && p[1] <= self.length - radius;
        inside
            && self
                .jaws
                .iter()
                .all(|j| (p - j.center).norm() >= j.radius + radius)
            && self
                .pockets
                .iter()
                .all(|k| (p - k.center).norm() >= k.radius)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pool_table_has_pooltools_parts() {
        let t = Table::pool(&PocketTableSpecs::default());
        assert_eq!(
            (t.cushions.len(), t.jaws.len(), t.pockets.len()),
            (18, 12, 6)
        );
        // Every jaw touches the line of the rail or face it rounds off: it is tangent to
        // both, so its centre is one jaw radius from some cushion's line.
        for j in &t.jaws {
            let tangent = t.cushions.iter().any(|c| {
                let d = (j.center - c.p1).dot(c.normal()).abs();
                (d - j.radius).abs() < 1e-12
            });
            assert!(tangent, "jaw {} touches no cushion line", j.id);
        }
        // The table is symmetric under both mirrors.
        for c in &t.cushions {
            let m = Vector([t.width - c.p1[0], c.p1[1]]);
            assert!(
                t.cushions
                    .iter()
                    .any(|o| (o.p1 - m).norm() < 1e-12 || (o.p2 - m).norm() < 1e-12),
                "{} has no mirror image",
                c.id
            );
        }
    }

    #[test]
    fn a_ball_on_the_cloth_is_held_and_one_in_a_pocket_is_not() {
        let t = Table::pool(&PocketTableSpecs::default());
        let r = 0.028575;
        assert!(t.holds(Vector([0.5, 1.0]), r));
        assert!(t.holds(Vector([r, 1.0]), r));
        assert!(!t.holds(Vector([r * 0.5, 1.0]), r));
        assert!(!t.holds(Vector([0.0, 0.0]), r));
    }
}
