//! Measuring tools: the ray-traced reference, error metrics, timing, the plot and
//! the checker of students' images and printouts. They use the pipeline, the
//! scenes and the extensions' inputs; the report and the catalogue of hard cases
//! that use them are commands of the application.

pub mod bvh;
pub mod check;
pub mod heat;
pub mod metrics;
pub mod plot;
pub mod raytrace;
pub mod timing;
