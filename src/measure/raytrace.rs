//! The reference: a ray tracer as in lab 2, one ray per pixel through its centre
//! (or N x N rays with `samples`), nearest hit, the same eq. 10 and 11 as the
//! rasterizer ([`Light::reflected`]). Everything the rasterizer's stages are
//! measured against (`rasterlab report`) comes from here.

use crate::extensions::normal_map::tangent_frame;
use crate::extensions::texture::{Filter, Model, Texture};
use crate::measure::bvh::Bvh;
use crate::pipeline::target::pack;
use crate::pipeline::{Camera, Frame, Light};
use glam::{Vec2, Vec3};

/// What the reference shows at a hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shading {
    /// The nearest triangle's colour: what `filled` and `depth` mean to draw.
    Flat,
    /// Eq. 10 and 11 at the hit: what the lit stages approximate.
    Lit,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    pub shading: Shading,
    /// Lab 2's shadow ray: a hit that cannot see the light gets only indirect light.
    pub shadows: bool,
    /// Rays per pixel along each axis (N x N in all), spread evenly over the pixel.
    pub samples: u32,
    /// Ignore primary hits nearer than this camera-space depth, like the
    /// rasterizer's near plane.
    pub near: Option<f32>,
    /// How textures are read between texels, as `--filter` tells the rasterizer.
    pub filter: Filter,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            shading: Shading::Lit,
            shadows: false,
            samples: 1,
            near: None,
            filter: Filter::Nearest,
        }
    }
}

/// A traced image and, per pixel, the index of the triangle the centre ray hit.
#[derive(Clone, Debug)]
pub struct Traced {
    pub frame: Frame,
    pub hit: Vec<Option<u32>>,
}

/// What a ray can hit: the mesh's triangles in a [`Bvh`], and its vertex normals
/// for smooth shading where it has them.
pub struct Scene {
    pub bvh: Bvh,
    /// Per face, its three vertex normals; empty for a mesh without them.
    normals: Vec<[Vec3; 3]>,
    /// Per face, what its material maps and where; empty for a mesh without
    /// textures or without texture coordinates.
    mapped: Vec<Option<Mapping>>,
    textures: Vec<Texture>,
}

/// A face's texture and normal map, its corners' texture coordinates and its
/// tangent frame.
#[derive(Clone, Copy, Debug)]
struct Mapping {
    texture: Option<u32>,
    normal_map: Option<u32>,
    uv: [Vec2; 3],
    tangent: Vec3,
    bitangent: Vec3,
}

impl Scene {
    pub fn new<'a>(model: impl Into<Model<'a>>) -> Scene {
        let Model { mesh, maps } = model.into();
        let normals = if mesh.normals.is_empty() {
            Vec::new()
        } else {
            mesh.faces
                .iter()
                .map(|f| f.vertices.map(|i| mesh.normals[i as usize]))
                .collect()
        };
        let mapped = if mesh.uvs.is_empty() || maps.images.is_empty() {
            Vec::new()
        } else {
            mesh.faces
                .iter()
                .map(|f| {
                    let m = maps.of(f.material);
                    let uv = f.vertices.map(|i| mesh.uvs[i as usize]);
                    let p = f.vertices.map(|i| mesh.positions[i as usize]);
                    let frame = tangent_frame(p, uv, f.normal);
                    let (tangent, bitangent) = (frame.tangent, frame.bitangent);
                    (m.texture.is_some() || m.normal_map.is_some()).then_some(Mapping {
                        texture: m.texture,
                        normal_map: m.normal_map,
                        uv,
                        tangent,
                        bitangent,
                    })
                })
                .collect()
        };
        Scene {
            bvh: Bvh::new(mesh.triangles().collect()),
            normals,
            mapped,
            textures: maps.images.clone(),
        }
    }

    /// The barycentric weights of `hit` in triangle `i`'s second and third
    /// corners; `None` for a degenerate triangle.
    fn barycentric(&self, i: usize, hit: Vec3) -> Option<(f32, f32)> {
        let tri = &self.bvh.triangles[i];
        let (e1, e2, p) = (tri.v1 - tri.v0, tri.v2 - tri.v0, hit - tri.v0);
        let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let (dp1, dp2) = (p.dot(e1), p.dot(e2));
        let det = d11 * d22 - d12 * d12;
        if det == 0.0 {
            return None;
        }
        Some(((d22 * dp1 - d12 * dp2) / det, (d11 * dp2 - d12 * dp1) / det))
    }

    /// What the surface of triangle `i` is at `hit`: its reflectance ρ (the
    /// texture at the hit's texture coordinate, or the colour) and its normal
    /// (the face's, or the vertex normals weighted by the hit's barycentric
    /// coordinates and renormalised, then tilted by a normal map as the
    /// rasterizer does). The barycentric weights and the texture coordinate are
    /// found once for both.
    fn surface_at(&self, i: usize, hit: Vec3, filter: Filter) -> (Vec3, Vec3) {
        let tri = &self.bvh.triangles[i];
        let weights = self.barycentric(i, hit);
        let normal = match (self.normals.get(i), weights) {
            (Some(n), Some((u, v))) => {
                (n[0] * (1.0 - u - v) + n[1] * u + n[2] * v).normalize_or(tri.normal)
            }
            _ => tri.normal,
        };
        let (Some(&Some(m)), Some((u, v))) = (self.mapped.get(i), weights) else {
            return (tri.color, normal);
        };
        let uv = m.uv[0] * (1.0 - u - v) + m.uv[1] * u + m.uv[2] * v;
        let texture = |t: Option<u32>| t.and_then(|t| self.textures.get(t as usize));
        let rho = texture(m.texture).map_or(tri.color, |t| t.sample(uv, filter));
        let normal = texture(m.normal_map).map_or(normal, |map| {
            map.tangent_normal(uv, filter, [m.tangent, m.bitangent, normal])
        });
        (rho, normal)
    }
}

/// The colour one ray brings back (black for a miss) and the triangle it hit.
pub fn trace(
    scene: &Scene,
    light: &Light,
    origin: Vec3,
    dir: Vec3,
    options: &Options,
) -> (Vec3, Option<usize>) {
    let Some((t, i)) = scene.bvh.nearest(origin, dir, 0.0) else {
        return (Vec3::ZERO, None);
    };
    let tri = &scene.bvh.triangles[i];
    let color = match options.shading {
        Shading::Flat => tri.color,
        Shading::Lit => {
            let hit = origin + dir * t;
            let to_light = light.position - hit;
            let blocked = options.shadows
                && scene
                    .bvh
                    .nearest(hit, to_light, 1e-4)
                    .is_some_and(|(s, _)| s < 1.0);
            let (rho, normal) = scene.surface_at(i, hit, options.filter);
            if blocked {
                rho * light.indirect
            } else {
                light.reflected(hit, normal, rho)
            }
        }
    };
    (color, Some(i))
}

/// Traces the scene as `camera` sees it: the ray for screen point (sx, sy) goes
/// through camera-space (sx - W/2, sy - H/2, f), the inverse of the rasterizer's
/// projection, and pixel (x, y) is sampled at (x + 0.5, y + 0.5).
pub fn raytrace<'a>(
    model: impl Into<Model<'a>>,
    camera: &Camera,
    light: &Light,
    options: &Options,
) -> Traced {
    let scene = &Scene::new(model);
    let (w, h) = (camera.width, camera.height);
    let [right, down, forward] = camera.axes();
    let (half_w, half_h) = ((w / 2) as f32, (h / 2) as f32);
    let n = options.samples.max(1);
    let mut frame = Frame::new(w, h);
    let mut hit = vec![None; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            // The direction's forward part is f, so a hit at distance t along it
            // lies at camera depth t f; starting the ray at depth `near` cuts
            // what the near plane cuts.
            let start = options.near.map_or(0.0, |n| n / camera.focal);
            let ray = |sx: f32, sy: f32| {
                let dir = right * (sx - half_w) + down * (sy - half_h) + forward * camera.focal;
                trace(scene, light, camera.position + dir * start, dir, options)
            };
            let (x, y) = (x as f32, y as f32);
            // The triangle under the pixel's centre, for telling edges from interiors.
            let (centre_color, centre_hit) = ray(x + 0.5, y + 0.5);
            let color = if n == 1 {
                centre_color
            } else {
                let mut sum = Vec3::ZERO;
                for j in 0..n {
                    for i in 0..n {
                        let (dx, dy) = ((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                        sum += ray(x + dx, y + dy).0;
                    }
                }
                sum / (n * n) as f32
            };
            let idx = (y as u32 * w + x as u32) as usize;
            frame.color[idx] = pack(color);
            hit[idx] = centre_hit.map(|i| i as u32);
        }
    }
    Traced { frame, hit }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::bvh::intersect;
    use crate::pipeline::Triangle;
    use crate::scene::cornell_box;

    #[test]
    fn a_ray_hits_a_triangle_where_expected() {
        let tri = Triangle::new(
            Vec3::new(-1.0, -1.0, 2.0),
            Vec3::new(1.0, -1.0, 2.0),
            Vec3::new(0.0, 1.0, 2.0),
            Vec3::ONE,
        );
        assert_eq!(intersect(Vec3::ZERO, Vec3::Z, &tri, 0.0), Some(2.0));
        assert_eq!(
            intersect(Vec3::ZERO, -Vec3::Z, &tri, 0.0),
            None,
            "behind the origin"
        );
        assert_eq!(
            intersect(Vec3::new(5.0, 0.0, 0.0), Vec3::Z, &tri, 0.0),
            None,
            "beside it"
        );
        assert_eq!(
            intersect(Vec3::ZERO, Vec3::Z, &tri, 2.5),
            None,
            "nearer than t_min"
        );
    }

    #[test]
    fn the_centre_pixel_sees_the_back_wall_lit_by_hand() {
        // The ray through pixel (250, 150)'s centre hits the back wall (z = 1,
        // normal -z). The hit is at camera distance 4.001, so
        // x = 0.5 * 4.001 / 500 and y = -99.5 * 4.001 / 500.
        let scene = cornell_box();
        let camera = Camera::handout(500, 500);
        let light = Light::handout();
        let traced = raytrace(&scene, &camera, &light, &Options::default());
        let idx = 150 * 500 + 250;
        let wall = traced.hit[idx].unwrap() as usize;
        assert!(wall == 8 || wall == 9, "back wall, got triangle {wall}");
        let p = Vec3::new(0.5 * 4.001 / 500.0, -99.5 * 4.001 / 500.0, 1.0);
        let r = light.position - p;
        let d = 1.1 * (r.z.abs() / r.length()) / (4.0 * std::f32::consts::PI * r.length_squared());
        let expected = pack(Vec3::splat(0.75 * (d + 0.5)));
        assert_eq!(traced.frame.color[idx], expected);
        // By hand: r = (-0.004, 0.296, -1.7), |r|² = 2.9776, cos = 0.9852,
        // D = 1.1 * 0.9852 / (4π 2.9776) = 0.02896, R = 0.75 * 0.52896 = 0.3967 -> 101.
        assert_eq!(traced.frame.rgb(250, 150), [101, 101, 101]);
    }

    #[test]
    fn shadows_darken_the_floor_behind_a_block() {
        // The line from the light (0, -0.5, -0.7) through the tall block's middle,
        // (-0.33, 0.4, 0.27), meets the floor near (-0.55, 1, 0.92). A ray from just
        // above that point straight down hits the floor; with shadows it gets only
        // the indirect term, 0.5 times the floor's reflectance.
        let scene = Scene::new(&cornell_box());
        let light = Light::handout();
        let eye = Vec3::new(-0.55, 0.5, 0.92);
        let opts = Options {
            shadows: true,
            ..Options::default()
        };
        let (c, hit) = trace(&scene, &light, eye, Vec3::Y, &opts);
        assert!(matches!(hit, Some(0) | Some(1)), "{hit:?}");
        assert!(
            (c - Vec3::new(0.15, 0.75, 0.15) * 0.5).length() < 1e-6,
            "{c}"
        );
        let (lit, _) = trace(&scene, &light, eye, Vec3::Y, &Options::default());
        // Unshadowed, the floor there gets D = 1.1 cos / (4π r²) with r from
        // (-0.55, 1, 0.92) to the light: r² = 0.3025 + 2.25 + 2.6244 = 5.18,
        // cos = 1.5 / 2.276 = 0.659, D = 0.01113; green gains 0.75 D = 0.00835.
        assert!((lit.y - c.y - 0.00835).abs() < 2e-4, "{lit} vs {c}");
    }
}
