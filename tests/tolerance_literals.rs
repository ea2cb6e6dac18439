//! No unexplained literal tolerance in the tests: a tolerance is a named
//! constant of `v2ref_core::tolerance` (or of the test file, with its reason in
//! its doc comment), or the literal carries its reason where it stands, in
//! a comment starting `tol:` on its line or in the comment lines directly
//! above it.
//!
//! A literal tolerance is a float literal in the tolerance argument of
//! `assert_rel_eq!`/`assert_abs_eq!` (the third) or `assert_within_sigmas!`
//! (the fourth), after `.abs() <` or `.abs() <=` anywhere in a test's code,
//! or after `<`/`<=` in the condition of an `assert!`. Comments and string
//! literals are not read.

use std::path::Path;

/// The code of Rust source `text`, one entry per line, with comments
/// blanked and the contents of string and char literals blanked (lengths
/// and lines kept), and the comment text of each line.
fn code_and_comments(text: &str) -> (Vec<String>, Vec<String>) {
    #[derive(PartialEq)]
    enum In {
        Code,
        LineComment,
        BlockComment,
        Str,
        RawStr(usize),
    }
    let chars: Vec<char> = text.chars().collect();
    let (mut code, mut comments) = (vec![String::new()], vec![String::new()]);
    let mut state = In::Code;
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '\n' {
            code.push(String::new());
            comments.push(String::new());
            if state == In::LineComment {
                state = In::Code;
            }
            i += 1;
            continue;
        }
        let (line, note) = (code.last_mut().unwrap(), comments.last_mut().unwrap());
        match state {
            In::Code => {
                let ident_before = i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_');
                if c == '/' && next == Some('/') {
                    state = In::LineComment;
                    continue;
                } else if c == '/' && next == Some('*') {
                    state = In::BlockComment;
                    i += 2;
                    continue;
                } else if c == '"' {
                    state = In::Str;
                } else if c == 'r' && !ident_before && matches!(next, Some('"' | '#')) {
                    let hashes = chars[i + 1..].iter().take_while(|&&h| h == '#').count();
                    if chars.get(i + 1 + hashes) == Some(&'"') {
                        state = In::RawStr(hashes);
                        line.push_str(&" ".repeat(hashes + 2));
                        i += hashes + 2;
                        continue;
                    }
                } else if c == '\'' {
                    // A char literal ('x', '\n'); a lifetime ('a) is code.
                    let len = if next == Some('\\') {
                        chars[i + 2..]
                            .iter()
                            .position(|&q| q == '\'')
                            .map(|p| p + 3)
                    } else {
                        (chars.get(i + 2) == Some(&'\'')).then_some(3)
                    };
                    if let Some(len) = len {
                        line.push_str(&" ".repeat(len));
                        i += len;
                        continue;
                    }
                }
                line.push(c);
            }
            In::LineComment => {
                note.push(c);
                line.push(' ');
            }
            In::BlockComment => {
                note.push(c);
                line.push(' ');
                if c == '*' && next == Some('/') {
                    state = In::Code;
                    line.push(' ');
                    i += 1;
                }
            }
            In::Str => {
                line.push(if c == '"' { '"' } else { ' ' });
                if c == '\\' && next.is_some_and(|n| n != '\n') {
                    line.push(' ');
                    i += 1;
                } else if c == '"' {
                    state = In::Code;
                }
            }
            In::RawStr(hashes) => {
                line.push(' ');
                let closes = c == '"'
                    && chars[i + 1..]
                        .iter()
                        .take(hashes)
                        .filter(|&&h| h == '#')
                        .count()
                        == hashes;
                if closes {
                    line.push_str(&" ".repeat(hashes));
                    i += hashes;
                    state = In::Code;
                }
            }
        }
        i += 1;
    }
    (code, comments)
}

/// The length of the float literal (`1e-9`, `0.05`, `5.0`, `2.5e3_f64`)
/// starting at `at` of `s`, if one does (an integer is not one).
fn float_literal_at(s: &[char], at: usize) -> Option<usize> {
    let before = at.checked_sub(1).map(|b| s[b]);
    if before.is_some_and(|b| b.is_alphanumeric() || b == '_' || b == '.') {
        return None;
    }
    let digits = |from: usize| {
        s[from..]
            .iter()
            .take_while(|c| c.is_ascii_digit() || **c == '_')
            .count()
    };
    let whole = digits(at);
    if whole == 0 {
        return None;
    }
    let mut end = at + whole;
    let mut float = false;
    if s.get(end) == Some(&'.') && s.get(end + 1).is_some_and(|c| c.is_ascii_digit()) {
        end += 1 + digits(end + 1);
        float = true;
    }
    if s.get(end) == Some(&'e') {
        let sign = usize::from(matches!(s.get(end + 1), Some('-' | '+')));
        let exponent = digits(end + 1 + sign);
        if exponent > 0 {
            end += 1 + sign + exponent;
            float = true;
        }
    }
    float.then_some(end - at)
}

/// Whether `s[from..to]` holds a float literal.
fn has_float(s: &[char], from: usize, to: usize) -> Option<usize> {
    (from..to).find(|&i| float_literal_at(s, i).is_some())
}

/// The arguments of the macro call whose `(` is at `open`: their spans
/// (top-level commas split them).
fn arguments(s: &[char], open: usize) -> Vec<(usize, usize)> {
    let (mut depth, mut start, mut out) = (0, open + 1, Vec::new());
    for (i, &c) in s.iter().enumerate().skip(open + 1) {
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' if depth == 0 => {
                out.push((start, i));
                break;
            }
            ')' | ']' | '}' => depth -= 1,
            ',' if depth == 0 => {
                out.push((start, i));
                start = i + 1;
            }
            _ => {}
        }
    }
    out
}

/// The positions (in `code`) of the literal tolerances of `code`.
fn literal_tolerances(code: &[char]) -> Vec<usize> {
    let starts = |pattern: &str| -> Vec<usize> {
        let pattern: Vec<char> = pattern.chars().collect();
        (0..code.len())
            .filter(|&i| code[i..].starts_with(&pattern))
            .collect()
    };
    let mut found = Vec::new();
    for (name, arg) in [
        ("assert_rel_eq!(", 2),
        ("assert_abs_eq!(", 2),
        ("assert_within_sigmas!(", 3),
    ] {
        for at in starts(name) {
            let args = arguments(code, at + name.chars().count() - 1);
            if let Some(&(from, to)) = args.get(arg) {
                found.extend(has_float(code, from, to));
            }
        }
    }
    let after_less = |i: usize| {
        let mut j = i + 1;
        if code.get(j) == Some(&'=') {
            j += 1;
        }
        while code.get(j).is_some_and(|c| c.is_whitespace()) {
            j += 1;
        }
        float_literal_at(code, j).map(|_| j)
    };
    for at in starts(".abs()") {
        let mut j = at + 6;
        while code.get(j).is_some_and(|c| c.is_whitespace()) {
            j += 1;
        }
        if code.get(j) == Some(&'<') {
            found.extend(after_less(j));
        }
    }
    for at in starts("assert!(") {
        if let Some(&(from, to)) = arguments(code, at + 7).first() {
            found.extend(
                (from..to)
                    .filter(|&i| code[i] == '<')
                    .filter_map(after_less),
            );
        }
    }
    found.sort_unstable();
    found.dedup();
    found
}

/// Whether line `line` (0-based) or the comment lines directly above it
/// say why its tolerance is what it is (`tol:`).
fn justified(code: &[String], comments: &[String], line: usize) -> bool {
    if comments[line].contains("tol:") {
        return true;
    }
    (0..line)
        .rev()
        .take_while(|&k| code[k].trim().is_empty() && !comments[k].trim().is_empty())
        .any(|k| comments[k].contains("tol:"))
}

/// The unexplained literal tolerances of Rust source `text`, as
/// `(line, code of the line)`, lines counted from 1.
fn unexplained(text: &str) -> Vec<(usize, String)> {
    let (lines, comments) = code_and_comments(text);
    let code: Vec<char> = lines.join("\n").chars().collect();
    let mut line_starts = vec![0];
    for line in &lines {
        line_starts.push(line_starts.last().unwrap() + line.chars().count() + 1);
    }
    let mut out: Vec<(usize, String)> = literal_tolerances(&code)
        .into_iter()
        .map(|at| line_starts.partition_point(|&s| s <= at) - 1)
        .filter(|&line| !justified(&lines, &comments, line))
        .map(|line| (line + 1, lines[line].trim().to_owned()))
        .collect();
    out.dedup();
    out
}

#[test]
fn every_literal_tolerance_of_the_tests_is_named_or_explained() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("tests/ is readable")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "rs"))
        .collect();
    files.sort();
    let mut found = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).expect("a readable test file");
        let name = file.file_name().unwrap_or_default().to_string_lossy();
        for (line, code) in unexplained(&text) {
            found.push(format!("tests/{name}:{line}: {code}"));
        }
    }
    assert!(
        found.is_empty(),
        "{} literal tolerances without a name or a `// tol:` reason (use a constant of v2ref_core::tolerance, or say why at the site):\n{}",
        found.len(),
        found.join("\n")
    );
}

/// The scan finds the literals it is for, on the line they stand, and
/// accepts a name, a reason, or a literal in a comment or a string.
#[test]
fn the_tolerance_scan_sees_literals() {
    let lines = |text: &str| -> Vec<usize> { unexplained(text).into_iter().map(|h| h.0).collect() };
    assert_eq!(lines("assert_rel_eq!(a, b, 1e-9);"), [1]);
    assert_eq!(
        lines("assert_abs_eq!(\n    a,\n    b,\n    2.0 * EPS\n);"),
        [4]
    );
    assert_eq!(
        lines("assert_rel_eq!(f(a, 1.5), b, ROUNDING_REL);"),
        Vec::<usize>::new()
    );
    assert_eq!(lines("assert_within_sigmas!(m, mu, se, 3.0);"), [1]);
    assert_eq!(
        lines("assert_within_sigmas!(m, mu, se);"),
        Vec::<usize>::new()
    );
    assert_eq!(lines("let ok = (a - b).abs() <= 1e-12 * b;"), [1]);
    assert_eq!(lines("assert!(err < 0.05, \"{err}\");"), [1]);
    assert_eq!(lines("assert!(n < 5 && v > 0.5);"), Vec::<usize>::new());
    assert_eq!(
        lines("// tol: two roundings of a 1e3 sum.\nassert!((a - b).abs() < 1e-12);"),
        Vec::<usize>::new()
    );
    assert_eq!(
        lines("assert!((a - b).abs() < 1e-12); // tol: printed to 12 digits"),
        Vec::<usize>::new()
    );
    assert_eq!(
        lines("// assert!((a - b).abs() < 1e-12);\nlet s = \"x.abs() < 0.5\";"),
        Vec::<usize>::new()
    );
    assert_eq!(lines("let c = '\"'; assert!(x.abs() < 1e-3);"), [1]);
}
