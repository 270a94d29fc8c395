//! Lines and filled polygons from projected vertices: the handout's `DrawLineSDL`
//! (section 3), `ComputePolygonRows` and `DrawPolygonRows` (section 4).
//!
//! Every function takes the screen as a clip rectangle: the handout writes pixels
//! anywhere, which is undefined in C++; here a pixel outside the screen is skipped
//! and rows outside it are never stored.

use crate::interpolate::{line_pixels, Pixel, Steps, Varying, RUNNING_SUM_LIMIT};
use std::ops::Range;

/// The pixels a primitive may touch: `x` in `0..width`, `y` in `0..height`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Clip {
    pub x: Range<i32>,
    pub y: Range<i32>,
}

impl Clip {
    pub fn screen(width: u32, height: u32) -> Self {
        Clip {
            x: 0..width as i32,
            y: 0..height as i32,
        }
    }

    /// No limit: for printing rows of a polygon that is not on any screen.
    pub fn unbounded() -> Self {
        Clip {
            x: i32::MIN..i32::MAX,
            y: i32::MIN..i32::MAX,
        }
    }

    fn contains<V>(&self, p: &Pixel<V>) -> bool {
        self.x.contains(&p.x) && self.y.contains(&p.y)
    }
}

/// `DrawLineSDL`: the `max(|dx|, |dy|) + 1` interpolated pixels from `a` to `b`,
/// each handed to `plot` if it is on the screen.
pub fn draw_line<V: Varying>(
    a: Pixel<V>,
    b: Pixel<V>,
    clip: &Clip,
    mut plot: impl FnMut(Pixel<V>),
) {
    for p in Steps::new(a, b, line_pixels(&a, &b)) {
        if clip.contains(&p) {
            plot(p);
        }
    }
}

/// The handout's `leftPixels` and `rightPixels`: the first and last pixel of every
/// row a polygon covers, from row `top` down. Kept between polygons so that
/// drawing allocates only when a polygon is taller than any before it.
#[derive(Clone, Debug, Default)]
pub struct Rows<V> {
    pub top: i32,
    pub left: Vec<Pixel<V>>,
    pub right: Vec<Pixel<V>>,
}

impl<V> Rows<V> {
    pub fn new() -> Self {
        Rows {
            top: 0,
            left: Vec::new(),
            right: Vec::new(),
        }
    }

    pub fn len(&self) -> usize {
        self.left.len()
    }

    pub fn is_empty(&self) -> bool {
        self.left.is_empty()
    }
}

/// `ComputePolygonRows` for a convex polygon: one (left, right) pair per row from the
/// smallest to the largest y, found by walking every edge with `Interpolate` and
/// keeping the smallest and largest x seen on each row. Rows outside `clip.y` are
/// not stored. A row that no edge reaches keeps left = `i32::MAX`,
/// right = `i32::MIN` and draws nothing.
pub fn compute_polygon_rows<V: Varying>(vertices: &[Pixel<V>], clip: &Clip, rows: &mut Rows<V>) {
    rows.left.clear();
    rows.right.clear();
    let Some(first) = vertices.first() else {
        return;
    };
    // 1. The rows the polygon spans, cut to the screen.
    let (y_min, y_max) = vertices
        .iter()
        .fold((first.y, first.y), |(lo, hi), p| (lo.min(p.y), hi.max(p.y)));
    let top = y_min.max(clip.y.start);
    let bottom = y_max.min(clip.y.end.saturating_sub(1));
    rows.top = top;
    if top > bottom {
        return;
    }
    // 2. and 3. One entry per row; left starts very large and right very small.
    let n = (bottom as i64 - top as i64 + 1) as usize;
    let unset = |x: i32, row: usize| Pixel {
        x,
        y: top + row as i32,
        v: first.v,
    };
    rows.left.extend((0..n).map(|r| unset(i32::MAX, r)));
    rows.right.extend((0..n).map(|r| unset(i32::MIN, r)));
    // 4. Walk each edge and widen the rows it passes through.
    let count = vertices.len();
    for i in 0..count {
        let (a, b) = (vertices[i], vertices[(i + 1) % count]);
        for p in Steps::new(a, b, line_pixels(&a, &b)) {
            let row = p.y as i64 - top as i64;
            if row < 0 || row >= n as i64 {
                continue;
            }
            let row = row as usize;
            if p.x < rows.left[row].x {
                rows.left[row] = p;
            }
            if p.x > rows.right[row].x {
                rows.right[row] = p;
            }
        }
    }
}

/// `DrawPolygonRows`: interpolate each row from its left to its right pixel and hand
/// every on-screen pixel to `shade` (the handout's `PixelShader`).
///
/// Along a row x steps by `(n - 1) / (n - 1)`, exactly 1, so the running sum of x
/// holds whole numbers and only the varying needs one; the result is bit for bit
/// the handout's `Interpolate` over the row. Pixels left of the screen still add
/// their step, so the sum is the same as if they were drawn. Rows longer than
/// `RUNNING_SUM_LIMIT` compute each value directly (see `interpolate`).
pub fn draw_polygon_rows<V: Varying>(rows: &Rows<V>, clip: &Clip, mut shade: impl FnMut(Pixel<V>)) {
    for (l, r) in rows.left.iter().zip(&rows.right) {
        let n = r.x as i64 - l.x as i64 + 1;
        if n <= 0 {
            continue;
        }
        let span = r.v.sub(l.v);
        let d = (n - 1).max(1) as f32;
        let first = l.x.max(clip.x.start);
        let last = r.x.min(clip.x.end - 1);
        if n as usize > RUNNING_SUM_LIMIT {
            // Too long for a running sum to stay accurate: each value directly.
            for x in first..=last {
                let t = (x as i64 - l.x as i64) as f32 / d;
                shade(Pixel {
                    x,
                    y: l.y,
                    v: l.v.add(span.scale(t)),
                });
            }
            continue;
        }
        let step = span.div(d);
        let mut v = l.v;
        for _ in l.x..first {
            v = v.add(step);
        }
        for x in first..=last {
            shade(Pixel { x, y: l.y, v });
            v = v.add(step);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows_of(points: &[(i32, i32)]) -> Vec<((i32, i32), (i32, i32))> {
        let v: Vec<_> = points.iter().map(|&(x, y)| Pixel::at(x, y)).collect();
        let mut rows = Rows::new();
        compute_polygon_rows(&v, &Clip::unbounded(), &mut rows);
        rows.left
            .iter()
            .zip(&rows.right)
            .map(|(l, r)| ((l.x, l.y), (r.x, r.y)))
            .collect()
    }

    #[test]
    fn the_handouts_triangle_of_section_4() {
        // (10,20), (30,10), (20,40) spans 40 - 10 + 1 = 31 rows.
        assert_eq!(rows_of(&[(10, 20), (30, 10), (20, 40)]).len(), 31);
    }

    #[test]
    fn rows_off_screen_are_not_stored() {
        let v = [Pixel::at(5, -10), Pixel::at(-20, 10), Pixel::at(30, 30)];
        let mut rows = Rows::new();
        compute_polygon_rows(&v, &Clip::screen(8, 8), &mut rows);
        assert_eq!(rows.top, 0);
        assert_eq!(rows.len(), 8);
        let mut seen = 0;
        draw_polygon_rows(&rows, &Clip::screen(8, 8), |p| {
            assert!((0..8).contains(&p.x) && (0..8).contains(&p.y));
            seen += 1;
        });
        assert!(seen > 0);
    }
}
