//! The handout's stages as types. A stage picks the primitive it draws, whether it
//! needs a depth buffer, and the per-pixel data ([`Stage::Varying`]) that is
//! interpolated between vertices. Everything else is the shared core in
//! [`crate::render`].
//!
//! | stage | section | primitive | depth buffer | interpolated |
//! |---|---|---|---|---|
//! | [`Points`] | 2 | points | no | nothing |
//! | [`Wireframe`] | 3 | lines | no | nothing |
//! | [`Filled`] | 4 | polygons | no | nothing |
//! | [`Depth`] | 5 | polygons | yes | 1/z |
//! | [`VertexLight`] | 6.1 | polygons | yes | 1/z, eq. 11's light over z |
//! | [`PixelLight`] | 6.2 | polygons | yes | 1/z, 3D position over z |

use crate::interpolate::Varying;
use crate::light::Light;
use crate::scene::Triangle;
use glam::Vec3;
use std::marker::PhantomData;

/// What a stage draws for each triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Primitive {
    /// Each projected vertex as one pixel (section 2).
    Points,
    /// Each edge as a line (section 3).
    Lines,
    /// Each triangle filled row by row (section 4).
    Polygons,
}

/// One stage of the handout: its vertex and pixel shaders and what flows between them.
pub trait Stage {
    /// The per-pixel data the stage interpolates; `()` when it needs none.
    type Varying: Varying;
    const PRIMITIVE: Primitive;
    /// Whether pixels go through the depth test of section 5.
    const DEPTH_BUFFER: bool;

    /// Per-vertex values that are linear over the triangle in 3D (a position, eq.
    /// 11's light at the vertex); what the near-plane clip interpolates.
    type Attributes: Varying;

    /// The stage's part of the handout's `VertexShader`: its per-vertex work for a
    /// vertex at `world` of triangle `tri`.
    fn vertex_shader(&self, world: Vec3, tri: &Triangle) -> Self::Attributes;

    /// What is interpolated on the screen for a vertex with these attributes and
    /// inverse camera depth `zinv` (for example q/z and 1/z).
    fn to_varying(&self, a: Self::Attributes, zinv: f32) -> Self::Varying;

    /// 1/z at a pixel, for the depth test. Only called when `DEPTH_BUFFER`.
    fn zinv(_v: &Self::Varying) -> f32 {
        0.0
    }

    /// The colour part of the handout's `PixelShader` (the depth test is the core's).
    fn pixel_shader(&self, v: &Self::Varying, tri: &Triangle) -> Vec3;

    /// Moves the light, for stages that have one (the viewer's a, w, s, d).
    fn set_light(&mut self, _light: Light) {}

    /// Whether the core should collect a triangle's visible pixels and colour them
    /// together with [`Stage::shade_batch`], for stages whose pixel shader is worth
    /// running in loops the compiler can vectorise.
    const BATCHED: bool = false;

    /// The pixel shader over many pixels of one triangle, packed as `0x00RRGGBB`.
    /// Must give exactly what [`Stage::pixel_shader`] gives, pixel by pixel.
    fn shade_batch(&self, v: &[Self::Varying], tri: &Triangle, out: &mut [u32]) {
        for (o, v) in out.iter_mut().zip(v) {
            *o = crate::render::pack(self.pixel_shader(v, tri));
        }
    }
}

/// Section 2: the projected vertices, white on black.
#[derive(Clone, Copy, Debug, Default)]
pub struct Points;

/// Section 3: the triangles' edges, white on black.
#[derive(Clone, Copy, Debug, Default)]
pub struct Wireframe;

/// Section 4: triangles filled in their colour, in scene order (no occlusion).
#[derive(Clone, Copy, Debug, Default)]
pub struct Filled;

macro_rules! unlit_stage {
    ($stage:ty, $primitive:expr, $color:expr) => {
        impl Stage for $stage {
            type Varying = ();
            type Attributes = ();
            const PRIMITIVE: Primitive = $primitive;
            const DEPTH_BUFFER: bool = false;

            fn vertex_shader(&self, _: Vec3, _: &Triangle) {}

            fn to_varying(&self, _: (), _: f32) {}

            fn pixel_shader(&self, _: &(), tri: &Triangle) -> Vec3 {
                let color: fn(&Triangle) -> Vec3 = $color;
                color(tri)
            }
        }
    };
}

unlit_stage!(Points, Primitive::Points, |_| Vec3::ONE);
unlit_stage!(Wireframe, Primitive::Lines, |_| Vec3::ONE);
unlit_stage!(Filled, Primitive::Polygons, |t| t.color);

/// How a quantity that is linear in 3D is interpolated across the screen.
///
/// Only 1/z, and q/z for any such q, is linear in the image (section 6.2), so the
/// correct way carries those and divides at the pixel. The affine way carries z and
/// q themselves: the mistake behind the handout's Figure 8.
pub trait Correction: Copy + Default + 'static {
    /// True when interpolation is perspective-correct.
    const PERSPECTIVE: bool;
    /// What is interpolated for depth, from a vertex's 1/z.
    fn depth(zinv: f32) -> f32;
    /// 1/z at a pixel, from the interpolated depth.
    fn zinv(depth: f32) -> f32;
    /// What is interpolated for a quantity q at a vertex.
    fn encode(q: Vec3, zinv: f32) -> Vec3;
    /// q at a pixel, from what was interpolated and the pixel's 1/z.
    fn decode(q: Vec3, zinv: f32) -> Vec3;
}

/// Interpolate 1/z and q/z; at the pixel q = (q/z) * z. The default.
#[derive(Clone, Copy, Debug, Default)]
pub struct Perspective;

/// Interpolate z and q linearly in screen space (`--affine`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Affine;

impl Correction for Perspective {
    const PERSPECTIVE: bool = true;
    #[inline]
    fn depth(zinv: f32) -> f32 {
        zinv
    }
    #[inline]
    fn zinv(depth: f32) -> f32 {
        depth
    }
    #[inline]
    fn encode(q: Vec3, zinv: f32) -> Vec3 {
        q * zinv
    }
    #[inline]
    fn decode(q: Vec3, zinv: f32) -> Vec3 {
        q * (1.0 / zinv)
    }
}

impl Correction for Affine {
    const PERSPECTIVE: bool = false;
    #[inline]
    fn depth(zinv: f32) -> f32 {
        1.0 / zinv
    }
    #[inline]
    fn zinv(depth: f32) -> f32 {
        1.0 / depth
    }
    #[inline]
    fn encode(q: Vec3, _: f32) -> Vec3 {
        q
    }
    #[inline]
    fn decode(q: Vec3, _: f32) -> Vec3 {
        q
    }
}

/// Section 5: filled triangles behind a depth buffer of 1/z.
#[derive(Clone, Copy, Debug, Default)]
pub struct Depth<C = Perspective>(PhantomData<C>);

impl<C: Correction> Depth<C> {
    pub fn new() -> Self {
        Depth(PhantomData)
    }
}

impl<C: Correction> Stage for Depth<C> {
    type Varying = f32;
    type Attributes = ();
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_BUFFER: bool = true;

    fn vertex_shader(&self, _: Vec3, _: &Triangle) {}

    fn to_varying(&self, _: (), zinv: f32) -> f32 {
        C::depth(zinv)
    }

    #[inline]
    fn zinv(v: &f32) -> f32 {
        C::zinv(*v)
    }

    #[inline]
    fn pixel_shader(&self, _: &f32, tri: &Triangle) -> Vec3 {
        tri.color
    }
}

/// Section 6.1: eq. 10 and 11 at each vertex; the reflected light is interpolated.
#[derive(Clone, Copy, Debug)]
pub struct VertexLight<C = Perspective> {
    pub light: Light,
    correction: PhantomData<C>,
}

impl<C: Correction> VertexLight<C> {
    pub fn new(light: Light) -> Self {
        VertexLight {
            light,
            correction: PhantomData,
        }
    }
}

impl<C: Correction> Stage for VertexLight<C> {
    /// (depth, reflected light R of eq. 11, encoded for interpolation)
    type Varying = (f32, Vec3);
    /// R of eq. 11 at the vertex.
    type Attributes = Vec3;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_BUFFER: bool = true;

    fn vertex_shader(&self, world: Vec3, tri: &Triangle) -> Vec3 {
        self.light.reflected(world, tri.normal, tri.color)
    }

    fn to_varying(&self, reflected: Vec3, zinv: f32) -> (f32, Vec3) {
        (C::depth(zinv), C::encode(reflected, zinv))
    }

    fn set_light(&mut self, light: Light) {
        self.light = light;
    }

    #[inline]
    fn zinv(v: &(f32, Vec3)) -> f32 {
        C::zinv(v.0)
    }

    #[inline]
    fn pixel_shader(&self, v: &(f32, Vec3), _: &Triangle) -> Vec3 {
        C::decode(v.1, C::zinv(v.0))
    }
}

/// Section 6.2: the 3D position is interpolated and eq. 10 and 11 run at each pixel,
/// with the triangle's normal and reflectance (the handout's `currentNormal`,
/// `currentReflectance`).
#[derive(Clone, Copy, Debug)]
pub struct PixelLight<C = Perspective> {
    pub light: Light,
    correction: PhantomData<C>,
}

impl<C: Correction> PixelLight<C> {
    pub fn new(light: Light) -> Self {
        PixelLight {
            light,
            correction: PhantomData,
        }
    }
}

impl<C: Correction> Stage for PixelLight<C> {
    /// (depth, world position, encoded for interpolation)
    type Varying = (f32, Vec3);
    /// The world position.
    type Attributes = Vec3;
    const PRIMITIVE: Primitive = Primitive::Polygons;
    const DEPTH_BUFFER: bool = true;

    fn vertex_shader(&self, world: Vec3, _: &Triangle) -> Vec3 {
        world
    }

    fn to_varying(&self, world: Vec3, zinv: f32) -> (f32, Vec3) {
        (C::depth(zinv), C::encode(world, zinv))
    }

    fn set_light(&mut self, light: Light) {
        self.light = light;
    }

    #[inline]
    fn zinv(v: &(f32, Vec3)) -> f32 {
        C::zinv(v.0)
    }

    #[inline]
    fn pixel_shader(&self, v: &(f32, Vec3), tri: &Triangle) -> Vec3 {
        let position = C::decode(v.1, C::zinv(v.0));
        self.light.reflected(position, tri.normal, tri.color)
    }

    const BATCHED: bool = true;

    /// The same eq. 10 and 11 as `pixel_shader`, in chunks: positions are decoded
    /// into three plain arrays first, so the light loop reads f32s in a row and
    /// the compiler runs it four pixels at a time. Same operations, same order,
    /// same bits.
    fn shade_batch(&self, v: &[(f32, Vec3)], tri: &Triangle, out: &mut [u32]) {
        const CHUNK: usize = 64;
        let (normal, rho) = (tri.normal, tri.color);
        for (v, out) in v.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            let (mut x, mut y, mut z) = ([0.0f32; CHUNK], [0.0f32; CHUNK], [0.0f32; CHUNK]);
            for (i, (depth, q)) in v.iter().enumerate() {
                let p = C::decode(*q, C::zinv(*depth));
                (x[i], y[i], z[i]) = (p.x, p.y, p.z);
            }
            let mut packed = [0u32; CHUNK];
            for i in 0..CHUNK {
                let p = Vec3::new(x[i], y[i], z[i]);
                packed[i] = crate::render::pack(self.light.reflected(p, normal, rho));
            }
            out.copy_from_slice(&packed[..out.len()]);
        }
    }
}

/// The stages by name, as the command line and the viewer know them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
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

    /// Whether `--affine` changes anything for this stage.
    pub fn interpolates(self) -> bool {
        matches!(
            self,
            StageName::Depth | StageName::VertexLight | StageName::PixelLight
        )
    }
}

/// One of the handout's figures: a stage, and whether it interpolates affinely.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct View {
    pub stage: StageName,
    pub affine: bool,
}

impl View {
    /// Figures 2 to 8, in the handout's order, as `rasterlab all` writes them.
    pub const FIGURES: [View; 7] = [
        View::of(StageName::Points),
        View::of(StageName::Wireframe),
        View::of(StageName::Filled),
        View::of(StageName::Depth),
        View::of(StageName::VertexLight),
        View::of(StageName::PixelLight),
        View {
            stage: StageName::PixelLight,
            affine: true,
        },
    ];

    pub const fn of(stage: StageName) -> Self {
        View {
            stage,
            affine: false,
        }
    }

    /// The file name `rasterlab all` gives this figure (design notes).
    pub fn figure_file(self) -> &'static str {
        match (self.stage, self.affine) {
            (StageName::Points, _) => "fig2-points.png",
            (StageName::Wireframe, _) => "fig3-wireframe.png",
            (StageName::Filled, _) => "fig4-filled.png",
            (StageName::Depth, false) => "fig5-depth.png",
            (StageName::Depth, true) => "fig5-depth-affine.png",
            (StageName::VertexLight, false) => "fig6-vertex-light.png",
            (StageName::VertexLight, true) => "fig6-vertex-light-affine.png",
            (StageName::PixelLight, false) => "fig7-pixel-light.png",
            (StageName::PixelLight, true) => "fig8-pixel-light-affine.png",
        }
    }

    /// A short label: the stage name, with ` --affine` where it applies.
    pub fn label(self) -> String {
        if self.affine && self.stage.interpolates() {
            format!("{} --affine", self.stage.name())
        } else {
            self.stage.name().to_string()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::pack;

    fn tri() -> Triangle {
        Triangle::new(
            Vec3::new(-1.0, 1.0, -1.0),
            Vec3::new(1.0, 1.0, -1.0),
            Vec3::new(0.0, 1.0, 1.0),
            Vec3::new(0.15, 0.75, 0.15),
        )
    }

    /// Varyings from ordinary to hostile: every value the batch may meet.
    fn varyings() -> Vec<(f32, Vec3)> {
        let mut v = Vec::new();
        for i in 0..200 {
            let t = i as f32 / 199.0;
            let p = Vec3::new(t * 2.0 - 1.0, 1.0 - t, t * 3.0 - 1.5);
            v.push((0.1 + t, p * (0.1 + t)));
        }
        for bad in [0.0, -1.0, f32::NAN, f32::INFINITY, 1e-30, 1e30] {
            v.push((bad, Vec3::new(0.0, -0.5, -0.7) * bad)); // at the light, and worse
            v.push((0.5, Vec3::splat(bad)));
        }
        v
    }

    fn batch_matches_pixel_by_pixel<S: Stage<Varying = (f32, Vec3)>>(stage: S) {
        let t = tri();
        let v = varyings();
        let mut out = vec![0u32; v.len()];
        stage.shade_batch(&v, &t, &mut out);
        for (i, (v, o)) in v.iter().zip(&out).enumerate() {
            assert_eq!(*o, pack(stage.pixel_shader(v, &t)), "pixel {i}: {v:?}");
        }
    }

    #[test]
    fn the_batched_light_is_the_per_pixel_light_bit_for_bit() {
        batch_matches_pixel_by_pixel(PixelLight::<Perspective>::new(Light::handout()));
        batch_matches_pixel_by_pixel(PixelLight::<Affine>::new(Light::handout()));
        batch_matches_pixel_by_pixel(VertexLight::<Perspective>::new(Light::handout()));
    }

    #[test]
    fn pack_is_clamp_then_round() {
        let reference = |v: f32| {
            if v.is_nan() {
                0
            } else {
                (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u32
            }
        };
        let mut values: Vec<f32> = (0..=4000).map(|i| i as f32 / 3000.0 - 0.1).collect();
        values.extend([
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            -0.0,
            1.0,
            0.5 / 255.0,
        ]);
        for v in values {
            assert_eq!(pack(Vec3::splat(v)), reference(v) * 0x01_01_01, "{v}");
        }
    }
}
