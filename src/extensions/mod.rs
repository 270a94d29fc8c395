//! What goes beyond the handout, kept outside [`crate::pipeline`], which section 6
//! says a richer image should not need to change: each extension works on what
//! the pipeline gives it. Depth of field is a post-process of a finished frame,
//! from its colour and 1/z buffers.
//!
//! (Textures, normal maps, parallax and shadows still live in the pipeline's
//! stages; issue #19 moves them here as stages that own their inputs.)

pub mod depth_of_field;
