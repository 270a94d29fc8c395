//! Finding the render inside a screenshot (issue #22). An OS screenshot of the
//! lab's window holds the render with a title bar above it and borders around
//! it, and on a HiDPI screen at twice its size. Checked as it is, the bar and
//! the borders would be read as part of the picture and misexplain it.
//!
//! The search: at scale 1 and, for a large enough screenshot, 1/2 (each pixel
//! the mean of a 2 x 2 block), every square of the shorter side down to 16
//! pixels less, at every place it fits, is compared with the handout's seven
//! figures drawn at its size (focal length = its side, as `check` assumes) on a
//! grid of 48 x 48 samples; the share of samples within 16/255 of the best
//! figure scores it. The best square is the render when it scores at least 90 %
//! and what it leaves out is not black (a render of another shape keeps its
//! black bands: those are the render's own).

use super::image::handout_figures;
use crate::pipeline::{Camera, Frame};
use crate::scene::cornell_box;

/// The render found inside a screenshot, and what was done to find it.
#[derive(Clone, Debug)]
pub struct Located {
    pub frame: Frame,
    /// In words, for the report: what was left out, and any scaling.
    pub note: String,
    /// The render's place in the screenshot: x, y, width, height.
    pub crop: [u32; 4],
}

/// How much shorter than the screenshot's shorter side the render may be: two
/// window borders of up to 8 pixels.
const MAX_BORDERS: u32 = 16;

/// Samples along each side of a candidate square.
const SAMPLES: u32 = 48;

/// The largest shorter side searched at full scale.
const MAX_FULL_SIDE: u32 = 1100;

/// The share of samples a located render must match.
const MIN_SCORE: f64 = 0.9;

/// The render inside `shot`, if `shot` holds one with a frame around it (see the
/// module's rules); `None` when it is a plain render or holds none.
pub fn locate(shot: &Frame) -> Option<Located> {
    let mut best: Option<(f64, u32, u32, u32, u32)> = None; // score, scale, side, x, y
    for scale in [1u32, 2] {
        let image = match scale {
            1 => shot.clone(),
            _ if shot.width.min(shot.height) >= 2 * 64 => half(shot),
            _ => continue,
        };
        let short = image.width.min(image.height);
        // Larger squares at full scale cost seconds to draw and compare; a
        // screenshot that large is searched at half its size only.
        if scale == 1 && short > MAX_FULL_SIDE {
            continue;
        }
        for side in (short.saturating_sub(MAX_BORDERS).max(16)..=short).rev() {
            let figures = figures_at(side);
            let points = sample_points(side);
            for y in 0..=image.height - side {
                for x in 0..=image.width - side {
                    let score = score(&image, x, y, &points, &figures);
                    if best.is_none_or(|b| score > b.0) {
                        best = Some((score, scale, side, x, y));
                    }
                }
            }
        }
    }
    let (score, scale, side, x, y) = best?;
    let image = if scale == 1 { shot.clone() } else { half(shot) };
    let whole = (x, y, side, side) == (0, 0, image.width, image.height);
    if score < MIN_SCORE || (whole && scale == 1) {
        return None;
    }
    let cut = crop(&image, x, y, side);
    if scale == 1 && outside_is_black(&image, x, y, side) {
        return None;
    }
    let (left, top) = (x * scale, y * scale);
    let (right, bottom) = (
        shot.width - (x + side) * scale,
        shot.height - (y + side) * scale,
    );
    let mut parts = Vec::new();
    for (n, what) in [
        (top, "above"),
        (bottom, "below"),
        (left, "left of"),
        (right, "right of"),
    ] {
        if n > 0 {
            parts.push(format!("{n} pixels {what}"));
        }
    }
    let mut note = format!(
        "the render is the {0}x{0} square at ({left}, {top}) of this {1}x{2} screenshot",
        side * scale,
        shot.width,
        shot.height
    );
    if !parts.is_empty() {
        note += &format!(
            "; left out: {} (a window's title bar and borders)",
            parts.join(", ")
        );
    }
    if scale == 2 {
        note += &format!("; it was halved to {side}x{side} (a HiDPI screenshot at twice the size)");
    }
    let crop = [left, top, side * scale, side * scale];
    Some(Located {
        frame: cut,
        note,
        crop,
    })
}

/// The handout's seven figures at `side` x `side`, focal length `side`.
fn figures_at(side: u32) -> Vec<Frame> {
    let camera = Camera {
        focal: side as f32,
        ..Camera::handout(side, side)
    };
    let mesh = cornell_box();
    handout_figures(&mesh, &camera)
}

/// A grid of [`SAMPLES`] x [`SAMPLES`] points of a square of `side`, at the
/// centres of its cells.
fn sample_points(side: u32) -> Vec<(u32, u32)> {
    (0..SAMPLES)
        .flat_map(|j| (0..SAMPLES).map(move |i| (i, j)))
        .map(|(i, j)| {
            let at = |k: u32| (2 * k + 1) * side / (2 * SAMPLES);
            (at(i), at(j))
        })
        .collect()
}

/// The best share, over `figures`, of `points` of the square at (x, y) whose
/// colour is within 16/255 of the figure's.
fn score(image: &Frame, x: u32, y: u32, points: &[(u32, u32)], figures: &[Frame]) -> f64 {
    figures
        .iter()
        .map(|f| {
            let near = points
                .iter()
                .filter(|&&(u, v)| close(image.rgb(x + u, y + v), f.rgb(u, v)))
                .count();
            near as f64 / points.len() as f64
        })
        .fold(0.0, f64::max)
}

fn close(a: [u8; 3], b: [u8; 3]) -> bool {
    (0..3).all(|i| a[i].abs_diff(b[i]) <= 16)
}

/// Whether everything outside the square at (x, y) is black.
fn outside_is_black(image: &Frame, x: u32, y: u32, side: u32) -> bool {
    (0..image.height).all(|v| {
        (0..image.width).all(|u| {
            let inside = (x..x + side).contains(&u) && (y..y + side).contains(&v);
            inside || image.rgb(u, v) == [0, 0, 0]
        })
    })
}

/// The square of `side` at (x, y).
fn crop(image: &Frame, x: u32, y: u32, side: u32) -> Frame {
    let mut out = Frame::new(side, side);
    for v in 0..side {
        for u in 0..side {
            out.color[(v * side + u) as usize] =
                image.color[((y + v) * image.width + x + u) as usize];
        }
    }
    out
}

/// `image` at half its size, each pixel the mean of a 2 x 2 block.
fn half(image: &Frame) -> Frame {
    let (w, h) = (image.width / 2, image.height / 2);
    let mut out = Frame::new(w, h);
    for y in 0..h {
        for x in 0..w {
            let mut sum = [0u32; 3];
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let p = image.rgb(2 * x + dx, 2 * y + dy);
                for c in 0..3 {
                    sum[c] += p[c] as u32;
                }
            }
            let [r, g, b] = sum.map(|s| (s + 2) / 4);
            out.color[(y * w + x) as usize] = r << 16 | g << 8 | b;
        }
    }
    out
}
