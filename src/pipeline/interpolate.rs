//! The handout's `Interpolate` (section 3), for any per-pixel struct, and the two
//! ways of interpolating a quantity across the screen (section 6.2).
//!
//! A [`Pixel`] is the handout's struct: an integer position, the zinv value of
//! section 5 and whatever the stage needs at every pixel (its [`Varying`]: nothing,
//! an illumination, a 3D position). The handout grows its `Pixel` by hand each
//! section; here the stage names the struct and the same code interpolates it.

use glam::Vec2;
use std::iter::Take;
use std::ops::{Add, Div, Mul, Range, Sub};

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

/// `value + step + step + ...`, `n` additions in f32, bit for bit what adding one
/// step at a time gives, in a few additions for each power of two the sum passes
/// through. Between two powers of two every f32 is a multiple of the same unit,
/// so each addition adds `step` rounded to that unit: the same amount every time
/// (a tie rounds to an even multiple, and an even sum stays even), which two
/// additions in a row confirm before the sum jumps to where that power ends.
pub fn add_n_times(mut value: f32, step: f32, mut n: usize) -> f32 {
    while n > 0 {
        if !value.is_finite() {
            return value + step; // infinite or NaN after one more addition, for good
        }
        let next = value + step;
        // Sterbenz: with |step| <= |value| / 2 both differences are exact.
        if value.is_normal() && step.abs() <= value.abs() / 2.0 && n > 1 {
            let added = next - value;
            if added == 0.0 {
                return value; // the step is lost in the rounding, every time
            }
            if next + step - next == added {
                let jumps = jumps_within_binade(value, added).min(n);
                if jumps > 0 {
                    // A multiple of the unit inside the power of two: exact.
                    value = (value as f64 + jumps as f64 * added as f64) as f32;
                    n -= jumps;
                    continue;
                }
            }
        }
        value = next;
        n -= 1;
    }
    value
}

/// How many times `added` can be added to `value` with every sum at least a unit
/// inside the power of two `value` lies in (`value` normal, `added` a multiple
/// of its unit); the sums need no rounding there.
fn jumps_within_binade(value: f32, added: f32) -> usize {
    let magnitude = value.abs() as f64;
    let exponent = ((value.to_bits() >> 23) & 0xff) as i32 - 127;
    let (low, unit) = (2f64.powi(exponent), 2f64.powi(exponent - 23));
    let room = if (added > 0.0) == (value > 0.0) {
        (2.0 * low - unit) - magnitude
    } else {
        magnitude - (low + unit)
    };
    // Exact operands, and a quotient never within rounding of the next integer.
    (room / added.abs() as f64).floor().max(0.0) as usize
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
        if size_of::<V>() == 0 && self.i < i {
            // Only x, y and 1/z are summed: each one's additions, all at once.
            let (c, step, n) = (&mut self.sum.current, &self.sum.step, i - self.i);
            c.xy.x = add_n_times(c.xy.x, step.xy.x, n);
            c.xy.y = add_n_times(c.xy.y, step.xy.y, n);
            c.zinv = add_n_times(c.zinv, step.zinv, n);
            self.i = i;
        }
        while self.i < i {
            self.sum.advance();
            self.i += 1;
        }
    }
}

impl<V: Varying> Steps<V> {
    /// The values whose row (y truncated) is in `rows`. y moves one way along a
    /// walk, so they follow each other: those before are passed over
    /// ([`Steps::skip_to`]) and the walk ends where y leaves the rows.
    pub fn within_rows(mut self, rows: Range<i32>) -> Take<Steps<V>> {
        let (here, n) = (self.i, self.n);
        let rising = match n > RUNNING_SUM_LIMIT {
            true => self.span.xy.y,
            false => self.sum.step.xy.y,
        };
        let (from, to) = if rising >= 0.0 {
            let first = self.first_index(rows.start, |y| y >= rows.start);
            (first, self.first_index(rows.end, |y| y >= rows.end))
        } else {
            let first = self.first_index(rows.end.saturating_sub(1), |y| y < rows.end);
            (
                first,
                self.first_index(rows.start.saturating_sub(1), |y| y < rows.start),
            )
        };
        let to = to.max(from);
        self.skip_to(from);
        debug_assert!(here <= from && to <= n);
        self.take(to - from)
    }

    /// The row of the `i`-th value (`i` not before the next one).
    fn row_at(&self, i: usize) -> i32 {
        if self.n > RUNNING_SUM_LIMIT {
            let t = i as f32 / self.last;
            return (self.start.xy.y + self.span.xy.y * t) as i32;
        }
        let c = &self.sum;
        add_n_times(c.current.xy.y, c.step.xy.y, i - self.i) as i32
    }

    /// The first index from the next value's on whose row `reached` holds, or
    /// the end: `reached` holds from some value on. Looked for from where a
    /// straight line would reach row `target`, doubling the stride outward,
    /// then halving it.
    fn first_index(&self, target: i32, reached: impl Fn(i32) -> bool) -> usize {
        let (lo, hi) = (self.i, self.n);
        if lo >= hi {
            return hi;
        }
        let reached = |i: usize| reached(self.row_at(i));
        // The direct form counts from the first value, the running sum from here.
        let (base, y, per_step) = match self.n > RUNNING_SUM_LIMIT {
            true => (0, self.start.xy.y, self.span.xy.y / self.last),
            false => (lo, self.sum.current.xy.y, self.sum.step.xy.y),
        };
        let steps = ((target as f64 - y as f64) / per_step as f64).ceil();
        let guess = match steps.is_finite() {
            true => base.saturating_add_signed(steps.clamp(-1e9, 1e9) as isize),
            false => lo,
        };
        let guess = guess.clamp(lo, hi - 1);
        // The answer lies in low..=high.
        let (mut low, mut high);
        let mut stride = 1;
        if reached(guess) {
            high = guess;
            loop {
                if high - lo < stride {
                    low = lo;
                    break;
                }
                if !reached(high - stride) {
                    low = high - stride + 1;
                    break;
                }
                high -= stride;
                stride *= 2;
            }
        } else {
            low = guess + 1;
            loop {
                let probe = low + stride - 1;
                if probe >= hi {
                    high = hi;
                    break;
                }
                if reached(probe) {
                    high = probe;
                    break;
                }
                low = probe + 1;
                stride *= 2;
            }
        }
        while low < high {
            let mid = low + (high - low) / 2;
            if reached(mid) {
                high = mid;
            } else {
                low = mid + 1;
            }
        }
        low
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
    /// What a pixel that passed the depth test keeps until it is shaded in a
    /// batch: the carried struct, with its 1/z only if `decode` reads it, so
    /// that the shading loop loads nothing it does not use (an unread 1/z
    /// beside each q kept the affine loop from vectorising well).
    type Kept<V: Varying>: Copy + Default + Send;
    /// What is carried for a per-pixel struct `q` at a vertex whose 1/z is `zinv`.
    fn encode<V: Varying>(zinv: f32, q: V) -> V;
    /// The per-pixel struct at a pixel whose 1/z is `zinv`, from what was carried.
    fn decode<V: Varying>(zinv: f32, q: V) -> V;
    /// What a pixel whose 1/z is `zinv` and carried struct `q` keeps.
    fn keep<V: Varying>(zinv: f32, q: V) -> Self::Kept<V>;
    /// The per-pixel struct of a kept pixel, as `decode` gives it.
    fn decode_kept<V: Varying>(kept: Self::Kept<V>) -> V;
}

/// Interpolate q/z; at the pixel q = (q/z) · z. What `pixel-light` does.
#[derive(Clone, Copy, Debug, Default)]
pub struct Perspective;

/// Interpolate q linearly in screen space: what `vertex-light` does (section 6.1),
/// and `pixel-light --affine` (Figure 8).
#[derive(Clone, Copy, Debug, Default)]
pub struct Affine;

impl Interpolation for Perspective {
    type Kept<V: Varying> = (f32, V);
    #[inline]
    fn encode<V: Varying>(zinv: f32, q: V) -> V {
        q * zinv
    }
    #[inline]
    fn decode<V: Varying>(zinv: f32, q: V) -> V {
        q * (1.0 / zinv)
    }
    #[inline]
    fn keep<V: Varying>(zinv: f32, q: V) -> (f32, V) {
        (zinv, q)
    }
    #[inline]
    fn decode_kept<V: Varying>((zinv, q): (f32, V)) -> V {
        Self::decode(zinv, q)
    }
}

impl Interpolation for Affine {
    type Kept<V: Varying> = V;
    #[inline]
    fn encode<V: Varying>(_: f32, q: V) -> V {
        q
    }
    #[inline]
    fn decode<V: Varying>(_: f32, q: V) -> V {
        q
    }
    #[inline]
    fn keep<V: Varying>(_: f32, q: V) -> V {
        q
    }
    #[inline]
    fn decode_kept<V: Varying>(q: V) -> V {
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

    /// What [`add_n_times`] must equal: one addition at a time.
    fn one_at_a_time(mut value: f32, step: f32, n: usize) -> f32 {
        for _ in 0..n {
            value += step;
        }
        value
    }

    fn same(a: f32, b: f32) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    #[test]
    fn adding_n_times_crosses_powers_of_two_and_zero_as_adding_does() {
        // A third of a pixel from row 0 to 1500 crosses eleven powers of two;
        // 0.5 on odd starts is a tie at every power above 2^23; a step of
        // -0.7 from 3 crosses zero; 1e-9 on 1 is lost in the rounding.
        let cases = [
            (0.0, 1.0 / 3.0, 4500),
            (-1500.0, 1.0 / 3.0, 4096),
            (8_388_609.0, 0.5, 4000),
            (16_777_215.0, 1.5, 4000),
            (3.0, -0.7, 40),
            (1.0, 1e-9, 4096),
            (0.0, f32::from_bits(1), 4096),
            (f32::MAX, f32::MAX / 4.0, 3),
            (1.0, f32::NAN, 2),
        ];
        for (value, step, n) in cases {
            for k in [0, 1, 2, 3, n / 3, n - 1, n] {
                let (got, want) = (add_n_times(value, step, k), one_at_a_time(value, step, k));
                assert!(same(got, want), "{value} + {step} x {k}: {got} != {want}");
            }
        }
    }

    fn value() -> impl Strategy<Value = f32> {
        prop_oneof![
            3 => (-8192i32..8192).prop_map(|v| v as f32),
            2 => -1e4f32..1e4,
            1 => -1e-3f32..1e-3,
            1 => 0.0f32..1.0,
            1 => any::<f32>(),
        ]
    }

    fn step() -> impl Strategy<Value = f32> {
        prop_oneof![
            // The handout's steps: a whole change over a whole number of steps.
            4 => (-8192i32..8192, 1i32..4096).prop_map(|(d, n)| d as f32 / n as f32),
            // Ties: a few bits at a power of two.
            2 => (-64i32..64, 0i32..30).prop_map(|(k, e)| k as f32 * 2f32.powi(-e)),
            2 => -10f32..10.0,
            1 => -1e-6f32..1e-6,
            1 => any::<f32>(),
        ]
    }

    fn line_end() -> impl Strategy<Value = Pixel<Nothing>> {
        (-6000i32..6000, -6000i32..6000, 0.0f32..1.0).prop_map(|(x, y, zinv)| Pixel {
            zinv,
            ..Pixel::at(x, y)
        })
    }

    use proptest::prelude::*;

    proptest! {
        #[test]
        fn adding_n_times_is_adding_one_at_a_time(
            value in value(), step in step(), n in 0usize..5000
        ) {
            let (got, want) = (add_n_times(value, step, n), one_at_a_time(value, step, n));
            prop_assert!(same(got, want), "{} + {} x {}: {} != {}", value, step, n, got, want);
        }

        #[test]
        fn a_walk_within_rows_gives_the_walks_values_in_those_rows(
            a in line_end(),
            b in line_end(),
            start in -6100i32..6100,
            rows in 0i32..3000,
            short in prop::bool::ANY,
        ) {
            // Short lines (the running sum) and long ones (the direct form).
            let b = match short {
                true => Pixel { x: a.x + b.x / 8, y: a.y + b.y / 8, ..b },
                false => b,
            };
            let rows = start..start + rows;
            let n = line_pixels(&a, &b);
            let all = Steps::new(a, b, n).filter(|p| rows.contains(&p.y));
            let within = Steps::new(a, b, n).within_rows(rows.clone());
            prop_assert_eq!(within.collect::<Vec<_>>(), all.collect::<Vec<_>>());
            // A varying with fields is walked, not skipped: the same values.
            let with = |p: Pixel<Nothing>| Pixel { varying: p.zinv * 3.0, x: p.x, y: p.y, zinv: p.zinv };
            let all = Steps::new(with(a), with(b), n).filter(|p| rows.contains(&p.y));
            let within = Steps::new(with(a), with(b), n).within_rows(rows.clone());
            prop_assert_eq!(within.collect::<Vec<_>>(), all.collect::<Vec<_>>());
        }
    }
}
