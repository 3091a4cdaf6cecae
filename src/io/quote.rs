//! Quoting input in error messages: never more than a bounded prefix. An answer line of
//! a process, a field of a case file or a line of an OBJ file can be megabytes long;
//! an error that quotes it shows at most [`QUOTE_CHARS`] characters of it and says how
//! long it was.

/// The most characters of an input an error message quotes (after escaping, for
/// [`quote`]).
pub const QUOTE_CHARS: usize = 200;

/// `s` itself when it has at most [`QUOTE_CHARS`] characters, else its first
/// [`QUOTE_CHARS`] characters followed by `... (N bytes)`.
pub fn clip(s: &str) -> String {
    match s.char_indices().nth(QUOTE_CHARS) {
        None => s.to_string(),
        Some((cut, _)) => format!("{}... ({} bytes)", &s[..cut], s.len()),
    }
}

/// `s` quoted and escaped as Rust's `{:?}` does, when that takes at most
/// [`QUOTE_CHARS`] characters; else the longest prefix whose escaped form fits, quoted,
/// followed by `... (N bytes)` (the length of all of `s`).
pub fn quote(s: &str) -> String {
    let mut used = 0;
    for (i, c) in s.char_indices() {
        used += c.escape_debug().count();
        if used > QUOTE_CHARS {
            return format!("{:?}... ({} bytes)", &s[..i], s.len());
        }
    }
    format!("{s:?}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_text_is_quoted_whole_and_long_text_is_cut() {
        assert_eq!(clip("abc"), "abc");
        assert_eq!(quote("a\"b"), "\"a\\\"b\"");
        let long = "x".repeat(10_000_000);
        let c = clip(&long);
        assert!(c.len() < 300 && c.ends_with("... (10000000 bytes)"), "{c}");
        let q = quote(&long);
        assert!(q.len() < 300 && q.starts_with("\"xxx") && q.ends_with("\"... (10000000 bytes)"), "{q}");
        // Characters that escape to several are counted as written.
        let ctl = "\u{1}".repeat(1_000_000);
        assert!(quote(&ctl).len() < 300, "{}", quote(&ctl));
        let wide = "é".repeat(1000);
        assert!(clip(&wide).chars().count() < 250);
        assert_eq!(clip(&"y".repeat(QUOTE_CHARS)), "y".repeat(QUOTE_CHARS));
    }
}
