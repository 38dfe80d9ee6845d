//! The command line's output: a closed pipe ends quietly, a full disk is an error.

use std::process::{Command, Stdio};

fn rigidlab() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_rigidlab"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

/// Runs with stdout sent to `stdout`; returns (exit code, stderr).
fn run_to(args: &[&str], stdout: Stdio) -> (i32, String) {
    let out = rigidlab()
        .args(args)
        .stdout(stdout)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

const FREE_FALL: &str = "levels/kinematics/free_fall.ron";

/// Every command that prints, with output cheap enough to produce in a test.
const PRINTING: &[&[&str]] = &[
    &["check", FREE_FALL],
    &["check", FREE_FALL, "--json"],
    &["run", FREE_FALL],
    &["study", "stability", "spinning_disc", "--quick"],
    &["study", "stability", "spinning_disc", "--quick", "--json"],
];

#[test]
fn a_closed_pipe_ends_quietly() {
    // `rigidlab check levels | head -1`: the reader is gone before rigidlab writes (closed before
    // the start, so that the test does not race the child).
    for args in PRINTING {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let (code, err) = run_to(args, Stdio::from(writer));
        assert_eq!(code, 141, "{args:?}: {err}");
        assert!(
            err.is_empty(),
            "{args:?}: a closed pipe is not worth a message: {err}"
        );
    }
}

#[test]
fn a_full_disk_is_an_error() {
    for args in PRINTING {
        let full = std::fs::File::create("/dev/full").unwrap();
        let (code, err) = run_to(args, Stdio::from(full));
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(
            err.contains("cannot write the output") && err.contains("No space left"),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}
