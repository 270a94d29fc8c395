//! Rasterizers: from projected vertices to the pixels a point, a line or a
//! polygon covers, each with its interpolated depth and varying.
//!
//! A rasterizer is a strategy: the pipeline hands it projected (and clipped)
//! corners and gets pixels back, so a second way of covering pixels plugs in
//! beside the handout's without touching the stages. [`RowRaster`] is the
//! handout's (sections 3 and 4); [`EdgeRaster`] is exact (edge functions, pixel
//! centres, the top-left rule).

pub mod bresenham;
pub mod edge;
pub mod rows;

pub use edge::EdgeRaster;
pub use rows::RowRaster;
pub use rows::{LineWalk, Lines};

use super::clip::ScreenVertex;
use super::interpolate::{Nothing, Pixel, Varying};
use std::ops::Range;

/// The pixels a primitive may write: `x` in `0..width` and `y` in the target's
/// band of rows. The handout writes anywhere, which is undefined in C++; here a
/// pixel outside is skipped and rows outside are never stored.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Bounds {
    pub x: Range<i32>,
    pub y: Range<i32>,
}

impl Bounds {
    /// No limit: for printing rows of a polygon that is not on any screen.
    pub fn unbounded() -> Self {
        Bounds {
            x: i32::MIN..i32::MAX,
            y: i32::MIN..i32::MAX,
        }
    }

    #[inline]
    pub fn contains<V>(&self, p: &Pixel<V>) -> bool {
        self.x.contains(&p.x) && self.y.contains(&p.y)
    }
}

/// Where projected vertices land: the image's half size as the handout adds it
/// after truncating (`W/2`, `H/2` in integers), the image centre unrounded for the
/// exact rasterizer, and the pixels that may be written.
#[derive(Clone, Debug, PartialEq)]
pub struct Viewport {
    pub half_width: i32,
    pub half_height: i32,
    pub centre: (f32, f32),
    pub bounds: Bounds,
    /// How lines, and the rows rasterizer's polygon edges, are walked.
    pub lines: Lines,
}

/// A way of covering pixels, as a value the pipeline holds (the handout's and the
/// exact one are unit structs; `rasterlab check`'s carries a student's variants).
/// Its scratch buffers are kept by the caller from one primitive and one frame to
/// the next.
pub trait Rasterizer: Copy + Default + Send + 'static {
    type Scratch<V: Varying>: Default + Send;

    /// A projected point as one pixel, if it lands in the bounds.
    fn point<V: Varying>(
        &self,
        p: ScreenVertex<V>,
        viewport: &Viewport,
        plot: impl FnMut(Pixel<V>),
    );

    /// The pixels of the segment from `a` to `b`.
    fn line<V: Varying>(
        &self,
        a: ScreenVertex<V>,
        b: ScreenVertex<V>,
        viewport: &Viewport,
        plot: impl FnMut(Pixel<V>),
    );

    /// The pixels of a convex polygon, each once.
    fn polygon<V: Varying>(
        &self,
        scratch: &mut Self::Scratch<V>,
        corners: &[ScreenVertex<V>],
        viewport: &Viewport,
        plot: impl FnMut(Pixel<V>),
    );

    /// Where a projected position (from the screen's centre) lands for this
    /// rasterizer: the handout's truncated pixel, the exact rasterizer's point on
    /// its sub-pixel grid. The pipeline places each vertex of a mesh in full view
    /// once per frame, however many faces share it.
    type Place: Copy + Default + Send;
    fn place(&self, x: f32, y: f32, viewport: &Viewport) -> Self::Place;

    /// Makes room in `scratch` for a polygon `rows` rows tall, so that no later
    /// frame allocates, whichever band of rows it draws.
    fn reserve<V: Varying>(&self, scratch: &mut Self::Scratch<V>, rows: usize) {
        let _ = (scratch, rows);
    }

    /// Whether a triangle placed at `places` surely covers no pixel, so that
    /// the pipeline can pass it over before shading its vertices.
    fn misses(&self, places: [Self::Place; 3], viewport: &Viewport) -> bool;

    /// Whether a triangle placed at `places` surely covers no pixel in the
    /// image rows `rows`, so that a band of a frame drawn in bands passes over
    /// its neighbour's triangles before shading their vertices. Never, unless
    /// the rasterizer says: a triangle it draws is cut to the band's rows.
    fn misses_rows(&self, places: [Self::Place; 3], rows: &Range<i32>) -> bool {
        let _ = (places, rows);
        false
    }

    /// How the pipeline may place every vertex of a mesh in full view in the
    /// pass that projects them, once per frame for all bands: the built-in
    /// rasterizers' places are two `i32`s. None: each band places its own.
    const SHARED: Option<SharedPlacing> = None;

    /// Places made so ([`Rasterizer::SHARED`]) as this rasterizer's.
    fn shared_places(places: &[(i32, i32)]) -> Option<&[Self::Place]> {
        let _ = places;
        None
    }

    /// [`Rasterizer::polygon`] for a triangle whose corners are placed already.
    fn triangle<V: Varying>(
        &self,
        scratch: &mut Self::Scratch<V>,
        corners: [Placed<Self::Place, V>; 3],
        viewport: &Viewport,
        plot: impl FnMut(Pixel<V>),
    );
}

/// A built-in rasterizer's [`Rasterizer::place`], named so that the pass that
/// projects a frame's vertices can place them too.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SharedPlacing {
    Rows,
    Edge,
}

impl SharedPlacing {
    /// Every point of `screen` placed into `places`.
    pub fn place_all(
        self,
        screen: &[ScreenVertex<Nothing>],
        places: &mut [(i32, i32)],
        viewport: &Viewport,
    ) {
        // A loop each, so that the compiler takes several points at once.
        match self {
            SharedPlacing::Rows => place_each(RowRaster, screen, places, viewport),
            SharedPlacing::Edge => place_each(EdgeRaster, screen, places, viewport),
        }
    }
}

fn place_each<R: Rasterizer>(
    raster: R,
    screen: &[ScreenVertex<Nothing>],
    places: &mut [R::Place],
    viewport: &Viewport,
) {
    for (p, s) in places.iter_mut().zip(screen) {
        *p = raster.place(s.x, s.y, viewport);
    }
}

/// A corner as a rasterizer placed it ([`Rasterizer::place`]), with its 1/z and
/// what it carries.
#[derive(Clone, Copy, Debug, Default)]
pub struct Placed<P, V> {
    pub place: P,
    pub zinv: f32,
    pub varying: V,
}
