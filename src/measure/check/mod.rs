//! `rasterlab check`: what a student's screenshot or rows printout shows, and what
//! was done differently from the handout to get it (issue #14).
//!
//! - [`walk`]: the known ways of walking an edge (the handout's `Interpolate` and
//!   its variants).
//! - [`rows`]: `check rows`, a printed `ComputePolygonRows` against ours.
//! - [`student`]: the variants built on the core (a rasterizer, and stages that
//!   measure a pixel's surface and direct light).
//! - [`image`]: `check IMAGE`'s hypotheses, what each draws, its errors and
//!   where they are; [`fit`]: P and N, the variants and the light fitted, and
//!   [`check_image`], the whole check; [`report`]: its words and JSON.

pub mod fit;
pub mod image;
pub mod locate;
pub mod pose;
pub mod probe;
pub mod report;
pub mod rows;
pub mod student;
pub mod walk;

pub use fit::check_image;
