//! The handout's stages as values. A stage is the handout's `VertexShader` and
//! `PixelShader` and the per-pixel struct between them ([`Stage::Varying`]), plus
//! the primitive it draws and whether it tests depth; it owns what its shaders
//! read (a lit stage its light). The rest is the shared core in [`super::draw`].
//!
//! | stage | section | primitive | depth test | interpolated |
//! |---|---|---|---|---|
//! | [`Points`] | 2 | points | no | nothing |
//! | [`Wireframe`] | 3 | lines | no | nothing |
//! | [`Filled`] | 4 | polygons | no | nothing |
//! | [`Depth`] | 5 | polygons | yes | nothing (1/z is the core's) |
//! | [`VertexLight`] | 6.1 | polygons | yes | [`Illumination`]: eq. 11 at the vertices |
//! | [`PixelLight`] | 6.2 | polygons | yes | [`Position`]: the 3D position |
//!
//! Section 6 says a richer image needs new shaders and a new per-pixel struct,
//! never a new core: `crate::extensions` holds those stages.

use super::interpolate::{linear_ops, Nothing, Varying};
use super::light::Light;
use super::mesh::{Mesh, Vertex};
use glam::Vec3;

/// The handout's six stages by name, in its order, as the command line and the
/// viewer name them.
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

    /// Whether the stage draws light (section 6): vertex-light and pixel-light.
    pub fn is_lit(self) -> bool {
        matches!(self, StageName::VertexLight | StageName::PixelLight)
    }

    /// Whether the stage tests depth (section 5 on): depth and the lit stages.
    pub fn has_depth(self) -> bool {
        matches!(
            self,
            StageName::Depth | StageName::VertexLight | StageName::PixelLight
        )
    }

    /// Whether the stage interpolates anything whose interpolation can be affine or
    /// perspective-correct (1/z alone is always interpolated as it is): the lit
    /// stages' light or position.
    pub fn interpolates(self) -> bool {
        self.is_lit()
    }

    /// The handout's choice for this stage: section 6.1 interpolates the
    /// illumination linearly on the screen; section 6.2 corrects the position.
    pub fn affine_by_default(self) -> bool {
        self == StageName::VertexLight
    }
}

/// What a stage draws for each triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Primitive {
    /// Each projected vertex as one pixel (section 2).
    Points,
    /// Each edge as a line (section 3).
    Lines,
    /// Each triangle filled (section 4).
    Polygons,
}

/// The triangle being drawn, as its shaders see it: the handout's `currentNormal`
/// and `currentReflectance`, and which face and material of the mesh it is (for
/// stages that keep more about either).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Surface {
    pub normal: Vec3,
    /// The material's colour: ρ of eq. 11.
    pub reflectance: Vec3,
    /// Index into the mesh's faces.
    pub face: u32,
    /// Index into the mesh's materials.
    pub material: u32,
}

impl Surface {
    /// Face `index` of `mesh` as its shaders see it.
    pub fn of(mesh: &Mesh, index: usize) -> Surface {
        let face = &mesh.faces[index];
        Surface {
            normal: face.normal,
            reflectance: mesh.material(face).color,
            face: index as u32,
            material: face.material,
        }
    }
}

/// One stage of the handout, or any other pair of shaders.
pub trait Stage: Sync {
    /// What the vertex shader computes and every pixel receives, interpolated.
    type Varying: Varying;
    const PRIMITIVE: Primitive;
    /// Whether pixels go through the depth test of section 5.
    const DEPTH_TEST: bool;

    /// The stage's part of the handout's `VertexShader` (the projection is the
    /// core's): what the pixels of this vertex's triangle interpolate.
    fn vertex_shader(&self, vertex: &Vertex, surface: &Surface) -> Self::Varying;

    /// The colour part of the handout's `PixelShader` (the depth test is the
    /// core's): a linear colour, which the render target rounds to 8 bits.
    fn pixel_shader(&self, varying: &Self::Varying, surface: &Surface) -> Vec3;

    /// Whether the pixel shader colours every varying the same on `a` as on
    /// `b`: a stage that reads less of the surface than all of it says so, and
    /// the pipeline may shade the pixels of such faces together.
    fn shades_alike(a: &Surface, b: &Surface) -> bool {
        a == b
    }
}

/// What lights a lit stage: eq. 11 at a surface point. The handout's [`Light`]
/// is one; a stage adapter may put its own in (one that blocks part of the
/// direct light, say), and the lit stages stay as they are.
pub trait Lighting: Copy + Sync {
    /// The light leaving a point at `position` whose normal is `normal` and
    /// reflectance `rho`, on `surface` (whose own normal may differ from a smooth
    /// or mapped `normal`).
    fn reflected(&self, position: Vec3, normal: Vec3, surface: &Surface, rho: Vec3) -> Vec3;

    /// Whether `reflected` is the same on `a` as on `b` for every other
    /// argument ([`Stage::shades_alike`]).
    fn shades_alike(a: &Surface, b: &Surface) -> bool {
        a == b
    }
}

impl Lighting for Light {
    #[inline]
    fn reflected(&self, position: Vec3, normal: Vec3, _: &Surface, rho: Vec3) -> Vec3 {
        Light::reflected(self, position, normal, rho)
    }

    /// The handout's light reads nothing of the surface beyond the normal and
    /// reflectance it is handed.
    fn shades_alike(_: &Surface, _: &Surface) -> bool {
        true
    }
}

/// Section 2: the projected vertices, white on black.
#[derive(Clone, Copy, Debug, Default)]
pub struct Points;

impl Stage for Points {
    type Varying = Nothing;
    const PRIMITIVE: Primitive = Primitive::Points;
    const DEPTH_TEST: bool = false;

    fn vertex_shader(&self, _: &Vertex, _: &Surface) -> Nothing {
        Nothing {}
    }

    fn pixel_shader(&self, _: &Nothing, _: &Surface) -> Vec3 {
        Vec3::ONE
    }
}

/// Section 3: the triangles' edges, white on black.
#[derive(Clone, Copy, Debug, Default)]
pub struct Wireframe;

impl Stage for Wireframe {
    type Varying = Nothing;
    const PRIMITIVE: Primitive = Primitive::Lines;
    const DEPTH_TEST: bool = false;

    fn vertex_shader(&self, _: &Vertex, _: &Surface) -> Nothing {
        Nothing {}
    }

    fn pixel_shader(&self, _: &Nothing, _: &Surface) -> Vec3 {
        Vec3::ONE
    }
}

/// Section 4: triangles filled in their colour, in scene order (no occlusion).
#[derive(Clone, Copy, Debug, Default)]
pub struct Filled;

impl Stage for Filled {
    type Varying = Nothing;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = false;

    fn vertex_shader(&self, _: &Vertex, _: &Surface) -> Nothing {
        Nothing {}
    }

    fn pixel_shader(&self, _: &Nothing, surface: &Surface) -> Vec3 {
        surface.reflectance
    }
}

/// Section 5: filled triangles behind a depth buffer of 1/z.
#[derive(Clone, Copy, Debug, Default)]
pub struct Depth;

impl Stage for Depth {
    type Varying = Nothing;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;

    fn vertex_shader(&self, _: &Vertex, _: &Surface) -> Nothing {
        Nothing {}
    }

    fn pixel_shader(&self, _: &Nothing, surface: &Surface) -> Vec3 {
        surface.reflectance
    }
}

/// Section 6.1's per-pixel struct: the light R of eq. 11 that leaves the surface.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Illumination {
    pub light: Vec3,
}

linear_ops!(Illumination { light });

/// Section 6.1: eq. 10 and 11 at each vertex; the reflected light is interpolated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexLight<L = Light> {
    pub light: L,
}

impl<L: Lighting> Stage for VertexLight<L> {
    type Varying = Illumination;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;

    fn vertex_shader(&self, vertex: &Vertex, surface: &Surface) -> Illumination {
        let rho = surface.reflectance;
        Illumination {
            light: self
                .light
                .reflected(vertex.position, vertex.normal, surface, rho),
        }
    }

    fn pixel_shader(&self, varying: &Illumination, _: &Surface) -> Vec3 {
        varying.light
    }
}

/// Section 6.2's per-pixel struct: the handout's `pos3d`, the point's world position.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Position {
    pub world: Vec3,
}

linear_ops!(Position { world });

/// Section 6.2: the 3D position is interpolated and eq. 10 and 11 run at each
/// pixel with the triangle's normal and reflectance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelLight<L = Light> {
    pub light: L,
}

impl<L: Lighting> Stage for PixelLight<L> {
    type Varying = Position;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;

    fn vertex_shader(&self, vertex: &Vertex, _: &Surface) -> Position {
        Position {
            world: vertex.position,
        }
    }

    #[inline]
    fn pixel_shader(&self, varying: &Position, surface: &Surface) -> Vec3 {
        let rho = surface.reflectance;
        self.light
            .reflected(varying.world, surface.normal, surface, rho)
    }

    /// The same normal and reflectance, bit for bit (0.0 and -0.0 are not
    /// taken as one), and a light that reads nothing else.
    fn shades_alike(a: &Surface, b: &Surface) -> bool {
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        bits(a.normal) == bits(b.normal)
            && bits(a.reflectance) == bits(b.reflectance)
            && L::shades_alike(a, b)
    }
}
