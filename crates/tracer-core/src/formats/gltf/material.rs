//! glTF's metallic-roughness materials (also in `docs/formats.md`). raygine draws them with
//! glTF 2.0 Appendix B's model (`crate::shading::MetalRough`):
//!
//! - `baseColorFactor` (RGB; alpha unused), `metallicFactor`, `roughnessFactor`;
//! - `KHR_materials_ior`: the dielectric layer's F0 = ((ior − 1) / (ior + 1))², 0.04 at the
//!   default 1.5;
//! - `KHR_materials_transmission`: thin-walled transmission of the dielectric (its rough
//!   spread drawn smooth, noted);
//! - emission: emissive factor × `KHR_materials_emissive_strength`, read as
//!   `emission_scale` cd/m² per unit (1 by default: nits), noted once per material;
//! - `baseColorTexture` (sRGB; its alpha times the factor's is the alpha) and
//!   `metallicRoughnessTexture` (roughness in G, metallic in B) multiply their factors, read
//!   with their UV set, `KHR_texture_transform` and sampler (wrap modes; a NEAREST
//!   magnification filter, else bilinear);
//! - `alphaMode` MASK cuts the surface where alpha < `alphaCutoff` (0.5), for every ray; BLEND
//!   makes it present with probability alpha (stochastic transparency);
//! - `normalTexture` with its `scale`: a tangent-space normal map, with the file's `TANGENT`s or
//!   MikkTSpace's;
//! - `emissiveTexture` (sRGB) multiplies the emission;
//! - occlusion textures are not used (noted: a path tracer computes occlusion).
//!
//! The description also carries a Blinn-Phong approximation for readers that want one
//! (`formats::metal_rough`, shared with USD's UsdPreviewSurface).

use crate::formats::{
    EmissionDescription, ImageSource, MaterialDescription, MetalRoughDescription,
};
use crate::light::EmissionSides;
use crate::texture::{AlphaMode, Filter, Maps, TextureRef, UvTransform, Wrap};
use std::path::Path;

pub(super) fn to_description(
    m: &::gltf::Material<'_>,
    path: &Path,
    emission_scale: f32,
    images: &[ImageSource],
    notes: &mut Vec<String>,
) -> MaterialDescription {
    let index = m
        .index()
        .map_or_else(|| "default".to_owned(), |i| i.to_string());
    let name = m
        .name()
        .map_or_else(|| format!("material{index}"), str::to_owned);
    let at = format!("{}: material {name}", path.display());
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, _] = pbr.base_color_factor();
    let model = MetalRoughDescription {
        base_color: [r, g, b],
        metallic: pbr.metallic_factor(),
        roughness: pbr.roughness_factor(),
        transmission: m.transmission().map_or(0.0, |t| t.transmission_factor()),
        ior: m.ior().unwrap_or(1.5),
    };
    let strength = m.emissive_strength().unwrap_or(1.0).max(0.0);
    let emissive = m.emissive_factor().map(|c| c.max(0.0) * strength);
    let sides = if m.double_sided() {
        EmissionSides::Both
    } else {
        EmissionSides::Front
    };
    let emission =
        EmissionDescription::from_unitless(emissive, emission_scale, sides, &at, "emissive", notes);
    let maps = maps(m, images, &at, notes);
    MaterialDescription {
        name,
        source: path.to_owned(),
        emission,
        maps: (!maps.is_empty()).then(|| Box::new(maps)),
        ..crate::formats::metal_rough::material(model, &at, notes)
    }
}

/// The material's textures and alpha.
fn maps(
    m: &::gltf::Material<'_>,
    images: &[ImageSource],
    at: &str,
    notes: &mut Vec<String>,
) -> Maps<TextureRef<ImageSource>> {
    let pbr = m.pbr_metallic_roughness();
    let mut out = Maps {
        material: m.name().map_or_else(
            || format!("material{}", m.index().unwrap_or(0)),
            str::to_owned,
        ),
        alpha_factor: pbr.base_color_factor()[3].clamp(0.0, 1.0),
        ..Maps::default()
    };
    let mut one = |info: Option<::gltf::texture::Info<'_>>| {
        let info = info?;
        let transform = info.texture_transform();
        let set = transform
            .as_ref()
            .and_then(|t| t.tex_coord())
            .unwrap_or(info.tex_coord());
        let transform = transform.map_or(UvTransform::IDENTITY, |t| {
            UvTransform::from_offset_rotation_scale(t.offset(), t.rotation(), t.scale())
        });
        texture_ref(&info.texture(), set, transform, images, at, notes)
    };
    out.base_color = one(pbr.base_color_texture());
    out.metal_rough = one(pbr.metallic_roughness_texture());
    out.emissive = one(m.emissive_texture());
    if let Some(normal) = m.normal_texture() {
        // gltf 1.4 types KHR_texture_transform on texture infos only: here it is JSON.
        let (transform, set) = normal
            .extension_value("KHR_texture_transform")
            .map_or((UvTransform::IDENTITY, None), transform_of_json);
        out.normal = texture_ref(
            &normal.texture(),
            set.unwrap_or(normal.tex_coord()),
            transform,
            images,
            at,
            notes,
        );
        out.normal_scale = if normal.scale().is_finite() {
            normal.scale()
        } else {
            1.0
        };
    }
    out.alpha_mode = match m.alpha_mode() {
        ::gltf::material::AlphaMode::Opaque => AlphaMode::Opaque,
        ::gltf::material::AlphaMode::Mask => AlphaMode::Mask {
            cutoff: m.alpha_cutoff().unwrap_or(0.5).clamp(0.0, 1.0),
        },
        ::gltf::material::AlphaMode::Blend => AlphaMode::Blend,
    };
    let unused: Vec<&str> = [(
        m.occlusion_texture().is_some(),
        "occlusionTexture (a path tracer computes it)",
    )]
    .into_iter()
    .filter_map(|(has, name)| has.then_some(name))
    .collect();
    if !unused.is_empty() {
        notes.push(format!("{at}: not used: {}", unused.join(", ")));
    }
    out
}

/// `KHR_texture_transform` from its JSON: the transform and the texCoord override.
fn transform_of_json(v: &::gltf::json::Value) -> (UvTransform, Option<u32>) {
    let number = |x: &::gltf::json::Value| x.as_f64().filter(|x| x.is_finite()).map(|x| x as f32);
    let pair = |key: &str, default: [f32; 2]| {
        v.get(key)
            .and_then(|a| Some([number(a.get(0)?)?, number(a.get(1)?)?]))
            .unwrap_or(default)
    };
    let rotation = v.get("rotation").and_then(number).unwrap_or(0.0);
    let set = v
        .get("texCoord")
        .and_then(::gltf::json::Value::as_u64)
        .map(|s| s.min(u64::from(u32::MAX)) as u32);
    (
        UvTransform::from_offset_rotation_scale(
            pair("offset", [0.0; 2]),
            rotation,
            pair("scale", [1.0; 2]),
        ),
        set,
    )
}

/// One texture as raygine reads it: its image, UV set, transform and sampler.
fn texture_ref(
    texture: &::gltf::Texture<'_>,
    set: u32,
    transform: UvTransform,
    images: &[ImageSource],
    at: &str,
    notes: &mut Vec<String>,
) -> Option<TextureRef<ImageSource>> {
    use ::gltf::texture::{MagFilter, WrappingMode};
    let image = images.get(texture.source().index())?.clone();
    if set > 1 {
        notes.push(format!(
            "{at}: texture {} reads TEXCOORD_{set}; raygine reads sets 0 and 1, so it reads set 0",
            texture.index()
        ));
    }
    let sampler = texture.sampler();
    let wrap = |w: WrappingMode| match w {
        WrappingMode::Repeat => Wrap::Repeat,
        WrappingMode::ClampToEdge => Wrap::Clamp,
        WrappingMode::MirroredRepeat => Wrap::Mirror,
    };
    Some(TextureRef {
        texture: image,
        set: if set == 1 { 1 } else { 0 },
        transform,
        wrap: [wrap(sampler.wrap_s()), wrap(sampler.wrap_t())],
        filter: match sampler.mag_filter() {
            Some(MagFilter::Nearest) => Filter::Nearest,
            _ => Filter::Linear,
        },
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    fn material(json: &str) -> MaterialDescription {
        let doc = ::gltf::Gltf::from_slice(
            format!(r#"{{"asset":{{"version":"2.0"}},"materials":[{json}]}}"#).as_bytes(),
        )
        .expect("valid");
        let m = doc.materials().next().expect("one material");
        to_description(&m, Path::new("t.gltf"), 1.0, &[], &mut Vec::new())
    }

    /// Every map with its sampler, set and transform; the normal map's transform comes from its
    /// JSON.
    #[test]
    fn maps_keep_their_sets_samplers_and_transforms() {
        let doc = ::gltf::Gltf::from_slice(
            br#"{"asset":{"version":"2.0"},"images":[{"uri":"a.png"},{"uri":"n.png"}],
                "samplers":[{"wrapS":33071,"wrapT":33648,"magFilter":9728}],
                "textures":[{"source":0,"sampler":0},{"source":1}],
                "materials":[{"alphaMode":"MASK","alphaCutoff":0.3,
                  "pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.5],"baseColorTexture":{"index":0,"texCoord":1}},
                  "normalTexture":{"index":1,"scale":0.5,"extensions":{"KHR_texture_transform":{"offset":[0.5,0],"scale":[2,2],"texCoord":1}}},
                  "emissiveTexture":{"index":0}}]}"#,
        )
        .expect("valid");
        let images = [
            ImageSource::File("a.png".into()),
            ImageSource::File("n.png".into()),
        ];
        let m = doc.materials().next().unwrap();
        let mut notes = Vec::new();
        let d = to_description(&m, Path::new("t.gltf"), 1.0, &images, &mut notes);
        let maps = d.maps.expect("maps");
        let base = maps.base_color.as_ref().unwrap();
        assert_eq!(base.texture, images[0]);
        assert_eq!((base.set, base.filter), (1, Filter::Nearest));
        assert_eq!(base.wrap, [Wrap::Clamp, Wrap::Mirror]);
        let normal = maps.normal.as_ref().unwrap();
        assert_eq!((normal.set, maps.normal_scale), (1, 0.5));
        assert_eq!(
            normal.transform.apply(glam::Vec2::new(0.25, 0.5)),
            glam::Vec2::new(1.0, 1.0)
        );
        assert!(maps.emissive.is_some());
        assert_eq!(maps.alpha_mode, AlphaMode::Mask { cutoff: 0.3 });
        assert_eq!(maps.alpha_factor, 0.5);
        assert!(notes.is_empty(), "{notes:?}");
    }

    #[test]
    fn factors_and_extensions_become_the_metallic_roughness_model() {
        let m = material(
            r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.9,0.8,0.7,0.5],"metallicFactor":0.25,"roughnessFactor":0.4},
                "extensions":{"KHR_materials_ior":{"ior":1.33},"KHR_materials_transmission":{"transmissionFactor":0.6}}}"#,
        );
        let mr = m.metal_rough.expect("metallic-roughness");
        assert_eq!(mr.base_color, [0.9, 0.8, 0.7]);
        assert_eq!((mr.metallic, mr.roughness), (0.25, 0.4));
        assert_eq!((mr.transmission, mr.ior), (0.6, 1.33));
        // glTF's defaults: white, metallic 1, roughness 1, ior 1.5, no transmission.
        let d = material("{}").metal_rough.expect("metallic-roughness");
        assert_eq!(
            d,
            MetalRoughDescription {
                base_color: [1.0; 3],
                metallic: 1.0,
                roughness: 1.0,
                transmission: 0.0,
                ior: 1.5
            }
        );
    }

    #[test]
    fn metallic_roughness_maps_as_documented() {
        // A smooth-ish dielectric: Kd = c (1 - 0.04), lobe 0.04 with g = 2 / r^4 - 2.
        let m = material(
            r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.5,0.5,1],"metallicFactor":0,"roughnessFactor":0.5}}"#,
        );
        assert!((m.diffuse[0] - 0.48).abs() < 1e-6, "{:?}", m.diffuse);
        assert!((m.specular[0] - 0.04).abs() < 1e-6);
        assert!((m.glossiness - 30.0).abs() < 1e-3, "{}", m.glossiness);
        // glTF's default material (white, metallic 1, roughness 1) is a white diffuser.
        let d = material("{}");
        assert_eq!((d.specular, d.glossiness), ([0.0; 3], 0.0));
        assert!((d.diffuse[0] - 1.0).abs() < 1e-6, "{:?}", d.diffuse);
        // Roughness 0 is a mirror of the base colour for a metal.
        let mirror = material(
            r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.9,0.8,0.7,1],"roughnessFactor":0}}"#,
        );
        assert_eq!(mirror.glossiness, 0.0);
        assert!((mirror.specular[1] - 0.8).abs() < 1e-6);
    }
}
