//! Errors of building a scene and reading its sidecar.

use crate::formats::SceneFileError;
use crate::shp::ShpError;
use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error(transparent)]
    Shp(#[from] ShpError),
    #[error(transparent)]
    Format(#[from] SceneFileError),
    #[error("{}: line {line}: the placement of brep {brep} moves a vertex to infinity", path.display())]
    NonFinitePlacement {
        path: PathBuf,
        line: usize,
        brep: String,
    },
    #[error(
        "{}: line {line}: the placement of {brep} is not finite or not invertible (it flattens the mesh)",
        path.display()
    )]
    SingularPlacement {
        path: PathBuf,
        line: usize,
        brep: String,
    },
    #[error(
        "{}: line {line}: mesh {brep} is an instance of a mesh that is not before it or is an instance itself",
        path.display()
    )]
    BadInstance {
        path: PathBuf,
        line: usize,
        brep: String,
    },
    #[error("{}: the scene has more than {limit} triangles (with its instances)", path.display())]
    TooManyTriangles { path: PathBuf, limit: usize },
    #[error("brep {brep}: triangle {triangle} uses a vertex the brep does not have")]
    BadIndex { brep: String, triangle: usize },
    #[error("{}: the scene has no triangles", path.display())]
    NoTriangles { path: PathBuf },
    #[error("{}: cannot read the sidecar: {error}", path.display())]
    SidecarIo {
        path: PathBuf,
        error: std::io::Error,
    },
    #[error("{}: {message}", path.display())]
    Sidecar { path: PathBuf, message: String },
}
