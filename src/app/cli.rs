//! The command line's words: every subcommand and the groups of options it
//! takes, as clap parses them, and how a group becomes the library's settings.
//! A subcommand declares only the groups its work reads, so `--help` lists what
//! it takes and clap refuses (with a suggestion) what it would not use.

use super::{parallel, parse, Settings};
use crate::app::figure::{Figure, Raster};
use crate::extensions::depth_of_field::DepthOfField;
use crate::extensions::shadow::Shadows;
use crate::extensions::texture::Filter;
use crate::pipeline::camera::DEFAULT_NEAR;
use crate::pipeline::draw::Cull;
use crate::pipeline::raster::Lines;
use crate::pipeline::{Camera, Light, StageName};
use crate::scene::texture::{
    apply_normal_map, apply_parallax, apply_texture, parse_normal_map, TextureSpec,
};
use crate::scene::{framed_view, parse_scene, Scene};
use clap::{Args, CommandFactory, Parser, Subcommand};
use glam::Vec3;
use std::path::PathBuf;

/// A CPU rasterizer that reproduces the DH2323 lab 3 handout, stage by stage.
///
/// Each stage subcommand draws the Cornell box as one section of the handout does
/// and writes a PNG. `rasterlab all --out figures` writes every figure.
#[derive(Parser, Debug)]
#[command(name = "rasterlab", version)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Section 2: the projected vertices as white points (Figure 2).
    Points(Render<PointsOptions>),
    /// Section 3: the triangles' edges as white lines (Figure 3).
    Wireframe(Render<EdgesOptions>),
    /// Section 4: triangles filled in scene order, no depth test (Figure 4).
    Filled(Render<EdgesOptions>),
    /// Section 5: filled triangles behind a depth buffer of 1/z (Figure 5).
    Depth(RenderDepth<DepthOptions>),
    /// Section 6.1: equations 10 and 11 at each vertex, interpolated linearly on the
    /// screen (Figure 6).
    VertexLight(RenderDepth<VertexLightOptions>),
    /// Section 6.2: equations 10 and 11 at each pixel (Figure 7; Figure 8 with --affine).
    PixelLight(RenderDepth<PixelLightOptions>),
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
    /// `rasterlab check shot.png` reads a PNG, BMP or JPEG of any size (a JPEG
    /// only as far as its compression shows); `rasterlab check
    /// submissions/` (or several files) checks every file, in parallel, one row
    /// each; `rasterlab check rows FILE 10,5 5,10 15,15` compares a printed
    /// ComputePolygonRows output instead. docs/check.md shows a report.
    ///
    /// Exit status, as diff and cmp: 0 when every image is the handout's figure
    /// within 2/255 at every pixel (or the rows are the handout's), 1 when any
    /// differs or is not a lab 3 image (in a folder or a list, also when a file
    /// cannot be read: it is a row of its own), 2 for trouble (bad usage, the one
    /// input given cannot be read, an output that cannot be written).
    Check(CheckArgs),
}

/// Why a command failed: a bad argument found after parsing (exit code 2), or a
/// failure while running (exit code 1).
pub enum Failure {
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

impl From<super::image_io::WriteError> for Failure {
    fn from(e: super::image_io::WriteError) -> Failure {
        match e.closed_early {
            true => Failure::ClosedEarly,
            false => Failure::Run(e.to_string()),
        }
    }
}

/// What to draw and the image: every command that draws takes these.
#[derive(Args, Debug)]
#[command(next_help_heading = "Scene and image")]
pub struct SceneGroup {
    /// What to draw: cornell (the handout's box), cornell:K (each triangle split
    /// K x K), sphere:N, grid:N (about N triangles), or a model file PATH.obj.
    #[arg(long, value_name = "SCENE", default_value = "cornell")]
    pub scene: String,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, value_name = "WxH", default_value = "500x500", value_parser = parse::size,
          allow_hyphen_values = true)]
    pub size: (u32, u32),
    /// Focal length f in pixels (eq. 1 to 4).
    #[arg(long, value_name = "F", default_value = "500", value_parser = parse::focal,
          allow_hyphen_values = true)]
    pub focal: f32,
    /// Near clipping plane: geometry closer to the camera than Z is cut away
    /// [default: 0.01; for a scene smaller than the box, scaled with its size].
    #[arg(long, value_name = "Z", value_parser = parse::positive, allow_hyphen_values = true)]
    pub near: Option<f32>,
    /// Draw as the handout does, without clipping: a triangle with a corner behind
    /// the camera is projected through it and drawn wrong (but never out of bounds).
    #[arg(long)]
    pub no_clip: bool,
}

/// Where the camera is and where it looks. Vectors are X,Y,Z; y points down.
#[derive(Args, Debug)]
#[command(next_help_heading = "Camera")]
pub struct CameraGroup {
    /// Camera position C (eq. 5) in world space [default: 0,0,-3.001 for the box;
    /// other scenes are framed, and the pose used is printed].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse::vec3, allow_hyphen_values = true)]
    pub camera: Option<Vec3>,
    /// Turn about the y-axis, in degrees; positive turns right.
    #[arg(long, value_name = "DEG", default_value = "0", value_parser = parse::finite,
          allow_hyphen_values = true)]
    pub yaw: f32,
    /// Tilt, in degrees; positive looks up [default: 0; a grid is looked down on
    /// from above].
    #[arg(long, value_name = "DEG", value_parser = parse::finite, allow_hyphen_values = true)]
    pub pitch: Option<f32>,
}

/// The light of section 6.1, for the lit stages.
#[derive(Args, Debug)]
#[command(next_help_heading = "Light (section 6.1)")]
pub struct LightGroup {
    /// Light position [default: 0,-0.5,-0.7 for the box; for other scenes the same
    /// place relative to the scene, scaled].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse::vec3, allow_hyphen_values = true)]
    pub light: Option<Vec3>,
    /// Light power P of eq. 10, the same in each channel (lab 2 used 14) [default:
    /// 1.1 for the box; for other scenes scaled with the scene's size squared].
    #[arg(long, value_name = "P", value_parser = parse::non_negative, allow_hyphen_values = true)]
    pub light_power: Option<f32>,
    /// Indirect light N of eq. 11, the same in each channel.
    #[arg(long, value_name = "N", default_value = "0.5", value_parser = parse::non_negative,
          allow_hyphen_values = true)]
    pub indirect: f32,
}

/// How the rasterizer draws.
#[derive(Args, Debug)]
#[command(next_help_heading = "Rasterizer")]
pub struct RasterGroup {
    /// The rasterizer: rows (the handout's) or edge (exact).
    #[arg(long, value_name = "RASTER", value_enum, default_value = "rows")]
    pub raster: RasterArg,
    /// Leave out back- or front-facing faces (normal away from or toward the camera).
    #[arg(long, value_name = "FACES", value_enum, default_value = "none")]
    pub cull: CullArg,
    /// Threads drawing bands of the image; the image is the same for any number
    /// [default: all cores].
    #[arg(long, value_name = "N", value_parser = |s: &str| parse::whole(s, 1, 256),
          allow_hyphen_values = true)]
    pub threads: Option<u64>,
    /// Print what the frame did on stderr: triangles culled, outside the view,
    /// clipped and drawn; pixels written and rejected by the depth test.
    #[arg(long)]
    pub stats: bool,
}

/// How lines are walked, for the stages that draw or follow them.
#[derive(Args, Debug)]
#[command(next_help_heading = "Rasterizer")]
pub struct LinesGroup {
    /// How lines are walked: the wireframe's, and with --raster rows the polygon
    /// edges that ComputePolygonRows follows [default: interpolate].
    #[arg(long, value_name = "WALK", value_enum)]
    pub lines: Option<LinesArg>,
}

/// How a lit stage's per-pixel struct crosses the screen.
#[derive(Args, Debug)]
#[command(next_help_heading = "Light (section 6.1)")]
pub struct InterpolationGroup {
    /// How the light or the position is interpolated across the screen [default:
    /// the handout's: affine for vertex-light, perspective for pixel-light]. 1/z,
    /// and so the depth test, is the same either way.
    #[arg(long, value_name = "MODE", value_enum)]
    pub interpolation: Option<Mode>,
    /// Short for --interpolation affine (with pixel-light: Figure 8).
    #[arg(long, conflicts_with = "interpolation")]
    pub affine: bool,
}

/// Textures, for what is lit.
#[derive(Args, Debug)]
#[command(next_help_heading = "Beyond the handout")]
pub struct TextureGroup {
    /// Read each surface's reflectance from a texture: checker (a checker of each
    /// wall's colour; the box's blocks stay plain) or an image PATH. A model's own
    /// MTL map_Kd is used without this; none leaves it out.
    #[arg(long, value_name = "checker|none|PATH")]
    pub texture: Option<String>,
    /// How textures are read between texels.
    #[arg(long, value_enum, default_value = "nearest")]
    pub filter: FilterArg,
}

/// Shadows from a shadow map, for the lit stages.
#[derive(Args, Debug)]
#[command(next_help_heading = "Beyond the handout")]
pub struct ShadowGroup {
    /// Shadows from a shadow map: six 512 x 512 depth images drawn from the light.
    #[arg(long)]
    pub shadows: bool,
    /// With --shadows: percentage-closer filtering, the share of the 3 x 3 texels
    /// around each point that see the light, for soft edges.
    #[arg(long, requires = "shadows")]
    pub pcf: bool,
}

/// Depth of field, for the stages with a depth buffer.
#[derive(Args, Debug)]
#[command(next_help_heading = "Beyond the handout")]
pub struct DofGroup {
    /// Depth of field: a blur that follows each pixel's circle of confusion,
    /// focused at depth FOCUS with a lens of radius APERTURE (world units).
    #[arg(long, value_name = "FOCUS,APERTURE", value_parser = parse::dof,
          allow_hyphen_values = true)]
    pub dof: Option<DepthOfField>,
}

/// A normal map, for what is lit per pixel.
#[derive(Args, Debug)]
#[command(next_help_heading = "Beyond the handout")]
pub struct NormalMapGroup {
    /// Tilt each pixel's normal by a tangent-space normal map, bumps (round
    /// domes) or an image PATH, on the surfaces --texture would cover.
    #[arg(long, value_name = "bumps|PATH")]
    pub normal_map: Option<String>,
}

/// Section 2's options: the scene, the camera and the rasterizer.
#[derive(Args, Debug)]
pub struct PointsOptions {
    #[command(flatten)]
    pub scene: SceneGroup,
    #[command(flatten)]
    pub camera: CameraGroup,
    #[command(flatten)]
    pub raster: RasterGroup,
}

/// Sections 3 and 4: points' options and how lines are walked.
#[derive(Args, Debug)]
pub struct EdgesOptions {
    #[command(flatten)]
    pub points: PointsOptions,
    #[command(flatten)]
    pub lines: LinesGroup,
}

/// Section 5: and depth of field, which reads the depth buffer.
#[derive(Args, Debug)]
pub struct DepthOptions {
    #[command(flatten)]
    pub edges: EdgesOptions,
    #[command(flatten)]
    pub dof: DofGroup,
}

/// Section 6.1: and the light, its interpolation, textures and shadows.
#[derive(Args, Debug)]
pub struct VertexLightOptions {
    #[command(flatten)]
    pub depth: DepthOptions,
    #[command(flatten)]
    pub light: LightGroup,
    #[command(flatten)]
    pub interpolation: InterpolationGroup,
    #[command(flatten)]
    pub texture: TextureGroup,
    #[command(flatten)]
    pub shadows: ShadowGroup,
}

/// Section 6.2: and a normal map, which tilts normals per pixel.
#[derive(Args, Debug)]
pub struct PixelLightOptions {
    #[command(flatten)]
    pub lit: VertexLightOptions,
    #[command(flatten)]
    pub normal_map: NormalMapGroup,
    /// With --normal-map bumps: parallax, the texture coordinates moved along the
    /// view by the bumps' heights, so the bumps stand out of the surface and hide
    /// what lies behind them.
    #[arg(long, requires = "normal_map", help_heading = "Beyond the handout")]
    pub parallax: bool,
}

/// Everything a drawing command was given, each group where the command has it.
#[derive(Clone, Copy)]
pub struct Parts<'a> {
    pub scene: &'a SceneGroup,
    pub camera: &'a CameraGroup,
    pub raster: Option<&'a RasterGroup>,
    pub lines: Option<LinesArg>,
    pub light: Option<&'a LightGroup>,
    pub interpolation: Option<&'a InterpolationGroup>,
    pub texture: Option<&'a TextureGroup>,
    pub shadows: bool,
    pub pcf: bool,
    pub dof: Option<DepthOfField>,
    pub normal_map: Option<&'a str>,
    pub parallax: bool,
}

/// A stage's options, however many groups they hold.
pub trait StageOptions {
    fn parts(&self) -> Parts<'_>;
}

impl StageOptions for PointsOptions {
    fn parts(&self) -> Parts<'_> {
        Parts {
            raster: Some(&self.raster),
            ..Parts::new(&self.scene, &self.camera)
        }
    }
}

impl StageOptions for EdgesOptions {
    fn parts(&self) -> Parts<'_> {
        Parts {
            lines: self.lines.lines,
            ..self.points.parts()
        }
    }
}

impl StageOptions for DepthOptions {
    fn parts(&self) -> Parts<'_> {
        Parts {
            dof: self.dof.dof,
            ..self.edges.parts()
        }
    }
}

impl StageOptions for VertexLightOptions {
    fn parts(&self) -> Parts<'_> {
        Parts {
            light: Some(&self.light),
            interpolation: Some(&self.interpolation),
            texture: Some(&self.texture),
            shadows: self.shadows.shadows,
            pcf: self.shadows.pcf,
            ..self.depth.parts()
        }
    }
}

impl StageOptions for PixelLightOptions {
    fn parts(&self) -> Parts<'_> {
        Parts {
            normal_map: self.normal_map.normal_map.as_deref(),
            parallax: self.parallax,
            ..self.lit.parts()
        }
    }
}

impl<'a> Parts<'a> {
    /// The scene and the camera, and no other group: the handout's for the rest.
    pub fn new(scene: &'a SceneGroup, camera: &'a CameraGroup) -> Self {
        Parts {
            scene,
            camera,
            raster: None,
            lines: None,
            light: None,
            interpolation: None,
            texture: None,
            shadows: false,
            pcf: false,
            dof: None,
            normal_map: None,
            parallax: false,
        }
    }

    /// The figure `stage` is drawn as: the handout's, changed by what was given.
    pub fn figure(&self, stage: StageName) -> Result<Figure, Failure> {
        let raster = match self.raster.map(|r| r.raster) {
            Some(RasterArg::Edge) => Raster::Edge,
            _ => Raster::Rows,
        };
        if self.lines.is_some() && raster == Raster::Edge && stage != StageName::Wireframe {
            return Err(Failure::Usage(format!(
                "--lines does nothing for {} --raster edge: the edge rasterizer fills polygons without walking their edges",
                stage.name()
            )));
        }
        let cull = match self.raster.map(|r| r.cull) {
            Some(CullArg::Back) => Cull::Back,
            Some(CullArg::Front) => Cull::Front,
            _ => Cull::None,
        };
        let lines = match self.lines {
            Some(LinesArg::Bresenham) => Lines::Bresenham,
            _ => Lines::Interpolate,
        };
        let shadows = match (self.shadows, self.pcf) {
            (false, _) => Shadows::None,
            (true, false) => Shadows::Hard,
            (true, true) => Shadows::Pcf,
        };
        let affine = self.interpolation.and_then(|i| match i.affine {
            true => Some(true),
            false => i.interpolation.map(|m| m == Mode::Affine),
        });
        Ok(Figure::with_interpolation(stage, affine)
            .with_raster(raster)
            .with_cull(cull)
            .with_lines(lines)
            .with_shadows(shadows))
    }

    /// The scene and the settings to draw it with: what the command line gives,
    /// and where it gives no camera or light, the framing of the scene (printed, so
    /// the image can be made again with explicit options).
    pub fn resolve(&self) -> Result<(Scene, Settings), Failure> {
        let mut scene = load_scene(&self.scene.scene)?;
        if let Some(spec) = self.texture.and_then(|t| t.texture.as_deref()) {
            apply_texture(&mut scene, &TextureSpec::parse(spec)).map_err(Failure::Run)?;
        }
        if let Some(spec) = self.normal_map {
            let map = parse_normal_map(spec).map_err(Failure::Run)?;
            apply_normal_map(&mut scene, map);
        }
        if self.parallax {
            if self.normal_map != Some("bumps") {
                return Err(Failure::Usage(
                    "--parallax needs --normal-map bumps: only the bumps come with heights".into(),
                ));
            }
            apply_parallax(&mut scene);
        }
        let (s, c) = (self.scene, self.camera);
        let light = self.light;
        let looking = Camera {
            yaw: c.yaw.to_radians(),
            pitch: c.pitch.unwrap_or(scene.pitch).to_radians(),
            focal: s.focal,
            near: (!s.no_clip).then_some(DEFAULT_NEAR),
            ..Camera::handout(s.size.0, s.size.1)
        };
        let (framed, framed_light) = framed_view(&scene, &looking)?;
        let (given_light, given_power) = (
            light.and_then(|l| l.light),
            light.and_then(|l| l.light_power),
        );
        let settings = Settings {
            camera: Camera {
                position: c.camera.unwrap_or(framed.position),
                near: framed.near.map(|near| s.near.unwrap_or(near)),
                ..framed
            },
            light: Light {
                position: given_light.unwrap_or(framed_light.position),
                power: given_power.map_or(framed_light.power, Vec3::splat),
                indirect: light.map_or(framed_light.indirect, |l| Vec3::splat(l.indirect)),
            },
            threads: self
                .raster
                .and_then(|r| r.threads)
                .map_or_else(parallel::cores, |n| n as usize),
            filter: match self.texture.map(|t| t.filter) {
                Some(FilterArg::Bilinear) => Filter::Bilinear,
                _ => Filter::Nearest,
            },
            dof: self.dof,
        };
        let framed = c.camera.is_none()
            || given_light.is_none()
            || given_power.is_none()
            || s.near.is_none();
        if framed && !scene.is_box {
            let v = |v: Vec3| format!("{},{},{}", v.x, v.y, v.z);
            let (camera, light) = (settings.camera, settings.light);
            let near = camera
                .near
                .map_or("--no-clip".to_string(), |n| format!("--near {n}"));
            crate::say!(
                "scene {} ({} triangles): --camera {} --pitch {} --light {} --light-power {} {near}",
                super::streams::printable(&scene.name),
                scene.mesh.faces.len(),
                v(camera.position),
                c.pitch.unwrap_or(scene.pitch),
                v(light.position),
                light.power.x,
            );
        }
        Ok((scene, settings))
    }
}

/// How many of a scene's warnings are printed.
pub const MAX_WARNINGS: usize = 64;

/// The scene a `--scene` spec names: a bad spec is a usage error, a model file
/// that cannot be read (or a scene too large for the memory there is) a failure. Warnings about the file go to stderr.
pub fn load_scene(spec: &str) -> Result<Scene, Failure> {
    let scene = parse_scene(spec).map_err(|e| {
        if spec.to_lowercase().ends_with(".obj") || e.starts_with("out of memory") {
            Failure::Run(e)
        } else {
            Failure::Usage(e)
        }
    })?;
    // A file can hold a warning's cause many thousand times over.
    for warning in scene.warnings.iter().take(MAX_WARNINGS) {
        crate::say!("warning: {}", super::streams::printable(warning));
    }
    if let Some(more) = scene.warnings.len().checked_sub(MAX_WARNINGS + 1) {
        crate::say!("warning: and {} more warnings about the scene", more + 1);
    }
    Ok(scene)
}

/// Where a drawing goes, and whether it is timed.
#[derive(Args, Debug)]
#[command(next_help_heading = "Output")]
pub struct OutputGroup {
    /// Output image: .png or .bmp, or - for standard output [default: <stage>.png,
    /// <stage>-affine.png or <stage>-perspective.png]
    #[arg(short, long, value_name = "FILE", value_parser = parse::image_path,
          allow_hyphen_values = true)]
    pub out: Option<PathBuf>,
    /// Also render N times and print the median render time on stderr (no file I/O timed).
    #[arg(long, value_name = "N", value_parser = |s: &str| parse::whole(s, 1, 100_000),
          allow_hyphen_values = true)]
    pub time: Option<u64>,
}

/// A stage subcommand: its options, and the image it writes.
#[derive(Args, Debug)]
pub struct Render<O: Args> {
    #[command(flatten)]
    pub output: OutputGroup,
    #[command(flatten)]
    pub options: O,
}

/// A stage subcommand with a depth buffer, which it can write instead.
#[derive(Args, Debug)]
pub struct RenderDepth<O: Args> {
    #[command(flatten)]
    pub output: OutputGroup,
    /// Write the depth buffer (1/z, scaled to grey, with a legend) instead of the
    /// colours [default file: <stage>-buffer.png]
    #[arg(long, help_heading = "Output")]
    pub buffer: bool,
    #[command(flatten)]
    pub options: O,
}

/// How a lit stage's per-pixel values cross the screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Mode {
    /// Linearly on the screen (section 6.1; Figure 8 for pixel-light).
    Affine,
    /// Corrected for perspective (section 6.2).
    Perspective,
}

/// Which rasterizer draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum RasterArg {
    /// The handout's: truncated vertices, Interpolate, polygon rows.
    Rows,
    /// Exact: pixel centres, sub-pixel vertices, the top-left rule.
    Edge,
}

/// Which faces to leave out.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum CullArg {
    None,
    /// Faces whose normal points away from the camera.
    Back,
    /// Faces whose normal points toward the camera.
    Front,
}

/// How lines are walked.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum LinesArg {
    /// The handout's Interpolate: a running float sum, truncated.
    Interpolate,
    /// Bresenham's integer algorithm: the pixel nearest the true line.
    Bresenham,
}

/// How textures are read between texels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FilterArg {
    /// The texel containing the point.
    Nearest,
    /// The four nearest texel centres, weighted.
    Bilinear,
}

#[derive(Args, Debug)]
pub struct AllArgs {
    /// Folder for the figures (created if missing).
    #[arg(long, value_name = "DIR", default_value = "figures")]
    pub out: PathBuf,
    #[command(flatten)]
    pub scene: SceneGroup,
    #[command(flatten)]
    pub camera: CameraGroup,
    #[command(flatten)]
    pub light: LightGroup,
}

impl AllArgs {
    pub fn parts(&self) -> Parts<'_> {
        Parts {
            light: Some(&self.light),
            ..Parts::new(&self.scene, &self.camera)
        }
    }
}

#[derive(Args, Debug)]
pub struct RaytraceArgs {
    /// N x N rays per pixel, spread over the pixel (anti-aliasing).
    #[arg(long, value_name = "N", default_value = "1",
          value_parser = |s: &str| parse::whole(s, 1, 16).map(|n| n as u32),
          allow_hyphen_values = true)]
    pub samples: u32,
    /// The nearest triangle's flat colour instead of light (what filled and depth
    /// mean): no light, shadows, textures or normal maps.
    #[arg(long, conflicts_with_all = ["light", "light_power", "indirect", "shadows",
          "texture", "filter", "normal_map"])]
    pub flat: bool,
    /// A shadow ray from every hit: a hit that cannot see the light gets only
    /// indirect light.
    #[arg(long, help_heading = "Beyond the handout")]
    pub shadows: bool,
    #[command(flatten)]
    pub output: OutputGroup,
    #[command(flatten)]
    pub scene: SceneGroup,
    #[command(flatten)]
    pub camera: CameraGroup,
    #[command(flatten)]
    pub light: LightGroup,
    #[command(flatten)]
    pub texture: TextureGroup,
    #[command(flatten)]
    pub normal_map: NormalMapGroup,
}

impl RaytraceArgs {
    pub fn parts(&self) -> Parts<'_> {
        Parts {
            light: Some(&self.light),
            texture: Some(&self.texture),
            shadows: self.shadows,
            normal_map: self.normal_map.normal_map.as_deref(),
            ..Parts::new(&self.scene, &self.camera)
        }
    }
}

#[derive(Args, Debug)]
pub struct ReportArgs {
    /// What to measure: cornell (the default), cornell:K, sphere:N, grid:N or PATH.obj.
    #[arg(long, value_name = "SCENE", default_value = "cornell")]
    pub scene: String,
    /// Light position [default: the handout's for the box; framed for other scenes,
    /// which puts it inside a closed model: give one outside].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse::vec3, allow_hyphen_values = true)]
    pub light: Option<Vec3>,
    /// Light power P of eq. 10 [default: 1.1 for the box; scaled for other scenes].
    #[arg(long, value_name = "P", value_parser = parse::non_negative, allow_hyphen_values = true)]
    pub light_power: Option<f32>,
    /// Folder for report.md, report.csv and error-vs-time.png (created if missing).
    #[arg(long, value_name = "DIR", default_value = "report")]
    pub out: PathBuf,
    /// A small, fast version (two small sizes, k = 1 and 2, two runs each).
    #[arg(long)]
    pub quick: bool,
}

#[derive(Args, Debug)]
pub struct StressArgs {
    /// Leave out the 16000 x 16000 case (the slowest) and time one draw per case.
    #[arg(long)]
    pub quick: bool,
}

#[derive(Args, Debug)]
pub struct ViewArgs {
    /// The stage to show first: points, wireframe, filled, depth, vertex-light, pixel-light.
    #[arg(value_name = "STAGE", default_value = "pixel-light", value_parser = parse::stage)]
    pub stage: StageName,
    /// Quit after N frames.
    #[arg(long, value_name = "N", value_parser = |s: &str| parse::whole(s, 1, u64::MAX),
          allow_hyphen_values = true)]
    pub frames: Option<u64>,
    /// Save the last frame to FILE when quitting.
    #[arg(long, value_name = "FILE")]
    pub screenshot: Option<PathBuf>,
    /// Replay keys frame by frame, e.g. "right*30,w*10,up+left*5" (1/60 s per frame).
    #[arg(long, value_name = "SCRIPT")]
    pub keys: Option<super::controls::Script>,
    /// Frames per second to aim for; 0 draws as fast as it can.
    #[arg(long, value_name = "N", default_value = "60",
          value_parser = |s: &str| parse::whole(s, 0, 1000), allow_hyphen_values = true)]
    pub fps: u64,
    /// Every stage's options: the viewer's keys switch to every figure.
    #[command(flatten)]
    pub options: PixelLightOptions,
}

#[derive(Args, Debug)]
pub struct ExportArgs {
    /// The scene: cornell, cornell:K, sphere:N, grid:N or PATH.obj.
    #[arg(long, value_name = "SCENE", default_value = "cornell")]
    pub scene: String,
    /// The OBJ file to write; the MTL goes beside it.
    #[arg(short, long, value_name = "FILE.obj", value_parser = parse::obj_path)]
    pub out: PathBuf,
}

#[derive(Args, Debug)]
pub struct AnimateArgs {
    #[command(subcommand)]
    pub stage: AnimateStage,
    /// Output GIF, or - for standard output [default: <stage>.gif]
    #[arg(short, long, value_name = "FILE", value_parser = parse::gif_path,
          allow_hyphen_values = true, global = true)]
    pub out: Option<PathBuf>,
    /// How long each triangle shows, in milliseconds (the last image stays 2 s).
    #[arg(long, value_name = "MS", default_value = "150", global = true,
          value_parser = |s: &str| parse::whole(s, 10, 10_000), allow_hyphen_values = true)]
    pub delay: u64,
}

/// The stage to animate, with its options.
#[derive(Subcommand, Debug)]
pub enum AnimateStage {
    Points(PointsOptions),
    Wireframe(EdgesOptions),
    Filled(EdgesOptions),
    Depth(DepthOptions),
    VertexLight(VertexLightOptions),
    PixelLight(PixelLightOptions),
}

impl AnimateStage {
    /// The stage and its options.
    pub fn parts(&self) -> (StageName, Parts<'_>) {
        match self {
            AnimateStage::Points(o) => (StageName::Points, o.parts()),
            AnimateStage::Wireframe(o) => (StageName::Wireframe, o.parts()),
            AnimateStage::Filled(o) => (StageName::Filled, o.parts()),
            AnimateStage::Depth(o) => (StageName::Depth, o.parts()),
            AnimateStage::VertexLight(o) => (StageName::VertexLight, o.parts()),
            AnimateStage::PixelLight(o) => (StageName::PixelLight, o.parts()),
        }
    }
}

#[derive(Subcommand, Debug)]
pub enum Explain {
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
pub struct ExplainShared {
    /// The quad's corners A, B, C, D as X,Y image positions; fractions allowed.
    #[arg(value_name = "X,Y", num_args = 4, required = true, value_parser = parse::point_f32)]
    pub corners: Vec<(f32, f32)>,
    /// Output image (.png or .bmp, or - for standard output) [default: explain-shared.png]
    #[arg(short, long, value_name = "FILE", value_parser = parse::image_path,
          allow_hyphen_values = true)]
    pub out: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct ExplainEdge {
    /// The triangle's corners as X,Y image positions in pixels; fractions allowed.
    #[arg(value_name = "X,Y", num_args = 3, required = true, value_parser = parse::point_f32)]
    pub corners: Vec<(f32, f32)>,
    /// Output image (.png or .bmp, or - for standard output) [default: explain-edge.png]
    #[arg(short, long, value_name = "FILE", value_parser = parse::image_path,
          allow_hyphen_values = true)]
    pub out: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct ExplainLine {
    /// The line's first pixel, X,Y.
    #[arg(value_name = "A", value_parser = parse::point, allow_hyphen_values = true)]
    pub a: (i32, i32),
    /// The line's last pixel, X,Y.
    #[arg(value_name = "B", value_parser = parse::point, allow_hyphen_values = true)]
    pub b: (i32, i32),
    /// Output image (.png or .bmp, or - for standard output) [default:
    /// explain-line.png or explain-bresenham.png]
    #[arg(short, long, value_name = "FILE", value_parser = parse::image_path,
          allow_hyphen_values = true)]
    pub out: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct ExplainRows {
    /// The polygon's vertices as X,Y pixels, in order (either winding); a negative
    /// coordinate goes after `--` (`explain rows -- -3,4 ...`).
    #[arg(required = true, value_name = "X,Y", value_parser = parse::point)]
    pub vertices: Vec<(i32, i32)>,
    /// Output image (.png or .bmp, or - for standard output) [default: explain-rows.png]
    #[arg(short, long, value_name = "FILE", value_parser = parse::image_path,
          allow_hyphen_values = true)]
    pub out: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct RowsArgs {
    /// The polygon's vertices as X,Y pixels, in order (either winding).
    #[arg(required = true, value_name = "X,Y", value_parser = parse::point,
          allow_hyphen_values = true)]
    pub vertices: Vec<(i32, i32)>,
}

#[derive(Args, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct CheckArgs {
    #[command(subcommand)]
    pub rows: Option<CheckRows>,
    /// The screenshot: a PNG, BMP or JPEG of any size (the size sets the camera's
    /// screen; the focal length is the height unless --focal gives it). Several
    /// files, or folders (every file in them, recursively), give one row each.
    #[arg(value_name = "IMAGE|DIR", required = true, num_args = 1..)]
    pub images: Vec<PathBuf>,
    /// With several files or a folder: also write the table as CSV to FILE.
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// The stage the image shows [default: found from the image]: points,
    /// wireframe, filled, depth, vertex-light, pixel-light.
    #[arg(long, value_name = "STAGE", value_parser = parse::stage)]
    pub stage: Option<StageName>,
    /// The size the image must have, WIDTHxHEIGHT: a different one is an error.
    #[arg(long, value_name = "WxH", value_parser = parse::size, allow_hyphen_values = true)]
    pub size: Option<(u32, u32)>,
    /// Focal length f in pixels [default: the image's height].
    #[arg(long, value_name = "F", value_parser = parse::focal, allow_hyphen_values = true)]
    pub focal: Option<f32>,
    /// Camera position C [default: 0,0,-3.001].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse::vec3, allow_hyphen_values = true)]
    pub camera: Option<Vec3>,
    /// Turn about the y-axis, in degrees; positive turns right.
    #[arg(long, value_name = "DEG", default_value = "0", value_parser = parse::finite,
          allow_hyphen_values = true)]
    pub yaw: f32,
    /// Tilt, in degrees; positive looks up.
    #[arg(long, value_name = "DEG", default_value = "0", value_parser = parse::finite,
          allow_hyphen_values = true)]
    pub pitch: f32,
    /// Light position, not searched for [default: 0,-0.5,-0.7, and searched for
    /// where the shade inside the surfaces differs from it].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse::vec3, allow_hyphen_values = true)]
    pub light: Option<Vec3>,
    /// Light power P of eq. 10 [default: fitted to the image].
    #[arg(long, value_name = "P", value_parser = parse::non_negative, allow_hyphen_values = true)]
    pub light_power: Option<f32>,
    /// Indirect light N of eq. 11 [default: fitted to the image].
    #[arg(long, value_name = "N", value_parser = parse::non_negative, allow_hyphen_values = true)]
    pub indirect: Option<f32>,
    /// Search for the light's position (lit stages) from --light or the
    /// handout's, even where the shade inside the surfaces fits.
    #[arg(long)]
    pub fit_light: bool,
    /// Folder for IMAGE-heat.png (where the image differs from the best
    /// explanation) and IMAGE-expected.png (that explanation), created if missing.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Print the report as one JSON object instead of words (with several files,
    /// one object per line, each with `file` and `status`).
    #[arg(long)]
    pub json: bool,
}

impl CheckArgs {
    /// What the checker is asked, from the options.
    pub fn options(&self) -> crate::app::check::CheckOptions {
        crate::app::check::CheckOptions {
            stage: self.stage,
            size: self.size,
            focal: self.focal,
            camera: self.camera,
            yaw: self.yaw,
            pitch: self.pitch,
            light: self.light,
            light_power: self.light_power,
            indirect: self.indirect,
            fit_light: self.fit_light,
            out: self.out.clone(),
        }
    }
}

#[derive(Subcommand, Debug)]
pub enum CheckRows {
    /// Compares a printed ComputePolygonRows output (section 4's test program) with
    /// the handout's rows of the polygon, and names the variant that prints it.
    ///
    /// Example: `rasterlab check rows mine.txt 10,5 5,10 15,15`.
    Rows(CheckRowsArgs),
}

#[derive(Args, Debug)]
pub struct CheckRowsArgs {
    /// The printout: one `Start: (x,y). End: (x,y).` per row, or all on one line;
    /// - for standard input.
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    /// The polygon's vertices as X,Y pixels, in order, as given to ComputePolygonRows;
    /// a negative coordinate goes after `--` (`check rows FILE -- -3,4 ...`).
    #[arg(required = true, value_name = "X,Y", num_args = 1.., value_parser = parse::point)]
    pub vertices: Vec<(i32, i32)>,
    /// Print the result as one JSON object instead of words.
    #[arg(long)]
    pub json: bool,
}

/// clap's error as one line: its message up to the usage block, and its tips
/// ("a similar argument exists: ..."), which follow a blank line. An option that
/// other subcommands take, or one a letter or two from such an option, gets
/// instead of clap's guess the option and the subcommands that take it.
pub fn one_line(e: &clap::Error) -> String {
    let text = e.render().to_string();
    let mut message = String::new();
    for line in text.lines().map(str::trim).take_while(|l| !l.is_empty()) {
        let sep = match message.is_empty() || message.ends_with(':') {
            true => " ",
            false => "; ",
        };
        message = format!("{message}{sep}{line}").trim_start().to_string();
    }
    let tips: Vec<&str> = text
        .lines()
        .map(str::trim)
        .filter(|l| l.starts_with("tip: "))
        .collect();
    let tip = match e.get(clap::error::ContextKind::InvalidArg) {
        Some(clap::error::ContextValue::String(arg)) => elsewhere(arg),
        _ => None,
    };
    // clap's own tip when it names the very option meant: this subcommand has it.
    let tip = tip.filter(|(meant, _)| !tips.iter().any(|t| t.contains(&format!("'--{meant}'"))));
    match tip {
        Some((_, tip)) => message = format!("{message}; tip: {tip}"),
        None => {
            for tip in tips {
                message = format!("{message}; {tip}");
            }
        }
    }
    message
}

/// Where an option this subcommand does not take is taken: `--affine is an
/// option of vertex-light, pixel-light, ...`, or for a near miss (`--afine`) the
/// option meant (with the words). `None` when no subcommand has it or
/// anything close.
fn elsewhere(arg: &str) -> Option<(String, String)> {
    let given = arg.split('=').next()?.strip_prefix("--")?;
    let cli = Cli::command();
    let mut commands: Vec<(String, &clap::Command)> = Vec::new();
    for c in cli.get_subcommands() {
        commands.push((c.get_name().to_string(), c));
        for s in c.get_subcommands().filter(|_| c.get_name() == "animate") {
            commands.push((format!("animate {}", s.get_name()), s));
        }
    }
    let longs = |c: &clap::Command| -> Vec<String> {
        c.get_arguments()
            .filter_map(|a| a.get_long().map(str::to_string))
            .collect()
    };
    let mut known: Vec<String> = commands.iter().flat_map(|(_, c)| longs(c)).collect();
    known.sort();
    known.dedup();
    let meant = match known.iter().any(|l| l == given) {
        true => given.to_string(),
        false => known
            .into_iter()
            .filter(|l| edit_distance(l, given) <= 2 && l.len() > 3)
            .min_by_key(|l| edit_distance(l, given))?,
    };
    let takers: Vec<&str> = commands
        .iter()
        .filter(|(_, c)| longs(c).contains(&meant))
        .map(|(name, _)| name.as_str())
        .collect();
    let lead = match meant == given {
        true => format!("--{meant} is an option of"),
        false => format!("did you mean --{meant}? an option of"),
    };
    Some((meant, format!("{lead} {}", takers.join(", "))))
}

/// The Levenshtein distance between two short words.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let next = (diagonal + usize::from(ca != cb))
                .min(row[j] + 1)
                .min(row[j + 1] + 1);
            diagonal = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}
