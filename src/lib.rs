//! rasterlab: the DH2323 lab 3 "Rasterization" handout as a small Rust library.
//!
//! One core draws every stage of the handout. The pieces follow the pipeline of
//! its section 6, one file each:
//!
//! - [`scene`]: the test model (the Cornell box) as triangles.
//! - [`camera`]: world to camera (eq. 8) and the truncating projection (eq. 3, 4).
//! - [`interpolate`](mod@interpolate): the handout's `Interpolate`, generic over what a pixel carries.
//! - [`polygon`]: lines, `ComputePolygonRows` and `DrawPolygonRows`.
//! - [`stage`]: what each handout stage interpolates and shades.
//! - [`light`]: equations 10 and 11.
//! - [`clip`]: the near plane and the screen's guard band, which the handout leaves out.
//! - [`render`]: the handout's `Draw`: vertex shader, clipping, rasterization, depth
//!   test, pixel shader.
//! - [`image_io`], [`overview`], [`timing`], [`parse`]: writing PNGs, Figure 1, `--time`, arguments.
//!
//! Around the core:
//! - [`controls`], [`viewer`]: `rasterlab view`, the handout's `Update` loop in a window.
//! - [`raytrace`], [`metrics`], [`report`], [`plot`]: the ray-traced reference, error
//!   measures, and `rasterlab report`'s table and plot.
//! - [`stress`]: `rasterlab stress`, the hard cases.
//! - [`app`]: what each subcommand does.
//!
//! `docs/handout-map.md` maps each handout function to the item that implements it.

pub mod app;
pub mod camera;
pub mod clip;
pub mod controls;
pub mod image_io;
pub mod interpolate;
pub mod light;
pub mod metrics;
pub mod overview;
pub mod parse;
pub mod plot;
pub mod polygon;
pub mod raytrace;
pub mod render;
pub mod report;
pub mod scene;
pub mod stage;
pub mod stress;
pub mod timing;
pub mod viewer;

pub use camera::Camera;
pub use interpolate::{interpolate, Pixel, Varying};
pub use light::Light;
pub use render::{Frame, Rasterizer};
pub use scene::{cornell_box, Triangle};
pub use stage::{StageName, View};
