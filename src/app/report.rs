//! `rasterlab report`: every stage's error against the ray-traced reference and its
//! draw time, across image sizes and mesh densities, as a table, a CSV file and
//! an error-against-time plot.

use crate::app::figure::Figure;
use crate::app::figure::Inputs;
use crate::app::progress::Progress;
use crate::app::Settings;
use crate::extensions::depth_of_field::DepthOfField;
use crate::extensions::shadow::Shadows;
use crate::measure::heat::heat_map_picture;
use crate::measure::metrics::{
    differing_fraction, edge_pixels_within_one_pixel, image_error, interior_mask,
    points_within_one_pixel, ImageError,
};
use crate::measure::raytrace::{raytrace, Options, Shading, Traced};
use crate::measure::timing::{time_runs, Timing};
use crate::pipeline::StageName;
use crate::pipeline::{Camera, Frame, Mesh};
use crate::scene::{framed_view, subdivide, Scene};
use std::fmt::Write as _;

/// What one row measures against the reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Metric {
    /// Points and wireframe: drawn pixels within one pixel of the exact projection.
    Placement { within: usize, total: usize },
    /// Filled and depth: the fraction of pixels whose colour differs from the
    /// ray-cast nearest triangle's colour, everywhere and in interiors, and the
    /// interior RMSE against that flat image.
    Differing {
        all: f64,
        interior: f64,
        rmse_interior: f64,
    },
    /// Lit stages and the ray tracer: error against the ray-traced lit image.
    Light {
        all: ImageError,
        interior: ImageError,
    },
    /// Not measured (placement on dense meshes).
    None,
}

/// One measured configuration.
#[derive(Clone, Debug)]
pub struct Row {
    /// A stage label (`pixel-light --affine`) or `raytrace`.
    pub stage: String,
    pub size: u32,
    /// Each scene triangle split into k x k.
    pub k: u32,
    pub triangles: usize,
    pub timing: Timing,
    /// The ray tracer's median at this size on the plain box, over this median.
    pub speedup: f64,
    pub metric: Metric,
}

impl Row {
    pub fn ms(&self) -> f64 {
        self.timing.median.as_secs_f64() * 1e3
    }

    /// Interior RMSE for lit rows.
    pub fn interior_rmse(&self) -> Option<f64> {
        match self.metric {
            Metric::Light { interior, .. } => Some(interior.rmse),
            _ => None,
        }
    }
}

/// How big a report to make.
#[derive(Clone, Debug)]
pub struct Plan {
    pub sizes: Vec<u32>,
    pub ks: Vec<u32>,
    /// Size for the mesh-density sweep.
    pub k_size: u32,
    /// Timed runs after one warm-up.
    pub runs: usize,
}

impl Plan {
    pub fn full() -> Self {
        Plan {
            sizes: vec![250, 500, 1000, 2000],
            ks: vec![1, 2, 4, 8, 16],
            k_size: 500,
            runs: 5,
        }
    }

    /// Small and fast (about 2 s), yet large enough that its conclusions are the
    /// full report's: below about 250 pixels edges dominate every error.
    pub fn quick() -> Self {
        Plan {
            sizes: vec![250],
            ks: vec![1, 2],
            k_size: 250,
            runs: 2,
        }
    }
}

/// The margin, in pixels, around edges left out of interior errors: the
/// rasterizer truncates toward zero and samples pixel corners, the ray tracer
/// samples pixel centres, so near an edge they may see different surfaces.
pub const INTERIOR_MARGIN: u32 = 2;

struct Reference {
    lit: Traced,
    flat: Frame,
    mask: Vec<bool>,
    timing: Timing,
    /// Lab 2's final ray tracer, with shadow rays, and its time.
    shadowed: Frame,
    shadowed_timing: Timing,
}

/// What the report measures: the handout's figures, and vertex light corrected for
/// perspective (the other choice section 6 discusses).
pub fn measured_figures() -> Vec<Figure> {
    let mut figures = Figure::FIGURES.to_vec();
    figures.insert(
        5,
        Figure::with_interpolation(StageName::VertexLight, Some(false)),
    );
    figures
}

/// The label of the ray tracer's rows, and of its rows with shadows.
pub const RAYTRACE: &str = "raytrace";
pub const RAYTRACE_SHADOWS: &str = "raytrace --shadows";

/// The camera of a report at `size`: the view's, with f scaled with the image so
/// the view is the same at every size.
fn camera_for(size: u32, view: &Settings) -> Camera {
    Camera {
        focal: size as f32,
        width: size,
        height: size,
        ..view.camera
    }
}

/// The view a report draws `scene` in: the handout's for the box, framed otherwise
/// (the same at every size, since f grows with the image).
pub fn view_for(scene: &Scene) -> Result<Settings, String> {
    let tilted = Camera {
        pitch: scene.pitch.to_radians(),
        focal: 1.0,
        ..Camera::handout(1, 1)
    };
    let (camera, light) = framed_view(scene, &tilted)?;
    Ok(Settings {
        camera,
        light,
        ..Settings::default()
    })
}

fn reference(scene: &Mesh, size: u32, runs: usize, view: &Settings) -> Reference {
    let camera = camera_for(size, view);
    let light = view.light;
    let lit_options = Options::default();
    let mut lit = raytrace(scene, &camera, &light, &lit_options);
    let timing = time_runs(runs, || {
        lit = raytrace(scene, &camera, &light, &lit_options)
    });
    let flat_options = Options {
        shading: Shading::Flat,
        ..Options::default()
    };
    let flat = raytrace(scene, &camera, &light, &flat_options).frame;
    let mask = interior_mask(scene, &lit.hit, size, size, INTERIOR_MARGIN);
    let shadow_options = Options {
        shadows: true,
        ..Options::default()
    };
    let mut shadowed = raytrace(scene, &camera, &light, &shadow_options).frame;
    let shadowed_timing = time_runs(runs, || {
        shadowed = raytrace(scene, &camera, &light, &shadow_options).frame
    });
    Reference {
        lit,
        flat,
        mask,
        timing,
        shadowed,
        shadowed_timing,
    }
}

fn measure(
    view: Figure,
    base: &Mesh,
    scene: &Mesh,
    camera: &Camera,
    frame: &Frame,
    r: &Reference,
    k: u32,
) -> Metric {
    // Placement compares every drawn pixel with every projected edge: worth it on
    // the box, not on thousands of triangles.
    let placed = k == 1 && base.faces.len() <= 2000;
    match view.stage {
        StageName::Points if placed => {
            let (within, total) = points_within_one_pixel(base, camera, frame);
            Metric::Placement { within, total }
        }
        StageName::Wireframe if placed => {
            let (within, total) = edge_pixels_within_one_pixel(scene, camera, frame);
            Metric::Placement { within, total }
        }
        StageName::Points | StageName::Wireframe => Metric::None,
        StageName::Filled | StageName::Depth => Metric::Differing {
            all: differing_fraction(frame, &r.flat, None),
            interior: differing_fraction(frame, &r.flat, Some(&r.mask)),
            rmse_interior: image_error(frame, &r.flat, Some(&r.mask)).rmse,
        },
        StageName::VertexLight | StageName::PixelLight => Metric::Light {
            all: image_error(frame, &r.lit.frame, None),
            interior: image_error(frame, &r.lit.frame, Some(&r.mask)),
        },
    }
}

/// Measures everything in `plan`, one step of `progress` per row.
/// A scene other than the box is measured at k = 1 only: subdividing is the box's
/// way of trading triangles for accuracy.
pub fn measure_all(
    plan: &Plan,
    scene: &Scene,
    view: &Settings,
    progress: &mut Progress,
) -> Vec<Row> {
    let base = &scene.mesh;
    let inputs = Inputs::lit(view.light);
    let plan_ks: &[u32] = if scene.is_box { &plan.ks } else { &[1] };
    let mut rows = Vec::new();
    let mut sizes = plan.sizes.clone();
    if !sizes.contains(&plan.k_size) {
        sizes.push(plan.k_size);
    }
    let figures = measured_figures();
    let total = sizes.len() * (2 + figures.len()) + (plan_ks.len() - 1) * figures.len();
    progress.begin(total);
    let step = |what: &str, ms: f64, progress: &mut Progress| {
        progress.step(&format!("{what}: median {ms:.2} ms"));
    };
    for &size in &sizes {
        let r = reference(base, size, plan.runs, view);
        let rt_ms = r.timing.median.as_secs_f64() * 1e3;
        let self_error = image_error(&r.lit.frame, &r.lit.frame, None);
        rows.push(Row {
            stage: RAYTRACE.into(),
            size,
            k: 1,
            triangles: base.faces.len(),
            timing: r.timing,
            speedup: 1.0,
            metric: Metric::Light {
                all: self_error,
                interior: image_error(&r.lit.frame, &r.lit.frame, Some(&r.mask)),
            },
        });
        step(&format!("raytrace {size}x{size}"), rt_ms, progress);
        // The final ray tracer of lab 2: what shadows add, which no stage draws.
        let row = Row {
            stage: RAYTRACE_SHADOWS.into(),
            size,
            k: 1,
            triangles: base.faces.len(),
            timing: r.shadowed_timing,
            speedup: rt_ms / (r.shadowed_timing.median.as_secs_f64() * 1e3),
            metric: Metric::Light {
                all: image_error(&r.shadowed, &r.lit.frame, None),
                interior: image_error(&r.shadowed, &r.lit.frame, Some(&r.mask)),
            },
        };
        step(
            &format!("raytrace --shadows {size}x{size}"),
            row.ms(),
            progress,
        );
        rows.push(row);
        let ks: &[u32] = if size == plan.k_size { plan_ks } else { &[1] };
        for &k in ks {
            // The scene itself at k = 1: no copy of a large model.
            let split;
            let scene = if k == 1 {
                base
            } else {
                split = subdivide(base, k);
                &split
            };
            let camera = camera_for(size, view);
            for &view in &figures {
                let mut pipeline = view.pipeline_for(scene);
                let mut frame = Frame::default();
                pipeline.render(&inputs, scene, &camera, &mut frame); // warm-up
                let timing = time_runs(plan.runs, || {
                    pipeline.render(&inputs, scene, &camera, &mut frame)
                });
                let metric = measure(view, base, scene, &camera, &frame, &r, k);
                let row = Row {
                    stage: view.label(),
                    size,
                    k,
                    triangles: scene.faces.len(),
                    timing,
                    speedup: rt_ms / (timing.median.as_secs_f64() * 1e3),
                    metric,
                };
                step(
                    &format!("{} {size}x{size} k={k}", row.stage),
                    row.ms(),
                    progress,
                );
                rows.push(row);
            }
        }
    }
    rows
}

fn metric_cells(m: &Metric) -> [String; 7] {
    let f = |v: f64| format!("{v:.3}");
    let db = |v: f64| {
        if v.is_infinite() {
            "inf".to_string()
        } else {
            format!("{v:.1}")
        }
    };
    match m {
        Metric::Placement { within, total } => [
            format!("{within}/{total}"),
            String::new(),
            String::new(),
            String::new(),
            String::new(),
            String::new(),
            String::new(),
        ],
        Metric::Differing { all, interior, .. } => [
            String::new(),
            format!("{:.2}%", all * 100.0),
            format!("{:.2}%", interior * 100.0),
            String::new(),
            String::new(),
            String::new(),
            String::new(),
        ],
        Metric::Light { all, interior } => [
            String::new(),
            String::new(),
            String::new(),
            format!("{} / {} / {}", f(all.rmse), all.max, db(all.psnr)),
            f(interior.rmse),
            interior.max.to_string(),
            db(interior.psnr),
        ],
        Metric::None => Default::default(),
    }
}

/// `report.csv`: one line per row, every number unrounded.
pub fn csv(rows: &[Row]) -> String {
    let mut out = String::from(
        "stage,size,k,triangles,median_ms,min_ms,max_ms,runs,speedup_vs_raytrace,within_one_px,placed,\
         differing_all,differing_interior,rmse_all,max_all,psnr_all,rmse_interior,max_interior,psnr_interior\n",
    );
    for r in rows {
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
        let mut cells = vec![
            r.stage.clone(),
            r.size.to_string(),
            r.k.to_string(),
            r.triangles.to_string(),
            format!("{:.4}", ms(r.timing.median)),
            format!("{:.4}", ms(r.timing.min)),
            format!("{:.4}", ms(r.timing.max)),
            r.timing.runs.to_string(),
            format!("{:.2}", r.speedup),
        ];
        let blank = |n: usize| vec![String::new(); n];
        match r.metric {
            Metric::Placement { within, total } => {
                cells.extend([within.to_string(), total.to_string()]);
                cells.extend(blank(8));
            }
            Metric::Differing { all, interior, .. } => {
                cells.extend(blank(2));
                cells.extend([format!("{all:.6}"), format!("{interior:.6}")]);
                cells.extend(blank(6));
            }
            Metric::Light { all, interior } => {
                cells.extend(blank(4));
                for e in [all, interior] {
                    cells.extend([
                        format!("{:.4}", e.rmse),
                        e.max.to_string(),
                        format!("{:.2}", e.psnr),
                    ]);
                }
            }
            Metric::None => cells.extend(blank(10)),
        }
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

/// `report.md`: the table, by size then by mesh density.
pub fn markdown(rows: &[Row], plan: &Plan, machine: &str, scene: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# Error against run time\n");
    let _ = writeln!(
        out,
        "Made by `rasterlab report` on {machine}. Times are medians of {} draws after one \
         warm-up, one thread, file I/O excluded; min and max are in `report.csv`. Errors are \
         against the ray tracer (`rasterlab raytrace`, one ray through each pixel's centre, \
         same scene, camera, light and eq. 10 and 11). Interior pixels are those at least {} \
         pixels from any edge in the reference.\n",
        plan.runs, INTERIOR_MARGIN
    );
    let mut spread: Vec<f64> = rows
        .iter()
        .filter(|r| r.timing.median.as_nanos() > 0)
        .map(|r| (r.timing.max - r.timing.min).as_secs_f64() / r.timing.median.as_secs_f64())
        .collect();
    spread.sort_by(f64::total_cmp);
    if let (Some(mid), Some(worst)) = (spread.get(spread.len() / 2), spread.last()) {
        let _ = writeln!(
            out,
            "Noise: the spread of each row's draws, (max - min) / median, was {:.0}% for the \
             median row and {:.0}% at worst.\n",
            mid * 100.0,
            worst * 100.0
        );
    }
    out.push_str(&conclusions(rows, plan, scene));
    let header = TABLE_HEADER;
    let _ = writeln!(out, "## By image size (k = 1: the plain box)\n\n{header}");
    for r in rows
        .iter()
        .filter(|r| r.k == 1 && (plan.sizes.contains(&r.size)))
    {
        row_line(&mut out, r);
    }
    let _ = writeln!(
        out,
        "\n## By mesh density at {s}x{s} (every triangle split into k x k)\n\n\
         The ray tracer is timed on the plain box only, so `x faster` compares with \
         that.\n\n{header}",
        s = plan.k_size
    );
    for r in rows
        .iter()
        .filter(|r| r.size == plan.k_size && !r.stage.starts_with(RAYTRACE))
    {
        row_line(&mut out, r);
    }
    out
}

/// The size the conclusions and heat maps are given at: 500 when measured, else
/// the largest size.
pub fn conclusion_size(plan: &Plan) -> u32 {
    if plan.sizes.contains(&500) {
        500
    } else {
        plan.sizes.iter().copied().max().unwrap_or(500)
    }
}

/// Where each lit stage differs from the ray tracer, and Figure 7 from Figure 8,
/// as heat maps at the conclusion size: (file name, picture).
pub fn heat_maps(plan: &Plan, scene: &Scene, view: &Settings) -> Vec<(String, Frame)> {
    let size = conclusion_size(plan);
    let (mesh, camera, light) = (&scene.mesh, camera_for(size, view), view.light);
    let reference = raytrace(mesh, &camera, &light, &Options::default()).frame;
    let mut out = Vec::new();
    let lit = measured_figures()
        .into_iter()
        .filter(|f| f.stage.interpolates());
    for figure in lit {
        let frame = figure.render(mesh, &camera, light);
        let title = format!("{} against the ray tracer, {size}x{size}", figure.label());
        let name = format!("heat-{}", figure.default_file());
        out.extend(heat_map_picture(&frame, &reference, &title).map(|p| (name, p)));
    }
    let seven = Figure::of(StageName::PixelLight).render(mesh, &camera, light);
    let eight =
        Figure::with_interpolation(StageName::PixelLight, Some(true)).render(mesh, &camera, light);
    let title = "Figure 7 against Figure 8: what perspective correction changes";
    out.extend(
        heat_map_picture(&seven, &eight, title).map(|p| ("heat-fig7-vs-fig8.png".into(), p)),
    );
    out
}

/// The handout's questions answered from this run's own numbers, at 500 x 500 when
/// measured (else the largest size), on the plain box.
pub fn conclusions(rows: &[Row], plan: &Plan, scene: &str) -> String {
    let size = conclusion_size(plan);
    let find = |stage: &str| {
        rows.iter()
            .find(|r| r.stage == stage && r.size == size && r.k == 1)
    };
    let (Some(rt), Some(shadows), Some(filled), Some(depth)) = (
        find(RAYTRACE),
        find(RAYTRACE_SHADOWS),
        find("filled"),
        find("depth"),
    ) else {
        return String::new();
    };
    let (Some(vertex), Some(vertex_p), Some(pixel), Some(pixel_a)) = (
        find("vertex-light"),
        find("vertex-light --interpolation perspective"),
        find("pixel-light"),
        find("pixel-light --affine"),
    ) else {
        return String::new();
    };
    let rmse = |r: &Row| r.interior_rmse().unwrap_or(f64::NAN);
    let wrong = |r: &Row| match r.metric {
        Metric::Differing { interior, .. } => interior * 100.0,
        _ => f64::NAN,
    };
    // An error printed as 0.00 (a scene without light, say) has no ratio to
    // another: the sentences say so in words.
    let shown_zero = |e: f64| e < 0.005;
    let ratio = |a: f64, b: f64| if b > 0.0 { a / b } else { f64::INFINITY };
    let mut out = String::new();
    let _ = writeln!(
        out,
        "## What this run answers ({size} x {size}, {})\n",
        if scene == "cornell" {
            "the plain box".to_string()
        } else {
            format!("scene {scene}")
        }
    );
    if size < 250 {
        let _ = writeln!(
            out,
            "These images are smaller than 250 pixels, where edges dominate every error: \
             the comparisons below may not hold at the handout's size.\n"
        );
    }
    let _ = writeln!(
        out,
        "- **How much faster than ray tracing?** Filled triangles take {:.2} ms against the \
         ray tracer's {:.1} ms: {:.0} times faster. Per-pixel light ({:.2} ms) is {:.0} times \
         faster than the ray tracer and {:.0} times faster than lab 2's final one with \
         shadows ({:.1} ms), which also shows what no stage draws: shadows change the \
         interior by RMSE {:.2}.",
        filled.ms(),
        rt.ms(),
        ratio(rt.ms(), filled.ms()),
        pixel.ms(),
        ratio(rt.ms(), pixel.ms()),
        ratio(shadows.ms(), pixel.ms()),
        shadows.ms(),
        rmse(shadows),
    );
    let _ = writeln!(
        out,
        "- **What the depth buffer buys.** Without it {:.2}% of the interior shows the wrong \
         surface; with it {:.2}%, for {:.0}% more time.",
        wrong(filled),
        wrong(depth),
        (ratio(depth.ms(), filled.ms()) - 1.0) * 100.0,
    );
    let _ = writeln!(
        out,
        "- **Light per vertex or per pixel?** Per vertex (Figure 6) takes {:.0}% of the time \
         of per pixel and its interior error is {} (RMSE {:.2} against \
         {:.2}){}",
        ratio(vertex.ms(), pixel.ms()) * 100.0,
        match (shown_zero(rmse(vertex)), shown_zero(rmse(pixel))) {
            (true, true) => "the same".to_string(),
            (false, true) => "larger, where per pixel has none".to_string(),
            _ => format!("{:.1} times as large", rmse(vertex) / rmse(pixel)),
        },
        rmse(vertex),
        rmse(pixel),
        if !shown_zero(rmse(vertex)) && rmse(vertex) > 2.0 * rmse(pixel) {
            ": large triangles cannot follow the light's falloff."
        } else {
            ": the triangles are small enough for the light at their corners to do."
        },
    );
    let _ = writeln!(
        out,
        "- **What perspective correction buys.** For per-pixel light, interpolating the \
         position affinely (Figure 8) {} (RMSE {:.2} \
         against {:.2}) and changes the time by {:+.0}%. For per-vertex light the \
         correction moves the error from {:.2} to {:.2}: there the light, not the \
         interpolation, is the larger mistake.",
        match (shown_zero(rmse(pixel_a)), shown_zero(rmse(pixel))) {
            (true, true) => "leaves the interior error as it is".to_string(),
            (false, true) => "makes an interior error where there was none".to_string(),
            _ => format!(
                "multiplies the interior error by {:.1}",
                rmse(pixel_a) / rmse(pixel)
            ),
        },
        rmse(pixel_a),
        rmse(pixel),
        (ratio(pixel_a.ms(), pixel.ms()) - 1.0) * 100.0,
        rmse(vertex),
        rmse(vertex_p),
    );
    out.push('\n');
    out
}

fn row_line(out: &mut String, r: &Row) {
    let c = metric_cells(&r.metric);
    let _ = writeln!(
        out,
        "| {} | {} | {} | {} | {:.2} | {:.0} | {} |",
        r.stage,
        r.size,
        r.k,
        r.triangles,
        r.ms(),
        r.speedup,
        c.join(" | ")
    );
}

/// Each series of the plot: its label and colour.
const SERIES: [(&str, u32); 10] = [
    ("points", 0x0099_9999),
    ("wireframe", 0x0044_4444),
    ("filled", 0x00e7_298a),
    ("depth", 0x0066_a61e),
    ("vertex-light", 0x00d9_5f02),
    ("vertex-light --interpolation perspective", 0x00e6_ab02),
    ("pixel-light", 0x001b_9e77),
    ("pixel-light --affine", 0x0075_70b3),
    (RAYTRACE, 0x0000_0000),
    (RAYTRACE_SHADOWS, 0x00a6_761d),
];

/// The error a row is plotted at: interior RMSE against the matching ray-traced
/// image (lit, or flat for filled and depth) in 8-bit units, or for points and
/// wireframe the share of placements more than a pixel off, in percent.
fn plot_error(r: &Row) -> Option<f64> {
    match r.metric {
        Metric::Light { interior, .. } => Some(interior.rmse),
        Metric::Differing { rmse_interior, .. } => Some(rmse_interior),
        Metric::Placement { within, total } if total > 0 => {
            Some(100.0 * (total - within) as f64 / total as f64)
        }
        _ => None,
    }
}

/// A rectangle in pixels: left, top, right, bottom.
type Box2 = (i32, i32, i32, i32);

fn overlaps(a: Box2, b: Box2) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}

/// The font every plot's words are drawn in: DejaVu Sans, bundled, so that the
/// picture is the same on every machine.
fn plot_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let bytes: &'static [u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
        // A bundled, known font: registering it cannot fail but by a broken build.
        let _ =
            plotters::style::register_font("sans-serif", plotters::style::FontStyle::Normal, bytes);
    });
}

/// A colour of [`SERIES`] for plotters.
fn rgb(c: u32) -> plotters::style::RGBColor {
    plotters::style::RGBColor((c >> 16) as u8, (c >> 8) as u8, c as u8)
}

/// `error-vs-time.png`: every measured stage and the ray tracer as a point at its
/// median time and its error (log scales, by plotters); an error of exactly 0
/// sits on a dashed line below the error axis's smallest value. Lines join each
/// lit stage's points as the mesh gets denser. Labels (the image size) go inside
/// the plotting area where they overlap no other label, marker or line, or are
/// left out, so they never reach the axes' words.
pub fn plot(rows: &[Row], plan: &Plan) -> Frame {
    use plotters::prelude::*;
    plot_font();
    let points: Vec<(&Row, f64)> = rows
        .iter()
        .filter_map(|r| plot_error(r).map(|e| (r, e)))
        .collect();
    let xs: Vec<f64> = points.iter().map(|(r, _)| r.ms().max(1e-3)).collect();
    let positive: Vec<f64> = points.iter().map(|p| p.1).filter(|&e| e > 0.0).collect();
    let range = |v: &[f64], pad: f64| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        match lo.is_finite() && hi.is_finite() {
            true => (lo / pad, hi * pad),
            false => (0.1, 10.0),
        }
    };
    let (x_lo, x_hi) = range(&xs, 1.6);
    let (e_lo, e_hi) = range(&positive, 1.6);
    // The zero line, a decade below the smallest error, and a break above it.
    let zero = e_lo / 10.0;
    let (w, h) = (1700u32, 1000u32);
    let mut pixels = vec![0u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (w, h)).into_drawing_area();
        let _ = root.fill(&WHITE);
        let (left, legend) = root.split_horizontally(w - 470);
        let built = ChartBuilder::on(&left)
            .caption(
                "Error against draw time: each shortcut's price",
                ("sans-serif", 34),
            )
            .margin(24)
            .x_label_area_size(70)
            .y_label_area_size(110)
            .build_cartesian_2d((x_lo..x_hi).log_scale(), (zero / 2.0..e_hi).log_scale());
        let Ok(mut chart) = built else {
            return Frame::new(w, h);
        };
        let _ = chart
            .configure_mesh()
            .x_desc("median draw time, ms (log)")
            .y_desc(
                "error (log): 8-bit RMSE against the ray tracer; points, wireframe: % placed > 1 px off",
            )
            .axis_desc_style(("sans-serif", 20))
            .label_style(("sans-serif", 18))
            .y_label_formatter(&|v| match (*v >= e_lo / 1.01, *v >= 1.0) {
                (false, _) => String::new(),
                (true, true) => format!("{v:.0}"),
                (true, false) => format!("{v:.2}"),
            })
            .x_label_formatter(&|v| format!("{v}"))
            .draw();
        let at = |r: &Row, e: f64| (r.ms().max(1e-3), if e > 0.0 { e } else { zero });
        let dashed =
            DashedLineSeries::new([(x_lo, zero), (x_hi, zero)], 8, 6, BLACK.mix(0.6).into());
        let _ = chart.draw_series(dashed);
        let _ = chart.draw_series(std::iter::once(Text::new(
            "0 (exact)",
            (x_lo * 1.05, zero * 1.25),
            ("sans-serif", 18).into_font(),
        )));
        let (px, py) = chart.plotting_area().get_pixel_range();
        let inside: Box2 = (px.start, py.start, px.end, py.end);
        let mut obstacles: Vec<Box2> = Vec::new();
        // Mesh-density curves first, so the points sit on top.
        for (stage, col) in SERIES {
            let curve: Vec<(f64, f64)> = points
                .iter()
                .filter(|(r, _)| r.stage == stage && r.size == plan.k_size)
                .map(|&(r, e)| at(r, e))
                .collect();
            for pair in curve.windows(2) {
                let (a, b) = (chart.backend_coord(&pair[0]), chart.backend_coord(&pair[1]));
                for t in 0..=10 {
                    let p = (a.0 + (b.0 - a.0) * t / 10, a.1 + (b.1 - a.1) * t / 10);
                    obstacles.push((p.0 - 3, p.1 - 3, p.0 + 3, p.1 + 3));
                }
            }
            let _ = chart.draw_series(LineSeries::new(curve, rgb(col).stroke_width(3)));
        }
        let mut marks = Vec::new();
        for &(row, e) in &points {
            let Some(&(_, col)) = SERIES.iter().find(|(s, _)| *s == row.stage) else {
                continue;
            };
            let r = if row.k == 1 { 6 } else { 3 };
            let square = EmptyElement::at(at(row, e))
                + Rectangle::new([(-r, -r), (r, r)], rgb(col).filled());
            let _ = chart.draw_series(std::iter::once(square));
            let p = chart.backend_coord(&at(row, e));
            obstacles.push((p.0 - r - 1, p.1 - r - 1, p.0 + r + 2, p.1 + r + 2));
            let label = match row.k {
                1 => row.size.to_string(),
                k => format!("k={k}"),
            };
            marks.push((p, label, col));
        }
        let label_font = ("sans-serif", 16).into_font();
        let mut placed: Vec<Box2> = Vec::new();
        for (p, label, col) in marks {
            let (tw, th) = root
                .estimate_text_size(&label, &label_font.clone().into())
                .map_or((40, 16), |(a, b)| (a as i32, b as i32));
            let candidates = [
                (10, -th / 2),
                (-tw - 10, -th / 2),
                (-tw / 2, -th - 10),
                (-tw / 2, 10),
                (10, -th - 8),
                (10, 8),
                (-tw - 10, -th - 8),
                (-tw - 10, 8),
            ];
            let free = candidates
                .iter()
                .map(|&(dx, dy)| (p.0 + dx, p.1 + dy))
                .find(|&(x, y)| {
                    let bx = (x - 2, y - 2, x + tw + 2, y + th + 2);
                    bx.0 >= inside.0
                        && bx.2 <= inside.2
                        && bx.1 >= inside.1
                        && bx.3 <= inside.3
                        && !placed.iter().chain(&obstacles).any(|&o| overlaps(o, bx))
                });
            if let Some((x, y)) = free {
                placed.push((x - 2, y - 2, x + tw + 2, y + th + 2));
                let style = label_font.clone().color(&rgb(col));
                let _ = root.draw(&Text::new(label, (x, y), style));
            }
        }
        // Legend.
        let mut ly = 130;
        for (stage, col) in SERIES {
            let _ = legend.draw(&Rectangle::new(
                [(8, ly + 2), (20, ly + 14)],
                rgb(col).filled(),
            ));
            let name = stage.replace(" --interpolation ", ", ");
            let _ = legend.draw(&Text::new(name, (30, ly), ("sans-serif", 18).into_font()));
            ly += 30;
        }
        ly += 12;
        let note = format!("{s}x{s}, every triangle", s = plan.k_size);
        for line in [
            "big squares: the plain box,",
            "labelled by image size",
            "lines, small squares:",
            &note,
            "split k x k",
            "",
            "filled, depth: RMSE against",
            "the ray-cast flat colours",
            "raytrace --shadows: what",
            "shadows change (no stage",
            "draws them)",
        ] {
            let style = ("sans-serif", 17).into_font().color(&RGBColor(80, 80, 80));
            let _ = legend.draw(&Text::new(line, (0, ly), style));
            ly += 24;
        }
        let _ = root.present();
    }
    let mut frame = Frame::new(w, h);
    for (c, p) in frame.color.iter_mut().zip(pixels.chunks_exact(3)) {
        *c = (p[0] as u32) << 16 | (p[1] as u32) << 8 | p[2] as u32;
    }
    frame
}

/// One option beyond the handout, as the report measures it.
struct OptionCase {
    label: &'static str,
    scene: Scene,
    figure: Figure,
    dof: Option<DepthOfField>,
    /// The ray tracer's counterpart: the same mesh with shadow rays or not;
    /// `None` where it has none (depth of field, parallax).
    reference: Option<bool>,
}

/// Each option beyond the handout on pixel-light at `size` (`steps/9-textures.md`
/// to `12-normal-maps.md`): its draw time, shadow map and post-process included,
/// and its error against the ray tracer given the same option where it has one.
pub fn measure_options(
    scene: &Scene,
    view: &Settings,
    size: u32,
    runs: usize,
    progress: &mut Progress,
) -> Vec<Row> {
    use crate::scene::texture::{apply_normal_map, apply_parallax, apply_texture, bumps};
    let (camera, light) = (camera_for(size, view), view.light);
    let pixel_light = Figure::of(StageName::PixelLight);
    let with = |f: &dyn Fn(&mut Scene)| {
        let mut s = scene.clone();
        f(&mut s);
        s
    };
    let textured = with(&|s| {
        let _ = apply_texture(s, &crate::scene::texture::TextureSpec::Checker);
    });
    let bumped = with(&|s| apply_normal_map(s, bumps()));
    let parallax = with(&|s| {
        let _ = apply_texture(s, &crate::scene::texture::TextureSpec::Checker);
        apply_normal_map(s, bumps());
        apply_parallax(s);
    });
    // In focus at the middle of the scene's bounding sphere, a lens a fiftieth
    // of that depth wide.
    let focus = (crate::scene::bounding_sphere(&scene.mesh).0 - camera.position).length();
    let cases = [
        OptionCase {
            label: "pixel-light --texture checker",
            scene: textured,
            figure: pixel_light,
            dof: None,
            reference: Some(false),
        },
        OptionCase {
            label: "pixel-light --normal-map bumps",
            scene: bumped,
            figure: pixel_light,
            dof: None,
            reference: Some(false),
        },
        OptionCase {
            label: "pixel-light --texture checker --normal-map bumps --parallax",
            scene: parallax,
            figure: pixel_light,
            dof: None,
            reference: None,
        },
        OptionCase {
            label: "pixel-light --shadows",
            scene: scene.clone(),
            figure: pixel_light.with_shadows(Shadows::Hard),
            dof: None,
            reference: Some(true),
        },
        OptionCase {
            label: "pixel-light --shadows --pcf",
            scene: scene.clone(),
            figure: pixel_light.with_shadows(Shadows::Pcf),
            dof: None,
            reference: Some(true),
        },
        OptionCase {
            label: "pixel-light --dof (focus on the scene's centre)",
            scene: scene.clone(),
            figure: pixel_light,
            dof: Some(DepthOfField {
                focus,
                aperture: focus / 50.0,
            }),
            reference: None,
        },
    ];
    let plain = raytrace(&scene.mesh, &camera, &light, &Options::default());
    let mask = interior_mask(&scene.mesh, &plain.hit, size, size, INTERIOR_MARGIN);
    let rt_timing = time_runs(runs, || {
        raytrace(&scene.mesh, &camera, &light, &Options::default());
    });
    let rt_ms = rt_timing.median.as_secs_f64() * 1e3;
    let near = camera.near.unwrap_or(crate::pipeline::camera::DEFAULT_NEAR);
    let mut rows = Vec::new();
    progress.begin(cases.len());
    for case in cases {
        let mesh = &case.scene.mesh;
        let mut pipeline = case.figure.pipeline_for(&case.scene);
        let mut frame = Frame::default();
        let frames = case.figure.tangent_frames(&case.scene);
        let mut draw = |frame: &mut Frame| {
            let shadow = case.figure.shadow_map(mesh, &light, near);
            let inputs = Inputs {
                maps: &case.scene.maps,
                eye: camera.position,
                shadow: shadow.as_ref(),
                frames: &frames,
                ..Inputs::lit(light)
            };
            pipeline.render(&inputs, mesh, &camera, frame);
            if let Some(dof) = case.dof {
                dof.apply(frame, camera.focal);
            }
        };
        draw(&mut frame); // warm-up
        let timing = time_runs(runs, || draw(&mut frame));
        let metric = match case.reference {
            Some(shadows) => {
                let options = Options {
                    shadows,
                    ..Options::default()
                };
                let reference = raytrace(&case.scene, &camera, &light, &options).frame;
                Metric::Light {
                    all: image_error(&frame, &reference, None),
                    interior: image_error(&frame, &reference, Some(&mask)),
                }
            }
            None => Metric::None,
        };
        let row = Row {
            stage: case.label.to_string(),
            size,
            k: 1,
            triangles: mesh.faces.len(),
            timing,
            speedup: rt_ms / (timing.median.as_secs_f64() * 1e3),
            metric,
        };
        progress.step(&format!(
            "{} {size}x{size}: median {:.2} ms",
            row.stage,
            row.ms()
        ));
        rows.push(row);
    }
    rows
}

/// The options' rows as a section of report.md.
pub fn options_markdown(rows: &[Row]) -> String {
    let Some(size) = rows.first().map(|r| r.size) else {
        return String::new();
    };
    let mut out = format!(
        "\n## Options beyond the handout ({size}x{size}, pixel-light)\n\n\
         Each against the ray tracer given the same texture, normal map or shadow \
         rays (the shadow map's error is against shadow rays); parallax and depth of \
         field have no ray-traced counterpart here, so only their time is given. \
         Times include the shadow map and the post-process.\n\n{TABLE_HEADER}\n"
    );
    for r in rows {
        row_line(&mut out, r);
    }
    out
}

/// The header of every table of rows.
const TABLE_HEADER: &str = "| stage | size | k | triangles | median ms | x faster than ray tracer | within 1 px | pixels differing (all) | (interior) | RMSE / max / PSNR dB (all) | RMSE (interior) | max (interior) | PSNR dB (interior) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|";
