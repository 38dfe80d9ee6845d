//! `rigidlab study stability` (not built yet).

use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct Args {}

pub fn main(_: Args) -> ExitCode {
    eprintln!("rigidlab study stability is not built yet");
    ExitCode::from(2)
}
