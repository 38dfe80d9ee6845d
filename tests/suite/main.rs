//! rigidlab's integration tests: one test binary (`cargo test --release --test suite`), a module
//! for each stage of the data flow (level -> sim -> analysis -> questions/checks -> runner/CLI
//! -> study), the editor, the Bevy app, and the docs. One binary links the crate and Bevy once,
//! where a file per test linked them ~85 times. Run one topic with a name filter:
//! `cargo test --release --test suite -- sim::springs`. Where a new test goes: CONTRIBUTING.md.
//!
//! The tests of every module run in parallel threads of this one process: a test must not
//! change the process's state (environment variables, the current directory, a global) nor time
//! itself against the others. Helpers are in `common` (`use crate::common;`).

mod common;

mod analysis;
#[cfg(feature = "app")]
mod app;
mod checks;
mod docs;
mod editor;
mod level;
mod questions;
mod runner;
mod sim;
mod study;
