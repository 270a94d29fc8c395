//! The application: what the subcommands do apart from parsing (build the scene,
//! camera and light from the settings, draw, time and write files), image files,
//! Figure 1, and the viewer.

pub mod check;
pub mod controls;
pub mod explain;
pub mod image_io;
pub mod overview;
pub mod parallel;
pub mod parse;
pub mod viewer;

use crate::measure::figure::Figure;
use crate::measure::plot::Canvas;
use crate::measure::timing::{time_runs, Timing};
use crate::measure::{raytrace, report, stress};
use crate::pipeline::camera::DEFAULT_NEAR;
use crate::pipeline::dof::DepthOfField;
use crate::pipeline::draw::Stats;
use crate::pipeline::interpolate::Pixel;
use crate::pipeline::raster::rows::{compute_polygon_rows, Rows};
use crate::pipeline::raster::Bounds;
use crate::pipeline::{Camera, Filter, Frame, Light, Mesh, Uniforms};
use crate::scene::Scene;
use glam::Vec3;
use image_io::{write_png, write_text, WriteError};
use overview::figure_one;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Everything a render depends on besides the stage and the scene; the defaults
/// are the course skeleton's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    pub width: u32,
    pub height: u32,
    pub focal: f32,
    pub camera: Vec3,
    /// Degrees.
    pub yaw: f32,
    /// Degrees.
    pub pitch: f32,
    pub light: Vec3,
    pub light_power: f32,
    pub indirect: f32,
    /// Near clipping plane distance.
    pub near: f32,
    /// Clip at the near plane and the screen's guard band; false draws as the
    /// handout does (`--no-clip`).
    pub clip: bool,
    /// Threads that draw bands of the image (`--threads`); the image is the same
    /// for any number.
    pub threads: usize,
    /// How textures are read between texels (`--filter`).
    pub filter: Filter,
    /// Depth of field applied to each frame (`--dof`).
    pub dof: Option<DepthOfField>,
}

impl Default for Settings {
    fn default() -> Self {
        let camera = Camera::handout(500, 500);
        let light = Light::handout();
        Settings {
            width: 500,
            height: 500,
            focal: camera.focal,
            camera: camera.position,
            yaw: 0.0,
            pitch: 0.0,
            light: light.position,
            light_power: light.power.x,
            indirect: light.indirect.x,
            near: DEFAULT_NEAR,
            clip: true,
            threads: 1,
            filter: Filter::Nearest,
            dof: None,
        }
    }
}

impl Settings {
    pub fn camera(&self) -> Camera {
        Camera {
            position: self.camera,
            yaw: self.yaw.to_radians(),
            pitch: self.pitch.to_radians(),
            focal: self.focal,
            width: self.width,
            height: self.height,
            near: self.clip.then_some(self.near),
        }
    }

    pub fn light(&self) -> Light {
        Light {
            position: self.light,
            power: Vec3::splat(self.light_power),
            indirect: Vec3::splat(self.indirect),
        }
    }

    /// The light alone, for a mesh without textures.
    pub fn uniforms(&self) -> Uniforms<'static> {
        Uniforms {
            filter: self.filter,
            eye: self.camera,
            ..Uniforms::lit(self.light())
        }
    }

    /// The light, and the textures of `mesh` read with `--filter`.
    pub fn uniforms_for<'a>(&self, mesh: &'a Mesh) -> Uniforms<'a> {
        Uniforms {
            textures: &mesh.textures,
            ..self.uniforms()
        }
    }
}

/// Draws `figure` of `mesh`; with `runs`, draws it that many times and reports the
/// timing (drawing only, no file I/O).
pub fn render(
    figure: Figure,
    mesh: &Mesh,
    settings: &Settings,
    runs: Option<usize>,
) -> (Frame, Option<Timing>) {
    let (frame, timing, _) = render_with_stats(figure, mesh, settings, runs);
    (frame, timing)
}

/// [`render`], with what the frame did.
pub fn render_with_stats(
    figure: Figure,
    mesh: &Mesh,
    settings: &Settings,
    runs: Option<usize>,
) -> (Frame, Option<Timing>, Stats) {
    // No threads to be had: one band, on this thread.
    let mut pipeline = parallel::Parallel::new(figure, mesh, settings.threads)
        .or_else(|_| parallel::Parallel::new(figure, mesh, 1))
        .expect("one band needs no thread");
    let mut frame = Frame::default();
    draw_frame(&mut pipeline, figure, mesh, settings, &mut frame);
    let stats = pipeline.stats();
    let timing = runs.map(|n| {
        time_runs(n, || {
            draw_frame(&mut pipeline, figure, mesh, settings, &mut frame)
        })
    });
    (frame, timing, stats)
}

/// One frame of `figure` with everything it asks for: its shadow map (drawn
/// for each frame, since the light may move, and part of what the frame costs),
/// the pipeline, then depth of field on the finished frame.
pub fn draw_frame(
    pipeline: &mut parallel::Parallel,
    figure: Figure,
    mesh: &Mesh,
    settings: &Settings,
    frame: &mut Frame,
) {
    let shadow = figure.shadow_map(mesh, &settings.light(), settings.near);
    let uniforms = settings.uniforms_for(mesh).with_shadow(shadow.as_ref());
    pipeline.render(mesh, &settings.camera(), &uniforms, frame);
    if let Some(dof) = settings.dof {
        dof.apply(frame, settings.focal);
    }
}

/// `--stats`: the frame's counts, one per line, and what was left out and why.
pub fn stats_text(s: &Stats) -> String {
    let mut out = format!(
        "triangles: {} in, {} culled, {} outside the view, {} clipped, {} drawn\n\
         pixels: {} written, {} rejected by the depth test\n",
        s.triangles, s.culled, s.outside, s.clipped, s.drawn, s.pixels_written, s.depth_rejected
    );
    if s.near_plane_skipped {
        out += "left out: near-plane clipping (the whole mesh is in front of the near plane)\n";
    }
    if s.view_tests_skipped {
        out += "left out: view tests (the whole mesh projects inside the screen)\n";
    }
    out
}

/// Draws `figure` of `mesh` and writes it to `out`: its colours, or with
/// `buffer` its depth buffer as [`depth_buffer_picture`] shows it.
pub fn render_to_file(
    figure: Figure,
    mesh: &Mesh,
    settings: &Settings,
    out: &Path,
    runs: Option<usize>,
    buffer: bool,
) -> Result<(Option<Timing>, Stats), WriteError> {
    let (frame, timing, stats) = render_with_stats(figure, mesh, settings, runs);
    match buffer {
        true => write_png(&depth_buffer_picture(&frame), out)?,
        false => write_png(&frame, out)?,
    }
    Ok((timing, stats))
}

/// The image built up triangle by triangle: frame i shows the first i triangles of
/// `mesh` drawn (about `max_frames` frames: several triangles a frame for larger
/// meshes), so the order of drawing can be seen, Figure 4's mistake included.
pub fn build_up(figure: Figure, mesh: &Mesh, settings: &Settings, max_frames: usize) -> Vec<Frame> {
    let faces = mesh.faces.len();
    let per_frame = faces.div_ceil(max_frames.max(1)).max(1);
    let mut frames = Vec::new();
    let mut pipeline = parallel::Parallel::new(figure, mesh, settings.threads)
        .or_else(|_| parallel::Parallel::new(figure, mesh, 1))
        .expect("one band needs no thread");
    let (camera, uniforms) = (settings.camera(), settings.uniforms_for(mesh));
    // One copy of the mesh whose faces grow: no copy of the vertices per frame.
    let mut prefix = Mesh {
        faces: Vec::with_capacity(faces),
        ..mesh.clone()
    };
    while prefix.faces.len() < faces {
        let k = (prefix.faces.len() + per_frame).min(faces);
        prefix
            .faces
            .extend_from_slice(&mesh.faces[prefix.faces.len()..k]);
        let mut frame = Frame::default();
        pipeline.render(&prefix, &camera, &uniforms, &mut frame);
        frames.push(frame);
    }
    frames
}

/// `rasterlab animate`: [`build_up`] of `mesh` written as a GIF that
/// shows each triangle for `delay_ms` and the finished image for two seconds.
pub fn animate_to_file(
    figure: Figure,
    mesh: &Mesh,
    settings: &Settings,
    out: &Path,
    delay_ms: u32,
) -> Result<usize, WriteError> {
    let frames = build_up(figure, mesh, settings, 60);
    let fail = |e: image::ImageError| WriteError {
        path: out.to_path_buf(),
        reason: e.to_string(),
    };
    let mut bytes = Vec::new();
    {
        let mut encoder = image::codecs::gif::GifEncoder::new_with_speed(&mut bytes, 10);
        encoder
            .set_repeat(image::codecs::gif::Repeat::Infinite)
            .map_err(fail)?;
        let last = frames.len().saturating_sub(1);
        for (i, frame) in frames.iter().enumerate() {
            let rgba: Vec<u8> = frame
                .to_rgb8()
                .chunks_exact(3)
                .flat_map(|p| [p[0], p[1], p[2], 255])
                .collect();
            let image = image::RgbaImage::from_raw(frame.width, frame.height, rgba)
                .expect("a frame's size matches its pixels");
            let ms = if i == last { 2000 } else { delay_ms };
            let delay = image::Delay::from_numer_denom_ms(ms, 1);
            encoder
                .encode_frame(image::Frame::from_parts(image, 0, 0, delay))
                .map_err(fail)?;
        }
    }
    image_io::write_bytes(out, &bytes)?;
    Ok(frames.len())
}

/// The depth buffer of `frame` as a picture: 1/z scaled linearly from the
/// smallest drawn value (dark grey, farthest) to the largest (white, nearest),
/// black where nothing was drawn (1/z = 0), with a legend strip beneath.
pub fn depth_buffer_picture(frame: &Frame) -> Frame {
    let drawn = frame
        .depth
        .iter()
        .copied()
        .filter(|&z| z > 0.0 && z.is_finite());
    let (lo, hi) = drawn.fold((f32::INFINITY, 0.0f32), |(lo, hi), z| {
        (lo.min(z), hi.max(z))
    });
    let grey = |zinv: f32| -> u32 {
        if !(zinv > 0.0 && zinv.is_finite()) {
            return 0;
        }
        let t = if hi > lo {
            (zinv - lo) / (hi - lo)
        } else {
            1.0
        };
        let v = (64.0 + 191.0 * t).round() as u32;
        v << 16 | v << 8 | v
    };
    let (w, h) = (frame.width, frame.height);
    let legend = 64;
    let mut c = Canvas::new(w.max(360), h + legend, 0x00ff_ffff);
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let zinv = frame.depth.get(i).copied().unwrap_or(0.0);
            c.frame.color[(y * c.frame.width + x) as usize] = grey(zinv);
        }
    }
    if hi > 0.0 {
        let bar = (c.frame.width as i32 - 24).max(1);
        for i in 0..bar {
            let zinv = lo + (hi - lo) * i as f32 / bar as f32;
            c.rect((12 + i, h as i32 + 8), (1, 16), grey(zinv));
        }
        let ends = format!(
            "far 1/z {lo:.3} (z {:.2})   near 1/z {hi:.3} (z {:.2})",
            1.0 / lo,
            1.0 / hi
        );
        c.text((12, h as i32 + 30), &ends, 1, 0);
        c.text((12, h as i32 + 44), "black: nothing drawn (1/z = 0)", 1, 0);
    }
    c.frame
}

/// The overview's file name.
pub const OVERVIEW_FILE: &str = "fig1-overview.png";

/// Writes every figure, and the overview, into `dir` (created if missing).
/// Returns the paths written, in order.
pub fn render_all(
    mesh: &Mesh,
    settings: &Settings,
    dir: &Path,
) -> Result<Vec<PathBuf>, WriteError> {
    std::fs::create_dir_all(dir).map_err(|e| WriteError {
        path: dir.to_path_buf(),
        reason: e.to_string(),
    })?;
    let mut written = Vec::new();
    let mut frames = Vec::new();
    for figure in Figure::FIGURES {
        let (frame, _) = render(figure, mesh, settings, None);
        let path = dir.join(figure.figure_file());
        write_png(&frame, &path)?;
        written.push(path);
        frames.push(frame);
    }
    let overview = figure_one(&frames).expect("seven figures of one size");
    let path = dir.join(OVERVIEW_FILE);
    write_png(&overview, &path)?;
    written.push(path);
    Ok(written)
}

/// `ComputePolygonRows` for a polygon given as pixels, printed as the handout's
/// test program does: `Start: (x,y). End: (x,y). ` on one line per row.
pub fn rows_text(vertices: &[(i32, i32)]) -> String {
    let pixels: Vec<_> = vertices.iter().map(|&(x, y)| Pixel::at(x, y)).collect();
    let mut rows = Rows::new();
    compute_polygon_rows(&pixels, &Bounds::unbounded(), &mut rows);
    let mut out = String::new();
    for (l, r) in rows.left.iter().zip(&rows.right) {
        let _ = writeln!(out, "Start: ({},{}). End: ({},{}). ", l.x, l.y, r.x, r.y);
    }
    out
}

/// Ray-traces `scene` (the reference) and writes it to `out`; with `runs`,
/// times that many traces.
pub fn raytrace_to_file(
    scene: &Mesh,
    settings: &Settings,
    options: &raytrace::Options,
    out: &Path,
    runs: Option<usize>,
) -> Result<Option<Timing>, WriteError> {
    let (camera, light) = (settings.camera(), settings.light());
    let mut traced = raytrace::raytrace(scene, &camera, &light, options);
    let timing = runs.map(|n| {
        time_runs(n, || {
            traced = raytrace::raytrace(scene, &camera, &light, options)
        })
    });
    write_png(&traced.frame, out)?;
    Ok(timing)
}

/// The processor and core count, for saying where a report was made.
pub fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| "an unknown processor".into());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    format!("{cpu}, {cores} cores (one used)")
}

/// `rasterlab report`: measures, then writes report.md, report.csv and
/// error-vs-time.png into `dir`. Progress lines go to `progress`.
pub fn report(
    dir: &Path,
    quick: bool,
    scene: &Scene,
    pose: &crate::scene::Pose,
    mut progress: impl FnMut(&str),
) -> Result<Vec<PathBuf>, WriteError> {
    let plan = if quick {
        report::Plan::quick()
    } else {
        report::Plan::full()
    };
    // Find an unwritable folder before the minute of measuring, not after it.
    let fail = |e: std::io::Error| WriteError {
        path: dir.to_path_buf(),
        reason: e.to_string(),
    };
    std::fs::create_dir_all(dir).map_err(fail)?;
    let probe = dir.join(format!(".rasterlab-write-check.{}", std::process::id()));
    std::fs::write(&probe, b"").map_err(fail)?;
    let _ = std::fs::remove_file(&probe);
    let rows = report::measure_all(&plan, scene, pose, &mut progress);
    let size = report::conclusion_size(&plan);
    let options = report::measure_options(scene, pose, size, plan.runs, &mut progress);
    let md = dir.join("report.md");
    let csv = dir.join("report.csv");
    let png = dir.join("error-vs-time.png");
    let mut text = report::markdown(&rows, &plan, &machine(), &scene.name);
    text.push_str(&report::options_markdown(&options));
    text.push_str("\n![Error against time](error-vs-time.png)\n");
    write_text(&md, &text)?;
    write_text(&csv, &report::csv(&[rows.as_slice(), &options].concat()))?;
    write_png(&report::plot(&rows, &plan), &png)?;
    let mut written = vec![md, csv, png];
    for (name, picture) in report::heat_maps(&plan, scene, pose) {
        let path = dir.join(name);
        write_png(&picture, &path)?;
        written.push(path);
    }
    Ok(written)
}

/// `rasterlab stress`: runs the catalogue, progress to `progress`; returns the
/// tables to print, how many cases failed and how many ran.
pub fn stress(quick: bool, progress: impl FnMut(&str)) -> (String, usize, usize) {
    let outcomes = stress::run_all(quick, progress);
    let text = format!(
        "{}\nLong spans, largest distance from the exact position:\n\n{}",
        stress::table(&outcomes),
        stress::drift_table(&stress::DRIFT_SPANS)
    );
    let failed = outcomes.iter().filter(|o| !o.pass).count();
    (text, failed, outcomes.len())
}
