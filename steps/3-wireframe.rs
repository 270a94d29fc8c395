//! Handout section 3 (Figure 3): draw every triangle's edges as lines.
//!
//! Step 2's program plus `Interpolate`, `DrawLineSDL`, `DrawPolygonEdges` and a
//! camera that can turn (yaw). No clipping: a vertex behind the camera is drawn
//! wrong, as in the handout.
//! `cargo run --release --example 3-wireframe [OUT.png]` writes fig3-wireframe.png.

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
        let vertices = [triangle.v0, triangle.v1, triangle.v2];
        draw_polygon_edges(&mut screen, &vertices);
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

/// `DrawLineSDL`: as many pixels as the line is long along x or y, plus one.
fn draw_line_sdl(screen: &mut Screen, a: IVec2, b: IVec2, color: Vec3) {
    let delta = (a - b).abs();
    let pixels = delta.x.max(delta.y) + 1;
    let mut line = vec![IVec2::ZERO; pixels as usize];
    interpolate(a, b, &mut line);
    for p in line {
        screen.put_pixel(p.x, p.y, color);
    }
}

/// `DrawPolygonEdges`: project every vertex, then a line from each to the next.
fn draw_polygon_edges(screen: &mut Screen, vertices: &[Vec3]) {
    let projected: Vec<IVec2> = vertices.iter().map(|&v| vertex_shader(v)).collect();
    let n = projected.len();
    for i in 0..n {
        let j = (i + 1) % n;
        draw_line_sdl(screen, projected[i], projected[j], Vec3::new(1.0, 1.0, 1.0));
    }
}

fn main() {
    let out = std::env::args()
        .nth(1)
        .unwrap_or("fig3-wireframe.png".into());
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
