//! The `rasterlab` command: parses arguments and calls the library.

use clap::parser::ValueSource;
use clap::{ArgMatches, Args, CommandFactory, FromArgMatches, Parser, Subcommand};
use glam::Vec3;
use rasterlab::app::{self, controls, explain, parse, viewer, Settings};
use rasterlab::extensions::shadow::Shadows;
use rasterlab::extensions::texture::Filter;
use rasterlab::measure::figure::Raster;
use rasterlab::measure::raytrace;
use rasterlab::pipeline::draw::Cull;
use rasterlab::pipeline::raster::Lines;
use rasterlab::scene::texture::{
    apply_normal_map, apply_parallax, apply_texture, parse_normal_map, TextureSpec,
};
use rasterlab::scene::{framed_pose, parse_scene, Scene};
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
    Depth(Render),
    /// Section 6.1: equations 10 and 11 at each vertex, interpolated linearly on the
    /// screen (Figure 6).
    VertexLight(Render),
    /// Section 6.2: equations 10 and 11 at each pixel (Figure 7; Figure 8 with --affine).
    PixelLight(Render),
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
    /// Writes a scene as a Wavefront OBJ file with its MTL beside it (the design
    /// notes' conventions), so any scene can be loaded back or opened elsewhere.
    Export(ExportArgs),
    /// Draws a stage triangle by triangle into an animated GIF, so the order of
    /// drawing shows: Figure 4's mistake (`animate filled`) and its fix (`animate depth`).
    Animate(AnimateArgs),
    /// Draws the handout's algorithms on a magnified pixel grid: `explain line`
    /// (Interpolate) and `explain rows` (ComputePolygonRows, DrawPolygonRows).
    #[command(subcommand)]
    Explain(Explain),
    /// Prints ComputePolygonRows for a convex polygon, as the handout's section 4 test.
    ///
    /// Example: `rasterlab rows 10,5 5,10 15,15` prints the handout's 11 rows.
    Rows(RowsArgs),
    /// Checks your own lab: which stage a screenshot shows, the light that
    /// reproduces it, what was done differently from the handout, and where it
    /// still differs.
    ///
    /// `rasterlab check shot.png` reads a PNG or BMP of any size; `rasterlab check
    /// rows FILE 10,5 5,10 15,15` compares a printed ComputePolygonRows output
    /// instead. docs/check.md shows a report.
    ///
    /// Exit status, as diff and cmp: 0 when the image is the handout's figure
    /// within 2/255 at every pixel (or the rows are the handout's), 1 when it
    /// differs or is not a lab 3 image, 2 for trouble (bad usage, an input that
    /// cannot be read, an output that cannot be written).
    Check(CheckArgs),
}

/// The view: scene, image size, camera and light. Vectors are X,Y,Z and may be
/// negative.
#[derive(Args, Debug)]
struct SceneArgs {
    /// What to draw: cornell (the handout's box), cornell:K (each triangle split
    /// K x K), sphere:N, grid:N (about N triangles), or a model file PATH.obj.
    #[arg(long, value_name = "SCENE", default_value = "cornell")]
    scene: String,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, value_name = "WxH", default_value = "500x500", value_parser = parse::size,
          allow_hyphen_values = true)]
    size: (u32, u32),
    /// Focal length f in pixels (eq. 1 to 4).
    #[arg(long, value_name = "F", default_value = "500", value_parser = parse::focal,
          allow_hyphen_values = true)]
    focal: f32,
    /// Camera position C (eq. 5) in world space; y points down [default: 0,0,-3.001
    /// for the box; other scenes are framed, and the pose used is printed].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse::vec3, allow_hyphen_values = true)]
    camera: Option<Vec3>,
    /// Turn about the y-axis, in degrees; positive turns right.
    #[arg(long, value_name = "DEG", default_value = "0", value_parser = parse::finite,
          allow_hyphen_values = true)]
    yaw: f32,
    /// Tilt, in degrees; positive looks up [default: 0; a grid is looked down on
    /// from above].
    #[arg(long, value_name = "DEG", value_parser = parse::finite, allow_hyphen_values = true)]
    pitch: Option<f32>,
    /// Light position (section 6.1) [default: 0,-0.5,-0.7 for the box; for other
    /// scenes the same place relative to the scene, scaled].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse::vec3, allow_hyphen_values = true)]
    light: Option<Vec3>,
    /// Light power P of eq. 10, the same in each channel (lab 2 used 14) [default:
    /// 1.1 for the box; for other scenes scaled with the scene's size squared].
    #[arg(long, value_name = "P", value_parser = parse::non_negative, allow_hyphen_values = true)]
    light_power: Option<f32>,
    /// Indirect light N of eq. 11, the same in each channel.
    #[arg(long, value_name = "N", default_value = "0.5", value_parser = parse::non_negative,
          allow_hyphen_values = true)]
    indirect: f32,
    /// Near clipping plane: geometry closer to the camera than Z is cut away
    /// [default: 0.01; for a scene smaller than the box, scaled with its size].
    #[arg(long, value_name = "Z", value_parser = parse::positive, allow_hyphen_values = true)]
    near: Option<f32>,
    /// Draw as the handout does, without clipping: a triangle with a corner behind
    /// the camera is projected through it and drawn wrong (but never out of bounds).
    #[arg(long)]
    no_clip: bool,
    /// Threads drawing bands of the image; the image is the same for any number
    /// [default: all cores].
    #[arg(long, value_name = "N", value_parser = |s: &str| parse::whole(s, 1, 256),
          allow_hyphen_values = true)]
    threads: Option<u64>,
    /// Lit stages only: read each surface's reflectance from a texture: checker
    /// (a checker of each wall's colour; the box's blocks stay plain) or an image
    /// PATH. A model's own MTL map_Kd is used without this; none leaves it out.
    #[arg(long, value_name = "checker|none|PATH")]
    texture: Option<String>,
    /// How textures are read between texels.
    #[arg(long, value_enum, default_value = "nearest")]
    filter: FilterArg,
    /// Pixel-light only: tilt each pixel's normal by a tangent-space normal map,
    /// bumps (round domes) or an image PATH, on the surfaces --texture would cover.
    #[arg(long, value_name = "bumps|PATH")]
    normal_map: Option<String>,
    /// Pixel-light with --normal-map bumps: parallax, the texture coordinates
    /// moved along the view by the bumps' heights, so the bumps stand out of the
    /// surface and hide what lies behind them.
    #[arg(long)]
    parallax: bool,
    /// Depth, vertex-light and pixel-light: depth of field, a blur that follows
    /// each pixel's circle of confusion, focused at depth FOCUS with a lens of
    /// radius APERTURE (world units).
    #[arg(long, value_name = "FOCUS,APERTURE", value_parser = parse::dof,
          allow_hyphen_values = true)]
    dof: Option<rasterlab::extensions::depth_of_field::DepthOfField>,
}

/// How textures are read between texels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum FilterArg {
    /// The texel containing the point.
    Nearest,
    /// The four nearest texel centres, weighted.
    Bilinear,
}

impl SceneArgs {
    /// The scene and the settings to draw it with: what the command line gives,
    /// and where it gives no camera or light, the framing of the scene (printed, so
    /// the image can be made again with explicit options).
    fn resolve(&self) -> Result<(Scene, Settings), Failure> {
        let mut scene = load_scene(&self.scene)?;
        if let Some(spec) = &self.texture {
            apply_texture(&mut scene, &TextureSpec::parse(spec)).map_err(Failure::Run)?;
        }
        if let Some(spec) = &self.normal_map {
            let map = parse_normal_map(spec).map_err(Failure::Run)?;
            apply_normal_map(&mut scene, map);
        }
        if self.parallax {
            if self.normal_map.as_deref() != Some("bumps") {
                return Err(Failure::Usage(
                    "--parallax needs --normal-map bumps: only the bumps come with heights".into(),
                ));
            }
            apply_parallax(&mut scene);
        }
        let mut settings = Settings {
            width: self.size.0,
            height: self.size.1,
            focal: self.focal,
            yaw: self.yaw,
            pitch: self.pitch.unwrap_or(scene.pitch),
            indirect: self.indirect,
            clip: !self.no_clip,
            threads: self
                .threads
                .map_or_else(app::parallel::cores, |n| n as usize),
            filter: match self.filter {
                FilterArg::Nearest => Filter::Nearest,
                FilterArg::Bilinear => Filter::Bilinear,
            },
            dof: self.dof,
            ..Settings::default()
        };
        let forward = settings.camera().axes()[2];
        let pose = framed_pose(&scene, forward, self.focal, self.size.0, self.size.1)?;
        settings.camera = self.camera.unwrap_or(pose.camera);
        settings.light = self.light.unwrap_or(pose.light);
        settings.light_power = self.light_power.unwrap_or(pose.light_power);
        settings.near = self.near.unwrap_or(pose.near);
        let framed = self.camera.is_none()
            || self.light.is_none()
            || self.light_power.is_none()
            || self.near.is_none();
        if framed && !scene.is_box {
            let v = |v: Vec3| format!("{},{},{}", v.x, v.y, v.z);
            eprintln!(
                "scene {} ({} triangles): --camera {} --pitch {} --light {} --light-power {} --near {}",
                scene.name,
                scene.mesh.faces.len(),
                v(settings.camera),
                settings.pitch,
                v(settings.light),
                settings.light_power,
                settings.near
            );
        }
        Ok((scene, settings))
    }
}

/// The scene a `--scene` spec names: a bad spec is a usage error, a model file
/// that cannot be read a failure.
fn load_scene(spec: &str) -> Result<Scene, Failure> {
    let scene = parse_scene(spec).map_err(|e| {
        if spec.to_lowercase().ends_with(".obj") {
            Failure::Run(e)
        } else {
            Failure::Usage(e)
        }
    })?;
    for warning in &scene.warnings {
        eprintln!("warning: {warning}");
    }
    Ok(scene)
}

#[derive(Args, Debug)]
struct Render {
    /// Output image: .png or .bmp, or - for standard output [default: <stage>.png,
    /// <stage>-affine.png or <stage>-perspective.png]
    #[arg(short, long, value_name = "FILE", value_parser = parse::image_path,
          allow_hyphen_values = true)]
    out: Option<PathBuf>,
    /// Also render N times and print the median render time on stderr (no file I/O timed).
    #[arg(long, value_name = "N", value_parser = |s: &str| parse::whole(s, 1, 100_000),
          allow_hyphen_values = true)]
    time: Option<u64>,
    /// Print what the frame did on stderr: triangles culled, outside the view,
    /// clipped and drawn; pixels written and rejected by the depth test.
    #[arg(long)]
    stats: bool,
    /// Write the depth buffer (1/z, scaled to grey, with a legend) instead of the
    /// colours: depth, vertex-light and pixel-light [default file: <stage>-buffer.png]
    #[arg(long)]
    buffer: bool,
    #[command(flatten)]
    draw: DrawArgs,
    #[command(flatten)]
    scene: SceneArgs,
}

/// How a lit stage's per-pixel values cross the screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum Mode {
    /// Linearly on the screen (section 6.1; Figure 8 for pixel-light).
    Affine,
    /// Corrected for perspective (section 6.2).
    Perspective,
}

/// Which rasterizer draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum RasterArg {
    /// The handout's: truncated vertices, Interpolate, polygon rows.
    Rows,
    /// Exact: pixel centres, sub-pixel vertices, the top-left rule.
    Edge,
}

/// Which faces to leave out.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum CullArg {
    None,
    /// Faces whose normal points away from the camera.
    Back,
    /// Faces whose normal points toward the camera.
    Front,
}

/// How lines are walked.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum LinesArg {
    /// The handout's Interpolate: a running float sum, truncated.
    Interpolate,
    /// Bresenham's integer algorithm: the pixel nearest the true line.
    Bresenham,
}

/// How a stage is drawn.
#[derive(Args, Debug)]
struct DrawArgs {
    /// How vertex-light and pixel-light interpolate across the screen [default: the
    /// handout's: affine for vertex-light, perspective for pixel-light]. 1/z, and so
    /// the depth test, is the same either way.
    #[arg(long, value_name = "MODE", value_enum)]
    interpolation: Option<Mode>,
    /// Short for --interpolation affine (with pixel-light: Figure 8).
    #[arg(long, conflicts_with = "interpolation")]
    affine: bool,
    /// The rasterizer: rows (the handout's) or edge (exact).
    #[arg(long, value_name = "RASTER", value_enum, default_value = "rows")]
    raster: RasterArg,
    /// Leave out back- or front-facing faces (normal away from or toward the camera).
    #[arg(long, value_name = "FACES", value_enum, default_value = "none")]
    cull: CullArg,
    /// How lines are walked: the wireframe's, and with --raster rows the polygon
    /// edges that ComputePolygonRows follows.
    #[arg(long, value_name = "WALK", value_enum, default_value = "interpolate")]
    lines: LinesArg,
    /// Shadows: in vertex-light and pixel-light from a shadow map (six 512 x 512
    /// depth images drawn from the light), in raytrace by a shadow ray from every
    /// hit.
    #[arg(long)]
    shadows: bool,
    /// With --shadows: percentage-closer filtering, the share of the 3 x 3 texels
    /// around each point that see the light, for soft edges.
    #[arg(long, requires = "shadows")]
    pcf: bool,
}

impl DrawArgs {
    /// Some(true) for affine, Some(false) for perspective, None for the handout's.
    fn affine(&self) -> Option<bool> {
        if self.affine {
            Some(true)
        } else {
            self.interpolation.map(|m| m == Mode::Affine)
        }
    }

    fn figure(&self, stage: StageName) -> Figure {
        let raster = match self.raster {
            RasterArg::Rows => Raster::Rows,
            RasterArg::Edge => Raster::Edge,
        };
        let cull = match self.cull {
            CullArg::None => Cull::None,
            CullArg::Back => Cull::Back,
            CullArg::Front => Cull::Front,
        };
        let lines = match self.lines {
            LinesArg::Interpolate => Lines::Interpolate,
            LinesArg::Bresenham => Lines::Bresenham,
        };
        let shadows = match (self.shadows, self.pcf) {
            (false, _) => Shadows::None,
            (true, false) => Shadows::Hard,
            (true, true) => Shadows::Pcf,
        };
        Figure::with_interpolation(stage, self.affine())
            .with_raster(raster)
            .with_cull(cull)
            .with_lines(lines)
            .with_shadows(shadows)
    }
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
    /// What to measure: cornell (the default), cornell:K, sphere:N, grid:N or PATH.obj.
    #[arg(long, value_name = "SCENE", default_value = "cornell")]
    scene: String,
    /// Light position [default: the handout's for the box; framed for other scenes,
    /// which puts it inside a closed model: give one outside].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse::vec3, allow_hyphen_values = true)]
    light: Option<Vec3>,
    /// Light power P of eq. 10 [default: 1.1 for the box; scaled for other scenes].
    #[arg(long, value_name = "P", value_parser = parse::non_negative, allow_hyphen_values = true)]
    light_power: Option<f32>,
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
    #[command(flatten)]
    draw: DrawArgs,
    /// Quit after N frames.
    #[arg(long, value_name = "N", value_parser = |s: &str| parse::whole(s, 1, u64::MAX),
          allow_hyphen_values = true)]
    frames: Option<u64>,
    /// Save the last frame to FILE when quitting.
    #[arg(long, value_name = "FILE")]
    screenshot: Option<PathBuf>,
    /// Replay keys frame by frame, e.g. "right*30,w*10,up+left*5" (1/60 s per frame).
    #[arg(long, value_name = "SCRIPT")]
    keys: Option<controls::Script>,
    /// Frames per second to aim for; 0 draws as fast as it can.
    #[arg(long, value_name = "N", default_value = "60",
          value_parser = |s: &str| parse::whole(s, 0, 1000), allow_hyphen_values = true)]
    fps: u64,
    #[command(flatten)]
    scene: SceneArgs,
}

#[derive(Args, Debug)]
struct ExportArgs {
    /// The scene: cornell, cornell:K, sphere:N, grid:N or PATH.obj.
    #[arg(long, value_name = "SCENE", default_value = "cornell")]
    scene: String,
    /// The OBJ file to write; the MTL goes beside it.
    #[arg(short, long, value_name = "FILE.obj", value_parser = parse::obj_path)]
    out: PathBuf,
}

#[derive(Args, Debug)]
struct AnimateArgs {
    /// The stage: points, wireframe, filled, depth, vertex-light, pixel-light.
    #[arg(value_name = "STAGE", value_parser = parse::stage)]
    stage: StageName,
    /// Output GIF, or - for standard output [default: <stage>.gif]
    #[arg(short, long, value_name = "FILE", value_parser = parse::gif_path,
          allow_hyphen_values = true)]
    out: Option<PathBuf>,
    /// How long each triangle shows, in milliseconds (the last image stays 2 s).
    #[arg(long, value_name = "MS", default_value = "150",
          value_parser = |s: &str| parse::whole(s, 10, 10_000))]
    delay: u64,
    #[command(flatten)]
    draw: DrawArgs,
    #[command(flatten)]
    scene: SceneArgs,
}

#[derive(Subcommand, Debug)]
enum Explain {
    /// The pixels Interpolate gives a line from A to B (section 3), numbered.
    ///
    /// Example: `rasterlab explain line 4,2 1,8`, the handout's example.
    Line(ExplainLine),
    /// The same line walked by Interpolate (the handout's) and by Bresenham's
    /// algorithm (--lines bresenham): both pixel sets, and how far each strays.
    ///
    /// Example: `rasterlab explain bresenham 0,0 12,5`.
    Bresenham(ExplainLine),
    /// A convex polygon's edges, the pixels Interpolate puts on them, each row's
    /// start and end, and the filled rows (section 4), with the rows printout.
    ///
    /// Example: `rasterlab explain rows 10,5 5,10 15,15`, the handout's example.
    Rows(ExplainRows),
    /// The exact rasterizer (`--raster edge`) on one triangle: pixel centres,
    /// the pixels covered, and the top-left rule for centres on an edge.
    ///
    /// Example: `rasterlab explain edge 0.5,0.5 6.5,0.5 0.5,6.5`.
    Edge(ExplainEdge),
    /// Two triangles sharing an edge, (A, B, C) and (A, C, D), drawn by the rows
    /// rasterizer and by the edge rasterizer: the pixels drawn twice.
    ///
    /// Example: `rasterlab explain shared 1.3,1.2 12.6,2.4 11.2,11.7 2.1,10.4`.
    Shared(ExplainShared),
}

#[derive(Args, Debug)]
struct ExplainShared {
    /// The quad's corners A, B, C, D as X,Y image positions; fractions allowed.
    #[arg(value_name = "X,Y", num_args = 4, required = true, value_parser = parse::point_f32)]
    corners: Vec<(f32, f32)>,
    /// Output image (.png or .bmp, or - for standard output) [default: explain-shared.png]
    #[arg(short, long, value_name = "FILE", value_parser = parse::image_path,
          allow_hyphen_values = true)]
    out: Option<PathBuf>,
}

#[derive(Args, Debug)]
struct ExplainEdge {
    /// The triangle's corners as X,Y image positions in pixels; fractions allowed.
    #[arg(value_name = "X,Y", num_args = 3, required = true, value_parser = parse::point_f32)]
    corners: Vec<(f32, f32)>,
    /// Output image (.png or .bmp, or - for standard output) [default: explain-edge.png]
    #[arg(short, long, value_name = "FILE", value_parser = parse::image_path,
          allow_hyphen_values = true)]
    out: Option<PathBuf>,
}

#[derive(Args, Debug)]
struct ExplainLine {
    /// The line's first pixel, X,Y.
    #[arg(value_name = "A", value_parser = parse::point, allow_hyphen_values = true)]
    a: (i32, i32),
    /// The line's last pixel, X,Y.
    #[arg(value_name = "B", value_parser = parse::point, allow_hyphen_values = true)]
    b: (i32, i32),
    /// Output image (.png or .bmp, or - for standard output) [default:
    /// explain-line.png or explain-bresenham.png]
    #[arg(short, long, value_name = "FILE", value_parser = parse::image_path,
          allow_hyphen_values = true)]
    out: Option<PathBuf>,
}

#[derive(Args, Debug)]
struct ExplainRows {
    /// The polygon's vertices as X,Y pixels, in order (either winding); a negative
    /// coordinate goes after `--` (`explain rows -- -3,4 ...`).
    #[arg(required = true, value_name = "X,Y", value_parser = parse::point)]
    vertices: Vec<(i32, i32)>,
    /// Output image (.png or .bmp, or - for standard output) [default: explain-rows.png]
    #[arg(short, long, value_name = "FILE", value_parser = parse::image_path,
          allow_hyphen_values = true)]
    out: Option<PathBuf>,
}

#[derive(Args, Debug)]
struct RowsArgs {
    /// The polygon's vertices as X,Y pixels, in order (either winding).
    #[arg(required = true, value_name = "X,Y", value_parser = parse::point,
          allow_hyphen_values = true)]
    vertices: Vec<(i32, i32)>,
}

#[derive(Args, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
struct CheckArgs {
    #[command(subcommand)]
    rows: Option<CheckRows>,
    /// The screenshot: a PNG or BMP of any size (the size sets the camera's
    /// screen; the focal length is the height unless --focal gives it).
    #[arg(value_name = "IMAGE", required = true)]
    image: Option<PathBuf>,
    /// The stage the image shows [default: found from the image]: points,
    /// wireframe, filled, depth, vertex-light, pixel-light.
    #[arg(long, value_name = "STAGE", value_parser = parse::stage)]
    stage: Option<StageName>,
    /// The size the image must have, WIDTHxHEIGHT: a different one is an error.
    #[arg(long, value_name = "WxH", value_parser = parse::size, allow_hyphen_values = true)]
    size: Option<(u32, u32)>,
    /// Focal length f in pixels [default: the image's height].
    #[arg(long, value_name = "F", value_parser = parse::focal, allow_hyphen_values = true)]
    focal: Option<f32>,
    /// Camera position C [default: 0,0,-3.001].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse::vec3, allow_hyphen_values = true)]
    camera: Option<Vec3>,
    /// Turn about the y-axis, in degrees; positive turns right.
    #[arg(long, value_name = "DEG", default_value = "0", value_parser = parse::finite,
          allow_hyphen_values = true)]
    yaw: f32,
    /// Tilt, in degrees; positive looks up.
    #[arg(long, value_name = "DEG", default_value = "0", value_parser = parse::finite,
          allow_hyphen_values = true)]
    pitch: f32,
    /// Light position [default: 0,-0.5,-0.7; the start of the search with --fit-light].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse::vec3, allow_hyphen_values = true)]
    light: Option<Vec3>,
    /// Light power P of eq. 10 [default: fitted to the image].
    #[arg(long, value_name = "P", value_parser = parse::non_negative, allow_hyphen_values = true)]
    light_power: Option<f32>,
    /// Indirect light N of eq. 11 [default: fitted to the image].
    #[arg(long, value_name = "N", value_parser = parse::non_negative, allow_hyphen_values = true)]
    indirect: Option<f32>,
    /// Also search for the light's position (lit stages).
    #[arg(long)]
    fit_light: bool,
    /// Folder for IMAGE-heat.png (where the image differs from the best
    /// explanation) and IMAGE-expected.png (that explanation), created if missing.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Print the report as one JSON object instead of words.
    #[arg(long)]
    json: bool,
}

#[derive(Subcommand, Debug)]
enum CheckRows {
    /// Compares a printed ComputePolygonRows output (section 4's test program) with
    /// the handout's rows of the polygon, and names the variant that prints it.
    ///
    /// Example: `rasterlab check rows mine.txt 10,5 5,10 15,15`.
    Rows(CheckRowsArgs),
}

#[derive(Args, Debug)]
struct CheckRowsArgs {
    /// The printout: one `Start: (x,y). End: (x,y).` per row, or all on one line;
    /// - for standard input.
    #[arg(value_name = "FILE")]
    file: PathBuf,
    /// The polygon's vertices as X,Y pixels, in order, as given to ComputePolygonRows;
    /// a negative coordinate goes after `--` (`check rows FILE -- -3,4 ...`).
    #[arg(required = true, value_name = "X,Y", num_args = 1.., value_parser = parse::point)]
    vertices: Vec<(i32, i32)>,
    /// Print the result as one JSON object instead of words.
    #[arg(long)]
    json: bool,
}

/// `rasterlab check`: a screenshot, or with `rows` a rows printout.
fn check(a: &CheckArgs) -> Result<(), Failure> {
    use app::check::CheckError;
    // In the spirit of diff and cmp: 0 the handout's, 1 different, 2 trouble.
    let failure = |e: CheckError| match e {
        CheckError::Usage(m) => Failure::Usage(m),
        CheckError::Run(m) => Failure::Trouble(m),
    };
    if let Some(CheckRows::Rows(r)) = &a.rows {
        let result = app::check::check_rows_file(&r.file, &r.vertices).map_err(failure)?;
        match r.json {
            true => print_out(&format!("{}\n", result.json(&r.file.display().to_string())))?,
            false => print_out(&result.text())?,
        }
        return match result.is_handouts() {
            true => Ok(()),
            false => Err(Failure::Differs),
        };
    }
    let image = a
        .image
        .as_ref()
        .expect("clap requires IMAGE without a subcommand");
    let options = app::check::CheckOptions {
        stage: a.stage,
        size: a.size,
        focal: a.focal,
        camera: a.camera,
        yaw: a.yaw,
        pitch: a.pitch,
        light: a.light,
        light_power: a.light_power,
        indirect: a.indirect,
        fit_light: a.fit_light,
        out: a.out.clone(),
    };
    let (result, written) = app::check::check_image_file(image, &options).map_err(failure)?;
    let name = image.display().to_string();
    if a.json {
        print_out(&format!("{}\n", result.json(&name)))?;
    } else {
        print_out(&result.text(&name))?;
    }
    for path in written {
        eprintln!("wrote {}", path.display());
    }
    match result.is_handouts_figure(a.stage) {
        true => Ok(()),
        false => Err(Failure::Differs),
    }
}

/// Prints to standard output; a reader that has gone away (`| head`) ends the
/// output quietly.
fn print_out(text: &str) -> Result<(), Failure> {
    Ok(app::image_io::write_bytes(
        std::path::Path::new("-"),
        text.as_bytes(),
    )?)
}

fn render(stage: StageName, args: &Render) -> Result<(), Failure> {
    let figure = args.draw.figure(stage);
    let out = args.out.clone().unwrap_or_else(|| {
        let name = figure.default_file();
        PathBuf::from(match args.buffer {
            true => name.replace(".png", "-buffer.png"),
            false => name,
        })
    });
    let (scene, settings) = args.scene.resolve()?;
    let runs = args.time.map(|n| n as usize);
    let (timing, stats) =
        app::render_to_file(figure, scene.model(), &settings, &out, runs, args.buffer)?;
    if let Some(t) = timing {
        eprintln!("render: {t}");
    }
    if args.stats {
        eprint!("{}", app::stats_text(&stats));
    }
    eprintln!("wrote {}", app::image_io::describe(&out));
    Ok(())
}

/// Why a command failed: a bad argument found after parsing (exit code 2), or a
/// failure while running (exit code 1).
enum Failure {
    Usage(String),
    Run(String),
    /// Standard output's reader went away (`| head`): nothing more to say, but
    /// the output is not whole.
    ClosedEarly,
    /// `check` ran and said so, but the image is not the handout's figure within
    /// 2/255 (or not a lab 3 image), or the rows are not the handout's: exit
    /// code 1, as diff and cmp say "different".
    Differs,
    /// `check` could not read its input or write its output: exit code 2, as
    /// diff and cmp say "trouble".
    Trouble(String),
}

impl From<String> for Failure {
    fn from(message: String) -> Failure {
        Failure::Run(message)
    }
}

impl From<app::image_io::WriteError> for Failure {
    fn from(e: app::image_io::WriteError) -> Failure {
        match e.closed_early {
            true => Failure::ClosedEarly,
            false => Failure::Run(e.to_string()),
        }
    }
}

fn run(cli: Cli) -> Result<(), Failure> {
    match &cli.command {
        Command::Points(a) => render(StageName::Points, a),
        Command::Wireframe(a) => render(StageName::Wireframe, a),
        Command::Filled(a) => render(StageName::Filled, a),
        Command::Depth(a) => render(StageName::Depth, a),
        Command::VertexLight(a) => render(StageName::VertexLight, a),
        Command::PixelLight(a) => render(StageName::PixelLight, a),
        Command::All(a) => {
            let (scene, settings) = a.scene.resolve()?;
            let written = app::render_all(scene.model(), &settings, &a.out)?;
            for path in written {
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
                // --shadows: a shadow ray to the light from every hit.
                shadows: a.render.draw.shadows,
                samples: a.samples,
                ..raytrace::Options::default()
            };
            let out = a
                .render
                .out
                .clone()
                .unwrap_or_else(|| PathBuf::from("raytrace.png"));
            let (scene, settings) = a.render.scene.resolve()?;
            let options = raytrace::Options {
                filter: settings.filter,
                ..options
            };
            let timing = app::raytrace_to_file(
                scene.model(),
                &settings,
                &options,
                &out,
                a.render.time.map(|n| n as usize),
            )?;
            if let Some(t) = timing {
                eprintln!("render: {t}");
            }
            eprintln!("wrote {}", app::image_io::describe(&out));
            Ok(())
        }
        Command::Report(a) => {
            let scene = load_scene(&a.scene)?;
            let mut pose = rasterlab::measure::report::pose_for(&scene)?;
            pose.light = a.light.unwrap_or(pose.light);
            pose.light_power = a.light_power.unwrap_or(pose.light_power);
            let written = app::report(&a.out, a.quick, &scene, &pose, |line| eprintln!("{line}"))?;
            for path in written {
                eprintln!("wrote {}", path.display());
            }
            Ok(())
        }
        Command::Stress(a) => {
            app::stress_fits(a.quick)?;
            let (tables, failed, total) = app::stress(a.quick, |line| eprintln!("{line}"));
            print_out(&format!("{tables}\n"))?;
            if failed > 0 {
                return Err(format!("{failed} of {total} stress cases failed").into());
            }
            Ok(())
        }
        Command::View(a) => {
            let (scene, settings) = a.scene.resolve()?;
            let options = viewer::Options {
                settings,
                model: scene,
                scene: a.scene.scene.clone(),
                texture: a.scene.texture.clone(),
                normal_map: a.scene.normal_map.clone(),
                view: a.draw.figure(a.stage),
                frames: a.frames,
                screenshot: a.screenshot.clone(),
                script: a.keys.clone().unwrap_or_default().0,
                fps: a.fps as usize,
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
        Command::Export(a) => {
            let scene = load_scene(&a.scene)?;
            app::export_obj(&scene.mesh, &a.out)?;
            eprintln!(
                "wrote {} and its .mtl ({} triangles)",
                a.out.display(),
                scene.mesh.faces.len()
            );
            Ok(())
        }
        Command::Animate(a) => {
            let figure = a.draw.figure(a.stage);
            let name = figure.default_file().replace(".png", ".gif");
            let out = a.out.clone().unwrap_or_else(|| PathBuf::from(name));
            let (scene, settings) = a.scene.resolve()?;
            let frames =
                app::animate_to_file(figure, scene.model(), &settings, &out, a.delay as u32)?;
            eprintln!("wrote {} ({frames} frames)", app::image_io::describe(&out));
            Ok(())
        }
        Command::Explain(e) => {
            let (picture, out, default) = match e {
                Explain::Line(a) => (explain::explain_line(a.a, a.b), &a.out, "explain-line.png"),
                Explain::Bresenham(a) => (
                    explain::explain_bresenham(a.a, a.b),
                    &a.out,
                    "explain-bresenham.png",
                ),
                Explain::Rows(a) => (
                    explain::explain_rows(&a.vertices),
                    &a.out,
                    "explain-rows.png",
                ),
                Explain::Edge(a) => {
                    let c = [a.corners[0], a.corners[1], a.corners[2]];
                    (explain::explain_edge(&c), &a.out, "explain-edge.png")
                }
                Explain::Shared(a) => {
                    let c = [a.corners[0], a.corners[1], a.corners[2], a.corners[3]];
                    (explain::explain_shared(&c), &a.out, "explain-shared.png")
                }
            };
            let out = out.clone().unwrap_or_else(|| PathBuf::from(default));
            let frame = picture.map_err(Failure::Usage)?;
            app::image_io::write_image(&frame, &out)?;
            eprintln!("wrote {}", app::image_io::describe(&out));
            Ok(())
        }
        Command::Check(a) => check(a),
        Command::Rows(a) => {
            print_out(&app::rows_text(&a.vertices))?;
            Ok(())
        }
    }
}

/// One rule for options that nothing the command draws would use: they are refused
/// with the reason, so a typo or a misunderstanding never passes silently. (The
/// viewer takes them all: its keys switch to every figure.)
fn refuse_unused_options(command: &str, m: &ArgMatches) -> Result<(), String> {
    let given = |id: &str| {
        m.try_get_raw(id).is_ok_and(|v| v.is_some())
            && m.value_source(id) == Some(ValueSource::CommandLine)
    };
    let stage = match command {
        "animate" => m.get_one::<StageName>("stage").copied(),
        _ => StageName::from_name(command),
    };
    let lit = matches!(stage, Some(StageName::VertexLight | StageName::PixelLight));
    let interpolates = stage.is_some_and(StageName::interpolates);
    let what: &str = stage.map_or(command, |s| s.name());
    for id in ["affine", "interpolation"] {
        if given(id) && !interpolates {
            return Err(format!(
                "--{id} does nothing for {what}: only vertex-light and pixel-light interpolate values that perspective correction changes"
            ));
        }
    }
    if given("buffer") && !matches!(stage, Some(s) if s >= StageName::Depth) {
        return Err(format!(
            "--buffer does nothing for {command}: only depth, vertex-light and pixel-light have a depth buffer"
        ));
    }
    if given("lines") {
        let edge = m.get_one::<RasterArg>("raster") == Some(&RasterArg::Edge);
        match stage {
            Some(StageName::Points) => {
                return Err("--lines does nothing for points: points draw no lines".into())
            }
            Some(s) if s != StageName::Wireframe && edge => {
                return Err(format!(
                    "--lines does nothing for {what} --raster edge: the edge rasterizer fills polygons without walking their edges"
                ))
            }
            _ => {}
        }
    }
    let traced_lit = command == "raytrace" && !m.get_flag("flat");
    let pixel_light = stage == Some(StageName::PixelLight);
    if given("normal_map") && !(pixel_light || traced_lit || command == "view") {
        return Err(format!(
            "--normal-map does nothing for {what}: only pixel-light, raytrace without --flat and the viewer tilt normals per pixel"
        ));
    }
    if given("parallax") && !(pixel_light || command == "view") {
        return Err(format!(
            "--parallax does nothing for {what}: only pixel-light and the viewer move texture coordinates by height"
        ));
    }
    if given("shadows") && !(lit || command == "raytrace" || command == "view") {
        return Err(format!(
            "--shadows does nothing for {what}: only vertex-light and pixel-light are lit"
        ));
    }
    if given("dof") && !(matches!(stage, Some(s) if s >= StageName::Depth) || command == "view") {
        return Err(format!(
            "--dof does nothing for {what}: only depth, vertex-light, pixel-light and the viewer have the depth buffer it needs"
        ));
    }
    if (given("texture") || given("filter")) && !(lit || traced_lit || command == "view") {
        let id = if given("texture") {
            "texture"
        } else {
            "filter"
        };
        return Err(format!(
            "--{id} does nothing for {what}: only vertex-light, pixel-light, raytrace without --flat and the viewer read textures"
        ));
    }
    if command == "raytrace" {
        if given("pcf") {
            return Err(
                "--pcf does nothing for raytrace: a shadow ray is exact, there is no map to filter"
                    .into(),
            );
        }
        for id in ["raster", "cull", "stats", "buffer", "threads", "lines"] {
            if given(id) {
                return Err(format!(
                    "--{id} does nothing for raytrace: it casts rays, it does not rasterize"
                ));
            }
        }
    }
    // Why the light would do nothing, if it would.
    let unlit = if command == "raytrace" {
        m.get_flag("flat")
            .then(|| "raytrace --flat: flat colours are not lit".to_string())
    } else {
        (stage.is_some() && !lit)
            .then(|| format!("{what}: only vertex-light and pixel-light are lit"))
    };
    if let Some(reason) = unlit {
        for id in ["light", "light_power", "indirect"] {
            if given(id) {
                return Err(format!(
                    "--{} does nothing for {reason}",
                    id.replace('_', "-")
                ));
            }
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    let parsed = Cli::command()
        .try_get_matches()
        .and_then(|m| Cli::from_arg_matches(&m).map(|cli| (m, cli)));
    let (matches, cli) = match parsed {
        Ok(parsed) => parsed,
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
            // clap's tips ("a similar argument exists: ...") follow a blank line: kept.
            let text = e.render().to_string();
            let mut message: Vec<&str> = text
                .lines()
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            message.extend(
                text.lines()
                    .map(str::trim)
                    .filter(|l| l.starts_with("tip: ")),
            );
            eprintln!("{} (see 'rasterlab --help')", message.join("; "));
            return ExitCode::from(2);
        }
    };
    if let Some((command, m)) = matches.subcommand() {
        if let Err(message) = refuse_unused_options(command, m) {
            eprintln!("error: {message} (see 'rasterlab {command} --help')");
            return ExitCode::from(2);
        }
    }
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(message)) => {
            eprintln!("error: {message} (see 'rasterlab --help')");
            ExitCode::from(2)
        }
        Err(Failure::Run(message)) => {
            eprintln!("error: {message}");
            ExitCode::from(1)
        }
        Err(Failure::ClosedEarly) => ExitCode::from(1),
        Err(Failure::Differs) => ExitCode::from(1),
        Err(Failure::Trouble(message)) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}
