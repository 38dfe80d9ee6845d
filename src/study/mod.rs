//! Studies over many runs: what accuracy costs in time, and whether hard cases stay stable.

pub mod accuracy;
pub mod advice;
pub mod gaps;
pub mod other_engine;
pub mod stability;

use clap::Subcommand;
use std::process::ExitCode;

#[derive(Subcommand, Debug)]
pub enum StudyCommand {
    /// Sweep dt, substeps, solver iterations, precision and effects; error against cost.
    Accuracy(accuracy::Args),
    /// Run the hard cases and check that they stay numerically stable.
    Stability(stability::Args),
    /// Join the shards of an accuracy sweep (`study accuracy --shard K/N`) into one study.
    Merge(accuracy::merge::MergeArgs),
}

pub fn main(cmd: StudyCommand) -> ExitCode {
    match cmd {
        StudyCommand::Accuracy(a) => accuracy::main(a),
        StudyCommand::Stability(a) => stability::main(a),
        StudyCommand::Merge(a) => accuracy::merge::main(a),
    }
}
