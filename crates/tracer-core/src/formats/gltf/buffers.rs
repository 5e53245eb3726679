//! glTF buffers and the accessors raygine reads from them (positions, normals, indices), with
//! every offset and length checked, so no file makes the reader index out of bounds.
//!
//! Buffers come from the `.glb`'s binary chunk, a `data:` URI (base64) or a file beside the
//! `.gltf`: relative paths only, resolved inside the file's folder (`..` that leaves it, absolute
//! paths and other URI schemes are refused).

use crate::formats::error::{FormatError, MAX_SCENE_FILE_BYTES, read_limited};
use ::gltf::accessor::{DataType, Dimensions};
use base64::Engine;
use std::path::{Component, Path, PathBuf};

/// Loads the file a buffer URI names, relative to the `.gltf`'s folder.
pub type ExternalLoader<'a> = dyn Fn(&Path) -> Result<Vec<u8>, String> + 'a;

/// The bytes of every buffer, in order.
pub(super) fn load(
    doc: &::gltf::Document,
    blob: Option<&[u8]>,
    path: &Path,
    external: &ExternalLoader<'_>,
) -> Result<Vec<Vec<u8>>, FormatError> {
    let mut out = Vec::new();
    for buffer in doc.buffers() {
        let i = buffer.index();
        let what = |why: String| FormatError::new(path, 0, format!("buffer {i}: {why}"));
        if buffer.length() as u64 > MAX_SCENE_FILE_BYTES {
            return Err(what(format!(
                "{} bytes is larger than raygine reads ({MAX_SCENE_FILE_BYTES})",
                buffer.length()
            )));
        }
        let data = match buffer.source() {
            ::gltf::buffer::Source::Bin => blob
                .ok_or_else(|| what("refers to the binary chunk, which the file lacks".into()))?
                .to_vec(),
            ::gltf::buffer::Source::Uri(uri) => {
                if let Some(rest) = uri.strip_prefix("data:") {
                    decode_data_uri(rest).map_err(|why| what(format!("data URI: {why}")))?
                } else {
                    let relative = relative_path(uri).map_err(what)?;
                    external(&relative)
                        .map_err(|why| what(format!("{}: {why}", relative.display())))?
                }
            }
        };
        if data.len() < buffer.length() {
            return Err(what(format!(
                "holds {} bytes, the file declares {}",
                data.len(),
                buffer.length()
            )));
        }
        out.push(data);
    }
    Ok(out)
}

/// Where each image of the file is: inside a buffer view or a `data:` URI (its bytes, named
/// `FILE#imageN`), a file beside the `.gltf`, or missing with the reason. Decoding waits
/// until a material uses the image.
pub(super) fn images(
    doc: &::gltf::Document,
    buffers: &[Vec<u8>],
    path: &Path,
) -> Vec<crate::formats::ImageSource> {
    use crate::formats::ImageSource;
    let file = path
        .file_name()
        .map_or_else(String::new, |f| f.to_string_lossy().into_owned());
    let folder = path.parent().unwrap_or(Path::new(""));
    // From the JSON itself: gltf 1.4's `Image::source` unwraps a missing `mimeType` or `uri`.
    let json = doc.as_json();
    json.images
        .iter()
        .enumerate()
        .map(|(i, image)| {
            let name = format!("{file}#image{i}");
            let missing = |why: String| ImageSource::Missing {
                name: name.clone(),
                why,
            };
            if let Some(view) = &image.buffer_view {
                let bytes = json.buffer_views.get(view.value()).and_then(|v| {
                    let start = v.byte_offset.map_or(0, |o| o.0) as usize;
                    let end = start.checked_add(v.byte_length.0 as usize)?;
                    buffers.get(v.buffer.value())?.get(start..end)
                });
                match bytes {
                    Some(b) => ImageSource::Embedded {
                        name,
                        bytes: b.into(),
                    },
                    None => missing("its buffer view is missing or runs past its buffer".into()),
                }
            } else if let Some(uri) = &image.uri {
                if let Some(rest) = uri.strip_prefix("data:") {
                    match decode_data_uri(rest) {
                        Ok(b) => ImageSource::Embedded {
                            name,
                            bytes: b.into(),
                        },
                        Err(why) => missing(format!("data URI: {why}")),
                    }
                } else {
                    match relative_path(uri) {
                        Ok(relative) => ImageSource::File(folder.join(relative)),
                        Err(why) => missing(why),
                    }
                }
            } else {
                missing("the image has neither a uri nor a bufferView".into())
            }
        })
        .collect()
}

/// Reads a buffer file beside the `.gltf` (for [`load`]'s `external`).
pub fn read_beside(folder: &Path, relative: &Path) -> Result<Vec<u8>, String> {
    let file = folder.join(relative);
    read_limited(&file, "the buffer").map_err(|e| e.reason)
}

/// `data:[<mediatype>][;base64],<data>`: only base64 data is binary data.
fn decode_data_uri(rest: &str) -> Result<Vec<u8>, String> {
    let (header, data) = rest
        .split_once(',')
        .ok_or("no `,` between the media type and the data")?;
    if !header.ends_with(";base64") {
        return Err("not base64-encoded".into());
    }
    base64::engine::general_purpose::STANDARD
        .decode(data.trim())
        .map_err(|e| format!("does not decode as base64: {e}"))
}

/// A buffer URI as a path inside the `.gltf`'s folder.
fn relative_path(uri: &str) -> Result<PathBuf, String> {
    if uri.contains("://") || uri.starts_with('/') || uri.starts_with('\\') || uri.contains(':') {
        return Err(format!(
            "`{uri}`: only files beside the .gltf are read (no absolute paths or URLs)"
        ));
    }
    let decoded = percent_encoding::percent_decode_str(uri)
        .decode_utf8()
        .map_err(|_| format!("`{uri}`: not UTF-8 after percent-decoding"))?;
    let path = PathBuf::from(decoded.as_ref());
    let mut depth = 0i32;
    for c in path.components() {
        match c {
            Component::Normal(_) => depth += 1,
            Component::CurDir => {}
            Component::ParentDir => depth -= 1,
            _ => depth = -1,
        }
        if depth < 0 {
            return Err(format!("`{uri}` is outside the file's folder"));
        }
    }
    Ok(path)
}

/// What an accessor holds, as raygine reads it.
fn element(accessor: &::gltf::Accessor<'_>) -> (usize, usize) {
    let components = match accessor.dimensions() {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 => 4,
        Dimensions::Mat2 => 4,
        Dimensions::Mat3 => 9,
        Dimensions::Mat4 => 16,
    };
    let size = match accessor.data_type() {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    };
    (components, size)
}

/// The byte ranges of an accessor's elements: (slice of the view, stride), checked.
fn view_bytes<'b>(
    accessor: &::gltf::Accessor<'_>,
    buffers: &'b [Vec<u8>],
) -> Result<(&'b [u8], usize), String> {
    if accessor.sparse().is_some() {
        return Err("sparse accessors are not supported".into());
    }
    let view = accessor
        .view()
        .ok_or("has no buffer view (all zeros is not supported)")?;
    let data = buffers
        .get(view.buffer().index())
        .ok_or("its view names a buffer that does not exist")?;
    let (components, size) = element(accessor);
    let elem = components * size;
    let stride = view.stride().unwrap_or(elem);
    if stride < elem {
        return Err(format!(
            "stride {stride} is shorter than an element ({elem} bytes)"
        ));
    }
    let view_end = view
        .offset()
        .checked_add(view.length())
        .filter(|&e| e <= data.len())
        .ok_or("its view runs past the end of its buffer")?;
    let bytes = &data[view.offset()..view_end];
    let count = accessor.count();
    let needed = count
        .checked_sub(1)
        .map_or(Some(0), |last| {
            last.checked_mul(stride)
                .and_then(|x| x.checked_add(elem))
                .and_then(|x| x.checked_add(accessor.offset()))
        })
        .ok_or("its size overflows")?;
    if needed > bytes.len() {
        return Err(format!(
            "{count} elements need {needed} bytes, its view holds {}",
            bytes.len()
        ));
    }
    Ok((&bytes[accessor.offset().min(bytes.len())..], stride))
}

/// An accessor of `N`-vectors of f32 (`dimensions`: positions and normals are 3-vectors,
/// tangents 4-vectors), every component finite.
fn read_floats<const N: usize>(
    accessor: &::gltf::Accessor<'_>,
    buffers: &[Vec<u8>],
    dimensions: Dimensions,
) -> Result<Vec<[f32; N]>, String> {
    if accessor.dimensions() != dimensions || accessor.data_type() != DataType::F32 {
        return Err(format!(
            "{:?} of {:?}: raygine reads {N}-vectors of f32",
            accessor.dimensions(),
            accessor.data_type()
        ));
    }
    let (bytes, stride) = view_bytes(accessor, buffers)?;
    (0..accessor.count())
        .map(|i| {
            let at = i * stride;
            let v: [f32; N] = std::array::from_fn(|k| {
                let b = &bytes[at + 4 * k..at + 4 * k + 4];
                f32::from_le_bytes([b[0], b[1], b[2], b[3]])
            });
            if v.iter().all(|c| c.is_finite()) {
                Ok(v)
            } else {
                Err(format!("element {i} is not finite"))
            }
        })
        .collect()
}

/// An accessor of 3-vectors of f32 (positions, normals).
pub(super) fn read_vec3(
    accessor: &::gltf::Accessor<'_>,
    buffers: &[Vec<u8>],
) -> Result<Vec<[f32; 3]>, String> {
    read_floats(accessor, buffers, Dimensions::Vec3)
}

/// An accessor of tangents: 4-vectors of f32.
pub(super) fn read_vec4(
    accessor: &::gltf::Accessor<'_>,
    buffers: &[Vec<u8>],
) -> Result<Vec<[f32; 4]>, String> {
    read_floats(accessor, buffers, Dimensions::Vec4)
}

/// An accessor of texture coordinates: 2-vectors of f32, or of normalised u8 or u16. Values
/// that are not finite are an error.
pub(super) fn read_vec2(
    accessor: &::gltf::Accessor<'_>,
    buffers: &[Vec<u8>],
) -> Result<Vec<[f32; 2]>, String> {
    let size = match accessor.data_type() {
        DataType::F32 => 4,
        DataType::U16 if accessor.normalized() => 2,
        DataType::U8 if accessor.normalized() => 1,
        other => {
            return Err(format!(
                "{other:?}: raygine reads texture coordinates as f32 or normalised u8 or u16"
            ));
        }
    };
    if accessor.dimensions() != Dimensions::Vec2 {
        return Err(format!(
            "{:?}: texture coordinates are 2-vectors",
            accessor.dimensions()
        ));
    }
    let (bytes, stride) = view_bytes(accessor, buffers)?;
    (0..accessor.count())
        .map(|i| {
            let at = i * stride;
            let f = |k: usize| {
                let b = &bytes[at + size * k..at + size * k + size];
                match size {
                    4 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
                    2 => f32::from(u16::from_le_bytes([b[0], b[1]])) / 65535.0,
                    _ => f32::from(b[0]) / 255.0,
                }
            };
            let v = [f(0), f(1)];
            if v.iter().all(|c| c.is_finite()) {
                Ok(v)
            } else {
                Err(format!("element {i} is not finite"))
            }
        })
        .collect()
}

/// An index accessor (scalars of u8, u16 or u32).
pub(super) fn read_indices(
    accessor: &::gltf::Accessor<'_>,
    buffers: &[Vec<u8>],
) -> Result<Vec<u32>, String> {
    let (components, size) = element(accessor);
    if components != 1
        || !matches!(
            accessor.data_type(),
            DataType::U8 | DataType::U16 | DataType::U32
        )
    {
        return Err("indices must be scalars of u8, u16 or u32".into());
    }
    let (bytes, stride) = view_bytes(accessor, buffers)?;
    Ok((0..accessor.count())
        .map(|i| {
            let b = &bytes[i * stride..i * stride + size];
            match size {
                1 => u32::from(b[0]),
                2 => u32::from(u16::from_le_bytes([b[0], b[1]])),
                _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            }
        })
        .collect())
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    #[test]
    fn buffer_paths_stay_in_the_folder() {
        assert_eq!(
            relative_path("a%20b.bin").as_deref(),
            Ok(Path::new("a b.bin"))
        );
        assert!(relative_path("sub/../x.bin").is_ok());
        for bad in [
            "../x.bin",
            "sub/../../x.bin",
            "/etc/passwd",
            "http://a/b.bin",
            "C:\\x.bin",
        ] {
            assert!(relative_path(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn data_uris_decode_or_say_why_not() {
        assert_eq!(
            decode_data_uri("application/octet-stream;base64,AAEC"),
            Ok(vec![0, 1, 2])
        );
        assert!(decode_data_uri("application/octet-stream;base64,A*EC").is_err());
        assert!(decode_data_uri("text/plain,abc").is_err());
    }
}
