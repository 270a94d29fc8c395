//! The handout's stages as types. A stage is the handout's `VertexShader` and
//! `PixelShader` and the per-pixel struct between them ([`Stage::Varying`]), plus
//! the primitive it draws and whether it tests depth. The rest is the shared core
//! in [`super::draw`].
//!
//! | stage | section | primitive | depth test | interpolated |
//! |---|---|---|---|---|
//! | [`Points`] | 2 | points | no | nothing |
//! | [`Wireframe`] | 3 | lines | no | nothing |
//! | [`Filled`] | 4 | polygons | no | nothing |
//! | [`Depth`] | 5 | polygons | yes | nothing (1/z is the core's) |
//! | [`VertexLight`] | 6.1 | polygons | yes | [`Illumination`]: eq. 11 at the vertices |
//! | [`PixelLight`] | 6.2 | polygons | yes | [`Position`]: the 3D position |
//! | [`SmoothPixelLight`] | 6.2, for meshes with vertex normals | polygons | yes | [`SmoothSurface`]: the 3D position and the normal |
//! | [`TexturedVertexLight`] | 6.1, with a texture | polygons | yes | [`IlluminationUv`]: the light and the texture coordinate |
//! | [`TexturedPixelLight`] | 6.2, with a texture | polygons | yes | [`PositionUv`]: the 3D position and the texture coordinate |
//! | [`SmoothTexturedPixelLight`] | 6.2, with vertex normals and a texture | polygons | yes | [`SmoothSurfaceUv`] |
//! | [`NormalMappedPixelLight`] | 6.2, with a normal map | polygons | yes | [`SmoothSurfaceUv`] |

use super::interpolate::{linear_ops, Nothing, Varying};
use super::light::Light;
use super::mesh::{Material, Vertex};
use super::shadow::ShadowMap;
use super::texture::{Filter, Texture};
use glam::{Vec2, Vec3};

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

/// The height of a height map's white, in texture-coordinate units: 1 % of the
/// texture's width.
pub const PARALLAX_DEPTH: f32 = 0.01;

/// Scene-wide inputs of the shaders, the same for every vertex and pixel of a frame.
#[derive(Clone, Copy, Debug)]
pub struct Uniforms<'a> {
    pub light: Light,
    /// The mesh's textures, which [`Material::texture`] indexes.
    pub textures: &'a [Texture],
    /// How textures are read between texels.
    pub filter: Filter,
    /// The light's shadow map, for the stages drawn with shadows.
    pub shadow: Option<&'a ShadowMap>,
    /// The camera's position, for parallax's view direction.
    pub eye: Vec3,
}

impl Uniforms<'static> {
    /// Just the light: no textures.
    pub const fn lit(light: Light) -> Self {
        Uniforms {
            light,
            textures: &[],
            filter: Filter::Nearest,
            shadow: None,
            eye: Vec3::ZERO,
        }
    }
}

impl<'a> Uniforms<'a> {
    /// The same with `shadow` as the shadow map (for as long as both live).
    pub fn with_shadow<'b>(&self, shadow: Option<&'b ShadowMap>) -> Uniforms<'b>
    where
        'a: 'b,
    {
        Uniforms {
            light: self.light,
            textures: self.textures,
            filter: self.filter,
            shadow,
            eye: self.eye,
        }
    }
    /// Eq. 11 at a surface point: with `SHADOWS` and a shadow map, the direct
    /// light scaled by how much of it the map lets through; else the handout's.
    /// `SHADOWS` is the stage's, fixed at compile time, so a stage without
    /// shadows has no test here at all.
    /// The shadow map's depth bias follows `surface`'s own (face) normal: a
    /// smooth or mapped `normal` is not the slope the map was drawn with.
    #[inline]
    pub fn reflected<const SHADOWS: bool>(
        &self,
        surface: &Surface,
        position: Vec3,
        normal: Vec3,
        rho: Vec3,
    ) -> Vec3 {
        match self.shadow {
            Some(map) if SHADOWS => {
                let v = map.visibility(position, surface.normal);
                rho * (self.light.direct(position, normal) * v + self.light.indirect)
            }
            _ => self.light.reflected(position, normal, rho),
        }
    }

    /// Parallax: the texture coordinate seen at `uv` once the surface is raised
    /// by its material's height map, [`PARALLAX_DEPTH`] at most. The view
    /// direction in the face's tangent frame `v` moves it by `v.xy / v.z` times
    /// the height there (one step: steep views overshoot a little). `uv` itself
    /// without a height map or a frame.
    #[inline]
    pub fn parallax(&self, surface: &Surface, normal: Vec3, world: Vec3, uv: Vec2) -> Vec2 {
        let map = surface
            .material
            .height_map
            .and_then(|i| self.textures.get(i as usize));
        match map {
            Some(map) if surface.tangent != Vec3::ZERO => {
                let v = (self.eye - world).normalize_or_zero();
                let along = Vec2::new(v.dot(surface.tangent), v.dot(surface.bitangent));
                // Grazing views would send the offset to infinity: no closer than 0.2.
                let up = v.dot(normal).max(0.2);
                let height = map.sample(uv, self.filter).x * PARALLAX_DEPTH;
                uv + along / up * height
            }
            _ => uv,
        }
    }

    /// The normal at texture coordinate `uv` of a surface whose geometric normal
    /// is `normal`: the material's normal map read there (a colour c encodes the
    /// tangent-space normal 2c - 1) and turned into the surface's tangent frame;
    /// `normal` itself without a map or a frame.
    #[inline]
    pub fn mapped_normal(&self, surface: &Surface, normal: Vec3, uv: Vec2) -> Vec3 {
        let map = surface
            .material
            .normal_map
            .and_then(|i| self.textures.get(i as usize));
        match map {
            Some(map) => map.tangent_normal(
                uv,
                self.filter,
                [surface.tangent, surface.bitangent, normal],
            ),
            None => normal,
        }
    }

    /// The reflectance ρ of eq. 11 at texture coordinate `uv`: the material's
    /// texture there, or its colour if it has none.
    #[inline]
    pub fn reflectance(&self, material: &Material, uv: Vec2) -> Vec3 {
        match material.texture.and_then(|i| self.textures.get(i as usize)) {
            Some(texture) => texture.sample(uv, self.filter),
            None => material.color,
        }
    }
}

/// The triangle being drawn, as its shaders see it: the handout's `currentNormal`
/// and `currentReflectance` (the material's colour).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    pub normal: Vec3,
    pub material: Material,
    /// The face's tangent frame (directions of increasing u and v), for stages
    /// with [`Stage::TANGENTS`]; zero for the others.
    pub tangent: Vec3,
    pub bitangent: Vec3,
}

/// One stage of the handout.
pub trait Stage: Send + 'static {
    /// What the vertex shader computes and every pixel receives, interpolated.
    type Varying: Varying;
    const PRIMITIVE: Primitive;
    /// Whether pixels go through the depth test of section 5.
    const DEPTH_TEST: bool;
    /// Whether the core runs the pixel shader over each triangle's visible pixels
    /// together, after rasterizing it, instead of at each pixel as it is found:
    /// worth it for a shader heavy enough to gain from a vectorised loop. The
    /// same pixel shader runs either way, on the same pixels.
    const BATCH_SHADING: bool = false;
    /// Whether the pixel shader reads [`Surface::tangent`] and `bitangent`, which
    /// the core then computes for each face.
    const TANGENTS: bool = false;

    /// The stage's part of the handout's `VertexShader` (the projection is the
    /// core's): what the pixels of this vertex's triangle interpolate.
    fn vertex_shader(vertex: &Vertex, surface: &Surface, uniforms: &Uniforms) -> Self::Varying;

    /// The colour part of the handout's `PixelShader` (the depth test is the
    /// core's): a linear colour, which the render target rounds to 8 bits.
    fn pixel_shader(varying: &Self::Varying, surface: &Surface, uniforms: &Uniforms) -> Vec3;
}

/// Section 2: the projected vertices, white on black.
#[derive(Clone, Copy, Debug, Default)]
pub struct Points;

impl Stage for Points {
    type Varying = Nothing;
    const PRIMITIVE: Primitive = Primitive::Points;
    const DEPTH_TEST: bool = false;

    fn vertex_shader(_: &Vertex, _: &Surface, _: &Uniforms) -> Nothing {
        Nothing {}
    }

    fn pixel_shader(_: &Nothing, _: &Surface, _: &Uniforms) -> Vec3 {
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

    fn vertex_shader(_: &Vertex, _: &Surface, _: &Uniforms) -> Nothing {
        Nothing {}
    }

    fn pixel_shader(_: &Nothing, _: &Surface, _: &Uniforms) -> Vec3 {
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

    fn vertex_shader(_: &Vertex, _: &Surface, _: &Uniforms) -> Nothing {
        Nothing {}
    }

    fn pixel_shader(_: &Nothing, surface: &Surface, _: &Uniforms) -> Vec3 {
        surface.material.color
    }
}

/// Section 5: filled triangles behind a depth buffer of 1/z.
#[derive(Clone, Copy, Debug, Default)]
pub struct Depth;

impl Stage for Depth {
    type Varying = Nothing;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;

    fn vertex_shader(_: &Vertex, _: &Surface, _: &Uniforms) -> Nothing {
        Nothing {}
    }

    fn pixel_shader(_: &Nothing, surface: &Surface, _: &Uniforms) -> Vec3 {
        surface.material.color
    }
}

/// Section 6.1's per-pixel struct: the light R of eq. 11 that leaves the surface.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Illumination {
    pub light: Vec3,
}

linear_ops!(Illumination { light });

/// Section 6.1: eq. 10 and 11 at each vertex; the reflected light is interpolated.
#[derive(Clone, Copy, Debug, Default)]
pub struct VertexLight<const SHADOWS: bool = false>;

impl<const SHADOWS: bool> Stage for VertexLight<SHADOWS> {
    type Varying = Illumination;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;

    fn vertex_shader(vertex: &Vertex, surface: &Surface, uniforms: &Uniforms) -> Illumination {
        let rho = surface.material.color;
        Illumination {
            light: uniforms.reflected::<SHADOWS>(surface, vertex.position, vertex.normal, rho),
        }
    }

    fn pixel_shader(varying: &Illumination, _: &Surface, _: &Uniforms) -> Vec3 {
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
#[derive(Clone, Copy, Debug, Default)]
pub struct PixelLight<const SHADOWS: bool = false>;

impl<const SHADOWS: bool> Stage for PixelLight<SHADOWS> {
    type Varying = Position;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;
    const BATCH_SHADING: bool = true;

    fn vertex_shader(vertex: &Vertex, _: &Surface, _: &Uniforms) -> Position {
        Position {
            world: vertex.position,
        }
    }

    #[inline]
    fn pixel_shader(varying: &Position, surface: &Surface, uniforms: &Uniforms) -> Vec3 {
        let rho = surface.material.color;
        uniforms.reflected::<SHADOWS>(surface, varying.world, surface.normal, rho)
    }
}

/// The per-pixel struct of light per pixel on a mesh with vertex normals: the 3D
/// position and the normal, both interpolated.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SmoothSurface {
    pub world: Vec3,
    pub normal: Vec3,
}

linear_ops!(SmoothSurface { world, normal });

/// Section 6.2 on a smooth mesh: as [`PixelLight`], with the normal interpolated
/// from the vertices' normals and renormalised at each pixel instead of the face's.
#[derive(Clone, Copy, Debug, Default)]
pub struct SmoothPixelLight<const SHADOWS: bool = false>;

impl<const SHADOWS: bool> Stage for SmoothPixelLight<SHADOWS> {
    type Varying = SmoothSurface;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;
    const BATCH_SHADING: bool = true;

    fn vertex_shader(vertex: &Vertex, _: &Surface, _: &Uniforms) -> SmoothSurface {
        SmoothSurface {
            world: vertex.position,
            normal: vertex.normal,
        }
    }

    #[inline]
    fn pixel_shader(varying: &SmoothSurface, surface: &Surface, uniforms: &Uniforms) -> Vec3 {
        let rho = surface.material.color;
        let normal = varying.normal.normalize_or_zero();
        uniforms.reflected::<SHADOWS>(surface, varying.world, normal, rho)
    }
}

/// Section 6.1 with a texture: the light arriving at each vertex (eq. 10 and 11
/// with ρ = 1) and the texture coordinate are interpolated, and each pixel
/// multiplies the light by the reflectance its texture gives there.
#[derive(Clone, Copy, Debug, Default)]
pub struct TexturedVertexLight<const SHADOWS: bool = false>;

/// [`TexturedVertexLight`]'s per-pixel struct.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct IlluminationUv {
    /// The light eq. 11 reflects from a white surface.
    pub light: Vec3,
    pub uv: Vec2,
}

linear_ops!(IlluminationUv { light, uv });

impl<const SHADOWS: bool> Stage for TexturedVertexLight<SHADOWS> {
    type Varying = IlluminationUv;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;

    fn vertex_shader(vertex: &Vertex, surface: &Surface, uniforms: &Uniforms) -> IlluminationUv {
        IlluminationUv {
            light: uniforms.reflected::<SHADOWS>(
                surface,
                vertex.position,
                vertex.normal,
                Vec3::ONE,
            ),
            uv: vertex.uv,
        }
    }

    fn pixel_shader(varying: &IlluminationUv, surface: &Surface, uniforms: &Uniforms) -> Vec3 {
        uniforms.reflectance(&surface.material, varying.uv) * varying.light
    }
}

/// [`TexturedPixelLight`]'s per-pixel struct: the 3D position and the texture
/// coordinate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PositionUv {
    pub world: Vec3,
    pub uv: Vec2,
}

linear_ops!(PositionUv { world, uv });

/// Section 6.2 with a texture: as [`PixelLight`], with ρ read from the material's
/// texture at the interpolated texture coordinate.
#[derive(Clone, Copy, Debug, Default)]
pub struct TexturedPixelLight<const SHADOWS: bool = false>;

impl<const SHADOWS: bool> Stage for TexturedPixelLight<SHADOWS> {
    type Varying = PositionUv;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;

    fn vertex_shader(vertex: &Vertex, _: &Surface, _: &Uniforms) -> PositionUv {
        PositionUv {
            world: vertex.position,
            uv: vertex.uv,
        }
    }

    fn pixel_shader(varying: &PositionUv, surface: &Surface, uniforms: &Uniforms) -> Vec3 {
        let rho = uniforms.reflectance(&surface.material, varying.uv);
        uniforms.reflected::<SHADOWS>(surface, varying.world, surface.normal, rho)
    }
}

/// [`SmoothTexturedPixelLight`]'s per-pixel struct.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SmoothSurfaceUv {
    pub world: Vec3,
    pub normal: Vec3,
    pub uv: Vec2,
}

linear_ops!(SmoothSurfaceUv { world, normal, uv });

impl SmoothSurfaceUv {
    /// A vertex's position, normal and texture coordinate, as they are.
    pub fn of(vertex: &Vertex) -> Self {
        SmoothSurfaceUv {
            world: vertex.position,
            normal: vertex.normal,
            uv: vertex.uv,
        }
    }
}

/// [`SmoothPixelLight`] with a texture.
#[derive(Clone, Copy, Debug, Default)]
pub struct SmoothTexturedPixelLight<const SHADOWS: bool = false>;

impl<const SHADOWS: bool> Stage for SmoothTexturedPixelLight<SHADOWS> {
    type Varying = SmoothSurfaceUv;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;

    fn vertex_shader(vertex: &Vertex, _: &Surface, _: &Uniforms) -> SmoothSurfaceUv {
        SmoothSurfaceUv::of(vertex)
    }

    fn pixel_shader(varying: &SmoothSurfaceUv, surface: &Surface, uniforms: &Uniforms) -> Vec3 {
        let rho = uniforms.reflectance(&surface.material, varying.uv);
        let normal = varying.normal.normalize_or_zero();
        uniforms.reflected::<SHADOWS>(surface, varying.world, normal, rho)
    }
}

/// Section 6.2 with a normal map: the position, the normal (the vertices' where
/// the mesh has them, else the face's) and the texture coordinate are
/// interpolated; each pixel tilts its normal by the map in the face's tangent
/// frame, and reads ρ from the material's texture if it has one.
#[derive(Clone, Copy, Debug, Default)]
pub struct NormalMappedPixelLight<const SHADOWS: bool = false>;

impl<const SHADOWS: bool> Stage for NormalMappedPixelLight<SHADOWS> {
    type Varying = SmoothSurfaceUv;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;
    const TANGENTS: bool = true;

    fn vertex_shader(vertex: &Vertex, _: &Surface, _: &Uniforms) -> SmoothSurfaceUv {
        SmoothSurfaceUv::of(vertex)
    }

    fn pixel_shader(varying: &SmoothSurfaceUv, surface: &Surface, uniforms: &Uniforms) -> Vec3 {
        let normal = varying.normal.normalize_or(surface.normal);
        let uv = uniforms.parallax(surface, normal, varying.world, varying.uv);
        let rho = uniforms.reflectance(&surface.material, uv);
        let normal = uniforms.mapped_normal(surface, normal, uv);
        uniforms.reflected::<SHADOWS>(surface, varying.world, normal, rho)
    }
}
