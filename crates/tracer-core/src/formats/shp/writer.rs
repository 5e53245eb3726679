//! A description back to `.shp` text: a comment line, the `define breps` blocks, then the
//! `set breps` blocks, LF line ends. Numbers are written with Rust's shortest exact decimal
//! form (no exponent), so reading the text back gives the same `f64`s bit for bit.

use std::fmt;

use super::description::{BrepDef, Placement, ShpDescription};

/// Part indices per line, as Lumicept writes them.
const PARTS_PER_LINE: usize = 10;

/// Displays as the `.shp` text of a description.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ShpText<'a>(pub &'a ShpDescription);

impl fmt::Display for ShpText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, ";; Written by raygine")?;
        for brep in &self.0.breps {
            writeln!(f)?;
            write_brep(f, brep)?;
        }
        for placement in &self.0.placements {
            writeln!(f)?;
            write_placement(f, placement)?;
        }
        Ok(())
    }
}

fn write_brep(f: &mut fmt::Formatter<'_>, brep: &BrepDef) -> fmt::Result {
    writeln!(f, "define breps {}", brep.name)?;
    writeln!(f, "vertices {} ;; Number of vertices", brep.vertices.len())?;
    for [x, y, z] in &brep.vertices {
        writeln!(f, "  {x} {y} {z}")?;
    }
    writeln!(
        f,
        "triangles {} ;; Number of triangles",
        brep.triangles.len()
    )?;
    for [a, b, c] in &brep.triangles {
        writeln!(f, " {a} {b} {c}")?;
    }
    writeln!(f, "parts {} ;; Number of parts", brep.part_count)?;
    for row in brep.parts.chunks(PARTS_PER_LINE) {
        for part in row {
            write!(f, " {part}")?;
        }
        writeln!(f)?;
    }
    writeln!(f, "enddef")
}

fn write_placement(f: &mut fmt::Formatter<'_>, placement: &Placement) -> fmt::Result {
    let [rx, ry, rz] = placement.rotation_deg;
    let [tx, ty, tz] = placement.translation;
    let [sx, sy, sz] = placement.scale;
    writeln!(f, "set breps {}", placement.name)?;
    writeln!(f, "  rotation {rx} {ry} {rz}")?;
    writeln!(f, "  translation {tx} {ty} {tz}")?;
    writeln!(f, "  scale {sx} {sy} {sz}")?;
    writeln!(f, "enddef")
}
