//! One decoded texture image: RGBA8 texels, rows from the top (glTF's and the image's order).

use std::io::Cursor;

/// The largest side accepted, texels.
pub const MAX_TEXTURE_SIDE: u32 = 16_384;
/// The most texels accepted in one image (256 MB as RGBA8).
pub const MAX_TEXELS: u64 = 64 * 1024 * 1024;

/// Why an image could not become a texture.
#[derive(Debug, thiserror::Error)]
pub enum TextureError {
    #[error("cannot read {0}")]
    Io(String),
    #[error(
        "{width} x {height} texels is too large (at most {MAX_TEXTURE_SIDE} a side and {MAX_TEXELS} in all)"
    )]
    TooLarge { width: u32, height: u32 },
    #[error("not a PNG or JPEG image it can decode: {0}")]
    Decode(String),
    #[error("the image is empty (0 texels)")]
    Empty,
}

/// A texture: the image's texels as RGBA8 (grey images spread to RGB, alpha 255 where the
/// image has none), decoded per lookup (`super::Encoding`).
#[derive(Clone, PartialEq)]
pub struct Texture {
    /// The file name (or `model.glb#image2` for an embedded image), for the user.
    pub name: String,
    pub width: u32,
    pub height: u32,
    /// Channels in the file: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA.
    pub channels: u8,
    /// Row-major, row 0 at the top of the image (v = 0).
    pub texels: Vec<[u8; 4]>,
}

impl std::fmt::Debug for Texture {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "Texture({} {}x{} x{})",
            self.name, self.width, self.height, self.channels
        )
    }
}

impl Texture {
    /// Decodes PNG or JPEG bytes (`name` for messages), refusing images above
    /// [`MAX_TEXTURE_SIDE`] or [`MAX_TEXELS`] before allocating their texels.
    pub fn decode(name: &str, bytes: &[u8]) -> Result<Texture, TextureError> {
        let reader = image::ImageReader::new(Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|e| TextureError::Decode(e.to_string()))?;
        let (width, height) = reader
            .into_dimensions()
            .map_err(|e| TextureError::Decode(e.to_string()))?;
        if width == 0 || height == 0 {
            return Err(TextureError::Empty);
        }
        if width > MAX_TEXTURE_SIDE
            || height > MAX_TEXTURE_SIDE
            || u64::from(width) * u64::from(height) > MAX_TEXELS
        {
            return Err(TextureError::TooLarge { width, height });
        }
        let mut reader = image::ImageReader::new(Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|e| TextureError::Decode(e.to_string()))?;
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(MAX_TEXTURE_SIDE);
        limits.max_image_height = Some(MAX_TEXTURE_SIDE);
        limits.max_alloc = Some(MAX_TEXELS * 16);
        reader.limits(limits);
        let image = reader
            .decode()
            .map_err(|e| TextureError::Decode(e.to_string()))?;
        let channels = image.color().channel_count();
        let rgba = image.to_rgba8();
        let texels = rgba.pixels().map(|p| p.0).collect();
        Ok(Texture {
            name: name.to_owned(),
            width,
            height,
            channels,
            texels,
        })
    }

    /// A texture from texels given directly (tests, generated maps): `texels` row-major from
    /// the top, `width * height` of them.
    pub fn from_texels(name: &str, width: u32, height: u32, texels: Vec<[u8; 4]>) -> Texture {
        debug_assert_eq!(texels.len() as u64, u64::from(width) * u64::from(height));
        Texture {
            name: name.to_owned(),
            width,
            height,
            channels: 4,
            texels,
        }
    }

    /// Whether the file has an alpha channel.
    pub fn has_alpha(&self) -> bool {
        self.channels == 2 || self.channels == 4
    }

    /// Bytes of texel memory.
    pub fn bytes(&self) -> usize {
        self.texels.len() * 4
    }

    /// The texel at column `x`, row `y` (both in range).
    #[inline]
    pub fn texel(&self, x: u32, y: u32) -> [u8; 4] {
        self.texels[(y as usize) * (self.width as usize) + x as usize]
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    fn png(width: u32, height: u32, color: image::ColorType) -> Vec<u8> {
        let n = (width * height) as usize * color.bytes_per_pixel() as usize;
        let data: Vec<u8> = (0..n).map(|i| (i * 37 % 251) as u8).collect();
        let mut out = Vec::new();
        image::write_buffer_with_format(
            &mut Cursor::new(&mut out),
            &data,
            width,
            height,
            color,
            image::ImageFormat::Png,
        )
        .unwrap();
        out
    }

    #[test]
    fn grey_and_grey_alpha_images_spread_to_rgb() {
        let t = Texture::decode("g.png", &png(3, 2, image::ColorType::L8)).unwrap();
        assert_eq!((t.width, t.height, t.channels), (3, 2, 1));
        let [r, g, b, a] = t.texel(1, 0);
        assert_eq!((r, g, b, a), (37, 37, 37, 255));
        assert!(!t.has_alpha());
        let t = Texture::decode("ga.png", &png(2, 2, image::ColorType::La8)).unwrap();
        assert!(t.has_alpha());
        assert_eq!(t.texel(0, 0), [0, 0, 0, 37]);
    }

    #[test]
    fn jpeg_files_decode_too() {
        let rgb: Vec<u8> = (0..16 * 8 * 3)
            .map(|i| if i % 3 == 0 { 200 } else { 40 })
            .collect();
        let mut jpeg = Vec::new();
        image::codecs::jpeg::JpegEncoder::new_with_quality(&mut jpeg, 95)
            .encode(&rgb, 16, 8, image::ExtendedColorType::Rgb8)
            .unwrap();
        let t = Texture::decode("t.jpg", &jpeg).unwrap();
        assert_eq!((t.width, t.height, t.channels), (16, 8, 3));
        // Lossy, but near the colour written.
        let [r, g, b, a] = t.texel(5, 3);
        assert!(r.abs_diff(200) < 8 && g.abs_diff(40) < 8 && b.abs_diff(40) < 8 && a == 255);
    }

    #[test]
    fn garbage_and_truncated_files_are_errors_not_panics() {
        assert!(matches!(
            Texture::decode("x.png", b"not an image"),
            Err(TextureError::Decode(_))
        ));
        let good = png(8, 8, image::ColorType::Rgb8);
        for cut in [8, 20, 40, good.len() - 5] {
            assert!(Texture::decode("x.png", &good[..cut]).is_err(), "{cut}");
        }
    }

    #[test]
    fn huge_declared_dimensions_are_refused_before_allocating() {
        // A PNG header declaring 100 000 x 100 000 texels, with no data behind it.
        let mut bytes = png(1, 1, image::ColorType::Rgb8);
        bytes[16..20].copy_from_slice(&100_000u32.to_be_bytes());
        bytes[20..24].copy_from_slice(&100_000u32.to_be_bytes());
        let e = Texture::decode("big.png", &bytes).unwrap_err();
        assert!(
            matches!(e, TextureError::TooLarge { .. } | TextureError::Decode(_)),
            "{e}"
        );
    }
}
