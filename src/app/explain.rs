//! `rasterlab explain`: pictures of the handout's algorithms on a magnified pixel
//! grid, so what `Interpolate` and `ComputePolygonRows` do can be seen, not only
//! read.
//!
//! - `explain line A B`: the pixels `Interpolate` gives a line (section 3), numbered
//!   in order, over the exact segment.
//! - `explain bresenham A B`: the same line walked by `Interpolate` and by
//!   Bresenham's algorithm (`--lines bresenham`), and how far each strays.
//! - `explain rows A B C ...`: a polygon's exact edges, the pixels `Interpolate` puts
//!   on each edge, each row's start and end, and the filled rows (section 4), with
//!   the printout of `rasterlab rows` beside them.
//! - `explain edge A B C`: the exact rasterizer on a triangle given in fractions of
//!   a pixel: each pixel's centre, the pixels covered, and the centres that lie
//!   exactly on an edge, in or out by the top-left rule.

use crate::measure::plot::{Canvas, Rgb, BLACK, DARK, GREY};
use crate::pipeline::clip::ScreenVertex;
use crate::pipeline::interpolate::{line_pixels, Pixel, Steps};
use crate::pipeline::raster::edge::SUBPIXEL;
use crate::pipeline::raster::rows::walk_line;
use crate::pipeline::raster::rows::{compute_polygon_rows, draw_polygon_rows, Rows};
use crate::pipeline::raster::{Bounds, EdgeRaster, Lines, Rasterizer, RowRaster, Viewport};
use crate::pipeline::Frame;
use crate::pipeline::Nothing;

/// The largest grid `explain` draws, in pixels of the explained image per side.
pub const MAX_EXTENT: i32 = 64;

const WHITE: Rgb = 0x00ff_ffff;
const FILLED: Rgb = 0x00c6_dbef;
const ROW_END: Rgb = 0x0031_82bd;
const EXACT: Rgb = 0x00d9_5f02;
/// One colour per edge, for the pixels `Interpolate` puts on it.
const EDGE_COLORS: [Rgb; 5] = [
    0x001b_9e77,
    0x0075_70b3,
    0x00e7_298a,
    0x0066_a61e,
    0x00e6_ab02,
];

/// The grid around a set of pixels: which pixels it shows and how big a cell is.
struct Grid {
    min: (i32, i32),
    cells: (i32, i32),
    cell: i32,
    origin: (i32, i32),
}

impl Grid {
    fn around(points: &[(i32, i32)]) -> Result<Grid, String> {
        let xs = points.iter().map(|p| p.0);
        let ys = points.iter().map(|p| p.1);
        let (x0, x1) = (xs.clone().min().unwrap_or(0), xs.max().unwrap_or(0));
        let (y0, y1) = (ys.clone().min().unwrap_or(0), ys.max().unwrap_or(0));
        let cells = (x1 - x0 + 3, y1 - y0 + 3); // a free cell on each side
        if cells.0 > MAX_EXTENT + 2 || cells.1 > MAX_EXTENT + 2 {
            return Err(format!(
                "the points span {} x {} pixels; explain draws at most {MAX_EXTENT} x {MAX_EXTENT}",
                x1 - x0 + 1,
                y1 - y0 + 1
            ));
        }
        let cell = (640 / cells.0.max(cells.1)).clamp(10, 48);
        Ok(Grid {
            min: (x0 - 1, y0 - 1),
            cells,
            cell,
            origin: (56, 56),
        })
    }

    fn size(&self) -> (i32, i32) {
        (self.cells.0 * self.cell, self.cells.1 * self.cell)
    }

    /// The top-left corner of pixel (x, y)'s cell.
    fn corner(&self, x: i32, y: i32) -> (i32, i32) {
        (
            self.origin.0 + (x - self.min.0) * self.cell,
            self.origin.1 + (y - self.min.1) * self.cell,
        )
    }

    /// The centre of pixel (x, y)'s cell.
    fn centre(&self, x: i32, y: i32) -> (i32, i32) {
        let (cx, cy) = self.corner(x, y);
        (cx + self.cell / 2, cy + self.cell / 2)
    }

    fn fill(&self, c: &mut Canvas, x: i32, y: i32, color: Rgb) {
        let (cx, cy) = self.corner(x, y);
        c.rect((cx + 1, cy + 1), (self.cell - 1, self.cell - 1), color);
    }

    /// A dot in the middle of pixel (x, y)'s cell.
    fn dot(&self, c: &mut Canvas, x: i32, y: i32, color: Rgb) {
        let (cx, cy) = self.centre(x, y);
        let r = (self.cell / 5).max(2);
        c.rect((cx - r, cy - r), (2 * r + 1, 2 * r + 1), color);
    }

    /// Cell borders, and every fifth coordinate along the top and left.
    fn draw_lines(&self, c: &mut Canvas) {
        let (w, h) = self.size();
        let (ox, oy) = self.origin;
        for i in 0..=self.cells.0 {
            let x = ox + i * self.cell;
            c.line((x, oy), (x, oy + h), GREY, 1);
        }
        for j in 0..=self.cells.1 {
            let y = oy + j * self.cell;
            c.line((ox, y), (ox + w, y), GREY, 1);
        }
        for i in 0..self.cells.0 {
            let x = self.min.0 + i;
            if x % 5 == 0 {
                let (cx, _) = self.centre(x, 0);
                let s = x.to_string();
                c.text((cx - Canvas::text_width(&s, 1) / 2, oy - 14), &s, 1, DARK);
            }
        }
        for j in 0..self.cells.1 {
            let y = self.min.1 + j;
            if y % 5 == 0 {
                let (_, cy) = self.centre(0, y);
                let s = y.to_string();
                c.text((ox - 8 - Canvas::text_width(&s, 1), cy - 4), &s, 1, DARK);
            }
        }
    }
}

/// A canvas holding the grid and, on its right, `text` (one line per row).
fn canvas_for(grid: &Grid, title: &str, text: &[String]) -> Canvas {
    let (w, h) = grid.size();
    let text_w = text
        .iter()
        .map(|l| Canvas::text_width(l, 1))
        .max()
        .unwrap_or(0);
    let width = grid.origin.0 + w + 40 + text_w + 24;
    let height = (grid.origin.1 + h + 24).max(grid.origin.1 + 12 * text.len() as i32 + 24);
    let mut c = Canvas::new(width as u32, height as u32, WHITE);
    c.text((grid.origin.0, 12), title, 2, BLACK);
    for (i, line) in text.iter().enumerate() {
        c.text(
            (grid.origin.0 + w + 40, grid.origin.1 + 12 * i as i32),
            line,
            1,
            BLACK,
        );
    }
    c
}

/// `explain line A B`: `Interpolate`'s `max(|dx|, |dy|) + 1` pixels from `a` to
/// `b`, numbered, over the exact segment between the two pixels' centres.
pub fn explain_line(a: (i32, i32), b: (i32, i32)) -> Result<Frame, String> {
    let (pa, pb) = (Pixel::at(a.0, a.1), Pixel::at(b.0, b.1));
    let n = line_pixels(&pa, &pb);
    let pixels: Vec<(i32, i32)> = Steps::new(pa, pb, n).map(|p| (p.x, p.y)).collect();
    let grid = Grid::around(&[a, b])?;
    let mut text = vec![format!(
        "Interpolate({},{} -> {},{}), {n} pixels:",
        a.0, a.1, b.0, b.1
    )];
    text.extend(
        pixels
            .iter()
            .enumerate()
            .map(|(i, p)| format!("{i}: ({},{})", p.0, p.1)),
    );
    text.extend(
        [
            "",
            "cells: the pixels, numbered in order",
            "line: the exact segment, centre to centre",
        ]
        .map(String::from),
    );
    let mut c = canvas_for(&grid, "Interpolate: the pixels of a line", &text);
    for &(x, y) in &pixels {
        grid.fill(&mut c, x, y, FILLED);
    }
    grid.draw_lines(&mut c);
    c.line(grid.centre(a.0, a.1), grid.centre(b.0, b.1), EXACT, 2);
    for (i, &(x, y)) in pixels.iter().enumerate() {
        let (cx, cy) = grid.corner(x, y);
        if grid.cell >= 16 {
            c.text((cx + 3, cy + 3), &i.to_string(), 1, BLACK);
        }
    }
    Ok(c.frame)
}

/// How far a line's pixels stray from the exact segment between the centres of
/// its end pixels, measured across the line (along its minor axis): the largest
/// and the mean, in pixels.
pub fn line_offsets(a: (i32, i32), b: (i32, i32), pixels: &[(i32, i32)]) -> (f64, f64) {
    let (dx, dy) = ((b.0 - a.0) as f64, (b.1 - a.1) as f64);
    let offset = |&(x, y): &(i32, i32)| {
        let (u, v) = ((x - a.0) as f64, (y - a.1) as f64);
        match (dx.abs() >= dy.abs(), dx == 0.0) {
            (_, true) if dy == 0.0 => u.hypot(v),
            (true, _) => (v - u * dy / dx).abs(),
            (false, _) => (u - v * dx / dy).abs(),
        }
    };
    let max = pixels.iter().map(offset).fold(0.0, f64::max);
    let mean = pixels.iter().map(offset).sum::<f64>() / pixels.len().max(1) as f64;
    (max, mean)
}

/// The pixels of a line from `a` to `b`, walked the way `lines` says.
fn walked(lines: Lines, a: (i32, i32), b: (i32, i32)) -> Vec<(i32, i32)> {
    let mut pixels = Vec::new();
    walk_line(lines, Pixel::at(a.0, a.1), Pixel::at(b.0, b.1), |p| {
        pixels.push((p.x, p.y))
    });
    pixels
}

/// Interpolate against Bresenham over every line from (0, 0) to a point with
/// |dx|, |dy| <= `reach`: the share of pixels where they differ, and for each the
/// largest and the mean offset from the exact line.
pub fn compare_line_walks(reach: i32) -> LineComparison {
    let (mut pixels, mut differing) = (0usize, 0usize);
    let (mut max, mut sum) = ([0.0f64; 2], [0.0f64; 2]);
    for dx in -reach..=reach {
        for dy in -reach..=reach {
            let b = (dx, dy);
            let walks = [Lines::Interpolate, Lines::Bresenham].map(|l| walked(l, (0, 0), b));
            differing += walks[0]
                .iter()
                .zip(&walks[1])
                .filter(|(p, q)| p != q)
                .count();
            pixels += walks[0].len();
            for (k, walk) in walks.iter().enumerate() {
                let (m, mean) = line_offsets((0, 0), b, walk);
                max[k] = max[k].max(m);
                sum[k] += mean * walk.len() as f64;
            }
        }
    }
    LineComparison {
        pixels,
        differing,
        max_offset: max,
        mean_offset: sum.map(|s| s / pixels as f64),
    }
}

/// What [`compare_line_walks`] found; `[Interpolate, Bresenham]` in the arrays.
#[derive(Clone, Copy, Debug)]
pub struct LineComparison {
    pub pixels: usize,
    pub differing: usize,
    pub max_offset: [f64; 2],
    pub mean_offset: [f64; 2],
}

/// `explain bresenham A B`: the pixels `Interpolate` gives a line (light cells)
/// and those of Bresenham's algorithm (dots), over the exact segment, with both
/// lists and how far each strays from the line; below, the same comparison over
/// every line of up to 16 pixels each way.
pub fn explain_bresenham(a: (i32, i32), b: (i32, i32)) -> Result<Frame, String> {
    let grid = Grid::around(&[a, b])?;
    let by_interpolate = walked(Lines::Interpolate, a, b);
    let by_bresenham = walked(Lines::Bresenham, a, b);
    let differ = by_interpolate
        .iter()
        .zip(&by_bresenham)
        .filter(|(p, q)| p != q)
        .count();
    let mut text = vec![
        format!(
            "({},{}) -> ({},{}), {} pixels:",
            a.0,
            a.1,
            b.0,
            b.1,
            by_interpolate.len()
        ),
        "   Interpolate  Bresenham".to_string(),
    ];
    text.extend(
        by_interpolate
            .iter()
            .zip(&by_bresenham)
            .enumerate()
            .map(|(i, (p, q))| {
                let mark = if p == q { "" } else { "  *" };
                format!("{i:>2}: ({},{})  ({},{}){mark}", p.0, p.1, q.0, q.1)
            }),
    );
    let (oi, ob) = (
        line_offsets(a, b, &by_interpolate),
        line_offsets(a, b, &by_bresenham),
    );
    let all = compare_line_walks(16);
    text.extend([
        String::new(),
        format!("{differ} of {} pixels differ (*)", by_interpolate.len()),
        "off the exact line, largest / mean:".to_string(),
        format!("  Interpolate {:.2} / {:.2} px", oi.0, oi.1),
        format!("  Bresenham   {:.2} / {:.2} px", ob.0, ob.1),
        String::new(),
        "every line from 0,0 to |dx|, |dy| <= 16:".to_string(),
        format!(
            "  {:.1} % of {} pixels differ",
            100.0 * all.differing as f64 / all.pixels as f64,
            all.pixels
        ),
        format!(
            "  Interpolate {:.2} / {:.2} px",
            all.max_offset[0], all.mean_offset[0]
        ),
        format!(
            "  Bresenham   {:.2} / {:.2} px",
            all.max_offset[1], all.mean_offset[1]
        ),
        String::new(),
        "cells: Interpolate's pixels".to_string(),
        "dots: Bresenham's pixels".to_string(),
        "line: the exact segment, centre to centre".to_string(),
    ]);
    let mut c = canvas_for(&grid, "Interpolate and Bresenham", &text);
    for &(x, y) in &by_interpolate {
        grid.fill(&mut c, x, y, FILLED);
    }
    grid.draw_lines(&mut c);
    c.line(grid.centre(a.0, a.1), grid.centre(b.0, b.1), EXACT, 2);
    for &(x, y) in &by_bresenham {
        grid.dot(&mut c, x, y, EDGE_COLORS[1]);
    }
    Ok(c.frame)
}

/// `explain rows A B C ...`: the polygon's exact edges, the pixels `Interpolate`
/// puts on each edge (a dot in the edge's colour), each row's start and end (dark
/// cells) and the filled rows (light cells), with `rows_text` beside them.
pub fn explain_rows(vertices: &[(i32, i32)]) -> Result<Frame, String> {
    let grid = Grid::around(vertices)?;
    let pixels: Vec<Pixel<_>> = vertices.iter().map(|&(x, y)| Pixel::at(x, y)).collect();
    let mut rows = Rows::new();
    compute_polygon_rows(&pixels, &Bounds::unbounded(), &mut rows);
    let mut text = vec![format!("ComputePolygonRows, {} rows:", rows.len())];
    text.extend(super::rows_text(vertices).lines().map(String::from));
    text.extend(
        [
            "",
            "light cells: the rows DrawPolygonRows fills",
            "dark cells: each row's start and end",
            "dots: the pixels Interpolate gives each edge",
            "(one colour per edge, vertex i to i + 1)",
            "line: the exact edge, centre to centre",
        ]
        .map(String::from),
    );
    let mut c = canvas_for(&grid, "ComputePolygonRows and DrawPolygonRows", &text);
    draw_polygon_rows(&rows, &Bounds::unbounded(), |p| {
        grid.fill(&mut c, p.x, p.y, FILLED)
    });
    for (l, r) in rows.left.iter().zip(&rows.right) {
        if l.x <= r.x {
            grid.fill(&mut c, l.x, l.y, ROW_END);
            grid.fill(&mut c, r.x, r.y, ROW_END);
        }
    }
    grid.draw_lines(&mut c);
    let n = vertices.len();
    for i in 0..n {
        let (a, b) = (vertices[i], vertices[(i + 1) % n]);
        c.line(grid.centre(a.0, a.1), grid.centre(b.0, b.1), EXACT, 2);
    }
    for i in 0..n {
        let (a, b) = (pixels[i], pixels[(i + 1) % n]);
        let color = EDGE_COLORS[i % EDGE_COLORS.len()];
        for p in Steps::new(a, b, line_pixels(&a, &b)) {
            grid.dot(&mut c, p.x, p.y, color);
        }
    }
    Ok(c.frame)
}

/// The grid around points given in image pixels, fractions allowed, with a
/// viewport that puts image position (x, y) at (x, y): what `explain edge` and
/// `explain shared` rasterize into.
fn fractional_grid(corners: &[(f32, f32)]) -> Result<(Grid, Viewport), String> {
    let cells: Vec<(i32, i32)> = corners
        .iter()
        .map(|&(x, y)| (x.floor() as i32, y.floor() as i32))
        .collect();
    let grid = Grid::around(&cells)?;
    let (ox, oy) = grid.min;
    let viewport = Viewport {
        half_width: 0,
        half_height: 0,
        centre: (0.0, 0.0),
        bounds: Bounds {
            x: ox..ox + grid.cells.0,
            y: oy..oy + grid.cells.1,
        },
        lines: Lines::Interpolate,
    };
    Ok((grid, viewport))
}

/// A corner at image position (x, y) as the rasterizers take it.
fn screen_vertex((x, y): (f32, f32)) -> ScreenVertex<Nothing> {
    ScreenVertex {
        x,
        y,
        zinv: 1.0,
        varying: Nothing {},
    }
}

impl Grid {
    /// Where image position (x, y), fractions allowed, falls on the canvas.
    fn exact(&self, (x, y): (f32, f32)) -> (i32, i32) {
        let (cx, cy) = self.corner(self.min.0, self.min.1);
        (
            cx + ((x - self.min.0 as f32) * self.cell as f32).round() as i32,
            cy + ((y - self.min.1 as f32) * self.cell as f32).round() as i32,
        )
    }
}

/// `explain edge A B C`: the exact rasterizer (`--raster edge`) on one triangle
/// whose corners are image positions in pixels (fractions allowed): the pixels it
/// covers (light), every pixel centre (small dots), and the centres exactly on an
/// edge, taken by the top-left rule (green) or left to the neighbour (red).
pub fn explain_edge(corners: &[(f32, f32); 3]) -> Result<Frame, String> {
    let (grid, viewport) = fractional_grid(corners)?;
    let (ox, oy) = grid.min;
    let vertices = corners.map(screen_vertex);
    let mut covered = Vec::new();
    EdgeRaster.polygon(&mut (), &vertices, &viewport, |p| covered.push((p.x, p.y)));
    // Centres exactly on an edge, in the same fixed point the rasterizer uses.
    let snap = |(x, y): (f32, f32)| {
        (
            (x * SUBPIXEL as f32).round() as i64,
            (y * SUBPIXEL as f32).round() as i64,
        )
    };
    let s = corners.map(snap);
    let on_edge = |px: i64, py: i64| {
        (0..3).any(|k| {
            let (a, b) = (s[k], s[(k + 1) % 3]);
            let cross = (b.0 - a.0) * (py - a.1) - (b.1 - a.1) * (px - a.0);
            let within = px >= a.0.min(b.0)
                && px <= a.0.max(b.0)
                && py >= a.1.min(b.1)
                && py <= a.1.max(b.1);
            cross == 0 && within
        })
    };
    let mut text = vec![format!("{} pixels covered", covered.len())];
    text.extend(
        corners
            .iter()
            .zip(&s)
            .map(|(c, f)| format!("({}, {}) snaps to ({}, {})/256", c.0, c.1, f.0, f.1)),
    );
    text.extend(
        [
            "",
            "light cells: covered (centre inside)",
            "dots: pixel centres",
            "green: centre on an edge, taken",
            "red: centre on an edge, left out",
            "(the top-left rule: taken when the inside",
            "is to its right, or below a flat edge)",
        ]
        .map(String::from),
    );
    let mut c = canvas_for(
        &grid,
        "The edge rasterizer: centres and the top-left rule",
        &text,
    );
    for &(x, y) in &covered {
        grid.fill(&mut c, x, y, FILLED);
    }
    grid.draw_lines(&mut c);
    let at = |p| grid.exact(p);
    for k in 0..3 {
        c.line(at(corners[k]), at(corners[(k + 1) % 3]), EXACT, 2);
    }
    for j in 0..grid.cells.1 {
        for i in 0..grid.cells.0 {
            let (x, y) = (ox + i, oy + j);
            let (px, py) = (
                SUBPIXEL * x as i64 + SUBPIXEL / 2,
                SUBPIXEL * y as i64 + SUBPIXEL / 2,
            );
            let color = match (on_edge(px, py), covered.contains(&(x, y))) {
                (true, true) => EDGE_COLORS[0],
                (true, false) => EDGE_COLORS[2],
                (false, _) => DARK,
            };
            let (cx, cy) = grid.centre(x, y);
            let r = if color == DARK {
                1
            } else {
                (grid.cell / 6).max(2)
            };
            c.rect((cx - r, cy - r), (2 * r + 1, 2 * r + 1), color);
        }
    }
    Ok(c.frame)
}

/// Two triangles sharing an edge, `(a, b, c)` and `(a, c, d)`, as each rasterizer
/// covers them: the handout's rows (left) draw the pixels along the shared edge
/// twice and place corners by truncation; the edge rasterizer (right) gives every
/// pixel to exactly one triangle. Light: one triangle; darker: the other; red:
/// both.
pub fn explain_shared(corners: &[(f32, f32); 4]) -> Result<Frame, String> {
    let (grid, viewport) = fractional_grid(corners)?;
    let (ox, oy) = grid.min;
    let [a, b, c, d] = corners.map(screen_vertex);
    let index = |x: i32, y: i32| ((y - oy) * grid.cells.0 + (x - ox)) as usize;
    let cover = |edge: bool| {
        let mut hits = vec![[0u8; 2]; (grid.cells.0 * grid.cells.1) as usize];
        for (k, tri) in [[a, b, c], [a, c, d]].iter().enumerate() {
            let mut plot = |p: Pixel<_>| hits[index(p.x, p.y)][k] += 1;
            if edge {
                EdgeRaster.polygon(&mut (), tri, &viewport, &mut plot);
            } else {
                RowRaster.polygon(&mut Rows::new(), tri, &viewport, &mut plot);
            }
        }
        hits
    };
    let panel = |edge: bool| {
        let hits = cover(edge);
        let twice = hits.iter().filter(|h| h[0] > 0 && h[1] > 0).count();
        let name = if edge {
            "edge rasterizer"
        } else {
            "the handout's rows"
        };
        let text = vec![
            format!("{name}:"),
            format!("{} pixels drawn twice", twice),
            "light, dark: one triangle each".into(),
            "red: drawn by both".into(),
        ];
        let mut c = canvas_for(&grid, name, &text);
        for y in oy..oy + grid.cells.1 {
            for x in ox..ox + grid.cells.0 {
                let h = hits[index(x, y)];
                let color = match (h[0] > 0, h[1] > 0) {
                    (true, true) => 0x00e3_1a1c,
                    (true, false) => FILLED,
                    (false, true) => ROW_END,
                    (false, false) => continue,
                };
                grid.fill(&mut c, x, y, color);
            }
        }
        grid.draw_lines(&mut c);
        let at = |p| grid.exact(p);
        for (p, q) in [(0, 1), (1, 2), (2, 3), (3, 0), (0, 2)] {
            c.line(at(corners[p]), at(corners[q]), EXACT, 2);
        }
        c.frame
    };
    let panels = [false, true].map(|edge| super::overview::Panel {
        frame: panel(edge),
        label: String::new(),
    });
    super::overview::grid(&panels)
}

/// How many pixels of `mesh` two triangles of one flat surface (same normal and
/// colour, as a wall's two halves) both draw: the rows rasterizer's double
/// drawing along shared edges, which the edge rasterizer's top-left rule removes.
pub fn pixels_drawn_twice(
    mesh: &crate::pipeline::Mesh,
    settings: &super::Settings,
    raster: crate::app::figure::Raster,
) -> usize {
    use crate::app::figure::Figure;
    use crate::pipeline::StageName;
    use std::collections::HashMap;
    let mut surfaces: HashMap<usize, Vec<usize>> = HashMap::new();
    for (face, surface) in crate::measure::metrics::surfaces(mesh)
        .into_iter()
        .enumerate()
    {
        surfaces.entry(surface).or_default().push(face);
    }
    let figure = Figure::of(StageName::Filled).with_raster(raster);
    // One copy of the mesh, drawn one face at a time.
    let mut one = crate::pipeline::Mesh {
        faces: Vec::with_capacity(1),
        ..mesh.clone()
    };
    let mut twice = 0;
    for faces in surfaces.values() {
        let mut hits = vec![0u8; (settings.camera.width * settings.camera.height) as usize];
        for &f in faces {
            one.faces.clear();
            one.faces.push(mesh.faces[f]);
            let frame = super::render(figure, &one, settings, None).0;
            for (h, &c) in hits.iter_mut().zip(&frame.color) {
                *h += (c != 0) as u8;
            }
        }
        twice += hits.iter().filter(|&&h| h >= 2).count();
    }
    twice
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_handouts_line_is_four_numbered_pixels() {
        let f = explain_line((4, 2), (1, 8)).unwrap();
        // Grid from (0, 1) to (5, 9), 9 cells high: 640 / 9 = 71, clamped to 48.
        let grid = Grid::around(&[(4, 2), (1, 8)]).unwrap();
        assert_eq!(grid.cell, 48);
        let filled = |x: i32, y: i32| {
            let (cx, cy) = grid.corner(x, y);
            f.color[((cy + 40) as u32 * f.width + (cx + 40) as u32) as usize] == FILLED
        };
        for (x, y) in [(4, 2), (3, 4), (2, 6), (1, 8)] {
            assert!(filled(x, y), "({x}, {y})");
        }
        assert!(!filled(4, 3) && !filled(1, 7));
    }

    #[test]
    fn rows_mark_every_row_end_and_refuse_huge_polygons() {
        let f = explain_rows(&[(10, 5), (5, 10), (15, 15)]).unwrap();
        let grid = Grid::around(&[(10, 5), (5, 10), (15, 15)]).unwrap();
        let at = |x: i32, y: i32| {
            let (cx, cy) = grid.corner(x, y);
            f.color[((cy + 2) as u32 * f.width + (cx + 2) as u32) as usize]
        };
        // The handout's first rows: (10,5)-(10,5), (9,6)-(10,6); the last (15,15).
        assert_eq!(at(10, 5), ROW_END);
        assert_eq!(at(9, 6), ROW_END);
        assert_eq!(at(10, 6), ROW_END);
        assert_eq!(at(11, 6), WHITE);
        assert_eq!(at(15, 15), ROW_END);
        assert_eq!(at(4, 10), WHITE, "outside the polygon");
        assert!(explain_rows(&[(0, 0), (100, 0), (0, 5)]).is_err());
    }

    #[test]
    fn edge_marks_centres_on_edges() {
        // A right triangle whose legs run through pixel centres (x = 0.5, y = 0.5):
        // the centres on the left leg are taken, those on the hypotenuse are not.
        let f = explain_edge(&[(0.5, 0.5), (6.5, 0.5), (0.5, 6.5)]).unwrap();
        let grid = Grid::around(&[(0, 0), (6, 0), (0, 6)]).unwrap();
        let centre = |x: i32, y: i32| {
            let (cx, cy) = grid.centre(x, y);
            f.color[(cy as u32 * f.width + cx as u32) as usize]
        };
        assert_eq!(centre(0, 3), EDGE_COLORS[0], "left leg: taken");
        assert_eq!(centre(3, 3), EDGE_COLORS[2], "hypotenuse: left out");
    }
}

#[cfg(test)]
mod bresenham_tests {
    use super::*;

    #[test]
    fn bresenham_stays_within_half_a_pixel_and_interpolate_does_not() {
        let all = compare_line_walks(16);
        // Every line gets max(|dx|, |dy|) + 1 pixels either way.
        let expected: usize = (-16i32..=16)
            .flat_map(|dx| (-16i32..=16).map(move |dy| dx.abs().max(dy.abs()) as usize + 1))
            .sum();
        assert_eq!(all.pixels, expected);
        assert_eq!(all.max_offset[1], 0.5, "Bresenham: the nearest pixel");
        // Truncation moves a pixel by up to one; the running sum's drift can
        // push a value that should be whole just below it.
        assert!(
            all.max_offset[0] > 0.9 && all.max_offset[0] <= 1.0 + 1e-9,
            "{all:?}"
        );
        assert!(all.mean_offset[1] < all.mean_offset[0], "{all:?}");
        assert!(
            all.differing > all.pixels / 4 && all.differing < all.pixels / 2,
            "{all:?}"
        );
    }
}
