//! The sections of one brep, shared by `define breps` blocks and `.brs` files: an optional
//! `GeoChecked` line, then `vertices N` and N lines `x y z`, `triangles M` and M lines `a b c`,
//! `parts P` and M part indices over any number of lines. Sections come in this order; trailing
//! ones may be missing (no `parts` means one part holding every triangle).

use std::path::PathBuf;

use super::description::BrepDef;
use super::error::ShpError;
use super::lexer::{Lexer, Line, parse_u32};
use super::memory::{BYTES_PER_TRIANGLE, BYTES_PER_VERTEX};

/// Shortest possible item line, `0 0 0` and its line break: bounds counts by the bytes left.
const MIN_ITEM_LINE_BYTES: usize = 6;
/// Unused parts beyond the triangle count are accepted up to this many.
const MAX_UNUSED_PARTS: u32 = 1 << 16;

/// Where a brep is in its sequence of sections.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Stage {
    Start,
    Vertices,
    Triangles,
    Parts,
}

/// Accumulates one brep section by section.
#[derive(Debug)]
pub(crate) struct BrepReader {
    def: BrepDef,
    stage: Stage,
}

impl BrepReader {
    /// `line` 0 means "the line of the `vertices` section", as for a `.brs` file.
    pub fn new(name: String, source: PathBuf, line: usize) -> Self {
        let def = BrepDef {
            name,
            source,
            line,
            ..BrepDef::default()
        };
        Self {
            def,
            stage: Stage::Start,
        }
    }

    pub fn name(&self) -> &str {
        &self.def.name
    }

    /// Whether a `vertices` section has been read.
    pub fn has_vertices(&self) -> bool {
        self.stage >= Stage::Vertices
    }

    pub fn has_triangles(&self) -> bool {
        self.stage >= Stage::Triangles
    }

    /// The part count so far: 1 until a `parts` section declares one.
    pub fn part_count(&self) -> u32 {
        if self.stage == Stage::Parts {
            self.def.part_count
        } else {
            1
        }
    }

    /// What may come next, for messages.
    pub fn expected(&self) -> &'static str {
        match self.stage {
            Stage::Start => "`GeoChecked` or `vertices N`",
            Stage::Vertices => "`triangles M`",
            Stage::Triangles => "`parts P`",
            Stage::Parts => "the end of the brep",
        }
    }

    /// Reads the section `line` opens; `Ok(false)` when `line` opens none of a brep's sections.
    pub fn section(&mut self, lex: &mut Lexer<'_>, line: Line<'_>) -> Result<bool, ShpError> {
        let wanted = if line.is("GeoChecked") {
            return Ok(true);
        } else if line.is("vertices") {
            Stage::Vertices
        } else if line.is("triangles") {
            Stage::Triangles
        } else if line.is("parts") {
            Stage::Parts
        } else {
            return Ok(false);
        };
        let previous = match wanted {
            Stage::Vertices => Stage::Start,
            Stage::Triangles => Stage::Vertices,
            _ => Stage::Triangles,
        };
        if self.stage != previous {
            let context = format!("brep {}", self.def.name);
            return Err(lex.unexpected(
                &line,
                line.keyword(),
                context,
                self.expected().to_string(),
            ));
        }
        let count = header_count(lex, &line)?;
        match wanted {
            Stage::Vertices => self.vertices(lex, line, count)?,
            Stage::Triangles => self.triangles(lex, line, count)?,
            _ => self.parts(lex, line, count)?,
        }
        self.stage = wanted;
        Ok(true)
    }

    /// The brep; without a `parts` section every triangle is in part 0 of 1.
    pub fn finish(mut self) -> BrepDef {
        if self.stage < Stage::Parts {
            self.def.part_count = 1;
            self.def.parts = vec![0; self.def.triangles.len()];
        }
        self.def
    }

    fn vertices(
        &mut self,
        lex: &mut Lexer<'_>,
        header: Line<'_>,
        count: u32,
    ) -> Result<(), ShpError> {
        // The room first: a small file announcing billions is cut short or corrupt, and says
        // so more precisely; a big real file passes it and meets the memory check.
        lex.check_room(&header, count, "vertices", MIN_ITEM_LINE_BYTES)?;
        lex.declare_memory(&header, count, BYTES_PER_VERTEX)?;
        if self.def.line == 0 {
            self.def.line = header.no;
        }
        let name = &self.def.name;
        let vertices = &mut self.def.vertices;
        vertices.reserve_exact(count as usize);
        for i in 0..count {
            let what = || format!("vertex {i} of brep {name}");
            let line = lex.expect_line(|| {
                format!("brep {name} announces {count} vertices, the file has {i}")
            })?;
            vertices.push(lex.three(&line, &what, |token| lex.float(token, line.no, what))?);
        }
        Ok(())
    }

    fn triangles(
        &mut self,
        lex: &mut Lexer<'_>,
        header: Line<'_>,
        count: u32,
    ) -> Result<(), ShpError> {
        lex.check_room(&header, count, "triangles", MIN_ITEM_LINE_BYTES)?;
        lex.declare_memory(&header, count, BYTES_PER_TRIANGLE)?;
        let name = &self.def.name;
        let vertex_count = self.def.vertices.len();
        let triangles = &mut self.def.triangles;
        triangles.reserve_exact(count as usize);
        for i in 0..count {
            let what = || format!("triangle {i} of brep {name}");
            let line = lex.expect_line(|| {
                format!("brep {name} announces {count} triangles, the file has {i}")
            })?;
            let triangle = lex.three(&line, &what, |token| lex.whole(token, line.no, what))?;
            if let Some(&vertex) = triangle.iter().find(|&&v| v as usize >= vertex_count) {
                return Err(ShpError::VertexOutOfRange {
                    path: lex.path().to_path_buf(),
                    line: line.no,
                    brep: name.clone(),
                    triangle: i as usize,
                    vertex,
                    vertex_count,
                });
            }
            triangles.push(triangle);
        }
        Ok(())
    }

    fn parts(
        &mut self,
        lex: &mut Lexer<'_>,
        header: Line<'_>,
        part_count: u32,
    ) -> Result<(), ShpError> {
        let name = &self.def.name;
        let triangle_count = self.def.triangles.len();
        if part_count as usize > triangle_count && part_count > MAX_UNUSED_PARTS {
            return Err(ShpError::TooManyParts {
                path: lex.path().to_path_buf(),
                line: header.no,
                brep: name.clone(),
                part_count,
                triangles: triangle_count,
            });
        }
        self.def.part_count = part_count;
        let parts = &mut self.def.parts;
        parts.reserve_exact(triangle_count);
        let list = format!("the `parts` list of brep {name} (one per triangle)");
        read_list(lex, triangle_count, &list, |lex, token, line| {
            let triangle = parts.len();
            let part = parse_u32(token).ok_or_else(|| {
                lex.malformed(
                    token,
                    line,
                    format!("part of triangle {triangle} of brep {name}"),
                    "a part index",
                )
            })?;
            if part >= part_count {
                return Err(ShpError::PartOutOfRange {
                    path: lex.path().to_path_buf(),
                    line,
                    brep: name.clone(),
                    triangle,
                    part,
                    part_count,
                });
            }
            parts.push(part);
            Ok(())
        })
    }
}

/// The count of a section header such as `vertices 25`: exactly one whole number.
pub(crate) fn header_count(lex: &Lexer<'_>, line: &Line<'_>) -> Result<u32, ShpError> {
    let keyword = line.keyword();
    let what = || format!("`{keyword}`");
    let mut words = line.words().skip(1);
    let Some(token) = words.next() else {
        let path = lex.path().to_path_buf();
        return Err(ShpError::MissingNumber {
            path,
            line: line.no,
            what: what(),
            expected: 1,
            found: 0,
        });
    };
    let count = lex.whole(token, line.no, what)?;
    if let Some(extra) = words.next() {
        return Err(ShpError::ExtraValue {
            path: lex.path().to_path_buf(),
            line: line.no,
            what: what(),
            token: super::lexer::excerpt(extra),
            expected: 1,
        });
    }
    Ok(count)
}

/// Reads `count` whitespace-separated values over as many lines as they take, handing each to
/// `each` with the lexer (for messages) and its line number. A word before the list is complete is a missing-number error.
pub(crate) fn read_list(
    lex: &mut Lexer<'_>,
    count: usize,
    list: &str,
    mut each: impl FnMut(&Lexer<'_>, &str, usize) -> Result<(), ShpError>,
) -> Result<(), ShpError> {
    let mut found = 0;
    while found < count {
        let line =
            lex.expect_line(|| format!("{list} needs {count} values, the file has {found}"))?;
        for token in line.words() {
            if found == count {
                return Err(ShpError::ExtraValue {
                    path: lex.path().to_path_buf(),
                    line: line.no,
                    what: list.to_string(),
                    token: super::lexer::excerpt(token),
                    expected: count,
                });
            }
            if token.starts_with(|c: char| c.is_ascii_alphabetic()) {
                return Err(ShpError::MissingNumber {
                    path: lex.path().to_path_buf(),
                    line: line.no,
                    what: format!("{list}, cut short by `{}`,", super::lexer::excerpt(token)),
                    expected: count,
                    found,
                });
            }
            each(lex, token, line.no)?;
            found += 1;
        }
    }
    Ok(())
}
