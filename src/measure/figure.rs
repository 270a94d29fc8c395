//! The stages by name, and the handout's figures as (stage, interpolation) pairs:
//! the one place that turns a choice made at run time into a pipeline type.

use crate::pipeline::{
    Affine, Camera, Depth, Filled, Frame, Interpolation, Mesh, Perspective, Pipeline, PixelLight,
    Points, Render, Stage, Uniforms, VertexLight, Wireframe,
};

/// The stages, as the command line and the viewer name them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
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

    /// Whether `--affine` changes anything for this stage.
    pub fn interpolates(self) -> bool {
        matches!(
            self,
            StageName::Depth | StageName::VertexLight | StageName::PixelLight
        )
    }
}

/// A stage and whether it interpolates affinely: one of the handout's figures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Figure {
    pub stage: StageName,
    pub affine: bool,
}

/// Something to do with a pipeline once its stage and interpolation types are known.
pub trait WithStage {
    type Output;
    fn with<S: Stage, I: Interpolation>(self) -> Self::Output;
}

fn with_interpolation<I: Interpolation, W: WithStage>(stage: StageName, w: W) -> W::Output {
    match stage {
        StageName::Points => w.with::<Points, I>(),
        StageName::Wireframe => w.with::<Wireframe, I>(),
        StageName::Filled => w.with::<Filled, I>(),
        StageName::Depth => w.with::<Depth, I>(),
        StageName::VertexLight => w.with::<VertexLight, I>(),
        StageName::PixelLight => w.with::<PixelLight, I>(),
    }
}

struct NewPipeline;

impl WithStage for NewPipeline {
    type Output = Box<dyn Render>;
    fn with<S: Stage, I: Interpolation>(self) -> Box<dyn Render> {
        Box::new(Pipeline::<S, I>::new())
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
        },
    ];

    pub const fn of(stage: StageName) -> Self {
        Figure {
            stage,
            affine: false,
        }
    }

    /// The file name `rasterlab all` gives this figure.
    pub fn figure_file(self) -> &'static str {
        match (self.stage, self.affine) {
            (StageName::Points, _) => "fig2-points.png",
            (StageName::Wireframe, _) => "fig3-wireframe.png",
            (StageName::Filled, _) => "fig4-filled.png",
            (StageName::Depth, false) => "fig5-depth.png",
            (StageName::Depth, true) => "fig5-depth-affine.png",
            (StageName::VertexLight, false) => "fig6-vertex-light.png",
            (StageName::VertexLight, true) => "fig6-vertex-light-affine.png",
            (StageName::PixelLight, false) => "fig7-pixel-light.png",
            (StageName::PixelLight, true) => "fig8-pixel-light-affine.png",
        }
    }

    /// A short label: the stage name, with ` --affine` where it applies.
    pub fn label(self) -> String {
        if self.affine && self.stage.interpolates() {
            format!("{} --affine", self.stage.name())
        } else {
            self.stage.name().to_string()
        }
    }

    /// Calls `w` with this figure's stage and interpolation types.
    pub fn with_stage<W: WithStage>(self, w: W) -> W::Output {
        if self.affine {
            with_interpolation::<Affine, W>(self.stage, w)
        } else {
            with_interpolation::<Perspective, W>(self.stage, w)
        }
    }

    /// The pipeline that draws this figure.
    pub fn pipeline(self) -> Box<dyn Render> {
        self.with_stage(NewPipeline)
    }

    /// Draws this figure of `mesh` into a new frame.
    pub fn render(self, mesh: &Mesh, camera: &Camera, uniforms: &Uniforms) -> Frame {
        let mut frame = Frame::default();
        self.pipeline().render(mesh, camera, uniforms, &mut frame);
        frame
    }
}
