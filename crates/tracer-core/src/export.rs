//! Writing images without ever leaving a half-written file: encode to a temporary file in the
//! destination's folder, then rename it into place. On failure the temporary file is removed and
//! any existing file at the destination is untouched.

use crate::render::Film;
use glam::Vec3;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error("{}: {reason}", path.display())]
    Io { path: PathBuf, reason: String },
    #[error("{}: cannot encode the image: {reason}", path.display())]
    Encode { path: PathBuf, reason: String },
}

/// Writes RGBA8 pixels (row-major, top row first) as a PNG.
pub fn write_png(path: &Path, rgba: Vec<u8>, width: u32, height: u32) -> Result<(), ExportError> {
    write_png_pixels(path, &rgba, width, height, ExtendedColorType::Rgba8)
}

/// Writes RGB8 pixels (row-major, top row first, 3 bytes a pixel) as a PNG. Rendered images are
/// opaque, so this is the smaller and faster form of [`write_png`].
pub fn write_png_rgb(path: &Path, rgb: &[u8], width: u32, height: u32) -> Result<(), ExportError> {
    write_png_pixels(path, rgb, width, height, ExtendedColorType::Rgb8)
}

fn write_png_pixels(
    path: &Path,
    pixels: &[u8],
    width: u32,
    height: u32,
    color: ExtendedColorType,
) -> Result<(), ExportError> {
    let expected = width as usize * height as usize * usize::from(color.bits_per_pixel() / 8);
    if pixels.len() != expected {
        return Err(ExportError::Encode {
            path: path.to_owned(),
            reason: "pixel buffer does not match the image size".to_owned(),
        });
    }
    write_atomically(path, |w| {
        // Fast deflate with the Up filter: renders compress nearly as well as with adaptive
        // filtering, at a fraction of the encoding time.
        let encoder = PngEncoder::new_with_quality(w, CompressionType::Fast, FilterType::Up);
        encoder
            .write_image(pixels, width, height, color)
            .map_err(|e| e.to_string())
    })
}

/// Writes the film's mean linear luminance per channel (cd/m²) as OpenEXR (32-bit float).
pub fn write_exr(path: &Path, film: &Film) -> Result<(), ExportError> {
    write_exr_with_denoised(path, film, None)
}

/// [`write_exr`], and when `denoised` is given (cd/m² per channel, one per pixel) the denoised
/// picture beside it as the channels `denoised.R`, `denoised.G`, `denoised.B`. The raw R, G, B
/// stay the film's unbiased means.
///
/// Streamed: each pixel's mean is computed as the encoder asks for it, block by block, so the
/// export holds no copy of the image (a 3840x2160 picture's floats alone are 100 MB).
pub fn write_exr_with_denoised(
    path: &Path,
    film: &Film,
    denoised: Option<&[Vec3]>,
) -> Result<(), ExportError> {
    use exr::prelude::{
        Encoding, Image, Layer, LayerAttributes, SpecificChannels, Vec2, WritableImage,
    };
    let n = film.len();
    if denoised.is_some_and(|d| d.len() != n) {
        return Err(ExportError::Encode {
            path: path.to_owned(),
            reason: "the denoised image does not match the film's size".to_owned(),
        });
    }
    let size = (film.width as usize, film.height as usize);
    let width = size.0;
    let raw = |p: Vec2<usize>| film.mean_rgb(p.1 * width + p.0);
    write_atomically(path, |w| {
        let written = match denoised {
            None => {
                let channels = SpecificChannels::rgb(|p: Vec2<usize>| {
                    let c = raw(p);
                    (c.x, c.y, c.z)
                });
                let attributes = LayerAttributes::default();
                let layer = Layer::new(size, attributes, Encoding::FAST_LOSSLESS, channels);
                Image::from_layer(layer).write().to_buffered(w)
            }
            Some(d) => {
                let channels = SpecificChannels::build()
                    .with_channel("R")
                    .with_channel("G")
                    .with_channel("B")
                    .with_channel("denoised.R")
                    .with_channel("denoised.G")
                    .with_channel("denoised.B")
                    .with_pixel_fn(|p: Vec2<usize>| {
                        let (c, e) = (raw(p), d[p.1 * width + p.0]);
                        (c.x, c.y, c.z, e.x, e.y, e.z)
                    });
                let attributes = LayerAttributes::default();
                let layer = Layer::new(size, attributes, Encoding::FAST_LOSSLESS, channels);
                Image::from_layer(layer).write().to_buffered(w)
            }
        };
        written.map_err(|e| e.to_string())
    })
}

/// Writes bytes (a part file) atomically.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), ExportError> {
    write_atomically(path, |w| w.write_all(bytes).map_err(|e| e.to_string()))
}

/// Writes text (a sidecar) atomically.
pub fn write_text(path: &Path, text: &str) -> Result<(), ExportError> {
    write_atomically(path, |w| {
        w.write_all(text.as_bytes()).map_err(|e| e.to_string())
    })
}

fn write_atomically(
    path: &Path,
    encode: impl FnOnce(&mut BufWriter<std::fs::File>) -> Result<(), String>,
) -> Result<(), ExportError> {
    let io_err = |reason: String| ExportError::Io {
        path: path.to_owned(),
        reason,
    };
    if path.is_dir() {
        return Err(io_err("is a directory".to_owned()));
    }
    // A symbolic link is followed (its target is replaced, the link kept), and what is not a
    // regular file (/dev/stdout, a pipe) is written directly: renaming over it would replace a
    // device or a link with a plain file.
    let resolved;
    let path = match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => {
            resolved = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_owned());
            resolved.as_path()
        }
        _ => path,
    };
    if std::fs::metadata(path).is_ok_and(|m| !m.is_file()) {
        let file = std::fs::OpenOptions::new()
            .write(true)
            .open(path)
            .map_err(|e| io_err(format!("cannot write: {e}")))?;
        let mut w = BufWriter::new(file);
        encode(&mut w).map_err(|reason| ExportError::Encode {
            path: path.to_owned(),
            reason,
        })?;
        return w
            .into_inner()
            .map(|_| ())
            .map_err(|e| io_err(format!("cannot write: {}", e.error())));
    }
    let file_name = path
        .file_name()
        .ok_or_else(|| io_err("not a file path".to_owned()))?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let tmp = dir.join(format!(
        ".{}.{}.tmp",
        file_name.to_string_lossy(),
        std::process::id()
    ));
    let result = (|| {
        let file = std::fs::File::create(&tmp).map_err(|e| io_err(format!("cannot write: {e}")))?;
        let mut w = BufWriter::new(file);
        encode(&mut w).map_err(|reason| ExportError::Encode {
            path: path.to_owned(),
            reason,
        })?;
        let file = w
            .into_inner()
            .map_err(|e| io_err(format!("cannot write: {}", e.error())))?;
        file.sync_all()
            .map_err(|e| io_err(format!("cannot write: {e}")))?;
        std::fs::rename(&tmp, path).map_err(|e| io_err(format!("cannot replace the file: {e}")))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    /// A link is followed (the link stays a link, its target gets the text), and what is not a
    /// regular file is written in place, never renamed over.
    #[cfg(unix)]
    #[test]
    fn writing_through_a_link_keeps_the_link() {
        let dir = std::env::temp_dir().join(format!("raygine-link-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (target, link) = (dir.join("target.json"), dir.join("link.json"));
        std::fs::write(&target, "old").unwrap();
        let _ = std::fs::remove_file(&link);
        std::os::unix::fs::symlink(&target, &link).unwrap();
        write_text(&link, "new").unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        write_text(Path::new("/dev/null"), "nothing").unwrap();
        assert!(!std::fs::metadata("/dev/null").unwrap().is_file());
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// Reads every channel of an EXR: name → samples (row-major).
    fn channels(path: &Path) -> Vec<(String, Vec<f32>)> {
        use exr::prelude::*;
        let image = read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .first_valid_layer()
            .all_attributes()
            .from_file(path)
            .unwrap();
        image
            .layer_data
            .channel_data
            .list
            .iter()
            .map(|c| (c.name.to_string(), c.sample_data.values_as_f32().collect()))
            .collect()
    }

    #[test]
    fn the_streamed_exr_holds_the_film_means_and_the_denoised_picture() {
        let (w, h) = (70, 9);
        let rgb: Vec<Vec3> = (0..w * h)
            .map(|i| Vec3::new(i as f32 * 0.37, 1.0 / (1.0 + i as f32), 3.0e6))
            .collect();
        let film = Film::from_values(w, h, &rgb, &vec![0.0; rgb.len()]);
        let denoised: Vec<Vec3> = rgb.iter().map(|c| *c * 0.5 + Vec3::X).collect();
        let dir = std::env::temp_dir().join(format!("raygine-exr-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (plain, both) = (dir.join("plain.exr"), dir.join("both.exr"));
        write_exr(&plain, &film).unwrap();
        write_exr_with_denoised(&both, &film, Some(&denoised)).unwrap();
        let expect =
            |k: usize, pixels: &[Vec3]| -> Vec<f32> { pixels.iter().map(|p| p[k]).collect() };
        let means: Vec<Vec3> = (0..film.len()).map(|i| film.mean_rgb(i)).collect();
        let got = channels(&plain);
        let names: Vec<&str> = got.iter().map(|c| c.0.as_str()).collect();
        assert_eq!(names, ["B", "G", "R"]);
        for (name, samples) in &got {
            let k = ["R", "G", "B"].iter().position(|n| n == name).unwrap();
            assert_eq!(*samples, expect(k, &means), "{name}");
        }
        let got = channels(&both);
        assert_eq!(got.len(), 6);
        for (name, samples) in &got {
            let (source, channel) = match name.strip_prefix("denoised.") {
                Some(c) => (&denoised, c),
                None => (&means, name.as_str()),
            };
            let k = ["R", "G", "B"].iter().position(|n| *n == channel).unwrap();
            assert_eq!(*samples, expect(k, source), "{name}");
        }
        let short = write_exr_with_denoised(&both, &film, Some(&denoised[1..]));
        assert!(short.is_err());
        std::fs::remove_dir_all(&dir).ok();
    }
}
