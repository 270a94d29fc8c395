//! Bresenham's line algorithm (`--lines bresenham`), the alternative one student
//! report put in place of `Interpolate`: the same `max(|dx|, |dy|) + 1` pixels per
//! line, but each the pixel nearest the true line, found with integer sums alone,
//! where `Interpolate` truncates a running float sum (and so leans toward smaller
//! x and y by up to a pixel). Depth and the varying are still interpolated along
//! the line as `Interpolate` does it (`rows::walk_line`); only the pixel
//! positions change.

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
}
