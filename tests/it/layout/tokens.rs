//! The tokens of Rust source that the import scan ([`super::scan`]) reads: identifiers, `::`,
//! braces, commas, semicolons and `*`, with comments, string, raw-string and character literals
//! left out (a lifetime is not a character literal).

/// A token of Rust source with comments, strings and character literals removed.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Tok {
    Ident(String),
    Path,
    Open,
    Close,
    Comma,
    Semi,
    Star,
    Other(char),
}

/// The tokens of `text` that the import scan needs.
pub(super) fn tokens(text: &str) -> Vec<Tok> {
    let c: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        let ch = c[i];
        let next = c.get(i + 1).copied();
        if ch == '/' && next == Some('/') {
            while i < c.len() && c[i] != '\n' {
                i += 1;
            }
        } else if ch == '/' && next == Some('*') {
            i += 2;
            while i + 1 < c.len() && !(c[i] == '*' && c[i + 1] == '/') {
                i += 1;
            }
            i += 2;
        } else if ch == 'r' && (next == Some('"') || next == Some('#')) && raw_string(&c, i) {
            let mut j = i + 1;
            let mut hashes = 0;
            while c[j] == '#' {
                hashes += 1;
                j += 1;
            }
            j += 1;
            loop {
                if j >= c.len() {
                    break;
                }
                if c[j] == '"' && (0..hashes).all(|h| c.get(j + 1 + h) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            i = j;
        } else if ch == '"' {
            i += 1;
            while i < c.len() && c[i] != '"' {
                i += if c[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
        } else if ch == '\'' && char_literal_len(&c, i) > 0 {
            i += char_literal_len(&c, i);
        } else if ch.is_alphabetic() || ch == '_' {
            let start = i;
            while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
                i += 1;
            }
            out.push(Tok::Ident(c[start..i].iter().collect()));
        } else {
            out.push(match ch {
                ':' if next == Some(':') => {
                    i += 1;
                    Tok::Path
                }
                '{' => Tok::Open,
                '}' => Tok::Close,
                ',' => Tok::Comma,
                ';' => Tok::Semi,
                '*' => Tok::Star,
                _ => Tok::Other(ch),
            });
            i += 1;
        }
    }
    out.retain(|t| !matches!(t, Tok::Other(c) if c.is_whitespace()));
    out
}

/// Whether a raw string literal (`r"`, `r#"`) starts at `i` (not an identifier ending in `r`).
fn raw_string(c: &[char], i: usize) -> bool {
    let after_ident = i > 0 && (c[i - 1].is_alphanumeric() || c[i - 1] == '_');
    let mut j = i + 1;
    while c.get(j) == Some(&'#') {
        j += 1;
    }
    !after_ident && c.get(j) == Some(&'"')
}

/// The length of a character literal starting at `i` (`'x'`, `'\n'`, `'\''`), or 0 for a
/// lifetime.
fn char_literal_len(c: &[char], i: usize) -> usize {
    match (c.get(i + 1), c.get(i + 2), c.get(i + 3)) {
        (Some('\\'), _, _) => {
            let mut j = i + 2;
            while j < c.len() && c[j] != '\'' {
                j += 1;
            }
            j + 1 - i
        }
        (Some(_), Some('\''), _) => 3,
        _ => 0,
    }
}
