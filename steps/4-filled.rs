//! Handout section 4 (Figure 4): fill every triangle, row by row, in its colour.
//!
//! Step 3's program plus `ComputePolygonRows`, `DrawPolygonRows` and `DrawPolygon`.
//! Triangles are drawn in the scene's order with no depth test, so a far one
//! drawn late covers a near one: Figure 4's mistake.
//! `cargo run --release --example 4-filled [OUT.png]` writes fig4-filled.png.

use glam::{IVec2, Vec3};

const SCREEN_WIDTH: i32 = 500;
const SCREEN_HEIGHT: i32 = 500;
const FOCAL_LENGTH: f32 = 500.0;
const CAMERA_POS: Vec3 = Vec3::new(0.0, 0.0, -3.001);
/// Turn about the y-axis, in radians (the `Update` loop would change it).
const YAW: f32 = 0.0;

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

/// The window's pixels, as linear colours, row after row.
pub struct Screen {
    pub pixels: Vec<Vec3>,
}

impl Screen {
    fn new() -> Screen {
        Screen {
            pixels: vec![Vec3::ZERO; (SCREEN_WIDTH * SCREEN_HEIGHT) as usize],
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

pub fn draw() -> Screen {
    let triangles = load_test_model();
    let mut screen = Screen::new();
    for triangle in &triangles {
        let current_color = triangle.color;
        let vertices = [triangle.v0, triangle.v1, triangle.v2];
        draw_polygon(&mut screen, &vertices, current_color);
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
fn vertex_shader(v: Vec3) -> IVec2 {
    // P' = (P - C) R (eq. 8), P a row vector: one dot product per column of R.
    let [right, down, forward] = rotation();
    let d = v - CAMERA_POS;
    let pos = Vec3::new(d.dot(right), d.dot(down), d.dot(forward));
    let zinv = 1.0 / pos.z;
    IVec2::new(
        (FOCAL_LENGTH * pos.x * zinv) as i32 + SCREEN_WIDTH / 2,
        (FOCAL_LENGTH * pos.y * zinv) as i32 + SCREEN_HEIGHT / 2,
    )
}

/// `Interpolate`: `result.len()` positions from `a` to `b`, in equal float steps,
/// each truncated to whole pixels.
fn interpolate(a: IVec2, b: IVec2, result: &mut [IVec2]) {
    let n = result.len();
    let step = (b - a).as_vec2() / (n.max(2) - 1) as f32;
    let mut current = a.as_vec2();
    for r in result.iter_mut() {
        *r = IVec2::new(current.x as i32, current.y as i32);
        current += step;
    }
}

/// `ComputePolygonRows`: the leftmost and rightmost pixel of every row of a convex
/// polygon, from its smallest to its largest y, found by walking its edges.
fn compute_polygon_rows(vertex_pixels: &[IVec2]) -> (Vec<IVec2>, Vec<IVec2>) {
    // 1. The polygon's smallest and largest y, and so its number of rows.
    let min_y = vertex_pixels.iter().map(|p| p.y).min().unwrap();
    let max_y = vertex_pixels.iter().map(|p| p.y).max().unwrap();
    let rows = (max_y - min_y + 1) as usize;
    // 2. and 3. One entry per row; left x very large, right x very small.
    let mut left_pixels = vec![IVec2::ZERO; rows];
    let mut right_pixels = vec![IVec2::ZERO; rows];
    for i in 0..rows {
        left_pixels[i] = IVec2::new(i32::MAX, min_y + i as i32);
        right_pixels[i] = IVec2::new(i32::MIN, min_y + i as i32);
    }
    // 4. Walk each edge as a line and widen the rows it passes through.
    let n = vertex_pixels.len();
    for i in 0..n {
        let (a, b) = (vertex_pixels[i], vertex_pixels[(i + 1) % n]);
        let delta = (a - b).abs();
        let mut edge = vec![IVec2::ZERO; (delta.x.max(delta.y) + 1) as usize];
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
fn draw_polygon_rows(screen: &mut Screen, left: &[IVec2], right: &[IVec2], color: Vec3) {
    for (l, r) in left.iter().zip(right) {
        let pixels = r.x - l.x + 1;
        if pixels <= 0 {
            continue; // a row no edge reached
        }
        let mut row = vec![IVec2::ZERO; pixels as usize];
        interpolate(*l, *r, &mut row);
        for p in row {
            screen.put_pixel(p.x, p.y, color);
        }
    }
}

/// `DrawPolygon`: project the vertices, find the rows, fill them.
fn draw_polygon(screen: &mut Screen, vertices: &[Vec3], color: Vec3) {
    let vertex_pixels: Vec<IVec2> = vertices.iter().map(|&v| vertex_shader(v)).collect();
    let (left_pixels, right_pixels) = compute_polygon_rows(&vertex_pixels);
    draw_polygon_rows(screen, &left_pixels, &right_pixels, color);
}

fn main() {
    let out = std::env::args().nth(1).unwrap_or("fig4-filled.png".into());
    let rgb = draw().to_rgb8();
    let (w, h) = (SCREEN_WIDTH as u32, SCREEN_HEIGHT as u32);
    match image::save_buffer(&out, &rgb, w, h, image::ExtendedColorType::Rgb8) {
        Ok(()) => println!("wrote {out}"),
        Err(e) => {
            eprintln!("error: cannot write {out}: {e}");
            std::process::exit(1);
        }
    }
}
