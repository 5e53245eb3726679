//! The `.shp` grammar: a sequence of blocks, each a header line and lines up to `enddef`.
//! `define breps NAME` and `set breps NAME` are read; every other block (`ProcessMesh`,
//! `Light`, `Camera`, `product` ...) is skipped up to the first `enddef`. Real files never nest
//! `enddef`s: the indented `attrs`/`parts` lists of `product` blocks and the `def` list of a
//! `Diagram` have none of their own. A skipped block that reaches the end of the file, or that
//! runs into a `define breps`/`set breps` line, is reported as missing its `enddef` rather than
//! silently swallowing geometry.

use std::collections::HashMap;
use std::path::Path;

use super::brep::BrepReader;
use super::description::{Placement, ShpDescription};
use super::error::ShpError;
use super::lexer::{Lexer, Line, excerpt};

pub(crate) fn parse(bytes: &[u8], path: &Path) -> Result<ShpDescription, ShpError> {
    let mut lex = Lexer::new(bytes, path)?;
    let mut desc = ShpDescription {
        path: path.to_path_buf(),
        ..ShpDescription::default()
    };
    let mut defined: HashMap<String, usize> = HashMap::new();
    while let Some(line) = lex.next_line()? {
        match header(&line) {
            Header::DefineBreps => {
                let name = block_name(&lex, &line)?;
                if let Some(&first_line) = defined.get(&name) {
                    return Err(ShpError::DuplicateBrep {
                        path: path.to_path_buf(),
                        line: line.no,
                        name,
                        first_line,
                    });
                }
                defined.insert(name.clone(), line.no);
                desc.breps.push(define_block(&mut lex, line, name)?);
            }
            Header::SetBreps => {
                let name = block_name(&lex, &line)?;
                desc.placements.push(set_block(&mut lex, line, name)?);
            }
            Header::Other
                if line
                    .keyword()
                    .starts_with(|c: char| c.is_ascii_alphabetic() || c == '_') =>
            {
                if line.is("enddef") {
                    return Err(top_level_error(&lex, &line));
                }
                skip_block(&mut lex, line)?;
            }
            Header::Other => return Err(top_level_error(&lex, &line)),
        }
    }
    // Without a placement still to resolve from a `.brs`, an empty scene is final.
    let unresolved = desc
        .placements
        .iter()
        .any(|p| !defined.contains_key(&p.name));
    if !unresolved && desc.breps.iter().all(|b| b.triangles.is_empty()) {
        return Err(ShpError::NoTriangles {
            path: path.to_path_buf(),
        });
    }
    Ok(desc)
}

enum Header {
    DefineBreps,
    SetBreps,
    Other,
}

fn header(line: &Line<'_>) -> Header {
    let mut words = line.words();
    let first = words.next().unwrap_or("");
    if !words
        .next()
        .is_some_and(|w| w.eq_ignore_ascii_case("breps"))
    {
        Header::Other
    } else if first.eq_ignore_ascii_case("define") {
        Header::DefineBreps
    } else if first.eq_ignore_ascii_case("set") {
        Header::SetBreps
    } else {
        Header::Other
    }
}

fn top_level_error(lex: &Lexer<'_>, line: &Line<'_>) -> ShpError {
    let expected =
        "a block such as `define breps NAME`, `set breps NAME` or `ProcessMesh`".to_string();
    lex.unexpected(
        line,
        line.keyword(),
        "the top level of the file".to_string(),
        expected,
    )
}

/// The third word of `define breps NAME` / `set breps NAME`; brep names have no blanks.
fn block_name(lex: &Lexer<'_>, line: &Line<'_>) -> Result<String, ShpError> {
    let mut words = line.words().skip(2);
    let block = || format!("{} breps", line.keyword());
    let Some(name) = words.next() else {
        return Err(ShpError::MissingName {
            path: lex.path().to_path_buf(),
            line: line.no,
            block: block(),
        });
    };
    if let Some(extra) = words.next() {
        let context = format!("`{} {}`", block(), excerpt(name));
        return Err(lex.unexpected(
            line,
            extra,
            context,
            "the end of the line (brep names have no blanks)".into(),
        ));
    }
    Ok(name.to_string())
}

fn missing_enddef(lex: &Lexer<'_>, header: &Line<'_>) -> ShpError {
    ShpError::MissingEnddef {
        path: lex.path().to_path_buf(),
        line: header.no,
        block: excerpt(header.text),
        last_line: lex.line_no(),
    }
}

fn define_block(
    lex: &mut Lexer<'_>,
    header: Line<'_>,
    name: String,
) -> Result<super::BrepDef, ShpError> {
    let mut reader = BrepReader::new(name, lex.path().to_path_buf(), header.no);
    loop {
        let Some(line) = lex.next_line()? else {
            return Err(missing_enddef(lex, &header));
        };
        if line.is("enddef") {
            return Ok(reader.finish());
        }
        if !reader.section(lex, line)? {
            let context = format!("brep {}", reader.name());
            let expected = format!("{} or `enddef`", reader.expected());
            return Err(lex.unexpected(&line, line.keyword(), context, expected));
        }
    }
}

fn set_block(lex: &mut Lexer<'_>, header: Line<'_>, name: String) -> Result<Placement, ShpError> {
    const KEYS: [&str; 3] = ["rotation", "translation", "scale"];
    let mut placement = Placement {
        name,
        source: lex.path().to_path_buf(),
        line: header.no,
        ..Placement::default()
    };
    let mut seen_at = [None::<usize>; 3];
    loop {
        let Some(line) = lex.next_line()? else {
            return Err(missing_enddef(lex, &header));
        };
        if line.is("enddef") {
            return Ok(placement);
        }
        let context = || format!("`set breps {}`", placement.name);
        let Some(key) = KEYS.iter().position(|k| line.is(k)) else {
            let expected = "`rotation`, `translation`, `scale` or `enddef`".to_string();
            return Err(lex.unexpected(&line, line.keyword(), context(), expected));
        };
        if let Some(first) = seen_at[key] {
            let expected = format!(
                "each transform once (`{}` was given at line {first})",
                KEYS[key]
            );
            return Err(lex.unexpected(&line, line.keyword(), context(), expected));
        }
        seen_at[key] = Some(line.no);
        let what = || format!("{} of {}", KEYS[key], context());
        let values = lex.three(&line.after_keyword(), &what, |token| {
            lex.float(token, line.no, what)
        })?;
        match key {
            0 => placement.rotation_deg = values,
            1 => placement.translation = values,
            _ => placement.scale = values,
        }
    }
}

/// Skips a block this reader does not use, up to its `enddef`.
fn skip_block(lex: &mut Lexer<'_>, header: Line<'_>) -> Result<(), ShpError> {
    loop {
        let Some(line) = lex.next_line()? else {
            return Err(missing_enddef(lex, &header));
        };
        if line.is("enddef") {
            return Ok(());
        }
        if !matches!(self::header(&line), Header::Other) {
            let context = format!(
                "the `{}` block opened at line {}",
                excerpt(header.text),
                header.no
            );
            let found = line.words().take(2).collect::<Vec<_>>().join(" ");
            return Err(lex.unexpected(
                &line,
                &found,
                context,
                "`enddef` first (is one missing?)".into(),
            ));
        }
    }
}
