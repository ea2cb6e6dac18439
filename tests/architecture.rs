//! The workspace's levels (the oracle's crate docs, "Levels"). Between
//! crates: each crate depends only on crates of lower levels ([`CRATES`],
//! checked against each `crates/*/Cargo.toml`). Inside the numerics
//! `crates/v2ref-core`: a module uses only modules of its own level or below.
//! Every path `crate::<module>` in the code of `crates/v2ref-core/src/`
//! (comments and doc comments aside: a doc link to a higher module is a
//! pointer for the reader, not a dependency) is checked against [`LEVELS`],
//! which must place every module of that folder.

use std::path::{Path, PathBuf};

/// The oracle's module levels, lowest first.
const LEVELS: &[&[&str]] = &[
    &[
        "error",
        "tolerance",
        "bounds",
        "csv_lines",
        "manifest",
        "math",
        "montecarlo",
        "words",
    ],
    &["formalism"],
    &["record"],
    &["bias"],
    &["noise", "piston"],
    &["simulator"],
    &["conformance"],
    &["prelude", "oracle", "lib"],
];

/// The workspace's crates, lowest level first (the command line, the
/// repository's root package `v2ref-cli`, is the top): a crate may depend
/// on crates of lower levels only.
const CRATES: &[&[&str]] = &[
    &["v2ref-core"],
    &["v2ref", "v2ref-commands"],
    &["v2ref-files"],
    &["v2ref-oifits", "v2ref-reproduction"],
    &["v2ref-python", "v2ref-cli"],
];

/// The oracle's sources.
fn oracle_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/v2ref-core/src")
}

/// The level of the top module `name`.
fn level(name: &str) -> Option<usize> {
    LEVELS.iter().position(|l| l.contains(&name))
}

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("src/ is readable") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The top module a file of `src/` belongs to: `crates/v2ref-commands/src/report/noise.rs` is
/// in `noise`, `crates/v2ref-core/src/record.rs` in `record`.
fn top_module(src: &Path, file: &Path) -> String {
    let first = file
        .strip_prefix(src)
        .expect("a file under src/")
        .components()
        .next()
        .expect("a path component");
    let name = first.as_os_str().to_string_lossy();
    name.trim_end_matches(".rs").to_owned()
}

/// `text` without its comments (line, doc and block comments).
fn code_of(text: &str) -> String {
    let mut code = String::new();
    let mut rest = text;
    while !rest.is_empty() {
        let line = rest.find("//").unwrap_or(usize::MAX);
        let block = rest.find("/*").unwrap_or(usize::MAX);
        if line == usize::MAX && block == usize::MAX {
            code.push_str(rest);
            break;
        }
        let at = line.min(block);
        code.push_str(&rest[..at]);
        let (end, skip) = if line < block { ("\n", 0) } else { ("*/", 2) };
        rest = rest[at..].find(end).map_or("", |e| &rest[at + e + skip..]);
    }
    code
}

/// The top modules that `code` names as `crate::<module>` (and in
/// `crate::{a, b::c}` groups); `$crate` of macros aside.
fn modules_used(code: &str) -> Vec<String> {
    let ident = |s: &str| -> String {
        s.trim_start()
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let mut used = Vec::new();
    for (at, _) in code.match_indices("crate::") {
        let before = code[..at].chars().next_back();
        if before.is_some_and(|c| c == '$' || c.is_alphanumeric() || c == '_') {
            continue;
        }
        let after = &code[at + "crate::".len()..];
        if let Some(group) = after.strip_prefix('{') {
            let group = &group[..group.find('}').unwrap_or(group.len())];
            used.extend(group.split(',').map(ident));
        } else {
            used.push(ident(after));
        }
    }
    used.retain(|m| !m.is_empty());
    used
}

#[test]
fn every_module_uses_only_its_level_and_below() {
    let src = oracle_src();
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut breaches = Vec::new();
    for file in &files {
        let module = top_module(&src, file);
        let own = level(&module).unwrap_or_else(|| {
            panic!("crates/v2ref-core/src/{module}: place the module in a level (tests/architecture.rs and the crate docs)")
        });
        let text = std::fs::read_to_string(file).expect("a source file");
        for used in modules_used(&code_of(&text)) {
            // Names at the crate's root that are not modules: re-exports
            // (`crate::Result`) and exported macros (`crate::assert_rel_eq`).
            let Some(theirs) = level(&used) else { continue };
            if theirs > own {
                let shown = file.strip_prefix(&src).unwrap_or(file).display();
                breaches.push(format!(
                    "crates/v2ref-core/src/{shown} ({module}) uses crate::{used}"
                ));
            }
        }
    }
    assert!(
        breaches.is_empty(),
        "modules using a higher level:\n{}",
        breaches.join("\n")
    );
}

#[test]
fn the_checker_sees_what_it_should() {
    let code = code_of(
        "use crate::noise::Formula; // crate::plan\n/* crate::conformance */\n\
         /// [`crate::reproduction`]\nlet x = crate::simulator::Model::new();\n\
         use crate::{bias::report, piston};\n$crate::tolerance::x!();",
    );
    assert_eq!(
        modules_used(&code),
        ["noise", "simulator", "bias", "piston"]
    );
}

#[test]
fn every_top_module_has_a_level() {
    let src = oracle_src();
    for entry in std::fs::read_dir(&src).expect("src/ is readable") {
        let path = entry.expect("a directory entry").path();
        let module = top_module(&src, &path);
        assert!(
            level(&module).is_some(),
            "crates/v2ref-core/src/{module} has no level"
        );
    }
}

/// The level of the crate `name`.
fn crate_level(name: &str) -> Option<usize> {
    CRATES.iter().position(|l| l.contains(&name))
}

/// The workspace crates named in the `[dependencies]` table of the manifest
/// `text` (a line `v2ref… = { path = … }`).
fn workspace_dependencies(text: &str) -> Vec<String> {
    let mut deps = Vec::new();
    let mut in_deps = false;
    for line in text.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            in_deps = line == "[dependencies]";
        } else if in_deps && line.starts_with("v2ref") && line.contains("path =") {
            deps.push(line.split('=').next().unwrap_or("").trim().to_owned());
        }
    }
    deps
}

#[test]
fn every_crate_depends_only_on_lower_levels() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut manifests = vec![("v2ref-cli".to_owned(), root.join("Cargo.toml"))];
    for entry in std::fs::read_dir(root.join("crates")).expect("crates/ is readable") {
        let dir = entry.expect("a directory entry").path();
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        manifests.push((name, dir.join("Cargo.toml")));
    }
    let mut breaches = Vec::new();
    for (name, manifest) in &manifests {
        let own = crate_level(name).unwrap_or_else(|| {
            panic!("{name}: place the crate in a level (tests/architecture.rs)")
        });
        let text = std::fs::read_to_string(manifest).expect("a manifest");
        for dep in workspace_dependencies(&text) {
            let theirs = crate_level(&dep).unwrap_or(usize::MAX);
            if theirs >= own {
                breaches.push(format!("{name} depends on {dep}"));
            }
        }
    }
    assert!(
        breaches.is_empty(),
        "crates depending on their own level or above:\n{}",
        breaches.join("\n")
    );
}

#[test]
fn the_manifest_reader_sees_what_it_should() {
    let text = "[dependencies]\nv2ref = { path = \"../v2ref\" }\nserde = \"1\"\n\
                [dev-dependencies]\nv2ref-files = { path = \"../v2ref-files\" }\n";
    assert_eq!(workspace_dependencies(text), ["v2ref"]);
}
