//! Extended XYZ trajectories, as read by ASE (`ase.io.read`) and OVITO.
//!
//! Each frame is a count line, a comment line of `key=value` pairs and one line per body:
//!
//! ```text
//! 2
//! Lattice="4 0 0 0 4 0 0 0 0" Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1:mass:R:1:image:I:3:id:I:1 Time=0.5 pbc="T T F"
//! X 0.5 1 0 1 0 0 0.25 1 0 -1 0 7
//! …
//! ```
//!
//! Coordinates always have three components (`z = 0` in 2D, where the third lattice vector is
//! zero and not periodic). Bodies are of species `X` (ASE's dummy element). Periodic worlds
//! write `Lattice` (origin at zero) and `pbc="T T T"`; walled worlds write the walls' bounding
//! box as `Lattice` with its corner as `Origin` and `pbc="F F F"`. Numbers are written so that
//! they read back as the same `f64`.

use super::frame::{Cell, Frame};
use std::fmt::Write as _;
use std::io::{self, Write};

/// Writes frames to an extended XYZ stream.
pub struct XyzWriter<W: Write> {
    out: W,
    line: String,
}

impl<W: Write> XyzWriter<W> {
    /// A writer appending frames to `out` (buffer it: a frame is many small writes).
    pub fn new(out: W) -> Self {
        XyzWriter {
            out,
            line: String::new(),
        }
    }

    /// Appends one frame.
    pub fn write<const D: usize>(&mut self, frame: &Frame<D>) -> io::Result<()> {
        let line = &mut self.line;
        line.clear();
        let _ = writeln!(line, "{}", frame.len());
        let (lattice, origin, pbc) = match frame.cell.origin_and_size() {
            Some((origin, size)) => (
                Some(size),
                matches!(frame.cell, Cell::Walls { .. }).then_some(origin),
                matches!(frame.cell, Cell::Periodic(_)),
            ),
            None => (None, None, false),
        };
        if let Some(size) = lattice {
            line.push_str("Lattice=\"");
            for a in 0..3 {
                for b in 0..3 {
                    let x = if a == b && a < D { size[a] } else { 0.0 };
                    if a + b > 0 {
                        line.push(' ');
                    }
                    push_number(line, x);
                }
            }
            line.push_str("\" ");
        }
        if let Some(origin) = origin {
            line.push_str("Origin=\"");
            for a in 0..3 {
                if a > 0 {
                    line.push(' ');
                }
                push_number(line, if a < D { origin[a] } else { 0.0 });
            }
            line.push_str("\" ");
        }
        line.push_str(
            "Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1:mass:R:1:image:I:3:id:I:1",
        );
        if frame.spins.is_some() {
            line.push_str(":angvel:R:3");
        }
        line.push_str(" Time=");
        // With a decimal point, so that readers guessing types take the time for a real.
        let at = line.len();
        push_number(line, frame.time);
        if !line[at..].contains(['.', 'e', 'N', 'i']) {
            line.push_str(".0");
        }
        line.push_str(" pbc=\"");
        for a in 0..3 {
            if a > 0 {
                line.push(' ');
            }
            line.push(if pbc && a < D { 'T' } else { 'F' });
        }
        line.push_str("\"\n");
        self.out.write_all(line.as_bytes())?;
        for i in 0..frame.len() {
            line.clear();
            line.push('X');
            for v in [&frame.positions[i], &frame.velocities[i]] {
                for a in 0..3 {
                    line.push(' ');
                    push_number(line, if a < D { v[a] } else { 0.0 });
                }
            }
            line.push(' ');
            push_number(line, frame.radii[i]);
            line.push(' ');
            push_number(line, frame.masses[i]);
            for a in 0..3 {
                let _ = write!(line, " {}", if a < D { frame.images[i][a] } else { 0 });
            }
            let _ = write!(line, " {}", frame.ids[i]);
            if let Some(spins) = &frame.spins {
                for w in spins[i].0 {
                    line.push(' ');
                    push_number(line, w);
                }
            }
            line.push('\n');
            self.out.write_all(line.as_bytes())?;
        }
        Ok(())
    }

    /// Flushes and returns the stream.
    pub fn finish(mut self) -> io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }
}

/// `x` in the shortest form that reads back as the same `f64`: plain for moderate magnitudes,
/// with an exponent otherwise (Rust's `{}` never uses one, which would spell out 1e-300).
fn push_number(line: &mut String, x: f64) {
    let m = x.abs();
    if x == 0.0 || (1e-5..1e16).contains(&m) {
        let _ = write!(line, "{x}");
    } else {
        let _ = write!(line, "{x:e}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Vector;

    fn frame() -> Frame<2> {
        Frame {
            time: 0.5,
            cell: Cell::Periodic(Vector([4.0, 3.0])),
            ids: vec![7, 9],
            positions: vec![Vector([0.5, 1.0]), Vector([3.25, 1e-300])],
            images: vec![[1, -1], [0, 2]],
            strain: 0.0,
            velocities: vec![Vector([1.0, 0.0]), Vector([-0.1, 2.5e20])],
            radii: vec![0.25, 0.25],
            masses: vec![1.0, 2.0],
            spins: None,
        }
    }

    #[test]
    fn writes_the_documented_layout() {
        let mut w = XyzWriter::new(Vec::new());
        w.write(&frame()).unwrap();
        let text = String::from_utf8(w.finish().unwrap()).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 4);
        assert_eq!(lines[0], "2");
        assert_eq!(
            lines[1],
            "Lattice=\"4 0 0 0 3 0 0 0 0\" Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1\
             :mass:R:1:image:I:3:id:I:1 Time=0.5 pbc=\"T T F\""
        );
        assert_eq!(lines[2], "X 0.5 1 0 1 0 0 0.25 1 1 -1 0 7");
        assert_eq!(lines[3], "X 3.25 1e-300 0 -0.1 2.5e20 0 0.25 2 0 2 0 9");
    }

    #[test]
    fn numbers_read_back_exactly() {
        for x in [
            0.1,
            1.0 / 3.0,
            1e-7,
            123_456_789.123,
            6.02e23,
            -2.5e-310,
            f64::MAX,
        ] {
            let mut s = String::new();
            push_number(&mut s, x);
            assert_eq!(s.parse::<f64>().unwrap(), x, "{s}");
        }
    }

    #[test]
    fn walled_cells_carry_their_origin_and_are_not_periodic() {
        let mut f = frame();
        f.cell = Cell::Walls {
            lo: Vector([-1.0, -2.0]),
            hi: Vector([1.0, 2.0]),
        };
        let mut w = XyzWriter::new(Vec::new());
        w.write(&f).unwrap();
        let text = String::from_utf8(w.finish().unwrap()).unwrap();
        let comment = text.lines().nth(1).unwrap();
        assert!(comment.starts_with("Lattice=\"2 0 0 0 4 0 0 0 0\" Origin=\"-1 -2 0\" "));
        assert!(comment.ends_with("pbc=\"F F F\""));
    }
}
