//! Shadows from the point light (`--shadows`): a shadow map, the scene's 1/z seen
//! from the light through the six 90° faces of a cube, drawn with the depth stage
//! and the exact edge rasterizer; a surface point is in shadow where the map holds
//! something nearer to the light than the point itself.
//!
//! The depth bias. The map stores, per texel, the depth of the surface at the
//! texel's centre; a receiver is looked up at its own position, up to half a texel
//! away. On a surface at angle θ to the light's rays, half a texel of a face at
//! depth z with focal length f spans `z tan θ / (2 f)` in depth, so a lit surface
//! would shadow itself in stripes (shadow acne) without a margin that grows with
//! tan θ. The bias is `z (0.002 + 1.5 tan θ / f)`: the slope term covers the
//! half texel with room for the next texel's slope, the constant the rounding of
//! 1/z. A larger bias detaches shadows from their casters (peter-panning); this
//! one keeps a block's shadow touching the block at the map sizes used here.

use crate::pipeline::raster::EdgeRaster;
use crate::pipeline::{Camera, Depth, Frame, Light, Lighting, Mesh, Pipeline, Surface};
use glam::Vec3;
use std::f32::consts::FRAC_PI_2;

/// How shadows are looked up.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Shadows {
    /// No shadow map: the handout's light.
    #[default]
    None,
    /// One texel: lit or not.
    Hard,
    /// Percentage-closer filtering: the share of the 3 x 3 texels around the
    /// point that see the light.
    Pcf,
}

/// The faces' texels along each side.
pub const SHADOW_MAP_SIZE: u32 = 512;

/// The scene's depth from the light, one depth image per cube face.
#[derive(Clone, Debug)]
pub struct ShadowMap {
    light: Vec3,
    /// +x, -x, +y, -y, +z, -z.
    faces: [(Camera, Frame); 6],
    filter: Shadows,
}

/// The camera of cube face `k` at `light`: 90° wide, looking along the face's axis.
fn face_camera(light: Vec3, k: usize, size: u32, near: f32) -> Camera {
    let (yaw, pitch) = match k {
        0 => (FRAC_PI_2, 0.0),            // +x
        1 => (-FRAC_PI_2, 0.0),           // -x
        2 => (0.0, -FRAC_PI_2),           // +y (down)
        3 => (0.0, FRAC_PI_2),            // -y (up)
        4 => (0.0, 0.0),                  // +z
        _ => (std::f32::consts::PI, 0.0), // -z
    };
    Camera {
        position: light,
        yaw,
        pitch,
        focal: size as f32 / 2.0,
        width: size,
        height: size,
        near: Some(near),
    }
}

/// The face whose frustum holds direction `d` from the light: its major axis.
fn face_of(d: Vec3) -> usize {
    let a = d.abs();
    if a.x >= a.y && a.x >= a.z {
        if d.x >= 0.0 {
            0
        } else {
            1
        }
    } else if a.y >= a.z {
        if d.y >= 0.0 {
            2
        } else {
            3
        }
    } else if d.z >= 0.0 {
        4
    } else {
        5
    }
}

impl ShadowMap {
    /// The map of a light at `light`, with six faces of `size` x `size` texels,
    /// each `mesh`'s 1/z as the face's camera sees it: drawn by the depth stage
    /// with the exact rasterizer, which samples the texel centres the lookups
    /// assume. `near` is the faces' near plane: geometry closer to the light
    /// casts no shadow.
    pub fn render(light: Vec3, size: u32, near: f32, filter: Shadows, mesh: &Mesh) -> ShadowMap {
        let mut pipeline = Pipeline::<_, crate::pipeline::Perspective, EdgeRaster>::new();
        let faces = std::array::from_fn(|k| {
            let camera = face_camera(light, k, size, near);
            let mut frame = Frame::default();
            pipeline.render(&Depth, mesh, &camera, &mut frame);
            (camera, frame)
        });
        ShadowMap {
            light,
            faces,
            filter,
        }
    }

    /// How much of the light reaches `position` on a surface of (geometric)
    /// `normal`: 1 lit, 0 in shadow, between with percentage-closer filtering.
    /// Eq. 11 then becomes `ρ (v D + N)` ([`Shadowed`]).
    pub fn visibility(&self, position: Vec3, normal: Vec3) -> f32 {
        let to_point = position - self.light;
        let (camera, frame) = &self.faces[face_of(to_point)];
        let c = camera.to_camera(position);
        if c.z <= 0.0 || !c.is_finite() {
            return 1.0;
        }
        let size = camera.width as f32;
        let (x, y) = (
            camera.focal * c.x / c.z + size / 2.0,
            camera.focal * c.y / c.z + size / 2.0,
        );
        let cos = normal.dot(-to_point).abs() / to_point.length().max(f32::MIN_POSITIVE);
        let cos = cos.clamp(0.05, 1.0);
        let tan = (1.0 - cos * cos).sqrt() / cos;
        let receiver = c.z - c.z * (0.002 + 1.5 * tan / camera.focal);
        let lit = |i: i64, j: i64| -> f32 {
            let last = camera.width as i64 - 1;
            let (i, j) = (i.clamp(0, last) as usize, j.clamp(0, last) as usize);
            let zinv = frame.depth[j * camera.width as usize + i];
            // Nearer than the receiver: a larger 1/z. An empty texel holds 0.
            if zinv * receiver > 1.0 {
                0.0
            } else {
                1.0
            }
        };
        let (i, j) = (x.floor() as i64, y.floor() as i64);
        match self.filter {
            Shadows::None => 1.0,
            Shadows::Hard => lit(i, j),
            Shadows::Pcf => {
                let mut sum = 0.0;
                for dj in -1..=1 {
                    for di in -1..=1 {
                        sum += lit(i + di, j + dj);
                    }
                }
                sum / 9.0
            }
        }
    }
}

/// The handout's light with a shadow map: eq. 11 as `ρ (v D + N)`, v the share
/// of the light the map lets reach the point (the handout's light without a
/// map). A lit stage drawn with it (`PixelLight { light: Shadowed { .. } }`)
/// casts shadows, and nothing else of the stage changes.
#[derive(Clone, Copy, Debug)]
pub struct Shadowed<'a> {
    pub light: Light,
    pub map: Option<&'a ShadowMap>,
}

impl Lighting for Shadowed<'_> {
    /// The map's depth bias follows the surface's own (face) normal: a smooth or
    /// mapped `normal` is not the slope the map was drawn with.
    #[inline]
    fn reflected(&self, position: Vec3, normal: Vec3, surface: &Surface, rho: Vec3) -> Vec3 {
        match self.map {
            Some(map) => {
                let v = map.visibility(position, surface.normal);
                rho * (self.light.direct(position, normal) * v + self.light.indirect)
            }
            None => self.light.reflected(position, normal, rho),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::Triangle;

    #[test]
    fn each_direction_falls_in_the_face_that_looks_along_it() {
        for (k, d) in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z]
            .into_iter()
            .enumerate()
        {
            assert_eq!(face_of(d), k);
            let forward = face_camera(Vec3::ZERO, k, 8, 0.01).axes()[2];
            assert!((forward - d).length() < 1e-6, "face {k}: {forward}");
        }
    }

    #[test]
    fn a_square_between_the_light_and_a_floor_shadows_the_floor_under_it() {
        // Light at the origin, a small square 1 below it (y down is +y), a wide
        // floor 2 below.
        let white = Vec3::ONE;
        let square = |y: f32, half: f32| {
            let (a, b, c, d) = (
                Vec3::new(-half, y, -half),
                Vec3::new(half, y, -half),
                Vec3::new(half, y, half),
                Vec3::new(-half, y, half),
            );
            [Triangle::new(a, b, c, white), Triangle::new(a, c, d, white)]
        };
        let mut triangles = square(1.0, 0.25).to_vec();
        triangles.extend(square(2.0, 10.0));
        let mesh = Mesh::from_triangles(&triangles);
        let light = Light {
            position: Vec3::ZERO,
            ..Light::handout()
        };
        let map = ShadowMap::render(light.position, 256, 0.01, Shadows::Hard, &mesh);
        let up = -Vec3::Y;
        // Under the square (its shadow reaches 0.5 from the centre at y = 2).
        assert_eq!(map.visibility(Vec3::new(0.0, 2.0, 0.0), up), 0.0);
        assert_eq!(map.visibility(Vec3::new(0.4, 2.0, 0.3), up), 0.0);
        // Beyond the shadow, and the square's own lit side.
        assert_eq!(map.visibility(Vec3::new(0.7, 2.0, 0.0), up), 1.0);
        assert_eq!(map.visibility(Vec3::new(3.0, 2.0, -2.0), up), 1.0);
        assert_eq!(map.visibility(Vec3::new(0.1, 1.0, 0.1), up), 1.0);
        // Filtered: on the shadow's edge, part of the texels see the light.
        let pcf = ShadowMap::render(light.position, 256, 0.01, Shadows::Pcf, &mesh);
        let edge = pcf.visibility(Vec3::new(0.5, 2.0, 0.0), up);
        assert!(edge > 0.0 && edge < 1.0, "{edge}");
    }
}
