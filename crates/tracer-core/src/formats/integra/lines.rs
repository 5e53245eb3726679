//! What the Integra text files share: lines of blank-separated words, `;;` comments, blocks
//! `Keyword NAME ... enddef`, and the checks on the values keys carry.

use super::error::IntegraError;
use std::path::Path;

/// Largest Integra file read (bytes): real ones are a few kB.
pub const MAX_FILE_BYTES: usize = 16 << 20;

/// One line with data: its 1-based number and its words (comment removed).
#[derive(Clone, Debug)]
pub(crate) struct Line<'a> {
    pub no: usize,
    pub words: Vec<&'a str>,
}

impl<'a> Line<'a> {
    /// The first word (every line has one).
    pub fn key(&self) -> &'a str {
        self.words.first().copied().unwrap_or("")
    }

    pub fn is(&self, keyword: &str) -> bool {
        self.key().eq_ignore_ascii_case(keyword)
    }

    /// The words after the key.
    pub fn values(&self) -> &[&'a str] {
        self.words.get(1..).unwrap_or(&[])
    }
}

/// A block: `Keyword NAME` on its own line, the lines up to `enddef`.
#[derive(Clone, Debug)]
pub(crate) struct Block<'a> {
    pub keyword: &'a str,
    pub name: &'a str,
    pub line: usize,
    pub body: Vec<Line<'a>>,
}

/// The file's text: UTF-8, else Latin-1 (files written on Windows); binary data is refused.
pub(crate) fn decode(bytes: &[u8], path: &Path) -> Result<String, IntegraError> {
    if bytes.len() > MAX_FILE_BYTES {
        return Err(IntegraError::new(
            path,
            0,
            format!(
                "{} bytes: larger than any Integra file ({MAX_FILE_BYTES})",
                bytes.len()
            ),
        ));
    }
    let binary = bytes
        .iter()
        .position(|&b| b < 0x20 && !matches!(b, b'\n' | b'\r' | b'\t' | 0x0c | 0x1a));
    if let Some(at) = binary {
        let line = 1 + bytes[..at].iter().filter(|&&b| b == b'\n').count();
        return Err(IntegraError::new(
            path,
            line,
            "binary data: not an Integra text file",
        ));
    }
    Ok(match std::str::from_utf8(bytes) {
        Ok(s) => s.to_owned(),
        Err(_) => bytes.iter().map(|&b| char::from(b)).collect(),
    })
}

/// The lines that hold data, numbered from 1. LF, CRLF and lone CR all end lines.
pub(crate) fn lines(text: &str) -> Vec<Line<'_>> {
    let mut out = Vec::new();
    let mut no = 0;
    for raw in text.split('\n') {
        // A lone CR also ends a line; CRLF leaves one CR at the end, which trimming removes.
        let pieces: Vec<&str> = raw.trim_end_matches('\r').split('\r').collect();
        for piece in pieces {
            no += 1;
            let data = piece.split(";;").next().unwrap_or("");
            let words: Vec<&str> = data.split_whitespace().collect();
            if !words.is_empty() {
                out.push(Line { no, words });
            }
        }
    }
    out
}

/// Splits lines into blocks. Every line outside a block must open one (`Keyword NAME`); a block
/// ends at `enddef`. `what` names the file kind in messages.
pub(crate) fn blocks<'a>(
    lines: Vec<Line<'a>>,
    path: &Path,
    what: &str,
) -> Result<Vec<Block<'a>>, IntegraError> {
    let mut out = Vec::new();
    let mut open: Option<Block<'a>> = None;
    for line in lines {
        match open.as_mut() {
            Some(_) if line.is("enddef") => {
                if line.words.len() > 1 {
                    return Err(IntegraError::new(
                        path,
                        line.no,
                        "nothing may follow `enddef` on its line",
                    ));
                }
                out.extend(open.take());
            }
            Some(block) => block.body.push(line),
            None if line.is("enddef") => {
                return Err(IntegraError::new(
                    path,
                    line.no,
                    "`enddef` without an open block",
                ));
            }
            None => {
                let [keyword, name] = line.words[..] else {
                    return Err(IntegraError::new(
                        path,
                        line.no,
                        format!(
                            "expected a block `Keyword NAME` of a {what} file, found `{}`",
                            line.words.join(" ")
                        ),
                    ));
                };
                open = Some(Block {
                    keyword,
                    name,
                    line: line.no,
                    body: Vec::new(),
                });
            }
        }
    }
    if let Some(block) = open {
        return Err(IntegraError::new(
            path,
            block.line,
            format!(
                "block `{} {}` has no `enddef` (the file ends first)",
                block.keyword, block.name
            ),
        ));
    }
    Ok(out)
}

/// A finite number; `what` says what it is for the message.
pub(crate) fn number(
    path: &Path,
    line: usize,
    word: &str,
    what: &str,
) -> Result<f64, IntegraError> {
    match word.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(IntegraError::new(
            path,
            line,
            format!("{what}: `{word}` is not a finite number"),
        )),
        Err(_) => Err(IntegraError::new(
            path,
            line,
            format!("{what}: expected a number, found `{word}`"),
        )),
    }
}

/// Exactly `N` numbers after the key.
pub(crate) fn numbers<const N: usize>(path: &Path, line: &Line) -> Result<[f64; N], IntegraError> {
    let values = line.values();
    if values.len() != N {
        return Err(IntegraError::new(
            path,
            line.no,
            format!(
                "`{}` takes {N} number{}, found {}",
                line.key(),
                if N == 1 { "" } else { "s" },
                values.len()
            ),
        ));
    }
    let mut out = [0.0; N];
    for (o, w) in out.iter_mut().zip(values) {
        *o = number(path, line.no, w, line.key())?;
    }
    Ok(out)
}

/// One word after the key.
pub(crate) fn word<'a>(path: &Path, line: &Line<'a>) -> Result<&'a str, IntegraError> {
    match line.values() {
        [w] => Ok(w),
        other => Err(IntegraError::new(
            path,
            line.no,
            format!("`{}` takes one word, found {}", line.key(), other.len()),
        )),
    }
}

/// `on` or `off`.
pub(crate) fn switch(path: &Path, line: &Line) -> Result<bool, IntegraError> {
    let w = word(path, line)?;
    match w.to_ascii_lowercase().as_str() {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err(IntegraError::new(
            path,
            line.no,
            format!("`{}` takes on or off, found `{w}`", line.key()),
        )),
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn line_ends_comments_and_blocks() {
        let text = ";; head\r\nAttr a\r  kd 0.5 ;; diffuse\n\nenddef\r\n";
        let ls = lines(text);
        assert_eq!(ls.iter().map(|l| l.no).collect::<Vec<_>>(), [2, 3, 5]);
        let bs = blocks(ls, Path::new("x.atr"), ".atr").unwrap();
        assert_eq!((bs[0].keyword, bs[0].name, bs[0].line), ("Attr", "a", 2));
        assert_eq!(bs[0].body[0].words, ["kd", "0.5"]);
        let err = blocks(lines("Attr a\nkd 1\n"), Path::new("x.atr"), ".atr").unwrap_err();
        assert_eq!(
            err.to_string(),
            "x.atr:1: block `Attr a` has no `enddef` (the file ends first)"
        );
    }
}
