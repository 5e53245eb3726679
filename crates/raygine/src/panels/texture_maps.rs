//! The textures of the selected material in the Materials panel: each map's name, a thumbnail
//! of its image and the file it came from, with its size on hover. Thumbnails are made once per
//! image (at most 64 texels a side, sampled from the texels) and kept while the scene is.

use std::collections::HashMap;
use tracer_core::scene::{Material, Scene};
use tracer_core::texture::Texture;

/// The thumbnails' largest side, pixels.
const SIDE: usize = 64;

/// Thumbnails of the open scene's textures.
#[derive(Default)]
pub struct TextureThumbnails {
    /// The scene's textures they were made from (compared by address).
    scene: usize,
    made: HashMap<u32, egui::TextureHandle>,
}

impl std::fmt::Debug for TextureThumbnails {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "TextureThumbnails({})", self.made.len())
    }
}

/// A small picture of `t`: its texels sampled on a grid (they are sRGB already).
fn thumbnail(t: &Texture) -> egui::ColorImage {
    let scale = (t.width.max(t.height) as usize).div_ceil(SIDE).max(1);
    let (w, h) = (
        (t.width as usize).div_ceil(scale),
        (t.height as usize).div_ceil(scale),
    );
    let pixels = (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) * scale, (i / w) * scale);
            let [r, g, b, a] = t.texel((x as u32).min(t.width - 1), (y as u32).min(t.height - 1));
            egui::Color32::from_rgba_unmultiplied(r, g, b, a)
        })
        .collect();
    egui::ColorImage::new([w, h], pixels)
}

impl TextureThumbnails {
    fn get(
        &mut self,
        ctx: &egui::Context,
        scene: &Scene,
        index: u32,
    ) -> Option<egui::TextureHandle> {
        let key = scene.textures.as_ptr() as usize;
        if key != self.scene {
            self.made.clear();
            self.scene = key;
        }
        let t = scene.textures.get(index as usize)?;
        Some(
            self.made
                .entry(index)
                .or_insert_with(|| {
                    ctx.load_texture(
                        format!("texture {}", t.name),
                        thumbnail(t),
                        egui::TextureOptions::NEAREST,
                    )
                })
                .clone(),
        )
    }
}

/// The maps of material `m` of `scene`, when it has any.
pub fn texture_maps_ui(
    ui: &mut egui::Ui,
    scene: &Scene,
    m: &Material,
    thumbnails: &mut TextureThumbnails,
) {
    let Some(set) = m.textures.and_then(|s| scene.texture_sets.get(s as usize)) else {
        return;
    };
    let named = set.named();
    if named.is_empty() && !set.cuts() {
        return;
    }
    ui.label("Texture maps (from the file; the values above multiply them):");
    for (name, map) in named {
        let Some(t) = scene.textures.get(map.texture as usize) else {
            continue;
        };
        ui.horizontal(|ui| {
            if let Some(handle) = thumbnails.get(ui.ctx(), scene, map.texture) {
                let size = handle.size_vec2();
                let fit = 32.0 / size.x.max(size.y).max(1.0);
                ui.image((handle.id(), size * fit));
            }
            let file = std::path::Path::new(&t.name)
                .file_name()
                .map_or_else(|| t.name.clone(), |f| f.to_string_lossy().into_owned());
            ui.label(format!("{name}: {file}")).on_hover_text(format!(
                "{}\n{} x {} texels, {} channels, {:.2} MB",
                t.name,
                t.width,
                t.height,
                t.channels,
                t.bytes() as f64 / 1e6
            ));
        });
    }
    if set.cuts() {
        ui.label(match set.alpha_mode {
            tracer_core::texture::AlphaMode::Mask { cutoff } => {
                format!("alpha: cut out below {cutoff}")
            }
            _ => "alpha: blended (stochastic transparency)".to_owned(),
        });
    }
}
