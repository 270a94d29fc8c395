//! Where the light falls, drawn once: the search for the light's position tries
//! hundreds of positions, and drawing each one's direct light through the
//! pipeline dominated a check. The pixels it scores are a fixed sample (every
//! [`LIGHT_STRIDE`]th interior pixel), and what they show does not depend on
//! the light: for light per pixel (section 6.2), the interpolated 3D position
//! and the face's normal; for light per vertex (section 6.1), the face's three
//! corners and each one's weight in the interpolation, which the interpolated
//! position gives (the same weights interpolate every per-vertex value). Eq. 10
//! is then evaluated at those, for any light, without drawing.

use super::image::{draw_as, Hypothesis, Measured};
use super::student::{decode, DepthMode, FaceIndex, WorldAxis, AXIS_OFFSET};
use crate::pipeline::{Camera, Frame, Light, Mesh, StageName};
use glam::Vec3;

/// Every `LIGHT_STRIDE`th pixel is enough to place the light: the interiors
/// of a 500 x 500 screenshot still give 20 000 of them.
pub const LIGHT_STRIDE: usize = 8;

/// Every `COARSE_STRIDE`th pixel is enough to rank a coarse grid of lights.
pub const COARSE_STRIDE: usize = 16;

/// What one sampled pixel's direct light is made of.
#[derive(Clone, Copy, Debug)]
enum Source {
    /// A point and its normal: light per pixel.
    Point(Vec3, Vec3),
    /// A face and its three corners' weights: light per vertex.
    Corners(u32, [f32; 3]),
}

/// A hypothesis' surfaces with their direct light worked out, at the sampled
/// pixels, for whichever light [`LightProbe::light_at`] is given.
pub struct LightProbe {
    /// The hypothesis' measure; its `direct` is the last light's at the samples.
    pub measured: Measured,
    /// The sampled pixels: every `stride`th interior one.
    pub pixels: Vec<usize>,
    sources: Vec<Source>,
    /// Per face, its corners (position, normal): light per vertex only.
    corners: Vec<[(Vec3, Vec3); 3]>,
    /// Per face, the last light's direct light at its corners.
    at_corners: Vec<[f32; 3]>,
}

impl LightProbe {
    /// The probe of a lit hypothesis `h` whose surfaces are `measured`.
    pub fn new(
        h: Hypothesis,
        measured: &Measured,
        mesh: &Mesh,
        camera: &Camera,
        stride: usize,
    ) -> LightProbe {
        let g = h.geometry;
        let depth = g.depth != DepthMode::None;
        let draw_axis = |axis: usize| -> Frame {
            match (depth, axis) {
                (true, 0) => draw_as(g, &WorldAxis::<true, 0>, h.affine, mesh, camera),
                (true, 1) => draw_as(g, &WorldAxis::<true, 1>, h.affine, mesh, camera),
                (true, _) => draw_as(g, &WorldAxis::<true, 2>, h.affine, mesh, camera),
                (false, 0) => draw_as(g, &WorldAxis::<false, 0>, h.affine, mesh, camera),
                (false, 1) => draw_as(g, &WorldAxis::<false, 1>, h.affine, mesh, camera),
                (false, _) => draw_as(g, &WorldAxis::<false, 2>, h.affine, mesh, camera),
            }
        };
        let axes = [0, 1, 2].map(draw_axis);
        let per_vertex = h.stage == StageName::VertexLight;
        let faces = per_vertex.then(|| match depth {
            true => draw_as(g, &FaceIndex::<true>, h.affine, mesh, camera),
            false => draw_as(g, &FaceIndex::<false>, h.affine, mesh, camera),
        });
        let (mut pixels, mut sources) = (Vec::new(), Vec::new());
        for i in (0..measured.surface.len()).step_by(stride) {
            if !measured.interior[i] {
                continue;
            }
            let p = Vec3::from_array(axes.each_ref().map(|f| decode(f.color[i]) - AXIS_OFFSET));
            let normal = measured.surfaces[measured.surface[i] as usize].1;
            let source = match &faces {
                None => Source::Point(p, normal),
                Some(faces) => {
                    let k = (faces.color[i] & 0x00ff_ffff) as usize;
                    let Some(face) = k.checked_sub(1).and_then(|k| mesh.faces.get(k)) else {
                        continue;
                    };
                    let corners = [0, 1, 2].map(|c| mesh.vertex(face, c).position);
                    Source::Corners(k as u32 - 1, barycentric(p, corners))
                }
            };
            pixels.push(i);
            sources.push(source);
        }
        let corners: Vec<[(Vec3, Vec3); 3]> = match per_vertex {
            true => (mesh.faces.iter())
                .map(|f| {
                    [0, 1, 2].map(|c| {
                        let v = mesh.vertex(f, c);
                        (v.position, v.normal)
                    })
                })
                .collect(),
            false => Vec::new(),
        };
        LightProbe {
            measured: measured.clone(),
            pixels,
            sources,
            at_corners: vec![[0.0; 3]; corners.len()],
            corners,
        }
    }

    /// The probe of a fitted lit hypothesis, with `setup`'s mesh and camera.
    pub fn of(f: &super::image::Fitted, setup: &super::image::Setup, stride: usize) -> LightProbe {
        LightProbe::new(
            f.hypothesis,
            &f.measured,
            &setup.mesh,
            &setup.camera,
            stride,
        )
    }

    /// Sets the direct light per unit power at the samples to the light's at `position`.
    pub fn light_at(&mut self, position: Vec3) {
        let light = Light {
            position,
            power: Vec3::ONE,
            indirect: Vec3::ZERO,
        };
        // Light per vertex: eq. 10 once per corner, as the vertex shader has it.
        for (at, corners) in self.at_corners.iter_mut().zip(&self.corners) {
            *at = corners.map(|(p, n)| light.direct(p, n).x);
        }
        for (&i, &source) in self.pixels.iter().zip(&self.sources) {
            self.measured.direct[i] = match source {
                Source::Point(p, n) => light.direct(p, n).x,
                Source::Corners(face, w) => {
                    let d = self.at_corners[face as usize];
                    w[0] * d[0] + w[1] * d[1] + w[2] * d[2]
                }
            };
        }
    }
}

/// The weights of `p` in the triangle `v` (they sum to 1; p in its plane).
fn barycentric(p: Vec3, v: [Vec3; 3]) -> [f32; 3] {
    let (e1, e2, d) = (v[1] - v[0], v[2] - v[0], p - v[0]);
    let (a, b, c) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (x, y) = (d.dot(e1), d.dot(e2));
    let det = a * c - b * b;
    if det.abs() < 1e-20 {
        return [1.0, 0.0, 0.0];
    }
    let w1 = (c * x - b * y) / det;
    let w2 = (a * y - b * x) / det;
    [1.0 - w1 - w2, w1, w2]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::check::image::{direct_pass, measure, Setup};

    /// The probe's and the pipeline's direct light at each sample.
    fn drawn_at_samples(
        probe: &LightProbe,
        h: Hypothesis,
        mesh: &Mesh,
        camera: &Camera,
        light: Vec3,
    ) -> Vec<(f32, f32)> {
        let drawn = direct_pass(h, mesh, camera, light);
        probe
            .pixels
            .iter()
            .map(|&i| (probe.measured.direct[i], drawn[i]))
            .collect()
    }

    /// The probe's direct light is the pipeline's, within 0.3 % (its positions
    /// are read back at 24 bits), for both kinds of light, at three lights.
    #[test]
    fn the_probe_gives_the_drawn_direct_light() {
        let setup = Setup::handout(200, 200);
        for stage in [StageName::PixelLight, StageName::VertexLight] {
            for affine in [false, true] {
                let h = Hypothesis {
                    affine,
                    ..Hypothesis::handout(stage)
                };
                let m = measure(h, &setup.mesh, &setup.camera, setup.light);
                let mut probe = LightProbe::new(h, &m, &setup.mesh, &setup.camera, LIGHT_STRIDE);
                assert!(probe.pixels.len() > 3000, "{stage:?}");
                for light in [
                    setup.light,
                    Vec3::new(-0.6, 0.2, 0.5),
                    Vec3::new(0.3, -0.9, -1.5),
                ] {
                    probe.light_at(light);
                    let pairs = drawn_at_samples(&probe, h, &setup.mesh, &setup.camera, light);
                    let worst = pairs
                        .iter()
                        .map(|&(a, b)| (a - b).abs() / b.max(1e-3))
                        .fold(0.0f32, f32::max);
                    assert!(worst < 3e-3, "{stage:?} affine {affine} {light}: {worst}");
                }
            }
        }
    }
}
