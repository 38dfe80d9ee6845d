//! `rigidlab study accuracy`: what accuracy costs in time.
//!
//! Method of Erez, Tassa & Todorov (ICRA 2015), adapted to one engine:
//! - **error** against an exact solution where the level has one (its questions' textbook answers,
//!   the constant_acceleration closed form), otherwise against the engine's own f64 run at a very
//!   small step, on short pieces restarted from that reference so that chaos does not dominate
//!   ([`measure::self_consistency`]); plus energy and momentum drift where the level conserves them
//!   and the joints' anchor separation;
//! - **cost** as wall time of stepping per simulated second, timed one run at a time after all
//!   error runs are done (median of repeats);
//! - one knob varied at a time from the level's settings: dt, substeps, PGS iterations,
//!   precision (f32 / f64), effects (declared / all).
//!
//! `--engine rapier,box2d` sweeps each level on each engine that runs it (`accuracy/engines.rs`; a level an
//! engine refuses is listed with the feature it lacks).
//!
//! Output: `accuracy.csv`, one Pareto plot per level, `summary.md`; a sweep can be split into
//! shards (`--shard K/N`, [`shard`]) run anywhere and joined by `study merge` ([`merge`]).

mod engine_verdict;
mod engines;
mod jobs;
pub mod measure;
pub mod merge;
pub mod metrics;
mod output;
mod plan;
mod plot;
mod rows;
mod run;
pub mod shard;
mod summary;

pub use engines::parse_engine;
pub use output::*;
pub use plan::*;
pub use rows::*;
pub use run::*;

use crate::level::{self, CheckKind, Effect, PhysicsEngine, Scene};
use indicatif::{ProgressBar, ProgressStyle};
use measure::{Precision, Setting};
use rayon::prelude::*;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;
