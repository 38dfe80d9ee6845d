//! `rigidlab study accuracy` (not built yet).

use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct Args {}

pub fn main(_: Args) -> ExitCode {
    eprintln!("rigidlab study accuracy is not built yet");
    ExitCode::from(2)
}
