//! The frame's simulated time, drawn in its top-left corner (`t = 1.250 s`) with a built-in
//! 3×5 pixel font: tiny-skia draws shapes, not text, and a clock needs only digits and a few
//! signs, so no font file or text-shaping crate is needed.

use super::colour::{self, Rgb};
use tiny_skia::{Color, Paint, Pixmap, Rect, Transform};

/// The text of the label for simulated time `t`, seconds.
#[must_use]
pub(crate) fn label_text(t: f64) -> String {
    format!("t = {t:.3} s")
}

/// Rows of a glyph, top first, three pixels each (bit 2 is the left column); `None` for a
/// character the font lacks, drawn as a space.
fn glyph(c: char) -> Option<[u8; 5]> {
    Some(match c {
        '0' => [0b111, 0b101, 0b101, 0b101, 0b111],
        '1' => [0b010, 0b110, 0b010, 0b010, 0b111],
        '2' => [0b111, 0b001, 0b111, 0b100, 0b111],
        '3' => [0b111, 0b001, 0b111, 0b001, 0b111],
        '4' => [0b101, 0b101, 0b111, 0b001, 0b001],
        '5' => [0b111, 0b100, 0b111, 0b001, 0b111],
        '6' => [0b111, 0b100, 0b111, 0b101, 0b111],
        '7' => [0b111, 0b001, 0b001, 0b001, 0b001],
        '8' => [0b111, 0b101, 0b111, 0b101, 0b111],
        '9' => [0b111, 0b101, 0b111, 0b001, 0b111],
        '.' => [0b000, 0b000, 0b000, 0b000, 0b010],
        '-' => [0b000, 0b000, 0b111, 0b000, 0b000],
        '=' => [0b000, 0b111, 0b000, 0b111, 0b000],
        't' => [0b010, 0b111, 0b010, 0b010, 0b011],
        's' => [0b000, 0b011, 0b100, 0b001, 0b110],
        _ => return None,
    })
}

fn paint(c: Rgb, alpha: u8) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(c[0], c[1], c[2], alpha));
    p
}

/// Draws [`label_text`] of `t` in the top-left corner of `pm`, on a darkened strip so that it
/// reads over bodies; glyph pixels are squares of a side that grows with the image (1 pixel
/// up to 199 pixels high, 2 up to 399, …, at most 4).
pub(crate) fn draw_time_label(pm: &mut Pixmap, t: f64) {
    let text = label_text(t);
    let scale = (pm.height() / 200 + 1).min(4) as f32;
    let margin = 2.0 * scale;
    let advance = 4.0 * scale;
    let width = advance * text.chars().count() as f32 + scale;
    if let Some(r) = Rect::from_xywh(margin - scale, margin - scale, width, 7.0 * scale) {
        pm.fill_rect(
            r,
            &paint(colour::BACKGROUND, 200),
            Transform::identity(),
            None,
        );
    }
    let ink = paint(colour::WALL, 255);
    for (k, c) in text.chars().enumerate() {
        let Some(rows) = glyph(c) else { continue };
        let x0 = margin + advance * k as f32;
        for (row, bits) in rows.iter().enumerate() {
            for col in 0..3 {
                if bits & (0b100 >> col) != 0 {
                    let x = x0 + scale * col as f32;
                    let y = margin + scale * row as f32;
                    if let Some(r) = Rect::from_xywh(x, y, scale, scale) {
                        pm.fill_rect(r, &ink, Transform::identity(), None);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_character_of_a_label_has_a_glyph() {
        for t in [0.0, 1.25, -3.5, 12_345.678_9] {
            let text = label_text(t);
            assert!(
                text.chars().all(|c| c == ' ' || glyph(c).is_some()),
                "{text}"
            );
        }
        assert_eq!(label_text(1.25), "t = 1.250 s");
    }

    #[test]
    fn the_label_is_drawn_in_the_top_left_corner_and_differs_by_time() {
        let draw = |t: f64| {
            let mut pm = Pixmap::new(160, 120).unwrap();
            pm.fill(Color::BLACK);
            draw_time_label(&mut pm, t);
            pm
        };
        let a = draw(1.0);
        let lit = |pm: &Pixmap, x0: u32, x1: u32, y0: u32, y1: u32| {
            (y0..y1)
                .flat_map(|y| (x0..x1).map(move |x| (x, y)))
                .filter(|&(x, y)| pm.pixel(x, y).unwrap().red() > 100)
                .count()
        };
        assert!(lit(&a, 0, 80, 0, 12) > 20, "ink in the corner");
        assert_eq!(lit(&a, 0, 160, 12, 120), 0, "nothing below the label");
        assert_ne!(a.data(), draw(2.0).data(), "another time, another label");
    }
}
