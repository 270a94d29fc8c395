//! `rasterlab stress`: a catalogue of the cases that break the handout's
//! rasterizer (cameras inside and through walls, vertices at and behind the camera,
//! degenerate and huge triangles, extreme scales and sizes, lights on surfaces),
//! each drawn by the core with every pixel checked for NaN and infinity, compared
//! with the ray tracer where that means something, and timed.

use crate::app::figure::{Attributes, Figure, Inputs, MakeStage, WithStage};
use crate::app::progress::Progress;
use crate::app::report::INTERIOR_MARGIN;
use crate::measure::metrics::{differing_fraction, image_error, interior_mask};
use crate::measure::raytrace::{self, raytrace, Shading};
use crate::measure::timing::time_runs;
use crate::pipeline::interpolate::{Pixel, Steps};
use crate::pipeline::mesh::Vertex;
use crate::pipeline::raster::Rasterizer;
use crate::pipeline::stage::{Primitive, Surface};
use crate::pipeline::StageName;
use crate::pipeline::{Camera, Frame, Interpolation, Light, Mesh, Pipeline, Stage, Triangle};
use crate::scene::cornell_box;
use glam::Vec3;
use std::fmt::Write as _;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicU64, Ordering};

/// A stage that counts every non-finite colour its pixel shader produces.
struct Checked<S> {
    stage: S,
    non_finite: AtomicU64,
}

impl<S: Stage> Stage for Checked<S> {
    type Varying = S::Varying;
    const PRIMITIVE: Primitive = S::PRIMITIVE;
    const DEPTH_TEST: bool = S::DEPTH_TEST;

    fn vertex_shader(&self, vertex: &Vertex, surface: &Surface) -> S::Varying {
        self.stage.vertex_shader(vertex, surface)
    }

    fn pixel_shader(&self, varying: &S::Varying, surface: &Surface) -> Vec3 {
        let c = self.stage.pixel_shader(varying, surface);
        if !c.is_finite() {
            self.non_finite.fetch_add(1, Ordering::Relaxed);
        }
        c
    }
}

/// Draws a scene through the pipeline with the stage wrapped in [`Checked`]: the
/// frame, how many non-finite colours the first draw shaded plus non-finite
/// values it left in the depth buffer, and the median time in ms.
struct DrawChecked<'a> {
    scene: &'a Mesh,
    camera: &'a Camera,
    light: Light,
    runs: usize,
}

impl WithStage for DrawChecked<'_> {
    type Output = (Frame, u64, f64);
    fn with<M: MakeStage, I: Interpolation, R: Rasterizer>(self) -> (Frame, u64, f64) {
        let inputs = Inputs::lit(self.light);
        let checked = Checked {
            stage: M::make(&inputs),
            non_finite: AtomicU64::new(0),
        };
        let mut pipeline = Pipeline::<M::Varying, I, R>::new();
        let mut frame = Frame::default();
        pipeline.render(&checked, self.scene, self.camera, &mut frame);
        let depth = frame.depth.iter().filter(|z| !z.is_finite()).count() as u64;
        let bad = checked.non_finite.load(Ordering::Relaxed) + depth;
        let t = time_runs(self.runs, || {
            pipeline.render(&checked, self.scene, self.camera, &mut frame)
        });
        (frame, bad, t.median.as_secs_f64() * 1e3)
    }
}

/// What a case's error is measured against.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Check {
    /// Interior RMSE (8-bit units) against the ray-traced lit image, at most this.
    Rmse(f64),
    /// Share of interior pixels whose flat colour differs from the ray-cast one, at most this.
    Wrong(f64),
    /// Only NaN, infinity and panics are checked (no meaningful reference).
    Safety,
    /// Measured to show a limit; not held to a bound.
    Measure,
}

/// One hard case.
#[derive(Clone, Debug)]
pub struct Case {
    pub name: String,
    pub scene: Mesh,
    pub camera: Camera,
    pub light: Light,
    pub view: Figure,
    pub check: Check,
}

/// What running a case showed.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub name: String,
    pub stage: String,
    pub non_finite: u64,
    pub panicked: bool,
    /// The measured error, for cases with a reference.
    pub error: Option<f64>,
    /// Pixels the error was measured over.
    pub compared: usize,
    pub check: Check,
    pub ms: f64,
    pub pass: bool,
}

fn lab_camera(position: Vec3, yaw: f32, pitch: f32) -> Camera {
    Camera {
        position,
        yaw: yaw.to_radians(),
        pitch: pitch.to_radians(),
        ..Camera::handout(500, 500)
    }
}

/// Yaw and pitch (degrees) that look from `from` toward `to`.
fn facing(from: Vec3, to: Vec3) -> (f32, f32) {
    let d = (to - from).normalize();
    (d.x.atan2(d.z).to_degrees(), (-d.y).asin().to_degrees())
}

fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle {
    Triangle::new(
        Vec3::from(a),
        Vec3::from(b),
        Vec3::from(c),
        Vec3::new(0.75, 0.75, 0.75),
    )
}

/// The bound lit views are held to, in 8-bit units of interior RMSE. Per-pixel light
/// that is perspective-correct differs from the ray tracer only in where it samples
/// a pixel (its corner, truncated, against its centre: at most 1.5 pixels apart),
/// so in interiors the error is what the light changes over about a pixel: 0.31 on
/// the default view and at most that in the catalogue. One 8-bit step RMS is the
/// line between "sampled elsewhere" and "drawn wrong".
pub const LIT_BOUND: f64 = 1.0;

/// The named catalogue.
pub fn catalogue(quick: bool) -> Vec<Case> {
    let box_: Vec<Triangle> = cornell_box().triangles().collect();
    let light = Light::handout();
    let pixel = Figure::of(StageName::PixelLight);
    let mut cases = Vec::new();
    let mut add = |name: &str,
                   scene: &[Triangle],
                   camera: Camera,
                   light: Light,
                   view: Figure,
                   check: Check| {
        cases.push(Case {
            name: name.into(),
            scene: Mesh::from_triangles(scene),
            camera,
            light,
            view,
            check,
        });
    };
    // Camera poses inside and through the box.
    add(
        "inside, centre, looking at the back wall",
        &box_,
        lab_camera(Vec3::ZERO, 0.0, 0.0),
        light,
        pixel,
        Check::Rmse(LIT_BOUND),
    );
    // A wide lens (f = 200, 102 degrees across) so the walls around the opening show.
    let back = Camera {
        focal: 200.0,
        ..lab_camera(Vec3::new(0.0, 0.0, 0.5), 180.0, 0.0)
    };
    add(
        "inside, looking back out of the opening",
        &box_,
        back,
        light,
        pixel,
        Check::Rmse(LIT_BOUND),
    );
    for (i, corner) in [
        (-1.0, -1.0, -1.0),
        (1.0, -1.0, -1.0),
        (-1.0, 1.0, -1.0),
        (1.0, 1.0, -1.0),
        (-1.0, -1.0, 1.0),
        (1.0, -1.0, 1.0),
        (-1.0, 1.0, 1.0),
        (1.0, 1.0, 1.0),
    ]
    .into_iter()
    .enumerate()
    {
        let at = Vec3::new(corner.0, corner.1, corner.2) * 0.95;
        let (yaw, pitch) = facing(at, Vec3::ZERO);
        add(
            &format!("inside, corner {} looking at the centre", i + 1),
            &box_,
            lab_camera(at, yaw, pitch),
            light,
            pixel,
            Check::Rmse(LIT_BOUND),
        );
    }
    add(
        "half a near plane from the left wall, facing it",
        &box_,
        lab_camera(Vec3::new(-0.995, 0.0, 0.0), -90.0, 0.0),
        light,
        pixel,
        Check::Rmse(LIT_BOUND),
    );
    add(
        "standing in the left wall, looking along it",
        &box_,
        lab_camera(Vec3::new(-1.0, 0.0, 0.0), 0.0, 0.0),
        light,
        pixel,
        Check::Rmse(LIT_BOUND),
    );
    add(
        "front vertices exactly at z = 0",
        &box_,
        lab_camera(Vec3::new(0.0, 0.0, -1.0), 0.0, 0.0),
        light,
        pixel,
        Check::Rmse(LIT_BOUND),
    );
    add(
        "front vertices just behind the camera",
        &box_,
        lab_camera(Vec3::new(0.0, 0.0, -1.0 + 1e-6), 0.0, 0.0),
        light,
        pixel,
        Check::Rmse(LIT_BOUND),
    );
    let mut close = lab_camera(Vec3::new(0.0, 0.0, 1.0 - 1e-4), 0.0, 0.0);
    close.near = Some(1e-5);
    add(
        "back wall 1e-4 in front: huge triangles",
        &box_,
        close,
        light,
        pixel,
        Check::Rmse(LIT_BOUND),
    );
    let mut unclipped = lab_camera(Vec3::new(0.3, 0.2, -0.9), 40.0, 0.0);
    unclipped.near = None;
    for stage in [
        StageName::Wireframe,
        StageName::Filled,
        StageName::PixelLight,
    ] {
        add(
            "unclipped (--no-clip), corners behind the camera",
            &box_,
            unclipped,
            light,
            Figure::of(stage),
            Check::Safety,
        );
    }

    // Degenerate triangles, each on its own in front of the default camera.
    let degenerate: [(&str, Triangle); 7] = [
        (
            "zero area: a repeated vertex",
            tri([0.0, 0.0, 0.0], [0.5, 0.5, 0.0], [0.0, 0.0, 0.0]),
        ),
        (
            "zero area: three points on a line",
            tri([-0.5, 0.0, 0.0], [0.0, 0.0, 0.0], [0.5, 0.0, 0.0]),
        ),
        (
            "one point three times",
            tri([0.1, 0.1, 0.1], [0.1, 0.1, 0.1], [0.1, 0.1, 0.1]),
        ),
        (
            "one-pixel triangle",
            tri([0.0, 0.0, 0.0], [0.004, 0.0, 0.0], [0.0, 0.004, 0.0]),
        ),
        (
            "sub-pixel triangle",
            tri(
                [0.001, 0.001, 0.0],
                [0.002, 0.001, 0.0],
                [0.001, 0.002, 0.0],
            ),
        ),
        (
            "sliver 1e-6 wide, 1e4 pixels long",
            tri([-30.0, 0.0, 0.0], [30.0, 0.0, 0.0], [30.0, 1e-6, 0.0]),
        ),
        (
            "seen exactly edge-on",
            tri([-0.5, 0.0, -1.0], [0.5, 0.0, -1.0], [0.0, 0.0, 1.0]),
        ),
    ];
    for (name, t) in degenerate {
        for stage in [
            StageName::Wireframe,
            StageName::Depth,
            StageName::PixelLight,
        ] {
            add(
                name,
                &[t],
                Camera::handout(500, 500),
                light,
                Figure::of(stage),
                Check::Safety,
            );
        }
    }

    // Extreme magnitudes: the box and the camera scaled together.
    for scale in [1e-6f32, 1e6] {
        let scene: Vec<Triangle> = box_
            .iter()
            .map(|t| Triangle::new(t.v0 * scale, t.v1 * scale, t.v2 * scale, t.color))
            .collect();
        let mut camera = Camera::handout(500, 500);
        camera.position *= scale;
        camera.near = camera.near.map(|n| n * scale);
        let light = Light {
            position: light.position * scale,
            power: light.power * scale * scale, // eq. 10 falls off as 1/r²
            ..light
        };
        add(
            &format!("box and camera scaled by {scale:e}"),
            &scene,
            camera,
            light,
            pixel,
            Check::Rmse(LIT_BOUND),
        );
    }
    // Far cameras: 1/z in f32 runs out of precision; f grows so the box keeps its size.
    for distance in [3.001f32, 300.0, 3e4, 3e5, 3e6, 3e7, 3e8] {
        let mut camera = lab_camera(Vec3::new(0.0, 0.0, -distance), 0.0, 0.0);
        camera.focal = 500.0 * (distance - 1.0) / 2.001;
        add(
            &format!("camera {distance:e} away: depth precision"),
            &box_,
            camera,
            light,
            Figure::of(StageName::Depth),
            Check::Measure,
        );
    }

    // The light in awkward places.
    let at = |position: Vec3, power: f32| Light {
        position,
        power: Vec3::splat(power),
        ..light
    };
    let base = Camera::handout(500, 500);
    for (name, position, power) in [
        ("light on the left wall", Vec3::new(-1.0, 0.0, 0.0), 1.1),
        (
            "light on a vertex (back top corner)",
            Vec3::new(1.0, -1.0, 1.0),
            1.1,
        ),
        ("light behind the back wall", Vec3::new(0.0, 0.0, 1.5), 1.1),
        ("zero light power", light.position, 0.0),
        ("negative light power", light.position, -1.1),
    ] {
        add(
            name,
            &box_,
            base,
            at(position, power),
            pixel,
            Check::Rmse(LIT_BOUND),
        );
    }
    add(
        "light on a vertex, per vertex",
        &box_,
        Camera::handout(500, 500),
        at(Vec3::new(1.0, -1.0, 1.0), 1.1),
        Figure::of(StageName::VertexLight),
        Check::Safety,
    );

    // Sizes and focal lengths.
    let sized = |w: u32, h: u32, f: f32| Camera {
        focal: f,
        ..Camera::handout(w, h)
    };
    add(
        "1 x 1 pixels",
        &box_,
        sized(1, 1, 1.0),
        light,
        pixel,
        Check::Safety,
    );
    add(
        "1 x 10000 pixels",
        &box_,
        sized(1, 10000, 10000.0),
        light,
        pixel,
        Check::Safety,
    );
    add(
        "10000 x 1 pixels",
        &box_,
        sized(10000, 1, 10000.0),
        light,
        pixel,
        Check::Safety,
    );
    if !quick {
        add(
            "16000 x 16000 pixels",
            &box_,
            sized(16000, 16000, 16000.0),
            light,
            pixel,
            Check::Safety,
        );
    }
    add(
        "focal length 1e-3 (the box in one pixel)",
        &box_,
        sized(500, 500, 1e-3),
        light,
        pixel,
        Check::Safety,
    );
    add(
        "focal length 1e6 (a few millimetres of wall)",
        &box_,
        sized(500, 500, 1e6),
        light,
        pixel,
        Check::Rmse(LIT_BOUND),
    );
    cases
}

/// Runs every case of the catalogue, `runs` timed draws each, telling `progress`
/// about each as it finishes.
pub fn run_all(quick: bool, progress: &mut Progress) -> Vec<Outcome> {
    let cases = catalogue(quick);
    let runs = if quick { 1 } else { 3 };
    let mut outcomes = Vec::new();
    progress.begin(cases.len());
    for case in &cases {
        let o = run(case, runs);
        progress.step(&format!(
            "{} ({}): {}",
            o.name,
            o.stage,
            if o.pass { "ok" } else { "FAIL" }
        ));
        outcomes.push(o);
    }
    outcomes
}

/// The spans `rasterlab stress` measures drift over.
pub const DRIFT_SPANS: [usize; 7] = [1_000, 4_096, 5_000, 32_000, 100_000, 1_000_000, 10_000_000];

/// Draws a case, checks it, and compares it with the ray tracer if it has a bound.
pub fn run(case: &Case, runs: usize) -> Outcome {
    let drawn = catch_unwind(AssertUnwindSafe(|| {
        let draw = DrawChecked {
            scene: &case.scene,
            camera: &case.camera,
            light: case.light,
            runs,
        };
        case.view
            .with_stage(Attributes::of((&case.scene).into()), draw)
    }));
    let mut outcome = Outcome {
        name: case.name.clone(),
        stage: case.view.label(),
        non_finite: 0,
        panicked: drawn.is_err(),
        error: None,
        compared: 0,
        check: case.check,
        ms: 0.0,
        pass: false,
    };
    let Ok((frame, bad, ms)) = drawn else {
        return outcome;
    };
    outcome.non_finite = bad;
    outcome.ms = ms;
    let (w, h) = (case.camera.width, case.camera.height);
    let reference = |shading| {
        let options = raytrace::Options {
            shading,
            near: case.camera.near,
            ..raytrace::Options::default()
        };
        raytrace(&case.scene, &case.camera, &case.light, &options)
    };
    // Interior pixels of the reference; where the reference shows no surface at
    // all (everything clipped or out of view), every pixel, which must then be
    // black in both.
    let compare = |shading| {
        let r = reference(shading);
        let mut mask = interior_mask(&case.scene, &r.hit, w, h, INTERIOR_MARGIN);
        if r.hit.iter().all(Option::is_none) {
            mask.fill(true);
        }
        let compared = mask.iter().filter(|&&m| m).count();
        (r, mask, compared)
    };
    outcome.error = match case.check {
        Check::Rmse(_) => {
            let (r, mask, n) = compare(Shading::Lit);
            outcome.compared = n;
            Some(image_error(&frame, &r.frame, Some(&mask)).rmse)
        }
        Check::Wrong(_) | Check::Measure => {
            let (r, mask, n) = compare(Shading::Flat);
            outcome.compared = n;
            Some(differing_fraction(&frame, &r.frame, Some(&mask)))
        }
        Check::Safety => None,
    };
    let within = match (case.check, outcome.error) {
        // A comparison over no pixels would prove nothing.
        (Check::Rmse(b), Some(e)) | (Check::Wrong(b), Some(e)) => e <= b && outcome.compared > 0,
        _ => true,
    };
    outcome.pass = !outcome.panicked && bad == 0 && within;
    outcome
}

/// Drift over a long span: a line `n` pixels long that climbs `n / 3` pixels, so
/// its y step (about 1/3) is not exact in f32. Returns the largest distance of y
/// from the exact value, in pixels, for the handout's running sum and for the
/// direct form `a + (b - a) i / (n - 1)`, both in f32. ([`Steps`] itself switches
/// to the direct form past `RUNNING_SUM_LIMIT` steps.)
pub fn interpolation_drift(n: usize) -> (f64, f64) {
    let rise = (n / 3) as f32;
    let step = rise / (n - 1) as f32;
    let (mut sum, mut running, mut direct) = (0.0f32, 0.0f64, 0.0f64);
    for i in 0..n {
        let exact = rise as f64 * i as f64 / (n - 1) as f64;
        running = running.max((sum as f64 - exact).abs());
        sum += step;
        let d = rise * (i as f32 / (n - 1) as f32);
        direct = direct.max((d as f64 - exact).abs());
    }
    (running, direct)
}

/// The largest y error of [`Steps`] itself over such a span, in pixels.
pub fn steps_drift(n: usize) -> f64 {
    let rise = (n / 3) as f32;
    let at = |varying: f32| Pixel {
        x: 0,
        y: 0,
        zinv: 0.0,
        varying,
    };
    Steps::new(at(0.0), at(rise), n)
        .enumerate()
        .map(|(i, p)| (p.varying as f64 - rise as f64 * i as f64 / (n - 1) as f64).abs())
        .fold(0.0, f64::max)
}

fn check_text(c: Check) -> String {
    match c {
        Check::Rmse(b) => format!("RMSE <= {b}"),
        Check::Wrong(b) => format!("wrong <= {:.2}%", b * 100.0),
        Check::Safety => "no NaN, no panic".into(),
        Check::Measure => "measured".into(),
    }
}

/// The table `rasterlab stress` prints.
pub fn table(outcomes: &[Outcome]) -> String {
    let mut out = String::from(
        "| case | stage | NaN/inf | panic | error vs ray tracer | pixels compared | bound | ms | result |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for o in outcomes {
        let error = match (o.check, o.error) {
            (Check::Rmse(_), Some(e)) => format!("RMSE {e:.3}"),
            (Check::Wrong(_) | Check::Measure, Some(e)) => format!("{:.2}% wrong", e * 100.0),
            _ => "-".into(),
        };
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {:.2} | {} |",
            o.name,
            o.stage,
            o.non_finite,
            if o.panicked { "yes" } else { "no" },
            error,
            if o.error.is_some() {
                o.compared.to_string()
            } else {
                "-".into()
            },
            check_text(o.check),
            o.ms,
            if o.pass { "ok" } else { "FAIL" }
        );
    }
    out
}

/// The long-span part of the report.
pub fn drift_table(sizes: &[usize]) -> String {
    let mut out = String::from(
        "| steps | running sum (the handout's) | direct a + (b - a) i / (n - 1) | the core (`Steps`) |\n|---|---|---|---|\n",
    );
    for &n in sizes {
        let (r, d) = interpolation_drift(n);
        let _ = writeln!(
            out,
            "| {n} | {r:.4} px | {d:.4} px | {:.4} px |",
            steps_drift(n)
        );
    }
    out
}
