//! Figure 1: every stage's figure side by side, so the steps can be compared at a
//! glance. Four columns, left to right and top to bottom in the handout's order,
//! separated by a grey gutter.

use crate::pipeline::target::unpack;
use crate::pipeline::Frame;

/// Gutter between panels, in pixels.
pub const GUTTER: u32 = 8;
/// Panels per row.
pub const COLUMNS: u32 = 4;
const GUTTER_RGB: [u8; 3] = [64, 64, 64];

/// Lays out same-sized frames in a grid; returns (width, height, RGB rows).
/// Returns `None` if there are no frames or their sizes differ.
pub fn overview(frames: &[Frame]) -> Option<(u32, u32, Vec<u8>)> {
    let first = frames.first()?;
    let (fw, fh) = (first.width, first.height);
    if frames.iter().any(|f| (f.width, f.height) != (fw, fh)) {
        return None;
    }
    let count = frames.len() as u32;
    let cols = count.min(COLUMNS);
    let rows = count.div_ceil(COLUMNS);
    let width = cols * fw + (cols - 1) * GUTTER;
    let height = rows * fh + (rows - 1) * GUTTER;
    let mut rgb: Vec<u8> = GUTTER_RGB
        .iter()
        .copied()
        .cycle()
        .take((width * height * 3) as usize)
        .collect();
    for (i, frame) in frames.iter().enumerate() {
        let (col, row) = (i as u32 % COLUMNS, i as u32 / COLUMNS);
        let (x0, y0) = (col * (fw + GUTTER), row * (fh + GUTTER));
        for y in 0..fh {
            let src = &frame.color[(y * fw) as usize..((y + 1) * fw) as usize];
            let start = (((y0 + y) * width + x0) * 3) as usize;
            let dst = &mut rgb[start..start + (fw * 3) as usize];
            for (d, &c) in dst.chunks_exact_mut(3).zip(src) {
                d.copy_from_slice(&unpack(c));
            }
        }
    }
    Some((width, height, rgb))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn panels_land_in_a_grid() {
        let mut a = Frame::new(2, 2);
        a.color[3] = 0x00ff_0000; // bottom right of panel 0
        let mut frames = vec![a];
        for _ in 0..4 {
            frames.push(Frame::new(2, 2));
        }
        let (w, h, rgb) = overview(&frames).unwrap();
        assert_eq!((w, h), (4 * 2 + 3 * GUTTER, 2 * 2 + GUTTER));
        let at = |x: u32, y: u32| &rgb[((y * w + x) * 3) as usize..][..3];
        assert_eq!(at(1, 1), [255, 0, 0]);
        assert_eq!(at(2, 0), GUTTER_RGB);
        assert_eq!(at(0, 2 + GUTTER), [0, 0, 0]);
        assert!(overview(&[]).is_none());
    }
}
