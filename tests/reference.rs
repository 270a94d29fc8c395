//! The ray-traced reference and the report built on it.

use crate::common;
use common::temp_dir;
use rasterlab::app::report::INTERIOR_MARGIN;
use rasterlab::app::Settings;
use rasterlab::measure::metrics::{image_error, interior_mask};
use rasterlab::measure::raytrace::{raytrace, Options};
use rasterlab::{cornell_box, Figure, StageName};
use std::process::Command;

#[test]
fn pixel_light_is_the_closest_lit_stage_to_the_ray_tracer() {
    let s = Settings::default();
    let scene = cornell_box();
    let reference = raytrace(&scene, &s.camera, &s.light, &Options::default());
    let mask = interior_mask(&scene, &reference.hit, 500, 500, INTERIOR_MARGIN);
    let error = |stage, affine| {
        let frame =
            Figure::with_interpolation(stage, Some(affine)).render(&scene, &s.camera, s.light);
        image_error(&frame, &reference.frame, Some(&mask)).rmse
    };
    let correct = error(StageName::PixelLight, false);
    let affine = error(StageName::PixelLight, true);
    let vertex = error(StageName::VertexLight, false);
    let numbers = format!(
        "interior RMSE against the ray tracer: pixel-light {correct:.3}, pixel-light --affine {affine:.3}, vertex-light {vertex:.3}"
    );
    assert!(correct < affine && correct < vertex, "{numbers}");
    // Perspective-correct per-pixel light differs from the ray tracer only by where
    // each samples a pixel (corner and truncation against centre): well under one
    // 8-bit step on average in interiors.
    assert!(correct < 1.0, "{numbers}");
}

#[test]
fn report_refuses_an_unwritable_folder_before_measuring() {
    let dir = temp_dir("report-unwritable");
    let file = dir.join("a-file");
    std::fs::write(&file, b"").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args(["report", "--out", file.join("sub").to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "nothing measured first: {err}");
    assert!(err.starts_with("error: cannot write "), "{err}");
}

#[test]
fn quick_report_writes_its_three_files() {
    let dir = temp_dir("report");
    let out = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args(["report", "--quick", "--out", dir.to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    // Progress is for a terminal: piped, standard error holds only what was written.
    assert!(
        err.lines().all(|l| l.starts_with("wrote ")),
        "no progress when piped: {err}"
    );
    assert_eq!(err.lines().count(), 8, "{err}");
    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(md.starts_with("# Error against run time"), "{md}");
    assert!(
        md.contains("| pixel-light --affine | 250 | 2 | 120 |"),
        "{md}"
    );
    // The answers come from the run's own numbers, and keep the full report's
    // conclusions at this size.
    assert!(md.contains("## What this run answers (250 x 250"), "{md}");
    assert!(!md.contains("smaller than 250 pixels"), "{md}");
    let rmse = |stage: &str| -> f64 {
        let line = md
            .lines()
            .find(|l| l.starts_with(&format!("| {stage} | 250 | 1 |")))
            .unwrap_or_else(|| panic!("no row for {stage}: {md}"));
        line.split('|').nth(11).unwrap().trim().parse().unwrap()
    };
    let (pixel, affine, vertex) = (
        rmse("pixel-light"),
        rmse("pixel-light --affine"),
        rmse("vertex-light"),
    );
    assert!(
        pixel < affine && affine < vertex,
        "{pixel} {affine} {vertex}"
    );
    let csv = std::fs::read_to_string(dir.join("report.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    // One size x (ray tracer, with shadows, 8 figures) + k = 2 x 8 figures, and
    // the six options beyond the handout.
    assert_eq!(lines.len(), 1 + 10 + 8 + 6, "{csv}");
    assert!(md.contains("## Options beyond the handout (250x250, pixel-light)"));
    // The shadow map's row is measured against shadow rays: an interior RMSE
    // under 2 levels (0.51 measured at 250x250).
    let shadows = md
        .lines()
        .find(|l| l.starts_with("| pixel-light --shadows | 250 | 1 |"))
        .unwrap_or_else(|| panic!("no shadow row: {md}"));
    let rmse: f64 = shadows.split('|').nth(11).unwrap().trim().parse().unwrap();
    assert!(rmse < 2.0, "{shadows}");
    let columns = lines[0].split(',').count();
    assert!(
        lines.iter().all(|l| l.split(',').count() == columns),
        "{csv}"
    );
    let (w, h, _) = rasterlab::app::image_io::read_rgb(&dir.join("error-vs-time.png")).unwrap();
    assert_eq!((w, h), (1700, 1000));
}

#[test]
fn raytrace_subcommand() {
    let dir = temp_dir("raytrace");
    let out = dir.join("rt.png");
    let o = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args([
            "raytrace",
            "--shadows",
            "--samples",
            "2",
            "--size",
            "40x30",
            "-o",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (w, h, _) = rasterlab::app::image_io::read_rgb(&out).unwrap();
    assert_eq!((w, h), (40, 30));
    let o = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args(["raytrace", "--samples", "0"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
}
