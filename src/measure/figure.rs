//! The stages by name, and the handout's figures as (stage, interpolation) pairs:
//! the one place that turns a choice made at run time into a pipeline type.

use crate::pipeline::{
    Affine, Camera, Depth, Filled, Frame, Interpolation, Mesh, Perspective, Pipeline, PixelLight,
    Points, Render, Stage, Uniforms, VertexLight, Wireframe,
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

/// A stage and whether its per-pixel struct is interpolated affinely (linearly on
/// the screen) or perspective-correctly: one of the handout's figures, or a
/// variation of one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Figure {
    pub stage: StageName,
    /// Only meaningful where [`StageName::interpolates`]; false elsewhere.
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

    /// The stage as the handout draws it.
    pub const fn of(stage: StageName) -> Self {
        Figure {
            stage,
            affine: matches!(stage, StageName::VertexLight),
        }
    }

    /// The stage with the interpolation given (`Some(true)` affine), or the
    /// handout's when `None` or when the stage interpolates nothing it would change.
    pub fn with_interpolation(stage: StageName, affine: Option<bool>) -> Self {
        Figure {
            stage,
            affine: match affine {
                Some(a) if stage.interpolates() => a,
                _ => Figure::of(stage).affine,
            },
        }
    }

    /// Whether this is the handout's interpolation for its stage.
    pub fn is_default(self) -> bool {
        self == Figure::of(self.stage)
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

    /// A short label: the stage name and any option that changes its interpolation.
    pub fn label(self) -> String {
        format!("{}{}", self.stage.name(), self.interpolation_flag())
    }

    /// The image file a stage subcommand writes without `-o`: the label's words
    /// joined, so `pixel-light --affine` does not overwrite `pixel-light.png`.
    pub fn default_file(self) -> String {
        let flag = self.interpolation_flag().trim_start_matches(" --");
        let flag = flag.strip_prefix("interpolation ").unwrap_or(flag);
        if flag.is_empty() {
            format!("{}.png", self.stage.name())
        } else {
            format!("{}-{flag}.png", self.stage.name())
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
