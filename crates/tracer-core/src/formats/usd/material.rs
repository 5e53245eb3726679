//! UsdShade materials: which material a prim is bound to, and UsdPreviewSurface read as glTF's
//! metallic-roughness model (`formats::metal_rough`, the same mapping):
//!
//! - `diffuseColor` (0.18 when unset) is the base colour, `metallic` (0), `roughness` (0.5) and
//!   `ior` (1.5) as glTF's;
//! - `opacity` (1) below 1 makes the surface present with that probability (glTF's BLEND), or,
//!   with `opacityThreshold` > 0, cut where opacity is below the threshold (glTF's MASK);
//! - `emissiveColor` glows at `emission_scale` cd/m² per unit (as glTF emission; noted);
//! - `UsdUVTexture` inputs, read from files beside the layer or inside the `.usdz` with UV set
//!   0 (`st`), repeat and bilinear: `diffuseColor` (sRGB base colour), `emissiveColor`, `normal`
//!   (tangent space), `roughness` and `metallic` from an image's `r` output (or glTF's packing:
//!   roughness from `g` and metallic from `b` of one image), `opacity` (alpha, else red). A
//!   textured input takes the texture's value (its constant is not a factor). Occlusion and
//!   clearcoat are noted, not used; UsdUVTexture's `scale`, `bias`, `wrapS/T` and
//!   UsdTransform2d are not read.
//! - `useSpecularWorkflow = 1`: drawn with the metallic workflow (noted).
//!
//! A material that is not a UsdPreviewSurface (MDL, MaterialX) draws with the prim's
//! `primvars:displayColor`, else raygine's default material, and is noted.

use super::Reader;
use super::values::{self, Time};
use crate::formats::{EmissionDescription, ImageSource, MetalRoughDescription};
use crate::light::EmissionSides;
use crate::texture::{AlphaMode, Filter, Maps, TextureRef, UvTransform, Wrap};
use openusd::schemas::shade::{self, Channel};
use openusd::sdf;
use openusd::usd::Prim;

/// The material bound to `prim` for all purposes: its own `material:binding`, else its nearest
/// ancestor's (UsdShadeMaterialBindingAPI's rule, with `bindMaterialAs` strengths honoured where
/// the API is applied).
pub(super) fn bound_material(prim: &Prim) -> Option<sdf::Path> {
    let stage = prim.stage();
    if let Ok(Some(api)) = shade::MaterialBindingAPI::get(stage, prim.path().clone())
        && let Ok(Some(found)) = api.compute_bound_material("")
    {
        return Some(found);
    }
    let mut at = Some(prim.path().clone());
    while let Some(path) = at {
        if let Ok(rel) = path.append_property("material:binding")
            && let Ok(targets) = stage.relationship(rel).targets()
            && let Some(first) = targets.into_iter().next()
        {
            return Some(first);
        }
        at = path.parent().filter(|p| !p.is_abs_root());
    }
    None
}

impl Reader<'_> {
    /// The description index of the material at `path`, read once; None when it is not a
    /// UsdPreviewSurface.
    pub(super) fn material(&mut self, path: &sdf::Path) -> Option<usize> {
        let key = path.as_str().to_owned();
        if let Some(&known) = self.materials.get(&key) {
            return known;
        }
        let index = self.read_material(path);
        self.materials.insert(key, index);
        index
    }

    fn read_material(&mut self, path: &sdf::Path) -> Option<usize> {
        let at = format!("{}: material {}", self.path.display(), path.as_str());
        let surface = match shade::read_preview_surface(self.stage, path) {
            Ok(Some(s)) => s,
            Ok(None) => {
                self.desc.notes.push(format!(
                    "{at}: not a UsdPreviewSurface (raygine reads no other shaders); drawn with \
                     displayColor or the default material"
                ));
                return None;
            }
            Err(e) => {
                self.desc.notes.push(format!(
                    "{at}: cannot be read ({e:#}); drawn with the default material"
                ));
                return None;
            }
        };
        // A textured input takes the texture's value: its factor is 1.
        let color = |c: &Channel<openusd::gf::Vec3f>, default: [f32; 3]| match c {
            Channel::Value(v) => [v.x, v.y, v.z],
            Channel::Texture(_) => [1.0; 3],
            Channel::Unset => default,
        };
        let number = |c: &Channel<f32>, default: f32| match c {
            Channel::Value(v) if v.is_finite() => *v,
            Channel::Texture(_) => 1.0,
            _ => default,
        };
        let model = MetalRoughDescription {
            base_color: color(&surface.diffuse_color, [0.18; 3]),
            metallic: number(&surface.metallic, 0.0),
            roughness: number(&surface.roughness, 0.5),
            transmission: 0.0,
            ior: number(&surface.ior, 1.5).max(1.0),
        };
        let shader = self
            .stage
            .prim(sdf::Path::new(&surface.shader).unwrap_or_else(|_| path.clone()));
        if values::attr_scalar(&shader, "inputs:useSpecularWorkflow", Time::Default, 0.0)
            .unwrap_or(0.0)
            != 0.0
        {
            self.desc.notes.push(format!(
                "{at}: useSpecularWorkflow is drawn with the metallic workflow (specularColor \
                 is not used)"
            ));
        }
        let emission = EmissionDescription::from_unitless(
            color(&surface.emissive_color, [0.0; 3]),
            self.emission_scale,
            EmissionSides::Front,
            &at,
            "emissiveColor",
            &mut self.desc.notes,
        );
        let name = path.as_str().to_owned();
        let mut maps = Maps {
            material: name.clone(),
            ..Maps::default()
        };
        maps.base_color = self.texture(surface.diffuse_color.texture(), &at);
        maps.emissive = self.texture(surface.emissive_color.texture(), &at);
        maps.normal = self.texture(surface.normal.texture(), &at);
        maps.normal_scale = 1.0;
        // Roughness and metallic: from the red channel of their own images, or glTF's packing
        // (roughness in G, metallic in B of one image).
        let channel = |input: &str| output_channel(&shader, input);
        let (rough_file, metal_file) = (surface.roughness.texture(), surface.metallic.texture());
        let mut unread_maps = Vec::new();
        match (
            rough_file,
            metal_file,
            channel("roughness"),
            channel("metallic"),
        ) {
            (Some(r), Some(m), Some('g'), Some('b')) if r == m => {
                maps.metal_rough = self.texture(Some(r), &at);
            }
            (r, m, rc, mc) => {
                match (r, rc) {
                    (Some(file), Some('r')) => maps.roughness = self.texture(Some(file), &at),
                    (Some(_), _) => unread_maps.push("roughness (a channel other than r)"),
                    _ => {}
                }
                match (m, mc) {
                    (Some(file), Some('r')) => maps.metallic = self.texture(Some(file), &at),
                    (Some(_), _) => unread_maps.push("metallic (a channel other than r)"),
                    _ => {}
                }
            }
        }
        if let Some(file) = surface.opacity.texture() {
            maps.alpha_map = self.texture(Some(file), &at);
        }
        let opacity = number(&surface.opacity, 1.0).clamp(0.0, 1.0);
        let threshold = number(&surface.opacity_threshold, 0.0).clamp(0.0, 1.0);
        if opacity < 1.0 || maps.alpha_map.is_some() {
            maps.alpha_factor = opacity;
            maps.alpha_mode = if threshold > 0.0 {
                AlphaMode::Mask { cutoff: threshold }
            } else {
                AlphaMode::Blend
            };
        }
        let unread: Vec<&str> = [
            ("occlusion", surface.occlusion.texture().is_some()),
            ("clearcoat", surface.clearcoat.is_set()),
        ]
        .into_iter()
        .filter_map(|(name, has)| has.then_some(name))
        .chain(unread_maps)
        .collect();
        if !unread.is_empty() {
            self.desc.notes.push(format!(
                "{at}: not read: {} (their constants or defaults are used)",
                unread.join(", ")
            ));
        }
        let maps = (!maps.is_empty()).then(|| Box::new(maps));
        let description = crate::formats::MaterialDescription {
            name,
            source: self.path.to_owned(),
            emission,
            maps,
            ..crate::formats::metal_rough::material(model, &at, &mut self.desc.notes)
        };
        self.desc.materials.push(description);
        Some(self.desc.materials.len() - 1)
    }

    /// A UsdUVTexture's image: a file beside the root layer, or an entry of the `.usdz`.
    fn texture(&mut self, file: Option<&str>, at: &str) -> Option<TextureRef<ImageSource>> {
        let file = file?.trim();
        if file.is_empty() {
            return None;
        }
        let image = if self.is_usdz {
            let name = format!("{}[{}]", self.path.display(), file.trim_start_matches("./"));
            match self.package_bytes(file) {
                Ok(bytes) => ImageSource::Embedded {
                    name,
                    bytes: bytes.into(),
                },
                Err(why) => ImageSource::Missing { name, why },
            }
        } else {
            let folder = self.path.parent().unwrap_or(std::path::Path::new(""));
            let p = folder.join(file);
            if p.is_file() {
                ImageSource::File(p)
            } else {
                self.desc
                    .notes
                    .push(format!("{at}: texture {file} not found beside the file"));
                ImageSource::Missing {
                    name: p.display().to_string(),
                    why: "not found".into(),
                }
            }
        };
        Some(TextureRef {
            texture: image,
            set: 0,
            transform: UvTransform::IDENTITY,
            wrap: [Wrap::Repeat; 2],
            filter: Filter::Linear,
        })
    }
}

/// The channel (`r`, `g`, `b`, `a`) of the UsdUVTexture output that `inputs:NAME` of `shader`
/// connects to (`outputs:g` gives `g`; `outputs:rgb` gives None).
fn output_channel(shader: &Prim, input: &str) -> Option<char> {
    let source = shader
        .attribute(format!("inputs:{input}"))
        .connections()
        .ok()?
        .into_iter()
        .next()?;
    let name = source.as_str().rsplit_once(".outputs:")?.1.to_owned();
    let mut chars = name.chars();
    match (chars.next(), chars.next()) {
        (Some(c @ ('r' | 'g' | 'b' | 'a')), None) => Some(c),
        _ => None,
    }
}
