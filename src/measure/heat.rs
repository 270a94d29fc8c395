//! Error heat maps: where two images differ, and by how much, as a picture.

use crate::measure::plot::{Canvas, BLACK};
use crate::pipeline::target::unpack;
use crate::pipeline::Frame;

/// A difference of this many 8-bit steps or more is drawn white in a heat map.
pub const HEAT_FULL_SCALE: u8 = 32;

/// The colour of a difference of `d` steps: black through red and yellow to
/// white at [`HEAT_FULL_SCALE`].
fn heat(d: u8) -> u32 {
    let t = (d.min(HEAT_FULL_SCALE) as f32 / HEAT_FULL_SCALE as f32) * 3.0;
    let channel = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u32;
    channel(t) << 16 | channel(t - 1.0) << 8 | channel(t - 2.0)
}

/// The largest channel difference of two images per pixel, from black through
/// red and yellow to white at [`HEAT_FULL_SCALE`] steps.
pub fn heat_map(a: &Frame, b: &Frame) -> Result<Frame, String> {
    if (a.width, a.height) != (b.width, b.height) {
        return Err(format!(
            "a heat map of a {}x{} image against a {}x{} one",
            a.width, a.height, b.width, b.height
        ));
    }
    let mut out = Frame::try_new(a.width, a.height, false)?;
    for ((o, &p), &q) in out.color.iter_mut().zip(&a.color).zip(&b.color) {
        let (p, q) = (unpack(p), unpack(q));
        *o = heat((0..3).map(|i| p[i].abs_diff(q[i])).max().unwrap_or(0));
    }
    Ok(out)
}

/// [`heat_map`] with a title above and a colour scale beneath, for pages that show
/// it on its own.
pub fn heat_map_picture(a: &Frame, b: &Frame, title: &str) -> Result<Frame, String> {
    let map = heat_map(a, b)?;
    let (w, h) = (map.width.max(420), map.height);
    let mut c = Canvas::try_new(w, h + 84, 0x00ff_ffff)?;
    c.text((8, 6), title, 1, BLACK);
    for y in 0..h {
        let src = &map.color[(y * map.width) as usize..][..map.width as usize];
        let start = ((y + 20) * w) as usize;
        c.frame.color[start..start + map.width as usize].copy_from_slice(src);
    }
    let bar = w as i32 - 16;
    for i in 0..bar {
        let d = (i * (HEAT_FULL_SCALE as i32 + 1) / bar) as u8;
        c.rect((8 + i, h as i32 + 28), (1, 16), heat(d));
    }
    c.text((8, h as i32 + 50), "0", 1, BLACK);
    let full = format!("{HEAT_FULL_SCALE}+ steps of 255 (largest channel difference)");
    c.text(
        (w as i32 - 8 - Canvas::text_width(&full, 1), h as i32 + 50),
        &full,
        1,
        BLACK,
    );
    Ok(c.frame)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heat_map_scales_the_largest_channel_difference() {
        let mut a = Frame::new(3, 1);
        let b = Frame::new(3, 1);
        a.color = vec![0, 0x0000_0010, 0x0000_ff00];
        let h = heat_map(&a, &b).unwrap();
        assert_eq!(h.rgb(0, 0), [0, 0, 0]);
        // 16 of 32 steps: t = 1.5, full red, half green.
        assert_eq!(h.rgb(1, 0), [255, 128, 0]);
        assert_eq!(h.rgb(2, 0), [255, 255, 255]);
    }
}
