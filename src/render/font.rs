//! Text on [`Image`]s (the heat-map legend's tick labels), drawn by the embedded-graphics
//! library with its monospaced ASCII fonts: 4 x 6 pixels at scale 1, 6 x 12 from scale 2.

use super::Image;
use embedded_graphics::mono_font::ascii::{FONT_4X6, FONT_6X12};
use embedded_graphics::mono_font::{MonoFont, MonoTextStyle};
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::text::{Baseline, Text};

/// The font of `scale`.
fn font(scale: u32) -> &'static MonoFont<'static> {
    if scale >= 2 { &FONT_6X12 } else { &FONT_4X6 }
}

/// An [`Image`] as an embedded-graphics drawing target; pixels outside it are clipped.
struct Canvas<'a>(&'a mut Image);

impl OriginDimensions for Canvas<'_> {
    fn size(&self) -> Size {
        Size::new(self.0.width(), self.0.height())
    }
}

impl DrawTarget for Canvas<'_> {
    type Color = Rgb888;
    type Error = std::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        let (w, h) = (self.0.width() as i32, self.0.height() as i32);
        for Pixel(p, c) in pixels {
            if (0..w).contains(&p.x) && (0..h).contains(&p.y) {
                self.0.set(p.x as u32, p.y as u32, [c.r(), c.g(), c.b()]);
            }
        }
        Ok(())
    }
}

/// Height of a line of text at `scale`, in pixels.
pub fn text_height(scale: u32) -> u32 {
    font(scale).character_size.height
}

/// Width of `text` at `scale`, in pixels.
pub fn text_width(text: &str, scale: u32) -> u32 {
    let f = font(scale);
    let n = text.chars().count() as u32;
    (n * (f.character_size.width + f.character_spacing)).saturating_sub(f.character_spacing)
}

/// Draws `text` with its top-left corner at `(x, y)`; pixels outside the image are clipped.
pub fn draw_text(img: &mut Image, x: u32, y: u32, text: &str, scale: u32, colour: [u8; 3]) {
    let style = MonoTextStyle::new(font(scale), Rgb888::new(colour[0], colour[1], colour[2]));
    let at = Point::new(x as i32, y as i32);
    let Ok(_) = Text::with_baseline(text, at, style, Baseline::Top).draw(&mut Canvas(img));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_lands_inside_its_box() {
        for scale in [1, 2] {
            let (w, h) = (text_width("1024+", scale), text_height(scale));
            let mut img = Image::new(w + 4, h + 4);
            draw_text(&mut img, 2, 2, "1024+", scale, [255; 3]);
            let lit: Vec<(u32, u32)> = (0..img.height())
                .flat_map(|j| (0..img.width()).map(move |i| (i, j)))
                .filter(|&(i, j)| img.pixel(i, j) == [255; 3])
                .collect();
            assert!(lit.len() > 10, "scale {scale}: glyphs drawn");
            assert!(
                lit.iter()
                    .all(|&(i, j)| (2..2 + w).contains(&i) && (2..2 + h).contains(&j))
            );
        }
        assert_eq!(text_height(1), 6);
        assert_eq!(text_width("1024+", 1), 20);
        let mut small = Image::new(3, 3);
        draw_text(&mut small, 1, 1, "88", 2, [1; 3]); // clipped, no panic
    }
}
