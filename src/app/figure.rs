//! The stages by name, and the handout's figures as (stage, interpolation) pairs:
//! the one place that turns a choice made at run time into a pipeline type, and
//! the one that knows which stages beyond the handout a mesh's maps call for.

use crate::extensions::normal_map::{tangent_frames, NormalMappedPixelLight, TangentFrame};
use crate::extensions::shadow::{ShadowMap, Shadowed, Shadows, SHADOW_MAP_SIZE};
use crate::extensions::smooth::SmoothPixelLight;
use crate::extensions::texture::{Filter, Maps, Model, NO_MAPS};
use crate::extensions::textured::{
    SmoothTexturedPixelLight, TexturedPixelLight, TexturedVertexLight,
};
use crate::pipeline::draw::{Cull, Handover, Stats};
use crate::pipeline::raster::{EdgeRaster, Lines, Rasterizer, RowRaster, SharedPlacing};
use crate::pipeline::vertices::Vertices;
use crate::pipeline::StageName;
use crate::pipeline::{
    Affine, Camera, Depth, Filled, Frame, Interpolation, Light, Lighting, Mesh, Perspective,
    Pipeline, PixelLight, Points, Primitive, Stage, Target, Varying, VertexLight, Wireframe,
};
use glam::Vec3;
use std::marker::PhantomData;

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

/// Everything the stages of one frame read, beyond the mesh: the light, and for
/// the stages beyond the handout the mesh's maps, how they are read, the shadow
/// map, the eye and the faces' tangent frames.
#[derive(Clone, Copy, Debug)]
pub struct Inputs<'a> {
    pub light: Light,
    pub maps: &'a Maps,
    pub filter: Filter,
    pub shadow: Option<&'a ShadowMap>,
    /// The camera's position, for parallax.
    pub eye: Vec3,
    /// The faces' tangent frames, for normal maps.
    pub frames: &'a [TangentFrame],
}

impl Inputs<'static> {
    /// Just the light: the handout's stages need nothing more.
    pub fn lit(light: Light) -> Self {
        Inputs {
            light,
            maps: &NO_MAPS,
            filter: Filter::Nearest,
            shadow: None,
            eye: Vec3::ZERO,
            frames: &[],
        }
    }
}

/// A stage type chosen at run time, made for each frame from that frame's
/// [`Inputs`] (a stage owns what it reads, so it lives no longer than they do).
pub trait MakeStage: 'static {
    type Varying: Varying;
    type Stage<'a>: Stage<Varying = Self::Varying>;
    fn make<'a>(inputs: &Inputs<'a>) -> Self::Stage<'a>;
}

/// What lights a lit stage, chosen at run time: the handout's [`Light`], or
/// [`WithShadows`].
pub trait MakeLight: 'static {
    type Lighting<'a>: Lighting;
    fn make<'a>(inputs: &Inputs<'a>) -> Self::Lighting<'a>;
}

impl MakeLight for Light {
    type Lighting<'a> = Light;
    fn make(inputs: &Inputs) -> Light {
        inputs.light
    }
}

/// The light through the frame's shadow map ([`Shadowed`]).
pub struct WithShadows;

impl MakeLight for WithShadows {
    type Lighting<'a> = Shadowed<'a>;
    fn make<'a>(inputs: &Inputs<'a>) -> Shadowed<'a> {
        Shadowed {
            light: inputs.light,
            map: inputs.shadow,
        }
    }
}

macro_rules! make_plain {
    ($($stage:ident),*) => {$(
        impl MakeStage for $stage {
            type Varying = <$stage as Stage>::Varying;
            type Stage<'a> = $stage;
            fn make(_: &Inputs) -> $stage {
                $stage
            }
        }
    )*};
}

make_plain!(Points, Wireframe, Filled, Depth);

macro_rules! make_lit {
    ($($stage:ident),*) => {$(
        impl<L: MakeLight> MakeStage for $stage<L> {
            type Varying = <$stage as Stage>::Varying;
            type Stage<'a> = $stage<L::Lighting<'a>>;
            fn make<'a>(inputs: &Inputs<'a>) -> Self::Stage<'a> {
                $stage { light: L::make(inputs) }
            }
        }
    )*};
}

make_lit!(VertexLight, PixelLight, SmoothPixelLight);

macro_rules! make_textured {
    ($($stage:ident),*) => {$(
        impl<L: MakeLight> MakeStage for $stage<'static, L> {
            type Varying = <$stage<'static> as Stage>::Varying;
            type Stage<'a> = $stage<'a, L::Lighting<'a>>;
            fn make<'a>(inputs: &Inputs<'a>) -> Self::Stage<'a> {
                $stage {
                    light: L::make(inputs),
                    maps: inputs.maps,
                    filter: inputs.filter,
                }
            }
        }
    )*};
}

make_textured!(
    TexturedVertexLight,
    TexturedPixelLight,
    SmoothTexturedPixelLight
);

impl<L: MakeLight> MakeStage for NormalMappedPixelLight<'static, L> {
    type Varying = <NormalMappedPixelLight<'static> as Stage>::Varying;
    type Stage<'a> = NormalMappedPixelLight<'a, L::Lighting<'a>>;
    fn make<'a>(inputs: &Inputs<'a>) -> Self::Stage<'a> {
        NormalMappedPixelLight {
            light: L::make(inputs),
            maps: inputs.maps,
            filter: inputs.filter,
            frames: inputs.frames,
            eye: inputs.eye,
        }
    }
}

/// Something to do with a pipeline once its stage, interpolation and rasterizer
/// types are known.
pub trait WithStage {
    type Output;
    fn with<M: MakeStage, I: Interpolation, R: Rasterizer>(self) -> Self::Output;
}

/// What a mesh has that a stage may carry to its pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Attributes {
    /// Vertex normals, for smooth light per pixel.
    pub normals: bool,
    /// (u, v) coordinates and a material with a texture, for the lit stages to
    /// read ρ from.
    pub texture: bool,
    /// (u, v) coordinates and a material with a normal map, for light per pixel.
    pub normal_map: bool,
}

impl Attributes {
    pub fn of(model: Model) -> Attributes {
        Attributes {
            normals: !model.mesh.normals.is_empty(),
            texture: model.maps.any(model.mesh, |m| m.texture),
            normal_map: model.maps.any(model.mesh, |m| m.normal_map),
        }
    }
}

/// The stage type for `stage` and a mesh with `attributes`, chosen here once,
/// never per pixel: light per pixel on a mesh with vertex normals is
/// [`SmoothPixelLight`]; a textured mesh's lit stages interpolate (u, v)
/// coordinates, and only then; `shadows` lights the lit stages through the
/// shadow map.
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
        _ if shadows => with_lit_types::<I, R, W, WithShadows>(stage, attributes, w),
        _ => with_lit_types::<I, R, W, Light>(stage, attributes, w),
    }
}

/// [`with_types`] for vertex-light and pixel-light, lit by `L`.
fn with_lit_types<I: Interpolation, R: Rasterizer, W: WithStage, L: MakeLight>(
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
        StageName::VertexLight if texture => w.with::<TexturedVertexLight<L>, I, R>(),
        StageName::VertexLight => w.with::<VertexLight<L>, I, R>(),
        StageName::PixelLight if normal_map => w.with::<NormalMappedPixelLight<L>, I, R>(),
        StageName::PixelLight if normals && texture => {
            w.with::<SmoothTexturedPixelLight<L>, I, R>()
        }
        StageName::PixelLight if normals => w.with::<SmoothPixelLight<L>, I, R>(),
        StageName::PixelLight if texture => w.with::<TexturedPixelLight<L>, I, R>(),
        _ => w.with::<PixelLight<L>, I, R>(),
    }
}

/// What every band of a frame reads: the inputs its stage is made from, the
/// mesh, the camera, and the mesh's vertices prepared once for all bands
/// ([`Vertices::prepare`]).
#[derive(Clone, Copy)]
pub struct Prepared<'a> {
    pub inputs: &'a Inputs<'a>,
    pub mesh: &'a Mesh,
    pub camera: &'a Camera,
    pub vertices: &'a Vertices,
}

/// A pipeline whose stage was chosen at run time, behind one interface.
pub trait Render: Send {
    /// [`Pipeline::draw`] with the stage made from `inputs`: draws `mesh` into
    /// `target`, a band of the camera's image.
    fn draw(&mut self, inputs: &Inputs, mesh: &Mesh, camera: &Camera, target: &mut Target);

    /// [`Render::draw`] with the frame's vertices prepared once for all bands,
    /// beside another thread, which may take some of the band's rows
    /// ([`Pipeline::draw_sharing`]).
    fn draw_sharing<'t>(
        &mut self,
        frame: Prepared,
        target: &mut Target<'t>,
        handover: Option<&dyn Handover<'t>>,
    );

    /// The faces from face `from` on, drawn into rows another thread handed
    /// over ([`Pipeline::draw_given`]).
    fn draw_given(&mut self, frame: Prepared, target: &mut Target, from: usize);

    /// What the last frame did.
    fn stats(&self) -> Stats;

    /// Whether the stage tests depth, so its target needs a depth buffer.
    fn depth_test(&self) -> bool;

    /// What the stage draws for each triangle.
    fn primitive(&self) -> Primitive;

    /// How the rasterizer's places may be made for every band at once
    /// ([`Rasterizer::SHARED`]).
    fn shared_placing(&self) -> Option<SharedPlacing>;

    /// Sizes `frame` to the camera's image and draws `mesh` into all of it.
    fn render(&mut self, inputs: &Inputs, mesh: &Mesh, camera: &Camera, frame: &mut Frame) {
        frame.resize(camera.width, camera.height, self.depth_test());
        self.draw(inputs, mesh, camera, &mut frame.target());
    }
}

/// The pipeline of stage `M`, interpolated by `I` and rasterized by `R`.
struct Drawn<M: MakeStage, I: Interpolation, R: Rasterizer> {
    pipeline: Pipeline<M::Varying, I, R>,
    stage: PhantomData<fn() -> M>,
}

impl<M: MakeStage, I: Interpolation, R: Rasterizer> Render for Drawn<M, I, R> {
    fn draw(&mut self, inputs: &Inputs, mesh: &Mesh, camera: &Camera, target: &mut Target) {
        self.pipeline.draw(&M::make(inputs), mesh, camera, target)
    }

    fn draw_sharing<'t>(
        &mut self,
        frame: Prepared,
        target: &mut Target<'t>,
        handover: Option<&dyn Handover<'t>>,
    ) {
        let Prepared { mesh, camera, .. } = frame;
        let stage = M::make(frame.inputs);
        self.pipeline
            .draw_sharing(&stage, mesh, camera, frame.vertices, target, handover)
    }

    fn draw_given(&mut self, frame: Prepared, target: &mut Target, from: usize) {
        let Prepared { mesh, camera, .. } = frame;
        let stage = M::make(frame.inputs);
        self.pipeline
            .draw_given(&stage, mesh, camera, frame.vertices, target, from)
    }

    fn stats(&self) -> Stats {
        *self.pipeline.stats()
    }

    fn depth_test(&self) -> bool {
        <M::Stage<'static> as Stage>::DEPTH_TEST
    }

    fn primitive(&self) -> Primitive {
        <M::Stage<'static> as Stage>::PRIMITIVE
    }

    fn shared_placing(&self) -> Option<SharedPlacing> {
        R::SHARED
    }
}

struct NewPipeline {
    cull: Cull,
    lines: Lines,
    batch_shading: bool,
}

impl WithStage for NewPipeline {
    type Output = Box<dyn Render>;
    fn with<M: MakeStage, I: Interpolation, R: Rasterizer>(self) -> Box<dyn Render> {
        let mut pipeline = Pipeline::<M::Varying, I, R>::new();
        pipeline.cull = self.cull;
        pipeline.lines = self.lines;
        pipeline.batch_shading = self.batch_shading;
        Box::new(Drawn::<M, I, R> {
            pipeline,
            stage: PhantomData,
        })
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
    pub fn shadow_map(self, mesh: &Mesh, light: &Light, near: f32) -> Option<ShadowMap> {
        if self.shadows == Shadows::None {
            return None;
        }
        Some(ShadowMap::render(
            light.position,
            SHADOW_MAP_SIZE,
            near,
            self.shadows,
            mesh,
        ))
    }

    /// With shadows, for the lit stages; others draw no light to shadow.
    pub fn with_shadows(self, shadows: Shadows) -> Self {
        let lit = self.stage.is_lit();
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

    /// The pipeline that draws this figure of `model`: the stage types fit the
    /// mesh's attributes (smooth light where it has vertex normals, (u, v)
    /// coordinates where it has a texture).
    pub fn pipeline_for<'a>(self, model: impl Into<Model<'a>>) -> Box<dyn Render> {
        let attributes = Attributes::of(model.into());
        // Light per pixel vectorises when shaded a triangle at a time; a texture
        // lookup does not, and light per vertex is too light to gain.
        let batch_shading =
            self.stage == StageName::PixelLight && !attributes.texture && !attributes.normal_map;
        self.with_stage(
            attributes,
            NewPipeline {
                cull: self.cull,
                lines: self.lines,
                batch_shading,
            },
        )
    }

    /// The faces' tangent frames this figure of `model` reads ([`Inputs::frames`]):
    /// every face's where it draws a normal map, none otherwise.
    pub fn tangent_frames<'a>(self, model: impl Into<Model<'a>>) -> Vec<TangentFrame> {
        let model = model.into();
        let mapped = self.stage == StageName::PixelLight && Attributes::of(model).normal_map;
        match mapped {
            true => tangent_frames(model.mesh),
            false => Vec::new(),
        }
    }

    /// Draws this figure of `mesh`, lit by `light`, into a new frame: the
    /// handout's stages on a mesh's colours.
    pub fn render(self, mesh: &Mesh, camera: &Camera, light: Light) -> Frame {
        let mut frame = Frame::default();
        self.pipeline_for(mesh)
            .render(&Inputs::lit(light), mesh, camera, &mut frame);
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
