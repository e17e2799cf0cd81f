//! The integration tests of this package, one test binary (one link instead of one per
//! file: a clean `cargo test --workspace` fits the CI machine's disk). Each file of this
//! directory is a module; run one with `cargo test --test integration FILE::`.

mod csv;
mod figure;
mod figure_palette;
mod figure_pdf_colorbar;
mod figure_text;
mod interrupt;
mod json_scenes;
mod modes_vs_dynamics;
mod scene;
mod scene_arrays;
mod scene_clusters;
mod scene_dynamics;
mod scene_fuzz;
mod scene_mutations;
mod scene_strict;
mod scene_supports;
mod vtk;
