//! The known differences of students' implementations, built on the core: a
//! rasterizer that places vertices and walks edges the other ways, and stages that
//! measure what a pixel shows (its surface, the direct light per unit power) so
//! that the light's power and the indirect light can be fitted afterwards.
//!
//! A rasterizer is a value the pipeline holds, so [`StudentRaster`] carries the
//! variants as a field: one rasterizer type for all 8 walks x 2 projections x
//! the depth modes, chosen per pipeline at run time.

use super::walk::Walk;
use crate::pipeline::clip::{ScreenVertex, MAX_CORNERS};
use crate::pipeline::interpolate::{Nothing, Pixel, Varying};
use crate::pipeline::mesh::Vertex;
use crate::pipeline::raster::rows::{compute_polygon_rows_by, draw_polygon_rows, Rows};
use crate::pipeline::raster::{Placed, Rasterizer, Viewport};
use crate::pipeline::stage::{Primitive, Stage, Surface};
use crate::pipeline::Light;
use glam::Vec3;

/// How the depth test is done.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DepthMode {
    /// The handout's: 1/z interpolated, the larger kept.
    #[default]
    InverseZ,
    /// No depth buffer: the triangle drawn last wins (painter's order).
    None,
    /// z itself interpolated linearly on the screen, the smaller kept.
    Z,
}

/// Everything that decides which pixel shows which surface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Geometry {
    /// `int(f X/Z + W/2)`: the half size added before truncating.
    pub projection_sum: bool,
    pub walk: Walk,
    pub depth: DepthMode,
}

/// With [`DepthMode::Z`], what the rasterizer carries in place of 1/z:
/// `Z_CARRIED - z`, linear in z and larger when nearer, so the core's test (keep
/// the larger, 0 = nothing drawn) keeps the smaller z. Every z of the lab's
/// views is far below it; a small power of two keeps the most of z's bits. The
/// running sums still round differently from a student's sum of z itself, so
/// where two surfaces tie (along a shared edge) the winner can differ.
const Z_CARRIED: f32 = 16.0;

/// The rows rasterizer with the variants of [`Geometry`]; the handout's when the
/// geometry is the default.
#[derive(Clone, Copy, Debug, Default)]
pub struct StudentRaster {
    pub geometry: Geometry,
}

#[inline]
fn place<V>(s: ScreenVertex<V>, viewport: &Viewport, g: Geometry) -> Pixel<V> {
    let (hw, hh) = (viewport.half_width, viewport.half_height);
    let (x, y) = if g.projection_sum {
        ((s.x + hw as f32) as i32, (s.y + hh as f32) as i32)
    } else {
        (s.x as i32 + hw, s.y as i32 + hh)
    };
    let zinv = match g.depth {
        DepthMode::Z => Z_CARRIED - 1.0 / s.zinv,
        _ => s.zinv,
    };
    Pixel {
        x,
        y,
        zinv,
        varying: s.varying,
    }
}

impl Rasterizer for StudentRaster {
    type Scratch<V: Varying> = Rows<V>;

    fn point<V: Varying>(
        &self,
        p: ScreenVertex<V>,
        viewport: &Viewport,
        mut plot: impl FnMut(Pixel<V>),
    ) {
        let p = place(p, viewport, self.geometry);
        if viewport.bounds.contains(&p) {
            plot(p);
        }
    }

    fn line<V: Varying>(
        &self,
        a: ScreenVertex<V>,
        b: ScreenVertex<V>,
        viewport: &Viewport,
        mut plot: impl FnMut(Pixel<V>),
    ) {
        let g = self.geometry;
        let (a, b) = (place(a, viewport, g), place(b, viewport, g));
        for p in g.walk.pixels(a, b) {
            if viewport.bounds.contains(&p) {
                plot(p);
            }
        }
    }

    fn polygon<V: Varying>(
        &self,
        rows: &mut Rows<V>,
        corners: &[ScreenVertex<V>],
        viewport: &Viewport,
        plot: impl FnMut(Pixel<V>),
    ) {
        let g = self.geometry;
        let mut pixels = [Pixel::default(); MAX_CORNERS];
        for (p, &c) in pixels.iter_mut().zip(corners) {
            *p = place(c, viewport, g);
        }
        compute_polygon_rows_by(&g.walk, &pixels[..corners.len()], &viewport.bounds, rows);
        draw_polygon_rows(rows, &viewport.bounds, plot);
    }

    /// Left unplaced: a student's placing may also change 1/z.
    type Place = (f32, f32);

    /// Never: a student's rows, like the handout's, cover every row the corners span.
    fn misses(&self, _: [(f32, f32); 3], _: &Viewport) -> bool {
        false
    }

    fn place(&self, x: f32, y: f32, _: &Viewport) -> (f32, f32) {
        (x, y)
    }

    fn triangle<V: Varying>(
        &self,
        rows: &mut Rows<V>,
        corners: [Placed<(f32, f32), V>; 3],
        viewport: &Viewport,
        plot: impl FnMut(Pixel<V>),
    ) {
        let corners = corners.map(|c| ScreenVertex {
            x: c.place.0,
            y: c.place.1,
            zinv: c.zinv,
            varying: c.varying,
        });
        self.polygon(rows, &corners, viewport, plot)
    }
}

/// The largest direct light per unit power [`encode`] keeps; more is clamped. A
/// surface 0.14 from the light facing it receives 4.
pub const DIRECT_RANGE: f32 = 4.0;

/// A value in [0, [`DIRECT_RANGE`]) as a colour whose 8-bit packing holds it in
/// 24 bits: the render target keeps bytes, and this way it keeps the value to
/// 2.4e-7 instead of 1/255.
#[inline]
pub fn encode(v: f32) -> Vec3 {
    let k = (v / DIRECT_RANGE * 16_777_216.0).clamp(0.0, 16_777_215.0) as u32;
    Vec3::new(
        (k >> 16) as f32 / 255.0,
        ((k >> 8) & 0xff) as f32 / 255.0,
        (k & 0xff) as f32 / 255.0,
    )
}

/// The value [`encode`] put in a packed colour.
pub fn decode(c: u32) -> f32 {
    (c & 0x00ff_ffff) as f32 / 16_777_216.0 * DIRECT_RANGE
}

/// What a pixel shows: its surface's reflectance (`NORMAL` false) or its normal
/// mapped into [0, 1] (`NORMAL` true), with or without the depth test.
#[derive(Clone, Copy, Debug, Default)]
pub struct Shows<const DEPTH: bool, const NORMAL: bool>;

impl<const DEPTH: bool, const NORMAL: bool> Stage for Shows<DEPTH, NORMAL> {
    type Varying = Nothing;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = DEPTH;

    fn vertex_shader(&self, _: &Vertex, _: &Surface) -> Nothing {
        Nothing {}
    }

    fn pixel_shader(&self, _: &Nothing, surface: &Surface) -> Vec3 {
        if NORMAL {
            surface.normal * 0.5 + 0.5
        } else {
            surface.reflectance
        }
    }
}

/// Eq. 10 per unit power at each pixel, from the interpolated 3D position
/// (section 6.2), encoded: draw with a light of power 1.
#[derive(Clone, Copy, Debug)]
pub struct DirectPerPixel<const DEPTH: bool> {
    pub light: Light,
}

impl<const DEPTH: bool> Stage for DirectPerPixel<DEPTH> {
    type Varying = crate::pipeline::stage::Position;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = DEPTH;

    fn vertex_shader(&self, vertex: &Vertex, _: &Surface) -> Self::Varying {
        crate::pipeline::stage::Position {
            world: vertex.position,
        }
    }

    fn pixel_shader(&self, varying: &Self::Varying, surface: &Surface) -> Vec3 {
        encode(self.light.direct(varying.world, surface.normal).x)
    }
}

/// Eq. 10 per unit power at each vertex, interpolated (section 6.1), encoded.
#[derive(Clone, Copy, Debug)]
pub struct DirectPerVertex<const DEPTH: bool> {
    pub light: Light,
}

impl<const DEPTH: bool> Stage for DirectPerVertex<DEPTH> {
    type Varying = f32;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = DEPTH;

    fn vertex_shader(&self, vertex: &Vertex, _: &Surface) -> f32 {
        self.light.direct(vertex.position, vertex.normal).x
    }

    fn pixel_shader(&self, varying: &f32, _: &Surface) -> Vec3 {
        encode(*varying)
    }
}

/// How far below zero a coordinate [`WorldAxis`] draws may be: the box spans
/// -1 to 1, and [`DIRECT_RANGE`] leaves room either side.
pub const AXIS_OFFSET: f32 = 2.0;

/// One coordinate (`AXIS`: 0 x, 1 y, 2 z) of the interpolated 3D position at
/// each pixel, plus [`AXIS_OFFSET`], encoded: where the light falls, drawn once
/// so that any light is then worked out without drawing.
#[derive(Clone, Copy, Debug, Default)]
pub struct WorldAxis<const DEPTH: bool, const AXIS: usize>;

impl<const DEPTH: bool, const AXIS: usize> Stage for WorldAxis<DEPTH, AXIS> {
    type Varying = crate::pipeline::stage::Position;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = DEPTH;

    fn vertex_shader(&self, vertex: &Vertex, _: &Surface) -> Self::Varying {
        crate::pipeline::stage::Position {
            world: vertex.position,
        }
    }

    fn pixel_shader(&self, varying: &Self::Varying, _: &Surface) -> Vec3 {
        encode(varying.world[AXIS] + AXIS_OFFSET)
    }
}

/// The index of the face each pixel shows, plus one (0 is no face), encoded in
/// the colour's 24 bits.
#[derive(Clone, Copy, Debug, Default)]
pub struct FaceIndex<const DEPTH: bool>;

impl<const DEPTH: bool> Stage for FaceIndex<DEPTH> {
    type Varying = Nothing;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_TEST: bool = DEPTH;

    fn vertex_shader(&self, _: &Vertex, _: &Surface) -> Nothing {
        Nothing {}
    }

    fn pixel_shader(&self, _: &Nothing, surface: &Surface) -> Vec3 {
        let k = surface.face + 1;
        Vec3::new(
            (k >> 16 & 0xff) as f32 / 255.0,
            (k >> 8 & 0xff) as f32 / 255.0,
            (k & 0xff) as f32 / 255.0,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::target::pack;

    #[test]
    fn the_default_geometry_draws_the_handouts_figures() {
        use crate::pipeline::{Camera, Depth, Perspective};
        use crate::pipeline::{Frame, Pipeline, PixelLight, Wireframe};
        let (mesh, camera) = (crate::scene::cornell_box(), Camera::handout(200, 150));
        fn both<S: Stage>(stage: &S, mesh: &crate::pipeline::Mesh, c: &Camera) -> [Frame; 2] {
            let (mut core, mut student) = (Frame::default(), Frame::default());
            Pipeline::<S::Varying, Perspective>::new().render(stage, mesh, c, &mut core);
            Pipeline::<S::Varying, Perspective, StudentRaster>::new().render(
                stage,
                mesh,
                c,
                &mut student,
            );
            [core, student]
        }
        let light = Light::handout();
        for [core, student] in [
            both(&Wireframe, &mesh, &camera),
            both(&Depth, &mesh, &camera),
            both(&PixelLight { light }, &mesh, &camera),
        ] {
            assert!(core.color.iter().any(|&c| c != 0));
            assert_eq!(core.color, student.color);
        }
    }

    #[test]
    fn encoded_values_survive_8_bit_packing() {
        for v in [0.0, 1e-6, 0.0123, 0.25, 1.0, 3.99] {
            let back = decode(pack(encode(v)));
            assert!(
                (back - v).abs() <= DIRECT_RANGE / 16_777_216.0,
                "{v}: {back}"
            );
        }
    }
}
