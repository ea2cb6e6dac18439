//! The workspace's levels (the oracle's crate docs, "Levels"). Between
//! crates: each crate depends only on crates of lower levels ([`CRATES`],
//! checked against each `crates/*/Cargo.toml`). Inside the numerics
//! `crates/v2ref-core`: a module uses only modules of its own level or below.
//! Every path `crate::<module>` in the code of `crates/v2ref-core/src/`
//! (comments and doc comments aside: a doc link to a higher module is a
//! pointer for the reader, not a dependency) is checked against [`LEVELS`],
//! which must place every module of that folder. In every crate (the
//! command line's `src/` too): no import circle between modules, each file
//! a module, each path `crate::…`, `self::…`, `super::…` outside comments
//! and test modules an edge between the two siblings that hold its ends
//! (`plan::correlation` → `plan::observation`, `simulator` → `noise`), the
//! circles left listed in [`KNOWN_CIRCLES`].

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
        "text",
        "photometric_band",
        "target_list",
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
    &["v2ref", "v2ref-commands", "v2ref-files"],
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

/// The source folders of the workspace's crates: the command line's
/// `src/` (root `main.rs`) and each `crates/*/src/`.
fn crate_sources() -> Vec<(String, PathBuf)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut sources = vec![("v2ref-cli".to_owned(), root.join("src"))];
    for entry in std::fs::read_dir(root.join("crates")).expect("crates/ is readable") {
        let dir = entry.expect("a directory entry").path();
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        sources.push((name, dir.join("src")));
    }
    sources.sort();
    sources
}

/// The module a file of `src` is: `lib.rs` and `main.rs` the crate's root
/// (`[]`), `plan/mod.rs` `[plan]`, `plan/observation.rs` `[plan, observation]`.
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let mut path: Vec<String> = file
        .strip_prefix(src)
        .expect("a file under src/")
        .with_extension("")
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if path.len() == 1 && (path[0] == "lib" || path[0] == "main")
        || path.last().is_some_and(|l| l == "mod")
    {
        path.pop();
    }
    path
}

/// The code of a file before its test module (`#[cfg(test)]` then `mod`,
/// at the end of a file by the workspace's habit): what the crate is
/// built from; a test's imports are not the module's.
fn non_test(code: &str) -> &str {
    let mut from = 0;
    while let Some(at) = code[from..].find("#[cfg(test)]") {
        let after = &code[from + at + "#[cfg(test)]".len()..];
        if after.trim_start().starts_with("mod ") {
            return &code[..from + at];
        }
        from += at + 1;
    }
    code
}

/// Paths, each as (how many `super`s up, or `None` from the crate's root;
/// the segments after).
type PathsNamed = Vec<(Option<usize>, Vec<String>)>;

/// The paths `code` names from `crate::`, `self::` or `super::` (and
/// `super::super::`), a `{…}` group giving one path per item.
fn paths_named(code: &str) -> PathsNamed {
    fn ident(s: &str) -> &str {
        let end = s
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(s.len());
        &s[..end]
    }
    /// The segments of `rest` (after a `::`), groups expanded, each path
    /// appended to `out` after `prefix`.
    fn segments(rest: &str, prefix: Vec<String>, out: &mut Vec<Vec<String>>) {
        let rest = rest.trim_start();
        if let Some(group) = rest.strip_prefix('{') {
            // The group's items at its own depth, split at its commas.
            let (mut depth, mut start) = (0usize, 0usize);
            for (i, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => {
                        segments_item(&group[start..i], &prefix, out);
                        return;
                    }
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        segments_item(&group[start..i], &prefix, out);
                        start = i + 1;
                    }
                    _ => {}
                }
            }
            return;
        }
        let name = ident(rest);
        if name.is_empty() {
            out.push(prefix);
            return;
        }
        let mut path = prefix;
        path.push(name.to_owned());
        match rest[name.len()..].strip_prefix("::") {
            Some(more) => segments(more, path, out),
            None => out.push(path),
        }
    }
    fn segments_item(item: &str, prefix: &[String], out: &mut Vec<Vec<String>>) {
        if !item.trim().is_empty() {
            segments(item, prefix.to_vec(), out);
        }
    }
    let mut named = Vec::new();
    for start in ["crate::", "self::", "super::"] {
        for (at, _) in code.match_indices(start) {
            let before = code[..at].chars().next_back();
            if before.is_some_and(|c| c == '$' || c == ':' || c.is_alphanumeric() || c == '_') {
                continue;
            }
            let mut rest = &code[at + start.len()..];
            let base = match start {
                "crate::" => None,
                "self::" => Some(0),
                _ => {
                    let mut up = 1;
                    while let Some(more) = rest.strip_prefix("super::") {
                        up += 1;
                        rest = more;
                    }
                    Some(up)
                }
            };
            let mut paths = Vec::new();
            segments(rest, Vec::new(), &mut paths);
            named.extend(paths.into_iter().map(|p| (base, p)));
        }
    }
    named
}

/// The edges between sibling modules of one crate: a file of module A
/// naming a path in module B (the longest prefix of the path that is one of
/// `modules`), A and B neither equal nor one inside the other, gives the
/// edge from A's ancestor to B's ancestor just under their common parent
/// (`simulator::rows` → `noise::model` is `simulator` → `noise`).
fn sibling_edges(
    modules: &[Vec<String>],
    uses: &[(Vec<String>, PathsNamed)],
) -> std::collections::BTreeSet<(String, String)> {
    let mut edges = std::collections::BTreeSet::new();
    for (from, paths) in uses {
        for (base, segments) in paths {
            let mut full: Vec<String> = match base {
                None => Vec::new(),
                Some(up) => from[..from.len().saturating_sub(*up)].to_vec(),
            };
            full.extend(segments.iter().cloned());
            let Some(to) = (0..=full.len())
                .rev()
                .map(|n| &full[..n])
                .find(|p| modules.iter().any(|m| m == p))
            else {
                continue;
            };
            let common = from.iter().zip(to).take_while(|(a, b)| a == b).count();
            if common == from.len() || common == to.len() {
                continue;
            }
            edges.insert((from[..=common].join("::"), to[..=common].join("::")));
        }
    }
    edges
}

/// The import circles of a graph: each group of two or more nodes that
/// all reach one another (sorted), with its edges.
fn circles(
    edges: &std::collections::BTreeSet<(String, String)>,
) -> Vec<(Vec<String>, Vec<String>)> {
    let reach = |from: &str| -> std::collections::BTreeSet<String> {
        let mut seen = std::collections::BTreeSet::new();
        let mut todo = vec![from.to_owned()];
        while let Some(node) = todo.pop() {
            for (a, b) in edges {
                if *a == node && seen.insert(b.clone()) {
                    todo.push(b.clone());
                }
            }
        }
        seen
    };
    let mut groups: Vec<Vec<String>> = Vec::new();
    for (a, _) in edges {
        if groups.iter().any(|g| g.contains(a)) {
            continue;
        }
        let from_a = reach(a);
        let group: Vec<String> = from_a
            .iter()
            .filter(|b| reach(b).contains(a))
            .cloned()
            .collect();
        if group.len() > 1 {
            groups.push(group);
        }
    }
    groups
        .into_iter()
        .map(|g| {
            let inside = edges
                .iter()
                .filter(|(a, b)| g.contains(a) && g.contains(b))
                .map(|(a, b)| format!("{a} -> {b}"))
                .collect();
            (g, inside)
        })
        .collect()
}

/// Import circles found on 2026-12-08 and not yet broken (issue 56): the
/// check fails on any other circle, and on one of these once it is gone
/// (then delete its line). Each says what closes it.
const KNOWN_CIRCLES: &[(&str, &[&str])] = &[
    // `plan::instrument`'s `Instrument::apply` fills the command's
    // `commands::plan::PlanRequest`, which the command builds from `plan`.
    ("v2ref-commands", &["commands", "plan"]),
    // `formats` re-exports `atomic` (`pub use crate::atomic`, the path
    // v2ref-oifits' write.rs takes); `atomic::set` opens with `formats::open`.
    ("v2ref-files", &["atomic", "formats"]),
];

#[test]
fn no_crate_has_an_import_circle() {
    let mut found = Vec::new();
    let mut known_seen = Vec::new();
    for (name, src) in crate_sources() {
        let mut files = Vec::new();
        rust_files(&src, &mut files);
        files.sort();
        let modules: Vec<Vec<String>> = files.iter().map(|f| module_of(&src, f)).collect();
        let uses: Vec<_> = files
            .iter()
            .zip(&modules)
            .map(|(file, module)| {
                let text = std::fs::read_to_string(file).expect("a source file");
                (module.clone(), paths_named(non_test(&code_of(&text))))
            })
            .collect();
        for (nodes, edges) in circles(&sibling_edges(&modules, &uses)) {
            let known = KNOWN_CIRCLES.iter().position(|(c, m)| {
                *c == name && nodes.iter().map(String::as_str).eq(m.iter().copied())
            });
            match known {
                Some(k) => known_seen.push(k),
                None => found.push(format!("{name}: {}", edges.join(", "))),
            }
        }
    }
    assert!(
        found.is_empty(),
        "modules that use one another (move what they share into a module below both):\n{}",
        found.join("\n")
    );
    for (k, (name, modules)) in KNOWN_CIRCLES.iter().enumerate() {
        assert!(
            known_seen.contains(&k),
            "{name}: the circle {modules:?} is broken: delete it from KNOWN_CIRCLES"
        );
    }
}

#[test]
fn the_circle_finder_sees_what_it_should() {
    let code = "use super::scans::{affordable, Scans};\nuse crate::plan::{self, observation::X};\n\
                let n = super::super::top::f();\n$crate::x!(); a::crate::b;\n\
                #[cfg(test)]\nmod tests { use crate::noise::Y; }";
    let named = paths_named(non_test(code));
    let strings = |p: &[String]| p.join("::");
    let shown: Vec<(Option<usize>, String)> = named.iter().map(|(b, p)| (*b, strings(p))).collect();
    assert_eq!(
        shown,
        [
            (None, "plan::self".to_owned()),
            (None, "plan::observation::X".to_owned()),
            (Some(1), "scans::affordable".to_owned()),
            (Some(1), "scans::Scans".to_owned()),
            (Some(2), "top::f".to_owned()),
        ]
    );
    let module = |s: &str| -> Vec<String> {
        s.split("::")
            .filter(|x| !x.is_empty())
            .map(str::to_owned)
            .collect()
    };
    let modules: Vec<Vec<String>> = [
        "",
        "plan",
        "plan::observation",
        "plan::correlation",
        "plan::scans",
    ]
    .iter()
    .map(|m| module(m))
    .collect();
    let paths = |p: &[(Option<usize>, &str)]| -> PathsNamed {
        p.iter().map(|(b, s)| (*b, module(s))).collect()
    };
    let uses = vec![
        (
            module("plan::observation"),
            paths(&[(Some(1), "correlation::Corr"), (Some(1), "PlanInputs")]),
        ),
        (
            module("plan::correlation"),
            paths(&[(None, "plan::observation::affordable")]),
        ),
        (module("plan"), paths(&[(Some(0), "observation::run")])),
    ];
    let edges = sibling_edges(&modules, &uses);
    let (nodes, inside) = circles(&edges).pop().expect("one circle");
    assert_eq!(nodes, ["plan::correlation", "plan::observation"]);
    assert_eq!(
        inside,
        [
            "plan::correlation -> plan::observation",
            "plan::observation -> plan::correlation"
        ]
    );
    let uses_after = vec![
        (
            module("plan::observation"),
            paths(&[
                (Some(1), "correlation::Corr"),
                (Some(1), "scans::affordable"),
            ]),
        ),
        (
            module("plan::correlation"),
            paths(&[(None, "plan::scans::affordable")]),
        ),
    ];
    assert!(circles(&sibling_edges(&modules, &uses_after)).is_empty());
}
