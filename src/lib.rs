//! rasterlab: the DH2323 lab 3 "Rasterization" handout as a small Rust library.
//!
//! Five layers, each using only the ones before it:
//!
//! - [`pipeline`]: the rasterizer of the handout's section 6 for any mesh (camera,
//!   clipping, rasterizers, interpolation, stages, light, render targets). It
//!   depends on glam alone.
//! - [`extensions`]: what goes beyond the handout on top of the pipeline, without
//!   changing it: smooth normals, textures, normal maps and parallax, shadows,
//!   depth of field; each a stage, a light or a post-process.
//! - [`scene`]: what builds meshes: the handout's Cornell box (and its
//!   subdivisions), procedural scenes (a sphere, a floor grid) and OBJ models read
//!   with tobj, chosen by a `--scene` spec; it also frames a scene other than the
//!   box for the camera and the light.
//! - [`measure`]: the ray-traced reference, error metrics, timing, the plot and
//!   `rasterlab check` (a student's screenshot or rows printout explained).
//! - [`app`]: the command line's work: [`Figure`], the one place that turns a
//!   stage's name and options into a pipeline with its extensions, image files,
//!   Figure 1, `rasterlab report` and `rasterlab stress`, and the viewer.
//!
//! `docs/handout-map.md` maps each handout function to the item that implements it.

pub mod app;
pub mod extensions;
pub mod measure;
pub mod pipeline;
pub mod scene;

pub use app::figure::Figure;
pub use pipeline::{interpolate, Camera, Frame, Light, Mesh, Pixel, StageName, Triangle};
pub use scene::cornell_box;
