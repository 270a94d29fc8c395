//! Shared helpers for the integration tests.
#![allow(dead_code)]

use rasterlab::app::{self, Settings};
use rasterlab::{cornell_box, Figure, Frame, StageName};
use std::path::PathBuf;

/// The 8-bit value of a linear colour channel as the figures write it.
pub fn u8_of(c: f32) -> u8 {
    (c * 255.0 + 0.5) as u8
}

pub const BLACK: [u8; 3] = [0, 0, 0];
pub const WHITE_PX: [u8; 3] = [255, 255, 255];
/// 0.75 and 0.15 in 8 bits: 191 and 38.
pub const RED: [u8; 3] = [191, 38, 38];
pub const BLUE: [u8; 3] = [38, 38, 191];
pub const GREEN: [u8; 3] = [38, 191, 38];
pub const PURPLE: [u8; 3] = [191, 38, 191];
pub const YELLOW: [u8; 3] = [191, 191, 38];
pub const CYAN: [u8; 3] = [38, 191, 191];
pub const WHITE: [u8; 3] = [191, 191, 191];

pub fn render(stage: StageName, affine: bool) -> Frame {
    app::render(
        Figure::with_interpolation(stage, Some(affine)),
        &cornell_box(),
        &Settings::default(),
        None,
    )
    .0
}

/// Pixels whose colour in the `depth` figure is `color` and whose 7x7
/// neighbourhood is too: a surface's interior, away from edges where stages
/// may legitimately disagree about which triangle owns a pixel.
pub fn interior(depth: &Frame, color: [u8; 3]) -> Vec<(u32, u32)> {
    let (w, h) = (depth.width, depth.height);
    let k = 3u32;
    let mut out = Vec::new();
    for y in k..h - k {
        for x in k..w - k {
            let all =
                (y - k..=y + k).all(|yy| (x - k..=x + k).all(|xx| depth.rgb(xx, yy) == color));
            if all {
                out.push((x, y));
            }
        }
    }
    out
}

/// Largest per-channel difference between two frames over `pixels`, and where.
pub fn max_diff(a: &Frame, b: &Frame, pixels: &[(u32, u32)]) -> (u8, (u32, u32)) {
    let mut best = (0u8, (0, 0));
    for &(x, y) in pixels {
        let (p, q) = (a.rgb(x, y), b.rgb(x, y));
        let d = (0..3).map(|i| p[i].abs_diff(q[i])).max().unwrap();
        if d > best.0 {
            best = (d, (x, y));
        }
    }
    best
}

/// A fresh, empty folder under the system's temporary folder, removed with
/// everything in it when the test is done with it (also when it fails).
pub struct TempDir(PathBuf);

impl std::ops::Deref for TempDir {
    type Target = std::path::Path;
    fn deref(&self) -> &std::path::Path {
        &self.0
    }
}

impl AsRef<std::path::Path> for TempDir {
    fn as_ref(&self) -> &std::path::Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

pub fn temp_dir(name: &str) -> TempDir {
    let dir = std::env::temp_dir().join(format!("rasterlab-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    TempDir(dir)
}

/// The CRC-32 of PNG chunks (ISO 3309), for writing hand-made PNG headers.
pub fn crc32(data: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in data {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 == 1 {
                0xedb8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}
