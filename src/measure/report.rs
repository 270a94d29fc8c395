//! `rasterlab report`: every stage's error against the ray-traced reference and its
//! draw time, across image sizes and mesh densities, as a table, a CSV file and
//! an error-against-time plot.

use crate::measure::figure::{Figure, StageName};
use crate::measure::metrics::{
    differing_fraction, edge_pixels_within_one_pixel, image_error, interior_mask,
    points_within_one_pixel, ImageError,
};
use crate::measure::plot::{Canvas, LogLog, BLACK, DARK};
use crate::measure::raytrace::{raytrace, Options, Shading, Traced};
use crate::measure::timing::{time_runs, Timing};
use crate::pipeline::{Camera, Frame, Light, Mesh, Uniforms};
use crate::scene::{cornell_box, subdivide};
use std::fmt::Write as _;

/// What one row measures against the reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Metric {
    /// Points and wireframe: drawn pixels within one pixel of the exact projection.
    Placement { within: usize, total: usize },
    /// Filled and depth: the fraction of pixels whose colour differs from the
    /// ray-cast nearest triangle's colour, everywhere and in interiors.
    Differing { all: f64, interior: f64 },
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

    /// Small and fast, for tests.
    pub fn quick() -> Self {
        Plan {
            sizes: vec![48, 96],
            ks: vec![1, 2],
            k_size: 96,
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
}

fn camera_for(size: u32) -> Camera {
    // The same view at every size: f scales with the image.
    Camera {
        focal: size as f32,
        ..Camera::handout(size, size)
    }
}

fn reference(scene: &Mesh, size: u32, runs: usize) -> Reference {
    let camera = camera_for(size);
    let light = Light::handout();
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
    Reference {
        lit,
        flat,
        mask,
        timing,
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
    match view.stage {
        StageName::Points if k == 1 => {
            let (within, total) = points_within_one_pixel(base, camera, frame);
            Metric::Placement { within, total }
        }
        StageName::Wireframe if k == 1 => {
            let (within, total) = edge_pixels_within_one_pixel(scene, camera, frame);
            Metric::Placement { within, total }
        }
        StageName::Points | StageName::Wireframe => Metric::None,
        StageName::Filled | StageName::Depth => Metric::Differing {
            all: differing_fraction(frame, &r.flat, None),
            interior: differing_fraction(frame, &r.flat, Some(&r.mask)),
        },
        StageName::VertexLight | StageName::PixelLight => Metric::Light {
            all: image_error(frame, &r.lit.frame, None),
            interior: image_error(frame, &r.lit.frame, Some(&r.mask)),
        },
    }
}

/// Measures everything in `plan`, printing progress to `progress`.
pub fn measure_all(plan: &Plan, mut progress: impl FnMut(&str)) -> Vec<Row> {
    let base = cornell_box();
    let uniforms = Uniforms {
        light: Light::handout(),
    };
    let mut rows = Vec::new();
    let mut sizes = plan.sizes.clone();
    if !sizes.contains(&plan.k_size) {
        sizes.push(plan.k_size);
    }
    let total =
        sizes.len() * (1 + Figure::FIGURES.len()) + (plan.ks.len() - 1) * Figure::FIGURES.len();
    let mut done = 0;
    let mut step = |what: &str, ms: f64, progress: &mut dyn FnMut(&str)| {
        done += 1;
        progress(&format!("[{done:>3}/{total}] {what}: median {ms:.2} ms"));
    };
    for &size in &sizes {
        let r = reference(&base, size, plan.runs);
        let rt_ms = r.timing.median.as_secs_f64() * 1e3;
        let self_error = image_error(&r.lit.frame, &r.lit.frame, None);
        rows.push(Row {
            stage: "raytrace".into(),
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
        step(&format!("raytrace {size}x{size}"), rt_ms, &mut progress);
        let ks: &[u32] = if size == plan.k_size { &plan.ks } else { &[1] };
        for &k in ks {
            let scene = subdivide(&base, k);
            let camera = camera_for(size);
            for view in Figure::FIGURES {
                let mut pipeline = view.pipeline();
                let mut frame = Frame::default();
                pipeline.render(&scene, &camera, &uniforms, &mut frame); // warm-up
                let timing = time_runs(plan.runs, || {
                    pipeline.render(&scene, &camera, &uniforms, &mut frame)
                });
                let metric = measure(view, &base, &scene, &camera, &frame, &r, k);
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
                    &mut progress,
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
        Metric::Differing { all, interior } => [
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
            Metric::Differing { all, interior } => {
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
pub fn markdown(rows: &[Row], plan: &Plan, machine: &str) -> String {
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
    let header = "| stage | size | k | triangles | median ms | x faster than ray tracer | within 1 px | pixels differing (all) | (interior) | RMSE / max / PSNR dB (all) | RMSE (interior) | max (interior) | PSNR dB (interior) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|";
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
         The ray tracer is timed on the plain box only; its cost grows with the triangle \
         count (no acceleration structure), so `x faster` compares with that.\n\n{header}",
        s = plan.k_size
    );
    for r in rows
        .iter()
        .filter(|r| r.size == plan.k_size && r.stage != "raytrace")
    {
        row_line(&mut out, r);
    }
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

const STAGE_COLORS: [(&str, u32); 4] = [
    ("vertex-light", 0x00d9_5f02),
    ("pixel-light", 0x001b_9e77),
    ("pixel-light --affine", 0x0075_70b3),
    ("raytrace", 0x0000_0000),
];

/// `error-vs-time.png`: interior RMSE (log) against median time (log). Points for
/// each lit stage and size; lines for vertex-light and affine pixel-light as the
/// mesh gets denser; an error of zero is drawn on a labelled floor.
pub fn plot(rows: &[Row], plan: &Plan) -> Frame {
    let lit: Vec<&Row> = rows
        .iter()
        .filter(|r| r.interior_rmse().is_some())
        .collect();
    let positive: Vec<f64> = lit
        .iter()
        .filter_map(|r| r.interior_rmse())
        .filter(|&e| e > 0.0)
        .collect();
    let floor = positive
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min)
        .min(1.0)
        / 10.0;
    let floor = 10f64.powf(floor.log10().floor());
    let error = |r: &Row| {
        r.interior_rmse()
            .map(|e| if e > 0.0 { e } else { floor })
            .unwrap_or(floor)
    };
    let xs: Vec<f64> = lit.iter().map(|r| r.ms().max(1e-3)).collect();
    let mut ys: Vec<f64> = lit.iter().map(|r| error(r)).collect();
    ys.push(floor / 3.0); // room under the floor line for its labels

    let (w, h) = (1600, 940);
    let mut c = Canvas::new(w, h, 0x00ff_ffff);
    let axes = LogLog::covering(&xs, &ys, (140, 120, w as i32 - 440, h as i32 - 90));
    c.text(
        (140, 20),
        "Error against draw time: each shortcut's price",
        3,
        BLACK,
    );
    axes.draw_axes(
        &mut c,
        "median draw time, ms (log)",
        "interior RMSE vs ray tracer, 8-bit units (log)",
    );
    let (l, _, r, _) = axes.area;
    let (_, fy) = axes.map(1.0, floor);
    c.dashed((l, fy), (r, fy), DARK);
    c.text((l + 8, fy - 20), "error 0 (the reference itself)", 2, DARK);

    let color = |stage: &str| {
        STAGE_COLORS
            .iter()
            .find(|(s, _)| *s == stage)
            .map(|(_, c)| *c)
    };
    // Mesh-density curves, drawn first so the points sit on top.
    for stage in ["vertex-light", "pixel-light --affine", "pixel-light"] {
        let curve: Vec<&&Row> = lit
            .iter()
            .filter(|r| r.stage == stage && r.size == plan.k_size)
            .collect();
        let Some(col) = color(stage) else { continue };
        for pair in curve.windows(2) {
            let (a, b) = (
                axes.map(pair[0].ms(), error(pair[0])),
                axes.map(pair[1].ms(), error(pair[1])),
            );
            c.line(a, b, col, 3);
        }
        // Label the vertex-light curve, and affine's first step; the rest crowd
        // into the perspective-correct cluster.
        let labelled = |r: &Row| match stage {
            "vertex-light" => true,
            "pixel-light --affine" => r.k == 2,
            _ => false,
        };
        for r in &curve {
            if r.k > 1 && labelled(r) {
                let p = axes.map(r.ms(), error(r));
                c.text((p.0 + 8, p.1 + 6), &format!("k={}", r.k), 2, col);
            }
            if r.k > 1 {
                c.marker(axes.map(r.ms(), error(r)), 3, col);
            }
        }
    }
    for r in lit.iter().filter(|r| r.k == 1) {
        let Some(col) = color(&r.stage) else { continue };
        let p = axes.map(r.ms(), error(r));
        c.marker(p, 6, col);
        c.text((p.0 + 10, p.1 - 18), &r.size.to_string(), 2, col);
    }
    // Legend.
    let (lx, mut ly) = (w as i32 - 410, 130);
    for (stage, col) in STAGE_COLORS {
        c.marker((lx + 8, ly + 8), 6, col);
        c.text((lx + 24, ly), stage, 2, BLACK);
        ly += 32;
    }
    ly += 10;
    for line in [
        "big squares: the plain",
        "box at each image size",
        "(number = pixels square)",
        "",
        "lines, small squares:",
        &format!("{s}x{s}, each triangle", s = plan.k_size),
        "split k x k",
    ] {
        c.text((lx, ly), line, 2, DARK);
        ly += 22;
    }
    c.frame
}
