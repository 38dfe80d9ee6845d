//! The docs and the architecture agree with the tree: ARCHITECTURE.md's file list, the equation
//! key, the data flow between stage folders.

mod app_import_rule;
mod architecture_doc;
mod equation_key;
mod source_scan;
mod stage_layers;
