//! Smooth normals: light per pixel (section 6.2) on a mesh with vertex normals,
//! the normal interpolated from its vertices' and renormalised at each pixel
//! instead of the face's.

use crate::pipeline::interpolate::linear_ops;
use crate::pipeline::{Light, Lighting, Primitive, Stage, Surface, Vertex};
use glam::Vec3;

/// [`SmoothPixelLight`]'s per-pixel struct: the 3D position and the normal.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SmoothSurface {
    pub world: Vec3,
    pub normal: Vec3,
}

linear_ops!(SmoothSurface { world, normal });

/// Section 6.2 on a smooth mesh: as `PixelLight`, with the interpolated normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmoothPixelLight<L = Light> {
    pub light: L,
}

impl<L: Lighting> Stage for SmoothPixelLight<L> {
    type Varying = SmoothSurface;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;

    fn vertex_shader(&self, vertex: &Vertex, _: &Surface) -> SmoothSurface {
        SmoothSurface {
            world: vertex.position,
            normal: vertex.normal,
        }
    }

    #[inline]
    fn pixel_shader(&self, varying: &SmoothSurface, surface: &Surface) -> Vec3 {
        let normal = varying.normal.normalize_or_zero();
        self.light
            .reflected(varying.world, normal, surface, surface.reflectance)
    }
}
