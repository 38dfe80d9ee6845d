//! The textbook formulas and the frame, window and linkage analyses (src/analysis).

mod formulas;
mod frame;
mod general_periods;
mod links;
mod reference;
mod small_oscillations;
mod textbook;
mod windows;
