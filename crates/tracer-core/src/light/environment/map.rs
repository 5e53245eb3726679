//! An environment map read from a file: a latitude-longitude image (Radiance `.hdr` or
//! OpenEXR, through the `image` crate), 2:1, linear RGB, with the density that samples it.

use super::distribution::Distribution2d;
use crate::light::luminance;
use glam::Vec3;
use image::{DynamicImage, ImageDecoder, ImageFormat, ImageReader, Limits};
use std::f32::consts::PI;
use std::fs::File;
use std::io::{BufRead, BufReader, Cursor, ErrorKind, Seek, SeekFrom};
use std::panic::{self, AssertUnwindSafe};
use std::path::{Path, PathBuf};

/// A latitude-longitude map: row 0 is the zenith, the last row the nadir; see
/// [`super::EnvironmentLight`] for the directions of its columns.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvironmentMap {
    pub file: PathBuf,
    pub width: usize,
    pub height: usize,
    /// Linear RGB, row by row.
    pub texels: Vec<Vec3>,
    /// Samples a texel by its luminance times the sine of its row's polar angle.
    pub(super) distribution: Distribution2d,
    /// ∫ Y dω over the sphere of the texels' luminance Y (unscaled).
    pub(super) integral: f64,
}

impl EnvironmentMap {
    /// Reads `path`. Texels that are NaN, infinite or negative are read as 0 and reported in
    /// the returned notes; a map that is not twice as wide as high, or larger than
    /// [`Self::MAX_TEXELS`], is an error. Errors start with the file's name.
    pub fn load(path: &Path) -> Result<(EnvironmentMap, Vec<String>), String> {
        let file = File::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
        Self::decode(BufReader::new(file), path)
    }

    /// Reads a map from `bytes`, as [`Self::load`] reads a file: the content decides between
    /// Radiance `.hdr` and OpenEXR, else the extension of `name`, which also names the map
    /// (and starts every error).
    pub fn from_bytes(bytes: &[u8], name: &Path) -> Result<(EnvironmentMap, Vec<String>), String> {
        Self::decode(Cursor::new(bytes), name)
    }

    /// The most texels a map may have: 16384 x 8192, the largest latitude-longitude maps
    /// commonly published. The size is checked before decoding, which allocates 12 or 16 bytes
    /// a texel (RGB or RGBA f32) before it reads a pixel: a header alone cannot ask for a
    /// buffer of more than 2 GiB.
    pub const MAX_TEXELS: usize = 1 << 27;

    /// `load` and `from_bytes`: the pixels, then the map.
    fn decode(
        reader: impl BufRead + Seek,
        path: &Path,
    ) -> Result<(EnvironmentMap, Vec<String>), String> {
        let shown = path.display();
        // Crafted files overflow integers inside the decoders (image 0.25.10's .hdr run
        // markers, fixed upstream in image-rs/image#2714 but unreleased; exr 1.74's B44
        // unpacking). A release build wraps and then fails; where overflow checks are on,
        // that is a panic, which must not take the renderer down.
        let (width, height, texels) =
            panic::catch_unwind(AssertUnwindSafe(|| read_texels(reader, path))).map_err(
                |payload| {
                    let why = payload
                        .downcast_ref::<&str>()
                        .map(|s| s.to_string())
                        .or_else(|| payload.downcast_ref::<String>().cloned())
                        .unwrap_or_default();
                    format!("{shown}: the image decoder failed on this file ({why})")
                },
            )??;
        let (map, bad) = Self::from_texels(path, width, height, texels)?;
        let notes = if bad > 0 {
            vec![format!(
                "{shown}: {bad} texels are NaN, infinite or negative; read as 0"
            )]
        } else {
            Vec::new()
        };
        Ok((map, notes))
    }

    /// A map of `texels` (row by row); returns it and how many texels were invalid (NaN,
    /// infinite, negative, or so bright that their luminance is infinite), set to 0. A map
    /// whose luminance sums beyond `f32::MAX` is an error: its density could not be sampled.
    pub fn from_texels(
        path: &Path,
        width: usize,
        height: usize,
        mut texels: Vec<Vec3>,
    ) -> Result<(EnvironmentMap, usize), String> {
        check_size(path, width, height)?;
        if texels.len() != width * height {
            return Err(format!(
                "{}: {} texels for a {width} x {height} px map",
                path.display(),
                texels.len()
            ));
        }
        let mut bad = 0;
        for t in &mut texels {
            if !(t.is_finite() && t.min_element() >= 0.0 && luminance(*t).is_finite()) {
                bad += 1;
                *t = Vec3::ZERO;
            }
        }
        // Each texel's share of the sphere: sin θ dθ dφ at its row's centre.
        let cell = (PI / height as f32) * (2.0 * PI / width as f32);
        let weights: Vec<f32> = texels
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let theta = ((i / width) as f32 + 0.5) / height as f32 * PI;
                luminance(*t) * theta.sin()
            })
            .collect();
        let distribution = Distribution2d::new(&weights, width);
        let integral = distribution.total() * f64::from(cell);
        if !integral.is_finite() {
            return Err(format!(
                "{}: too bright to sample: its texels' luminance sums beyond {:e}",
                path.display(),
                f32::MAX
            ));
        }
        Ok((
            EnvironmentMap {
                file: path.to_owned(),
                width,
                height,
                texels,
                distribution,
                integral,
            },
            bad,
        ))
    }

    /// The texel at `uv` in [0, 1)² (nearest: the same cells the density samples).
    pub(super) fn texel(&self, uv: [f32; 2]) -> Vec3 {
        let col = ((uv[0] * self.width as f32) as usize).min(self.width - 1);
        let row = ((uv[1] * self.height as f32) as usize).min(self.height - 1);
        self.texels[row * self.width + col]
    }
}

/// What decoding the largest map may allocate for one buffer: its texels as RGBA f32.
const MAX_DECODED_BYTES: u64 = EnvironmentMap::MAX_TEXELS as u64 * 16;

/// A map of `width` x `height` px is not empty, 2:1 and at most `MAX_TEXELS`.
fn check_size(path: &Path, width: usize, height: usize) -> Result<(), String> {
    let shown = path.display();
    if width == 0 || height == 0 {
        return Err(format!(
            "{shown}: an empty environment map ({width} x {height} px)"
        ));
    }
    if width != 2 * height {
        return Err(format!(
            "{shown}: a latitude-longitude map is twice as wide as high; this one is \
             {width} x {height} px"
        ));
    }
    if width.saturating_mul(height) > EnvironmentMap::MAX_TEXELS {
        let max_height = (EnvironmentMap::MAX_TEXELS / 2).isqrt();
        return Err(format!(
            "{shown}: {width} x {height} px is too large an environment map (at most {} x \
             {max_height} px)",
            2 * max_height
        ));
    }
    Ok(())
}

/// The size and linear RGB texels of a Radiance .hdr or OpenEXR image: the format from the
/// content (else the extension), then the size from the header, checked before the pixels'
/// buffer is allocated.
fn read_texels(
    reader: impl BufRead + Seek,
    path: &Path,
) -> Result<(usize, usize, Vec<Vec3>), String> {
    let shown = path.display();
    let mut reader = ImageReader::new(reader);
    if let Ok(format) = ImageFormat::from_path(path) {
        reader.set_format(format);
    }
    let reader = reader
        .with_guessed_format()
        .map_err(|e| format!("{shown}: {e}"))?;
    let format = match reader.format() {
        Some(format @ (ImageFormat::Hdr | ImageFormat::OpenExr)) => format,
        Some(other) => {
            return Err(format!(
                "{shown}: a {other:?} image; an environment map is a Radiance .hdr or OpenEXR \
                 file"
            ));
        }
        None => {
            return Err(format!(
                "{shown}: neither a Radiance .hdr nor an OpenEXR file"
            ));
        }
    };
    let mut inner = reader.into_inner();
    if format == ImageFormat::OpenExr {
        let io = |e: std::io::Error| format!("{shown}: {e}");
        let start = inner.stream_position().map_err(io)?;
        check_exr_layers(&mut inner, path)?;
        inner.seek(SeekFrom::Start(start)).map_err(io)?;
    }
    let mut reader = ImageReader::with_format(inner, format);
    // Decoders that count their allocations stop at the largest map as RGBA f32.
    let mut limits = Limits::default();
    limits.max_alloc = Some(MAX_DECODED_BYTES);
    reader.limits(limits);
    let unreadable = |e: image::ImageError| match e {
        image::ImageError::IoError(e) if e.kind() == ErrorKind::UnexpectedEof => {
            format!("{shown}: the file ends before the image does")
        }
        e => format!("{shown}: not a readable .hdr or .exr image: {e}"),
    };
    let decoder = reader.into_decoder().map_err(unreadable)?;
    let (width, height) = decoder.dimensions();
    let (width, height) = (width as usize, height as usize);
    check_size(path, width, height)?;
    let texels = DynamicImage::from_decoder(decoder)
        .map_err(unreadable)?
        .into_rgb32f()
        .into_raw()
        .chunks_exact(3)
        .map(Vec3::from_slice)
        .collect();
    Ok((width, height, texels))
}

/// OpenEXR files are read block by block, sized by each layer's data window and channels, not
/// by the display window that `image` reports: each layer and each of its blocks must fit in
/// what the largest map needs, checked before any block is read.
fn check_exr_layers(reader: &mut impl BufRead, path: &Path) -> Result<(), String> {
    let shown = path.display();
    let meta = exr::meta::MetaData::read_from_buffered(reader, false)
        .map_err(|e| format!("{shown}: not a readable .hdr or .exr image: {e}"))?;
    for header in &meta.headers {
        let (width, height) = (header.layer_size.width(), header.layer_size.height());
        let texels = (width as u64).saturating_mul(height as u64);
        let texel_bytes = header.channels.bytes_per_pixel as u64;
        let block_texels = match header.blocks {
            exr::meta::BlockDescription::ScanLines => {
                (header.compression.scan_lines_per_block() as u64).saturating_mul(width as u64)
            }
            exr::meta::BlockDescription::Tiles(tiles) => {
                (tiles.tile_size.width() as u64).saturating_mul(tiles.tile_size.height() as u64)
            }
        };
        if texels > EnvironmentMap::MAX_TEXELS as u64
            || texels.saturating_mul(texel_bytes) > MAX_DECODED_BYTES
            || block_texels.saturating_mul(texel_bytes) > MAX_DECODED_BYTES
        {
            return Err(format!(
                "{shown}: a layer of {width} x {height} px in {} channels is too large for an \
                 environment map",
                header.channels.list.len()
            ));
        }
    }
    Ok(())
}
