//! Every integration test in one binary, so that the pipeline and its stages are
//! compiled and linked once, not once per file (the set-up time README.md gives).
//! Each module is the file of its name; `cargo test --release --test suite steps::`
//! runs one. `viewer.rs` needs a display and stays a binary of its own.

mod allocations;
mod benched;
mod check;
mod cli;
mod common;
mod depth_of_field;
mod doc_commands;
mod edge_raster;
mod figures;
mod fuzz;
mod handout_text;
mod hostile;
mod normal_maps;
mod output;
mod parallel;
mod plain;
mod properties;
mod quoted;
mod reference;
mod scenes;
mod shadows;
mod stability;
mod stages;
mod steps;
mod textures;
