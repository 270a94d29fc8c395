//! A canvas drawn with our own core for `explain`'s magnified pixel grids:
//! lines from [`draw_line`], text from an 8x8 bitmap font (font8x8), written as
//! PNG like every figure. (The report's error-against-time plot is plotters'.)

use crate::pipeline::interpolate::Pixel;
use crate::pipeline::raster::rows::draw_line;
use crate::pipeline::raster::Bounds;
use crate::pipeline::Frame;

pub type Rgb = u32;
pub const BLACK: Rgb = 0x00_00_00;
pub const GREY: Rgb = 0xcc_cc_cc;
pub const DARK: Rgb = 0x55_55_55;

/// An image to draw lines, markers and text on.
pub struct Canvas {
    pub frame: Frame,
    bounds: Bounds,
}

impl Canvas {
    pub fn new(width: u32, height: u32, background: Rgb) -> Self {
        Canvas::of(Frame::new(width, height), background)
    }

    /// [`Canvas::new`], refused when its memory cannot be had.
    pub fn try_new(width: u32, height: u32, background: Rgb) -> Result<Self, String> {
        Ok(Canvas::of(
            Frame::try_new(width, height, false)?,
            background,
        ))
    }

    fn of(mut frame: Frame, background: Rgb) -> Self {
        frame.color.fill(background);
        Canvas {
            bounds: Bounds {
                x: 0..frame.width as i32,
                y: 0..frame.height as i32,
            },
            frame,
        }
    }

    fn put(&mut self, x: i32, y: i32, color: Rgb) {
        if self.bounds.x.contains(&x) && self.bounds.y.contains(&y) {
            self.frame.color[(y as u32 * self.frame.width + x as u32) as usize] = color;
        }
    }

    /// A filled rectangle with its top-left corner at `at`.
    pub fn rect(&mut self, at: (i32, i32), size: (i32, i32), color: Rgb) {
        for y in at.1..at.1 + size.1 {
            for x in at.0..at.0 + size.0 {
                self.put(x, y, color);
            }
        }
    }

    /// A line `width` pixels thick (drawn as parallel one-pixel lines).
    pub fn line(&mut self, a: (i32, i32), b: (i32, i32), color: Rgb, width: i32) {
        let steep = (b.1 - a.1).abs() > (b.0 - a.0).abs();
        for o in -(width / 2)..=(width - 1) / 2 {
            let (dx, dy) = if steep { (o, 0) } else { (0, o) };
            let (p, q) = (Pixel::at(a.0 + dx, a.1 + dy), Pixel::at(b.0 + dx, b.1 + dy));
            let bounds = self.bounds.clone();
            draw_line(p, q, &bounds, |p| self.put(p.x, p.y, color));
        }
    }

    /// Text with its top-left corner at `at`, each font pixel `scale` pixels wide.
    pub fn text(&mut self, at: (i32, i32), text: &str, scale: i32, color: Rgb) {
        for (i, ch) in text.chars().enumerate() {
            let glyph = font8x8::legacy::BASIC_LEGACY
                .get(ch as usize)
                .copied()
                .unwrap_or([0; 8]);
            let x0 = at.0 + i as i32 * 8 * scale;
            for (row, bits) in glyph.iter().enumerate() {
                for col in 0..8 {
                    if bits & (1 << col) != 0 {
                        for sy in 0..scale {
                            for sx in 0..scale {
                                self.put(
                                    x0 + col * scale + sx,
                                    at.1 + row as i32 * scale + sy,
                                    color,
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    /// Width in pixels of `text` at `scale`.
    pub fn text_width(text: &str, scale: i32) -> i32 {
        text.chars().count() as i32 * 8 * scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_sets_the_glyphs_pixels() {
        let mut c = Canvas::new(16, 8, 0x00ff_ffff);
        c.text((0, 0), "I", 1, BLACK);
        let dark = c.frame.color.iter().filter(|&&p| p == BLACK).count();
        // font8x8's "I": rows 0x1E, 0x0C x5, 0x1E, 0: 4 + 5 * 2 + 4 pixels.
        assert_eq!(dark, 18);
    }
}
