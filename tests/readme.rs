//! The commands of the README and of the guide it links (docs/guide.md)
//! run as written: every `cargo run --release -- …` line of their shell
//! blocks (continuation lines joined, comments dropped) is run with the
//! built binary, in a scratch folder, in the pages' order, and must exit 0.
//! A flag renamed or a sample file moved without the pages following fails
//! here. Skipped, with the test that covers each: the full
//! `reproduce` (tests/reproduce.rs, CI's reproduction diff), `claims`
//! (tests/claims.rs), `golden` (tests/golden.rs).
//!
//! The guide's `plan` examples search the default grid (80 points, 17 s of
//! piston Monte Carlo each): the quick tier runs them on 2 points
//! ([`SMALL_GRID`], same flags otherwise, so the same power against a
//! renamed flag or a moved file); the slow tier runs them as written.

use std::path::Path;
use std::process::Command;

/// Subcommands not run here, each covered by its own test.
const SKIPPED: &[&str] = &["reproduce", "claims", "golden"];

/// The `cargo run --release -- ` command lines of a page's `sh` blocks,
/// as argument lists after the `--`.
fn readme_commands(readme: &str) -> Vec<Vec<String>> {
    let mut in_sh = false;
    let mut joined = Vec::new();
    let mut current = String::new();
    for line in readme.lines() {
        if line.starts_with("```") {
            in_sh = !in_sh && line.trim_start_matches('`').starts_with("sh");
            continue;
        }
        if !in_sh {
            continue;
        }
        let code = line.split(" #").next().unwrap_or("").trim_end();
        let continued = code.ends_with('\\');
        current.push_str(code.trim_end_matches('\\').trim());
        current.push(' ');
        if !continued {
            joined.push(std::mem::take(&mut current));
        }
    }
    joined
        .iter()
        .filter_map(|l| l.trim().strip_prefix("cargo run --release -- "))
        .map(|rest| rest.split_whitespace().map(str::to_owned).collect())
        .collect()
}

/// Runs `v2ref args` in `dir` (stderr is a pipe: no progress bars).
fn run(args: &[String], dir: &Path) {
    let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "README command `v2ref {}` failed: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Appended to the guide's `plan` commands in the quick tier: 2 fringe
/// frequencies by 1 stroke instead of the default 20 by 4 (one of them
/// reaches the target: the plan's SVG has a point to draw).
const SMALL_GRID: &[&str] = &["--fringe-hz", "300:1000:2:log", "--stroke-um", "32"];

#[test]
fn readme_commands_run_with_a_small_plan_grid() {
    run_readme_commands(SMALL_GRID);
}

#[test]
#[ignore = "slow tier: the guide's four plans on the full default grid (55 s)"]
fn readme_commands_run_as_written() {
    run_readme_commands(&[]);
}

/// The pages whose commands run, in order: the README, then the guide.
const PAGES: &[&str] = &["README.md", "docs/guide.md"];

/// Runs the pages' commands in order, `plan_extra` appended to each `plan`.
fn run_readme_commands(plan_extra: &[&str]) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let commands: Vec<Vec<String>> = PAGES
        .iter()
        .flat_map(|page| readme_commands(&std::fs::read_to_string(root.join(page)).unwrap()))
        .collect();
    assert!(
        commands.len() >= 10,
        "found only {} commands",
        commands.len()
    );
    let dir = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink(root.join("examples"), dir.path().join("examples")).unwrap();
    let mut ran = Vec::new();
    for args in &commands {
        let sub = args[0].as_str();
        if SKIPPED.contains(&sub) {
            continue;
        }
        if sub == "score" {
            // The user's pipeline writes est.csv: stand in with v2ref's own
            // estimates (the next README command), then score them (again
            // before each score: --force, as the file is the stand-in's own).
            run(
                &[
                    "estimate",
                    "--sidecar",
                    "set.json",
                    "--out",
                    "est.csv",
                    "--force",
                ]
                .map(String::from),
                dir.path(),
            );
        }
        let mut args = args.clone();
        if sub == "plan" {
            args.extend(plan_extra.iter().map(|a| a.to_string()));
        }
        run(&args, dir.path());
        ran.push(sub.to_owned());
    }
    for sub in [
        "bias", "snr", "simulate", "piston", "plan", "synth", "score", "estimate",
    ] {
        assert!(
            ran.iter().any(|s| s == sub),
            "no command for {sub} in {PAGES:?}"
        );
    }
    assert!(dir.path().join("plan.svg").exists());
}

#[test]
fn the_parser_joins_continuations_and_drops_comments() {
    let text = "```sh\n# a comment\ncargo run --release -- bias --a 1 \\\n    --b 2   # note\nls\n```\n```python\ncargo run --release -- nope\n```\n";
    assert_eq!(
        readme_commands(text),
        vec![vec!["bias", "--a", "1", "--b", "2"]]
    );
}
