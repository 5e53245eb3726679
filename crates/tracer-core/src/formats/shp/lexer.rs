//! Bytes to lines and numbers. A line is what precedes `;;`, trimmed; blank lines are skipped.
//! Lines end in LF, CRLF or a lone CR. Only the data part of a line must be UTF-8: comment text
//! is never parsed, so whatever encoding a writer used for it does no harm.

use super::bytes::find_break_or_semicolon;
pub(crate) use super::bytes::{excerpt, parse_u32};
use std::path::Path;
use std::str::SplitAsciiWhitespace;

use super::error::ShpError;
use super::memory::MemoryBudget;

/// How much of the file start is inspected to tell text from binary.
const SNIFF_BYTES: usize = 1024;
/// An ESRI shapefile starts with the big-endian file code 9994.
const ESRI_MAGIC: [u8; 4] = [0x00, 0x00, 0x27, 0x0A];
const UTF8_BOM: [u8; 3] = [0xEF, 0xBB, 0xBF];

/// One non-blank line: its data without comment and surrounding blanks.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Line<'a> {
    /// 1-based line number.
    pub no: usize,
    /// Never empty, except for what `after_keyword` returns.
    pub text: &'a str,
}

impl<'a> Line<'a> {
    pub fn words(&self) -> SplitAsciiWhitespace<'a> {
        self.text.split_ascii_whitespace()
    }

    /// The line after its first word (possibly empty), for `rotation 0 0 0` and the like.
    pub fn after_keyword(&self) -> Line<'a> {
        let rest = self
            .text
            .trim_start_matches(|c: char| !c.is_ascii_whitespace());
        Line {
            no: self.no,
            text: rest.trim_ascii_start(),
        }
    }

    /// The first word; `text` is never empty, so there always is one.
    pub fn keyword(&self) -> &'a str {
        self.words().next().unwrap_or("")
    }

    /// Whether the first word is `keyword`, ignoring ASCII case.
    pub fn is(&self, keyword: &str) -> bool {
        self.keyword().eq_ignore_ascii_case(keyword)
    }
}

/// Walks a file's lines, remembering the path and line number for errors.
#[derive(Debug)]
pub(crate) struct Lexer<'a> {
    bytes: &'a [u8],
    path: &'a Path,
    /// Byte offset of the next unread line.
    pos: usize,
    /// Number of the last line read (blank ones included).
    line_no: usize,
    /// What the counts declared so far need in memory, against what the machine has.
    memory: MemoryBudget,
}

impl<'a> Lexer<'a> {
    /// Rejects binary and UTF-16 input up front; skips a UTF-8 byte order mark.
    pub fn new(bytes: &'a [u8], path: &'a Path) -> Result<Self, ShpError> {
        if bytes.starts_with(&[0xFF, 0xFE]) || bytes.starts_with(&[0xFE, 0xFF]) {
            return Err(ShpError::NotUtf8 {
                path: path.to_path_buf(),
                line: 1,
                column: 1,
            });
        }
        if looks_binary(bytes) {
            return Err(ShpError::Binary {
                path: path.to_path_buf(),
            });
        }
        let pos = if bytes.starts_with(&UTF8_BOM) {
            UTF8_BOM.len()
        } else {
            0
        };
        Ok(Self {
            bytes,
            path,
            pos,
            line_no: 0,
            memory: MemoryBudget::from_system(),
        })
    }

    pub fn path(&self) -> &'a Path {
        self.path
    }

    /// The number of the last line read; at the end of the file, the file's last line.
    pub fn line_no(&self) -> usize {
        self.line_no.max(1)
    }

    /// The next non-blank line, or `None` at the end of the file.
    pub fn next_line(&mut self) -> Result<Option<Line<'a>>, ShpError> {
        while let Some((data, line_no)) = self.raw_line() {
            let text = data.trim_ascii_start();
            let lead = data.len() - text.len();
            let text = text.trim_ascii_end();
            if text.is_empty() {
                continue;
            }
            return match std::str::from_utf8(text) {
                Ok(text) => Ok(Some(Line { no: line_no, text })),
                Err(e) => Err(ShpError::NotUtf8 {
                    path: self.path.to_path_buf(),
                    line: line_no,
                    column: lead + e.valid_up_to() + 1,
                }),
            };
        }
        Ok(None)
    }

    /// The next non-blank line; the end of the file is an error saying what was still expected.
    pub fn expect_line(&mut self, what: impl FnOnce() -> String) -> Result<Line<'a>, ShpError> {
        match self.next_line()? {
            Some(line) => Ok(line),
            None => Err(ShpError::UnexpectedEnd {
                path: self.path.to_path_buf(),
                line: self.line_no(),
                what: what(),
            }),
        }
    }

    /// Adds `count` items of about `bytes_each` bytes (in the built scene) to the file's memory
    /// estimate; an error when the scene would not fit in the memory available.
    pub fn declare_memory(
        &mut self,
        line: &Line<'_>,
        count: u32,
        bytes_each: u64,
    ) -> Result<(), ShpError> {
        self.memory
            .declare(self.path, line.no, line.keyword(), count, bytes_each)
    }

    #[cfg(test)]
    pub fn set_memory_budget(&mut self, memory: MemoryBudget) {
        self.memory = memory;
    }

    /// Rejects `count` items that the rest of the file cannot hold, before anything is allocated
    /// for them. Each item takes at least `min_bytes` bytes, separator included (a vertex or
    /// triangle line at least `0 0 0` and its line break), so the bytes left bound the number of
    /// item lines left; counting lines exactly would cost a pass over the file.
    pub fn check_room(
        &self,
        line: &Line<'_>,
        count: u32,
        items: &'static str,
        min_bytes: usize,
    ) -> Result<(), ShpError> {
        let bytes_left = self.bytes.len().saturating_sub(self.pos);
        let fits = (bytes_left + 1) / min_bytes.max(1);
        if count as usize <= fits {
            return Ok(());
        }
        Err(ShpError::CountTooLarge {
            path: self.path.to_path_buf(),
            line: line.no,
            keyword: line.keyword().to_string(),
            count,
            items,
            room: format!("{bytes_left} bytes follow, room for at most {fits} lines"),
        })
    }

    /// A finite `f64`; `what` names the item for the message and is built only on error.
    pub fn float(
        &self,
        token: &str,
        line: usize,
        what: impl FnOnce() -> String,
    ) -> Result<f64, ShpError> {
        match token.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok(value),
            Ok(_) => Err(ShpError::NonFinite {
                path: self.path.to_path_buf(),
                line,
                what: what(),
                token: excerpt(token),
            }),
            Err(_) => Err(self.malformed(token, line, what(), "a number")),
        }
    }

    /// A whole number `0..=u32::MAX` (`+` allowed, `-0` read as 0).
    pub fn whole(
        &self,
        token: &str,
        line: usize,
        what: impl FnOnce() -> String,
    ) -> Result<u32, ShpError> {
        parse_u32(token).ok_or_else(|| {
            self.malformed(token, line, what(), "a whole number from 0 to 4294967295")
        })
    }

    /// Exactly three values on `line`, each read by `parse`. A word in place of the first value
    /// means a section ended early, which is reported as an unexpected keyword.
    pub fn three<T: Copy + Default>(
        &self,
        line: &Line<'_>,
        what: &dyn Fn() -> String,
        parse: impl Fn(&str) -> Result<T, ShpError>,
    ) -> Result<[T; 3], ShpError> {
        let mut out = [T::default(); 3];
        let mut words = line.words();
        for (i, slot) in out.iter_mut().enumerate() {
            let Some(token) = words.next() else {
                return Err(ShpError::MissingNumber {
                    path: self.path.to_path_buf(),
                    line: line.no,
                    what: what(),
                    expected: 3,
                    found: i,
                });
            };
            *slot = match parse(token) {
                Ok(value) => value,
                // A word that is not a number at all; `nan` and `inf` are numbers, and say so.
                Err(ShpError::MalformedNumber { .. })
                    if i == 0 && token.starts_with(|c: char| c.is_ascii_alphabetic()) =>
                {
                    return Err(self.unexpected(line, token, what(), "3 numbers".into()));
                }
                Err(e) => return Err(e),
            };
        }
        if let Some(token) = words.next() {
            return Err(ShpError::ExtraValue {
                path: self.path.to_path_buf(),
                line: line.no,
                what: what(),
                token: excerpt(token),
                expected: 3,
            });
        }
        Ok(out)
    }

    pub fn malformed(
        &self,
        token: &str,
        line: usize,
        what: String,
        expected: &'static str,
    ) -> ShpError {
        ShpError::MalformedNumber {
            path: self.path.to_path_buf(),
            line,
            what,
            token: excerpt(token),
            expected,
        }
    }

    pub fn unexpected(
        &self,
        line: &Line<'_>,
        found: &str,
        context: String,
        expected: String,
    ) -> ShpError {
        ShpError::UnexpectedKeyword {
            path: self.path.to_path_buf(),
            line: line.no,
            found: excerpt(found),
            context,
            expected,
        }
    }

    /// The next line's data (up to `;;`, untrimmed) and number, or `None` at the end.
    fn raw_line(&mut self) -> Option<(&'a [u8], usize)> {
        let rest = self.bytes.get(self.pos..).filter(|rest| !rest.is_empty())?;
        let mut data_end = None;
        let mut from = 0;
        let end = loop {
            let Some(found) = rest.get(from..).and_then(find_break_or_semicolon) else {
                break rest.len();
            };
            let at = from + found;
            if rest[at] != b';' {
                break at;
            }
            if data_end.is_none() && rest.get(at + 1) == Some(&b';') {
                data_end = Some(at);
            }
            from = at + 1;
        };
        let next = match rest.get(end..end + 2) {
            Some(b"\r\n") => end + 2,
            _ => (end + 1).min(rest.len()),
        };
        self.pos += next;
        self.line_no += 1;
        Some((&rest[..data_end.unwrap_or(end)], self.line_no))
    }
}

/// An ESRI shapefile's magic, a NUL or many control characters near the start.
fn looks_binary(bytes: &[u8]) -> bool {
    if bytes.starts_with(&ESRI_MAGIC) {
        return true;
    }
    let head = &bytes[..bytes.len().min(SNIFF_BYTES)];
    if head.contains(&0) {
        return true;
    }
    let control = head
        .iter()
        .filter(|&&b| (b < 0x20 && !matches!(b, b'\t' | b'\n' | b'\r' | 0x0C)) || b == 0x7F)
        .count();
    control * 16 > head.len()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    fn lines(text: &[u8]) -> Vec<(usize, String)> {
        let path = Path::new("t.shp");
        let mut lexer = Lexer::new(text, path).unwrap();
        let mut out = Vec::new();
        while let Some(line) = lexer.next_line().unwrap() {
            out.push((line.no, line.text.to_string()));
        }
        out
    }

    #[test]
    fn line_ends_comments_and_blanks() {
        let got = lines(b"a ;; c\r\n\r\n\t b c \rd;;x;;y\n;; only comment\ne");
        let want = [(1, "a"), (3, "b c"), (4, "d"), (6, "e")];
        assert_eq!(got, want.map(|(n, s)| (n, s.to_string())));
    }

    #[test]
    fn single_semicolon_is_data() {
        assert_eq!(lines(b"a;b ;; c"), vec![(1, "a;b".to_string())]);
    }

    #[test]
    fn bom_skipped_and_comment_bytes_unchecked() {
        assert_eq!(
            lines(b"\xEF\xBB\xBFx ;; \x93\xFA\x96\x7B\ny"),
            vec![(1, "x".into()), (2, "y".into())]
        );
    }

    #[test]
    fn non_utf8_data_names_line_and_column() {
        let mut lexer = Lexer::new(b"ok\n  ab\xFFc\n", Path::new("t.shp")).unwrap();
        lexer.next_line().unwrap();
        let err = lexer.next_line().unwrap_err();
        assert!(
            matches!(
                err,
                ShpError::NotUtf8 {
                    line: 2,
                    column: 5,
                    ..
                }
            ),
            "{err}"
        );
    }

    #[test]
    fn whole_numbers() {
        assert_eq!(parse_u32("0"), Some(0));
        assert_eq!(parse_u32("+17"), Some(17));
        assert_eq!(parse_u32("-0"), Some(0));
        assert_eq!(parse_u32("4294967295"), Some(u32::MAX));
        for bad in [
            "",
            "+",
            "-",
            "-1",
            "4294967296",
            "1.0",
            "1e3",
            "x",
            "99999999999999999999",
        ] {
            assert_eq!(parse_u32(bad), None, "{bad}");
        }
    }

    /// Regression (found while tabulating bad inputs): `nan 0 0` was reported as an unexpected
    /// keyword `nan` instead of as a number that is not finite, unlike `0 nan 0`.
    #[test]
    fn nan_and_inf_first_are_non_finite_numbers_not_keywords() {
        let path = Path::new("t.shp");
        let lexer = Lexer::new(b"", path).unwrap();
        for text in [
            "nan 0 0",
            "0 nan 0",
            "inf 0 0",
            "-inf 1 2",
            "NaN 0 0",
            "infinity 0 0",
        ] {
            let line = Line { no: 4, text };
            let what = || "vertex 1".to_string();
            let err = lexer
                .three(&line, &what, |t| lexer.float(t, 4, what))
                .unwrap_err();
            assert!(
                matches!(err, ShpError::NonFinite { line: 4, .. }),
                "{text}: {err}"
            );
        }
        let line = Line {
            no: 4,
            text: "triangles 3",
        };
        let what = || "vertex 1".to_string();
        let err = lexer
            .three(&line, &what, |t| lexer.float(t, 4, what))
            .unwrap_err();
        assert!(matches!(err, ShpError::UnexpectedKeyword { .. }), "{err}");
    }

    #[test]
    fn binary_detection() {
        assert!(looks_binary(&[0, 0, 0x27, 0x0A, 0, 0, 0, 0]));
        assert!(looks_binary(b"abc\0def"));
        assert!(looks_binary(b"\x01\x02\x03abc"));
        assert!(!looks_binary(b"define breps a\r\n\tvertices 1\x0C\n"));
    }
}
