//! Level files: parsing, validation and its errors, geometry, fuzzing of the parser (src/level).

mod bad_input;
mod challenges;
mod curved_geometry;
mod f32_increments;
mod fuzz;
mod hints;
mod joint_anchors;
mod parameters;
mod quantity_forms;
mod sign_conventions;
mod tracks;
mod validation_scale;
