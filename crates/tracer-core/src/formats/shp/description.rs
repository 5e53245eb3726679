//! The plain description of a Lumicept scene: what the files say, item by item, with the line each
//! item came from. No transforms are applied and no materials exist here; `scene` builds from it.

use std::path::PathBuf;

/// Everything read from one `.shp` file (and the `.brs` files it pulls in).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ShpDescription {
    /// The `.shp` file this came from.
    pub path: PathBuf,
    /// Brep geometry in the order it was defined (in the `.shp`, then any loaded `.brs`).
    pub breps: Vec<BrepDef>,
    /// `set breps NAME` blocks in file order.
    pub placements: Vec<Placement>,
}

/// One `define breps NAME ... enddef` block, or one `.brs` file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BrepDef {
    pub name: String,
    /// The file the geometry came from (the `.shp` itself or `NAME.brs`).
    pub source: PathBuf,
    /// 1-based line of `define breps` (or of `vertices` in a `.brs`).
    pub line: usize,
    /// Vertex positions in file coordinates (the scene unit), as written.
    pub vertices: Vec<[f64; 3]>,
    /// 0-based vertex indices local to this brep, validated `< vertices.len()`.
    pub triangles: Vec<[u32; 3]>,
    /// Number of parts (material slots) declared by `parts P`; 1 when the section is absent.
    pub part_count: u32,
    /// One part index per triangle, validated `< part_count`; all 0 when the section is absent.
    pub parts: Vec<u32>,
}

/// One `set breps NAME ... enddef` block: the placement of a brep.
#[derive(Clone, Debug, PartialEq)]
pub struct Placement {
    pub name: String,
    /// The file and 1-based line of `set breps`.
    pub source: PathBuf,
    pub line: usize,
    /// `rotation rx ry rz` as written (degrees, see `placement.rs`).
    pub rotation_deg: [f64; 3],
    pub translation: [f64; 3],
    pub scale: [f64; 3],
}

impl Default for Placement {
    fn default() -> Self {
        Self {
            name: String::new(),
            source: PathBuf::new(),
            line: 0,
            rotation_deg: [0.0; 3],
            translation: [0.0; 3],
            scale: [1.0; 3],
        }
    }
}
