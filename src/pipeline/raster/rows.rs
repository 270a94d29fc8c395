//! The handout's rasterizer: vertices truncated to whole pixels, lines by
//! `Interpolate` (`DrawLineSDL`, section 3), polygons by `ComputePolygonRows` and
//! `DrawPolygonRows` (section 4). How a line or an edge is walked is a
//! [`LineWalk`]: the handout's `Interpolate`, Bresenham's (`--lines bresenham`,
//! in `super::bresenham`), or in `rasterlab check` a student's.

use super::bresenham::bresenham;
use super::{Bounds, Placed, Rasterizer, SharedPlacing, Viewport};
use crate::pipeline::clip::ScreenVertex;
use crate::pipeline::interpolate::{
    line_pixels, Pixel, RunningSum, Steps, Varying, RUNNING_SUM_LIMIT,
};
use std::ops::Range;

/// The handout's rows rasterizer (`--raster rows`, the default).
#[derive(Clone, Copy, Debug, Default)]
pub struct RowRaster;

/// A projected vertex on its pixel, as the handout's `VertexShader` places it:
/// `int(f X/Z) + W/2`, truncating toward zero before the half size is added. The
/// pipeline only passes vertices inside the guard band, far inside `i32`.
#[inline]
pub fn to_pixel<V>(s: ScreenVertex<V>, viewport: &Viewport) -> Pixel<V> {
    let (x, y) = RowRaster.place(s.x, s.y, viewport);
    Pixel {
        x,
        y,
        zinv: s.zinv,
        varying: s.varying,
    }
}

impl Rasterizer for RowRaster {
    type Scratch<V: Varying> = Rows<V>;

    fn reserve<V: Varying>(&self, rows: &mut Rows<V>, height: usize) {
        if rows.left.capacity() < height {
            rows.left.reserve(height);
            rows.right.reserve(height);
        }
    }

    fn point<V: Varying>(
        &self,
        p: ScreenVertex<V>,
        viewport: &Viewport,
        mut plot: impl FnMut(Pixel<V>),
    ) {
        let p = to_pixel(p, viewport);
        if viewport.bounds.contains(&p) {
            plot(p);
        }
    }

    fn line<V: Varying>(
        &self,
        a: ScreenVertex<V>,
        b: ScreenVertex<V>,
        viewport: &Viewport,
        plot: impl FnMut(Pixel<V>),
    ) {
        let (a, b) = (to_pixel(a, viewport), to_pixel(b, viewport));
        draw_line_by(viewport.lines, a, b, &viewport.bounds, plot);
    }

    fn polygon<V: Varying>(
        &self,
        rows: &mut Rows<V>,
        corners: &[ScreenVertex<V>],
        viewport: &Viewport,
        plot: impl FnMut(Pixel<V>),
    ) {
        let mut pixels = [Pixel::default(); crate::pipeline::clip::MAX_CORNERS];
        for (p, &c) in pixels.iter_mut().zip(corners) {
            *p = to_pixel(c, viewport);
        }
        let corners = &pixels[..corners.len()];
        compute_polygon_rows_by(&viewport.lines, corners, &viewport.bounds, rows);
        draw_polygon_rows(rows, &viewport.bounds, plot);
    }

    type Place = (i32, i32);

    const SHARED: Option<SharedPlacing> = Some(SharedPlacing::Rows);

    fn shared_places(places: &[(i32, i32)]) -> Option<&[(i32, i32)]> {
        Some(places)
    }

    /// Never: `ComputePolygonRows` gives every triangle the rows its corners span.
    fn misses(&self, _: [(i32, i32); 3], _: &Viewport) -> bool {
        false
    }

    /// When the rows its corners span are all above or all below `rows`.
    #[inline]
    fn misses_rows(&self, places: [(i32, i32); 3], rows: &Range<i32>) -> bool {
        let [a, b, c] = places.map(|(_, y)| y);
        a.max(b).max(c) < rows.start || a.min(b).min(c) >= rows.end
    }

    #[inline]
    fn place(&self, x: f32, y: f32, viewport: &Viewport) -> (i32, i32) {
        (
            x as i32 + viewport.half_width,
            y as i32 + viewport.half_height,
        )
    }

    fn triangle<V: Varying>(
        &self,
        rows: &mut Rows<V>,
        corners: [Placed<(i32, i32), V>; 3],
        viewport: &Viewport,
        plot: impl FnMut(Pixel<V>),
    ) {
        let corners = corners.map(|c| Pixel {
            x: c.place.0,
            y: c.place.1,
            zinv: c.zinv,
            varying: c.varying,
        });
        compute_polygon_rows_by(&viewport.lines, &corners, &viewport.bounds, rows);
        draw_polygon_rows(rows, &viewport.bounds, plot);
    }
}

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

/// `DrawLineSDL`: the `max(|dx|, |dy|) + 1` interpolated pixels from `a` to `b`,
/// each handed to `plot` if it is in the bounds.
pub fn draw_line<V: Varying>(
    a: Pixel<V>,
    b: Pixel<V>,
    bounds: &Bounds,
    plot: impl FnMut(Pixel<V>),
) {
    draw_line_by(Lines::Interpolate, a, b, bounds, plot)
}

/// [`draw_line`], with the line walked the way `lines` says. The handout's walk
/// starts at the bounds' first row and ends at their last (a band of a frame on
/// threads draws only its own rows), with the pixels it gives unchanged.
pub fn draw_line_by<V: Varying>(
    lines: Lines,
    a: Pixel<V>,
    b: Pixel<V>,
    bounds: &Bounds,
    mut plot: impl FnMut(Pixel<V>),
) {
    let in_bounds = |p: Pixel<V>| {
        if bounds.contains(&p) {
            plot(p);
        }
    };
    match lines {
        Lines::Interpolate => {
            let steps = Steps::new(a, b, line_pixels(&a, &b));
            // Both ends in the bounds' rows: no search for where the walk
            // enters and leaves them (`in_bounds` tests each pixel anyway).
            if bounds.y.contains(&a.y) && bounds.y.contains(&b.y) {
                steps.for_each(in_bounds)
            } else {
                steps.within_rows(bounds.y.clone()).for_each(in_bounds)
            }
        }
        Lines::Bresenham => walk_line(lines, a, b, in_bounds),
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
/// keeping the smallest and largest x seen on each row. Rows outside `bounds.y` are
/// not stored. A row that no edge reaches keeps left = `i32::MAX`,
/// right = `i32::MIN` and draws nothing.
pub fn compute_polygon_rows<V: Varying>(
    vertices: &[Pixel<V>],
    bounds: &Bounds,
    rows: &mut Rows<V>,
) {
    compute_polygon_rows_by(&Lines::Interpolate, vertices, bounds, rows)
}

/// [`compute_polygon_rows`], with the edges walked by `lines`.
pub fn compute_polygon_rows_by<V: Varying>(
    lines: &impl LineWalk,
    vertices: &[Pixel<V>],
    bounds: &Bounds,
    rows: &mut Rows<V>,
) {
    rows.left.clear();
    rows.right.clear();
    let Some(first) = vertices.first() else {
        return;
    };
    // 1. The rows the polygon spans, cut to the bounds.
    let (y_min, y_max) = vertices
        .iter()
        .fold((first.y, first.y), |(lo, hi), p| (lo.min(p.y), hi.max(p.y)));
    let top = y_min.max(bounds.y.start);
    let bottom = y_max.min(bounds.y.end.saturating_sub(1));
    rows.top = top;
    if top > bottom {
        return;
    }
    // 2. and 3. One entry per row; left starts very large and right very small.
    let n = (bottom as i64 - top as i64 + 1) as usize;
    let unset = |x: i32, row: usize| Pixel {
        x,
        y: top + row as i32,
        ..*first
    };
    rows.left.extend((0..n).map(|r| unset(i32::MAX, r)));
    rows.right.extend((0..n).map(|r| unset(i32::MIN, r)));
    // 4. Walk each edge and widen the rows it passes through.
    let count = vertices.len();
    for i in 0..count {
        let (a, b) = (vertices[i], vertices[(i + 1) % count]);
        lines.walk(a, b, |p| {
            let row = p.y as i64 - top as i64;
            if row < 0 || row >= n as i64 {
                return;
            }
            let row = row as usize;
            if p.x < rows.left[row].x {
                rows.left[row] = p;
            }
            if p.x > rows.right[row].x {
                rows.right[row] = p;
            }
        });
    }
}

/// `DrawPolygonRows`: interpolate each row from its left to its right pixel with
/// `Interpolate` (`Steps`) and hand every pixel in the bounds to `plot`.
///
/// Along a row x steps by `(n - 1) / (n - 1)`, exactly 1, so x is counted in
/// integers and only 1/z and the varying need the running sum; the result is bit
/// for bit the handout's `Interpolate` over the row. Pixels left of the bounds still
/// add their step, so the sum is the same as if they were drawn. Rows longer than
/// `RUNNING_SUM_LIMIT` compute each value directly (see `Steps`).
pub fn draw_polygon_rows<V: Varying>(
    rows: &Rows<V>,
    bounds: &Bounds,
    mut plot: impl FnMut(Pixel<V>),
) {
    for (l, r) in rows.left.iter().zip(&rows.right) {
        let n = r.x as i64 - l.x as i64 + 1;
        if n <= 0 {
            continue;
        }
        let first = l.x.max(bounds.x.start);
        let last = r.x.min(bounds.x.end - 1);
        if first > last {
            continue;
        }
        let skipped = (first as i64 - l.x as i64) as usize;
        // An exclusive range (last < bounds.x.end) and the row's y read once:
        // the pixel loop then keeps both in registers.
        let (columns, y) = (first..last + 1, l.y);
        if n as usize > RUNNING_SUM_LIMIT {
            let mut steps = Steps::new(*l, *r, n as usize);
            steps.skip_to(skipped);
            for (x, p) in columns.zip(steps) {
                plot(Pixel { x, ..p });
            }
            continue;
        }
        let mut sum = RunningSum::new(l, r, (n - 1).max(1) as f32);
        for _ in 0..skipped {
            sum.advance();
        }
        for x in columns {
            plot(sum.at(x, y));
            sum.advance();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn screen(w: i32, h: i32) -> Bounds {
        Bounds { x: 0..w, y: 0..h }
    }

    fn rows_of(points: &[(i32, i32)]) -> Vec<((i32, i32), (i32, i32))> {
        let v: Vec<_> = points.iter().map(|&(x, y)| Pixel::at(x, y)).collect();
        let mut rows = Rows::new();
        compute_polygon_rows(&v, &Bounds::unbounded(), &mut rows);
        rows.left
            .iter()
            .zip(&rows.right)
            .map(|(l, r)| ((l.x, l.y), (r.x, r.y)))
            .collect()
    }

    #[test]
    fn a_band_misses_exactly_the_triangles_whose_rows_lie_beyond_it() {
        let triangles = [
            [(10, 20), (30, 10), (20, 40)],
            [(0, 5), (3, 5), (1, 5)],
            [(5, 0), (0, 9), (9, 9)],
        ];
        for triangle in triangles {
            let spanned: Vec<i32> = rows_of(&triangle).iter().map(|(l, _)| l.1).collect();
            for rows in [0..5, 5..6, 6..10, 10..11, 11..40, 40..41, 41..60] {
                let touched = spanned.iter().any(|y| rows.contains(y));
                let beyond = RowRaster.misses_rows(triangle, &rows);
                assert_eq!(beyond, !touched, "{triangle:?} in rows {rows:?}");
            }
        }
    }

    #[test]
    fn the_handouts_triangle_of_section_4() {
        // (10,20), (30,10), (20,40) spans 40 - 10 + 1 = 31 rows.
        assert_eq!(rows_of(&[(10, 20), (30, 10), (20, 40)]).len(), 31);
    }

    #[test]
    fn rows_outside_the_bounds_are_not_stored() {
        let v = [Pixel::at(5, -10), Pixel::at(-20, 10), Pixel::at(30, 30)];
        let mut rows = Rows::new();
        compute_polygon_rows(&v, &screen(8, 8), &mut rows);
        assert_eq!(rows.top, 0);
        assert_eq!(rows.len(), 8);
        let mut seen = 0;
        draw_polygon_rows(&rows, &screen(8, 8), |p| {
            assert!((0..8).contains(&p.x) && (0..8).contains(&p.y));
            seen += 1;
        });
        assert_eq!(seen, 64, "the triangle covers the whole 8 x 8 screen");
    }

    #[test]
    fn a_row_is_interpolate_over_the_row_even_where_it_is_cut() {
        // One row from x = -7 to 12 with 1/z and a varying that do not divide
        // evenly; cut at x = 0 it must give what the whole walk gives there.
        let l = Pixel {
            x: -7,
            y: 3,
            zinv: 0.3,
            varying: 1.7f32,
        };
        let mut r = l;
        (r.x, r.zinv, r.varying) = (12, 0.9, -2.2);
        let whole: Vec<_> = Steps::new(l, r, 20).filter(|p| p.x >= 0).collect();
        let rows = Rows {
            top: 3,
            left: vec![l],
            right: vec![r],
        };
        let mut cut = Vec::new();
        draw_polygon_rows(&rows, &screen(10, 10), |p| cut.push(p));
        assert_eq!(cut, whole[..10]);
        assert_eq!(cut[0].x, 0);
    }

    #[test]
    fn a_band_of_rows_draws_exactly_its_part_of_the_whole() {
        let v = [Pixel::at(3, 1), Pixel::at(60, 20), Pixel::at(10, 50)];
        let draw = |b: Bounds| {
            let mut rows = Rows::new();
            compute_polygon_rows(&v, &b, &mut rows);
            let mut out = Vec::new();
            draw_polygon_rows(&rows, &b, |p| out.push((p.x, p.y)));
            out
        };
        let whole = draw(screen(64, 64));
        let mut bands = draw(Bounds { x: 0..64, y: 0..17 });
        bands.extend(draw(Bounds {
            x: 0..64,
            y: 17..64,
        }));
        assert_eq!(bands, whole);
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
