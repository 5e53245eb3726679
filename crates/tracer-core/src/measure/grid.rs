//! Calculation grids: rectangles of sensor points at cell centres.

use glam::Vec3;

/// A rectangle of `nu` x `nv` sensor points, each measuring the illuminance arriving from the
/// side `normal` points to. Point (i, j) sits at the centre of its cell:
/// `origin + (i + ½)/nu · u + (j + ½)/nv · v`.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// `[A-Za-z0-9_-]+`.
    pub name: String,
    /// A corner, scene coordinates.
    pub origin: [f32; 3],
    /// Edge vectors, scene units.
    pub u: [f32; 3],
    pub v: [f32; 3],
    pub nu: u32,
    pub nv: u32,
    /// Unit normal of the measuring side.
    pub normal: [f32; 3],
    /// The activity whose requirements the report checks it against (`task` in the sidecar:
    /// a key of the requirements table).
    pub task: Option<String>,
    /// The observers whose glare the report judges it by.
    pub observers: Vec<String>,
}

/// One sensor point of a grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorPoint {
    pub i: u32,
    pub j: u32,
    pub position: Vec3,
    pub normal: Vec3,
}

/// Why a grid cannot be measured.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum GridError {
    #[error("grid name `{0}` must be non-empty and use only A-Z, a-z, 0-9, _ and -")]
    BadName(String),
    #[error("grid {0}: nu and nv must be at least 1")]
    NoPoints(String),
    #[error("grid {0}: more than 1,000,000 points")]
    TooManyPoints(String),
    #[error("grid {0}: origin, u, v and normal must be finite numbers")]
    NonFinite(String),
    #[error("grid {0}: u and v span no area (zero-length or parallel edges)")]
    ZeroArea(String),
    #[error("grid {0}: the normal has zero length")]
    ZeroNormal(String),
    #[error("two grids are named {0}")]
    Duplicate(String),
}

impl Grid {
    /// A checked grid. `normal` defaults to u × v normalised, computed on the numbers as
    /// written.
    pub fn new(
        name: &str,
        origin: [f32; 3],
        u: [f32; 3],
        v: [f32; 3],
        nu: u32,
        nv: u32,
        normal: Option<[f32; 3]>,
    ) -> Result<Grid, GridError> {
        let valid_name = !name.is_empty()
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        if !valid_name {
            return Err(GridError::BadName(name.to_owned()));
        }
        let owned = || name.to_owned();
        if nu == 0 || nv == 0 {
            return Err(GridError::NoPoints(owned()));
        }
        if u64::from(nu) * u64::from(nv) > 1_000_000 {
            return Err(GridError::TooManyPoints(owned()));
        }
        let all = [origin, u, v, normal.unwrap_or([0.0; 3])];
        if !all.iter().flatten().all(|x| x.is_finite()) {
            return Err(GridError::NonFinite(owned()));
        }
        let cross = Vec3::from(u).cross(Vec3::from(v));
        if !cross.is_finite() || cross.length() <= 0.0 {
            return Err(GridError::ZeroArea(owned()));
        }
        let normal = match normal {
            Some(n) => Vec3::from(n)
                .try_normalize()
                .ok_or_else(|| GridError::ZeroNormal(owned()))?,
            None => cross.normalize(),
        };
        Ok(Grid {
            name: name.to_owned(),
            origin,
            u,
            v,
            nu,
            nv,
            normal: normal.to_array(),
            task: None,
            observers: Vec::new(),
        })
    }

    pub fn point_count(&self) -> usize {
        self.nu as usize * self.nv as usize
    }

    /// Point `k` in the order i fastest: k = j · nu + i.
    pub fn point(&self, k: usize) -> SensorPoint {
        let i = (k % self.nu as usize) as u32;
        let j = (k / self.nu as usize) as u32;
        let fu = (i as f32 + 0.5) / self.nu as f32;
        let fv = (j as f32 + 0.5) / self.nv as f32;
        SensorPoint {
            i,
            j,
            position: Vec3::from(self.origin) + Vec3::from(self.u) * fu + Vec3::from(self.v) * fv,
            normal: Vec3::from(self.normal),
        }
    }

    pub fn points(&self) -> impl Iterator<Item = SensorPoint> + '_ {
        (0..self.point_count()).map(|k| self.point(k))
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn points_sit_at_cell_centres_and_the_normal_defaults_to_u_cross_v() {
        let g = Grid::new(
            "floor",
            [0.0; 3],
            [4.0, 0.0, 0.0],
            [0.0, 0.0, 2.0],
            4,
            2,
            None,
        )
        .expect("grid");
        assert_eq!(g.normal, [0.0, -1.0, 0.0]);
        let p = g.point(5);
        assert_eq!((p.i, p.j), (1, 1));
        assert_eq!(p.position, Vec3::new(1.5, 0.0, 1.5));
        assert_eq!(g.points().count(), 8);
    }

    #[test]
    fn bad_grids_are_refused_by_name() {
        let ok = |n| Grid::new(n, [0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 2, 2, None);
        assert!(matches!(ok("a b"), Err(GridError::BadName(_))));
        assert!(matches!(
            Grid::new("g", [0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], 2, 2, None),
            Err(GridError::ZeroArea(_))
        ));
        assert!(matches!(
            Grid::new("g", [0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0, 2, None),
            Err(GridError::NoPoints(_))
        ));
        assert!(matches!(
            Grid::new(
                "g",
                [f32::NAN, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                1,
                1,
                None
            ),
            Err(GridError::NonFinite(_))
        ));
        let e = ok("x y").err().map(|e| e.to_string()).unwrap_or_default();
        assert!(e.contains("x y"), "{e}");
    }
}
