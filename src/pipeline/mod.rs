//! The rasterization pipeline of the handout's section 6, for any mesh:
//!
//! ```text
//! mesh -> vertex shader -> camera (eq. 8) -> near-plane clip -> projection (eq. 3, 4)
//!      -> rasterizer (the handout's rows) -> interpolation of the stage's per-pixel struct
//!      -> depth test -> pixel shader -> render target
//! ```
//!
//! - [`mesh`]: the input, vertices and faces with materials.
//! - [`stage`]: the six stages, each a vertex shader, a pixel shader and the struct
//!   between them; [`light`]: eq. 10 and 11, which the lit stages share.
//! - [`camera`]: world to camera (eq. 8) and the projection (eq. 3, 4).
//! - [`clip`]: the near plane and the screen's guard band, which the handout leaves out.
//! - [`raster`]: rasterizers; [`raster::rows`] is the handout's `Interpolate`,
//!   `ComputePolygonRows` and `DrawPolygonRows`.
//! - [`interpolate`](mod@interpolate): `Interpolate` for any per-pixel struct, and
//!   perspective-correct or affine interpolation.
//! - [`target`]: colour and depth buffers over a band of rows, and 8-bit packing.
//! - [`vertices`]: each vertex of the mesh taken to camera space and projected
//!   once per frame, whichever faces share it.
//! - [`draw`]: the handout's `Draw` and `DrawPolygon`, which joins them;
//!   [`bands`]: the faces in groups, for a frame drawn in bands of rows.
//!
//! This layer uses nothing of the crate outside it: only glam and std.

pub mod bands;
pub mod camera;
pub mod clip;
pub mod draw;
pub mod interpolate;
pub mod light;
pub mod mesh;
pub mod raster;
pub mod stage;
pub mod target;
pub mod vertices;

pub use camera::Camera;
pub use draw::{Cull, Pipeline, Stats};
pub use interpolate::{interpolate, Affine, Interpolation, Nothing, Perspective, Pixel, Varying};
pub use light::Light;
pub use mesh::{Face, Material, Mesh, Triangle, Vertex};
pub use raster::RowRaster;
pub use stage::{
    Depth, Filled, Lighting, PixelLight, Points, Primitive, Stage, StageName, Surface, VertexLight,
    Wireframe,
};
pub use target::{Frame, Target};

/// The unit tests' random numbers: an xorshift generator, the same every run.
#[cfg(test)]
fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    }
}
