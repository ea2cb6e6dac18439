//! Runs the command line as a user does, for the suites that check its
//! answers: one runner instead of a copy in each file.

use std::process::Command;

/// Runs `v2ref ARGS`: its exit status (-1 when a signal ended it), standard
/// output and standard error.
pub fn v2ref(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(args)
        .output()
        .expect("the binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}
