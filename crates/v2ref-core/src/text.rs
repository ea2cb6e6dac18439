//! Text from data made safe to show: a name or cell read from a user's
//! file may hold terminal control sequences (an escape that recolours the
//! terminal, retitles its window or moves the cursor), which must reach a
//! terminal as visible characters, never as commands.

use std::borrow::Cow;

/// `text` with every control character but a line feed and a tab written
/// as Rust writes it escaped (`\u{1b}` for ESC, `\r` for a carriage
/// return); unchanged, without a copy, when it has none.
pub fn printable(text: &str) -> Cow<'_, str> {
    let shown = |c: char| !c.is_control() || c == '\n' || c == '\t';
    if text.chars().all(shown) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if shown(c) {
            out.push(c);
        } else {
            out.extend(c.escape_default());
        }
    }
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_shown_escaped() {
        assert_eq!(printable("\u{1b}[31mRED"), "\\u{1b}[31mRED");
        assert_eq!(printable("a\rb\u{7}"), "a\\rb\\u{7}");
        assert_eq!(printable("two\nlines\tok"), "two\nlines\tok");
        assert!(matches!(printable("α Cen"), Cow::Borrowed(_)));
    }
}
