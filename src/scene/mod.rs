//! What builds meshes for the pipeline: the handout's Cornell box and its
//! subdivisions.

pub mod cornell;

pub use cornell::{cornell_box, subdivide};
