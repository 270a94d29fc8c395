//! `rasterlab check IMAGE`: which stage a screenshot shows, the light's power and
//! the indirect light that reproduce it, which known differences from the
//! handout it has, and where it still differs.
//!
//! Each hypothesis (a stage, its interpolation and a [`Geometry`]) is drawn through
//! the core once per pass: what surface each pixel shows, and for the lit stages
//! the direct light per unit power there. P and N enter eq. 10 and 11 linearly,
//! `colour = 255 ρ (P d + N)`, so they follow from least squares over the surface
//! interiors (in [`super::fit`]); the colour is then packed to 8 bits by rounding
//! or by truncating and compared with the screenshot.

use super::student::{
    decode, DepthMode, DirectPerPixel, DirectPerVertex, Geometry, Shows, StudentRaster,
};
use super::walk::Walk;
use crate::pipeline::interpolate::{Affine, Interpolation, Perspective};
use crate::pipeline::target::{pack, unpack};
use crate::pipeline::StageName;
use crate::pipeline::{
    Camera, Depth, Filled, Frame, Light, Mesh, Pipeline, PixelLight, Points, Stage, VertexLight,
    Wireframe,
};
use crate::scene::cornell;
use glam::Vec3;

/// π as students who write it 3.14 have it in eq. 10.
#[allow(clippy::approx_constant)]
pub const PI_314: f32 = 3.14;

/// A difference of more than this many 8-bit steps counts as a difference.
pub const THRESHOLD: u8 = 2;

/// The best hypothesis must get at least this share of the pixels within
/// [`LAB3_TOLERANCE`] steps, and as large a share of the pixels it draws, to be
/// called a lab 3 image. Screenshots of the lab get over 90 % of both, even with
/// the light elsewhere and not searched for (94 % for docs/check.md's example),
/// since their differences are edges and a shade; noise and a gradient get 2 %
/// at most, and a black image 0 % of the pixels any stage draws, since the box's
/// surfaces, black background and colours must all be where the stage puts
/// them. Half is far from both.
pub const LAB3_SHARE: f64 = 0.5;

/// See [`LAB3_SHARE`]: loose enough for a light moved a little without `--fit-light`.
pub const LAB3_TOLERANCE: u8 = 16;

/// What to check an image against.
#[derive(Clone, Debug)]
pub struct Setup {
    pub mesh: Mesh,
    pub camera: Camera,
    /// Where the light is, unless `fit_light` searches for it.
    pub light: Vec3,
    /// Fixed light power P instead of fitted.
    pub power: Option<f32>,
    /// Fixed indirect light N instead of fitted.
    pub indirect: Option<f32>,
    pub fit_light: bool,
    /// The stage, when known; otherwise every stage is tried.
    pub stage: Option<StageName>,
    /// Whether the image's edges are where a rasterizer put them, seen from
    /// exactly this camera: not so for a shrunk screenshot (its edges are
    /// blends) nor for a fitted camera (within a fraction of a pixel). The
    /// variants, whose traces are on edges, are looked for only then.
    pub edges_exact: bool,
    /// Whether the image was resampled (shrunk, and checked doubled): its
    /// interiors are means of pixels, too rough to tell π as 3.14 from π.
    pub resampled: bool,
    /// Whether the image was stored with lossy compression (a JPEG): every
    /// colour moved by a few levels, too much to tell truncated colours (half a
    /// level) from rounded ones.
    pub lossy: bool,
}

impl Setup {
    /// The handout's box seen as the skeleton sees it, on an image `width` x
    /// `height`: the camera at (0, 0, -3.001) and, since the handout sets the focal
    /// length to the screen's size, f = the height.
    pub fn handout(width: u32, height: u32) -> Setup {
        let mut camera = Camera::handout(width, height);
        camera.focal = height as f32;
        Setup {
            mesh: cornell::cornell_box(),
            camera,
            light: Light::handout().position,
            power: None,
            indirect: None,
            fit_light: false,
            stage: None,
            edges_exact: true,
            resampled: false,
            lossy: false,
        }
    }
}

/// A stage, drawn a way: one explanation of an image, before its light is fitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Hypothesis {
    pub stage: StageName,
    /// The lit stages' interpolation: affine (linear on the screen) or perspective-correct.
    pub affine: bool,
    pub geometry: Geometry,
}

impl Hypothesis {
    /// The stage as the handout draws it.
    pub fn handout(stage: StageName) -> Hypothesis {
        Hypothesis {
            stage,
            affine: stage.affine_by_default(),
            geometry: Geometry {
                // Section 4 fills without a depth buffer; section 5 adds it.
                depth: if stage == StageName::Filled {
                    DepthMode::None
                } else {
                    DepthMode::InverseZ
                },
                ..Geometry::default()
            },
        }
    }

    /// The handout's figure number this hypothesis draws, or a variation of.
    pub fn figure(self) -> u8 {
        match self.stage {
            StageName::Points => 2,
            StageName::Wireframe => 3,
            StageName::Filled => 4,
            StageName::Depth => 5,
            StageName::VertexLight => 6,
            StageName::PixelLight if self.affine => 8,
            StageName::PixelLight => 7,
        }
    }

    pub fn lit(self) -> bool {
        self.stage.is_lit()
    }

    /// Whether the stage fills polygons with a depth test by default.
    fn tests_depth(self) -> bool {
        self.stage.has_depth()
    }

    /// The variants of this hypothesis' geometry and interpolation, by name.
    pub fn variants(self) -> Vec<&'static str> {
        let g = self.geometry;
        let mut names = Vec::new();
        if g.projection_sum {
            names.push("projection-sum-truncated");
        }
        names.extend(g.walk.names());
        match g.depth {
            _ if !self.tests_depth() => {}
            DepthMode::InverseZ => {}
            DepthMode::None => names.push("no-depth-test"),
            DepthMode::Z => names.push("z-interpolated"),
        }
        if self.stage == StageName::VertexLight && !self.affine {
            names.push("perspective-vertex-light");
        }
        names
    }

    /// Every hypothesis one change away: the projection, each choice of the
    /// edge walk, the depth test, and the lit stages' interpolation.
    pub fn neighbours(self) -> Vec<Hypothesis> {
        let mut out = Vec::new();
        let g = self.geometry;
        let with = |geometry: Geometry| Hypothesis { geometry, ..self };
        out.push(with(Geometry {
            projection_sum: !g.projection_sum,
            ..g
        }));
        if self.stage != StageName::Points {
            let w = g.walk;
            for walk in [
                Walk {
                    rounding: !w.rounding,
                    ..w
                },
                Walk {
                    dy_sampling: !w.dy_sampling,
                    ..w
                },
                Walk {
                    step_over_n: !w.step_over_n,
                    ..w
                },
            ] {
                out.push(with(Geometry { walk, ..g }));
            }
        }
        // Without its depth test the depth stage draws Figure 4: found as such when
        // the stage is not given, and as this variant of it with `--stage depth`.
        let depths: &[DepthMode] = match self.stage {
            StageName::Depth | StageName::VertexLight | StageName::PixelLight => {
                &[DepthMode::InverseZ, DepthMode::None, DepthMode::Z]
            }
            _ => &[],
        };
        for &depth in depths {
            if depth != g.depth {
                out.push(with(Geometry { depth, ..g }));
            }
        }
        if self.lit() {
            out.push(Hypothesis {
                affine: !self.affine,
                ..self
            });
        }
        // z carried in place of 1/z breaks the division by 1/z that
        // perspective-correct interpolation needs: tried with affine only.
        out.retain(|h| !(h.geometry.depth == DepthMode::Z && h.lit() && !h.affine));
        out
    }
}

/// No surface: the background.
pub(super) const NONE: u16 = u16::MAX;

/// What a hypothesis draws at each pixel, before the light is known.
#[derive(Clone, Debug)]
pub struct Measured {
    pub width: u32,
    pub height: u32,
    /// The surface each pixel shows (an index into `surfaces`), [`NONE`] for none.
    pub(super) surface: Vec<u16>,
    /// Per surface: its reflectance ρ and normal.
    pub(super) surfaces: Vec<(Vec3, Vec3)>,
    /// The direct light per unit power (eq. 10 with P = 1); lit stages only.
    pub(super) direct: Vec<f32>,
    /// Interior pixels: the surface's own, 2 pixels from any other.
    pub(super) interior: Vec<bool>,
}

/// `stage` of `mesh` as the rows rasterizer draws it with a student's `geometry`.
fn draw<S: Stage, I: Interpolation>(
    geometry: Geometry,
    stage: &S,
    mesh: &Mesh,
    camera: &Camera,
) -> Frame {
    let mut frame = Frame::default();
    let mut pipeline = Pipeline::<S::Varying, I, StudentRaster>::new();
    pipeline.raster = StudentRaster { geometry };
    pipeline.render(stage, mesh, camera, &mut frame);
    frame
}

/// [`draw`] with the per-pixel struct interpolated affinely or perspective-correctly.
pub(super) fn draw_as<S: Stage>(
    g: Geometry,
    stage: &S,
    affine: bool,
    mesh: &Mesh,
    camera: &Camera,
) -> Frame {
    match affine {
        true => draw::<_, Affine>(g, stage, mesh, camera),
        false => draw::<_, Perspective>(g, stage, mesh, camera),
    }
}

/// The handout's seven figures (2 to 8) of `mesh`, drawn with the handout's
/// walk and light.
pub(super) fn handout_figures(mesh: &Mesh, camera: &Camera) -> Vec<Frame> {
    let (light, g) = (Light::handout(), Geometry::default());
    vec![
        draw::<_, Affine>(g, &Points, mesh, camera),
        draw::<_, Affine>(g, &Wireframe, mesh, camera),
        draw::<_, Affine>(g, &Filled, mesh, camera),
        draw::<_, Affine>(g, &Depth, mesh, camera),
        draw::<_, Affine>(g, &VertexLight { light }, mesh, camera),
        draw::<_, Perspective>(g, &PixelLight { light }, mesh, camera),
        draw::<_, Affine>(g, &PixelLight { light }, mesh, camera),
    ]
}

/// The light with power 1 and no indirect light: what the lit passes draw with.
fn unit_light(position: Vec3) -> Light {
    Light {
        position,
        power: Vec3::ONE,
        indirect: Vec3::ZERO,
    }
}

/// The direct light per unit power at each pixel, as `h` interpolates it.
pub(super) fn direct_pass(h: Hypothesis, mesh: &Mesh, camera: &Camera, light: Vec3) -> Vec<f32> {
    let depth = h.geometry.depth != DepthMode::None;
    let g = h.geometry;
    let frame = {
        let light = unit_light(light);
        match (h.stage == StageName::VertexLight, depth) {
            (true, true) => draw_as(
                g,
                &DirectPerVertex::<true> { light },
                h.affine,
                mesh,
                camera,
            ),
            (true, false) => draw_as(
                g,
                &DirectPerVertex::<false> { light },
                h.affine,
                mesh,
                camera,
            ),
            (false, true) => draw_as(g, &DirectPerPixel::<true> { light }, h.affine, mesh, camera),
            (false, false) => draw_as(
                g,
                &DirectPerPixel::<false> { light },
                h.affine,
                mesh,
                camera,
            ),
        }
    };
    frame.color.iter().map(|&c| decode(c)).collect()
}

/// Draws what `h` shows on `mesh` with the light at `light`.
pub fn measure(h: Hypothesis, mesh: &Mesh, camera: &Camera, light: Vec3) -> Measured {
    let (w, h_px) = (camera.width, camera.height);
    let n = (w * h_px) as usize;
    let mut surface = vec![NONE; n];
    let mut surfaces = Vec::new();
    let mut direct = Vec::new();
    match h.stage {
        StageName::Points | StageName::Wireframe => {
            let g = h.geometry;
            let frame = match h.stage {
                StageName::Points => draw::<_, Affine>(g, &Points, mesh, camera),
                _ => draw::<_, Affine>(g, &Wireframe, mesh, camera),
            };
            surfaces.push((Vec3::ONE, Vec3::ZERO));
            for (s, &c) in surface.iter_mut().zip(&frame.color) {
                if c != 0 {
                    *s = 0;
                }
            }
        }
        _ => {
            let depth = h.geometry.depth != DepthMode::None;
            let g = h.geometry;
            let (colors, normals) = if depth {
                (
                    draw::<_, Affine>(g, &Shows::<true, false>, mesh, camera),
                    draw::<_, Affine>(g, &Shows::<true, true>, mesh, camera),
                )
            } else {
                (
                    draw::<_, Affine>(g, &Shows::<false, false>, mesh, camera),
                    draw::<_, Affine>(g, &Shows::<false, true>, mesh, camera),
                )
            };
            // Each drawn pixel's (material, face normal), by their packed colours.
            let mut known: Vec<(u32, u32)> = Vec::new();
            for face in &mesh.faces {
                let key = (
                    pack(mesh.material(face).color),
                    pack(face.normal * 0.5 + 0.5),
                );
                if !known.contains(&key) {
                    known.push(key);
                    surfaces.push((mesh.material(face).color, face.normal));
                }
            }
            for (i, s) in surface.iter_mut().enumerate() {
                if colors.color[i] == 0 {
                    continue;
                }
                let key = (colors.color[i], normals.color[i]);
                if let Some(k) = known.iter().position(|&k| k == key) {
                    *s = k as u16;
                }
            }
            if h.lit() {
                direct = direct_pass(h, mesh, camera, light);
            }
        }
    }
    let interior = interior_of(&surface, w, h_px, 2);
    Measured {
        width: w,
        height: h_px,
        surface,
        surfaces,
        direct,
        interior,
    }
}

/// Pixels whose (2 margin + 1)² neighbourhood shows one surface.
fn interior_of(surface: &[u16], width: u32, height: u32, margin: u32) -> Vec<bool> {
    let (w, h, m) = (width as usize, height as usize, margin as usize);
    let mut mask = vec![false; w * h];
    for y in m..h.saturating_sub(m) {
        for x in m..w.saturating_sub(m) {
            let s = surface[y * w + x];
            mask[y * w + x] = s != NONE
                && (y - m..=y + m).all(|yy| (x - m..=x + m).all(|xx| surface[yy * w + xx] == s));
        }
    }
    mask
}

/// The light and the 8-bit packing a hypothesis is drawn with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shading {
    pub power: f32,
    pub indirect: f32,
    /// π as eq. 10 is coded: π itself, 3.14 (the direct light 1.0005 times
    /// stronger) or 3 (1.047 times).
    pub pi: f32,
    /// The reflectance multiplied in twice, `ρ ρ (D + N)`: ρ applied in the
    /// light and again as the colour (lit stages).
    pub rho_squared: bool,
    /// Colours truncated to 8 bits instead of rounded.
    pub truncated: bool,
}

impl Shading {
    pub fn handout() -> Shading {
        let l = Light::handout();
        Shading {
            power: l.power.x,
            indirect: l.indirect.x,
            pi: std::f32::consts::PI,
            rho_squared: false,
            truncated: false,
        }
    }

    /// The power that multiplies the direct light per unit power computed with π.
    fn effective_power(self) -> f32 {
        self.power * (std::f32::consts::PI / self.pi)
    }
}

/// The colour `m` predicts at pixel `i` with `shading`, packed to `0x00RRGGBB`.
pub(super) fn predict(m: &Measured, i: usize, lit: bool, shading: Shading) -> u32 {
    let s = m.surface[i];
    if s == NONE {
        return 0;
    }
    let rho = m.surfaces[s as usize].0;
    let c = if lit {
        let rho = if shading.rho_squared { rho * rho } else { rho };
        rho * (shading.effective_power() * m.direct[i] + shading.indirect)
    } else {
        rho
    };
    if shading.truncated {
        let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0) as u32;
        (q(c.x) << 16) | (q(c.y) << 8) | q(c.z)
    } else {
        pack(c)
    }
}

/// The whole image `m` predicts.
pub fn predicted(m: &Measured, lit: bool, shading: Shading) -> Frame {
    let mut frame = Frame::new(m.width, m.height);
    for (i, c) in frame.color.iter_mut().enumerate() {
        *c = predict(m, i, lit, shading);
    }
    frame
}

/// How far a prediction is from the screenshot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Errors {
    /// RMSE over the interior pixels' channels, in 8-bit steps (over every pixel
    /// when the stage has no interiors: points and lines).
    pub interior_rmse: f64,
    /// Share of all pixels with a channel off by more than [`THRESHOLD`].
    pub off: f64,
    /// Share of all pixels within [`LAB3_TOLERANCE`].
    pub near: f64,
    /// Share of the pixels the hypothesis draws within [`LAB3_TOLERANCE`].
    pub near_drawn: f64,
    /// Pixels equal in every channel.
    pub exact: usize,
    /// The largest channel difference.
    pub max: u8,
}

pub(super) fn largest_difference(a: u32, b: u32) -> u8 {
    let (p, q) = (unpack(a), unpack(b));
    (0..3).map(|k| p[k].abs_diff(q[k])).max().unwrap_or(0)
}

pub(super) fn errors(m: &Measured, observed: &Frame, lit: bool, shading: Shading) -> Errors {
    let use_interior = m.interior.iter().any(|&b| b);
    let (mut sum, mut count, mut off, mut near, mut drawn, mut near_drawn) =
        (0u64, 0u64, 0, 0, 0, 0);
    let (mut exact, mut max) = (0, 0u8);
    for (i, &o) in observed.color.iter().enumerate() {
        let p = predict(m, i, lit, shading);
        let d = largest_difference(p, o);
        max = max.max(d);
        exact += (p == o) as usize;
        off += (d > THRESHOLD) as usize;
        near += (d <= LAB3_TOLERANCE) as usize;
        if m.surface[i] != NONE {
            drawn += 1;
            near_drawn += (d <= LAB3_TOLERANCE) as usize;
        }
        if !use_interior || m.interior[i] {
            let (a, b) = (unpack(p), unpack(o));
            for k in 0..3 {
                let e = a[k].abs_diff(b[k]) as u64;
                sum += e * e;
            }
            count += 3;
        }
    }
    let n = observed.color.len().max(1) as f64;
    Errors {
        interior_rmse: if count == 0 {
            0.0
        } else {
            (sum as f64 / count as f64).sqrt()
        },
        off: off as f64 / n,
        near: near as f64 / n,
        near_drawn: if drawn == 0 {
            0.0
        } else {
            near_drawn as f64 / drawn as f64
        },
        exact,
        max,
    }
}

/// A hypothesis with its light fitted, and how well it explains the image.
#[derive(Clone, Debug)]
pub struct Fitted {
    pub hypothesis: Hypothesis,
    pub shading: Shading,
    pub light: Vec3,
    pub errors: Errors,
    pub measured: Measured,
}

impl Fitted {
    /// Every variant's name: the geometry's and the shading's.
    pub fn variants(&self) -> Vec<&'static str> {
        let mut names = self.hypothesis.variants();
        if self.shading.truncated {
            names.push("truncated-colours");
        }
        if self.shading.pi == PI_314 {
            names.push("pi-3.14");
        }
        if self.shading.pi == 3.0 {
            names.push("pi-3");
        }
        if self.shading.rho_squared {
            names.push("rho-squared");
        }
        names
    }

    /// Better: fewer pixels off, then a smaller interior error, then fewer
    /// variants. Where the edges are not exact (blended, or seen from a fitted
    /// camera) they rank nothing: a clearly smaller interior error (a fifth
    /// less, and 0.05/255) is needed, so the plainer `other` keeps its place.
    pub(super) fn better_than(&self, other: &Fitted, edges_exact: bool) -> bool {
        if !edges_exact {
            return self.errors.interior_rmse < 0.8 * other.errors.interior_rmse - 0.05;
        }
        let key = |f: &Fitted| (f.errors.off, f.errors.interior_rmse, f.variants().len());
        let (a, b) = (key(self), key(other));
        (a.0, a.1, a.2) < (b.0, b.1, b.2)
    }
}

/// Where the differences left after the fit are.
#[derive(Clone, Debug, PartialEq)]
pub struct Where {
    /// Pixels off by more than [`THRESHOLD`].
    pub total: usize,
    /// Of them, on the edges: not in any surface's interior.
    pub edges: usize,
    /// The rest, by surface name, most first.
    pub surfaces: Vec<(String, usize)>,
}

impl Where {
    /// One word for a teacher's script: `none`, `edges`, `one-surface` or `everywhere`.
    pub fn summary(&self) -> &'static str {
        let inside = self.total - self.edges;
        if self.total == 0 {
            "none"
        } else if inside * 20 <= self.total {
            "edges"
        } else if self
            .surfaces
            .first()
            .is_some_and(|(_, k)| k * 5 >= inside * 4)
        {
            "one-surface"
        } else {
            "everywhere"
        }
    }
}

/// A surface of the box by its colour and the way it faces.
pub fn surface_name(rho: Vec3, normal: Vec3) -> String {
    let named = [
        (cornell::GREEN, "the floor"),
        (cornell::PURPLE, "the left wall"),
        (cornell::YELLOW, "the right wall"),
        (cornell::CYAN, "the ceiling"),
        (cornell::WHITE, "the back wall"),
        (cornell::RED, "the short block"),
        (cornell::BLUE, "the tall block"),
    ];
    let Some(&(_, name)) = named.iter().find(|(c, _)| *c == rho) else {
        return format!("the surface of colour {rho}");
    };
    if rho != cornell::RED && rho != cornell::BLUE {
        return name.to_string();
    }
    let facing = if normal.y < -0.9 {
        "top"
    } else if normal.z < -0.5 {
        "front"
    } else if normal.x < -0.5 {
        "left side"
    } else if normal.x > 0.5 {
        "right side"
    } else {
        "back"
    };
    format!("{name}'s {facing}")
}

pub(super) fn where_off(f: &Fitted, observed: &Frame) -> Where {
    let m = &f.measured;
    let lit = f.hypothesis.lit();
    let mut by_surface = vec![0usize; m.surfaces.len()];
    let (mut total, mut edges) = (0, 0);
    for (i, &o) in observed.color.iter().enumerate() {
        if largest_difference(predict(m, i, lit, f.shading), o) <= THRESHOLD {
            continue;
        }
        total += 1;
        if m.interior[i] {
            by_surface[m.surface[i] as usize] += 1;
        } else {
            edges += 1;
        }
    }
    let mut surfaces: Vec<(String, usize)> = by_surface
        .iter()
        .enumerate()
        .filter(|(_, &k)| k > 0)
        .map(|(s, &k)| {
            let (rho, normal) = m.surfaces[s];
            let name = if lit || f.hypothesis.stage >= StageName::Filled {
                surface_name(rho, normal)
            } else {
                "the lines".to_string()
            };
            (name, k)
        })
        .collect();
    surfaces.sort_by_key(|s| std::cmp::Reverse(s.1));
    Where {
        total,
        edges,
        surfaces,
    }
}

/// What `check` found in a screenshot.
#[derive(Clone, Debug)]
pub struct ImageCheck {
    pub width: u32,
    pub height: u32,
    /// The best explanation, or `None` when it is not a lab 3 image.
    pub fitted: Option<Fitted>,
    /// The best explanation even when it is too poor to count (for the message).
    pub closest: Fitted,
    /// The handout's figure of the same number against the screenshot.
    pub before: Errors,
    pub remaining: Where,
    /// What the best explanation draws.
    pub expected: Frame,
    /// Whether the light's position was searched for (`--fit-light`, or
    /// because the shade differed) and this check is from the light found.
    pub light_searched: bool,
    /// Whether the light was searched for because the shade differed, and no
    /// position explained the image better: this check is from the light given.
    pub light_searched_in_vain: bool,
    /// What was done to the image before checking it, in words (red and blue
    /// swapped back, a focal length other than assumed).
    pub notes: Vec<String>,
    /// Whether the image was adjusted before it was explained (red and blue
    /// swapped back, flipped, a gamma taken off): the student's program has the
    /// slip, so the image is not the handout's figure even when the repair is.
    pub adjusted: bool,
    /// The camera fitted to the image when it is not the handout's.
    pub camera: Option<crate::pipeline::Camera>,
    /// Where the render was found inside a screenshot: x, y, width, height.
    pub crop: Option<[u32; 4]>,
    /// Whether the image is a JPEG, whose pixels are not compared to 2/255.
    pub lossy: bool,
    /// The other of filled and depth when, from this camera, it draws the
    /// same image as the stage fitted ([`Alike`]).
    pub alike: Option<Alike>,
}

/// Figure 4 and Figure 5 from a camera where no surface hides another inside
/// the image: the same surfaces in every pixel but along edges (which of two
/// faces sharing an edge draws it). Exact edges tell the two apart; a fitted
/// camera's or a resized image's do not, nor does an image where the two
/// draw the same pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Alike {
    pub hypothesis: Hypothesis,
    /// Pixels where the two draw differently, all on edges.
    pub pixels: usize,
}

impl ImageCheck {
    /// Whether the image is the handout's figure (of `stage`, when one is
    /// asked for) within [`THRESHOLD`] at every pixel: `check`'s exit status 0.
    pub fn is_handouts_figure(&self, stage: Option<StageName>) -> bool {
        let asked = |f: &Fitted| stage.is_none_or(|s| f.hypothesis.stage == s);
        self.fitted.as_ref().is_some_and(asked) && self.before.off == 0.0 && !self.adjusted
    }
}
