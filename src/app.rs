//! What the subcommands do, apart from parsing: build the scene, camera and light
//! from the settings, draw, time and write files.

use crate::camera::Camera;
use crate::image_io::{write_png, write_rgb_png, WriteError};
use crate::interpolate::Pixel;
use crate::light::Light;
use crate::overview::overview;
use crate::polygon::{compute_polygon_rows, Clip, Rows};
use crate::raytrace;
use crate::render::Frame;
use crate::report;
use crate::scene::{cornell_box, Triangle};
use crate::stage::View;
use crate::timing::{time_runs, Timing};
use glam::Vec3;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Everything a render depends on besides the stage; the defaults are the course
/// skeleton's (design notes).
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
            near: crate::camera::DEFAULT_NEAR,
            clip: true,
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
}

/// Draws `view` of the Cornell box; with `runs`, draws it that many times and
/// reports the timing (drawing only, no file I/O).
pub fn render(view: View, settings: &Settings, runs: Option<usize>) -> (Frame, Option<Timing>) {
    let scene: Vec<Triangle> = cornell_box();
    let camera = settings.camera();
    let mut rasterizer = view.rasterizer(settings.light());
    let mut frame = Frame::default();
    rasterizer.draw(&scene, &camera, &mut frame);
    let timing = runs.map(|n| time_runs(n, || rasterizer.draw(&scene, &camera, &mut frame)));
    (frame, timing)
}

/// Draws `view` and writes it to `out`.
pub fn render_to_file(
    view: View,
    settings: &Settings,
    out: &Path,
    runs: Option<usize>,
) -> Result<Option<Timing>, WriteError> {
    let (frame, timing) = render(view, settings, runs);
    write_png(&frame, out)?;
    Ok(timing)
}

/// The overview's file name.
pub const OVERVIEW_FILE: &str = "fig1-overview.png";

/// Writes every figure, and the overview, into `dir` (created if missing).
/// Returns the paths written, in order.
pub fn render_all(settings: &Settings, dir: &Path) -> Result<Vec<PathBuf>, WriteError> {
    std::fs::create_dir_all(dir).map_err(|e| WriteError {
        path: dir.to_path_buf(),
        reason: e.to_string(),
    })?;
    let mut written = Vec::new();
    let mut frames = Vec::new();
    for view in View::FIGURES {
        let (frame, _) = render(view, settings, None);
        let path = dir.join(view.figure_file());
        write_png(&frame, &path)?;
        written.push(path);
        frames.push(frame);
    }
    let (w, h, rgb) = overview(&frames).expect("all figures share one size");
    let path = dir.join(OVERVIEW_FILE);
    write_rgb_png(&rgb, w, h, &path)?;
    written.push(path);
    Ok(written)
}

/// `ComputePolygonRows` for a polygon given as pixels, printed as the handout's
/// test program does: `Start: (x,y). End: (x,y). ` on one line per row.
pub fn rows_text(vertices: &[(i32, i32)]) -> String {
    let pixels: Vec<Pixel<()>> = vertices.iter().map(|&(x, y)| Pixel::at(x, y)).collect();
    let mut rows = Rows::new();
    compute_polygon_rows(&pixels, &Clip::unbounded(), &mut rows);
    let mut out = String::new();
    for (l, r) in rows.left.iter().zip(&rows.right) {
        let _ = writeln!(out, "Start: ({},{}). End: ({},{}). ", l.x, l.y, r.x, r.y);
    }
    out
}

/// Ray-traces the Cornell box (the reference) and writes it to `out`; with `runs`,
/// times that many traces.
pub fn raytrace_to_file(
    settings: &Settings,
    options: &raytrace::Options,
    out: &Path,
    runs: Option<usize>,
) -> Result<Option<Timing>, WriteError> {
    let scene = cornell_box();
    let (camera, light) = (settings.camera(), settings.light());
    let mut traced = raytrace::raytrace(&scene, &camera, &light, options);
    let timing = runs.map(|n| {
        time_runs(n, || {
            traced = raytrace::raytrace(&scene, &camera, &light, options)
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
    progress: impl FnMut(&str),
) -> Result<Vec<PathBuf>, WriteError> {
    let plan = if quick {
        report::Plan::quick()
    } else {
        report::Plan::full()
    };
    let rows = report::measure_all(&plan, progress);
    report::write_report(&rows, &plan, dir, &machine())
}
