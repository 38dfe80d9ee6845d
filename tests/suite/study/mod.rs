//! The studies: accuracy, stability and the advice for a failing level (src/study).

mod accuracy;
mod advice;
mod advice_names_gaps;
mod advice_reproducible;
mod domino_field;
mod engines;
mod other_engine;
mod sand_pile;
mod shards;
mod stability;
