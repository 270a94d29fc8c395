//! The application: what the subcommands do apart from parsing (build the scene,
//! camera and light from the settings, draw, time and write files), image files,
//! Figure 1, and the viewer.

pub mod check;
pub mod cli;
pub mod controls;
pub mod explain;
pub mod figure;
pub mod image_io;
pub mod overview;
pub mod parallel;
pub mod parse;
pub mod progress;
pub mod report;
pub mod streams;
pub mod stress;
pub mod viewer;

use crate::app::figure::{Figure, Inputs};
use crate::extensions::depth_of_field::DepthOfField;
use crate::extensions::texture::{Filter, Model};
use crate::measure::plot::Canvas;
use crate::measure::raytrace;
use crate::measure::timing::{time_runs, Timing};
use crate::pipeline::camera::DEFAULT_NEAR;
use crate::pipeline::draw::Stats;
use crate::pipeline::interpolate::Pixel;
use crate::pipeline::raster::rows::{compute_polygon_rows, Rows};
use crate::pipeline::raster::Bounds;
use crate::pipeline::{Camera, Frame, Light, Mesh};
use crate::scene::Scene;
use image_io::{write_image, WriteError};
use overview::figure_one;
use progress::Progress;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Everything a render depends on besides the stage and the scene; the defaults
/// are the course skeleton's (`Camera::handout`, `Light::handout`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Where it stands, where it looks, the focal length, the image's size and
    /// the near plane (`None` draws without clipping, as the handout does:
    /// `--no-clip`).
    pub camera: Camera,
    pub light: Light,
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
        Settings {
            camera: Camera::handout(500, 500),
            light: Light::handout(),
            threads: 1,
            filter: Filter::Nearest,
            dof: None,
        }
    }
}

impl Settings {
    /// What a frame's stage reads: the light, and the maps of `model` read
    /// with `--filter` from the camera's position.
    pub fn inputs<'a>(&self, model: Model<'a>) -> Inputs<'a> {
        Inputs {
            maps: model.maps,
            filter: self.filter,
            eye: self.camera.position,
            ..Inputs::lit(self.light)
        }
    }
}

/// Draws `figure` of `mesh`; with `runs`, draws it that many times and reports the
/// timing (drawing only, no file I/O).
pub fn render<'a>(
    figure: Figure,
    model: impl Into<Model<'a>>,
    settings: &Settings,
    runs: Option<usize>,
) -> (Frame, Option<Timing>) {
    let (frame, timing, _) = render_with_stats(figure, model.into(), settings, runs);
    (frame, timing)
}

/// [`render`], with what the frame did.
pub fn render_with_stats(
    figure: Figure,
    model: Model,
    settings: &Settings,
    runs: Option<usize>,
) -> (Frame, Option<Timing>, Stats) {
    render_into(figure, model, settings, runs, Frame::default())
}

/// [`render_with_stats`] into `frame`, whose buffers are reused when they have
/// the image's size.
fn render_into(
    figure: Figure,
    model: Model,
    settings: &Settings,
    runs: Option<usize>,
    mut frame: Frame,
) -> (Frame, Option<Timing>, Stats) {
    // No threads to be had: one band, on this thread.
    let mut pipeline = parallel::Parallel::new(figure, model, settings.threads)
        .or_else(|_| parallel::Parallel::new(figure, model, 1))
        .expect("one band needs no thread");
    draw_frame(&mut pipeline, figure, model, settings, &mut frame);
    let stats = pipeline.stats();
    let timing = runs.map(|n| {
        time_runs(n, || {
            draw_frame(&mut pipeline, figure, model, settings, &mut frame)
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
    model: Model,
    settings: &Settings,
    frame: &mut Frame,
) {
    let near = settings.camera.near.unwrap_or(DEFAULT_NEAR);
    let shadow = figure.shadow_map(model.mesh, &settings.light, near);
    let inputs = Inputs {
        shadow: shadow.as_ref(),
        ..settings.inputs(model)
    };
    pipeline.render(&inputs, model.mesh, &settings.camera, frame);
    if let Some(dof) = settings.dof {
        dof.apply(frame, settings.camera.focal);
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
pub fn render_to_file<'a>(
    figure: Figure,
    model: impl Into<Model<'a>>,
    settings: &Settings,
    out: &Path,
    runs: Option<usize>,
    buffer: bool,
) -> Result<(Option<Timing>, Stats), WriteError> {
    let model = model.into();
    // The depth buffer's picture is drawn on a canvas of its own (4 bytes a pixel).
    let picture = if buffer { 4 } else { 0 };
    let frame = frame_for(settings, picture, out)?;
    let (frame, timing, stats) = render_into(figure, model, settings, runs, frame);
    match buffer {
        true => write_image(&depth_buffer_picture(&frame), out)?,
        false => write_image(&frame, out)?,
    }
    Ok((timing, stats))
}

/// A frame of the settings' size with a depth buffer, allocated before drawing
/// so that too large a size is refused with what it needs instead of aborting.
/// `more` bytes a pixel are asked for besides, for what is made from the frame.
fn frame_for(settings: &Settings, more: usize, out: &Path) -> Result<Frame, WriteError> {
    let (w, h) = (settings.camera.width, settings.camera.height);
    // Colour and depth (4 + 4 bytes a pixel), then the 8-bit rows written (3);
    // depth of field sums each channel over the image (three u64s a pixel).
    let blur = match settings.dof {
        Some(_) => 24,
        None => 0,
    };
    reserve(out, w, h, 11 + blur + more, "drawing and writing")?;
    Frame::try_new(w, h, true).map_err(|why| WriteError::new(out, why))
}

/// Refuses, with the memory it needs, a `width` x `height` image that needs
/// `per_pixel` bytes a pixel for `what` when that much cannot be had: asked for
/// at once (and given back), so that the work that follows does not abort half
/// way through.
fn reserve(
    out: &Path,
    width: u32,
    height: u32,
    per_pixel: usize,
    what: &str,
) -> Result<(), WriteError> {
    let bytes = (width as usize * height as usize).saturating_mul(per_pixel);
    match crate::pipeline::target::memory_for(bytes) {
        true => Ok(()),
        false => {
            let need = crate::pipeline::target::megabytes(bytes);
            Err(WriteError::new(
                out,
                format!("out of memory: {what} a {width}x{height} image needs {need}"),
            ))
        }
    }
}

/// Writes `mesh` as an OBJ file at `path` and its materials as an MTL file
/// beside it (same name, `.mtl`): both paths are checked and both files written
/// in full before either is renamed into place ([`crate::scene::obj_text`]).
pub fn export_obj(mesh: &Mesh, path: &Path) -> Result<(), WriteError> {
    let mtl_path = path.with_extension("mtl");
    let (Some(_), Some(mtl_name)) = (path.file_name(), mtl_path.file_name()) else {
        return Err(WriteError::new(path, "not a file name"));
    };
    // `mtllib NAME` loads back only a name without spaces at its ends or
    // control characters: the reader takes the rest of its line, trimmed.
    let name = mtl_name.to_string_lossy();
    if name.trim() != name || name.chars().any(char::is_control) {
        return Err(WriteError::new(
            path,
            "the .mtl beside it would be named in a way the OBJ cannot name it (spaces at the ends, or a control character)",
        ));
    }
    let (obj, mtl) =
        crate::scene::obj_text(mesh, &name).map_err(|why| WriteError::new(path, why))?;
    let mut files = image_io::AllOrNone::default();
    files.bytes(&mtl_path, mtl.as_bytes())?;
    files.bytes(path, obj.as_bytes())?;
    files.commit()
}

/// The image built up triangle by triangle: frame i shows the first i triangles of
/// `mesh` drawn (about `max_frames` frames: several triangles a frame for larger
/// meshes), so the order of drawing can be seen, Figure 4's mistake included.
/// Each frame is allocated before it is drawn, so too large a size is refused
/// with what the frames need.
pub fn build_up<'a>(
    figure: Figure,
    model: impl Into<Model<'a>>,
    settings: &Settings,
    max_frames: usize,
) -> Result<Vec<Frame>, String> {
    let model = model.into();
    let mesh = model.mesh;
    let faces = mesh.faces.len();
    let per_frame = faces.div_ceil(max_frames.max(1)).max(1);
    let mut frames = Vec::new();
    let mut pipeline = parallel::Parallel::new(figure, model, settings.threads)
        .or_else(|_| parallel::Parallel::new(figure, model, 1))
        .expect("one band needs no thread");
    let camera = settings.camera;
    // One copy of the mesh whose faces grow: no copy of the vertices per frame.
    let mut prefix = Mesh {
        faces: Vec::with_capacity(faces),
        ..mesh.clone()
    };
    let count = faces.div_ceil(per_frame);
    let depth = pipeline.depth_test();
    let (w, h) = (settings.camera.width, settings.camera.height);
    while prefix.faces.len() < faces {
        let k = (prefix.faces.len() + per_frame).min(faces);
        prefix
            .faces
            .extend_from_slice(&mesh.faces[prefix.faces.len()..k]);
        let mut frame = Frame::try_new(w, h, depth).map_err(|why| {
            let each = (w as usize * h as usize) * if depth { 8 } else { 4 };
            let all = crate::pipeline::target::megabytes(each * count);
            format!("{why}; the animation's {count} frames need {all}")
        })?;
        pipeline.render(&settings.inputs(model), &prefix, &camera, &mut frame);
        frames.push(frame);
    }
    Ok(frames)
}

/// The largest side `animate` draws: its frames are all kept (8 bytes a pixel
/// with depth) and each encoded on its own, about a second for 30 frames at
/// 1024x1024 here, so 16384x16384 would take minutes and 60 GB.
pub const MAX_ANIMATE_SIDE: u32 = 2048;

/// Whether `animate` draws a `width` x `height` image; if not, why.
pub fn animation_size(width: u32, height: u32) -> Result<(), String> {
    match width.max(height) <= MAX_ANIMATE_SIDE {
        true => Ok(()),
        false => Err(format!(
            "animate draws at most {MAX_ANIMATE_SIDE} pixels a side, not {width}x{height} (it keeps and encodes every frame); a stage command draws the finished image at that size"
        )),
    }
}

/// `rasterlab animate`: [`build_up`] of `mesh` written as a GIF that
/// shows each triangle for `delay_ms` and the finished image for two seconds.
pub fn animate_to_file<'a>(
    figure: Figure,
    model: impl Into<Model<'a>>,
    settings: &Settings,
    out: &Path,
    delay_ms: u32,
) -> Result<usize, WriteError> {
    let model = model.into();
    let frames = build_up(figure, model, settings, 60).map_err(|why| WriteError::new(out, why))?;
    let fail = |e: image::ImageError| WriteError::new(out, e.to_string());
    let mut bytes = Vec::new();
    {
        let mut encoder = image::codecs::gif::GifEncoder::new_with_speed(&mut bytes, 10);
        encoder
            .set_repeat(image::codecs::gif::Repeat::Infinite)
            .map_err(fail)?;
        let last = frames.len().saturating_sub(1);
        for (i, frame) in frames.iter().enumerate() {
            let mut rgba = Vec::new();
            rgba.try_reserve_exact(frame.color.len() * 4)
                .map_err(|_| WriteError::new(out, "out of memory for a frame of the GIF"))?;
            rgba.extend(
                frame
                    .color
                    .iter()
                    .flat_map(|&c| crate::pipeline::target::unpack(c).into_iter().chain([255])),
            );
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
/// Returns the paths written, in order. The memory all of it needs is asked
/// for first, and the files are renamed into place only once every one is
/// written ([`image_io::AllOrNone`]): a failure leaves the folder as it was.
pub fn render_all(
    model: Model,
    settings: &Settings,
    dir: &Path,
) -> Result<Vec<PathBuf>, WriteError> {
    let (w, h) = (settings.camera.width, settings.camera.height);
    reserve(
        dir,
        w,
        h,
        ALL_BYTES_A_PIXEL,
        "the seven figures and their overview for",
    )?;
    let folder = create_folder(dir)?;
    let mut files = image_io::AllOrNone::default();
    let mut written = Vec::new();
    let mut frames = Vec::new();
    for figure in Figure::FIGURES {
        let frame = frame_for(settings, 0, dir)?;
        let (frame, _, _) = render_into(figure, model, settings, None, frame);
        let path = dir.join(figure.figure_file());
        files.image(&frame, &path)?;
        written.push(path);
        // The overview needs the colours only.
        frames.push(Frame {
            depth: Vec::new(),
            ..frame
        });
    }
    let path = dir.join(OVERVIEW_FILE);
    let overview = figure_one(frames).map_err(|why| WriteError::new(&path, why))?;
    files.image(&overview, &path)?;
    files.commit()?;
    folder.keep();
    written.push(path);
    Ok(written)
}

/// The most memory [`render_all`] holds at once, in bytes a pixel of a figure:
/// measured, 65 (the peak resident size at 2048x2048, 272 MB: seven figures'
/// colours, the points dilated, the heat map, the overview's 4 x 2 panels and
/// its 8-bit rows), with a tenth more for room.
const ALL_BYTES_A_PIXEL: usize = 72;

/// Creates the folder `dir` (and its parents) if missing; a file in its place
/// is named as such rather than as the system's "File exists". Nothing is made
/// through a link another user planted ([`image_io`]'s rules). The folders it
/// made are taken away again, if still empty, unless [`MadeFolder::keep`] is
/// called: a command that could write nothing leaves nothing behind.
pub fn create_folder(dir: &Path) -> Result<MadeFolder, WriteError> {
    image_io::refuse_planted_links(dir)?;
    if dir.exists() && !dir.is_dir() {
        return Err(WriteError::new(dir, "not a folder"));
    }
    // Deepest first, as they are taken away.
    let made = dir
        .ancestors()
        .take_while(|d| !d.as_os_str().is_empty() && !d.exists())
        .map(Path::to_path_buf)
        .collect();
    std::fs::create_dir_all(dir)
        .map(|()| MadeFolder { made })
        .map_err(|e| {
            let why = match e.kind() {
                std::io::ErrorKind::AlreadyExists | std::io::ErrorKind::NotADirectory => {
                    "a part of it is not a folder".to_string()
                }
                _ => e.to_string(),
            };
            WriteError::new(dir, why)
        })
}

/// The folders [`create_folder`] made, taken away when dropped if they are
/// still empty (never a folder with anything in it).
#[must_use = "dropped, it takes the folders away again"]
pub struct MadeFolder {
    made: Vec<PathBuf>,
}

impl MadeFolder {
    /// Keeps the folders: the command wrote into them.
    pub fn keep(mut self) {
        self.made.clear();
    }
}

impl Drop for MadeFolder {
    fn drop(&mut self) {
        for dir in &self.made {
            // Fails, and so keeps it, where anything is inside.
            let _ = std::fs::remove_dir(dir);
        }
    }
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
pub fn raytrace_to_file<'a>(
    scene: impl Into<Model<'a>>,
    settings: &Settings,
    options: &raytrace::Options,
    out: &Path,
    runs: Option<usize>,
) -> Result<Option<Timing>, WriteError> {
    let scene = scene.into();
    // Too large an image is refused here, with what it needs, not aborted on.
    // The frame (4 bytes a pixel), each pixel's hit (8) and the rows written (3).
    reserve(
        out,
        settings.camera.width,
        settings.camera.height,
        15,
        "ray-tracing and writing",
    )?;
    let (camera, light) = (settings.camera, settings.light);
    let mut traced = raytrace::raytrace(scene, &camera, &light, options);
    let timing = runs.map(|n| {
        time_runs(n, || {
            traced = raytrace::raytrace(scene, &camera, &light, options)
        })
    });
    write_image(&traced.frame, out)?;
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
    match cores {
        1 => format!("{cpu}, 1 core"),
        n => format!("{cpu}, {n} cores (one used)"),
    }
}

/// `rasterlab report`: measures, then writes report.md, report.csv and
/// error-vs-time.png into `dir`, telling `progress` as each row is measured.
pub fn report(
    dir: &Path,
    quick: bool,
    scene: &Scene,
    view: &Settings,
    progress: &mut Progress,
) -> Result<Vec<PathBuf>, WriteError> {
    let plan = if quick {
        report::Plan::quick()
    } else {
        report::Plan::full()
    };
    // Find an unwritable folder before the minute of measuring, not after it.
    let folder = create_folder(dir)?;
    // Created exclusively under a random name, removed when dropped.
    tempfile::Builder::new()
        .prefix(".rasterlab-")
        .tempfile_in(dir)
        .map_err(|e| WriteError::new(dir, e.to_string()))?;
    let rows = report::measure_all(&plan, scene, view, progress);
    let size = report::conclusion_size(&plan);
    let options = report::measure_options(scene, view, size, plan.runs, progress);
    let md = dir.join("report.md");
    let csv = dir.join("report.csv");
    let png = dir.join("error-vs-time.png");
    let mut text = report::markdown(&rows, &plan, &machine(), &scene.name);
    text.push_str(&report::options_markdown(&options));
    text.push_str("\n![Error against time](error-vs-time.png)\n");
    // Renamed into place together: a file that cannot be written leaves the
    // folder's last report whole.
    let mut files = image_io::AllOrNone::default();
    files.bytes(&md, text.as_bytes())?;
    let table = report::csv(&[rows.as_slice(), &options].concat());
    files.bytes(&csv, table.as_bytes())?;
    files.image(&report::plot(&rows, &plan), &png)?;
    let mut written = vec![md, csv, png];
    for (name, picture) in report::heat_maps(&plan, scene, view) {
        let path = dir.join(name);
        files.image(&picture, &path)?;
        written.push(path);
    }
    files.commit()?;
    folder.keep();
    Ok(written)
}

/// `rasterlab stress`: runs the catalogue, progress to `progress`; returns the
/// tables to print, how many cases failed and how many ran.
/// The most memory the full catalogue needs, as address space: its 16000 x 16000
/// case draws into 2 GB of colour and depth. Measured: the run passes under
/// `ulimit -v 3300000` and aborts under 3000000; `--quick` peaks at 18 MB.
pub const STRESS_MEMORY: usize = 3_200_000_000;

/// Refuses the full catalogue up front, with what it needs, when that much memory
/// cannot be had, instead of aborting half way through it.
pub fn stress_fits(quick: bool) -> Result<(), String> {
    match quick || crate::pipeline::target::memory_for(STRESS_MEMORY) {
        true => Ok(()),
        false => Err(format!(
            "out of memory: stress needs about {} of memory (its 16000 x 16000 case); stress --quick needs about 20 MB",
            crate::pipeline::target::megabytes(STRESS_MEMORY)
        )),
    }
}

pub fn stress(quick: bool, progress: &mut Progress) -> (String, usize, usize) {
    let outcomes = stress::run_all(quick, progress);
    let text = format!(
        "{}\nLong spans, largest distance from the exact position:\n\n{}",
        stress::table(&outcomes),
        stress::drift_table(&stress::DRIFT_SPANS)
    );
    let failed = outcomes.iter().filter(|o| !o.pass).count();
    (text, failed, outcomes.len())
}
