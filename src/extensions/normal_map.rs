//! Normal maps and parallax: light per pixel (section 6.2) with the normal
//! tilted at each pixel by a tangent-space normal map, read in each face's
//! tangent frame, and optionally the (u, v) coordinate moved along the view by a
//! height map. The stage owns its maps, the faces' frames and the eye.

use super::texture::{Filter, Maps};
use super::textured::{reflectance, SmoothSurfaceUv};
use crate::pipeline::{Light, Lighting, Mesh, Primitive, Stage, Surface, Vertex};
use glam::{Vec2, Vec3};

/// The height of a height map's white, in (u, v) units: 1 % of the texture's
/// width.
pub const PARALLAX_DEPTH: f32 = 0.01;

/// A face's tangent frame: the directions in which u and v grow.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TangentFrame {
    pub tangent: Vec3,
    pub bitangent: Vec3,
}

/// The directions of increasing u and v on a triangle with corners `p` and
/// texture coordinates `uv`, made perpendicular to `normal` and unit length: the
/// tangent frame a tangent-space normal map is read in. Zero vectors where the
/// coordinates do not span the triangle.
pub fn tangent_frame(p: [Vec3; 3], uv: [Vec2; 3], normal: Vec3) -> TangentFrame {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let (d1, d2) = (uv[1] - uv[0], uv[2] - uv[0]);
    let det = d1.x * d2.y - d2.x * d1.y;
    if det == 0.0 || !det.is_finite() {
        return TangentFrame::default();
    }
    let tangent = (e1 * d2.y - e2 * d1.y) / det;
    let bitangent = (e2 * d1.x - e1 * d2.x) / det;
    let along = |v: Vec3| (v - normal * normal.dot(v)).normalize_or_zero();
    TangentFrame {
        tangent: along(tangent),
        bitangent: along(bitangent),
    }
}

/// Every face's tangent frame, in the order of `mesh.faces`; none for a mesh
/// without (u, v) coordinates.
pub fn tangent_frames(mesh: &Mesh) -> Vec<TangentFrame> {
    if mesh.uvs.is_empty() {
        return Vec::new();
    }
    mesh.faces
        .iter()
        .map(|face| {
            let at = face.vertices.map(|i| i as usize);
            tangent_frame(
                at.map(|i| mesh.positions[i]),
                at.map(|i| mesh.uvs[i]),
                face.normal,
            )
        })
        .collect()
}

/// Section 6.2 with a normal map: the position, the normal (the vertices' where
/// the mesh has them, else the face's) and the (u, v) coordinate are
/// interpolated; each pixel tilts its normal by the map in the face's tangent
/// frame, and reads ρ from the material's texture if it has one.
#[derive(Clone, Copy, Debug)]
pub struct NormalMappedPixelLight<'a, L = Light> {
    pub light: L,
    pub maps: &'a Maps,
    pub filter: Filter,
    /// [`tangent_frames`] of the mesh drawn.
    pub frames: &'a [TangentFrame],
    /// The camera's position, for parallax's view direction.
    pub eye: Vec3,
}

impl<L: Lighting> NormalMappedPixelLight<'_, L> {
    fn frame(&self, surface: &Surface) -> TangentFrame {
        self.frames
            .get(surface.face as usize)
            .copied()
            .unwrap_or_default()
    }

    /// Parallax: the coordinate seen at `uv` once the surface is raised by its
    /// material's height map, [`PARALLAX_DEPTH`] at most. The view direction in
    /// the face's tangent frame `v` moves it by `v.xy / v.z` times the height
    /// there (one step: steep views overshoot a little). `uv` itself without a
    /// height map or a frame.
    #[inline]
    fn parallax(
        &self,
        surface: &Surface,
        frame: TangentFrame,
        normal: Vec3,
        world: Vec3,
        uv: Vec2,
    ) -> Vec2 {
        match self.maps.image(self.maps.of(surface.material).height_map) {
            Some(map) if frame.tangent != Vec3::ZERO => {
                let v = (self.eye - world).normalize_or_zero();
                let along = Vec2::new(v.dot(frame.tangent), v.dot(frame.bitangent));
                // Grazing views would send the offset to infinity: no closer than 0.2.
                let up = v.dot(normal).max(0.2);
                let height = map.sample(uv, self.filter).x * PARALLAX_DEPTH;
                uv + along / up * height
            }
            _ => uv,
        }
    }

    /// The normal at `uv` of a surface whose geometric normal is `normal`: the
    /// material's normal map read there (a colour c encodes the tangent-space
    /// normal 2c - 1) and turned into the face's frame; `normal` itself without
    /// a map.
    #[inline]
    fn mapped_normal(
        &self,
        surface: &Surface,
        frame: TangentFrame,
        normal: Vec3,
        uv: Vec2,
    ) -> Vec3 {
        match self.maps.image(self.maps.of(surface.material).normal_map) {
            Some(map) => {
                map.tangent_normal(uv, self.filter, [frame.tangent, frame.bitangent, normal])
            }
            None => normal,
        }
    }
}

impl<L: Lighting> Stage for NormalMappedPixelLight<'_, L> {
    type Varying = SmoothSurfaceUv;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = true;

    fn vertex_shader(&self, vertex: &Vertex, _: &Surface) -> SmoothSurfaceUv {
        SmoothSurfaceUv::of(vertex)
    }

    fn pixel_shader(&self, varying: &SmoothSurfaceUv, surface: &Surface) -> Vec3 {
        let frame = self.frame(surface);
        let normal = varying.normal.normalize_or(surface.normal);
        let uv = self.parallax(surface, frame, normal, varying.world, varying.uv);
        let rho = reflectance(self.maps, self.filter, surface, uv);
        let normal = self.mapped_normal(surface, frame, normal, uv);
        self.light.reflected(varying.world, normal, surface, rho)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tangent_frame_follows_u_and_v() {
        // A triangle in the z = 0 plane whose texture coordinates are its x and
        // -y (v up, y down): u grows along x, v along -y.
        let p = [
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, -2.0, 0.0),
        ];
        let uv = [Vec2::ZERO, Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0)];
        let TangentFrame {
            tangent: t,
            bitangent: b,
        } = tangent_frame(p, uv, Vec3::Z);
        assert!((t - Vec3::X).length() < 1e-6, "{t}");
        assert!((b + Vec3::Y).length() < 1e-6, "{b}");
        // Coordinates that do not span the triangle give no frame.
        assert_eq!(
            tangent_frame(p, [Vec2::ZERO; 3], Vec3::Z),
            TangentFrame::default()
        );
    }
}
