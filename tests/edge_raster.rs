//! The exact rasterizer tested as conformance suites test GPUs: triangles that tile
//! the screen must cover every pixel exactly once (the top-left rule), and depth
//! drawn with it must agree with a ray cast through each pixel's centre.

use rasterlab::measure::raytrace::{raytrace, Options, Shading};
use rasterlab::pipeline::clip::ScreenVertex;
use rasterlab::pipeline::raster::{Bounds, EdgeRaster, Rasterizer, Viewport};
use rasterlab::pipeline::Nothing;

const W: i32 = 64;
const H: i32 = 48;

/// A small deterministic generator (xorshift), so failures reproduce.
struct Random(u64);

impl Random {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

fn viewport() -> Viewport {
    Viewport {
        half_width: W / 2,
        half_height: H / 2,
        centre: (W as f32 / 2.0, H as f32 / 2.0),
        bounds: Bounds { x: 0..W, y: 0..H },
        lines: Default::default(),
    }
}

/// Rasterizes each triangle (corners in image pixels) and counts hits per pixel.
fn hits(triangles: &[[(f32, f32); 3]], random: &mut Random) -> Vec<u32> {
    let mut count = vec![0u32; (W * H) as usize];
    for t in triangles {
        // Either winding.
        let mut t = *t;
        if random.next() < 0.5 {
            t.swap(1, 2);
        }
        let corners = t.map(|(x, y)| ScreenVertex {
            x: x - W as f32 / 2.0,
            y: y - H as f32 / 2.0,
            zinv: 1.0,
            varying: Nothing {},
        });
        EdgeRaster.polygon(&mut (), &corners, &viewport(), |p| {
            count[(p.y * W + p.x) as usize] += 1;
        });
    }
    count
}

fn assert_once(name: &str, triangles: &[[(f32, f32); 3]], random: &mut Random) -> usize {
    let count = hits(triangles, random);
    let wrong: Vec<(i32, i32, u32)> = (0..W * H)
        .filter(|&i| count[i as usize] != 1)
        .map(|i| (i % W, i / W, count[i as usize]))
        .collect();
    assert!(
        wrong.is_empty(),
        "{name}: pixels not hit exactly once (x, y, hits): {:?}",
        &wrong[..wrong.len().min(10)]
    );
    triangles.len()
}

/// A grid of points over the whole screen, interior points jittered (or snapped
/// onto pixel centres and edges, the hardest case), each cell split along a random
/// diagonal. The jitter stays small enough that every cell stays convex, so the
/// triangles tile the screen without overlapping.
fn jittered_grid(
    cells: (usize, usize),
    jitter: f32,
    centres: bool,
    r: &mut Random,
) -> Vec<[(f32, f32); 3]> {
    let (nx, ny) = cells;
    let point = |i: usize, j: usize, r: &mut Random| {
        let x = i as f32 * W as f32 / nx as f32;
        let y = j as f32 * H as f32 / ny as f32;
        let inner = |k: usize, n: usize| k > 0 && k < n;
        let (mut x, mut y) = (x, y);
        if inner(i, nx) {
            x += (r.next() - 0.5) * jitter;
        }
        if inner(j, ny) {
            y += (r.next() - 0.5) * jitter;
        }
        if centres {
            // Onto a pixel centre or a pixel edge: (k + 0.5) or k.
            let snap = |v: f32| (v * 2.0).round() / 2.0;
            if inner(i, nx) {
                x = snap(x);
            }
            if inner(j, ny) {
                y = snap(y);
            }
        }
        (x, y)
    };
    let mut grid = vec![vec![(0.0, 0.0); ny + 1]; nx + 1];
    for (i, column) in grid.iter_mut().enumerate() {
        for (j, p) in column.iter_mut().enumerate() {
            *p = point(i, j, r);
        }
    }
    let mut out = Vec::new();
    for i in 0..nx {
        for j in 0..ny {
            let (a, b, c, d) = (
                grid[i][j],
                grid[i + 1][j],
                grid[i + 1][j + 1],
                grid[i][j + 1],
            );
            if r.next() < 0.5 {
                out.push([a, b, c]);
                out.push([a, c, d]);
            } else {
                out.push([a, b, d]);
                out.push([b, c, d]);
            }
        }
    }
    out
}

/// A fan around an inner point to points along the screen's border: long slivers
/// when the border is finely divided.
fn fan(centre: (f32, f32), per_side: usize) -> Vec<[(f32, f32); 3]> {
    let (w, h) = (W as f32, H as f32);
    let mut border = Vec::new();
    for k in 0..per_side {
        let t = k as f32 / per_side as f32;
        border.push((t * w, 0.0));
    }
    for k in 0..per_side {
        let t = k as f32 / per_side as f32;
        border.push((w, t * h));
    }
    for k in 0..per_side {
        let t = k as f32 / per_side as f32;
        border.push((w - t * w, h));
    }
    for k in 0..per_side {
        let t = k as f32 / per_side as f32;
        border.push((0.0, h - t * h));
    }
    (0..border.len())
        .map(|k| [centre, border[k], border[(k + 1) % border.len()]])
        .collect()
}

#[test]
fn tilings_cover_every_pixel_exactly_once() {
    let mut r = Random(0x2545_f491_4f6c_dd1d);
    let mut total = 0;
    for round in 0..4 {
        total += assert_once(
            "grid 24x16",
            &jittered_grid((24, 16), 1.3, false, &mut r),
            &mut r,
        );
        total += assert_once(
            "grid 32x24 on centres",
            &jittered_grid((32, 24), 0.6, true, &mut r),
            &mut r,
        );
        total += assert_once(
            "grid 40x30 fine",
            &jittered_grid((40, 30), 0.8, false, &mut r),
            &mut r,
        );
        let c = (W as f32 * r.next(), H as f32 * r.next());
        total += assert_once("fan", &fan(c, 16 + round), &mut r);
        // Slivers: hundreds of triangles a fraction of a pixel wide.
        total += assert_once("slivers", &fan((32.5, 24.5), 150), &mut r);
    }
    assert!(total >= 10_000, "{total} triangles");
}

#[test]
fn edge_depth_agrees_with_a_ray_cast_through_pixel_centres() {
    // depth --raster edge against the ray tracer's flat image, which samples the
    // same pixel centres. They may differ only where a centre is within the
    // snapping distance (1/256 pixel, so 1/128 to be safe) of a projected edge, or
    // where two surfaces meet at one depth and the two break the tie differently.
    let s = rasterlab::app::Settings::default();
    let (camera, light) = (s.camera, s.light);
    let mesh = rasterlab::cornell_box();
    let edge = rasterlab::Figure::of(rasterlab::StageName::Depth)
        .with_raster(rasterlab::app::figure::Raster::Edge)
        .render(&mesh, &camera, light);
    let options = Options {
        shading: Shading::Flat,
        ..Options::default()
    };
    let reference = raytrace(&mesh, &camera, &light, &options).frame;
    // Distance in pixels from a centre to the nearest projected edge.
    let p = camera.projection();
    let edges: Vec<((f32, f32), (f32, f32))> = mesh
        .triangles()
        .flat_map(|t| {
            let v = t.vertices().map(|v| {
                let (x, y, _) = p.project_centred(p.to_camera(v)).unwrap();
                (x + 250.0, y + 250.0)
            });
            [(v[0], v[1]), (v[1], v[2]), (v[2], v[0])]
        })
        .collect();
    let distance = |(px, py): (f32, f32)| {
        edges
            .iter()
            .map(|&((ax, ay), (bx, by))| {
                let (dx, dy) = (bx - ax, by - ay);
                let t = (((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
                ((px - ax - t * dx).powi(2) + (py - ay - t * dy).powi(2)).sqrt()
            })
            .fold(f32::INFINITY, f32::min)
    };
    let (mut near_edge, mut elsewhere) = (0, Vec::new());
    for y in 0..500u32 {
        for x in 0..500u32 {
            if edge.rgb(x, y) != reference.rgb(x, y) {
                if distance((x as f32 + 0.5, y as f32 + 0.5)) <= 1.0 / 128.0 {
                    near_edge += 1;
                } else {
                    elsewhere.push((x, y));
                }
            }
        }
    }
    // Measured: no pixel differs away from an edge, 238 within snapping distance
    // of one (seams where two faces meet at one depth among them); the bound
    // leaves room for rounding, not for a different rule.
    assert!(
        elsewhere.is_empty(),
        "{} pixels differ away from edges: {:?}",
        elsewhere.len(),
        &elsewhere[..elsewhere.len().min(10)]
    );
    assert!(
        near_edge <= 300,
        "{near_edge} pixels differ within snapping distance of an edge"
    );
}
