//! Loading the images a scene description names, each file once however many materials use
//! it, with a note (material, map, file, reason) for every map that cannot be used: that map
//! is dropped and the material keeps its factor.

use super::{Maps, Texture, TextureRef, TextureSet};
use crate::formats::ImageSource;
use std::collections::HashMap;

/// The largest texture file read, bytes.
const MAX_FILE_BYTES: u64 = 512 * 1024 * 1024;

/// The textures of a scene, shared by the materials that name the same image.
#[derive(Debug, Default)]
pub struct Library {
    pub textures: Vec<Texture>,
    /// Image key to its texture, or the reason it failed.
    by_key: HashMap<String, Result<u32, String>>,
}

impl Library {
    /// The texture of `image`, loading it the first time.
    fn texture(&mut self, image: &ImageSource) -> Result<u32, String> {
        let key = image.key();
        if let Some(known) = self.by_key.get(&key) {
            return known.clone();
        }
        let loaded = load(image).map(|t| {
            self.textures.push(t);
            (self.textures.len() - 1) as u32
        });
        self.by_key.insert(key, loaded.clone());
        loaded
    }

    /// The maps of a described material with their images loaded. Every map whose image
    /// cannot be used adds a note to `notes` (starting with `at`: the material's file, line
    /// and name) and is left out.
    pub fn resolve(
        &mut self,
        maps: &Maps<TextureRef<ImageSource>>,
        at: &str,
        notes: &mut Vec<String>,
    ) -> TextureSet {
        maps.try_map(|name, r| match self.texture(&r.texture) {
            Ok(i) => Some(r.with_texture(i)),
            Err(why) => {
                notes.push(format!(
                    "{at}: {name} texture {}: {why}; the material keeps its factor",
                    r.texture.name()
                ));
                None
            }
        })
    }

    /// Bytes of texel memory in all.
    pub fn bytes(&self) -> usize {
        self.textures.iter().map(Texture::bytes).sum()
    }
}

fn load(image: &ImageSource) -> Result<Texture, String> {
    let name = image.name();
    match image {
        ImageSource::File(path) => {
            let size = std::fs::metadata(path)
                .map_err(|e| format!("cannot read it ({e})"))?
                .len();
            if size > MAX_FILE_BYTES {
                return Err(format!(
                    "the file is {size} bytes, more than the {MAX_FILE_BYTES} read"
                ));
            }
            let bytes = std::fs::read(path).map_err(|e| format!("cannot read it ({e})"))?;
            Texture::decode(&name, &bytes).map_err(|e| e.to_string())
        }
        ImageSource::Embedded { bytes, .. } => {
            Texture::decode(&name, bytes).map_err(|e| e.to_string())
        }
        ImageSource::Missing { why, .. } => Err(why.clone()),
    }
}
