//! A small log-log chart drawn with our own core: lines from
//! [`draw_line`], text from an 8x8 bitmap font (font8x8), written
//! as PNG like every figure. Enough for `report`'s error-against-time plot.

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
        let mut frame = Frame::new(width, height);
        frame.color.fill(background);
        Canvas {
            frame,
            bounds: Bounds {
                x: 0..width as i32,
                y: 0..height as i32,
            },
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

    /// A dashed one-pixel line.
    pub fn dashed(&mut self, a: (i32, i32), b: (i32, i32), color: Rgb) {
        let n = (b.0 - a.0).abs().max((b.1 - a.1).abs()).max(1);
        for i in (0..n).step_by(12) {
            let t0 = i as f32 / n as f32;
            let t1 = ((i + 6).min(n)) as f32 / n as f32;
            let at = |t: f32| {
                (
                    a.0 + ((b.0 - a.0) as f32 * t) as i32,
                    a.1 + ((b.1 - a.1) as f32 * t) as i32,
                )
            };
            self.line(at(t0), at(t1), color, 1);
        }
    }

    /// A filled square marker of side `2 r + 1` with a black outline.
    pub fn marker(&mut self, c: (i32, i32), r: i32, color: Rgb) {
        for y in -r - 1..=r + 1 {
            for x in -r - 1..=r + 1 {
                let edge = x.abs() == r + 1 || y.abs() == r + 1;
                self.put(c.0 + x, c.1 + y, if edge { BLACK } else { color });
            }
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

/// Maps data to pixels on log axes inside a plot area.
#[derive(Clone, Copy, Debug)]
pub struct LogLog {
    /// log10 of the x range.
    pub x: (f64, f64),
    /// log10 of the y range.
    pub y: (f64, f64),
    /// Plot area: left, top, right, bottom in pixels.
    pub area: (i32, i32, i32, i32),
}

impl LogLog {
    /// Axes that cover `xs` and `ys` (positive values), widened to whole decades.
    pub fn covering(xs: &[f64], ys: &[f64], area: (i32, i32, i32, i32)) -> Self {
        let range = |v: &[f64]| {
            let lo = v
                .iter()
                .copied()
                .fold(f64::INFINITY, f64::min)
                .log10()
                .floor();
            let hi = v
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max)
                .log10()
                .ceil();
            (lo, if hi > lo { hi } else { lo + 1.0 })
        };
        LogLog {
            x: range(xs),
            y: range(ys),
            area,
        }
    }

    pub fn map(&self, x: f64, y: f64) -> (i32, i32) {
        let (l, t, r, b) = self.area;
        let fx = (x.log10() - self.x.0) / (self.x.1 - self.x.0);
        let fy = (y.log10() - self.y.0) / (self.y.1 - self.y.0);
        (
            l + (fx * (r - l) as f64).round() as i32,
            b - (fy * (b - t) as f64).round() as i32,
        )
    }

    /// Frame, decade grid lines and their labels (`1`, `10`, `0.1`, ...).
    pub fn draw_axes(&self, c: &mut Canvas, x_title: &str, y_title: &str) {
        let (l, t, r, b) = self.area;
        let label = |e: f64| {
            let v = 10f64.powf(e);
            if e >= 0.0 {
                format!("{v:.0}")
            } else {
                format!("{v:.prec$}", prec = (-e) as usize)
            }
        };
        for e in (self.x.0 as i32)..=(self.x.1 as i32) {
            let (px, _) = self.map(10f64.powi(e), 10f64.powf(self.y.0));
            c.line((px, t), (px, b), GREY, 1);
            let s = label(e as f64);
            c.text((px - Canvas::text_width(&s, 2) / 2, b + 8), &s, 2, BLACK);
        }
        for e in (self.y.0 as i32)..=(self.y.1 as i32) {
            let (_, py) = self.map(10f64.powf(self.x.0), 10f64.powi(e));
            c.line((l, py), (r, py), GREY, 1);
            let s = label(e as f64);
            c.text((l - 8 - Canvas::text_width(&s, 2), py - 8), &s, 2, BLACK);
        }
        c.line((l, t), (r, t), BLACK, 1);
        c.line((l, b), (r, b), BLACK, 1);
        c.line((l, t), (l, b), BLACK, 1);
        c.line((r, t), (r, b), BLACK, 1);
        c.text(
            ((l + r) / 2 - Canvas::text_width(x_title, 2) / 2, b + 34),
            x_title,
            2,
            BLACK,
        );
        c.text((l, t - 34), y_title, 2, BLACK);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decades_map_to_the_plot_area() {
        let p = LogLog::covering(&[2.0, 300.0], &[0.05, 4.0], (100, 50, 700, 450));
        assert_eq!((p.x, p.y), ((0.0, 3.0), (-2.0, 1.0)));
        assert_eq!(p.map(1.0, 0.01), (100, 450));
        assert_eq!(p.map(1000.0, 10.0), (700, 50));
        assert_eq!(p.map(10.0, 0.1), (300, 317));
    }

    #[test]
    fn text_sets_the_glyphs_pixels() {
        let mut c = Canvas::new(16, 8, 0x00ff_ffff);
        c.text((0, 0), "I", 1, BLACK);
        let dark = c.frame.color.iter().filter(|&&p| p == BLACK).count();
        // font8x8's "I": rows 0x1E, 0x0C x5, 0x1E, 0: 4 + 5 * 2 + 4 pixels.
        assert_eq!(dark, 18);
    }
}
