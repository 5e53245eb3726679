//! The bare `.brs` file IPUR writes beside a `.shp`: one brep's sections with no
//! `define`/`enddef` around them, then an optional `shading` section of one value per part,
//! which is checked and dropped.

use std::path::Path;

use super::brep::{BrepReader, header_count, read_list};
use super::description::BrepDef;
use super::error::ShpError;
use super::lexer::Lexer;

pub(crate) fn parse(bytes: &[u8], path: &Path, name: &str) -> Result<BrepDef, ShpError> {
    let mut lex = Lexer::new(bytes, path)?;
    let mut reader = BrepReader::new(name.to_string(), path.to_path_buf(), 0);
    let mut shading_done = false;
    while let Some(line) = lex.next_line()? {
        if shading_done {
            let context = format!("the .brs file of brep {name}");
            return Err(lex.unexpected(
                &line,
                line.keyword(),
                context,
                "nothing after `shading`".into(),
            ));
        }
        if line.is("shading") && reader.has_triangles() {
            // IPUR writes a bare `shading`; a count, if given, overrides the part count.
            let count = if line.words().nth(1).is_some() {
                header_count(&lex, &line)?
            } else {
                reader.part_count()
            };
            let list = format!("the `shading` list of brep {name} (one per part)");
            read_list(&mut lex, count as usize, &list, |lex, token, line| {
                lex.float(token, line, || format!("shading value of brep {name}"))
                    .map(|_| ())
            })?;
            shading_done = true;
        } else if !reader.section(&mut lex, line)? {
            let context = format!("the .brs file of brep {name}");
            let expected = match reader.has_triangles() {
                true => format!("{} or `shading`", reader.expected()),
                false => reader.expected().to_string(),
            };
            return Err(lex.unexpected(&line, line.keyword(), context, expected));
        }
    }
    if !reader.has_vertices() {
        let what = format!("the .brs file of brep {name} has no `vertices N` section");
        return Err(ShpError::UnexpectedEnd {
            path: path.to_path_buf(),
            line: lex.line_no(),
            what,
        });
    }
    Ok(reader.finish())
}
