//! A 3 x 5 pixel bitmap font for the digits and `+`, enough for legend tick labels.

use super::Image;

/// Glyph rows, top first, 3 bits each (bit 2 is the left column).
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
        '+' => [0b000, 0b010, 0b111, 0b010, 0b000],
        _ => return None,
    })
}

/// Height of a line of text at `scale`, in pixels.
pub fn text_height(scale: u32) -> u32 {
    5 * scale
}

/// Width of `text` at `scale` (3 pixels per glyph and 1 between glyphs, times `scale`).
pub fn text_width(text: &str, scale: u32) -> u32 {
    let n = text.chars().count() as u32;
    (n * 4).saturating_sub(1) * scale
}

/// Draws `text` with its top-left corner at `(x, y)`; characters without a glyph are left blank
/// and pixels outside the image are clipped.
pub fn draw_text(img: &mut Image, x: u32, y: u32, text: &str, scale: u32, colour: [u8; 3]) {
    for (k, c) in text.chars().enumerate() {
        let Some(rows) = glyph(c) else { continue };
        let gx = x + k as u32 * 4 * scale;
        for (r, bits) in rows.iter().enumerate() {
            for col in 0..3u32 {
                if bits & (0b100 >> col) != 0 {
                    let px = gx + col * scale;
                    let py = y + r as u32 * scale;
                    img.fill(px, py, px + scale, py + scale, colour);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_a_one() {
        let mut img = Image::new(8, 6);
        draw_text(&mut img, 0, 0, "1+", 1, [255; 3]);
        // '1': top row has only the middle column lit; bottom row is full.
        assert_eq!(img.pixel(0, 0), [0; 3]);
        assert_eq!(img.pixel(1, 0), [255; 3]);
        assert!((0..3).all(|i| img.pixel(i, 4) == [255; 3]));
        // '+' starts at column 4: its middle row is full.
        assert!((4..7).all(|i| img.pixel(i, 2) == [255; 3]));
        assert_eq!(text_width("1024+", 2), 38);
        draw_text(&mut img, 7, 5, "88", 3, [1; 3]); // clipped, no panic
    }
}
