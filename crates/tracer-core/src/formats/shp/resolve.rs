//! Loading the `.brs` files of placed breps that the `.shp` does not define.

use std::collections::HashSet;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use super::brs;
use super::description::ShpDescription;
use super::error::ShpError;

/// Appends, in placement order, the brep of every `set breps NAME` whose geometry is missing,
/// read from `NAME.brs` beside the `.shp`.
pub(crate) fn load_missing_breps(desc: &mut ShpDescription) -> Result<(), ShpError> {
    let dir = desc
        .path
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let mut known: HashSet<String> = desc.breps.iter().map(|b| b.name.clone()).collect();
    let mut loaded = Vec::new();
    for placement in &desc.placements {
        if known.contains(&placement.name) {
            continue;
        }
        let brs_path = brs_path(&dir, &placement.name);
        let missing = || ShpError::MissingBrep {
            path: desc.path.clone(),
            line: placement.line,
            name: placement.name.clone(),
            brs_path: brs_path.clone(),
        };
        // A name with a path separator would reach outside the folder: never a sibling file.
        if placement.name.contains(['/', '\\']) {
            return Err(missing());
        }
        let bytes = match fs::read(&brs_path) {
            Ok(bytes) => bytes,
            Err(e) if e.kind() == io::ErrorKind::NotFound => return Err(missing()),
            Err(error) => {
                return Err(ShpError::Io {
                    path: brs_path,
                    error,
                });
            }
        };
        loaded.push(brs::parse(&bytes, &brs_path, &placement.name)?);
        known.insert(placement.name.clone());
    }
    desc.breps.extend(loaded);
    Ok(())
}

/// `dir/NAME.brs`; when that does not exist, a file in `dir` whose name matches it ignoring
/// ASCII case (scenes written on Windows name files freely).
fn brs_path(dir: &Path, name: &str) -> PathBuf {
    let file_name = format!("{name}.brs");
    let exact = dir.join(&file_name);
    if exact.is_file() {
        return exact;
    }
    let listing = if dir.as_os_str().is_empty() {
        fs::read_dir(".")
    } else {
        fs::read_dir(dir)
    };
    listing
        .into_iter()
        .flatten()
        .flatten()
        .find(|entry| {
            entry
                .file_name()
                .to_str()
                .is_some_and(|n| n.eq_ignore_ascii_case(&file_name))
        })
        .map_or(exact, |entry| dir.join(entry.file_name()))
}
