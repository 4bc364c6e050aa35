//! An 8-bit RGB image and its PNG file.

use super::RenderError;
use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

/// An 8-bit sRGB image, row-major from the top-left pixel, three bytes per pixel.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    width: u32,
    height: u32,
    rgb: Vec<u8>,
}

impl Image {
    /// A black image. Sizes are checked by the renderers ([`super::RenderOptions::validate`]).
    pub fn new(width: u32, height: u32) -> Image {
        Image {
            width,
            height,
            rgb: vec![0; width as usize * height as usize * 3],
        }
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixel at column `i`, row `j` (row 0 at the top).
    pub fn pixel(&self, i: u32, j: u32) -> [u8; 3] {
        let k = self.offset(i, j);
        [self.rgb[k], self.rgb[k + 1], self.rgb[k + 2]]
    }

    /// Sets pixel `(i, j)`; pixels outside the image are ignored (drawing may overhang).
    pub fn set(&mut self, i: u32, j: u32, c: [u8; 3]) {
        if i < self.width && j < self.height {
            let k = self.offset(i, j);
            self.rgb[k..k + 3].copy_from_slice(&c);
        }
    }

    /// Fills the rectangle `[x0, x1) x [y0, y1)`, clipped to the image.
    pub fn fill(&mut self, x0: u32, y0: u32, x1: u32, y1: u32, c: [u8; 3]) {
        for j in y0..y1.min(self.height) {
            for i in x0..x1.min(self.width) {
                self.set(i, j, c);
            }
        }
    }

    /// The raw RGB bytes, row-major.
    pub fn as_bytes(&self) -> &[u8] {
        &self.rgb
    }

    /// The rows as mutable byte slices (for filling rows in parallel).
    pub(crate) fn rows_mut(&mut self) -> std::slice::ChunksExactMut<'_, u8> {
        self.rgb.chunks_exact_mut(self.width.max(1) as usize * 3)
    }

    /// Appends the rows of `below` (same width) under this image.
    pub(crate) fn stack(mut self, below: &Image) -> Image {
        debug_assert_eq!(self.width, below.width);
        self.rgb.extend_from_slice(&below.rgb);
        self.height += below.height;
        self
    }

    /// Writes an 8-bit RGB PNG.
    pub fn write_png(&self, path: &Path) -> Result<(), RenderError> {
        let io = |e: &dyn std::fmt::Display| RenderError::Write {
            path: path.to_owned(),
            message: e.to_string(),
        };
        let file = File::create(path).map_err(|e| io(&e))?;
        let mut enc = png::Encoder::new(BufWriter::new(file), self.width, self.height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header().map_err(|e| io(&e))?;
        w.write_image_data(&self.rgb).map_err(|e| io(&e))?;
        w.finish().map_err(|e| io(&e))
    }

    fn offset(&self, i: u32, j: u32) -> usize {
        (j as usize * self.width as usize + i as usize) * 3
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_round_trip() {
        let mut img = Image::new(3, 2);
        img.set(2, 1, [10, 20, 30]);
        img.set(5, 5, [1, 1, 1]); // outside: ignored
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("x.png");
        img.write_png(&p).unwrap();
        let dec = png::Decoder::new(File::open(&p).unwrap());
        let mut r = dec.read_info().unwrap();
        let mut buf = vec![0; r.output_buffer_size()];
        let info = r.next_frame(&mut buf).unwrap();
        assert_eq!((info.width, info.height), (3, 2));
        assert_eq!(&buf[..info.buffer_size()], img.as_bytes());
        assert_eq!(img.pixel(2, 1), [10, 20, 30]);
        let bad = img.write_png(&dir.path().join("no/such/dir.png"));
        assert!(matches!(bad, Err(RenderError::Write { .. })));
    }
}
