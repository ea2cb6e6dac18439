//! No number in a claim's note is typed by hand: every string literal of
//! the claims' providers (`crates/v2ref-reproduction/src/claims/`) is read, its format
//! placeholders (`{x:.3}`, filled from computed values or from the case's
//! inputs declared in code) taken out, and any number left in the text is a
//! typed one, which fails the test unless it belongs to a formula or a
//! citation listed in [`SYMBOLIC`].
//!
//! What the scan cannot see: a number typed as a format argument
//! (`format!("{}", 43)`); such a literal is code, read in review like any
//! other constant.

use std::path::{Path, PathBuf};

/// Text whose digits are not evidence numbers: the symbolic formulas the
/// notes quote (their coefficients hold for any input: the paper's printed
/// forms and the exact ones beside them), the paper's figures and sections
/// named by number, and the citations of the literature. Each is taken out
/// of a literal before its numbers are looked for; keep it to formulas and
/// references: a case's input belongs in a named constant of the code.
const SYMBOLIC: &[&str] = &[
    // Reciprocal of a formatted value: "1/{x}".
    "1/\u{1}",
    "1/stroke",
    "1/(N dx)",
    "1/sqrt(",
    "as 1/f",
    "(1/dx)",
    // The definition of the normalization's deviation: u is V2 of a source
    // of visibility 1.
    "|1 - u|",
    "|1 - u^2|",
    "a 100% visibility source",
    // The white-light sample, named by its index.
    "Sample 0",
    "sample 0",
    // Integration and bandwidth.
    "pi^2/8",
    "2/pi",
    "sqrt(2P/pi)",
    "(C^2+S^2)/T^2",
    // The Appendix's printed and exact moments and variances.
    "n^4+6n^3+7n^2+n",
    "n^2+n",
    "m^2 + n",
    "m^4 + 6m^2 n + 4mn + n + 3n^2",
    "n_i(4n_i^2+6n_i+1)",
    "4 m_i^2 n_i + 4 m_i n_i + 2 n_i^2 + n_i",
    "4m_i^2 n_i + 4 m_i n_i + 2n_i^2 + n_i",
    "4 m_0^2 n_0 + 4 m_0 n_0 + 2 n_0^2 + n_0",
    "4m_0^2 n_0 + 4m_0 n_0 + 2n_0^2 + n_0",
    "2 N^2 s^2 [2 sum m^2 + N s^2]",
    "2 N^4 s^2 [2 m_0^2 + s^2]",
    "sqrt(2 s^2 (2 m_0^2 + s^2))",
    "the 2 kappa2^2 term",
    "4m^2 k2 + 4m k3 + k4 + 2 k2^2",
    "cross term 4 s^2 n",
    "16 s^4",
    // The paper's figures, named by number.
    "Fig. 4",
    "Fig. 5",
    // Citations: author, year, journal volume and page.
    "Gan 1995",
    "Pickles 1998, PASP 110, 863",
    "Perrin (1997)",
];

/// Marks a format placeholder once it is taken out of a literal.
const PLACEHOLDER: char = '\u{1}';

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("the claims' sources are readable") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The contents of the string literals of Rust source `code`, with the
/// line each starts on (comments, char literals and lifetimes skipped; an
/// escaped line end and the indentation after it removed, as the compiler
/// does).
fn string_literals(code: &str) -> Vec<(usize, String)> {
    let b = code.as_bytes();
    let line_of = |at: usize| code[..at].matches('\n').count() + 1;
    let (mut out, mut i) = (Vec::new(), 0);
    while i < b.len() {
        let rest = &code[i..];
        if rest.starts_with("//") {
            i += rest.find('\n').unwrap_or(rest.len());
        } else if rest.starts_with("/*") {
            i += rest.find("*/").map_or(rest.len(), |e| e + 2);
        } else if b[i] == b'\'' {
            // A char literal ('x', '\n', '–') or a lifetime ('a).
            let mut chars = rest[1..].char_indices();
            i += match chars.next() {
                Some((_, '\\')) => rest[2..].find('\'').map_or(1, |e| e + 3),
                Some((_, c)) if rest[1 + c.len_utf8()..].starts_with('\'') => 2 + c.len_utf8(),
                _ => 1,
            };
        } else if b[i] == b'r'
            && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_'))
            && (rest[1..].starts_with('"') || rest[1..].starts_with("#\""))
        {
            let hashes = rest[1..].len() - rest[1..].trim_start_matches('#').len();
            let open = 1 + hashes + 1;
            let close = format!("\"{}", "#".repeat(hashes));
            let end = rest[open..].find(&close).expect("a closed raw string") + open;
            out.push((line_of(i), rest[open..end].to_owned()));
            i += end + close.len();
        } else if b[i] == b'"' {
            let (text, length) = string_body(&rest[1..]);
            out.push((line_of(i), text));
            i += 1 + length;
        } else {
            i += rest.chars().next().map_or(1, char::len_utf8);
        }
    }
    out
}

/// The contents of a string literal whose opening quote precedes `body`,
/// and the bytes it takes up to and with its closing quote. Escapes are
/// kept as written, an escaped line end and the indentation after it
/// removed.
fn string_body(body: &str) -> (String, usize) {
    let mut text = String::new();
    let mut chars = body.char_indices().peekable();
    while let Some((at, c)) = chars.next() {
        match c {
            '"' => return (text, at + 1),
            '\\' => match chars.next() {
                Some((_, '\n')) => while chars.next_if(|(_, c)| c.is_whitespace()).is_some() {},
                Some((_, escaped)) => {
                    text.push('\\');
                    text.push(escaped);
                }
                None => break,
            },
            c => text.push(c),
        }
    }
    panic!("a string literal is not closed")
}

/// The numbers typed in the text of a format string `literal`: what is
/// left once the placeholders and the [`SYMBOLIC`] text are taken out. A
/// word (a run of letters, digits and `_ . ^ -`) is a number when it starts
/// with a digit: `V1^2`, `m_0` and `fig5_sensitivity` are names, `0.2`,
/// `43` and `2.0-2.4` numbers.
fn typed_numbers(literal: &str) -> Vec<String> {
    let mut text = String::new();
    let mut depth = 0;
    let unescaped = literal.replace("{{", "(").replace("}}", ")");
    for c in unescaped.chars() {
        match c {
            '{' => {
                depth += 1;
                if depth == 1 {
                    text.push(PLACEHOLDER);
                }
            }
            '}' if depth > 0 => depth -= 1,
            _ if depth > 0 => {}
            c => text.push(c),
        }
    }
    for phrase in SYMBOLIC {
        text = text.replace(phrase, " ");
    }
    let is_word = |c: char| c.is_alphanumeric() || "_.^-".contains(c);
    text.split(|c: char| !is_word(c))
        .map(|w| w.trim_start_matches(['-', '.']))
        .filter(|w| w.starts_with(|c: char| c.is_ascii_digit()))
        .map(str::to_owned)
        .collect()
}

/// The typed numbers of every literal of the claims' providers (their unit
/// tests aside), as `file:line: numbers in "literal"`.
fn typed_numbers_in_claims() -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(
        &root.join("crates/v2ref-reproduction/src/claims"),
        &mut files,
    );
    files.sort();
    let mut found = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).expect("a readable source");
        let code = text.split("#[cfg(test)]").next().unwrap_or_default();
        for (line, literal) in string_literals(code) {
            let numbers = typed_numbers(&literal);
            if !numbers.is_empty() {
                let name = file.strip_prefix(root).unwrap_or(&file).display();
                found.push(format!("{name}:{line}: {numbers:?} in {literal:?}"));
            }
        }
    }
    found
}

#[test]
fn no_note_of_a_claim_types_a_number() {
    let found = typed_numbers_in_claims();
    assert!(
        found.is_empty(),
        "numbers typed in the claims' notes (format them from the computed value or from a named input of the case):\n{}",
        found.join("\n")
    );
}

/// The scan finds what it is for: a typed number beside formatted ones, in
/// a raw string, across an escaped line end; names, formulas, placeholders
/// and comments are not numbers.
#[test]
fn the_note_scan_sees_typed_numbers() {
    assert_eq!(
        typed_numbers("the {DIAMETER_MAS} mas disk over {S_MIN_CPAS}-{S_MAX_CPAS:.0}: {v:.3e}"),
        Vec::<String>::new()
    );
    assert_eq!(typed_numbers("the 43 mas disk at {s}"), ["43"]);
    assert_eq!(typed_numbers("over 0-{S_MAX_CPAS}"), ["0-"]);
    assert_eq!(
        typed_numbers("flat 2.0-2.4 um, below 0.2%"),
        ["2.0-2.4", "0.2"]
    );
    assert_eq!(
        typed_numbers("4x the visibilities, (3, 4)"),
        ["4x", "3", "4"]
    );
    assert_eq!(
        typed_numbers("V1^2 of m_0, pi^2/8 = {x}, 1/{w:.1}, fig5_sensitivity"),
        Vec::<String>::new()
    );
    assert_eq!(typed_numbers("{{not a placeholder}} 10 km/s"), ["10"]);
    let code = "// 43 in a comment\nlet c = 'x'; fn f<'a>() {}\nlet s = r#\"raw 7 \"#;\nlet t = \"a \\\n    12 b {y}\";";
    let literals = string_literals(code);
    assert_eq!(
        literals,
        [(3, "raw 7 ".to_owned()), (4, "a 12 b {y}".to_owned())]
    );
    assert_eq!(typed_numbers(&literals[1].1), ["12"]);
}
