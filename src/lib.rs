//! rigidlab: a 2D rigid-body sandbox that checks rapier2d against the engineering-dynamics textbook.
//!
//! Data flows one way, a module per stage:
//! `level` (file -> validated scene) -> `sim` (rapier world with only the declared
//! effects -> per-step [`snapshot::Snapshot`]) -> `analysis` (textbook quantities,
//! pure functions) -> `checks` (theory against engine, every step) and `questions` (the
//! exercise's answers, read at their moment) -> `report` (table, JSON, CSV).
//! `runner` drives one level through all stages headless; the Bevy sandbox (`app`,
//! behind the `app` feature) is a thin shell over the same core.

/// `eprintln!` that cannot panic: where stderr cannot take a message (`2>/dev/full`) it is
/// dropped, and the exit code still says what happened (`eprintln!` would exit 101).
macro_rules! stderr {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        // Escaped for the terminal: a level's names are part of many messages.
        let _ = writeln!(
            std::io::stderr(),
            "{}",
            $crate::terminal::text(&format!($($arg)*))
        );
    }};
}

pub mod analysis;
pub mod checks;
pub mod cli;
pub mod clock;
pub mod editor;
pub mod files;
pub mod level;
pub mod questions;
pub mod report;
pub mod runner;
pub mod sim;
pub mod simulation;
pub mod snapshot;
pub mod study;
pub mod terminal;

/// The simulation stage compiled against rapier2d-f64 (same source as `sim`).
// Loading `sim`'s files a second time is the point (duplicate_mod). The shared source converts
// between f64 and rapier's real with `as`, which widens or narrows in `sim` (f32) and is the
// identity here; `sim` is still linted for casts that do nothing (unnecessary_cast).
#[allow(clippy::duplicate_mod, clippy::unnecessary_cast)]
#[path = "sim"]
pub mod sim64 {
    pub(crate) use rapier2d_f64 as rapier;
    pub(crate) const PRECISION: crate::sim::Precision = crate::sim::Precision::F64;
    mod arc_contacts;
    mod arc_curvature;
    mod arc_split;
    mod arc_track;
    mod build;
    mod contact_points;
    mod coupling_tension;
    mod couplings;
    mod impacts;
    mod interventions;
    mod joint_sums;
    pub mod joints;
    mod probes;
    mod profiles;
    mod readings;
    mod setup;
    mod step;
    mod track_shape;
    mod welds;
    mod world;
    pub use world::Simulation;
}

#[cfg(feature = "app")]
pub mod app;
