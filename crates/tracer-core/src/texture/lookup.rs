//! Reading a texture at a hit: the UV set and its transform (`KHR_texture_transform`), the wrap
//! modes, bilinear or nearest filtering, and the decoding of 8-bit texels.

use super::Texture;
use glam::{Vec2, Vec4};
use std::sync::LazyLock;

/// How texture coordinates outside 0..1 fold back (glTF's sampler modes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Wrap {
    #[default]
    Repeat,
    Clamp,
    Mirror,
}

/// Magnification filter.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Filter {
    /// Bilinear between the four nearest texel centres.
    #[default]
    Linear,
    /// The texel the point lies in.
    Nearest,
}

/// How the 8-bit texels encode values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    /// Colour: RGB through the sRGB transfer function to linear; alpha linear.
    Srgb,
    /// Data (roughness, metallic, normals, heights, alpha): value / 255.
    Linear,
}

/// An affine map of texture coordinates, `u' = a u + b v + c`, `v' = d u + e v + f`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform(pub [f32; 6]);

impl Default for UvTransform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl UvTransform {
    pub const IDENTITY: UvTransform = UvTransform([1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);

    /// `KHR_texture_transform`: translation · rotation · scale, the rotation turning UVs
    /// counter-clockwise by `rotation` radians in the image (v down).
    pub fn from_offset_rotation_scale(offset: [f32; 2], rotation: f32, scale: [f32; 2]) -> Self {
        let (s, c) = rotation.sin_cos();
        UvTransform([
            c * scale[0],
            s * scale[1],
            offset[0],
            -s * scale[0],
            c * scale[1],
            offset[1],
        ])
    }

    /// A scale and offset (MTL's `-s` and `-o`).
    pub fn from_scale_offset(scale: [f32; 2], offset: [f32; 2]) -> Self {
        UvTransform([scale[0], 0.0, offset[0], 0.0, scale[1], offset[1]])
    }

    #[inline]
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        let [a, b, c, d, e, f] = self.0;
        Vec2::new(a * uv.x + b * uv.y + c, d * uv.x + e * uv.y + f)
    }

    pub fn is_identity(&self) -> bool {
        *self == Self::IDENTITY
    }
}

/// One map of a material: which texture, read how. `I` names the image: an index into the
/// scene's textures once loaded, a `crate::formats::ImageSource` in a scene description.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureRef<I = u32> {
    /// Index into the scene's textures (or where the image is).
    pub texture: I,
    /// Which UV set (0 or 1: glTF's `TEXCOORD_0`, `TEXCOORD_1`).
    pub set: u8,
    pub transform: UvTransform,
    /// Wrap modes along u and v.
    pub wrap: [Wrap; 2],
    pub filter: Filter,
}

/// The sRGB transfer function's inverse (IEC 61966-2-1) of a value in 0..=1.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear value of each 8-bit sRGB code.
static SRGB_LUT: LazyLock<[f32; 256]> =
    LazyLock::new(|| std::array::from_fn(|i| srgb_to_linear(i as f32 / 255.0)));

/// Folds texel index `i` into `0..n` by `wrap`.
#[inline]
fn fold(i: i64, n: u32, wrap: Wrap) -> u32 {
    let n = i64::from(n);
    let k = match wrap {
        Wrap::Repeat => i.rem_euclid(n),
        Wrap::Clamp => i.clamp(0, n - 1),
        Wrap::Mirror => {
            let m = i.rem_euclid(2 * n);
            if m >= n { 2 * n - 1 - m } else { m }
        }
    };
    k as u32
}

impl Texture {
    /// The decoded texel at integer coordinates (any, folded by `wrap`).
    #[inline]
    fn decoded(&self, x: i64, y: i64, wrap: [Wrap; 2], encoding: Encoding) -> Vec4 {
        let [r, g, b, a] = self.texel(fold(x, self.width, wrap[0]), fold(y, self.height, wrap[1]));
        let alpha = f32::from(a) / 255.0;
        match encoding {
            Encoding::Srgb => {
                let lut = &*SRGB_LUT;
                Vec4::new(lut[r as usize], lut[g as usize], lut[b as usize], alpha)
            }
            Encoding::Linear => {
                Vec4::new(f32::from(r), f32::from(g), f32::from(b), f32::from(a)) / 255.0
            }
        }
    }

    /// The filtered value at texture coordinates `uv` (texel centres at (i + ½) / width), with
    /// `u`, `v` in the image's frame (v = 0 at the top row). Coordinates that are not finite
    /// read as 0.
    pub fn sample(&self, uv: Vec2, wrap: [Wrap; 2], filter: Filter, encoding: Encoding) -> Vec4 {
        let uv = Vec2::new(
            if uv.x.is_finite() { uv.x } else { 0.0 },
            if uv.y.is_finite() { uv.y } else { 0.0 },
        );
        // Far outside 0..1 the f32 has no fraction left; keep the index arithmetic in range.
        let x = f64::from(uv.x).clamp(-1e9, 1e9) * f64::from(self.width);
        let y = f64::from(uv.y).clamp(-1e9, 1e9) * f64::from(self.height);
        match filter {
            Filter::Nearest => self.decoded(x.floor() as i64, y.floor() as i64, wrap, encoding),
            Filter::Linear => {
                let (x, y) = (x - 0.5, y - 0.5);
                let (x0, y0) = (x.floor(), y.floor());
                let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
                let (x0, y0) = (x0 as i64, y0 as i64);
                let t00 = self.decoded(x0, y0, wrap, encoding);
                let t10 = self.decoded(x0 + 1, y0, wrap, encoding);
                let t01 = self.decoded(x0, y0 + 1, wrap, encoding);
                let t11 = self.decoded(x0 + 1, y0 + 1, wrap, encoding);
                let top = t00 + (t10 - t00) * fx;
                let bottom = t01 + (t11 - t01) * fx;
                top + (bottom - top) * fy
            }
        }
    }
}

impl<I> TextureRef<I> {
    /// The same map naming its image by `texture`.
    pub fn with_texture<J>(&self, texture: J) -> TextureRef<J> {
        TextureRef {
            texture,
            set: self.set,
            transform: self.transform,
            wrap: self.wrap,
            filter: self.filter,
        }
    }
}

impl TextureRef {
    /// The map's value at a hit whose UV sets are `uv` (set 0, set 1).
    #[inline]
    pub fn read(&self, textures: &[Texture], uv: [Vec2; 2], encoding: Encoding) -> Vec4 {
        let Some(t) = textures.get(self.texture as usize) else {
            return Vec4::ONE;
        };
        let at = self.transform.apply(uv[usize::from(self.set.min(1))]);
        t.sample(at, self.wrap, self.filter, encoding)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checker() -> Texture {
        // 2 x 2: white, black / black, white (sRGB codes 188 and 94 in the red channel).
        Texture::from_texels(
            "checker",
            2,
            2,
            vec![
                [188, 0, 0, 255],
                [94, 0, 0, 255],
                [94, 0, 0, 128],
                [188, 0, 0, 0],
            ],
        )
    }

    #[test]
    fn srgb_codes_decode_exactly() {
        // IEC 61966-2-1 by hand: ((188/255 + 0.055) / 1.055)^2.4 and the same for 94.
        assert!(
            (SRGB_LUT[188] - 0.502_886).abs() < 1e-5,
            "{}",
            SRGB_LUT[188]
        );
        assert!((SRGB_LUT[94] - 0.111_932).abs() < 1e-5, "{}", SRGB_LUT[94]);
        assert_eq!(SRGB_LUT[0], 0.0);
        assert!((SRGB_LUT[255] - 1.0).abs() < 1e-6);
        assert!((SRGB_LUT[10] - 10.0 / 255.0 / 12.92).abs() < 1e-7);
    }

    #[test]
    fn texel_centres_read_their_texel_and_midpoints_blend_after_decoding() {
        let t = checker();
        let at = |u: f32, v: f32| {
            t.sample(
                Vec2::new(u, v),
                [Wrap::Repeat; 2],
                Filter::Linear,
                Encoding::Srgb,
            )
        };
        assert!((at(0.25, 0.25).x - SRGB_LUT[188]).abs() < 1e-6);
        assert!((at(0.75, 0.25).x - SRGB_LUT[94]).abs() < 1e-6);
        assert!((at(0.25, 0.75).w - 128.0 / 255.0).abs() < 1e-6);
        // Half way between two centres: the mean of the linear values, not of the codes.
        let mid = at(0.5, 0.25).x;
        assert!(
            (mid - 0.5 * (SRGB_LUT[188] + SRGB_LUT[94])).abs() < 1e-6,
            "{mid}"
        );
        // Linear data: code / 255.
        let d = t.sample(
            Vec2::new(0.75, 0.25),
            [Wrap::Repeat; 2],
            Filter::Linear,
            Encoding::Linear,
        );
        assert!((d.x - 94.0 / 255.0).abs() < 1e-6);
    }

    #[test]
    fn wrap_modes_fold_as_gltf_says() {
        assert_eq!(fold(-1, 4, Wrap::Repeat), 3);
        assert_eq!(fold(5, 4, Wrap::Repeat), 1);
        assert_eq!(fold(-1, 4, Wrap::Clamp), 0);
        assert_eq!(fold(9, 4, Wrap::Clamp), 3);
        // Mirror: 0 1 2 3 | 3 2 1 0 | 0 1 ...
        let mirrored: Vec<u32> = (-2..10).map(|i| fold(i, 4, Wrap::Mirror)).collect();
        assert_eq!(mirrored, vec![1, 0, 0, 1, 2, 3, 3, 2, 1, 0, 0, 1]);
        let t = checker();
        let red = |u: f32, wrap: Wrap| {
            t.sample(
                Vec2::new(u, 0.25),
                [wrap; 2],
                Filter::Nearest,
                Encoding::Linear,
            )
            .x * 255.0
        };
        assert_eq!(red(1.25, Wrap::Repeat).round(), 188.0);
        assert_eq!(red(1.25, Wrap::Clamp).round(), 94.0);
        assert_eq!(red(1.25, Wrap::Mirror).round(), 94.0);
        assert_eq!(red(1.75, Wrap::Mirror).round(), 188.0);
        // NaN coordinates read as 0 instead of poisoning the render.
        assert!(
            t.sample(Vec2::NAN, [Wrap::Repeat; 2], Filter::Linear, Encoding::Srgb)
                .is_finite()
        );
    }

    #[test]
    fn the_texture_transform_is_translation_rotation_scale() {
        // KHR_texture_transform's example: a quarter turn maps (1, 0) to (0, -1).
        let t = UvTransform::from_offset_rotation_scale(
            [0.0; 2],
            std::f32::consts::FRAC_PI_2,
            [1.0; 2],
        );
        let p = t.apply(Vec2::new(1.0, 0.0));
        assert!((p - Vec2::new(0.0, -1.0)).length() < 1e-6, "{p}");
        let t = UvTransform::from_offset_rotation_scale([0.5, 0.25], 0.0, [2.0, 3.0]);
        assert_eq!(t.apply(Vec2::new(1.0, 1.0)), Vec2::new(2.5, 3.25));
    }
}
