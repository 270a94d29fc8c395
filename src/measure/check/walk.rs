//! The ways students walk an edge that leave a trace in the rows: `Interpolate`
//! rounding instead of truncating, an edge sampled at |dy| + 1 points instead of
//! max(|dx|, |dy|) + 1, steps of (b - a) / N instead of (b - a) / (N - 1). The
//! handout's walk is the core's `Steps`; these are the same running sum with one
//! of its choices made differently. Each is a `LineWalk`, so the core's one
//! `ComputePolygonRows` (`compute_polygon_rows_by`) walks the edges with any of them.

use crate::pipeline::interpolate::{Pixel, Steps, Varying};
use crate::pipeline::raster::LineWalk;

/// How an edge or line is walked. The default is the handout's.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Walk {
    /// Positions rounded to the nearest pixel (halves away from zero, C++'s
    /// `round`) instead of truncated toward zero.
    pub rounding: bool,
    /// |dy| + 1 samples per edge: one per row, which leaves gaps on shallow edges.
    pub dy_sampling: bool,
    /// A step of (b - a) / N, so the walk stops one step short of `b`.
    pub step_over_n: bool,
}

impl Walk {
    /// The number of pixels the walk puts on the segment from `a` to `b`.
    pub fn samples<V>(self, a: &Pixel<V>, b: &Pixel<V>) -> usize {
        let dx = (a.x as i64 - b.x as i64).unsigned_abs();
        let dy = (a.y as i64 - b.y as i64).unsigned_abs();
        let n = if self.dy_sampling { dy } else { dx.max(dy) };
        n as usize + 1
    }

    /// The pixels from `a` to `b` as this walk gives them: the core's running
    /// sum (`Steps`) with this walk's count, step and placement.
    pub fn pixels<V: Varying>(self, a: Pixel<V>, b: Pixel<V>) -> impl Iterator<Item = Pixel<V>> {
        let n = self.samples(&a, &b);
        let d = if self.step_over_n {
            n as f32
        } else {
            (n.max(2) - 1) as f32
        };
        let mut steps = Steps::with_divisor(a, b, n, d);
        let rounding = self.rounding;
        std::iter::from_fn(move || {
            steps.next_placed(|v| if rounding { v.round() as i32 } else { v as i32 })
        })
    }

    /// The names of what differs from the handout's walk, as the checker reports them.
    pub fn names(self) -> Vec<&'static str> {
        let mut names = Vec::new();
        if self.rounding {
            names.push("rounding");
        }
        if self.dy_sampling {
            names.push("dy-sampling");
        }
        if self.step_over_n {
            names.push("step-over-n");
        }
        names
    }

    /// Every walk, the handout's first, then one change, then two, then all three.
    pub fn all() -> Vec<Walk> {
        let mut all: Vec<Walk> = (0..8u8)
            .map(|bits| Walk {
                rounding: bits & 1 != 0,
                dy_sampling: bits & 2 != 0,
                step_over_n: bits & 4 != 0,
            })
            .collect();
        all.sort_by_key(|w| w.names().len());
        all
    }
}

/// A student's walk plugs into the core's `ComputePolygonRows`
/// (`raster::rows::compute_polygon_rows_by`): no student's variant is part of the
/// pipeline, and there is one `ComputePolygonRows`.
impl LineWalk for Walk {
    fn walk<V: Varying>(&self, a: Pixel<V>, b: Pixel<V>, f: impl FnMut(Pixel<V>)) {
        self.pixels(a, b).for_each(f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::interpolate::line_pixels;

    #[test]
    fn the_default_walk_is_the_cores() {
        let cases = [
            ((0, 0), (7, 3)),
            ((4, 2), (1, 8)),
            ((-5, 9), (6, -4)),
            ((2, 2), (2, 2)),
        ];
        for ((ax, ay), (bx, by)) in cases {
            let (a, b) = (Pixel::at(ax, ay), Pixel::at(bx, by));
            let ours: Vec<_> = Walk::default().pixels(a, b).collect();
            let core: Vec<_> = Steps::new(a, b, line_pixels(&a, &b)).collect();
            assert_eq!(ours, core);
        }
    }

    #[test]
    fn the_default_walks_rows_are_the_cores() {
        use crate::pipeline::raster::rows::{compute_polygon_rows, compute_polygon_rows_by, Rows};
        use crate::pipeline::raster::Bounds;
        let polygons: [&[(i32, i32)]; 4] = [
            &[(10, 5), (5, 10), (15, 15)],
            &[(3, 2), (40, 9), (17, 31)],
            &[(50, 3), (2, 20), (31, 44), (61, 30)],
            &[(-20, -5), (30, 8), (4, 60)],
        ];
        for vertices in polygons {
            let v: Vec<_> = vertices.iter().map(|&(x, y)| Pixel::at(x, y)).collect();
            for bounds in [Bounds::unbounded(), Bounds { x: 0..40, y: 0..25 }] {
                let (mut core, mut ours) = (Rows::new(), Rows::new());
                compute_polygon_rows(&v, &bounds, &mut core);
                compute_polygon_rows_by(&Walk::default(), &v, &bounds, &mut ours);
                assert_eq!(core.top, ours.top);
                assert_eq!((core.left, core.right), (ours.left, ours.right));
            }
        }
    }

    #[test]
    fn each_change_moves_the_pixels_it_should() {
        let (a, b) = (Pixel::at(0, 0), Pixel::at(3, 2));
        let xy = |w: Walk| -> Vec<(i32, i32)> { w.pixels(a, b).map(|p| (p.x, p.y)).collect() };
        // Steps of (1, 2/3): y is 0, 0.67, 1.33, 2.
        assert_eq!(xy(Walk::default()), [(0, 0), (1, 0), (2, 1), (3, 2)]);
        let rounding = Walk {
            rounding: true,
            ..Walk::default()
        };
        assert_eq!(xy(rounding), [(0, 0), (1, 1), (2, 1), (3, 2)]);
        let dy = Walk {
            dy_sampling: true,
            ..Walk::default()
        };
        assert_eq!(xy(dy), [(0, 0), (1, 1), (3, 2)]);
        let over_n = Walk {
            step_over_n: true,
            ..Walk::default()
        };
        // Steps of (3/4, 1/2): x is 0, 0.75, 1.5, 2.25.
        assert_eq!(xy(over_n), [(0, 0), (0, 0), (1, 1), (2, 1)]);
        assert_eq!(Walk::all().len(), 8);
        assert_eq!(Walk::all()[0], Walk::default());
    }
}
