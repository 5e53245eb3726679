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
pub fn write_exr_with_denoised(
    path: &Path,
    film: &Film,
    denoised: Option<&[Vec3]>,
) -> Result<(), ExportError> {
    use exr::prelude::{
        AnyChannel, AnyChannels, Encoding, FlatSamples, Image, Layer, LayerAttributes, SmallVec,
        WritableImage,
    };
    let n = film.pixels.len();
    if denoised.is_some_and(|d| d.len() != n) {
        return Err(ExportError::Encode {
            path: path.to_owned(),
            reason: "the denoised image does not match the film's size".to_owned(),
        });
    }
    let raw = film.mean_rgb_all();
    let mut channels: SmallVec<[AnyChannel<FlatSamples>; 4]> = SmallVec::new();
    let mut add = |prefix: &str, pixels: &[Vec3]| {
        for (k, name) in ["R", "G", "B"].into_iter().enumerate() {
            let samples = pixels.iter().map(|p| p[k]).collect();
            channels.push(AnyChannel::new(
                format!("{prefix}{name}").as_str(),
                FlatSamples::F32(samples),
            ));
        }
    };
    add("", &raw);
    if let Some(d) = denoised {
        add("denoised.", d);
    }
    let layer = Layer::new(
        (film.width as usize, film.height as usize),
        LayerAttributes::default(),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(channels),
    );
    let image = Image::from_layer(layer);
    write_atomically(path, |w| {
        image.write().to_buffered(w).map_err(|e| e.to_string())
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
