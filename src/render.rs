//! The handout's `Draw`: every triangle goes through the vertex shader, is
//! rasterized as points, lines or rows, and every pixel goes through the depth test
//! (for stages that have one) and the pixel shader into the frame.

use crate::camera::{Camera, Projection};
use crate::clip::{
    clip_near, clip_rect, clip_segment_near, clip_segment_rect, CameraVertex, Polygon, Rect,
    ScreenVertex,
};
use crate::interpolate::Pixel;
use crate::light::Light;
use crate::polygon::{compute_polygon_rows, draw_line, draw_polygon_rows, Clip, Rows};
use crate::scene::Triangle;
use crate::stage::{
    Affine, Correction, Depth, Filled, Perspective, PixelLight, Points, Primitive, Stage,
    StageName, VertexLight, View, Wireframe,
};
use glam::Vec3;

/// The image being drawn: colours as `0x00RRGGBB` (the layout a window wants) and,
/// for stages that test depth, 1/z per pixel (0 = infinitely far).
#[derive(Clone, Debug, Default)]
pub struct Frame {
    pub width: u32,
    pub height: u32,
    pub color: Vec<u32>,
    /// Empty unless the last stage drawn uses a depth buffer.
    pub depth: Vec<f32>,
}

impl Frame {
    pub fn new(width: u32, height: u32) -> Self {
        Frame {
            width,
            height,
            color: vec![0; width as usize * height as usize],
            depth: Vec::new(),
        }
    }

    /// Black, and with `depth` a depth buffer cleared to 0 (section 5); without it
    /// the depth buffer is dropped. Reuses the buffers when the size is unchanged.
    pub fn clear(&mut self, width: u32, height: u32, depth: bool) {
        let n = width as usize * height as usize;
        self.width = width;
        self.height = height;
        self.color.clear();
        self.color.resize(n, 0);
        self.depth.clear();
        if depth {
            self.depth.resize(n, 0.0);
        } else {
            self.depth.shrink_to_fit();
        }
    }

    /// The colour at (x, y) as 8-bit RGB.
    pub fn rgb(&self, x: u32, y: u32) -> [u8; 3] {
        unpack(self.color[(y * self.width + x) as usize])
    }

    /// The whole image as 8-bit RGB rows, top first.
    pub fn to_rgb8(&self) -> Vec<u8> {
        self.color.iter().flat_map(|&c| unpack(c)).collect()
    }
}

/// `0x00RRGGBB` as `[r, g, b]`: the inverse of [`pack`]'s layout.
#[inline]
pub fn unpack(c: u32) -> [u8; 3] {
    [(c >> 16) as u8, (c >> 8) as u8, c as u8]
}

/// A linear colour in [0, 1] as `0x00RRGGBB`, clamped and rounded to 8 bits.
/// NaN becomes 0.
#[inline]
pub fn pack(c: Vec3) -> u32 {
    // Written as selects and a plain conversion, not clamp and `as`, so loops over
    // pixels vectorise; for every input, NaN included, the result is that of
    // clamping then rounding.
    let q = |v: f32| {
        let v = if v > 0.0 { v } else { 0.0 }; // NaN -> 0
        let v = if v < 1.0 { v } else { 1.0 };
        // SAFETY: v is in [0, 1], so the value is in [0.5, 255.5]: finite and
        // representable as i32, which is all `to_int_unchecked` requires.
        unsafe { (v * 255.0 + 0.5).to_int_unchecked::<i32>() as u32 }
    };
    (q(c.x) << 16) | (q(c.y) << 8) | q(c.z)
}

/// The handout's `VertexShader` after any near-plane clip: eq. 3 and 4 (before
/// truncation) and the stage's screen-space data for one camera-space vertex.
/// `None` if the vertex lies on the camera plane and cannot be projected.
#[inline]
pub fn vertex_shader<S: Stage>(
    stage: &S,
    projection: &Projection,
    c: CameraVertex<S::Attributes>,
) -> Option<ScreenVertex<S::Varying>> {
    let (x, y, zinv) = projection.project_centred(c.pos)?;
    Some(ScreenVertex {
        x,
        y,
        v: stage.to_varying(c.a, zinv),
    })
}

/// How far the guard band reaches beyond each side of the screen, in screen
/// sizes: primitives are cut there, so none costs more than a few screens.
pub const GUARD_BAND: f32 = 1.0;

/// A projected vertex on its pixel, truncated as the handout does.
#[inline]
fn to_pixel<V>(projection: &Projection, s: ScreenVertex<V>) -> Pixel<V> {
    let (x, y) = projection.to_pixel(s.x, s.y);
    Pixel { x, y, v: s.v }
}

/// True if every corner lies beyond one side of the screen by more than the
/// pixel or two that rounding and running sums can move a pixel.
fn off_screen<V>(corners: &[ScreenVertex<V>], screen: &Rect) -> bool {
    let m = 2.0;
    corners.iter().all(|v| v.x < screen.left - m)
        || corners.iter().all(|v| v.x > screen.right + m)
        || corners.iter().all(|v| v.y < screen.top - m)
        || corners.iter().all(|v| v.y > screen.bottom + m)
}

/// The depth test of section 5 for pixel `i`: true, with the depth buffer updated,
/// if the pixel is nearer than what is there (or the stage has no depth buffer).
#[inline(always)]
fn depth_test<S: Stage>(frame: &mut Frame, i: usize, v: &S::Varying) -> bool {
    if !S::DEPTH_BUFFER {
        return true;
    }
    let zinv = S::zinv(v);
    // Nearer means larger 1/z. A NaN compares false and is never drawn.
    if zinv <= frame.depth[i] || zinv.is_nan() {
        return false;
    }
    frame.depth[i] = zinv;
    true
}

/// The handout's `PixelShader`: the depth test (if the stage has a depth buffer),
/// then the stage's colour into the frame. `p` is on the screen.
#[inline(always)]
fn pixel_shader<S: Stage>(stage: &S, frame: &mut Frame, p: Pixel<S::Varying>, tri: &Triangle) {
    let i = p.y as usize * frame.width as usize + p.x as usize;
    if depth_test::<S>(frame, i, &p.v) {
        frame.color[i] = pack(stage.pixel_shader(&p.v, tri));
    }
}

/// A triangle's pixels that passed the depth test, waiting to be coloured
/// together (`Stage::BATCHED`). Kept between triangles and frames.
struct Batch<V> {
    index: Vec<usize>,
    v: Vec<V>,
    color: Vec<u32>,
}

/// A stage with the buffers it reuses from one polygon and one frame to the next.
pub struct Rasterizer<S: Stage> {
    pub stage: S,
    rows: Rows<S::Varying>,
    batch: Batch<S::Varying>,
}

impl<S: Stage> Rasterizer<S> {
    pub fn new(stage: S) -> Self {
        Rasterizer {
            stage,
            rows: Rows::new(),
            batch: Batch {
                index: Vec::new(),
                v: Vec::new(),
                color: Vec::new(),
            },
        }
    }

    /// The handout's `Draw`: clear the frame, then draw every triangle of `scene`.
    ///
    /// With `camera.near` set, each primitive is clipped at the near plane before
    /// projection and at a guard band around the screen after it (see `clip`).
    /// A triangle in full view goes through neither cut, so its pixels are
    /// exactly the handout's.
    pub fn draw(&mut self, scene: &[Triangle], camera: &Camera, frame: &mut Frame) {
        frame.clear(camera.width, camera.height, S::DEPTH_BUFFER);
        let view = ViewVolume::new(camera);
        for tri in scene {
            let corners = tri.vertices().map(|w| CameraVertex {
                pos: view.projection.to_camera(w),
                a: self.stage.vertex_shader(w, tri),
            });
            match S::PRIMITIVE {
                Primitive::Points => draw_points(&self.stage, &view, &corners, tri, frame),
                Primitive::Lines => draw_edges(&self.stage, &view, &corners, tri, frame),
                Primitive::Polygons => self.draw_polygon(&view, &corners, tri, frame),
            }
        }
    }

    /// The handout's `DrawPolygon`: clip, project, `ComputePolygonRows`, and
    /// `DrawPolygonRows` with the depth test and the pixel shader.
    fn draw_polygon(
        &mut self,
        view: &ViewVolume,
        corners: &[CameraVertex<S::Attributes>; 3],
        tri: &Triangle,
        frame: &mut Frame,
    ) {
        let stage = &self.stage;
        let mut polygon = Polygon::from_slice(corners);
        if let Some(n) = view.near {
            polygon = clip_near(&polygon, n);
        }
        let mut on_screen = Polygon::default();
        for &c in polygon.as_slice() {
            match vertex_shader(stage, &view.projection, c) {
                Some(s) => on_screen.push(s),
                None => return, // a corner on the camera plane (only without clipping)
            }
        }
        if off_screen(on_screen.as_slice(), &view.screen) {
            return;
        }
        if !on_screen.as_slice().iter().all(|s| view.band.contains(s)) {
            on_screen = clip_rect(&on_screen, &view.band);
        }
        let mut pixels = Polygon::default();
        for &s in on_screen.as_slice() {
            pixels.push(to_pixel(&view.projection, s));
        }
        compute_polygon_rows(pixels.as_slice(), &view.clip, &mut self.rows);
        if !S::BATCHED {
            draw_polygon_rows(&self.rows, &view.clip, |p| {
                pixel_shader(stage, frame, p, tri)
            });
            return;
        }
        // The same depth tests, then the triangle's visible pixels coloured in one
        // go: no pixel is visited twice within a triangle, so the frame ends up
        // exactly as pixel by pixel.
        let b = &mut self.batch;
        b.index.clear();
        b.v.clear();
        draw_polygon_rows(&self.rows, &view.clip, |p| {
            let i = p.y as usize * frame.width as usize + p.x as usize;
            if depth_test::<S>(frame, i, &p.v) {
                b.index.push(i);
                b.v.push(p.v);
            }
        });
        b.color.resize(b.v.len(), 0);
        stage.shade_batch(&b.v, tri, &mut b.color);
        for (&i, &c) in b.index.iter().zip(&b.color) {
            frame.color[i] = c;
        }
    }
}

/// Where a frame can be drawn: the camera's projection, its near plane, the screen,
/// and the guard band around it.
struct ViewVolume {
    projection: Projection,
    near: Option<f32>,
    clip: Clip,
    screen: Rect,
    band: Rect,
}

impl ViewVolume {
    fn new(camera: &Camera) -> Self {
        let screen = camera.screen_rect();
        let g = camera.width.max(camera.height) as f32 * GUARD_BAND;
        ViewVolume {
            projection: camera.projection(),
            near: camera.near,
            clip: Clip::screen(camera.width, camera.height),
            screen,
            band: Rect {
                left: screen.left - g,
                top: screen.top - g,
                right: screen.right + g,
                bottom: screen.bottom + g,
            },
        }
    }
}

/// Section 2: each corner in front of the near plane as one pixel.
fn draw_points<S: Stage>(
    stage: &S,
    view: &ViewVolume,
    corners: &[CameraVertex<S::Attributes>; 3],
    tri: &Triangle,
    frame: &mut Frame,
) {
    for &c in corners {
        if view.near.is_some_and(|n| c.pos.z < n || c.pos.z.is_nan()) {
            continue;
        }
        let Some(s) = vertex_shader(stage, &view.projection, c).filter(|s| view.band.contains(s))
        else {
            continue;
        };
        let p = to_pixel(&view.projection, s);
        if view.clip.x.contains(&p.x) && view.clip.y.contains(&p.y) {
            pixel_shader(stage, frame, p, tri);
        }
    }
}

/// The handout's `DrawPolygonEdges`: a line from corner i to corner (i + 1) mod 3,
/// each cut at the near plane and the guard band first.
fn draw_edges<S: Stage>(
    stage: &S,
    view: &ViewVolume,
    corners: &[CameraVertex<S::Attributes>; 3],
    tri: &Triangle,
    frame: &mut Frame,
) {
    let project = |c| vertex_shader(stage, &view.projection, c);
    for i in 0..3 {
        let (p, q) = (corners[i], corners[(i + 1) % 3]);
        let near_cut = match view.near {
            Some(n) => clip_segment_near(p, q, n),
            None => Some((p, q)),
        };
        let Some((p, q)) = near_cut else { continue };
        let (Some(p), Some(q)) = (project(p), project(q)) else {
            continue;
        };
        let banded = if view.band.contains(&p) && view.band.contains(&q) {
            Some((p, q))
        } else {
            clip_segment_rect(p, q, &view.band)
        };
        let Some((p, q)) = banded else { continue };
        let (p, q) = (to_pixel(&view.projection, p), to_pixel(&view.projection, q));
        draw_line(p, q, &view.clip, |px| pixel_shader(stage, frame, px, tri));
    }
}

/// Any stage's rasterizer behind one interface, for choosing a stage at run time.
pub trait Draw {
    fn draw(&mut self, scene: &[Triangle], camera: &Camera, frame: &mut Frame);
    /// Moves the light; stages without light ignore it.
    fn set_light(&mut self, light: Light);
}

impl<S: Stage> Draw for Rasterizer<S> {
    fn draw(&mut self, scene: &[Triangle], camera: &Camera, frame: &mut Frame) {
        Rasterizer::draw(self, scene, camera, frame)
    }

    fn set_light(&mut self, light: Light) {
        self.stage.set_light(light)
    }
}

/// Something to do with a stage once its type is known: the one place that turns
/// a `View` (a name and a flag, chosen at run time) into a concrete stage type.
pub trait WithStage {
    type Output;
    fn with<S: Stage + 'static>(self, stage: S) -> Self::Output;
}

fn with_correction<C: Correction, W: WithStage>(stage: StageName, light: Light, w: W) -> W::Output {
    match stage {
        StageName::Points => w.with(Points),
        StageName::Wireframe => w.with(Wireframe),
        StageName::Filled => w.with(Filled),
        StageName::Depth => w.with(Depth::<C>::new()),
        StageName::VertexLight => w.with(VertexLight::<C>::new(light)),
        StageName::PixelLight => w.with(PixelLight::<C>::new(light)),
    }
}

struct Boxed;

impl WithStage for Boxed {
    type Output = Box<dyn Draw>;
    fn with<S: Stage + 'static>(self, stage: S) -> Box<dyn Draw> {
        Box::new(Rasterizer::new(stage))
    }
}

impl View {
    /// Calls `w` with this figure's stage, lit by `light` where it shades.
    pub fn with_stage<W: WithStage>(self, light: Light, w: W) -> W::Output {
        if self.affine {
            with_correction::<Affine, W>(self.stage, light, w)
        } else {
            with_correction::<Perspective, W>(self.stage, light, w)
        }
    }

    /// The rasterizer for this figure, with `light` for the stages that shade.
    pub fn rasterizer(self, light: Light) -> Box<dyn Draw> {
        self.with_stage(light, Boxed)
    }

    /// Draws this figure of `scene` into a new frame.
    pub fn render(self, scene: &[Triangle], camera: &Camera, light: Light) -> Frame {
        let mut frame = Frame::default();
        self.rasterizer(light).draw(scene, camera, &mut frame);
        frame
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pack_rounds_and_clamps() {
        assert_eq!(pack(Vec3::new(1.0, 0.5, 0.0)), 0x00ff_8000);
        assert_eq!(pack(Vec3::new(2.0, -1.0, f32::NAN)), 0x00ff_0000);
        assert_eq!(pack(Vec3::splat(0.75)), 0x00bf_bfbf); // 191.25 rounds to 191
    }
}
