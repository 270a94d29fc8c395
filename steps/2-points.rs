//! Handout section 2 (Figure 2): project every vertex of the scene and plot it.
//!
//! A plain program, written the way the handout's C++ is: no generics, no
//! clipping, no batching. Only the scene's data comes from the rasterlab library.
//! `cargo run --release --example 2-points [OUT.png]` writes fig2-points.png.

use glam::{IVec2, Vec3};

const SCREEN_WIDTH: i32 = 500;
const SCREEN_HEIGHT: i32 = 500;
const FOCAL_LENGTH: f32 = 500.0;
const CAMERA_POS: Vec3 = Vec3::new(0.0, 0.0, -3.001);

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
        for v in vertices {
            let proj_pos = vertex_shader(v);
            let color = Vec3::new(1.0, 1.0, 1.0);
            screen.put_pixel(proj_pos.x, proj_pos.y, color);
        }
    }
    screen
}

/// The camera transform and the perspective projection (eq. 3 and 4); the
/// handout's `int(...)` truncates toward zero, before the half size is added.
fn vertex_shader(v: Vec3) -> IVec2 {
    let pos = v - CAMERA_POS;
    let zinv = 1.0 / pos.z;
    IVec2::new(
        (FOCAL_LENGTH * pos.x * zinv) as i32 + SCREEN_WIDTH / 2,
        (FOCAL_LENGTH * pos.y * zinv) as i32 + SCREEN_HEIGHT / 2,
    )
}

fn main() {
    let out = std::env::args().nth(1).unwrap_or("fig2-points.png".into());
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
