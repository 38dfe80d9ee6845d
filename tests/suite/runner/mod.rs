//! The runner and the command line: the run budget, input and output, memory, files kept, the
//! fuzz campaign (src/runner, src/cli.rs).

mod budget;
mod check_assignment;
mod cli_io;
mod cli_memory;
mod fuzz_campaign;
mod grade_cli;
mod grade_variants;
mod link_cli;
mod report_step_calls;
mod user_files_kept;
mod verify_cli;
