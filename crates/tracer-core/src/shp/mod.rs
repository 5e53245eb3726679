//! TEMPORARY minimal reader (replaced by the shp-parser branch).
pub mod description;
pub use description::{BrepDef, Placement, ShpDescription};
use std::path::{Path, PathBuf};

#[derive(Debug, thiserror::Error)]
#[error("{}: line {line}: {message}", path.display())]
pub struct ShpError {
    pub path: PathBuf,
    pub line: usize,
    pub message: String,
}

pub fn load(path: &Path) -> Result<ShpDescription, ShpError> {
    let bytes = std::fs::read(path).map_err(|e| ShpError {
        path: path.into(),
        line: 0,
        message: e.to_string(),
    })?;
    parse_shp(&bytes, path)
}

pub fn parse_shp(bytes: &[u8], path: &Path) -> Result<ShpDescription, ShpError> {
    let text = String::from_utf8_lossy(bytes);
    let mut d = ShpDescription {
        path: path.into(),
        ..Default::default()
    };
    let mut lines = text
        .lines()
        .map(|l| l.split(";;").next().unwrap_or("").trim());
    let nums = |l: &str| -> Vec<f64> {
        l.split_whitespace()
            .filter_map(|t| t.parse().ok())
            .collect()
    };
    while let Some(l) = lines.next() {
        if let Some(name) = l.strip_prefix("define breps ") {
            let mut b = BrepDef {
                name: name.trim().into(),
                source: path.into(),
                part_count: 1,
                ..Default::default()
            };
            while let Some(l) = lines.next() {
                if let Some(n) = l.strip_prefix("vertices") {
                    let n: usize = n.trim().parse().unwrap_or(0);
                    for _ in 0..n {
                        let v = nums(lines.next().unwrap_or(""));
                        b.vertices.push([v[0], v[1], v[2]]);
                    }
                } else if let Some(n) = l.strip_prefix("triangles") {
                    let n: usize = n.trim().parse().unwrap_or(0);
                    for _ in 0..n {
                        let v = nums(lines.next().unwrap_or(""));
                        b.triangles.push([v[0] as u32, v[1] as u32, v[2] as u32]);
                    }
                } else if l == "enddef" {
                    break;
                }
            }
            b.parts = vec![0; b.triangles.len()];
            d.breps.push(b);
        }
    }
    Ok(d)
}
