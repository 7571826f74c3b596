//! The text of the ASCII formats: meaningful lines with their numbers, their fields, and the
//! numbers in them. Every error names the file and the line.

use std::path::Path;

use crate::error::{Error, Result};

/// A syntax error at line `line` of `path`.
pub(super) fn error_at(path: &Path, line: usize, message: impl std::fmt::Display) -> Error {
    Error::invalid_input(format!("{}:{line}: {message}", path.display()))
}

/// `bytes` as text, or an error naming the line of the first byte that is not UTF-8.
pub(super) fn utf8<'a>(path: &Path, bytes: &'a [u8], first_line: usize) -> Result<&'a str> {
    std::str::from_utf8(bytes).map_err(|e| {
        let before = &bytes[..e.valid_up_to()];
        let line = first_line + before.iter().filter(|&&b| b == b'\n').count();
        error_at(path, line, "the text is not ASCII or UTF-8")
    })
}

/// A finite real number, or `None`.
fn parse_real(token: &str) -> Option<f64> {
    token.parse::<f64>().ok().filter(|x| x.is_finite())
}

/// The meaningful lines of a text: blank lines and comments (from the comment character to
/// the end of the line) left out.
pub(super) struct Lines<'a> {
    path: &'a Path,
    lines: std::iter::Enumerate<std::str::Lines<'a>>,
    comment: Option<char>,
    /// The number of the first line of the text.
    first: usize,
    /// The number of the last line read, meaningful or not (`first - 1` before any).
    last: usize,
}

impl<'a> Lines<'a> {
    /// The lines of `text`, numbered from `first`; `comment` starts a comment, if any.
    pub(super) fn new(path: &'a Path, text: &'a str, comment: Option<char>, first: usize) -> Self {
        Lines {
            path,
            lines: text.lines().enumerate(),
            comment,
            first,
            last: first.saturating_sub(1),
        }
    }

    pub(super) fn path(&self) -> &'a Path {
        self.path
    }

    /// The next meaningful line, if any.
    pub(super) fn next_line(&mut self) -> Option<Line<'a>> {
        for (k, text) in self.lines.by_ref() {
            self.last = self.first + k;
            let text = match self.comment {
                Some(c) => text.split(c).next().unwrap_or(""),
                None => text,
            };
            let fields: Vec<&str> = text.split_ascii_whitespace().collect();
            if !fields.is_empty() {
                return Some(Line {
                    path: self.path,
                    number: self.last,
                    fields,
                });
            }
        }
        None
    }

    /// The next meaningful line, or an error saying that `what` was expected.
    pub(super) fn expect(&mut self, what: &str) -> Result<Line<'a>> {
        self.next_line().ok_or_else(|| self.end_error(what))
    }

    /// The error of a text that ends where `what` was expected.
    pub(super) fn end_error(&self, what: &str) -> Error {
        error_at(
            self.path,
            self.last.max(self.first),
            format!("end of file where {what} was expected"),
        )
    }
}

/// A meaningful line: its number and its whitespace-separated fields.
pub(super) struct Line<'a> {
    path: &'a Path,
    pub(super) number: usize,
    pub(super) fields: Vec<&'a str>,
}

impl<'a> Line<'a> {
    /// A syntax error at this line.
    pub(super) fn error(&self, message: impl std::fmt::Display) -> Error {
        error_at(self.path, self.number, message)
    }

    /// Field `k`, or an error saying that `what` is missing.
    pub(super) fn field(&self, k: usize, what: &str) -> Result<&'a str> {
        self.fields
            .get(k)
            .copied()
            .ok_or_else(|| self.error(format!("missing {what} (field {})", k + 1)))
    }

    /// Field `k` as a finite real number.
    pub(super) fn real(&self, k: usize, what: &str) -> Result<f64> {
        let field = self.field(k, what)?;
        parse_real(field)
            .ok_or_else(|| self.error(format!("{what} \"{field}\" is not a finite number")))
    }

    /// Field `k` as an integer.
    pub(super) fn integer(&self, k: usize, what: &str) -> Result<i64> {
        let field = self.field(k, what)?;
        field
            .parse::<i64>()
            .map_err(|_| self.error(format!("{what} \"{field}\" is not an integer")))
    }

    /// Field `k` as a count (a non-negative integer).
    pub(super) fn count(&self, k: usize, what: &str) -> Result<usize> {
        let n = self.integer(k, what)?;
        usize::try_from(n).map_err(|_| self.error(format!("{what} {n} is negative")))
    }

    /// The point of fields `k..k + 3`.
    pub(super) fn point(&self, k: usize) -> Result<[f64; 3]> {
        Ok([
            self.real(k, "x")?,
            self.real(k + 1, "y")?,
            self.real(k + 2, "z")?,
        ])
    }

    /// Field `k` as a 0-based index below `n`, written with the numbering `base`.
    pub(super) fn index(&self, k: usize, base: i64, n: usize, what: &str) -> Result<u32> {
        let i = self.integer(k, what)?;
        to_index(i.saturating_sub(base), n).ok_or_else(|| {
            self.error(format!(
                "{what} {i} is out of range ({base} to {})",
                base + n as i64 - 1
            ))
        })
    }
}

/// `i` as a vertex index, when it is in `0..n`.
pub(super) fn to_index(i: i64, n: usize) -> Option<u32> {
    u32::try_from(i).ok().filter(|&i| (i as usize) < n)
}

/// A field of a text read field by field across lines, with its line number.
#[derive(Clone, Copy)]
pub(super) struct Token<'a> {
    pub(super) text: &'a str,
    pub(super) line: usize,
}

/// The fields of a text one after the other, whatever the lines.
pub(super) struct Tokens<'a> {
    lines: Lines<'a>,
    /// The fields of the current line not read yet, in reverse order.
    pending: Vec<&'a str>,
    line: usize,
}

impl<'a> Tokens<'a> {
    pub(super) fn new(lines: Lines<'a>) -> Self {
        Tokens {
            line: lines.first,
            lines,
            pending: Vec::new(),
        }
    }

    /// A syntax error at line `line`.
    pub(super) fn error_at(&self, line: usize, message: impl std::fmt::Display) -> Error {
        error_at(self.lines.path(), line, message)
    }

    /// The line of the last field read.
    pub(super) fn line(&self) -> usize {
        self.line
    }

    /// True when no field is left.
    pub(super) fn at_end(&mut self) -> bool {
        self.fill();
        self.pending.is_empty()
    }

    /// Reads the next line into `pending` when the current one is used up.
    fn fill(&mut self) {
        while self.pending.is_empty() {
            let Some(line) = self.lines.next_line() else {
                return;
            };
            self.line = line.number;
            self.pending = line.fields;
            self.pending.reverse();
        }
    }

    /// The next field, or an error saying that `what` was expected.
    pub(super) fn next(&mut self, what: &str) -> Result<Token<'a>> {
        self.fill();
        match self.pending.pop() {
            Some(text) => Ok(Token {
                text,
                line: self.line,
            }),
            None => Err(self.lines.end_error(what)),
        }
    }

    /// Drops the fields left on the current line.
    pub(super) fn skip_line(&mut self) {
        self.pending.clear();
    }

    /// Reads the keyword `word` (ASCII case ignored).
    pub(super) fn keyword(&mut self, word: &str) -> Result<Token<'a>> {
        let token = self.next(&format!("\"{word}\""))?;
        if !token.text.eq_ignore_ascii_case(word) {
            return Err(self.error_at(
                token.line,
                format!("expected \"{word}\", found \"{}\"", token.text),
            ));
        }
        Ok(token)
    }

    /// The next field as a finite real number.
    pub(super) fn real(&mut self, what: &str) -> Result<f64> {
        let token = self.next(what)?;
        parse_real(token.text).ok_or_else(|| {
            self.error_at(
                token.line,
                format!("{what} \"{}\" is not a finite number", token.text),
            )
        })
    }

    /// The next field as an integer.
    pub(super) fn integer(&mut self, what: &str) -> Result<i64> {
        let token = self.next(what)?;
        token.text.parse::<i64>().map_err(|_| {
            self.error_at(
                token.line,
                format!("{what} \"{}\" is not an integer", token.text),
            )
        })
    }
}
