//! Handout section 6.2 (Figures 7 and 8): light computed at each pixel.
//!
//! Step 6's program with the 3D position in `Pixel` instead of the light, and
//! eq. 10 and 11 moved from `VertexShader` to `PixelShader`, with the triangle's
//! normal and reflectance. Interpolated as position/z and multiplied by z at the
//! pixel it is perspective-correct (Figure 7); as the position itself, affine
//! (Figure 8).
//! `cargo run --release --example 7-pixel-light [OUT.png]` writes
//! fig7-pixel-light.png; `draw(false)` in `main` draws Figure 8.

use glam::{IVec2, Vec3};
use std::f32::consts::PI;

const SCREEN_WIDTH: i32 = 500;
const SCREEN_HEIGHT: i32 = 500;
const FOCAL_LENGTH: f32 = 500.0;
const CAMERA_POS: Vec3 = Vec3::new(0.0, 0.0, -3.001);
/// Turn about the y-axis, in radians (the `Update` loop would change it).
const YAW: f32 = 0.0;
const LIGHT_POS: Vec3 = Vec3::new(0.0, -0.5, -0.7);
const LIGHT_POWER: Vec3 = Vec3::new(1.1, 1.1, 1.1);
const INDIRECT_LIGHT_POWER_PER_AREA: Vec3 = Vec3::new(0.5, 0.5, 0.5);

/// The handout's `Triangle`.
pub struct Triangle {
    pub v0: Vec3,
    pub v1: Vec3,
    pub v2: Vec3,
    pub normal: Vec3,
    pub color: Vec3,
}

/// The handout's `LoadTestModel`: the Cornell box.
pub fn load_test_model() -> Vec<Triangle> {
    rasterlab::cornell_box()
        .triangles()
        .map(|t| Triangle {
            v0: t.v0,
            v1: t.v1,
            v2: t.v2,
            normal: t.normal,
            color: t.color,
        })
        .collect()
}

/// The window's pixels, as linear colours, row after row, and the depth buffer:
/// 1/z of what each pixel shows, 0 (infinitely far) where it shows nothing.
pub struct Screen {
    pub pixels: Vec<Vec3>,
    pub depth_buffer: Vec<f32>,
}

/// The handout's `Pixel`: a position, its inverse depth and the 3D point shown
/// there (divided by z when perspective-correct).
#[derive(Clone, Copy, Default)]
struct Pixel {
    x: i32,
    y: i32,
    zinv: f32,
    pos3d: Vec3,
}

/// The handout's `Vertex`: a position.
#[derive(Clone, Copy)]
struct Vertex {
    position: Vec3,
}

impl Screen {
    fn new() -> Screen {
        Screen {
            pixels: vec![Vec3::ZERO; (SCREEN_WIDTH * SCREEN_HEIGHT) as usize],
            depth_buffer: vec![0.0; (SCREEN_WIDTH * SCREEN_HEIGHT) as usize],
        }
    }

    /// `PutPixelSDL`; a pixel off the screen is skipped.
    fn put_pixel(&mut self, x: i32, y: i32, color: Vec3) {
        if (0..SCREEN_WIDTH).contains(&x) && (0..SCREEN_HEIGHT).contains(&y) {
            self.pixels[(y * SCREEN_WIDTH + x) as usize] = color;
        }
    }

    /// 8-bit RGB: each channel clamped to [0, 1] and rounded.
    pub fn to_rgb8(&self) -> Vec<u8> {
        let to_u8 = |c: f32| (c.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
        self.pixels
            .iter()
            .flat_map(|c| [to_u8(c.x), to_u8(c.y), to_u8(c.z)])
            .collect()
    }
}

/// The triangle being drawn, as the pixel shader sees it: the handout's
/// `currentNormal` and `currentReflectance`.
#[derive(Clone, Copy)]
struct Surface {
    normal: Vec3,
    reflectance: Vec3,
}

pub fn draw(perspective_correct: bool) -> Screen {
    let triangles = load_test_model();
    let mut screen = Screen::new();
    for triangle in &triangles {
        let surface = Surface {
            normal: triangle.normal,
            reflectance: triangle.color,
        };
        let vertices = [triangle.v0, triangle.v1, triangle.v2].map(|position| Vertex { position });
        draw_polygon(&mut screen, &vertices, surface, perspective_correct);
    }
    screen
}

/// The rotation R as its three columns: the camera's right, down and forward.
fn rotation() -> [Vec3; 3] {
    let (s, c) = YAW.sin_cos();
    [
        Vec3::new(c, 0.0, -s),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(s, 0.0, c),
    ]
}

/// The camera transform and the perspective projection (eq. 3 and 4); the
/// handout's `int(...)` truncates toward zero, before the half size is added.
/// The pixel keeps 1/z for the depth test and the 3D position.
fn vertex_shader(vertex: &Vertex, perspective_correct: bool) -> Pixel {
    let v = vertex.position;
    // P' = (P - C) R (eq. 8), P a row vector: one dot product per column of R.
    let [right, down, forward] = rotation();
    let d = v - CAMERA_POS;
    let pos = Vec3::new(d.dot(right), d.dot(down), d.dot(forward));
    let zinv = 1.0 / pos.z;
    Pixel {
        x: (FOCAL_LENGTH * pos.x * zinv) as i32 + SCREEN_WIDTH / 2,
        y: (FOCAL_LENGTH * pos.y * zinv) as i32 + SCREEN_HEIGHT / 2,
        zinv,
        pos3d: if perspective_correct { v * zinv } else { v },
    }
}

/// Eq. 10: the light from the point light that falls on a surface at `position`
/// facing `normal`, `P max(r̂·n̂, 0) / (4π |r|²)`, written as `(r·n) / (4π |r|² |r|)`.
fn direct_light(position: Vec3, normal: Vec3) -> Vec3 {
    let r = LIGHT_POS - position;
    let r2 = r.dot(r);
    LIGHT_POWER * (r.dot(normal).max(0.0) / (4.0 * PI * r2 * r2.sqrt()))
}

/// `PixelShader`: draw the pixel only if it is nearer than what is there, that
/// is if its 1/z is larger.
fn pixel_shader(screen: &mut Screen, p: Pixel, surface: Surface, perspective_correct: bool) {
    if !(0..SCREEN_WIDTH).contains(&p.x) || !(0..SCREEN_HEIGHT).contains(&p.y) {
        return;
    }
    let i = (p.y * SCREEN_WIDTH + p.x) as usize;
    if p.zinv > screen.depth_buffer[i] {
        screen.depth_buffer[i] = p.zinv;
        let position = if perspective_correct {
            p.pos3d * (1.0 / p.zinv)
        } else {
            p.pos3d
        };
        let illumination = surface.reflectance
            * (direct_light(position, surface.normal) + INDIRECT_LIGHT_POWER_PER_AREA);
        screen.put_pixel(p.x, p.y, illumination);
    }
}

/// `Interpolate`: `result.len()` pixels from `a` to `b`, in equal float steps of
/// the position, 1/z and the 3D position, each position truncated to whole pixels.
fn interpolate(a: Pixel, b: Pixel, result: &mut [Pixel]) {
    let n = result.len();
    let d = (n.max(2) - 1) as f32;
    let step = (
        IVec2::new(b.x - a.x, b.y - a.y).as_vec2() / d,
        (b.zinv - a.zinv) / d,
        (b.pos3d - a.pos3d) / d,
    );
    let mut current = (IVec2::new(a.x, a.y).as_vec2(), a.zinv, a.pos3d);
    for r in result.iter_mut() {
        *r = Pixel {
            x: current.0.x as i32,
            y: current.0.y as i32,
            zinv: current.1,
            pos3d: current.2,
        };
        current.0 += step.0;
        current.1 += step.1;
        current.2 += step.2;
    }
}

/// `ComputePolygonRows`: the leftmost and rightmost pixel of every row of a convex
/// polygon, from its smallest to its largest y, found by walking its edges.
fn compute_polygon_rows(vertex_pixels: &[Pixel]) -> (Vec<Pixel>, Vec<Pixel>) {
    // 1. The polygon's smallest and largest y, and so its number of rows.
    let min_y = vertex_pixels.iter().map(|p| p.y).min().unwrap();
    let max_y = vertex_pixels.iter().map(|p| p.y).max().unwrap();
    let rows = (max_y - min_y + 1) as usize;
    // 2. and 3. One entry per row; left x very large, right x very small.
    let mut left_pixels = vec![Pixel::default(); rows];
    let mut right_pixels = vec![Pixel::default(); rows];
    for i in 0..rows {
        left_pixels[i].x = i32::MAX;
        left_pixels[i].y = min_y + i as i32;
        right_pixels[i].x = i32::MIN;
        right_pixels[i].y = min_y + i as i32;
    }
    // 4. Walk each edge as a line and widen the rows it passes through.
    let n = vertex_pixels.len();
    for i in 0..n {
        let (a, b) = (vertex_pixels[i], vertex_pixels[(i + 1) % n]);
        let delta = IVec2::new(a.x - b.x, a.y - b.y).abs();
        let mut edge = vec![Pixel::default(); (delta.x.max(delta.y) + 1) as usize];
        interpolate(a, b, &mut edge);
        for p in edge {
            // The float running sum can land a step outside the polygon's rows
            // (4.9999 truncates to 4): such a pixel belongs to no row.
            let Some(row) = usize::try_from(p.y - min_y).ok().filter(|&r| r < rows) else {
                continue;
            };
            if p.x < left_pixels[row].x {
                left_pixels[row] = p;
            }
            if p.x > right_pixels[row].x {
                right_pixels[row] = p;
            }
        }
    }
    (left_pixels, right_pixels)
}

/// `DrawPolygonRows`: every pixel of every row, from its left to its right end.
fn draw_polygon_rows(
    screen: &mut Screen,
    left: &[Pixel],
    right: &[Pixel],
    surface: Surface,
    perspective_correct: bool,
) {
    for (l, r) in left.iter().zip(right) {
        let pixels = r.x - l.x + 1;
        if pixels <= 0 {
            continue; // a row no edge reached
        }
        let mut row = vec![Pixel::default(); pixels as usize];
        interpolate(*l, *r, &mut row);
        for p in row {
            pixel_shader(screen, p, surface, perspective_correct);
        }
    }
}

/// `DrawPolygon`: project the vertices, find the rows, fill them.
fn draw_polygon(
    screen: &mut Screen,
    vertices: &[Vertex],
    surface: Surface,
    perspective_correct: bool,
) {
    let vertex_pixels: Vec<Pixel> = vertices
        .iter()
        .map(|v| vertex_shader(v, perspective_correct))
        .collect();
    let (left_pixels, right_pixels) = compute_polygon_rows(&vertex_pixels);
    draw_polygon_rows(
        screen,
        &left_pixels,
        &right_pixels,
        surface,
        perspective_correct,
    );
}

fn main() {
    let out = std::env::args()
        .nth(1)
        .unwrap_or("fig7-pixel-light.png".into());
    // draw(false) interpolates the position affinely: Figure 8.
    let rgb = draw(true).to_rgb8();
    let (w, h) = (SCREEN_WIDTH as u32, SCREEN_HEIGHT as u32);
    match image::save_buffer(&out, &rgb, w, h, image::ExtendedColorType::Rgb8) {
        Ok(()) => println!("wrote {out}"),
        Err(e) => {
            eprintln!("error: cannot write {out}: {e}");
            std::process::exit(1);
        }
    }
}
