//! `rasterlab check IMAGE`: which stage a screenshot shows, the light's power and
//! the indirect light that reproduce it, which known differences from the
//! handout it has, and where it still differs.
//!
//! Each hypothesis (a stage, its interpolation and a [`Geometry`]) is drawn through
//! the core once per pass: what surface each pixel shows, and for the lit stages
//! the direct light per unit power there. P and N enter eq. 10 and 11 linearly,
//! `colour = 255 ρ (P d + N)`, so they follow from least squares over the surface
//! interiors; the colour is then packed to 8 bits by rounding or by truncating and
//! compared with the screenshot.

use super::student::{
    decode, with_geometry, DepthMode, DirectPerPixel, DirectPerVertex, Geometry, Shows,
    StudentRaster,
};
use super::walk::Walk;
use crate::measure::figure::StageName;
use crate::pipeline::interpolate::{Affine, Interpolation, Perspective};
use crate::pipeline::target::{pack, unpack};
use crate::pipeline::{
    Camera, Frame, Light, Mesh, Pipeline, Points, Render, Stage, Uniforms, Wireframe,
};
use crate::scene::cornell;
use glam::Vec3;
use std::fmt::Write as _;

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

    fn lit(self) -> bool {
        self.stage.interpolates()
    }

    /// Whether the stage fills polygons with a depth test by default.
    fn tests_depth(self) -> bool {
        self.stage >= StageName::Depth
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
        // Without its depth test the depth stage is Figure 4, found as such.
        let depths: &[DepthMode] = match self.stage {
            StageName::Depth => &[DepthMode::InverseZ, DepthMode::Z],
            StageName::VertexLight | StageName::PixelLight => {
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
const NONE: u16 = u16::MAX;

/// What a hypothesis draws at each pixel, before the light is known.
#[derive(Clone, Debug)]
pub struct Measured {
    pub width: u32,
    pub height: u32,
    /// The surface each pixel shows (an index into `surfaces`), [`NONE`] for none.
    surface: Vec<u16>,
    /// Per surface: its reflectance ρ and normal.
    surfaces: Vec<(Vec3, Vec3)>,
    /// The direct light per unit power (eq. 10 with P = 1); lit stages only.
    direct: Vec<f32>,
    /// Interior pixels: the surface's own, 2 pixels from any other.
    interior: Vec<bool>,
}

fn draw<S: Stage, I: Interpolation>(mesh: &Mesh, camera: &Camera, uniforms: &Uniforms) -> Frame {
    let mut frame = Frame::default();
    Pipeline::<S, I, StudentRaster>::new().render(mesh, camera, uniforms, &mut frame);
    frame
}

/// The light with power 1 and no indirect light: what the lit passes draw with.
fn unit_light(position: Vec3) -> Uniforms {
    Uniforms {
        light: Light {
            position,
            power: Vec3::ONE,
            indirect: Vec3::ZERO,
        },
    }
}

/// The direct light per unit power at each pixel, as `h` interpolates it.
fn direct_pass(h: Hypothesis, mesh: &Mesh, camera: &Camera, light: Vec3) -> Vec<f32> {
    let u = unit_light(light);
    let depth = h.geometry.depth != DepthMode::None;
    let frame = with_geometry(h.geometry, || {
        match (h.stage == StageName::VertexLight, depth, h.affine) {
            (true, true, true) => draw::<DirectPerVertex<true>, Affine>(mesh, camera, &u),
            (true, true, false) => draw::<DirectPerVertex<true>, Perspective>(mesh, camera, &u),
            (true, false, true) => draw::<DirectPerVertex<false>, Affine>(mesh, camera, &u),
            (true, false, false) => draw::<DirectPerVertex<false>, Perspective>(mesh, camera, &u),
            (false, true, true) => draw::<DirectPerPixel<true>, Affine>(mesh, camera, &u),
            (false, true, false) => draw::<DirectPerPixel<true>, Perspective>(mesh, camera, &u),
            (false, false, true) => draw::<DirectPerPixel<false>, Affine>(mesh, camera, &u),
            (false, false, false) => draw::<DirectPerPixel<false>, Perspective>(mesh, camera, &u),
        }
    });
    frame.color.iter().map(|&c| decode(c)).collect()
}

/// Draws what `h` shows on `mesh` with the light at `light`.
pub fn measure(h: Hypothesis, mesh: &Mesh, camera: &Camera, light: Vec3) -> Measured {
    let u = unit_light(light);
    let (w, h_px) = (camera.width, camera.height);
    let n = (w * h_px) as usize;
    let mut surface = vec![NONE; n];
    let mut surfaces = Vec::new();
    let mut direct = Vec::new();
    match h.stage {
        StageName::Points | StageName::Wireframe => {
            let frame = with_geometry(h.geometry, || match h.stage {
                StageName::Points => draw::<Points, Affine>(mesh, camera, &u),
                _ => draw::<Wireframe, Affine>(mesh, camera, &u),
            });
            surfaces.push((Vec3::ONE, Vec3::ZERO));
            for (s, &c) in surface.iter_mut().zip(&frame.color) {
                if c != 0 {
                    *s = 0;
                }
            }
        }
        _ => {
            let depth = h.geometry.depth != DepthMode::None;
            let (colors, normals) = with_geometry(h.geometry, || {
                if depth {
                    (
                        draw::<Shows<true, false>, Affine>(mesh, camera, &u),
                        draw::<Shows<true, true>, Affine>(mesh, camera, &u),
                    )
                } else {
                    (
                        draw::<Shows<false, false>, Affine>(mesh, camera, &u),
                        draw::<Shows<false, true>, Affine>(mesh, camera, &u),
                    )
                }
            });
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
    /// π written as 3.14 in eq. 10: the direct light 1.0005 times stronger.
    pub pi_314: bool,
    /// Colours truncated to 8 bits instead of rounded.
    pub truncated: bool,
}

impl Shading {
    pub fn handout() -> Shading {
        let l = Light::handout();
        Shading {
            power: l.power.x,
            indirect: l.indirect.x,
            pi_314: false,
            truncated: false,
        }
    }

    /// The power that multiplies the direct light per unit power computed with π.
    fn effective_power(self) -> f32 {
        if self.pi_314 {
            self.power * (std::f32::consts::PI / PI_314)
        } else {
            self.power
        }
    }
}

/// The colour `m` predicts at pixel `i` with `shading`, packed to `0x00RRGGBB`.
fn predict(m: &Measured, i: usize, lit: bool, shading: Shading) -> u32 {
    let s = m.surface[i];
    if s == NONE {
        return 0;
    }
    let rho = m.surfaces[s as usize].0;
    let c = if lit {
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

fn largest_difference(a: u32, b: u32) -> u8 {
    let (p, q) = (unpack(a), unpack(b));
    (0..3).map(|k| p[k].abs_diff(q[k])).max().unwrap_or(0)
}

fn errors(m: &Measured, observed: &Frame, lit: bool, shading: Shading) -> Errors {
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

/// Least squares for P and N over the interior pixels' unclamped channels:
/// `(observed + offset) / 255 = ρ d P + ρ N`, the offset 1/2 for truncated
/// colours. Two passes: the second leaves out what the first misses by more than
/// 3 steps (an edge the hypothesis places differently, a highlight clamped).
fn fit_light(
    m: &Measured,
    observed: &Frame,
    truncated: bool,
    power: Option<f32>,
    indirect: Option<f32>,
    stride: usize,
) -> (f32, f32) {
    let offset = if truncated { 0.5 } else { 0.0 };
    let handout = Shading::handout();
    let mut estimate: Option<(f64, f64)> = None;
    for _ in 0..2 {
        let (mut saa, mut sab, mut sbb, mut say, mut sby) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for i in (0..observed.color.len()).step_by(stride) {
            let s = m.surface[i];
            if !m.interior[i] || s == NONE {
                continue;
            }
            let rho = m.surfaces[s as usize].0.to_array();
            let o = unpack(observed.color[i]);
            for k in 0..3 {
                if o[k] == 0 || o[k] == 255 {
                    continue; // clamped: says only "at least" or "at most"
                }
                let a = rho[k] as f64 * m.direct[i] as f64;
                let b = rho[k] as f64;
                let y = (o[k] as f64 + offset) / 255.0;
                if let Some((p, n)) = estimate {
                    if ((a * p + b * n - y) * 255.0).abs() > 3.0 {
                        continue;
                    }
                }
                saa += a * a;
                sab += a * b;
                sbb += b * b;
                say += a * y;
                sby += b * y;
            }
        }
        let solved = match (power, indirect) {
            (Some(p), Some(n)) => Some((p as f64, n as f64)),
            (Some(p), None) => (sbb > 0.0).then(|| (p as f64, (sby - p as f64 * sab) / sbb)),
            (None, Some(n)) => (saa > 0.0).then(|| ((say - n as f64 * sab) / saa, n as f64)),
            (None, None) => {
                let det = saa * sbb - sab * sab;
                (det.abs() > 1e-12 * (saa * sbb).max(1e-300))
                    .then(|| ((say * sbb - sby * sab) / det, (sby * saa - say * sab) / det))
            }
        };
        match solved {
            Some(s) => estimate = Some(s),
            None => break,
        }
    }
    let (p, n) = estimate.unwrap_or((handout.power as f64, handout.indirect as f64));
    (p as f32, n as f32)
}

/// `v` rounded to `decimals` places.
fn round_to(v: f32, decimals: i32) -> f32 {
    let s = 10f32.powi(decimals);
    (v * s).round() / s
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
        if self.shading.pi_314 {
            names.push("pi-3.14");
        }
        names
    }

    /// Better: fewer pixels off, then a smaller interior error, then fewer variants.
    fn better_than(&self, other: &Fitted) -> bool {
        let key = |f: &Fitted| (f.errors.off, f.errors.interior_rmse, f.variants().len());
        let (a, b) = (key(self), key(other));
        (a.0, a.1, a.2) < (b.0, b.1, b.2)
    }
}

/// The shading that best explains `observed` under `m`: each packing, P and N
/// fitted, then the plain values nearby (P to one or two decimals, N to two,
/// and the same with π as 3.14) preferred when they match as many pixels.
fn best_shading(m: &Measured, observed: &Frame, lit: bool, setup: &Setup) -> (Shading, Errors) {
    if !lit {
        let s = Shading::handout();
        return (s, errors(m, observed, false, s));
    }
    let mut best: Option<(Shading, Errors)> = None;
    for truncated in [false, true] {
        let (p, n) = fit_light(m, observed, truncated, setup.power, setup.indirect, 1);
        let fitted = Shading {
            power: p,
            indirect: n,
            pi_314: false,
            truncated,
        };
        let fitted_errors = errors(m, observed, true, fitted);
        let interior = m.interior.iter().filter(|&&b| b).count();
        // "As many": within 0.05 % of the interior, far less than the share a
        // slightly wrong P or π costs (a few percent) and more than the pixels a
        // fit of 8-bit data can move.
        let slack = (interior / 2000).max(3);
        let mut chosen = (fitted, fitted_errors);
        let mut candidates = Vec::new();
        let scale_pi = PI_314 / std::f32::consts::PI;
        let nice_n = setup.indirect.unwrap_or(round_to(n, 2));
        let nice = |v: f32, decimals| setup.power.unwrap_or(round_to(v, decimals));
        for (pi_314, decimals) in [(true, 2), (true, 1), (false, 2), (false, 1)] {
            let power = if pi_314 { p * scale_pi } else { p };
            candidates.push(Shading {
                power: nice(power, decimals),
                indirect: nice_n,
                pi_314,
                truncated,
            });
        }
        // Later candidates are plainer; each one wins if it matches as many pixels.
        let mut best_exact = fitted_errors.exact;
        for c in candidates {
            let e = errors(m, observed, true, c);
            best_exact = best_exact.max(e.exact);
            if e.exact + slack >= best_exact && e.exact + slack >= chosen.1.exact {
                chosen = (c, e);
            }
        }
        let replace = match &best {
            None => true,
            Some((_, e)) => chosen.1.exact > e.exact + slack,
        };
        if replace {
            best = Some(chosen);
        }
    }
    best.expect("two packings tried")
}

/// `h` with P and N fitted for rounded and for truncated colours, unless the
/// setup fixes them, and the better kept: enough to rank hypotheses and light
/// positions. (The plain values and π come later, in [`best_shading`].)
fn quick_fit(h: Hypothesis, observed: &Frame, setup: &Setup, light: Vec3) -> Fitted {
    fitted(
        h,
        measure(h, &setup.mesh, &setup.camera, light),
        observed,
        setup,
        light,
    )
}

/// [`quick_fit`] of what has been measured.
fn fitted(
    h: Hypothesis,
    measured: Measured,
    observed: &Frame,
    setup: &Setup,
    light: Vec3,
) -> Fitted {
    let mut best: Option<(Shading, Errors)> = None;
    for truncated in [false, true] {
        if !h.lit() && truncated {
            continue;
        }
        let shading = if h.lit() {
            let (power, indirect) = fit_light(
                &measured,
                observed,
                truncated,
                setup.power,
                setup.indirect,
                1,
            );
            Shading {
                power,
                indirect,
                truncated,
                ..Shading::handout()
            }
        } else {
            Shading::handout()
        };
        let e = errors(&measured, observed, h.lit(), shading);
        if best.is_none_or(|(_, b)| e.interior_rmse < b.interior_rmse) {
            best = Some((shading, e));
        }
    }
    let (shading, errors) = best.expect("one packing tried");
    Fitted {
        hypothesis: h,
        shading,
        light,
        errors,
        measured,
    }
}

/// `f` with the light at `light`: only the direct light is drawn again, since
/// which surface each pixel shows does not depend on the light.
fn relit(f: &Fitted, observed: &Frame, setup: &Setup, light: Vec3) -> Fitted {
    let mut measured = f.measured.clone();
    measured.direct = direct_pass(f.hypothesis, &setup.mesh, &setup.camera, light);
    fitted(f.hypothesis, measured, observed, setup, light)
}

/// The best of `hypotheses`.
fn best_of(hypotheses: &[Hypothesis], observed: &Frame, setup: &Setup, light: Vec3) -> Fitted {
    let mut best: Option<Fitted> = None;
    for &h in hypotheses {
        let f = quick_fit(h, observed, setup, light);
        if best.as_ref().is_none_or(|b| f.better_than(b)) {
            best = Some(f);
        }
    }
    best.expect("at least one hypothesis")
}

/// How many pixels `candidate` explains better than `current`, and worse: of the
/// pixels where their predictions differ by more than [`THRESHOLD`], those where
/// it is nearer the image, and those where it is farther.
fn explains(current: &Fitted, candidate: &Fitted, observed: &Frame) -> (usize, usize) {
    let (mut better, mut worse) = (0, 0);
    for (i, &o) in observed.color.iter().enumerate() {
        let a = predict(
            &current.measured,
            i,
            current.hypothesis.lit(),
            current.shading,
        );
        let b = predict(
            &candidate.measured,
            i,
            candidate.hypothesis.lit(),
            candidate.shading,
        );
        if a == b {
            continue;
        }
        let (da, db) = (largest_difference(a, o), largest_difference(b, o));
        if da.abs_diff(db) <= THRESHOLD {
            continue;
        }
        better += (db < da) as usize;
        worse += (db > da) as usize;
    }
    (better, worse)
}

/// From `start`, one change at a time while a change explains the image better.
/// The variants leave separate traces (left and top edges, the rows' ends,
/// occlusions, the shade inside), so each one found improves the match on its own.
/// A change is taken only if it explains at least 10 pixels better and three
/// times as many as it explains worse: the right variant explains nearly all the
/// pixels it changes, while with something else wrong (a light elsewhere) a
/// wrong one that happens to lower the error does barely better than chance.
fn climb(start: Fitted, observed: &Frame, setup: &Setup) -> Fitted {
    let mut best = start;
    loop {
        let mut next: Option<(Fitted, usize)> = None;
        for h in best.hypothesis.neighbours() {
            let mut f = quick_fit(h, observed, setup, best.light);
            if setup.fit_light && h.lit() {
                // A variant that moves the pixels moves the light that fits
                // them best: each is judged with the light fitted to it.
                f = search_light(observed, setup, f, 0.02, 40);
            }
            let (better, worse) = explains(&best, &f, observed);
            let gain = better.saturating_sub(worse);
            if better >= 10 && better >= 3 * worse && next.as_ref().is_none_or(|(_, g)| gain > *g) {
                next = Some((f, gain));
            }
        }
        match next {
            Some((f, _)) => best = f,
            None => return best,
        }
    }
}

/// Every [`LIGHT_STRIDE`]th pixel is enough to place the light: the interiors
/// of 500 x 500 screenshot still give 40 000 of them.
const LIGHT_STRIDE: usize = 4;

/// How well the light at `light` explains the interiors under `shapes`' surfaces
/// and packing, P and N fitted: the interior RMSE over every [`LIGHT_STRIDE`]th pixel.
fn light_score(shapes: &Fitted, observed: &Frame, setup: &Setup, light: Vec3) -> f64 {
    let mut m = shapes.measured.clone();
    m.direct = direct_pass(shapes.hypothesis, &setup.mesh, &setup.camera, light);
    let truncated = shapes.shading.truncated;
    let (power, indirect) = fit_light(
        &m,
        observed,
        truncated,
        setup.power,
        setup.indirect,
        LIGHT_STRIDE,
    );
    let shading = Shading {
        power,
        indirect,
        truncated,
        ..Shading::handout()
    };
    let (mut sum, mut count) = (0u64, 0u64);
    for i in (0..observed.color.len()).step_by(LIGHT_STRIDE) {
        if !m.interior[i] {
            continue;
        }
        let (a, b) = (
            unpack(predict(&m, i, true, shading)),
            unpack(observed.color[i]),
        );
        for k in 0..3 {
            let e = a[k].abs_diff(b[k]) as u64;
            sum += e * e;
        }
        count += 3;
    }
    if count == 0 {
        f64::INFINITY
    } else {
        (sum as f64 / count as f64).sqrt()
    }
}

/// The light's position by Hooke and Jeeves' pattern search: steps along each
/// axis from `first_step` down to 0.0002, at most `max_tries` positions, and
/// after each success a jump along the way the light moved, which follows the
/// long valley a brighter light farther away makes with a dimmer one nearer. P
/// and N are fitted at each position tried.
fn search_light(
    observed: &Frame,
    setup: &Setup,
    start: Fitted,
    first_step: f32,
    max_tries: usize,
) -> Fitted {
    let mut tries = 0;
    let mut score = |light: Vec3| {
        tries += 1;
        light_score(&start, observed, setup, light)
    };
    // The best of `from` and its neighbours `step` away along each axis.
    let explore = |from: (Vec3, f64), step: f32, score: &mut dyn FnMut(Vec3) -> f64| {
        let mut best = from;
        for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
            for sign in [1.0, -1.0] {
                let light = best.0 + axis * step * sign;
                let e = score(light);
                if e < best.1 - 1e-9 {
                    best = (light, e);
                    break;
                }
            }
        }
        best
    };
    let first = start.light;
    let mut base = (first, score(first));
    let mut step = first_step;
    let mut budget = max_tries;
    while step >= 2e-4 && budget > 0 {
        let mut next = explore(base, step, &mut score);
        budget = budget.saturating_sub(6);
        if next.1 >= base.1 - 1e-9 {
            step /= 2.0;
            continue;
        }
        // Jump on along the way the light moved while that keeps helping.
        loop {
            let jump = next.0 * 2.0 - base.0;
            base = next;
            let jumped = (jump, score(jump));
            let beyond = explore(jumped, step, &mut score);
            budget = budget.saturating_sub(7);
            if beyond.1 < base.1 - 1e-9 && budget > 0 {
                next = beyond;
            } else {
                break;
            }
        }
    }
    if base.0 == start.light {
        return start;
    }
    relit(&start, observed, setup, base.0)
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

fn where_off(f: &Fitted, observed: &Frame) -> Where {
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
    /// Whether the light's position was searched for (`--fit-light`).
    pub light_searched: bool,
}

/// Checks `observed` against every hypothesis `setup` allows.
pub fn check_image(observed: &Frame, setup: &Setup) -> ImageCheck {
    let light = setup.light;
    let stages: Vec<StageName> = match setup.stage {
        Some(s) => vec![s],
        None => StageName::ALL.to_vec(),
    };
    // First the stage (each as the handout draws it, both interpolations for the
    // lit ones), then every variant of that stage.
    let mut first = Vec::new();
    for &s in &stages {
        first.push(Hypothesis::handout(s));
        if s.interpolates() {
            first.push(Hypothesis {
                affine: !s.affine_by_default(),
                ..Hypothesis::handout(s)
            });
        }
    }
    let mut best = best_of(&first, observed, setup, light);
    // The light first: with it elsewhere, every variant's trace is hidden under
    // the difference in shade. Then the variants, each with the light refitted.
    let search = setup.fit_light && best.hypothesis.lit();
    if search {
        best = search_light(observed, setup, best, 0.1, 300);
    }
    best = climb(best, observed, setup);
    if search {
        // A position with two decimals, as people write them, wins if it explains
        // the interiors as well (within 0.02 of a step).
        let plain = (best.light * 100.0).round() / 100.0;
        let snapped = relit(&best, observed, setup, plain);
        if snapped.errors.interior_rmse <= best.errors.interior_rmse + 0.02 {
            best = snapped;
        }
    }
    let (shading, fitted_errors) =
        best_shading(&best.measured, observed, best.hypothesis.lit(), setup);
    best.shading = shading;
    best.errors = fitted_errors;
    let stage = best.hypothesis.stage;
    let handout = Hypothesis {
        affine: if stage == StageName::PixelLight {
            best.hypothesis.affine
        } else {
            Hypothesis::handout(stage).affine
        },
        ..Hypothesis::handout(stage)
    };
    let handout_measured = measure(handout, &setup.mesh, &setup.camera, setup.light);
    let before = errors(
        &handout_measured,
        observed,
        handout.lit(),
        Shading::handout(),
    );
    let remaining = where_off(&best, observed);
    let expected = predicted(&best.measured, best.hypothesis.lit(), best.shading);
    let lab3 = best.errors.near >= LAB3_SHARE && best.errors.near_drawn >= LAB3_SHARE;
    ImageCheck {
        width: observed.width,
        height: observed.height,
        fitted: lab3.then(|| best.clone()),
        closest: best,
        before,
        remaining,
        expected,
        light_searched: setup.fit_light,
    }
}

/// A number for the report: three significant digits, no trailing zeros.
pub fn three_digits(v: f32) -> String {
    let v = v + 0.0; // -0 is 0
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let digits = (2 - v.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A variant's meaning, in words.
pub fn variant_words(name: &str) -> &'static str {
    match name {
        "projection-sum-truncated" => {
            "the projection truncates the whole sum, int(f X/Z + W/2), not int(f X/Z) + W/2"
        }
        "rounding" => "Interpolate rounds positions instead of truncating them",
        "dy-sampling" => "edges are sampled at |dy| + 1 points instead of max(|dx|, |dy|) + 1",
        "step-over-n" => "Interpolate steps by (b - a) / N instead of (b - a) / (N - 1)",
        "no-depth-test" => "there is no depth test: the triangle drawn last wins",
        "z-interpolated" => "the depth test interpolates z instead of 1/z",
        "perspective-vertex-light" => "the light per vertex is interpolated perspective-correctly",
        "truncated-colours" => "colours are truncated to 8 bits instead of rounded",
        "pi-3.14" => "pi is written as 3.14",
        _ => "an unknown variant",
    }
}

impl ImageCheck {
    /// The report, plain words first.
    pub fn text(&self, name: &str) -> String {
        let mut out = String::new();
        let Some(f) = &self.fitted else {
            let c = &self.closest;
            let _ = writeln!(
                out,
                "{name} is not a lab 3 image: the closest stage, {} (Figure {}), gets only {:.0} % of its pixels within {}/255 ({:.0} % of those it draws); a lab 3 screenshot gets over 90 %.",
                c.hypothesis.stage.name(),
                c.hypothesis.figure(),
                c.errors.near * 100.0,
                LAB3_TOLERANCE,
                c.errors.near_drawn * 100.0
            );
            let _ = writeln!(
                out,
                "If it is one, check its size ({}x{}) and the camera; for a light elsewhere give --light or --fit-light.",
                self.width, self.height
            );
            return out;
        };
        let h = f.hypothesis;
        let lit = h.lit();
        let variants = f.variants();
        let mut first = format!("Your image is the handout's Figure {}", h.figure());
        if lit {
            let default = Shading::handout();
            let differs = |a: f32, b: f32| three_digits(a) != three_digits(b);
            if differs(f.shading.power, default.power) {
                let _ = write!(first, " at light power {}", three_digits(f.shading.power));
            }
            if differs(f.shading.indirect, default.indirect) {
                let _ = write!(
                    first,
                    "{} indirect light {}",
                    if differs(f.shading.power, default.power) {
                        " and"
                    } else {
                        " at"
                    },
                    three_digits(f.shading.indirect)
                );
            }
            if f.light != Light::handout().position {
                let _ = write!(
                    first,
                    " with the light at ({}, {}, {})",
                    three_digits(f.light.x),
                    three_digits(f.light.y),
                    three_digits(f.light.z)
                );
            }
        }
        if !variants.is_empty() {
            let words: Vec<&str> = variants.iter().map(|v| variant_words(v)).collect();
            let _ = write!(first, "; {}", words.join("; "));
        }
        let r = &self.remaining;
        let within = if f.errors.max <= 1 { 1 } else { THRESHOLD };
        if r.total == 0 {
            let _ = write!(first, ". Every pixel matches within {within}/255.");
        } else {
            let _ = write!(
                first,
                ". Every pixel matches within {}/255 except {} ({:.2} %): {}.",
                THRESHOLD,
                r.total,
                f.errors.off * 100.0,
                self.where_words()
            );
        }
        let _ = writeln!(out, "{first}");
        let _ = writeln!(out);
        let _ = writeln!(
            out,
            "stage:      {} (Figure {})",
            h.stage.name(),
            h.figure()
        );
        if lit {
            let _ = writeln!(
                out,
                "light:      power P = {}, indirect N = {}, at ({}, {}, {}){}",
                three_digits(f.shading.power),
                three_digits(f.shading.indirect),
                three_digits(f.light.x),
                three_digits(f.light.y),
                three_digits(f.light.z),
                if self.light_searched {
                    " (fitted)"
                } else if f.light == Light::handout().position {
                    " (the handout's)"
                } else {
                    " (given)"
                }
            );
        }
        let _ = writeln!(
            out,
            "variants:   {}",
            if variants.is_empty() {
                "none".to_string()
            } else {
                variants.join(", ")
            }
        );
        let _ = writeln!(
            out,
            "before fit: interior RMSE {:.2}/255, {:.2} % of pixels off by more than {}/255 (the handout's Figure {})",
            self.before.interior_rmse,
            self.before.off * 100.0,
            THRESHOLD,
            h.figure()
        );
        let _ = writeln!(
            out,
            "after fit:  interior RMSE {:.2}/255, {:.2} % of pixels off by more than {}/255",
            f.errors.interior_rmse,
            f.errors.off * 100.0,
            THRESHOLD
        );
        let _ = writeln!(out, "remaining:  {}", r.summary());
        if lit && !self.light_searched && r.total > r.edges * 2 {
            let _ = writeln!(
                out,
                "The shade still differs inside the surfaces: if your light is elsewhere, --fit-light searches for it."
            );
        }
        out
    }

    fn where_words(&self) -> String {
        let r = &self.remaining;
        let mut parts = Vec::new();
        if r.edges > 0 {
            parts.push(format!("{} on edges", r.edges));
        }
        for (name, k) in r.surfaces.iter().take(3) {
            parts.push(format!("{k} inside {name}"));
        }
        if r.surfaces.len() > 3 {
            let rest: usize = r.surfaces[3..].iter().map(|(_, k)| k).sum();
            parts.push(format!("{rest} inside other surfaces"));
        }
        parts.join(", ")
    }

    /// The report as one JSON object, for a teacher's script.
    pub fn json(&self, name: &str) -> String {
        let mut out = String::from("{");
        let _ = write!(out, "\"image\":{}", json_string(name));
        let _ = write!(out, ",\"width\":{},\"height\":{}", self.width, self.height);
        let Some(f) = &self.fitted else {
            let _ = write!(
                out,
                ",\"lab3\":false,\"figure\":null,\"stage\":null,\"light_power\":null,\"indirect\":null,\"light\":null,\"variants\":[],\"interior_rmse\":null}}"
            );
            return out;
        };
        let h = f.hypothesis;
        let _ = write!(
            out,
            ",\"lab3\":true,\"figure\":{},\"stage\":{}",
            h.figure(),
            json_string(h.stage.name())
        );
        if h.lit() {
            let _ = write!(
                out,
                ",\"light_power\":{},\"indirect\":{},\"light\":[{},{},{}]",
                three_digits(f.shading.power),
                three_digits(f.shading.indirect),
                three_digits(f.light.x),
                three_digits(f.light.y),
                three_digits(f.light.z)
            );
        } else {
            let _ = write!(
                out,
                ",\"light_power\":null,\"indirect\":null,\"light\":null"
            );
        }
        let names: Vec<String> = f.variants().iter().map(|v| json_string(v)).collect();
        let _ = write!(out, ",\"variants\":[{}]", names.join(","));
        let _ = write!(
            out,
            ",\"interior_rmse\":{:.3},\"interior_rmse_before\":{:.3},\"off\":{:.5},\"off_before\":{:.5},\"threshold\":{}",
            f.errors.interior_rmse,
            self.before.interior_rmse,
            f.errors.off,
            self.before.off,
            THRESHOLD
        );
        let r = &self.remaining;
        let _ = write!(
            out,
            ",\"remaining\":{},\"differing\":{},\"on_edges\":{}}}",
            json_string(r.summary()),
            r.total,
            r.edges
        );
        out
    }
}

/// A JSON string literal.
pub fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_three_significant_digits() {
        assert_eq!(three_digits(1.1), "1.1");
        assert_eq!(three_digits(14.1), "14.1");
        assert_eq!(three_digits(1.100_56), "1.1");
        assert_eq!(three_digits(0.5), "0.5");
        assert_eq!(three_digits(-0.7), "-0.7");
        assert_eq!(three_digits(-0.0), "0");
        assert_eq!(three_digits(123.4), "123");
        assert_eq!(json_string("a\"b\\c\n"), "\"a\\\"b\\\\c\\u000a\"");
    }
}
