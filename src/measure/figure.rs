//! The stages by name, and the handout's figures as (stage, interpolation) pairs:
//! the one place that turns a choice made at run time into a pipeline type.

use crate::pipeline::draw::Cull;
use crate::pipeline::raster::{EdgeRaster, Lines, Rasterizer, RowRaster};
use crate::pipeline::shadow::{ShadowMap, Shadows, SHADOW_MAP_SIZE};
use crate::pipeline::stage::{
    NormalMappedPixelLight, SmoothPixelLight, SmoothTexturedPixelLight, TexturedPixelLight,
    TexturedVertexLight,
};
use crate::pipeline::{
    Affine, Camera, Depth, Filled, Frame, Interpolation, Light, Mesh, Perspective, Pipeline,
    PixelLight, Points, Render, Stage, Uniforms, VertexLight, Wireframe,
};

/// The stages, as the command line and the viewer name them, in the handout's order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum StageName {
    Points,
    Wireframe,
    Filled,
    Depth,
    VertexLight,
    PixelLight,
}

impl StageName {
    pub const ALL: [StageName; 6] = [
        StageName::Points,
        StageName::Wireframe,
        StageName::Filled,
        StageName::Depth,
        StageName::VertexLight,
        StageName::PixelLight,
    ];

    /// The subcommand's name.
    pub fn name(self) -> &'static str {
        match self {
            StageName::Points => "points",
            StageName::Wireframe => "wireframe",
            StageName::Filled => "filled",
            StageName::Depth => "depth",
            StageName::VertexLight => "vertex-light",
            StageName::PixelLight => "pixel-light",
        }
    }

    /// The stage called `name`, as the subcommands spell it.
    pub fn from_name(name: &str) -> Option<StageName> {
        StageName::ALL.into_iter().find(|s| s.name() == name)
    }

    /// Whether the stage interpolates anything whose interpolation can be affine or
    /// perspective-correct (1/z alone is always interpolated as it is).
    pub fn interpolates(self) -> bool {
        matches!(self, StageName::VertexLight | StageName::PixelLight)
    }

    /// The handout's choice for this stage: section 6.1 interpolates the
    /// illumination linearly on the screen; section 6.2 corrects the position.
    pub fn affine_by_default(self) -> bool {
        self == StageName::VertexLight
    }
}

/// Which rasterizer draws: the handout's rows (`--raster rows`, the default) or
/// the exact edge-function rasterizer (`--raster edge`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Raster {
    #[default]
    Rows,
    Edge,
}

/// A stage and how it is drawn: whether its per-pixel struct is interpolated
/// affinely (linearly on the screen) or perspective-correctly, by which
/// rasterizer, and which faces are culled. One of the handout's figures, or a
/// variation of one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Figure {
    pub stage: StageName,
    /// Only meaningful where [`StageName::interpolates`]; false elsewhere.
    pub affine: bool,
    pub raster: Raster,
    pub cull: Cull,
    /// How lines (and the rows' polygon edges) are walked: the handout's
    /// `Interpolate` or Bresenham's algorithm.
    pub lines: Lines,
    /// Shadows from a shadow map, for the lit stages.
    pub shadows: Shadows,
}

/// Something to do with a pipeline once its stage, interpolation and rasterizer
/// types are known.
pub trait WithStage {
    type Output;
    fn with<S: Stage, I: Interpolation, R: Rasterizer>(self) -> Self::Output;
}

/// What a mesh has that a stage may carry to its pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Attributes {
    /// Vertex normals, for smooth light per pixel.
    pub normals: bool,
    /// Texture coordinates and a material with a texture, for the lit stages to
    /// read ρ from.
    pub texture: bool,
    /// Texture coordinates and a material with a normal map, for light per pixel.
    pub normal_map: bool,
}

impl Attributes {
    pub fn of(mesh: &Mesh) -> Attributes {
        Attributes {
            normals: !mesh.normals.is_empty(),
            texture: !mesh.uvs.is_empty() && mesh.materials.iter().any(|m| m.texture.is_some()),
            normal_map: !mesh.uvs.is_empty()
                && mesh.materials.iter().any(|m| m.normal_map.is_some()),
        }
    }
}

/// The stage type for `stage` and a mesh with `attributes`, chosen here once,
/// never per pixel: light per pixel on a mesh with vertex normals is
/// [`SmoothPixelLight`]; a textured mesh's lit stages interpolate texture
/// coordinates, and only then; `shadows` picks the lit stages' `SHADOWS`.
fn with_types<I: Interpolation, R: Rasterizer, W: WithStage>(
    stage: StageName,
    attributes: Attributes,
    shadows: bool,
    w: W,
) -> W::Output {
    match stage {
        StageName::Points => w.with::<Points, I, R>(),
        StageName::Wireframe => w.with::<Wireframe, I, R>(),
        StageName::Filled => w.with::<Filled, I, R>(),
        StageName::Depth => w.with::<Depth, I, R>(),
        _ if shadows => with_lit_types::<I, R, W, true>(stage, attributes, w),
        _ => with_lit_types::<I, R, W, false>(stage, attributes, w),
    }
}

/// [`with_types`] for vertex-light and pixel-light, with or without shadows.
fn with_lit_types<I: Interpolation, R: Rasterizer, W: WithStage, const SHADOWS: bool>(
    stage: StageName,
    attributes: Attributes,
    w: W,
) -> W::Output {
    let Attributes {
        normals,
        texture,
        normal_map,
    } = attributes;
    match stage {
        StageName::VertexLight if texture => w.with::<TexturedVertexLight<SHADOWS>, I, R>(),
        StageName::VertexLight => w.with::<VertexLight<SHADOWS>, I, R>(),
        StageName::PixelLight if normal_map => w.with::<NormalMappedPixelLight<SHADOWS>, I, R>(),
        StageName::PixelLight if normals && texture => {
            w.with::<SmoothTexturedPixelLight<SHADOWS>, I, R>()
        }
        StageName::PixelLight if normals => w.with::<SmoothPixelLight<SHADOWS>, I, R>(),
        StageName::PixelLight if texture => w.with::<TexturedPixelLight<SHADOWS>, I, R>(),
        _ => w.with::<PixelLight<SHADOWS>, I, R>(),
    }
}

struct NewPipeline {
    cull: Cull,
    lines: Lines,
}

impl WithStage for NewPipeline {
    type Output = Box<dyn Render + Send>;
    fn with<S: Stage, I: Interpolation, R: Rasterizer>(self) -> Box<dyn Render + Send> {
        let mut pipeline = Pipeline::<S, I, R>::new();
        pipeline.cull = self.cull;
        pipeline.lines = self.lines;
        Box::new(pipeline)
    }
}

impl Figure {
    /// Figures 2 to 8, in the handout's order, as `rasterlab all` writes them.
    pub const FIGURES: [Figure; 7] = [
        Figure::of(StageName::Points),
        Figure::of(StageName::Wireframe),
        Figure::of(StageName::Filled),
        Figure::of(StageName::Depth),
        Figure::of(StageName::VertexLight),
        Figure::of(StageName::PixelLight),
        Figure {
            stage: StageName::PixelLight,
            affine: true,
            raster: Raster::Rows,
            cull: Cull::None,
            lines: Lines::Interpolate,
            shadows: Shadows::None,
        },
    ];

    /// The stage as the handout draws it.
    pub const fn of(stage: StageName) -> Self {
        Figure {
            stage,
            affine: matches!(stage, StageName::VertexLight),
            raster: Raster::Rows,
            cull: Cull::None,
            lines: Lines::Interpolate,
            shadows: Shadows::None,
        }
    }

    /// The stage with the interpolation given (`Some(true)` affine), or the
    /// handout's when `None` or when the stage interpolates nothing it would change.
    pub fn with_interpolation(stage: StageName, affine: Option<bool>) -> Self {
        Figure {
            affine: match affine {
                Some(a) if stage.interpolates() => a,
                _ => Figure::of(stage).affine,
            },
            ..Figure::of(stage)
        }
    }

    pub fn with_raster(self, raster: Raster) -> Self {
        Figure { raster, ..self }
    }

    pub fn with_cull(self, cull: Cull) -> Self {
        Figure { cull, ..self }
    }

    pub fn with_lines(self, lines: Lines) -> Self {
        Figure { lines, ..self }
    }

    /// The light's shadow map when this figure draws shadows; none otherwise, so
    /// a frame without shadows draws no map. `near` is the camera's near plane.
    /// The map is drawn by the depth stage with the exact rasterizer, which
    /// samples the texel centres the lookups assume.
    pub fn shadow_map(self, mesh: &Mesh, light: &Light, near: f32) -> Option<ShadowMap> {
        if self.shadows == Shadows::None {
            return None;
        }
        let mut pipeline = Pipeline::<Depth, Perspective, EdgeRaster>::new();
        let uniforms = Uniforms::lit(*light);
        let draw_depth = |camera: &Camera| {
            let mut frame = Frame::default();
            pipeline.render(mesh, camera, &uniforms, &mut frame);
            frame
        };
        Some(ShadowMap::render(
            light.position,
            SHADOW_MAP_SIZE,
            near,
            self.shadows,
            draw_depth,
        ))
    }

    /// With shadows, for the lit stages; others draw no light to shadow.
    pub fn with_shadows(self, shadows: Shadows) -> Self {
        let lit = matches!(self.stage, StageName::VertexLight | StageName::PixelLight);
        Figure {
            shadows: if lit { shadows } else { Shadows::None },
            ..self
        }
    }

    /// Whether this is the handout's interpolation for its stage.
    pub fn is_default(self) -> bool {
        self.affine == Figure::of(self.stage).affine
    }

    /// The file name `rasterlab all` gives this figure.
    pub fn figure_file(self) -> &'static str {
        match (self.stage, self.affine) {
            (StageName::Points, _) => "fig2-points.png",
            (StageName::Wireframe, _) => "fig3-wireframe.png",
            (StageName::Filled, _) => "fig4-filled.png",
            (StageName::Depth, _) => "fig5-depth.png",
            (StageName::VertexLight, true) => "fig6-vertex-light.png",
            (StageName::VertexLight, false) => "fig6-vertex-light-perspective.png",
            (StageName::PixelLight, false) => "fig7-pixel-light.png",
            (StageName::PixelLight, true) => "fig8-pixel-light-affine.png",
        }
    }

    /// The options that select this interpolation when it is not the handout's:
    /// `--affine` or `--interpolation perspective`; empty for the default.
    pub fn interpolation_flag(self) -> &'static str {
        match (self.is_default(), self.affine) {
            (true, _) => "",
            (false, true) => " --affine",
            (false, false) => " --interpolation perspective",
        }
    }

    /// Every option that makes this figure differ from the handout's, as the
    /// command line spells them: ` --affine --raster edge --cull back`.
    pub fn flags(self) -> String {
        let mut flags = self.interpolation_flag().to_string();
        if self.raster == Raster::Edge {
            flags += " --raster edge";
        }
        match self.cull {
            Cull::None => {}
            Cull::Back => flags += " --cull back",
            Cull::Front => flags += " --cull front",
        }
        if self.lines == Lines::Bresenham {
            flags += " --lines bresenham";
        }
        match self.shadows {
            Shadows::None => {}
            Shadows::Hard => flags += " --shadows",
            Shadows::Pcf => flags += " --shadows --pcf",
        }
        flags
    }

    /// A short label: the stage name and the options that change it.
    pub fn label(self) -> String {
        format!("{}{}", self.stage.name(), self.flags())
    }

    /// The image file a stage subcommand writes without `-o`: the label's words
    /// joined, so `pixel-light --affine` does not overwrite `pixel-light.png`.
    pub fn default_file(self) -> String {
        let words = self
            .flags()
            .replace(" --interpolation ", " ")
            .replace(" --", " ");
        let words: Vec<&str> = words.split_whitespace().collect();
        if words.is_empty() {
            format!("{}.png", self.stage.name())
        } else {
            format!("{}-{}.png", self.stage.name(), words.join("-"))
        }
    }

    /// Calls `w` with this figure's stage, interpolation and rasterizer types, for
    /// a mesh with `attributes`.
    pub fn with_stage<W: WithStage>(self, attributes: Attributes, w: W) -> W::Output {
        let (stage, a) = (self.stage, attributes);
        let sh = self.shadows != Shadows::None;
        match (self.affine, self.raster) {
            (false, Raster::Rows) => with_types::<Perspective, RowRaster, W>(stage, a, sh, w),
            (true, Raster::Rows) => with_types::<Affine, RowRaster, W>(stage, a, sh, w),
            (false, Raster::Edge) => with_types::<Perspective, EdgeRaster, W>(stage, a, sh, w),
            (true, Raster::Edge) => with_types::<Affine, EdgeRaster, W>(stage, a, sh, w),
        }
    }

    /// The pipeline that draws this figure of `mesh`: the stage types fit the
    /// mesh's attributes (smooth light where it has vertex normals, texture
    /// coordinates where it has a texture).
    pub fn pipeline_for(self, mesh: &Mesh) -> Box<dyn Render + Send> {
        self.with_stage(
            Attributes::of(mesh),
            NewPipeline {
                cull: self.cull,
                lines: self.lines,
            },
        )
    }

    /// Draws this figure of `mesh` into a new frame.
    pub fn render(self, mesh: &Mesh, camera: &Camera, uniforms: &Uniforms) -> Frame {
        let mut frame = Frame::default();
        self.pipeline_for(mesh)
            .render(mesh, camera, uniforms, &mut frame);
        frame
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_say_what_differs_from_the_handout() {
        let f = |stage, affine| Figure::with_interpolation(stage, affine);
        assert_eq!(f(StageName::VertexLight, None).label(), "vertex-light");
        assert_eq!(
            f(StageName::VertexLight, Some(false)).label(),
            "vertex-light --interpolation perspective"
        );
        assert_eq!(
            f(StageName::PixelLight, Some(true)).label(),
            "pixel-light --affine"
        );
        assert_eq!(
            f(StageName::Depth, Some(true)),
            Figure::of(StageName::Depth)
        );
        assert_eq!(
            f(StageName::PixelLight, Some(true)).default_file(),
            "pixel-light-affine.png"
        );
        assert_eq!(
            f(StageName::VertexLight, Some(false)).default_file(),
            "vertex-light-perspective.png"
        );
        assert_eq!(Figure::of(StageName::Points).default_file(), "points.png");
        let files: Vec<&str> = Figure::FIGURES.iter().map(|f| f.figure_file()).collect();
        assert_eq!(files[4], "fig6-vertex-light.png");
        assert_eq!(files[6], "fig8-pixel-light-affine.png");
    }
}
