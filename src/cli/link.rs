//! `rigidlab link LEVEL [--base URL]`: prints the web page's address carrying the level whole
//! (`level::link`), for a teacher to hand out. The level must load: a link to a level with errors
//! would only show its error on the student's page.

use super::bad;
use crate::level;
use std::path::Path;
use std::process::ExitCode;

/// Where `web/serve.sh` serves the page: the base when none is given.
pub const DEFAULT_BASE: &str = "http://localhost:8080/";

/// Checks the level loads, then prints its link on the page at `base`.
pub fn link(path: &Path, base: &str) -> ExitCode {
    if let Err(e) = level::load(path) {
        return bad(e);
    }
    let text = match level::read_text(path) {
        Ok(t) => t,
        Err(e) => return bad(e),
    };
    let name = path
        .file_name()
        .map_or(level::link::DEFAULT_NAME.into(), |n| {
            n.to_string_lossy().to_string()
        });
    let url = level::link::url(base, &name, &text);
    crate::report::print(&format!("{url}\n"), ExitCode::SUCCESS)
}
