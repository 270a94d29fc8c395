//! The exact rasterizer (`--raster edge`): edge functions over each triangle's
//! bounding box, in the way of GPUs and of one of the student reports.
//!
//! - Vertices are projected without truncation and snapped to 1/256 of a pixel.
//! - Pixel (i, j) is sampled at its centre, (256 i + 128, 256 j + 128).
//! - Edge functions are exact integers (i64). A pixel is covered when its centre is
//!   strictly inside, or on an edge whose inside lies immediately to its right (x
//!   increasing) or, for a horizontal edge, immediately below it (y increasing):
//!   the top-left rule, so a pixel on an edge shared by two triangles is drawn once.
//! - What the pipeline carries (1/z and the varying, encoded by the interpolation)
//!   is weighted by the pixel centre's barycentric coordinates; perspective
//!   correction then divides as for the rows rasterizer.
//! - Points land on pixel (floor(x), floor(y)); lines join such pixels with the
//!   handout's `Interpolate`.

use super::rows::draw_line_by;
use super::{Placed, Rasterizer, SharedPlacing, Viewport};
use crate::pipeline::clip::ScreenVertex;
use crate::pipeline::interpolate::{Pixel, Varying};
use std::ops::Range;

/// The exact rasterizer.
#[derive(Clone, Copy, Debug, Default)]
pub struct EdgeRaster;

/// Sub-pixel steps per pixel: 8 bits of precision.
pub const SUBPIXEL: i64 = 256;

/// Boxes fewer pixels wide than this are scanned centre by centre; wider ones
/// solve each row's run of covered pixels.
const SMALL_SPAN: i64 = 8;

/// A vertex on the sub-pixel grid, and what it carries.
#[derive(Clone, Copy, Debug)]
struct Snapped<V> {
    x: i64,
    y: i64,
    zinv: f32,
    varying: V,
}

/// A position from the screen's centre in image pixels, unrounded: `f X/Z + W/2`.
#[inline]
fn image_position(x: f32, y: f32, viewport: &Viewport) -> (f32, f32) {
    (x + viewport.centre.0, y + viewport.centre.1)
}

fn snap<V: Copy>(s: &ScreenVertex<V>, viewport: &Viewport) -> Snapped<V> {
    let (x, y) = EdgeRaster.place(s.x, s.y, viewport);
    Snapped {
        x: x.into(),
        y: y.into(),
        zinv: s.zinv,
        varying: s.varying,
    }
}

/// `v.round() as i32`, halves away from zero, without the library call
/// `f32::round` is on x86-64 before SSE4.1 (9 % of the samples for a million small
/// triangles): truncate, then step by the remainder, which is exact in f32.
#[inline]
fn round_to_i32(v: f32) -> i32 {
    let whole = v as i32;
    let rest = v - whole as f32;
    whole.saturating_add((rest >= 0.5) as i32 - (rest <= -0.5) as i32)
}

/// The pixel a point lands on: the one containing it.
fn point_pixel<V>(s: ScreenVertex<V>, viewport: &Viewport) -> Pixel<V> {
    let (x, y) = image_position(s.x, s.y, viewport);
    Pixel {
        x: x.floor() as i32,
        y: y.floor() as i32,
        zinv: s.zinv,
        varying: s.varying,
    }
}

/// One edge, from `a` to `b`: `E(p) = (b - a) x (p - a)`, positive on the inside of
/// a triangle whose area (as this function gives it) is positive.
#[derive(Clone, Copy, Debug)]
struct Edge {
    /// E at the first pixel centre of the current row, and its steps.
    dx: i64,
    dy: i64,
    /// 0 if a centre exactly on the edge is covered (the top-left rule), else 1.
    bias: i64,
}

impl Edge {
    fn new(ax: i64, ay: i64, bx: i64, by: i64) -> Edge {
        // E(p) = (bx - ax)(py - ay) - (by - ay)(px - ax): dE/dx = ay - by,
        // dE/dy = bx - ax. A centre on the edge is covered when moving it by
        // (+e, +e^2) goes inside: dE/dx > 0, or dE/dx = 0 and dE/dy > 0.
        let (dx, dy) = (ay - by, bx - ax);
        let covered = dx > 0 || (dx == 0 && dy > 0);
        Edge {
            dx,
            dy,
            bias: if covered { 0 } else { 1 },
        }
    }

    fn at(&self, ax: i64, ay: i64, px: i64, py: i64) -> i64 {
        self.dy * (py - ay) + self.dx * (px - ax)
    }
}

/// The pixels whose centres a triangle's bounding box contains, within the
/// bounds: from the first centre at or after its least corner to the last at or
/// before its greatest.
struct CentreBox {
    first_i: i64,
    last_i: i64,
    first_j: i64,
    last_j: i64,
}

/// The first and last column (or row) of centres between the least and the
/// greatest of three coordinates on the sub-pixel grid: the first at or after
/// the least, the last at or before the greatest (before the first if none).
#[inline]
fn centres_between(p: i64, q: i64, r: i64) -> (i64, i64) {
    let (least, greatest) = (p.min(q).min(r), p.max(q).max(r));
    (
        (least - SUBPIXEL / 2 + SUBPIXEL - 1).div_euclid(SUBPIXEL),
        (greatest - SUBPIXEL / 2).div_euclid(SUBPIXEL),
    )
}

impl CentreBox {
    /// The box of the corners `(x, y)` on the sub-pixel grid; none if it holds
    /// no centre, as for most triangles of a fine mesh.
    #[inline]
    fn of(corners: [(i64, i64); 3], viewport: &Viewport) -> Option<CentreBox> {
        let [a, b, c] = corners;
        let ((first_i, last_i), (first_j, last_j)) = (
            centres_between(a.0, b.0, c.0),
            centres_between(a.1, b.1, c.1),
        );
        let bounds = &viewport.bounds;
        let (first_i, last_i) = (
            first_i.max(bounds.x.start as i64),
            last_i.min(bounds.x.end as i64 - 1),
        );
        let (first_j, last_j) = (
            first_j.max(bounds.y.start as i64),
            last_j.min(bounds.y.end as i64 - 1),
        );
        (first_i <= last_i && first_j <= last_j).then_some(CentreBox {
            first_i,
            last_i,
            first_j,
            last_j,
        })
    }
}

/// Rasterizes one triangle with the rules above; a box narrower than `small_span`
/// pixels is scanned centre by centre ([`SMALL_SPAN`]).
fn triangle<V: Varying>(
    corners: [Snapped<V>; 3],
    viewport: &Viewport,
    small_span: i64,
    plot: &mut impl FnMut(Pixel<V>),
) {
    let [a, mut b, mut c] = corners;
    let Some(CentreBox {
        first_i,
        last_i,
        first_j,
        last_j,
    }) = CentreBox::of([(a.x, a.y), (b.x, b.y), (c.x, c.y)], viewport)
    else {
        return;
    };
    let (s, h) = (SUBPIXEL, SUBPIXEL / 2);
    let area = Edge::new(a.x, a.y, b.x, b.y).at(a.x, a.y, c.x, c.y);
    if area == 0 {
        return; // zero area covers nothing
    }
    if area < 0 {
        std::mem::swap(&mut b, &mut c); // draw both windings
    }
    let area = area.abs();
    // Edges opposite a, b and c: their values are the weights of a, b and c.
    let edges = [
        (Edge::new(b.x, b.y, c.x, c.y), b),
        (Edge::new(c.x, c.y, a.x, a.y), c),
        (Edge::new(a.x, a.y, b.x, b.y), a),
    ];
    let inv_area = 1.0 / area as f32;
    let columns = last_i - first_i;
    let weighted = |e: [i64; 3], i: i64, j: i64| {
        let w = e.map(|v| v as f32 * inv_area);
        Pixel {
            x: i as i32,
            y: j as i32,
            zinv: a.zinv * w[0] + b.zinv * w[1] + c.zinv * w[2],
            varying: a.varying * w[0] + b.varying * w[1] + c.varying * w[2],
        }
    };
    let step_x = edges.map(|(edge, _)| edge.dx * s);
    let step_y = edges.map(|(edge, _)| edge.dy * s);
    let bias = edges.map(|(edge, _)| edge.bias);
    let advance = |e: &mut [i64; 3], step: [i64; 3], times: i64| {
        for (v, d) in e.iter_mut().zip(step) {
            *v += d * times;
        }
    };
    if columns < small_span {
        // A narrow box (most triangles of a fine mesh): every centre in it is
        // tested, which is cheaper than solving for each row's run with three
        // divisions. The same integers decide, so the same pixels and weights.
        // Each edge's value less its bias, so that a centre is covered when all
        // three are at least 0: fewer values held in the loop.
        let (px, py) = (s * first_i + h, s * first_j + h);
        let mut row = edges.map(|(edge, from)| edge.at(from.x, from.y, px, py) - edge.bias);
        for j in first_j..=last_j {
            let mut e = row;
            for i in first_i..=last_i {
                if (e[0] | e[1] | e[2]) >= 0 {
                    let e = [e[0] + bias[0], e[1] + bias[1], e[2] + bias[2]];
                    plot(weighted(e, i, j));
                }
                advance(&mut e, step_x, 1);
            }
            advance(&mut row, step_y, 1);
        }
        return;
    }
    for j in first_j..=last_j {
        let py = s * j + h;
        let px = s * first_i + h;
        let mut e = edges.map(|(edge, from)| edge.at(from.x, from.y, px, py));
        // The covered pixels of a row are one run: where each edge function, a
        // line in i, is at least its bias. Solved exactly in integers per edge.
        let (mut from, mut to) = (0, columns);
        for ((&v, b), step) in e.iter().zip(bias).zip(step_x) {
            let value = v - b;
            match step.signum() {
                1 => from = from.max(-value.div_euclid(step)),
                -1 => to = to.min(value.div_euclid(-step)),
                _ if value < 0 => to = -1,
                _ => {}
            }
        }
        advance(&mut e, step_x, from.max(0));
        for t in from.max(0)..=to {
            plot(weighted(e, first_i + t, j));
            advance(&mut e, step_x, 1);
        }
    }
}

impl Rasterizer for EdgeRaster {
    type Scratch<V: Varying> = ();

    fn point<V: Varying>(
        &self,
        p: ScreenVertex<V>,
        viewport: &Viewport,
        mut plot: impl FnMut(Pixel<V>),
    ) {
        let p = point_pixel(p, viewport);
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
        let (a, b) = (point_pixel(a, viewport), point_pixel(b, viewport));
        draw_line_by(viewport.lines, a, b, &viewport.bounds, plot);
    }

    /// A convex polygon as a fan of triangles from its first corner: the fan's
    /// inner edges are shared, and the top-left rule draws each pixel once.
    fn polygon<V: Varying>(
        &self,
        _: &mut (),
        corners: &[ScreenVertex<V>],
        viewport: &Viewport,
        mut plot: impl FnMut(Pixel<V>),
    ) {
        let Some(first) = corners.first() else {
            return;
        };
        let first = snap(first, viewport);
        for pair in corners[1..].windows(2) {
            let tri = [first, snap(&pair[0], viewport), snap(&pair[1], viewport)];
            triangle(tri, viewport, SMALL_SPAN, &mut plot);
        }
    }

    /// `i32`, half the bytes of the edge functions' `i64`, for the places a frame
    /// keeps for all its vertices: a point of the guard band (one screen beyond
    /// each side) of an image up to 4 million pixels a side fits, in 1/256 pixels.
    type Place = (i32, i32);

    /// On the sub-pixel grid: `f X/Z + W/2` in 1/256 pixels, rounded.
    #[inline]
    fn place(&self, x: f32, y: f32, viewport: &Viewport) -> (i32, i32) {
        let (x, y) = image_position(x, y, viewport);
        (
            round_to_i32(x * SUBPIXEL as f32),
            round_to_i32(y * SUBPIXEL as f32),
        )
    }

    const SHARED: Option<SharedPlacing> = Some(SharedPlacing::Edge);

    fn shared_places(places: &[(i32, i32)]) -> Option<&[(i32, i32)]> {
        Some(places)
    }

    /// No pixel centre in the triangle's bounding box (the bounds aside: a
    /// triangle the pipeline asks about is in view).
    #[inline]
    fn misses(&self, places: [(i32, i32); 3], _: &Viewport) -> bool {
        let [a, b, c] = places.map(|(x, y)| (i64::from(x), i64::from(y)));
        let none_between = |p, q, r| {
            let (first, last) = centres_between(p, q, r);
            last < first
        };
        // The rows only if the columns hold a centre.
        none_between(a.0, b.0, c.0) || none_between(a.1, b.1, c.1)
    }

    /// No row of pixel centres between its corners is one of `rows`.
    #[inline]
    fn misses_rows(&self, places: [(i32, i32); 3], rows: &Range<i32>) -> bool {
        let [a, b, c] = places.map(|(_, y)| i64::from(y));
        let (first, last) = centres_between(a, b, c);
        last < i64::from(rows.start) || first >= i64::from(rows.end)
    }

    fn triangle<V: Varying>(
        &self,
        _: &mut (),
        corners: [Placed<(i32, i32), V>; 3],
        viewport: &Viewport,
        mut plot: impl FnMut(Pixel<V>),
    ) {
        let corners = corners.map(|c| Snapped {
            x: c.place.0.into(),
            y: c.place.1.into(),
            zinv: c.zinv,
            varying: c.varying,
        });
        triangle(corners, viewport, SMALL_SPAN, &mut plot);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::interpolate::Nothing;
    use crate::pipeline::raster::Bounds;
    use glam::Vec3;

    #[test]
    fn round_to_i32_is_f32_round_for_every_value() {
        // Every 31st bit pattern (all signs, exponents, NaN and infinities), and
        // every value within 64 steps of each half from -4 to 4.
        for bits in (0..=u32::MAX).step_by(31) {
            let v = f32::from_bits(bits);
            assert_eq!(round_to_i32(v), v.round() as i32, "{v:e} ({bits:#x})");
        }
        for half in -8..8 {
            let h = half as f32 + 0.5;
            for k in -64..=64 {
                let v = f32::from_bits((h.to_bits() as i32 + k) as u32);
                assert_eq!(round_to_i32(v), v.round() as i32, "{v:e}");
            }
        }
    }

    fn viewport(w: i32, h: i32) -> Viewport {
        Viewport {
            half_width: w / 2,
            half_height: h / 2,
            centre: (w as f32 / 2.0, h as f32 / 2.0),
            bounds: Bounds { x: 0..w, y: 0..h },
            lines: Default::default(),
        }
    }

    /// A vertex at image position (x, y) on a `w` x `h` viewport.
    fn at(x: f32, y: f32, w: i32, h: i32) -> ScreenVertex<Nothing> {
        ScreenVertex {
            x: x - w as f32 / 2.0,
            y: y - h as f32 / 2.0,
            zinv: 1.0,
            varying: Nothing {},
        }
    }

    fn covered(corners: &[(f32, f32)]) -> Vec<(i32, i32)> {
        let v: Vec<_> = corners.iter().map(|&(x, y)| at(x, y, 16, 16)).collect();
        let mut out = Vec::new();
        EdgeRaster.polygon(&mut (), &v, &viewport(16, 16), |p| out.push((p.x, p.y)));
        out.sort();
        out
    }

    #[test]
    fn centres_strictly_inside_and_the_top_left_rule() {
        // The square [1, 3] x [1, 3] as two triangles: its pixels are those whose
        // centres (i + 0.5) lie inside: (1, 1), (2, 1), (1, 2), (2, 2). Centres on
        // its edges: none. Both triangles together draw each exactly once.
        let mut both = covered(&[(1.0, 1.0), (3.0, 1.0), (3.0, 3.0)]);
        both.extend(covered(&[(1.0, 1.0), (3.0, 3.0), (1.0, 3.0)]));
        both.sort();
        assert_eq!(both, [(1, 1), (1, 2), (2, 1), (2, 2)]);
        // A square whose edges pass through centres: [0.5, 2.5]^2. The left and top
        // edges' centres are in, the right and bottom ones out.
        let mut square = covered(&[(0.5, 0.5), (2.5, 0.5), (2.5, 2.5)]);
        square.extend(covered(&[(0.5, 0.5), (2.5, 2.5), (0.5, 2.5)]));
        square.sort();
        assert_eq!(square, [(0, 0), (0, 1), (1, 0), (1, 1)]);
        // Either winding, the same pixels; zero area, none.
        assert_eq!(
            covered(&[(1.0, 1.0), (3.0, 3.0), (3.0, 1.0)]),
            covered(&[(1.0, 1.0), (3.0, 1.0), (3.0, 3.0)])
        );
        assert!(covered(&[(1.0, 1.0), (2.0, 2.0), (3.0, 3.0)]).is_empty());
    }

    /// Numbers in 0..range, the same every run.
    fn xorshift(seed: u64) -> impl FnMut(i64) -> i64 {
        let mut next = crate::pipeline::xorshift(seed);
        move |range| (next() % range as u64) as i64
    }

    #[test]
    fn scanning_a_narrow_box_covers_what_solving_each_row_covers() {
        // Random triangles up to 20 pixels across, snapped anywhere on the
        // sub-pixel grid (edges through centres included): the centre-by-centre
        // scan and the per-row solve give the same pixels with the same bits.
        let mut next = xorshift(0x9e37_79b9_7f4a_7c15u64);
        let view = viewport(40, 40);
        let mut drawn = 0;
        for _ in 0..20_000 {
            let (x0, y0) = (next(30 * SUBPIXEL), next(30 * SUBPIXEL));
            let size = 1 + next(20 * SUBPIXEL);
            let mut corner = |k: f32| Snapped {
                x: x0 + next(size) - size / 2,
                y: y0 + next(size) - size / 2,
                zinv: 0.5 + k,
                varying: Vec3::new(k, 2.0 * k, 1.0),
            };
            let tri = [corner(0.0), corner(0.1), corner(0.3)];
            let by = |small_span| {
                let mut out = Vec::new();
                triangle(tri, &view, small_span, &mut |p| {
                    out.push((
                        p.x,
                        p.y,
                        p.zinv.to_bits(),
                        p.varying.to_array().map(f32::to_bits),
                    ))
                });
                out.sort();
                out
            };
            let scanned = by(i64::MAX);
            assert_eq!(scanned, by(0), "{tri:?}");
            drawn += scanned.len();
        }
        assert!(drawn > 100_000, "{drawn} pixels");
    }

    #[test]
    fn the_box_of_centres_misses_no_covered_centre() {
        // Tiny triangles with corners on a grid of quarter pixels, so that many
        // corners and edges fall exactly on pixel centres: the pixels drawn are
        // those found by testing every centre of the viewport.
        let mut next = xorshift(0x2545_f491_4f6c_dd1du64);
        let view = viewport(8, 8);
        let (mut drawn, mut empty, mut passed_over) = (0, 0, 0);
        let mut beyond_band = 0;
        for _ in 0..20_000 {
            let (x0, y0) = (2 + next(4), 2 + next(4));
            let mut corner = || Snapped {
                x: (4 * x0 + next(9) - 4) * SUBPIXEL / 4,
                y: (4 * y0 + next(9) - 4) * SUBPIXEL / 4,
                zinv: 1.0,
                varying: Nothing {},
            };
            let tri = [corner(), corner(), corner()];
            let mut got = Vec::new();
            triangle(tri, &view, SMALL_SPAN, &mut |p| got.push((p.x, p.y)));
            got.sort();
            let [a, mut b, mut c] = tri;
            if Edge::new(a.x, a.y, b.x, b.y).at(a.x, a.y, c.x, c.y) < 0 {
                std::mem::swap(&mut b, &mut c);
            }
            let mut want = Vec::new();
            for (j, i) in (0..8).flat_map(|j| (0..8).map(move |i| (j, i))) {
                let (px, py) = (SUBPIXEL * i + SUBPIXEL / 2, SUBPIXEL * j + SUBPIXEL / 2);
                let inside = [(a, b, c), (b, c, a), (c, a, b)].iter().all(|(_, p, q)| {
                    let edge = Edge::new(p.x, p.y, q.x, q.y);
                    edge.at(p.x, p.y, px, py) >= edge.bias
                });
                let area = Edge::new(a.x, a.y, b.x, b.y).at(a.x, a.y, c.x, c.y);
                if inside && area != 0 {
                    want.push((i as i32, j as i32));
                }
            }
            want.sort();
            assert_eq!(got, want, "{tri:?}");
            // The pipeline's question before shading: never yes for a triangle
            // that covers a pixel.
            let places = tri.map(|c| (c.x as i32, c.y as i32));
            let missed = EdgeRaster.misses(places, &view);
            assert!(!missed || got.is_empty(), "{tri:?}");
            // A band's question: never yes for a triangle that covers a pixel
            // in the band's rows.
            for rows in [0..3, 3..5, 5..8, 4..5] {
                let beyond = EdgeRaster.misses_rows(places, &rows);
                let within = got.iter().filter(|(_, y)| rows.contains(y)).count();
                assert!(!beyond || within == 0, "{tri:?} in rows {rows:?}");
                beyond_band += (beyond && !got.is_empty()) as usize;
            }
            drawn += got.len();
            empty += got.is_empty() as usize;
            passed_over += missed as usize;
        }
        // Both kinds are common: triangles that cover centres and ones that
        // cover none, some of which are told apart before any setup.
        assert!(
            drawn > 8_000 && empty > 5_000 && passed_over > 1_000,
            "{drawn} pixels, {empty} empty, {passed_over} passed over"
        );
        // And triangles that do cover pixels, all in other rows, are found so.
        assert!(beyond_band > 10_000, "{beyond_band} beyond a band");
    }

    #[test]
    fn weights_interpolate_linearly_at_centres() {
        let v =
            [(0.0, 0.0, 0.0f32), (8.0, 0.0, 8.0), (0.0, 8.0, 0.0)].map(|(x, y, q)| ScreenVertex {
                x: x - 8.0,
                y: y - 8.0,
                zinv: 1.0,
                varying: q,
            });
        let mut seen = 0;
        EdgeRaster.polygon(&mut (), &v, &viewport(16, 16), |p| {
            // q = x at the centre, x + 0.5.
            assert!((p.varying - (p.x as f32 + 0.5)).abs() < 1e-5, "{p:?}");
            assert!((p.zinv - 1.0).abs() < 1e-6);
            seen += 1;
        });
        // Centres (i + 0.5, j + 0.5) strictly inside: i + j <= 6, 28 of them; the 8
        // centres on the long edge have the inside to their left: not covered.
        assert_eq!(seen, 28);
    }
}
