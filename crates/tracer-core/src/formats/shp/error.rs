//! Everything that can be wrong with a `.shp` or `.brs` file. Every message names the file and,
//! where one applies, the 1-based line, then says what was expected. Item numbers in messages
//! (vertex, triangle) are 0-based, like the indices in the files.

use std::io;
use std::path::{Path, PathBuf};

/// A file that could not be read as a Lumicept scene.
#[derive(Debug, thiserror::Error)]
pub enum ShpError {
    /// The file could not be read at all.
    #[error("{}: cannot read the file: {error}", path.display())]
    Io {
        path: PathBuf,
        /// Shown in the message, not chained as a source (the message already says it).
        error: io::Error,
    },

    /// The bytes are not text: an ESRI shapefile (same extension) or some other binary file.
    #[error("{}: this is a binary file, not a Lumicept text .shp (an ESRI shapefile?)", path.display())]
    Binary { path: PathBuf },

    /// A line's data (comments are not checked) is not UTF-8, or the file is UTF-16.
    #[error(
        "{}: line {line}: the text is not UTF-8 (bad byte at column {column}); save the file as UTF-8 or ASCII",
        path.display()
    )]
    NotUtf8 {
        path: PathBuf,
        line: usize,
        column: usize,
    },

    /// A number that parses but is NaN or infinite (including literals too large for f64).
    #[error("{}: line {line}: {what}: `{token}` is not a finite number", path.display())]
    NonFinite {
        path: PathBuf,
        line: usize,
        what: String,
        token: String,
    },

    /// A line has fewer numbers than its item needs.
    #[error("{}: line {line}: {what} needs {expected} numbers, found {found}", path.display())]
    MissingNumber {
        path: PathBuf,
        line: usize,
        what: String,
        expected: usize,
        found: usize,
    },

    /// The file ends before a section or block is complete; `line` is the file's last line.
    #[error("{}: line {line}: the file ends early: {what}", path.display())]
    UnexpectedEnd {
        path: PathBuf,
        line: usize,
        what: String,
    },

    /// A token that should be a number is not one.
    #[error("{}: line {line}: {what}: `{token}` is not {expected}", path.display())]
    MalformedNumber {
        path: PathBuf,
        line: usize,
        what: String,
        token: String,
        expected: &'static str,
    },

    /// A count larger than the rest of the file could possibly hold; rejected before allocating.
    #[error(
        "{}: line {line}: `{keyword} {count}` announces more {items} than the rest of the file can hold ({room})",
        path.display()
    )]
    CountTooLarge {
        path: PathBuf,
        line: usize,
        keyword: String,
        count: u32,
        items: &'static str,
        room: String,
    },

    /// Declared counts whose scene would not fit in the memory available; refused up front.
    #[error(
        "{}: line {line}: `{keyword} {count}` makes the scene need about {needed} of memory, more than the {available} available",
        path.display()
    )]
    TooLargeForMemory {
        path: PathBuf,
        line: usize,
        keyword: String,
        count: u32,
        /// The estimate for everything declared up to this line, e.g. `400.0 GB`.
        needed: String,
        available: String,
    },

    /// More values on a line than its item takes.
    #[error("{}: line {line}: {what}: unexpected `{token}` after the {expected} expected values", path.display())]
    ExtraValue {
        path: PathBuf,
        line: usize,
        what: String,
        token: String,
        expected: usize,
    },

    /// A triangle refers to a vertex its brep does not have.
    #[error(
        "{}: line {line}: triangle {triangle} of brep {brep} uses vertex {vertex}, but the brep has {vertex_count} vertices",
        path.display()
    )]
    VertexOutOfRange {
        path: PathBuf,
        line: usize,
        brep: String,
        triangle: usize,
        vertex: u32,
        vertex_count: usize,
    },

    /// A triangle's part index is not below the brep's part count.
    #[error(
        "{}: line {line}: triangle {triangle} of brep {brep} is in part {part}, but the brep declares {part_count} parts",
        path.display()
    )]
    PartOutOfRange {
        path: PathBuf,
        line: usize,
        brep: String,
        triangle: usize,
        part: u32,
        part_count: u32,
    },

    /// `set breps NAME` for a brep that is neither defined in the file nor found as `NAME.brs`.
    #[error(
        "{}: line {line}: `set breps {name}` places a brep that is neither defined in this file nor found as {}",
        path.display(),
        brs_path.display()
    )]
    MissingBrep {
        path: PathBuf,
        line: usize,
        name: String,
        brs_path: PathBuf,
    },

    /// A `define breps` or `set breps` line without the brep's name.
    #[error("{}: line {line}: `{block}` needs a brep name", path.display())]
    MissingName {
        path: PathBuf,
        line: usize,
        block: String,
    },

    /// A part count no triangle list could use (more parts than triangles and more than 65,536);
    /// rejected so that callers allocating per part cannot be made to exhaust memory.
    #[error(
        "{}: line {line}: brep {brep} declares {part_count} parts but has only {triangles} triangles",
        path.display()
    )]
    TooManyParts {
        path: PathBuf,
        line: usize,
        brep: String,
        part_count: u32,
        triangles: usize,
    },

    /// Nothing to render: no brep has a triangle.
    #[error("{}: the scene has no triangles (no brep with a `triangles` section)", path.display())]
    NoTriangles { path: PathBuf },

    /// A second `define breps` with a name already defined.
    #[error("{}: line {line}: brep {name} is defined twice (first at line {first_line})", path.display())]
    DuplicateBrep {
        path: PathBuf,
        line: usize,
        name: String,
        first_line: usize,
    },

    /// A block still open when the file ends; `line` is where the block opened.
    #[error(
        "{}: line {line}: the `{block}` block opened here has no `enddef`: the file ends at line {last_line}",
        path.display()
    )]
    MissingEnddef {
        path: PathBuf,
        line: usize,
        block: String,
        last_line: usize,
    },

    /// A keyword where something else was expected.
    #[error("{}: line {line}: unexpected `{found}` in {context}; expected {expected}", path.display())]
    UnexpectedKeyword {
        path: PathBuf,
        line: usize,
        found: String,
        context: String,
        expected: String,
    },
}

impl ShpError {
    /// The file the error is about (the `.brs` file for errors inside one).
    pub fn path(&self) -> &Path {
        match self {
            Self::Io { path, .. }
            | Self::Binary { path }
            | Self::NotUtf8 { path, .. }
            | Self::NonFinite { path, .. }
            | Self::MissingNumber { path, .. }
            | Self::UnexpectedEnd { path, .. }
            | Self::MalformedNumber { path, .. }
            | Self::CountTooLarge { path, .. }
            | Self::TooLargeForMemory { path, .. }
            | Self::ExtraValue { path, .. }
            | Self::VertexOutOfRange { path, .. }
            | Self::PartOutOfRange { path, .. }
            | Self::MissingBrep { path, .. }
            | Self::MissingName { path, .. }
            | Self::TooManyParts { path, .. }
            | Self::NoTriangles { path }
            | Self::DuplicateBrep { path, .. }
            | Self::MissingEnddef { path, .. }
            | Self::UnexpectedKeyword { path, .. } => path,
        }
    }

    /// The 1-based line the error is about, when one applies.
    pub fn line(&self) -> Option<usize> {
        match self {
            Self::Io { .. } | Self::Binary { .. } | Self::NoTriangles { .. } => None,
            Self::NotUtf8 { line, .. }
            | Self::NonFinite { line, .. }
            | Self::MissingNumber { line, .. }
            | Self::UnexpectedEnd { line, .. }
            | Self::MalformedNumber { line, .. }
            | Self::CountTooLarge { line, .. }
            | Self::TooLargeForMemory { line, .. }
            | Self::ExtraValue { line, .. }
            | Self::VertexOutOfRange { line, .. }
            | Self::PartOutOfRange { line, .. }
            | Self::MissingBrep { line, .. }
            | Self::MissingName { line, .. }
            | Self::TooManyParts { line, .. }
            | Self::DuplicateBrep { line, .. }
            | Self::MissingEnddef { line, .. }
            | Self::UnexpectedKeyword { line, .. } => Some(*line),
        }
    }
}
