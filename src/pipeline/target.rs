//! What the pipeline draws into: a colour buffer and a depth buffer, either of
//! them optional, over a band of the image's rows. The caller owns the buffers;
//! [`Frame`] is the usual owner of a whole image.

use glam::Vec3;
use std::ops::Range;

/// A render target: `rows` of an image `width` x `height`, with a colour buffer
/// (`0x00RRGGBB`, the layout a window wants) and a depth buffer (1/z per pixel,
/// 0 = infinitely far), each `width` x `rows.len()` and indexed from the band's
/// first row. A depth-only pass has no colour; a stage without a depth test
/// needs no depth.
#[derive(Debug, Default)]
pub struct Target<'a> {
    pub width: u32,
    pub height: u32,
    pub rows: Range<u32>,
    pub color: Option<&'a mut [u32]>,
    pub depth: Option<&'a mut [f32]>,
}

impl Target<'_> {
    /// The handout's clearing at the start of `Draw`: black, depth 0.
    pub fn clear(&mut self) {
        if let Some(c) = self.color.as_deref_mut() {
            c.fill(0);
        }
        if let Some(d) = self.depth.as_deref_mut() {
            d.fill(0.0);
        }
    }

    /// This band cut in two before image row `row` (kept within the band): the
    /// rows above it and the rows from it on, each a target of its own.
    pub fn split_at_row(self, row: u32) -> (Self, Self) {
        let row = row.clamp(self.rows.start, self.rows.end);
        let pixels = ((row - self.rows.start) * self.width) as usize;
        let (color_top, color_bottom) = split(self.color, pixels);
        let (depth_top, depth_bottom) = split(self.depth, pixels);
        let (width, height) = (self.width, self.height);
        let top = Target {
            width,
            height,
            rows: self.rows.start..row,
            color: color_top,
            depth: depth_top,
        };
        let bottom = Target {
            width,
            height,
            rows: row..self.rows.end,
            color: color_bottom,
            depth: depth_bottom,
        };
        (top, bottom)
    }

    /// The index of pixel (x, y) in the buffers; (x, y) must be in the band.
    #[inline]
    pub fn index(&self, x: i32, y: i32) -> usize {
        (y as u32 - self.rows.start) as usize * self.width as usize + x as usize
    }
}

/// A buffer, if there is one, cut in two at index `at`.
fn split<T>(buffer: Option<&mut [T]>, at: usize) -> (Option<&mut [T]>, Option<&mut [T]>) {
    match buffer.map(|b| b.split_at_mut(at)) {
        Some((a, b)) => (Some(a), Some(b)),
        None => (None, None),
    }
}

/// A whole image with its own buffers.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    pub width: u32,
    pub height: u32,
    pub color: Vec<u32>,
    /// Empty unless the last stage drawn tests depth.
    pub depth: Vec<f32>,
}

impl Frame {
    pub fn new(width: u32, height: u32) -> Self {
        Frame {
            width,
            height,
            color: vec![0; width as usize * height as usize],
            depth: Vec::new(),
        }
    }

    /// Sizes the buffers for a `width` x `height` image, with a depth buffer when
    /// `depth`; reuses them when the size is unchanged.
    pub fn resize(&mut self, width: u32, height: u32, depth: bool) {
        let n = width as usize * height as usize;
        self.width = width;
        self.height = height;
        self.color.resize(n, 0);
        if depth {
            self.depth.resize(n, 0.0);
        } else {
            self.depth = Vec::new();
        }
    }

    /// The whole image as a render target.
    pub fn target(&mut self) -> Target<'_> {
        Target {
            width: self.width,
            height: self.height,
            rows: 0..self.height,
            color: Some(&mut self.color),
            depth: (!self.depth.is_empty()).then_some(&mut self.depth[..]),
        }
    }

    /// The colour at (x, y) as 8-bit RGB.
    pub fn rgb(&self, x: u32, y: u32) -> [u8; 3] {
        unpack(self.color[(y * self.width + x) as usize])
    }

    /// The whole image as 8-bit RGB rows, top first.
    pub fn to_rgb8(&self) -> Vec<u8> {
        self.color.iter().flat_map(|&c| unpack(c)).collect()
    }

    /// [`Frame::to_rgb8`], refused with the size it needs when that memory
    /// cannot be had.
    pub fn try_to_rgb8(&self) -> Result<Vec<u8>, String> {
        let mut rgb = Vec::new();
        let bytes = self.color.len() * 3;
        rgb.try_reserve_exact(bytes).map_err(|_| {
            format!(
                "out of memory: the {}x{} image's 8-bit rows need {}",
                self.width,
                self.height,
                megabytes(bytes)
            )
        })?;
        rgb.extend(self.color.iter().flat_map(|&c| unpack(c)));
        Ok(rgb)
    }

    /// A black `width` x `height` frame, with a depth buffer when `depth`,
    /// refused with the size it needs when that memory cannot be had (a render
    /// then fails with a message instead of aborting).
    pub fn try_new(width: u32, height: u32, depth: bool) -> Result<Frame, String> {
        let n = width as usize * height as usize;
        let bytes = n * (4 + if depth { 4 } else { 0 });
        let refuse = |_| {
            format!(
                "out of memory: a {width}x{height} image needs {} for its colour{} buffer",
                megabytes(bytes),
                if depth { " and depth" } else { "" }
            )
        };
        let mut frame = Frame {
            width,
            height,
            ..Frame::default()
        };
        frame.color.try_reserve_exact(n).map_err(refuse)?;
        frame.color.resize(n, 0);
        if depth {
            frame.depth.try_reserve_exact(n).map_err(refuse)?;
            frame.depth.resize(n, 0.0);
        }
        Ok(frame)
    }
}

/// Whether `bytes` of memory can be had now: asked for at once and given
/// back, so that work too large for the memory there is is refused before it
/// starts rather than aborting half way (Rust's allocations abort on failure).
pub fn memory_for(bytes: usize) -> bool {
    Vec::<u8>::new().try_reserve_exact(bytes).is_ok()
}

/// A byte count as people read it: "805 MB".
pub fn megabytes(bytes: usize) -> String {
    format!("{} MB", bytes.div_ceil(1_000_000))
}

/// `0x00RRGGBB` as `[r, g, b]`: the inverse of [`pack`]'s layout.
#[inline]
pub fn unpack(c: u32) -> [u8; 3] {
    [(c >> 16) as u8, (c >> 8) as u8, c as u8]
}

/// A linear colour in [0, 1] as `0x00RRGGBB`, clamped and rounded to 8 bits.
/// NaN becomes 0.
#[inline]
pub fn pack(c: Vec3) -> u32 {
    // Written as selects and a plain conversion, not clamp and `as`, so loops over
    // pixels vectorise; for every input, NaN included, the result is that of
    // clamping then rounding.
    let q = |v: f32| {
        let v = if v > 0.0 { v } else { 0.0 }; // NaN -> 0
        let v = if v < 1.0 { v } else { 1.0 };
        // SAFETY: v is in [0, 1], so the value is in [0.5, 255.5]: finite and
        // representable as i32, which is all `to_int_unchecked` requires.
        unsafe { (v * 255.0 + 0.5).to_int_unchecked::<i32>() as u32 }
    };
    (q(c.x) << 16) | (q(c.y) << 8) | q(c.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pack_rounds_and_clamps() {
        assert_eq!(pack(Vec3::new(1.0, 0.5, 0.0)), 0x00ff_8000);
        assert_eq!(pack(Vec3::new(2.0, -1.0, f32::NAN)), 0x00ff_0000);
        assert_eq!(pack(Vec3::splat(0.75)), 0x00bf_bfbf); // 191.25 rounds to 191
    }

    #[test]
    fn pack_is_clamp_then_round() {
        let reference = |v: f32| {
            if v.is_nan() {
                0
            } else {
                (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u32
            }
        };
        let mut values: Vec<f32> = (0..=4000).map(|i| i as f32 / 3000.0 - 0.1).collect();
        values.extend([
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            -0.0,
            1.0,
            0.5 / 255.0,
        ]);
        for v in values {
            assert_eq!(pack(Vec3::splat(v)), reference(v) * 0x01_01_01, "{v}");
        }
    }

    #[test]
    fn bands_cover_the_image_once() {
        let mut f = Frame::new(4, 10);
        f.resize(4, 10, true);
        let (top, rest) = f.target().split_at_row(4);
        let (middle, bottom) = rest.split_at_row(8);
        let bands = [top, middle, bottom];
        let rows: Vec<_> = bands.iter().map(|b| b.rows.clone()).collect();
        assert_eq!(rows, [0..4, 4..8, 8..10]);
        let sizes: Vec<_> = bands
            .iter()
            .map(|b| b.color.as_ref().unwrap().len())
            .collect();
        assert_eq!(sizes, [16, 16, 8]);
        assert!(bands
            .iter()
            .all(|b| b.depth.as_ref().unwrap().len() == b.color.as_ref().unwrap().len()));
        // A cut beyond the band is kept within it: the part past it is empty.
        let (all, none) = f.target().split_at_row(40);
        assert_eq!((all.rows, none.rows), (0..10, 10..10));
    }

    #[test]
    fn a_band_indexes_from_its_first_row() {
        let mut color = vec![0u32; 10 * 3];
        let t = Target {
            width: 10,
            height: 8,
            rows: 4..7,
            color: Some(&mut color),
            depth: None,
        };
        assert_eq!(t.index(0, 4), 0);
        assert_eq!(t.index(9, 6), 29);
    }
}
