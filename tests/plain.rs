//! The plain step programs of steps/: `steps` holds them equal to the core, and
//! `check` draws with them what a student's lab draws. Each has a `main` the tests
//! do not call.
#![allow(dead_code)]

#[path = "../steps/5-depth.rs"]
pub mod depth;
#[path = "../steps/4-filled.rs"]
pub mod filled;
#[path = "../steps/7-pixel-light.rs"]
pub mod pixel_light;
#[path = "../steps/2-points.rs"]
pub mod points;
#[path = "../steps/6-vertex-light.rs"]
pub mod vertex_light;
#[path = "../steps/3-wireframe.rs"]
pub mod wireframe;
