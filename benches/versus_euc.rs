//! `cargo bench --features bench --bench versus_euc`: rasterlab against euc 0.5.3 in one process,
//! on the same mesh, camera, 1/z depth buffer and light code, frames interleaved
//! (rows, edge, euc, in turn) so that the shared machine's noise falls on all
//! three alike. Prints a markdown table of median frame times, Mtriangles/s and
//! the ratio rasterlab / euc (below 1: rasterlab is faster), then how many pixels
//! the two images differ in, which shows the comparison draws the same picture.
//!
//! Run it in both builds: the default one, and
//! `RUSTFLAGS="-C target-cpu=native" cargo bench --features bench --bench versus_euc` (euc's
//! `mul_add` becomes one FMA instruction there). The table's title says which.
//! `cargo test` runs only the smallest case, once, as a smoke test.
//! `RASTERLAB_RECORD=1` writes the medians to docs/bench/.

mod common;

use euc::buffer::Buffer2d;
use euc::rasterizer::{BackfaceCullingDisabled, Triangles};
use euc::{Interpolate, Pipeline as _, Target as _};
use glam::Vec3;
use rasterlab::app::figure::Inputs;
use rasterlab::app::figure::Raster;
use rasterlab::app::Settings;
use rasterlab::pipeline::camera::Projection;
use rasterlab::pipeline::target::pack;
use rasterlab::scene::{cornell_box, subdivide};
use rasterlab::{Figure, Frame, Light, Mesh, StageName};
use std::time::{Duration, Instant};

/// One corner of a triangle as euc takes it (euc has no index buffer): the
/// position, and the face's normal and colour, which every corner repeats.
#[derive(Clone, Copy)]
struct Corner {
    position: Vec3,
    normal: Vec3,
    color: Vec3,
}

/// What euc interpolates. Only `world` varies over a triangle; the face's normal
/// and colour are carried from the first corner, as rasterlab's `Surface` is.
#[derive(Clone, Copy)]
struct Varying {
    world: Vec3,
    normal: Vec3,
    color: Vec3,
}

impl Interpolate for Varying {
    #[inline(always)]
    fn lerp2(a: Self, b: Self, x: f32, y: f32) -> Self {
        Varying {
            world: a.world * x + b.world * y,
            ..a
        }
    }
    #[inline(always)]
    fn lerp3(a: Self, b: Self, c: Self, x: f32, y: f32, z: f32) -> Self {
        Varying {
            world: a.world * x + b.world * y + c.world * z,
            ..a
        }
    }
}

/// A flat colour that is not interpolated at all, for the depth stage: euc then
/// does no more per-pixel work than rasterlab's `Nothing`.
#[derive(Clone, Copy)]
struct Flat(u32);

impl Interpolate for Flat {
    #[inline(always)]
    fn lerp2(a: Self, _: Self, _: f32, _: f32) -> Self {
        a
    }
    #[inline(always)]
    fn lerp3(a: Self, _: Self, _: Self, _: f32, _: f32, _: f32) -> Self {
        a
    }
}

/// rasterlab's camera as euc's clip coordinates: `x = f X/Z + W/2` becomes
/// x_clip = X f/(W/2), w = Z (euc maps x_clip/w in [-1, 1] onto [0, W]); y is
/// negated because euc's y points up. z_clip = -1 makes euc's depth -1/Z, so its
/// "less or equal wins" test is rasterlab's 1/z test (larger 1/z wins).
#[derive(Clone, Copy)]
struct Clip {
    projection: Projection,
    sx: f32,
    sy: f32,
}

impl Clip {
    #[inline(always)]
    fn of(&self, world: Vec3) -> [f32; 4] {
        let p = self.projection.to_camera(world);
        [p.x * self.sx, -p.y * self.sy, -1.0, p.z]
    }
}

struct EucDepth(Clip);

impl euc::Pipeline for EucDepth {
    type Vertex = Corner;
    type VsOut = Flat;
    type Pixel = u32;
    #[inline(always)]
    fn vert(&self, v: &Corner) -> ([f32; 4], Flat) {
        (self.0.of(v.position), Flat(pack(v.color)))
    }
    #[inline(always)]
    fn frag(&self, v: &Flat) -> u32 {
        v.0
    }
}

struct EucPixelLight(Clip, Light);

impl euc::Pipeline for EucPixelLight {
    type Vertex = Corner;
    type VsOut = Varying;
    type Pixel = u32;
    #[inline(always)]
    fn vert(&self, v: &Corner) -> ([f32; 4], Varying) {
        let out = Varying {
            world: v.position,
            normal: v.normal,
            color: v.color,
        };
        (self.0.of(v.position), out)
    }
    #[inline(always)]
    fn frag(&self, v: &Varying) -> u32 {
        // The same eq. 11 and the same 8-bit packing as rasterlab's PixelLight.
        pack(self.1.reflected(v.world, v.normal, v.color))
    }
}

struct Euc {
    corners: Vec<Corner>,
    clip: Clip,
    light: Light,
    color: Buffer2d<u32>,
    depth: Buffer2d<f32>,
}

impl Euc {
    fn new(mesh: &Mesh, settings: &Settings) -> Self {
        let corners = mesh
            .triangles()
            .flat_map(|t| {
                [t.v0, t.v1, t.v2].map(|position| Corner {
                    position,
                    normal: t.normal,
                    color: t.color,
                })
            })
            .collect();
        let size = [
            settings.camera.width as usize,
            settings.camera.height as usize,
        ];
        Euc {
            corners,
            clip: Clip {
                projection: settings.camera.projection(),
                sx: settings.camera.focal / (settings.camera.width as f32 / 2.0),
                sy: settings.camera.focal / (settings.camera.height as f32 / 2.0),
            },
            light: settings.light,
            color: Buffer2d::new(size, 0),
            depth: Buffer2d::new(size, 0.0),
        }
    }

    fn render(&mut self, stage: StageName) {
        self.color.clear(0);
        self.depth.clear(0.0);
        let depth = Some(&mut self.depth);
        type Tri<'a> = Triangles<'a, Buffer2d<f32>, BackfaceCullingDisabled>;
        match stage {
            StageName::Depth => {
                EucDepth(self.clip).draw::<Tri, _>(&self.corners, &mut self.color, depth)
            }
            StageName::PixelLight => EucPixelLight(self.clip, self.light).draw::<Tri, _>(
                &self.corners,
                &mut self.color,
                depth,
            ),
            _ => unreachable!("only depth and pixel-light are compared"),
        }
    }
}

struct Case {
    name: &'static str,
    mesh: Mesh,
    size: (u32, u32),
    stage: StageName,
    rounds: usize,
}

fn median(mut v: Vec<Duration>) -> f64 {
    v.sort();
    v[v.len() / 2].as_secs_f64() * 1e3
}

/// Runs one case; returns its table row, the pixels in which euc's image and
/// rasterlab's edge rasterizer's differ, and what the sitting records: the
/// medians (rows, edge, euc, in ms) and those pixels as a percentage.
fn run(case: &Case) -> (String, usize, Vec<f64>) {
    let settings = common::settings(case.size);
    let (camera, uniforms) = (settings.camera, Inputs::lit(settings.light));
    let figure = Figure::of(case.stage);
    let mut ours: Vec<_> = [Raster::Rows, Raster::Edge]
        .map(|r| {
            (
                figure.with_raster(r).pipeline_for(&case.mesh),
                Frame::default(),
            )
        })
        .into();
    let mut euc = Euc::new(&case.mesh, &settings);
    let mut times: [Vec<Duration>; 3] = Default::default();
    // One untimed round first: buffers sized, caches warm.
    for round in 0..=case.rounds {
        for k in 0..3 {
            let which = (round + k) % 3; // rotate the order each round
            let start = Instant::now();
            if which < 2 {
                let (pipeline, frame) = &mut ours[which];
                pipeline.render(&uniforms, &case.mesh, &camera, frame);
                std::hint::black_box(&frame.color);
            } else {
                euc.render(case.stage);
                std::hint::black_box(euc.color.as_ref());
            }
            if round > 0 {
                times[which].push(start.elapsed());
            }
        }
    }
    let differing = ours[1]
        .1
        .color
        .iter()
        .zip(euc.color.as_ref())
        .filter(|(a, b)| a != b)
        .count();
    let [rows, edge, e] = [0, 1, 2].map(|k| median(times[k].clone()));
    // Triangles per second where triangles dominate, pixels per second elsewhere.
    let (triangles, pixels) = (case.mesh.faces.len(), case.size.0 * case.size.1);
    let rate = |ms: f64| {
        if triangles > 1000 {
            format!("{ms:.2} ms, {:.1} Mtri/s", triangles as f64 / ms / 1e3)
        } else {
            format!("{ms:.2} ms, {:.0} Mpx/s", pixels as f64 / ms / 1e3)
        }
    };
    let percent = 100.0 * differing as f64 / pixels as f64;
    let row = format!(
        "| {} | {} | {} | {} | {} | {:.2} | {:.2} | {:.3} % |",
        case.name,
        triangles,
        rate(rows),
        rate(edge),
        rate(e),
        rows / e,
        edge / e,
        percent,
    );
    (row, differing, vec![rows, edge, e, percent])
}

fn build() -> &'static str {
    if cfg!(target_feature = "avx512f") {
        "`-C target-cpu=native` (AVX-512, FMA)"
    } else if cfg!(target_feature = "fma") {
        "`-C target-cpu=native` (AVX2, FMA)"
    } else {
        "default (x86-64 baseline, SSE2)"
    }
}

fn main() {
    let benching = std::env::args().any(|a| a == "--bench");
    let box_ = cornell_box();
    let mut cases = vec![
        Case {
            name: "box, depth, 500x500",
            mesh: box_.clone(),
            size: (500, 500),
            stage: StageName::Depth,
            rounds: 300,
        },
        Case {
            name: "box, pixel-light, 500x500",
            mesh: box_.clone(),
            size: (500, 500),
            stage: StageName::PixelLight,
            rounds: 300,
        },
    ];
    if !benching {
        // `cargo test`: one round of the small cases, and the images must agree.
        for case in &mut cases {
            case.rounds = 1;
            let (_, differing, _) = run(case);
            assert!(differing < 2000, "{}: {differing} pixels differ", case.name);
        }
        return;
    }
    let split = |k| subdivide(&box_, k);
    cases.extend([
        Case {
            name: "cornell:64, depth, 1920x1080",
            mesh: split(64),
            size: (1920, 1080),
            stage: StageName::Depth,
            rounds: 60,
        },
        Case {
            name: "cornell:183, depth, 1920x1080",
            mesh: split(183),
            size: (1920, 1080),
            stage: StageName::Depth,
            rounds: 20,
        },
        Case {
            name: "cornell:183, pixel-light, 1920x1080",
            mesh: split(183),
            size: (1920, 1080),
            stage: StageName::PixelLight,
            rounds: 20,
        },
    ]);
    println!(
        "Build: {}. One thread, frames interleaved; median of each.\n",
        build()
    );
    println!("| case | triangles | rasterlab rows | rasterlab edge | euc 0.5.3 | rows / euc | edge / euc | pixels differing, edge vs euc |");
    println!("|---|---|---|---|---|---|---|---|");
    let mut sitting = Vec::new();
    for case in &cases {
        let (row, _, medians) = run(case);
        println!("{row}");
        sitting.push((case.name.to_string(), medians));
    }
    if common::recording() {
        common::record(
            "versus_euc",
            &["rows_ms", "edge_ms", "euc_ms", "differing_percent"],
            &sitting,
        );
    }
}
