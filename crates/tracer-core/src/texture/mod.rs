//! Image textures: decoded images shared between the materials that name the same file
//! ([`Texture`]), how a material reads one at a hit ([`TextureRef`]: UV set, transform, wrap
//! modes, filter) and the set of maps one material carries ([`TextureSet`]).
//!
//! Filtering is bilinear over the 8-bit texels after decoding them (sRGB to linear for colours,
//! /255 for data), with no mip-maps and no ray footprint: every progressive sample lands at a
//! fresh jittered point of its pixel, so the average over a pixel's samples converges to the
//! texture box-filtered over the pixel's footprint, with no blur added. Mip-maps would bias a
//! minified texture towards its blur level and make texel values depend on distance; a few
//! samples more where a texture is minified are the price (see `docs/formats.md`).

mod bend;
mod image_file;
mod library;
mod lookup;
mod set;

pub use bend::{MIN_COS, SurfaceDerivatives, above_surface};
pub use image_file::{MAX_TEXELS, MAX_TEXTURE_SIDE, Texture, TextureError};
pub use library::Library;
pub use lookup::{Encoding, Filter, TextureRef, UvTransform, Wrap, srgb_to_linear};
pub use set::{AlphaMode, Maps, TextureSet};
