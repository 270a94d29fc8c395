//! Textures: the lit stages with ρ read from each material's texture at the
//! interpolated (u, v) coordinate instead of its colour. Each stage owns the
//! images it reads and the filter it reads them with.

use super::texture::{Filter, Maps};
use crate::pipeline::interpolate::linear_ops;
use crate::pipeline::{Light, Lighting, Primitive, Stage, Surface, Vertex};
use glam::{Vec2, Vec3};

/// The reflectance ρ of eq. 11 at `uv` on `surface`: its material's texture
/// there, or its colour if it has none.
#[inline]
pub fn reflectance(maps: &Maps, filter: Filter, surface: &Surface, uv: Vec2) -> Vec3 {
    match maps.image(maps.of(surface.material).texture) {
        Some(texture) => texture.sample(uv, filter),
        None => surface.reflectance,
    }
}

/// [`TexturedVertexLight`]'s per-pixel struct.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct IlluminationUv {
    /// The light eq. 11 reflects from a white surface.
    pub light: Vec3,
    pub uv: Vec2,
}

linear_ops!(IlluminationUv { light, uv });

/// Section 6.1 with a texture: the light arriving at each vertex (eq. 10 and 11
/// with ρ = 1) and the (u, v) coordinate are interpolated, and each pixel
/// multiplies the light by the reflectance its texture gives there.
#[derive(Clone, Copy, Debug)]
pub struct TexturedVertexLight<'a, L = Light> {
    pub light: L,
    pub maps: &'a Maps,
    pub filter: Filter,
}

impl<L: Lighting> Stage for TexturedVertexLight<'_, L> {
    type Varying = IlluminationUv;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;

    fn vertex_shader(&self, vertex: &Vertex, surface: &Surface) -> IlluminationUv {
        IlluminationUv {
            light: self
                .light
                .reflected(vertex.position, vertex.normal, surface, Vec3::ONE),
            uv: vertex.uv,
        }
    }

    fn pixel_shader(&self, varying: &IlluminationUv, surface: &Surface) -> Vec3 {
        reflectance(self.maps, self.filter, surface, varying.uv) * varying.light
    }
}

/// [`TexturedPixelLight`]'s per-pixel struct: the 3D position and the (u, v)
/// coordinate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PositionUv {
    pub world: Vec3,
    pub uv: Vec2,
}

linear_ops!(PositionUv { world, uv });

/// Section 6.2 with a texture: as `PixelLight`, with ρ from the texture.
#[derive(Clone, Copy, Debug)]
pub struct TexturedPixelLight<'a, L = Light> {
    pub light: L,
    pub maps: &'a Maps,
    pub filter: Filter,
}

impl<L: Lighting> Stage for TexturedPixelLight<'_, L> {
    type Varying = PositionUv;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;

    fn vertex_shader(&self, vertex: &Vertex, _: &Surface) -> PositionUv {
        PositionUv {
            world: vertex.position,
            uv: vertex.uv,
        }
    }

    fn pixel_shader(&self, varying: &PositionUv, surface: &Surface) -> Vec3 {
        let rho = reflectance(self.maps, self.filter, surface, varying.uv);
        self.light
            .reflected(varying.world, surface.normal, surface, rho)
    }
}

/// The per-pixel struct of the smooth textured and normal-mapped stages.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SmoothSurfaceUv {
    pub world: Vec3,
    pub normal: Vec3,
    pub uv: Vec2,
}

linear_ops!(SmoothSurfaceUv { world, normal, uv });

impl SmoothSurfaceUv {
    /// A vertex's position, normal and (u, v) coordinate, as they are.
    pub fn of(vertex: &Vertex) -> Self {
        SmoothSurfaceUv {
            world: vertex.position,
            normal: vertex.normal,
            uv: vertex.uv,
        }
    }
}

/// [`super::smooth::SmoothPixelLight`] with a texture.
#[derive(Clone, Copy, Debug)]
pub struct SmoothTexturedPixelLight<'a, L = Light> {
    pub light: L,
    pub maps: &'a Maps,
    pub filter: Filter,
}

impl<L: Lighting> Stage for SmoothTexturedPixelLight<'_, L> {
    type Varying = SmoothSurfaceUv;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;

    fn vertex_shader(&self, vertex: &Vertex, _: &Surface) -> SmoothSurfaceUv {
        SmoothSurfaceUv::of(vertex)
    }

    fn pixel_shader(&self, varying: &SmoothSurfaceUv, surface: &Surface) -> Vec3 {
        let rho = reflectance(self.maps, self.filter, surface, varying.uv);
        let normal = varying.normal.normalize_or_zero();
        self.light.reflected(varying.world, normal, surface, rho)
    }
}
