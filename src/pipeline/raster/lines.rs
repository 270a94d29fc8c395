//! How a line's pixels are walked ([`LineWalk`]): the handout's `Interpolate`
//! (the running sum of `Steps`, truncated), or Bresenham's line algorithm
//! (`--lines bresenham`), the alternative one student report put in its place: the same
//! `max(|dx|, |dy|) + 1` pixels per line, but each the pixel nearest the true
//! line, found with integer sums alone, where `Interpolate` truncates a running
//! float sum (and so leans toward smaller x and y by up to a pixel).
//!
//! Depth and the varying are still interpolated along the line exactly as
//! `Interpolate` does it; only the pixel positions change.

use crate::pipeline::interpolate::{line_pixels, Pixel, Steps, Varying};

/// How lines are walked: the lines of the wireframe, and in the rows rasterizer
/// also the polygon edges that `ComputePolygonRows` follows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Lines {
    /// The handout's `Interpolate` (section 3).
    #[default]
    Interpolate,
    Bresenham,
}

/// A way of walking the pixels of a line, first to last: the handout's
/// `Interpolate`, Bresenham's, or (in `rasterlab check`) a student's. The rows
/// rasterizer's `ComputePolygonRows` takes any.
pub trait LineWalk {
    fn walk<V: Varying>(&self, a: Pixel<V>, b: Pixel<V>, f: impl FnMut(Pixel<V>));
}

impl LineWalk for Lines {
    #[inline]
    fn walk<V: Varying>(&self, a: Pixel<V>, b: Pixel<V>, f: impl FnMut(Pixel<V>)) {
        walk_line(*self, a, b, f)
    }
}

/// Every pixel of the line from `a` to `b`, first to last, walked the way `lines`
/// says. The choice is made once per line; each loop is its own code.
#[inline]
pub fn walk_line<V: Varying>(lines: Lines, a: Pixel<V>, b: Pixel<V>, mut f: impl FnMut(Pixel<V>)) {
    let steps = Steps::new(a, b, line_pixels(&a, &b));
    match lines {
        Lines::Interpolate => steps.for_each(f),
        Lines::Bresenham => {
            for ((x, y), p) in bresenham((a.x, a.y), (b.x, b.y)).zip(steps) {
                f(Pixel { x, y, ..p })
            }
        }
    }
}

/// The integer pixels of Bresenham's line from `a` to `b`, ends included, in any
/// of the eight octants: one step along the major axis per pixel, and a step along
/// the minor axis whenever the error term says the true line has crossed the
/// midpoint between two pixels. `max(|dx|, |dy|) + 1` pixels.
pub fn bresenham(a: (i32, i32), b: (i32, i32)) -> impl Iterator<Item = (i32, i32)> {
    // i64: the differences of two i32 coordinates do not overflow.
    let (dx, dy) = (b.0 as i64 - a.0 as i64, b.1 as i64 - a.1 as i64);
    let (sx, sy) = (dx.signum() as i32, dy.signum() as i32);
    let (dx, dy) = (dx.abs(), dy.abs());
    let (major, minor) = (dx.max(dy), dx.min(dy));
    let x_major = dx >= dy;
    // Twice the distance from the true line to the midpoint, scaled by `major`:
    // step along the minor axis when it turns positive.
    let mut error = 2 * minor - major;
    let (mut x, mut y) = a;
    (0..=major).map(move |_| {
        let p = (x, y);
        if error > 0 {
            if x_major {
                y += sy;
            } else {
                x += sx;
            }
            error -= 2 * major;
        }
        error += 2 * minor;
        if x_major {
            x += sx;
        } else {
            y += sy;
        }
        p
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shallow_line_by_hand() {
        // From (0, 0) to (5, 2): the true line passes y = 0.4 at x = 1 and 0.8 at
        // x = 2, so the nearest pixels are (1, 0) and (2, 1).
        let got: Vec<_> = bresenham((0, 0), (5, 2)).collect();
        assert_eq!(got, [(0, 0), (1, 0), (2, 1), (3, 1), (4, 2), (5, 2)]);
    }

    #[test]
    fn every_octant_ends_at_the_end_with_the_handouts_pixel_count() {
        for (bx, by) in [
            (7, 3),
            (3, 7),
            (-3, 7),
            (-7, 3),
            (-7, -3),
            (-3, -7),
            (3, -7),
            (7, -3),
        ] {
            let got: Vec<_> = bresenham((10, 10), (10 + bx, 10 + by)).collect();
            assert_eq!(got.len(), 8, "to ({bx}, {by})");
            assert_eq!(got[0], (10, 10));
            assert_eq!(*got.last().unwrap(), (10 + bx, 10 + by));
            // Each step moves one pixel along the major axis, at most one along the
            // other: a line with no holes and no doubled pixel.
            for w in got.windows(2) {
                let (ddx, ddy) = ((w[1].0 - w[0].0).abs(), (w[1].1 - w[0].1).abs());
                assert_eq!(ddx.max(ddy), 1, "{w:?}");
            }
            // Every pixel is within half a pixel of the true line along the minor axis.
            for &(x, y) in &got {
                let (t, u) = ((x - 10) as f64, (y - 10) as f64);
                let off = if bx.abs() >= by.abs() {
                    (u - t * by as f64 / bx as f64).abs()
                } else {
                    (t - u * bx as f64 / by as f64).abs()
                };
                assert!(
                    off <= 0.5,
                    "({x}, {y}) is {off} off the line to ({bx}, {by})"
                );
            }
        }
    }

    #[test]
    fn depth_is_interpolated_as_interpolate_does() {
        let mut a = Pixel::at(0, 0);
        let mut b = Pixel::at(5, 2);
        (a.zinv, b.zinv) = (1.0, 4.0);
        let walk = |lines| {
            let mut pixels = Vec::new();
            walk_line(lines, a, b, |p| pixels.push(p));
            pixels
        };
        let (by_interpolate, by_bresenham) = (walk(Lines::Interpolate), walk(Lines::Bresenham));
        let z = |v: &[Pixel<_>]| v.iter().map(|p| p.zinv).collect::<Vec<_>>();
        assert_eq!(z(&by_interpolate), z(&by_bresenham));
        // Interpolate truncates y = 0.4 i, so rows 0.8 and 1.6 stay below the
        // nearer pixel; Bresenham takes the nearest.
        let ys = |v: &[Pixel<_>]| v.iter().map(|p| p.y).collect::<Vec<_>>();
        assert_eq!(ys(&by_interpolate), [0, 0, 0, 1, 1, 2]);
        assert_eq!(ys(&by_bresenham), [0, 0, 1, 1, 2, 2]);
    }
}
