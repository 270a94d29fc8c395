//! The handout's `Interpolate` (section 3), generic over what a pixel carries.
//!
//! A [`Pixel`] is an integer position plus a [`Varying`]: whatever the stage needs
//! at every pixel (nothing, 1/z, an illumination, a position over z). The handout
//! grows its `Pixel` struct by hand each section; here the stage names the type and
//! the same code interpolates it.

use glam::Vec3;

/// Per-pixel data that can be interpolated linearly in screen space.
///
/// `Interpolate` needs just these: the difference of two values, that difference
/// divided by the number of steps, and a running sum.
pub trait Varying: Copy + Default {
    fn add(self, other: Self) -> Self;
    fn sub(self, other: Self) -> Self;
    fn div(self, d: f32) -> Self;
    /// Used only by clipping, to place a new vertex part way along an edge.
    fn scale(self, s: f32) -> Self;
}

/// Stages that carry nothing but the position (points, lines, flat fill).
impl Varying for () {
    fn add(self, _: ()) {}
    fn sub(self, _: ()) {}
    fn div(self, _: f32) {}
    fn scale(self, _: f32) {}
}

impl Varying for f32 {
    fn add(self, o: f32) -> f32 {
        self + o
    }
    fn sub(self, o: f32) -> f32 {
        self - o
    }
    fn div(self, d: f32) -> f32 {
        self / d
    }
    fn scale(self, s: f32) -> f32 {
        self * s
    }
}

impl Varying for Vec3 {
    fn add(self, o: Vec3) -> Vec3 {
        self + o
    }
    fn sub(self, o: Vec3) -> Vec3 {
        self - o
    }
    fn div(self, d: f32) -> Vec3 {
        self / d
    }
    fn scale(self, s: f32) -> Vec3 {
        self * s
    }
}

/// Two varyings side by side, e.g. `(depth, illumination)`.
impl<A: Varying, B: Varying> Varying for (A, B) {
    fn add(self, o: Self) -> Self {
        (self.0.add(o.0), self.1.add(o.1))
    }
    fn sub(self, o: Self) -> Self {
        (self.0.sub(o.0), self.1.sub(o.1))
    }
    fn div(self, d: f32) -> Self {
        (self.0.div(d), self.1.div(d))
    }
    fn scale(self, s: f32) -> Self {
        (self.0.scale(s), self.1.scale(s))
    }
}

/// The handout's `Pixel`: an integer image position and the data the stage carries.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pixel<V> {
    pub x: i32,
    pub y: i32,
    pub v: V,
}

impl<V> Pixel<V> {
    pub const fn new(x: i32, y: i32, v: V) -> Self {
        Pixel { x, y, v }
    }
}

impl Pixel<()> {
    /// A bare position, the handout's `ivec2`.
    pub fn at(x: i32, y: i32) -> Self {
        Pixel { x, y, v: () }
    }
}

/// Spans of at most this many steps use the handout's running sum; longer ones
/// compute each value directly. Adding the same f32 step thousands of times drifts:
/// a line climbing 1/3 pixel per step is 0.025 pixels off after 4000 steps but 1.8
/// after 32000 (`rasterlab stress`, docs/stability.md), while `a + (b - a) i / (n - 1)`
/// stays within 0.002. Every span of the 500 x 500 figures is far shorter, so they
/// are the handout's to the bit.
pub const RUNNING_SUM_LIMIT: usize = 4096;

/// The values from `a` to `b` in `n` steps, computed exactly as the handout's
/// `Interpolate`: `step = (b - a) / max(n - 1, 1)` in f32, a running sum
/// `current += step`, and each position truncated toward zero, as C++'s
/// float-to-int conversion does. It yields without storing, so rows need no buffer.
/// Spans longer than [`RUNNING_SUM_LIMIT`] use the direct form instead.
#[derive(Clone, Debug)]
pub struct Steps<V> {
    x: f32,
    y: f32,
    v: V,
    dx: f32,
    dy: f32,
    dv: V,
    /// For the direct form: the start, the whole change, and the step count.
    start: (f32, f32, V),
    span: (f32, f32, V),
    last: f32,
    i: usize,
    n: usize,
}

impl<V: Varying> Steps<V> {
    pub fn new(a: Pixel<V>, b: Pixel<V>, n: usize) -> Self {
        let d = (n.max(2) - 1) as f32;
        let span = ((b.x - a.x) as f32, (b.y - a.y) as f32, b.v.sub(a.v));
        Steps {
            x: a.x as f32,
            y: a.y as f32,
            v: a.v,
            dx: span.0 / d,
            dy: span.1 / d,
            dv: span.2.div(d),
            start: (a.x as f32, a.y as f32, a.v),
            span,
            last: d,
            i: 0,
            n,
        }
    }
}

impl<V: Varying> Iterator for Steps<V> {
    type Item = Pixel<V>;

    #[inline]
    fn next(&mut self) -> Option<Pixel<V>> {
        if self.i >= self.n {
            return None;
        }
        if self.n > RUNNING_SUM_LIMIT {
            let t = self.i as f32 / self.last;
            self.x = self.start.0 + self.span.0 * t;
            self.y = self.start.1 + self.span.1 * t;
            self.v = self.start.2.add(self.span.2.scale(t));
        }
        let p = Pixel {
            x: self.x as i32,
            y: self.y as i32,
            v: self.v,
        };
        self.x += self.dx;
        self.y += self.dy;
        self.v = self.v.add(self.dv);
        self.i += 1;
        Some(p)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.n - self.i;
        (left, Some(left))
    }
}

/// The handout's `Interpolate(a, b, result)`: fills `result` with `result.len()`
/// values from `a` to `b`.
pub fn interpolate<V: Varying>(a: Pixel<V>, b: Pixel<V>, result: &mut [Pixel<V>]) {
    let n = result.len();
    for (slot, p) in result.iter_mut().zip(Steps::new(a, b, n)) {
        *slot = p;
    }
}

/// How many pixels a line from `a` to `b` needs so it has no holes:
/// `max(|dx|, |dy|) + 1` (section 3).
pub fn line_pixels<V>(a: &Pixel<V>, b: &Pixel<V>) -> usize {
    let dx = (a.x as i64 - b.x as i64).unsigned_abs();
    let dy = (a.y as i64 - b.y as i64).unsigned_abs();
    dx.max(dy) as usize + 1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_single_step_gives_the_start() {
        let mut r = [Pixel::at(0, 0); 1];
        interpolate(Pixel::at(3, 4), Pixel::at(9, 9), &mut r);
        assert_eq!(r, [Pixel::at(3, 4)]);
    }

    #[test]
    fn the_running_sum_is_kept() {
        // Ten steps of 0.1 in f32 add up to 1.0000001, not 1: the handout's form
        // accumulates, and the last value shows it.
        let v: Vec<f32> = Steps::new(Pixel::new(0, 0, 0.0f32), Pixel::new(0, 0, 1.0f32), 11)
            .map(|p| p.v)
            .collect();
        let mut sum = 0.0f32;
        let expected: Vec<f32> = (0..11)
            .map(|_| {
                let s = sum;
                sum += 0.1;
                s
            })
            .collect();
        assert_eq!(v, expected);
        assert_eq!(v[10], 1.000_000_1);
    }
}
