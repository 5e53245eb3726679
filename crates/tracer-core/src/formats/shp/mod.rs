//! Reading Lumicept `.shp` scenes (and IPUR's `.brs` brep files) into a plain
//! [`ShpDescription`]: what the file says, each item with its line, no transforms applied.
//!
//! ```text
//! bytes ──lexer──▶ lines (comment-free, trimmed, numbered) ──parser/brep──▶ ShpDescription
//!                                                          └─resolve: NAME.brs for `set breps`
//! ```
//!
//! What is accepted, as real files show it (see `../shared/scenes/README.md`):
//! - LF, CRLF or lone-CR line ends, blanks and tabs anywhere, blank lines, `;;` comments anywhere
//!   (their text is never parsed and need not be UTF-8), a UTF-8 byte order mark.
//! - Keywords compared ignoring ASCII case; brep names compared exactly.
//! - Numbers as Rust's `f64` grammar reads them (`-0`, `+1`, `1.000000e+000`, `1E-3`), finite
//!   only; indices and counts are whole numbers from 0 to `u32::MAX`.
//! - Blocks closed by `enddef`: `define breps NAME` and `set breps NAME` are read, any other
//!   block is skipped up to the first `enddef` (real files never nest them; `parser.rs`
//!   says why that holds for `product` blocks). An unknown block still open at the end of
//!   the file is an error, not silently accepted: the file is more likely cut short than
//!   complete.
//!
//! Counts are checked against what the rest of the file could hold before anything is
//! allocated, so no input makes the reader exhaust memory; nothing in it panics. They are also
//! added up into an estimate of the built scene's memory (about 200 bytes a triangle with its
//! BVH, 40 a vertex), and a file whose scene would need more than the machine has available
//! (`MemAvailable` on Linux) is refused with a clear error when the count is read.

mod brep;
mod brs;
mod bytes;
pub mod description;
mod error;
mod lexer;
pub(crate) mod memory;
mod neutral;
mod parser;
pub mod placement;
mod resolve;
mod writer;

use std::fs;
use std::path::Path;

pub use description::{BrepDef, Placement, ShpDescription};
pub use error::ShpError;
pub use placement::world_from_local;

/// Reads a `.shp` file; for every `set breps NAME` whose geometry is not defined in the file,
/// loads `NAME.brs` from the same folder (matching the file name's case loosely if need be).
pub fn load(path: &Path) -> Result<ShpDescription, ShpError> {
    let bytes = fs::read(path).map_err(|error| ShpError::Io {
        path: path.to_path_buf(),
        error,
    })?;
    let mut desc = parse_shp(&bytes, path)?;
    resolve::load_missing_breps(&mut desc)?;
    if desc.breps.iter().all(|b| b.triangles.is_empty()) {
        return Err(ShpError::NoTriangles {
            path: path.to_path_buf(),
        });
    }
    Ok(desc)
}

/// Parses `.shp` bytes already in memory (`path` is used only in messages and as `source`).
/// Does not load `.brs` files: a placement whose brep is not defined is kept in `placements`,
/// and the caller decides. A file with no triangles and no such placement is an error.
pub fn parse_shp(bytes: &[u8], path: &Path) -> Result<ShpDescription, ShpError> {
    parser::parse(bytes, path)
}

/// Parses a bare `.brs` file's bytes into one brep named `name`; `line` is that of `vertices`.
pub fn parse_brs(bytes: &[u8], path: &Path, name: &str) -> Result<BrepDef, ShpError> {
    brs::parse(bytes, path, name)
}

/// Writes a description as `.shp` text (LF, `define breps` blocks then `set breps` blocks), for
/// tests and asset generators. `parse_shp` of the result gives back the same geometry and
/// placements, provided names have no blanks and `parts` has one entry per triangle.
pub fn write_shp(desc: &ShpDescription) -> String {
    writer::ShpText(desc).to_string()
}
