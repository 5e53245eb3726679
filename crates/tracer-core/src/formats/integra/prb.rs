//! `.prb` part-to-attribute maps. Lists of one word a line, each opened by its keyword and
//! closed by `enddef` or by the next list's keyword:
//!
//! ```text
//! product pproom2        the product (a name; opens no list)
//!   attrs                attribute ids, upper case (A000001 for the .atr's a000001)
//!   parts                part names: part i of the brep is parts[i] and uses attrs[i]
//!   mapp                 texture mapping per part (`none` or a mapping name)
//! ```
//!
//! IPUR writes the lists in either order, with or without the `enddef`s.

use super::error::IntegraError;
use super::lines;
use std::path::Path;

/// One list entry and its line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PrbItem {
    pub name: String,
    pub line: usize,
}

/// A `.prb` file as written.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Prb {
    /// `product NAME`, if given.
    pub product: Option<PrbItem>,
    pub attrs: Vec<PrbItem>,
    pub parts: Vec<PrbItem>,
    pub mapp: Vec<PrbItem>,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum List {
    Attrs,
    Parts,
    Mapp,
}

impl List {
    fn keyword(self) -> &'static str {
        match self {
            List::Attrs => "attrs",
            List::Parts => "parts",
            List::Mapp => "mapp",
        }
    }
}

/// Reads a `.prb` file's bytes (`path` only names it in messages).
pub fn parse_prb(bytes: &[u8], path: &Path) -> Result<Prb, IntegraError> {
    let text = lines::decode(bytes, path)?;
    let mut prb = Prb::default();
    let mut open: Option<List> = None;
    let mut seen: Vec<(List, usize)> = Vec::new();
    for line in lines::lines(&text) {
        let list = [List::Attrs, List::Parts, List::Mapp]
            .into_iter()
            .find(|l| line.is(l.keyword()));
        if line.is("product") {
            let name = lines::word(path, &line)?;
            if let Some(first) = &prb.product {
                return Err(IntegraError::new(
                    path,
                    line.no,
                    format!("a second `product` (the first is at line {})", first.line),
                ));
            }
            prb.product = Some(PrbItem {
                name: name.to_owned(),
                line: line.no,
            });
            open = None;
        } else if let Some(list) = list {
            if line.words.len() > 1 {
                return Err(IntegraError::new(
                    path,
                    line.no,
                    format!("`{}` stands alone on its line", list.keyword()),
                ));
            }
            if let Some((_, first)) = seen.iter().find(|(l, _)| *l == list) {
                return Err(IntegraError::new(
                    path,
                    line.no,
                    format!(
                        "a second `{}` list (the first is at line {first})",
                        list.keyword()
                    ),
                ));
            }
            seen.push((list, line.no));
            open = Some(list);
        } else if line.is("enddef") {
            if open.take().is_none() {
                return Err(IntegraError::new(
                    path,
                    line.no,
                    "`enddef` without an open `attrs`, `parts` or `mapp` list",
                ));
            }
        } else {
            let Some(list) = open else {
                return Err(IntegraError::new(
                    path,
                    line.no,
                    format!(
                        "expected `product`, `attrs`, `parts` or `mapp`, found `{}`",
                        line.key()
                    ),
                ));
            };
            let [name] = line.words[..] else {
                return Err(IntegraError::new(
                    path,
                    line.no,
                    format!("one name a line in the `{}` list", list.keyword()),
                ));
            };
            let item = PrbItem {
                name: name.to_owned(),
                line: line.no,
            };
            match list {
                List::Attrs => prb.attrs.push(item),
                List::Parts => prb.parts.push(item),
                List::Mapp => prb.mapp.push(item),
            }
        }
    }
    Ok(prb)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn both_layouts_read_alike() {
        let top = "product p\n  attrs\n    A000001\n    A000002\n  enddef\n  parts\n    p_1\n    p_2\n  enddef\n";
        let folder = ";; c\n  parts\n p_1\n p_2\n enddef\n product p\n attrs\n A000001\n A000002\n mapp\n none\n set_x\n enddef\n";
        let a = parse_prb(top.as_bytes(), Path::new("a.prb")).unwrap();
        let b = parse_prb(folder.as_bytes(), Path::new("b.prb")).unwrap();
        let names = |v: &[PrbItem]| v.iter().map(|i| i.name.clone()).collect::<Vec<_>>();
        assert_eq!(names(&a.attrs), names(&b.attrs));
        assert_eq!(names(&a.parts), ["p_1", "p_2"]);
        assert_eq!(names(&b.mapp), ["none", "set_x"]);
        assert_eq!(a.parts[1].line, 8);
    }

    #[test]
    fn errors_name_file_and_line() {
        for (text, message) in [
            (
                "A000001\n",
                "x.prb:1: expected `product`, `attrs`, `parts` or `mapp`, found `A000001`",
            ),
            (
                "parts\na b\n",
                "x.prb:2: one name a line in the `parts` list",
            ),
            (
                "parts\nenddef\nparts\n",
                "x.prb:3: a second `parts` list (the first is at line 1)",
            ),
            (
                "enddef\n",
                "x.prb:1: `enddef` without an open `attrs`, `parts` or `mapp` list",
            ),
        ] {
            let err = parse_prb(text.as_bytes(), Path::new("x.prb")).unwrap_err();
            assert_eq!(err.to_string(), message);
        }
    }
}
