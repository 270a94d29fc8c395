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

use super::image::{handout_figures, largest_difference};
use super::pose::Classes;
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

/// How many pixels a JPEG's square may slide from where the samples put it.
const MAX_SLIDE: u32 = 12;

/// The share of samples a located render must match.
const MIN_SCORE: f64 = 0.9;

/// The render inside `shot`, if `shot` holds one with a frame around it (see the
/// module's rules); `None` when it is a plain render or holds none. In a `lossy`
/// screenshot (a JPEG) no edge is sharp and no colour exact: there the half
/// scale, whose means smooth the noise away and so always score a little
/// higher, is searched only when the full scale holds no render, and the
/// square is placed by its summed difference from the figure.
pub fn locate(shot: &Frame, lossy: bool) -> Option<Located> {
    let mut figures = Figures::default();
    let mut best: Option<(f64, u32, u32, u32, u32)> = None; // score, scale, side, x, y
    for scale in [1u32, 2] {
        if scale == 2 && lossy && best.is_some_and(|b| b.0 >= MIN_SCORE) {
            break;
        }
        let image = match scale {
            1 => shot.clone(),
            _ if shot.width.min(shot.height) >= 2 * 64 => half(shot),
            _ => continue,
        };
        for (side, x, y) in candidates(&image) {
            // Larger squares at full scale cost seconds to draw and compare; a
            // render that large is searched at half its size only.
            if scale == 1 && side > MAX_FULL_SIDE {
                continue;
            }
            let points = sample_points(side, side);
            let at_side = figures.at(side);
            for (x, y) in positions(&image, side, x, y) {
                let score = score(&image, x, y, &points, at_side);
                if best.is_none_or(|b| score > b.0) {
                    best = Some((score, scale, side, x, y));
                }
            }
        }
    }
    let (score, scale, side, x, y) = best?;
    let image = if scale == 1 { shot.clone() } else { half(shot) };
    // The samples cannot tell a square one pixel off (a row of the title bar
    // in, a row of the render out); every pixel can.
    // A JPEG's samples can leave the square a few pixels off (all within
    // 16/255 of a figure a little larger): there it is polished until it stays,
    // each round moving it a pixel at most.
    let rounds = if lossy { MAX_SLIDE } else { 1 };
    let (mut side, mut x, mut y) = (side, x, y);
    for _ in 0..rounds {
        let again = polish(&image, side, x, y, &mut figures, lossy);
        if again == (side, x, y) {
            break;
        }
        (side, x, y) = again;
    }
    let whole = (x, y, side, side) == (0, 0, image.width, image.height);
    if score < MIN_SCORE || (whole && scale == 1) {
        return None;
    }
    let cut = crop(&image, [x, y, side, side]);
    if scale == 1 && outside_is_black(&image, [x, y, side, side]) {
        return None;
    }
    let (left, top) = (x * scale, y * scale);
    let (right, bottom) = (
        shot.width - (x + side) * scale,
        shot.height - (y + side) * scale,
    );
    let mut note = format!(
        "the render is the {0}x{0} square at ({left}, {top}) of this {1}x{2} screenshot",
        side * scale,
        shot.width,
        shot.height
    );
    if (left, top, right, bottom) != (0, 0, 0, 0) {
        note += &format!(
            "; left out: {}",
            left_out([top, bottom, left, right], scale)
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

/// Where to look, as (side, x range, y range): around the bounds of the box's
/// coloured walls when it shows some (at the handout's pose the side walls
/// reach the render's left, right, top and bottom edges, so those bounds are
/// the render), else every square of the shorter side down to
/// [`MAX_BORDERS`] less.
fn candidates(image: &Frame) -> Vec<(u32, [u32; 2], [u32; 2])> {
    let short = image.width.min(image.height);
    match coloured_bounds(image) {
        Some([x0, y0, x1, y1]) => {
            let across = (x1 - x0 + 1).max(y1 - y0 + 1);
            let near = |v: u32| [v.saturating_sub(SLACK), v + SLACK];
            (across.saturating_sub(SLACK).max(16)..=(across + SLACK).min(short))
                .map(|side| {
                    // A square as wide as the walls, placed to hold them all.
                    let ys = if y1 - y0 + 1 + SLACK >= side {
                        near(y0)
                    } else {
                        [(y1 + 1).saturating_sub(side), y0]
                    };
                    let xs = if x1 - x0 + 1 + SLACK >= side {
                        near(x0)
                    } else {
                        [(x1 + 1).saturating_sub(side), x0]
                    };
                    (side, xs, ys)
                })
                .collect()
        }
        None => (short.saturating_sub(MAX_BORDERS).max(16)..=short)
            .map(|side| (side, [0, u32::MAX], [0, u32::MAX]))
            .collect(),
    }
}

/// How far the render's edge may be from the walls' bounds, in pixels: a row
/// or column the walls leave black at the render's edge, and the search's slack.
const SLACK: u32 = 3;

/// The places of a square of `side` inside `image` within the ranges given.
fn positions(image: &Frame, side: u32, xs: [u32; 2], ys: [u32; 2]) -> Vec<(u32, u32)> {
    if side > image.width || side > image.height {
        return Vec::new();
    }
    let (xmax, ymax) = (image.width - side, image.height - side);
    let (x0, x1) = (xs[0].min(xmax), xs[1].min(xmax));
    let (y0, y1) = (ys[0].min(ymax), ys[1].min(ymax));
    (y0..=y1)
        .flat_map(|y| (x0..=x1).map(move |x| (x, y)))
        .collect()
}

/// The bounds (x0, y0, x1, y1, inclusive) of the pixels coloured like the box's
/// red, green, blue, yellow, cyan or purple surfaces, when there are enough of
/// them (a hundredth of the image) to be walls. Specks of such colour apart from
/// the walls (a window's red, yellow and green buttons, an icon) are left out:
/// only patches (of pixels at most [`BRIDGE`] apart) of at least [`MIN_PATCH`]
/// of the coloured pixels count.
fn coloured_bounds(image: &Frame) -> Option<[u32; 4]> {
    let classes = Classes::of(&cornell_box());
    let (w, h) = (image.width as usize, image.height as usize);
    // Coloured and not yet in a patch.
    let mut left: Vec<bool> = image.color.iter().map(|&c| classes.coloured(c)).collect();
    let count = left.iter().filter(|&&c| c).count();
    if count * 100 < image.color.len() {
        return None;
    }
    // Each patch of coloured pixels, found by a flood fill.
    let mut stack = Vec::new();
    let mut b = [u32::MAX, u32::MAX, 0, 0];
    for start in 0..left.len() {
        if !left[start] {
            continue;
        }
        left[start] = false;
        stack.push(start);
        let (mut patch, mut size) = ([u32::MAX, u32::MAX, 0, 0], 0usize);
        while let Some(i) = stack.pop() {
            let (x, y) = (i % w, i / w);
            patch = [
                patch[0].min(x as u32),
                patch[1].min(y as u32),
                patch[2].max(x as u32),
                patch[3].max(y as u32),
            ];
            size += 1;
            for v in y.saturating_sub(BRIDGE)..(y + BRIDGE + 1).min(h) {
                for u in x.saturating_sub(BRIDGE)..(x + BRIDGE + 1).min(w) {
                    let j = v * w + u;
                    if left[j] {
                        left[j] = false;
                        stack.push(j);
                    }
                }
            }
        }
        if size as f64 >= MIN_PATCH * count as f64 {
            b = [
                b[0].min(patch[0]),
                b[1].min(patch[1]),
                b[2].max(patch[2]),
                b[3].max(patch[3]),
            ];
        }
    }
    // Only specks, none a patch: no walls.
    (b[0] <= b[2]).then_some(b)
}

/// How far apart two coloured pixels may be and still be of one patch, in
/// pixels along each axis: a JPEG's noise and a shaded wall's darkest corner
/// break a wall into crumbs a pixel or two apart, while a window's buttons are
/// eight pixels and more from the render.
const BRIDGE: usize = 3;

/// The share of all the coloured pixels a patch must hold to be part of the
/// walls: the handout's walls are patches of thousands of pixels each, a
/// window's buttons a hundred (0.1 % of a 500 x 500 render's coloured pixels).
const MIN_PATCH: f64 = 0.01;

/// The square within a pixel of (`side`, `x`, `y`) whose pixels are nearest the
/// best figure's: the most within 16/255, or in a `lossy` image (whose blurred
/// edges are off by more than that on either side of the right place) the least
/// mean difference.
fn polish(
    image: &Frame,
    side: u32,
    x: u32,
    y: u32,
    figures: &mut Figures,
    lossy: bool,
) -> (u32, u32, u32) {
    // Larger is better: the count of close pixels, or the mean difference (in
    // 1/1024 levels, a whole number) negated.
    let mut best = (i64::MIN, side, x, y);
    for s in side.saturating_sub(1).max(16)..=side + 1 {
        if s > image.width || s > image.height {
            continue;
        }
        let drawn = figures.at(s);
        let around = |v: u32, most: u32| v.saturating_sub(1)..=(v + 1).min(most);
        for v in around(y, image.height - s) {
            for u in around(x, image.width - s) {
                let pixels = || (0..s).flat_map(|j| (0..s).map(move |i| (i, j)));
                let near = drawn
                    .iter()
                    .map(|f| match lossy {
                        false => pixels()
                            .filter(|&(i, j)| close(image.rgb(u + i, v + j), f.rgb(i, j)))
                            .count() as i64,
                        true => {
                            -pixels()
                                .map(|(i, j)| {
                                    let (a, b) = (image.rgb(u + i, v + j), f.rgb(i, j));
                                    (0..3).map(|k| a[k].abs_diff(b[k]) as i64).sum::<i64>()
                                })
                                .sum::<i64>()
                                * 1024
                                / (s as i64 * s as i64)
                        }
                    })
                    .max()
                    .unwrap_or(i64::MIN);
                if near > best.0 {
                    best = (near, s, u, v);
                }
            }
        }
    }
    (best.1, best.2, best.3)
}

/// The handout's figures at each side drawn so far: the search and its
/// polish ask for the same sides again.
#[derive(Default)]
struct Figures(std::collections::HashMap<u32, Vec<Frame>>);

impl Figures {
    fn at(&mut self, side: u32) -> &[Frame] {
        self.0.entry(side).or_insert_with(|| figures_at(side))
    }
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

/// A grid of [`SAMPLES`] x [`SAMPLES`] points of a `width` x `height`
/// rectangle, at the centres of its cells.
fn sample_points(width: u32, height: u32) -> Vec<(u32, u32)> {
    let at = |k: u32, side: u32| (2 * k + 1) * side / (2 * SAMPLES);
    (0..SAMPLES)
        .flat_map(|j| (0..SAMPLES).map(move |i| (at(i, width), at(j, height))))
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

/// Whether everything outside the `width` x `height` rectangle at (x, y) is black.
fn outside_is_black(image: &Frame, [x, y, width, height]: [u32; 4]) -> bool {
    (0..image.height).all(|v| {
        (0..image.width).all(|u| {
            let inside = (x..x + width).contains(&u) && (y..y + height).contains(&v);
            inside || image.rgb(u, v) == [0, 0, 0]
        })
    })
}

/// The `width` x `height` rectangle at (x, y).
fn crop(image: &Frame, [x, y, width, height]: [u32; 4]) -> Frame {
    let mut out = Frame::new(width, height);
    for v in 0..height {
        let from = ((y + v) * image.width + x) as usize;
        out.color[(v * width) as usize..((v + 1) * width) as usize]
            .copy_from_slice(&image.color[from..from + width as usize]);
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

/// The largest side tested for a shrunk screenshot: twice it is drawn seven times.
const MAX_SHRUNK_SIDE: u32 = 600;

/// Whether a square `image` is a render shrunk to half its size: the handout's
/// figures drawn twice as large and halved (each pixel the mean of a 2 x 2
/// block, as image viewers shrink) match clearly more of its pixels within
/// 2/255 than the figures drawn at its size. Shrinking blends the colours on
/// either side of every edge, which no rasterizer draws.
pub fn shrunk(image: &Frame) -> bool {
    let side = image.width;
    if image.height != side || !(16..=MAX_SHRUNK_SIDE).contains(&side) {
        return false;
    }
    let matching = |figures: &[Frame]| {
        figures
            .iter()
            .map(|f| {
                f.color
                    .iter()
                    .zip(&image.color)
                    .filter(|&(&a, &b)| largest_difference(a, b) <= 2)
                    .count()
            })
            .max()
            .unwrap_or(0)
    };
    let direct = matching(&figures_at(side));
    let halved: Vec<Frame> = figures_at(2 * side).iter().map(half).collect();
    let halved = matching(&halved);
    let n = image.color.len();
    halved * 2 >= n && halved > direct + n / 200
}

/// The share of an image's sharp edges whose middle pixel lies between its two
/// neighbours above which `blended_edges` takes it for resampled. A rasterizer
/// without anti-aliasing gives each pixel one surface's colour, so across an edge
/// the middle pixel is one side or the other (the handout's seven figures: none
/// between); resizing mixes them (Figures 5 to 7 resized bilinearly to 375, 400
/// and 450 pixels: 24 % to 45 %).
const BLENDED_SHARE: f64 = 0.15;

/// Whether `image`'s edges are blended: resized to a size other than half (see
/// [`shrunk`]), or drawn anti-aliased. Such an image cannot show the variants
/// that move edges by a pixel, and its colours near edges are no rasterizer's.
/// Looked at along rows and columns: three pixels in a line whose ends differ by
/// at least 48/255 in some channel are a sharp edge, and the middle one is
/// between when, in that channel, it is at least a quarter of the step from
/// either end.
pub fn blended_edges(image: &Frame) -> bool {
    blended_share(image).is_some_and(|share| share > BLENDED_SHARE)
}

/// The share of `image`'s sharp edges whose middle pixel is between (see
/// [`blended_edges`]); `None` with fewer than 64 sharp edges or a side under 16.
pub fn blended_share(image: &Frame) -> Option<f64> {
    let (w, h) = (image.width as usize, image.height as usize);
    if w < 16 || h < 16 {
        return None;
    }
    let at = |x: usize, y: usize| crate::pipeline::target::unpack(image.color[y * w + x]);
    let (mut edges, mut between) = (0u64, 0u64);
    let mut look = |a: [u8; 3], m: [u8; 3], b: [u8; 3]| {
        let Some(k) = (0..3).max_by_key(|&k| a[k].abs_diff(b[k])) else {
            return;
        };
        let step = a[k].abs_diff(b[k]);
        if step < 48 {
            return;
        }
        edges += 1;
        let margin = step / 4;
        let (lo, hi) = (a[k].min(b[k]), a[k].max(b[k]));
        if m[k] >= lo.saturating_add(margin) && m[k] <= hi.saturating_sub(margin) {
            between += 1;
        }
    };
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            look(at(x - 1, y), at(x, y), at(x + 1, y));
            look(at(x, y - 1), at(x, y), at(x, y + 1));
        }
    }
    (edges >= 64).then(|| between as f64 / edges as f64)
}

/// The share of 2 x 2 blocks that must be of one colour for an image to be a
/// render shown at twice its size. A render drawn at that size has its edges
/// cutting blocks (the box at 1000 x 1000: about 2 % of them).
const DOUBLED_BLOCKS: f64 = 0.999;

/// `image` halved when it is a render shown at twice its size pixel for pixel,
/// as a HiDPI screen shows a window: every 2 x 2 block one colour, and enough
/// drawn that this says something (64 changes of colour along its rows), with
/// a slanted edge ([`SLANT_LINES`]): a render whose edges all run along rows
/// or columns (a camera facing one wall's edge) has them between blocks one
/// time in four at its own size.
pub fn pixel_doubled(image: &Frame) -> Option<Frame> {
    let (w, h) = (image.width / 2, image.height / 2);
    if !image.width.is_multiple_of(2) || !image.height.is_multiple_of(2) || w < 16 || h < 16 {
        return None;
    }
    let at = |x: u32, y: u32| image.color[(y * image.width + x) as usize];
    let uniform = (0..h)
        .flat_map(|y| (0..w).map(move |x| (2 * x, 2 * y)))
        .filter(|&(x, y)| {
            let c = at(x, y);
            at(x + 1, y) == c && at(x, y + 1) == c && at(x + 1, y + 1) == c
        })
        .count();
    if (uniform as f64) < DOUBLED_BLOCKS * f64::from(w * h) {
        return None;
    }
    // Something drawn: a plain colour (a black image) is uniform at any scale.
    let halved = half(image);
    let changes = halved.color.windows(2).filter(|p| p[0] != p[1]).count();
    (changes >= 64 && slanted(&halved)).then_some(halved)
}

/// How many columns and how many rows of an image must hold a change of
/// colour (along its rows, and down its columns) for it to have an edge that
/// is neither a row nor a column: each edge of the box seen in perspective
/// changes colour in tens of them.
const SLANT_LINES: usize = 8;

/// Whether `image` has an edge that runs along neither its rows nor its
/// columns: changes of colour along its rows fall in [`SLANT_LINES`] columns
/// or more, and down its columns in as many rows.
fn slanted(image: &Frame) -> bool {
    let (w, h) = (image.width as usize, image.height as usize);
    let at = |x: usize, y: usize| image.color[y * w + x];
    let columns = (0..w - 1)
        .filter(|&x| (0..h).any(|y| at(x, y) != at(x + 1, y)))
        .count();
    let rows = (0..h - 1)
        .filter(|&y| (0..w).any(|x| at(x, y) != at(x, y + 1)))
        .count();
    columns >= SLANT_LINES && rows >= SLANT_LINES
}

/// `image` at twice its size, each pixel a 2 x 2 block.
pub fn doubled(image: &Frame) -> Frame {
    let (w, h) = (image.width * 2, image.height * 2);
    let mut out = Frame::new(w, h);
    for y in 0..h {
        for x in 0..w {
            out.color[(y * w + x) as usize] = image.color[((y / 2) * image.width + x / 2) as usize];
        }
    }
    out
}

/// The share of a side's pixels that must change across it for the side to be
/// the render's edge: a window's frame against the render changes nearly all of
/// them, a line inside the render (a wall's edge) only the part it spans.
const FRAME_EDGE: f64 = 0.6;

/// The first of `lines` (going out from the walls) whose `share` makes it a
/// frame's edge, or one of the next two out if it is stronger: a JPEG smears the
/// frame's colour a row or two into the render, which makes a weaker line of its
/// own just inside the frame's.
fn first_strong(mut lines: impl Iterator<Item = u32>, share: impl Fn(u32) -> f64) -> Option<u32> {
    let at = lines.find(|&v| share(v) >= FRAME_EDGE)?;
    let mut best = (share(at), at);
    for v in lines.take(2) {
        if share(v) > best.0 {
            best = (share(v), v);
        }
    }
    Some(best.1)
}

/// The render inside `shot` whatever the camera, found by its frame: the box's
/// coloured walls lie inside the render, and each side of the render is either
/// the screenshot's own edge or the nearest line beyond the walls across which
/// the colour changes along most of the side to something not black (a wall's
/// edge inside the render has the render's black beyond it; a window's title
/// bar and borders are not black). `None` when that is the
/// whole screenshot, when it is small, or when what it leaves out is black
/// (the render's own bands).
pub fn locate_by_frame(shot: &Frame) -> Option<Located> {
    let [bx0, by0, bx1, by1] = coloured_bounds(shot)?;
    let (w, h) = (shot.width, shot.height);
    // The share of `pairs` (the render's pixel, the frame's beyond it) whose
    // colour changes to something not black.
    let share = |pairs: &mut dyn ExactSizeIterator<Item = ([u8; 3], [u8; 3])>| {
        let n = pairs.len().max(1);
        let changed = pairs
            .filter(|(inside, outside)| {
                *outside != [0; 3] && (0..3).any(|k| inside[k].abs_diff(outside[k]) > 8)
            })
            .count();
        changed as f64 / n as f64
    };
    // The line between row (or column) `at - 1` and `at`, over `along`, seen
    // from the walls (`before`: the walls are past the line); the screenshot's
    // edges count as lines.
    let row_line = |at: u32, along: std::ops::Range<u32>, before: bool| -> f64 {
        if at == 0 || at == h {
            return 1.0;
        }
        let (inside, outside) = if before { (at, at - 1) } else { (at - 1, at) };
        share(&mut along.map(|x| (shot.rgb(x, inside), shot.rgb(x, outside))))
    };
    let column_line = |at: u32, along: std::ops::Range<u32>, before: bool| -> f64 {
        if at == 0 || at == w {
            return 1.0;
        }
        let (inside, outside) = if before { (at, at - 1) } else { (at - 1, at) };
        share(&mut along.map(|y| (shot.rgb(inside, y), shot.rgb(outside, y))))
    };
    let strong = |s: f64| s >= FRAME_EDGE;
    let top = first_strong((0..=by0).rev(), |y| row_line(y, bx0..bx1 + 1, true))?;
    let bottom = first_strong(by1 + 1..=h, |y| row_line(y, bx0..bx1 + 1, false))?;
    let left = first_strong((0..=bx0).rev(), |x| column_line(x, top..bottom, true))?;
    let right = first_strong(bx1 + 1..=w, |x| column_line(x, top..bottom, false))?;
    // Each side must be an edge along the render's whole width or height, not
    // only beside the walls.
    let framed = strong(row_line(top, left..right, true))
        && strong(row_line(bottom, left..right, false))
        && strong(column_line(left, top..bottom, true))
        && strong(column_line(right, top..bottom, false));
    let (rw, rh) = (right - left, bottom - top);
    if !framed || (rw, rh) == (w, h) || rw < 64 || rh < 64 {
        return None;
    }
    let crop_at = [left, top, rw, rh];
    if outside_is_black(shot, crop_at) {
        return None;
    }
    let frame = crop(shot, crop_at);
    let note = format!(
        "the render is the {rw}x{rh} rectangle at ({left}, {top}) of this {w}x{h} screenshot, inside its frame; left out: {}",
        left_out([top, h - bottom, left, w - right], 1)
    );
    Some(Located {
        frame,
        note,
        crop: crop_at,
    })
}

/// What was cut from around the render, `[above, below, left, right]` pixels of
/// the screenshot, in words: "30 pixels above (a window's title bar and borders)".
fn left_out(around: [u32; 4], scale: u32) -> String {
    // Borders are a few pixels; anything wider beside or below is a desktop.
    let [_, below, left, right] = around;
    let what = match left.max(right).max(below) > 16 * scale {
        true => "the window's title bar and borders, and the desktop around it",
        false => "a window's title bar and borders",
    };
    format!("{} ({what})", sides(around))
}

/// How many pixels are `around` a rectangle (above, below, left of, right of),
/// in words, the sides with none left out.
fn sides(around: [u32; 4]) -> String {
    let parts: Vec<String> = around
        .iter()
        .zip(["above", "below", "left of", "right of"])
        .filter(|(&n, _)| n > 0)
        .map(|(&n, what)| match n {
            1 => format!("1 pixel {what}"),
            _ => format!("{n} pixels {what}"),
        })
        .collect();
    parts.join(", ")
}

/// A render cut out of: the handout's size, 500 x 500.
const CUT_FROM: u32 = 500;

/// The shortest side of a part of a render [`cut_from_render`] looks for: a
/// hand-made crop loses a few rows or columns, not half the render.
const MIN_CUT_SIDE: u32 = 400;

/// The share of samples a part of a render must match within 16/255: a render
/// of another size, scaled rather than cut, misplaces its edges by pixels all
/// round and misses it.
const MIN_CUT_SCORE: f64 = 0.99;

/// A render cut out of a larger one (a screenshot trimmed by hand, a few rows
/// or columns lost): the `shot` is smaller than the handout's 500 x 500 along
/// some side, at least [`MIN_CUT_SIDE`] along each, and matches one of its
/// figures at 500 x 500 at some offset (samples within 16/255, then every pixel
/// within a pixel of the best place). Returns that figure with the shot pasted
/// in at the offset, the offset, and the note.
pub fn cut_from_render(shot: &Frame) -> Option<Located> {
    let (w, h) = (shot.width, shot.height);
    if w > CUT_FROM || h > CUT_FROM || (w, h) == (CUT_FROM, CUT_FROM) || w.min(h) < MIN_CUT_SIDE {
        return None;
    }
    let figures = figures_at(CUT_FROM);
    let points = sample_points(w, h);
    // (share of samples, figure, x, y)
    let mut best = (0.0, 0, 0, 0);
    for (k, f) in figures.iter().enumerate() {
        for y in 0..=CUT_FROM - h {
            for x in 0..=CUT_FROM - w {
                let near = points
                    .iter()
                    .filter(|&&(u, v)| close(shot.rgb(u, v), f.rgb(x + u, y + v)))
                    .count();
                let share = near as f64 / points.len() as f64;
                if share > best.0 {
                    best = (share, k, x, y);
                }
            }
        }
    }
    let (share, k, x0, y0) = best;
    if share < MIN_CUT_SCORE {
        return None;
    }
    // Every pixel decides among the places a pixel around the samples' best.
    let figure = &figures[k];
    let near_at = |x: u32, y: u32| {
        (0..h)
            .flat_map(|v| (0..w).map(move |u| (u, v)))
            .filter(|&(u, v)| close(shot.rgb(u, v), figure.rgb(x + u, y + v)))
            .count()
    };
    let mut place = (near_at(x0, y0), x0, y0);
    for y in y0.saturating_sub(1)..=(y0 + 1).min(CUT_FROM - h) {
        for x in x0.saturating_sub(1)..=(x0 + 1).min(CUT_FROM - w) {
            let near = near_at(x, y);
            if near > place.0 {
                place = (near, x, y);
            }
        }
    }
    let (_, x, y) = place;
    let mut whole = figure.clone();
    for (v, row) in shot.color.chunks_exact(w as usize).enumerate() {
        let at = ((y + v as u32) * CUT_FROM + x) as usize;
        whole.color[at..at + w as usize].copy_from_slice(row);
    }
    let lost = sides([y, CUT_FROM - h - y, x, CUT_FROM - w - x]);
    let note = format!(
        "the image is the {w}x{h} part at ({x}, {y}) of a {CUT_FROM}x{CUT_FROM} render, cut out of it (lost: {lost}); it was checked in its place in the render, whose other pixels were taken from the handout's figure it matches"
    );
    Some(Located {
        frame: whole,
        note,
        crop: [x, y, w, h],
    })
}
