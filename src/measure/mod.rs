//! Measuring tools: the ray-traced reference, error metrics, timing, the report
//! and its plot, and the catalogue of hard cases. They use the pipeline and the
//! scenes; [`figure`] names the stages and figures they measure.

pub mod bvh;
pub mod check;
pub mod figure;
pub mod heat;
pub mod metrics;
pub mod plot;
pub mod raytrace;
pub mod report;
pub mod stress;
pub mod timing;
