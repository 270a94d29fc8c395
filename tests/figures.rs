//! The figures committed in steps/ must be what the code draws now. After a
//! change that alters a figure on purpose, regenerate them with
//! `cargo run --release -- all --out steps` and commit the new PNGs.

mod common;
use rasterlab::app::image_io::read_rgb_png;
use rasterlab::app::overview::figure_one;
use rasterlab::app::{self, Settings, OVERVIEW_FILE};
use rasterlab::{cornell_box, Figure};
use std::path::Path;

fn steps() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/steps"))
}

/// Compares an image with a committed PNG, naming the first differing pixel.
fn assert_matches(name: &str, width: u32, height: u32, rgb: &[u8]) {
    let path = steps().join(name);
    let (w, h, committed) = read_rgb_png(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((w, h), (width, height), "{name}: size");
    if let Some(i) = (0..rgb.len())
        .step_by(3)
        .find(|&i| rgb[i..i + 3] != committed[i..i + 3])
    {
        let p = i as u32 / 3;
        let differing = (0..rgb.len())
            .step_by(3)
            .filter(|&i| rgb[i..i + 3] != committed[i..i + 3])
            .count();
        panic!(
            "{name}: {differing} pixels differ from the committed figure, first at ({}, {}): drawn {:?}, committed {:?}; \
             regenerate with `cargo run --release -- all --out steps` if the change is meant",
            p % w,
            p / w,
            &rgb[i..i + 3],
            &committed[i..i + 3]
        );
    }
}

#[test]
fn committed_figures_match_the_code() {
    let mut frames = Vec::new();
    for view in Figure::FIGURES {
        let (frame, _) = app::render(view, &cornell_box(), &Settings::default(), None);
        assert_matches(
            view.figure_file(),
            frame.width,
            frame.height,
            &frame.to_rgb8(),
        );
        frames.push(frame);
    }
    let overview = figure_one(&frames).unwrap();
    assert_matches(
        OVERVIEW_FILE,
        overview.width,
        overview.height,
        &overview.to_rgb8(),
    );
}
