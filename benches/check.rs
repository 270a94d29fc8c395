//! `cargo bench --features bench --bench check`: the time `rasterlab check` takes per 500 x 500
//! screenshot (issue #22 asks for a full fit, light and pose, in at most 2 s on
//! one core; run it pinned: `taskset -c 0 cargo bench --features bench --bench check`). Each case
//! is a render of our own written as PNG and checked as a file, as a student's
//! would be: the handout's Figure 7; Figure 7 with --fit-light; a walked-around
//! camera (the pose fitted); a public solution's moved light with --fit-light;
//! and both moved, with --fit-light.

mod common;
#[path = "common/criterion.rs"]
mod medians;

use criterion::Criterion;
use glam::Vec3;
use rasterlab::app::check::{check_image_file, CheckOptions};
use rasterlab::app::{self as app, image_io::write_image, Settings};
use rasterlab::{cornell_box, Camera, Figure, Light, StageName};
use std::hint::black_box;

fn checks(c: &mut Criterion, ids: &mut Vec<String>) {
    let dir = std::env::temp_dir().join(format!("rasterlab-bench-check-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let walked = Camera {
        position: Vec3::new(0.2, -0.1, -4.0),
        yaw: (-6f32).to_radians(),
        ..Camera::handout(500, 500)
    };
    let moved = Light {
        position: Vec3::new(-0.6, 0.2, 0.5),
        power: Vec3::splat(5.1),
        ..Light::handout()
    };
    let handout = common::settings((500, 500));
    let fit = CheckOptions {
        fit_light: true,
        ..CheckOptions::default()
    };
    let plain = CheckOptions::default();
    let cases = [
        ("figure 7", handout, &plain),
        ("figure 7, --fit-light", handout, &fit),
        (
            "walked camera",
            Settings {
                camera: walked,
                ..handout
            },
            &plain,
        ),
        (
            "moved light, --fit-light",
            Settings {
                light: moved,
                ..handout
            },
            &fit,
        ),
        (
            "walked camera and moved light, --fit-light",
            Settings {
                camera: walked,
                light: moved,
                ..handout
            },
            &fit,
        ),
    ];
    let mut g = c.benchmark_group("check 500x500");
    medians::short(&mut g, 10);
    for (i, (name, settings, options)) in cases.into_iter().enumerate() {
        let (frame, _) = app::render(
            Figure::of(StageName::PixelLight),
            &cornell_box(),
            &settings,
            None,
        );
        let path = dir.join(format!("{i}.png"));
        write_image(&frame, &path).expect("the screenshot written");
        ids.push(format!("check 500x500/{name}"));
        g.bench_function(name, |b| {
            b.iter(|| black_box(check_image_file(&path, options).expect("checked")))
        });
    }
    g.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

fn main() {
    medians::run_and_record("check", checks);
}
