//! Whether parts make one whole: the same kind, raygine version, scene and setup, settings, N
//! and M, and every shard 0..M exactly once.

use super::file::{PartError, PartHeader};
use std::path::{Path, PathBuf};

/// Checks that `parts` (file, header) are all the shards of one render or measurement. The first
/// part is the reference the others are compared with; errors name the file at fault.
pub fn check_set(parts: &[(PathBuf, PartHeader)]) -> Result<(), PartError> {
    let Some((first_path, first)) = parts.first() else {
        return Err(PartError::NoParts);
    };
    let mut seen: Vec<Option<&Path>> = vec![None; first.shard.count as usize];
    for (path, h) in parts {
        let mismatch = |what: &'static str, this: String, that: String| PartError::Mismatch {
            path: path.clone(),
            other: first_path.clone(),
            what,
            this,
            that,
        };
        if h.kind != first.kind {
            let (a, b) = (h.kind.name().to_owned(), first.kind.name().to_owned());
            return Err(mismatch("the kind of part", a, b));
        }
        if h.version != first.version {
            return Err(mismatch(
                "the raygine version",
                h.version.clone(),
                first.version.clone(),
            ));
        }
        if h.scene_hash != first.scene_hash {
            return Err(mismatch(
                "the scene or its setup",
                format!("{} {:016x}", h.scene, h.scene_hash),
                format!("{} {:016x}", first.scene, first.scene_hash),
            ));
        }
        if h.settings != first.settings {
            return Err(mismatch(
                "the settings",
                h.settings.clone(),
                first.settings.clone(),
            ));
        }
        if h.samples != first.samples {
            return Err(mismatch(
                "the total sample count",
                h.samples.to_string(),
                first.samples.to_string(),
            ));
        }
        if h.shard.count != first.shard.count {
            return Err(mismatch(
                "the shard count",
                h.shard.count.to_string(),
                first.shard.count.to_string(),
            ));
        }
        // Same count as the first part, and Shard::new checked index < count on reading.
        let Some(slot) = seen.get_mut(h.shard.index as usize) else {
            return Err(PartError::Header {
                path: path.clone(),
                reason: format!("shard {} of {}", h.shard.index, h.shard.count),
            });
        };
        if let Some(other) = slot {
            return Err(PartError::Duplicate {
                path: path.clone(),
                other: other.to_path_buf(),
                index: h.shard.index,
                count: h.shard.count,
            });
        }
        *slot = Some(path);
    }
    let missing: Vec<String> = seen
        .iter()
        .enumerate()
        .filter(|(_, p)| p.is_none())
        .map(|(k, _)| k.to_string())
        .collect();
    if missing.is_empty() {
        return Ok(());
    }
    let mut given: Vec<String> = parts
        .iter()
        .take(4)
        .map(|(p, _)| p.display().to_string())
        .collect();
    if parts.len() > 4 {
        given.push(format!("and {} more", parts.len() - 4));
    }
    let missing = match missing.as_slice() {
        [one] => format!("shard {one}"),
        many => format!("shards {}", many.join(", ")),
    };
    Err(PartError::Missing {
        missing,
        count: first.shard.count,
        given: given.join(", "),
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;
    use crate::shard::{PartKind, Shard};

    fn part(k: u32, m: u32) -> (PathBuf, PartHeader) {
        (
            PathBuf::from(format!("part{k}.rgp")),
            PartHeader {
                kind: PartKind::Render,
                version: "0.1.0".into(),
                scene: "box".into(),
                scene_hash: 42,
                settings: "8x8 path".into(),
                samples: 8,
                shard: Shard::new(k, m, 8).unwrap(),
            },
        )
    }

    #[test]
    fn a_whole_set_passes_in_any_order() {
        let set = vec![part(2, 3), part(0, 3), part(1, 3)];
        assert_eq!(check_set(&set), Ok(()));
    }

    #[test]
    fn bad_sets_are_refused_naming_the_file() {
        let message = |set: Vec<(PathBuf, PartHeader)>| check_set(&set).unwrap_err().to_string();
        let m = message(vec![part(0, 3), part(2, 3)]);
        assert!(
            m.starts_with("missing shard 1 of 3") && m.contains("part2.rgp"),
            "{m}"
        );
        let m = message(vec![part(0, 2), part(1, 2), part(1, 2)]);
        assert!(m.starts_with("part1.rgp: shard 1 of 2 again"), "{m}");
        let mut other = part(1, 2);
        other.1.scene_hash = 7;
        other.0 = PathBuf::from("other.rgp");
        let m = message(vec![part(0, 2), other]);
        assert!(
            m.starts_with("other.rgp: the scene or its setup differs from part0.rgp"),
            "{m}"
        );
        let mut old = part(1, 2);
        old.1.version = "0.0.9".into();
        let m = message(vec![part(0, 2), old]);
        assert!(m.contains("raygine version"), "{m}");
        assert_eq!(check_set(&[]), Err(PartError::NoParts));
    }
}
