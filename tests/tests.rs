//! Every test of grinlight outside its modules: one binary (one link, one run), each file
//! a module named for what it tests. `cargo test --release` runs them all; `cargo test
//! --release --test tests docs::` runs one file's.

mod common;

mod birefringence;
mod black_hole_exact;
mod bsdf;
mod cli;
mod docs;
mod error_estimate;
mod exact_arc;
mod fiber;
mod fluorescence;
mod footprint;
mod furnace;
mod glossy;
mod hostile;
mod import;
mod import_pbrt;
mod integrators;
mod linearize;
mod luminaire;
mod media;
mod photon_map;
mod plane;
mod ply;
mod polarization;
mod polarized_plastic;
mod radiometry;
mod render;
mod repository;
mod safety;
mod sampling;
mod scene;
mod shapes;
mod shard;
mod spectral;
mod validation;
mod vdb;
mod volume;
