//! Depth of field as a post-process (`--dof FOCUS,APERTURE`), from the colour and
//! the 1/z depth buffer a frame already has, as one student report did with a
//! fixed 5x5 Gaussian; here the blur follows each pixel's circle of confusion.
//!
//! A thin lens of radius A focused at depth F images a point at depth z as a disc
//! on the image plane of radius `f A |1/z - 1/F|` pixels (f the focal length in
//! pixels), and the depth buffer holds 1/z already. Each pixel becomes the mean of
//! the square of that half-width around it, read from a summed-area table, so the
//! cost does not grow with the blur.

use crate::pipeline::target::{pack, unpack, Frame};
use glam::Vec3;

/// The widest blur, in pixels either side: beyond it a picture is a smear.
pub const MAX_RADIUS: u32 = 32;

/// Where the lens focuses and how wide it is open.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthOfField {
    /// Depth F in focus (camera space, world units), > 0.
    pub focus: f32,
    /// Lens radius A, in world units, >= 0 (0: a pinhole, everything sharp).
    pub aperture: f32,
}

impl DepthOfField {
    /// The circle of confusion's radius in pixels for a pixel whose depth buffer
    /// holds `zinv` (0 where nothing was drawn: infinitely far), with focal length
    /// `focal` in pixels, rounded to whole pixels and capped at [`MAX_RADIUS`].
    pub fn radius(&self, zinv: f32, focal: f32) -> u32 {
        let r = focal * self.aperture * (zinv - 1.0 / self.focus).abs();
        if r.is_finite() {
            (r.round() as u32).min(MAX_RADIUS)
        } else {
            0
        }
    }

    /// Blurs `frame` in place by each pixel's circle of confusion: the table
    /// keeps the sharp colours, so each pixel can be overwritten as it is done.
    /// A frame without a depth buffer is left as it is.
    pub fn apply(&self, frame: &mut Frame, focal: f32) {
        let (w, h) = (frame.width as usize, frame.height as usize);
        if frame.depth.len() != w * h || w == 0 || h == 0 {
            return;
        }
        let table = SummedArea::new(frame);
        for (i, (color, &zinv)) in frame.color.iter_mut().zip(&frame.depth).enumerate() {
            let r = self.radius(zinv, focal) as usize;
            if r > 0 {
                let (x, y) = (i % w, i / w);
                let (x0, x1) = (x.saturating_sub(r), (x + r).min(w - 1));
                let (y0, y1) = (y.saturating_sub(r), (y + r).min(h - 1));
                *color = pack(table.mean(x0, y0, x1, y1));
            }
        }
    }
}

/// Sums of every channel over each rectangle from the image's corner, so that a
/// rectangle's mean costs four reads. Whole numbers of 8-bit levels: exact.
struct SummedArea {
    width: usize,
    /// (w + 1) x (h + 1): row 0 and column 0 are zero.
    sums: Vec<[u64; 3]>,
}

impl SummedArea {
    fn new(frame: &Frame) -> SummedArea {
        let (w, h) = (frame.width as usize, frame.height as usize);
        let mut sums = vec![[0u64; 3]; (w + 1) * (h + 1)];
        for y in 0..h {
            let mut row = [0u64; 3];
            for x in 0..w {
                let c = unpack(frame.color[y * w + x]);
                for k in 0..3 {
                    row[k] += c[k] as u64;
                    sums[(y + 1) * (w + 1) + x + 1][k] = sums[y * (w + 1) + x + 1][k] + row[k];
                }
            }
        }
        SummedArea { width: w, sums }
    }

    /// The mean colour over pixels x0..=x1, y0..=y1.
    fn mean(&self, x0: usize, y0: usize, x1: usize, y1: usize) -> Vec3 {
        let s = |x: usize, y: usize| self.sums[y * (self.width + 1) + x];
        let (a, b, c, d) = (s(x0, y0), s(x1 + 1, y0), s(x0, y1 + 1), s(x1 + 1, y1 + 1));
        let n = ((x1 - x0 + 1) * (y1 - y0 + 1)) as f32 * 255.0;
        Vec3::from_array([0, 1, 2].map(|k| (d[k] + a[k] - b[k] - c[k]) as f32 / n))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(color: Vec<u32>, depth: Vec<f32>, w: u32) -> Frame {
        let h = color.len() as u32 / w;
        Frame {
            width: w,
            height: h,
            color,
            depth,
        }
    }

    #[test]
    fn the_circle_of_confusion_is_zero_in_focus_and_grows_away_from_it() {
        let dof = DepthOfField {
            focus: 2.0,
            aperture: 0.1,
        };
        // f A |1/z - 1/F| with f = 500: 50 |1/z - 0.5|.
        assert_eq!(dof.radius(0.5, 500.0), 0);
        assert_eq!(dof.radius(0.25, 500.0), 13); // z = 4: 12.5, rounded
        assert_eq!(dof.radius(1.0, 500.0), 25); // z = 1
        assert_eq!(dof.radius(0.0, 500.0), 25); // nothing drawn: infinitely far
        assert_eq!(dof.radius(100.0, 500.0), MAX_RADIUS);
        assert_eq!(dof.radius(f32::NAN, 500.0), 0);
    }

    #[test]
    fn in_focus_pixels_stay_and_blurred_ones_take_their_squares_mean() {
        // 5 x 1: a white pixel among black ones; the middle pixel in focus.
        let white = pack(Vec3::ONE);
        let color = vec![0, 0, white, 0, 0];
        let dof = DepthOfField {
            focus: 1.0,
            aperture: 1.0,
        };
        // f = 1: radius |1/z - 1|, so depth 1 is sharp and 1/z = 2 has radius 1.
        let depth = vec![2.0, 2.0, 1.0, 2.0, 2.0];
        let mut out = frame(color, depth, 5);
        dof.apply(&mut out, 1.0);
        assert_eq!(out.color[2], white, "in focus");
        assert_eq!(out.color[0], 0, "pixels 0 and 1: black");
        // Pixel 1: the mean of pixels 0 to 2, a third of white.
        assert_eq!(out.color[1], pack(Vec3::splat(1.0 / 3.0)));
        assert_eq!(out.color[3], pack(Vec3::splat(1.0 / 3.0)));
    }

    #[test]
    fn a_frame_without_depth_is_unchanged() {
        let f = frame(vec![1, 2, 3, 4], Vec::new(), 2);
        let dof = DepthOfField {
            focus: 1.0,
            aperture: 1.0,
        };
        let mut out = f.clone();
        dof.apply(&mut out, 500.0);
        assert_eq!(out, f);
    }
}
