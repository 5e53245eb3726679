//! `.cam` cameras: a `Camera NAME` block with the eye (`viewpoint x y z`), the image plane as
//! three corners after `screen` (top-left, top-right, bottom-left) and `resolution W H`.
//!
//! The corners give everything: the screen centre c = (c2 + c3) / 2 is the look-at point, the
//! up direction is c1 − c3, the vertical field of view is 2 atan(|c1 − c3| / 2 / d) with d the
//! eye's distance to the screen plane, and the aspect is |c2 − c1| / |c1 − c3|. The right
//! direction c2 − c1 equals up × forward, so these files are left-handed, as raygine's
//! default frame for Lumicept scenes draws them.

use super::error::IntegraError;
use super::lines::{self, Line, blocks, numbers};
use crate::formats::description::CameraDescription;
use glam::DVec3;
use std::path::Path;

/// One `Camera` block as written.
#[derive(Clone, Debug, PartialEq)]
pub struct Cam {
    pub name: String,
    /// 1-based line of `Camera NAME`.
    pub line: usize,
    pub viewpoint: [f64; 3],
    /// Top-left, top-right and bottom-left corners of the image plane.
    pub screen: [[f64; 3]; 3],
    pub resolution: Option<[u32; 2]>,
}

/// Reads a `.cam` file's bytes: its first `Camera` block (`Ok(None)` when it has none).
pub fn parse_cam(bytes: &[u8], path: &Path) -> Result<Option<Cam>, IntegraError> {
    let text = lines::decode(bytes, path)?;
    let Some(block) = blocks(lines::lines(&text), path, ".cam")?
        .into_iter()
        .find(|b| b.keyword.eq_ignore_ascii_case("Camera"))
    else {
        return Ok(None);
    };
    let mut viewpoint = None;
    let mut screen = None;
    let mut resolution = None;
    let mut body = block.body.iter();
    while let Some(line) = body.next() {
        match line.key().to_ascii_lowercase().as_str() {
            "viewpoint" => viewpoint = Some(numbers::<3>(path, line)?),
            "screen" => {
                if !line.values().is_empty() {
                    return Err(IntegraError::new(
                        path,
                        line.no,
                        "`screen` stands alone; its three corners follow, one a line",
                    ));
                }
                let mut corners = [[0.0; 3]; 3];
                for corner in &mut corners {
                    let Some(next) = body.next() else {
                        return Err(IntegraError::new(
                            path,
                            line.no,
                            "`screen` needs three corner lines `x y z` (top-left, top-right, bottom-left)",
                        ));
                    };
                    *corner = corner_of(path, next)?;
                }
                screen = Some(corners);
            }
            "resolution" => {
                let [w, h] = numbers::<2>(path, line)?;
                let ok = |x: f64| x.fract() == 0.0 && (1.0..=65_536.0).contains(&x);
                if !(ok(w) && ok(h)) {
                    return Err(IntegraError::new(
                        path,
                        line.no,
                        format!(
                            "`resolution` takes two whole numbers from 1 to 65536, found {w} {h}"
                        ),
                    ));
                }
                resolution = Some([w as u32, h as u32]);
            }
            _ => {}
        }
    }
    let missing = |what: &str| {
        IntegraError::new(
            path,
            block.line,
            format!("camera {} has no `{what}`", block.name),
        )
    };
    Ok(Some(Cam {
        name: block.name.to_owned(),
        line: block.line,
        viewpoint: viewpoint.ok_or_else(|| missing("viewpoint"))?,
        screen: screen.ok_or_else(|| missing("screen"))?,
        resolution,
    }))
}

fn corner_of(path: &Path, line: &Line) -> Result<[f64; 3], IntegraError> {
    let [x, y, z] = line.words[..] else {
        return Err(IntegraError::new(
            path,
            line.no,
            format!(
                "a screen corner is `x y z`, found `{}`",
                line.words.join(" ")
            ),
        ));
    };
    let n = |w| lines::number(path, line.no, w, "screen corner");
    Ok([n(x)?, n(y)?, n(z)?])
}

impl Cam {
    /// The pinhole camera the corners describe, or why they describe none (a degenerate
    /// screen, an eye on its plane).
    pub fn to_camera(&self, path: &Path) -> Result<CameraDescription, IntegraError> {
        let eye = DVec3::from(self.viewpoint);
        let [c1, c2, c3] = self.screen.map(DVec3::from);
        let right = c2 - c1;
        let up = c1 - c3;
        let centre = (c2 + c3) * 0.5;
        let normal = right.cross(up).normalize_or_zero();
        let distance = (centre - eye).dot(normal).abs();
        let height = up.length();
        let makes_a_view =
            normal != DVec3::ZERO && distance > 1e-9 * height.max(1.0) && height > 0.0;
        if !makes_a_view {
            return Err(IntegraError::new(
                path,
                self.line,
                format!(
                    "camera {}: the screen corners and the viewpoint do not make a view (a \
                     screen of no area, or the eye on its plane)",
                    self.name
                ),
            ));
        }
        let fov_deg = (2.0 * (0.5 * height / distance).atan()).to_degrees();
        Ok(CameraDescription {
            line: self.line,
            position: eye.as_vec3().to_array(),
            look_at: centre.as_vec3().to_array(),
            up: up.normalize().as_vec3().to_array(),
            fov_deg: fov_deg as f32,
            resolution: self.resolution,
        })
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn errors_name_file_and_line() {
        for (text, message) in [
            (
                "Camera c\n viewpoint 1 2\nenddef\n",
                "c.cam:2: `viewpoint` takes 3 numbers, found 2",
            ),
            (
                "Camera c\n viewpoint 0 0 0\n screen\n 1 1 1\nenddef\n",
                "c.cam:3: `screen` needs three corner lines `x y z` (top-left, top-right, bottom-left)",
            ),
            (
                "Camera c\n viewpoint 0 0 0\nenddef\n",
                "c.cam:1: camera c has no `screen`",
            ),
            (
                "Camera c\n resolution 0 5\nenddef\n",
                "c.cam:2: `resolution` takes two whole numbers from 1 to 65536, found 0 5",
            ),
        ] {
            let err = parse_cam(text.as_bytes(), Path::new("c.cam")).unwrap_err();
            assert_eq!(err.to_string(), message);
        }
        let flat = "Camera c\n viewpoint 0 0 0\n screen\n 0 1 0\n 1 1 0\n 0 0 0\nenddef\n";
        let cam = parse_cam(flat.as_bytes(), Path::new("c.cam"))
            .unwrap()
            .unwrap();
        assert!(cam.to_camera(Path::new("c.cam")).is_err());
    }
}
