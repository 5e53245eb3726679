//! Notes on a loaded scene that name where they come from: the sidecar's file and line, and
//! lights by the number the viewer shows them with (Light 1 is the first).

use super::geometry::Scene;
use super::setup::Setup;
use std::path::{Path, PathBuf};

/// The sidecar text notes are placed in.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SourceText {
    pub path: PathBuf,
    pub text: String,
}

impl SourceText {
    /// `note` prefixed with the file and the line that gave it: "room.raygine.toml:7: material
    /// glas: …". A note's subject is what precedes its first colon ("material glas", "hidden
    /// lamp", "Light 2", "camera"); its line is the first that names the subject's last word
    /// (the key, `[[lights]]` for a light); without one, the file alone.
    pub fn place(&self, note: &str) -> String {
        let subject = note.split(':').next().unwrap_or("");
        let file = self.path.display();
        match self.line_of(subject) {
            Some(line) => format!("{file}:{line}: {note}"),
            None => format!("{file}: {note}"),
        }
    }

    fn line_of(&self, subject: &str) -> Option<usize> {
        let mut words = subject.split_whitespace();
        let first = words.next()?;
        let last = words.last().unwrap_or(first);
        if first.eq_ignore_ascii_case("light")
            && let Ok(n) = last.parse::<usize>()
        {
            // The n-th [[lights]] table.
            return self
                .text
                .lines()
                .enumerate()
                .filter(|(_, l)| l.trim_start().starts_with("[[lights]]"))
                .nth(n.checked_sub(1)?)
                .map(|(i, _)| i + 1);
        }
        let key = last.trim_matches('"');
        self.text
            .lines()
            .position(|l| {
                let code = l.split('#').next().unwrap_or("");
                // `[materials.glas]`, `"glas"`, `materials."lamp.001"`.
                code.split(|c: char| !(c.is_alphanumeric() || "_-./".contains(c)))
                    .any(|w| w == key || w.strip_suffix(key).is_some_and(|h| h.ends_with('.')))
            })
            .map(|i| i + 1)
    }
}

/// The distance from `p` to the nearest surface along the 26 axis and diagonal directions.
pub(crate) fn nearest_surface(scene: &Scene, p: glam::Vec3) -> Option<f32> {
    let mut best: Option<f32> = None;
    for x in -1..=1 {
        for y in -1..=1 {
            for z in -1..=1 {
                let dir = glam::Vec3::new(x as f32, y as f32, z as f32);
                let Some(dir) = dir.try_normalize() else {
                    continue;
                };
                if let Some(hit) = scene.intersect(&crate::geometry::Ray::new(p, dir)) {
                    best = Some(best.map_or(hit.t, |b: f32| b.min(hit.t)));
                }
            }
        }
    }
    best
}

/// The warning for light `index` (0-based) when it is a luminaire closer to a surface than five
/// times its luminous opening while drawn as a point (`shape = "point"`), where the point-source
/// model breaks; it names the light as the viewer does ("Light 2").
pub fn luminaire_near_surface(scene: &Scene, setup: &Setup, index: usize) -> Option<String> {
    let light = setup.lights.get(index)?;
    let crate::light::LightKind::Luminaire(placement) = &light.kind else {
        return None;
    };
    let lum = &placement.luminaire;
    let mpu = setup.unit.metres_per_unit();
    if placement.opening(mpu) != crate::light::LuminousShape::Point {
        // Drawn with its opening: exact near it.
        return None;
    }
    let opening = lum.photometry.opening_m() / mpu;
    let d = nearest_surface(scene, light.position())?;
    (opening > 0.0 && d < 5.0 * opening).then(|| {
        let unit = setup.unit.symbol();
        format!(
            "Light {}: a surface is {d:.3} {unit} away, closer than five times the luminous \
             opening ({opening:.3} {unit}): the far-field (point source) assumption breaks there; \
             shape = \"file\" draws its opening",
            index + 1
        )
    })
}

/// The note for light `index` when it is a luminaire drawn with its file's opening and the
/// file's shape is one raygine does not draw (it became a point).
pub fn luminaire_shape(setup: &Setup, index: usize) -> Option<String> {
    let light = setup.lights.get(index)?;
    let crate::light::LightKind::Luminaire(placement) = &light.kind else {
        return None;
    };
    if placement.shape != crate::light::ShapeChoice::File {
        return None;
    }
    let note = placement.luminaire.photometry.shape_note.as_ref()?;
    Some(format!(
        "Light {}: {}: {note}",
        index + 1,
        placement.luminaire.file.display()
    ))
}

/// When `path` lies in `dir` or below it (both resolved, when they exist), the path relative to
/// `dir`.
pub fn relative_below(path: &Path, dir: &Path) -> Option<PathBuf> {
    let resolve = |p: &Path| p.canonicalize().unwrap_or_else(|_| p.to_path_buf());
    resolve(path)
        .strip_prefix(resolve(dir))
        .ok()
        .map(Path::to_path_buf)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn notes_name_the_line_of_their_key() {
        let src = SourceText {
            path: PathBuf::from("room.raygine.toml"),
            text: "unit = \"mm\"\nhidden = [\"lamp\"]\n\n[materials.glas]\nkd = [1, 0, 0]\n\
                   [[lights]]\nposition = [0, 0, 0]\n[[lights]]\nposition = [1, 0, 0]\n"
                .to_owned(),
        };
        assert_eq!(
            src.place("material glas: the scene has no such brep or part"),
            "room.raygine.toml:4: material glas: the scene has no such brep or part"
        );
        assert_eq!(
            src.place("hidden lamp: the scene has no such brep or part"),
            "room.raygine.toml:2: hidden lamp: the scene has no such brep or part"
        );
        assert_eq!(
            src.place("Light 2: too close"),
            "room.raygine.toml:8: Light 2: too close"
        );
        assert_eq!(
            src.place("camera: not finite"),
            "room.raygine.toml: camera: not finite"
        );
    }
}
