//! What goes beyond the handout, kept outside [`crate::pipeline`], which section 6
//! says a richer image should not need to change: each extension is a stage (a
//! vertex and a pixel shader with the per-pixel struct between them) that owns
//! what it reads, a light a lit stage can be drawn with, or a post-process of a
//! finished frame. Adding or removing one touches no file of the pipeline.
//!
//! - [`smooth`]: light per pixel with normals interpolated from the vertices'.
//! - [`texture`]: images read at (u, v) coordinates, and the maps a mesh's
//!   materials read beside their colours; [`textured`]: the lit stages with ρ
//!   from a texture.
//! - [`normal_map`]: normals tilted per pixel by a map in each face's tangent
//!   frame, and parallax from a height map.
//! - [`shadow`]: a cube shadow map from the point light, and the light through it.
//! - [`depth_of_field`]: a thin-lens blur of a finished frame from its 1/z.

pub mod depth_of_field;
pub mod normal_map;
pub mod shadow;
pub mod smooth;
pub mod texture;
pub mod textured;
