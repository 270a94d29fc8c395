//! The handout's `Interpolate` (section 3), for any per-pixel struct, and the two
//! ways of interpolating a quantity across the screen (section 6.2).
//!
//! A [`Pixel`] is the handout's struct: an integer position, the zinv value of
//! section 5 and whatever the stage needs at every pixel (its [`Varying`]: nothing,
//! an illumination, a 3D position). The handout grows its `Pixel` by hand each
//! section; here the stage names the struct and the same code interpolates it.

use glam::Vec2;
use std::ops::{Add, Div, Mul, Sub};

/// A per-pixel struct that can be interpolated: anything with `+`, `-`, `* f32`
/// and `/ f32`, which is all `Interpolate` and clipping use. Implemented for every
/// such type (f32, glam's vectors, the stages' structs).
pub trait Varying:
    Copy
    + Send
    + Default
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<f32, Output = Self>
    + Div<f32, Output = Self>
{
}

impl<T> Varying for T where
    T: Copy
        + Send
        + Default
        + Add<Output = T>
        + Sub<Output = T>
        + Mul<f32, Output = T>
        + Div<f32, Output = T>
{
}

/// Implements `+`, `-`, `* f32` and `/ f32` field by field for a struct of
/// varyings, so that it is a [`Varying`].
macro_rules! linear_ops {
    ($name:ident { $($field:ident),* }) => {
        impl std::ops::Add for $name {
            type Output = $name;
            #[inline]
            #[allow(unused_variables)]
            fn add(self, o: $name) -> $name {
                $name { $($field: self.$field + o.$field),* }
            }
        }
        impl std::ops::Sub for $name {
            type Output = $name;
            #[inline]
            #[allow(unused_variables)]
            fn sub(self, o: $name) -> $name {
                $name { $($field: self.$field - o.$field),* }
            }
        }
        impl std::ops::Mul<f32> for $name {
            type Output = $name;
            #[inline]
            #[allow(unused_variables)]
            fn mul(self, s: f32) -> $name {
                $name { $($field: self.$field * s),* }
            }
        }
        impl std::ops::Div<f32> for $name {
            type Output = $name;
            #[inline]
            #[allow(unused_variables)]
            fn div(self, d: f32) -> $name {
                $name { $($field: self.$field / d),* }
            }
        }
    };
}

pub(crate) use linear_ops;

/// The per-pixel struct of stages that need nothing but the position and zinv.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Nothing {}

linear_ops!(Nothing {});

/// The handout's `Pixel`: an integer image position, 1/z (section 5) and the
/// stage's per-pixel struct, as the interpolation carries it (see [`Interpolation`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pixel<V> {
    pub x: i32,
    pub y: i32,
    pub zinv: f32,
    pub varying: V,
}

impl Pixel<Nothing> {
    /// A bare position, the handout's `ivec2`.
    pub fn at(x: i32, y: i32) -> Self {
        Pixel {
            x,
            y,
            zinv: 0.0,
            varying: Nothing {},
        }
    }
}

/// Spans of at most this many steps use the handout's running sum; longer ones
/// compute each value directly. Adding the same f32 step thousands of times drifts:
/// a line climbing 1/3 pixel per step is 0.025 pixels off after 4000 steps but 1.8
/// after 32000 (`rasterlab stress`, docs/stability.md), while `a + (b - a) i / (n - 1)`
/// stays within 0.002. Every span of the 500 x 500 figures is far shorter, so they
/// are the handout's to the bit.
pub const RUNNING_SUM_LIMIT: usize = 4096;

/// The handout's running sum: `current += step` once per pixel, in f32, for the
/// position, 1/z and the varying together. [`Steps`] walks lines and edges with it
/// and `DrawPolygonRows` walks rows with it.
#[derive(Clone, Copy, Debug)]
pub struct RunningSum<V> {
    current: Sum<V>,
    step: Sum<V>,
}

impl<V: Varying> RunningSum<V> {
    /// Starting at `a`, with the step `(b - a) / d`.
    #[inline]
    pub fn new(a: &Pixel<V>, b: &Pixel<V>, d: f32) -> Self {
        let (start, end) = (Sum::of(a), Sum::of(b));
        RunningSum {
            current: start,
            step: end.minus(&start).over(d),
        }
    }

    /// The current value, its position placed on a pixel by `place`.
    #[inline]
    pub fn value(&self, place: impl Fn(f32) -> i32) -> Pixel<V> {
        let c = &self.current;
        Pixel {
            x: place(c.xy.x),
            y: place(c.xy.y),
            zinv: c.zinv,
            varying: c.varying,
        }
    }

    /// The current 1/z and varying at pixel (x, y): for a walk that counts its
    /// positions in integers, as a row does.
    #[inline]
    pub fn at(&self, x: i32, y: i32) -> Pixel<V> {
        Pixel {
            x,
            y,
            zinv: self.current.zinv,
            varying: self.current.varying,
        }
    }

    #[inline]
    pub fn advance(&mut self) {
        let c = &mut self.current;
        c.xy += self.step.xy;
        c.zinv += self.step.zinv;
        c.varying = c.varying + self.step.varying;
    }
}

/// The values from `a` to `b` in `n` steps, computed exactly as the handout's
/// `Interpolate`: `step = (b - a) / max(n - 1, 1)` in f32, the [`RunningSum`], and
/// each position truncated toward zero, as C++'s float-to-int conversion does. It
/// yields without storing, so rows need no buffer. Spans longer than
/// [`RUNNING_SUM_LIMIT`] use the direct form instead.
#[derive(Clone, Debug)]
pub struct Steps<V> {
    sum: RunningSum<V>,
    /// For the direct form: the start, the whole change, and the last step's index.
    start: Sum<V>,
    span: Sum<V>,
    last: f32,
    i: usize,
    n: usize,
}

/// Everything `Interpolate` carries, as floats: x, y, zinv and the varying.
#[derive(Clone, Copy, Debug, Default)]
struct Sum<V> {
    xy: Vec2,
    zinv: f32,
    varying: V,
}

impl<V: Varying> Sum<V> {
    #[inline]
    fn of(p: &Pixel<V>) -> Self {
        Sum {
            xy: Vec2::new(p.x as f32, p.y as f32),
            zinv: p.zinv,
            varying: p.varying,
        }
    }

    #[inline]
    fn minus(&self, o: &Sum<V>) -> Self {
        Sum {
            xy: self.xy - o.xy,
            zinv: self.zinv - o.zinv,
            varying: self.varying - o.varying,
        }
    }

    #[inline]
    fn over(&self, d: f32) -> Self {
        Sum {
            xy: self.xy / d,
            zinv: self.zinv / d,
            varying: self.varying / d,
        }
    }
}

impl<V: Varying> Steps<V> {
    pub fn new(a: Pixel<V>, b: Pixel<V>, n: usize) -> Self {
        Steps::with_divisor(a, b, n, (n.max(2) - 1) as f32)
    }

    /// `n` values from `a` by steps of `(b - a) / d`: the handout's `d` is
    /// `n - 1`, so the last value is `b`; a student's `d = n` stops a step short.
    pub fn with_divisor(a: Pixel<V>, b: Pixel<V>, n: usize, d: f32) -> Self {
        let start = Sum::of(&a);
        Steps {
            sum: RunningSum::new(&a, &b, d),
            start,
            span: Sum::of(&b).minus(&start),
            last: d,
            i: 0,
            n,
        }
    }

    /// The next value, its position placed on a pixel by `place` (the handout
    /// truncates; `rasterlab check` also tries a student's rounding).
    #[inline]
    pub fn next_placed(&mut self, place: impl Fn(f32) -> i32) -> Option<Pixel<V>> {
        if self.i >= self.n {
            return None;
        }
        if self.n > RUNNING_SUM_LIMIT {
            let t = self.i as f32 / self.last;
            let c = &mut self.sum.current;
            c.xy = self.start.xy + self.span.xy * t;
            c.zinv = self.start.zinv + self.span.zinv * t;
            c.varying = self.start.varying + self.span.varying * t;
        }
        let p = self.sum.value(place);
        self.sum.advance();
        self.i += 1;
        Some(p)
    }

    /// Passes over the values before the `i`-th, still adding their steps, so
    /// that what follows is what walking them would have given.
    pub fn skip_to(&mut self, i: usize) {
        let i = i.min(self.n);
        if self.n > RUNNING_SUM_LIMIT {
            self.i = self.i.max(i);
        }
        while self.i < i {
            self.sum.advance();
            self.i += 1;
        }
    }
}

impl<V: Varying> Iterator for Steps<V> {
    type Item = Pixel<V>;

    /// The next value, each position truncated toward zero as C++'s float-to-int
    /// conversion does.
    #[inline]
    fn next(&mut self) -> Option<Pixel<V>> {
        self.next_placed(|v| v as i32)
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

/// How a quantity that is linear in 3D is interpolated across the screen.
///
/// Only 1/z, and q/z for any such q, is linear in the image (section 6.2), so the
/// perspective-correct way carries q/z and multiplies by z at the pixel. The affine
/// way carries q itself: linear on the screen, as section 6.1 interpolates the
/// illumination and as Figure 8 shows the mistake for the position. 1/z itself is
/// carried as it is either way, so depth and the visible surfaces do not change.
pub trait Interpolation: Copy + Default + Send + 'static {
    /// What is carried for a per-pixel struct `q` at a vertex whose 1/z is `zinv`.
    fn encode<V: Varying>(zinv: f32, q: V) -> V;
    /// The per-pixel struct at a pixel whose 1/z is `zinv`, from what was carried.
    fn decode<V: Varying>(zinv: f32, q: V) -> V;
}

/// Interpolate q/z; at the pixel q = (q/z) · z. What `pixel-light` does.
#[derive(Clone, Copy, Debug, Default)]
pub struct Perspective;

/// Interpolate q linearly in screen space: what `vertex-light` does (section 6.1),
/// and `pixel-light --affine` (Figure 8).
#[derive(Clone, Copy, Debug, Default)]
pub struct Affine;

impl Interpolation for Perspective {
    #[inline]
    fn encode<V: Varying>(zinv: f32, q: V) -> V {
        q * zinv
    }
    #[inline]
    fn decode<V: Varying>(zinv: f32, q: V) -> V {
        q * (1.0 / zinv)
    }
}

impl Interpolation for Affine {
    #[inline]
    fn encode<V: Varying>(_: f32, q: V) -> V {
        q
    }
    #[inline]
    fn decode<V: Varying>(_: f32, q: V) -> V {
        q
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn a_single_step_gives_the_start() {
        let mut r = [Pixel::at(0, 0); 1];
        interpolate(Pixel::at(3, 4), Pixel::at(9, 9), &mut r);
        assert_eq!(r, [Pixel::at(3, 4)]);
    }

    fn with(v: f32) -> Pixel<f32> {
        Pixel {
            x: 0,
            y: 0,
            zinv: 0.0,
            varying: v,
        }
    }

    #[test]
    fn the_running_sum_is_kept() {
        // Ten steps of 0.1 in f32 add up to 1.0000001, not 1: the handout's form
        // accumulates, and the last value shows it.
        let v: Vec<f32> = Steps::new(with(0.0), with(1.0), 11)
            .map(|p| p.varying)
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

    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    struct Two {
        a: f32,
        b: Vec3,
    }
    linear_ops!(Two { a, b });

    #[test]
    fn perspective_correction_recovers_any_struct_affine_does_not() {
        // q is linear in 3D from z = 1 to z = 3; half way across the screen 1/z is
        // (1 + 1/3) / 2 = 2/3, so z = 1.5 and the true q is a quarter of the way.
        let q0 = Two {
            a: 0.0,
            b: Vec3::ZERO,
        };
        let q1 = Two {
            a: 4.0,
            b: Vec3::splat(8.0),
        };
        let zinv = (1.0 + 1.0 / 3.0) / 2.0;
        let mid = |v0: Two, v1: Two| (v0 + v1) / 2.0;
        let v = mid(
            Perspective::encode(1.0, q0),
            Perspective::encode(1.0 / 3.0, q1),
        );
        let q = Perspective::decode(zinv, v);
        assert!(
            (q.a - 1.0).abs() < 1e-6 && q.b.abs_diff_eq(Vec3::splat(2.0), 1e-6),
            "{q:?}"
        );
        let v = mid(Affine::encode(1.0, q0), Affine::encode(1.0 / 3.0, q1));
        assert_eq!(
            Affine::decode(zinv, v),
            Two {
                a: 2.0,
                b: Vec3::splat(4.0)
            }
        );
    }
}
