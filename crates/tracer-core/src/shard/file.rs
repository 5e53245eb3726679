//! The part file: a text header anyone can read with `head`, then the binary payload.
//!
//! ```text
//! raygine-partial 1                        magic and format version
//! kind render                              render (a film) or measure (grid sums)
//! raygine 0.1.0                            the version that wrote it
//! scene cornell_box                        the scene's name (for people; not compared)
//! scene_hash 5f0e6c1d2b3a4958              shard::scene_hash of the built scene and setup
//! settings 64x48 path max_depth=5 …        what else the sums depend on (compared verbatim)
//! samples 16                               N, samples of the whole image
//! shard 2 of 4                             K of M
//! sample_range 8..12                       the sample indices in this part
//! payload_bytes 20480                      length of the payload
//! checksum 9a4c…                           FNV-1a 64 of the lines above and the payload
//! (empty line)
//! payload
//! ```
//!
//! Files are written to a temporary name and renamed into place, so a part is whole or absent; a
//! shard that crashes and is run again writes the same bytes.

use super::Shard;
use super::hash::StableHash;
use std::path::{Path, PathBuf};

/// The part format this build writes and reads (5: squared luminances in two fields each, to
/// 2⁻⁴⁸).
pub const PART_FORMAT: u32 = 5;

const MAGIC: &str = "raygine-partial";
/// Longest header read before deciding a file is not a part.
const MAX_HEADER: usize = 4096;

/// What a part holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PartKind {
    /// A film: per-pixel sums (`render::partial`).
    Render,
    /// Grid sums: per-point sums (`measure::partial`).
    Measure,
}

impl PartKind {
    pub fn name(self) -> &'static str {
        match self {
            PartKind::Render => "render",
            PartKind::Measure => "measure",
        }
    }

    fn from_name(s: &str) -> Option<PartKind> {
        [PartKind::Render, PartKind::Measure]
            .into_iter()
            .find(|k| k.name() == s)
    }
}

/// Everything a part says about itself besides its payload.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PartHeader {
    pub kind: PartKind,
    /// The raygine version that wrote it.
    pub version: String,
    /// The scene's name, for people.
    pub scene: String,
    /// [`super::scene_hash`] of the scene and setup.
    pub scene_hash: u64,
    /// The settings the sums depend on besides the scene, as one line.
    pub settings: String,
    /// N: samples of the whole image (or per point).
    pub samples: u32,
    pub shard: Shard,
}

/// Why a part cannot be written, read or merged. Every message names the file.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum PartError {
    #[error("{}: {reason}", path.display())]
    Io { path: PathBuf, reason: String },
    #[error("{}: not a raygine part file (it does not start with `{MAGIC}`)", path.display())]
    NotAPart { path: PathBuf },
    #[error("{}: part format {found}; this raygine reads format {PART_FORMAT}", path.display())]
    Format { path: PathBuf, found: String },
    #[error("{}: damaged header: {reason}", path.display())]
    Header { path: PathBuf, reason: String },
    #[error("{}: truncated: {found} of {expected} payload bytes", path.display())]
    Truncated {
        path: PathBuf,
        found: usize,
        expected: usize,
    },
    #[error("{}: damaged: {reason}", path.display())]
    Damaged { path: PathBuf, reason: String },
    #[error("{}: {what} differs from {} ({this} here, {that} there)", path.display(), other.display())]
    Mismatch {
        path: PathBuf,
        other: PathBuf,
        what: &'static str,
        this: String,
        that: String,
    },
    #[error("{}: shard {index} of {count} again (also in {})", path.display(), other.display())]
    Duplicate {
        path: PathBuf,
        other: PathBuf,
        index: u32,
        count: u32,
    },
    #[error("missing {missing} of {count} (parts given: {given})")]
    Missing {
        missing: String,
        count: u32,
        given: String,
    },
    #[error("no parts to merge")]
    NoParts,
}

fn clean(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect()
}

/// The header lines up to (not including) the checksum line.
fn header_lines(h: &PartHeader, payload_len: usize) -> String {
    let range = h.shard.samples(h.samples);
    format!(
        "{MAGIC} {PART_FORMAT}\nkind {}\nraygine {}\nscene {}\nscene_hash {:016x}\nsettings {}\n\
         samples {}\nshard {} of {}\nsample_range {}..{}\npayload_bytes {payload_len}\n",
        h.kind.name(),
        clean(&h.version),
        clean(&h.scene),
        h.scene_hash,
        clean(&h.settings),
        h.samples,
        h.shard.index,
        h.shard.count,
        range.start,
        range.end,
    )
}

fn checksum(head: &[u8], payload: &[u8]) -> u64 {
    let mut h = StableHash::new();
    h.write(head);
    h.write(payload);
    h.finish()
}

/// Writes a part atomically (temporary file, then rename).
pub fn write_part(path: &Path, header: &PartHeader, payload: &[u8]) -> Result<(), PartError> {
    let head = header_lines(header, payload.len());
    let sum = checksum(head.as_bytes(), payload);
    let mut bytes = Vec::with_capacity(head.len() + 32 + payload.len());
    bytes.extend_from_slice(head.as_bytes());
    bytes.extend_from_slice(format!("checksum {sum:016x}\n\n").as_bytes());
    bytes.extend_from_slice(payload);
    crate::export::write_bytes(path, &bytes).map_err(|e| PartError::Io {
        path: path.to_owned(),
        reason: match e {
            crate::export::ExportError::Io { reason, .. }
            | crate::export::ExportError::Encode { reason, .. } => reason,
        },
    })
}

/// Reads a part and checks it is whole: magic, format, header, length and checksum.
pub fn read_part(path: &Path) -> Result<(PartHeader, Vec<u8>), PartError> {
    let bytes = std::fs::read(path).map_err(|e| PartError::Io {
        path: path.to_owned(),
        reason: format!("cannot read: {e}"),
    })?;
    let err_header = |reason: String| PartError::Header {
        path: path.to_owned(),
        reason,
    };
    if !bytes.starts_with(MAGIC.as_bytes()) {
        return Err(PartError::NotAPart {
            path: path.to_owned(),
        });
    }
    let window = &bytes[..bytes.len().min(MAX_HEADER)];
    let Some(end) = window.windows(2).position(|w| w == b"\n\n") else {
        return Err(err_header(
            "it has no end (the file is cut short or not a part)".to_owned(),
        ));
    };
    let text = std::str::from_utf8(&bytes[..end + 1])
        .map_err(|_| err_header("not UTF-8 text".to_owned()))?;
    let mut lines = text.lines();
    let mut field = |key: &'static str| -> Result<&str, PartError> {
        let line = lines
            .next()
            .ok_or_else(|| err_header(format!("no `{key}` line")))?;
        line.strip_prefix(key)
            .and_then(|rest| rest.strip_prefix(' '))
            .ok_or_else(|| err_header(format!("expected `{key} …`, found `{line}`")))
    };
    let format = field(MAGIC)?;
    if format != PART_FORMAT.to_string() {
        return Err(PartError::Format {
            path: path.to_owned(),
            found: format.to_owned(),
        });
    }
    let number = |key: &str, s: &str| {
        s.parse::<u64>()
            .map_err(|_| err_header(format!("`{key}` is not a number: `{s}`")))
    };
    let kind = field("kind")?;
    let kind =
        PartKind::from_name(kind).ok_or_else(|| err_header(format!("unknown kind `{kind}`")))?;
    let version = field("raygine")?.to_owned();
    let scene = field("scene")?.to_owned();
    let hash_text = field("scene_hash")?;
    let scene_hash = u64::from_str_radix(hash_text, 16)
        .map_err(|_| err_header(format!("`scene_hash` is not hexadecimal: `{hash_text}`")))?;
    let settings = field("settings")?.to_owned();
    let samples = field("samples")?;
    let samples = u32::try_from(number("samples", samples)?)
        .map_err(|_| err_header("`samples` is too large".to_owned()))?;
    let shard_text = field("shard")?;
    let (k, m) = shard_text
        .split_once(" of ")
        .ok_or_else(|| err_header(format!("expected `shard K of M`, found `{shard_text}`")))?;
    let (k, m) = (number("shard", k)?, number("shard", m)?);
    let (Ok(index), Ok(count)) = (u32::try_from(k), u32::try_from(m)) else {
        return Err(err_header("the shard numbers are too large".to_owned()));
    };
    let shard = Shard::new(index, count, samples).map_err(|e| err_header(e.to_string()))?;
    let range = field("sample_range")?;
    let expected_range = shard.samples(samples);
    if range != format!("{}..{}", expected_range.start, expected_range.end) {
        return Err(err_header(format!(
            "sample_range {range} is not shard {index} of {count}'s"
        )));
    }
    let payload_len = field("payload_bytes")?;
    let payload_len = usize::try_from(number("payload_bytes", payload_len)?)
        .map_err(|_| err_header("`payload_bytes` is too large".to_owned()))?;
    // The checksum covers every byte before its own line.
    let head_len = text.trim_end_matches('\n').rfind('\n').map_or(0, |i| i + 1);
    let stored = field("checksum")?;
    let stored = u64::from_str_radix(stored, 16)
        .map_err(|_| err_header(format!("`checksum` is not hexadecimal: `{stored}`")))?;
    if lines.next().is_some() {
        return Err(err_header("unexpected lines after `checksum`".to_owned()));
    }
    let payload = &bytes[end + 2..];
    if payload.len() < payload_len {
        return Err(PartError::Truncated {
            path: path.to_owned(),
            found: payload.len(),
            expected: payload_len,
        });
    }
    if payload.len() > payload_len {
        return Err(PartError::Damaged {
            path: path.to_owned(),
            reason: format!("{} bytes after the payload", payload.len() - payload_len),
        });
    }
    if checksum(&bytes[..head_len], payload) != stored {
        return Err(PartError::Damaged {
            path: path.to_owned(),
            reason: "the checksum does not match the contents".to_owned(),
        });
    }
    let header = PartHeader {
        kind,
        version,
        scene,
        scene_hash,
        settings,
        samples,
        shard,
    };
    Ok((header, payload.to_vec()))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    fn header() -> PartHeader {
        PartHeader {
            kind: PartKind::Measure,
            version: "0.1.0".into(),
            scene: "room\nwith a newline".into(),
            scene_hash: 0xfeed,
            settings: "grids path max_bounces=none".into(),
            samples: 10,
            shard: Shard::new(1, 3, 10).unwrap(),
        }
    }

    #[test]
    fn parts_round_trip_and_damage_is_found() {
        let dir = std::env::temp_dir().join(format!("raygine-part-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("p.rgp");
        let payload: Vec<u8> = (0..200u32).map(|i| (i * 7) as u8).collect();
        write_part(&path, &header(), &payload).unwrap();
        let (h, p) = read_part(&path).unwrap();
        assert_eq!(h.scene, "room?with a newline");
        assert_eq!(
            (h.shard, h.scene_hash, p),
            (header().shard, 0xfeed, payload)
        );
        let bytes = std::fs::read(&path).unwrap();
        let text = String::from_utf8_lossy(&bytes[..200]).into_owned();
        assert!(text.contains("shard 1 of 3\nsample_range 3..6\n"), "{text}");

        let broken = dir.join("b.rgp");
        std::fs::write(&broken, &bytes[..bytes.len() - 10]).unwrap();
        let e = read_part(&broken).unwrap_err().to_string();
        assert!(
            e.contains("b.rgp: truncated: 190 of 200 payload bytes"),
            "{e}"
        );
        let mut flipped = bytes.clone();
        let n = flipped.len();
        flipped[n - 50] ^= 1;
        std::fs::write(&broken, &flipped).unwrap();
        let e = read_part(&broken).unwrap_err().to_string();
        assert!(e.contains("b.rgp: damaged: the checksum"), "{e}");
        let at = text.find("samples 10").unwrap() + 9;
        let mut header_flip = bytes.clone();
        header_flip[at] = b'2';
        std::fs::write(&broken, &header_flip).unwrap();
        assert!(read_part(&broken).is_err());
        std::fs::write(&broken, b"P6\n").unwrap();
        let e = read_part(&broken).unwrap_err().to_string();
        assert!(e.contains("not a raygine part file"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
