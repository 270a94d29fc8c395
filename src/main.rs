//! The `rasterlab` command: parses arguments and calls the library.

use clap::{Args, Parser, Subcommand};
use glam::Vec3;
use rasterlab::app::{self, controls, parse, viewer, Settings};
use rasterlab::measure::raytrace;
use rasterlab::{Figure, StageName};
use std::path::PathBuf;
use std::process::ExitCode;

/// A CPU rasterizer that reproduces the DH2323 lab 3 handout, stage by stage.
///
/// Each stage subcommand draws the Cornell box as one section of the handout does
/// and writes a PNG. `rasterlab all --out figures` writes every figure.
#[derive(Parser, Debug)]
#[command(name = "rasterlab", version)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Section 2: the projected vertices as white points (Figure 2).
    Points(Render),
    /// Section 3: the triangles' edges as white lines (Figure 3).
    Wireframe(Render),
    /// Section 4: triangles filled in scene order, no depth test (Figure 4).
    Filled(Render),
    /// Section 5: filled triangles behind a depth buffer of 1/z (Figure 5).
    Depth(Interpolating),
    /// Section 6.1: equations 10 and 11 at each vertex, interpolated (Figure 6).
    VertexLight(Interpolating),
    /// Section 6.2: equations 10 and 11 at each pixel (Figure 7; Figure 8 with --affine).
    PixelLight(Interpolating),
    /// Every figure (fig2 to fig8) and fig1-overview.png, all stages side by side.
    All(AllArgs),
    /// The reference: ray-traces the same scene, one ray per pixel centre (lab 2).
    ///
    /// Nearest hit, equations 10 and 11 with the same code as the rasterizer; with
    /// --shadows a hit that cannot see the light gets only indirect light.
    Raytrace(RaytraceArgs),
    /// Measures every stage against the ray tracer: error and draw time, as
    /// report.md, report.csv and error-vs-time.png.
    Report(ReportArgs),
    /// Runs the catalogue of hard cases and prints a table: NaN and infinity
    /// counts, panics, error against the ray tracer with its bound, draw time.
    ///
    /// Exits with 1 if any case fails. docs/stability.md explains each case.
    Stress(StressArgs),
    /// Opens a window on a stage; walk with the arrows, move the light with a/w/s/d.
    ///
    /// Keys: up/down move, left/right turn, pageup/pagedown (or r/f) look up/down, left
    /// mouse button + drag looks around; a/d, w/s, q/e move the light along x, z, y;
    /// 1-7 switch figures (7 = pixel-light --affine); p toggles perspective-correct
    /// interpolation; c saves a PNG; h prints the keys; Esc quits. On exit the
    /// command that renders the last frame to a file is printed on stderr.
    View(ViewArgs),
    /// Prints ComputePolygonRows for a convex polygon, as the handout's section 4 test.
    ///
    /// Example: `rasterlab rows 10,5 5,10 15,15` prints the handout's 11 rows.
    Rows(RowsArgs),
}

/// The view: image size, camera and light. Vectors are X,Y,Z and may be negative.
#[derive(Args, Debug)]
struct SceneArgs {
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, value_name = "WxH", default_value = "500x500", value_parser = parse::size)]
    size: (u32, u32),
    /// Focal length f in pixels (eq. 1 to 4).
    #[arg(long, value_name = "F", default_value = "500", value_parser = parse::positive,
          allow_hyphen_values = true)]
    focal: f32,
    /// Camera position C (eq. 5) in world space; y points down.
    #[arg(long, value_name = "X,Y,Z", default_value = "0,0,-3.001",
          value_parser = parse::vec3, allow_hyphen_values = true)]
    camera: Vec3,
    /// Turn about the y-axis, in degrees; positive turns right.
    #[arg(long, value_name = "DEG", default_value = "0", value_parser = parse::finite,
          allow_hyphen_values = true)]
    yaw: f32,
    /// Tilt, in degrees; positive looks up.
    #[arg(long, value_name = "DEG", default_value = "0", value_parser = parse::finite,
          allow_hyphen_values = true)]
    pitch: f32,
    /// Light position (section 6.1).
    #[arg(long, value_name = "X,Y,Z", default_value = "0,-0.5,-0.7",
          value_parser = parse::vec3, allow_hyphen_values = true)]
    light: Vec3,
    /// Light power P of eq. 10, the same in each channel (lab 2 used 14).
    #[arg(long, value_name = "P", default_value = "1.1", value_parser = parse::finite,
          allow_hyphen_values = true)]
    light_power: f32,
    /// Indirect light N of eq. 11, the same in each channel.
    #[arg(long, value_name = "N", default_value = "0.5", value_parser = parse::finite,
          allow_hyphen_values = true)]
    indirect: f32,
    /// Near clipping plane: geometry closer to the camera than Z is cut away.
    #[arg(long, value_name = "Z", default_value = "0.01", value_parser = parse::positive,
          allow_hyphen_values = true)]
    near: f32,
    /// Draw as the handout does, without clipping: a triangle with a corner behind
    /// the camera is projected through it and drawn wrong (but never out of bounds).
    #[arg(long)]
    no_clip: bool,
}

impl SceneArgs {
    fn settings(&self) -> Settings {
        Settings {
            width: self.size.0,
            height: self.size.1,
            focal: self.focal,
            camera: self.camera,
            yaw: self.yaw,
            pitch: self.pitch,
            light: self.light,
            light_power: self.light_power,
            indirect: self.indirect,
            near: self.near,
            clip: !self.no_clip,
        }
    }
}

#[derive(Args, Debug)]
struct Render {
    /// Output PNG [default: <stage>.png]
    #[arg(short, long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Also render N times and print the median render time on stderr (no file I/O timed).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=100_000))]
    time: Option<u32>,
    #[command(flatten)]
    scene: SceneArgs,
}

#[derive(Args, Debug)]
struct Interpolating {
    /// Interpolate linearly in screen space, without perspective correction.
    #[arg(long)]
    affine: bool,
    #[command(flatten)]
    render: Render,
}

#[derive(Args, Debug)]
struct AllArgs {
    /// Folder for the figures (created if missing).
    #[arg(long, value_name = "DIR", default_value = "figures")]
    out: PathBuf,
    #[command(flatten)]
    scene: SceneArgs,
}

#[derive(Args, Debug)]
struct RaytraceArgs {
    /// Cast a shadow ray to the light from every hit.
    #[arg(long)]
    shadows: bool,
    /// N x N rays per pixel, spread over the pixel (anti-aliasing).
    #[arg(long, value_name = "N", default_value = "1",
          value_parser = clap::value_parser!(u32).range(1..=16))]
    samples: u32,
    /// The nearest triangle's flat colour instead of light (what filled and depth mean).
    #[arg(long)]
    flat: bool,
    #[command(flatten)]
    render: Render,
}

#[derive(Args, Debug)]
struct ReportArgs {
    /// Folder for report.md, report.csv and error-vs-time.png (created if missing).
    #[arg(long, value_name = "DIR", default_value = "report")]
    out: PathBuf,
    /// A small, fast version (two small sizes, k = 1 and 2, two runs each).
    #[arg(long)]
    quick: bool,
}

#[derive(Args, Debug)]
struct StressArgs {
    /// Leave out the 16000 x 16000 case (the slowest) and time one draw per case.
    #[arg(long)]
    quick: bool,
}

#[derive(Args, Debug)]
struct ViewArgs {
    /// The stage to show first: points, wireframe, filled, depth, vertex-light, pixel-light.
    #[arg(value_name = "STAGE", default_value = "pixel-light", value_parser = parse::stage)]
    stage: StageName,
    /// Start with affine (not perspective-correct) interpolation.
    #[arg(long)]
    affine: bool,
    /// Quit after N frames.
    #[arg(long, value_name = "N")]
    frames: Option<u64>,
    /// Save the last frame to FILE when quitting.
    #[arg(long, value_name = "FILE")]
    screenshot: Option<PathBuf>,
    /// Replay keys frame by frame, e.g. "right*30,w*10,up+left*5" (1/60 s per frame).
    #[arg(long, value_name = "SCRIPT")]
    keys: Option<controls::Script>,
    /// Frames per second to aim for; 0 draws as fast as it can.
    #[arg(long, value_name = "N", default_value = "60")]
    fps: usize,
    #[command(flatten)]
    scene: SceneArgs,
}

#[derive(Args, Debug)]
struct RowsArgs {
    /// The polygon's vertices as X,Y pixels, in order (either winding).
    #[arg(required = true, value_name = "X,Y", value_parser = parse::point,
          allow_hyphen_values = true)]
    vertices: Vec<(i32, i32)>,
}

fn render(stage: StageName, affine: bool, args: &Render) -> Result<(), String> {
    let view = Figure { stage, affine };
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("{}.png", stage.name())));
    let settings = args.scene.settings();
    let timing = app::render_to_file(view, &settings, &out, args.time.map(|n| n as usize))
        .map_err(|e| e.to_string())?;
    if let Some(t) = timing {
        eprintln!("render: {t}");
    }
    eprintln!("wrote {}", out.display());
    Ok(())
}

fn run(cli: Cli) -> Result<(), String> {
    match &cli.command {
        Command::Points(a) => render(StageName::Points, false, a),
        Command::Wireframe(a) => render(StageName::Wireframe, false, a),
        Command::Filled(a) => render(StageName::Filled, false, a),
        Command::Depth(a) => render(StageName::Depth, a.affine, &a.render),
        Command::VertexLight(a) => render(StageName::VertexLight, a.affine, &a.render),
        Command::PixelLight(a) => render(StageName::PixelLight, a.affine, &a.render),
        Command::All(a) => {
            for path in app::render_all(&a.scene.settings(), &a.out).map_err(|e| e.to_string())? {
                eprintln!("wrote {}", path.display());
            }
            Ok(())
        }
        Command::Raytrace(a) => {
            let options = raytrace::Options {
                shading: if a.flat {
                    raytrace::Shading::Flat
                } else {
                    raytrace::Shading::Lit
                },
                shadows: a.shadows,
                samples: a.samples,
                near: None,
            };
            let out = a
                .render
                .out
                .clone()
                .unwrap_or_else(|| PathBuf::from("raytrace.png"));
            let timing = app::raytrace_to_file(
                &a.render.scene.settings(),
                &options,
                &out,
                a.render.time.map(|n| n as usize),
            )
            .map_err(|e| e.to_string())?;
            if let Some(t) = timing {
                eprintln!("render: {t}");
            }
            eprintln!("wrote {}", out.display());
            Ok(())
        }
        Command::Report(a) => {
            let written = app::report(&a.out, a.quick, |line| eprintln!("{line}"))
                .map_err(|e| e.to_string())?;
            for path in written {
                eprintln!("wrote {}", path.display());
            }
            Ok(())
        }
        Command::Stress(a) => {
            let (tables, failed, total) = app::stress(a.quick, |line| eprintln!("{line}"));
            println!("{tables}");
            if failed > 0 {
                return Err(format!("{failed} of {total} stress cases failed"));
            }
            Ok(())
        }
        Command::View(a) => {
            let options = viewer::Options {
                settings: a.scene.settings(),
                view: controls::view_of(a.stage, a.affine),
                frames: a.frames,
                screenshot: a.screenshot.clone(),
                script: a.keys.clone().unwrap_or_default().0,
                fps: a.fps,
            };
            let summary = viewer::run(options)?;
            eprintln!(
                "view: {} frames, frame time median {:.2} ms, draw median {:.2} ms",
                summary.frames,
                summary.frame_median.as_secs_f64() * 1e3,
                summary.draw_median.as_secs_f64() * 1e3
            );
            eprintln!("view: last frame: {}", summary.reproduce());
            Ok(())
        }
        Command::Rows(a) => {
            print!("{}", app::rows_text(&a.vertices));
            Ok(())
        }
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            // Plain `rasterlab`: the help, but as the usage error it is.
            let _ = e.print();
            return ExitCode::from(2);
        }
        Err(e) if !e.use_stderr() => {
            // --help and --version: clap prints them in full.
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            // One line: clap's message up to its usage block, joined; the usage is in --help.
            let text = e.render().to_string();
            let message: Vec<&str> = text
                .lines()
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            eprintln!("{} (see 'rasterlab --help')", message.join(" "));
            return ExitCode::from(2);
        }
    };
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(1)
        }
    }
}
